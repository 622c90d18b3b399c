"""The calculator description: fields that depend on other choices (Field.when)."""

import pytest

from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get


def test_field_used_only_for_its_section():
    beam = get("beam")
    wall = beam.field("wall")
    assert wall.active(None, {"section": "round_tube"})
    assert not wall.active(None, {"section": "hex"})
    # a bad entry in a field the chosen section does not use neither blocks nor leaks
    values, _ = parse_inputs(beam, {"section": "hex", "wall": "3 kg"})
    assert values["wall"] == pytest.approx(0.0625 * 0.0254)
    with pytest.raises(InputError) as err:
        parse_inputs(beam, {"section": "round_tube", "wall": "3 kg"})
    assert err.value.field == "wall"


def test_field_shown_when_any_named_effect_is_on():
    projectile = get("projectile")
    drag = projectile.field("drag_coefficient")
    assert not drag.active("forward", {"effects": frozenset()})
    assert not drag.active("forward", {"effects": frozenset({"magnus"})})
    assert drag.active("forward", {"effects": frozenset({"air_drag", "magnus"})})
    # vacuum flight ignores a nonsense drag coefficient; with drag on it is named
    assert solve("projectile", {"effects": "", "drag_coefficient": "-3"}).outputs
    with pytest.raises(InputError) as err:
        solve("projectile", {"effects": "air_drag", "drag_coefficient": "-3"})
    assert err.value.field == "drag_coefficient"


@pytest.mark.parametrize("typed", ["125", "125 psi", "861844.6616460452 Pa", "0.86184466164604 MPa"])
def test_a_bound_typed_in_another_unit_is_accepted_as_the_bound(typed):
    """125 psi typed against a bound of 125 psi read in Pa: conversion may land one rounding step
    outside; it is the bound, not an error, and formulas see exactly the bound."""
    from gearhead.core.model import Field

    relief = 125 * 6894.757293168361
    f = Field("p", "Pressure", "pressure", "psi", max=125)
    bound = f.bounds_si()[1]
    assert bound == pytest.approx(relief, rel=1e-15)
    value = f.parse(typed)
    assert value <= bound and value == pytest.approx(bound, rel=1e-9)
    if "125" in typed:
        assert value == bound  # a hair outside is the bound itself
    with pytest.raises(InputError):
        f.parse("125.001 psi")  # a real excess is still refused


def test_a_failing_formula_is_a_message_not_a_traceback(monkeypatch):
    """The last-resort guard: an arithmetic failure inside a calculator reaches the user as an
    InputError (the robustness tests make sure no real input ever gets here)."""
    import dataclasses

    from gearhead.core import registry

    broken = dataclasses.replace(get("ratio_distance"), compute=lambda v: 1 / 0)
    monkeypatch.setitem(registry.calculators(), "ratio_distance", broken)
    with pytest.raises(InputError) as err:
        solve("ratio_distance", {})
    assert err.value.field == "(result)" and "ZeroDivisionError" in err.value.message


# ---- field kinds (core/fields.py): a new kind is one class -------------------------------------


def _hex_kind():
    """A toy kind, declared here and nowhere else: a whole number written in hexadecimal."""
    from gearhead.core.fields import INTEGER, Kind

    class Hex(Kind):
        name = "hex"
        numeric = True
        whole = True

        def parse(self, f, raw):
            text = str(raw).strip().lower()
            try:
                value = int(text, 16) if text.startswith("0x") else None
            except ValueError:
                value = None
            if value is None:
                raise InputError(f.name, f"{text[:20]!r} is not a hexadecimal number like 0x1f")
            return self.checked(f, value, text)

        def holds(self, f, value):
            return isinstance(value, int) and not isinstance(value, bool)

        bound_text = INTEGER.bound_text

        def stored(self, f, entry):
            return str(entry).strip().lower()

        def vocabulary(self, f):
            return ("0x10", "0xff", "0x", "0xg")

    return Hex()


def _toy_calculator():
    from gearhead.core.model import Calculator, Field, Output, Result

    code = Field("code", "Code", kind=_hex_kind(), default="0x10", min=1, max=0xFFFF, help="Any CAN id.")
    return Calculator(
        "toy_hex",
        "Toy hex",
        "A toy with a hexadecimal field.",
        (code,),
        (Output("double", "Twice the code"),),
        lambda v: Result({"double": 2 * v["code"]}),
    )


