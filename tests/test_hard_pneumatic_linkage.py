"""Hard cases for the pneumatic linkage (seed section 11): dead centre, tangent circles, a pivot almost
on the arm pivot, a tiny swing. Each against a closed form or an mpmath reference (50 digits) built
from the same float inputs, written independently of the module's formulas (plain acos / vectors)."""

import math

import mpmath as mp
import pytest

from gearhead.core.calculators import pneumatic_linkage as pl
from gearhead.core.model import solve

mp.mp.dps = 50


def mp_circle_intersections(p1, p2, l1, l2):
    """Both points at distance l1 from p1 and l2 from p2, in mpmath (vectors, no closed forms shared)."""
    dx, dy = p2[0] - p1[0], p2[1] - p1[1]
    c = mp.sqrt(dx**2 + dy**2)
    ex, ey = dx / c, dy / c
    a = (l1**2 - l2**2 + c**2) / (2 * c)
    h = mp.sqrt(max(l1**2 - a**2, 0))
    return [(p1[0] + a * ex - s * h * ey, p1[1] + a * ey + s * h * ex) for s in (1, -1)]


def test_forward_one_part_in_2e12_short_of_dead_centre():
    """ℓ2 = d + r − 2⁻⁴⁰: γ2 is 1.13e-6 rad short of π. acos((r² + d² − ℓ²)/2rd) is evaluated at
    −1 + 1.3e-12, where one rounding of its argument moves γ by ~1e-10 (plain acos is off by 3.9e-11
    here); the atan2/Heron form must stay at the 1e-16 rounding floor of an angle near π."""
    dL = 3 - 2.0**-40  # L + ΔL = 7 − 2⁻⁴⁰ is exact in binary
    f = pl.forward(3.0, 4.0, 2.0, 0.0, 4.0, dL)  # C = (−3, 4): d = 5 exactly; r = 2
    ell2 = mp.mpf(4) + mp.mpf(dL)
    gamma2 = mp.acos((4 + 25 - ell2**2) / 20)  # (89) as the law of cosines
    gamma1 = mp.acos(mp.mpf(4 + 25 - 16) / 20)
    psi = mp.atan2(4, -3)
    assert float(mp.pi - gamma2) == pytest.approx(1.1284026685904956e-06, rel=1e-15)  # sanity of the ref
    assert abs(f["g2"] - gamma2) < 3e-16
    theta2 = psi + gamma2  # primary assembly, φ = 0
    assert abs(mp.mpf(f["theta2"]) - theta2) < 2e-15
    assert abs(mp.mpf(f["theta1"]) - (psi + gamma1)) < 1e-15
    # lever arm r·d·sin γ/ℓ ≈ 1.6e-6 m: relative accuracy, not just absolute
    h = pl.lever_arm(2.0, 5.0, 4.0 + dL)
    assert h == pytest.approx(float(10 * mp.sin(gamma2) / ell2), rel=1e-12)


def test_forward_exactly_at_dead_centre_is_finite():
    """ℓ2 = d + r exactly: the Heron product is 0 (a degenerate triangle), the lever arm and torque are
    exactly 0, and θ2 = ψ − φ + π in closed form; nothing may become NaN (acos(−1 − ulp) would)."""
    sol = solve(
        "pneumatic_linkage",
        {
            "pivot_x": "3 m",
            "pivot_y": "4 m",
            "arm_x": "2 m",
            "arm_y": "0 m",
            "retracted_length": "4 m",
            "stroke": "3 m",
            "cylinder_force": "100 N",
        },
    )
    o = {k: v.value for k, v in sol.outputs.items()}
    assert o["extended_lever_arm"] == 0.0 and o["extended_torque"] == 0.0
    assert o["extended_angle"] == pytest.approx(math.atan2(4, -3) + math.pi, abs=1e-15)
    assert o["extended_angle_alt"] == pytest.approx(math.atan2(4, -3) - math.pi, abs=1e-15)
    assert any("dead centre" in w for w in sol.warnings)


def test_forward_pivot_almost_on_the_arm_pivot():
    """d = 2⁻³⁰ m beside r = 1 m: ℓ only spans 1 ± 2⁻³⁰, and r² + d² − ℓ² cancels 30 bits
    (plain acos is off by 4e-10 rad). Writing it d² + (r − ℓ)(r + ℓ) keeps full accuracy."""
    d = 2.0**-30
    f = pl.forward(d, 0.0, 1.0, 0.0, 1 - 2.0**-31, 2.0**-30)  # ℓ = 1 ∓ 2⁻³¹, both exact
    psi = mp.pi  # C = (−d, 0)
    for key, ell in (("1", 1 - mp.mpf(2) ** -31), ("2", 1 + mp.mpf(2) ** -31)):
        gamma = mp.acos((1 + mp.mpf(d) ** 2 - ell**2) / (2 * d))
        assert abs(mp.mpf(f["g" + key]) - gamma) < 3e-16
    theta1 = psi + mp.acos((1 + mp.mpf(d) ** 2 - (1 - mp.mpf(2) ** -31) ** 2) / (2 * d)) - 2 * mp.pi
    assert abs(mp.mpf(f["theta1"]) - theta1) < 1e-15


