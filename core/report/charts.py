"""The report's charts as SVG, drawn by matplotlib: the one module of Gearhead that imports it (the
app's start and the other commands never load it: tests/test_report_speed.py checks).

Deterministic: the same chart gives the same bytes (no date in the metadata, a fixed hash salt for
the ids matplotlib makes, glyphs drawn as paths from the fonts matplotlib ships, so no font of the
reader's machine changes a page). Each series is a line whose group id is `{chart.key}-s{i}` and the
axes' is `{chart.key}-axes`, so a test finds a series' path and maps its points back to the data.
"""

from __future__ import annotations

import io
import re
import threading

from .document import Chart

WIDTH_IN = 7.0
HEIGHT_IN = 3.2
DPI = 72  # the SVG backend's own: a figure at this dpi has the same coordinates on screen and in the file
COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e")
RC = {
    "svg.hashsalt": "gearhead-report",
    "svg.fonttype": "none",  # text as text (searchable, and 30 % quicker than glyph paths)
    "font.family": "DejaVu Sans",
    "font.size": 9,
    "axes.grid": True,
    "grid.alpha": 0.35,
    "path.simplify": False,  # every point of a series is in the file (a test maps them back)
    "axes.formatter.useoffset": False,
}


def plain(text: str) -> str:
    """Text shown as it is: matplotlib reads $...$ as mathematics (a name with two $ signs would
    render as math, or raise on a bad expression)."""
    return text.replace("\\", "\\\\").replace("$", r"\$")


def figure(chart: Chart):
    """The chart's matplotlib Figure (no pyplot: no global state, no GUI backend). A line chart
    reuses one Figure and its Axes (emptied): a new Axes, its ticks and their labels cost ~40 % of
    a chart's time, and the page's charts all share that frame (same size, margins, tick density).
    The returned Figure is valid until the next call."""
    import matplotlib

    with matplotlib.rc_context(RC):
        if chart.heat is not None:
            fig, ax = _new_axes()
            _heat(fig, ax, chart)
        else:
            fig, ax = _line_axes()
            if chart.stacked:
                _stack(ax, chart)
            for i, s in enumerate(chart.series if not chart.stacked else ()):
                (line,) = ax.plot(
                    s.x, s.y, color=COLOURS[i % len(COLOURS)], linewidth=1.4, label=plain(s.label)
                )
                line.set_gid(f"{chart.key}-s{i}")
            if chart.level is not None:
                value, label = chart.level
                ax.axhline(value, color="#888888", linestyle="--", linewidth=1, label=plain(label))
            if len(chart.series) > 1 or chart.level is not None:
                ax.legend(loc="best", fontsize=8, frameon=False)
        ax.set_gid(f"{chart.key}-axes")
        ax.set_title(plain(chart.title), fontsize=10, loc="left")
        ax.set_xlabel(plain(chart.x_label))
        ax.set_ylabel(plain(chart.y_label))
    return fig


def _new_axes():
    from matplotlib.figure import Figure

    fig = Figure(figsize=(WIDTH_IN, HEIGHT_IN), dpi=DPI)
    ax = fig.add_subplot(1, 1, 1)
    ax.locator_params(nbins=5)  # fewer ticks: as readable on a page, and a quarter less to draw
    fig.subplots_adjust(left=0.11, right=0.97, top=0.88, bottom=0.16)
    return fig, ax


_DRAWING = threading.Lock()  # the app builds a report in a thread worker
_LINES: list = []  # the line charts' Figure and Axes, made once (under RC) and emptied for each chart


def _line_axes():
    """The reused Figure and Axes, emptied as a new one is: no line, no legend, no data limits
    (autoscaling on, as at first); the title and labels are set again by `figure`."""
    if not _LINES:
        _LINES.extend(_new_axes())
        return tuple(_LINES)
    fig, ax = _LINES
    for artist in [*ax.lines, *ax.collections]:
        artist.remove()
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    ax.relim()  # no artist left: the data limits are null, the next plot's alone
    ax.set_autoscale_on(True)
    return fig, ax


def _stack(ax, chart: Chart) -> None:
    """Layers stacked on each other (stackplot: each a filled area from the sum of those below),
    the first in grey (the base load), each with its group id as a line's."""
    colours = ["#9e9e9e", *COLOURS]
    areas = ax.stackplot(
        chart.series[0].x,
        *[s.y for s in chart.series],
        labels=[plain(s.label) for s in chart.series],
        colors=[colours[i % len(colours)] for i in range(len(chart.series))],
        linewidth=0,
    )
    for i, area in enumerate(areas):
        area.set_gid(f"{chart.key}-s{i}")


def _heat(fig, ax, chart: Chart) -> None:
    """A heat map as vector cells (pcolormesh), each with its value, the pick outlined."""
    import numpy as np

    h = chart.heat
    z = np.array([[np.nan if v is None else v for v in row] for row in h.z], dtype=float)
    mesh = ax.pcolormesh(_edges(h.x), _edges(h.y), np.ma.masked_invalid(z), cmap="viridis", shading="flat")
    mesh.set_gid(f"{chart.key}-cells")
    fig.colorbar(mesh, ax=ax, label=plain(h.z_label))
    fig.subplots_adjust(right=0.9)
    ax.grid(False)
    for j, y in enumerate(h.y):
        for i, x in enumerate(h.x):
            v = h.z[j][i]
            if v is not None and len(h.x) * len(h.y) <= 100:
                ax.text(x, y, f"{v:.3g}", ha="center", va="center", fontsize=7, color="white")
    if h.pick is not None:
        j, i = h.pick
        xe, ye = _edges(h.x), _edges(h.y)
        ax.plot(
            [xe[i], xe[i + 1], xe[i + 1], xe[i], xe[i]],
            [ye[j], ye[j], ye[j + 1], ye[j + 1], ye[j]],
            color="red",
        )


def _edges(centres: list[float]) -> list[float]:
    """Cell edges around the given centres (midpoints; the ends half a step out)."""
    if len(centres) == 1:
        c = centres[0]
        return [c - 0.5 * (abs(c) or 1), c + 0.5 * (abs(c) or 1)]
    mids = [(a + b) / 2 for a, b in zip(centres, centres[1:])]
    return [2 * centres[0] - mids[0], *mids, 2 * centres[-1] - mids[-1]]


def svg(chart: Chart) -> str:
    """The chart as one SVG document (text), the same bytes for the same chart; its ids begin with
    the chart's key, so several charts inline in one HTML page never share an id."""
    with _DRAWING:  # one reused Figure, and rcParams changed for the while: a thread at a time
        return scoped(svg_of(figure(chart)), chart.key)


_ID_USE = re.compile(r'(id="|href="#|url\(#)([^")]+)')


def scoped(text: str, key: str) -> str:
    """Every id matplotlib made (figure_1, glyph and marker ids) and each reference to it, prefixed
    with `key-`; the gids set here already carry the key."""
    ids = {m for m in re.findall(r'id="([^"]+)"', text) if not m.startswith(key + "-")}

    def prefix(m: re.Match) -> str:
        return m.group(1) + (f"{key}-{m.group(2)}" if m.group(2) in ids else m.group(2))

    return _ID_USE.sub(prefix, text)


def svg_of(fig) -> str:
    import matplotlib
    from matplotlib.backends.backend_svg import FigureCanvasSVG

    FigureCanvasSVG(fig)
    out = io.StringIO()
    with matplotlib.rc_context(RC):
        fig.savefig(out, format="svg", metadata={"Date": None})
    return out.getvalue()
