"""`gearhead fit` against a hostile user (issue 44's attack): paths that are not log files (a FIFO must
not hang, a device must not be read forever), logs whose values overflow the replay, --apply to
files that cannot take it. Each case: a message naming the field and what is wrong, exit 2, no
traceback, nothing written."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import warnings

import pytest

from gearhead.core.errors import InputError
from gearhead.core.fit import logs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _gearhead(*args, timeout=60):
    return subprocess.run(
        [sys.executable, "-m", "gearhead.tui", *args], capture_output=True, text=True, timeout=timeout
    )


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
@pytest.mark.parametrize("name", ["pipe.wpilog", "pipe.csv"])
def test_fifo_is_refused_not_waited_on(tmp_path, name):
    # open() of a FIFO with no writer blocks forever: the CLI hung, and the app's fit worker thread
    # with it (the app could not even quit: Python waits for the thread)
    path = tmp_path / name
    os.mkfifo(path)
    r = _gearhead("fit", str(path), "--card", "elevator", timeout=30)
    assert r.returncode == 2, r.stderr
    assert f"{path}: log: is a pipe (FIFO), not a log file" in r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_device_is_refused(device):
    if not os.path.exists(device):
        pytest.skip(f"no {device}")
    for name in (device,):
        with pytest.raises(InputError, match=f"{device}: log: is a device, not a log file"):
            logs.read(name, lambda n: True)


def test_directory_is_named(tmp_path):
    for suffix in ("", ".csv"):
        d = tmp_path / f"logs{suffix}"
        d.mkdir()
        with pytest.raises(InputError, match="log: is a directory, not a log file"):
            logs.read(d, lambda n: True)


# --- CSV: read as written, or refused naming the cell ---------------------------------------------


@pytest.mark.parametrize("cell", ["1_000", "١٢", "0x10", "1,5"])
def test_csv_cell_python_reads_but_no_log_writes_is_text_named(tmp_path, cell):
    # float() took '1_000' as 1000 and Arabic-Indic digits as 12: silently another number
    path = tmp_path / "log.csv"
    path.write_text(f'Timestamp,v\n0.5,1.0\n0.75,"{cell}"\n', encoding="utf-8")
    sigs, _, _ = logs.read(path, lambda n: True)
    assert not sigs["v"].numeric()
    assert [logs.is_number(x) for x in sigs["v"].values] == [True, False]


def test_csv_time_python_reads_but_no_log_writes_is_refused(tmp_path):
    path = tmp_path / "log.csv"
    path.write_text("Timestamp,v\n1_0,1.0\n", encoding="utf-8")
    with pytest.raises(InputError, match="line 2: the time '1_0' is not a number"):
        logs.read(path, lambda n: True)


def test_csv_two_columns_of_one_name_refused(tmp_path):
    # the second silently replaced the first
    path = tmp_path / "log.csv"
    path.write_text("Timestamp,v,w,v\n0,1,2,3\n", encoding="utf-8")
    with pytest.raises(InputError, match=r"has two columns named 'v' \(columns 2 and 4\)"):
        logs.read(path, lambda n: True)
    sigs, _, _ = logs.read(path, lambda n: n == "w")  # a twin not read is no matter
    assert list(sigs["w"].values) == [2.0]


def test_csv_endless_line_refused_in_bounded_memory(tmp_path, monkeypatch):
    monkeypatch.setattr(logs, "CSV_LINE", 1 << 12)
    path = tmp_path / "log.csv"
    path.write_text("Timestamp," + "v," * 5000 + "\n0,1\n", encoding="utf-8")
    with pytest.raises(InputError, match="has a line longer than"):
        logs.read(path, lambda n: True)
    path.write_text("Timestamp," + "v," * 1000 + "\n0,1\n", encoding="utf-8")  # long, but a line
    with pytest.raises(InputError, match="two columns named 'v'"):
        logs.read(path, lambda n: True)


def test_fit_names_the_text_cell_of_a_numeric_role(tmp_path, capsys):
    import csv as csvmod

    sys.path.insert(0, os.path.dirname(__file__))
    from fit_plants import simulate

    from gearhead.tui.cli import main

    pytest.importorskip("wpiutil")
    src = tmp_path / "src.csv"
    simulate(tmp_path / "src.wpilog", "elevator", ELEVATOR, csv_path=src, noise=1e-3)
    rows = list(csvmod.reader(src.open()))
    rows[700][2] = "1_000"
    bad = tmp_path / "bad.csv"
    with bad.open("w", newline="") as f:
        csvmod.writer(f).writerows(rows)
    assert main(["fit", str(bad), "--card", "elevator", "--units", "meters"]) == 2
    err = capsys.readouterr().err
    assert "voltage-motor-mech: holds text, not the voltage's numbers: '1_000' at t = " in err


ELEVATOR = {"kS": 0.2, "kV": 3.0, "kA": 0.3, "kG": 0.5}


def test_replay_overflow_is_a_note_not_a_warning(tmp_path, capsys):
    # a position of 1e308 m overflowed the replay's squared error: numpy's RuntimeWarning on
    # stderr and a '-' in the table with no word of why
    sys.path.insert(0, os.path.dirname(__file__))
    from fit_plants import simulate

    from gearhead.tui.cli import main

    pytest.importorskip("wpiutil")
    src = tmp_path / "src.csv"
    simulate(tmp_path / "src.wpilog", "elevator", ELEVATOR, csv_path=src, noise=1e-3)
    lines = src.read_text().splitlines()
    cells = lines[700].split(",")
    cells[3] = "1e308"
    lines[700] = ",".join(cells)
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join(lines) + "\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        assert main(["fit", str(bad), "--card", "elevator", "--json"]) == 0
    out = capsys.readouterr().out
    import json

    data = json.loads(out)
    assert data["replay"][data["favoured"]]["position_rmse"] is None
    assert any(
        "position-motor-mech: the replay's position error is beyond the float range" in n and "1e+308" in n
        for n in data["notes"]
    )


# --- --apply --------------------------------------------------------------------------------------

WORKBOOK = """format = 1
name = "hostile"
# the lift, inline
[cards]
lift = { calculator = "elevator", inputs = { load_mass = "15 lb", ratio = 9 } }  # keep me
"""


@pytest.fixture(scope="module")
def lift_log(tmp_path_factory):
    pytest.importorskip("wpiutil")
    sys.path.insert(0, os.path.dirname(__file__))
    from fit_plants import simulate

    return simulate(tmp_path_factory.mktemp("lift") / "lift.wpilog", "elevator", ELEVATOR, noise=1e-3)


def test_apply_to_a_workbook_with_a_byte_order_mark_and_crlf(tmp_path, lift_log, capsys):
    # the card loaded (presets.read_text takes a BOM) but --apply read the file itself: "is not
    # TOML (Empty key at line 1 col 0)"; and a CRLF file came back LF
    from gearhead.tui.cli import main

    wb = tmp_path / "wb.toml"
    wb.write_bytes(b"\xef\xbb\xbf" + WORKBOOK.replace("\n", "\r\n").encode())
    code = main(
        ["fit", str(lift_log), "--card", "elevator", "--workbook", str(wb), "--name", "lift", "--apply"]
    )
    assert code == 0, capsys.readouterr().err
    after = wb.read_bytes().decode("utf-8-sig")
    assert "\n" not in after.replace("\r\n", "") and "# keep me\r\n" in after
    assert 'load_mass = "15 lb"' not in after and "kg" in after
    assert main(["check", str(wb)]) == 0


@pytest.mark.parametrize("where", ["workbook", "preset"])
def test_apply_refuses_a_file_changed_since_it_was_read(tmp_path, lift_log, monkeypatch, capsys, where):
    # the fitted entries come from the card as read (its motor, ratio, spool): a ratio changed on
    # disk meanwhile had them written beside it, silently wrong
    from gearhead.core.fit import entries
    from gearhead.tui.cli import main

    path = tmp_path / "card.toml"
    if where == "workbook":
        path.write_text(WORKBOOK, encoding="utf-8")
        args = ["--workbook", str(path), "--name", "lift"]
    else:
        path.write_text(
            'format = 1\ncalculator = "elevator"\nname = "lift"\n[inputs]\nload_mass = "15 lb"\nratio = 9\n',
            encoding="utf-8",
        )
        args = ["--preset", str(path)]
    real = entries.load_card

    def load_then_edit(*a, **k):
        card = real(*a, **k)
        path.write_text(path.read_text(encoding="utf-8").replace("ratio = 9", "ratio = 12"), encoding="utf-8")
        return card

    monkeypatch.setattr(entries, "load_card", load_then_edit)
    capsys.readouterr()
    code = main(["fit", str(lift_log), "--card", "elevator", *args, "--apply", "--json"])
    err = capsys.readouterr().err
    assert code == 2 and f"{where}: changed on disk since it was read" in err and "nothing written" in err
    edited = path.read_text(encoding="utf-8")
    assert "ratio = 12" in edited and "friction_force" not in edited and "15 lb" in edited


def test_preset_takes_what_every_preset_option_takes_and_apply_names_what_it_will_not_change(
    lift_log, capsys, tmp_path
):
    # README: --preset takes a file, builtin:CALC/NAME or a share code; `fit` said "file not found"
    # for builtin:elevator/two_neo, and --apply to `--workbook builtin:robot_2027` said the same
    from gearhead.tui.cli import main

    log = str(lift_log)
    wb = ["--workbook", "builtin:robot_2027", "--name", "lift"]
    assert main(["fit", log, "--card", "elevator", "--preset", "builtin:elevator/two_neo", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["card_source"] == "builtin:elevator/two_neo"
    for args, words in (
        (["--preset", "builtin:elevator/two_neo"], "--apply: does not change a built-in preset"),
        (wb, "--apply: does not change an example workbook"),
        (["--preset", ""], "--preset: is empty"),
    ):
        assert main(["fit", log, "--card", "elevator", *args, "--apply"]) == 2
        err = capsys.readouterr().err
        assert words in err and err.count("\n") == 1, err
    assert main(["share", os.path.join(ROOT, "presets/elevator/two_neo.toml")]) == 0
    code = capsys.readouterr().out.split()[0]
    assert main(["fit", log, "--card", "elevator", "--preset", code, "--apply"]) == 2
    assert "--apply: writes into a preset file; this preset is not one" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


# --- options and signals named wrong ------------------------------------------------------------------


@pytest.mark.parametrize(
    "args, words",
    [
        # a voltage named as the current (its metadata says Volt) was fitted as amps, silently
        (["--current", "voltage-motor-mech"], "voltage-motor-mech: has the unit 'Volt'; a current in amps"),
        (
            ["--bus-voltage", "position-motor-mech"],
            "position-motor-mech: has the unit 'Meter'; a voltage in volts",
        ),
        # an empty option (an unset shell variable) was read as not given
        (["--units", ""], "--units: is empty"),
        (["--state", " "], "--state: is empty"),
        (["--motor", ""], "--motor: is empty"),
        # position × 1e308 overflowed to inf: numpy's RuntimeWarning, then a wrong reason
        (["--scale", "1e308"], "position-motor-mech: overflows when scaled to SI (× 1e+308"),
    ],
)
def test_a_wrong_option_is_named(lift_log, capsys, args, words):
    from gearhead.tui.cli import main

    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        assert main(["fit", str(lift_log), "--card", "elevator", *args]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1, err


def test_a_long_unit_is_cut_in_the_message(tmp_path):
    from gearhead.core.fit.signals import unit_factor

    with pytest.raises(InputError) as exc:
        unit_factor("Furlong" * 5000, False, "position", "log")
    assert len(str(exc.value)) < 300


def test_a_battery_whose_voltage_rises_with_current_is_not_fitted(tmp_path):
    # R = -0.03 Ω was shown as the "battery + wiring resistance", ± its sigma, as a fitted entry
    pytest.importorskip("wpiutil")
    sys.path.insert(0, os.path.dirname(__file__))
    from fit_plants import simulate

    from gearhead.core import fit

    g = {"kS": 0.2, "kV": 3.0, "kA": 0.3, "kG": 0.5}
    path = simulate(tmp_path / "bat.wpilog", "elevator", g, battery=(12.6, -0.03, 1, 0.1, 1.4), noise=1e-3)
    r = fit.fit_log(path, "elevator")
    assert not any(e[0] == "battery + wiring resistance" for e in r.entries)
    assert any("battery resistance not fitted" in n and "≤ 0" in n for n in r.notes), r.notes


# --- the app ------------------------------------------------------------------------------------------


def test_enter_pressed_again_as_the_palette_runs_a_command_does_not_end_the_app(tmp_path):
    # ctrl+p, a command, then Enter Enter Enter in one burst (how "Fit from log…" is reached, and
    # what a key storm on the fit dialog typed): Textual's palette dismissed itself once per Enter,
    # popping the screens below it, and ended the app with ScreenStackError
    import time

    from tests.test_storm import TMUX, Storm

    if TMUX is None:
        pytest.skip("tmux is not installed")
    storm = Storm(tmp_path)
    try:
        deadline = time.monotonic() + 20
        while "F1 Motors" not in storm.screen():
            assert time.monotonic() < deadline, storm.screen()
            time.sleep(0.1)
        for command in ("Open Elevator", "Open Motor", "Open Arm"):
            storm.tmux("send-keys", "-t", "app", "C-p")
            time.sleep(0.6)
            storm.tmux("send-keys", "-t", "app", "-l", command)
            time.sleep(0.8)
            storm.tmux("send-keys", "-t", "app", "Enter", "Enter", "Enter")
            time.sleep(1.0)
            assert "GEARHEAD-EXIT=" not in storm.screen(), (command, storm.screen())
        assert "Traceback" not in storm.log_text(), storm.log_text()[-3000:]
    finally:
        storm.tmux("kill-server")


async def test_esc_during_a_long_fit_leaves_nothing_the_app_waits_for_on_quitting(monkeypatch):
    # the fit ran in the worker's own (executor) thread: after Esc it read on (a 170 MB log:
    # 20-45 s), and the app, whose exit joins that thread, took as long to end after ctrl+q
    import threading

    from gearhead.core import fit as fitmod
    from gearhead.tui.app import GearheadApp
    from tests.test_fit_app import SIZE, open_fit

    release, ran = threading.Event(), []

    def slow(*args, **kwargs):
        ran.append(threading.current_thread().daemon)
        release.wait(30)
        raise InputError("log", "released")

    monkeypatch.setattr(fitmod, "fit_log", slow)
    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    try:
        async with app.run_test(size=SIZE) as pilot:
            screen = await open_fit(pilot)
            screen.query_one("#fit-path").value = "whatever.wpilog"
            await pilot.press("enter")
            await pilot.pause(0.2)
            assert ran == [True], "the fit runs where the app's exit would wait for it"
            await pilot.press("escape")
            await pilot.pause(0.2)
            assert not isinstance(app.screen, type(screen))
    finally:
        release.set()
