"""The trebuchet's effects (core.sim.trebuchet.EFFECTS): for each, off means no extra state and no
extra right-hand-side term (the assembled scene has neither), on adds them and changes the result.
Also the retired 'optimise' flag (core.sim.effects.RetiredFlags, retire)."""

import math
import random

import pytest

from gearhead.core.calculators import trebuchet as calc
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import trebuchet as tb
from gearhead.core.sim.effects import RetiredFlags, retire

SEED = dict(M=500, k=2, m=50, L=15, a=0.25, h=4, m_p=5, l=5, g=9.81)
DEG = math.pi / 180


def scene(ground_contact=False, **kw):
    return tb.build(tb.Machine(**{**SEED, **kw}), ground_contact)


def state(sc):
    """A state away from rest, of the scene's own length."""
    return [0.3, 1.1, 2.4, 0.7, 0.2, -0.4][: sc.n]


def out(effects, **raw):
    return solve("trebuchet", {"effects": effects, **raw}).outputs


def test_the_arm_alone_has_two_states_and_no_term():
    sc = scene(sling=False)
    assert sc.asm.on == () and sc.asm.states == ("phi", "omega")
    assert sc.asm.n_terms == 0 and all(v is None for v in sc.asm.slots.values())
    assert sc.contact is None and sc.mobility is None
    assert len(sc.rhs(False)(0.0, state(sc))) == 2
    # no term: the arm's own equation, ω̇ = −g·(m·s − M·r + m_p·R)·cos φ / (I_φ + m_p·R²) (T5, T6)
    p = sc.p
    wd = -p.g * (p.m * p.s - p.M * p.r + p.m_p * p.R) * math.cos(0.3) / (p.I_phi + p.m_p * p.R**2)
    assert sc.rhs(False)(0.0, [0.3, 1.1])[1] == pytest.approx(wd, rel=1e-14)


def test_sling_adds_two_states_and_its_terms_only_when_on():
    off, on = scene(sling=False), scene()
    assert on.asm.on == ("sling",) and on.asm.states == ("phi", "omega", "gamma", "gamma_dot")
    assert on.asm.contributors["coupling"] == ("sling",) and on.asm.contributors["tip"] == ("sling",)
    assert off.asm.n_terms == 0 and on.asm.n_terms == 3  # coupling, energy, tip
    assert len(on.rhs(False)(0.0, state(on))) == 4 and len(off.rhs(False)(0.0, state(off))) == 2
    assert tb.initial_state(on.p) == [on.p.phi0, 0.0, math.pi, 0.0]  # the sling lies flat, toward the pivot
    a, b = out(""), out("sling")
    assert b["release_speed"].value > 1.5 * a["release_speed"].value  # the sling whips the projectile


def test_hinged_counterweight_at_its_centre_adds_no_state_but_changes_the_inertia():
    rigid, hinged = scene(), scene(rigid=False)
    assert hinged.asm.on == ("sling", "hinged_counterweight")
    assert hinged.asm.states == rigid.asm.states and hinged.asm.n_terms == rigid.asm.n_terms
    assert rigid.p.I_phi - hinged.p.I_phi == pytest.approx(500 * 2**2, rel=1e-14)  # M·k² (T1, seed 1.2)
    a, b = out("sling"), out("sling, hinged_counterweight", hanger_length=0)
    assert b["arm_speed_at_vertical"].value != pytest.approx(a["arm_speed_at_vertical"].value, rel=1e-3)


def test_hinged_counterweight_on_a_hanger_adds_the_pendulum():
    sc = scene(rigid=False, d=0.5)
    assert sc.asm.states == ("phi", "omega", "gamma", "gamma_dot", "psi", "psi_dot")
    assert sc.asm.contributors["coupling"] == ("sling", "hinged_counterweight")
    assert sc.asm.contributors["hanger"] == ("hinged_counterweight",)
    assert sc.asm.offset("hinged_counterweight") == 4
    assert len(sc.rhs(False)(0.0, state(sc))) == 6
    a = out("sling, hinged_counterweight", hanger_length=0)
    b = out("sling, hinged_counterweight", hanger_length="0.5 m")
    assert b["range"].value != pytest.approx(a["range"].value, rel=1e-3)


def test_ground_contact_adds_the_constraint_and_no_state():
    off, on = scene(), scene(ground_contact=True)
    assert on.asm.states == off.asm.states
    assert off.contact is None and off.asm.contributors["constraint"] == ()
    assert on.asm.contributors["constraint"] == ("ground_contact",) and on.asm.n_terms == off.asm.n_terms + 1
    y = tb.initial_state(on.p)
    free = off.rhs(False)(0.0, y)
    held = on.rhs(True)(0.0, y)
    assert held != free  # the ground holds the projectile up at rest
    assert on.accelerations(y, True)[1] > 0  # the ground pushes up
    # on the ground the constraint's second derivative holds: J·q̈ = R·sin φ·ω² + l·sin γ·γ̇² (T7)
    y = [0.3, 1.1, 2.4, 0.7]
    (x1, x2), _ = on.accelerations(y, True)
    p = on.p
    J_qdd = p.R * math.cos(y[0]) * x1 + p.l * math.cos(y[2]) * x2
    assert J_qdd == pytest.approx(p.R * math.sin(0.3) * 1.1**2 + p.l * math.sin(2.4) * 0.7**2, rel=1e-12)
    (f1, f2), _ = off.accelerations(y, False)
    assert p.R * math.cos(y[0]) * f1 + p.l * math.cos(y[2]) * f2 != pytest.approx(J_qdd, rel=1e-3)
    a, b = out("sling"), out("sling, ground_contact")
    assert "liftoff_time" in b and "liftoff_time" not in a
    assert b["range"].value != pytest.approx(a["range"].value, rel=1e-3)


