"""core/match/brownout.py and the timeline's brownouts: the roboRIO's state machine with
hysteresis (M10), crossings located in time (M11), on synthetic loads worked by hand."""

from __future__ import annotations

import pytest

from gearhead.core.errors import InputError
from gearhead.core.match.battery import Battery
from gearhead.core.match.brownout import Controller, brownouts, time_below
from gearhead.core.match.timeline import Load, Match


def test_frc_docs_thresholds():
    assert Controller.named("roborio2").brownout == 6.75
    assert Controller.named("roborio1").brownout == 6.3
    assert Controller().recovery == 7.5
    with pytest.raises(InputError) as e:
        Controller.named("cRIO")
    assert e.value.field == "controller"
    with pytest.raises(InputError) as e:
        Controller(brownout=7.6)
    assert e.value.field == "controller.recovery"
    with pytest.raises(InputError) as e:
        Controller(dwell=float("nan"))
    assert e.value.field == "controller.dwell"


def test_hysteresis_on_a_trace_by_hand():
    """8 V → 6.5 V over 1 s crosses 6.75 V at t = 1.25/1.5 = 0.8333 s; the bus then rises to 7.2 V
    (above 6.75 V, below 7.5 V: still disabled), dips to 7.0 V, and rises to 7.8 V at t = 4, crossing
    7.5 V at 3 + 0.5/0.8 = 3.625 s; a second dip to 6.0 V at t = 6 crosses 6.75 V at
    5 + 1.05/1.8 = 5.5833 s and the trace ends disabled."""
    t = [0, 1, 2, 3, 4, 5, 6]
    v = [8.0, 6.5, 7.2, 7.0, 7.8, 7.8, 6.0]
    got = brownouts(t, v, Controller(dwell=0.02))
    assert len(got) == 2
    assert got[0].start == pytest.approx(1.25 / 1.5, rel=1e-14)
    assert got[0].end == pytest.approx(3.625, rel=1e-14)
    assert got[1].start == pytest.approx(5 + 1.05 / 1.8, rel=1e-14)
    assert got[1].end == 6.0
    # without hysteresis (recovery at the brownout voltage) the 7.2 V would have ended the first
    plain = brownouts(t, v, Controller(brownout=6.75, recovery=6.7501, dwell=0.02))
    assert len(plain) == 2 and plain[0].end < 2.0
    # the roboRIO 1 (6.3 V): the dip to 6.5 V is no brownout
    assert brownouts(t, v, Controller.named("roborio1"))[0].start == pytest.approx(5 + 1.5 / 1.8, rel=1e-14)
    # time below 6.75 V: 1 − 0.8333 + (1.25/0.7) of the next segment, + the last dip
    below = (1 - 1.25 / 1.5) + 0.25 / 0.7 + (6 - (5 + 1.05 / 1.8))
    assert time_below(t, v, 6.75) == pytest.approx(below, rel=1e-14)


def test_dwell_holds_the_outputs_off():
    """The bus recovers past 7.5 V 0.01 s after the brownout; the outputs wait for the 0.05 s dwell."""
    got = brownouts([0.0, 1.0, 1.01, 2.0], [8.0, 6.7, 7.6, 7.6], Controller(dwell=0.05))
    start = (8.0 - 6.75) / 1.3  # the fall through 6.75 V (M11)
    assert got[0].start == pytest.approx(start, rel=1e-14)
    assert got[0].end == pytest.approx(start + 0.05, rel=1e-14)


def _ramp(peak, t0, t1, rising):
    """A current ramping linearly 0 → peak (rising) or peak → 0 between t0 and t1."""
    if rising:
        return lambda t: (peak * (t - t0) / (t1 - t0), 0.0, 0.0)
    return lambda t: (peak * (t1 - t) / (t1 - t0), 0.0, 0.0)


def test_a_load_crossing_the_threshold_oscillates_as_worked_by_hand():
    """Flat 12.5 V battery (one table row), R = 0.02 Ω, a triangle 0 → 400 A → 0 over 2 s. Outputs on,
    V = 12.5 − 0.02·I: under 6.75 V where I > 287.5 A, i.e. for 0.71875 < t < 1.28125. The bus falls
    through 6.75 V at 0.71875 s; with the load off it is 12.5 V > 7.5 V, so after the 0.1 s dwell the
    outputs return, the load pulls the bus under 6.75 V at once, and so on: brownouts begin at
    0.71875 + 0.1·j while that is before 1.28125 (j = 0…5), each 0.1 s long."""
    battery = Battery(ocv_table=((0.5, 12.5),), resistance=0.02)
    loads = (
        Load("up", _ramp(400.0, 0.0, 1.0, True), 0.0, 1.0),
        Load("down", _ramp(400.0, 1.0, 2.0, False), 1.0, 2.0),
    )
    r = Match(battery=battery, controller=Controller(dwell=0.1), length=3.0, loads=loads).run()
    starts = [b.start for b in r.brownouts]
    assert starts == pytest.approx([0.71875 + 0.1 * j for j in range(6)], abs=1e-9)
    assert [b.length for b in r.brownouts] == pytest.approx([0.1] * 6, abs=1e-9)
    assert r.brownouts[0].loads_running == ("up",)
    assert r.brownouts[-1].loads_running == ("down",)
    # the lowest bus: the instant the outputs return nearest the peak, t = 1.01875 on the way down
    # (I = 400·(2 − 1.01875) = 392.5 A, V = 12.5 − 7.85 = 4.65 V)
    assert r.min_voltage == pytest.approx(12.5 - 0.02 * 400 * (2 - 1.01875), abs=1e-9)
    assert r.min_voltage_time == pytest.approx(1.01875, abs=1e-9)
    # the load drew only while the outputs were on: 0 → 0.71875 s, then from 1.31875 s
    q = 0.5 * 287.5 * 0.71875 + 0.5 * (400 * (2 - 1.31875)) * (2 - 1.31875)
    assert r.charge_ah * 3600 == pytest.approx(q, rel=1e-8)


def test_roborio1_threshold_on_the_same_load():
    """At 6.3 V the bus is under the threshold where I > 310 A: 0.775 < t < 1.225; dwell 0.1 s:
    brownouts start at 0.775 + 0.1·j for j = 0…4 (0.775 + 0.5 = 1.275 > 1.225)."""
    battery = Battery(ocv_table=((0.5, 12.5),), resistance=0.02)
    loads = (
        Load("up", _ramp(400.0, 0.0, 1.0, True), 0.0, 1.0),
        Load("down", _ramp(400.0, 1.0, 2.0, False), 1.0, 2.0),
    )
    ctl = Controller(brownout=6.3, dwell=0.1)
    r = Match(battery=battery, controller=ctl, length=3.0, loads=loads).run()
    assert [b.start for b in r.brownouts] == pytest.approx([0.775 + 0.1 * j for j in range(5)], abs=1e-9)
