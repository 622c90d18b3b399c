"""Pneumatic linkage, seed section 11: (88) re-derived, hand-worked geometry both ways, clear
errors when the linkage cannot close, and reverse(forward(x)) returning x (hypothesis)."""

import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from gearhead.core import presets
from gearhead.core.calculators import pneumatic_linkage as pl
from gearhead.core.errors import InputError
from gearhead.core.model import solve

DEG = math.pi / 180


def out(**raw):
    sol = solve("pneumatic_linkage", raw)
    return {k: v.value for k, v in sol.outputs.items()}, sol.warnings


def error(**raw):
    with pytest.raises(InputError) as e:
        solve("pneumatic_linkage", raw)
    return e.value


def test_eq88_and_lever_arm_rederived_with_sympy():
    """(84)²+(86)² gives (88); the moment arm |P × u| of the cylinder's line is dℓ/dθ."""
    sp = pytest.importorskip("sympy")
    A, B, X, Y, t = sp.symbols("A B X Y theta", real=True)
    px, py = X * sp.cos(t) - Y * sp.sin(t), X * sp.sin(t) + Y * sp.cos(t)
    eq88 = (
        A**2
        + B**2
        + X**2
        + Y**2
        + 2 * A * X * sp.cos(t)
        - 2 * B * Y * sp.cos(t)
        - 2 * B * X * sp.sin(t)
        - 2 * A * Y * sp.sin(t)
    )
    assert sp.simplify((A + px) ** 2 + (B - py) ** 2 - eq88) == 0  # L cos α, L sin α from (84), (86)
    ell = sp.sqrt(eq88)
    moment = (px * (py - B) - py * (px + A)) / ell  # P × (P − C)/ℓ with C = (−A, B)
    assert sp.simplify(moment - sp.diff(ell, t)) == 0


def test_forward_3_4_5_triangle_by_hand():
    # Rod end (0, 3) up the arm, cylinder pivot C = (−A, B) = (0, 4): r = 3, d = 4.
    # L = 5: 5² = 3² + 4² ⇒ γ1 = 90°; ψ = atan2(4, 0) = 90°, φ = 90° ⇒ θ1 = 90 − 90 + 90 = 90°:
    #   P(90°) = (−3, 0), |P − C| = sqrt(9 + 16) = 5 ✓. Other assembly: θ1 = −90°, P = (3, 0).
    # L + ΔL = √37: 37 = 9 + 16 − 24 cos γ2 ⇒ cos γ2 = −1/2, γ2 = 120° ⇒ θ2 = 120° (alt −120°):
    #   P(120°) = (−3 sin 120°, 3 cos 120°) = (−2.598, −1.5), |P − C|² = 6.75 + 30.25 = 37 ✓.
    # Lever arms r·d·sin γ/ℓ: 12/5 = 2.4 m; 12·(√3/2)/√37 = 1.708480 m. F = 100 N.
    # α1 = atan2(B − Py, A + Px) = atan2(4, −3) = 126.8699°; α2 = atan2(5.5, −2.598) = 115.2856°.
    o, w = out(
        pivot_x="0 m",
        pivot_y="4 m",
        arm_x="0 m",
        arm_y="3 m",
        retracted_length="5 m",
        stroke=f"{math.sqrt(37) - 5} m",
        cylinder_force="100 N",
    )
    assert o["retracted_angle"] == pytest.approx(90 * DEG, abs=1e-14)
    assert o["extended_angle"] == pytest.approx(120 * DEG, abs=1e-14)
    assert o["retracted_angle_alt"] == pytest.approx(-90 * DEG, abs=1e-14)
    assert o["extended_angle_alt"] == pytest.approx(-120 * DEG, abs=1e-14)
    assert o["sweep"] == pytest.approx(30 * DEG, abs=1e-14)
    assert o["retracted_lever_arm"] == pytest.approx(2.4, rel=1e-14)
    assert o["extended_lever_arm"] == pytest.approx(6 * math.sqrt(3) / math.sqrt(37), rel=1e-14)
    assert o["retracted_torque"] == pytest.approx(240.0, rel=1e-14)  # counter-clockwise
    assert o["extended_torque"] == pytest.approx(600 * math.sqrt(3) / math.sqrt(37), rel=1e-14)
    assert o["retracted_cylinder_angle"] == pytest.approx(math.atan2(4, -3), abs=1e-14)
    assert o["extended_cylinder_angle"] == pytest.approx(math.atan2(5.5, -1.5 * math.sqrt(3)), abs=1e-14)
    assert (o["min_length"], o["max_length"]) == (1.0, 7.0)
    assert w == []


