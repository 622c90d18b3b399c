"""The flywheel's spin-up on the match's bus (core/match/mechanisms.py _Flywheel): its torque law
derived with sympy, alone it is its card (spin-up time, peak currents, lowest bus), bad entries
named."""

import tomllib
from pathlib import Path

import pytest
import sympy as sp

from gearhead.core import model
from gearhead.core.errors import InputError
from gearhead.core.match.battery import Battery
from gearhead.core.match.brownout import Controller
from gearhead.core.match.mechanisms import IdealSource, MechanismMatch, from_card
from gearhead.core.sim.scene import LEVELS

KEYS = ("spin_up_time", "peak_stator_current", "peak_supply_current", "min_bus_voltage")
PRESET = tomllib.loads(
    (Path(__file__).resolve().parents[1] / "presets/flywheel/frc_two_kraken_limits.toml").read_text()
)["inputs"]


def test_torque_law_derived_with_sympy():
    """(F1) written as (B1): τ = A·(I − i_f)/(i_s − i_f) with I = (V_b − G·ω/Kv)/R is A at rest
    (i_s = V_b/R) and 0 at ω = Kv·(V_b − R·i_f)/G, the v_ref the bus scales by."""
    Vb, R, i_f, A, G, Kv, w = sp.symbols("V_b R i_f A G K_v omega", positive=True)
    i_s = Vb / R
    tau = A * ((Vb - G * w / Kv) / R - i_f) / (i_s - i_f)
    assert sp.simplify(tau.subs(w, 0) - A) == 0
    assert sp.simplify(sp.solve(sp.Eq(tau, 0), w)[0] - Kv * (Vb - R * i_f) / G) == 0


def alone(raw, accuracy):
    mv = from_card("flywheel", raw)
    v = mv.setup.values
    R = v["battery_resistance"] if "battery_sag" in v["effects"] else 0.0
    battery = Battery(ocv_table=((1.0, v["voltage"]),), resistance=R) if R else IdealSource(v["voltage"])
    res = MechanismMatch(
        (mv,), battery, Controller(brownout=0.1, recovery=0.2), length=60.0, rtol=LEVELS[accuracy]
    ).run()
    m = res.mechanisms[0]
    got = (m.time_to_goal, m.peak_stator_current, m.peak_supply_current, res.min_bus_voltage)
    return dict(zip(KEYS, got)), res


CASES = [
    PRESET,  # 40 A stator, 60 A supply, battery sag
    dict(PRESET, effects="battery_sag"),
    dict(PRESET, effects=""),
    dict(PRESET, effects="stator_limit"),
    dict(PRESET, effects="supply_limit, battery_sag", supply_current_limit="30 A"),
    {},  # the card's defaults (VEX 393s, the seed)
]


@pytest.mark.parametrize("accuracy", ["default", "fine"])
@pytest.mark.parametrize("raw", CASES)
def test_a_spin_up_alone_is_its_card(raw, accuracy):
    s = model.solve("flywheel", dict(raw, accuracy="tight"))
    got, res = alone(dict(raw, accuracy=accuracy), accuracy)
    tol = 20 * LEVELS[accuracy]
    for k in KEYS:
        if k in s.outputs:  # the electrical extremes: with an electrical effect
            assert got[k] == pytest.approx(s.outputs[k].value, rel=tol, abs=tol), k
    assert res.energy_oc == pytest.approx(res.energy_bus + res.energy_r, rel=tol)  # (M5)


@pytest.mark.parametrize(
    "raw, field",
    [
        (dict(PRESET, control="velocity_loop"), "control"),
        (dict(PRESET, target_speed="100000 rpm"), "target_speed"),
        (dict(PRESET, stator_current_limit="1 A"), "stator_current_limit"),
        (dict(PRESET, ratio="fast"), "ratio"),
    ],
)
def test_bad_spin_ups_are_named(raw, field):
    with pytest.raises(InputError) as e:
        MechanismMatch((from_card("flywheel", raw),)).run()
    assert e.value.field == field


BURSTS = [
    PRESET,  # stator-limited: constant torque between shots
    dict(PRESET, effects="battery_sag"),
    dict(PRESET, effects=""),
    dict(PRESET, transfer="energy"),
    {},  # the seed's (VEX 393s, four shots)
]


@pytest.mark.parametrize("accuracy", ["default", "fine"])
@pytest.mark.parametrize("raw", BURSTS)
def test_a_burst_alone_is_its_card(raw, accuracy):
    """(B11): the card's burst on the bus: its spin-up, the first shot on arrival, then one every
    shot_interval, each the card's shot (an instant drop); the slowest ball and the recovery after
    the first shot are the card's."""
    from gearhead.core.match.mechanisms import MechanismMove, burst
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get

    card = model.solve("flywheel", dict(raw, accuracy="tight")).outputs
    v = parse_inputs(get("flywheel"), dict(raw, accuracy=accuracy))[0]
    R = v["battery_resistance"] if "battery_sag" in v["effects"] else 0.0
    battery = Battery(ocv_table=((1.0, v["voltage"]),), resistance=R) if R else IdealSource(v["voltage"])
    move = MechanismMove("fw", burst(v), 0.0, hold=True)
    res = MechanismMatch(
        (move,), battery, Controller(brownout=0.1, recovery=0.2), length=10.0, rtol=LEVELS[accuracy]
    ).run()
    m = res.mechanisms[0]
    tol = 20 * LEVELS[accuracy]
    assert len(m.shots) == v["shots"]
    assert [t for t, *_ in m.shots] == pytest.approx(
        [m.arrival + j * v["shot_interval"] for j in range(v["shots"])], rel=1e-12
    )
    assert m.shots[0][1] == pytest.approx(card["ball_speed"].value, rel=1e-12)
    assert min(V for _, V, _, _ in m.shots) == pytest.approx(card["slowest_ball_speed"].value, rel=tol)
    t0 = m.shots[0][0]
    back = min(t for t, n in res.switches if n == "goal0" and t > t0)
    assert back - t0 == pytest.approx(card["recovery_time"].value, rel=tol)
    assert m.time_to_goal == pytest.approx(card["spin_up_time"].value, rel=tol)


def test_a_burst_with_the_motor_during_the_shot_is_refused():
    from gearhead.core.match.mechanisms import burst
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get

    v = parse_inputs(get("flywheel"), dict(PRESET, effects="motor_during_shot"))[0]
    with pytest.raises(InputError) as e:
        burst(v)
    assert e.value.field == "effects"
