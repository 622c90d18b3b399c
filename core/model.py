"""The one path that solves a calculator: parse what was entered, compute, format.

The TUI, the CLI and presets all go through `solve`; none keeps its own list of fields.

Layers (one way; tests/test_architecture.py checks no import cycle among core modules comes back):
errors, units, fields (Field and its kinds) at the bottom; declarations (what a calculator
declares: Output, Plot, Table, Result, Calculator, and the checks of a declaration) above them;
the registry (which loads the calculators) above that; this module on top. The declaration classes
are re-exported here, so `from gearhead.core.model import Calculator, Field` keeps working; a
calculator module imports them from core.fields and core.declarations (the registry imports the
calculators, so a calculator that imported this module would close a circle).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, replace
from dataclasses import field as dc_field
from typing import Any

from . import units
from .declarations import Calculator as Calculator
from .declarations import Column as Column
from .declarations import HeatMap as HeatMap
from .declarations import HeatMapData as HeatMapData
from .declarations import Output as Output
from .declarations import PendingEstimate
from .declarations import Plot as Plot
from .declarations import Result as Result
from .declarations import Table as Table
from .errors import InputError, raise_all, shown
from .fields import Field as Field
from .registry import get
from .sim.effects import retire


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
    series_labels: dict[str, str] = dc_field(default_factory=dict)  # Result.series_labels
    heat_maps: dict[str, HeatMapData] = dc_field(default_factory=dict)  # Result.heat_maps (SI)
    # a solve asked with estimate="later": its "error_estimate" output reads "…" until
    # finish_estimate(solution) runs this (the second step; None once done or never asked)
    pending_estimate: Callable[[], Value] | None = None

    def entries(self) -> dict[str, Any]:
        """Each input's value by field name (SI), as a calculator's compute saw them."""
        return {name: value.value for name, value in self.inputs.items()}

    def series_label(self, name: str) -> str:
        return self.series_labels.get(name, name)

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
        if self.heat_maps:  # only a solve that drew one (the limit grid) has the key
            out["heat_maps"] = {name: data.as_json() for name, data in self.heat_maps.items()}
        return out


MAX_UNKNOWN_LISTED = 5  # unknown names reported one by one; more are counted, the first few named


def parse_inputs(
    calc: Calculator, raw: Mapping[str, Any], ignored: list[str] | None = None, *, retired: bool = False
) -> tuple[dict[str, Any], dict[str, str]]:
    """SI values for every field (defaults fill gaps) and the text shown for each.

    Fields the current mode does not use never block a solve: a bad entry there falls back
    to its default, so switching modes never loses or is blocked by what was typed. Each such
    fallback is one line appended to `ignored` (when given), and its text is the default's, so
    a report never shows "banana" beside the default's value. `retired`: the caller has already
    replaced retired names (core.sim.effects.retire), once for the whole solve.

    Every wrong entry is reported, not only the first: one is raised as it is, several as one
    InputErrors (core.errors) whose primary, the first met, is the error raised before (unknown
    names first, then the fields in the calculator's order). A wrong mode stops the reading there:
    which fields are used depends on it.
    """
    if not retired:
        raw, _ = retire(calc.fields, raw)  # a name retired from a flags field: what replaced it
    known = {f.name for f in calc.fields}
    unknown = [name for name in raw if name not in known]
    fields = ", ".join(sorted(known))
    errors = [InputError(name, f"unknown field for {calc.id} (fields: {fields})") for name in unknown]
    if len(unknown) > MAX_UNKNOWN_LISTED:  # a file of 60 000 junk keys: one line, not 60 000
        rest = ", ".join(shown(n, 20) for n in unknown[1:MAX_UNKNOWN_LISTED])
        errors = [
            InputError(
                unknown[0],
                f"unknown field for {calc.id}, and {len(unknown) - 1} more unknown names ({rest}, …) "
                f"(fields: {fields})",
            )
        ]
    mode = None
    if "mode" in known:
        try:
            mode = calc.field("mode").parse(raw.get("mode", calc.field("mode").default))
        except InputError as exc:
            raise_all(errors + [exc])
    choices = choice_values(calc, raw, retired=True)
    values: dict[str, Any] = {}
    texts: dict[str, str] = {}
    for f in calc.fields:
        entered = raw.get(f.name, f.default)
        if f.active(mode, choices):
            try:
                values[f.name] = f.parse(entered)
            except InputError as exc:
                errors.append(exc)
                continue  # no text: the entry is refused (and its text may not be writable: [1, 2])
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
    raise_all(errors)
    return values, texts


def choice_values(calc: Calculator, raw: Mapping[str, Any], *, retired: bool = False) -> dict[str, Any]:
    """The choice fields that other fields' `when` depends on, parsed (default if unreadable); an old
    name among a flags field counts as what replaced it (core.sim.effects.retire, unless `retired`
    says the caller has done it)."""
    if not retired:
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
    # a count is an integer; a physical quantity that happens to be an int (a sum of nothing) is not
    if isinstance(value, numbers.Integral) and not units.SI_UNITS.get(quantity):
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


ESTIMATE = "error_estimate"  # a scene's output that may come in a second step (finish_estimate)
ESTIMATE_PENDING_TEXT = "…"
ESTIMATE_OVER_BUDGET_TEXT = "— (over one solve's budget)"


def solve(
    calc_id: str,
    raw: Mapping[str, Any] | None = None,
    display_units: Mapping[str, str] | None = None,
    estimate: str = "now",
) -> Solution:
    """Parse, compute and format one calculator. Raises InputError on any bad entry.

    estimate="later": a simulated calculator leaves its error estimate for a second step
    (Solution.pending_estimate, run by finish_estimate); the others solve as with "now"."""
    calc = get(calc_id)
    if estimate not in ("now", "later"):
        raise ValueError(f"estimate is 'now' or 'later', not {estimate!r}")
    if raw is not None and not isinstance(raw, Mapping):  # solve("motor", [1, 2]): named, not a TypeError
        raise InputError("inputs", f"must be a mapping of field names to entries, got {type(raw).__name__}")
    raw, notices = retire(calc.fields, raw or {})  # once per solve: parse_inputs is told so
    values, texts = parse_inputs(calc, raw, notices, retired=True)
    later = estimate == "later" and any(o.name == ESTIMATE for o in calc.outputs)
    with last_resort():
        # a calculator with the error estimate output (a scene) takes `estimate` (scene.run_with_stats)
        result = calc.compute(values, estimate="later") if later else calc.compute(values)
    display_units = check_display_units(calc, display_units)
    pending = None
    inputs = {}
    for f in calc.fields:
        value, si_unit = f.kind.reported(f, values[f.name])
        inputs[f.name] = Value(value, si_unit, texts[f.name])
    outputs = {}
    for o in calc.outputs:
        if o.name not in result.values:
            continue
        v = result.values[o.name]
        if isinstance(v, PendingEstimate):
            pending = _estimate_step(v, o, display_units.get(o.name, o.unit))
            outputs[o.name] = Value(None, "", ESTIMATE_PENDING_TEXT)
            continue
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
    return Solution(
        calc.id,
        inputs,
        outputs,
        notices + list(result.warnings),
        dict(result.series),
        tables,
        dict(result.series_labels),
        _checked_heat_maps(result.heat_maps),
        pending,
    )


def _estimate_step(pending: PendingEstimate, o: Output, unit: str) -> Callable[[], Value]:
    """The second step of a solve asked with estimate="later": the estimate's Value, or a dash
    when it does not fit in one solve's budget (the results above it stand)."""

    def step() -> Value:
        try:
            with last_resort():
                value = pending.compute()
        except InputError:
            return Value(None, "", ESTIMATE_OVER_BUDGET_TEXT)
        if not math.isfinite(value):  # the last-resort guard: never NaN or inf on screen
            return Value(None, "", "— (could not be computed)")
        return format_value(value, o.quantity, unit)

    return step


def finish_estimate(solution: Solution) -> Solution:
    """The solution with its error estimate computed (the second step of estimate="later"); the
    same solution when none is pending. Raises integrate.Cancelled when the caller's budget
    cancels it (the app: the entries changed meanwhile)."""
    if solution.pending_estimate is None:
        return solution
    value = solution.pending_estimate()
    outputs = {name: (value if name == ESTIMATE else v) for name, v in solution.outputs.items()}
    return replace(solution, outputs=outputs, pending_estimate=None)


def _checked_heat_maps(maps: dict[str, HeatMapData]) -> dict[str, HeatMapData]:
    """The heat maps, with the same last-resort guard as the outputs: no NaN or inf is shown."""
    for name, data in maps.items():
        for row in data.z:
            if any(z is not None and not math.isfinite(z) for z in row):
                raise InputError("(result)", f"{name} could not be computed from these inputs")
    return dict(maps)
