"""The export dialog (ctrl+e) offers the design report of the card, and of the workbook the app
opened; it is built in a worker and saved through the same atomic, never-overwrite writing as the
other exports."""

from __future__ import annotations

import asyncio
import time

from textual.widgets import Button, Input, OptionList

from gearhead.core import workbook
from gearhead.core.report import html
from gearhead.tui.app import GearheadApp
from tests.tui_helpers import settle

SIZE = (140, 45)


async def _until(pilot, condition, timeout: float = 60) -> None:
    deadline = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < deadline, "the report was never written"
        await asyncio.sleep(0.1)
    await settle(pilot)


def _labels(app) -> list[str]:
    options = app.screen.query_one(OptionList)
    return [str(options.get_option_at_index(i).prompt) for i in range(options.option_count)]


async def _save(app, pilot, label_start: str) -> None:
    await pilot.press("ctrl+e")
    await settle(pilot)
    labels = _labels(app)
    app.screen.query_one(OptionList).highlighted = next(
        i for i, t in enumerate(labels) if t.startswith(label_start)
    )
    await settle(pilot)
    app.screen.query_one("#save", Button).press()


async def test_ctrl_e_saves_the_cards_design_report(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+e")
        await settle(pilot)
        labels = _labels(app)
        # the report comes last: the other options keep their places (tests/test_tui.py picks them by index)
        assert labels[:2] == [
            "Results table as Markdown",
            "Results table as CSV (shown and full-precision SI values)",
        ]
        assert labels[-1] == "Report: Motor as a design report (HTML)"
        await pilot.press("escape")
        await settle(pilot)
        await _save(app, pilot, "Report: Motor")
        assert app.screen.query_one("#export-path", Input).value == "motor_report.html"
        path = tmp_path / "motor_report.html"
        await _until(pilot, path.exists)
        page = path.read_text(encoding="utf-8")
        solution = app.query_one("#calc-motor").solution
        for value in solution.inputs.values():
            assert f'<td class="value">{html.esc(value.text)}</td>' in page
        assert page.count("<svg") >= 1
        # saved again: refused, as every export is, never over the file
        await _save(app, pilot, "Report: Motor")
        await _until(pilot, lambda: "exists" in str(app.screen.query_one("#export-error").render()))
        assert path.read_text(encoding="utf-8") == page


async def test_ctrl_e_offers_the_opened_workbooks_report(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    book = workbook.load("builtin:robot_2027")
    app = GearheadApp(blink=False, initial="motor", workbook=book)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        while app.screen.__class__.__name__ == "WorkbookScreen":  # back to the calculator cards
            await pilot.press("escape")
            await settle(pilot)
        await _save(app, pilot, "Report: the workbook 2027 robot")
        path = tmp_path / "robot_2027_report.html"
        await _until(pilot, path.exists, timeout=120)
        page = path.read_text(encoding="utf-8")
        assert "<h1>2027 robot</h1>" in page and "Requirements" in page and 'id="card-lift"' in page
