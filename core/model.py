"""How a calculator is described (once, as data) and the one path that solves it.

The TUI, the CLI and presets all go through `solve`; none keeps its own list of fields.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from dataclasses import field as dc_field
from typing import Any

from . import units
from .errors import InputError
from .fields import BOOLEAN, CHOICE, FLAGS, INTEGER, QUANTITY, Kind, kind_of

_BUILTIN_KINDS = (QUANTITY, INTEGER, CHOICE, FLAGS, BOOLEAN)


@dataclass(frozen=True)
class Field:
    """One input. `default`, `min` and `max` are what the user would type: numbers in the display
    unit `unit` (the unit the author reads beside the field; a string default may carry its own
    unit), e.g. `Field("wall", "Wall", "length", "in", default=0.0625, min=0, max=1)` is 0 to 1 in.
    Parsed values are SI; `bounds_si` gives the bounds in SI. What sort of value it holds (a
    quantity, whole number, choice, set of flags, yes/no) is its `kind` (core/fields.py), named
    by the declaration syntax (`integer=True`, `choices=(...)`, `boolean=True`, `flags=True`;
    else a quantity) or given as `kind=`."""

    name: str
    label: str
    quantity: str = "dimensionless"  # a key of units.SI_UNITS
    unit: str = ""  # display unit; a bare number typed by the user means this unit
    default: Any = 0
    min: float | None = None
    max: float | None = None
    min_exclusive: bool = False
    max_exclusive: bool = False
    choices: tuple[str, ...] = ()
    choice_labels: tuple[str, ...] = ()
    integer: bool = False
    boolean: bool = False
    flags: bool = False  # a set of the choices (e.g. the effects a scene switches on)
    help: str = ""
    modes: tuple[str, ...] = ()  # shown and used only in these modes; empty means all
    # shown and used only when other choice fields hold one of these values (for a flags field:
    # when one of them is on), e.g. (("section", ("round_tube", "rectangular_tube")),) for a wall
    when: tuple[tuple[str, tuple[str, ...]], ...] = ()
    kind: Kind | None = None  # after construction always the field's Kind

    def __post_init__(self) -> None:
        legacy = kind_of(self)
        # a built-in kind follows the syntax (so dataclasses.replace(f, integer=True) re-kinds f);
        # any other kind object given is kept
        declared = self.kind
        if declared is None or (declared in _BUILTIN_KINDS and legacy is not QUANTITY):
            declared = legacy
        object.__setattr__(self, "kind", declared)

    @property
    def type(self) -> str:
        """The kind's name ("quantity", "int", "choice", "flags", "bool", ...)."""
        return self.kind.name

    def label_of(self, choice: str) -> str:
        if self.choice_labels:
            return self.choice_labels[self.choices.index(choice)]
        return choice.replace("_", " ")

    def active(self, mode: str | None, choices: Mapping[str, Any] | None = None) -> bool:
        """Whether this field is shown and used, given the mode and the other choices made."""
        if self.modes and mode is not None and mode not in self.modes:
            return False
        if choices is not None:
            for name, allowed in self.when:
                if name not in choices:
                    continue
                chosen = choices[name]
                if isinstance(chosen, frozenset):  # a flags field: any of the allowed is on
                    if not chosen & set(allowed):
                        return False
                elif chosen not in allowed:
                    return False
        return True

    def default_text(self) -> str:
        return self.kind.default_text(self)

    def entry_text(self, entered: Any) -> str:
        """The text shown for what was entered."""
        return self.kind.entry_text(self, entered)

    def parse(self, raw: Any) -> Any:
        """SI value (float), int, bool, choice string or set of flags (as the kind reads it) from
        what a user entered; or an InputError naming this field, in one line, quoting at most the
        start of what was typed."""
        limit = self.kind.max_chars(self)
        if isinstance(raw, str) and len(raw) > limit:
            raise InputError(self.name, f"is too long ({len(raw)} characters; at most {limit})")
        return self.kind.parse(self, raw)

    def _check_bounds(self, value: float, typed: str) -> float:
        """`value` (SI) checked against the bounds (and, for a quantity, the magnitude limits)."""
        return self.kind.checked(self, value, typed)

    def bounds_si(self) -> tuple[float | None, float | None]:
        """(min, max) in the unit `parse` returns (SI), None where unbounded; `min` and `max` are
        declared in the display unit (converted once, on first use, as a bare number typed)."""
        try:
            return self.__dict__["_bounds_si"]
        except KeyError:
            pass
        bounds = tuple(None if b is None else self.kind.bound_si(self, b) for b in (self.min, self.max))
        object.__setattr__(self, "_bounds_si", bounds)
        return bounds


@dataclass(frozen=True)
class Output:
    name: str
    label: str
    quantity: str = "dimensionless"
    unit: str = ""
    help: str = ""
    # the seed's equation number(s) this output comes from, e.g. "(12)" or "(61)-(64)"; shown on the
    # result row with `help` as its one-line "how"
    equation: str = ""


