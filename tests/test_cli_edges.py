"""The command line's edges found by the second fuzz (issue 34 item 6): an empty --preset or
--preset-out, stdout closed or full, no terminal for the app, control characters in a preset's
name, junk in a field the mode does not use, and bounds in `calculators --json`."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from gearhead.core.registry import calculators
from gearhead.tui.cli import EXIT_BAD_INPUT, EXIT_IO, main

ROOT = Path(__file__).resolve().parents[1]


def _cli(*args, **kwargs):
    return subprocess.run(
        [sys.executable, "-m", "gearhead.tui", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=60,
        **kwargs,
    )


@pytest.mark.parametrize(
    "args,option",
    [
        (["solve", "motor", "--preset", ""], "--preset"),
        (["solve", "motor", "--preset", "  "], "--preset"),
        (["solve", "motor", "--preset-out", ""], "--preset-out"),
        (["accuracy", "pneumatics", "--preset", ""], "--preset"),
        (["sweep", "motor", "--vary", "voltage=6..12:3", "--preset", ""], "--preset"),
    ],
)
def test_an_empty_preset_option_is_an_error_not_ignored(capsys, args, option):
    """`--preset ""` (an unset shell variable) solved the defaults, `--preset-out ""` wrote nothing,
    both saying nothing."""
    assert main(args) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert f"{option}: is empty" in err and len(err.strip().splitlines()) == 1


def test_solve_with_stdout_closed_fails_saying_so():
    """`gearhead solve motor --json >&-` printed nothing and exited 0."""
    out = subprocess.run(
        f"{sys.executable} -m gearhead.tui solve motor --json >&-",
        shell=True,
        capture_output=False,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
        timeout=60,
    )
    assert out.returncode == EXIT_IO and "standard output is closed" in out.stderr


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="no /dev/full")
@pytest.mark.parametrize("json_flag", [[], ["--json"]])
def test_solve_to_a_full_disk_fails_saying_so(json_flag):
    with open("/dev/full", "w") as full:
        out = subprocess.run(
            [sys.executable, "-m", "gearhead.tui", "solve", "motor", *json_flag],
            stdout=full,
            stderr=subprocess.PIPE,
            text=True,
            cwd=ROOT,
            timeout=60,
        )
    assert out.returncode == EXIT_IO and "cannot write the results" in out.stderr
    assert "Traceback" not in out.stderr and len(out.stderr.strip().splitlines()) == 1


def test_the_app_with_no_terminal_exits_at_once_saying_why():
    """`gearhead < /dev/null > file` drew the app into the file and never exited."""
    out = subprocess.run(
        [sys.executable, "-m", "gearhead.tui"],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=60,
    )
    assert out.returncode == EXIT_BAD_INPUT and "needs a terminal" in out.stderr and out.stdout == ""


def test_control_characters_in_a_preset_name_are_shown_escaped(capsys):
    """A name holding ESC [2J (clear screen) or an OSC sequence was printed raw by `presets`."""
    from gearhead.core import presets

    folder = presets.user_dir() / "motor"
    folder.mkdir(parents=True)
    name = "Evil\x1b[2J\x1b]0;title\x07\x9b name"
    escaped = "".join(c if c.isprintable() else f"\\u{ord(c):04x}" for c in name)  # TOML's escapes
    (folder / "evil.toml").write_text(
        f'calculator = "motor"\nname = "{escaped}"\n[inputs]\n', encoding="utf-8"
    )
    assert main(["presets", "motor"]) == 0
    out = capsys.readouterr().out
    assert "Evil" in out and "\\x1b[2J" in out and "\\x07" in out and "\\x9b" in out
    assert not any(ch != "\n" and not ch.isprintable() for ch in out)


def test_junk_in_a_field_the_mode_does_not_use_is_a_warning_and_not_reported_as_entered(capsys):
    """`--set target_current=banana` in max-power mode was dropped without the promised warning,
    and --json showed value 40 beside text "banana"."""
    args = ["solve", "gear_ratio", "--set", "mode=max_power", "--set", "target_current=banana"]
    assert main([*args, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["inputs"]["target_current"] == {"value": 40.0, "unit": "A", "text": "40 A"}
    (warning,) = [w for w in data["warnings"] if w.startswith("target_current:")]
    assert "ignored" in warning and "banana" in warning and "40 A" in warning
    assert main(args) == 0
    assert "warning: target_current: ignored" in capsys.readouterr().out


def test_calculators_json_lists_each_numeric_fields_bounds(capsys):
    assert main(["calculators", "--json"]) == 0
    described = {c["id"]: c for c in json.loads(capsys.readouterr().out)}
    for calc_id, calc in calculators().items():
        for f, d in zip(calc.fields, described[calc_id]["fields"]):
            assert d["name"] == f.name
            if not f.kind.numeric:
                assert "min" not in d
                continue
            lo, hi = f.bounds_si()
            assert d["min"] == f.min and d["max"] == f.max
            assert d["min_si"] == lo and d["max_si"] == hi
            assert d["min_exclusive"] == f.min_exclusive and d["max_exclusive"] == f.max_exclusive
    wall = {f["name"]: f for f in described["beam"]["fields"]}["wall"]
    assert wall["unit"] == "in" and wall["min_si"] == 0 and wall["min_exclusive"]
