"""The command line: JSON shape (DESIGN.md), exit status 2 with a one-line message on bad input."""

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]


def run(capsys, *args):
    code = main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_solve_gear_ratio_preset_json(capsys):
    code, out, _ = run(
        capsys,
        "solve",
        "gear_ratio",
        "--preset",
        str(ROOT / "presets/gear_ratio/elevator_neo.toml"),
        "--json",
    )
    assert code == 0
    data = json.loads(out)
    assert data["calculator"] == "gear_ratio"
    assert set(data) == {"calculator", "inputs", "outputs", "warnings"}
    assert data["inputs"]["load"] == {"value": pytest.approx(177.928864610), "unit": "N", "text": "40 lbf"}
    for name in [
        "ratio",
        "free_speed",
        "loaded_speed",
        "linear_free_speed",
        "linear_loaded_speed",
        "current_per_motor",
        "stall_load",
        "stall_voltage",
    ]:
        assert name in data["outputs"]
    assert data["outputs"]["loaded_speed"]["unit"] == "rad/s"
    assert data["outputs"]["stall_load"]["unit"] == "N"
    assert data["outputs"]["ratio"]["unit"] == ""
    assert data["outputs"]["linear_loaded_speed"]["value"] == pytest.approx(5 * 0.3048)


def test_solve_motor_json_has_required_outputs(capsys):
    code, out, _ = run(capsys, "solve", "motor", "--set", "motor=NEO", "--set", "motor_count=2", "--json")
    data = json.loads(out)
    for name in [
        "free_speed",
        "stall_torque",
        "stall_current",
        "free_current",
        "peak_power",
        "kt",
        "max_efficiency",
        "max_efficiency_torque",
    ]:
        assert math.isfinite(data["outputs"][name]["value"])
    assert data["outputs"]["stall_torque"]["value"] == pytest.approx(5.2)
    assert data["outputs"]["kt"]["unit"] == "N*m/A"


@pytest.mark.parametrize(
    "args,field",
    [
        (["solve", "gear_ratio", "--set", "load=abc"], "load"),
        (["solve", "gear_ratio", "--set", "radius=3 kg"], "radius"),
        (["solve", "gear_ratio", "--set", "wheels=4"], "wheels"),
        (["solve", "motor", "--set", "motor_count=0"], "motor_count"),
        (["solve", "nope"], "calculator"),
    ],
)
def test_bad_input_exits_2_naming_the_field(capsys, args, field):
    code, out, err = run(capsys, *args)
    assert code == 2
    assert out == ""
    assert len(err.strip().splitlines()) == 1 and f"{field}:" in err


def test_calculators_and_presets_listings(capsys):
    code, out, _ = run(capsys, "calculators", "--json")
    ids = [c["id"] for c in json.loads(out)]
    assert ids[:2] == ["motor", "gear_ratio"]
    code, out, _ = run(capsys, "presets", "gear_ratio")
    assert "Elevator, 2 NEO" in out and "built-in" in out


def test_console_script_entry_point_runs():
    out = subprocess.run(
        [sys.executable, "-m", "gearhead.tui", "solve", "motor", "--json"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert out.returncode == 0 and json.loads(out.stdout)["calculator"] == "motor"


def test_unit_option_changes_only_the_display(capsys):
    code, out, _ = run(capsys, "solve", "gear_ratio", "--unit", "free_speed=rad/s", "--json")
    assert code == 0
    default = json.loads(run(capsys, "solve", "gear_ratio", "--json")[1])["outputs"]["free_speed"]
    shown = json.loads(out)["outputs"]["free_speed"]
    assert shown["value"] == default["value"] and shown["text"].endswith(" rad/s")
    assert float(shown["text"].split()[0]) == pytest.approx(default["value"], rel=1e-4)


@pytest.mark.parametrize(
    "spec, named",
    [("free_speed=lbf", "free_speed"), ("nothing=m", "nothing"), ("free_speed=furlongs/", "free_speed")],
)
def test_bad_unit_option_exits_2_naming_the_output(capsys, spec, named):
    code, out, err = run(capsys, "solve", "gear_ratio", "--unit", spec)
    assert code == 2 and out == "" and named in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("as_json", [[], ["--json"]])
def test_several_bad_inputs_exit_2_with_a_line_for_each(capsys, as_json):
    """The first line is what one bad input printed; each further bad field has its own line."""
    args = ["solve", "gear_ratio", "--set", "load=abc", "--set", "radius=3 kg", *as_json]
    code, out, err = run(capsys, *args)
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert (
        len(lines) == 2
        and lines[0].startswith("gearhead: load: ")
        and lines[1].startswith("gearhead: radius: ")
    )
    _, _, alone = run(capsys, "solve", "gear_ratio", "--set", "load=abc", *as_json)
    assert lines[0] == alone.strip()