def test_reverse_by_hand_both_pivots():
    # Rod end (1, 0); θ1 = 0 → P1 = (1, 0), θ2 = 90° → P2 = (0, 1). L = 1, L + ΔL = √5.
    # C = (2, 0): |C − P1| = 1, |C − P2| = √(4 + 1) = √5 ✓. Its mirror in the chord x + y = 1 is
    # (1 − y, 1 − x) = (1, −1): |·− P1| = 1, |·− P2| = √5 ✓. Neither passes dead centre (ψ = 0°, −45°;
    # rod end 0°→90°). (1, −1) lies on the arm pivot's side of the chord (0 + 0 < 1) so it is first.
    # Pivot fields are (A, B) = (−Cx, Cy): (−1, −1) and (−2, 0).
    o, w = out(
        mode="reverse",
        retracted_angle="0 deg",
        extended_angle="90 deg",
        arm_x="1 m",
        arm_y="0 m",
        retracted_length="1 m",
        stroke=f"{math.sqrt(5) - 1} m",
        cylinder_force="10 N",
    )
    assert (o["pivot_x"], o["pivot_y"]) == pytest.approx((-1, -1), abs=1e-14)
    assert (o["pivot_x_alt"], o["pivot_y_alt"]) == pytest.approx((-2, 0), abs=1e-14)
    # C = (1, −1), P1 = (1, 0): cylinder along x = 1, through... the line x = 1 is 1 m from the arm pivot
    assert o["retracted_lever_arm"] == pytest.approx(1.0, rel=1e-14)
    assert o["retracted_torque"] == pytest.approx(10.0, rel=1e-14)
    # P2 = (0, 1): line from (1, −1) to (0, 1) is 2x + y = 1, distance from origin 1/√5
    assert o["extended_lever_arm"] == pytest.approx(1 / math.sqrt(5), rel=1e-14)
    assert any("Two pivot positions" in x for x in w)


def test_reverse_clockwise_swing_gives_negative_torque():
    # Mirror of the case above in the x axis: θ 0 → −90°, pivots (A, B) = (−1, 1) and (−2, 0).
    o, _ = out(
        mode="reverse",
        retracted_angle="0 deg",
        extended_angle="-90 deg",
        arm_x="1 m",
        arm_y="0 m",
        retracted_length="1 m",
        stroke=f"{math.sqrt(5) - 1} m",
        cylinder_force="10 N",
    )
    assert (o["pivot_x"], o["pivot_y"]) == pytest.approx((-1, 1), abs=1e-14)
    assert (o["pivot_x_alt"], o["pivot_y_alt"]) == pytest.approx((-2, 0), abs=1e-14)
    assert o["retracted_torque"] == pytest.approx(-10.0, rel=1e-14)


def test_reverse_warns_when_the_pivot_found_ends_at_dead_centre():
    # Rod end (1, 0), θ 0° -> 90°, C = (0, -2): ℓ1 = |(1, 2)| = √5, ℓ2 = |(0, 3)| = 3 = d + r: extended,
    # the rod end (0, 1) is in line with both pivots (lever arm 0), as forward mode would warn.
    sol = solve(
        "pneumatic_linkage",
        {
            "mode": "reverse",
            "retracted_angle": "0 deg",
            "extended_angle": "90 deg",
            "arm_x": "1 m",
            "arm_y": "0 m",
            "retracted_length": f"{math.sqrt(5)!r} m",
            "stroke": f"{3 - math.sqrt(5)!r} m",
        },
    )
    assert (sol.outputs["pivot_x"].value, sol.outputs["pivot_y"].value) == pytest.approx((0, -2), abs=1e-14)
    assert sol.outputs["extended_lever_arm"].value == pytest.approx(0, abs=1e-7)
    assert any("When extended the arm is at dead centre" in w for w in sol.warnings)
    assert not any("When retracted" in w for w in sol.warnings)  # lever arm there 2/√5 m, γ = 63.4°


