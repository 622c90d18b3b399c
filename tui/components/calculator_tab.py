"""One generic card that renders any calculator from its description (core.model.Calculator).

The form is one Sheet (sheet.py: a row per field, spreadsheet keys), the results one ResultsList
(results.py); beside them the calculator's charts and tables, its warnings and a status line.
Every change of an entry is solved at once in a thread (one solve at a time per card, latest
wins), so the interface never waits for pint or scipy. A solution is tagged with the entries it
was solved from and shown only while they are the entries on screen.
"""

from __future__ import annotations

from threading import Event, get_ident
from types import SimpleNamespace
from typing import Any

from rich.text import Text
from textual.app import ComposeResult
from textual.containers import Horizontal, Vertical, VerticalScroll
from textual.widget import Widget
from textual.widgets import DataTable, Static

from gearhead.core.errors import InputError
from gearhead.core.model import Calculator, Field, Solution
from gearhead.core.sim.scene import VOLATILE

from ..guard import guard, guarded
from .results import FRESH, PENDING, STALE, ResultRow, ResultsList
from .sheet import Sheet
from .unit_text import pretty_quantity, pretty_unit

BUSY_AFTER_S = 0.1  # a solve running longer than this shows '… solving'


def _entries_key(entries: dict[str, Any], display_units: dict[str, str], system: str) -> tuple:
    """What a solution was solved from: the entries, the units chosen and the units preference."""
    return (
        tuple(sorted((k, repr(v)) for k, v in entries.items())),
        tuple(sorted(display_units.items())),
        system,
    )


