"""What a calculator declares (its outputs, plots and tables, what its compute returns, the
Calculator itself; its fields are core/fields.py), and the checks of a declaration.

A calculator's declaration is checked when the registry loads it, so a slip in a description
(a misspelled quantity kind, a unit of the wrong dimension, a default outside its bounds, a `when`
naming a field that does not exist) fails at once with the calculator and the field named, instead
of as a KeyError or a pint traceback the first time someone solves it.

Conventions checked here (the Field docstring states them too): `default`, `min` and `max` are what a
user would type, numbers in the field's display unit (a string default may carry its own unit), and
the default lies within the bounds. Cheap enough to
run on every load: units are looked up in the generated factor table, pint only for a unit missing
from it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from dataclasses import field as dc_field
from typing import Any

from . import units
from .errors import InputError
from .fields import Field


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
class HeatMap:
    """A chart of one value over a grid of two (e.g. the time per stator × supply current limit):
    a coloured cell with its value for each pair, one cell marked (the pick). Listed among a
    calculator's plots; its data is Result.heat_maps[name] (x, y, z in SI)."""

    title: str
    name: str  # key of Result.heat_maps
    x_label: str  # the columns
    x_quantity: str
    x_unit: str
    y_label: str  # the rows
    y_quantity: str
    y_unit: str
    z_label: str  # the value in each cell
    z_quantity: str
    z_unit: str
    series: tuple[str, ...] = ()  # no line series: code that draws lines finds none here


@dataclass
class HeatMapData:
    """A heat map's values: z[row][column] at (x[column], y[row]), all SI; None where there is no
    value (`notes` then holds a short word for the cell: why); `pick` the (row, column) marked."""

    x: list[float]
    y: list[float]
    z: list[list[float | None]]
    pick: tuple[int, int] | None = None
    notes: list[list[str]] = dc_field(default_factory=list)

    def as_json(self) -> dict[str, Any]:
        return {
            "x": self.x,
            "y": self.y,
            "z": self.z,
            "pick": list(self.pick) if self.pick else None,
            "notes": self.notes,
        }


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
    modes: tuple[str, ...] = ()  # shown only in these modes of the calculator; empty means all
    # and only when other choice fields hold one of these values (as Field.when), e.g. the
    # flywheel's (("control", ("limit_grid",)),): its `mode` is the inertia's
    when: tuple[tuple[str, tuple[str, ...]], ...] = ()

    def shown_in(self, inputs: Mapping[str, Any]) -> bool:
        """Whether the table applies to these entries (each field's value by name)."""
        if self.modes and inputs.get("mode") not in self.modes:
            return False
        for name, allowed in self.when:
            chosen = inputs.get(name)
            if isinstance(chosen, frozenset):  # a flags field: any of the allowed is on
                if not chosen & set(allowed):
                    return False
            elif name in inputs and chosen not in allowed:
                return False
        return True

    def column(self, name: str) -> Column:
        for c in self.columns:
            if c.name == name:
                return c
        raise KeyError(name)


@dataclass(frozen=True)
class PendingEstimate:
    """A scene's error estimate not computed yet (a solve asked with estimate="later"): the value
    a compute function leaves in Result.values["error_estimate"]; `compute()` gives the estimate
    (within its own solve budget). core.model.finish_estimate runs it."""

    compute: Callable[[], float]


@dataclass
class Result:
    """What a compute function returns: output values in SI, and warnings for the user."""

    values: dict[str, Any]
    warnings: list[str] = dc_field(default_factory=list)
    series: dict[str, tuple[list[float], list[float]]] = dc_field(default_factory=dict)  # for plots
    tables: dict[str, list[dict[str, Any]]] = dc_field(default_factory=dict)  # rows of each Table
    # what a chart's legend calls a series whose key is a slot, not a name (the motors table's
    # "curve 1" is the motor chosen for it); a key not here is its own label
    series_labels: dict[str, str] = dc_field(default_factory=dict)
    heat_maps: dict[str, HeatMapData] = dc_field(default_factory=dict)  # the data of each HeatMap


@dataclass(frozen=True)
class Document:
    """A file another tool reads, built from one solution (e.g. a PathPlanner settings.json):
    `build(solution) -> text`, or a ValueError saying what cannot be exported."""

    name: str  # the CLI's --document NAME
    label: str  # for people, in the export dialog
    filename: str  # the name the other tool expects
    build: Callable[[Any], str]


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
    plots: tuple[Plot | HeatMap, ...] = ()
    tables: tuple[Table, ...] = ()
    documents: tuple[Document, ...] = ()  # files for other tools (ctrl+e, `solve --document NAME`)
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


class DeclarationError(RuntimeError):
    """A calculator's description is inconsistent: a developer's mistake, named precisely."""

    def __init__(self, calc_id: str, part: str, message: str):
        self.calc_id, self.part, self.message = calc_id, part, message
        super().__init__(f"calculator {calc_id!r}, {part}: {message}")