def test_reverse_rejects_a_pivot_that_passes_dead_centre():
    # P1 = (1, 0), P2 = (0, 1), L = 0.5, L + ΔL = 1.5. Both circles meet at C = P1 ± (√2/4)(1, 1):
    #   C+ = (1 + √2/4, √2/4): |C+ − P1| = 0.5, |C+ − P2|² = (1.35355)² + (0.64645)² = 2.25 ✓
    #   C− = (1 − √2/4, −√2/4): |C− − P1| = 0.5, |C− − P2|² = (0.64645)² + (1.35355)² = 2.25 ✓
    # C+ is at ψ = atan2(0.354, 1.354) = 14.6°, inside the swing 0°..90°: the rod end passes the point
    # nearest C+ (length d − r = 1.3990 − 1 = 0.399 < L), dead centre, so only C− works.
    s = math.sqrt(2) / 4
    o, w = out(
        mode="reverse",
        retracted_angle="0 deg",
        extended_angle="90 deg",
        arm_x="1 m",
        arm_y="0 m",
        retracted_length="0.5 m",
        stroke="1 m",
    )
    assert (o["pivot_x"], o["pivot_y"]) == pytest.approx((-(1 - s), -s), abs=1e-14)  # (A, B) = (−Cx, Cy)
    assert "pivot_x_alt" not in o
    assert any("not a working linkage" in x for x in w)
    rv = pl.reverse(0.0, math.pi / 2, 1.0, 0.0, 0.5, 1.0)
    assert rv["rejected"] == [pytest.approx((-(1 + s), s), abs=1e-14)]


def test_no_working_pivot_is_an_input_error():
    # θ ±30°, r = 1: chord 1 m, but the stroke is 1 cm on a 3 m cylinder: both intersections sit
    # near the chord's perpendicular bisector, i.e. in line with the arm pivot: the arm passes dead centre.
    e = error(
        mode="reverse",
        retracted_angle="-30 deg",
        extended_angle="30 deg",
        arm_x="1 m",
        retracted_length="3 m",
        stroke="0.01 m",
    )
    assert e.field == "stroke" and "dead centre" in e.message
    # 0° → 90°, L = 2 m, ΔL = 0.3 m: same story
    e = error(
        mode="reverse",
        retracted_angle="0 deg",
        extended_angle="90 deg",
        arm_x="1 m",
        retracted_length="2 m",
        stroke="0.3 m",
    )
    assert e.field == "stroke" and "dead centre" in e.message


@pytest.mark.parametrize(
    "raw,field,words",
    [
        (dict(arm_x=0, arm_y=0), "arm_x", "arm pivot"),
        (dict(pivot_x=0, pivot_y=0), "pivot_x", "never changes"),
        (dict(retracted_length="5 in"), "retracted_length", "too short"),
        (dict(retracted_length="30 in"), "retracted_length", "too long"),
        (dict(stroke="12 in"), "stroke", "too long"),
        (dict(mode="reverse", extended_angle="-45 deg"), "extended_angle", "must turn"),
        (dict(mode="reverse", extended_angle="150 deg"), "extended_angle", "180°"),
        (dict(mode="reverse", stroke="8 in"), "stroke", "longer than the rod end travels"),
        (dict(mode="reverse", retracted_length="1 in", stroke="1 in"), "retracted_length", "too short"),
        (dict(mode="reverse", arm_x=0), "arm_x", "arm pivot"),
    ],
)
def test_geometry_that_cannot_close_names_a_field(raw, field, words):
    # defaults: d = |(−6, −14)| = 15.23 in, r = 5 in: lengths 10.23..20.23 in.
    # reverse defaults: r = 5 in, θ −45°→45°: chord 2·5·sin 45° = 7.07 in.
    e = error(**raw)
    assert e.field == field and words in e.message


