"""Checks every input of core/match passes: a wrong entry is an InputError naming its field, so no
NaN, infinity, bool or string reaches the arithmetic (and no run's work grows without bound)."""

from __future__ import annotations

import math
from numbers import Real

from gearhead.core.errors import InputError, shown

MAX_TABLE_ROWS = 1000  # a voltage or trip-time table longer than this is no data sheet's


def number(
    field: str,
    value: object,
    *,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    high_open: bool = False,
) -> float:
    """`value` as a finite float within [low, high] (an end open where asked), else InputError."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise InputError(field, f"must be a number, got {shown(value)}")
    try:
        x = float(value)
    except (OverflowError, ValueError):  # an int past float's range
        raise InputError(field, f"must be a finite number, got {shown(value)}") from None
    if not math.isfinite(x):
        raise InputError(field, f"must be a finite number, got {shown(value)}")
    if low is not None and (x < low or (low_open and x == low)):
        raise InputError(field, f"must be {'>' if low_open else '≥'} {low:g}, got {x:g}")
    if high is not None and (x > high or (high_open and x == high)):
        raise InputError(field, f"must be {'<' if high_open else '≤'} {high:g}, got {x:g}")
    return x


def rows(field: str, value: object, width: int = 2, limit: int = MAX_TABLE_ROWS) -> list[tuple]:
    """`value` as a list of `width`-tuples (the numbers still to check), at most `limit` rows."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or not hasattr(value, "__iter__"):
        raise InputError(field, f"must be a table of rows of {width} numbers, got {shown(value)}")
    if len(value) > limit:
        raise InputError(field, f"has {len(value)} rows; at most {limit}")
    out = []
    for i, row in enumerate(value):
        if isinstance(row, (str, bytes)) or not hasattr(row, "__len__") or len(row) != width:
            raise InputError(f"{field}[{i}]", f"must be a row of {width} numbers, got {shown(row)}")
        out.append(tuple(row))
    return out
