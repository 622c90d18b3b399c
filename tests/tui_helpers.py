"""What pilot tests share: waiting until the app has finished solving and drawing."""

from __future__ import annotations

from textual.widgets import DataTable

from tui.components.calculator_tab import CalculatorTab


async def settle(pilot) -> None:
    """Wait until every tab has solved its latest entries and tables and plots are drawn
    (DataTable sizes its columns on idle; under load that can come late)."""
    app = pilot.app
    for _ in range(200):
        await pilot.pause()
        await app.workers.wait_for_complete()
        await pilot.pause()
        if not any(tab.busy for tab in app.query(CalculatorTab)):
            break
    for _ in range(50):
        await pilot.pause()
        await pilot.wait_for_scheduled_animations()
        if not any(t._require_update_dimensions or t._updated_cells or t._new_rows
                   for t in app.query(DataTable)):
            break
    await pilot.pause()  # plots draw after the results land
    await pilot.pause()