def test_defaults_near_dead_centre_warning():
    # extended exactly at d + r: dead centre, zero lever arm and torque, finite angles
    o, w = out(pivot_x="0 m", pivot_y="4 m", arm_x="0 m", arm_y="3 m", retracted_length="5 m", stroke="2 m")
    assert o["extended_angle"] == pytest.approx(180 * DEG, abs=1e-14)
    assert o["extended_lever_arm"] == 0 and o["extended_torque"] == 0
    assert any("dead centre" in x for x in w)


def test_lever_arm_is_the_derivative_of_cylinder_length():
    """Virtual work: torque = F·dℓ/dθ; dℓ/dθ by central differences of |P(θ) − C| (no shared code)."""
    A, B, X, Y = 0.15, -0.35, 0.12, 0.03
    o, _ = out(
        pivot_x=f"{A} m",
        pivot_y=f"{B} m",
        arm_x=f"{X} m",
        arm_y=f"{Y} m",
        retracted_length="0.3 m",
        stroke="0.15 m",
        cylinder_force="500 N",
    )

    def length(t):
        return math.hypot(X * math.cos(t) - Y * math.sin(t) + A, X * math.sin(t) + Y * math.cos(t) - B)

    for which, ell in (("retracted", 0.3), ("extended", 0.45)):
        t = o[f"{which}_angle"]
        assert length(t) == pytest.approx(ell, rel=1e-13)
        assert length(o[f"{which}_angle_alt"]) == pytest.approx(ell, rel=1e-13)
        h = 1e-5
        slope = (length(t + h) - length(t - h)) / (2 * h)
        assert o[f"{which}_lever_arm"] == pytest.approx(slope, rel=1e-8)
        assert o[f"{which}_torque"] == pytest.approx(500 * slope, rel=1e-8)


def test_plot_series_runs_from_theta1_to_theta2():
    sol = solve("pneumatic_linkage", {})
    xs, ys = sol.series["torque"]
    assert xs[0] == pytest.approx(sol.outputs["retracted_angle"].value, abs=1e-14)
    assert xs[-1] == pytest.approx(sol.outputs["extended_angle"].value, abs=1e-12)
    assert ys[0] == pytest.approx(sol.outputs["retracted_torque"].value, rel=1e-12)
    assert all(b > a for a, b in zip(xs, xs[1:]))


def test_plot_series_clockwise_swing_has_clockwise_torque():
    # The clockwise case above, pivot (A, B) = (-1, 1), i.e. C = (1, 1): the cylinder line through
    # P1 = (1, 0) is x = 1, 1 m from the arm pivot -> -10 N·m at θ1; at θ2 = -90°, P2 = (0, -1), the
    # line from (1, 1) along (-1, -2) is |1·(-2) - 1·(-1)|/√5 = 1/√5 m away -> -10/√5 N·m.
    # The plot runs 0° -> -90° and every torque is clockwise (< 0).
    sol = solve(
        "pneumatic_linkage",
        {
            "mode": "reverse",
            "retracted_angle": "0 deg",
            "extended_angle": "-90 deg",
            "arm_x": "1 m",
            "arm_y": "0 m",
            "retracted_length": "1 m",
            "stroke": f"{math.sqrt(5) - 1} m",
            "cylinder_force": "10 N",
        },
    )
    xs, ys = sol.series["torque"]
    assert xs[0] == pytest.approx(0, abs=1e-14) and xs[-1] == pytest.approx(-math.pi / 2, rel=1e-12)
    assert ys[0] == pytest.approx(-10.0, rel=1e-12) and ys[-1] == pytest.approx(-10 / math.sqrt(5), rel=1e-12)
    assert all(y < 0 for y in ys)


sides = st.floats(0.2, 1.0)
unit = st.floats(0.0, 1.0)


