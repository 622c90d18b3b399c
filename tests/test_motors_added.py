"""The motors added for issue 31 (docs/motors.md), against their sources: ReCalc's Motor.ts as read at
tervay/recalc commit 03511cb4, WPILib's DCMotor (robotpy 2026.2.2), goBILDA's specifications; and the
motor model's derived constants (M1) against WPILib's DCMotor built from the same figures."""

import math

import pytest
from wpimath.system.plant import DCMotor

from gearhead.core import motors
from gearhead.core.constants import RPM
from gearhead.core.model import solve
from gearhead.core.sim.motor_limits import circuit_of

# Motor.ts (commit 03511cb4), copied from its ALL_MOTORS entries: name: (free rpm, τs N·m, is A, if A, lb or None)
MOTOR_TS = {
    "Minion (Adv Hall)": (7644, 3.201, 207.18, 2.384, 0.65),
    "Thrifty Pulsar": (7500, 3.1, 189, 1, 0.65),
    "BaneBots 550": (19300, 0.488, 85, 1.4, None),  # Motor.ts: 1.0 lb, its placeholder
    "Snowblower": (100, 7.90893775, 24, 5, None),
    "Modern Robotics": (5900, 0.19, 11, 0.3, None),
}


@pytest.mark.parametrize("name", sorted(MOTOR_TS))
def test_recalc_motor_ts_figures(name):
    rpm, ts, i_s, i_f, lb = MOTOR_TS[name]
    m, note = motors.lookup(name, "recalc")
    assert note is None and m.source == "recalc" and m.v_spec == 12.0
    assert (m.free_speed, m.stall_torque, m.stall_current, m.free_current) == pytest.approx(
        (rpm * 2 * math.pi / 60, ts, i_s, i_f), rel=1e-12
    )
    assert (m.mass is None) == (lb is None)
    if lb is not None:
        assert m.mass == pytest.approx(lb * 0.45359237, rel=1e-12)


@pytest.mark.parametrize("name", sorted(MOTOR_TS))
def test_derived_constants_are_wpilibs_for_the_same_figures(name):
    """R and Kv (M1) as WPILib's DCMotor computes them from the same four figures, and the seed's Kt
    τs/(Is − If) from WPILib's (ReCalc runs WPILib's DCMotor too: Motor.toWpilibMotor)."""
    rpm, ts, i_s, i_f, _ = MOTOR_TS[name]
    theirs = DCMotor(12.0, ts, i_s, i_f, rpm * math.pi / 30, 1)
    mine, _ = motors.lookup(name, "recalc")
    c = circuit_of(mine, 12.0)
    assert c.R == pytest.approx(theirs.R, rel=1e-12)
    assert c.Kv == pytest.approx(theirs.Kv, rel=1e-12)
    s = motors.system(mine, 1, 12.0, 1.0)
    assert s.kt == pytest.approx(theirs.stallTorque / (theirs.stallCurrent - theirs.freeCurrent), rel=1e-12)


def test_romi_is_wpilibs_builtin_motor():
    theirs = DCMotor.romiBuiltIn(1)
    mine, note = motors.lookup("Romi", "wpilib")
    assert note is None
    assert (mine.v_spec, mine.stall_torque, mine.stall_current, mine.free_current, mine.free_speed) == (
        pytest.approx(theirs.nominalVoltage, rel=1e-12),
        pytest.approx(theirs.stallTorque, rel=1e-12),
        pytest.approx(theirs.stallCurrent, rel=1e-12),
        pytest.approx(theirs.freeCurrent, rel=1e-12),
        pytest.approx(theirs.freeSpeed, rel=1e-12),
    )
    c = circuit_of(mine, 4.5)
    assert (c.R, c.Kv) == (pytest.approx(theirs.R, rel=1e-12), pytest.approx(theirs.Kv, rel=1e-12))


def test_romi_at_twelve_volts_warns_of_its_rating():
    sol = solve("motor", {"motor": "Romi", "torque": "0.1 N*m"})
    assert any("specified at 4.5 V" in w for w in sol.warnings)
    sol = solve("motor", {"motor": "Romi", "voltage": "4.5 V", "torque": "0.1 N*m"})
    assert sol.outputs["free_speed"].value == pytest.approx(150 * RPM, rel=1e-12)


# goBILDA 5203 series: ratio, rpm, stall kg·cm (9.2 A stall, 0.25 A free)
GOBILDA = {
    "goBILDA Yellow Jacket 1150 rpm": (5.2, 1150, 7.9),
    "goBILDA Yellow Jacket 435 rpm": (13.7, 435, 18.7),
    "goBILDA Yellow Jacket 312 rpm": (19.2, 312, 24.3),
    "goBILDA Yellow Jacket 223 rpm": (26.9, 223, 38.0),
}


@pytest.mark.parametrize("name", sorted(GOBILDA))
def test_gobilda_figures(name):
    ratio, rpm, kgcm = GOBILDA[name]
    m, note = motors.lookup(name, "wpilib")
    assert note is None  # a vendor's only data: no "WPILib has no data" note
    # 1 kg·cm = 9.80665 N × 0.01 m; 24.3 kg·cm = 2.38301595 N·m (by hand)
    assert m.stall_torque == pytest.approx(kgcm * 0.0980665, rel=1e-12)
    assert (m.stall_current, m.free_current, m.v_spec) == (9.2, 0.25, 12.0)
    assert m.free_speed == pytest.approx(rpm * RPM, rel=1e-12)
    # one bare motor behind every ratio: ratio × output speed is goBILDA's 6000 rpm within 0.7 %
    assert ratio * rpm == pytest.approx(6000, rel=0.007)


def test_gobilda_312_stall_torque_by_hand():
    m, _ = motors.lookup("goBILDA Yellow Jacket 312 rpm")
    assert m.stall_torque == pytest.approx(2.38301595, rel=1e-12)


def test_added_motors_follow_every_earlier_one():
    """The choice lists only grow at the end: a preset or a type-ahead sequence keeps its meaning."""
    names = motors.motor_names()
    added = [*MOTOR_TS, "Romi", *GOBILDA]
    assert list(names[-len(added) :]) == added
    assert names.index("VEX 393 high speed") == len(names) - len(added) - 1


def test_placeholder_masses_are_not_masses():
    """Motor.ts weighs motors it has no weight for at 1.0 lb: not a mass to divide power by."""
    for name in ("775 RedLine", "NeveRest", "REV HD Hex", "REV Core Hex"):
        assert motors.lookup(name, "recalc")[0].mass is None
    assert motors.lookup("Kraken X60", "recalc")[0].mass == pytest.approx(1.2 * 0.45359237)


@pytest.mark.parametrize("name", [*MOTOR_TS, "Romi", *GOBILDA])
def test_every_added_motor_solves_on_the_motor_tab(name):
    m, _ = motors.lookup(name)
    sol = solve("motor", {"motor": name, "voltage": f"{m.v_spec} V", "torque": "0 N*m"})
    # at its own voltage, with no load, the motor runs at its rated free speed (one motor model)
    assert sol.outputs["speed"].value == pytest.approx(m.free_speed, rel=1e-12)
    assert sol.outputs["stall_torque"].value == pytest.approx(m.stall_torque, rel=1e-12)
