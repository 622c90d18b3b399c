"""One snapshot per tab (pytest-textual-snapshot), deterministic: fixed size, no blink, no clock."""

import pytest
from textual.widgets import DataTable

from core.registry import calculators
from tui.app import GearheadApp

SIZE = (140, 45)


async def settle(pilot):
    """Wait until results, tables and plots are drawn: workers done and no widget with work
    deferred to idle (DataTable sizes its columns on idle; under load that can come late)."""
    await pilot.pause()
    await pilot.app.workers.wait_for_complete()
    for _ in range(50):
        await pilot.pause()
        await pilot.wait_for_scheduled_animations()
        if not any(t._require_update_dimensions or t._updated_cells or t._new_rows
                   for t in pilot.app.query(DataTable)):
            break
    await pilot.pause()  # plots draw after the results land
    await pilot.pause()


@pytest.mark.parametrize("calc_id", list(calculators()))
def test_tab_snapshot(snap_compare, calc_id):
    assert snap_compare(GearheadApp(blink=False, initial=calc_id, hide_timings=True), terminal_size=SIZE, run_before=settle)


def test_invalid_entry_snapshot(snap_compare):
    async def type_bad_radius(pilot):
        await settle(pilot)
        pilot.app.query_one("#calc-gear_ratio #in-radius").value = "3 kg"
        await settle(pilot)

    assert snap_compare(GearheadApp(blink=False, initial="gear_ratio", hide_timings=True), terminal_size=SIZE,
                        run_before=type_bad_radius)
