"""Sweep view (ctrl+w, palette "Sweep…"): one input over a range, chosen outputs plotted, a table
under the plot, export to CSV. The sweep runs in a thread (core.sweep.run); a progress bar shows
when it takes longer than PROGRESS_AFTER_S, and Esc cancels a running sweep (Esc again closes)."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from rich.markup import escape
from rich.text import Text
from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.widgets import Checkbox, DataTable, Input, Label, ProgressBar, Select, SelectionList, Static
from textual.worker import get_current_worker

from gearhead.core import atomic_file, units
from gearhead.core.errors import InputError
from gearhead.core.model import Calculator, Field
from gearhead.core.sweep import cell_text

from .dialog import Dialog
from .field_input import FieldInput
from .plot_panel import COLOURS, axis_label
from .tick_box import TickBox, TickList
from .unit_text import pretty_unit

PROGRESS_AFTER_S = 0.2
DEFAULT_POINTS = 21


def sweepable(calc: Calculator, entries: dict[str, Any]) -> list[Field]:
    """Numeric inputs the current choices use."""
    from gearhead.core.model import choice_values

    mode = entries.get("mode")
    choices = choice_values(calc, entries)
    return [f for f in calc.fields if f.kind.numeric and f.active(mode, choices)]


def default_range(f: Field, entry: Any) -> tuple[str, str]:
    """Half to one and a half times the current value (whole numbers: ±3 within bounds), as text."""
    from gearhead.core import tolerance

    try:  # the row may hold a wrong entry ('5 mm ± 1 ± 1'): the range starts from the default
        nominal, _ = tolerance.split(entry)
        x = f.parse(nominal)
    except InputError:
        x = f.parse(f.default)
    if f.kind.whole:
        lo = max(int(f.min) if f.min is not None else x - 3, x - 3)
        hi = min(int(f.max) if f.max is not None else x + 3, x + 3)
        return str(lo), str(hi if hi > lo else lo + 1)
    shown = units.to_unit(x, f.unit, f.quantity) if f.kind.with_unit else x
    if shown == 0:
        lo, hi = 0.0, 1.0
    else:
        lo, hi = sorted((shown * 0.5, shown * 1.5))
    return units.format_number(lo), units.format_number(hi)


class SweepScreen(Dialog[None]):
    DEFAULT_CSS = """
    SweepScreen { align: center middle; }
    .sweep-dialog { width: 124; max-width: 100%; height: 44; max-height: 100%; padding: 0 1;
                    border: thick $primary; background: $surface; }
    .sweep-title { text-style: bold; padding-bottom: 1; }
    .sweep-form { height: 1; margin-bottom: 1; }
    .sweep-form Select { width: 1fr; max-width: 34; }
    .sweep-form Input { width: 12; margin-left: 1; }
    #sweep-unit { width: auto; margin-left: 1; }
    #sweep-log { width: auto; margin-left: 2; }
    /* plot over table, 3:2, down to an 80x24 terminal */
    .sweep-body { height: 3fr; min-height: 6; }
    #sweep-outputs { width: 1fr; max-width: 32; height: 100%; }
    #sweep-plot { width: 3fr; height: 100%; }
    #sweep-plot PlotWidget { height: 1fr; }
    #sweep-progress { height: 1; }
    #sweep-table { height: 2fr; min-height: 3; }
    #sweep-status { height: auto; }
    """
    BINDINGS = [
        Binding("escape", "cancel_or_close", "Cancel / close"),
        Binding("ctrl+e", "export", "Export CSV"),
    ]

    def __init__(
        self,
        calculator: Calculator,
        entries: dict[str, Any],
        field_name: str | None = None,
        blink: bool = True,
        hide_timings: bool = False,
        shown: tuple[str, ...] = (),
    ) -> None:
        super().__init__()
        self.shown = shown  # the outputs the card shows now: the first is plotted at first
        self.calculator = calculator
        self.entries = dict(entries)
        self.fields = sweepable(calculator, self.entries)
        names = [f.name for f in self.fields]
        self.field_name = field_name if field_name in names else (names[0] if names else None)
        self.blink = blink
        self.hide_timings = hide_timings
        self.result = None  # the last finished core.sweep.Sweep
        self._sweeping = False  # a sweep runs (not `_running`: that is Textual's MessagePump state)
        self._started = 0.0

    # ---- layout ----------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        calc = self.calculator
        with Vertical(classes="sweep-dialog"):  # not .dialog: the app's 72-column dialog is too narrow
            yield Label(Text(f"{calc.title}: sweep"), classes="sweep-title")
            if self.field_name is None:
                yield Static(Text("This calculator has no numeric input to sweep with these choices."))
                return
            f = calc.field(self.field_name)
            start, stop = default_range(f, self.entries.get(f.name, f.default))
            with Horizontal(classes="sweep-form"):
                yield Select(
                    [(Text(x.label), x.name) for x in self.fields],
                    value=f.name,
                    allow_blank=False,
                    compact=True,
                    id="sweep-field",
                )
                for wid, value, tip in (
                    ("sweep-start", start, "from (any unit)"),
                    ("sweep-stop", stop, "to"),
                    ("sweep-points", str(DEFAULT_POINTS), "points"),
                ):
                    entry = FieldInput(value=value, id=wid, compact=True, tooltip=tip, select_on_focus=False)
                    entry.cursor_blink = self.blink
                    yield entry
                yield Label(Text(pretty_unit(f.unit)), id="sweep-unit")
                yield TickBox("log", id="sweep-log", compact=True)
            with Horizontal(classes="sweep-body"):
                outputs = [
                    o
                    for o in calc.outputs
                    if o.name not in ("error_estimate", "rhs_evaluations", "wall_time")
                ]
                # the first output this mode produces (the elevator's first, its optimise-only
                # 'Fastest ratio', gave an empty plot and table in a move)
                first = next(
                    (o.name for o in outputs if o.name in self.shown), outputs[0].name if outputs else None
                )
                yield TickList[str](
                    *[(Text(o.label), o.name, o.name == first) for o in outputs], id="sweep-outputs"
                )
                yield Vertical(id="sweep-plot")
            yield ProgressBar(total=100, show_eta=False, id="sweep-progress")
            yield DataTable(cursor_type="row", zebra_stripes=True, id="sweep-table")
            yield Static("", id="sweep-status")
            yield Static(Text("Enter: run   Esc: cancel / close   ctrl+e: export CSV", style="dim"))

    def on_mount(self) -> None:
        self.query_one("#sweep-progress").display = False
        if self.field_name is not None:
            self.run_sweep()

    # ---- running ---------------------------------------------------------------------------
    def _spec(self) -> str:
        start = self.query_one("#sweep-start", Input).value.strip()
        stop = self.query_one("#sweep-stop", Input).value.strip()
        points = self.query_one("#sweep-points", Input).value.strip()
        log = ":log" if self.query_one("#sweep-log", Checkbox).value else ""
        return f"{self.field_name}={start}..{stop}:{points}{log}"

    @on(Input.Submitted)
    def run_sweep(self) -> None:
        from gearhead.core import sweep

        if self._sweeping:
            self.workers.cancel_group(self, "sweep")
        status = self.query_one("#sweep-status", Static)
        try:
            spec = sweep.parse_vary(self.calculator, self._spec())
        except InputError as exc:
            status.update(Text(f"{exc.field}: {exc.message}", style="bold red"))
            return
        self._sweeping = True
        self._started = time.perf_counter()
        status.update(Text("… sweeping", style="dim"))
        bar = self.query_one("#sweep-progress", ProgressBar)
        bar.update(total=spec.points, progress=0)
        self.set_timer(PROGRESS_AFTER_S, self._maybe_show_progress)
        self._sweep_in_thread(spec)

    def _maybe_show_progress(self) -> None:
        if self._sweeping:
            self.query_one("#sweep-progress").display = True

    @work(thread=True, exclusive=True, group="sweep")
    def _sweep_in_thread(self, spec) -> None:
        from gearhead.core import sweep, tolerance

        worker = get_current_worker()
        last = [0.0]

        def progress(done: int, total: int) -> None:
            now = time.perf_counter()
            if now - last[0] > 0.05 or done == total:  # a redraw per point would cost more than a solve
                last[0] = now
                self.app.call_from_thread(self._progress, done, total)

        try:
            raw, tolerances = tolerance.split_inputs(self.calculator, self.entries)
            result = sweep.run(
                self.calculator, raw, [spec], progress=progress, cancelled=lambda: worker.is_cancelled
            )
            if tolerances:
                result.notes.append(f"tolerances on {', '.join(tolerances)} not swept: nominal values used")
            error = None
        except InputError as exc:
            result, error = None, exc
        except Exception as exc:  # a bug: said in the status line and logged; the dialog stays
            from ..bug_log import record
            from ..guard import internal_error

            result, error = (
                None,
                InputError("sweep", internal_error(exc, record(exc, "gearhead (the app) sweep"))),
            )
        if worker.is_cancelled:
            return
        try:
            self.app.call_from_thread(self._done, result, error)
        except RuntimeError:  # the app closed while the sweep ran
            pass

    def _progress(self, done: int, total: int) -> None:
        self.query_one("#sweep-progress", ProgressBar).update(total=total, progress=done)

    async def _done(self, result, error: InputError | None) -> None:
        self._sweeping = False
        self.query_one("#sweep-progress").display = False
        status = self.query_one("#sweep-status", Static)
        if error is not None:
            status.update(Text(f"{error.field}: {error.message}", style="bold red"))
            return
        self.result = result
        await self._draw()

    def action_cancel_or_close(self) -> None:
        if self._sweeping:
            self.workers.cancel_group(self, "sweep")
            self._sweeping = False
            self.query_one("#sweep-progress").display = False
            self.query_one("#sweep-status", Static).update(Text("cancelled", style="yellow"))
            return
        self.dismiss(None)

    # ---- showing ---------------------------------------------------------------------------
    @on(Select.Changed, "#sweep-field")
    def _field_changed(self, event: Select.Changed) -> None:
        event.stop()
        if event.value == self.field_name:
            return
        self.field_name = str(event.value)
        f = self.calculator.field(self.field_name)
        start, stop = default_range(f, self.entries.get(f.name, f.default))
        self.query_one("#sweep-start", Input).value = start
        self.query_one("#sweep-stop", Input).value = stop
        self.query_one("#sweep-unit", Label).update(Text(pretty_unit(f.unit)))
        self.run_sweep()

    @on(Checkbox.Changed, "#sweep-log")
    def _log_changed(self) -> None:
        self.run_sweep()

    @on(SelectionList.SelectedChanged, "#sweep-outputs")
    async def _outputs_changed(self) -> None:
        if self.result is not None:
            await self._draw()

    @property
    def chosen(self) -> list[str]:
        picked = set(self.query_one("#sweep-outputs", SelectionList).selected)
        return [n for n in self.result.outputs if n in picked] if self.result else []

    async def _draw(self) -> None:
        from textual_plot import HiResMode, PlotWidget

        from .plot_panel import quiet_plot_widget

        result = self.result
        calc = self.calculator
        vary = result.varies[0]
        f = calc.field(vary.name)
        names = self.chosen
        # the plot
        holder = self.query_one("#sweep-plot")
        plots = holder.query(PlotWidget)
        plot = plots.first() if plots else quiet_plot_widget()(allow_pan_and_zoom=False)
        if not plots:
            await holder.mount(plot)
        plot.clear()
        index = {c[0]: i for i, c in enumerate(result.columns())}
        for colour, name in zip(COLOURS, names):
            xs, ys = [], []
            o = calc.output(name)
            for p in result.points:
                y = p.outputs.get(name)
                if p.error is None and isinstance(y, (int, float)) and not isinstance(y, bool):
                    x = p.inputs[vary.name]
                    xs.append(units.to_unit(x, vary.unit, f.quantity) if f.kind.with_unit else x)
                    ys.append(units.to_unit(float(y), o.unit, o.quantity))
            if xs:
                plot.plot(
                    xs,
                    ys,
                    line_style=colour,
                    hires_mode=HiResMode.BRAILLE,
                    label=escape(axis_label(o.label, pretty_unit(o.unit))) if len(names) > 1 else None,
                )
        if len(names) > 1:
            plot.show_legend()
        plot.set_xlabel(escape(axis_label(f.label, pretty_unit(vary.unit))))
        if len(names) == 1:
            o = calc.output(names[0])
            plot.set_ylabel(escape(axis_label(o.label, pretty_unit(o.unit))))
        else:
            plot.set_ylabel("")
        # the table
        table = self.query_one("#sweep-table", DataTable)
        table.clear(columns=True)
        table.add_column(Text(axis_label(f.label, pretty_unit(vary.unit))), key=vary.name)
        for name in names:
            o = calc.output(name)
            table.add_column(Text(axis_label(o.label, pretty_unit(o.unit))), key=name)
        table.add_column("status", key="status")
        for i, p in enumerate(result.points):
            row = result.display_row(p)
            cells = [Text(cell_text(row[0]))]
            for name in names:
                cells.append(Text("" if p.error else cell_text(row[index[name]])))
            if p.error:
                cells.append(Text(f"infeasible: {p.error}", style="red"))
            elif p.warnings:
                cells.append(Text(p.warnings[0], style="yellow"))
            else:
                cells.append(Text("ok", style="green"))
            table.add_row(*cells, key=str(i))
        bad = sum(1 for p in result.points if p.error)
        cost = result.cost
        wall = "(hidden)" if self.hide_timings else f"{cost.wall_time * 1e3:.1f} ms"
        line = Text(
            f"{len(result.points)} points: {cost.solves} solves, {cost.rhs_evaluations} RHS evaluations, "
            f"{wall}",
            style="dim",
        )
        if bad:
            line.append(f"   {bad} infeasible (reason in the row)", style="yellow")
        if result.cancelled:
            line.append("   cancelled", style="yellow")
        for note in result.notes:
            line.append(f"   {note}", style="yellow")
        self.query_one("#sweep-status", Static).update(line)

    def csv_text(self) -> str:
        return self.result.csv_text() if self.result else ""

    def action_export(self) -> None:
        """The sweep's table (every output, display units, a status column) as CSV: to the clipboard
        and to a new file in the working directory (never over an existing one)."""
        if self.result is None:
            self.notify("Nothing swept yet.", severity="warning")
            return
        text = self.result.csv_text()
        self.app.copy_to_clipboard(text)
        base = f"{self.calculator.id}_sweep_{self.result.varies[0].name}"
        for n in range(1, 1000):
            path = Path(f"{base}.csv" if n == 1 else f"{base}_{n}.csv")
            try:
                atomic_file.write_text(path, text)  # whole or not at all
                break
            except atomic_file.FileExists:
                continue
            except atomic_file.WriteError as exc:
                self.notify(
                    f"Copied to the clipboard; cannot write a file ({exc.reason})",
                    severity="warning",
                    markup=False,
                )
                return
        self.notify(f"Sweep copied to the clipboard and saved to {path}", title="Exported", markup=False)
