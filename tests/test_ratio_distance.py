"""Ratio & distance (seed section 9): ReCalc cross-checks, nearest whole-tooth pairs by hand,
and forward(reverse(x)) = x."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core import presets
from gearhead.core.errors import InputError
from gearhead.core.model import solve

IN = 0.0254


def out(**raw):
    return {k: v.value for k, v in solve("ratio_distance", raw).outputs.items()}


@pytest.mark.parametrize("n,N,dp,d", [(20, 40, 20, 1.5), (24, 48, 16, 2.25)])
def test_recalc_cross_checks(n, N, dp, d):
    # ReCalc: 20T/40T at 20 DP -> 1.5 in; 24/48 at 16 DP -> 2.25 in. Reverse: ratio 2 at that distance.
    o = out(ratio=2, center_distance=f"{d} in", diametral_pitch=dp)
    assert o["small_teeth"] == pytest.approx(n, rel=1e-13) and o["large_teeth"] == pytest.approx(N, rel=1e-13)
    assert (o["nearest_small_teeth"], o["nearest_large_teeth"]) == (n, N)
    assert o["nearest_center_distance"] / IN == pytest.approx(d, rel=1e-14)
    assert o["small_pitch_diameter"] / IN == pytest.approx(n / dp, rel=1e-14)  # (69)
    assert o["large_outside_diameter"] / IN == pytest.approx((N + 2) / dp, rel=1e-14)  # (70)


def test_fractional_and_nearest_pairs_by_hand():
    # G = 4.3, d = 2 in, 32 DP: n = 2·2·32/5.3 = 24.1509..., N = 103.849...; total 2dp = 128
    # splits of 128: 24/104 = 4.3333 (above), 25/103 = 4.12 (below); |ln(4.3333/4.3)| = 0.00772 <
    # |ln(4.12/4.3)| = 0.0428, so 24/104 is nearest.
    o = out(ratio=4.3, center_distance="2 in", diametral_pitch=32)
    assert o["small_teeth"] == pytest.approx(128 / 5.3, rel=1e-13)
    assert o["large_teeth"] == pytest.approx(128 / 5.3 * 4.3, rel=1e-13)
    assert (o["nearest_small_teeth"], o["nearest_large_teeth"]) == (24, 104)
    assert (o["below_small_teeth"], o["below_large_teeth"]) == (25, 103)
    assert (o["above_small_teeth"], o["above_large_teeth"]) == (24, 104)
    assert o["nearest_ratio"] == pytest.approx(104 / 24, rel=1e-15)
    assert o["below_ratio"] == pytest.approx(4.12, rel=1e-15)


def test_center_distance_off_the_tooth_grid_warns():
    # 1.51 in at 20 DP: 2dp = 60.4 -> 60 teeth total -> 1.5 in
    sol = solve("ratio_distance", {"ratio": 2, "center_distance": "1.51 in", "diametral_pitch": 20})
    assert sol.outputs["nearest_center_distance"].value / IN == pytest.approx(1.5, rel=1e-14)
    assert any("1.5 in" in w for w in sol.warnings)


def test_too_small_center_is_an_input_error():
    with pytest.raises(InputError) as e:
        solve("ratio_distance", {"center_distance": "0.01 in", "diametral_pitch": 20})
    assert e.value.field == "center_distance"


def test_unreachable_ratio_offers_the_smallest_pinion_counted():
    # 1 in at 20 DP: 40 teeth; ratio 30 needs n = 40/31 = 1.29: refused, 10:30 offered
    sol = solve("ratio_distance", {"ratio": 30, "center_distance": "1 in", "diametral_pitch": 20})
    assert (sol.outputs["nearest_small_teeth"].value, sol.outputs["nearest_large_teeth"].value) == (10, 30)
    assert any("below the 10-tooth minimum" in w and "10:30" in w for w in sol.warnings)


@settings(max_examples=300, deadline=None)
@given(n=st.integers(10, 200), extra=st.integers(0, 400), dp=st.sampled_from([12, 16, 20, 24, 32, 48, 64]))
def test_reverse_of_forward_pair(n, extra, dp):
    # forward (75), (76): a whole pair gives G and d; reverse (77), (78) must return that pair
    N = n + extra
    G, d = N / n, (N + n) / (2 * dp)
    o = out(ratio=repr(G), center_distance=f"{d!r} in", diametral_pitch=dp)
    assert o["small_teeth"] == pytest.approx(n, rel=1e-12) and o["large_teeth"] == pytest.approx(N, rel=1e-12)
    assert (o["nearest_small_teeth"], o["nearest_large_teeth"]) == (n, N)
    assert o["nearest_center_distance"] / IN == pytest.approx(d, rel=1e-13)


@settings(max_examples=300, deadline=None)
@given(G=st.floats(1, 20), d=st.floats(0.7, 10), dp=st.sampled_from([16, 20, 32]))
def test_nearest_pair_is_best_split_of_its_total(G, d, dp):
    o = out(ratio=repr(G), center_distance=f"{d!r} in", diametral_pitch=dp)
    total = o["nearest_small_teeth"] + o["nearest_large_teeth"]
    assert total == round(2 * d * dp)
    best = min(abs(math.log((total - k) / k) - math.log(G)) for k in range(10, total // 2 + 1))
    assert abs(math.log(o["nearest_ratio"]) - math.log(G)) == pytest.approx(best, abs=1e-12)


def test_ratio_typed_short_lands_just_above_a_whole_pinion():
    # G = 3.3333333333 (10/3 to 10 digits), 1.3 in at 20 DP: total 52, n = 52/4.3333333333 =
    # 12.00000000009 (7.7e-12 above 12, a typing slip, not a 13th tooth): 12/40 on both sides, not
    # 13/39 (ratio 3.0) "below". The mirror case of test_ratio_typed_as_rounded_fraction.
    o = out(ratio="3.3333333333", center_distance="1.3 in", diametral_pitch=20)
    assert o["small_teeth"] == pytest.approx(12 + 12 * 7.7e-12, rel=1e-12)
    assert (o["below_small_teeth"], o["below_large_teeth"]) == (12, 40)
    assert (o["above_small_teeth"], o["above_large_teeth"]) == (12, 40)
    assert (o["nearest_small_teeth"], o["nearest_large_teeth"]) == (12, 40)


def test_presets_load_and_solve():
    found = [p for p in presets.listing("ratio_distance") if p.builtin]
    assert len(found) >= 2
    for p in found:
        assert solve("ratio_distance", p.inputs).outputs
