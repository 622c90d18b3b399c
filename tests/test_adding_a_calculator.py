"""docs/adding-a-calculator.md, tried: the page's toy calculator (tests/toy_calculator.py) goes
through everything the page says a new calculator goes through, so the page cannot rot silently.

- every Python block the page quotes from the toy is still in tests/toy_calculator.py, word for word;
- the toy passes the registry's declaration checks, solves to hand values, answers `solve --json`
  on the command line and survives a preset round trip (the page's preset, saved and loaded);
- its tests are of the kinds the page asks for (hand values, hypothesis, hard cases, hostile entries).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from gearhead.core import presets, registry
from gearhead.core.declarations import check, check_links
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from tests import toy_calculator as toy

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "adding-a-calculator.md"
FT, IN, RPM = 0.3048, 0.0254, 2 * math.pi / 60


def blocks(language: str) -> list[str]:
    return re.findall(rf"```{language}\n(.*?)```", PAGE.read_text(encoding="utf-8"), flags=re.S)


@pytest.fixture(scope="module", autouse=True)
def registered():
    """The toy in the registry while this module runs (a real calculator is registered by
    core/registry.py, which imports every module of core/calculators)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setitem(registry.calculators(), toy.CALCULATOR.id, toy.CALCULATOR)
        yield toy.CALCULATOR


def test_the_page_quotes_the_toy_as_it_is():
    source = (ROOT / "tests" / "toy_calculator.py").read_text(encoding="utf-8")
    quoted = [b for b in blocks("python") if b.startswith("# tests/toy_calculator.py")]
    assert len(quoted) >= 4, "the page walks through the toy's fields, outputs, compute and Calculator"
    for block in quoted:
        body = block.split("\n", 1)[1]
        assert body.strip() and body in source, f"the page quotes code the toy no longer has:\n{body[:300]}"


def test_the_toy_passes_the_declaration_checks_the_registry_runs():
    check(toy.CALCULATOR)
    check_links({**registry.calculators(), toy.CALCULATOR.id: toy.CALCULATOR})


def test_bounds_and_defaults_are_in_the_display_unit():
    wheel = toy.CALCULATOR.field("wheel_diameter")
    assert wheel.bounds_si() == (pytest.approx(0.5 * IN), pytest.approx(12 * IN))
    with pytest.raises(InputError, match="at most 12 in"):
        wheel.parse("13")


def test_hand_values():
    # NEO 5676 rpm through 8.45:1 on a 4 in wheel: 5676/8.45 = 671.716 rpm at the wheel (T1);
    # v = (π·4/12 ft)·(671.716/60 s) = 1.047198 · 11.19527 = 11.72366 ft/s (T3), worked on paper
    sol = solve("toy_wheel", {})
    assert sol.outputs["wheel_speed"].value / RPM == pytest.approx(671.7160, rel=1e-6)
    assert sol.outputs["surface_speed"].value / FT == pytest.approx(11.72366, rel=1e-6)
    assert sol.outputs["surface_speed"].text == "11.724 ft/s"
    # a 0.25 in tread on each side: d_e = 4.5 in (T2), v scales by 4.5/4
    tread = solve("toy_wheel", {"tread": "tread", "tread_thickness": "0.25"})
    assert tread.outputs["effective_diameter"].value == pytest.approx(4.5 * IN, rel=1e-15)
    assert tread.outputs["surface_speed"].value == pytest.approx(sol.outputs["surface_speed"].value * 4.5 / 4)
    # reverse: 15 ft/s on the 4 in wheel needs G = ω_m·d/(2v) = 594.4 rad/s · 0.1016 m/(2 · 4.572 m/s) = 6.6043
    assert solve("toy_wheel", {"mode": "ratio"}).outputs["ratio_needed"].value == pytest.approx(
        6.60430, rel=1e-5
    )


@settings(max_examples=100, deadline=None, database=None)
@given(speed=st.floats(1, 40), diameter=st.floats(2, 8), motor=st.floats(1000, 20000))
def test_the_ratio_for_a_speed_gives_that_speed(speed, diameter, motor):
    assume(1.001 < motor * RPM * diameter * IN / (2 * speed * FT) < 999)  # within the ratio's bounds
    common = {"wheel_diameter": repr(diameter), "motor_speed": repr(motor)}
    G = (
        solve("toy_wheel", {"mode": "ratio", "target_speed": repr(speed), **common})
        .outputs["ratio_needed"]
        .value
    )
    v = solve("toy_wheel", {"mode": "speed", "ratio": repr(G), **common}).outputs["surface_speed"].value
    assert v / FT == pytest.approx(speed, rel=1e-12)


