"""Charts of a calculator's series (textual-plot), in display units, one plot at a time."""

from __future__ import annotations

from functools import cache

from rich.markup import escape
from rich.segment import Segment
from rich.text import Text
from textual import events, on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.message import Message
from textual.strip import Strip
from textual.widget import Widget

from gearhead.core import units
from gearhead.core.model import HeatMap, Plot, Solution

from .unit_text import fit_cells, pretty_unit

COLOURS = ("cyan", "magenta", "yellow", "green", "red")


def axis_label(label: str, unit: str) -> str:
    return f"{label} [{pretty_unit(unit)}]" if unit else label


class ChartChooser(Widget, can_focus=True):
    """Which chart the panel shows, on one line drawn as a compact Select ("Title ▼"). Enter,
    Space, ↑ or ↓ (or a click) opens the list of charts, the list a choice row of the sheet opens
    (Enter picks, Esc leaves it). One widget instead of Select's seven (its list is built when
    opened): a card with charts was the slowest to show for the first time."""

    COMPONENT_CLASSES = {"chart-chooser--arrow"}
    DEFAULT_CSS = """
    ChartChooser {
        height: 1;
        background: $surface;
        color: $foreground;
        pointer: pointer;
        &:focus { background-tint: $foreground 5%; }
        & > .chart-chooser--arrow { color: $foreground 50%; }
    }
    """

    class Changed(Message):
        def __init__(self, chooser: ChartChooser, value: int) -> None:
            super().__init__()
            self.chooser, self.value = chooser, value

        @property
        def control(self) -> ChartChooser:
            return self.chooser

    def __init__(self, titles: list[str], value: int = 0, **kwargs) -> None:
        super().__init__(**kwargs)
        self.titles = titles
        self._value = value

    @property
    def value(self) -> int:
        return self._value

    @value.setter
    def value(self, value: int) -> None:
        if value != self._value:
            self._value = value
            self.refresh()
            self.post_message(self.Changed(self, value))

    def render_line(self, y: int) -> Strip:
        width, base = self.size.width, self.rich_style
        if y != 0 or width < 3:
            return Strip.blank(width, base)
        arrow = base + self.get_component_rich_style("chart-chooser--arrow")
        segments = [Segment(fit_cells(self.titles[self._value], width - 3), base), Segment(" ", base)]
        return Strip([*segments, Segment("▼", arrow), Segment(" ", base)])

    # bindings, not a key handler: the key bar then says what Enter does here
    BINDINGS = [
        Binding("enter", "open", "Charts"),
        Binding("space", "open", show=False),
        Binding("up", "open", show=False),
        Binding("down", "open", show=False),
    ]

    def action_open(self) -> None:
        self.open()

    def on_click(self, event: events.Click) -> None:
        self.open()

    def open(self) -> None:
        from .choice_screen import ChoiceScreen

        def chosen(value: str | None) -> None:
            if value is not None:
                self.value = int(value)

        options = tuple((str(i), title) for i, title in enumerate(self.titles))
        self.app.push_screen(ChoiceScreen("Chart", options, str(self._value)), chosen)


