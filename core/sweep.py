"""Sweeps: one input over a range (a table, a plot) or two (a grid), each point solved as `solve` does.

The base inputs are parsed once (core.model.parse_inputs); each point replaces the varied inputs'
SI values, checks them against the field's bounds exactly as Field.parse does, and calls the
calculator's compute with the same guards as core.model.solve. A point that cannot be solved is a
row carrying the reason (the message `solve` would give), never a gap and never a crash.

    ratio=3..12:50                     50 points from 3 to 12 (the field's unit)
    spool_diameter=1 in..2 in:21       units as anywhere; the table shows inches
    voltage=6..12:7:log                log-spaced
    wheel_count=1..6                   a whole-number field: every whole number in the range
"""

from __future__ import annotations

import dataclasses
import math
import numbers
import re
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from dataclasses import field as dc_field
from typing import Any

from . import units
from .errors import InputError
from .model import (
    UNCOMPUTABLE,
    Calculator,
    Field,
    check_display_units,
    choice_values,
    parse_inputs,
    uncomputable,
)
from .sim import integrate  # integrate.cpu_clock read at each use (tests slow it down)
from .sim.effects import retire

DEFAULT_POINTS = 21
MAX_POINTS = 20_000  # a grid larger than this is a typo (a missing ':'), not a study
# CPU seconds of the sweeping thread for a whole sweep: 20 000 points of a default beam (0.23 s a
# solve) would run 77 minutes; past this the sweep stops with the points it has, and says so
SWEEP_SECONDS = 300.0
STATS = ("error_estimate", "rhs_evaluations", "wall_time")  # a scene's cost figures, not its physics
_NUMBER_THEN_UNIT = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*(?P<unit>.*?)\s*$")


@dataclass(frozen=True)
class Vary:
    """One varied input: SI endpoints, point count, spacing, and the unit its column is shown in."""

    name: str
    start: float
    stop: float
    points: int
    log: bool = False
    unit: str = ""  # display unit of the column (the unit typed for START, else the field's)

    def values(self, f: Field) -> list[float] | list[int]:
        n = self.points
        if f.kind.whole:
            lo, hi = sorted((self.start, self.stop))
            first, last = math.ceil(lo), math.floor(hi)
            if n >= last - first + 1:  # (len(range) overflows past 2**63: a sweep to 1e19)
                picked = list(range(first, last + 1))
            else:
                picked = sorted({round(x) for x in _spaced(lo, hi, n, self.log)})
            return picked if self.start <= self.stop else picked[::-1]
        return _spaced(self.start, self.stop, n, self.log)


def _spaced(start: float, stop: float, n: int, log: bool) -> list[float]:
    """n points from start to stop inclusive; the endpoints are exactly what was typed."""
    if n == 1:
        return [start]
    if log and math.isfinite(stop / start) and stop / start != 0:
        ratio = stop / start
        inner = [start * ratio ** (i / (n - 1)) for i in range(1, n - 1)]
    elif log:  # in logarithms: stop/start overflows for 1e-200..1e200 lbf (4.4e200/4.4e-200 is inf)
        sign, a, b = math.copysign(1.0, start), math.log(abs(start)), math.log(abs(stop))
        inner = [sign * math.exp(a + (b - a) * i / (n - 1)) for i in range(1, n - 1)]
    elif math.isfinite(stop - start):
        inner = [start + (stop - start) * i / (n - 1) for i in range(1, n - 1)]
    else:  # -1e308..1e308: the span overflows; each point weighs the ends instead
        inner = [start * (1 - i / (n - 1)) + stop * (i / (n - 1)) for i in range(1, n - 1)]
    return [start, *inner, stop]


