"""Units as people write them on screen: mm⁴ not mm**4, m/s² not m/s**2, N·m not N*m.

Display only (the JSON and CLI keep pint's spelling). A user may type either spelling: pint reads
"mm⁴" and "m/s²", and core.units turns "·" into "*".
"""

from __future__ import annotations

import re

_POWER = re.compile(r"\*\*(-?\d+)")
_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def pretty_unit(unit: str) -> str:
    return _POWER.sub(lambda m: m.group(1).translate(_SUPERSCRIPT), unit).replace("*", "·")


def pretty_quantity(text: str) -> str:
    """'77425 mm**4' -> '77425 mm⁴': the unit is everything after the number."""
    number, sep, unit = text.partition(" ")
    return f"{number}{sep}{pretty_unit(unit)}" if sep else text


def fit_cells(text: str, width: int) -> str:
    """`text` in exactly `width` terminal cells: padded, or cut with an ellipsis (a wide character
    counts two cells; rich's own cropping pads but does not mark the cut)."""
    from rich.cells import cell_len

    length = cell_len(text)
    if length <= width:
        return text + " " * (width - length)
    out, used = [], 0
    for ch in text:
        w = cell_len(ch)
        if used + w > width - 1:
            break
        out.append(ch)
        used += w
    return "".join(out) + "…" + " " * (width - 1 - used)