def test_a_new_field_kind_is_one_class(monkeypatch, tmp_path):
    """The toy kind above is the only code written for it: declarations, parse_inputs, solve's
    JSON, presets and the generated hostile entries all work through the kind object."""
    from hypothesis import given, settings

    from gearhead.core import presets, registry
    from gearhead.core.declarations import check
    from tests.test_input_hostile import hostile_text, parse_once

    calc = _toy_calculator()
    code = calc.field("code")
    check(calc)
    assert code.type == "hex" and code.default_text() == "0x10"
    assert code.parse(" 0x1F ") == 31
    with pytest.raises(InputError, match="too large: must be at most 65535"):
        code.parse("0x10000")
    with pytest.raises(InputError) as err:
        code.parse("31")
    assert err.value.field == "code"
    # a kind that changes a built-in syntax flag is kept (replace keeps it, too)
    import dataclasses

    assert dataclasses.replace(code, help="x").kind is code.kind

    monkeypatch.setitem(registry.calculators(), "toy_hex", calc)
    out = solve("toy_hex", {"code": "0xff"}).as_json()
    assert out["inputs"]["code"] == {"value": 255, "unit": "", "text": "0xff"}
    assert out["outputs"]["double"]["value"] == 510

    preset = presets.Preset("toy_hex", "Toy", inputs={"code": code.kind.stored(code, " 0xFF")})
    path = presets.save(preset, tmp_path / "toy.toml")
    assert presets.load(path).inputs == {"code": "0xff"}
    with pytest.raises(InputError) as err:
        presets.from_dict({"calculator": "toy_hex", "inputs": {"code": "12"}})
    assert err.value.field == "code"

    @settings(max_examples=30, deadline=None, database=None, derandomize=True)
    @given(hostile_text(code))
    def hostile(text):
        parse_once(code, text)  # a value the kind holds, or a one-line message naming the field

    hostile()


def test_a_new_numeric_kind_sweeps_and_a_new_quantity_kind_carries_a_tolerance(monkeypatch):
    """Sweeps, tolerances and the units preference ask the kind (numeric, whole, with_unit), never
    its name: the toy hex kind is swept through whole numbers (its ends typed as it reads them, each
    point held to its bounds), and a quantity kind of another name reads '30 deg ± 1 deg'."""
    import dataclasses

    from gearhead.core import registry, sweep, tolerance
    from gearhead.core.fields import Quantity
    from gearhead.core.model import Field
    from gearhead.core.unit_systems import typed_units

    calc = _toy_calculator()
    monkeypatch.setitem(registry.calculators(), "toy_hex", calc)
    vary = sweep.parse_vary(calc, "code=0xfffe..0x10001")
    assert (vary.start, vary.stop, vary.points) == (0xFFFE, 0x10001, 4)
    study = sweep.run(calc, {}, [vary])
    assert [p.inputs["code"] for p in study.points] == [0xFFFE, 0xFFFF, 0x10000, 0x10001]
    assert [p.outputs.get("double") for p in study.points] == [2 * 0xFFFE, 2 * 0xFFFF, None, None]
    assert "too large: must be at most 65535" in study.points[2].error
    assert study.display_row(study.points[0])[0] == 0xFFFE and study.as_json()["vary"][0]["unit"] == ""
    with pytest.raises(InputError, match="no tolerance|cannot carry a tolerance"):
        tolerance.split_inputs(calc, {"code": "0x10 ± 0x1"})

    class Angle(Quantity):
        name = "angle"

    tilt = Field("tilt", "Tilt", "angle", "deg", kind=Angle(), default=30, min=0, max=90, help="Tilt.")
    toy = dataclasses.replace(calc, id="toy_tilt", fields=(*calc.fields, tilt))
    nominal, tols = tolerance.split_inputs(toy, {"tilt": "30 deg ± 1 deg"})
    assert tols == {"tilt": "1 deg"}
    assert typed_units(toy.fields, {"tilt": "0.5 rad"}) == {"angle": "rad"}


async def test_a_new_field_kind_renders_in_the_generic_tab(monkeypatch):
    """The tab draws the toy kind from its widget description (an input, no unit label), puts a
    preset's value into it, and hands it back as a preset stores it."""
    from textual.app import App

    from gearhead.core import registry
    from gearhead.tui.components.calculator_tab import CalculatorTab
    from gearhead.tui.components.sheet import GAP, LABEL_CELLS

    calc = _toy_calculator()
    monkeypatch.setitem(registry.calculators(), "toy_hex", calc)

    class Harness(App):
        def compose(self):
            yield CalculatorTab(calc, blink=False, hide_timings=True)

    app = Harness()
    async with app.run_test(size=(120, 30)) as pilot:
        tab = app.query_one(CalculatorTab)

        async def solved():
            for _ in range(200):
                await pilot.pause()
                await app.workers.wait_for_complete()
                if not tab.busy:
                    return

        await solved()
        assert tab.entries["code"] == "0x10"
        (stop,) = tab.sheet.stops
        assert stop.shape == "input" and stop.spec.unit == ""  # an input, no unit label
        value_at = 1 + LABEL_CELLS + GAP
        assert tab.sheet.render_line(0).text[value_at:].strip() == "0x10"  # drawn as entered
        assert tab.solution.outputs["double"].value == 32
        tab.set_entries({"code": "0xFF"})
        await solved()
        assert tab.entries["code"] == "0xFF"
        assert tab.sheet.render_line(0).text[value_at:].strip() == "0xFF"
        assert tab.current_inputs() == {"code": "0xff"}
        assert tab.solution.outputs["double"].value == 510


