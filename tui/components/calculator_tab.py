"""One generic card that renders any calculator from its description (core.model.Calculator).

The form is one Sheet (sheet.py: a row per field, spreadsheet keys), the results one ResultsList
(results.py); beside them the calculator's charts and tables, its warnings and a status line.

The path of a key: the sheet hands the card a changed entry; `solve` starts a Textual thread
worker on the entries on screen (one per card: a newer solve cancels the older, which never starts
or stops at its next integration step); the worker solves through core.solving.solve, the CLI's
own solve, builds every text the card will draw (card_text.drawn: rows, table cells, status) and
posts `Solved` carrying the key of what it solved; the card puts those texts on screen only while
that key is still the card's. A scene's error estimate is a second step: once its results are
shown, another worker runs core.model.finish_estimate and posts `Estimated`. No other thread
touches the card; nothing waits.
"""

from __future__ import annotations

from time import perf_counter
from typing import Any

from rich.text import Text
from textual import events, work
from textual.app import ComposeResult
from textual.containers import Vertical
from textual.message import Message
from textual.widget import Widget
from textual.widgets import Static
from textual.worker import Worker, WorkerState, get_current_worker

from gearhead.core.errors import InputError
from gearhead.core.model import Calculator, Field, Solution

from ..guard import guard, guarded, report
from . import card_text
from .card_parts import Tables, Warnings
from .results import FRESH, PENDING, STALE, ResultsList
from .sheet import Sheet

BUSY_AFTER_S = 0.1  # a solve running longer than this shows '… solving'


