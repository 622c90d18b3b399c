"""Accuracy vs time: one scene at every accuracy level against a tight reference (table + plot)."""

from __future__ import annotations

import math
from typing import Any

from rich.markup import escape
from rich.text import Text
from textual import work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.widgets import DataTable, Label, Static

from gearhead.core.model import Calculator

from .dialog import Dialog


class AccuracyScreen(Dialog[None]):
    BINDINGS = [Binding("escape", "dismiss(None)", "Close")]

    def __init__(self, calculator: Calculator, values: dict[str, Any], hide_timings: bool = False) -> None:
        super().__init__()
        self.calculator = calculator
        self.values = values
        self.hide_timings = hide_timings
        self.rungs = []

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog accuracy-dialog"):
            yield Label(Text(f"{self.calculator.title}: accuracy vs time"), classes="dialog-title")
            table = DataTable(cursor_type="none", id="ladder")
            # fixed widths: columns sized from the header alone clipped "coarse" and "1e-03"
            for key, label, width in (
                ("level", "Level", 8),
                ("rtol", "rtol", 6),
                ("error", "Error vs reference", 18),
                ("time", "Wall time", 10),
                ("nfev", "RHS evaluations", 15),
            ):
                table.add_column(label, key=key, width=width)
            yield table
            yield Static(Text("running…", style="dim"), id="ladder-status")
            yield Vertical(id="ladder-plot")

    def on_mount(self) -> None:
        self.run_ladder()

    @work(thread=True, exclusive=True)
    def run_ladder(self) -> None:
        from gearhead.core.sim.scene import REFERENCE_RTOL, ladder

        try:
            rungs, reference = ladder(self.calculator.simulate, self.values)
        except Exception as exc:  # a wrong entry, or a bug (logged): said here, the app keeps running
            from gearhead.core.errors import InputError

            from ..bug_log import record
            from ..guard import internal_error

            if isinstance(exc, InputError):
                text = str(exc)
            else:
                text = internal_error(exc, record(exc, "gearhead (the app) accuracy ladder"))
            self.app.call_from_thread(self._failed, text)
            return
        self.app.call_from_thread(self._show, rungs, reference.nfev, REFERENCE_RTOL)

    def _failed(self, text: str) -> None:
        self.query_one("#ladder-status", Static).update(Text(text, style="bold red"))

    async def _show(self, rungs, ref_nfev: int, ref_rtol: float) -> None:
        self.rungs = rungs
        table = self.query_one(DataTable)
        for r in rungs:
            wall = "(hidden)" if self.hide_timings else f"{r.wall_time * 1e3:.3f} ms"
            table.add_row(r.level, f"{r.rtol:.0e}", f"{r.error:.2e}", wall, str(r.nfev), key=r.level)
        status = self.query_one("#ladder-status", Static)
        if all(r.nfev == 0 for r in rungs) and ref_nfev == 0:
            # a plot of identical points on a log axis would only show rounding noise
            status.update(
                Text(
                    "Nothing is integrated: with these effects the scene has a closed form, "
                    "so every accuracy level gives the same exact result.",
                    style="yellow",
                )
            )
            return
        status.update(
            Text(
                f"reference: rtol {ref_rtol:.0e}, {ref_nfev} RHS evaluations; wall time is the best of 3 runs",
                style="dim",
            )
        )
        from .plot_panel import quiet_plot_widget

        plot = quiet_plot_widget()(allow_pan_and_zoom=False)
        await self.query_one("#ladder-plot").mount(plot)
        floor = 1e-17  # an exact hit still needs a place on a log axis
        xs = [
            math.log10(max(r.wall_time, 1e-9) * 1e3) if not self.hide_timings else math.log10(r.nfev)
            for r in rungs
        ]
        ys = [math.log10(max(r.error, floor)) for r in rungs]
        from textual_plot import HiResMode

        plot.scatter(xs, ys, marker="●")
        plot.plot(xs, ys, line_style="cyan", hires_mode=HiResMode.BRAILLE)
        plot.set_xlabel(escape("log10 evaluations" if self.hide_timings else "log10 wall time [ms]"))
        plot.set_ylabel(escape("log10 error"))
