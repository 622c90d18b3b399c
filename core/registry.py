"""The calculators Gearhead knows: every module in core/calculators that defines CALCULATOR."""

from __future__ import annotations

import importlib
import pkgutil
from functools import lru_cache

from .errors import InputError
from .model import Calculator

# Tab and listing order (DESIGN.md's list); a calculator not named here sorts last.
ORDER = ("motor", "gear_ratio", "lead_screw", "drivetrain", "beam", "projectile", "chain_belt",
         "gear_clearance", "ratio_distance", "pneumatics", "pneumatic_linkage", "flywheel",
         "trebuchet")


@lru_cache(maxsize=1)
def calculators() -> dict[str, Calculator]:
    from . import calculators as package

    found: dict[str, Calculator] = {}
    for info in pkgutil.iter_modules(package.__path__):
        module = importlib.import_module(f"{package.__name__}.{info.name}")
        calc = getattr(module, "CALCULATOR", None)
        if isinstance(calc, Calculator):
            found[calc.id] = calc
    rank = {cid: i for i, cid in enumerate(ORDER)}
    return dict(sorted(found.items(), key=lambda kv: (rank.get(kv[0], len(ORDER)), kv[0])))


def get(calc_id: str) -> Calculator:
    try:
        return calculators()[calc_id]
    except KeyError:
        raise InputError("calculator", f"unknown calculator {calc_id!r} (known: {', '.join(calculators())})") from None
