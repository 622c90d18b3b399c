"""Sweeps (core.sweep, `gearhead sweep`): every point is exactly what a single solve gives; an
infeasible point is a row with solve's reason; bad --vary text is a one-line message."""

import csv
import io
import json
from pathlib import Path

import pytest

from gearhead.core import sweep, units
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.presets import load
from gearhead.core.registry import get
from gearhead.core.sim.scene import VOLATILE
from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]


def preset_inputs(calc: str, name: str) -> dict:
    return dict(load(ROOT / "presets" / calc / f"{name}.toml").inputs)


def si_text(calc_id: str, name: str, x) -> str:
    """The SI value as an entry solve reads exactly (a unit factor of 1, no rounding)."""
    f = get(calc_id).field(name)
    if f.type == "int":
        return str(x)
    unit = units.SI_UNITS[f.quantity]
    return f"{x!r} {unit}".strip()


def assert_point_is_solve(calc_id: str, raw: dict, point: sweep.Point, notes=()) -> None:
    entries = {**raw, **{n: si_text(calc_id, n, x) for n, x in point.inputs.items()}}
    if point.error is not None:
        with pytest.raises(InputError) as exc:
            solve(calc_id, entries)
        assert point.error.split(":")[0] == exc.value.field
        return
    single = solve(calc_id, entries)
    got = {n: v for n, v in point.outputs.items() if n not in VOLATILE}
    want = {n: v.value for n, v in single.outputs.items() if n not in VOLATILE}
    assert got == want  # exactly: the same floats, bit for bit
    # a warning every point gives is the sweep's note, said once (issue 40), not the point's
    assert point.warnings == [w for w in single.warnings if f"at every point: {w}" not in notes]


def test_sweep_points_equal_single_solves_closed_form():
    raw = preset_inputs("gear_ratio", "elevator_neo")
    result = sweep.run(get("gear_ratio"), raw, ["radius=0.5 in..1.5 in:11"])
    assert len(result.points) == 11
    assert result.points[0].inputs["radius"] == pytest.approx(0.0127, rel=1e-15)
    assert result.points[-1].inputs["radius"] == pytest.approx(0.0381, rel=1e-15)
    for p in result.points:
        assert p.error is None
        assert_point_is_solve("gear_ratio", raw, p)
    assert result.varies[0].unit == "in"  # the column is shown in the unit typed
    assert result.cost.solves == 11


def test_sweep_with_infeasible_points_gives_the_reason():
    raw = preset_inputs("gear_ratio", "elevator_neo")
    result = sweep.run(get("gear_ratio"), raw, ["radius=-0.5 in..1 in:7"])
    bad = [p for p in result.points if p.error]
    good = [p for p in result.points if not p.error]
    assert bad and good
    for p in result.points:
        assert_point_is_solve("gear_ratio", raw, p)
    assert all("radius" in p.error for p in bad)
    assert all(p.outputs == {} for p in bad)


@pytest.mark.parametrize(
    "calc_id, preset, vary",
    [
        ("beam", "frame_rail_1x2", "length=10 in..40 in:9"),
        ("lead_screw", "t8_lift", "friction=0.05..0.6:8:log"),
        ("flywheel", "nbn_seed_single_wheel", "wheel_count=0..4"),
        ("trebuchet", "seed_kastmaskin", "release_angle=30 deg..60 deg:4"),
        ("motor", "v5_green", "voltage=6..13:5"),
    ],
)
def test_sweep_points_equal_single_solves(calc_id, preset, vary):
    raw = preset_inputs(calc_id, preset)
    result = sweep.run(get(calc_id), raw, [vary])
    assert len(result.points) >= 4
    for p in result.points:
        assert_point_is_solve(calc_id, raw, p, result.notes)


def test_whole_number_sweep_every_value_and_bounds_as_rows():
    raw = preset_inputs("flywheel", "nbn_seed_single_wheel")
    result = sweep.run(get("flywheel"), raw, ["wheel_count=0..3"])
    assert [p.inputs["wheel_count"] for p in result.points] == [0, 1, 2, 3]
    assert result.points[0].error is not None and "too small" in result.points[0].error
    assert all(p.error is None for p in result.points[1:])


def test_log_spacing_and_endpoints_exact():
    v = sweep.parse_vary(get("lead_screw"), "friction=0.01..1:3:log")
    assert v.values(get("lead_screw").field("friction")) == [0.01, pytest.approx(0.1, rel=1e-15), 1.0]


def test_grid_first_input_slowest_and_exact():
    raw = preset_inputs("gear_ratio", "elevator_neo")
    result = sweep.run(get("gear_ratio"), raw, ["radius=0.5 in..1 in:3", "load=20 lbf..60 lbf:4"], ["ratio"])
    assert len(result.points) == 12
    radii = [p.inputs["radius"] for p in result.points]
    assert radii[:4] == [radii[0]] * 4 and radii[4] > radii[0]
    for p in result.points:
        assert_point_is_solve("gear_ratio", raw, p)
    text = sweep.text_table(result)
    assert "radius \\ load" in text  # two inputs, one output: a matrix


