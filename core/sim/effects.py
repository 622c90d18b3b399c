"""Composable effects: each piece of physics a scene may switch on, declared once, as a part.

An `Effect` declares
- its fields (shown and used only while it is on: `when` is filled in here),
- its outputs (reported only while it is on),
- `build(values, ctx) -> Part`: what it contributes to one solve, built once per solve from the
  parsed inputs and the scene's context (`ctx`, whatever the scene hands its parts: constants,
  the math namespace `xp`, ...).

A `Part` holds
- `terms`: {slot: function}. A slot is a named quantity the scene's right-hand side reads
  (a force, a flow, a bound on the motor duty ...). The scene declares its slots and how terms
  combine (`Slot.combine`: "sum", "vsum", "min", "fold" or "each"); the assembly composes the terms of the effects that
  are on into ONE function per slot, or None when nothing contributes, so the scene specialises
  its right-hand side once: an effect that is off leaves no call, no addition and no branch.
- `states`: (name, initial value) of the state it adds, with `derivative(t, y) -> [..]` for them
  (y is the whole state; the assembly appends the derivatives after the scene's own). States
  coupled to the scene's own (a degree of freedom in a mass matrix) have no `derivative`: the
  scene computes theirs from its "each" slots, reading each term's own states (`with_state`).
- `events`: core.sim.integrate.Event objects (e.g. a pressure switch).
- `params`: constants the scene reads (e.g. a resistance that changes a closed form).
- `report(run) -> {output: value}`: its outputs after the run.

A model choice (e.g. a transfer model) is a choice field of the calculator, not an effect; an
action (optimise) is a mode. `Effects` is the catalogue a scene offers: it makes the `effects`
flags field, the effect-owned fields and outputs, and `assemble`s the parts that are on.

How the older scenes map onto it (for their migration):
- projectile (done, core.sim.flight): slot "accel" (combine "fold": each term adds its (ax, ay) to
  the running one, starting from gravity's (0, −g), so the sums round as the hand-written right-hand
  side did); `air_drag` and `magnus` each add a term; with neither the slot is None and the closed
  form answers.
- pneumatics: slot "inflow" (dP/dt); `compressor` adds the flow term, `pressure_switch` adds a
  discrete state through its events; `absolute_pressure` is a model choice (a choice field).
- flywheel: energy/momentum transfer is a choice field; `motor_during_shot` adds the slip phase's
  state (wheel speed, ball speed) with its derivative and its end-of-slip event.
- trebuchet (done, core.sim.trebuchet): `sling` and `hinged_counterweight` (on a hanger) add states
  (γ, γ̇ / ψ, ψ̇) and their blocks of the mass matrix through the "each" slot "coupling" (the scene
  eliminates them itself), and their shares of energy and geometry; `ground_contact` adds the
  constraint term ("constraint") and the swing its phase events; `optimise` is a mode, the
  retired flag still read (RetiredFlags, retire).
- motor scenes (core.sim.motion): slots "force" (sum), "friction" (sum), "duty" (min).

Why hand-written: no library composes ODE right-hand sides from declared parts at the cost of
plain closures (our DP54 in core.sim.integrate runs on plain floats for speed).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..declarations import Output
from ..errors import InputError
from ..fields import Field

Term = Callable[..., Any]


@dataclass(frozen=True)
class Slot:
    """A quantity the scene's right-hand side reads, assembled from the terms of the effects on."""

    name: str
    # "sum": terms add; "vsum": vectors add component-wise; "min": the smallest wins; "fold": each
    # term takes the running value first, term(acc, *args) -> acc', applied in catalogue order (the
    # scene passes the start value: slot(start, *args)), so the order of the additions is fixed;
    # "each": the slot holds the terms themselves, a tuple in catalogue order (for terms that do not
    # simply add, e.g. the blocks of a mass matrix a scene eliminates itself; see Assembly.with_state)
    combine: str = "sum"
    help: str = ""
    # "fold" only: how many arguments follow the running value (1-3 composes without *args
    # packing, about half the cost of a two-term fold); None: any number
    arity: int | None = None


