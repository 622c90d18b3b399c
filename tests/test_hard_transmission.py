"""Hard cases for chain_belt, gear_clearance and ratio_distance: numerically delicate inputs,
each compared with a closed form or an mpmath high-precision reference."""

import math

import mpmath as mp
import pytest

from gearhead.core.calculators import chain_belt as cb
from gearhead.core.model import solve

IN = 0.0254


def mp_span(L, r1, r2, dps=80):
    """mpmath reference (X, D) by plain bisection at high precision on the exact open-drive
    length in the β form (Appendix E, corrected), written for the span X = √(C² − Δ²):
    L = 2X + π(r1 + r2) + 2Δ·asin(Δ/C), C = √(X² + Δ²). L(X) increases; X ∈ [S, S + πΔ/2]."""
    with mp.workdps(dps):
        L, r1, r2 = +mp.mpf(L), mp.mpf(r1), mp.mpf(r2)
        delta = abs(r2 - r1)
        S = (L - 2 * mp.pi * max(r1, r2)) / 2

        def length(X):
            C = mp.sqrt(X**2 + delta**2)
            return 2 * X + mp.pi * (r1 + r2) + 2 * delta * mp.asin(delta / C)

        lo, hi = mp.mpf(0), S + mp.pi * delta / 2 + 1
        for _ in range(dps * 4 + 60):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if length(mid) < L else (lo, mid)
        X = (lo + hi) / 2
        return X, mp.sqrt(X**2 + delta**2)


def test_chain_barely_longer_than_the_minimum():
    """L = L_min·(1 + 1e-10): dL/dD = 2X/D → 0 at the minimum (D → Δ), so Newton from L/2 (the
    seed's method) stalls and L(D) − L cancels; the span X ~ (L − L_min)^(1/3) and the wrap
    angle 2·atan(X/Δ) are lost entirely if computed from D − Δ. Reference: mpmath, 80 digits.
    (L − 2π r_2 is itself only known to ~eps·L/S = 1e-6 relative: that rounding is in the input,
    so X is checked for the excess length S the double-precision input actually describes.)"""
    r1, r2 = 50e-3 / math.pi, 75e-3 / math.pi  # 20T and 30T on 5 mm pitch
    L = cb.minimum_length(r1, r2) * (1 + 1e-10)
    S = (L - 2 * math.pi * r2) / 2  # exactly what the double-precision input says is spare
    D, X = cb.span_from_length(L, r1, r2)
    _, D_ref = mp_span(L, r1, r2)
    assert D == pytest.approx(float(D_ref), rel=1e-14)
    with mp.workdps(80):
        X_ref, _ = mp_span(2 * mp.pi * mp.mpf(r2) + 2 * mp.mpf(S), r1, r2)
        wrap_ref = 2 * mp.atan(X_ref / abs(mp.mpf(r2) - mp.mpf(r1)))
    assert X == pytest.approx(float(X_ref), rel=1e-12)
    assert cb.wrap_angle(X, r1, r2) == pytest.approx(float(wrap_ref), rel=1e-12)
    # closed form for the leading order: Δ(u³/3) = S -> u = (3S/Δ)^(1/3)
    delta = r2 - r1
    assert X / delta == pytest.approx((3 * S / delta) ** (1 / 3), rel=1e-5)


def test_chain_nearly_equal_sprockets_meets_the_closed_form():
    """Δ = 1e-12·r: the general branch (brentq on u with s ~ 1e12) must join the equal-sprocket
    closed form D = (L − π(d1 + d2)/2)/2 without a jump; asin(Δ/D) and the bracket s + π/2 lose
    all of π/2 to rounding. Reference: mpmath at 80 digits, and the closed form."""
    r1 = 0.02
    r2 = r1 * (1 + 1e-12)
    L = 1.0
    D = cb.center_from_length(L, r1, r2)
    _, D_ref = mp_span(L, r1, r2)
    assert D == pytest.approx(float(D_ref), rel=1e-14)
    assert D == pytest.approx((L - math.pi * (r1 + r2)) / 2, rel=1e-12)


def test_chain_enormously_long_relative_to_sprockets():
    """s = (L − 2π r_2)/(2Δ) ~ 1e14: the bracket [s, s + π/2] is a few ulps wide and
    u − atan(u) − s is evaluated at the edge of double precision. Reference: mpmath."""
    r1, r2 = 1e-3, 2e-3
    L = 2e11 * 1e-3 * math.pi
    D = cb.center_from_length(L, r1, r2)
    _, D_ref = mp_span(L, r1, r2)
    assert D == pytest.approx(float(D_ref), rel=1e-14)


