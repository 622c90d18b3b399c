"""The motors teams use today that WPILib's DCMotor lacks, against ReCalc's Motor.ts as read at
tervay/recalc commit 03511cb4 (12 V: free rpm, stall N·m, stall A, free A), and Minion from both."""

import pytest

from gearhead.core import motors
from gearhead.core.constants import RPM

RECALC_MOTOR_TS = {  # name here: (name in Motor.ts, free rpm, τs, is, if)
    "NEO 2.0": ("NEO 2.0", 5906, 4.201, 216.269, 1.782),
    "Minion": ("Minion", 7703, 3.173, 211.607, 2.206),
    "775 RedLine": ("775 RedLine", 19500, 0.64, 122, 2.6),
    "775pro": ("775pro", 18730, 0.71, 134, 0.7),
    "NeveRest": ("NeveRest", 5480, 0.173, 9.8, 0.355),
    "REV HD Hex": ("HD Hex", 6000, 0.105, 8.5, 0.4),
    "REV Core Hex": ("Core Hex", 125, 3.2, 4.4, 0.5),
}


@pytest.mark.parametrize("name", sorted(RECALC_MOTOR_TS))
def test_recalc_figures(name):
    _, rpm, ts, i_s, i_f = RECALC_MOTOR_TS[name]
    m, note = motors.lookup(name, "recalc")
    assert note is None and m.source == "recalc"
    assert (m.free_speed, m.stall_torque, m.stall_current, m.free_current) == pytest.approx(
        (rpm * RPM, ts, i_s, i_f), rel=1e-12
    )


@pytest.mark.parametrize("name", ["NEO 2.0", "775 RedLine", "NeveRest", "REV HD Hex", "REV Core Hex"])
def test_wpilib_has_no_data_and_says_so(name):
    m, note = motors.lookup(name, "wpilib")
    assert m.source == "recalc"
    assert note == f"WPILib DCMotor has no data for {name}; using ReCalc (dyno)"


def test_minion_in_both_sources():
    w, note_w = motors.lookup("Minion", "wpilib")
    r, note_r = motors.lookup("Minion", "recalc")
    assert note_w is None and note_r is None
    assert (w.stall_torque, w.stall_current, w.free_current, w.free_speed) == pytest.approx(
        (3.17, 211, 2, 7704 * RPM), rel=1e-12
    )
    assert r.stall_torque == pytest.approx(3.173, rel=1e-12)


def test_neo_vortex_free_current_is_wpilibs():
    """WPILib's DCMotor.getNeoVortex has 3.615 A free (REFERENCE_DATA.md's table shows 3.6): with
    3.6 every Vortex result was off WPILib's by up to 7e-5 (kP/kD 3.7e-4, issue 28)."""
    m, _ = motors.lookup("NEO Vortex", "wpilib")
    assert (m.stall_torque, m.stall_current, m.free_current, m.free_speed) == pytest.approx(
        (3.60, 211, 3.615, 6784 * RPM), rel=1e-12
    )
