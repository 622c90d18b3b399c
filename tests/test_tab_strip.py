"""The tab strips (tui/components/tab_strip.py): one Line-API widget each, drawn as Textual's Tabs
draws (cell for cell: character, colours, bold, dim) and used as Tabs is used (keys, clicks)."""

from __future__ import annotations

import html
import re

import pytest
from textual.app import App
from textual.widgets import Static, Tab, Tabs

from gearhead.tui.app import GearheadApp
from gearhead.tui.components.tab_strip import TabStrip
from tests.tui_helpers import settle

LABELS = [
    ("tab-a", "1 Lead screw"),
    ("tab-b", "2 Drivetrain"),
    ("tab-c", "3 Drivetrain sprint"),
    ("tab-d", "4 Elevator"),
    ("tab-e", "5 Arm"),
    ("tab-f", "6 Intake"),
]


def cells(svg: str) -> dict[tuple[int, int], tuple[str, str, str]]:
    """A screenshot's cells: (line, column) -> (character, its text style, its background)."""
    styles = dict(re.findall(r"\.terminal-\d+-(r\d+) \{ ([^}]*) \}", svg))
    grid: dict[tuple[int, int], list[str]] = {}
    for fill, x, y, width in re.findall(
        r'<rect fill="([^"]+)" x="([\d.]+)" y="([\d.]+)" width="([\d.]+)"', svg
    ):
        line, column = round((float(y) - 1.5) / 24.4), round(float(x) / 12.2)
        for i in range(round(float(width) / 12.2)):
            grid.setdefault((line, column + i), ["", "", ""])[2] = fill
    for cls, x, line, text in re.findall(
        r'<text class="terminal-\d+-(r\d+)" x="([\d.]+)" y="[\d.]+" textLength="[\d.]+" '
        r'clip-path="url\(#terminal-\d+-line-(\d+)\)">([^<]*)</text>',
        svg,
    ):
        for i, ch in enumerate(html.unescape(text)):
            cell = grid.setdefault((int(line), round(float(x) / 12.2) + i), ["", "", ""])
            cell[0], cell[1] = ch, styles[cls]
    return {key: tuple(value) for key, value in grid.items() if key[0] < 2}  # the strip's two lines


def strip_app(kind: str, ansi: bool):
    class Strips(App):
        AUTO_FOCUS = None
        CSS = "#other { height: 1fr; }"

        def __init__(self) -> None:
            super().__init__(ansi_color=ansi)

        def compose(self):
            if kind == "tabs":
                yield Tabs(*(Tab(label, id=tid) for tid, label in LABELS), active="tab-c", id="strip")
            else:
                yield TabStrip(LABELS, active="tab-c", id="strip")
            yield Static("x", id="other")

    return Strips()


async def screenshot(kind: str, ansi: bool, width: int, steps: str) -> tuple[dict, str]:
    app = strip_app(kind, ansi)
    async with app.run_test(size=(width, 6)) as pilot:
        await pilot.pause(0.1)
        strip = app.query_one("#strip")
        for step in steps.split():
            if step == "focus":
                strip.focus()
            elif step in ("left", "right"):
                await pilot.press(step)
            elif step.startswith("click@") or step.startswith("hover@"):
                x, y = map(int, step[6:].split(","))
                await (pilot.click if step[0] == "c" else pilot.hover)("#strip", offset=(x, y))
            elif step == "away":
                await pilot.hover("#other", offset=(2, 1))
            elif step == "narrow":
                await pilot.resize_terminal(33, 6)
            await pilot.pause(0.05)
        await pilot.pause(0.6)  # Tabs animates its underline and its scroll (0.3 s)
        return cells(app.export_screenshot()), strip.active


STATES = [
    "",  # unfocused
    "focus",
    "focus right",
    "focus right right right right right left left",  # wraps round
    "focus left left",
    "hover@2,0",  # a tab under the pointer
    "hover@31,0",  # the active tab under the pointer
    "hover@2,0 away",
    "click@35,0",  # a label: focus and activate
    "click@3,1",  # the bar under a tab
    "focus right right narrow",  # resized narrower than the tabs: the active tab scrolled into view
]


@pytest.mark.parametrize("ansi", [False, True], ids=["truecolor", "ansi"])
@pytest.mark.parametrize("width", [100, 60, 40])
@pytest.mark.parametrize("steps", STATES)
async def test_a_strip_draws_what_tabs_draws(steps, width, ansi):
    """Every cell of the two lines as Tabs draws it, in every state: focus, hover, the active tab
    moved by keys and clicks, a strip wider than the terminal (scrolled as Tabs scrolls)."""
    tabs, tabs_active = await screenshot("tabs", ansi, width, steps)
    strip, strip_active = await screenshot("strip", ansi, width, steps)
    assert strip_active == tabs_active
    assert len(strip) >= min(width, 33)  # the cells drawn (a blank ANSI cell has no rect)
    assert strip == tabs


async def test_a_strip_posts_tab_activated_when_its_tab_changes_not_when_built():
    got: list[tuple[str, str]] = []

    class Host(App):
        def compose(self):
            yield TabStrip(LABELS, active="tab-b", id="strip")

        def on_tab_strip_tab_activated(self, message: TabStrip.TabActivated) -> None:
            got.append((message.control.id, message.tab_id))

    app = Host()
    async with app.run_test(size=(100, 6)) as pilot:
        await pilot.pause()
        assert got == []
        app.query_one(TabStrip).focus()
        await pilot.press("right")
        await pilot.click("#strip", offset=(2, 0))
        app.query_one(TabStrip).active = "tab-e"
        await pilot.pause()
    assert got == [("strip", "tab-c"), ("strip", "tab-a"), ("strip", "tab-e")]


async def test_clicking_the_app_s_strips_shows_the_card_clicked():
    """A click on an area's tab shows that area at its calculator; a click on a calculator's tab
    (or on the bar under it) shows that card, its sheet taking the keys (as with Tabs); ← → on a
    focused calculator strip move through the area's cards, ↓ goes into the card."""
    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        x, _ = app.query_one("#areas", TabStrip).span("area-mechanisms")
        await pilot.click("#areas", offset=(x + 2, 0))
        await settle(pilot)
        assert (app.current_area, app.current_calculator) == ("mechanisms", "lead_screw")
        strip = app.query_one("#calcs-mechanisms", TabStrip)
        x, _ = strip.span("tab-elevator")
        await pilot.click("#calcs-mechanisms", offset=(x + 2, 1))  # the bar under the tab
        await settle(pilot)
        assert app.current_calculator == "elevator"
        assert app.focused is app.current_tab.sheet
        strip.focus()
        await pilot.press("right")
        await settle(pilot)
        assert app.current_calculator == "arm"
        assert app.current_tab.display and not app.query_one("#calc-elevator").display
        strip.focus()  # a card's first visit gives its sheet the keys once built
        await pilot.press("left", "left")
        await settle(pilot)
        assert app.current_calculator == "sprint"
        await pilot.press("down")  # into the card
        await pilot.pause()
        assert app.focused is app.current_tab.sheet
