"""Motor system, seed section 1: eqs. (1)-(10) and Appendix A, against values worked by hand/mpmath."""

import math

import mpmath as mp
import pytest
from scipy.optimize import minimize_scalar

from gearhead.core import motors
from gearhead.core.errors import InputError
from gearhead.core.model import solve

RPM = 2 * math.pi / 60


def test_cim_datasheet_values_and_derived_constants():
    out = solve("motor", {"motor": "CIM", "source": "wpilib", "torque": "1 N*m"}).outputs
    wf, ts, i_s, i_f = mp.mpf(5310) * 2 * mp.pi / 60, mp.mpf("2.42"), mp.mpf(133), mp.mpf("2.7")
    assert out["free_speed"].value == pytest.approx(float(wf), rel=1e-12)
    assert out["peak_power"].value == pytest.approx(float(wf * ts / 4), rel=1e-12)  # 336.417 W
    assert out["peak_power"].value == pytest.approx(336.4174, rel=1e-6)
    assert out["kt"].value == pytest.approx(float(ts / (i_s - i_f)), rel=1e-12)  # 0.0185725
    # operating point at 1 N*m: (8), (9)
    assert out["speed"].value == pytest.approx(float(wf * (1 - 1 / ts)), rel=1e-12)
    assert out["current"].value == pytest.approx(float((i_s - i_f) / ts + i_f), rel=1e-12)


def test_scaling_with_count_voltage_and_efficiency():
    one = solve("motor", {"motor": "NEO", "source": "wpilib"}).outputs
    three = solve(
        "motor", {"motor": "NEO", "source": "wpilib", "motor_count": 3, "voltage": "10 V", "efficiency": 0.9}
    ).outputs
    s = 10 / 12
    assert three["free_speed"].value == pytest.approx(one["free_speed"].value * s)  # (1)
    assert three["stall_torque"].value == pytest.approx(one["stall_torque"].value * 0.9 * 3 * s)  # (2)
    assert three["free_current"].value == pytest.approx(one["free_current"].value * 3 * s)  # (3)
    assert three["stall_current"].value == pytest.approx(one["stall_current"].value * 3 * s)  # (4)
    assert three["peak_power"].value == pytest.approx(one["peak_power"].value * 0.9 * 3 * s**2)  # (6)


@pytest.mark.parametrize("name", ["CIM", "Kraken X60", "NEO 550", "BAG", "V5 200 rpm (green)", "VEX 393"])
def test_max_efficiency_point_is_the_maximum_of_eq10(name):
    m = motors.system(motors.lookup(name, "wpilib")[0], 2, 11.0, 0.85)
    res = minimize_scalar(
        lambda t: -m.efficiency_at(t),
        bounds=(1e-9, m.stall_torque),
        method="bounded",
        options={"xatol": 1e-12},
    )
    assert m.max_efficiency_torque == pytest.approx(res.x, rel=1e-5)  # (91)
    assert m.max_efficiency == pytest.approx(-res.fun, rel=1e-10)
    # closed form agrees with (10) evaluated at (91)
    assert m.max_efficiency == pytest.approx(m.efficiency_at(m.max_efficiency_torque), rel=1e-13)


def test_max_efficiency_with_zero_free_current_is_finite_limit():
    ideal = motors.Motor("ideal", "test", 12.0, 500.0, 2.0, 100.0, 0.0)
    m = motors.system(ideal, 1, 12.0, 1.0)
    assert m.max_efficiency_torque == 0.0
    # limit of (10) as τ → 0 with ĩf = 0: ω̃f·τ̃s/(V·ĩs)
    assert m.max_efficiency == pytest.approx(500.0 * 2.0 / (12.0 * 100.0), rel=1e-15)
    assert m.efficiency_at(1e-9) == pytest.approx(m.max_efficiency, rel=1e-8)


def test_both_data_sources_are_selectable_and_differ_where_sources_differ():
    w = solve("motor", {"motor": "NEO", "source": "wpilib"}).outputs["stall_torque"].value
    r = solve("motor", {"motor": "NEO", "source": "recalc"}).outputs["stall_torque"].value
    assert (w, r) == (pytest.approx(2.6), pytest.approx(4.201))


