"""Generates the stored SI factors of the units Gearhead declares (core/unit_factors.json, read by
core.units.stored_factor), so that a solve with bare numbers (the CLI in a script's loop) never pays
for pint's registry (~150 ms).

pint stays the source of truth: tests/test_unit_factors.py checks every stored factor against pint
and that every unit a calculator declares is stored. Regenerate after adding a unit:

    .venv/bin/python -m gearhead.core.unit_factors

A tool on top of the registry (it reads every calculator's declaration); nothing in core imports it.
"""

from __future__ import annotations

import json

from .registry import calculators
from .unit_systems import TO_IMPERIAL, TO_METRIC
from .units import COMMON_UNITS, FACTOR_TABLE, SI_UNITS, registry, stored_factors


def declared_units() -> set[tuple[str, str]]:
    """(unit, kind) of every field, output and plot axis, every unit of the result-unit ring and of
    the units preference."""
    found = set()
    for calc in calculators().values():
        for f in calc.fields:
            if f.kind.with_unit and f.unit:
                found.add((f.unit, f.quantity))
        for o in calc.outputs:
            if o.unit:
                found.add((o.unit, o.quantity))
        for p in calc.plots:
            found.update(
                {(p.x_unit, p.x_quantity), (p.y_unit, p.y_quantity)}
                - {("", p.x_quantity), ("", p.y_quantity)}
            )
    for kind, ring in COMMON_UNITS.items():
        found.update((u, kind) for u in ring if u)
    for table in (TO_METRIC, TO_IMPERIAL):
        found |= {(table[unit], kind) for unit, kind in found if unit in table}
    return found


# Unit names people type beside the declared ones, by kind ("20 inches"; "5 lbs" is not one: pint
# has no lbs). Each is stored under its kind and every kind of the same SI unit (pressure's under
# modulus too); one pint does not read as that kind is left out, so such an entry still goes to
# pint (and is refused there with its message). Names pint reads as something else ("amps" is
# attometre per picosecond, "cfm" centi-femto-metre, "mil" an angle) are not listed.
TYPED_UNITS: dict[str, str] = {
    "length": "inch inches foot feet yd yard um µm micron meter meters metre metres millimeter "
    "millimeters centimeter km mi mile miles",
    "force": "newton newtons kgf ozf",
    "torque": "lbf*ft lbf*in ozf*in mN*m kN*m",
    "mass": "pound pounds gram grams kilogram kilograms ounce ounces",
    "time": "second seconds sec minute minutes hour h",
    "speed": "mm/s kph ft/min",
    "angular_speed": "rps",
    "angle": "degree degrees radian radians revolution turn",
    "current": "amp ampere",
    "voltage": "volt volts mV kV",
    "resistance": "ohms",
    "pressure": "bar mbar Pa MPa GPa atm",
    "power": "watt watts",
    "energy": "lbf*ft Wh",
    "volume": "mL liter liters litre cm**3 mm**3 ft**3 gal",
    "inertia": "lb*ft**2 g*cm**2 kg*cm**2",
    "dimensionless": "percent",
    "acceleration": "in/s**2",
    "flow": "L/min",
    "area": "cm**2",
    "area_moment": "cm**4",
}


def generate() -> dict[str, float]:
    """Every declared unit's factor, and every typed unit's (TYPED_UNITS) under each kind it
    converts to, from pint (the same computation as core.units.factor)."""
    import pint

    # a fresh registry: the shared one, once it has converted other units, can give a factor one
    # rounding step apart (in*lbf: ...167 vs ...1671), which made the equality test order-dependent
    ureg = registry.__wrapped__()
    out = {}
    for unit, kind in sorted(declared_units()):
        out[f"{kind}|{unit}"] = float(
            ureg.Quantity(1.0, unit).to(SI_UNITS[kind] or "dimensionless").magnitude
        )
    for group, names in TYPED_UNITS.items():
        kinds = [kind for kind, si in SI_UNITS.items() if si == SI_UNITS[group]]
        for unit in names.split():
            for kind in kinds:
                if f"{kind}|{unit}" in out:
                    continue
                try:
                    value = float(ureg.Quantity(1.0, unit).to(SI_UNITS[kind] or "dimensionless").magnitude)
                except (pint.errors.PintError, ValueError, AttributeError, TypeError):
                    continue  # not a name pint knows as this kind
                out[f"{kind}|{unit}"] = value
    return out


if __name__ == "__main__":
    from gearhead.core import atomic_file  # every write goes through it (a developer's too)

    atomic_file.write_text(
        FACTOR_TABLE, json.dumps(generate(), indent=0, sort_keys=True) + "\n", overwrite=True
    )
    print(f"wrote {len(stored_factors.__wrapped__())} factors to {FACTOR_TABLE}")
