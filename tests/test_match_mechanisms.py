"""Mechanisms on the match's bus (core/match/mechanisms.py, B1-B6): one alone is its card, two at
once share the bus, brownout disables them inside their equations."""

import math

import pytest
import sympy as sp

from gearhead.core import model
from gearhead.core.errors import InputError
from gearhead.core.match.battery import Battery
from gearhead.core.match.brownout import Controller
from gearhead.core.match.mechanisms import IdealSource, MechanismMatch, MechanismMove, from_card
from gearhead.core.sim.scene import LEVELS

G0 = 9.80665
LB = 0.45359237


def test_duty_branches_derived_with_sympy():
    """(B3)-(B5): the supply current u·I of each branch of the duty rule, in the bus voltage V."""
    V, E, R, I_st, I_sup, u, I = sp.symbols("V E R I_st I_sup u I", positive=True)
    stator = (u * V - E) / R  # motion (M2)
    # full duty: affine in V
    full = sp.expand((u * stator).subs(u, 1))
    assert sp.simplify(full - (-E / R + V / R)) == 0
    # stator limit: the duty that holds I = I_st, and the supply current: constant power
    u_st = sp.solve(sp.Eq(stator, I_st), u)[0]
    assert sp.simplify(u_st - (E + R * I_st) / V) == 0
    assert sp.simplify(u_st * I_st * V - (E + R * I_st) * I_st) == 0  # V·I_s independent of V
    # supply limit: u·I = I_sup: a constant current; its stator current the positive root of (B5)
    u_sup = sp.symbols("u_sup", positive=True)
    I_of = sp.solve(sp.Eq(I * (E + R * I) / V, I_sup), I)  # u = (E + R·I)/V from (M2)
    pos = [r for r in I_of if r.subs({E: 1, R: 0.1, I_sup: 30, V: 12}) > 0][0]
    assert sp.simplify(pos - 2 * I_sup * V / (E + sp.sqrt(E**2 + 4 * R * I_sup * V))) == 0
    del u_sup
    # the supply current rises with the duty wherever I ≥ 0: lowering the duty to a limit lowers it
    d = sp.diff(u * stator, u)
    assert sp.simplify(d - (2 * u * V - E) / R) == 0


def card(calc, raw):
    s = model.solve(calc, raw)
    return {
        k: s.outputs[k].value
        for k in ("time_to_goal", "peak_stator_current", "peak_supply_current", "min_bus_voltage", "energy")
    }


def alone(calc, raw, R_batt, V_b=12.0, accuracy="default"):
    """The card's move alone on a battery with a flat open-circuit voltage V_b and resistance R_batt."""
    mv = from_card(calc, raw)
    battery = Battery(ocv_table=((1.0, V_b),), resistance=R_batt) if R_batt else IdealSource(V_b)
    rtol = LEVELS[raw.get("accuracy", accuracy)]
    # brownout far below: the card knows none
    res = MechanismMatch((mv,), battery, Controller(brownout=0.1, recovery=0.2), length=60.0, rtol=rtol).run()
    m = res.mechanisms[0]
    return {
        "time_to_goal": m.time_to_goal,
        "peak_stator_current": m.peak_stator_current,
        "peak_supply_current": m.peak_supply_current,
        "min_bus_voltage": res.min_bus_voltage,
        "energy": m.energy,
    }, res


CASES = [
    ("elevator", {"effects": "gravity"}, 0.0),
    ("elevator", {"effects": "gravity, battery_sag"}, 0.02),
    ("elevator", {"effects": "gravity, stator_limit"}, 0.0),
    ("elevator", {"effects": "gravity, battery_sag, stator_limit"}, 0.02),
    (
        "elevator",
        {"effects": "gravity, battery_sag, stator_limit, supply_limit", "battery_resistance": 0.03},
        0.03,
    ),
    (
        "elevator",
        {
            "effects": "gravity, battery_sag, stator_limit",
            "stator_current_limit": 90,
            "battery_resistance": 0.05,
        },
        0.05,
    ),
    ("elevator", {"effects": "gravity, battery_sag, stator_limit", "ratio": 200}, 0.02),  # stiff: LSODA
    (
        "elevator",
        {
            "effects": "gravity, battery_sag, stator_limit",
            "stator_current_limit": 35,
            "battery_resistance": 0.1,
        },
        0.1,
    ),  # two roots at rest, merging at E = 1.14 V (test_constant_power_branch_is_continuous_with_two_roots)
    ("elevator", {"effects": "gravity, battery_sag, stator_limit", "travel": -40}, 0.02),  # down
    ("arm", {"effects": "gravity"}, 0.0),
    ("arm", {"effects": "gravity, battery_sag, stator_limit"}, 0.02),
    ("arm", {"effects": "gravity, battery_sag, stator_limit, supply_limit"}, 0.02),
]