def test_motor_missing_from_a_source_falls_back_with_a_warning():
    sol = solve("motor", {"motor": "BaneBots RS550", "source": "recalc"})
    assert sol.outputs["stall_torque"].value == pytest.approx(0.38)
    assert any(
        "ReCalc (dyno) has no data for BaneBots RS550; using WPILib DCMotor" in w for w in sol.warnings
    )


def test_every_reference_motor_is_present():
    names = set(motors.motor_names())
    for n in [
        "CIM",
        "MiniCIM",
        "BAG",
        "775pro",
        "AndyMark RS775-125",
        "BaneBots RS775",
        "AndyMark 9015",
        "BaneBots RS550",
        "NEO",
        "NEO 550",
        "Falcon 500",
        "Falcon 500 FOC",
        "Kraken X60",
        "Kraken X60 FOC",
        "Kraken X44",
        "Kraken X44 FOC",
        "Minion",
        "NEO Vortex",
        "VEX 393",
        "V5 100 rpm (red)",
        "V5 200 rpm (green)",
        "V5 600 rpm (blue)",
        "NEO 2.0",
        "775 RedLine",
        "NeveRest",
        "REV HD Hex",
        "REV Core Hex",
    ]:
        assert n in names
    # 18 before issue 31, which added Minion (Adv Hall), Thrifty Pulsar, BaneBots 550, Snowblower, Modern Robotics
    # and 25 since issue 40 (Falcon 500 FOC, AndyMark 9015: ReCalc lists both)
    assert len([m for m in motors.MOTORS if m.source == "recalc"]) == 25


def test_motors_only_recalc_has_say_so_when_wpilib_is_asked():
    # ReCalc Motor.ts: Core Hex 125 rpm, 3.2 N·m, 4.4 A stall, 0.5 A free (at its output shaft)
    sol = solve("motor", {"motor": "REV Core Hex", "source": "wpilib"})
    assert any("WPILib DCMotor has no data for REV Core Hex; using ReCalc (dyno)" in w for w in sol.warnings)
    assert sol.outputs["stall_torque"].value == pytest.approx(3.2)
    assert sol.outputs["free_speed"].value == pytest.approx(125 * RPM)
    sol = solve("elevator", {"motor": "NEO 2.0", "source": "wpilib"})
    assert any("has no data for NEO 2.0" in w for w in sol.warnings)


def test_torque_above_stall_names_the_field():
    with pytest.raises(InputError) as e:
        solve("motor", {"motor": "CIM", "torque": "3 N*m"})
    assert e.value.field == "torque"


def test_vex_393_uses_its_own_specification_voltage():
    out = solve("motor", {"motor": "VEX 393", "voltage": "7.2 V"}).outputs
    assert out["free_speed"].value == pytest.approx(100 * RPM)
    assert out["stall_torque"].value == pytest.approx(1.67)


def test_operating_point_power_and_efficiency_by_hand():
    # Kraken X60 (WPILib), 12 V, τ = 0.2 N*m:
    # (8)  ω = 628.3185·(1 − 0.2/7.09) = 610.594 rad/s;  P = 0.2·610.594 = 122.119 W
    # (9)  i = 364·0.2/7.09 + 2 = 12.2680 A;  (10) η = 122.119/(12·12.2680) = 0.82952
    out = solve("motor", {"motor": "Kraken X60", "torque": "0.2 N*m"}).outputs
    assert out["output_power"].value == pytest.approx(122.119, rel=1e-5)
    assert out["efficiency_at_torque"].value == pytest.approx(0.82952, rel=1e-5)


def test_vex_393_at_the_frc_default_voltage_is_warned():
    # 12 V / 7.2 V = 1.67: the 393's figures would be scaled up 67 % past its rating
    sol = solve("motor", {"motor": "VEX 393"})
    assert sol.outputs["free_speed"].value == pytest.approx(100 * RPM * 12 / 7.2)
    assert any("specified at 7.2 V" in w for w in sol.warnings)
    assert not solve("motor", {"motor": "VEX 393", "voltage": "7.2 V"}).warnings
    assert not solve("motor", {"motor": "Kraken X60", "voltage": "13 V"}).warnings
