"""The one way a card's entries are solved: the app's card and `gearhead solve` both call `solve`.

Entries as typed (a value may carry `± tolerance`), the units the user chose for some results and
the units preference go in; a Solved comes out: the solution at the nominal entries, the spread
over the tolerances (or None), the notes on tolerances, and the unit each result is shown in.
A plain solve never imports the tolerance module (a command starts as fast without it).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from contextlib import nullcontext
from dataclasses import dataclass, field
from typing import Any

from . import model, unit_systems
from .declarations import Calculator
from .errors import InputError
from .registry import get
from .sim.integrate import budget

# A tolerance's Monte Carlo stops here when a card asks for it (a slow scene would keep the card
# busy); the CLI waits as long as its samples take.
CARD_SPREAD_SECONDS = 2.0


@dataclass
class Solved:
    solution: model.Solution  # at the nominal entries (what model.solve gives for them)
    spread: Any = None  # core.tolerance.Spread when an entry carries a tolerance
    notes: list[str] = field(default_factory=list)  # why a tolerance was dropped, what it covers
    units: dict[str, str] = field(default_factory=dict)  # output -> unit it is shown in, when not its own


def has_tolerance(entries: Mapping[str, Any]) -> bool:
    return any(isinstance(v, str) and ("±" in v or "+-" in v or "+/-" in v) for v in entries.values())


def solve(
    calculator: Calculator | str,
    entries: Mapping[str, Any],
    chosen_units: Mapping[str, str] | None = None,
    system: str = "calculator",
    *,
    estimate: str = "now",
    method: str = "auto",
    samples: int | None = None,
    seed: int | None = None,
    spread_seconds: float | None = None,
    cancelled: Callable[[], bool] | None = None,
) -> Solved:
    """Solve `entries`; raises InputError (a wrong entry, named) or integrate.Cancelled (when
    `cancelled()` turns true between integration steps or tolerance samples).

    chosen_units: output -> unit the user picked (CLI --unit, Enter on a result); they override
    the preference `system` (core.unit_systems). estimate="later": a simulated card's error
    estimate is a second step (model.finish_estimate), never with tolerances (their spread needs
    each estimate)."""
    calc = get(calculator) if isinstance(calculator, str) else calculator
    if not isinstance(entries, Mapping):
        raise InputError(
            "inputs", f"must be a mapping of field names to entries, got {type(entries).__name__}"
        )
    units = {**unit_systems.display_units(calc, system, entries), **(chosen_units or {})}
    with budget(cancel=cancelled) if cancelled is not None else nullcontext():
        if not has_tolerance(entries):
            return Solved(model.solve(calc.id, entries, units, estimate), units=units)
        from . import tolerance  # only now: a plain solve does not pay its import

        options = {"samples": samples, "seed": seed}
        solution, spread, notes = tolerance.solve(
            calc.id,
            entries,
            units,
            method,
            cancelled=cancelled,
            budget_s=spread_seconds,
            **{k: v for k, v in options.items() if v is not None},
        )
    if spread is None:  # every tolerance dropped (zero, unused field): the notes say why
        solution.warnings.extend(notes)
    return Solved(solution, spread, notes, units)
