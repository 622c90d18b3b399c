"""The projectile and pneumatics scenes on the effects API (core.sim.effects): for each effect,
off means it is not even built (no term in any slot, no state, no event, no call during the run),
on means its term is called at every right-hand-side evaluation and the result changes.

Every term and event an effect builds is wrapped here with a counter (the catalogue's entry is
replaced for the test), and the integrator the scene calls is wrapped to record the state length
and to count the evaluations independently of the integrator's own count."""

import dataclasses
import math

import pytest

from gearhead.core.calculators import pneumatics as pn
from gearhead.core.calculators import projectile as pj
from gearhead.core.model import parse_inputs
from gearhead.core.registry import get
from gearhead.core.sim import flight
from gearhead.core.sim.integrate import Event

G = 9.80665


class Spy:
    """Counts the builds, term calls and event-function calls of a catalogue's effects, and what
    the scene hands the integrator (state length, right-hand-side evaluations)."""

    def __init__(self, monkeypatch, effects, module):
        self.built: list[str] = []
        self.term_calls: dict[str, int] = {}
        self.event_calls: dict[str, int] = {}
        self.states: list[int] = []
        self.rhs_calls = 0
        for name, effect in list(effects.by_name.items()):
            monkeypatch.setitem(effects.by_name, name, dataclasses.replace(effect, build=self._build(effect)))
        original = module.integrate

        def integrate(rhs, t0, t1, y0, *args, **kwargs):
            self.states.append(len(y0))

            def counted(t, y):
                self.rhs_calls += 1
                out = rhs(t, y)
                assert len(out) == len(y0)
                return out

            return original(counted, t0, t1, y0, *args, **kwargs)

        monkeypatch.setattr(module, "integrate", integrate)

    def _build(self, effect):
        def build(values, ctx):
            self.built.append(effect.name)
            part = effect.build(values, ctx)
            self.term_calls.setdefault(effect.name, 0)
            self.event_calls.setdefault(effect.name, 0)

            def term(fn):
                def counted(*a):
                    self.term_calls[effect.name] += 1
                    return fn(*a)

                return counted

            def event(ev):
                def g(t, y):
                    self.event_calls[effect.name] += 1
                    return ev.g(t, y)

                return Event(ev.name, g, ev.direction, ev.terminal)

            return dataclasses.replace(
                part,
                terms={s: term(f) for s, f in part.terms.items()},
                events=tuple(event(ev) for ev in part.events),
            )

        return build


# --- projectile ------------------------------------------------------------------------------------


def pj_values(**raw):
    return parse_inputs(get("projectile"), {"spin": "2000 rpm", **raw})[0]


@pytest.mark.parametrize("on", ["", "air_drag", "magnus", "air_drag, magnus"])
def test_projectile_effect_off_is_not_built_and_on_is_called_at_every_evaluation(monkeypatch, on):
    spy = Spy(monkeypatch, pj.EFFECTS, flight)
    run = pj.simulate(pj_values(effects=on), 1e-6)
    names = [n.strip() for n in on.split(",") if n.strip()]
    assert spy.built == names  # an effect that is off is not even built
    assert set(spy.states) <= {4}  # (x, y, vx, vy): no effect adds state
    if not names:
        assert run.nfev == 0 and spy.states == [] and spy.rhs_calls == 0  # closed form, nothing integrated
        return
    assert spy.rhs_calls == run.nfev > 0  # the spy sees every evaluation the scene reports
    for name in names:
        assert spy.term_calls[name] == spy.rhs_calls  # one call of each term per evaluation, no more
    asm = pj.scene_air(pj_values(effects=on)).assembly
    assert asm.contributors == {"accel": tuple(names)} and asm.n_terms == len(names)
    assert asm.states == flight.STATES and asm.events == () and asm.y0_extra == ()


def test_projectile_each_effect_on_changes_the_flight():
    heights = {
        on: pj.simulate(pj_values(effects=on), 1e-9).values["target_height"]
        for on in ("", "air_drag", "magnus", "air_drag, magnus")
    }
    assert heights["air_drag"] < heights[""] < heights["magnus"]  # drag lowers it, backspin lifts it
    assert heights["air_drag"] < heights["air_drag, magnus"] < heights["magnus"]


def test_projectile_effect_on_with_no_force_adds_no_term():
    """magnus on with zero spin (or air_drag with C_d = 0) exerts nothing: no term, closed form."""
    for raw in ({"effects": "magnus", "spin": 0}, {"effects": "air_drag", "drag_coefficient": 0}):
        a = pj.scene_air(pj_values(**raw))
        assert a.vacuum and a.assembly.n_terms == 0
        assert pj.simulate(pj_values(**raw), 1e-6).nfev == 0


