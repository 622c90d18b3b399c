"""The flywheel's current-limit grid (control = limit_grid, (FW6)-(FW8)): the quadrature spin-up time
against the flywheel's own integrated spin-up (full_power with the same limits and ratio), the best
ratio against its neighbours on that independent path, the energy against a closed form where no
limit binds, and the pick's rule."""

import math

import pytest

from gearhead.core.calculators import flywheel as fc
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.sim.shooter import grid_energy, grid_spin_up

BASE = {
    "motor": "Kraken X60",
    "voltage": "12 V",
    "motor_count": 2,
    "ratio": 1.0,
    "mode": "moment_of_inertia",
    "wheel_inertia": "0.003 kg*m**2",
    "target_speed": "4000 rpm",
    "accuracy": "fine",
}
GRID = BASE | {
    "control": "limit_grid",
    "stator_min": "40 A",
    "stator_max": "100 A",
    "stator_step": "30 A",
    "supply_min": "30 A",
    "supply_max": "60 A",
    "supply_step": "30 A",
    "supply_budget": "45 A",
}


def full_power(stator: float, supply: float, ratio: float) -> dict:
    raw = BASE | {
        "ratio": ratio,
        "effects": "stator_limit, supply_limit",
        "stator_current_limit": f"{stator!r} A",
        "supply_current_limit": f"{supply!r} A",
    }
    return {k: v.value for k, v in solve("flywheel", raw).outputs.items()}


@pytest.fixture(scope="module")
def grid():
    return solve("flywheel", GRID)


def test_cells_are_the_integrated_spin_up_at_their_best_ratio(grid):
    rows = grid.tables["limit_grid"]
    assert len(rows) == 3 * 2 == grid.outputs["grid_cells"].value
    for row in rows:
        st, sup = row["stator_limit"].value, row["supply_limit"].value
        G, t = row["ratio"].value, row["time"].value
        at = full_power(st, sup, G)
        # (FW6) by quadrature against the scene's integrator (DP54 at the fine accuracy)
        assert t == pytest.approx(at["spin_up_time"], rel=1e-7)
        assert row["peak_supply_current"].value == pytest.approx(at["peak_supply_current"], rel=1e-12)
        assert row["peak_stator_current"].value == pytest.approx(at["peak_stator_current"], rel=1e-12)
        # (FW7): 1 % either side is slower on the independent path
        for other in (G * 0.99, G * 1.01):
            assert full_power(st, sup, other)["spin_up_time"] > at["spin_up_time"]


def test_pick_is_the_quickest_within_the_budget(grid):
    rows = grid.tables["limit_grid"]
    out = {k: v.value for k, v in grid.outputs.items()}
    within = [r for r in rows if r["peak_supply_current"].value <= 45 * (1 + 1e-12)]
    assert within and len(within) < len(rows)  # the budget leaves some cells out
    best = min(within, key=lambda r: r["time"].value)
    assert [r for r in rows if "pick" in r] == [best]
    assert (out["pick_stator_limit"], out["pick_supply_limit"]) == (
        best["stator_limit"].value,
        best["supply_limit"].value,
    )
    assert out["grid_spin_up_time"] == best["time"].value and out["best_ratio"] == best["ratio"].value


def test_energy_against_a_closed_form_where_no_limit_binds():
    """Limits above the stall current: τ_w = A·(1 − ω/ω_f), I − i_f = (i_s − i_f)·(1 − ω/ω_f), so
    E = N·V·J/A·((i_s − i_f)·ω_t − i_f·ω_f·ln(1 − ω_t/ω_f))."""
    v, _ = parse_inputs(
        fc.CALCULATOR,
        BASE
        | {
            "effects": "stator_limit, supply_limit",
            "stator_current_limit": "1500 A",
            "supply_current_limit": "1500 A",
        },
    )
    t, sc = grid_spin_up(dict(v), 1.0)
    d, w_t, w_f = sc.drive, v["target_speed"], sc.free_speed
    closed = 2 * 12.0 * sc.I / d.A * ((d.i_s - d.i_f) * w_t - d.i_f * w_f * math.log1p(-w_t / w_f))
    assert grid_energy(sc, dict(v)) == pytest.approx(closed, rel=1e-9)
    assert t == pytest.approx(sc.T * -math.log1p(-w_t / w_f), rel=1e-9)  # (FW2)'s T·ln(ω_f/(ω_f − ω_t))


