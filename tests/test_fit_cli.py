"""`gearhead fit` (issue 44 item 6): text and --json on a synthetic SysId log, the card from its
defaults, a preset or a workbook; bad logs and entries exit 2 with one line naming what is wrong."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import pytest

from gearhead.tui.cli import main

pytest.importorskip("wpiutil")
sys.path.insert(0, str(Path(__file__).parent))
from fit_plants import simulate  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
ARM = {"kS": 0.15, "kV": 2.0, "kA": 0.2, "kG": 0.8, "offset": 0.3}


def run(capsys, *args):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture(scope="module")
def arm_log(tmp_path_factory):
    return simulate(tmp_path_factory.mktemp("fit") / "arm.wpilog", "arm", ARM, noise=0.002, jitter=0.001)


def test_json(capsys, arm_log):
    code, out, err = run(capsys, "fit", arm_log, "--card", "arm", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["card"] == "arm" and data["favoured"] in ("continuous", "discrete")
    assert data["signals"]["voltage"] == "voltage-motor-mech"
    for form in ("continuous", "discrete"):
        g = data["fits"][form]["gains"]
        assert g["kV"] == pytest.approx(2.0, rel=0.01) and g["kG"] == pytest.approx(0.8, rel=0.01)
        assert g["offset"] == pytest.approx(0.3, abs=0.01)
    entries = {e["entry"]: e for e in data["entries"]}
    assert entries["angle offset"]["fitted"] == pytest.approx(math.degrees(0.3), abs=0.6)
    assert set(data["replay"]) == {"design", "continuous", "discrete"}
    assert set(data["moves"]) == {"design", "fitted"} and data["moves"]["fitted"]["time_to_goal"] > 0


def test_text_and_preset(capsys, arm_log):
    code, out, err = run(
        capsys, "fit", arm_log, "--card", "arm", "--preset", ROOT / "presets/arm/single_kraken.toml"
    )
    assert code == 0, err
    assert "single_kraken.toml" in out and "favoured:" in out and "angle offset" in out
    assert "replay of the logged voltage" in out and "dynamic-forward: velocity measured" in out


def test_workbook_card(capsys, arm_log):
    code, out, err = run(
        capsys,
        "fit",
        arm_log,
        "--card",
        "arm",
        "--workbook",
        ROOT / "examples/robot_2027.toml",
        "--name",
        "arm",
    )
    assert code == 0, err
    assert "robot_2027.toml: arm" in out


@pytest.mark.parametrize(
    "extra, words",
    [
        (["--scale", "nan"], "--scale: is nan"),
        (["--scale", "-1"], "--scale: is -1.0"),
        (["--name", "arm"], "--name: names a workbook's card"),
        (["--preset", ROOT / "presets/elevator/two_neo.toml"], "is an elevator preset, not arm"),
        (["--routine", "nope"], "'sysid-test-state-nope' is not in the log"),
        (["--velocity", "nope"], "--velocity: no entry 'nope'"),
        (["--units", "furlongs"], "'furlongs', which cannot be converted"),
    ],
)
def test_bad_entries_exit_2(capsys, arm_log, extra, words):
    code, out, err = run(capsys, "fit", arm_log, "--card", "arm", *extra)
    assert code == 2 and out == ""
    assert words in err and err.count("\n") == 1


@pytest.mark.parametrize(
    "data, words",
    [
        (b"", "is not a WPILog"),
        (b"WPILOG\x00\x02\x00\x00\x00\x00", "version 2.0"),
        (b"WPILOG\x00\x01\x00\x00\x00\x00", "no SysId test state"),
    ],
)
def test_bad_logs_exit_2(capsys, tmp_path, data, words):
    path = tmp_path / "bad.wpilog"
    path.write_bytes(data)
    code, out, err = run(capsys, "fit", path, "--card", "flywheel", "--json")
    assert code == 2 and out == "" and str(path) in err and words in err


def test_missing_log_exits_2(capsys, tmp_path):
    code, _, err = run(capsys, "fit", tmp_path / "none.wpilog", "--card", "elevator")
    assert code == 2 and "none.wpilog: log: cannot be read" in err


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("card", ["elevator", "arm", "flywheel", "sprint"])
def test_unrelated_signals_give_a_fit_or_a_message(capsys, tmp_path, seed, card):
    """Voltage, position and velocity that have nothing to do with each other (random, some huge):
    a result or one line and exit 2, never a traceback or a NaN in the JSON."""
    import numpy as np
    import wpiutil
    from wpiutil import log as wlog

    rng = np.random.default_rng(seed)
    scale = [1.0, 1e-6, 1e150, 1e300, 1.0, 1e-300][seed]
    path = tmp_path / "junk.wpilog"
    w = wpiutil.DataLogWriter(str(path))
    st = wlog.StringLogEntry(w, "sysid-test-state-j", "", 1)
    es = [
        wlog.DoubleLogEntry(w, f"{r}-m-j", u, 1)
        for r, u in (("voltage", "Volt"), ("position", "Rotation"), ("velocity", "Rotation per Second"))
    ]
    t = 1000
    for state in ("quasistatic-forward", "quasistatic-reverse", "dynamic-forward", "dynamic-reverse", "none"):
        for _ in range(40 if seed != 4 else 3):
            st.append(state, t)
            for e in es:
                e.append(float(rng.normal(0, 1) * scale), t)
            t += 20_000
    w.flush()
    w.stop()
    del w
    code, out, err = run(capsys, "fit", path, "--card", card, "--json")
    assert code in (0, 2), err
    if code == 0:
        json.loads(out)  # allow_nan=False when written: no NaN or inf
    else:
        assert out == "" and err.count("\n") == 1 and str(path) in err


# --- --apply ---------------------------------------------------------------------------------------


def test_apply_writes_a_workbook_card_keeping_comments_and_links(capsys, tmp_path, arm_log):
    wb = tmp_path / "robot.toml"
    wb.write_text((ROOT / "examples/robot_2027.toml").read_text(encoding="utf-8"), encoding="utf-8")
    before = wb.read_text(encoding="utf-8")
    code, out, err = run(
        capsys, "fit", arm_log, "--card", "arm", "--workbook", wb, "--name", "arm", "--apply", "--json"
    )
    assert code == 0, err
    applied = json.loads(out)["applied"]
    after = wb.read_text(encoding="utf-8")
    assert after != before and applied["diff"].startswith("---")
    assert set(applied["changes"]) >= {"arm_mass", "moment_of_inertia", "inertia_model"}
    # every comment line is kept, and the card's link stays a link
    assert [line for line in before.splitlines() if "#" in line] == [
        line for line in after.splitlines() if "#" in line
    ]
    assert 'motor = "= mechanism_motor"' in after
    code, out, err = run(capsys, "check", wb, "--json")  # the workbook still loads and checks
    assert code in (0, 1), err
    assert json.loads(out)["card_errors"] == {}
    from gearhead.core import workbook

    card = workbook.load(wb).cards["arm"]
    assert card.inputs["inertia_model"] == "entered"


def test_apply_notes_a_linked_field_and_writes_the_rest(capsys, tmp_path):
    from gearhead.core.fit import entries

    card = entries.load_card("elevator")
    log = simulate(tmp_path / "lift.wpilog", "elevator", dict(card.design, kS=card.design["kS"] + 0.3))
    wb = tmp_path / "robot.toml"
    wb.write_text((ROOT / "examples/robot_2027.toml").read_text(encoding="utf-8"), encoding="utf-8")
    code, out, err = run(
        capsys, "fit", log, "--card", "elevator", "--workbook", wb, "--name", "lift", "--apply"
    )
    assert code == 0, err
    assert "note: load_mass is linked (= lift_load): not written" in out
    assert 'load_mass = "= lift_load"' in wb.read_text(encoding="utf-8")
    assert "friction_force" in wb.read_text(encoding="utf-8")


def test_apply_to_a_preset_copy(capsys, tmp_path, arm_log):
    preset = tmp_path / "arm.toml"
    preset.write_text("# my arm\n" + (ROOT / "presets/arm/single_kraken.toml").read_text(encoding="utf-8"))
    code, out, err = run(capsys, "fit", arm_log, "--card", "arm", "--preset", preset, "--apply")
    assert code == 0, err
    text = preset.read_text(encoding="utf-8")
    assert text.startswith("# my arm\n") and 'inertia_model = "entered"' in text and "written to" in out
    from gearhead.core import presets

    assert presets.load(preset).inputs["inertia_model"] == "entered"


@pytest.mark.parametrize(
    "extra, words",
    [
        ([], "--apply: needs the card's file"),
        # the installed built-in (from a clean clone installed without -e, the repository's presets/
        # is a plain file beside it: the test once wrote into it there)
        (["--preset", "BUILTIN"], "does not change a built-in preset"),
    ],
)
def test_apply_refused(capsys, arm_log, extra, words):
    from gearhead.core import presets

    extra = [presets.builtin_dir() / "arm/single_kraken.toml" if e == "BUILTIN" else e for e in extra]
    before = [p.read_bytes() for p in extra if isinstance(p, Path)]
    code, out, err = run(capsys, "fit", arm_log, "--card", "arm", "--apply", *extra)
    assert code == 2 and out == "" and words in err
    assert [p.read_bytes() for p in extra if isinstance(p, Path)] == before


def test_apply_writes_nothing_on_a_bad_log(capsys, tmp_path):
    wb = tmp_path / "robot.toml"
    wb.write_text((ROOT / "examples/robot_2027.toml").read_text(encoding="utf-8"), encoding="utf-8")
    before = wb.read_bytes()
    bad = tmp_path / "bad.wpilog"
    bad.write_bytes(b"WPILOG\x00\x01\x00\x00")  # cut off in its header
    code, _, err = run(capsys, "fit", bad, "--card", "arm", "--workbook", wb, "--name", "arm", "--apply")
    assert code == 2 and "bad.wpilog" in err
    assert wb.read_bytes() == before  # the flywheel's and sprint's: tests/test_fit_apply.py


def test_sprint_card(capsys, tmp_path):
    """`--card sprint` (issue 44 item 7): a drivetrain's log in metres, or in wheel rotations (times
    the wheel's radius); the robot's mass and the efficiency back from kA through the sprint card's
    motors, ratio and wheel (kA = m·R/(η·N·Kt·n), S9); --apply without the card's file refused
    (written into a file: tests/test_fit_apply.py)."""
    from gearhead.core.fit import entries

    card = entries.load_card("sprint")
    g = {"kS": card.design["kS"] * 3, "kV": card.design["kV"], "kA": card.design["kA"] * 1.2}
    log = simulate(tmp_path / "drive.wpilog", "sprint", g, period=0.02, step=4.0, dynamic_time=1.5)
    code, out, err = run(capsys, "fit", log, "--card", "sprint", "--json")
    assert code == 0, err
    data = json.loads(out)
    fitted = data["fits"][data["favoured"]]["gains"]
    for k in g:
        assert fitted[k] == pytest.approx(g[k], rel=0.01), k
    rows = {e["entry"]: e for e in data["entries"]}
    assert rows["moving mass"]["fitted"] == pytest.approx(1.2 * card.values["robot_mass"], rel=0.01)
    assert rows["moving mass"]["unit"] == "kg"
    assert rows["efficiency at the card's mass"]["fitted"] == pytest.approx(
        card.values["efficiency"] / 1.2, rel=0.01
    )
    assert rows["friction"]["fitted"] == pytest.approx(2 * card.design["kS"] * card.f, rel=0.01)
    code, out, err = run(capsys, "fit", log, "--card", "sprint", "--units", "rotation")
    assert code == 0, err
    assert "of the wheel, × its radius" in out
    code, out, err = run(capsys, "fit", log, "--card", "sprint", "--apply")
    assert code == 2 and out == "" and "--apply: needs the card's file" in err


def named_log(tmp_path, motor: bytes = b"m\xff") -> Path:
    """An elevator's SysId log whose motor's name is not UTF-8 (its three entries' names: the log
    written with motor 'mA', the two bytes then replaced)."""
    log = simulate(tmp_path / "bad-name.wpilog", "elevator", {"kS": 0.2, "kV": 10.0, "kA": 1.2, "kG": 0.6},
                   mech="lift", motor="mA")  # fmt: skip
    data = log.read_bytes()
    assert data.count(b"-mA-lift") == 3
    log.write_bytes(data.replace(b"-mA-lift", b"-" + motor + b"-lift"))
    return log


def test_a_name_not_utf8_is_shown_escaped_and_can_be_typed_as_shown(capsys, tmp_path):
    # it was shown with the replacement character (\ufffd), which no one can type back
    log = named_log(tmp_path)
    code, out, err = run(capsys, "fit", log, "--card", "elevator")
    assert code == 0, err
    assert "voltage 'voltage-m\\xff-lift'" in out and "\ufffd" not in out, out
    # typed as shown, or with the raw byte as a shell passes it (surrogateescape, as os.fsdecode)
    for name in ("voltage-m\\xff-lift", b"voltage-m\xff-lift".decode("utf-8", "surrogateescape")):
        code, out, err = run(capsys, "fit", log, "--card", "elevator", "--voltage", name, "--json")
        assert code == 0, err
        assert json.loads(out)["signals"]["voltage"] == "voltage-m\\xff-lift"
    code, out, err = run(capsys, "fit", log, "--card", "elevator", "--voltage", "voltage-m-lift")
    assert code == 2 and "no entry 'voltage-m-lift' in the log" in err
