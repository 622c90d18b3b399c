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
        pilot.app.query_one("#calc-gear_ratio #in-radius").value = "3 kg"
        await settle(pilot)

    assert snap_compare(
        GearheadApp(blink=False, initial="gear_ratio", hide_timings=True),
        terminal_size=SIZE,
        run_before=type_bad_radius,
    )