def test_magnus_owns_the_spin_ratio_output():
    assert "spin_ratio" not in pj.simulate(pj_values(effects="air_drag"), 1e-6).values
    got = pj.simulate(pj_values(effects="magnus"), 1e-6).values["spin_ratio"]
    assert got == pytest.approx(2000 * 2 * math.pi / 60 * 0.12 / 7.5, rel=1e-12)  # |ω|·r/v_i, release 7.5 m/s


def test_assembled_drag_and_magnus_flight_against_solve_ivp():
    """The assembled right-hand side (both terms folded onto gravity) against scipy's DOP853 on the
    equations written out here: a = −k_d|v|v + k_m|v|(−vy, vx) − g·ŷ."""
    from scipy.integrate import solve_ivp

    kd, km, h, th, v0, d = 0.04, 0.015, 0.5, 0.7, 11.0, 6.0

    def rhs(t, s):
        speed = math.hypot(s[2], s[3])
        return [
            s[2],
            s[3],
            -kd * speed * s[2] - km * speed * s[3],
            -G - kd * speed * s[3] + km * speed * s[2],
        ]

    hit = lambda t, s: s[0] - d  # noqa: E731
    hit.terminal = True
    ref = solve_ivp(
        rhs,
        (0, 30),
        [0, h, v0 * math.cos(th), v0 * math.sin(th)],
        method="DOP853",
        rtol=1e-13,
        atol=1e-14,
        events=hit,
    )
    f = flight.fly(flight.air_with(G, kd, km), h, th, v0, d, 1e-11)
    assert f.reached
    assert f.t == pytest.approx(ref.t_events[0][0], rel=1e-9)
    assert f.height == pytest.approx(ref.y_events[0][0][1], rel=1e-9)


# --- pneumatics ------------------------------------------------------------------------------------


def pn_values(**raw):
    return parse_inputs(get("pneumatics"), raw)[0]


CASES = [
    "",
    "compressor",
    "compressor, pressure_switch",
    "compressor, regulator",
    "compressor, pressure_switch, regulator",
    "pressure_switch, regulator",
]


@pytest.mark.parametrize("on", CASES)
def test_pneumatics_effect_off_is_not_built_and_on_is_called(monkeypatch, on):
    spy = Spy(monkeypatch, pn.EFFECTS, pn)
    run = pn.simulate(pn_values(effects=on), 1e-6)
    names = [n.strip() for n in on.split(",") if n.strip()]
    assert spy.built == names
    assert set(spy.states) <= {1}  # storage pressure only: no effect adds state
    asm = pn.assemble(pn_values(effects=on))
    assert asm.states == ("pressure",) and asm.y0_extra == ()
    if "compressor" not in names:
        assert asm.slots["inflow"] is None and run.nfev == 0 and spy.rhs_calls == 0  # closed form
    else:
        assert asm.contributors["inflow"] == ("compressor",)
        assert spy.term_calls["compressor"] == spy.rhs_calls == run.nfev > 0
    if "pressure_switch" in names:
        assert [ev.name for ev in asm.events] == ["switch_off"]
        assert spy.event_calls["pressure_switch"] > 0 or "compressor" not in names
    else:
        assert asm.events == () and "switch_on" not in asm.params
    assert ("regulated" in asm.params) == ("regulator" in names)
    assert asm.n_terms == ("compressor" in names)  # the only term any pneumatics effect adds


@pytest.mark.parametrize("effect", ["compressor", "pressure_switch", "regulator"])
def test_pneumatics_each_effect_on_changes_the_match(effect):
    full = "compressor, pressure_switch, regulator"
    without = ", ".join(e for e in full.split(", ") if e != effect)
    a = pn.simulate(pn_values(effects=full), 1e-9).values
    b = pn.simulate(pn_values(effects=without), 1e-9).values
    assert (a["final_pressure"], a["compressor_duty"]) != (b["final_pressure"], b["compressor_duty"])
    if effect == "compressor":
        assert b["compressor_duty"] == 0 and b["final_pressure"] < a["final_pressure"]
    if effect == "pressure_switch":  # without it the motor runs all match
        assert b["compressor_duty"] == 1.0 > a["compressor_duty"]
    if effect == "regulator":  # unregulated strokes take air at storage pressure (> 60 psi)
        assert b["min_pressure"] < a["min_pressure"]


def test_pressure_model_is_a_choice_not_an_effect():
    """Absolute bookkeeping changes the firing map only: the same parts, slots and states."""
    gauge, absolute = pn_values(), pn_values(pressure_model="absolute")
    a, b = pn.assemble(gauge), pn.assemble(absolute)
    assert (a.on, a.contributors, a.states) == (b.on, b.contributors, b.states)
    assert "absolute_pressure" not in pn.EFFECTS.names
    assert (
        pn.simulate(absolute, 1e-6).values["final_pressure"]
        < pn.simulate(gauge, 1e-6).values["final_pressure"]
    )