@dataclass
class Part:
    """What one effect that is on contributes to one solve."""

    terms: Mapping[str, Term] = field(default_factory=dict)
    states: tuple[tuple[str, float], ...] = ()
    derivative: Callable[[float, list], list] | None = None
    events: tuple = ()
    params: Mapping[str, Any] = field(default_factory=dict)
    report: Callable[[Any], Mapping[str, Any]] | None = None


@dataclass(frozen=True)
class Effect:
    name: str
    help: str
    build: Callable[[Mapping[str, Any], Any], Part]
    fields: tuple[Field, ...] = ()
    outputs: tuple[Output, ...] = ()
    default_on: bool = False


def _sum(fns: Sequence[Term]) -> Term:
    if len(fns) == 1:
        return fns[0]
    if len(fns) == 2:
        f, g = fns
        return lambda *a: f(*a) + g(*a)
    head, rest = fns[0], _sum(fns[1:])
    return lambda *a: head(*a) + rest(*a)


def _vsum(fns: Sequence[Term]) -> Term:
    """Component-wise sum of terms that return vectors (e.g. accelerations (ax, ay))."""
    if len(fns) == 1:
        return fns[0]
    if len(fns) == 2:
        f, g = fns
        return lambda *a: [x + y for x, y in zip(f(*a), g(*a))]
    head, rest = fns[0], _vsum(fns[1:])
    return lambda *a: [x + y for x, y in zip(head(*a), rest(*a))]


def _min(fns: Sequence[Term], minimum: Callable) -> Term:
    if len(fns) == 1:
        return fns[0]
    head, rest = fns[0], _min(fns[1:], minimum)
    return lambda *a: minimum(head(*a), rest(*a))


def _fold(fns: Sequence[Term], arity: int | None = None) -> Term:
    """term_n(...term_2(term_1(acc, *a), *a)..., *a): left to right, each on the running value."""
    if len(fns) == 1:
        return fns[0]
    f, g = _fold(fns[:-1], arity), fns[-1]
    if arity == 1:
        return lambda acc, a: g(f(acc, a), a)
    if arity == 2:
        return lambda acc, a, b: g(f(acc, a, b), a, b)
    if arity == 3:
        return lambda acc, a, b, c: g(f(acc, a, b, c), a, b, c)
    return lambda acc, *a: g(f(acc, *a), *a)


@dataclass
class Assembly:
    """The parts of the effects that are on, composed for one solve."""

    on: tuple[str, ...]
    parts: dict[str, Part]
    slots: dict[str, Term | None]  # one function per slot, None when no effect contributes
    contributors: dict[str, tuple[str, ...]]  # slot -> names of the effects whose terms it holds
    states: tuple[str, ...]  # the scene's own states, then those the effects add
    y0_extra: tuple[float, ...]
    events: tuple
    params: dict[str, Any]

    @property
    def n_terms(self) -> int:
        """Terms in the assembled right-hand side (what the tests count)."""
        return sum(len(c) for c in self.contributors.values())

    def rhs(self, base: Callable[[float, list], list]) -> Callable[[float, list], list]:
        """The scene's right-hand side with the derivatives of the states effects add appended;
        `base` itself when no effect adds state (no wrapper, no cost)."""
        extra = [p.derivative for p in self.parts.values() if p.states and p.derivative is not None]
        if not extra:
            return base
        if len(extra) == 1:
            d = extra[0]
            return lambda t, y: base(t, y) + d(t, y)

        def rhs(t, y):
            out = base(t, y)
            for d in extra:
                out = out + d(t, y)
            return out

        return rhs

    def offset(self, name: str) -> int:
        """Index in the state vector of the first state effect `name` adds."""
        i = len(self.states) - len(self.y0_extra)
        for n, p in self.parts.items():
            if n == name:
                return i
            i += len(p.states)
        raise KeyError(name)

    def with_state(self, slot: str) -> tuple[tuple[int, Term], ...]:
        """((offset of the contributor's own states, term), ...) of an "each" slot, for terms that
        read the states their effect adds."""
        return tuple((self.offset(n), self.parts[n].terms[slot]) for n in self.contributors[slot])

    def report(self, run: Any) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for p in self.parts.values():
            if p.report is not None:
                out.update(p.report(run))
        return out


