"""The current-limit grid: for every pair of a stator and a supply current limit (per motor), the
reduction that reaches the goal first from rest at full voltage, with its time, peak currents and
energy; the cell to pick is the fastest whose peak supply current stays within a budget. The grid
(its axes, the pick, the table and the heat map: `grid`, `run_cells`) is shared by every calculator
that offers it; a calculator gives its cells. The elevator (a constant load) and the arm (gravity's
torque varying with the angle) give their setup and the screen below solves the cells
(mechanism_cells, run_mode); the flywheel gives its own ((FW6)-(FW8): the spin-up to a speed).

    G_hold(I_st, I_sup) = L·load/(η·N·Kt·(I0 − i_f)), the least ratio whose motors at rest beat the
        most the load resists on the path (I0 the current at rest under the limits, the same at
        every ratio; L the length per motor radian at n = 1): the cell's candidates start above it;
        none holds when I0 ≤ i_f or G_hold > MAX_RATIO: the cell "cannot hold"              (LG0)
    for each supply limit I_sup (one numpy batch each; the stator limits and the candidate ratios
    broadcast against each other, (stators × 1) with (1 × ratios)):
        T(I_st, G) = motion.batch_times (exponential Euler per candidate, the arrival on a cubic)
        G*(I_st, I_sup) = argmin over CANDIDATES ratios log-spaced over ±1.5 decades about the
        characteristic ratio (motion.characteristic_n); when G_hold is past the middle of that
        range, from just above G_hold up to 100·G_hold (or the range's top) instead           (LG1)
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
MAX_RATIO = 1e5  # the ratio field's bound: a cell that needs more cannot hold the load
PICK = "◆"
CANNOT_HOLD = "cannot hold"  # the motors at rest lose to the load at every ratio (LG0)
NO_ARRIVAL = "no arrival"  # they hold it, but no ratio screened reaches the goal
SHORT_NOTES = {CANNOT_HOLD: "hold✗", NO_ARRIVAL: "—"}  # in a heat map's cell
MODES = ("limit_grid",)  # the mode of a mechanism (elevator, arm) that runs the grid


def axis(lo: float, hi: float, step: float, prefix: str) -> list[float]:
    """lo, lo + step, ... ≤ hi: the limits of one axis (fields prefix_max, prefix_step)."""
    if hi < lo:
        raise InputError(f"{prefix}_max", f"is below the range's start ({hi:.4g} A < {lo:.4g} A)")
    count = math.floor((hi - lo) / step + 1e-9) + 1
    if count > 40:
        raise InputError(f"{prefix}_step", f"makes {count} limits (more than 40): widen the step")
    return [lo + i * step for i in range(count)]


def hold_ratios(make_setup, base: dict, stators, supply: float, length_scale: float):
    """G_hold per stator limit (an array, inf where no ratio holds) for one supply limit (LG0).
    At rest the current each motor gets is set by the limits alone (E = 0 in (E1)-(E3)), the
    same at every ratio, and the force it gives, η·N·Kt·n·(I0 − i_f) (M3), grows with n = G/L:
    G_hold = L·load/(η·N·Kt·(I0 − i_f)), load the most the field and the friction resist on the path."""
    import numpy as np

    from . import motion
    from .motor_limits import _Array

    unit = make_setup(
        {**base, "stator_current_limit": stators, "supply_current_limit": float(supply)},
        np.ones_like(stators) * length_scale,  # n = 1 motor radian per unit of q
        _Array(),
    )
    m = unit.mech
    lo, hi = sorted((m.q0, m.q1))
    points = [m.q0, m.q1] + [q for q in unit.critical if lo < q < hi]
    field = motion.field_force(unit)
    load = max(float(np.max(-m.s * np.asarray(field(q)))) for q in points) + motion.effect_friction(unit)
    _, I0 = motion.electrical(m, unit.asm.slots["duty"])(0.0 * stators)
    margin = np.asarray(I0 - m.free_current, dtype=float) * np.ones_like(stators)
    fpa = np.asarray(m.force_per_amp, dtype=float) * np.ones_like(stators)  # η·N·Kt at n = 1
    with np.errstate(divide="ignore", invalid="ignore"):
        G_hold = np.where(margin > 0, length_scale * load / (fpa * margin), np.inf)
    return np.where(load <= 0, 0.0, G_hold)  # nothing to hold against: every ratio starts moving


def run_mode(make_setup, v: dict, rtol: float, length_scale: float) -> SimRun:
    """The grid mode of a mechanism: its cells by (LG0)-(LG2) over the axes and budget its fields
    give. make_setup(values, ratio, xp) -> motion.Setup (the calculator's own setup); n = G/length_scale."""
    return run_cells(v, rtol, mechanism_cells(make_setup, length_scale))


def run(
    make_setup,
    values: dict,
    stators: list[float],
    supplies: list[float],
    budget: float,
    rtol: float,
    length_scale: float,
) -> SimRun:
    """A mechanism's grid over the given axes and budget (run_mode with the axes given)."""
    return grid(values, stators, supplies, budget, rtol, mechanism_cells(make_setup, length_scale))


# What a mechanism's pick reports: the row's column -> the output it fills (LG3)
MECHANISM_PICK = {
    "ratio": "best_ratio",
    "time": "time_to_goal",
    "peak_stator_current": "peak_stator_current",
    "peak_supply_current": "peak_supply_current",
    "energy": "energy",
}
MECHANISM_NONE = "no pair of limits in the grid moves the load to the goal"


def run_cells(
    v: dict, rtol: float, cells, pick_as: dict = MECHANISM_PICK, none_arrive: str = MECHANISM_NONE
) -> SimRun:
    """The grid over the axes and budget the fields (`fields`) give, each cell solved by `cells`."""
    stators = axis(v["stator_min"], v["stator_max"], v["stator_step"], "stator")
    supplies = axis(v["supply_min"], v["supply_max"], v["supply_step"], "supply")
    return grid(dict(v), stators, supplies, v["supply_budget"], rtol, cells, pick_as, none_arrive)


def grid(
    values: dict,
    stators: list[float],
    supplies: list[float],
    budget: float,
    rtol: float,
    cells,
    pick_as: dict = MECHANISM_PICK,
    none_arrive: str = MECHANISM_NONE,
) -> SimRun:
    """Every stator × supply limit pair (both limits on, with the other effects chosen), the pick
    within the budget (LG3), the table's rows and the heat map. `cells(base, stators, supplies,
    rtol) -> (rows, nfev)`: a row per cell, supply limit outer and stator limit inner, each with
    stator_limit, supply_limit and either the columns of `pick_as` (ratio, time, peak currents,
    energy) or a note (CANNOT_HOLD, NO_ARRIVAL). `pick_as` names the output each column of the
    pick fills; `none_arrive` is the error when no cell arrives. The values are grid_cells and
    the pick's; the key the pick's time (0 when no cell is within the budget)."""
    if len(stators) * len(supplies) > MAX_CELLS:
        raise InputError("stator_step", f"the grid has more than {MAX_CELLS} cells: widen a step")
    base = {**values, "effects": frozenset(values["effects"]) | {"stator_limit", "supply_limit"}}
    rows, nfev = cells(base, stators, supplies, rtol)
    within = [r for r in rows if "time" in r and r["peak_supply_current"] <= budget * (1 + 1e-12)]
    warnings = []
    values_out: dict[str, Any] = {"grid_cells": len(rows)}
    pick = None
    if within:
        pick = min(within, key=lambda r: r["time"])  # (LG3)
        pick["pick"] = PICK
        values_out.update(pick_stator_limit=pick["stator_limit"], pick_supply_limit=pick["supply_limit"])
        values_out.update({out: pick[col] for col, out in pick_as.items()})
    else:
        warnings.append(
            f"No cell keeps the peak supply current within the budget of {budget:.4g} A per motor."
        )
    unheld = sum(r.get("note") == CANNOT_HOLD for r in rows)
    if not any("time" in r for r in rows):
        if unheld == len(rows):
            raise InputError(
                "stator_min",
                f"no pair of limits in the grid lets the motors hold the load at rest, at any ratio up "
                f"to {MAX_RATIO:.0e}: raise the limits",
            )
        raise InputError("stator_min", none_arrive)
    if unheld:
        warnings.append(
            f"{unheld} cell(s) cannot hold the load at rest: with those limits the motors' current at "
            f"rest, less their free current, needs a ratio above {MAX_RATIO:.0e} to beat the load (LG0)."
        )
    time_out = pick_as["time"]
    return SimRun(
        values_out,
        {time_out: values_out.get(time_out, 0.0)},
        nfev,
        warnings,
        tables={"limit_grid": rows},
        heat_maps={"limit_grid_time": heat_map(rows, stators, supplies, pick)},
    )


def mechanism_cells(make_setup, length_scale: float):
    """A mechanism's cells (LG0)-(LG2): per supply limit one numpy batch of every stator limit's
    candidate ratios, then the accurate move at each cell's best."""

    def cells(base: dict, stators: list[float], supplies: list[float], rtol: float):
        import numpy as np

        from . import motion
        from .motor_limits import _Array

        probe = make_setup(
            {**base, "stator_current_limit": max(stators), "supply_current_limit": max(supplies)}
        )
        G_char = motion.characteristic_n(probe.mech) * length_scale
        lo_base, hi_base = G_char * 10**-1.5, G_char * 10**1.5
        st = np.asarray(stators, dtype=float)[:, None]
        rows: list[dict[str, Any]] = []
        nfev = 0
        for sup in supplies:
            # below its G_hold (LG0) a cell's candidates cannot move: when that would leave fewer
            # than half of the range (G_hold past its geometric middle, G_char) they start above it
            G_hold = hold_ratios(make_setup, base, st, float(sup), length_scale)
            holds = G_hold * 1.001 <= MAX_RATIO
            lo = np.where(holds & (1.001 * G_hold > G_char), 1.001 * G_hold, lo_base)
            hi = np.maximum(hi_base, 100 * lo)
            ratios = np.geomspace(lo, hi, CANDIDATES, axis=1)[:, :, 0]  # (stators × candidates)
            batch = make_setup(
                {**base, "stator_current_limit": st, "supply_current_limit": float(sup)}, ratios, _Array()
            )
            times = np.asarray(motion.batch_times(batch), dtype=float) * np.ones((len(stators), CANDIDATES))
            for i, I_st in enumerate(stators):
                row: dict[str, Any] = {"stator_limit": I_st, "supply_limit": float(sup)}
                ok = np.isfinite(times[i])
                if not holds[i, 0]:
                    row["note"] = CANNOT_HOLD  # no ratio up to MAX_RATIO holds the load at rest
                    rows.append(row)
                    continue
                if not ok.any():
                    row["note"] = NO_ARRIVAL
                    rows.append(row)
                    continue
                G_best = float(ratios[i, int(np.nanargmin(np.where(ok, times[i], np.nan)))])  # (LG1)
                cell = make_setup(
                    {**base, "stator_current_limit": I_st, "supply_current_limit": float(sup)}, G_best
                )
                try:
                    mv = motion.move(cell, rtol)  # (LG2)
                except InputError:
                    row["note"] = NO_ARRIVAL
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
        return rows, nfev

    return cells


def heat_map(rows, stators, supplies, pick):
    """The time per cell as a heat map's data: a column per supply limit, a row per stator limit."""
    from ..declarations import HeatMapData

    at = {(r["stator_limit"], r["supply_limit"]): r for r in rows}
    z, notes = [], []
    for I_st in stators:
        cells = [at[(I_st, float(sup))] for sup in supplies]
        z.append([c.get("time") for c in cells])
        notes.append([SHORT_NOTES.get(c.get("note", ""), "") for c in cells])
    where = None
    if pick is not None:
        where = (
            stators.index(pick["stator_limit"]),
            [float(s) for s in supplies].index(pick["supply_limit"]),
        )
    return HeatMapData(list(map(float, supplies)), list(map(float, stators)), z, where, notes)


def fields(modes: tuple[str, ...] = MODES, when: tuple = ()) -> tuple:
    """The grid's ranges and budget (a mechanism's mode; the flywheel's shown by its own choice),
    declared once: the same words wherever they appear (tests/test_shared_fields.py)."""
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
            modes=modes,
            when=when,
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
            "The cell picked is the quickest (least time) whose peak supply current per motor "
            "stays within this (e.g. what the breaker and the battery allow).",
        ),
    )


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


