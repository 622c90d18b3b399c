"""Gear clearance (seed section 8): hand values with the corrected (71)-(74), and the seed's
pitch-radius slip measured."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core import presets
from gearhead.core.model import solve

IN = 0.0254


def out(**raw):
    return {k: v.value for k, v in solve("gear_clearance", raw).outputs.items()}


def test_defaults_hand_values():
    # 20 DP everywhere, 0.5 in axle. D = (50 + 12)/(2·20) = 1.55 in
    # r_o1 = (36 + 2)/40 = 0.95 in, r_o4 = (20 + 2)/40 = 0.55 in
    # C_a = 1.55 - 0.95 - 0.25 = 0.35 in; C_g = 1.55 - 0.95 - 0.55 = 0.05 in; gear 4 vs A: 1.55 - 0.55 - 0.25 = 0.75
    o = out(teeth_1=36, teeth_2=50, teeth_3=12, teeth_4=20, axle_diameter="0.5 in")
    assert o["center_distance"] / IN == pytest.approx(1.55, rel=1e-14)
    assert o["outside_diameter_1"] / IN == pytest.approx(1.9, rel=1e-14)
    assert o["axle_clearance"] / IN == pytest.approx(0.35, rel=1e-13)
    assert o["gear_clearance"] / IN == pytest.approx(0.05, rel=1e-12)
    assert o["axle_clearance_4"] / IN == pytest.approx(0.75, rel=1e-13)
    assert o["axle_clears"] is True and o["gear_clears"] is True and o["axle_clears_4"] is True


def test_seed_pitch_radius_would_pass_a_gear_that_hits():
    # 20 DP: D = (40 + 20)/40 = 1.5 in; gear 1 = 40T, gear 4 = 18T.
    # Seed (74) with pitch radii: 1.5 - 40/40 - 18/40 = +0.05 in ("clears").
    # Tips: 1.5 - 42/40 - 20/40 = -0.05 in: the teeth collide.
    sol = solve("gear_clearance", {"teeth_1": 40, "teeth_2": 40, "teeth_3": 20, "teeth_4": 18})
    assert sol.outputs["gear_clearance"].value / IN == pytest.approx(-0.05, rel=1e-12)
    assert sol.outputs["gear_clears"].value is False
    assert any("Gears 1 and 4" in w for w in sol.warnings)


def test_mixed_pitches():
    # gears 2-3 at 32 DP: D = (64 + 16)/64 = 1.25 in; gear 1 at 20 DP 18T: r_o1 = 20/40 = 0.5 in
    # gear 4 at 16 DP 10T: r_o4 = 12/32 = 0.375 in; axle 3/8 in -> C_a = 1.25 - 0.5 - 0.1875 = 0.5625
    # C_g = 1.25 - 0.5 - 0.375 = 0.375 in
    o = out(
        teeth_1=18,
        teeth_2=64,
        teeth_3=16,
        teeth_4=10,
        diametral_pitch_1=20,
        diametral_pitch_23=32,
        diametral_pitch_4=16,
        axle_diameter="0.375 in",
    )
    assert o["axle_clearance"] / IN == pytest.approx(0.5625, rel=1e-13)
    assert o["gear_clearance"] / IN == pytest.approx(0.375, rel=1e-13)


def test_pitch_in_other_units():
    # 20 teeth per inch = 20/25.4 per mm; results must not change
    a = out(diametral_pitch_1="20 1/in")
    b = out(diametral_pitch_1=f"{20 / 25.4!r} 1/mm")
    assert a["gear_clearance"] == pytest.approx(b["gear_clearance"], rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(n=st.lists(st.integers(5, 200), min_size=4, max_size=4), dp=st.sampled_from([12, 16, 20, 24, 32, 48]))
def test_clearance_sign_matches_integer_tooth_arithmetic(n, dp):
    # One pitch for all: C_g·2p = (n2 + n3) - (n1 + 2) - (n4 + 2) exactly, an integer.
    n1, n2, n3, n4 = n
    o = out(
        teeth_1=n1,
        teeth_2=n2,
        teeth_3=n3,
        teeth_4=n4,
        diametral_pitch_1=dp,
        diametral_pitch_23=dp,
        diametral_pitch_4=dp,
    )
    k = (n2 + n3) - (n1 + 2) - (n4 + 2)
    assert o["gear_clearance"] / IN == pytest.approx(k / (2 * dp), rel=1e-12, abs=1e-15)
    assert o["gear_clears"] is (k > 0)


def test_presets_load_and_solve():
    found = [p for p in presets.listing("gear_clearance") if p.builtin]
    assert len(found) >= 2
    for p in found:
        assert solve("gear_clearance", p.inputs).outputs