@pytest.mark.parametrize("accuracy", ["default", "fine"])
@pytest.mark.parametrize("calc, raw, R", CASES)
def test_one_mechanism_alone_is_its_card(calc, raw, R, accuracy):
    raw = dict(raw, accuracy=accuracy)
    want = card(calc, raw)
    got, res = alone(calc, raw, R)
    tol = 20 * LEVELS[accuracy]
    for k in want:
        assert got[k] == pytest.approx(want[k], rel=tol, abs=tol), k
    # energy: what the cells gave = bus + resistance (M5), the mechanism its whole share
    assert res.energy_oc == pytest.approx(res.energy_bus + res.energy_r, rel=tol)
    assert res.energy_oc == pytest.approx(got["energy"], rel=tol)


ELEVATOR = {"effects": "gravity, battery_sag, stator_limit", "stator_current_limit": 60}
ARM = {"effects": "gravity, battery_sag, stator_limit", "stator_current_limit": 60}


def test_two_mechanisms_share_the_bus():
    battery = Battery(ocv_table=((1.0, 12.0),), resistance=0.02)
    low = Controller(brownout=0.1, recovery=0.2)
    el, ar = from_card("elevator", ELEVATOR), from_card("arm", ARM, start=0.0005)
    one = [MechanismMatch((m,), battery, low, length=2.0).run() for m in (el, ar)]
    both = MechanismMatch((el, ar), battery, low, length=2.0).run()
    assert both.min_bus_voltage < min(r.min_bus_voltage for r in one) - 0.1
    # each slower together than alone (less voltage)
    for k in range(2):
        assert both.mechanisms[k].time_to_goal > one[k].mechanisms[0].time_to_goal
    # energy balance (M5) to the solver's tolerance
    assert both.energy_oc == pytest.approx(both.energy_bus + both.energy_r, rel=1e-5)
    assert both.energy_oc == pytest.approx(sum(m.energy for m in both.mechanisms), rel=1e-5)
    # the bus is continuous in time (the branch followed) at every switch but where a load starts
    # or stops (the arm's start, the arrivals): at a branch switch both sides give one voltage
    switches = {0.0005} | {m.arrival for m in both.mechanisms}
    jumps = [
        abs(v1 - v0)
        for (t0, v0, _), (t1, v1, _) in zip(both.trace, both.trace[1:])
        if t1 == t0 and not any(abs(t0 - s) < 1e-12 for s in switches)
    ]
    assert jumps and max(jumps) < 1e-6


def test_constant_power_branch_is_continuous_with_two_roots():
    """Strong sag (I_st·R_bus = 35·0.2 = 7 > V_b/2, motion (E6)): the stator-limited bus
    α·V² − W·V + R·P = 0 has two roots; the upper one is followed, continuous in time, until they
    merge (the discriminant reaches 0: a located switch), then the only root left (full duty),
    below the vertex: the card's jump, and its peak supply current and lowest bus."""
    raw = {
        "effects": "gravity, battery_sag, stator_limit",
        "stator_current_limit": 35,
        "battery_resistance": 0.1,
    }
    got, res = alone("elevator", raw, 0.1, accuracy="fine")
    want = card("elevator", dict(raw, accuracy="fine"))
    names = [name for _, name in res.switches]
    assert names[:2] == ["merge", "goal0"]
    t_merge = res.switches[0][0]
    before = [(t, v) for t, v, _ in res.trace if t < t_merge]
    vertex = 12.0 / 2  # W/(2α) with A = B = 0 on the stator branch
    assert all(v >= vertex - 1e-6 for _, v in before)  # the upper root all along
    steps = [abs(v1 - v0) for (t0, v0), (t1, v1) in zip(before, before[1:])]
    assert max(steps) < 0.5  # continuous: no jump between steps before the merge
    at_merge = [v for t, v, _ in res.trace if t == t_merge]
    assert at_merge[0] == pytest.approx(vertex, rel=1e-3)  # the roots meet at the vertex
    assert at_merge[-1] == pytest.approx(want["min_bus_voltage"], rel=1e-7)  # the full-duty root: the jump
    assert got["peak_supply_current"] == pytest.approx(want["peak_supply_current"], rel=1e-7)
    assert got["min_bus_voltage"] == pytest.approx(want["min_bus_voltage"], rel=1e-7)
    assert got["time_to_goal"] == pytest.approx(want["time_to_goal"], rel=1e-7)


