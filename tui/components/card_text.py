"""Every text a card draws, from what core solved: plain functions of (calculator, solution,
spread, error), no widget and no app, so they are tested as they are (tests/test_card_text.py).

The card (calculator_tab.py) only puts these texts where they go.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rich.text import Text

from gearhead.core.errors import InputError
from gearhead.core.model import Calculator, Field, Solution
from gearhead.core.sim.scene import VOLATILE

from .results import ResultRow
from .unit_text import pretty_quantity, pretty_unit

GLANCE_RESULTS = 3  # the first results of a calculator are its headline ones

HELP = (
    "Type to replace a value, Enter to edit it, Space to toggle; Tab and ↑↓ move. "
    "F1–F5 then a digit opens any calculator; ctrl+s saves, ctrl+o loads a preset."
)


def entries_key(entries: dict[str, Any], chosen_units: dict[str, str], system: str) -> tuple:
    """What a solution was solved from: the entries, the units chosen and the units preference."""
    return (
        tuple(sorted((k, repr(v)) for k, v in entries.items())),
        tuple(sorted(chosen_units.items())),
        system,
    )


def shown_by(calc: Calculator, entries: dict[str, Any]) -> tuple:
    """What decides which rows of the form show: the mode and the choices (a typed number cannot)."""
    from gearhead.core.model import choice_values

    return entries.get("mode"), tuple(sorted(choice_values(calc, entries).items()))


def visible_fields(calc: Calculator, entries: dict[str, Any]) -> tuple[Field, ...]:
    from gearhead.core.model import choice_values

    mode, choices = entries.get("mode"), choice_values(calc, entries)
    return tuple(f for f in calc.fields if f.active(mode, choices))


@dataclass(frozen=True)
class Drawn:
    """Everything a card draws for one solve, built in the solve's worker (off the UI thread)."""

    rows: list[ResultRow]
    tables: dict[str, list[tuple[str, ...]]]  # table name -> its rows' cells
    warnings: str
    status: Text
    glance: Text


def drawn(calc: Calculator, solved, seconds: float, hide_timings: bool = False) -> Drawn:
    """What a card shows for a core.solving.Solved that took `seconds`."""
    solution, spread = solved.solution, solved.spread
    return Drawn(
        result_rows(calc, solution, spread, hide_timings),
        {t.name: [table_cells(t, row) for row in solution.tables.get(t.name, [])] for t in calc.tables},
        warnings_text(solution.warnings, spread),
        solved_status(seconds, spread, hide_timings),
        glance(calc, solution),
    )


def next_unit(calc: Calculator, solution: Solution | None, name: str, shown: str | None) -> str | None:
    """The unit result `name` is shown in after `shown` (mm → cm → m → in → ft …); None when it
    has no other (not a quantity, no value, or a yes/no, text or count)."""
    from gearhead.core import units

    out = calc.output(name)
    value = solution.outputs.get(name) if solution is not None else None
    if out.quantity not in units.SI_UNITS or value is None or isinstance(value.value, (bool, str, int)):
        return None
    shown = shown or out.unit
    unit = units.next_unit(shown, out.quantity, out.unit)
    return unit if unit != shown else None


def can_send(calc: Calculator, solution: Solution | None) -> bool:
    """Whether ctrl+g has something to send: a result another calculator takes (in this mode:
    drivetrain's forward mode has no ratio), or a table row that fills one."""
    if solution is None:
        return bool(calc.exports) or any(t.exports for t in calc.tables)
    if any(out in solution.outputs for mapping in calc.exports.values() for out in mapping.values()):
        return True
    return any(t.exports and solution.tables.get(t.name) for t in calc.tables)


def duration(seconds: float) -> str:
    return f"{seconds * 1e3:.1f} ms" if seconds < 1 else f"{seconds:.2f} s"


def result_rows(
    calc: Calculator, solution: Solution, spread=None, hide_timings: bool = False
) -> list[ResultRow]:
    """One row per output solved: label, value text, equation label, and with tolerances its spread."""
    if spread is not None:  # only then: the tolerance module costs ~8 ms to import on a first visit
        from gearhead.core.tolerance import spread_text

    rows = []
    for name, value in solution.outputs.items():
        out = calc.output(name)
        text = "(hidden)" if hide_timings and name in VOLATILE else pretty_quantity(value.text)
        extra = ""
        if spread is not None:
            s = spread.outputs.get(name)
            extra = spread_text(calc, solution, s) if s else ""
            if s and s.main_input and s.low != s.high and len(spread.tolerances) > 1:
                extra += f"  {s.main_input}"
        rows.append(ResultRow(name, out.label, text, out.equation, extra))
    return rows


def glance(calc: Calculator, solution: Solution) -> Text:
    """The line above a narrow card: ✓ and its first results."""
    line = Text("✓ ", style="green")
    for i, (name, value) in enumerate(list(solution.outputs.items())[:GLANCE_RESULTS]):
        if i:
            line.append("  ·  ", style="dim")
        line.append(calc.output(name).label + " ", style="dim")
        line.append(pretty_quantity(value.text), style="bold")
    return line