def test_hard_cases():
    # a field `when` hides never blocks: junk in the tread thickness with no tread is ignored
    assert solve("toy_wheel", {"tread": "none", "tread_thickness": "3 kg"}).outputs
    with pytest.raises(InputError) as err:
        solve("toy_wheel", {"tread": "tread", "tread_thickness": "3 kg"})
    assert err.value.field == "tread_thickness"
    # a speed the motor cannot reach even direct drive: refused, naming the field
    with pytest.raises(InputError) as err:
        solve("toy_wheel", {"mode": "ratio", "target_speed": "99 ft/s", "motor_speed": "100 rpm"})
    assert err.value.field == "target_speed" and "below 1" in err.value.message
    fast = solve("toy_wheel", {"ratio": 1})
    assert any("30 ft/s" in w for w in fast.warnings)


def test_every_declared_output_is_produced_and_nothing_else():
    declared = {o.name for o in toy.CALCULATOR.outputs}
    produced = set()
    for mode in toy.CALCULATOR.modes:
        values, _ = parse_inputs(toy.CALCULATOR, {"mode": mode})
        result = toy.CALCULATOR.compute(values)
        assert set(result.values) <= declared
        assert set(result.series) == {s for p in toy.CALCULATOR.plots for s in p.series}
        produced |= set(result.values)
    assert produced == declared


def test_hostile_entries_in_every_field_read_or_name_the_field():
    from tests.test_input_hostile import field_and_entry, parse_once

    @settings(max_examples=100, deadline=None, database=None, derandomize=True)
    @given(field_and_entry(toy.CALCULATOR))
    def run(case):
        parse_once(*case)

    run()


def _page_preset(tmp_path) -> Path:
    (toml,) = [b for b in blocks("toml") if 'calculator = "toy_wheel"' in b]
    path = tmp_path / "presets" / "toy_wheel" / "drive_15fps.toml"
    path.parent.mkdir(parents=True)
    path.write_text(toml, encoding="utf-8")
    return path


def test_the_pages_preset_round_trips_and_solves_from_the_command_line(tmp_path, capsys):
    from gearhead.tui.cli import main

    path = _page_preset(tmp_path)
    preset = presets.load(path)
    assert preset.calculator == "toy_wheel" and not preset.warnings
    again = presets.load(presets.save(preset, tmp_path / "again.toml"))
    assert (again.name, again.description, again.inputs) == (preset.name, preset.description, preset.inputs)

    assert main(["solve", "toy_wheel", "--preset", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["calculator"] == "toy_wheel" and out["warnings"] == []
    assert out["inputs"]["wheel_diameter"] == {"value": pytest.approx(4 * IN), "unit": "m", "text": "4 in"}
    want = solve("toy_wheel", preset.inputs)
    assert out["outputs"]["ratio_needed"]["value"] == want.outputs["ratio_needed"].value
    assert sorted(out["tables"]["wheels"][0]) == ["diameter", "surface_speed"]
    # the golden record tests/golden_outputs.py would write for it: finite SI numbers
    assert all(math.isfinite(o["value"]) for o in out["outputs"].values())


def test_the_tab_renders_the_toy():
    """The generic tab builds the toy from its declaration alone (the snapshot test then
    records it); here the pieces it draws from are checked without a terminal."""
    from gearhead.tui.components.calculator_tab import CalculatorTab

    entries = {f.name: CalculatorTab.initial_entry(f) for f in toy.CALCULATOR.fields}
    assert entries["mode"] == "speed" and entries["wheel_diameter"] == "4"
    specs = {f.name: f.kind.widget(f) for f in toy.CALCULATOR.fields}
    assert specs["mode"].shape == "select" and specs["tread"].options[1] == ("tread", "Tread strip")
    assert specs["wheel_diameter"].shape == "input" and specs["wheel_diameter"].unit == "in"
