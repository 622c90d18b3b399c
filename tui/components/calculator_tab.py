"""One generic tab that renders any calculator from its description (core.model.Calculator).

Inputs on the left (label, entry, unit, inline error), results on the right. Every keystroke is
solved at once in a thread worker, one solve at a time per tab (latest wins), so the interface
never waits for pint or scipy.
"""

from __future__ import annotations

from threading import Event, get_ident
from types import SimpleNamespace
from typing import Any

from rich.cells import cell_len
from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.containers import Horizontal, Vertical, VerticalScroll
from textual.content import Content
from textual.reactive import var
from textual.widget import Widget
from textual.widgets import Checkbox, DataTable, Input, Select, Static
from textual.widgets.data_table import ColumnKey

from gearhead.core.errors import InputError
from gearhead.core.model import Calculator, Field, Solution
from gearhead.core.sim.scene import VOLATILE

from .field_input import FieldCheckbox, FieldInput, FieldSelect
from .plot_panel import PlotPanel
from .result_table import ResultTable
from .unit_text import pretty_quantity, pretty_unit


class Form(VerticalScroll, can_focus=False):
    """The field list: scrolls, but is not a Tab stop of its own (Tab goes field to field;
    the form scrolls to the focused field)."""


BUSY_AFTER_S = 0.1  # a solve running longer than this shows '… solving'


LABEL_CELLS = 32  # a field's label column (the entry's margin in gearhead.tcss); labels wrap by word


class FieldRow(Widget):
    """One field: its label, its entry widget and its unit; an error line appears under it when
    needed. The row draws the label and the unit itself, around its one child, the entry: a
    Label each for them were two of the five widgets a field cost, and every widget is paid for
    in a card's build, its layouts and the compositing of every frame it is on screen (the beam
    card had 126 widgets, and a first show took 3 frames of 100-250 ms)."""

    COMPONENT_CLASSES = {"field-row--unit"}

    def __init__(self, field: Field, value: Any, blink: bool) -> None:
        # the field's kind describes the widget (core.fields.Widget); a widget without a unit
        # label (choices, flags and yes/no) takes the unit's column too, so "pressure switch" or
        # "Rectangular tube" is not cut at 120 columns
        self.widget_spec = field.kind.widget(field)
        shape = self.widget_spec.shape
        super().__init__(
            classes="field-row"
            + (" flags-row" if shape == "checkboxes" else "")
            + (" unitless" if self.widget_spec.unit is None else ""),
            id=f"row-{field.name}",
        )
        self.field = field
        self.initial = value
        self.blink = blink
        self.label_lines = Content(field.label).wrap(LABEL_CELLS)  # as a Label of that width
        self.unit_text = pretty_unit(self.widget_spec.unit) if self.widget_spec.unit is not None else None

    def compose(self) -> ComposeResult:
        f, spec = self.field, self.widget_spec
        tip = Text(f.help) if f.help else None  # a str tooltip is markup: "[psi]" would vanish
        if spec.shape == "select":
            options = [(Text(label), value) for value, label in spec.options]
            yield FieldSelect(
                options,
                value=self.initial,
                allow_blank=False,
                id=f"in-{f.name}",
                classes="field-input",
                tooltip=tip,
                compact=True,
            )
        elif spec.shape == "checkboxes":
            chosen = set(x for x in str(self.initial).replace(",", " ").split() if x)
            with Vertical(classes="field-input flags", id=f"in-{f.name}"):
                for value, label in spec.options:
                    yield FieldCheckbox(
                        Content(label),
                        value=value in chosen,
                        id=f"flag-{f.name}--{value}",
                        compact=True,
                        tooltip=tip,
                    )
        elif spec.shape == "checkbox":
            yield FieldCheckbox(
                value=bool(self.initial), id=f"in-{f.name}", classes="field-input", tooltip=tip, compact=True
            )
        else:
            entry = FieldInput(
                value=str(self.initial),
                id=f"in-{f.name}",
                classes="field-input",
                tooltip=tip,
                select_on_focus=False,
                compact=True,
            )
            entry.cursor_blink = self.blink
            yield entry

    def get_content_height(self, container, viewport, width: int) -> int:
        # an entry is one line (compact: an input or a yes/no), flags one line each: known here,
        # where asking the layout arranged the row's children once more for every row in every
        # layout (a third of a card's first layout, cProfile). A choice list's text wraps.
        spec = self.widget_spec
        if spec.shape == "select":
            entry_lines = super().get_content_height(container, viewport, width)
        else:
            entry_lines = len(spec.options) if spec.shape == "checkboxes" else 1
        return max(entry_lines, len(self.label_lines))

    def render(self) -> Content:
        """The label's lines, and the unit one cell after the entry (which covers the middle)."""
        lines = [line.pad_right(LABEL_CELLS - line.cell_length) for line in self.label_lines]
        lines += [Content()] * (self.size.height - len(lines))
        if self.unit_text is not None and self.children and lines:
            entry = self.children[0].region
            entry_right = entry.right - self.content_region.x if entry else LABEL_CELLS
            unit_style = self.get_visual_style("field-row--unit", partial=True)
            lines[0] = Content.assemble(
                lines[0],
                " " * max(0, entry_right - LABEL_CELLS + 1),
                Content(self.unit_text).stylize(unit_style),
            )
        return Content("\n").join(lines)


