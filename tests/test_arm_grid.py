"""The arm's current-limit grid (core.sim.limit_grid shared with the elevator, issue 30): the screen's
ratio per cell against an accurate scan of the swing, each cell the move at its ratio, a cell whose
limits cannot hold the arm against gravity said so (not NaN, not an empty row), and no input giving a
traceback or a non-finite number."""

import json
import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from gearhead.core.calculators import arm as arm_calc
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import limit_grid, motion

SMALL = {
    "mode": "limit_grid",
    "stator_min": "20 A",
    "stator_max": "120 A",
    "stator_step": "50 A",
    "supply_min": "20 A",
    "supply_max": "80 A",
    "supply_step": "30 A",
    "supply_budget": "50 A",
}
SPACING = 1000 ** (1 / (limit_grid.CANDIDATES - 1))  # the widest candidate spacing, 3 decades (LG1)


@pytest.fixture(scope="module")
def grid():
    return solve("arm", SMALL)


def _rows(sol):
    return [{k: v.value for k, v in row.items()} for row in sol.tables["limit_grid"]]


def _cell_values(row):
    v, _ = parse_inputs(get("arm"), {})
    return {
        **v,
        "effects": frozenset(v["effects"]) | {"stator_limit", "supply_limit"},
        "stator_current_limit": row["stator_limit"],
        "supply_current_limit": row["supply_limit"],
    }


@pytest.mark.parametrize("index", [0, 4, 8])
def test_screened_ratio_is_the_accurate_fastest(grid, index):
    """Scan the ratio with the accurate integrator (rtol 1e-10) about the cell's ratio, refine with
    Brent: the screen's ratio is within one candidate spacing of the accurate optimum and its time
    within 0.5 % of the least time."""
    row = _rows(grid)[index]
    values = _cell_values(row)

    def time_at(G):
        try:
            return motion.move(arm_calc.setup(values, float(G)), 1e-10).time
        except InputError:
            return math.inf

    ratios = np.geomspace(row["ratio"] / 1.5, row["ratio"] * 1.5, 31)
    times = [time_at(G) for G in ratios]
    i = int(np.argmin(times))
    assert 0 < i < len(ratios) - 1  # the optimum is inside the scan, not at its edge
    best = minimize_scalar(time_at, bounds=(ratios[i - 1], ratios[i + 1]), method="bounded")
    assert best.fun <= row["time"] * (1 + 1e-9)
    assert row["time"] <= best.fun * 1.005
    assert 1 / SPACING <= row["ratio"] / best.x <= SPACING


def test_each_cell_is_the_move_at_its_ratio(grid):
    for row in _rows(grid)[::4]:
        one = solve(
            "arm",
            {
                "effects": "gravity, stator_limit, supply_limit",
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


def test_pick_is_the_fastest_within_the_budget_and_marked_on_the_heat_map(grid):
    rows = _rows(grid)
    within = [r for r in rows if r["peak_supply_current"] <= 50 * (1 + 1e-12)]
    fastest = min(within, key=lambda r: r["time"])
    assert fastest.get("pick") == "◆" and sum("pick" in r for r in rows) == 1
    hm = grid.heat_maps["limit_grid_time"]
    assert hm.x == [20.0, 50.0, 80.0] and hm.y == [20.0, 70.0, 120.0]
    j, i = hm.pick
    assert (hm.y[j], hm.x[i]) == (fastest["stator_limit"], fastest["supply_limit"])
    assert hm.z[j][i] == fastest["time"]


def test_a_limit_too_small_to_hold_the_arm_says_so():
    """1 A stator limit: the motor's free current (2 A for a Kraken X60) is more than the limit lets
    through at rest, so no ratio holds the arm against gravity (LG0)."""
    sol = solve("arm", {**SMALL, "stator_min": "1 A", "stator_step": "49.5 A", "stator_max": "100 A"})
    rows = _rows(sol)
    held = [r for r in rows if r["stator_limit"] == 1.0]
    assert len(held) == 3
    for r in held:
        assert r["note"] == limit_grid.CANNOT_HOLD and "time" not in r and "ratio" not in r
    assert all("time" in r and "note" not in r for r in rows if r["stator_limit"] != 1.0)
    hm = sol.heat_maps["limit_grid_time"]
    assert hm.z[0] == [None, None, None] and hm.notes[0] == ["hold✗"] * 3
    assert any("cannot hold" in w for w in sol.warnings)
    json.dumps(sol.as_json(), allow_nan=False)  # no NaN anywhere
    # the least ratio that holds, by hand: m·g·L·cos(0) (the swing crosses horizontal) against
    # η·N·Kt·(I0 − i_f) per unit ratio, I0 = the limit at rest
    v = _cell_values({"stator_limit": 40.0, "supply_limit": 80.0})
    s = arm_calc.setup(v, 1.0)
    m = s.mech
    G_hand = v["arm_mass"] * 9.80665 * v["com_distance"] / (m.force_per_amp * (40.0 - m.free_current))
    G_hold = limit_grid.hold_ratios(
        lambda values, G_=None, xp=motion.SCALAR: arm_calc.setup(values, G_, xp),
        v,
        np.array([[40.0]]),
        80.0,
        1.0,
    )
    assert float(G_hold[0, 0]) == pytest.approx(G_hand, rel=1e-12)


def test_no_cell_holding_names_the_field():
    with pytest.raises(InputError) as exc:
        solve("arm", {**SMALL, "arm_mass": "200000 lb"})
    assert exc.value.field == "stator_min" and "hold" in exc.value.message


HOSTILE = [
    {"goal_angle": "-30 deg"},  # start = goal
    {"goal_angle": "-80 deg"},  # down: gravity helps
    {"start_angle": "-90 deg", "goal_angle": "270 deg"},  # a full turn and more
    {"effects": "gravity, counterbalance", "counterbalance_torque": "30 N*m"},  # over-balanced
    {"effects": "gravity, friction, battery_sag", "friction_torque": "5 N*m"},
    {"effects": "gravity, battery_sag", "battery_resistance": "2 ohm"},
    {"effects": ""},
    {"inertia_model": "entered", "moment_of_inertia": "1 lb*in**2"},
    {"stator_step": "0.1 A"},
    {"supply_max": "10 A"},
    {"supply_budget": "0.001 A"},
    {"stator_min": "2000 A", "stator_max": "2000 A"},
    {"arm_mass": "0.001 lb", "com_distance": "0.01 in"},
    {"arm_mass": "500 lb"},
    {"motor_count": 0},
    {"voltage": "0.5 V"},
]


@pytest.mark.parametrize("raw", HOSTILE)
def test_no_input_gives_a_traceback_or_nan(raw):
    try:
        sol = solve("arm", {**SMALL, **raw})
    except InputError as exc:
        assert exc.field and exc.message
        return
    json.dumps(sol.as_json(), allow_nan=False)
    for row in sol.heat_maps["limit_grid_time"].z:
        assert all(z is None or (math.isfinite(z) and z > 0) for z in row)
