"""The heat map plot kind (core.declarations.HeatMap, issue 30): its data in --json, its text in the
CLI, its CSV, and the card's Line-API widget drawing the same text as the CLI (values in every cell,
the pick in brackets, 'hold✗' where the limits cannot hold the load)."""

import csv
import io
import json

import pytest
from textual.app import App

from gearhead.core import export
from gearhead.core.model import HeatMap, HeatMapData, solve
from gearhead.core.registry import get
from gearhead.tui.cli import main
from gearhead.tui.components.heat_map import HeatMapView
from gearhead.tui.components.heat_map_layout import decimals, layout, plain_lines

GRID = {
    "mode": "limit_grid",
    "stator_min": "1 A",
    "stator_max": "101 A",
    "stator_step": "50 A",
    "supply_min": "20 A",
    "supply_max": "60 A",
    "supply_step": "20 A",
    "supply_budget": "50 A",
}
SPEC = HeatMap("T", "t", "supply", "current", "A", "stator", "current", "A", "time", "time", "ms")


def _spec(calc_id):
    return next(p for p in get(calc_id).plots if isinstance(p, HeatMap))


@pytest.fixture(scope="module")
def arm_grid():
    return solve("arm", GRID)


def test_decimals_give_the_largest_value_its_digits():
    assert decimals([0.1846, 0.5076], 4) == 4  # 0.5076
    assert decimals([12.3, 1.5], 3) == 1  # 12.3
    assert decimals([4000.0], 4) == 0
    assert decimals([], 4) is None and decimals([2e7], 4) is None


def test_values_spanning_a_thousandfold_keep_their_digits():
    """Fixed decimals from the largest value would print 0.04 beside 1500 as "0" (the review):
    then every cell takes significant digits instead."""
    assert decimals([1500.0, 0.4, 0.04, 2.0], 4) is None
    spec = SPEC
    data = HeatMapData([20.0, 40.0], [10.0, 30.0], [[1.5, 4e-4], [4e-5, 2e-3]], (1, 0))
    lines = plain_lines(layout(spec, data))  # in ms: 1500, 0.4, 0.04, 2
    assert lines[3].split() == ["10", "1500", "0.4"]
    assert lines[4].split() == ["30", "[0.04]", "2"]


def test_layout_in_display_units_with_the_pick_and_the_notes():
    data = HeatMapData(
        [20.0, 40.0], [10.0, 30.0], [[None, 0.25], [0.5, 0.125]], (1, 1), [["hold✗", ""], ["", ""]]
    )
    lines = plain_lines(layout(SPEC, data))
    assert lines[0] == " time [ms] per cell; [ ] the pick"
    assert "stator [A]" in lines[1] and "supply [A]" in lines[1]
    assert lines[2].split() == ["20", "40"]
    assert lines[3].split() == ["10", "hold✗", "250.0"]  # ms, one decimal as 500.0 has four digits
    assert lines[4].split() == ["30", "500.0", "[125.0]"]
    assert lines[5].split() == ["lowest", "125.0", "ms,", "highest", "500.0", "ms"]


def test_json_has_the_grid_the_pick_and_no_nan(arm_grid):
    data = json.loads(json.dumps(arm_grid.as_json(), allow_nan=False))
    hm = data["heat_maps"]["limit_grid_time"]
    assert hm["x"] == [20.0, 40.0, 60.0] and hm["y"] == [1.0, 51.0, 101.0]
    assert hm["z"][0] == [None, None, None] and hm["notes"][0] == ["hold✗"] * 3
    rows = {(r["stator_limit"]["value"], r["supply_limit"]["value"]): r for r in data["tables"]["limit_grid"]}
    j, i = hm["pick"]
    assert rows[(hm["y"][j], hm["x"][i])]["pick"]["value"] == "◆"
    for j, y in enumerate(hm["y"][1:], 1):
        for i, x in enumerate(hm["x"]):
            assert hm["z"][j][i] == rows[(y, x)]["time"]["value"]
    assert "heat_maps" not in solve("arm", {}).as_json()  # only the grid draws one


def test_csv_has_a_row_per_cell(arm_grid):
    rows = list(csv.reader(io.StringIO(export.heat_map_csv(_spec("arm"), arm_grid))))
    assert rows[0] == ["supply limit [A]", "stator limit [A]", "time to goal [s]", "note", "pick"]
    assert len(rows) == 1 + 9
    assert [r[3] for r in rows[1:4]] == ["hold✗"] * 3 and all(r[2] == "" for r in rows[1:4])
    assert sum(r[4] == "1" for r in rows[1:]) == 1


def test_cli_prints_the_map(capsys, arm_grid):
    args = ["solve", "arm"] + [a for k, v in GRID.items() for a in ("--set", f"{k}={v}")]
    assert main(args) == 0
    out = capsys.readouterr().out
    expected = plain_lines(layout(_spec("arm"), arm_grid.heat_maps["limit_grid_time"]))
    assert "\n".join(expected) in out
    assert out.count("[") - out.count("[A]") - out.count("[s]") - out.count("[J]") - out.count("[ ]") == 1


async def test_widget_draws_the_cli_text(arm_grid):
    spec, data = _spec("arm"), arm_grid.heat_maps["limit_grid_time"]

    class One(App):
        def compose(self):
            yield HeatMapView()

    app = One()
    async with app.run_test(size=(90, 20)) as pilot:
        view = app.query_one(HeatMapView)
        view.show(spec, data)
        await pilot.pause()
        lines = view.text_lines()
        assert lines[:-1] == plain_lines(layout(spec, data))[:-1]  # the legend is a colour ramp there
        rendered = [view.render_line(y).text.rstrip() for y in range(len(lines))]
        assert rendered == lines
    async with One().run_test(size=(40, 20)) as pilot:  # narrow: three digits, the pick still marked
        view = pilot.app.query_one(HeatMapView)
        view.show(spec, data)
        await pilot.pause()
        assert any("[0." in line for line in view.text_lines())
        assert view.text_lines() == [s.rstrip() for s in plain_lines(layout(spec, data, 3))[:-1]] + [
            view.text_lines()[-1]
        ]


async def test_the_card_shows_the_heat_map_in_the_grid_mode_and_the_lines_out_of_it():
    from gearhead.tui.app import GearheadApp
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="arm", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.current_tab
        shown = []
        for mode in ("limit_grid", "move", "limit_grid", "optimise"):
            tab._take_entry("mode", mode)
            await settle(pilot)
            await pilot.pause()
            await settle(pilot)
            shown.append(tab.plot.current.title)
            view = app.query(HeatMapView)
            assert bool(view and view.first().display) == (mode == "limit_grid")
        assert shown == ["Time per current-limit pair (grid)", "Angle"] * 2


async def test_the_flywheel_card_shows_its_grid_by_control_not_by_mode():
    """The flywheel's `mode` is the inertia's: its grid table and heat map follow `control`
    (Table.when), shown in limit_grid and gone in full_power."""
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.result_table import ResultTable
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="flywheel", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.current_tab
        for control in ("limit_grid", "full_power", "limit_grid"):
            tab._take_entry("control", control)
            await settle(pilot)
            await pilot.pause()
            await settle(pilot)
            grid = tab.query_one("#table-limit_grid", ResultTable)
            assert grid.display == (control == "limit_grid")
            assert grid.row_count == (77 if control == "limit_grid" else 0) or not grid.display
            view = app.query(HeatMapView)
            assert bool(view and view.first().display) == (control == "limit_grid")
