"""Every keystroke lands where the user sees it, in order, however fast it comes.

In a real terminal a burst of keys arrives in one read. Textual runs a non-priority binding (Tab,
Backspace in an Input…) only once its key has bubbled to the app, after the keys read with it:
Tab then 11 put 11 in the field just left, Backspace Backspace 3 on `12` gave `1`. The card's
sheet handles every key in its own handler, in the order typed (tui/components/sheet.py). The
pilot tests post keys the way the terminal driver does (no waiting between them); the tmux tests
type into the real app.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest
from textual import events

from gearhead.core.registry import calculators, get
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.sheet import GAP, LABEL_CELLS, VALUE_CELLS
from tests.tui_helpers import card, settle, started

ROOT = Path(__file__).resolve().parents[1]
VALUE_COLUMN = 1 + 1 + LABEL_CELLS + GAP + 1  # border, padding, label, gap, the cell's space

PRINTABLE = {" ": ("space", " ")}


def key(k: str) -> events.Key:
    """A key as the driver posts it: printable characters carry themselves."""
    if k in PRINTABLE:
        return events.Key(*PRINTABLE[k])
    if len(k) == 1:
        return events.Key(k, k)
    chars = {
        "backspace": "\x7f",
        "tab": "\t",
        "enter": "\r",
        "escape": "\x1b",
        "ctrl+u": "\x15",
        "ctrl+a": "\x01",
    }
    return events.Key(k, chars.get(k))


async def burst(pilot, keys: list[str]) -> None:
    for k in keys:  # posted back to back, as the driver does for one read
        pilot.app.post_message(key(k))
    await settle(pilot)


# (keys from the Motors row of the motor card, expected Motors, expected Voltage)
BURSTS = [
    (["3", "tab", "1", "1"], "3", "11"),  # Tab then type: 11 goes to the row Tab moved to
    (["enter", "3", "enter", "5"], "13", "5"),  # Enter edits at the end, then commits down
    (["enter", "backspace", "4", "tab", "5"], "4", "5"),
    (["2", "escape", "tab", "9"], "1", "9"),  # Esc cancels the edit
    (["enter", "ctrl+a", "4", "shift+tab", "down", "down", "6"], "4", "6"),  # ctrl+a selects the cell
    (["8", "down", "backspace", "7", "up", "up", "down", "2"], "2", "7"),
    (["enter", "ctrl+u", "1", "2", "backspace", "backspace", "7", "tab", "tab", "shift+tab", "3"], "7", "3"),
]


@pytest.mark.parametrize("keys,motors,voltage", BURSTS)
async def test_key_burst_lands_where_the_cursor_is(keys, motors, voltage):
    app = GearheadApp(blink=False, hide_timings=True, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = card(app)
        tab.sheet.focus()
        tab.sheet.move_to_field("motor_count")
        await pilot.pause()
        await burst(pilot, keys)
        assert (tab.entries["motor_count"], tab.entries["voltage"]) == (motors, voltage)
        assert tab.solution.inputs["motor_count"].value == int(motors)
        assert tab.solution.inputs["voltage"].value == pytest.approx(float(voltage))


@pytest.mark.parametrize("gap", [0.0, 0.02, 0.15])
async def test_f_key_digit_then_tab_goes_into_the_card_picked(gap):
    """F5 2 Tab 7: the flywheel card, its first row typed into (Tab's focus chain, taken while
    the card switched, reached the projectile card being left: it was shown again)."""
    app = GearheadApp(blink=False, hide_timings=True, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        for k in ["f5", "2", "tab"]:
            app.post_message(key(k))
            if gap:
                await pilot.pause(gap)
        await settle(pilot)
        assert app.current_calculator == "flywheel"
        assert app.focused is card(app).sheet


@pytest.mark.parametrize("gap", [0.0, 0.05])
async def test_keys_after_an_f_key_and_digit_go_to_the_card_in_order(gap):
    """F2 3 ↓ ↓ ↓ 5 in one burst: the sprint card, its fourth row typed into. The pick is a
    priority binding taken in the order typed, and the card's sheet has focus at once (the strip
    held focus after a pick: ↓ did nothing there, and at 0 ms the 5 reached the strip and opened
    the arm)."""
    app = GearheadApp(blink=False, hide_timings=True, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        for k in ["f2", "3", "down", "down", "down", "5"]:
            app.post_message(key(k))
            if gap:
                await pilot.pause(gap)
        await settle(pilot)
        tab = card(app)
        assert app.current_calculator == "sprint"
        assert app.focused is tab.sheet
        assert tab.sheet.current_field.name == tab.sheet.stops[3].field.name == "motor_count"
        assert tab.entries["motor_count"] == "5"


@pytest.mark.parametrize(
    "keys,calc,field,entry", [(["f1", "x", "3"], "motor", "motor", None), (["3"], "motor", "motor", None)]
)
async def test_a_digit_picks_only_right_after_an_f_key(keys, calc, field, entry):
    """A digit not right after an F-key is typed, not a pick: F1 x 3 types into the motor card's
    first row (a choice: type-ahead), and so does 3 at start."""
    app = GearheadApp(blink=False, hide_timings=True, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        for k in keys:
            app.post_message(key(k))
        await settle(pilot)
        assert app.current_calculator == calc
        assert app.focused is card(app).sheet
        assert card(app).sheet.current_field.name == field


@pytest.mark.parametrize("calc_id", sorted(calculators()))
async def test_tab_then_type_in_every_card(calc_id):
    """On every card: the first two numeric rows, each typed right after the Tab that reaches it,
    in one burst, while the card solves."""
    numeric = [f for f in get(calc_id).fields if f.type in ("quantity", "int")]
    app = GearheadApp(blink=False, initial=calc_id, hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await started(pilot)
        tab = card(app)
        shown = [f for f in tab.sheet.shown_fields if f in numeric][:2]
        first = shown[0]
        tab.sheet.focus()
        tab.sheet.move_to_field(first.name)
        keys = ["enter", "ctrl+u", "1", "2", "backspace", "7"]
        second = None
        if len(shown) > 1:
            stops = [s.field.name for s in tab.sheet.stops]
            hops = stops.index(shown[1].name) - stops.index(first.name)
            keys += ["enter"] + ["tab"] * (hops - 1) + ["8"]
            second = shown[1].name
        await burst(pilot, keys)
        assert tab.entries[first.name] == "17"
        if second:
            assert tab.entries[second] == "8"
        assert tab.sheet.current_field.name == (second or first.name)


# ---- the real terminal ---------------------------------------------------------------------

TMUX = shutil.which("tmux")


class Terminal:
    """The app running in a tmux pane of its own server (never the user's tmux)."""

    def __init__(self, tmp: Path, **env_extra: str) -> None:
        self.socket = f"gearhead-test-{uuid.uuid4().hex[:8]}"
        # COLUMNS/LINES (set under pytest-xdist) would override the pane's size in Textual
        env = {
            k: v
            for k, v in os.environ.items()
            if k not in ("NO_COLOR", "TEXTUAL_THEME", "TMUX", "COLUMNS", "LINES")
        }
        env["XDG_CONFIG_HOME"] = str(tmp / "config")
        env.update(env_extra)
        self.env = env
        self.tmux(
            "new-session",
            "-d",
            "-s",
            "app",
            "-x",
            "140",
            "-y",
            "45",
            f"cd {ROOT} && {sys.executable} -m gearhead.tui",
        )
        self.wait_for(lambda screen: "Free speed" in screen, "the first frame")

    def tmux(self, *args: str) -> str:
        out = subprocess.run(
            [TMUX, "-L", self.socket, *args], capture_output=True, text=True, env=self.env, timeout=20
        )
        return out.stdout

    def keys(self, *keys: str) -> None:
        self.tmux("send-keys", "-t", "app", *keys)

    def screen(self) -> str:
        return self.tmux("capture-pane", "-p", "-t", "app")

    def wait_for(self, ready, what: str, timeout: float = 20.0) -> str:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            screen = self.screen()
            if ready(screen):
                return screen
            time.sleep(0.1)
        raise AssertionError(f"timed out waiting for {what}; screen:\n{self.screen()}")

    def field(self, label: str) -> str:
        """The value the sheet shows after `label` (its value column: the label's 32 cells, a gap
        and the cell's leading space; the unit follows after a gap)."""
        for line in self.screen().splitlines():
            if line.startswith(f"│ {label} "):
                return line[VALUE_COLUMN : VALUE_COLUMN + VALUE_CELLS - 1].strip()
        raise AssertionError(f"no field {label!r} on screen")

    def close(self) -> None:
        self.tmux("kill-server")


def _settle(term: Terminal, label: str, expected: str) -> str:
    try:
        # returns as soon as it is there: the long timeout only costs time on a failure, and a
        # loaded machine (the app building the other cards meanwhile) took more than 3 s
        term.wait_for(lambda _: term.field(label) == expected, f"{label} = {expected!r}", timeout=10)
    except AssertionError:
        pass
    return term.field(label)


def _cursor_label(screen: str) -> str | None:
    """The field the line under the form explains (the cursor's row), from 'Label: help'."""
    import re

    lines = screen.splitlines()
    for i, line in enumerate(lines[:-1]):
        if line.startswith("│──"):
            found = re.match(r"│ ([^│:]+): ", lines[i + 1])
            return found.group(1) if found else None
    return None


def _open(term: Terminal, fkey: str, digit: str, seen: str) -> None:
    term.keys(fkey)
    time.sleep(0.3)
    term.keys(digit)
    term.wait_for(lambda screen: seen in screen, f"{fkey} {digit} to open the card with {seen!r}")
    # the card's sheet has the keys at once (its help line shows the cursor's row)
    term.wait_for(lambda screen: _cursor_label(screen) is not None, "the sheet to take focus", timeout=5)


def _type(term: Terminal, keys: list[str], gap: float) -> None:
    for k in keys:
        term.keys(k)
        time.sleep(gap)


@pytest.mark.parametrize("gap", [0.03, 0.1])
def test_tab_then_type_in_a_real_terminal(terminal, gap):
    """Tab then a value, at 30 and 100 ms a key, on two cards: right after start, and later."""
    failures = []
    # right after start: the motor card, cursor on its first row (Motor)
    _open(terminal, "F1", "1", "Free speed")
    _type(terminal, ["Tab", "Tab", "3", "Tab", "1", "1", "Tab"], gap)  # Motor data, Motors=3, Voltage=11
    for label, want in (("Motors", "3"), ("Voltage", "11")):
        if (got := _settle(terminal, label, want)) != want:
            failures.append(f"motor {label}: {got!r} (want {want!r})")
    # later, another card: the flywheel's wheel diameter and the next rows
    _open(terminal, "F5", "2", "Wheel diameter")
    screen = terminal.screen()
    assert "Wheel diameter" in screen
    for _ in range(12):
        if _cursor_label(terminal.screen()) == "Wheel diameter":
            break
        terminal.keys("Tab")
        time.sleep(0.15)
    assert _cursor_label(terminal.screen()) == "Wheel diameter", terminal.screen()
    _type(terminal, ["4", "Tab", "5", "Enter", "Up", "Up", "6"], gap)
    want = {"Wheel diameter": "6"}
    for label, value in want.items():
        if (got := _settle(terminal, label, value)) != value:
            failures.append(f"flywheel {label}: {got!r} (want {value!r})")
    assert not failures, failures


def test_no_color_starts_and_shows_flags_without_colour(tmp_path):
    if TMUX is None:
        pytest.skip("tmux is not installed (.ci/run installs it)")
    term = Terminal(tmp_path, NO_COLOR="1")
    try:
        screen = term.screen()
        assert "Free speed" in screen and "[ ] stator limit" in screen
        term.keys("F1")
        time.sleep(0.3)
        term.keys("1")
        term.keys("Tab")
        for _ in range(8):
            if _cursor_label(term.screen()) == "Effects":
                break
            term.keys("Down")
            time.sleep(0.15)
        term.keys("Space")
        term.wait_for(lambda s: "[x] stator limit" in s, "Space to tick the flag under the cursor")
        assert "[ ] supply limit" in term.screen()
    finally:
        term.close()


async def test_a_click_selects_a_row_and_a_click_on_its_value_edits_or_toggles_it():
    app = GearheadApp(blink=False, hide_timings=True, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = card(app)
        sheet = tab.sheet

        def line_of(name, option=None):
            return next(
                y
                for y, line in enumerate(sheet.lines)
                if line.first
                and sheet.stops[line.stop].field.name == name
                and sheet.stops[line.stop].option in (option, None)
            )

        await pilot.click(sheet, offset=(3, line_of("voltage")))  # on the label: selects
        assert sheet.current_field.name == "voltage" and not sheet.editing
        await pilot.click(sheet, offset=(1 + LABEL_CELLS + GAP + 2, line_of("motor_count")))  # on the value
        assert sheet.current_field.name == "motor_count" and sheet.editing
        await pilot.press("5")
        await pilot.press("enter")
        await settle(pilot)
        assert tab.entries["motor_count"] == "15"
        await pilot.click(sheet, offset=(1 + LABEL_CELLS + GAP + 2, line_of("effects", "supply_limit")))
        await settle(pilot)
        assert "supply_limit" in tab.entries["effects"] and "stator_limit" not in tab.entries["effects"]


TMUX_NAMES = {
    "tab": "Tab",
    "shift+tab": "BTab",
    "enter": "Enter",
    "escape": "Escape",
    "backspace": "BSpace",
    "space": "Space",
    "up": "Up",
    "down": "Down",
}


@pytest.mark.parametrize("seed", [1, 2])
def test_the_real_terminal_shows_what_the_model_holds(terminal, seed):
    """Screen truth in a real terminal: a seeded random sequence typed into the motor card at
    30-60 ms a key; the same keys replayed in a pilot app give the card's entries; every row
    value the terminal shows must be the one the model holds."""
    import asyncio
    import random

    rng = random.Random(seed)
    # no shift+tab: from the first row it leaves the sheet for the strip, where digits open cards
    pool = list("0123456789.") + ["tab", "enter", "escape", "backspace", "space", "up", "down"]
    keys = ["tab"] + [rng.choice(pool) for _ in range(40)] + ["escape"]
    _open(terminal, "F1", "1", "Free speed")
    for k in keys[1:]:
        terminal.keys(TMUX_NAMES.get(k, k))
        time.sleep(rng.uniform(0.03, 0.06))
    time.sleep(1.5)

    async def replay() -> dict[str, str]:
        app = GearheadApp(blink=False, hide_timings=True, initial="motor")
        async with app.run_test(size=(140, 45)) as pilot:
            await settle(pilot)
            app.current_tab.sheet.focus()
            for k in keys[1:]:
                app.post_message(key(k))
                await pilot.pause()
            await settle(pilot)
            sheet = card(app).sheet
            return {
                stop.field.label: sheet.value_text(stop).split(" ▾")[0]
                for stop in sheet.stops
                if stop.shape == "input"
            }

    held = asyncio.run(replay())
    screen = terminal.screen()
    shown = {label: terminal.field(label) for label in held if f"│ {label} " in screen}
    assert shown, screen
    assert shown == {label: held[label] for label in shown}, (keys, screen)