def solved_status(seconds: float, spread=None, hide_timings: bool = False) -> Text:
    """The status line of a solve: how long it took, or with tolerances how they were spread."""
    if spread is None:
        return Text("✓ solved" if hide_timings else f"✓ solved in {duration(seconds)}", style="green")
    worst = (
        "optimiser" if any("optimiser" in s.worst_case_method for s in spread.outputs.values()) else "corners"
    )
    line = Text(f"✓ solved; tolerances: worst case by {worst}, σ first-order", style="green")
    if spread.samples:
        line.append(f" (* Monte Carlo, {spread.samples} samples, seed {spread.seed})")
    wall = "(hidden)" if hide_timings else f"{spread.cost.wall_time * 1e3:.0f} ms"
    line.append(
        f"; {spread.cost.solves} solves, {spread.cost.rhs_evaluations} RHS evaluations, {wall}", style="dim"
    )
    return line


def error_marks(calc: Calculator, error: InputError) -> dict[str, str]:
    """field -> message for every wrong entry (parse_inputs reports them all), marked on its row."""
    names = {f.name for f in calc.fields}
    marks: dict[str, str] = {}
    for e in error.errors:
        if e.field in names:
            marks.setdefault(e.field, e.message)
    return marks


def error_where(calc: Calculator, error: InputError) -> str:
    """The label the user sees on the form (not the internal field name), and how many more."""
    try:
        where = calc.field(error.field).label
    except KeyError:
        where = error.field
    if len(error.errors) > 1:
        where = f"{where} (and {len(error.errors) - 1} more)"
    return where


def error_status(calc: Calculator, error: InputError) -> Text:
    where = error_where(calc, error)
    return Text(f"✗ {where}: {error.message} (results show the last valid inputs)", style="red")


def error_glance(calc: Calculator, error: InputError) -> Text:
    return Text(f"✗ {error_where(calc, error)}: {error.message}", style="red")


def warnings_text(warnings: list[str], spread=None) -> str:
    text = "\n".join("! " + w for w in warnings)
    if spread is not None and spread.notes:  # e.g. 'backdrivable changes within the tolerances'
        text = "\n".join([text] * bool(text) + [f"± {n}" for n in spread.notes])
    return text


def field_help(f: Field, error: str | None = None) -> Text:
    """The help line of a form row: label, help, how to enter it; its error first, whole."""
    line = Text(f.label + ": ", style="bold")
    line.append(f.help or "")
    hint = f.kind.entry_hint(f)
    if hint:
        line.append(f"  ({hint})", style="dim")
    if error:  # the whole message: the status line and the glance cut it
        shown = Text()
        shown.append(f"⚠ {error}\n", style="bold red")
        shown.append_text(line)
        line = shown
    return line


def output_help(calc: Calculator, name: str, solution: Solution | None = None, spread=None) -> Text:
    """The help line of a result; with tolerances its spread in full: worst case and how it was
    found, σ and how, and the input that contributes most."""
    from gearhead.core import units

    out = calc.output(name)
    line = Text(out.label + (f" {out.equation}" if out.equation else "") + ": ", style="bold")
    line.append(out.help or "see the help of the fields it comes from")
    line.append("  (Enter: next unit)", style="dim")
    s = spread.outputs.get(name) if spread is not None and solution is not None else None
    if s is None or name not in solution.outputs:
        return line
    from gearhead.core.tolerance import short_method, shown_unit

    unit = shown_unit(calc, solution, name)

    def q(v):
        return f"{units.format_number(units.to_unit(v, unit, out.quantity))} {unit}".rstrip()

    worst, stat = short_method(s)
    line.append(f"\nWorst case {q(s.low)} .. {q(s.high)} ({s.worst_case_method}); σ {q(s.std)} ({stat})")
    if s.main_input and s.low != s.high:
        line.append(f"; mostly {s.main_input} ({s.shares[s.main_input] * 100:.0f} % of the variance)")
    return line


def table_cells(table, row: dict[str, Any]) -> tuple[str, ...]:
    """A table row's cells as the grid shows them (hidden columns left out)."""
    return tuple(
        pretty_quantity(row[c.name].text) if c.name in row else "" for c in table.columns if not c.hidden
    )


def table_header(column) -> str:
    return f"{column.label} [{pretty_unit(column.unit)}]" if column.unit else column.label


def in_field_unit(f: Field, entry: Any) -> Any:
    """A quantity entry written `number unit` in another unit than the field's, as the same
    amount in the field's unit with every digit (`0.1016 m` in an `in` field: `4.0 in`, shown
    `4`). Anything else (an expression, a tolerance, a bad entry) is kept as it is."""
    from .sheet import _ENTRY

    if not (f.kind.with_unit and f.unit and isinstance(entry, str)):
        return entry
    match = _ENTRY.match(entry)
    if match is None or not match.group(2) or match.group(2) == f.unit:
        return entry
    from gearhead.core import units

    try:
        si = units.parse(entry, f.unit, f.quantity, f.name)
        return f"{units.to_unit(si, f.unit, f.quantity)!r} {f.unit}"
    except (InputError, ValueError, ArithmeticError):
        return entry


def value_width(calc: Calculator) -> int:
    """The widest value text a result of `calc` can show: a number as units.format_number writes
    it at its widest ("-1.2346e-05") and the widest unit the output may be shown in (its own, the
    ring Enter walks, and the units preferences)."""
    from rich.cells import cell_len

    from gearhead.core import units
    from gearhead.core.unit_systems import SYSTEMS, system_unit

    widest = 0
    for o in calc.outputs:
        ring = (o.unit,) + units.COMMON_UNITS.get(o.quantity, ())
        ring += tuple(system_unit(u, system) for u in ring for system in SYSTEMS)
        unit = max(cell_len(pretty_unit(u)) for u in ring if u is not None)
        widest = max(widest, len("-1.2346e-05") + (1 + unit if unit else 0))
    return max(widest, 12)