class CalculatorTab(Widget):
    """The whole card for one calculator. Its handlers and the callbacks the sheet, the results
    list and timers call are @guarded: a bug in one is a notification and a logged traceback
    (guard.py), and the card keeps what was typed."""

    sheet_class = Sheet  # the form's class (a workbook card's refuses edits on its linked rows)

    class Solved(Message):
        """A solve's outcome for the entries of `key`: core.solving.Solved and what to draw of it
        (card_text.Drawn), or the InputError."""

        def __init__(
            self, key: tuple, solved, drawn: card_text.Drawn | None, error: InputError | None
        ) -> None:
            super().__init__()
            self.key, self.solved, self.drawn, self.error = key, solved, drawn, error

    class Estimated(Message):
        """The error estimate of `before` (a shown solution): `after` has it in place of "…"."""

        def __init__(self, before: Solution, after: Solution, rows: list) -> None:
            super().__init__()
            self.before, self.after, self.rows = before, after, rows

    def __init__(
        self, calculator: Calculator, blink: bool = True, hide_timings: bool = False, **kwargs
    ) -> None:
        super().__init__(**kwargs)
        self.calculator = calculator
        self.blink = blink
        self.hide_timings = hide_timings  # snapshot tests: no wall-clock figures on screen
        self.entries: dict[str, Any] = {f.name: self.initial_entry(f) for f in calculator.fields}
        self.display_units: dict[str, str] = {}  # output -> unit the user chose (Enter on a result)
        self.unit_system = "calculator"  # the units preference (core.unit_systems), set by the app
        self.preset_meta = ("", "")  # name and description of the preset last loaded here
        # what is shown: the last valid solve, and what is wrong with the entries on screen
        self.solution: Solution | None = None
        self.solution_key: tuple | None = None  # what it was solved from (entries_key)
        self.spread = None  # its core.tolerance.Spread, or None
        self.shown_units: dict[str, str] = {}  # output -> unit its results are shown in
        self.error: InputError | None = None
        self.error_key: tuple | None = None
        self.asked: tuple | None = None  # the key of the latest solve asked for
        self._estimate = None  # the worker computing the shown solution's error estimate
        self._sendable: bool | None = None  # ctrl+g had something to send at the last solve
        self._shown_by = None  # (mode, choices) the visible rows were chosen for (card_text.shown_by)
        self._help_text: Text | None = None
        self._mounted = False

    @staticmethod
    def initial_entry(f: Field) -> Any:
        """A field's default as the sheet holds it."""
        return f.kind.initial_entry(f)

    # ---- layout -------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        calc = self.calculator
        # narrow terminals stack the results under the form: the key results and the status stay
        # in sight on this line, docked above the panes, while typing (below 120 columns only:
        # composed on a narrow screen, else mounted once the screen is narrow, on_resize)
        self.glance = Static("", classes="glance")
        if self._narrow():
            yield self.glance
        # the panes are the card's own children, side by side (stacked below 120 columns): no
        # container around them, which every frame drew again under them (one widget the size of
        # the card)
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
            yield Static(Text(card_text.HELP, style="dim"), classes="help-line")
        with Vertical(classes="results-pane"):
            self.results = ResultsList(
                on_select=self._cycle_unit,
                on_cursor=self._explain_output,
                is_current=lambda: self.asked == self.solution_key,
                classes="results",
            )
            self.results.value_width = card_text.value_width(calc)
            widest = max((len(o.equation) for o in calc.outputs), default=0)
            self.results.equation_width = max(widest, 3) if widest else 0
            yield self.results
            self.plot = None
            if calc.plots:
                from .plot_panel import PlotPanel

                self.plot = PlotPanel(calc.plots)
                self.plot.unit_system = self.unit_system
                yield self.plot
            # a table under the results and the chart; warnings under it: mounted later (the mode
            # that shows the table, the first warnings), each goes above what follows it
            self.tables = Tables(
                calc, self.entries, lambda *table: self._mount_above(table, self.warnings_box)
            )
            yield from self.tables.compose()
            self.status = Static("", classes="status")
            # long or many warnings scroll in a box of their own (above the status line, mounted
            # with the first warnings) instead of pushing the status line out of the pane
            self.warnings_part = Warnings(lambda box: self._mount_above((box,), self.status))
            self.warnings, self.warnings_box = self.warnings_part.text_widget, self.warnings_part.box
            yield self.status

    @guarded
    def on_mount(self) -> None:
        self.help_line = self.query_one(".help-line", Static)
        self._mounted = True
        self._apply_mode()
        self.solve()

    def _mount_above(self, widgets: tuple[Widget, ...], below: Widget) -> None:
        """Mount widgets into the results pane above `below`, or above the status line when
        `below` is not mounted."""
        before = below if below.parent is not None else self.status
        self.status.parent.mount(*widgets, before=before)

    def _narrow(self) -> bool:
        """The screen is below the app's width breakpoint (GearheadApp.HORIZONTAL_BREAKPOINTS)."""
        return self.screen.has_class("-narrow")

    @guarded
    def on_resize(self, event: events.Resize) -> None:
        if self.glance.parent is None and self._narrow():  # the terminal narrowed: the glance line
            self.mount(self.glance, before=0)

    # ---- entries in -----------------------------------------------------------------------
    @guarded
    def _take_entry(self, name: str, value: Any) -> None:
        """The sheet changed an entry (a key, a toggle, a choice): solved at once."""
        if self.entries.get(name) == value:
            return
        self.entries = {**self.entries, name: value}
        self._entries_changed(name)

    def _entries_changed(self, name: str | None = None) -> None:
        """`name`: the one entry changed (its row alone is repainted); None: any of them."""
        if card_text.shown_by(self.calculator, self.entries) != self._shown_by:
            self._apply_mode()
            self.sheet.refresh()
        elif name is not None:
            self.sheet.refresh_field(name)
        else:
            self.sheet.refresh()
        self.solve()

    def _apply_mode(self) -> None:
        self._shown_by = card_text.shown_by(self.calculator, self.entries)
        self.sheet.set_visible(card_text.visible_fields(self.calculator, self.entries))

    def set_entries(self, values: dict[str, Any]) -> None:
        """Put values into the card (preset load, send-to), then solve once. A quantity given in
        another unit than the field's is converted to it, every digit kept (the sheet shows 6)."""
        merged = dict(self.entries)
        for name, value in values.items():
            f = self.calculator.field(name)
            merged[name] = card_text.in_field_unit(f, f.kind.entry(f, value))
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

    @guarded
    def _cycle_unit(self, name: str) -> None:
        """Show the chosen result in the next common unit of its kind (mm → cm → m → in → ft …)."""
        shown = self.display_units.get(name) or self.shown_units.get(name)
        unit = card_text.next_unit(self.calculator, self.solution, name, shown)
        if unit is not None:
            self.display_units = {**self.display_units, name: unit}
            self.solve()

    def set_unit_system(self, system: str) -> None:
        """Show results in a units preference; units chosen with Enter give way to it."""
        self.unit_system = system
        self.display_units = {}
        if self.plot is not None:
            self.plot.unit_system = system
        self.solve()

    # ---- solve out ------------------------------------------------------------------------
    @property
    def key(self) -> tuple:
        """What the card on screen asks to be solved."""
        return card_text.entries_key(self.entries, self.display_units, self.unit_system)

    @property
    def busy(self) -> bool:
        """The entries on screen are not solved and drawn yet: their solve, their error estimate or
        their chart is still to come (tests wait for this to clear)."""
        plot = self.plot if self._mounted else None
        waiting = self.asked is not None and self.asked not in (self.solution_key, self.error_key)
        return waiting or self._estimate is not None or (plot is not None and plot.pending)

    def solve(self) -> None:
        """Solve the entries on screen in a worker. The worker group is exclusive: starting one
        cancels the card's previous solve (a solve not begun never runs; a running one stops at its
        next integration step or tolerance sample, or ends and its result is dropped)."""
        self.asked = key = self.key
        # a card's first solve takes its error estimate with it: the estimate's run goes first and
        # pays the scene's one-off imports, so the time shown is what the accuracy costs
        estimate = "later" if self.solution is not None else "now"
        self._solve_worker(key, dict(self.entries), dict(self.display_units), self.unit_system, estimate)
        if self._estimate is not None:  # the shown solution's estimate is no longer wanted
            self._estimate.cancel()
            self._estimate = None
        if self.solution is not None and self.solution_key != key:
            self.results.refresh()  # drawn dimmed until these entries' result lands (is_current)
        self.set_timer(BUSY_AFTER_S, self._mark_busy)

    @work(thread=True, exclusive=True, group="solve", exit_on_error=False)
    def _solve_worker(self, key: tuple, entries: dict, chosen: dict, system: str, estimate: str) -> None:
        from gearhead.core import solving
        from gearhead.core.sim.integrate import Cancelled

        worker = get_current_worker()
        started = perf_counter()
        try:
            solved = solving.solve(
                self.calculator,
                entries,
                chosen,
                system,
                estimate=estimate,
                spread_seconds=solving.CARD_SPREAD_SECONDS,
                cancelled=lambda: worker.is_cancelled,
            )
            drawn = card_text.drawn(self.calculator, solved, perf_counter() - started, self.hide_timings)
            error = None
        except Cancelled:  # a newer solve of the card runs: it posts
            return
        except InputError as exc:
            solved, drawn, error = None, None, exc
            if exc.__cause__ is not None:  # the last-resort guard fired: keep the traceback
                from ..bug_log import record

                record(exc, f"{self.calculator.id} {entries!r}")
        except Exception as exc:  # a bug must not take the app (and what was typed) down with it
            from ..bug_log import record

            path = record(exc, f"{self.calculator.id} {entries!r}")
            solved = drawn = None
            error = InputError(
                "(result)",
                f"internal error: {type(exc).__name__}: {exc}" + (f" (traceback in {path})" if path else ""),
            )
        self.post_message(self.Solved(key, solved, drawn, error))

    @work(thread=True, exclusive=True, group="estimate", exit_on_error=False)
    def _estimate_worker(self, solution: Solution, spread) -> None:
        from gearhead.core.model import finish_estimate
        from gearhead.core.sim.integrate import Cancelled, budget

        worker = get_current_worker()
        try:
            with budget(cancel=lambda: worker.is_cancelled):
                after = finish_estimate(solution)
        except Cancelled:
            return
        # a bug raises out of here: the worker's ERROR state comes back as a message (below)
        rows = card_text.result_rows(self.calculator, after, spread, self.hide_timings)
        self.post_message(self.Estimated(solution, after, rows))

    @guarded
    def on_worker_state_changed(self, event: Worker.StateChanged) -> None:
        """A bug in the error estimate: a notice and a logged traceback; the results above stand."""
        if event.state == WorkerState.ERROR and event.worker.group == "estimate":
            if event.worker is self._estimate:
                self._estimate = None
            report(self, event.worker.error, "CalculatorTab._estimate_worker")

    @guarded
    def _mark_busy(self) -> None:
        if self._mounted and self.asked not in (self.solution_key, self.error_key):
            self.status.update(Text("… solving", style="yellow"), layout=False)
            if self.solution is not None:
                self.results.show(self.results.rows, PENDING)

    # ---- draw -----------------------------------------------------------------------------
    @guarded
    def on_calculator_tab_solved(self, message: Solved) -> None:
        message.stop()
        if message.key != self.key or not self._mounted:
            return  # solved from entries no longer on screen: the latest solve is running
        if message.error is not None:
            self._show_error(message.error, message.key)
        else:
            self._show_solved(message.solved, message.key, message.drawn)

    def _show_error(self, error: InputError, key: tuple) -> None:
        calc = self.calculator
        self.error, self.error_key = error, key
        self.sheet.set_errors(card_text.error_marks(calc, error))
        if self.solution is not None:
            self.results.show(self.results.rows, STALE)
        self.status.update(card_text.error_status(calc, error), layout=False)
        self.glance.update(card_text.error_glance(calc, error), layout=False)
        if self.plot is not None and not self.plot.has_class("stale"):
            self.plot.add_class("stale")

    def _show_solved(self, solved, key: tuple, drawn: card_text.Drawn) -> None:
        self.error = self.error_key = None
        self.sheet.set_errors({})
        solution = solved.solution
        self.solution, self.solution_key, self.spread = solution, key, solved.spread
        self.shown_units = solved.units
        self.results.show(drawn.rows, FRESH)
        if self.plot is not None:
            if self.plot.has_class("stale"):
                self.plot.remove_class("stale")
            self.plot.show_soon(solution)
        self.tables.show(solution, drawn.tables)
        self.warnings_part.show(drawn.warnings)
        self.status.update(drawn.status, layout=False)
        self.glance.update(drawn.glance, layout=False)
        sendable = self.can_send()
        if sendable != self._sendable:  # the key bar shows ^g only where it sends something
            self._sendable = sendable
            self.app.refresh_bindings()
        if solution.pending_estimate is not None:  # the second step, "…" in its row till then
            self._estimate = self._estimate_worker(solution, self.spread)

    @guarded
    def on_calculator_tab_estimated(self, message: Estimated) -> None:
        message.stop()
        if message.before is not self.solution or not self._mounted:
            return  # a newer solve is (or will be) on screen
        self._estimate = None
        self.solution = message.after
        if self.solution_key == self.key and self.error is None:
            self.results.show(message.rows, FRESH)

    def _show_warnings(self, warnings: list[str]) -> None:
        self.warnings_part.show(card_text.warnings_text(warnings, self.spread))

    # ---- the help line ----------------------------------------------------------------------
    @guarded
    def _explain_field(self, f: Field) -> None:
        if self._mounted:
            self._help(card_text.field_help(f, self.sheet.errors.get(f.name)))

    @guarded
    def _explain_output(self, name: str) -> None:
        self._help(card_text.output_help(self.calculator, name, self.solution, self.spread))

    def _help(self, text: Text) -> None:
        if text != self._help_text:  # the line's height is its text's: an update asks for a layout
            self._help_text = text
            self.help_line.update(text)

    # ---- what the app and tests read --------------------------------------------------------
    def can_send(self) -> bool:
        """Whether ctrl+g has something to send now (card_text.can_send)."""
        return card_text.can_send(self.calculator, self.solution)

    def selected_row(self):
        """(Table, row of Values) under the cursor of the table last focused, or None."""
        return self.tables.selected_row(self.solution)

    def shown_values(self) -> dict[str, str]:
        """The result texts the list draws now (name -> text; "…" while pending)."""
        state = self.results.state
        return {r.name: ("…" if state == PENDING else r.value) for r in self.results.rows}
