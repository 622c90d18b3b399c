"""A bug in the running app is one line and a logged traceback, never Textual's traceback on the
terminal (issue 34 item 1): a handler of the app or a card reports it in a notification and the app
keeps what was typed (tui/guard.py); an exception that still reaches Textual ends the app with
the command line's one line and exit code 70 (tui/app.py run, tui/cli.py)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
import time
import uuid
from pathlib import Path

import pytest

from gearhead.tui import bug_log, cli
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
from tests.tui_helpers import settle

ROOT = Path(__file__).resolve().parent.parent
TMUX = shutil.which("tmux")
INJECTED = "injected by the test"


@pytest.fixture
def state_home(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    bug_log._logger.cache_clear()
    yield tmp_path / "state"
    log = bug_log._logger()
    for handler in list(log.handlers if log else ()):
        handler.close()
        log.removeHandler(handler)
    bug_log._logger.cache_clear()


def _boom(*args, **kwargs):
    raise TypeError(INJECTED)


async def test_a_key_whose_handler_raises_is_a_notice_and_a_logged_traceback(state_home, monkeypatch):
    """ctrl+y with a card method that raises: before, Textual ended the app with its traceback
    (run_test re-raised the TypeError) and nothing was logged."""
    app = GearheadApp(blink=False, initial="gear_ratio")
    notices = []
    notify = app.notify

    def keep(message, *args, **kwargs):
        notices.append((str(message), kwargs.get("severity")))
        return notify(message, *args, **kwargs)

    app.notify = keep
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        monkeypatch.setattr(CalculatorTab, "current_inputs", _boom)
        await pilot.press("ctrl+y")
        await settle(pilot)
        assert app.is_running and app.return_code is None  # still up, everything typed kept
        errors = [message for message, severity in notices if severity == "error"]
        assert len(errors) == 1 and "\n" not in errors[0]
        assert errors[0].startswith(f"internal error (TypeError: {INJECTED}) (traceback in ")
        monkeypatch.undo()  # the app works on: another key, another card
        await pilot.press("ctrl+y")
        await settle(pilot)
        assert notices[-1][0].startswith("Gear ratio copied")
    log = next(state_home.rglob("gearhead.log")).read_text()
    assert "Traceback" in log and INJECTED in log and "action_copy_share_code" in log


def test_textuals_report_is_read_as_one_line():
    """The last frame box of Rich's traceback, then the exception's line (wrapped), then a note."""
    report = (
        "╭─ Traceback ─╮\n│ x = 1 │\n╰─────────╯\nTypeError: a long\n message\n\nNOTE: 1 of 2 errors shown."
    )
    assert cli._exception_line(report) == "TypeError: a long message"
    assert cli._exception_line("") == "the app stopped"


# ---- the real app in a terminal (tmux), with a failure injected through sitecustomize ---------------


class Pane:
    """`python -m gearhead.tui` in a tmux pane of its own server; the pane stays after the app
    exits, showing what the app left on the terminal and its exit code."""

    def __init__(self, tmp: Path, shim: str) -> None:
        (tmp / "shim").mkdir()
        (tmp / "shim" / "sitecustomize.py").write_text(textwrap.dedent(shim))
        self.socket = f"gearhead-crash-{uuid.uuid4().hex[:8]}"
        self.env = {
            k: v
            for k, v in os.environ.items()
            if k not in ("NO_COLOR", "TEXTUAL_THEME", "TMUX", "COLUMNS", "LINES", "PYTHONPATH")
        }
        self.env.update(
            XDG_CONFIG_HOME=str(tmp / "config"),
            XDG_STATE_HOME=str(tmp / "state"),
            PYTHONPATH=str(tmp / "shim"),
        )
        command = f"cd {ROOT} && {sys.executable} -m gearhead.tui; echo EXIT=$?; sleep 600"
        self.tmux("new-session", "-d", "-s", "app", "-x", "140", "-y", "45", command)

    def tmux(self, *args: str) -> str:
        out = subprocess.run(
            [TMUX, "-L", self.socket, *args], capture_output=True, text=True, env=self.env, timeout=20
        )
        return out.stdout

    def screen(self) -> str:
        return self.tmux("capture-pane", "-p", "-J", "-t", "app")  # -J: a wrapped line as one

    def wait_for(self, text: str, timeout: float = 30.0) -> str:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            screen = self.screen()
            if text in screen:
                return screen
            time.sleep(0.1)
        raise AssertionError(f"timed out waiting for {text!r}; screen:\n{self.screen()}")

    def close(self) -> None:
        self.tmux("kill-server")


@pytest.fixture
def pane(tmp_path):
    if TMUX is None:
        pytest.skip("tmux is not installed")
    panes = []

    def start(shim: str) -> Pane:
        panes.append(Pane(tmp_path, shim))
        return panes[-1]

    yield start
    for p in panes:
        p.close()


def test_a_handler_that_raises_in_the_terminal_leaves_the_app_running(pane, tmp_path):
    """Before: a traceback filled the terminal and the exit code was 0."""
    term = pane(f"""
        from gearhead.tui.components import calculator_tab

        def _boom(self):
            raise TypeError({INJECTED!r})

        calculator_tab.CalculatorTab.current_inputs = _boom
    """)
    term.wait_for("Free speed")
    term.tmux("send-keys", "-t", "app", "C-y")
    term.wait_for(f"internal error (TypeError: {INJECTED})")
    term.tmux("send-keys", "-t", "app", "C-q")
    lines = [line for line in term.wait_for("EXIT=").splitlines() if line.strip()]
    assert lines == ["EXIT=0"]
    assert INJECTED in next((tmp_path / "state").rglob("gearhead.log")).read_text()


def test_an_exception_that_reaches_textual_is_one_line_and_exit_70(pane, tmp_path):
    """A failure no handler of ours catches (the sheet's drawing, as the NO_COLOR start crash
    was): Textual ends the app; the terminal shows the command line's one line, exit code 70,
    and the log has the traceback. Before: Rich's traceback on the terminal, exit code 0."""
    term = pane(f"""
        from gearhead.tui.components import sheet

        def _boom(self, y):
            raise TypeError({INJECTED!r})

        sheet.Sheet.render_line = _boom
    """)
    lines = [line for line in term.wait_for("EXIT=").splitlines() if line.strip()]
    assert len(lines) == 2, lines
    assert lines[0].startswith(f"gearhead: internal error (TypeError: {INJECTED}) (traceback in ")
    assert lines[1] == f"EXIT={cli.EXIT_INTERNAL}"
    log = next((tmp_path / "state").rglob("gearhead.log")).read_text()
    assert "render_line" in log and INJECTED in log


