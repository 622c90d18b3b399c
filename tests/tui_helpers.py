"""What pilot tests share: waiting until the app has finished solving and drawing."""

from __future__ import annotations

from textual.widgets import DataTable

from gearhead.tui.components.calculator_tab import CalculatorTab


async def started(pilot) -> None:
    """Wait for the first card: the app draws its first frame without it (no calculator is
    imported before), and builds the card of the calculator on screen right after."""
    app = pilot.app
    for _ in range(500):
        if app.card_ready(app.current_calculator):
            return
        await pilot.pause()
    raise AssertionError(f"the {app.current_calculator} card was never built")


async def settle(pilot) -> None:
    """Wait until every tab has solved its latest entries and tables and plots are drawn
    (DataTable sizes its columns on idle; under load that can come late)."""
    app = pilot.app
    await started(pilot)
    for _ in range(200):
        await pilot.pause()
        await app.workers.wait_for_complete()
        await pilot.pause()
        if not any(tab.busy for tab in app.query(CalculatorTab)):
            break
    for _ in range(50):
        await pilot.pause()
        await pilot.wait_for_scheduled_animations()
        if not any(
            t._require_update_dimensions or t._updated_cells or t._new_rows for t in app.query(DataTable)
        ):
            break
    await pilot.pause()  # plots draw after the results land
    await pilot.pause()