def parse_vary(calc: Calculator, text: str) -> Vary:
    """'NAME=START..STOP[:N][:log]' -> Vary. Every mistake is an InputError naming the input."""
    name, sep, spec = str(text).partition("=")
    name = name.strip()
    if not sep or not name:
        raise InputError(name or "--vary", f"expected NAME=START..STOP[:N][:log], got {text!r}")
    try:
        f = calc.field(name)
    except KeyError:
        numeric = ", ".join(x.name for x in calc.fields if x.kind.numeric)
        raise InputError(name, f"is not an input of {calc.id} (numeric inputs: {numeric})") from None
    if not f.kind.numeric:
        raise InputError(name, f"is a {f.type} input; only numbers can be swept")
    parts = [p.strip() for p in spec.split(":")]
    rng, options = parts[0], parts[1:]
    if "..." in rng or rng.count("..") != 1:
        raise InputError(name, f"expected START..STOP (two dots), got {rng!r}")
    start_text, stop_text = (s.strip() for s in rng.split(".."))
    if not start_text or not stop_text:
        raise InputError(name, f"expected START..STOP, got {rng!r}")
    points, log = None, False
    for opt in options:
        if opt.lower() == "log":
            if log:
                raise InputError(name, "'log' given twice")
            log = True
        elif re.fullmatch(r"\d+", opt):
            if points is not None:
                raise InputError(name, f"the point count is given twice ({points} and {opt})")
            points = int(opt)
        else:
            raise InputError(
                name, f"{opt!r} is neither a point count nor 'log' (expected NAME=START..STOP[:N][:log])"
            )
    if f.kind.with_unit:
        start, stop = (units.parse(t, f.unit, f.quantity, name) for t in (start_text, stop_text))
        shown = _typed_unit(start_text, f)
    else:  # as the kind reads an entry (bounds: per point, as rows)
        start, stop = (_endpoint(f, t) for t in (start_text, stop_text))
        shown = ""
    if start == stop:
        raise InputError(name, f"the range {rng!r} is empty (start equals stop)")
    if points is None:
        points = abs(int(stop) - int(start)) + 1 if f.kind.whole else DEFAULT_POINTS
    if points < 2:
        raise InputError(name, f"needs at least 2 points, got {points}")
    if points > MAX_POINTS:
        raise InputError(name, f"{points} points is more than {MAX_POINTS}")
    if log and not (start * stop > 0):
        raise InputError(name, f"a log sweep needs both ends of one sign and not zero ({rng!r})")
    return Vary(name, start, stop, points, log, shown)


def _endpoint(f: Field, text: str) -> float | int:
    """One end of a range typed for a field without a unit, read by the field's kind but not held
    to its bounds (each point is checked, as rows)."""
    unbounded = dataclasses.replace(f, min=None, max=None, min_exclusive=False, max_exclusive=False)
    return unbounded.kind.parse(unbounded, text)


def _typed_unit(text: str, f: Field) -> str:
    """The unit written after the number ('1 in' -> 'in') if it can show this field, else the field's."""
    m = _NUMBER_THEN_UNIT.match(text)
    unit = m.group("unit") if m else ""
    if unit:
        try:
            units.factor(unit, f.quantity)
            return unit
        except Exception:  # not a plain unit (an expression such as '1 in + 2 mm'): the field's unit
            pass
    return f.unit


# ---------------------------------------------------------------------------------------------
# One point: exactly core.model.solve's compute and guards, on already-parsed values


@dataclass
class Outcome:
    outputs: dict[str, Any]  # SI
    warnings: list[str]
    error: str | None = None  # "field: message", as solve's InputError reads; None when solved
    rhs_evaluations: int = 0


def checked(f: Field, value: float | int) -> float | int:
    """A varied SI value through the field's own bounds check (what Field.parse applies)."""
    if f.kind.whole:
        if value != int(value):
            raise InputError(f.name, f"{value!r} is not a whole number")
        value = int(value)
    else:
        value = float(value)
    return f._check_bounds(value, f.kind.bound_text(f, value))


def evaluate(calc: Calculator, values: Mapping[str, Any]) -> Outcome:
    """Compute one point with core.model.solve's guards (an InputError, an arithmetic failure or a
    non-finite output is the point's error, with solve's message)."""
    try:
        result = calc.compute(values)
    except InputError as exc:
        return Outcome({}, [], str(exc))
    except UNCOMPUTABLE as exc:  # core.model.solve's last-resort guard, as the point's error
        return Outcome({}, [], str(uncomputable(exc)))
    out = {}
    for o in calc.outputs:
        if o.name not in result.values:
            continue
        v = result.values[o.name]
        if isinstance(v, float) and not math.isfinite(v):
            return Outcome(
                {}, list(result.warnings), f"(result): {o.name} could not be computed from these inputs"
            )
        out[o.name] = v
    nfev = out.get("rhs_evaluations", 0)
    return Outcome(out, list(result.warnings), None, int(nfev) if isinstance(nfev, numbers.Number) else 0)


