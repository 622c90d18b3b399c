"""Holding at the goal on the match's bus (core/match/mechanisms.py (B10)): after its move a
mechanism that holds draws the current that holds it (the card's hold_current, constant power on
the bus), stays there exactly, stops when the card's next move starts or at its release, and sags
in a brownout (falling under gravity less friction, by hand), then moves back."""

import math
from dataclasses import replace

import pytest
import sympy as sp

from gearhead.core import model
from gearhead.core.errors import InputError
from gearhead.core.match.battery import Battery
from gearhead.core.match.brownout import Controller
from gearhead.core.match.mechanisms import (
    IdealSource,
    MechanismMatch,
    MechanismMove,
    _Flywheel,
    _Mech,
    from_card,
)

LOW = Controller(brownout=0.1, recovery=0.2)
LIFT = {"effects": "gravity"}


def test_hold_power_derived_with_sympy():
    """(B10): holding at stator current I_h at the held speed (back-EMF E) the duty is
    u = (E + R·I_h)/V (motion (M2)), so each motor's supply u·I_h = (E + R·I_h)·I_h/V: constant
    power; at rest R·I_h²."""
    V, E, R, I_h = sp.symbols("V E R I_h", positive=True)
    u = sp.solve(sp.Eq((sp.Symbol("u") * V - E) / R, I_h), sp.Symbol("u"))[0]
    assert sp.simplify(u * I_h * V - (E + R * I_h) * I_h) == 0
    assert sp.simplify((u * I_h * V).subs(E, 0) - R * I_h**2) == 0


def test_an_elevator_holds_its_goal_on_its_hold_current():
    card = model.solve("elevator", dict(LIFT, accuracy="fine")).outputs
    mv = from_card("elevator", LIFT)
    held = MechanismMove("lift", mv.setup, 0.0, hold=True)
    res = MechanismMatch((held,), IdealSource(12.0), LOW, length=3.0, rtol=1e-9).run()
    alone = MechanismMatch((mv,), IdealSource(12.0), LOW, length=3.0, rtol=1e-9).run()
    m, a = res.mechanisms[0], alone.mechanisms[0]
    assert m.arrival == pytest.approx(card["time_to_goal"].value, rel=1e-8)
    mk = _Mech("m", held, 3.0)
    I_h = card["hold_current"].value  # the card's own: per motor, at the goal against gravity
    assert mk.I_hold == pytest.approx(I_h, rel=1e-12)
    after = [(t, q, w) for t, q, w in m.trace if t > m.arrival]
    q_goal = mv.setup.mech.q1
    assert after and all(q == q_goal and w == 0.0 for _, q, w in after)  # stays exactly there
    p = mk.N * mk.R * I_h**2  # (B10) at rest
    currents = [i for t, _, i in res.trace if t > m.arrival]
    assert currents == pytest.approx([p / 12.0] * len(currents), rel=1e-12)
    assert m.energy - a.energy == pytest.approx(p * (3.0 - m.arrival), rel=1e-9)
    assert m.peak_stator_current == pytest.approx(a.peak_stator_current, rel=1e-12)


def test_a_flywheel_holds_its_speed_on_its_loss_current():
    raw = {"effects": ""}
    mv = from_card("flywheel", raw)
    held = MechanismMove("shooter", mv.setup, 0.0, hold=True)
    res = MechanismMatch((held,), IdealSource(mv.setup.values["voltage"]), LOW, length=3.0).run()
    m = res.mechanisms[0]
    mk = _Flywheel("m", held, 3.0)  # the terms by hand: E at the target, I_h = i_f
    E = mv.setup.target * mk.n_kv
    V = mv.setup.values["voltage"]
    p = mk.N * (E + mk.R * mk.I_hold) * mk.I_hold
    assert all(w == mv.setup.target for t, _, w in m.trace if t > m.arrival)
    currents = [i for t, _, i in res.trace if t > m.arrival]
    assert currents == pytest.approx([p / V] * len(currents), rel=1e-12)
    assert m.time_to_goal == pytest.approx(
        model.solve("flywheel", raw).outputs["spin_up_time"].value, rel=2e-5
    )


def test_the_hold_ends_at_the_next_move_or_its_release():
    mv = from_card("elevator", LIFT)
    up = MechanismMove("up", mv.setup, 0.0, hold=True, channel="lift")
    back = from_card("elevator", dict(LIFT, travel=-40))
    down = MechanismMove("down", back.setup, 2.0, after=0, hold=True, channel="lift", release=3.0)
    res = MechanismMatch((up, down), IdealSource(12.0), LOW, length=4.0).run()
    u, d = res.mechanisms
    assert max(t for t, _, _ in u.trace) == pytest.approx(2.0)  # held until the next move started
    assert d.arrival is not None and d.arrival < 3.0
    assert max(t for t, _, _ in d.trace) == pytest.approx(3.0)  # released at 3 s
    assert all(i == 0.0 for t, _, i in res.trace if t > 3.0)  # nothing drawn after


