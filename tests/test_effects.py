"""The effects API on its own (core.sim.effects): a toy scene with a vector slot, a bound, an
effect that adds state and an event, as the migrated scenes (projectile, pneumatics, trebuchet)
will use it. The motor scenes' own checks are in tests/test_motion.py."""

import math

import pytest

from gearhead.core.model import Field, Output
from gearhead.core.sim.effects import Effect, Effects, Part, Slot
from gearhead.core.sim.integrate import Event, integrate

SLOTS = (Slot("accel", "vsum"), Slot("cap", "min"), Slot("heat", "sum"))


def _drag(values, ctx):
    k = values["k"]
    return Part(terms={"accel": lambda vx, vy: [-k * vx * math.hypot(vx, vy), -k * vy * math.hypot(vx, vy)]})


def _lift(values, ctx):
    c = values["c"]
    return Part(terms={"accel": lambda vx, vy: [-c * vy, c * vx]})


def _thermal(values, ctx):
    # adds one state (temperature) that the base scene knows nothing of, and an event on it
    return Part(
        states=(("temperature", 20.0),),
        derivative=lambda t, y: [1.0],
        events=(Event("hot", lambda t, y: y[-1] - 25.0, +1),),
        report=lambda run: {"final_temperature": run.y[-1][-1]},
    )


EFFECTS = Effects(
    Effect("drag", "quadratic drag", _drag, fields=(Field("k", "k", default=0.1),), default_on=True),
    Effect("lift", "lift", _lift, fields=(Field("c", "c", default=0.2), Field("k", "k", default=0.1))),
    Effect("cap1", "a bound", lambda v, c: Part(terms={"cap": lambda: 3.0})),
    Effect("cap2", "a bound", lambda v, c: Part(terms={"cap": lambda: 2.0})),
    Effect("thermal", "adds a state", _thermal, outputs=(Output("final_temperature", "T"),)),
)
VALUES = {"k": 0.1, "c": 0.2}


def assembled(on):
    return EFFECTS.assemble(frozenset(on), VALUES, None, SLOTS, ("x", "y", "vx", "vy"))


def test_fields_are_shown_only_with_the_effects_that_declare_them():
    fields = {f.name: f for f in EFFECTS.fields()}
    assert fields["k"].when == (("effects", ("drag", "lift")),)  # shared field: either effect
    assert fields["c"].when == (("effects", ("lift",)),)
    assert fields["c"].active(None, {"effects": frozenset({"drag"})}) is False
    assert fields["c"].active(None, {"effects": frozenset({"lift"})}) is True
    assert EFFECTS.field().default == "drag"
    assert [o.name for o in EFFECTS.outputs()] == ["final_temperature"]


def test_off_means_no_term_no_state_and_no_wrapper():
    base = lambda t, y: [y[2], y[3], 0.0, -9.8]  # noqa: E731
    a = assembled(())
    assert a.n_terms == 0 and a.slots == {"accel": None, "cap": None, "heat": None}
    assert a.states == ("x", "y", "vx", "vy") and a.rhs(base) is base and a.events == ()
    one = assembled({"drag"})
    assert one.n_terms == 1 and one.contributors["accel"] == ("drag",)
    assert one.slots["accel"] is one.parts["drag"].terms["accel"]  # a single term is used as is


def test_terms_combine_by_their_slot():
    a = assembled({"drag", "lift", "cap1", "cap2"})
    vx, vy = 3.0, 4.0
    got = a.slots["accel"](vx, vy)
    assert got == pytest.approx([-0.1 * 3 * 5 - 0.2 * 4, -0.1 * 4 * 5 + 0.2 * 3])
    assert a.slots["cap"]() == 2.0
    assert a.contributors == {"accel": ("drag", "lift"), "cap": ("cap1", "cap2"), "heat": ()}


def test_an_effect_that_adds_state_and_an_event_integrates_with_the_scene():
    a = assembled({"thermal"})
    assert a.states[-1] == "temperature" and a.y0_extra == (20.0,)
    rhs = a.rhs(lambda t, y: [y[2], y[3], 0.0, -9.8])
    run = integrate(rhs, 0.0, 100.0, [0.0, 0.0, 1.0, 10.0, *a.y0_extra], events=a.events)
    assert run.event == "hot" and run.t[-1] == pytest.approx(5.0, rel=1e-12)
    assert a.report(run) == {"final_temperature": pytest.approx(25.0)}


def test_unknown_effects_and_slots_are_refused():
    with pytest.raises(KeyError):
        assembled({"warp"})
    bad = Effects(Effect("x", "", lambda v, c: Part(terms={"nope": lambda: 0})))
    with pytest.raises(KeyError):
        bad.assemble({"x"}, {}, None, SLOTS)