@dataclass(frozen=True)
class Plot:
    """A chart of one or more series a compute function returns (x and y in SI)."""

    title: str
    series: tuple[str, ...]  # keys of Result.series, one line each
    x_label: str
    x_quantity: str
    x_unit: str
    y_label: str
    y_quantity: str
    y_unit: str


@dataclass(frozen=True)
class Column:
    """One column of a Table: a value per row, in SI like an Output."""

    name: str
    label: str
    quantity: str = "dimensionless"
    unit: str = ""
    hidden: bool = False  # carried for sending a row (exports), not shown
    width: int = 0  # characters on screen; fixed so the table never re-measures (0: the label's)


@dataclass(frozen=True)
class Table:
    """A list of alternatives a compute function returns (e.g. the ratio finder's combinations),
    shown under the results; each row is a dict of column values, a missing key an empty cell."""

    name: str  # key of Result.tables
    title: str
    columns: tuple[Column, ...]
    # a row sent to another calculator: {target_id: {target_field: column}}; a row is sent to the
    # targets whose columns it all has
    exports: Mapping[str, Mapping[str, str]] = dc_field(default_factory=dict)

    def column(self, name: str) -> Column:
        for c in self.columns:
            if c.name == name:
                return c
        raise KeyError(name)


@dataclass
class Result:
    """What a compute function returns: output values in SI, and warnings for the user."""

    values: dict[str, Any]
    warnings: list[str] = dc_field(default_factory=list)
    series: dict[str, tuple[list[float], list[float]]] = dc_field(default_factory=dict)  # for plots
    tables: dict[str, list[dict[str, Any]]] = dc_field(default_factory=dict)  # rows of each Table


@dataclass(frozen=True)
class Calculator:
    id: str
    title: str
    summary: str
    fields: tuple[Field, ...]
    outputs: tuple[Output, ...]
    compute: Callable[[Mapping[str, Any]], Result]
    section: str = ""  # where in the seed it comes from
    # Outputs that feed another calculator: {target_id: {target_field: output_name}}
    exports: Mapping[str, Mapping[str, str]] = dc_field(default_factory=dict)
    plots: tuple[Plot, ...] = ()
    tables: tuple[Table, ...] = ()
    # Simulated calculators: simulate(values, rtol) -> core.sim.scene.SimRun (for the accuracy ladder)
    simulate: Callable[[Mapping[str, Any], float], Any] | None = None

    def field(self, name: str) -> Field:
        return self._index("fields")[name]  # KeyError(name) when there is none

    def output(self, name: str) -> Output:
        return self._index("outputs")[name]

    def _index(self, what: str) -> dict[str, Any]:
        """{name: field} or {name: output}, built on first use: lookups run per key and per point."""
        key = f"_{what}_by_name"
        try:
            return self.__dict__[key]
        except KeyError:
            pass
        index: dict[str, Any] = {}
        for item in getattr(self, what):
            index.setdefault(item.name, item)  # the first of a name, as a scan would find
        object.__setattr__(self, key, index)
        return index

    @property
    def modes(self) -> tuple[str, ...]:
        try:
            return self.field("mode").choices
        except KeyError:
            return ()


@dataclass(frozen=True)
class Value:
    """A solved or parsed value as the outside world sees it (DESIGN.md JSON shape)."""

    value: Any  # SI float, int, bool or str
    unit: str  # SI unit ("" when dimensionless or not a quantity)
    text: str  # for people, in the display unit

    def as_json(self) -> dict[str, Any]:
        return {"value": self.value, "unit": self.unit, "text": self.text}


@dataclass
class Solution:
    calculator: str
    inputs: dict[str, Value]
    outputs: dict[str, Value]
    warnings: list[str]
    series: dict[str, tuple[list[float], list[float]]] = dc_field(default_factory=dict)
    tables: dict[str, list[dict[str, Value]]] = dc_field(default_factory=dict)

    def as_json(self) -> dict[str, Any]:
        out = {
            "calculator": self.calculator,
            "inputs": {k: v.as_json() for k, v in self.inputs.items()},
            "outputs": {k: v.as_json() for k, v in self.outputs.items()},
            "warnings": list(self.warnings),
        }
        if self.tables:  # only calculators that declare tables have the key
            out["tables"] = {
                name: [{k: v.as_json() for k, v in row.items()} for row in rows]
                for name, rows in self.tables.items()
            }
        return out