def test_held_at_the_goal_it_sags_in_a_brownout_then_moves_back():
    """A lift holds at its goal; at 2 s a second lift's stall pulls the weak bus below 6.75 V at
    once: both coast; the held one falls from rest at its goal at (weight − friction)/M, by hand,
    until the outputs return after the dwell, then its motors push it back toward the goal."""
    held = from_card("elevator", {"effects": "gravity, stator_limit", "stator_current_limit": 20})
    A = MechanismMove("A", held.setup, 0.0, hold=True)
    B = MechanismMove("B", from_card("elevator", {"effects": "gravity"}).setup, 2.0)
    res = MechanismMatch(
        (A, B), Battery(ocv_table=((1.0, 12.0),), resistance=0.06), Controller(), length=2.1, rtol=1e-10
    ).run()
    a = res.mechanisms[0]
    assert a.arrival < 2.0
    b0, b1 = res.brownouts[0]
    assert b0 == pytest.approx(2.0, abs=1e-12) and b1 - b0 == pytest.approx(0.02, rel=1e-9)
    mk = _Mech("A", A, 2.1)
    g_net = (-mk.field_force(mk.d) - mk.F_fric) / mk.M  # weight less friction, at the goal
    assert g_net > 0
    q_goal = held.setup.mech.q1
    inside = [(t, q, w) for t, q, w in a.trace if b0 < t <= b1]
    for t, q, w in inside:
        assert q == pytest.approx(q_goal - 0.5 * g_net * (t - b0) ** 2, rel=1e-9, abs=1e-12)
        assert w == pytest.approx(-g_net * (t - b0), rel=1e-7)
    # the stalled lift browns the bus out again at once each time: the held one falls all along
    t_end, q_end, _ = a.trace[-1]
    assert q_end == pytest.approx(q_goal - 0.5 * g_net * (t_end - 2.0) ** 2, rel=1e-9)


def test_after_a_sag_the_outputs_return_and_it_moves_back_up():
    """The second lift stator-limited so that the bus reaches 6.75 V mid-move (R as in
    test_match_mechanisms' brownout by hand): between its brownouts the outputs are on, and the
    held lift, sagged, is driven back up (its speed rises) on its move's own equations."""
    held = from_card("elevator", {"effects": "gravity, stator_limit", "stator_current_limit": 20})
    A = MechanismMove("A", held.setup, 0.0, hold=True)
    b = from_card("elevator", {"effects": "gravity, stator_limit", "stator_current_limit": 30})
    m = b.setup.mech
    R = 6.75 * (12 - 6.75) / (2 * (2.0 + m.R * 30.0) * 30.0)
    B = MechanismMove("B", b.setup, 2.0)
    res = MechanismMatch(
        (A, B), Battery(ocv_table=((1.0, 12.0),), resistance=R), Controller(), length=2.2, rtol=1e-10
    ).run()
    a = res.mechanisms[0]
    (b0, b1), (c0, _) = res.brownouts[:2]
    assert a.arrival < b0 and c0 > b1  # an enabled window between two brownouts
    q_goal = held.setup.mech.q1
    window = [(t, q, w) for t, q, w in a.trace if b1 <= t <= c0]
    assert window[0][1] < q_goal and window[0][2] < 0  # sagged, falling when the outputs return
    assert window[-1][2] > window[0][2]  # pushed back up


def test_bad_holds_are_named():
    mv = from_card("elevator", LIFT)
    for bad, field in (
        (MechanismMove("x", mv.setup, hold="yes"), "moves[0].hold"),
        (MechanismMove("x", mv.setup, hold=True, release=-1.0), "moves[0].release"),
        (MechanismMove("x", from_card("sprint", {}).setup, hold=True), "moves[0].hold"),
        (MechanismMove("x", mv.setup, hard_stops=1), "moves[0].hard_stops"),
        (MechanismMove("x", from_card("sprint", {}).setup, hard_stops=True), "moves[0].hard_stops"),
        (MechanismMove("x", from_card("flywheel", {}).setup, hard_stops=True), "moves[0].hard_stops"),
        (MechanismMove("x", from_card("flywheel", {}).setup, carry="yes"), "moves[0].carry"),
        (
            MechanismMove("x", replace(from_card("flywheel", {}).setup, shots=math.nan)),
            "moves[0].setup.shots",
        ),
        (
            MechanismMove("x", replace(from_card("flywheel", {}).setup, interval=-1.0)),
            "moves[0].setup.interval",
        ),
    ):
        with pytest.raises(InputError) as e:
            MechanismMatch((bad,)).run()
        assert e.value.field == field


def test_hard_stops_carry_it_at_the_ends_of_its_travel():
    """(B12) with hard_stops: a lift browned out at its start stays on its bottom stop instead of
    falling through the floor; one held at the top and browned out all along falls, by hand, onto
    its bottom stop and rests there; a move whose goal is the bottom needs no holding current."""
    stall = from_card("elevator", {"effects": "gravity"})
    weak = Battery(ocv_table=((1.0, 12.0),), resistance=0.06)
    one = MechanismMove("x", stall.setup, 0.0, hard_stops=True)
    res = MechanismMatch((one,), weak, Controller(), length=0.2).run()
    assert res.brownouts[0][0] == 0.0 and all(q == 0.0 and w == 0.0 for _, q, w in res.mechanisms[0].trace)
    held = from_card("elevator", {"effects": "gravity, stator_limit", "stator_current_limit": 20})
    A = MechanismMove("A", held.setup, 0.0, hold=True, hard_stops=True)
    B = MechanismMove("B", stall.setup, 2.0)
    res = MechanismMatch((A, B), weak, Controller(), length=4.0, rtol=1e-10).run()
    a = res.mechanisms[0]
    mk = _Mech("A", A, 4.0)
    g_net = (-mk.field_force(mk.d) - mk.F_fric) / mk.M
    t_floor = 2.0 + (2 * mk.d / g_net) ** 0.5  # falls the whole travel from rest
    hits = [t for t, n in res.switches if n == "wall0"]
    assert hits and hits[0] == pytest.approx(t_floor, rel=1e-7)
    assert all(q == held.setup.mech.q0 and w == 0.0 for t, q, w in a.trace if t > hits[0])
    down = from_card("elevator", {"effects": "gravity", "travel": -40})
    assert _Mech("d", MechanismMove("d", down.setup, hold=True, hard_stops=True), 1.0).I_hold == 0.0
    assert _Mech("d", MechanismMove("d", down.setup, hold=True), 1.0).I_hold < 0.0  # held up from below