def test_brownout_mid_lift_by_hand():
    """Stator-limited lift (I_st = 30 A) on a weak battery: the current is I_st, so the carriage
    accelerates at a constant a = (η·N·Kt·n·I_st − m·g − F_f)/m; the bus V solves
    V·(V_oc − V) = R·N·(E + R_m·I_st)·I_st (B4, the upper root), so R is chosen for it to reach
    6.75 V at E_b = 2 V: t_b = E_b·Kv/(n·a). Then the motors coast: the carriage decelerates at
    (m·g + F_f)/m, stops, and falls at (m·g − F_f)/m until the outputs come back."""
    from gearhead.core.match.mechanisms import _Mech

    raw = {"effects": "gravity, stator_limit", "stator_current_limit": 30}
    mv = from_card("elevator", raw)
    m = mv.setup.mech
    E_b, I_st = 2.0, 30.0
    R = 6.75 * (12 - 6.75) / (2 * (E_b + m.R * I_st) * I_st)
    mk = _Mech("m", mv, 10.0)
    weight = -mk.field_force(0.0)
    a = (m.force_per_amp * I_st - mk.F_fric - weight) / m.inertia
    w_b = E_b * m.Kv / m.n
    t_b = w_b / a
    res = MechanismMatch(
        (mv,), Battery(ocv_table=((1.0, 12.0),), resistance=R), Controller(), length=3.0, rtol=1e-10
    ).run()
    assert res.brownouts, "a brownout"
    b0 = res.brownouts[0]
    assert b0[0] == pytest.approx(t_b, rel=1e-7)
    # only the motors loaded the bus: off, it is at 12 V > 7.5 V; back after the dwell
    assert b0[1] - b0[0] == pytest.approx(0.02, rel=1e-9)
    tr = [(t, q, w) for t, q, w in res.mechanisms[0].trace if b0[0] <= t <= b0[1]]
    t_stop = t_b + w_b * m.inertia / (weight + mk.F_fric)
    q_stop = 0.5 * a * t_b**2 + 0.5 * w_b**2 * m.inertia / (weight + mk.F_fric)
    fall = (weight - mk.F_fric) / m.inertia
    assert t_stop < b0[1]
    t_end, q_end, w_end = tr[-1]
    assert t_end == pytest.approx(b0[1], abs=1e-12)
    assert w_end == pytest.approx(-fall * (b0[1] - t_stop), rel=1e-6)  # falling
    assert q_end == pytest.approx(q_stop - 0.5 * fall * (b0[1] - t_stop) ** 2, rel=1e-6)
    assert q_end < max(q for _, q, _ in tr)
    assert res.min_bus_voltage == pytest.approx(6.75, abs=1e-6)


def test_brownout_at_stall_the_carriage_falls():
    """No limit, a battery so weak that the stall current pulls the bus below 6.75 V: the outputs
    go off at once, the carriage falls under gravity less friction; after each dwell the motors come
    back, falling (E < 0, more current than at stall), and go off again: it falls all along."""
    raw = {"effects": "gravity"}
    mv = from_card("elevator", raw)
    res = MechanismMatch(
        (mv,), Battery(ocv_table=((1.0, 12.0),), resistance=0.06), Controller(), length=0.2, rtol=1e-9
    ).run()
    m = mv.setup.mech
    from gearhead.core.match.mechanisms import _Mech

    mk = _Mech("m", mv, 10.0)
    g_net = (-mk.field_force(0.0) - mk.F_fric) / m.inertia  # weight less friction
    assert res.brownouts[0][0] == 0.0
    assert len(res.brownouts) in (10, 11)  # 20 ms each; the last may be a rounding's sliver
    assert sum(b - a for a, b in res.brownouts) == pytest.approx(0.2, rel=1e-9)
    t, q, w = res.mechanisms[0].trace[-1]
    assert t == pytest.approx(0.2)
    assert q == pytest.approx(-0.5 * g_net * 0.2**2, rel=1e-7)
    assert res.mechanisms[0].arrival is None


