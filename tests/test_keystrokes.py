"""Every keystroke is kept, in order, however fast it comes and whatever the app is doing.

In a real terminal a burst of keys arrives in one read. Textual's Input used to insert printable
keys at once while its bound keys (backspace, ctrl+u…) bubbled to the app first, so they were
applied late: Backspace, Backspace, 3 on `12` gave `1`. The pilot test posts keys the way the
terminal driver does (no waiting between them); the tmux test types into the real app.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest
from textual import events
from textual.widgets import Input

from gearhead.tui.app import GearheadApp
from tests.tui_helpers import started

ROOT = Path(__file__).resolve().parents[1]

BURSTS = [
    # (start text, keys as (key, character), expected text)
    ("12", [("backspace", "\x7f"), ("backspace", "\x7f"), ("3", "3")], "3"),
    ("12", [("ctrl+u", "\x15"), ("1", "1"), ("2", "2")], "12"),
    ("12", [("left", None), ("left", None), ("9", "9")], "912"),
    ("19.05", [("home", None), ("delete", None), ("8", "8"), ("end", None), ("backspace", "\x7f")], "89.0"),
]


@pytest.mark.parametrize("start,keys,expected", BURSTS)
async def test_key_burst_applied_in_order(start, keys, expected):
    app = GearheadApp(blink=False, hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await started(pilot)
        entry = app.query_one("#in-voltage", Input)
        entry.focus()
        entry.value = start
        entry.cursor_position = len(start)
        await pilot.pause()
        for key, char in keys:  # posted back to back, as the driver does for one read
            app.post_message(events.Key(key, char))
        for _ in range(5):
            await pilot.pause()
        assert entry.value == expected


# ---- the real terminal ---------------------------------------------------------------------

TMUX = shutil.which("tmux")


class Terminal:
    """The app running in a tmux pane of its own server (never the user's tmux)."""

    def __init__(self, tmp: Path) -> None:
        self.socket = f"gearhead-test-{uuid.uuid4().hex[:8]}"
        # COLUMNS/LINES (set under pytest-xdist) would override the pane's size in Textual
        env = {
            k: v
            for k, v in os.environ.items()
            if k not in ("NO_COLOR", "TEXTUAL_THEME", "TMUX", "COLUMNS", "LINES")
        }
        env["XDG_CONFIG_HOME"] = str(tmp / "config")
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
        """The text in the entry after `label` on the form."""
        for line in self.screen().splitlines():
            if line.startswith(f"│ {label} "):
                # the entry, then a wide gap before the unit label
                return re.split(r"\s{3,}", line[len(label) + 2 :].split("│")[0].strip())[0]
        raise AssertionError(f"no field {label!r} on screen")

    def close(self) -> None:
        self.tmux("kill-server")


@pytest.fixture
def terminal(tmp_path):
    if TMUX is None:
        pytest.skip("tmux is not installed (.ci/run installs it)")
    term = Terminal(tmp_path)
    try:
        yield term
    finally:
        term.close()


def _settle(term: Terminal, label: str, expected: str) -> str:
    try:
        # returns as soon as it is there: the long timeout only costs time on a failure, and a
        # loaded machine (the app building the other cards meanwhile) took more than 3 s
        term.wait_for(lambda _: term.field(label) == expected, f"{label} = {expected!r}", timeout=10)
    except AssertionError:
        pass
    return term.field(label)


def _help_label(screen: str) -> str | None:
    """The field the line under the form explains (the focused one), from 'Label: help'."""
    lines = screen.splitlines()
    for i, line in enumerate(lines[:-1]):
        if line.startswith("│──"):
            found = re.match(r"│ ([^│:]+): ", lines[i + 1])
            return found.group(1) if found else None
    return None


def _tab_to(term: Terminal, label: str, most: int = 6) -> None:
    """Tab until focus is on the field `label`, each Tab seen to land before the next is sent
    (the line under the form names the focused field). A fixed pause per Tab was too short on a
    loaded machine; and the F-key's focus on the strip, when it comes after the first Tab, puts
    focus back on the strip: the next Tab then starts over, so Tab on until the field is reached."""
    for _ in range(most):
        before = _help_label(term.screen())
        term.keys("Tab")
        try:
            term.wait_for(
                lambda screen, before=before: _help_label(screen) != before, "the focus to move", timeout=3
            )
        except AssertionError:
            pass  # focus went to the strip (no help line of its own), or from it to the same field
        if _help_label(term.screen()) == label:
            return
    raise AssertionError(f"Tab never reached the {label} field; screen:\n{term.screen()}")


def test_keys_kept_in_a_real_terminal(terminal):
    # F1 1 puts focus on the calculator strip at Motor; Tab then walks motor, motor data, motors.
    # This also proves the two-key navigation in a real terminal. Then prove we are there.
    terminal.keys("F5")
    time.sleep(0.3)
    terminal.keys("2")
    terminal.wait_for(lambda screen: "Wheel diameter" in screen, "F5 2 to open the flywheel")
    terminal.keys("F1")
    time.sleep(0.3)
    terminal.keys("1")
    terminal.wait_for(lambda screen: "Free speed" in screen, "F1 1 to open the motor tab")
    _tab_to(terminal, "Motors")
    terminal.keys("C-u")
    terminal.keys("7")
    assert _settle(terminal, "Motors", "7") == "7", "focus is not on the Motors field"

    failures = []
    for trial in range(4):
        # Backspace, Backspace, 3 in one burst on "12" (was "1" or "" every time)
        terminal.keys("C-u")
        _settle(terminal, "Motors", "")
        terminal.keys("1", "2")
        _settle(terminal, "Motors", "12")
        terminal.keys("BSpace", "BSpace", "3")
        if (got := _settle(terminal, "Motors", "3")) != "3":
            failures.append(f"burst {trial}: {got!r}")
        # ctrl+u then 2 4 in one burst (the field used to be left empty)
        terminal.keys("C-u", "2", "4")
        if (got := _settle(terminal, "Motors", "24")) != "24":
            failures.append(f"ctrl+u burst {trial}: {got!r}")

    # human speed, 100 ms a key, while each key starts a solve: the Voltage entry on the next row
    _tab_to(terminal, "Voltage")
    for text in ("11 V", "-3 V", "9.05 V"):
        terminal.keys("C-u")
        for ch in text:
            terminal.keys("-l", ch)
            time.sleep(0.1)
        if (got := _settle(terminal, "Voltage", text)) != text:
            failures.append(f"typed {text!r}: {got!r}")
    assert not failures, failures


@pytest.mark.parametrize(
    "calc_id", sorted(__import__("gearhead.core.registry", fromlist=["x"]).calculators())
)
async def test_key_bursts_kept_in_every_tab(calc_id):
    """Every entry of every tab is a FieldInput: a burst typed while the tab solves is kept."""
    from gearhead.core.registry import get
    from gearhead.tui.components.field_input import FieldInput

    app = GearheadApp(blink=False, initial=calc_id, hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await started(pilot)
        tab = app.query_one(f"#calc-{calc_id}")
        entries = list(tab.query(Input))
        assert entries and all(isinstance(e, FieldInput) for e in entries)
        field = next(f for f in get(calc_id).fields if f.type in ("quantity", "int"))
        entry = tab.query_one(f"#in-{field.name}", Input)
        entry.focus()
        await pilot.pause()
        # ctrl+u, "12", backspace, backspace, "7", "8" in one burst, while the tab is solving
        for key, char in [
            ("ctrl+u", "\x15"),
            ("1", "1"),
            ("2", "2"),
            ("backspace", "\x7f"),
            ("backspace", "\x7f"),
            ("7", "7"),
            ("8", "8"),
        ]:
            app.post_message(events.Key(key, char))
        for _ in range(5):
            await pilot.pause()
        assert entry.value == "78"


def test_focus_moves_leave_no_stale_cells(terminal):
    """The home screen does not repaint itself whole when focus moves (HomeScreen): the widgets
    gaining and losing focus repaint themselves. What the terminal shows after Tab through the
    fields (drawn piece by piece) must equal a full redraw (forced by a resize), colours and
    attributes included, except the focused entry's row (its cursor blinks)."""
    terminal.keys("F1")
    time.sleep(0.3)
    terminal.keys("1")
    terminal.wait_for(lambda screen: "Free speed" in screen, "F1 1 to open the motor tab")
    _tab_to(terminal, "Operating torque", most=10)  # strip, Motor, Motor data, Motors, …
    time.sleep(1.0)

    def rows() -> list[str]:
        screen = terminal.tmux("capture-pane", "-e", "-p", "-t", "app").splitlines()
        plain = terminal.screen().splitlines()
        return [row for row, text in zip(screen, plain) if not text.startswith("│ Operating torque")]

    drawn = rows()
    terminal.tmux("resize-window", "-t", "app", "-x", "139")
    time.sleep(0.5)
    terminal.tmux("resize-window", "-t", "app", "-x", "140")
    time.sleep(1.0)
    redrawn = rows()
    assert len(redrawn) >= 40 and any("Free speed" in row for row in redrawn)
    stale = [i for i, (a, b) in enumerate(zip(drawn, redrawn)) if a != b]
    assert drawn == redrawn, f"rows differing from a full redraw: {stale}"
