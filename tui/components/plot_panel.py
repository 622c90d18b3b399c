"""Charts of a calculator's series (textual-plot), in display units, one plot at a time."""

from __future__ import annotations

from rich.markup import escape
from textual import on
from textual.app import ComposeResult
from textual.containers import Vertical
from textual.widgets import Select

from core import units
from core.model import Plot, Solution

COLOURS = ("cyan", "magenta", "yellow", "green", "red")


def axis_label(label: str, unit: str) -> str:
    return f"{label} [{unit}]" if unit else label


class PlotPanel(Vertical):
    def __init__(self, plots: tuple[Plot, ...]) -> None:
        super().__init__(classes="plot-panel")
        self.plots = plots
        self.solution: Solution | None = None

    def compose(self) -> ComposeResult:
        if len(self.plots) > 1:
            yield Select([(p.title, i) for i, p in enumerate(self.plots)], value=0, allow_blank=False,
                         compact=True, id="plot-choice")
        # the PlotWidget itself is mounted on first use: textual-plot and numpy load after the first frame

    @on(Select.Changed, "#plot-choice")
    def _choose(self, event: Select.Changed) -> None:
        event.stop()
        if self.solution is not None:
            self.call_later(self.show, self.solution)

    async def show(self, solution: Solution) -> None:
        self.solution = solution
        index = 0
        if len(self.plots) > 1:
            index = self.query_one("#plot-choice", Select).value
        spec = self.plots[index]
        from textual_plot import HiResMode, PlotWidget

        plots = self.query(PlotWidget)
        if plots:
            plot = plots.first()
        else:
            plot = PlotWidget(allow_pan_and_zoom=False)
            await self.mount(plot)
        plot.clear()
        for colour, name in zip(COLOURS, spec.series):
            if name not in solution.series:
                continue
            xs, ys = solution.series[name]
            fx = units.factor(spec.x_unit, spec.x_quantity)
            fy = units.factor(spec.y_unit, spec.y_quantity)
            plot.plot([x / fx for x in xs], [y / fy for y in ys], line_style=colour,
                      hires_mode=HiResMode.BRAILLE, label=escape(name) if len(spec.series) > 1 else None)
        if len(spec.series) > 1:
            plot.show_legend()
        # Textual markup would swallow "[psi]": escape every label (DESIGN.md pitfall)
        plot.set_xlabel(escape(axis_label(spec.x_label, spec.x_unit)))
        plot.set_ylabel(escape(axis_label(spec.y_label, spec.y_unit)))
