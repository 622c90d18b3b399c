"""One motor model on every tab (issue 28): the same motor at the same voltage and ratio has the same
free speed and stall current on the motor, gear ratio, drivetrain, flywheel, elevator and arm tabs.

The figures are worked from the motor data (REFERENCE_DATA.md, WPILib's DCMotor): the seed's eq. (1)
scales the rated free speed by V/V_spec, (4) the stall current. Before issue 28 the elevator and arm
used WPILib's Kt = τs/Is with no loss torque, so their free speed was Kv·V = ω_f·Is/(Is − If)·V/V_spec
(a Kraken X60 0.55 % faster there than on the motor tab)."""

import math

import pytest

from gearhead.core.model import solve

RPM = 2 * math.pi / 60
# name: (free speed rpm, stall current A, free current A) at 12 V, WPILib DCMotor
MOTORS = {
    "Kraken X60": (6000, 366, 2),
    "NEO": (5676, 105, 1.8),
    "CIM": (5310, 133, 2.7),
    "NEO Vortex": (6784, 211, 3.615),
}
V, G, R_WHEEL, R_SPOOL = 10.0, 7.5, 0.0508, 0.02


def outputs(calc, raw):
    return {k: o.value for k, o in solve(calc, raw).outputs.items()}


@pytest.mark.parametrize("name", MOTORS)
def test_free_speed_and_stall_current_are_the_same_on_every_tab(name):
    rpm, i_stall, _ = MOTORS[name]
    w_free = rpm * RPM * V / 12  # (1)
    base = {"motor": name, "motor_count": 2, "voltage": f"{V} V", "efficiency": 1}
    speeds = {
        "motor": outputs("motor", base)["free_speed"],
        "gear_ratio": outputs("gear_ratio", base | {"mode": "ratio", "ratio": G})["free_speed"] * G,
        "drivetrain": outputs("drivetrain", base | {"ratio": G, "wheel_diameter": f"{2 * R_WHEEL} m"})[
            "free_speed"
        ]
        * G
        / R_WHEEL,
        "flywheel": outputs("flywheel", base | {"ratio": 1 / G})["free_speed"] / G,
        "elevator": outputs(
            "elevator",
            base | {"ratio": G, "spool_diameter": f"{2 * R_SPOOL} m", "effects": "", "load_mass": "5 kg"},
        )["free_speed"]
        * G
        / R_SPOOL,
        "arm": outputs("arm", base | {"ratio": G * 10, "effects": ""})["free_speed"] * G * 10,
    }
    for tab, w in speeds.items():
        assert w == pytest.approx(w_free, rel=1e-12), f"{name} on the {tab} tab: {w} rad/s, not {w_free}"
    stall = i_stall * V / 12  # (4), per motor
    assert outputs("motor", base)["stall_current"] == pytest.approx(2 * stall, rel=1e-12)
    for calc, raw in (
        ("elevator", {"ratio": G, "effects": "", "load_mass": "5 kg"}),
        ("arm", {"ratio": G * 10, "effects": ""}),
    ):
        assert outputs(calc, base | raw)["peak_stator_current"] == pytest.approx(stall, rel=1e-12), calc


@pytest.mark.parametrize("name", MOTORS)
def test_elevator_stall_force_is_the_rated_stall_torque_through_the_spool(name):
    """kG at the stall current: the largest load the elevator holds is η·N·τs·(V/V_spec)·G/r (2),
    the motor tab's stall torque through the ratio, so kG reaches the bus voltage exactly there."""
    stall_torque = outputs("motor", {"motor": name, "voltage": f"{V} V"})["stall_torque"]
    F_stall = 2 * stall_torque * G / R_SPOOL
    out = outputs(
        "elevator",
        {
            "motor": name,
            "motor_count": 2,
            "voltage": f"{V} V",
            "ratio": G,
            "spool_diameter": f"{2 * R_SPOOL} m",
        }
        | {"effects": "", "load_mass": "5 kg"},
    )
    # kG per newton of load times the stall force: the stall voltage, less the loss's R·i_f (kS)
    kG_per_N = out["kA"] / 5.0  # kA = m·R/(η·N·Kt·n): volts per (N of force) = kA/m
    assert kG_per_N * F_stall + out["kS"] == pytest.approx(V, rel=1e-12)
