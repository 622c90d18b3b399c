"""Presets: TOML round trip, atomic and non-clobbering save, and clear errors naming file and field."""

import os
import stat
import subprocess
import sys
import threading
import tomllib
from pathlib import Path

import pytest

from gearhead.core import presets
from gearhead.core.errors import InputError
from gearhead.core.model import solve


def write(tmp_path, text, name="p.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


GOOD = """calculator = "gear_ratio"
name = "Lift"
description = "test"
format = 1

[inputs]
load = "25 lbf"
radius = 1.5
motor_count = 2
mode = "max_power"
"""


def test_builtin_presets_load_and_solve():
    found = presets.listing()
    assert {p.calculator for p in found} >= {"motor", "gear_ratio"}
    assert presets.problems() == []
    for p in found:
        assert p.builtin
        solve(p.calculator, p.inputs)


def test_round_trip_changes_nothing_typed(tmp_path):
    src = write(tmp_path, GOOD)
    p = presets.load(src)
    out = presets.save(p, tmp_path / "copy.toml")
    assert tomllib.loads(out.read_text()) == tomllib.loads(GOOD)
    assert presets.load(out).inputs == {
        "load": "25 lbf",
        "radius": 1.5,
        "motor_count": 2,
        "mode": "max_power",
    }


def test_save_never_overwrites_silently_and_leaves_no_temp_files(tmp_path):
    p = presets.load(write(tmp_path, GOOD))
    target = tmp_path / "out" / "lift.toml"
    presets.save(p, target)
    with pytest.raises(InputError) as e:
        presets.save(p, target)
    assert "exists" in e.value.message
    presets.save(p, target, overwrite=True)
    assert sorted(x.name for x in target.parent.iterdir()) == ["lift.toml"]


def test_user_presets_go_to_xdg_config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    p = presets.load(write(tmp_path, GOOD))
    path = presets.save(p)
    assert path == tmp_path / "cfg" / "gearhead" / "presets" / "gear_ratio" / "lift.toml"
    assert any(not q.builtin and q.name == "Lift" for q in presets.listing("gear_ratio"))


@pytest.mark.parametrize(
    "text,field,words",
    [
        (GOOD.replace('"gear_ratio"', '"warp_drive"'), "calculator", "unknown calculator"),
        (GOOD.replace("load =", "lode ="), "lode", "unknown field"),
        (GOOD.replace('"25 lbf"', '"25 kg"'), "load", "not a force"),
        (GOOD.replace('"25 lbf"', '"-25 lbf"'), "load", "too small"),
        (GOOD.replace("motor_count = 2", "motor_count = [2]"), "motor_count", "wrong type"),
        (GOOD.replace("format = 1", "format = 9"), "format", "newer"),
        (GOOD.replace('mode = "max_power"', 'mode = "fastest"'), "mode", "not one of"),
        (GOOD + "\n[inputs\n", "preset", "malformed TOML"),
    ],
)
def test_bad_presets_name_file_and_field(tmp_path, text, field, words):
    path = write(tmp_path, text)
    with pytest.raises(InputError) as e:
        presets.load(path)
    assert e.value.field == field
    assert words in e.value.message
    assert str(path) in str(e.value)


def test_broken_user_preset_is_reported_not_fatal(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    d = presets.user_dir() / "gear_ratio"
    d.mkdir(parents=True)
    (d / "bad.toml").write_text("this is not toml =")
    assert presets.listing("gear_ratio")  # built-ins still listed
    assert len(presets.problems("gear_ratio")) == 1


# ---- hostile preset files: each a one-line error naming the file, at once ---------------------


ROOT = Path(__file__).resolve().parents[1]
HEADER = 'calculator = "gear_ratio"\nformat = 1\n'


def hostile_files(tmp_path):
    """name -> (path, words the message must hold)."""
    files = {}
    deep_array = tmp_path / "deep_array.toml"
    deep_array.write_text(HEADER + "[inputs]\nload = " + "[" * 20_000 + "]" * 20_000 + "\n")
    files["deep array"] = (deep_array, "nested too deeply")
    deep_table = tmp_path / "deep_table.toml"
    deep_table.write_text(HEADER + "[inputs]\nload = " + "{a = " * 5_000 + "1" + "}" * 5_000 + "\n")
    files["deep inline table"] = (deep_table, "nested too deeply")
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    files["fifo"] = (fifo, "not a regular file")
    files["/dev/zero"] = (Path("/dev/zero"), "not a regular file")
    files["folder"] = (tmp_path, "folder")
    big = tmp_path / "big.toml"
    big.write_text(HEADER + "# " + "x" * presets.MAX_PRESET_BYTES + "\n")
    files["too large"] = (big, "too large")
    latin1 = tmp_path / "latin1.toml"
    latin1.write_bytes(HEADER.encode() + 'name = "\xc9l\xe9vateur"\n'.encode("latin-1"))
    files["not UTF-8"] = (latin1, "not UTF-8")
    negative = tmp_path / "negative_format.toml"
    negative.write_text(HEADER.replace("format = 1", "format = -1"))
    files["negative format"] = (negative, "whole number from 1")
    for name, value in (("float", "1.0"), ("string", '"1"'), ("zero", "0"), ("bool", "true")):
        p = tmp_path / f"format_{name}.toml"
        p.write_text(HEADER.replace("format = 1", f"format = {value}"))
        files[f"format {name}"] = (p, "whole number from 1")
    return files


def test_hostile_preset_files_are_clear_errors_naming_the_file(tmp_path):
    for kind, (path, words) in hostile_files(tmp_path).items():
        with pytest.raises(InputError) as e:
            presets.load(path)
        message = str(e.value)
        assert str(path) in message and words in message, (kind, message)
        assert "\n" not in message and len(message) < 300, (kind, message)


def test_hostile_presets_exit_2_from_the_cli_naming_the_file(tmp_path, capsys):
    """Deep nesting was a RecursionError traceback (exit 1), a FIFO hung, /dev/zero a MemoryError."""
    from gearhead.tui.cli import main

    for kind, (path, words) in hostile_files(tmp_path).items():
        if kind == "fifo":  # in a child process, so that a regression fails the test, not hangs it
            out = subprocess.run(
                [sys.executable, "-m", "gearhead.tui", "solve", "gear_ratio", "--preset", str(path)],
                capture_output=True,
                text=True,
                cwd=ROOT,
                timeout=60,
            )
            code, stdout, stderr = out.returncode, out.stdout, out.stderr
        else:
            code = main(["solve", "gear_ratio", "--preset", str(path)])
            stdout, stderr = capsys.readouterr()
        assert code == 2 and stdout == "", (kind, stderr[-300:])
        assert len(stderr.strip().splitlines()) == 1, (kind, stderr[-300:])
        assert str(path) in stderr and words in stderr, (kind, stderr)


def test_a_nul_in_the_path_is_a_clear_error():
    with pytest.raises(InputError) as e:
        presets.load("/tmp/a\0b.toml")
    assert "NUL" in e.value.message and "\\x00" in str(e.value) and "\n" not in str(e.value)


def test_the_presets_listing_reports_hostile_user_files_and_goes_on(tmp_path, capsys):
    from gearhead.tui.cli import main

    d = presets.user_dir() / "gear_ratio"
    d.mkdir(parents=True)
    os.mkfifo(d / "fifo.toml")
    (d / "deep.toml").write_text(HEADER + "x = " + "[" * 5000 + "]" * 5000 + "\n")
    (d / "good.toml").write_text(HEADER + 'name = "Mine"\n')
    assert main(["presets", "gear_ratio"]) == 0
    out, err = capsys.readouterr()
    assert "Mine" in out and "Elevator, 2 NEO" in out
    assert len(err.strip().splitlines()) == 2 and "fifo.toml" in err and "deep.toml" in err


def test_a_byte_order_mark_is_accepted(tmp_path):
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + GOOD.encode())
    assert presets.load(path).inputs["load"] == "25 lbf"


def test_a_junk_value_in_a_field_the_mode_ignores_is_a_warning_naming_it(tmp_path, capsys):
    from gearhead.tui.cli import main

    path = write(tmp_path, GOOD + 'target_linear_speed = "banana"\n')  # mode is max_power
    p = presets.load(path)
    assert len(p.warnings) == 1 and "target_linear_speed" in p.warnings[0] and str(path) in p.warnings[0]
    assert presets.load(write(tmp_path, GOOD + 'target_linear_speed = "5 ft/s"\n', "ok.toml")).warnings == []
    assert main(["solve", "gear_ratio", "--preset", str(path), "--json"]) == 0
    err = capsys.readouterr().err
    assert "warning" in err and "target_linear_speed" in err and len(err.strip().splitlines()) == 1


def test_two_saves_of_the_same_new_name_cannot_both_succeed(tmp_path, monkeypatch):
    """Both saves used to pass the exists() check, then both renamed into place."""
    p = presets.load(write(tmp_path, GOOD))
    target = tmp_path / "out" / "lift.toml"
    presets.save(p, target)
    monkeypatch.setattr(Path, "exists", lambda self: False)  # the second save checked before the first wrote
    with pytest.raises(InputError, match="exists"):
        presets.save(p, target)
    assert sorted(x.name for x in target.parent.iterdir()) == ["lift.toml"]


def test_simultaneous_saves_exactly_one_wins(tmp_path):
    p = presets.load(write(tmp_path, GOOD))
    target = tmp_path / "race" / "lift.toml"
    target.parent.mkdir()
    start, results = threading.Barrier(8), []

    def save():
        start.wait()
        try:
            presets.save(p, target)
            results.append("saved")
        except InputError:
            results.append("refused")

    threads = [threading.Thread(target=save) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results.count("saved") == 1 and results.count("refused") == 7
    assert sorted(x.name for x in target.parent.iterdir()) == ["lift.toml"]


def test_saved_files_get_the_umask_mode_and_a_replaced_file_keeps_its_mode(tmp_path):
    p = presets.load(write(tmp_path, GOOD))
    old = os.umask(0o022)
    try:
        new = presets.save(p, tmp_path / "new.toml")
        assert stat.S_IMODE(new.stat().st_mode) == 0o644
        os.chmod(new, 0o640)
        presets.save(p, new, overwrite=True)
        assert stat.S_IMODE(new.stat().st_mode) == 0o640
    finally:
        os.umask(old)


@pytest.mark.parametrize(
    "name,stem",
    [
        ("Élévateur", "élévateur"),
        ("日本語", "日本語"),
        ("Lift 2", "lift_2"),
        ("a/b\\c:d*?", "a_b_c_d"),
        ("CON", "con_preset"),
        ("...", "preset"),
        ("E\u0301le\u0301vateur", "élévateur"),
    ],
)
def test_file_names_keep_unicode_letters(name, stem):
    """`Élévateur` was `l_vateur.toml`; names of only non-ASCII letters were all `preset.toml`."""
    assert presets.slug(name) == stem


def test_long_names_save_under_a_capped_distinct_file_name(tmp_path, monkeypatch):
    """A 300-character name failed with an OS error (file name too long)."""
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    p = presets.load(write(tmp_path, GOOD))
    paths = []
    for name in ("x" * 300 + "a", "x" * 300 + "b", "Ä" * 300):
        p.name = name
        paths.append(presets.save(p))
        assert len(paths[-1].name.encode()) <= 255 and presets.load(paths[-1]).name == name
    assert len(set(paths)) == 3


def test_load_preview_shows_choices_by_their_labels():
    """The load dialog's preview reads like the form: a choice by its label (asked of the field's
    kind), a stale name as it was saved, other values as saved."""
    from gearhead.tui.components.preset_screens import preview

    preset = presets.Preset(
        "pneumatics",
        "probe",
        inputs={"pressure_model": "absolute", "accuracy": "retired_level", "tank_volume": "3.5 l"},
    )
    text = preview(preset).plain
    assert "Absolute P·V, isothermal" in text and "absolute" not in text.replace("Absolute", "")
    assert "retired_level" in text and "3.5 l" in text


def test_nesting_is_measured_without_recursing_and_skips_strings_and_comments():
    """tomllib recurses once per level: a 5000-deep preset ran deep into Python's stack before its
    RecursionError (a garbage collection at that depth once made pytest's report of an unrelated
    finalizer fail). The depth is measured first, strings and comments not counted."""
    from gearhead.core import presets

    assert presets.nesting("a = [1, [2, \"[[[ ]\"], {b = [3]}] # [[[[\nc = '''[[['''\n") == (3, 1)
    assert presets.nesting('x = "\\\\"\ny = [[[1]]]\n') == (3, 2)  # an escaped backslash ends the string
    assert presets.nesting("x = " + "[" * 5000 + "]" * 5000) == (5000, 1)
    with pytest.raises(InputError, match="nested too deeply"):
        presets.parse_text("x = " + "[" * (presets.MAX_NESTING + 1) + "]" * (presets.MAX_NESTING + 1))
    assert presets.parse_text("x = " + "[" * presets.MAX_NESTING + "]" * presets.MAX_NESTING)["x"]