class PlotPanel(Vertical):
    EMPTY = "No data to plot for these inputs."

    def __init__(self, plots: tuple[Plot | HeatMap, ...]) -> None:
        super().__init__(classes="plot-panel")
        self.plots = plots
        self.solution: Solution | None = None
        self.unit_system = "calculator"  # imperial / metric map the axes' units too
        self.empty = False  # the chart shown has no data: the panel says so (render)

    def compose(self) -> ComposeResult:
        if len(self.plots) > 1:
            yield ChartChooser([p.title for p in self.plots], id="plot-choice")
        # the PlotWidget itself is mounted on first use: textual-plot and numpy load after the first frame

    def render(self) -> Text:
        """The panel's own text, under its children: "no data" below the chooser's line while the
        chart shown has none (its widget is hidden then). A line of the panel, not a widget of its
        own: one widget fewer to compose and style on a card's first visit, and no layout when
        it comes or goes."""
        if not self.empty:
            return Text("")
        top = "\n" * (1 + (len(self.plots) > 1))  # a blank line under the chooser, as a padding
        return Text.assemble(top, " ", (self.EMPTY, "dim"))

    def _say_empty(self, empty: bool) -> None:
        if empty != self.empty:
            self.empty = empty
            self.refresh()

    @on(ChartChooser.Changed, "#plot-choice")
    def _choose(self, event: ChartChooser.Changed) -> None:
        event.stop()
        if self.solution is not None:
            self.call_later(self.show, self.solution)

    # A chart costs more than a frame to draw (textual-plot redraws every series on each render:
    # 10-30 ms on the motor tab, pilot), so it follows the results once typing pauses: the frame
    # that shows a key's results is never held up by it, and a burst of keys draws it once.
    QUIET_S = 0.08
    _pending = None  # the timer of a show_soon not yet done

    def show_soon(self, solution: Solution) -> None:
        self.solution = solution
        if self._pending is not None:
            self._pending.stop()
        self._pending = self.set_timer(self.QUIET_S, self._show_pending)

    @property
    def pending(self) -> bool:
        """A chart is waiting to be drawn (tests wait for it)."""
        return self._pending is not None

    async def _show_pending(self) -> None:
        self._pending = None
        if self.solution is not None and self.is_attached and self.app.is_running:
            await self.show(self.solution)

    def on_unmount(self) -> None:
        if self._pending is not None:  # the card (or the app) is going: no chart to draw
            self._pending.stop()
            self._pending = None

    @property
    def current(self) -> Plot | HeatMap:
        """The plot on screen (the one the selector shows)."""
        if len(self.plots) > 1:
            return self.plots[self.query_one("#plot-choice", ChartChooser).value]
        return self.plots[0]

    async def show(self, solution: Solution) -> None:
        from dataclasses import replace

        from gearhead.core.unit_systems import system_unit

        self.solution = solution
        other = self._with_data(solution)
        if other is not None:  # the selector's change shows it
            self.query_one("#plot-choice", ChartChooser).value = other
            return
        spec = self.current
        spec = replace(
            spec,
            x_unit=system_unit(spec.x_unit, self.unit_system),
            y_unit=system_unit(spec.y_unit, self.unit_system),
        )
        if isinstance(spec, HeatMap):
            await self._show_heat_map(
                replace(spec, z_unit=system_unit(spec.z_unit, self.unit_system)), solution
            )
            return
        for view in self.query("HeatMapView"):
            view.display = False
        from textual_plot import HiResMode, PlotWidget

        plots = self.query(PlotWidget)
        if plots:
            plot = plots.first()
        else:
            if not self.app.is_running:  # closing: a widget mounted now would never be composed
                return
            plot = quiet_plot_widget()(allow_pan_and_zoom=False)
            await self.mount(plot)
            if not plot.children:  # the app closed while it mounted: nothing to draw into
                return
        plot.clear()
        drawn = 0
        for colour, name in zip(COLOURS, spec.series):
            if name not in solution.series or not solution.series[name][0]:
                continue
            drawn += 1
            xs, ys = solution.series[name]
            fx = units.factor(spec.x_unit, spec.x_quantity)
            fy = units.factor(spec.y_unit, spec.y_quantity)
            plot.plot(
                [x / fx for x in xs],
                [y / fy for y in ys],
                line_style=colour,
                hires_mode=HiResMode.BRAILLE,
                label=escape(solution.series_label(name)) if len(spec.series) > 1 else None,
            )
        # an empty frame with an empty legend box looks like a drawing bug: say there is no data
        self._say_empty(drawn == 0)
        plot.display = drawn > 0
        if len(spec.series) > 1 and drawn:
            plot.show_legend()
        # Textual markup would swallow "[psi]": escape every label (DESIGN.md pitfall)
        plot.set_xlabel(escape(axis_label(spec.x_label, spec.x_unit)))
        plot.set_ylabel(escape(axis_label(spec.y_label, spec.y_unit)))

    def _has_data(self, plot: Plot | HeatMap, solution: Solution) -> bool:
        if isinstance(plot, HeatMap):
            return plot.name in solution.heat_maps
        return any(solution.series.get(s, ([], []))[0] for s in plot.series)

    def _with_data(self, solution: Solution) -> int | None:
        """A heat map is the one chart of its mode (the limit grid) and the line charts have no data
        there: the index of the chart to show instead of the one chosen when the chosen one is empty
        and a heat map has data (or a heat map is chosen, without data, and a line chart has data)."""
        if len(self.plots) < 2 or self._has_data(self.current, solution):
            return None
        chosen_map = isinstance(self.current, HeatMap)
        for i, plot in enumerate(self.plots):
            if isinstance(plot, HeatMap) != chosen_map and self._has_data(plot, solution):
                return i
        return None

    async def _show_heat_map(self, spec: HeatMap, solution: Solution) -> None:
        from textual_plot import PlotWidget

        from .heat_map import HeatMapView

        for plot in self.query(PlotWidget):
            plot.display = False
        data = solution.heat_maps.get(spec.name)
        views = self.query(HeatMapView)
        if views:
            view = views.first()
        else:
            if not self.app.is_running:
                return
            view = HeatMapView()
            await self.mount(view)
        self._say_empty(data is None)
        view.display = data is not None
        if data is not None:
            view.show(spec, data)


@cache
def quiet_plot_widget():
    """textual-plot's PlotWidget, quiet when the app closes while it is being mounted: its
    children are then never composed, and its on_mount and margin watchers query them (a
    traceback on the way out). Built on first use: textual-plot loads after the first frame."""
    from textual_plot import PlotWidget

    # not focusable: our charts allow no pan or zoom, yet a focused PlotWidget still pans on
    # the arrow keys, and on a chart with no size yet that divided by zero and ended the app
    # (a key storm: Tab onto the sweep's chart, then an arrow)
    class QuietPlotWidget(PlotWidget, can_focus=False):
        def on_mount(self, event) -> None:
            if not self.children:  # Textual runs PlotWidget.on_mount next unless prevented
                event.prevent_default()

        # the margin watchers lay out the children: none to lay out yet (module docstring above)
        def watch_margin_top(self) -> None:
            if self.children:
                super().watch_margin_top()

        def watch_margin_bottom(self) -> None:
            if self.children:
                super().watch_margin_bottom()

        def watch_margin_left(self) -> None:
            if self.children:
                super().watch_margin_left()

    return QuietPlotWidget