class Effects:
    """The effects a scene offers, in display order."""

    def __init__(self, *effects: Effect):
        self.effects = effects
        self.by_name = {e.name: e for e in effects}
        if len(self.by_name) != len(effects):
            raise ValueError("effect names must be unique")

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(e.name for e in self.effects)

    @property
    def defaults(self) -> tuple[str, ...]:
        return tuple(e.name for e in self.effects if e.default_on)

    def field(self, help: str | None = None, retired: tuple[tuple[str, str, str], ...] = ()) -> Field:
        """The `effects` flags field. `retired`: (old name, field, value) of names that are no longer
        effects and what replaced them (e.g. ("optimise", "mode", "optimise")): still read, so old
        presets load, but not offered (see RetiredFlags and retire)."""
        text = help or "; ".join(f"{e.name}: {e.help}" for e in self.effects)
        if retired:
            return RetiredFlags(
                "effects",
                "Effects",
                choices=self.names,
                flags=True,
                default=", ".join(self.defaults),
                help=text,
                retired=retired,
            )
        return Field(
            "effects", "Effects", choices=self.names, flags=True, default=", ".join(self.defaults), help=text
        )

    def fields(self) -> tuple[Field, ...]:
        """Every effect's own fields, each shown only while an effect that declares it is on."""
        owners: dict[str, list[str]] = {}
        first: dict[str, Field] = {}
        for e in self.effects:
            for f in e.fields:
                owners.setdefault(f.name, []).append(e.name)
                first.setdefault(f.name, f)
        return tuple(
            dataclasses.replace(f, when=f.when + (("effects", tuple(owners[n])),)) for n, f in first.items()
        )

    def outputs(self) -> tuple[Output, ...]:
        seen: dict[str, Output] = {}
        for e in self.effects:
            for o in e.outputs:
                seen.setdefault(o.name, o)
        return tuple(seen.values())

    def assemble(
        self,
        on: Sequence[str] | frozenset,
        values: Mapping[str, Any],
        ctx: Any,
        slots: Sequence[Slot],
        base_states: Sequence[str] = (),
        minimum: Callable = min,
    ) -> Assembly:
        """Build the parts of the effects that are on (in catalogue order) and compose each slot.
        `minimum` is the two-argument min of the namespace the terms compute in (min for floats,
        numpy.minimum for arrays)."""
        unknown = set(on) - set(self.by_name)
        if unknown:
            raise KeyError(f"unknown effects: {', '.join(sorted(unknown))}")
        names = tuple(e.name for e in self.effects if e.name in on)
        parts = {n: self.by_name[n].build(values, ctx) for n in names}
        declared = {s.name: s for s in slots}
        contributors: dict[str, tuple[str, ...]] = {}
        composed: dict[str, Term | None] = {}
        for s in slots:
            fns = [(n, p.terms[s.name]) for n, p in parts.items() if s.name in p.terms]
            contributors[s.name] = tuple(n for n, _ in fns)
            if not fns:
                composed[s.name] = None
            elif s.combine == "min":
                composed[s.name] = _min([f for _, f in fns], minimum)
            elif s.combine == "vsum":
                composed[s.name] = _vsum([f for _, f in fns])
            elif s.combine == "sum":
                composed[s.name] = _sum([f for _, f in fns])
            elif s.combine == "fold":
                composed[s.name] = _fold([f for _, f in fns], s.arity)
            elif s.combine == "each":
                composed[s.name] = tuple(f for _, f in fns)
            else:
                raise ValueError(f"slot {s.name}: unknown combine {s.combine!r}")
        for n, p in parts.items():
            stray = set(p.terms) - set(declared)
            if stray:
                raise KeyError(f"effect {n} adds to undeclared slots: {', '.join(sorted(stray))}")
        states = tuple(base_states) + tuple(name for p in parts.values() for name, _ in p.states)
        y0_extra = tuple(float(v) for p in parts.values() for _, v in p.states)
        events = tuple(ev for p in parts.values() for ev in p.events)
        params: dict[str, Any] = {}
        for p in parts.values():
            params.update(p.params)
        return Assembly(names, parts, composed, contributors, states, y0_extra, events, params)