@pytest.mark.parametrize(
    "kwargs, field",
    [
        ({"length": math.nan}, "length"),
        ({"length": -1}, "length"),
        ({"rtol": "tight"}, "rtol"),
        ({"base_load": math.inf}, "base_load"),
        ({"moves": "elevator"}, "moves"),
        ({"moves": (1,)}, "moves[0]"),
        ({"battery": 12}, "battery"),
    ],
)
def test_hostile_inputs_name_the_field(kwargs, field):
    args = {"moves": (from_card("elevator", {}),), **kwargs}
    with pytest.raises(InputError) as e:
        MechanismMatch(**args).run()
    assert e.value.field == field


def test_hostile_moves_name_the_field():
    mv = from_card("elevator", {})
    for bad, field in (
        (MechanismMove("x", mv.setup, start=-1.0), "moves[0].start"),
        (MechanismMove("x", mv.setup, start=math.nan), "moves[0].start"),
        (MechanismMove("", mv.setup), "moves[0].name"),
        (MechanismMove("x", "setup"), "moves[0].setup"),
        (MechanismMove("x", mv.setup, brownout_disables=1), "moves[0].brownout_disables"),
    ):
        with pytest.raises(InputError) as e:
            MechanismMatch((bad,)).run()
        assert e.value.field == field
    with pytest.raises(InputError) as e:
        MechanismMatch((mv, mv)).run()
    assert e.value.field == "moves[1].name"
    with pytest.raises(InputError) as e:
        from_card("elevator", {"mode": "optimise"})
    assert e.value.field == "mode"
    with pytest.raises(InputError) as e:
        from_card("pneumatics", {})
    assert e.value.field == "card"
    with pytest.raises(InputError) as e:
        from_card("elevator", {"ratio": "fast"})
    assert e.value.field == "ratio"
    with pytest.raises(InputError) as e:  # 10^5 moves: refused before any work
        MechanismMatch((mv,) * 100_000).run()
    assert e.value.field == "moves"
    with pytest.raises(InputError) as e:  # a move that cannot leave: the card's own check names it
        MechanismMatch(
            (from_card("elevator", {"effects": "gravity, stator_limit", "stator_current_limit": 1}),)
        ).run()
    assert e.value.field == "stator_current_limit"
    with pytest.raises(InputError) as e:  # starting past the match's end
        MechanismMatch((MechanismMove("x", mv.setup, start=11.0),), length=10.0).run()
    assert e.value.field == "moves[0].start"


def test_the_solve_budget_bounds_it():
    from gearhead.core.sim.integrate import BudgetExceeded, budget

    mv = from_card("elevator", {})
    with pytest.raises(BudgetExceeded), budget(max_nfev=50):
        MechanismMatch(
            (mv,), Battery(ocv_table=((1.0, 12.0),), resistance=0.02), Controller(), length=1.0
        ).run()


def test_a_move_is_its_card_however_many_moves_are_done():
    """The moves done take no part in a piece (mechanisms._reduced, a speed-up: 1.76 -> 0.29 s
    here): with 60 moves before it, a lift alone on the bus at 20 s is still its card to 20·rtol."""
    raw = {"effects": "gravity, battery_sag, stator_limit", "accuracy": "default"}
    want = card("elevator", raw)
    mv = from_card("elevator", raw)
    arm = from_card("arm", {"effects": "gravity"})
    early = tuple(MechanismMove(f"a{k}", arm.setup, 0.0, after=k - 1 if k else None) for k in range(60))
    last = MechanismMove("lift", mv.setup, 20.0)
    battery = Battery(ocv_table=((1.0, 12.0),), resistance=0.02)
    low = Controller(brownout=0.1, recovery=0.2)
    res = MechanismMatch((*early, last), battery, low, length=25.0, rtol=LEVELS["default"]).run()
    m = res.mechanisms[-1]
    assert all(r.arrival is not None and r.arrival < 20.0 for r in res.mechanisms[:-1])
    tol = 20 * LEVELS["default"]
    assert m.time_to_goal == pytest.approx(want["time_to_goal"], rel=tol)
    assert m.energy == pytest.approx(want["energy"], rel=tol)