@dataclass
class Cost:
    """What a study took: solves, right-hand-side evaluations (main runs) and wall time."""

    solves: int = 0
    rhs_evaluations: int = 0
    wall_time: float = 0.0

    def add(self, outcome: Outcome) -> None:
        self.solves += 1
        self.rhs_evaluations += outcome.rhs_evaluations

    def text(self) -> str:
        return (
            f"{self.solves} solve{'s' if self.solves != 1 else ''}, "
            f"{self.rhs_evaluations} RHS evaluations, {self.wall_time * 1e3:.1f} ms"
        )

    def as_json(self) -> dict[str, Any]:
        return {"solves": self.solves, "rhs_evaluations": self.rhs_evaluations, "wall_time": self.wall_time}


# ---------------------------------------------------------------------------------------------
# The sweep


@dataclass
class Point:
    inputs: dict[str, float | int]  # the varied inputs, SI
    outputs: dict[str, Any]  # SI (empty when infeasible)
    warnings: list[str]
    error: str | None


@dataclass
class Sweep:
    calculator: Calculator
    varies: list[Vary]
    outputs: list[str]  # the outputs shown, in order
    points: list[Point]
    cost: Cost
    cancelled: bool = False
    notes: list[str] = dc_field(default_factory=list)
    display_units: dict[str, str] = dc_field(default_factory=dict)  # output -> unit

    def output_unit(self, name: str) -> str:
        return self.display_units.get(name, self.calculator.output(name).unit)

    def columns(self) -> list[tuple[str, str, str]]:
        """(name, quantity, display unit) of every column: varied inputs, then outputs."""
        cols = []
        for v in self.varies:
            f = self.calculator.field(v.name)
            cols.append((v.name, f.quantity if f.kind.with_unit else "dimensionless", v.unit))
        for name in self.outputs:
            o = self.calculator.output(name)
            cols.append((name, o.quantity, self.output_unit(name)))
        return cols

    def display_row(self, point: Point) -> list[float | int | str | None]:
        """A point in display units (numbers), None where an output is absent, then its status."""
        row: list[Any] = []
        for v in self.varies:
            x = point.inputs[v.name]
            f = self.calculator.field(v.name)
            row.append(units.to_unit(x, v.unit, f.quantity) if f.kind.with_unit else x)
        for name in self.outputs:
            row.append(
                _display(
                    point.outputs.get(name), self.calculator.output(name).quantity, self.output_unit(name)
                )
            )
        return row

    def csv_text(self) -> str:
        import csv
        import io

        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow([f"{n} [{u}]" if u else n for n, _, u in self.columns()] + ["status"])
        for p in self.points:
            cells = [
                "" if x is None else (repr(x) if isinstance(x, float) else x) for x in self.display_row(p)
            ]
            writer.writerow(cells + [p.error or "ok"])
        return buf.getvalue()

    def as_json(self) -> dict[str, Any]:
        calc = self.calculator
        return {
            "calculator": calc.id,
            "vary": [
                {
                    "name": v.name,
                    "start": v.start,
                    "stop": v.stop,
                    "points": v.points,
                    "log": v.log,
                    "unit": calc.field(v.name).kind.reported(calc.field(v.name), v.start)[1],
                }
                for v in self.varies
            ],
            "outputs": {n: {"unit": units.SI_UNITS[calc.output(n).quantity]} for n in self.outputs},
            "points": [
                {
                    "inputs": p.inputs,
                    "outputs": {n: p.outputs[n] for n in self.outputs if n in p.outputs},
                    "warnings": p.warnings,
                    "error": p.error,
                }
                for p in self.points
            ],
            "cancelled": self.cancelled,
            "notes": self.notes,
            "cost": self.cost.as_json(),
        }


def _display(value: Any, quantity: str, unit: str) -> Any:
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    return units.to_unit(float(value), unit, quantity)


def numeric_outputs(calc: Calculator, sample: Mapping[str, Any] | None = None) -> list[str]:
    """Outputs worth a column: numbers (not flags or text), not a scene's cost figures."""
    names = []
    for o in calc.outputs:
        if o.name in STATS:
            continue
        if sample is not None:
            v = sample.get(o.name)
            if v is None or isinstance(v, (bool, str)):
                continue
        names.append(o.name)
    return names