@dataclass(frozen=True)
class RetiredFlags(Field):
    """A flags field that still reads names retired from its choices, without offering them: the one
    way a calculator keeps an old entry or preset meaning what it meant (`retire` rewrites the
    inputs, with a notice). `retired`: (old name, field, value): what replaced each, e.g.
    ("optimise", "mode", "optimise") or the flywheel's ("momentum", "transfer", "momentum").
    Its parse still accepts a retired name (kept in the set) for a caller that parses by hand."""

    retired: tuple[tuple[str, str, str], ...] = ()

    def parse(self, raw: Any) -> Any:
        old = {name for name, _, _ in self.retired}
        if isinstance(raw, str) and len(raw) <= self._max_chars():
            items = [x for x in raw.replace(",", " ").split() if x]
        elif isinstance(raw, (list, tuple, set, frozenset)) and all(isinstance(x, str) for x in raw):
            items = list(raw)
        else:
            return super().parse(raw)  # its own message (too long, wrong type)
        found = frozenset(x for x in items if x in old)
        return super().parse([x for x in items if x not in old]) | found

    def _max_chars(self) -> int:
        return self.kind.max_chars(self) + sum(len(name) + 2 for name, _, _ in self.retired)

    def notice(self, name: str) -> str:
        """What to tell the user who still names a retired flag."""
        _, field, value = next(r for r in self.retired if r[0] == name)
        return (
            f"{self.name}: '{name}' is no longer one of the {self.name}; it is read as {field} = {value} "
            f"(set that instead: '{name}' will stop being read in a later version)"
        )


def retire(fields: Sequence[Field], inputs: Mapping[str, Any]) -> tuple[dict[str, Any], list[str]]:
    """Inputs as typed with each retired flag replaced by what replaced it (an entry or a preset
    written before the flag was retired), and one notice per flag replaced.

    The one place retired names are read: core.model.parse_inputs (every solve, sweep and tolerance
    study) and core.presets.from_dict (a preset is stored in today's fields) call it; a calculator's
    compute never sees a retired name. The old name wins over its field given beside it (that is a
    default filled in, or the newer field an old name was written over); two retired names meaning
    different values of one field are an error naming the flags field."""
    out = dict(inputs)
    notes: list[str] = []
    for f in fields:
        if not isinstance(f, RetiredFlags) or f.name not in out:
            continue
        raw = out[f.name]
        if isinstance(raw, str):
            items = [x for x in raw.replace(",", " ").split() if x]
        elif isinstance(raw, (list, tuple, set, frozenset)) and all(isinstance(x, str) for x in raw):
            items = list(raw)
        else:
            continue  # the field's parse gives its own message
        named = [r for r in f.retired if r[0] in items]
        if not named:
            continue
        meant: dict[str, tuple[str, str]] = {}
        for name, field_name, value in named:
            other = meant.setdefault(field_name, (name, value))
            if other[1] != value:
                raise InputError(
                    f.name,
                    f"names both '{other[0]}' and '{name}' (retired: {field_name} = {other[1]} and "
                    f"{field_name} = {value}): choose one as `{field_name}`",
                )
        for name, field_name, value in named:
            out[field_name] = value
            notes.append(f.notice(name))
        old = {name for name, _, _ in named}
        kept = [x for x in items if x not in old]
        out[f.name] = ", ".join(kept) if isinstance(raw, str) else kept
    return out, notes


def nothing(values: Mapping[str, Any], ctx: Any) -> Part:
    """The build of an effect whose whole contribution is read elsewhere (e.g. a parameter)."""
    return Part()
