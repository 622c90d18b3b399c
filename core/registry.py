"""The calculators Gearhead knows: every module in core/calculators that defines CALCULATOR."""

from __future__ import annotations

import importlib
import pkgutil
from functools import lru_cache

from .declarations import Calculator, check, check_links
from .errors import InputError, shown

# Where each calculator lives in the app: areas in the order of the top tab strip, each with its
# calculators in tab order. Every calculator must be in exactly one area (checked at load), so a
# new calculator changes only its own area's strip, never another area's.
# The tab titles are the calculators' own (checked when the registry loads): the app draws its
# strips from this table without importing thirteen modules before its first frame.
AREAS: dict[str, tuple[str, tuple[str, ...]]] = {
    "gearing": ("Motors", ("motor", "gear_ratio", "ratio_distance", "ratio_finder", "motors")),
    "mechanisms": ("Mechanisms", ("lead_screw", "drivetrain", "sprint", "elevator", "arm", "intake")),
    "structure": ("Structure", ("beam", "chain_belt", "gear_clearance")),
    "pneumatics": ("Pneumatics", ("pneumatics", "pneumatic_linkage")),
    "shooters": ("Shooters", ("projectile", "flywheel", "trebuchet")),
}
TITLES = {
    "motor": "Motor",
    "motors": "Motor comparison",
    "intake": "Intake",
    "gear_ratio": "Gear ratio",
    "ratio_distance": "Ratio & distance",
    "lead_screw": "Lead screw",
    "drivetrain": "Drivetrain",
    "sprint": "Drivetrain sprint",
    "beam": "Beam",
    "chain_belt": "Chain/belt C-C",
    "gear_clearance": "Gear clearance",
    "pneumatics": "Pneumatics",
    "pneumatic_linkage": "Pneumatic linkage",
    "projectile": "Projectile",
    "flywheel": "Flywheel",
    "trebuchet": "Trebuchet",
    "ratio_finder": "Ratio finder",
    "elevator": "Elevator",
    "arm": "Arm",
}
ORDER = tuple(cid for _, ids in AREAS.values() for cid in ids)


def area_of(calc_id: str) -> str:
    return next(area for area, (_, ids) in AREAS.items() if calc_id in ids)


@lru_cache(maxsize=1)
def calculators() -> dict[str, Calculator]:
    from . import calculators as package

    found: dict[str, Calculator] = {}
    for info in pkgutil.iter_modules(package.__path__):
        module = importlib.import_module(f"{package.__name__}.{info.name}")
        calc = getattr(module, "CALCULATOR", None)
        if isinstance(calc, Calculator):
            found[calc.id] = calc
    unplaced = sorted(set(found) - set(ORDER))
    if unplaced or len(set(ORDER)) != len(ORDER):
        raise RuntimeError(
            f"core/registry.py AREAS must name every calculator exactly once "
            f"(not placed: {', '.join(unplaced) or 'none'})"
        )
    for calc in found.values():
        check(calc)
    check_links(found)
    for cid, calc in found.items():
        if TITLES.get(cid) != calc.title:
            raise RuntimeError(
                f"core/registry.py TITLES[{cid!r}] must be the calculator's title {calc.title!r}"
            )
    return {cid: found[cid] for cid in ORDER if cid in found}


def get(calc_id: str) -> Calculator:
    """One calculator; before the whole registry has loaded, only its own module is imported
    (the app's first card, the CLI's one solve)."""
    if calculators.cache_info().currsize == 0 and calc_id in ORDER:
        module = importlib.import_module(f"{__package__}.calculators.{calc_id}")
        calc = getattr(module, "CALCULATOR", None)
        if isinstance(calc, Calculator) and calc.id == calc_id:
            return calc
    try:
        return calculators()[calc_id]
    except KeyError:
        raise InputError(
            "calculator", f"unknown calculator {shown(calc_id)} (known: {', '.join(calculators())})"
        ) from None
