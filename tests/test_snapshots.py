"""One snapshot per tab (pytest-textual-snapshot), deterministic: fixed size, no blink, no clock."""

import pytest

from gearhead.core.registry import calculators
from gearhead.tui.app import GearheadApp
from tests.tui_helpers import settle

SIZE = (140, 45)


@pytest.mark.parametrize("calc_id", list(calculators()))
def test_tab_snapshot(snap_compare, calc_id):
    assert snap_compare(
        GearheadApp(blink=False, initial=calc_id, hide_timings=True), terminal_size=SIZE, run_before=settle
    )


def test_invalid_entry_snapshot(snap_compare):
    async def type_bad_radius(pilot):
        await settle(pilot)
        pilot.app.current_tab._take_entry("radius", "3 kg")  # as pasted into the row
        await settle(pilot)

    assert snap_compare(
        GearheadApp(blink=False, initial="gear_ratio", hide_timings=True),
        terminal_size=SIZE,
        run_before=type_bad_radius,
    )


def test_no_color_snapshot(snap_compare, monkeypatch):
    """NO_COLOR: the flags read [x] / [ ] and the cursor row is still marked, without colour."""
    monkeypatch.setenv("NO_COLOR", "1")

    async def tick_a_flag(pilot):
        await settle(pilot)
        tab = pilot.app.current_tab
        tab.sheet.focus()
        tab.sheet.move_to_field("effects")
        await pilot.press("space")
        await settle(pilot)

    assert snap_compare(
        GearheadApp(blink=False, initial="motor", hide_timings=True),
        terminal_size=SIZE,
        run_before=tick_a_flag,
    )


async def _elevator_grid_heat_map(pilot):
    """The elevator's current-limit grid: its heat map is the chart shown (the line charts are empty)."""
    from gearhead.core.model import HeatMap

    await settle(pilot)
    tab = pilot.app.current_tab
    tab._take_entry("mode", "limit_grid")
    await settle(pilot)
    await pilot.pause()
    await settle(pilot)
    assert isinstance(tab.plot.current, HeatMap)


def test_heat_map_snapshot(snap_compare):
    """The time per stator × supply limit, a coloured cell each with its value, the pick in brackets."""
    assert snap_compare(
        GearheadApp(blink=False, initial="elevator", hide_timings=True),
        terminal_size=SIZE,
        run_before=_elevator_grid_heat_map,
    )


def test_heat_map_no_color_snapshot(snap_compare, monkeypatch):
    """NO_COLOR: every cell still reads its value and the pick its brackets."""
    monkeypatch.setenv("NO_COLOR", "1")
    assert snap_compare(
        GearheadApp(blink=False, initial="elevator", hide_timings=True),
        terminal_size=SIZE,
        run_before=_elevator_grid_heat_map,
    )