def test_cancel_keeps_the_points_solved():
    calls = []
    raw = preset_inputs("gear_ratio", "elevator_neo")
    result = sweep.run(
        get("gear_ratio"),
        raw,
        ["radius=0.5 in..1.5 in:50"],
        progress=lambda done, total: calls.append(done),
        cancelled=lambda: len(calls) >= 3,
    )
    assert result.cancelled and len(result.points) == 3


def test_a_sweep_takes_the_calculator_itself():
    """sweep.run takes a Calculator, not an id (issue 42 item 3): one the registry does not hold
    (a workbook seen as one calculator) is swept by the same loop, each point its own solve."""
    from gearhead.core import workbook

    text = 'name = "w"\n[variables]\nmass = "10 lb"\nmass_limit = "= mass * 2"\n'
    text += '[[requirements]]\nname = "light"\ncheck = "mass < 25 lb"\n'
    wb = workbook.from_text(text, "w.toml")
    result = sweep.run(workbook.as_calculator(wb), {}, ["mass=10 lb..30 lb:3"], ["light"])
    assert [p.error for p in result.points] == [None] * 3
    assert [p.inputs["mass"] for p in result.points] == pytest.approx([x * 0.45359237 for x in (10, 20, 30)])
    for p in result.points:
        assert p.outputs["light"] == workbook.solve(wb, p.inputs).checks[0].margin_si
    assert result.calculator.id == "workbook" and result.cost.solves == 3


@pytest.mark.parametrize(
    "text, words",
    [
        ("ratio=3..12", "not used with these choices"),
        ("bogus=3..12", "not an input"),
        ("radius=1..", "START..STOP"),
        ("radius=1...2", "two dots"),
        ("radius=1..2:1", "at least 2"),
        ("radius=1..2:5:9", "twice"),
        ("radius=1..2:lin", "neither"),
        ("radius=1..1", "empty"),
        ("radius=-1 in..1 in:5:log", "log"),
        ("radius=1 lbf..2 in", "length"),
        ("motor=1..2", "only numbers"),
        ("radius=1..2:99999", "more than"),
        ("radius", "NAME=START..STOP"),
    ],
)
def test_bad_vary_is_a_message(text, words):
    with pytest.raises(InputError) as exc:
        sweep.run(get("gear_ratio"), {}, [text])
    assert words in str(exc.value)


def test_cli_sweep_json_matches_cli_solve(capsys):
    preset = str(ROOT / "presets/gear_ratio/elevator_neo.toml")
    assert main(["sweep", "gear_ratio", "--preset", preset, "--vary", "load=10 lbf..80 lbf:5", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["cost"]["solves"] == 5
    for point in data["points"]:
        x = point["inputs"]["load"]
        assert main(["solve", "gear_ratio", "--preset", preset, "--set", f"load={x!r} N", "--json"]) == 0
        single = json.loads(capsys.readouterr().out)
        assert point["outputs"] == {n: v["value"] for n, v in single["outputs"].items()}


def test_cli_sweep_csv_has_status_and_units(capsys):
    assert main(["sweep", "gear_ratio", "--vary", "radius=-1 in..1 in:3", "--output", "ratio", "--csv"]) == 0
    rows = list(csv.reader(io.StringIO(capsys.readouterr().out)))
    assert rows[0] == ["radius [in]", "ratio", "status"]
    assert rows[1][2].startswith("radius:") and rows[1][1] == ""
    assert rows[3][2] == "ok" and float(rows[3][0]) == 1.0


def test_cli_sweep_text_and_bad_input(capsys):
    assert main(["sweep", "gear_ratio", "--vary", "radius=0.5 in..1 in:3"]) == 0
    out = capsys.readouterr().out
    assert "radius [in]" in out and "cost: 3 solves" in out
    assert main(["sweep", "gear_ratio", "--vary", "radius=1..2:zz"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("gearhead: radius:")
    assert main(["sweep", "gear_ratio", "--vary", "radius=1..2", "--output", "nope"]) == 2
    assert "nope" in capsys.readouterr().err


def test_a_retired_flag_is_read_once_for_the_whole_sweep_with_its_notice():
    """An old name among the effects (the flywheel's 'momentum', now the choice `transfer`) means
    what replaced it at every point, and the notice is the sweep's, once."""
    base = load(ROOT / "presets" / "flywheel" / "nbn_seed_single_wheel.toml").inputs
    vary = ["ball_mass=0.05 kg..0.07 kg:3"]
    old = sweep.run(
        get("flywheel"), {**base, "effects": "momentum"}, vary, ["ball_speed", "wheel_speed_after"]
    )
    new = sweep.run(
        get("flywheel"), {**base, "transfer": "momentum"}, vary, ["ball_speed", "wheel_speed_after"]
    )
    energy = sweep.run(get("flywheel"), base, vary, ["ball_speed", "wheel_speed_after"])

    def values(study):
        return [{k: v for k, v in p.outputs.items() if k not in VOLATILE} for p in study.points]

    assert values(old) == values(new) != values(energy)
    old_notes, new_notes = ([n for n in s.notes if not n.startswith("at every point")] for s in (old, new))
    assert len(old_notes) == 1 and "transfer = momentum" in old_notes[0] and not new_notes