def test_chain_reverse_at_an_exact_link_count():
    """The wanted center is exactly the center of 74 links (computed in mpmath): the exact count
    is 74 ± rounding, and floor/ceil without snapping would report 72/74 or 74/76 instead of
    74/74."""
    p = 0.25 * IN
    r1, r2 = 12 * p / (2 * math.pi), 36 * p / (2 * math.pi)
    _, D_ref = mp_span(74 * p, r1, r2)
    o = {
        k: v.value
        for k, v in solve(
            "chain_belt",
            {
                "kind": "chain",
                "pitch_standard": "chain_25",
                "teeth_1": 12,
                "teeth_2": 36,
                "mode": "links_from_center",
                "target_center": f"{float(D_ref)!r} m",
            },
        ).outputs.items()
    }
    assert o["links_exact"] == pytest.approx(74, rel=1e-14)
    assert o["links_below"] == o["links_above"] == 74
    assert o["center_below"] == pytest.approx(float(D_ref), rel=1e-14)


def test_gears_exactly_touching_do_not_clear():
    """n_2 + n_3 = (n_1 + 2) + (n_4 + 2) at one pitch: the tips touch, C_g = 0 exactly (closed
    form, integer arithmetic). Summed term by term in SI (20 DP = 787.40157... 1/m) the rounding
    leaves ±1e-18 m and the verdict 'clears' would hang on a coin toss. Same for the axle:
    gear 1 tips exactly at the 0.5 in shaft surface."""
    sol = solve(
        "gear_clearance",
        {"teeth_1": 28, "teeth_2": 30, "teeth_3": 10, "teeth_4": 8, "axle_diameter": "0.5 in"},
    )
    # D = 40/40 = 1 in; r_o1 = 30/40 = 0.75 in; r_o4 = 10/40 = 0.25 in; C_g = 1 - 0.75 - 0.25 = 0
    # C_a = 1 - 0.75 - 0.25 = 0
    assert sol.outputs["gear_clearance"].value == 0.0
    assert sol.outputs["axle_clearance"].value == 0.0
    assert sol.outputs["gear_clears"].value is False and sol.outputs["axle_clears"].value is False
    # one tooth fewer on gear 4: clears by exactly 1/(2·20) in = 0.025 in
    sol = solve("gear_clearance", {"teeth_1": 28, "teeth_2": 30, "teeth_3": 10, "teeth_4": 7})
    assert sol.outputs["gear_clearance"].value / IN == pytest.approx(0.025, rel=1e-13)
    assert sol.outputs["gear_clears"].value is True


def test_ratio_typed_as_rounded_fraction():
    """G = 10/3 typed to 17 digits, 52 teeth in total (1.3 in at 20 DP, through two unit
    conversions): 52/(G + 1) = 11.999999999999998 in floating point, so a plain floor/ceil
    splits it 11/41 and 12/40 instead of recognising the exact pair 12/40 (closed form)."""
    assert 52 / (10 / 3 + 1) < 12  # the rounding this case is about
    o = {
        k: v.value
        for k, v in solve(
            "ratio_distance",
            {"ratio": repr(10 / 3), "center_distance": "1.3 in", "diametral_pitch": "20 1/in"},
        ).outputs.items()
    }
    assert (o["nearest_small_teeth"], o["nearest_large_teeth"]) == (12, 40)
    assert (o["below_small_teeth"], o["below_large_teeth"]) == (12, 40)
    assert (o["above_small_teeth"], o["above_large_teeth"]) == (12, 40)
    assert o["nearest_center_distance"] / IN == pytest.approx(1.3, rel=1e-15)


def _mp_length(D, r1, r2):
    """Open-drive length 2X + π(r_1 + r_2) + 2Δ·sin⁻¹(Δ/D), in mpmath (independent of core)."""
    D, r1, r2 = mp.mpf(D), mp.mpf(r1), mp.mpf(r2)
    delta = abs(r2 - r1)
    return 2 * mp.sqrt(D**2 - delta**2) + mp.pi * (r1 + r2) + 2 * delta * mp.asin(delta / D)