def test_ground_contact_without_the_sling_is_not_built():
    """The ground holds the projectile on a sling; with the cup at C it adds nothing (and says so)."""
    p = tb.Machine(**SEED, sling=False)
    assert p.effects(ground_contact=True) == frozenset()
    assert tb.build(p, True).contact is None
    sol = solve("trebuchet", {"effects": "ground_contact"})
    assert any("ground_contact needs the sling" in w for w in sol.warnings)


def test_air_drag_adds_nothing_to_the_swing_and_integrates_the_flight():
    v_off = parse_inputs(get("trebuchet"), {"effects": "sling"})[0]
    v_on = parse_inputs(get("trebuchet"), {"effects": "sling, air_drag"})[0]
    p = calc.machine(v_on)
    swing_work = tb.swing(p, v_on["release_angle"], False, 1e-6).nfev
    assert calc.simulate(v_off, 1e-6).nfev == swing_work  # vacuum flight: closed form, no integration
    assert calc.simulate(v_on, 1e-6).nfev > swing_work  # drag: the flight is integrated
    assert tb.EFFECTS.by_name["air_drag"].build(v_on, tb.Ctx(p)).terms == {}
    a, b = out("sling"), out("sling, air_drag")
    assert 0 < b["range"].value < a["range"].value


def test_effect_fields_are_shown_only_with_their_effect():
    c = get("trebuchet")
    assert c.field("sling_length").when == (("effects", ("sling",)),)
    assert c.field("hanger_length").when == (("effects", ("hinged_counterweight",)),)
    assert c.field("drag_coefficient").when == (("effects", ("air_drag",)),)
    assert not c.field("sling_length").active("throw", {"effects": frozenset()})
    assert c.output("liftoff_time").equation


def test_every_output_says_how_it_is_obtained():
    for o in get("trebuchet").outputs:
        assert o.help and "\n" not in o.help, o.name
        if o.name not in ("candidates", "error_estimate", "rhs_evaluations", "wall_time"):
            assert o.equation, o.name


# --- the retired flag (generic, core.sim.effects) --------------------------------------------------


def test_retired_flags_are_read_but_not_offered():
    f = get("trebuchet").field("effects")
    assert isinstance(f, RetiredFlags) and "optimise" not in f.choices
    assert f.parse("sling, optimise") == frozenset({"sling", "optimise"})
    assert f.parse(["optimise"]) == frozenset({"optimise"})
    with pytest.raises(InputError, match="unknown 'warp'"):
        f.parse("sling, warp")


def test_retire_rewrites_the_inputs_and_keeps_what_was_set():
    fields = get("trebuchet").fields
    inputs, notes = retire(fields, {"effects": "sling, optimise, air_drag"})
    assert inputs == {"effects": "sling, air_drag", "mode": "optimise"} and len(notes) == 1
    inputs, notes = retire(fields, {"effects": ["optimise"], "mode": "optimise"})
    assert inputs == {"effects": [], "mode": "optimise"} and len(notes) == 1
    # the old name wins over the mode beside it (a default filled in, or the newer field an old name
    # was written over), as the calculator itself honoured the flag before, with the notice
    inputs, notes = retire(fields, {"effects": "optimise", "mode": "throw"})
    assert inputs == {"effects": "", "mode": "optimise"} and len(notes) == 1
    assert retire(fields, {"effects": "sling"}) == ({"effects": "sling"}, [])


@pytest.mark.parametrize("kw", [{}, dict(rigid=False, d=0.5)])
def test_the_unrolled_elimination_is_the_loop_to_the_bit(kw):
    """One and two couplings run (T6) unrolled; the general loop (any number) must give the same
    bits: inert couplings (M1j = 0, Mjj = 1, no force) up to three send them through the loop."""
    sc = scene(**kw)
    p = sc.p
    m11 = p.I_phi + p.m_p * p.R * p.R
    K1 = -p.g * (p.m * p.s - p.M * p.r + p.m_p * p.R)
    dofs = sc.asm.with_state("coupling")
    unrolled = tb._elimination(m11, K1, math.cos, dofs)
    inert = (0, lambda phi, w, q, qd: (0.0, 1.0, 0.0, 0.0))
    loop = tb._elimination(m11, K1, math.cos, dofs + (inert,) * (3 - len(dofs)))
    assert unrolled.__name__ != loop.__name__ == "solve"
    rnd = random.Random(5)
    for _ in range(200):
        y = [rnd.uniform(-3, 3) for _ in range(6)]
        xs, _, den = unrolled(y[0], y[1], y[: sc.n])
        xl, _, den_l = loop(y[0], y[1], y[: sc.n])
        assert xl[: len(xs)] == xs and den_l == den and xl[len(xs) :] == [0.0] * (3 - len(dofs))
