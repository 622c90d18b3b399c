"""The current-limit grid (core.sim.limit_grid, issue 30): every cell is the full-voltage move at its
ratio (solved again on its own, it gives the same numbers), its ratio is within 1 % of the optimise
mode's time for those limits, the pick is the fastest cell within the supply budget, and the batch
over a column of stator limits is the per-limit batch."""

import numpy as np
import pytest

from gearhead.core.calculators import elevator as elevator_calc
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import motion
from gearhead.core.sim.motor_limits import _Array

SMALL = {
    "mode": "limit_grid",
    "effects": "gravity, battery_sag",
    "stator_min": "30 A",
    "stator_max": "90 A",
    "stator_step": "30 A",
    "supply_min": "30 A",
    "supply_max": "60 A",
    "supply_step": "15 A",
    "supply_budget": "45 A",
}


@pytest.fixture(scope="module")
def grid():
    return solve("elevator", SMALL)


def _rows(sol):
    return [{k: v.value for k, v in row.items()} for row in sol.tables["limit_grid"]]


def test_each_cell_is_the_move_at_its_ratio(grid):
    rows = _rows(grid)
    assert len(rows) == 3 * 3
    for row in rows[::4]:
        one = solve(
            "elevator",
            {
                "effects": "gravity, battery_sag, stator_limit, supply_limit",
                "stator_current_limit": f"{row['stator_limit']} A",
                "supply_current_limit": f"{row['supply_limit']} A",
                "ratio": row["ratio"],
            },
        )
        out = {k: v.value for k, v in one.outputs.items()}
        assert row["time"] == pytest.approx(out["time_to_goal"], rel=1e-5)
        assert row["peak_stator_current"] == pytest.approx(out["peak_stator_current"], rel=1e-9)
        assert row["peak_supply_current"] == pytest.approx(out["peak_supply_current"], rel=1e-9)
        assert row["energy"] == pytest.approx(out["energy"], rel=1e-5)


def test_cell_ratio_is_nearly_the_fastest(grid):
    row = _rows(grid)[4]
    best = solve(
        "elevator",
        {
            "mode": "optimise",
            "effects": "gravity, battery_sag, stator_limit, supply_limit",
            "stator_current_limit": f"{row['stator_limit']} A",
            "supply_current_limit": f"{row['supply_limit']} A",
        },
    )
    t_opt = best.outputs["time_to_goal"].value
    assert t_opt * (1 - 1e-6) <= row["time"] <= t_opt * 1.01


def test_pick_is_the_fastest_within_the_budget(grid):
    rows = _rows(grid)
    within = [r for r in rows if r["peak_supply_current"] <= 45 * (1 + 1e-12)]
    fastest = min(within, key=lambda r: r["time"])
    assert fastest.get("pick") == "◆" and sum("pick" in r for r in rows) == 1
    out = {k: v.value for k, v in grid.outputs.items()}
    assert (out["pick_stator_limit"], out["pick_supply_limit"]) == (
        fastest["stator_limit"],
        fastest["supply_limit"],
    )
    assert out["time_to_goal"] == fastest["time"] and out["best_ratio"] == fastest["ratio"]


def test_broadcast_batch_is_the_per_limit_batch():
    v, _ = parse_inputs(get("elevator"), {"effects": "gravity, battery_sag"})
    on = frozenset(v["effects"]) | {"stator_limit", "supply_limit"}
    ratios = np.geomspace(1, 40, 30)
    stators = np.array([25.0, 60.0, 110.0])
    batch = motion.batch_times(
        elevator_calc.setup(
            {**v, "effects": on, "stator_current_limit": stators[:, None], "supply_current_limit": 40.0},
            ratios[None, :],
            _Array(),
        )
    )
    for i, I_st in enumerate(stators):
        one = motion.batch_times(
            elevator_calc.setup(
                {**v, "effects": on, "stator_current_limit": float(I_st), "supply_current_limit": 40.0},
                ratios,
                _Array(),
            )
        )
        np.testing.assert_array_equal(batch[i], one)


@pytest.mark.parametrize(
    "raw, field",
    [
        ({"stator_min": "100 A", "stator_max": "50 A"}, "stator_max"),
        ({"supply_step": "0.5 A"}, "supply_step"),
    ],
)
def test_bad_ranges_name_their_field(raw, field):
    with pytest.raises(InputError) as exc:
        solve("elevator", {"mode": "limit_grid", **raw})
    assert exc.value.field == field
