"""The current-limit grid: for every pair of a stator and a supply current limit (per motor), the
reduction that reaches the goal first from rest at full voltage, with its time, peak currents and
energy; the cell to pick is the fastest whose peak supply current stays within a budget.

    for each supply limit I_sup (one numpy batch each; the stator limits and the candidate ratios
    broadcast against each other, (stators × 1) with (1 × ratios)):
        T(I_st, G) = motion.batch_times (exponential Euler per candidate, the arrival on a cubic)
        G*(I_st, I_sup) = argmin over CANDIDATES ratios log-spaced over ±1.5 decades about the
        characteristic ratio (motion.characteristic_n)                                        (LG1)
    at each cell's G*: the accurate move (motion.move, the scene's integrator) for the time and the
    energy, motion.extremes for the peak stator and supply currents and the lowest bus voltage  (LG2)
    pick = the cell with the least time among those whose peak supply current ≤ the budget      (LG3)
The ratio is the best of the candidates, not refined (their spacing is 6 %; the time's curve is flat
there: the time at the next candidate differs by well under 1 %).
"""

from __future__ import annotations

import math
from typing import Any

from ..errors import InputError
from .scene import SimRun

CANDIDATES = 120
MAX_CELLS = 400


def axis(lo: float, hi: float, step: float, prefix: str) -> list[float]:
    """lo, lo + step, ... ≤ hi: the limits of one axis (fields prefix_max, prefix_step)."""
    if hi < lo:
        raise InputError(f"{prefix}_max", f"is below the range's start ({hi:.4g} A < {lo:.4g} A)")
    count = math.floor((hi - lo) / step + 1e-9) + 1
    if count > 40:
        raise InputError(f"{prefix}_step", f"makes {count} limits (more than 40): widen the step")
    return [lo + i * step for i in range(count)]


def run(
    make_setup,
    values: dict,
    stators: list[float],
    supplies: list[float],
    budget: float,
    rtol: float,
    length_scale: float,
) -> SimRun:
    """make_setup(values, ratio, xp) -> motion.Setup (the calculator's own setup)."""
    import numpy as np

    from . import motion
    from .motor_limits import _Array

    if len(stators) * len(supplies) > MAX_CELLS:
        raise InputError("stator_step", f"the grid has more than {MAX_CELLS} cells: widen a step")
    on = frozenset(values["effects"]) | {"stator_limit", "supply_limit"}
    base = {**values, "effects": on}
    probe = make_setup({**base, "stator_current_limit": max(stators), "supply_current_limit": max(supplies)})
    G_char = motion.characteristic_n(probe.mech) * length_scale
    ratios = np.geomspace(G_char * 10**-1.5, G_char * 10**1.5, CANDIDATES)
    st = np.asarray(stators, dtype=float)[:, None]
    rows: list[dict[str, Any]] = []
    nfev = 0
    for sup in supplies:
        batch = make_setup(
            {**base, "stator_current_limit": st, "supply_current_limit": float(sup)},
            ratios[None, :],
            _Array(),
        )
        times = np.asarray(motion.batch_times(batch), dtype=float) * np.ones((len(stators), CANDIDATES))
        for i, I_st in enumerate(stators):
            row: dict[str, Any] = {"stator_limit": I_st, "supply_limit": float(sup)}
            ok = np.isfinite(times[i])
            if not ok.any():
                rows.append(row)  # no ratio moves the load with these limits: an empty row
                continue
            G_best = float(ratios[int(np.nanargmin(np.where(ok, times[i], np.nan)))])  # (LG1)
            cell = make_setup(
                {**base, "stator_current_limit": I_st, "supply_current_limit": float(sup)}, G_best
            )
            try:
                mv = motion.move(cell, rtol)  # (LG2)
            except InputError:
                rows.append(row)
                continue
            nfev += mv.nfev
            ex = motion.extremes(cell, mv.max_speed)
            row.update(
                ratio=G_best,
                time=mv.time,
                peak_stator_current=ex["peak_stator_current"],
                peak_supply_current=ex["peak_supply_current"],
                energy=abs(mv.energy),
            )
            rows.append(row)
    within = [r for r in rows if "time" in r and r["peak_supply_current"] <= budget * (1 + 1e-12)]
    warnings = []
    values_out: dict[str, Any] = {"grid_cells": len(rows)}
    if within:
        pick = min(within, key=lambda r: r["time"])  # (LG3)
        pick["pick"] = "◆"
        values_out.update(
            pick_stator_limit=pick["stator_limit"],
            pick_supply_limit=pick["supply_limit"],
            best_ratio=pick["ratio"],
            time_to_goal=pick["time"],
            peak_stator_current=pick["peak_stator_current"],
            peak_supply_current=pick["peak_supply_current"],
            energy=pick["energy"],
        )
    else:
        warnings.append(
            f"No cell keeps the peak supply current within the budget of {budget:.4g} A per motor."
        )
    if not any("time" in r for r in rows):
        raise InputError("stator_min", "no pair of limits in the grid moves the load to the goal")
    out = SimRun(values_out, {"time_to_goal": values_out.get("time_to_goal", 0.0)}, nfev, warnings)
    out.tables = {"limit_grid": rows}  # read by the calculator's compute (a SimRun has no tables)
    return out


def fields() -> tuple:
    from ..fields import Field

    def amps(name, label, default, help, min_=0.0):
        return Field(
            name,
            label,
            "current",
            "A",
            default=default,
            min=min_,
            min_exclusive=True,
            max=2000,
            modes=MODES,
            help=help,
        )

    return (
        amps("stator_min", "Stator limits from", 20, "The grid's first stator current limit (per motor)."),
        amps("stator_max", "Stator limits to", 120, "The grid's last stator current limit (per motor)."),
        amps("stator_step", "Stator limit step", 10, "Between the grid's stator limits."),
        amps("supply_min", "Supply limits from", 20, "The grid's first supply current limit (per motor)."),
        amps("supply_max", "Supply limits to", 80, "The grid's last supply current limit (per motor)."),
        amps("supply_step", "Supply limit step", 10, "Between the grid's supply limits."),
        amps(
            "supply_budget",
            "Supply budget",
            60,
            "The cell picked is the fastest whose peak supply current "
            "per motor stays within this (e.g. what the breaker and the battery allow the mechanism).",
        ),
    )


MODES = ("limit_grid",)


def outputs() -> tuple:
    from ..declarations import Output

    return (
        Output(
            "pick_stator_limit",
            "Pick: stator limit",
            "current",
            "A",
            help="The fastest cell within the supply budget (LG3).",
            equation="(LG3)",
        ),
        Output(
            "pick_supply_limit",
            "Pick: supply limit",
            "current",
            "A",
            help="The fastest cell within the supply budget (LG3).",
            equation="(LG3)",
        ),
        Output(
            "grid_cells", "Grid cells", help="Stator × supply limit pairs solved (LG1).", equation="(LG1)"
        ),
    )


def table():
    from ..declarations import Column, Table

    return Table(
        "limit_grid",
        "Current-limit grid: the fastest ratio per stator × supply limit",
        (
            Column("stator_limit", "Stator", "current", "A", width=8),
            Column("supply_limit", "Supply", "current", "A", width=8),
            Column("ratio", "Best ratio", width=10),
            Column("time", "Time", "time", "s", width=9),
            Column("peak_stator_current", "Peak stator", "current", "A", width=11),
            Column("peak_supply_current", "Peak supply", "current", "A", width=11),
            Column("energy", "Energy", "energy", "J", width=9),
            Column("pick", "Pick", width=4),
        ),
        modes=MODES,
    )
