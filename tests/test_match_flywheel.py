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