def table(
    title: str = "Current-limit grid: the fastest ratio per stator × supply limit",
    time_label: str = "Time",
    modes: tuple[str, ...] = MODES,
    when: tuple = (),
):
    """The grid's rows (a mechanism's mode; the flywheel's, shown by its own choice: `when`)."""
    from ..declarations import Column, Table

    return Table(
        "limit_grid",
        title,
        (
            Column("stator_limit", "Stator", "current", "A", width=8),
            Column("supply_limit", "Supply", "current", "A", width=8),
            Column("ratio", "Best ratio", width=10),
            Column("time", time_label, "time", "s", width=9),
            Column("peak_stator_current", "Peak stator", "current", "A", width=11),
            Column("peak_supply_current", "Peak supply", "current", "A", width=11),
            Column("energy", "Energy", "energy", "J", width=9),
            Column("pick", "Pick", width=4),
            Column("note", "Note", width=11),
        ),
        modes=modes,
        when=when,
    )


def heat_map_plot(title: str = "Time per current-limit pair (grid)", value: str = "time to goal"):
    """The time per cell, the pick marked (Result.heat_maps["limit_grid_time"])."""
    from ..declarations import HeatMap

    return HeatMap(
        title,
        "limit_grid_time",
        "supply limit",
        "current",
        "A",
        "stator limit",
        "current",
        "A",
        value,
        "time",
        "s",
    )