def test_grid_refusals_name_the_field():
    with pytest.raises(InputError) as exc:
        solve("flywheel", GRID | {"stator_max": "10 A"})
    assert "stator_max" in str(exc.value)
    with pytest.raises(InputError) as exc:
        solve("flywheel", GRID | {"stator_min": "1 A", "stator_max": "2000 A", "stator_step": "1 A"})
    assert "stator_step" in str(exc.value)
    with pytest.raises(InputError) as exc:  # 0.5-1.5 A per motor: below the Kraken's 2 A free current
        solve(
            "flywheel",
            GRID
            | {
                "stator_min": "0.5 A",
                "stator_max": "1.5 A",
                "stator_step": "0.5 A",
                "supply_min": "0.5 A",
                "supply_max": "1.5 A",
                "supply_step": "0.5 A",
            },
        )
    assert "stator_min" in str(exc.value)


def test_no_cell_within_a_tiny_budget_warns():
    sol = solve("flywheel", GRID | {"supply_budget": "1 A"})
    assert "pick_stator_limit" not in sol.outputs
    assert any("budget" in w for w in sol.warnings)


def test_heat_map_is_the_table_s_times_with_the_pick_marked(grid):
    """The grid's heat map holds each row's spin-up time at (stator, supply), the picked cell marked;
    the grid mode draws no line chart, so the card shows the map by itself."""
    data = grid.heat_maps["limit_grid_time"]
    assert (data.x, data.y) == ([30.0, 60.0], [40.0, 70.0, 100.0])
    for row in grid.tables["limit_grid"]:
        i, j = data.y.index(row["stator_limit"].value), data.x.index(row["supply_limit"].value)
        assert data.z[i][j] == row["time"].value
    picked = next(r for r in grid.tables["limit_grid"] if "pick" in r)
    assert data.pick == (
        data.y.index(picked["stator_limit"].value),
        data.x.index(picked["supply_limit"].value),
    )
    assert not any(xs for xs, _ in grid.series.values())


def test_a_cell_that_never_reaches_the_target_is_marked_not_blank():
    """A target above the free speed at every ratio the scan allows for a limit: the cell says so in
    the table (note) and the map (no value, a short note), never NaN."""
    raw = GRID | {"stator_min": "1 A", "stator_max": "31 A", "stator_step": "30 A", "supply_min": "30 A"}
    raw["supply_max"] = "30 A"
    s = solve("flywheel", raw)
    rows = s.tables["limit_grid"]
    weak = next(r for r in rows if r["stator_limit"].value == 1.0)
    assert "time" not in weak and weak["note"].value == "no arrival"
    data = s.heat_maps["limit_grid_time"]
    assert data.z[0] == [None] and data.notes[0] == ["—"]


def test_the_grid_table_shows_only_under_control_limit_grid():
    """Table.when: the flywheel's mode is the inertia's, so the table follows `control`."""
    assert fc.GRID_TABLE.shown_in({"mode": "moment_of_inertia", "control": "limit_grid"})
    assert not fc.GRID_TABLE.shown_in({"mode": "moment_of_inertia", "control": "velocity_loop"})
    assert not fc.GRID_TABLE.shown_in({"mode": "moment_of_inertia", "control": "full_power"})


def test_heavy_rotors_move_the_scan_below_its_first_span():
    """(FW7) with rotors heavy enough that the quickest ratio lies below G_max/100 (each motor's
    inertia grows as G²): the scan moves down until the optimum is inside, so 1 % either side is
    slower on the independent integrated path (the review found the pick stuck at the span's edge,
    17 % slower than a ratio just below)."""
    heavy = {"motor": "Kraken X60", "ratio": 1.0, "rotor_inertia": "1 kg*m**2"}  # the review's case
    amps = {"stator_current_limit": "40 A", "supply_current_limit": "40 A"}
    raw = heavy | {"control": "limit_grid", "stator_min": "40 A", "stator_max": "40 A"}
    s = solve("flywheel", raw | {"supply_min": "40 A", "supply_max": "40 A"})
    G = s.outputs["best_ratio"].value
    grid_time = s.outputs["grid_spin_up_time"].value
    assert math.isfinite(grid_time)

    def at(ratio: float) -> float:
        raw_fp = heavy | amps | {"ratio": ratio, "effects": "stator_limit, supply_limit"}
        return solve("flywheel", raw_fp).outputs["spin_up_time"].value

    assert grid_time == pytest.approx(at(G), rel=1e-6)
    assert at(G * 0.99) > at(G) < at(G * 1.01)