def _check_unit(calc_id: str, part: str, unit: str, kind: str) -> None:
    if kind not in units.SI_UNITS:
        raise DeclarationError(
            calc_id, part, f"unknown quantity kind {kind!r} (known: {', '.join(sorted(units.SI_UNITS))})"
        )
    if not unit:
        if kind != "dimensionless":
            raise DeclarationError(calc_id, part, f"a {kind} needs a display unit")
        return
    try:
        units.factor(unit, kind)
    except Exception as exc:  # unknown unit, wrong dimension: pint raises several types
        raise DeclarationError(
            calc_id, part, f"unit {unit!r} cannot show a {kind} ({type(exc).__name__})"
        ) from None


def check(calc: Calculator) -> None:
    """Raise DeclarationError at the first inconsistency in `calc`'s description."""
    cid = calc.id
    names = [f.name for f in calc.fields]
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise DeclarationError(cid, f"field {duplicates[0]!r}", "declared more than once")
    out_names = [o.name for o in calc.outputs]
    duplicates = sorted({n for n in out_names if out_names.count(n) > 1})
    if duplicates:
        raise DeclarationError(cid, f"output {duplicates[0]!r}", "declared more than once")
    by_name = {f.name: f for f in calc.fields}
    modes = calc.modes

    for f in calc.fields:
        part = f"field {f.name!r}"
        kinds = [
            k
            for k, on in (("integer", f.integer), ("boolean", f.boolean), ("choices", bool(f.choices)))
            if on
        ]
        if len(kinds) > 1:
            raise DeclarationError(cid, part, f"is both {' and '.join(kinds)}")
        if f.flags and not f.choices:
            raise DeclarationError(cid, part, "a flags field needs its choices")
        if f.choice_labels and len(f.choice_labels) != len(f.choices):
            raise DeclarationError(
                cid, part, f"{len(f.choice_labels)} choice labels for {len(f.choices)} choices"
            )
        if f.kind.with_unit:
            _check_unit(cid, part, f.unit, f.quantity)
        for word in ("min", "max"):
            bound = getattr(f, word)
            if bound is not None and (
                isinstance(bound, bool) or not isinstance(bound, (int, float)) or not math.isfinite(bound)
            ):
                raise DeclarationError(
                    cid,
                    part,
                    f"{word} {bound!r} is not a finite number (bounds are numbers in the display unit)",
                )
        if f.min is not None and f.max is not None and f.min > f.max:
            raise DeclarationError(
                cid,
                part,
                f"min {f.min} is above max {f.max} (both {'in ' + f.unit if f.unit else 'plain numbers'})",
            )
        problem = f.kind.declaration_problem(f)
        if problem:
            raise DeclarationError(cid, part, problem)
        for mode in f.modes:
            if mode not in modes:
                raise DeclarationError(
                    cid,
                    part,
                    f"shown in mode {mode!r}, which is not a mode (modes: {', '.join(modes) or 'none'})",
                )
        _check_when(cid, part, f.when, by_name)
        try:
            f.parse(f.default)
        except InputError as exc:
            raise DeclarationError(cid, part, f"default {f.default!r} is refused: {exc.message}") from None

    for o in calc.outputs:
        _check_unit(cid, f"output {o.name!r}", o.unit, o.quantity)
    for p in calc.plots:
        _check_unit(cid, f"plot {p.title!r} x axis", p.x_unit, p.x_quantity)
        _check_unit(cid, f"plot {p.title!r} y axis", p.y_unit, p.y_quantity)
        if isinstance(p, HeatMap):
            _check_unit(cid, f"plot {p.title!r} values", p.z_unit, p.z_quantity)
    for t in calc.tables:
        unknown_modes = [m for m in t.modes if m not in modes]
        if unknown_modes:
            raise DeclarationError(
                cid, f"table {t.name!r}", f"shown in mode {unknown_modes[0]!r}, not a mode"
            )
        _check_when(cid, f"table {t.name!r}", t.when, by_name)
    for target, mapping in calc.exports.items():
        for target_field, output in mapping.items():
            if output not in out_names:
                raise DeclarationError(
                    cid, f"export to {target}.{target_field}", f"{output!r} is not an output of {cid}"
                )


def _check_when(cid: str, part: str, when, by_name: Mapping[str, Field]) -> None:
    """A `when` names choice fields and only their choices."""
    for other, allowed in when:
        target = by_name.get(other)
        if target is None or not target.choices:
            raise DeclarationError(cid, part, f"`when` names {other!r}, which is not a choice field")
        unknown = [a for a in allowed if a not in target.choices]
        if unknown:
            raise DeclarationError(
                cid, part, f"`when` allows {', '.join(map(repr, unknown))}, not a choice of {other!r}"
            )


def check_links(found: dict[str, Calculator]) -> None:
    """What one calculator sends (ctrl+g) must land on a field of the same kind in another."""
    for calc in found.values():
        for target, mapping in calc.exports.items():
            if target not in found:
                raise DeclarationError(calc.id, f"export to {target!r}", "no such calculator")
            fields = {f.name: f for f in found[target].fields}
            for target_field, output in mapping.items():
                part = f"export to {target}.{target_field}"
                if target_field not in fields:
                    raise DeclarationError(calc.id, part, "no such field")
                sent, into = calc.output(output).quantity, fields[target_field].quantity
                if sent != into:
                    raise DeclarationError(calc.id, part, f"sends a {sent} to a {into} field")