def run(
    calc: Calculator,
    raw: Mapping[str, Any],
    varies: Sequence[str | Vary],
    outputs: Sequence[str] = (),
    display_units: Mapping[str, str] | None = None,
    progress: Callable[[int, int], None] | None = None,
    cancelled: Callable[[], bool] | None = None,
) -> Sweep:
    """Sweep `varies` (one or two 'NAME=START..STOP[:N][:log]' or Vary) of `calc` from the inputs
    `raw`. `calc` is the calculator itself, not an id: a workbook seen as one calculator
    (core.workbook.as_calculator) is swept by this same loop.

    Two varies make a grid: the first varies slowest. `progress(done, total)` is called as points
    finish; when `cancelled()` turns true the sweep stops and returns the points it has.
    """
    t0 = time.perf_counter()
    specs = [v if isinstance(v, Vary) else parse_vary(calc, v) for v in varies]
    if not 1 <= len(specs) <= 2:
        raise InputError("--vary", f"sweep one input (a table) or two (a grid), not {len(specs)}")
    if len(specs) == 2 and specs[0].name == specs[1].name:
        raise InputError(specs[0].name, "is varied twice")
    raw, notes = retire(calc.fields, raw)  # an old name among a flags field: noted once, not per point
    base, _ = parse_inputs(calc, raw, retired=True)
    mode = base.get("mode")
    choices = choice_values(calc, raw, retired=True)
    for v in specs:
        if not calc.field(v.name).active(mode, choices):
            raise InputError(
                v.name, f"is not used with these choices (mode {mode!r}); sweeping it changes nothing"
            )
    for name in outputs:
        try:
            calc.output(name)
        except KeyError:
            raise InputError(
                name, f"is not an output of {calc.id} (outputs: {', '.join(o.name for o in calc.outputs)})"
            ) from None
    display_units = check_display_units(calc, display_units)

    fields = [calc.field(v.name) for v in specs]
    axes = [v.values(f) for v, f in zip(specs, fields)]
    grid = [(x,) for x in axes[0]] if len(axes) == 1 else [(x, y) for x in axes[0] for y in axes[1]]
    if len(grid) > MAX_POINTS:
        raise InputError("--vary", f"{len(grid)} points is more than {MAX_POINTS}")
    cost = Cost()
    points: list[Point] = []
    stopped = False
    started = integrate.cpu_clock()
    for i, xs in enumerate(grid):
        if cancelled is not None and cancelled():
            stopped = True
            break
        if integrate.cpu_clock() - started > SWEEP_SECONDS:
            notes.append(
                f"stopped after {i} of {len(grid)} points: the sweep's budget ({SWEEP_SECONDS:g} s of "
                f"computing) is spent; sweep fewer points or a narrower range"
            )
            break
        values = dict(base)
        shown = {}
        error = None
        for f, x in zip(fields, xs):
            shown[f.name] = x
            try:
                values[f.name] = checked(f, x)
            except InputError as exc:
                error = str(exc)
        if error is None:
            outcome = evaluate(calc, values)
            cost.add(outcome)
            points.append(
                Point(
                    {f.name: values[f.name] for f in fields}, outcome.outputs, outcome.warnings, outcome.error
                )
            )
        else:
            points.append(Point(shown, {}, [], error))
        if progress is not None:
            progress(i + 1, len(grid))
    notes += _shared_warnings(points)
    chosen = list(outputs)
    if not chosen:
        sample = next((p.outputs for p in points if p.error is None), None)
        chosen = numeric_outputs(calc, sample)
    cost.wall_time = time.perf_counter() - t0
    return Sweep(calc, specs, chosen, points, cost, stopped, notes, display_units=display_units)


def _shared_warnings(points: list[Point]) -> list[str]:
    """The warnings every solved point gives (two or more points), taken off the points and returned
    to be said once: a row's status then says what is particular to it, "ok" when nothing is (the
    elevator's "closed form, no integration" repeated in every row said nothing about any row)."""
    solved = [p for p in points if p.error is None]
    if len(solved) < 2:
        return []
    shared = [w for w in solved[0].warnings if all(w in p.warnings for p in solved[1:])]
    for p in solved:
        p.warnings = [w for w in p.warnings if w not in shared]
    return [f"at every point: {w}" for w in shared]


