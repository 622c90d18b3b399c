"""Units at the boundary: parse what a user typed into SI, format SI for display.

pint is imported lazily (first call), so importing this module costs nothing at start-up.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache

from .errors import InputError

# Quantity kind -> the SI unit core works in (written as DESIGN.md's JSON shows them).
SI_UNITS: dict[str, str] = {
    "dimensionless": "",
    "length": "m",
    "area": "m**2",
    "volume": "m**3",
    "area_moment": "m**4",
    "mass": "kg",
    "time": "s",
    "force": "N",
    "torque": "N*m",
    "energy": "J",
    "power": "W",
    "speed": "m/s",
    "angular_speed": "rad/s",
    "angle": "rad",
    "current": "A",
    "voltage": "V",
    "resistance": "ohm",
    "pressure": "Pa",
    "modulus": "Pa",
    "torque_constant": "N*m/A",
    "inertia": "kg*m**2",
    "flow": "m**3/s",
    "density": "kg/m**3",
    "acceleration": "m/s**2",
    "reciprocal_length": "1/m",
    # WPILib feedforward and feedback gains (elevator: per metre; arm: per radian)
    "voltage_per_speed": "V*s/m",
    "voltage_per_angular_speed": "V*s/rad",
    "voltage_per_acceleration": "V*s**2/m",
    "voltage_per_angular_acceleration": "V*s**2/rad",
    "voltage_per_length": "V/m",
    "voltage_per_angle": "V/rad",
}

_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")


@lru_cache(maxsize=1)
def registry():
    """The shared pint registry (built once, on first use)."""
    import pint

    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("links = []")  # placeholder dimensionless counts read naturally
    return ureg


@lru_cache(maxsize=256)
def factor(unit: str, kind: str) -> float:
    """Multiply a value in `unit` by this to get SI for `kind` (cached: pint is slow)."""
    if unit in ("", "1"):
        if kind != "dimensionless":
            raise ValueError(f"a {kind.replace('_', ' ')} needs a unit")
        return 1.0
    from .unit_factors import lookup

    known = lookup(unit, kind)  # every declared unit, generated from pint: no registry to build
    if known is not None:
        return known
    ureg = registry()
    q = ureg.Quantity(1.0, unit)
    return float(q.to(SI_UNITS[kind] or "dimensionless").magnitude)


def parse(text: str | float | int, unit: str, kind: str, field: str) -> float:
    """SI value of what the user typed for `field`; a bare number is in `unit`.

    Raises InputError naming the field, what was typed and the quantity expected.
    """
    if isinstance(text, bool):
        raise InputError(field, f"expected a {_kind_words(kind)}, got {text!r}")
    if isinstance(text, (int, float)):
        value = float(text) * factor(unit, kind)
    else:
        s = str(text).strip()
        if not s:
            raise InputError(field, f"is empty; enter a {_kind_words(kind)}")
        if _NUMBER.match(s):
            value = float(s) * factor(unit, kind)
        else:
            value = _parse_with_unit(s, kind, field)
    if not math.isfinite(value):
        raise InputError(field, f"{text!r} is not a finite number")
    return value


def _parse_with_unit(s: str, kind: str, field: str) -> float:
    import pint

    ureg = registry()
    try:
        q = ureg.Quantity(s.replace("·", "*").replace("°", " deg"))
    except Exception as exc:  # pint's parser raises many types on junk text; all mean "unreadable"
        raise InputError(field, f"cannot read {s!r} as a {_kind_words(kind)} ({_short(exc)})") from None
    if not isinstance(q, ureg.Quantity):  # e.g. a bare expression like "2*3"
        q = ureg.Quantity(q)
    try:
        finite = math.isfinite(float(q.magnitude))
    except (TypeError, ValueError, OverflowError):
        finite = False
    if not finite:
        raise InputError(field, f"{s!r} is not a finite number")
    target = SI_UNITS[kind] or "dimensionless"
    try:
        return float(q.to(target).magnitude)
    except pint.errors.DimensionalityError:
        raise InputError(
            field, f"{s!r} is not a {_kind_words(kind)} (expected units like {example_unit(kind)})"
        ) from None
    except (TypeError, ValueError, OverflowError) as exc:
        raise InputError(field, f"cannot read {s!r}: {_short(exc)}") from None


def _short(exc: Exception) -> str:
    msg = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    return msg[:80]


def _kind_words(kind: str) -> str:
    return "number" if kind == "dimensionless" else kind.replace("_", " ")


_EXAMPLES = {
    "length": "mm, in, ft", "force": "N, lbf", "torque": "N*m, in*lbf", "speed": "m/s, ft/s",
    "angular_speed": "rpm, rad/s", "angle": "deg, rad", "current": "A", "voltage": "V",
    "pressure": "psi, kPa", "mass": "kg, lb", "volume": "cc, in**3, L", "time": "s, min",
    "power": "W, hp", "resistance": "ohm", "modulus": "GPa, psi", "dimensionless": "a plain number, %",
}


# Units a results table cycles through for each kind (the calculator's own unit comes first).
COMMON_UNITS: dict[str, tuple[str, ...]] = {
    "length": ("mm", "cm", "m", "in", "ft"),
    "area": ("mm**2", "in**2", "m**2"),
    "volume": ("cc", "in**3", "L", "m**3"),
    "area_moment": ("mm**4", "in**4", "m**4"),
    "mass": ("g", "kg", "lb"),
    "time": ("ms", "s", "min"),
    "force": ("N", "lbf", "kN"),
    "torque": ("N*m", "in*lbf", "ft*lbf"),
    "energy": ("J", "ft*lbf", "kJ"),
    "power": ("W", "hp", "kW"),
    "speed": ("m/s", "ft/s", "in/s", "km/h", "mph"),
    "angular_speed": ("rpm", "rad/s", "deg/s"),
    "angle": ("deg", "rad"),
    "current": ("A", "mA"),
    "voltage": ("V",),
    "resistance": ("ohm", "mohm"),
    "pressure": ("psi", "kPa", "bar", "Pa"),
    "modulus": ("GPa", "MPa", "ksi", "psi"),
    "inertia": ("kg*m**2", "lb*in**2"),
    "flow": ("L/s", "ft**3/min"),
    "density": ("kg/m**3", "g/cc"),
    "acceleration": ("m/s**2", "ft/s**2"),
    "dimensionless": ("", "%"),
}


def next_unit(current: str, kind: str, home: str) -> str:
    """The unit after `current` in the ring of a kind's common units, which starts at the output's
    own unit `home`: Enter on a result walks the whole ring (mm → cm → m → in → ft → mm) instead of
    bouncing between the first two."""
    ring = (home,) + tuple(u for u in COMMON_UNITS.get(kind, ()) if u != home)
    if current not in ring:
        return ring[0]
    return ring[(ring.index(current) + 1) % len(ring)]


def check_unit(unit: str, kind: str, name: str) -> str:
    """`unit` if it can show a `kind`, else an InputError naming `name`."""
    try:
        factor(unit, kind)
    except Exception:  # unknown unit or wrong dimension: both mean "cannot show it in that"
        raise InputError(name, f"cannot show a {_kind_words(kind)} in {unit!r} "
                               f"(units like {example_unit(kind)})") from None
    return unit


def example_unit(kind: str) -> str:
    return _EXAMPLES.get(kind, SI_UNITS.get(kind, "") or "a plain number")


def to_unit(value_si: float, unit: str, kind: str) -> float:
    return value_si / factor(unit, kind)


def format_number(x: float, sig: int = 5) -> str:
    """A compact, human number: 5 significant figures, no exponent for everyday sizes."""
    if x == 0 or not math.isfinite(x):
        return "0" if x == 0 else str(x)
    mag = abs(x)
    if 1e-4 <= mag < 1e7:
        decimals = max(0, sig - 1 - int(math.floor(math.log10(mag))))
        s = f"{x:.{decimals}f}"
        if "." in s:
            s = s.rstrip("0").rstrip(".")
        return s
    return f"{x:.{sig - 1}e}"


def format_quantity(value_si: float, unit: str, kind: str) -> str:
    """'187.33 mm' from 0.18733 (m) and display unit 'mm'."""
    v = to_unit(value_si, unit, kind)
    return f"{format_number(v)} {unit}".rstrip()