async def test_a_bug_in_a_solve_thread_is_a_notice_and_a_logged_traceback(state_home, monkeypatch):
    """The error estimate of a simulation runs in a worker after the results are shown: an
    exception there is a notice and a logged traceback (before, it ended the thread silently: the
    row kept its '…', nothing logged)."""
    app = GearheadApp(blink=False, initial="pneumatics")
    notices = []
    notify = app.notify

    def keep(message, *args, **kwargs):
        notices.append((str(message), kwargs.get("severity")))
        return notify(message, *args, **kwargs)

    app.notify = keep
    monkeypatch.setattr("gearhead.core.model.finish_estimate", _boom)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        app.current_tab.set_entries({"tank_volume": "1.5 L"})  # a card's later solves defer it
        await settle(pilot)
        for _ in range(100):
            if notices:
                break
            await pilot.pause(0.05)
        assert notices and all(severity == "error" for _, severity in notices)
        assert all(m.startswith(f"internal error (TypeError: {INJECTED}) (traceback in ") for m, _ in notices)
    assert "_estimate_worker" in next(state_home.rglob("gearhead.log")).read_text()


def test_a_bug_before_the_app_starts_is_the_same_one_line(state_home, monkeypatch, capsys):
    """`gearhead` with no arguments, failing before the app is built (reading its settings):
    before, a Python traceback."""
    monkeypatch.setattr(cli, "_terminal", lambda: True)
    monkeypatch.setattr("gearhead.tui.settings.load", _boom)
    assert cli.main([]) == cli.EXIT_INTERNAL
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"gearhead: internal error (TypeError: {INJECTED})")
    assert INJECTED in next(state_home.rglob("gearhead.log")).read_text()
