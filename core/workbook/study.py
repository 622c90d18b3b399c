"""Sweeps and tolerances over a workbook: its variables in, each requirement's margin out.

The workbook is seen as one calculator (core.workbook.solving.as_calculator: fields = its plain
variables, outputs = the requirements' margins in SI), so a sweep is core.sweep's points and table,
and the worst case core.tolerance's corners (and optimiser where a margin is not monotone). A margin is
how far a requirement holds (negative: fails); a requirement holds in the worst case when its
lowest margin over the tolerance box is not negative. Cards that read no varied variable are
solved once (core.workbook caches each card's solve by its entries).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from .. import sweep as sweeps
from .. import tolerance
from ..errors import InputError
from .book import Workbook
from .solving import as_calculator, studied


def run_sweep(
    wb: Workbook,
    varies: Sequence[str],
    outputs: Sequence[str] = (),
    progress: Callable[[int, int], None] | None = None,
    cancelled: Callable[[], bool] | None = None,
) -> sweeps.Sweep:
    """Sweep one variable (a table) or two (a grid): each point solves the whole workbook, through
    core.sweep.run's loop. What is checked here first is said in a workbook's words (a variable,
    a requirement), not a calculator's (an input, an output)."""
    calc = as_calculator(wb)
    if not calc.fields:
        raise InputError(
            "--vary", "the workbook has no plain variable (a number or quantity) to sweep", wb.source
        )
    specs = []
    for text in varies:
        name = str(text).partition("=")[0].strip()
        if name in wb.variables and name not in {f.name for f in calc.fields}:
            raise InputError(name, "is a reference or text; only a number or quantity variable can be swept")
        specs.append(sweeps.parse_vary(calc, text))
    if not 1 <= len(specs) <= 2:
        raise InputError("--vary", f"sweep one variable (a table) or two (a grid), not {len(specs)}")
    if len(specs) == 2 and specs[0].name == specs[1].name:
        raise InputError(specs[0].name, "is varied twice")
    known = [o.name for o in calc.outputs if o.name not in sweeps.STATS]
    for name in outputs:
        if name not in known:
            raise InputError(name, f"is not a requirement of the workbook (requirements: {', '.join(known)})")
    # every requirement a column, even one with no margin (a comparison of text): named, not picked
    # by the first point's numbers as a calculator's outputs are
    chosen = list(outputs) or known
    return sweeps.run(calc, {}, specs, chosen, progress=progress, cancelled=cancelled)


@dataclass
class WorstCase:
    """Each requirement's margin at the nominal values and at its worst over the tolerance box."""

    calculator: Any  # core.declarations.Calculator of the workbook
    spread: tolerance.Spread | None
    nominal: dict[str, float]  # requirement key -> margin (SI)
    notes: list[str]

    def holds(self, key: str) -> bool | None:
        """Whether the requirement holds at its worst (None: its margin could not be found)."""
        if self.spread is None or key not in self.spread.outputs:
            return None if key not in self.nominal else self.nominal[key] >= 0
        spread = self.spread.outputs[key]
        if spread.infeasible:  # a corner where the robot could not be solved fails the requirement
            return False
        return spread.low >= 0

    def low(self, key: str) -> float | None:
        if self.spread is None or key not in self.spread.outputs:
            return self.nominal.get(key)
        return self.spread.outputs[key].low

    def as_json(self) -> dict[str, Any]:
        out = {}
        for o in self.calculator.outputs:
            if o.name in sweeps.STATS:
                continue
            s = self.spread.outputs.get(o.name) if self.spread else None
            out[o.name] = {
                "nominal_margin": self.nominal.get(o.name),
                "worst_margin": self.low(o.name),
                "holds_in_worst_case": self.holds(o.name),
                "spread": s.as_json() if s else None,
            }
        return {
            "tolerances": [t.entry for t in self.spread.tolerances] if self.spread else [],
            "requirements": out,
            "notes": self.notes,
            "cost": self.spread.cost.as_json() if self.spread else None,
        }


def worst_case(wb: Workbook, cancelled: Callable[[], bool] | None = None) -> WorstCase:
    """Each requirement's worst margin over the variables' tolerances (core.tolerance: corners,
    the optimiser where a margin is not monotone; σ first-order, so no Monte Carlo runs)."""
    calc = as_calculator(wb)
    entries = {v.name: v.entry for v in wb.variables.values() if v.name in {f.name for f in calc.fields}}
    try:
        _, values, tols, notes = tolerance.parse(calc, entries)
    except InputError as exc:
        raise exc.from_source(wb.source) from None
    notes = notes + [  # never dropped silently
        f"{v.name}: its tolerance is not analysed ({v.unit} is a unit no Gearhead field takes)"
        for v in wb.variables.values()
        if v.tolerance and not studied(v)
    ]
    nominal = sweeps.evaluate(calc, values)
    if not tols:
        notes = notes + ['no variable carries a tolerance (write e.g. robot_mass = "125 lb ± 5 lb")']
        return WorstCase(calc, None, dict(nominal.outputs), notes)
    result = tolerance.spread(calc, values, tols, method="first-order", cancelled=cancelled)
    return WorstCase(calc, result, dict(nominal.outputs), notes + list(result.notes))
