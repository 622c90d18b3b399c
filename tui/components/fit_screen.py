"""The app's "Fit from log" (issue 44 item 7) on the elevator, arm, flywheel and sprint cards: a SysId log
(.wpilog or .csv) chosen by path or textual-fspicker's dialog, fitted in a worker thread by
core.fit.fit_log against the card as it is on screen (its entries, not its file), and shown as
`gearhead fit` shows it: the signals found, both forms' gains with their standard deviations, adj.
R², RMSE, the favoured form, the entries they give, and the replay of one test (measured velocity
against the favoured fit's and the design's). Apply puts the fitted entries (elevator: load mass and
friction; arm: mass, entered inertia and friction; flywheel: the wheel's entered moment of inertia;
sprint: robot mass and rolling resistance; core.fit.entries.fitted_raw) into the card's fields, after the screen has
shown what each becomes; the dialog returns them and the app sets them as the sheet would take a
typed entry. A log that cannot be fitted is one line naming the file and what is wrong.

The screen knows nothing of where the card lives: the caller passes the card's calculator, its
entries as on screen, a label for the title (a workbook's card: its name) and the fields Apply
must not write (a workbook's links, each with its reference: the screen says what the fit gives
for each, as `gearhead fit --apply` notes it), and takes what the dialog returns."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

from rich.markup import escape
from rich.text import Text
from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical, VerticalScroll
from textual.message import Message
from textual.widgets import Button, DataTable, Input, Label, Static
from textual.worker import get_current_worker

from gearhead.core.errors import InputError, printable
from gearhead.core.registry import Calculator

from .. import served_paths
from ..guard import guarded
from .dialog import Dialog
from .field_input import FieldInput
from .plot_panel import COLOURS, quiet_plot_widget

UNITS = {
    "elevator": ("m", "m/s"),
    "arm": ("rad", "rad/s"),
    "flywheel": ("rad", "rad/s"),
    "sprint": ("m", "m/s"),
}


def g(x: float) -> str:
    """4 significant digits, as `gearhead fit` prints; '-' for a value that is not finite."""
    return f"{x:.4g}" if isinstance(x, (int, float)) and math.isfinite(x) else "-"


def fitted_changes(report, held=()) -> tuple[dict[str, str], list[str]]:
    """The entries Apply writes (every digit the fit gives: the card then holds what the fit
    found), those that differ from the card's, and the notes (friction below the motors' loss).
    `held`: entries not written (a workbook's links), the others computed with the card's."""
    from gearhead.core.fit.apply import WRITTEN  # the entries Apply writes (as into the card's file)
    from gearhead.core.fit.entries import fitted_raw

    card = report.card
    raw, notes = fitted_raw(card, report.fits[report.favoured].gains, held)
    return {k: raw[k] for k in WRITTEN[card.kind] if k in raw and raw[k] != card.raw.get(k)}, notes


class FitScreen(Dialog[dict[str, Any] | None]):
    """Returns the entries to write into the card (Apply), or None (Esc, Close)."""

    DEFAULT_CSS = """
    FitScreen { align: center middle; }
    .fit-dialog { width: 124; max-width: 100%; height: 44; max-height: 100%; padding: 0 1;
                  border: thick $primary; background: $surface; }
    .fit-title { text-style: bold; }
    .fit-form { height: auto; }
    .fit-form Input { width: 1fr; }
    .fit-form Button { min-width: 10; margin-left: 1; }
    #fit-status { height: auto; }
    #fit-body { height: 1fr; }
    #fit-table, #fit-entries { height: auto; margin-top: 1; }
    #fit-plot { height: 16; }
    #fit-plot PlotWidget { height: 1fr; }
    #fit-diff { height: auto; margin-top: 1; }
    .fit-buttons { height: auto; }
    .fit-buttons Button { margin-right: 1; }
    """
    BINDINGS = [Binding("escape", "close", "Close")]
    AUTO_FOCUS = "#fit-path"

    class Fitted(Message):
        """The worker's result: the report, or the error to show, and the seconds it took."""

        def __init__(self, path: str, report, error: str | None, seconds: float) -> None:
            super().__init__()
            self.path = path
            self.report = report
            self.error = error
            self.seconds = seconds

    def __init__(
        self,
        calculator: Calculator,
        entries: dict[str, Any],
        blink: bool = True,
        hide_timings: bool = False,
        path: str = "",
        label: str = "",
        linked: dict[str, str] | None = None,
    ) -> None:
        super().__init__()
        self.calculator = calculator
        self.kind = calculator.id
        self.entries = dict(entries)
        self.label = label or calculator.title  # the title's name of the card
        self.linked = dict(linked or {})  # field -> its reference ('= lift_load'): not written by Apply
        self.blink = blink
        self.hide_timings = hide_timings
        self.path = path
        self.report = None  # the last fit shown (core.fit.Report)
        self.changes: dict[str, str] = {}  # what Apply writes
        self.seconds = math.nan  # from the file chosen to the table drawn
        self._started = 0.0
        self._fitting = False

    def compose(self) -> ComposeResult:
        with Vertical(classes="fit-dialog"):
            yield Label(Text(printable(f"{self.label}: fit from a SysId log")), classes="fit-title")
            with Horizontal(classes="fit-form"):
                entry = FieldInput(
                    value=self.path,
                    placeholder="A .wpilog or .csv SysId log, then Enter",
                    id="fit-path",
                    select_on_focus=False,
                )
                entry.cursor_blink = self.blink
                yield entry
                # a served session may not look around the serving machine's folders
                yield Button("Browse…", id="fit-browse", disabled=served_paths.confined())
            yield Static("", id="fit-status")
            with VerticalScroll(id="fit-body"):
                yield Static("", id="fit-signals")
                yield DataTable(cursor_type="none", zebra_stripes=True, id="fit-table")
                yield Static("", id="fit-favoured")
                yield DataTable(cursor_type="none", zebra_stripes=True, id="fit-entries")
                yield Static("", id="fit-replay")
                yield Vertical(id="fit-plot")
                yield Static("", id="fit-diff")
            with Horizontal(classes="fit-buttons"):
                yield Button("Apply", id="fit-apply", variant="primary", disabled=True)
                yield Button("Close", id="fit-close")
            yield Static(Text("Enter: fit   Tab: Browse, the fit, Apply, Close   Esc: close", style="dim"))

    def on_mount(self) -> None:
        for wid in ("#fit-table", "#fit-entries", "#fit-plot"):
            self.query_one(wid).display = False
        for wid in ("#fit-table", "#fit-entries"):  # read, not browsed: the body scrolls them, and Tab
            self.query_one(wid).can_focus = False  # goes from the log to Browse, the body and Apply
        if self.path:
            self.start(self.path)

    # ---- choosing and fitting ----------------------------------------------------------------
    @on(Input.Submitted, "#fit-path")
    def _submitted(self, event: Input.Submitted) -> None:
        event.stop()
        self.start(event.value)

    @on(Button.Pressed, "#fit-browse")
    @guarded
    def _browse(self) -> None:
        from textual_fspicker import FileOpen, Filters

        typed = self.query_one("#fit-path", Input).value.strip()
        start = Path(typed).expanduser().parent if typed else Path.cwd()
        if not start.is_dir():
            start = Path.cwd()
        dialog = FileOpen(
            start,
            title="Open a SysId log",
            filters=Filters(
                ("*.wpilog, *.csv", lambda p: p.suffix.lower() in (".wpilog", ".csv")),
                ("Any file", lambda _: True),
            ),
            # its completer globs what is typed: `**a` ended the app (textual-fspicker 1.0.1, issue 41)
            suggest_completions=False,
        )

        def chosen(path: Path | None) -> None:
            if path is not None:
                self.query_one("#fit-path", Input).value = str(path)
                self.start(str(path))

        self.app.push_screen(dialog, chosen)

    def _status(self, text: str, style: str = "") -> None:
        self.query_one("#fit-status", Static).update(Text(printable(text), style=style))

    def start(self, text: str) -> None:
        """Fit the log `text` names, in a worker (a 10-minute log takes about a second)."""
        text = text.strip()
        if not text:
            self._status("log: type the path of a .wpilog or .csv SysId log, or Browse…", "bold red")
            return
        try:
            if "\0" in text:  # the OS refuses such a name (Path raises ValueError deep inside)
                raise InputError("log", "a file path cannot contain a NUL character", repr(text)[:80])
            path = served_paths.check(text)
        except InputError as exc:
            self._status(str(exc), "bold red")
            return
        self._fitting = True
        self._started = time.perf_counter()
        self.query_one("#fit-apply", Button).disabled = True
        self._status(f"… fitting {text}", "dim")
        self._fit(str(path))

    @work(thread=True, exclusive=True, group="fit")
    def _fit(self, path: str) -> None:
        import threading

        from gearhead.core import fit
        from gearhead.core.fit.entries import card_from_entries
        from gearhead.core.tolerance import split_inputs

        got: dict[str, Any] = {}

        def run() -> None:
            try:
                raw, _ = split_inputs(self.calculator, self.entries)  # a tolerance's nominal value
                card = card_from_entries(self.kind, raw, f"the {self.label} card on screen")
                got["report"] = fit.fit_log(path, self.kind, card)
            except Exception as exc:
                got["exc"] = exc

        # The fit runs in a daemon thread this worker waits on, so that Esc (or ctrl+q) during a
        # long read leaves at once: the worker's own thread is joined when the app exits, and a
        # 170 MB log held ctrl+q for 23-47 s after Esc. The daemon thread's result is dropped.
        worker = get_current_worker()
        thread = threading.Thread(target=run, name="gearhead-fit", daemon=True)
        thread.start()
        while thread.is_alive():
            thread.join(0.05)
            if worker.is_cancelled:  # a newer fit, or the dialog closed
                return
        report, error = got.get("report"), None
        exc = got.get("exc")
        if isinstance(exc, InputError):
            error = str(exc)
        elif exc is not None:  # a bug: said in the status line and logged; the dialog stays
            from ..bug_log import record
            from ..guard import internal_error

            error = f"{path}: " + internal_error(exc, record(exc, "gearhead (the app) fit from log"))
        if not worker.is_cancelled:  # a newer fit, or the dialog closed
            self.post_message(self.Fitted(path, report, error, time.perf_counter() - self._started))

    @on(Fitted)
    @guarded
    async def _fitted(self, message: Fitted) -> None:
        self._fitting = False
        if message.error is not None:
            self.report = None
            self.changes = {}
            for wid in ("#fit-table", "#fit-entries", "#fit-plot"):
                self.query_one(wid).display = False
            for wid in ("#fit-signals", "#fit-favoured", "#fit-replay", "#fit-diff"):
                self.query_one(wid, Static).update("")
            self._status(message.error, "bold red")
            return
        self.report = message.report
        self._show_tables(message.report)
        self.seconds = time.perf_counter() - self._started
        took = "" if self.hide_timings else f" in {self.seconds * 1000:.0f} ms"
        self._status(f"{message.path}: fitted{took}", "green")
        await self._show_plot(message.report)

    # ---- showing -----------------------------------------------------------------------------
    def _show_tables(self, r) -> None:
        from gearhead.core.fit import favoured_reason

        pos, vel = UNITS[r.kind]
        p = r.picked
        lines = ["signals: " + ", ".join(f"{k} {v}" for k, v in p.names.items())]
        if p.units:
            lines.append("units: " + ", ".join(f"{k} {v}" for k, v in p.units.items()))
        lines.append(
            "samples: "
            + ", ".join(f"{s} {len(run.t_voltage)}" for s, run in p.runs.items())
            + f"; mean step {g(r.info['dt'] * 1000)} ms"
        )
        self.query_one("#fit-signals", Static).update(Text("\n".join(map(printable, lines))))

        table = self.query_one("#fit-table", DataTable)
        table.clear(columns=True)
        forms = list(r.fits)
        table.add_columns("gain", "card", *(f"{f} ★" if f == r.favoured else f for f in forms), "unit")
        unit = {"kS": "V", "kG": "V", "kV": f"V/({vel})", "kA": f"V/({vel}/s)", "offset": "rad"}
        for k in r.fits["continuous"].gains:
            card = r.card.design.get(k, 0.0 if k == "offset" else math.nan)
            cells = [f"{g(f.gains[k])} ± {g(f.sigma[k])}" for f in r.fits.values()]
            table.add_row(k, g(card), *cells, unit[k], key=k)
        for label, key in (("adj. R²", "adj_r2"), ("RMSE", "rmse"), ("samples", "samples")):
            table.add_row(label, "", *(g(getattr(f, key)) for f in r.fits.values()), "", key=key)
        table.add_row(
            "replay RMSE",
            g(r.replays["design"].velocity_rmse),
            *(g(r.replays[f].velocity_rmse) for f in forms),
            vel,
            key="replay",
        )
        table.display = True
        lines = [
            f"favoured: {r.favoured} ★ ({favoured_reason(r)}); the replay RMSE row: the velocity "
            "error of each form's replay, the card's column with its design's gains",
            *(f"note: {n}" for n in r.notes),
        ]
        # printable() shows a line break as \n: each line on its own (a signal's name may hold one)
        self.query_one("#fit-favoured", Static).update(Text("\n".join(map(printable, lines))))

        entries = self.query_one("#fit-entries", DataTable)
        entries.clear(columns=True)
        entries.add_columns("entry", "card", f"fitted ({r.favoured})", "unit")
        for name, card_value, value, sigma, u in r.entries:
            entries.add_row(name, g(card_value), f"{g(value)} ± {g(sigma)}", u, key=name)
        entries.display = True

        # as core/fit/apply.py: a link is not overwritten (what the fit gives it is said), and the
        # other entries are computed with it held
        free, _ = fitted_changes(r)
        self.changes, notes = fitted_changes(r, held=tuple(self.linked))
        self._show_diff(notes, free)

    def _show_diff(self, notes: list[str], free: dict[str, str]) -> None:
        from .card_text import in_field_unit
        from .sheet import shown_entry
        from .unit_text import pretty_unit

        def shown(f, v) -> str:
            u = pretty_unit(f.unit) if f.kind.with_unit and f.unit else ""
            return f"{shown_entry(f, str(in_field_unit(f, f.kind.entry(f, v))))} {u}".rstrip()

        for k in [k for k in free if k in self.linked]:
            f = self.calculator.field(k)
            notes = [
                *notes,
                f"{f.label} is linked ({self.linked[k]}): not written; the fit gives {shown(f, free[k])}",
            ]
            self.changes.pop(k, None)
        lines = []
        for k, v in list(self.changes.items()):
            f = self.calculator.field(k)
            new = in_field_unit(f, f.kind.entry(f, v))
            old = self.entries.get(k, "")
            u = pretty_unit(f.unit) if f.kind.with_unit and f.unit else ""
            if f.choices and str(old) in f.choices and str(new) in f.choices:  # a mode: as its menu says
                old, new = f.label_of(str(old)), f.label_of(str(new))
            lines.append(f"  {f.label}: {shown_entry(f, str(old))} → {shown_entry(f, str(new))} {u}".rstrip())
        head = "Apply writes into the card:" if lines else "Apply: nothing to change in the card."
        text = "\n".join([head, *lines, *(f"  note: {n}" for n in notes)])
        self.query_one("#fit-diff", Static).update(Text("\n".join(map(printable, text.split("\n")))))
        self.query_one("#fit-apply", Button).disabled = not self.changes

    async def _show_plot(self, r) -> None:
        from textual_plot import HiResMode

        fav = r.replays[r.favoured].traces
        state = next((s for s in ("dynamic-forward", *fav) if s in fav and len(fav[s][0]) > 1), None)
        holder = self.query_one("#fit-plot", Vertical)
        line = self.query_one("#fit-replay", Static)
        if state is None or state not in r.replays["design"].traces:
            holder.display = False
            line.update("")
            return
        plots = holder.query("PlotWidget")
        if plots:
            plot = plots.first()
        else:
            if not self.app.is_running:  # closing: a widget mounted now would never be composed
                return
            plot = quiet_plot_widget()(allow_pan_and_zoom=False)
            await holder.mount(plot)
            if not plot.children:  # the app closed while it mounted
                return
        t, _, v, _, vh = fav[state]
        vd = r.replays["design"].traces[state][4]
        x = [float(s - t[0]) for s in t]
        plot.clear()
        for colour, ys, label in (
            (COLOURS[0], v, "measured"),
            (COLOURS[1], vh, f"replayed, {r.favoured} fit"),
            (COLOURS[2], vd, "replayed, design"),
        ):
            plot.plot(x, [float(y) for y in ys], line_style=colour, hires_mode=HiResMode.BRAILLE, label=label)
        plot.show_legend()
        _, vel = UNITS[r.kind]
        plot.set_xlabel(escape("time [s]"))
        plot.set_ylabel(escape(f"velocity [{vel}]"))
        holder.display = True
        line.update(Text(f"replay of the {state} test: the logged voltage through the card's model"))

    # ---- leaving -----------------------------------------------------------------------------
    @on(Button.Pressed, "#fit-apply")
    def _apply(self) -> None:
        if self.changes:
            self.dismiss(dict(self.changes))

    @on(Button.Pressed, "#fit-close")
    def _close(self) -> None:
        self.action_close()

    def action_close(self) -> None:
        if self._fitting:
            self.workers.cancel_group(self, "fit")
        self.dismiss(None)