def test_switch_fields_are_checked_only_while_the_switch_is_on():
    from gearhead.core.errors import InputError

    bad = {"switch_on": "130 psi", "switch_off": "100 psi"}
    with pytest.raises(InputError) as err:
        pn.simulate(pn_values(**bad), 1e-6)
    assert err.value.field == "switch_on"
    assert (
        pn.simulate(pn_values(effects="compressor, regulator", **bad), 1e-6).values["compressor_duty"] == 1.0
    )


# --- the "fold" combine (added to core.sim.effects for the flight's slot) -------------------------


@pytest.mark.parametrize("arity", [None, 1, 2, 3])
def test_fold_applies_the_terms_in_catalogue_order_on_the_running_value(arity):
    from gearhead.core.sim.effects import Effect, Effects, Part, Slot

    n = arity or 2

    def effect(name):
        return Effect(
            name, "", lambda values, ctx: Part(terms={"s": lambda acc, *a: acc + f"{name}{sum(a)};"})
        )

    catalogue = Effects(effect("a"), effect("b"), effect("c"))
    slots = (Slot("s", "fold", arity=arity),)
    args = tuple(range(1, n + 1))
    for on, want in (({"a", "b", "c"}, "a;b;c;"), ({"c", "a"}, "a;c;"), ({"b"}, "b;")):
        got = catalogue.assemble(on, {}, None, slots).slots["s"]("start:", *args)
        assert got == "start:" + want.replace(";", f"{sum(args)};")
    assert catalogue.assemble((), {}, None, slots).slots["s"] is None


def test_the_retired_absolute_pressure_effect_still_means_the_absolute_model(tmp_path):
    """'absolute_pressure' was an effect; it is the choice pressure_model = absolute now. An entry or
    preset naming it solves exactly as the choice does, with a notice (never refused, never ignored)."""
    from gearhead.core.model import solve
    from gearhead.core.presets import load

    new = solve("pneumatics", {"effects": "compressor", "pressure_model": "absolute"})
    old = solve("pneumatics", {"effects": "compressor, absolute_pressure"})
    assert old.outputs["final_pressure"].value == new.outputs["final_pressure"].value
    assert any("pressure_model = absolute" in w for w in old.warnings)
    gauge = solve("pneumatics", {"effects": "compressor"})
    assert gauge.outputs["final_pressure"].value != new.outputs["final_pressure"].value
    path = tmp_path / "old.toml"
    path.write_text(
        'calculator = "pneumatics"\nname = "old"\nformat = 1\n[inputs]\n'
        'effects = "compressor, absolute_pressure"\n',
        encoding="utf-8",
    )
    loaded = load(path)
    assert (
        loaded.inputs["pressure_model"] == "absolute" and "absolute_pressure" not in loaded.inputs["effects"]
    )


def test_the_flywheels_transfer_models_named_among_the_effects_mean_the_transfer_choice():
    """'energy' and 'momentum' were effects of the flywheel; they are the choice `transfer` now, read
    by the same mechanism as every retired flag (core.sim.effects.retire): a preset naming one loads
    as the choice with the notice, a direct entry solves as the choice does with the notice, the old
    name wins over a `transfer` beside it, and naming both is refused on the effects field."""
    from pathlib import Path

    from gearhead.core.errors import InputError
    from gearhead.core.model import solve
    from gearhead.core.presets import from_dict, load

    base = load(Path(__file__).parents[1] / "presets" / "flywheel" / "nbn_seed_single_wheel.toml").inputs
    assert base["transfer"] == "energy"

    def values(sol):
        return {k: v.value for k, v in sol.outputs.items() if k != "wall_time"}

    new = solve("flywheel", {**base, "transfer": "momentum", "effects": "motor_during_shot"})
    energy = solve("flywheel", {**base, "effects": "motor_during_shot"})
    assert values(new) != values(energy)
    old = solve("flywheel", {**base, "effects": "momentum, motor_during_shot"})  # transfer = energy beside
    assert values(old) == values(new)
    assert any("transfer = momentum" in w for w in old.warnings)
    assert not any("transfer =" in w for w in new.warnings)
    written = {k: v for k, v in base.items() if k != "transfer"}  # as a preset of that time stored it
    loaded = from_dict(
        {
            "calculator": "flywheel",
            "format": 1,
            "inputs": {**written, "effects": "momentum, motor_during_shot"},
        }
    )
    assert loaded.inputs["transfer"] == "momentum" and loaded.inputs["effects"] == "motor_during_shot"
    assert any("transfer = momentum" in w for w in loaded.warnings)
    assert values(solve("flywheel", loaded.inputs)) == values(new)
    with pytest.raises(InputError) as err:
        solve("flywheel", {**base, "effects": "energy, momentum"})
    assert err.value.field == "effects" and "transfer" in err.value.message