class CalculatorTab(Widget):
    """The whole card for one calculator. Its handlers and the callbacks the sheet, the results
    list, timers and solve threads call are @guarded: a bug in one is a notification and a logged
    traceback (guard.py), and the card keeps what was typed."""

    sheet_class = Sheet  # the form's class (a workbook card's refuses edits on its linked rows)

    def __init__(
        self, calculator: Calculator, blink: bool = True, hide_timings: bool = False, **kwargs
    ) -> None:
        super().__init__(**kwargs)
        self.calculator = calculator
        self.blink = blink
        self.hide_timings = hide_timings  # snapshot tests: no wall-clock figures on screen
        self.entries: dict[str, Any] = {f.name: self.initial_entry(f) for f in calculator.fields}
        self.solution: Solution | None = None  # the last valid solution
        self.solution_key: tuple | None = None  # what it was solved from (_entries_key)
        self.error: InputError | None = None  # what is wrong with the entries on screen
        self.error_key: tuple | None = None
        self.display_units: dict[str, str] = {}  # output -> unit the user chose (Enter on a result)
        self.unit_system = "calculator"  # the units preference (core.unit_systems), set by the app
        self._preferred_units: dict[str, str] = {}  # output -> unit the preference gave last solve
        self.preset_meta = ("", "")  # name and description of the preset last loaded here
        self._solving = False  # a solve thread is running
        self._sendable: bool | None = None  # ctrl+g had something to send at the last solve
        self._dirty = False  # entries changed since the running solve started
        self._solve_seconds = 0.0  # wall time of the last whole solve
        self._estimating: set[int] = set()  # threads computing a shown solution's error estimate
        self._shown_by = None  # (mode, choices) the visible rows were chosen for
        self._warnings_text: str | None = None
        self._show_generation = 0  # solutions shown so far (a pending estimate belongs to the last)
        self.spread = None  # the last solve's core.tolerance.Spread, or None
        self._mounted = False

    @staticmethod
    def initial_entry(f: Field) -> Any:
        """A field's default as the sheet holds it."""
        return f.kind.initial_entry(f)

    # ---- layout -------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        calc = self.calculator
        # narrow terminals stack the results under the form: the key results and the status stay
        # in sight on this line, above the card, while typing (shown below 120 columns only)
        yield Static("", classes="glance")
        with Horizontal(classes="card"):
            with Vertical(classes="inputs-pane"):
                yield Static(Text(calc.summary), classes="summary")
                self.sheet = self.sheet_class(
                    calc,
                    entries=lambda: self.entries,
                    on_entry=self._take_entry,
                    on_cursor=self._explain_field,
                    on_choose=self._choose,
                    classes="form",
                )
                yield self.sheet
                yield Static(
                    Text(
                        "Type to replace a value, Enter to edit it, Space to toggle; Tab and ↑↓ move. "
                        "F1–F5 then a digit opens any calculator; ctrl+s saves, ctrl+o loads a preset.",
                        style="dim",
                    ),
                    classes="help-line",
                )
            with Vertical(classes="results-pane"):
                self.results = ResultsList(
                    on_select=self._cycle_unit, on_cursor=self._explain_output, classes="results"
                )
                self.results.value_width = value_width(calc)
                widest = max((len(o.equation) for o in calc.outputs), default=0)
                self.results.equation_width = max(widest, 3) if widest else 0
                yield self.results
                self.plot = None
                if calc.plots:
                    from .plot_panel import PlotPanel

                    self.plot = PlotPanel(calc.plots)
                    self.plot.unit_system = self.unit_system
                    yield self.plot
                yield from self._compose_tables()
                # long or many warnings scroll in a box of their own instead of pushing the
                # status line out of the pane
                with VerticalScroll(classes="warnings-box"):
                    self.warnings = Static("", classes="warnings")
                    yield self.warnings
                self.status = Static("", classes="status")
                yield self.status

    @guarded
    def on_mount(self) -> None:
        self.glance = self.query_one(".glance", Static)
        self.help_line = self.query_one(".help-line", Static)
        self.warnings_box = self.query_one(".warnings-box")
        self._mounted = True
        self._apply_mode()
        self.solve()

    # ---- entries ------------------------------------------------------------------------
    @guarded
    def _take_entry(self, name: str, value: Any) -> None:
        """The sheet changed an entry (a key, a toggle, a choice): solved at once."""
        if self.entries.get(name) == value:
            return
        self.entries = {**self.entries, name: value}
        self._entries_changed(name)

    def _entries_changed(self, name: str | None = None) -> None:
        """`name`: the one entry changed (its row alone is repainted); None: any of them."""
        from gearhead.core.model import choice_values

        # a typed number cannot show or hide a field: only a mode or choice change re-applies
        shown_by = (
            self.entries.get("mode"),
            tuple(sorted(choice_values(self.calculator, self.entries).items())),
        )
        if shown_by != self._shown_by:
            self._apply_mode()
            self.sheet.refresh()
        elif name is not None:
            self.sheet.refresh_field(name)
        else:
            self.sheet.refresh()
        self.solve()

    def _apply_mode(self) -> None:
        from gearhead.core.model import choice_values

        mode = self.entries.get("mode")
        choices = choice_values(self.calculator, self.entries)
        self._shown_by = (mode, tuple(sorted(choices.items())))
        self.sheet.set_visible(tuple(f for f in self.calculator.fields if f.active(mode, choices)))

    def set_entries(self, values: dict[str, Any]) -> None:
        """Put values into the card (preset load, send-to), then solve once. A quantity given in
        another unit than the field's is converted to it, every digit kept (the sheet shows 6)."""
        merged = dict(self.entries)
        for name, value in values.items():
            f = self.calculator.field(name)
            merged[name] = in_field_unit(f, f.kind.entry(f, value))
        self.entries = merged
        self.sheet.editing = False
        self._entries_changed()

    def current_inputs(self) -> dict[str, Any]:
        """What the user entered, as a preset stores it (whole numbers as TOML integers)."""
        return {f.name: f.kind.stored(f, self.entries[f.name]) for f in self.calculator.fields}

    @guarded
    def _choose(self, field: Field) -> None:
        """A choice row's list (Enter or a click on it)."""
        from .choice_screen import ChoiceScreen

        spec = field.kind.widget(field)

        def chosen(value) -> None:
            if value is not None:
                self._take_entry(field.name, value)

        self.app.push_screen(
            ChoiceScreen(field.label, spec.options, self.entries.get(field.name)), guard(self, chosen)
        )

    # ---- the help line ------------------------------------------------------------------
    @guarded
    def _explain_field(self, f: Field) -> None:
        line = Text(f.label + ": ", style="bold")
        line.append(f.help or "")
        hint = f.kind.entry_hint(f)
        if hint:
            line.append(f"  ({hint})", style="dim")
        error = self.sheet.errors.get(f.name)
        if error:  # the whole message, first: the status line and the glance cut it
            shown = Text()
            shown.append(f"⚠ {error}\n", style="bold red")
            shown.append_text(line)
            line = shown
        if self._mounted:
            self.help_line.update(line)

    @guarded
    def _explain_output(self, name: str) -> None:
        out = self.calculator.output(name)
        line = Text(out.label + (f" {out.equation}" if out.equation else "") + ": ", style="bold")
        line.append(out.help or "see the help of the fields it comes from")
        line.append("  (Enter: next unit)", style="dim")
        self._append_spread(name, line)
        self.help_line.update(line)

    @guarded
    def _cycle_unit(self, name: str) -> None:
        """Show the chosen result in the next common unit of its kind (mm → cm → m → in → ft …)."""
        from gearhead.core import units

        out = self.calculator.output(name)
        if out.quantity not in units.SI_UNITS or self.solution is None:
            return
        value = self.solution.outputs.get(name)
        if value is None or isinstance(value.value, (bool, str, int)):
            return
        shown = self.display_units.get(name) or self._preferred_units.get(name, out.unit)
        unit = units.next_unit(shown, out.quantity, out.unit)
        if unit != shown:
            self.display_units = {**self.display_units, name: unit}
            self.solve()

    def set_unit_system(self, system: str) -> None:
        """Show results in a units preference; units chosen with Enter give way to it."""
        self.unit_system = system
        self.display_units = {}
        if self.plot is not None:
            self.plot.unit_system = system
        self.solve()

    # ---- solving -----------------------------------------------------------------------
    # No fixed typing pause: a closed-form solve takes ~0.1 ms, so every change is solved at
    # once, in a thread (the first use of pint or scipy must not freeze typing). At most one solve
    # runs per card; changes meanwhile mark it dirty, and when the running solve ends its result
    # is dropped and the latest entries are solved instead (latest wins, nothing queues).
    @property
    def key(self) -> tuple:
        """What the card on screen asks to be solved."""
        return _entries_key(self.entries, self.display_units, self.unit_system)

    def solve(self) -> None:
        self._dirty = True
        if not self._solving:
            self._start_solve()

    @property
    def busy(self) -> bool:
        """A solve is running or waiting to run, or a shown solve's error estimate is being
        computed, or its chart is waiting to be drawn (tests wait for this to clear)."""
        plot = self.plot if self._mounted else None
        return self._solving or self._dirty or bool(self._estimating) or (plot is not None and plot.pending)

    # A solve that took less than WAIT_S last time is waited for, that long: its result is then
    # drawn in the frame that echoes the key, where a result from a thread waits for the next frame.
    WAIT_S = 0.008

    def _start_solve(self) -> None:
        from threading import Lock, Thread

        self._dirty = False
        self._solving = True
        key = self.key
        args = (dict(self.entries), dict(self.display_units), self.unit_system)
        handoff = SimpleNamespace(waiting=True, result=None, lock=Lock(), done=Event())
        Thread(
            target=self._solve_in_thread, args=(args, key, handoff), name="gearhead-solve", daemon=True
        ).start()
        if self._solve_seconds < self.WAIT_S:
            handoff.done.wait(self.WAIT_S)
        with handoff.lock:
            handoff.waiting = False
            result = handoff.result
        if result is not None:
            self._solve_done(*result)
        else:
            self._show_pending()
            self.set_timer(BUSY_AFTER_S, self._mark_busy)

    def _solve_in_thread(self, args: tuple, key: tuple, handoff: SimpleNamespace) -> None:
        solution, error, pending = self._solve_entries(*args)
        try:
            with handoff.lock:
                in_time = handoff.waiting
                if in_time:  # _start_solve is waiting: it shows the result itself
                    handoff.result = (solution, error, key)
                    handoff.done.set()
            if not in_time:
                self.app.call_from_thread(self._solve_done, solution, error, key)
            if pending:
                # once the frame with the results is drawn (this thread would hold the GIL from
                # it), and only if they are the ones on screen: now their error estimate
                drawn = Event()
                self.app.call_from_thread(self.call_after_refresh, drawn.set)
                drawn.wait(1.0)
                shown = solution.solution
                if self.solution is shown:
                    self.app.call_from_thread(
                        self._estimate_done, shown, self._run_estimate(pending[0], shown)
                    )
        except RuntimeError:  # the app closed while this solve ran
            pass
        except Exception as exc:  # a bug in the error estimate: logged and said, as a handler's
            from ..guard import report

            try:
                self.app.call_from_thread(report, self, exc, "CalculatorTab._solve_in_thread")
            except RuntimeError:  # the app closed meanwhile: the log alone
                from ..bug_log import record

                record(exc, "gearhead (the app) CalculatorTab._solve_in_thread")
        finally:
            self._estimating.discard(get_ident())

    def _solve_entries(self, entries: dict[str, Any], display_units: dict[str, str], system: str):
        """(solution, error, pending error estimate) of these entries; never raises."""
        from time import perf_counter

        from gearhead.core import unit_systems
        from gearhead.core.sim.integrate import Cancelled, budget
        from gearhead.core.sim.scene import deferred_estimate
        from gearhead.core.tolerance import solve_entries  # entries may carry '± tolerance'

        started = perf_counter()
        pending: list = []
        spread = None
        try:
            preferred = unit_systems.display_units(self.calculator, system, entries)
            self._preferred_units = preferred
            # a simulation polls this between steps: a change meanwhile drops it (latest wins)
            with budget(cancel=lambda: self._dirty), deferred_estimate() as pending:
                solution, spread = solve_entries(self.calculator.id, entries, {**preferred, **display_units})
            if pending and spread is None:
                # shown first with "…" in its row; computed below, after the results are on screen
                solution = self._estimate_pending(solution)
            else:
                pending = []  # with tolerances every solve is whole (the spread needs each estimate)
            error = None
        except Cancelled:  # only when _dirty: _solve_done starts the solve of the latest entries
            solution, error = None, None
        except InputError as exc:
            solution, error = None, exc
            if exc.__cause__ is not None:  # the last-resort guard fired: keep the traceback
                from ..bug_log import record

                record(exc, f"{self.calculator.id} {entries!r}")
        except Exception as exc:  # a bug must not take the app (and what was typed) down with it
            from ..bug_log import record

            path = record(exc, f"{self.calculator.id} {entries!r}")
            solution, error = (
                None,
                InputError(
                    "(result)",
                    f"internal error: {type(exc).__name__}: {exc}"
                    + (f" (traceback in {path})" if path else ""),
                ),
            )
        if solution is not None:
            solution = SimpleNamespace(solution=solution, spread=spread)
        self._solve_seconds = perf_counter() - started  # the whole solve (an optimiser's search too)
        return solution, error, pending

    @guarded
    def _solve_done(self, solved, error: InputError | None, key: tuple) -> None:
        self._solving = False
        if not self._mounted or not self.is_attached:
            return  # the app closed, or the card was removed, meanwhile
        if self._dirty or key != self.key:  # entries changed while solving: already stale
            self._start_solve()
            return
        if solved is None and error is None:  # cancelled, and nothing newer asked for
            self._start_solve()
            return
        self._show(solved, error, key)

    @guarded
    def _mark_busy(self) -> None:
        if self._solving:
            self.status.update(Text("… solving", style="yellow"), layout=False)

    def _show_pending(self) -> None:
        """The entries on screen are being solved: no result of other entries is drawn."""
        if self.solution is not None and self.solution_key != self.key:
            self.results.show(self._rows(self.solution), PENDING)

    def _show(self, solved, error: InputError | None, key: tuple) -> None:
        if error is not None:
            self.error, self.error_key = error, key
            names = {f.name for f in self.calculator.fields}
            # every wrong entry is marked on its row (parse_inputs reports them all: InputErrors)
            marks: dict[str, str] = {}
            for e in error.errors:
                if e.field in names:
                    marks.setdefault(e.field, e.message)
            self.sheet.set_errors(marks)
            try:  # the label the user sees on the form, not the internal field name
                where = self.calculator.field(error.field).label
            except KeyError:
                where = error.field
            if len(error.errors) > 1:
                where = f"{where} (and {len(error.errors) - 1} more)"
            if self.solution is not None:
                self.results.show(self._rows(self.solution), STALE)
            self.status.update(
                Text(f"✗ {where}: {error.message} (results show the last valid inputs)", style="red"),
                layout=False,
            )
            self.glance.update(Text(f"✗ {where}: {error.message}", style="red"), layout=False)
            if self.plot is not None and not self.plot.has_class("stale"):
                self.plot.add_class("stale")
            return
        self.error = self.error_key = None
        self.sheet.set_errors({})
        solution = solved.solution
        self.solution, self.solution_key, self.spread = solution, key, solved.spread
        self._show_generation += 1
        self.results.show(self._rows(solution), FRESH)
        if self.plot is not None:
            if self.plot.has_class("stale"):
                self.plot.remove_class("stale")
            self.plot.show_soon(solution)
        self._show_tables(solution)
        self._show_warnings(solution.warnings)
        status = Text(
            "✓ solved" if self.hide_timings else f"✓ solved in {_duration(self._solve_seconds)}",
            style="green",
        )
        if self.spread is not None:
            status = self._spread_status()
        self.status.update(status, layout=False)
        self.glance.update(self._glance_text(solution), layout=False)
        sendable = self.can_send()
        if sendable != self._sendable:  # the key bar shows ^g only where it sends something
            self._sendable = sendable
            self.app.refresh_bindings()

    def _rows(self, solution: Solution) -> list[ResultRow]:
        from gearhead.core.tolerance import spread_text

        rows = []
        spread = self.spread if solution is self.solution else None
        for name, value in solution.outputs.items():
            out = self.calculator.output(name)
            text = "(hidden)" if self.hide_timings and name in VOLATILE else pretty_quantity(value.text)
            extra = ""
            if spread is not None:
                s = spread.outputs.get(name)
                extra = spread_text(self.calculator, solution, s) if s else ""
                if s and s.main_input and s.low != s.high and len(spread.tolerances) > 1:
                    extra += f"  {s.main_input}"
            rows.append(ResultRow(name, out.label, text, out.equation, extra))
        return rows

    def _show_warnings(self, warnings: list[str]) -> None:
        text = "\n".join("! " + w for w in warnings)
        if self.spread is not None and self.spread.notes:  # e.g. 'backdrivable changes within the tolerances'
            text = "\n".join([text] * bool(text) + [f"± {n}" for n in self.spread.notes])
        if text == self._warnings_text:
            return
        # the box grows with its text: a layout repaints every widget of the screen, so only a
        # text that takes another number of lines asks for one (drivetrain's warnings quote
        # numbers that change with each key)
        content = Text(text, style="yellow")
        width = self.warnings.content_region.width
        lines = len(content.wrap(self.app.console, width)) if width and text else (0 if not text else -1)
        same_height = lines >= 0 and lines == self._warnings_lines and self.warnings_box.display == bool(text)
        self._warnings_text, self._warnings_lines = text, lines
        self.warnings.update(content, layout=not same_height)
        if self.warnings_box.display != bool(text):
            self.warnings_box.display = bool(text)

    _warnings_lines = -1  # lines the warnings took when last shown (-1: unknown, lay out)

    # ---- tolerances (core/tolerance.py): a worst-case column while any entry carries '±' --------
    def _spread_status(self) -> Text:
        result = self.spread
        worst = (
            "optimiser"
            if any("optimiser" in s.worst_case_method for s in result.outputs.values())
            else "corners"
        )
        line = Text(f"✓ solved; tolerances: worst case by {worst}, σ first-order", style="green")
        if result.samples:
            line.append(f" (* Monte Carlo, {result.samples} samples, seed {result.seed})")
        wall = "(hidden)" if self.hide_timings else f"{result.cost.wall_time * 1e3:.0f} ms"
        line.append(
            f"; {result.cost.solves} solves, {result.cost.rhs_evaluations} RHS evaluations, {wall}",
            style="dim",
        )
        return line

    def _append_spread(self, name: str, line: Text) -> None:
        """With tolerances, the help line of a result also gives its spread in full: worst case and
        how it was found, σ and how, and the input that contributes most."""
        from gearhead.core import units
        from gearhead.core.tolerance import short_method, shown_unit

        s = self.spread.outputs.get(name) if self.spread is not None and self.solution is not None else None
        if s is None or name not in self.solution.outputs:
            return
        o = self.calculator.output(name)
        unit = shown_unit(self.calculator, self.solution, name)

        def q(v):
            return f"{units.format_number(units.to_unit(v, unit, o.quantity))} {unit}".rstrip()

        worst, stat = short_method(s)
        line.append(f"\nWorst case {q(s.low)} .. {q(s.high)} ({s.worst_case_method}); σ {q(s.std)} ({stat})")
        if s.main_input and s.low != s.high:
            line.append(f"; mostly {s.main_input} ({s.shares[s.main_input] * 100:.0f} % of the variance)")

    # ---- the error estimate of a scene, after its results (core/sim/scene.py deferred_estimate) ----
    ESTIMATE = "error_estimate"

    def _estimate_pending(self, solution: Solution) -> Solution:
        """The solution with "…" in the estimate's row (in table order), until it arrives."""
        from dataclasses import replace

        from gearhead.core.model import Value

        outputs = {}
        for o in self.calculator.outputs:
            if o.name in solution.outputs:
                outputs[o.name] = solution.outputs[o.name]
            elif o.name == self.ESTIMATE:
                outputs[o.name] = Value(None, "", "…")
        self._estimating.add(get_ident())
        return replace(solution, outputs=outputs)

    def _run_estimate(self, estimate, solution: Solution):
        """The estimate's Value, None if a key came meanwhile (the next solve replaces it), or a
        dash when it does not fit in one solve's budget (the results above it stand)."""
        from gearhead.core.model import Value, format_value
        from gearhead.core.sim.integrate import Cancelled, budget

        shown = self._show_generation
        try:
            with budget(cancel=lambda: self._dirty or self._solving or self._show_generation != shown):
                value = estimate()
        except Cancelled:
            return None
        except InputError:
            return Value(None, "", "— (over one solve's budget)")
        o = self.calculator.output(self.ESTIMATE)
        return format_value(
            value, o.quantity, self.display_units.get(o.name) or self._preferred_units.get(o.name, o.unit)
        )

    @guarded
    def _estimate_done(self, solution: Solution, value) -> None:
        if value is None or solution is not self.solution or not self._mounted:
            return  # a newer solve is (or will be) on screen
        solution.outputs[self.ESTIMATE] = value
        if self.solution_key == self.key and self.error is None:
            self.results.show(self._rows(solution), FRESH)

    # ---- tables of alternatives (core.model.Table) -------------------------------------
    def _compose_tables(self) -> ComposeResult:
        """A scrollable table per declared Table, its header holding each column's unit."""
        for t in self.calculator.tables:
            yield Static(
                Text(t.title, style="bold"), classes="result-table-title", id=f"table-title-{t.name}"
            )
            grid = DataTable(
                classes="result-table", id=f"table-{t.name}", cursor_type="row", zebra_stripes=True
            )
            grid.tooltip = (
                "ctrl+g sends the row under the cursor to the calculator it feeds" if t.exports else None
            )
            for c in t.columns:
                if not c.hidden:
                    head = f"{c.label} [{pretty_unit(c.unit)}]" if c.unit else c.label
                    grid.add_column(Text(head), key=c.name, width=max(c.width, len(head)))
            yield grid

    def _show_tables(self, solution: Solution) -> None:
        entries = solution.entries()
        for t in self.calculator.tables:
            grid = self.query_one(f"#table-{t.name}", DataTable)
            shown = t.shown_in(entries)  # a table of another mode (the sprint's optimise table) gives way
            if grid.display != shown:
                grid.display = shown
                self.query_one(f"#table-title-{t.name}", Static).display = shown
            cursor = grid.cursor_row
            grid.clear()
            for n, row in enumerate(solution.tables.get(t.name, [])):
                grid.add_row(
                    *(
                        Text(pretty_quantity(row[c.name].text)) if c.name in row else Text("")
                        for c in t.columns
                        if not c.hidden
                    ),
                    key=str(n),
                )
            if 0 < cursor < grid.row_count:
                grid.move_cursor(row=cursor, animate=False)

    def can_send(self) -> bool:
        """Whether ctrl+g has something to send now: a result another calculator takes (in this
        mode: drivetrain's forward mode has no ratio), or a table row that fills one."""
        calc, solution = self.calculator, self.solution
        if solution is None:
            return bool(calc.exports) or any(t.exports for t in calc.tables)
        if any(out in solution.outputs for mapping in calc.exports.values() for out in mapping.values()):
            return True
        return any(t.exports and solution.tables.get(t.name) for t in calc.tables)

    def selected_row(self):
        """(Table, row of Values) under the cursor of the table last focused, or None."""
        if self.solution is None:
            return None
        for t in self.calculator.tables:
            grid = self.query_one(f"#table-{t.name}", DataTable)
            rows = self.solution.tables.get(t.name, [])
            if t.exports and 0 <= grid.cursor_row < len(rows):
                return t, rows[grid.cursor_row]
        return None

    GLANCE_RESULTS = 3  # the first results of a calculator are its headline ones

    def _glance_text(self, solution: Solution) -> Text:
        line = Text("✓ ", style="green")
        for i, (name, value) in enumerate(list(solution.outputs.items())[: self.GLANCE_RESULTS]):
            if i:
                line.append("  ·  ", style="dim")
            line.append(self.calculator.output(name).label + " ", style="dim")
            line.append(pretty_quantity(value.text), style="bold")
        return line

    # ---- what tests and the app read ------------------------------------------------------
    def shown_values(self) -> dict[str, str]:
        """The result texts the list draws now (name -> text; "…" while pending)."""
        state = self.results.state
        return {r.name: ("…" if state == PENDING else r.value) for r in self.results.rows}


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


def _duration(seconds: float) -> str:
    return f"{seconds * 1e3:.1f} ms" if seconds < 1 else f"{seconds:.2f} s"