@pytest.mark.parametrize(
    "standard,n1,n2,half",
    [
        ("chain_25", 13, 37, False),
        ("chain_35", 15, 40, True),
        ("chain_25", 16, 16, False),
        ("htd_5mm", 20, 30, False),
        ("gt2_3mm", 12, 72, False),
        ("rt25", 36, 36, False),
    ],
)
def test_fewest_links_is_the_first_count_at_which_the_wheels_clear(standard, n1, n2, half):
    """The old 'fewest links that wrap both' was the count with the small sprocket inside the large
    one (D = Δ). Now: the fewest at which D > (OD_1 + OD_2)/2, OD = p(0.6 + cot(180°/n)) for chain
    sprockets (ANSI B29.1), the pitch diameter n·p/π for belt pulleys. Checked from the touching
    distance with the length equation in mpmath: the count is the first step past it."""
    from gearhead.core.calculators import chain_belt as cb

    mp.mp.dps = 40
    p = cb.STANDARD_PITCH[standard]
    chain = standard.startswith("chain")
    step = 2 if chain and not half else 1
    if chain:
        touch = sum(p * (mp.mpf("0.6") + mp.cot(mp.pi / n)) for n in (n1, n2)) / 2
    else:
        touch = (n1 + n2) * mp.mpf(p) / (2 * mp.pi)
    r1, r2 = n1 * mp.mpf(p) / (2 * mp.pi), n2 * mp.mpf(p) / (2 * mp.pi)
    exact = _mp_length(touch, r1, r2) / p
    expected = step * int(mp.floor(exact / step) + 1)
    sol = solve(
        "chain_belt",
        {"pitch_standard": standard, "teeth_1": n1, "teeth_2": n2, "links": expected, "half_links": half},
    )
    assert sol.outputs["minimum_links"].value == expected
    assert sol.outputs["center_distance"].value > touch
    assert not any("overlap" in w for w in sol.warnings)
    below = expected - step
    short = solve(
        "chain_belt",
        {"pitch_standard": standard, "teeth_1": n1, "teeth_2": n2, "links": below, "half_links": half},
    )
    assert short.outputs["center_distance"].value <= touch
    assert any("overlap" in w for w in short.warnings)


def test_ratio_distance_never_offers_a_pinion_below_ten_teeth():
    """Ratio 39 at 1 in, 20 DP (40 teeth in all) needs n = 40/40 = 1 tooth: the old answer was a
    1:39 pair with a warning. Now the pinion is at least 10 T: 10:30 (ratio 3) is offered, the
    highest ratio the distance allows, and the warning says why."""
    sol = solve("ratio_distance", {"ratio": 39, "center_distance": "1 in", "diametral_pitch": 20})
    o = {k: v.value for k, v in sol.outputs.items()}
    assert (o["nearest_small_teeth"], o["nearest_large_teeth"]) == (10, 30)
    assert "above_small_teeth" not in o
    assert o["small_teeth"] == pytest.approx(1.0, rel=1e-15)  # (77), fractional, still shown
    assert any("below the 10-tooth minimum" in w for w in sol.warnings)
    for ratio, d, dp in [(2.5, 2, 20), (4.3, 2, 32), (1.0, 0.55, 20), (49.9, 10, 64)]:
        o = {
            k: v.value
            for k, v in solve(
                "ratio_distance", {"ratio": ratio, "center_distance": f"{d} in", "diametral_pitch": dp}
            ).outputs.items()
        }
        assert min(o.get(f"{w}_small_teeth", 99) for w in ("nearest", "below", "above")) >= 10


@pytest.mark.parametrize(
    "raw,field",
    [
        ({"ratio": "5.5e14"}, "ratio"),  # used to report an 'above' ratio of 249
        ({"ratio": 51}, "ratio"),
        ({"center_distance": "1e6 in"}, "center_distance"),
        ({"diametral_pitch": "1e9 1/in"}, "diametral_pitch"),
        ({"diametral_pitch": "0.5 1/in"}, "diametral_pitch"),
        ({"center_distance": "0.45 in", "diametral_pitch": 20}, "center_distance"),  # 18 teeth < 2·10
    ],
)
def test_ratio_distance_inputs_are_bounded_to_gear_pairs(raw, field):
    from gearhead.core.errors import InputError

    with pytest.raises(InputError) as e:
        solve("ratio_distance", raw)
    assert e.value.field == field
