"""The sprint on the match's bus (core/match/mechanisms.py _Sprint, B7-B8): alone it is its card
(time, peak currents, lowest bus, energy), the slip's constant current derived with sympy, a
brownout coasts the robot, bad entries named."""

import pytest
import sympy as sp

from gearhead.core import model
from gearhead.core.errors import InputError
from gearhead.core.match.battery import Battery
from gearhead.core.match.brownout import Controller
from gearhead.core.match.mechanisms import IdealSource, MechanismMatch, from_card
from gearhead.core.sim.scene import LEVELS

KEYS = ("time_to_distance", "peak_stator_current", "peak_supply_current", "min_bus_voltage", "energy")


def test_slip_terms_derived_with_sympy():
    """(B7): at the edge of slip the stator current is I_slip; the duty rule u ≤ 1, u·I ≤ I_sup
    gives u = min(1, I_sup/I_slip), so the supply u·I_slip = min(I_slip, I_sup). (B8): the gripping
    branches reach I_slip at V = E + R·I_slip (full duty, motion (M2)) and, on the supply limit
    (B5), where u = (E + R·I_slip)/V and u·I_slip = I_sup."""
    V, E, R, I_slip, I_sup = sp.symbols("V E R I_slip I_sup", positive=True)
    assert sp.solve(sp.Eq((V - E) / R, I_slip), V) == [E + R * I_slip]
    u = (E + R * I_slip) / V  # the duty at which (u·V − E)/R = I_slip
    assert sp.simplify(((u * V - E) / R) - I_slip) == 0
    assert sp.solve(sp.Eq(u * I_slip, I_sup), V) == [I_slip * (E + R * I_slip) / I_sup]


def card(raw):
    s = model.solve("sprint", dict(raw, accuracy="tight"))  # the card to 1e-11: the reference
    return {k: s.outputs[k].value for k in KEYS}


def alone(raw, accuracy):
    mv = from_card("sprint", raw)
    v = mv.setup.values
    on = mv.setup.asm.on
    R = v["battery_resistance"] if "battery_sag" in on else 0.0
    battery = Battery(ocv_table=((1.0, v["voltage"]),), resistance=R) if R else IdealSource(v["voltage"])
    res = MechanismMatch(
        (mv,), battery, Controller(brownout=0.1, recovery=0.2), length=60.0, rtol=LEVELS[accuracy]
    ).run()
    m = res.mechanisms[0]
    got = (m.time_to_goal, m.peak_stator_current, m.peak_supply_current, res.min_bus_voltage, m.energy)
    return dict(zip(KEYS, got)), res


CASES = [
    {"effects": ""},
    {"effects": "rolling_resistance"},  # traction-limited, then gripping at full duty
    {"effects": "stator_limit, supply_limit, rolling_resistance"},
    {"effects": "stator_limit, supply_limit, battery_sag, rolling_resistance"},  # the preset's
    {"effects": "stator_limit, supply_limit, battery_sag, rolling_resistance", "stator_current_limit": 40},
    {"effects": "stator_limit, battery_sag, rolling_resistance, air_drag, weight_transfer"},
    {"effects": "battery_sag, rolling_resistance", "ratio": 12},  # never slips
    {"effects": "stator_limit, supply_limit, battery_sag", "supply_current_limit": 30},  # slips on I_sup
    {"effects": "battery_sag, rolling_resistance", "ratio": 40, "distance": 16.54},  # stiff: LSODA
]


@pytest.mark.parametrize("accuracy", ["default", "fine"])
@pytest.mark.parametrize("raw", CASES)
def test_a_sprint_alone_is_its_card(raw, accuracy):
    want = card(raw)
    got, res = alone(raw, accuracy)
    tol = 20 * LEVELS[accuracy]
    for k in KEYS:
        assert got[k] == pytest.approx(want[k], rel=tol, abs=tol), k
    assert res.energy_oc == pytest.approx(res.energy_bus + res.energy_r, rel=tol)  # (M5)
    assert res.energy_oc == pytest.approx(got["energy"], rel=tol)
    # the distance crossed, the speed there, and the traction-limited phase (slip until the grip)
    s = model.solve("sprint", dict(raw, accuracy="tight")).outputs
    m = res.mechanisms[0]
    _, x_end, v_end = [r for r in m.trace if r[0] == m.arrival][0]
    assert x_end == pytest.approx(mv_distance(raw), rel=tol)
    assert v_end == pytest.approx(s["speed_at_distance"].value, rel=tol)
    grips = [t for t, n in res.switches if n == "branch0:grip"]
    slip = grips[0] if grips else 0.0
    assert slip == pytest.approx(s["traction_time"].value, rel=tol, abs=tol)


def mv_distance(raw):
    return from_card("sprint", raw).setup.distance


def test_slip_then_grip_is_located():
    """Traction-limited at the start (slip), then gripping: the switch is an event, the supply
    current constant before it (B7) and continuous across it (full duty: I_slip both sides)."""
    got, res = alone({"effects": "rolling_resistance"}, "fine")
    names = [n for _, n in res.switches]
    assert names == ["branch0:grip", "goal0"]
    t_grip = res.switches[0][0]
    before = [i for t, _, i in res.trace if t < t_grip]
    assert max(before) == pytest.approx(min(before), rel=1e-12)  # N·I_slip, constant
    at = [i for t, _, i in res.trace if t == t_grip]
    assert at[0] == pytest.approx(at[-1], rel=1e-9)
    assert card({"effects": "rolling_resistance"})["time_to_distance"] > t_grip


def test_brownout_coasts_the_robot():
    """A battery so weak the sprint browns the bus out at once: the motors coast (no current), the
    robot stays at rest (its loss and rolling resistance hold it), the outputs come back after the
    dwell, go off again: it never arrives."""
    mv = from_card("sprint", {"effects": "rolling_resistance"})
    res = MechanismMatch(
        (mv,), Battery(ocv_table=((1.0, 12.0),), resistance=0.05), Controller(), length=0.5
    ).run()
    assert res.brownouts and res.brownouts[0][0] == 0.0
    assert res.mechanisms[0].arrival is None
    assert all(q == 0.0 for _, q, _ in res.mechanisms[0].trace)


@pytest.mark.parametrize(
    "raw, field",
    [
        ({"mode": "optimise"}, "mode"),
        ({"effects": "voltage_ramp"}, "moves[0].effects"),
        ({"effects": "stator_limit", "stator_current_limit": 0.5}, "stator_current_limit"),
        ({"robot_mass": "heavy"}, "robot_mass"),
    ],
)
def test_bad_sprints_are_named(raw, field):
    with pytest.raises(InputError) as e:
        MechanismMatch((from_card("sprint", raw),)).run()
    assert e.value.field == field