# ---------------------------------------------------------------------------------------------
# Text for the command line


def text_table(sweep: Sweep, max_outputs: int | None = 6) -> str:
    """A plain table in display units: one row per point (a matrix when two inputs and one output)."""
    calc = sweep.calculator
    shown = sweep.outputs if max_outputs is None else sweep.outputs[:max_outputs]
    lines = [f"{calc.title} ({calc.id}): sweep of {' and '.join(v.name for v in sweep.varies)}"]
    if len(sweep.varies) == 2 and len(shown) == 1:
        lines += _matrix(sweep, shown[0])
    else:
        cols = [(n, q, u) for n, q, u in sweep.columns() if n in shown or n in {v.name for v in sweep.varies}]
        heads = [f"{n} [{u}]" if u else n for n, _, u in cols]
        body = []
        for p in sweep.points:
            cells = []
            row = dict(zip([c[0] for c in sweep.columns()], sweep.display_row(p)))
            for n, _, _ in cols:
                cells.append(cell_text(row[n]) if p.error is None or n in p.inputs else "")
            if p.error is not None:
                cells = cells[: len(sweep.varies)] + [f"infeasible: {p.error}"]
            elif p.warnings:
                cells.append(
                    "warning: "
                    + p.warnings[0]
                    + (f" (+{len(p.warnings) - 1})" if len(p.warnings) > 1 else "")
                )
            body.append(cells)
        widths = [
            max(
                [len(h)]
                + [len(r[i]) for r in body if i < len(r) and not r[i].startswith(("infeasible", "warning"))]
            )
            for i, h in enumerate(heads)
        ]
        lines.append("  ".join(h.rjust(w) for h, w in zip(heads, widths)))
        for r in body:
            lines.append(
                "  ".join(
                    c.rjust(w) if i < len(widths) and not c.startswith(("infeasible", "warning")) else c
                    for i, (c, w) in enumerate(zip(r, widths + [0] * len(r)))
                )
            )
    hidden = len(sweep.outputs) - len(shown)
    if hidden > 0:
        lines.append(
            f"({hidden} more output{'s' if hidden > 1 else ''}: choose with --output NAME, or all with --csv/--json)"
        )
    bad = sum(1 for p in sweep.points if p.error is not None)
    if bad:
        lines.append(f"{bad} of {len(sweep.points)} points infeasible (reason in the row)")
    if sweep.cancelled:
        lines.append("cancelled: the points above are all that were solved")
    lines.append(f"cost: {sweep.cost.text()}")
    return "\n".join(lines)


def cell_text(x: Any) -> str:
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, numbers.Integral):
        return str(int(x))
    if isinstance(x, float):
        return units.format_number(x)
    return str(x)


def _matrix(sweep: Sweep, name: str) -> list[str]:
    vx, vy = sweep.varies
    calc = sweep.calculator
    unit = sweep.output_unit(name)
    ys = []
    for p in sweep.points:
        if p.inputs[vy.name] not in ys:
            ys.append(p.inputs[vy.name])
    fy = calc.field(vy.name)
    fx = calc.field(vx.name)

    def show_in(f: Field, v: Vary, x):
        if f.kind.with_unit:
            return units.format_number(units.to_unit(x, v.unit, f.quantity))
        return f.kind.bound_text(f, x)

    corner = f"{vx.name} \\ {vy.name}"
    head = [corner] + [show_in(fy, vy, y) for y in ys]
    rows = []
    current = None
    for p in sweep.points:
        x = p.inputs[vx.name]
        if current is None or current[0] != x:
            current = [x, []]
            rows.append(current)
        v = p.outputs.get(name)
        current[1].append(
            "infeasible" if p.error else cell_text(_display(v, calc.output(name).quantity, unit))
        )
    table = [head] + [[show_in(fx, vx, x)] + cells for x, cells in rows]
    widths = [max(len(r[i]) for r in table if i < len(r)) for i in range(len(head))]
    out = [
        f"{name}{f' [{unit}]' if unit else ''}; rows {vx.name}{f' [{vx.unit}]' if vx.unit else ''}, "
        f"columns {vy.name}{f' [{vy.unit}]' if vy.unit else ''}"
    ]
    out += ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in table]
    reasons = sorted({p.error for p in sweep.points if p.error})
    out += [f"infeasible: {r}" for r in reasons[:5]]
    return out
