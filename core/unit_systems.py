"""Unit preference for results: each calculator's own units, imperial, metric, or as entered.

A calculator declares a display unit per output; a preference maps it to the matching unit of
the chosen system (in -> mm, psi -> kPa, N*m -> in*lbf …). Units that both systems use (rpm, A,
V, s, deg, %, W) never change. A test checks every mapping against pint (same dimension).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

from .errors import InputError
from .units import check_unit

SYSTEMS = ("calculator", "imperial", "metric", "as_entered")
SYSTEM_LABELS = {
    "calculator": "each calculator's own units",
    "imperial": "imperial (in, lbf, psi)",
    "metric": "metric (mm, N, kPa)",
    "as_entered": "the units you type into the fields",
}

TO_METRIC = {
    "in": "mm",
    "ft": "m",
    "mi": "km",
    "lbf": "N",
    "kip": "kN",
    "in*lbf": "N*m",
    "ft*lbf": "N*m",
    "ozf*in": "N*m",
    "psi": "kPa",
    "ksi": "MPa",
    "lb": "kg",
    "oz": "g",
    "ft/s": "m/s",
    "in/s": "mm/s",
    "mph": "km/h",
    "in**2": "mm**2",
    "in**3": "cc",
    "ft**3": "L",
    "in**4": "mm**4",
    "lb*in**2": "kg*m**2",
    "lb*ft**2": "kg*m**2",
    "ft**3/min": "L/s",
    "ft/s**2": "m/s**2",
    "in*lbf/A": "N*m/A",
    "lb/in**3": "g/cc",
    "lb/ft**3": "kg/m**3",
    "1/in": "1/mm",
}
TO_IMPERIAL = {
    "mm": "in",
    "cm": "in",
    "m": "ft",
    "km": "mi",
    "N": "lbf",
    "kN": "kip",
    "N*m": "in*lbf",
    "N*cm": "in*lbf",
    "kPa": "psi",
    "Pa": "psi",
    "bar": "psi",
    "MPa": "ksi",
    "GPa": "ksi",
    "kg": "lb",
    "g": "oz",
    "m/s": "ft/s",
    "mm/s": "in/s",
    "km/h": "mph",
    "mm**2": "in**2",
    "m**2": "ft**2",
    "cc": "in**3",
    "L": "in**3",
    "m**3": "ft**3",
    "mm**4": "in**4",
    "m**4": "in**4",
    "kg*m**2": "lb*in**2",
    "L/s": "ft**3/min",
    "m/s**2": "ft/s**2",
    "N*m/A": "in*lbf/A",
    "kg/m**3": "lb/ft**3",
    "g/cc": "lb/in**3",
    "J": "ft*lbf",
    "kJ": "ft*lbf",
    "1/m": "1/in",
    "1/mm": "1/in",
}
# the number, then what follows it is the unit the user typed ("3.5 in", "-2e3 N*m")
_TYPED = re.compile(r"^\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*(\S.*?)\s*$")


def system_unit(unit: str, system: str) -> str:
    """The unit of `system` that shows what `unit` shows (the same unit if it has no other)."""
    if system == "metric":
        return TO_METRIC.get(unit, unit)
    if system == "imperial":
        return TO_IMPERIAL.get(unit, unit)
    return unit


def typed_units(fields, entries: Mapping[str, Any]) -> dict[str, str]:
    """Quantity kind -> the unit the user typed for a field of that kind (the first one found),
    for the "as entered" preference. Bare numbers and expressions say nothing about a unit."""
    found: dict[str, str] = {}
    for f in fields:
        if not f.kind.with_unit or f.quantity in found or f.quantity == "dimensionless":
            continue
        match = _TYPED.match(str(entries.get(f.name, "")))
        if not match:
            continue
        unit = match.group(1)
        try:
            check_unit(unit, f.quantity, f.name)
        except InputError:
            continue
        found[f.quantity] = unit
    return found


def display_units(calc, system: str, entries: Mapping[str, Any]) -> dict[str, str]:
    """Display unit of every numeric output of `calc` under a preference (outputs whose unit the
    preference leaves alone are left out)."""
    if system not in SYSTEMS or system == "calculator":
        return {}
    typed = typed_units(calc.fields, entries) if system == "as_entered" else {}
    out = {}
    for o in calc.outputs:
        if not o.unit:
            continue
        unit = typed.get(o.quantity, o.unit) if system == "as_entered" else system_unit(o.unit, system)
        if unit != o.unit:
            out[o.name] = unit
    return out
