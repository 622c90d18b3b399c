"""An unexpected failure is one line for the user and a traceback in the user's log directory."""

import pytest

from gearhead.core.errors import InputError
from gearhead.tui import cli


@pytest.fixture
def state_home(tmp_path, monkeypatch):
    from gearhead.tui import bug_log

    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    bug_log._logger.cache_clear()
    yield tmp_path / "state"
    log = bug_log._logger()
    for handler in list(log.handlers if log else ()):
        handler.close()
        log.removeHandler(handler)
    bug_log._logger.cache_clear()


def _boom(*args, **kwargs):
    raise KeyError("nowhere_to_be_found")


def _guarded(*args, **kwargs):
    try:
        1 / 0  # noqa: B018 (the point: an arithmetic error)
    except ZeroDivisionError as exc:
        raise InputError("(result)", "could not be computed from these inputs") from exc


def test_a_bug_on_the_cli_is_one_line_and_a_logged_traceback(state_home, monkeypatch, capsys):
    monkeypatch.setattr("gearhead.core.model.solve", _boom)
    assert cli.main(["solve", "gear_ratio"]) == cli.EXIT_INTERNAL
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "internal error (KeyError" in err and "traceback in" in err
    log = next(state_home.rglob("gearhead.log")).read_text()
    assert "Traceback" in log and "nowhere_to_be_found" in log and "gearhead solve gear_ratio" in log


def test_the_last_resort_guard_keeps_its_cause_in_the_log(state_home, monkeypatch, capsys):
    monkeypatch.setattr("gearhead.core.model.solve", _guarded)
    assert cli.main(["solve", "gear_ratio"]) == cli.EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "traceback in" in err
    assert "ZeroDivisionError" in next(state_home.rglob("gearhead.log")).read_text()


def test_a_wrong_entry_is_not_logged(state_home, capsys):
    assert cli.main(["solve", "gear_ratio", "--set", "voltage=12 furlongs"]) == cli.EXIT_BAD_INPUT
    assert "traceback" not in capsys.readouterr().err
    assert not list(state_home.rglob("gearhead.log"))


async def test_a_bug_in_the_app_is_a_status_line_and_a_logged_traceback(state_home, monkeypatch):
    from textual.widgets import Static

    from gearhead.tui.app import GearheadApp
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        monkeypatch.setattr("gearhead.core.solving.solve", _boom)
        app.current_tab.set_entries({"voltage": "11"})
        await settle(pilot)
        status = str(app.current_tab.query_one(".status", Static).render())
        assert "internal error: KeyError" in status
    assert "nowhere_to_be_found" in next(state_home.rglob("gearhead.log")).read_text()


def test_a_reader_that_leaves_early_is_not_an_error(state_home):
    """`gearhead sweep ... | head -1`: the pipe closes under a long table; no message, no log."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "XDG_STATE_HOME": str(state_home)}
    pipe = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "gearhead.tui",
            "sweep",
            "gear_ratio",
            "--vary",
            "voltage=1..12:5000",
        ],  # far more than a pipe's 64 KB buffer
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
    )
    pipe.stdout.readline()
    pipe.stdout.close()  # the reader leaves after one line
    err = pipe.stderr.read().decode()
    assert pipe.wait(timeout=60) in (0, cli.EXIT_BROKEN_PIPE)
    assert err == ""
    assert not list(state_home.rglob("gearhead.log"))