class CalculatorTab(Widget):
    """The whole card for one calculator."""

    # a var, not a reactive: a reactive repaints the whole card on every key
    entries: var[dict[str, Any]] = var(dict, init=False, always_update=True)

    def __init__(
        self,
        calculator: Calculator,
        blink: bool = True,
        hide_timings: bool = False,
        in_steps: bool = False,
        **kwargs,
    ) -> None:
        super().__init__(**kwargs)
        self.calculator = calculator
        self.in_steps = in_steps  # built out of sight: field rows mounted a few at a time
        self.blink = blink
        self.hide_timings = hide_timings  # snapshot tests: no wall-clock figures on screen
        self.solution: Solution | None = None
        self.error: InputError | None = None
        self.display_units: dict[str, str] = {}  # output -> unit the user chose (Enter on a result)
        self.unit_system = "calculator"  # the units preference (core.unit_systems), set by the app
        self._preferred_units: dict[str, str] = {}  # output -> unit the preference gave last solve
        self.preset_meta = ("", "")  # name and description of the preset last loaded here
        self.stale = False  # the results shown are from earlier entries (one is bad now)
        self._solving = False  # a solve thread is running
        self._dirty = False  # entries changed since the running solve started
        self._solve_seconds = 0.0  # wall time of the last whole solve
        self._estimating: set[int] = set()  # threads computing a shown solution's error estimate
        self.set_reactive(CalculatorTab.entries, {f.name: self.initial_entry(f) for f in calculator.fields})

    @staticmethod
    def initial_entry(f: Field) -> Any:
        """A field's default as its widget holds it."""
        return f.kind.initial_entry(f)

    # ---- layout -------------------------------------------------------------------------
    def compose(self) -> ComposeResult:
        calc = self.calculator
        # narrow terminals stack the results under a long form that scrolls: the key results
        # and the status stay in sight on this line, above the scrolling card, while typing
        # (shown below 120 columns only)
        yield Static("", classes="glance")
        with Horizontal(classes="card"):
            with Vertical(classes="inputs-pane"):
                yield Static(Text(calc.summary), classes="summary")
                with Form(classes="form"):
                    if not self.in_steps:
                        yield from self._field_rows()
                yield Static(
                    Text(
                        "F1–F5 then a digit opens any calculator; Tab moves between fields; type any unit (3.5 in, 60 psi); Enter on a result changes its unit; "
                        "ctrl+s saves, ctrl+o loads a preset.",
                        style="dim",
                    ),
                    classes="help-line",
                )
            with Vertical(classes="results-pane"):
                table = ResultTable(classes="results", cursor_type="row", zebra_stripes=True)
                table.tooltip = "Enter or click on a result shows it in another unit"
                # fixed widths from the description: no re-measuring on idle, so the
                # layout is the same every time (snapshots) and never jumps while typing. The
                # value column fits the widest value any result can show (values are never
                # cut); the labels take the room left (_size_columns) and wrap when longer.
                table.add_column("Result", key="label", width=min(self._label_longest, 33))
                table.add_column("Value", key="value", width=value_width(calc))
                if self._equation_width:  # the seed's equation number of each result
                    table.add_column(Text("Eq.", style="dim"), key="equation", width=self._equation_width)
                yield table
                if calc.plots:
                    panel = PlotPanel(calc.plots)
                    panel.unit_system = self.unit_system
                    yield panel
                yield from self._compose_tables()
                # long or many warnings scroll in a box of their own instead of pushing the
                # status line out of the pane
                with VerticalScroll(classes="warnings-box"):
                    yield Static("", classes="warnings")
                yield Static("", classes="status")

    _parts = None  # the widgets a solve updates, found once (a CSS query per key cost ~1 ms)

    @property
    def _label_longest(self) -> int:
        return max([len(o.label) for o in self.calculator.outputs] + [6])

    @property
    def _equation_width(self) -> int:
        """Width of the equation column: 0 (no column) when no result has an equation number."""
        widest = max((len(o.equation) for o in self.calculator.outputs), default=0)
        return max(widest, 3) if widest else 0

    def on_resize(self) -> None:
        self.call_after_refresh(self._size_columns)

    # A card built out of sight (the warm-up) has no size yet; its results table will be as wide
    # as the one on screen (same panes, same stylesheet). Its columns are sized for that width
    # before its first solve, so its first visit does not re-fill and re-measure the table (an
    # extra layout and a 45-65 ms frame after the first).
    table_width_hint = 0

    @property
    def results_width(self) -> int:
        """The results table's width on screen (0 before the card has been shown)."""
        return self._parts.table.size.width if self._parts is not None else 0

    def _size_columns(self) -> None:
        """Columns for the table's width (column_widths); labels longer than theirs wrap."""
        table = self._parts.table if self._parts is not None else None
        table_width = (table.size.width or self.table_width_hint) if table is not None else 0
        if not table_width:
            return
        room = table_width - 2 - 2 * table.cell_padding * len(table.columns)  # 2: the scrollbar
        widths = {"label": 0, "equation": 0}
        others = sum(c.width for key, c in table.columns.items() if key.value not in widths)
        widths["label"], widths["equation"] = column_widths(
            room, others, self._label_longest, self._equation_width
        )
        columns = [c for key, c in table.columns.items() if key.value in widths]
        if any(c.width != widths[c.key.value] for c in columns):
            for c in columns:
                c.width = widths[c.key.value]
            self._rows_shown = None  # rows are re-added: the wrapped ones get their height
            if self.solution is not None and self.error is None:
                self._fill_results(table, self.solution)
                if self.spread is not None:  # the rebuilt rows' spread cells
                    self._show_spread(self.solution, table, self._parts.status)
            else:
                table._require_update_dimensions = True
                table.refresh()

    # A card built while the user reads another (the app's warm-up) mounts its field rows a few
    # at a time: a mount's steps all run before the app takes its next message, so a key waited
    # for the whole card (90-230 ms); now for a few rows.
    ROWS_PER_STEP = 4
    STEP_PAUSE_S = 0.01  # between steps: a key's messages pass from the app to the widget

    def _field_rows(self) -> list[FieldRow]:
        return [FieldRow(f, self.entries[f.name], self.blink) for f in self.calculator.fields]

    async def _mount_rows_in_steps(self) -> bool:
        """False if the app closed meanwhile (the card's widgets are gone)."""
        from asyncio import sleep

        form = self.query_one(Form)
        rows = self._field_rows()
        start = 0
        while start < len(rows):
            if not (self.is_attached and self.app.is_running):
                return False
            # the user came to this card meanwhile (hurry()): the rest at once, no pauses
            step = len(rows) if self._hurried else self.ROWS_PER_STEP
            await form.mount_all(rows[start : start + step])
            start += step
            if not self._hurried:
                await sleep(self.STEP_PAUSE_S)
        return self.is_attached and self.app.is_running

    _hurried = False

    def hurry(self) -> None:
        """A card being built in steps is wanted on screen: mount its remaining rows at once."""
        self._hurried = True

    async def on_mount(self) -> None:
        if self.in_steps and not await self._mount_rows_in_steps():
            return
        self._parts = SimpleNamespace(
            table=self.query_one(".results", DataTable),
            status=self.query_one(".status", Static),
            glance=self.query_one(".glance", Static),
            warnings=self.query_one(".warnings", Static),
            warnings_box=self.query_one(".warnings-box"),
            help_line=self.query_one(".help-line", Static),
            plot=self.query_one(PlotPanel) if self.calculator.plots else None,
            dimmed=list(self.query(".results, .plot-panel, .result-table")),
        )
        self._field_names = {f.name for f in self.calculator.fields}
        for entry in self.query(FieldInput):
            entry.edited = self._typed
        self._bad_field: str | None = None  # the field whose error line is shown
        self._warnings_text: str | None = None
        self._shown_by = None
        self._apply_mode()
        self._size_columns()  # with the width hint, when built out of sight
        self.solve()

    # ---- entry handling ----------------------------------------------------------------
    def _name_of(self, widget: Widget) -> str | None:
        wid = widget.id or ""
        if wid.startswith("flag-"):
            return wid[5:].split("--")[0]
        return wid[3:] if wid.startswith("in-") else None

    @on(Input.Changed)
    @on(Select.Changed)
    @on(Checkbox.Changed)
    def _entry_changed(self, event) -> None:
        event.stop()
        wid = event.control.id or ""
        if wid.startswith("flag-"):
            name = wid[5:].split("--")[0]
            f = self.calculator.field(name)
            value = ", ".join(c for c in f.choices if self.query_one(f"#flag-{name}--{c}", Checkbox).value)
        else:
            name = self._name_of(event.control)
            value = event.value
        self._take_entry(name, value)

    def _typed(self, entry: FieldInput) -> None:
        """A key changed an entry (FieldInput.edited): taken at once, before its Changed arrives."""
        self._take_entry(self._name_of(entry), entry.value)

    def _take_entry(self, name: str | None, value: Any) -> None:
        if name is None:
            return
        if self.entries.get(name) == value:
            return
        self.entries = {**self.entries, name: value}

    def watch_entries(self) -> None:
        # a typed number cannot show or hide a field: only a mode or choice change re-applies
        # (the loop over every field row cost ~1 ms a key on the long forms)
        from gearhead.core.model import choice_values

        shown_by = (
            self.entries.get("mode"),
            tuple(sorted(choice_values(self.calculator, self.entries).items())),
        )
        if shown_by != getattr(self, "_shown_by", None):
            self._shown_by = shown_by
            self._apply_mode()
        self.solve()

    def on_descendant_focus(self, event) -> None:
        if isinstance(event.widget, DataTable) and event.widget.has_class("results"):
            table = event.widget
            if table.row_count:
                self._explain_output(str(table.coordinate_to_cell_key((table.cursor_row, 0)).row_key.value))
            return
        name = self._name_of(event.widget) if event.widget else None
        if name:
            f = self.calculator.field(name)
            line = Text(f.label + ": ", style="bold")
            line.append(f.help or "")
            hint = f.kind.entry_hint(f)
            if hint:
                line.append(f"  ({hint})", style="dim")
            self.query_one(".help-line", Static).update(line)

    @on(DataTable.RowHighlighted, ".results")
    def _explain_result(self, event: DataTable.RowHighlighted) -> None:
        """The line under the form explains the result under the cursor, as it does a field."""
        event.stop()
        if event.data_table.has_focus and event.row_key.value is not None:
            self._explain_output(str(event.row_key.value))

    def _explain_output(self, name: str) -> None:
        out = self.calculator.output(name)
        line = Text(out.label + (f" {out.equation}" if out.equation else "") + ": ", style="bold")
        line.append(out.help or "see the help of the fields it comes from")
        line.append("  (Enter: next unit)", style="dim")
        self._append_spread(name, line)
        self.query_one(".help-line", Static).update(line)

    def _apply_mode(self) -> None:
        from gearhead.core.model import choice_values

        mode = self.entries.get("mode")
        choices = choice_values(self.calculator, self.entries)
        for f in self.calculator.fields:
            try:
                row = self.query_one(f"#row-{f.name}", FieldRow)
            except Exception:  # not composed yet
                return
            row.display = f.active(mode, choices)

    def set_entries(self, values: dict[str, Any]) -> None:
        """Put values into the widgets (preset load, send-to), then solve once."""
        merged = dict(self.entries)
        for name, value in values.items():
            f = self.calculator.field(name)
            value = f.kind.entry(f, value)
            row = self.query_one(f"#row-{name}", FieldRow)
            if row.widget_spec.shape == "checkboxes":
                chosen = set(x for x in str(value).replace(",", " ").split() if x)
                for c, _ in row.widget_spec.options:
                    self.query_one(f"#flag-{name}--{c}", Checkbox).value = c in chosen
            else:
                self.query_one(f"#in-{name}").value = value
            merged[name] = value
        self.entries = merged

    def current_inputs(self) -> dict[str, Any]:
        """What the user entered, as a preset stores it (whole numbers as TOML integers)."""
        return {f.name: f.kind.stored(f, self.entries[f.name]) for f in self.calculator.fields}

    @on(DataTable.RowSelected, ".results")
    def _cycle_unit(self, event: DataTable.RowSelected) -> None:
        """Show the chosen result in the next common unit of its kind (mm → cm → m → in → ft …)."""
        event.stop()
        from gearhead.core import units

        name = str(event.row_key.value)
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

    # ---- solving -----------------------------------------------------------------------
    # No fixed typing pause: a closed-form solve takes ~0.1 ms, so every keystroke is solved at
    # once, in a thread (the first use of pint or scipy must not freeze typing). At most one solve
    # runs per tab; keys typed meanwhile mark the tab dirty, and when the running solve ends its
    # result is dropped and the latest entries are solved instead (latest wins, nothing queues,
    # no stale result is shown).
    def solve(self) -> None:
        self._dirty = True
        if not self._solving:
            self._start_solve()

    @property
    def busy(self) -> bool:
        """A solve is running or waiting to run, or a shown solve's error estimate is being
        computed, or its chart is waiting to be drawn (tests wait for this to clear)."""
        plot = self._parts.plot if self._parts is not None else None
        return self._solving or self._dirty or bool(self._estimating) or (plot is not None and plot.pending)

    def set_unit_system(self, system: str) -> None:
        """Show results in a units preference; units chosen with Enter give way to it."""
        self.unit_system = system
        self.display_units = {}
        if self.calculator.plots:
            self.query_one(PlotPanel).unit_system = system
        self.solve()

    # Every solve runs in a thread (a slow one must not freeze typing, and a new key cancels a
    # running simulation). One that took less than WAIT_S last time is also waited for, that long: a
    # result in time is shown in the frame that echoes the key, where a result arriving from a
    # thread waits for the next frame (17 ms later). One that turns out slow (a new beam section,
    # a long ratio search, pint's registry built for a first unit) shows when done, as any other.
    # (closed form 0.1-0.5 ms, a scene's main run 0.4-4 ms; the last solve predicts the next)
    WAIT_S = 0.008  # half a frame: waited for when the last solve took less

    def _start_solve(self) -> None:
        from threading import Lock, Thread

        self._dirty = False
        self._solving = True
        args = (dict(self.entries), dict(self.display_units), self.unit_system)
        handoff = SimpleNamespace(waiting=True, result=None, lock=Lock(), done=Event())
        Thread(target=self._solve_in_thread, args=(args, handoff), name="gearhead-solve", daemon=True).start()
        if self._solve_seconds < self.WAIT_S:
            handoff.done.wait(self.WAIT_S)
        with handoff.lock:
            handoff.waiting = False
            result = handoff.result
        if result is not None:
            self._solve_done(*result)
        else:
            self.set_timer(BUSY_AFTER_S, self._mark_busy)

    def _solve_in_thread(self, args: tuple, handoff: SimpleNamespace) -> None:
        solution, error, pending = self._solve_entries(*args)
        try:
            with handoff.lock:
                in_time = handoff.waiting
                if in_time:  # _start_solve is waiting: it shows the result itself
                    handoff.result = (solution, error)
                    handoff.done.set()
            if not in_time:
                self.app.call_from_thread(self._solve_done, solution, error)
            if pending:
                # once the frame with the results is drawn (this thread would hold the GIL from
                # it), and only if they are the ones on screen: now their error estimate
                drawn = Event()
                self.app.call_from_thread(self.call_after_refresh, drawn.set)
                drawn.wait(1.0)
                if self.solution is solution:
                    self.app.call_from_thread(
                        self._estimate_done, solution, self._run_estimate(pending[0], solution)
                    )
        except RuntimeError:  # the app closed while this solve ran
            pass
        finally:
            self._estimating.discard(get_ident())

    def _solve_entries(self, entries: dict[str, Any], display_units: dict[str, str], system: str):
        """(solution, error, pending error estimate) of these entries; never raises."""
        from time import perf_counter

        from gearhead.core import unit_systems
        from gearhead.core.sim.integrate import Cancelled, budget
        from gearhead.core.sim.scene import deferred_estimate
        from gearhead.core.tolerance import (
            solve_entries,  # entries may carry '± tolerance' (core/tolerance.py)
        )

        started = perf_counter()
        pending: list = []
        try:
            # "as entered" reads units with pint: in a worker until its registry is built
            preferred = unit_systems.display_units(self.calculator, system, entries)
            self._preferred_units = preferred
            # a simulation polls this between steps: keys typed meanwhile drop it (latest wins at once)
            with budget(cancel=lambda: self._dirty), deferred_estimate() as pending:
                solution, self.spread = solve_entries(
                    self.calculator.id, entries, {**preferred, **display_units}
                )
            if pending and self.spread is None:
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
        self._solve_seconds = perf_counter() - started  # the whole solve (an optimiser's search too)
        return solution, error, pending

    # ---- the error estimate of a scene, after its results (core/sim/scene.py deferred_estimate) ----
    # self._estimating (__init__): the threads computing a shown solution's estimate
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

    def _estimate_done(self, solution: Solution, value) -> None:
        if value is None or solution is not self.solution or self._parts is None:
            return  # a newer solve is (or will be) on screen
        solution.outputs[self.ESTIMATE] = value
        self._fill_results(self._parts.table, solution)

    def _solve_done(self, solution: Solution | None, error: InputError | None) -> None:
        self._solving = False
        if self._parts is None or not self._parts.status.is_attached:
            return  # the app closed, or the card was removed or is being torn down, meanwhile
        if self._dirty:  # entries changed while solving: this result is already stale
            self._start_solve()
            return
        self._show(solution, error)

    def _mark_stale(self, stale: bool) -> None:
        """Dim the last valid results while an entry is bad. The class goes on the results and
        the plot only: on the whole tab it restyled every field row (40 ms on the beam tab)."""
        if stale == self.stale and self._parts is not None:
            return
        self.stale = stale
        for widget in self._parts.dimmed:
            widget.set_class(stale, "stale")

    def _mark_busy(self) -> None:
        if self._solving:
            self._parts.status.update(Text("… solving", style="yellow"), layout=False)

    # What a key costs to show is mostly what it makes Textual redo: a Static.update lays the
    # screen out again unless told the size stays (layout=False: status and glance are one line),
    # and clearing the table rebuilds it. So _show touches only what changed: the error line of
    # the field that was or is bad, the cells whose text changed, the warnings when they differ.
    def _show_field_error(self, error: InputError | None) -> None:
        bad = error.field if error is not None and error.field in self._field_names else None
        for name in {self._bad_field, bad} - {None}:
            row = self.query_one(f"#row-{name}", FieldRow)
            message = Text("⚠ " + error.message, style="bold red") if name == bad else ""
            lines = self.query(f"#err-{name}")
            if lines:
                line = lines.first(Static)
                line.update(message)
                line.display = name == bad
            elif name == bad:  # a field's first error: its line is made now (a card has 17-35)
                line = Static(message, classes="field-error", id=f"err-{name}")
                line.display = True
                row.parent.mount(line, after=row)
            row.set_class(name == bad, "invalid")
        self._bad_field = bad

    def _show(self, solution: Solution | None, error: InputError | None) -> None:
        parts = self._parts
        self._show_field_error(error)
        status = parts.status
        if error is not None:
            self.error = error
            self._mark_stale(True)
            try:  # the label the user sees on the form, not the internal field name
                where = self.calculator.field(error.field).label
            except KeyError:
                where = error.field
            status.update(
                Text(f"✗ {where}: {error.message} (results show the last valid inputs)", style="red"),
                layout=False,
            )
            parts.glance.update(Text(f"✗ {where}: {error.message}", style="red"), layout=False)
            return
        self.error = None
        self._mark_stale(False)
        self.solution = solution
        self._show_generation += 1
        table = parts.table
        self._fill_results(table, solution)
        if parts.plot is not None:
            parts.plot.show_soon(solution)
        self._show_tables(solution)
        self._show_warnings(solution.warnings)
        status.update(
            Text(
                "✓ solved" if self.hide_timings else f"✓ solved in {_duration(self._solve_seconds)}",
                style="green",
            ),
            layout=False,
        )
        parts.glance.update(self._glance_text(solution), layout=False)
        self._show_spread(solution, table, status)

    def _show_warnings(self, warnings: list[str]) -> None:
        """The warnings box grows with its text: laying the screen out again repaints every field
        (25 ms on the drivetrain card, whose warnings quote numbers that change with each key),
        so only a text that takes a different number of lines asks for a layout."""
        parts = self._parts
        text = "\n".join("! " + w for w in warnings)
        if text == self._warnings_text:
            return
        content = Text(text, style="yellow")
        width = parts.warnings.content_region.width
        # a hidden box has no width yet: its height is known once it has been laid out
        lines = (len(content.wrap(self.app.console, width)) if width else -1) if text else 0
        same_height = (
            lines >= 0 and lines == self._warnings_lines and parts.warnings_box.display == bool(text)
        )
        self._warnings_text, self._warnings_lines = text, lines
        parts.warnings.update(content, layout=not same_height)
        if parts.warnings_box.display != bool(text):
            parts.warnings_box.display = bool(text)

    _warnings_lines = -1  # lines the warnings took when last shown (-1: unknown, lay out)

    def _fill_results(self, table: DataTable, solution: Solution) -> None:
        """The results table: the same outputs as shown now get their changed cells updated in
        place (cursor and scroll stay); other outputs (a mode change) rebuild it."""
        rows = []
        for name, value in solution.outputs.items():
            text = "(hidden)" if self.hide_timings and name in VOLATILE else pretty_quantity(value.text)
            rows.append((name, text))
        names = [name for name, _ in rows]
        column = table.columns[ColumnKey("value")]
        widest = max((cell_len(text) for _, text in rows), default=0)
        if widest > column.width:  # a unit wider than foreseen (typed "as entered"): widen, never cut
            column.width = widest
            self._rows_shown = None  # rebuilt at the new width
            self.call_after_refresh(self._size_columns)
        if names == self._rows_shown:
            for (name, text), old in zip(rows, self._texts_shown):
                if text != old:
                    table.update_cell(name, "value", Text(text))
        else:
            cursor = table.cursor_row
            table.clear()
            label_width = table.columns[ColumnKey("label")].width
            equations = "equation" in {key.value for key in table.columns}
            for name, text in rows:
                out = self.calculator.output(name)
                cells = [Text(out.label), Text(text)] + (
                    [Text(out.equation, style="dim", no_wrap=True, overflow="ellipsis")] if equations else []
                )
                table.add_row(*cells, key=name, height=None if cell_len(out.label) > label_width else 1)
            if 0 < cursor < table.row_count:
                table.move_cursor(row=cursor, animate=False)
            self._rows_shown = names
        self._texts_shown = tuple(text for _, text in rows)

    _show_generation = 0  # solutions shown so far (a pending estimate belongs to the last)
    _rows_shown: list[str] | None = None  # output names in the table, in order
    _texts_shown: tuple[str, ...] = ()  # their value texts as shown

    # ---- tolerances (core/tolerance.py): a Spread column while any entry carries '±' ------------
    spread = None  # the last solve's core.tolerance.Spread, or None

    def _show_spread(self, solution: Solution, table: DataTable, status: Static) -> None:
        from gearhead.core.tolerance import spread_text

        result = self.spread
        has_column = "spread" in table.columns
        if result is None:
            if has_column:
                table.remove_column("spread")
                self.call_after_refresh(self._size_columns)  # the labels get their room back
            return
        if not has_column:
            table.add_column("Worst case  σ (*: Monte Carlo)", key="spread", width=30)
            self.call_after_refresh(self._size_columns)
        for name in solution.outputs:
            s = result.outputs.get(name)
            text = spread_text(self.calculator, solution, s) if s else ""
            if s and s.main_input and s.low != s.high and len(result.tolerances) > 1:
                text += f"  {s.main_input}"
            table.update_cell(name, "spread", Text(text, style="dim" if text == "unaffected" else ""))
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
        status.update(line)
        if result.notes:  # e.g. 'backdrivable changes within the tolerances', samples left out
            lines = [f"! {w}" for w in solution.warnings] + [f"± {n}" for n in result.notes]
            self._parts.warnings.update(Text("\n".join(lines), style="yellow"))
            self._parts.warnings_box.display = True
            self._warnings_text = None  # not the solution's own: the next _show rewrites it
            self._warnings_lines = -1

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

    # ---- tables of alternatives (core.model.Table) -------------------------------------
    def _compose_tables(self) -> ComposeResult:
        """A scrollable table per declared Table, its header holding each column's unit."""
        for t in self.calculator.tables:
            yield Static(Text(t.title, style="bold"), classes="result-table-title")
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
        for t in self.calculator.tables:
            grid = self.query_one(f"#table-{t.name}", DataTable)
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


# A result label narrower than this wraps onto three or four lines ("Thin-wal / l J"): the
# equation numbers, a reference, are cut first (with "…") to keep the labels readable.
LABEL_MIN = 16


def column_widths(room: int, others: int, longest: int, equations: int) -> tuple[int, int]:
    """(label, equation) column widths of a results table sharing `room` cells with its other
    columns (value, spread: never cut), `others` cells wide. The label takes what the equation
    numbers (`equations` wide, 0: no column) leave, up to its `longest` label; when that is
    under LABEL_MIN, the numbers give way, down to 3 cells ("(4…")."""
    left = room - others
    label = min(longest, left - equations)
    if label < min(longest, LABEL_MIN) and equations:
        label = min(longest, LABEL_MIN, left - 3)
    label = max(8, label)  # 8: labels wrap by word
    return label, (max(3, min(equations, left - label)) if equations else 0)


def value_width(calc: Calculator) -> int:
    """The widest value text a result of `calc` can show: a number as units.format_number writes
    it at its widest ("-1.2346e-05") and the widest unit the output may be shown in (its own, the
    ring Enter walks, and the units preferences)."""
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