def parse_inputs(
    calc: Calculator, raw: Mapping[str, Any], ignored: list[str] | None = None, *, retired: bool = False
) -> tuple[dict[str, Any], dict[str, str]]:
    """SI values for every field (defaults fill gaps) and the text shown for each.

    Fields the current mode does not use never block a solve: a bad entry there falls back
    to its default, so switching modes never loses or is blocked by what was typed. Each such
    fallback is one line appended to `ignored` (when given), and its text is the default's, so
    a report never shows "banana" beside the default's value. `retired`: the caller has already
    replaced retired names (core.sim.effects.retire), once for the whole solve.
    """
    if not retired:
        from .sim.effects import retire  # a name retired from a flags field: what replaced it

        raw, _ = retire(calc.fields, raw)
    known = {f.name for f in calc.fields}
    for name in raw:
        if name not in known:
            raise InputError(name, f"unknown field for {calc.id} (fields: {', '.join(sorted(known))})")
    mode = None
    if "mode" in known:
        mode = calc.field("mode").parse(raw.get("mode", calc.field("mode").default))
    choices = choice_values(calc, raw, retired=True)
    values: dict[str, Any] = {}
    texts: dict[str, str] = {}
    for f in calc.fields:
        entered = raw.get(f.name, f.default)
        if f.active(mode, choices):
            values[f.name] = f.parse(entered)
        else:
            try:
                values[f.name] = f.parse(entered)
            except InputError as exc:
                values[f.name] = f.parse(f.default)
                entered = f.default
                if ignored is not None:
                    ignored.append(
                        f"{f.name}: ignored (not used with these choices), and not valid: {exc.message}; "
                        f"the default {f.entry_text(f.default)} stands"
                    )
        texts[f.name] = f.entry_text(entered)
    return values, texts


def choice_values(calc: Calculator, raw: Mapping[str, Any], *, retired: bool = False) -> dict[str, Any]:
    """The choice fields that other fields' `when` depends on, parsed (default if unreadable); an old
    name among a flags field counts as what replaced it (core.sim.effects.retire, unless `retired`
    says the caller has done it)."""
    if not retired:
        from .sim.effects import retire

        try:
            raw, _ = retire(calc.fields, raw)
        except InputError:  # two old names at odds: parse_inputs says so; here the defaults serve
            pass
    names = {name for f in calc.fields for name, _ in f.when}
    out = {}
    for name in names:
        f = calc.field(name)
        try:
            out[name] = f.parse(raw.get(name, f.default))
        except InputError:
            out[name] = f.default
    return out


def format_value(value: Any, quantity: str, unit: str) -> Value:
    if isinstance(value, bool) or isinstance(value, str):
        text = ("yes" if value else "no") if isinstance(value, bool) else value
        return Value(value, "", text)
    if isinstance(value, numbers.Integral):
        return Value(int(value), "", str(int(value)))
    value = float(value)
    return Value(value, units.SI_UNITS[quantity], units.format_quantity(value, unit, quantity))


UNCOMPUTABLE = (ArithmeticError, ValueError, RuntimeError)  # what the last-resort guard turns into a message


def uncomputable(exc: BaseException) -> InputError:
    """The last-resort message for a failure a calculator did not foresee ("(result)" names no
    field: the robustness tests fail if it is ever given)."""
    return InputError("(result)", f"could not be computed from these inputs ({type(exc).__name__}: {exc})")


@contextmanager
def last_resort() -> Iterator[None]:
    """Last-resort guard, like the NaN one in `solve`: the user gets a message, never a traceback
    (an InputError passes through as it is)."""
    try:
        yield
    except InputError:
        raise
    except UNCOMPUTABLE as exc:
        raise uncomputable(exc) from exc


def check_display_units(calc: Calculator, display_units: Mapping[str, str] | None) -> dict[str, str]:
    """{output: unit} the user asked for, each a real output and a unit that can show it."""
    display_units = dict(display_units or {})
    for name, unit in display_units.items():
        try:
            out = calc.output(name)
        except KeyError:
            raise InputError(name, f"is not an output of {calc.id}") from None
        units.check_unit(unit, out.quantity, name)
    return display_units


def solve(
    calc_id: str, raw: Mapping[str, Any] | None = None, display_units: Mapping[str, str] | None = None
) -> Solution:
    """Parse, compute and format one calculator. Raises InputError on any bad entry."""
    from .registry import get
    from .sim.effects import retire

    calc = get(calc_id)
    raw, notices = retire(calc.fields, raw or {})  # once per solve: parse_inputs is told so
    values, texts = parse_inputs(calc, raw, notices, retired=True)
    with last_resort():
        result = calc.compute(values)
    display_units = check_display_units(calc, display_units)
    inputs = {}
    for f in calc.fields:
        value, si_unit = f.kind.reported(f, values[f.name])
        inputs[f.name] = Value(value, si_unit, texts[f.name])
    outputs = {}
    for o in calc.outputs:
        if o.name not in result.values:
            continue
        v = result.values[o.name]
        if isinstance(v, float) and not math.isfinite(v):
            # Last-resort guard: a calculator must never show NaN/inf. Tests assert it never fires.
            raise InputError("(result)", f"{o.name} could not be computed from these inputs")
        unit = display_units.get(o.name, o.unit)
        outputs[o.name] = format_value(v, o.quantity, unit)
    tables = {}
    for t in calc.tables:
        rows = []
        for row in result.tables.get(t.name, []):
            cells = {}
            for c in t.columns:
                if c.name not in row:
                    continue
                v = row[c.name]
                if isinstance(v, float) and not math.isfinite(v):  # the same last-resort guard
                    raise InputError("(result)", f"{t.name}.{c.name} could not be computed from these inputs")
                cells[c.name] = format_value(v, c.quantity, c.unit)
            rows.append(cells)
        tables[t.name] = rows
    return Solution(calc.id, inputs, outputs, notices + list(result.warnings), dict(result.series), tables)
