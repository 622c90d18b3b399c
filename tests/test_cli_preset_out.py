"""`gearhead solve ... --preset-out -|FILE`: the inputs solved, as a preset a script can chain."""

import json
import tomllib

from gearhead.core import presets
from gearhead.tui.cli import main


def run(capsys, *args):
    code = main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_preset_out_dash_prints_a_preset_that_solves_the_same(capsys, tmp_path):
    code, out, _ = run(
        capsys, "solve", "gear_ratio", "--set", "load=30 lbf", "--set", "motor_count=2", "--preset-out", "-"
    )
    assert code == 0
    data = tomllib.loads(out)  # stdout is the preset alone: it pipes into a file
    assert data["calculator"] == "gear_ratio"
    assert data["inputs"]["load"] == "30 lbf" and data["inputs"]["motor_count"] == 2
    path = tmp_path / "chained.toml"
    path.write_text(out)
    assert presets.load(path).inputs["load"] == "30 lbf"
    _, direct, _ = run(
        capsys, "solve", "gear_ratio", "--set", "load=30 lbf", "--set", "motor_count=2", "--json"
    )
    _, chained, _ = run(capsys, "solve", "gear_ratio", "--preset", str(path), "--json")
    assert json.loads(chained)["outputs"] == json.loads(direct)["outputs"]


def test_preset_out_file_never_overwrites_and_bad_input_writes_nothing(capsys, tmp_path):
    path = tmp_path / "beam.toml"
    code, out, err = run(capsys, "solve", "beam", "--set", "length=20 in", "--preset-out", str(path))
    assert code == 0 and "written to" in err and out  # the results still print
    first = path.read_text()
    assert tomllib.loads(first)["inputs"]["length"] == "20 in"
    code, _, err = run(capsys, "solve", "beam", "--set", "length=30 in", "--preset-out", str(path))
    assert code == 2 and "exists" in err and len(err.strip().splitlines()) == 1
    assert path.read_text() == first
    fresh = tmp_path / "bad.toml"
    code, _, err = run(capsys, "solve", "beam", "--set", "length=3 kg", "--preset-out", str(fresh))
    assert code == 2 and not fresh.exists()
    code, _, err = run(capsys, "solve", "beam", "--preset-out", str(tmp_path / "no" / "such" / "x.toml"))
    assert code == 2 and "cannot write" in err
