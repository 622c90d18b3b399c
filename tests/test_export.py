"""Results to take away: CSV and Markdown of the results table, plot data, preset text."""

import csv
import io
import tomllib

from gearhead.core import export, presets
from gearhead.core.model import solve
from gearhead.core.registry import get


def test_results_csv_round_trips_every_output_at_full_precision():
    sol = solve("gear_ratio", {"load": "25 lbf", "radius": "0.75 in"})
    rows = list(csv.DictReader(io.StringIO(export.results_csv(get("gear_ratio"), sol))))
    assert [r["output"] for r in rows] == list(sol.outputs)
    for r in rows:
        v = sol.outputs[r["output"]]
        assert r["shown"] == v.text and r["unit_si"] == v.unit
        if isinstance(v.value, float):
            assert float(r["value_si"]) == v.value  # repr: every digit, not the 5-figure text


def test_results_markdown_escapes_pipes_and_lists_warnings():
    calc = get("beam")
    sol = solve("beam", {})
    sol.warnings.append("a | b")
    md = export.results_markdown(calc, sol)
    lines = md.splitlines()
    assert lines[2] == "| Result | Value | Eq. |"
    body = [line for line in lines if line.startswith("| ") and line != "| Result | Value | Eq. |"]
    assert len(body) == len(sol.outputs)
    assert all(line.count(" | ") - line.count("\\| ") == 2 for line in body)
    assert "- a \\| b" in lines


def test_plot_csv_is_in_display_units():
    calc = get("motor")
    sol = solve("motor", {})
    plot = calc.plots[0]
    rows = list(csv.reader(io.StringIO(export.plot_csv(plot, sol))))
    assert rows[0][1].endswith(f"[{plot.x_unit}]")
    name = plot.series[0]
    xs, ys = sol.series[name]
    first = next(r for r in rows[1:] if r[0] == name)
    from gearhead.core import units

    assert float(first[2]) * units.factor(plot.y_unit, plot.y_quantity) == __import__("pytest").approx(
        ys[0], rel=1e-15
    )


def test_preset_toml_loads_back_to_the_same_solution(tmp_path):
    inputs = {"motor": "NEO", "motor_count": 2, "load": "40 lbf", "radius": "0.75 in"}
    text = export.preset_toml("gear_ratio", inputs, "Elevator", "two NEOs")
    data = tomllib.loads(text)
    p = presets.from_dict(data)
    assert p.inputs == inputs and p.name == "Elevator"
    assert solve("gear_ratio", p.inputs).outputs == solve("gear_ratio", inputs).outputs
