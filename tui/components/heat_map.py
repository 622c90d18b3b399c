"""A heat map (core.declarations.HeatMap): a coloured cell with its value for every (x, y) pair, the
pick in brackets, as one Line-API widget (Textual's ScrollView, as the sheet and DataTable).

Hand-drawn because textual-plot (0.10.1, and its repository's head) draws lines, scatter, error bars
and bars but no image or heat map. Every cell carries its value as text and the pick its brackets, so
the map reads the same without colour (NO_COLOR) or to a colour-blind eye; the colour only helps.
"""

from __future__ import annotations

from rich.color import Color
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Size
from textual.strip import Strip

from gearhead.core.model import HeatMap, HeatMapData

from .heat_map_layout import Layout, cell_text, cell_width, label_width, layout
from .line_view import LineView

# viridis at six stops (low to high): even steps of lightness, readable by colour-blind eyes
RAMP = ((68, 1, 84), (65, 68, 135), (42, 120, 142), (34, 168, 132), (122, 209, 81), (253, 231, 37))


def ramp(t: float) -> Color:
    """The colour at t in [0, 1] along RAMP (linear between stops)."""
    t = min(max(t, 0.0), 1.0) * (len(RAMP) - 1)
    i = min(int(t), len(RAMP) - 2)
    f = t - i
    a, b = RAMP[i], RAMP[i + 1]
    return Color.from_rgb(*(round(x + (y - x) * f) for x, y in zip(a, b)))


class HeatMapView(LineView, can_focus=False):
    """The lines: a title, the x axis' label and values, a row per y value (its value, then a cell
    per x), and a legend of the ramp with the lowest and highest values."""

    DEFAULT_CSS = """
    HeatMapView {
        height: 1fr;
    }
    """

    HEAD = 3  # title, x label, x values

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
        self.shown: Layout | None = None
        self._lines: list[Strip] = []

    shown_spec: tuple[HeatMap, HeatMapData] | None = None

    def show(self, spec: HeatMap, data: HeatMapData) -> None:
        self.shown_spec = (spec, data)
        self._fit()

    def on_resize(self) -> None:
        self._fit()

    def _fit(self) -> None:
        """Four significant digits in each cell when the map fits the width so, else three (the
        table under the chart has them all)."""
        if self.shown_spec is None:
            return
        for digits in (4, 3):
            self.shown = layout(*self.shown_spec, digits)
            if self._build() <= self.size.width:
                break

    def _build(self) -> int:
        """The lines of self.shown; returns their width."""
        L = self.shown
        if L is None:
            return 0
        dim = Style(dim=True)
        label_w, cell_w = label_width(L), cell_width(L)
        lines: list[list[Segment]] = [
            [Segment(" " + L.title, Style(bold=True))],
            [Segment(f" rows: {L.y_head} ↓   columns: {L.x_head} →", dim)],
            [Segment(" " + " " * label_w + " ", dim)] + [Segment(x.center(cell_w), dim) for x in L.xs],
        ]
        for j, y in enumerate(L.ys):
            segments = [Segment(" " + y.rjust(label_w) + " ", dim)]
            for i in range(len(L.xs)):
                shade = L.shades[j][i]
                picked = L.pick == (j, i)
                if shade is None:
                    style = dim
                else:
                    bg = ramp(shade)
                    r, g, b = bg.get_truecolor()
                    light = 0.299 * r + 0.587 * g + 0.114 * b > 140  # dark text on the light end
                    style = Style(color="black" if light else "white", bgcolor=bg, bold=picked)
                segments.append(Segment(cell_text(L, j, i), style))
            lines.append(segments)
        if L.low:
            steps = 12
            legend = [Segment(" " + " " * label_w + " " + L.low + " ", dim)]
            legend += [Segment(" ", Style(bgcolor=ramp(k / (steps - 1)))) for k in range(steps)]
            legend.append(Segment(" " + L.high, dim))
            lines.append(legend)
        width = max(sum(s.cell_length for s in line) for line in lines)
        self._lines = [Strip(line) for line in lines]
        self.virtual_size = Size(width, len(lines))
        self.refresh()
        return width

    def render_line(self, y: int) -> Strip:
        width = self.size.width
        base = self.base_style
        index = y + self.scroll_offset.y
        if not (0 <= index < len(self._lines)):
            return Strip.blank(width, base)
        x0 = self.scroll_offset.x
        strip = self._lines[index]
        # the rest of the line in the widget's own style, the cells keep theirs
        strip = Strip([Segment(s.text, base + s.style if s.style else base) for s in strip])
        return strip.crop(x0, x0 + width).adjust_cell_length(width, base)

    def text_lines(self) -> list[str]:
        """The map as plain text (tests, and what a screen reader would be given)."""
        return [strip.text.rstrip() for strip in self._lines]