# ---- bounds: min, max and default in the display unit -------------------------------------------


def test_bounds_are_in_the_display_unit_and_messages_quote_them_there():
    from gearhead.core.model import Field

    f = Field("wall", "Wall", "length", "in", default=0.0625, min=0, min_exclusive=True, max=1)
    assert f.bounds_si() == (0.0, 0.0254)
    assert f.parse("1 in") == 0.0254 and f.parse("25.4 mm") == pytest.approx(0.0254)
    with pytest.raises(InputError, match=r"too large: must be at most 1 in"):
        f.parse("26 mm")
    with pytest.raises(InputError, match=r"too small: must be greater than 0 in"):
        f.parse("0")
    pct = Field("loss", "Loss", "dimensionless", "%", default=5, min=0, max=100)
    assert pct.parse("100") == 1.0 and pct.parse("1") == 0.01
    with pytest.raises(InputError, match=r"at most 100 %"):
        pct.parse("150")


def test_retired_names_are_replaced_once_per_solve(monkeypatch):
    """retire() ran three times per solve (solve, parse_inputs, choice_values) (issue 34 item 7)."""
    from gearhead.core import model

    calls, real = [], model.retire  # core.sim.effects.retire, as core.model calls it
    monkeypatch.setattr(model, "retire", lambda *a, **k: calls.append(1) or real(*a, **k))
    model.solve("beam", {"section": "round_tube"})
    assert len(calls) == 1


# ---- every wrong entry reported, not only the first (issue 34: two wrong entries, one marked) ----


def test_several_wrong_entries_are_all_reported_the_first_as_before():
    from gearhead.core.errors import InputErrors

    raw = {"load": "abc", "radius": "3 kg", "motor_count": "0"}
    with pytest.raises(InputErrors) as exc:
        parse_inputs(get("gear_ratio"), raw)
    # in the calculator's field order (the motor's fields come first)
    assert [e.field for e in exc.value.errors] == ["motor_count", "load", "radius"]
    assert all(type(e) is InputError for e in exc.value.errors)
    # the primary is what parsing raised when it stopped at the first
    with pytest.raises(InputError) as first:
        parse_inputs(get("gear_ratio"), {"motor_count": "0"})
    assert isinstance(exc.value, InputError)
    assert (exc.value.field, exc.value.message, str(exc.value)) == (
        "motor_count",
        first.value.message,
        str(first.value),
    )
    assert str(exc.value.errors[1]) == "load: 'abc' is not a unit I know (units of a force: N, lbf)"


def test_one_wrong_entry_is_raised_as_it_was():
    with pytest.raises(InputError) as exc:
        solve("gear_ratio", {"load": "abc"})
    assert type(exc.value) is InputError and exc.value.errors == (exc.value,)


def test_unknown_names_come_first_and_a_wrong_mode_stops_the_reading():
    from gearhead.core.errors import InputErrors

    with pytest.raises(InputErrors) as exc:
        solve("gear_ratio", {"load": "abc", "wheels": "4", "spokes": "9"})
    assert [e.field for e in exc.value.errors] == ["wheels", "spokes", "load"]
    with pytest.raises(InputErrors) as exc:  # which fields are used depends on the mode
        solve("gear_ratio", {"wheels": "4", "mode": "fastest", "load": "abc"})
    assert [e.field for e in exc.value.errors] == ["wheels", "mode"]


def test_a_wrong_entry_in_a_field_not_used_is_still_only_a_notice():
    with pytest.raises(InputError) as exc:
        solve("gear_ratio", {"mode": "max_power", "target_current": "banana", "load": "abc"})
    assert [e.field for e in exc.value.errors] == ["load"]


def test_a_preset_with_several_wrong_entries_names_each_with_its_file():
    from gearhead.core import presets

    data = {"calculator": "gear_ratio", "inputs": {"load": "abc", "radius": "3 kg"}}
    with pytest.raises(InputError) as exc:
        presets.from_dict(data, "arm.toml")
    assert [(e.source, e.field) for e in exc.value.errors] == [("arm.toml", "load"), ("arm.toml", "radius")]
    assert str(exc.value).startswith("arm.toml: load: ")


def test_an_integer_valued_quantity_keeps_its_unit():
    """A calculator's 0 from sum() of nothing (the sprint's time slipping under a ramp) is still a
    time: '0 s', not the bare '0' of a count; a count stays an integer."""
    from gearhead.core.model import format_value

    assert format_value(0, "time", "s").text == "0 s"
    assert format_value(0, "time", "s").value == 0.0
    assert format_value(3, "dimensionless", "").text == "3"