@settings(max_examples=300, deadline=None)
@given(
    st.floats(-1, 1),
    st.floats(-1, 1),
    st.floats(-0.5, 0.5),
    st.floats(-0.5, 0.5),
    st.floats(0.05, 0.85),
    st.floats(0.1, 0.9),
    st.sampled_from([1, -1]),
    st.sampled_from([1e-3, 1.0, 1e3]),
)
def test_reverse_of_forward_returns_the_pivot(A, B, X, Y, u1, du, assembly, scale):
    """Forward gives (θ1, θ2) of each assembly; reverse from those angles lists (A, B) among its pivots,
    and every pivot it lists gives back L and L + ΔL at θ1, θ2."""
    r, d = math.hypot(X, Y), math.hypot(A, B)
    assume(r > 0.05 and d > 0.05)
    lo, hi = abs(d - r), d + r
    assume(hi - lo > 0.02)
    u2 = min(u1 + du, 0.95)
    assume(u2 - u1 > 0.05)
    L, L2 = lo + u1 * (hi - lo), lo + u2 * (hi - lo)
    A, B, X, Y, L, L2 = (scale * x for x in (A, B, X, Y, L, L2))
    dL = L2 - L
    f = pl.forward(A, B, X, Y, L, dL)
    t1, t2 = (f["theta1"], f["theta2"]) if assembly == 1 else (f["theta1_alt"], f["theta2_alt"])
    rv = pl.reverse(t1, t2, X, Y, L, dL)
    assert any(math.hypot(a - A, b - B) <= 1e-7 * scale for a, b in rv["found"]), (rv, A, B)
    for a, b in rv["found"]:
        for t, ell in ((t1, L), (t2, L + dL)):
            px, py = pl.rod_end(X, Y, t)
            assert math.hypot(px + a, py - b) == pytest.approx(ell, rel=1e-9)


@settings(max_examples=200, deadline=None)
@given(
    st.floats(-170, 170),
    st.floats(-170, 170),
    st.floats(-0.5, 0.5),
    st.floats(-0.5, 0.5),
    st.floats(0.05, 2.0),
    unit,
)
def test_forward_of_reverse_returns_the_angles(t1_deg, t2_deg, X, Y, L, frac):
    """Each pivot reverse reports, run forward, puts the arm back at θ1 and θ2 (same assembly sense)."""
    t1, t2 = t1_deg * DEG, t2_deg * DEG
    r = math.hypot(X, Y)
    assume(r > 0.05 and 0.05 < abs(t2 - t1) < math.pi - 0.05)
    chord = 2 * r * abs(math.sin((t2 - t1) / 2))
    dL = chord * (0.05 + 0.9 * frac)
    try:
        rv = pl.reverse(t1, t2, X, Y, L, dL)
    except InputError:
        return
    for A, B in rv["found"]:
        f = pl.forward(A, B, X, Y, L, dL)
        key = "" if t2 > t1 else "_alt"  # primary assembly turns counter-clockwise on extension
        assert math.remainder(f["theta1" + key] - t1, 2 * math.pi) == pytest.approx(0, abs=1e-7)
        assert math.remainder(f["theta2" + key] - t2, 2 * math.pi) == pytest.approx(0, abs=1e-7)


@given(st.sampled_from([2.0**-20, 2.0**-3, 2.0**12, 2.0**30]))
def test_scaling_every_length_keeps_angles(k):
    """Angles are scale-free; lever arms scale with the lengths (power-of-two factors are exact)."""
    base = pl.forward(6.0, -14.0, 5.0, 1.0, 11.0, 6.0)
    scaled = pl.forward(6.0 * k, -14.0 * k, 5.0 * k, 1.0 * k, 11.0 * k, 6.0 * k)
    for key in ("theta1", "theta2", "theta1_alt", "theta2_alt"):
        assert scaled[key] == pytest.approx(base[key], abs=1e-15)


def test_presets_load_and_solve():
    found = presets.listing("pneumatic_linkage")
    assert len(found) >= 2
    for p in found:
        sol = solve(p.calculator, p.inputs)
        assert sol.outputs
