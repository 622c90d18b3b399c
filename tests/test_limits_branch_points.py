"""The peak supply current and the lowest bus voltage at every branch point of the duty rule
(core.sim.motor_limits (E5)-(E7)), and elevator/arm moves at the edge of floating point (issue 28
item 2, issue 34 item 4)."""

import math
import tomllib
from pathlib import Path

import mpmath
import pytest

from gearhead.core import motors
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.sim import motion
from gearhead.core.sim.motor_limits import branch_emfs, circuit_of

PRESETS = Path(__file__).resolve().parents[1] / "presets"

# 4 × Kraken X60 (WPILib: 7.09 N·m, 366 A, 2 A, 6000 rpm at 12 V), 80 A stator limit each, a 12 V
# battery of 0.02 Ω shared by the four: R = 12/366 Ω, R_bus = 4·0.02 = 0.08 Ω. By hand:
#   I_st·R_bus = 6.4 V > V_b/2 = 6 V, so I(u) (E1) peaks below full duty and the roots of (E2) merge
#   at E6 = V_b²/(4·I_st·R_bus) − R·I_st = 144/25.6 − 960/366 = 5.625 − 2.62295082 = 3.00204918 V,
#   at the duty u = V_b/(2·I_st·R_bus) = 12/12.8 = 0.9375 < 1 (supply current there 0.9375·80 = 75 A).
#   Past E6 no duty gives 80 A: the duty jumps to 1 and the stator current to
#   I = (V_b − E6)/(R + R_bus) = 8.99795082/0.11278689 = 79.7783430 A, the supply current too (u = 1),
#   and the bus falls to V_b − R_bus·I = 12 − 0.08·79.7783430 = 5.6177326 V.
# Before: only the release E = V_b − I_st·(R + R_bus) = 2.97704918 V was looked at, where the duty is
# still the smaller root 0.875: 0.875·80 = 70.0 A and 12 − 0.08·70 = 6.40 V were shown.
PEAK_SUPPLY = 79.77834302325581  # A, (12 − E6)/(12/366 + 0.08), exact in sympy to 16 digits
MIN_BUS = 5.617732558139535  # V
E_MERGE = 5.625 - 960 / 366


def _kraken_sag(calc: str) -> dict:
    limits = {
        "motor": "Kraken X60",
        "motor_count": 4,
        "voltage": "12 V",
        "stator_current_limit": "80 A",
        "battery_resistance": "0.02 ohm",
    }
    if calc == "elevator":
        return {**limits, "effects": "gravity, stator_limit, battery_sag"}
    raw = tomllib.loads((PRESETS / "flywheel" / "frc_two_kraken_limits.toml").read_text())["inputs"]
    return {**raw, **limits, "effects": "stator_limit, battery_sag"}


def test_the_merge_point_by_hand():
    """E6 is where (E2)'s discriminant V_b² − 4·I_st·R_bus·(E + R·I_st) vanishes, and it is among
    the branch points searched."""
    c = circuit_of(motors.lookup("Kraken X60")[0], 12.0, 0.08)
    assert c.R == pytest.approx(12 / 366, rel=1e-15)
    Es = branch_emfs(c, {"stator_current_limit": 80.0}, {"stator_limit", "battery_sag"})
    assert min(Es, key=lambda E: abs(E - E_MERGE)) == pytest.approx(E_MERGE, rel=1e-14)
    assert 144 - 4 * 80 * 0.08 * (E_MERGE + c.R * 80) == pytest.approx(0, abs=1e-12)


@pytest.mark.parametrize("calc", ["elevator", "flywheel"])
def test_peak_supply_current_where_the_stator_limits_roots_merge(calc):
    out = {k: v.value for k, v in solve(calc, _kraken_sag(calc)).outputs.items()}
    assert out["peak_stator_current"] == pytest.approx(80.0, rel=1e-12)
    assert out["peak_supply_current"] == pytest.approx(PEAK_SUPPLY, rel=1e-9)  # was 70.0
    assert out["min_bus_voltage"] == pytest.approx(MIN_BUS, rel=1e-9)  # was 6.40


def test_the_elevator_passes_the_merge_point():
    """The case above is a test of E6 only if the move gets past it (back-EMF 3.0 V of 12)."""
    raw = _kraken_sag("elevator")
    top = solve("elevator", raw).outputs["max_speed"].value
    free = solve("elevator", {**raw, "effects": "gravity"}).outputs["free_speed"].value  # V_b·Kv/n
    assert top / free * 12 > E_MERGE * 1.1


def test_a_move_geared_to_free_fall_is_solved():
    """Ratio 1.23e-7 down a 180° incline: the motors barely push (free speed 9e7 m/s, time constant
    1.5e13 s) and the carriage falls its 40 in. (C2) with D = d/(w_f·τ) ~ 1e-21 cancelled to a zero
    time and "(result): could not be computed (max() arg is an empty sequence)" was shown (issue 34
    item 4). Free fall by hand: T = √(2·1.016/9.80665) = 0.45519923 s, the motors' pull a little less."""
    out = {
        k: v.value
        for k, v in solve("elevator", {"ratio": 1.2310516572251435e-07, "incline": "180 deg"}).outputs.items()
    }
    fall = math.sqrt(2 * 1.016 / 9.80665)
    assert 0 < fall - out["time_to_goal"] < 1e-6 * fall
    assert out["max_speed"] == pytest.approx(9.80665 * fall, rel=1e-6)
    assert out["peak_stator_current"] == pytest.approx(105, rel=1e-6)  # stalled: n·w/Kv ≈ 0


def test_an_arm_that_would_take_weeks_names_the_ratio():
    """220 000 lb at 4198 in on ratio 0.0014: the closed form's 18 days used to end in "max() arg is
    an empty sequence"; an integrated move stops at T_MAX = 1 h with a message naming the ratio,
    and so does the closed form now."""
    raw = {"ratio": 0.0014173097241146333, "effects": "", "arm_mass": "220000 lb", "com_distance": "4198 in"}
    with pytest.raises(InputError) as exc:
        solve("arm", raw)
    assert exc.value.field == "ratio" and "3600 s" in str(exc.value)


@pytest.mark.parametrize("D", [1e-300, 1e-30, 1e-21, 1e-12, 1e-6, 1e-3, 0.0099, 0.01, 0.5, 3.0, 1e3, 1e12])
def test_closed_form_time_to_rounding_for_any_distance(D):
    """x = T/τ with x + e^{−x} − 1 = D (C2), against mpmath at 400 digits (x ~ 1e-150 cancels 150 of
    them): to 1e-15 for every D (W₀ at its branch point and the direct g(x) both cancel for small D)."""
    from scipy.special import lambertw

    x = motion.close_time(D, lambda D: D + 1 + float(lambertw(-math.exp(-(D + 1))).real))
    with mpmath.workdps(400):
        Dm = mpmath.mpf(D)
        start = mpmath.sqrt(2 * Dm) if D < 1 else Dm + 1
        exact = mpmath.findroot(lambda t: t + mpmath.expm1(-t) - Dm, start, tol=mpmath.mpf(10) ** -50)
        assert abs(exact + mpmath.expm1(-exact) - Dm) <= Dm * mpmath.mpf(10) ** -40
        assert float(abs(x - exact) / exact) < 1e-15