def test_reverse_stroke_equal_to_rod_end_travel_circles_touch():
    """ΔL equals the chord 2r·sin(30°) = 1 only to rounding: the two circles touch, the discriminant is
    ±1 ulp, and the two pivots merge into one on the chord's extension, C = P1 − L·e. The answer must be
    finite, single, and at the touching point to √ulp (an exact tangency has no better conditioning)."""
    t2 = math.radians(60)
    rv = pl.reverse(0.0, t2, 1.0, 0.0, 0.5, 1.0)
    p1 = (mp.mpf(1), mp.mpf(0))
    p2 = (mp.cos(t2), mp.sin(t2))
    c = mp.sqrt((p2[0] - p1[0]) ** 2 + (p2[1] - p1[1]) ** 2)
    touch = (p1[0] - mp.mpf("0.5") * (p2[0] - p1[0]) / c, p1[1] - mp.mpf("0.5") * (p2[1] - p1[1]) / c)
    assert rv["found"] and not rv["rejected"]
    for A, B in rv["found"]:
        assert math.hypot(A + float(touch[0]), B - float(touch[1])) < 3e-8  # (A, B) = (−Cx, Cy)
    assert len(rv["found"]) == 1 or math.dist(*rv["found"]) < 6e-8


def test_reverse_tiny_swing():
    """Δθ = 2⁻³⁰ rad: P(θ2) − P(θ1) loses 30 bits to cancellation (chord off by 1.5e-8 relative if
    subtracted); the closed form 2r·sin(Δθ/2) and the chord direction from (θ1 + θ2)/2 keep the pivots
    accurate to rounding. Reference: the circle intersection in mpmath from the same float angles."""
    t1 = 0.3
    t2 = t1 + 2.0**-30
    L, dL = 0.5, 2.0**-32
    rv = pl.reverse(t1, t2, 1.0, 0.0, L, dL)
    p1, p2 = (mp.cos(t1), mp.sin(t1)), (mp.cos(t2), mp.sin(t2))
    ref = mp_circle_intersections(p1, p2, mp.mpf(L), mp.mpf(L) + mp.mpf(dL))
    assert len(rv["found"]) == 2
    for (A, B), (cx, cy) in zip(rv["found"], ref):
        assert abs(A + cx) < 1e-15 and abs(B - cy) < 1e-15


def test_dead_centre_warning_follows_the_lever_arm_not_the_arm_angle():
    """Cylinder pivot 0.3 in from the arm pivot (A = 0.3, B = 0), rod end 8.3 in out on the arm.
    The triangle's angle at the arm pivot is 45° retracted and 90° extended (far from 0/180°, so
    the old angle test stayed quiet), but the cylinder pushes almost through the arm pivot:
    h = r·d·sin γ/ℓ = 8.3·0.3·sin 45°/8.09065 = 0.217619 in (2.62 % of r) retracted and
    8.3·0.3/8.30542 = 0.299804 in (3.61 %) extended, both under 10 %: both warn."""
    r, d = 8.3, 0.3
    L = math.sqrt(r * r + d * d - 2 * r * d * math.cos(math.radians(45)))
    L2 = math.hypot(r, d)
    sol = solve(
        "pneumatic_linkage",
        dict(
            mode="forward",
            pivot_x=0.3,
            pivot_y=0,
            arm_x=8.3,
            arm_y=0,
            retracted_length=repr(L),
            stroke=repr(L2 - L),
        ),
    )
    IN = 0.0254
    assert sol.outputs["retracted_lever_arm"].value == pytest.approx(
        r * d * math.sin(math.pi / 4) / L * IN, rel=1e-12
    )
    assert sol.outputs["extended_lever_arm"].value == pytest.approx(r * d / L2 * IN, rel=1e-12)
    warned = [w for w in sol.warnings if "dead centre" in w]
    assert len(warned) == 2 and "2.62%" in warned[0] and "3.61%" in warned[1]


def test_no_dead_centre_warning_for_a_lever_arm_above_a_tenth_of_the_arm():
    """Defaults moved off dead centre: A = 6, B = −14, X = 5, L = 11, ΔL = 5: lever arms are
    4.2 and 1.9 in, over 10 % of the 5 in arm: no warning. Just under 10 % warns."""
    sol = solve("pneumatic_linkage", dict(mode="forward", stroke=5))
    h1, h2 = (sol.outputs[k].value / 0.0254 for k in ("retracted_lever_arm", "extended_lever_arm"))
    assert min(h1, h2) > 0.5
    assert not any("dead centre" in w for w in sol.warnings)


@pytest.mark.parametrize("field", ["retracted_angle", "extended_angle"])
@pytest.mark.parametrize("value", ["1e15 rad", "361 deg", "-6.3 rad"])
def test_arm_angles_are_bounded_to_a_turn(field, value):
    """1e15 rad used to be accepted (sin/cos of it keep no digits); angles are −360° to 360°."""
    from gearhead.core.errors import InputError

    with pytest.raises(InputError) as e:
        solve("pneumatic_linkage", {"mode": "reverse", field: value})
    assert e.value.field == field
