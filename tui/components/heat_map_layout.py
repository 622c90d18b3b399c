"""A heat map's text (core.declarations.HeatMap) in display units: the cells' values, their shades
along the colour ramp, the pick; no Textual import, so the CLI prints the same map the card draws."""

from __future__ import annotations

import math
from dataclasses import dataclass

from gearhead.core import units
from gearhead.core.model import HeatMap, HeatMapData

from .unit_text import pretty_unit


def number(value: float, digits: int = 4) -> str:
    return f"{value:.{digits}g}"


def decimals(values: list[float], digits: int) -> int | None:
    """Decimals that give the largest magnitude `digits` significant digits, the same in every cell
    so the column reads evenly (None: too large for fixed decimals, use `number`)."""
    top = max((abs(v) for v in values), default=0.0)
    if not top > 0 or top >= 1e6 or top < 1e-6:
        return None
    places = max(0, digits - 1 - math.floor(math.log10(top)))
    least = min(abs(v) for v in values if v != 0)
    if math.floor(math.log10(least)) + 1 + places < 2:  # values spanning 1000x: the least would lose
        return None  # its digits (0.04 beside 1500 read "0")
    return places


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


def cell_width(L: Layout) -> int:
    """Room for [ ] about the widest text; no gap between cells (each cell's spaces part them)."""
    return max([len(x) for x in L.xs] + [len(c) for row in L.cells for c in row]) + 2


def label_width(L: Layout) -> int:
    return max(len(y) for y in L.ys)


def cell_text(L: Layout, j: int, i: int) -> str:
    text = L.cells[j][i]
    return (f"[{text}]" if L.pick == (j, i) else f" {text} ").center(cell_width(L))


def plain_lines(L: Layout) -> list[str]:
    """The map as the card draws it, without the colours (the CLI's text)."""
    lw, cw = label_width(L), cell_width(L)
    lines = [
        f" {L.title}",
        f" rows: {L.y_head} ↓   columns: {L.x_head} →",
        " " + " " * lw + " " + "".join(x.center(cw) for x in L.xs),
    ]
    for j, y in enumerate(L.ys):
        lines.append(" " + y.rjust(lw) + " " + "".join(cell_text(L, j, i) for i in range(len(L.xs))))
    if L.low:
        lines.append(f" {' ' * lw} lowest {L.low}, highest {L.high}")
    return [line.rstrip() for line in lines]
