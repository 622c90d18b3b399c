"""A heat map (core.declarations.HeatMap): a coloured cell with its value for every (x, y) pair, the
pick in brackets, as one Line-API widget (Textual's ScrollView, as the sheet and DataTable).

Hand-drawn because textual-plot (0.10.1, and its repository's head) draws lines, scatter, error bars
and bars but no image or heat map. Every cell carries its value as text and the pick its brackets, so
the map reads the same without colour (NO_COLOR) or to a colour-blind eye; the colour only helps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rich.color import Color
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Size
from textual.strip import Strip

from gearhead.core import units
from gearhead.core.model import HeatMap, HeatMapData

from .line_view import LineView
from .unit_text import pretty_unit

# viridis at six stops (low to high): even steps of lightness, readable by colour-blind eyes
RAMP = ((68, 1, 84), (65, 68, 135), (42, 120, 142), (34, 168, 132), (122, 209, 81), (253, 231, 37))


def ramp(t: float) -> Color:
    """The colour at t in [0, 1] along RAMP (linear between stops)."""
    t = min(max(t, 0.0), 1.0) * (len(RAMP) - 1)
    i = min(int(t), len(RAMP) - 2)
    f = t - i
    a, b = RAMP[i], RAMP[i + 1]
    return Color.from_rgb(*(round(x + (y - x) * f) for x, y in zip(a, b)))


def number(value: float, digits: int = 4) -> str:
    return f"{value:.{digits}g}"


def decimals(values: list[float], digits: int) -> int | None:
    """Decimals that give the largest magnitude `digits` significant digits, the same in every cell
    so the column reads evenly (None: too large for fixed decimals, use `number`)."""
    top = max((abs(v) for v in values), default=0.0)
    if not top > 0 or top >= 1e6 or top < 1e-6:
        return None
    return max(0, digits - 1 - math.floor(math.log10(top)))


@dataclass
class Layout:
    """What the lines are built from, in display units."""

    title: str
    x_head: str
    y_head: str
    xs: list[str]
    ys: list[str]
    cells: list[list[str]]  # the value's text, or the cell's note
    shades: list[list[float | None]]  # 0..1 along the ramp, None: no value
    pick: tuple[int, int] | None
    low: str
    high: str


def layout(spec: HeatMap, data: HeatMapData, digits: int = 4) -> Layout:
    """The text and shades of every cell, values to `digits` significant digits (the axes' to 4)."""
    fx = units.factor(spec.x_unit, spec.x_quantity)
    fy = units.factor(spec.y_unit, spec.y_quantity)
    fz = units.factor(spec.z_unit, spec.z_quantity)
    zs = [z for row in data.z for z in row if z is not None]
    lo, hi = (min(zs), max(zs)) if zs else (0.0, 0.0)
    span = hi - lo
    places = decimals([z / fz for z in zs], digits)

    def text(z: float) -> str:
        return number(z / fz, digits) if places is None else f"{z / fz:.{places}f}"

    cells, shades = [], []
    for j, row in enumerate(data.z):
        notes = data.notes[j] if j < len(data.notes) else []
        cells.append(
            [text(z) if z is not None else (notes[i] if i < len(notes) else "") for i, z in enumerate(row)]
        )
        shades.append([None if z is None else ((z - lo) / span if span > 0 else 0.5) for z in row])
    z_unit = f" {pretty_unit(spec.z_unit)}" if spec.z_unit else ""
    return Layout(
        f"{spec.z_label}{f' [{pretty_unit(spec.z_unit)}]' if spec.z_unit else ''} per cell; [ ] the pick",
        f"{spec.x_label}{f' [{pretty_unit(spec.x_unit)}]' if spec.x_unit else ''}",
        f"{spec.y_label}{f' [{pretty_unit(spec.y_unit)}]' if spec.y_unit else ''}",
        [number(x / fx) for x in data.x],
        [number(y / fy) for y in data.y],
        cells,
        shades,
        data.pick,
        f"{text(lo)}{z_unit}" if zs else "",
        f"{text(hi)}{z_unit}" if zs else "",
    )


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
        label_w = max(len(y) for y in L.ys)
        # room for [ ] about the widest text; no gap between cells (each cell's spaces part them)
        cell_w = max([len(x) for x in L.xs] + [len(c) for row in L.cells for c in row]) + 2
        lines: list[list[Segment]] = [
            [Segment(" " + L.title, Style(bold=True))],
            [Segment(f" rows: {L.y_head} ↓   columns: {L.x_head} →", dim)],
            [Segment(" " + " " * label_w + " ", dim)] + [Segment(x.center(cell_w), dim) for x in L.xs],
        ]
        for j, y in enumerate(L.ys):
            segments = [Segment(" " + y.rjust(label_w) + " ", dim)]
            for i, text in enumerate(L.cells[j]):
                shade = L.shades[j][i]
                picked = L.pick == (j, i)
                shown = f"[{text}]" if picked else f" {text} "
                if shade is None:
                    style = dim
                else:
                    bg = ramp(shade)
                    r, g, b = bg.get_truecolor()
                    light = 0.299 * r + 0.587 * g + 0.114 * b > 140  # dark text on the light end
                    style = Style(color="black" if light else "white", bgcolor=bg, bold=picked)
                segments.append(Segment(shown.center(cell_w), style))
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
