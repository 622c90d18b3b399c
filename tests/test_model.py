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


@pytest.mark.parametrize("typed", ["125", "125 psi", "861844.6616460452 Pa"])
def test_a_bound_typed_in_another_unit_is_accepted_as_the_bound(typed):
    """125 psi against a bound of 125·6894.757… Pa: conversion may land one rounding step
    outside; it is the bound, not an error, and formulas see exactly the bound."""
    from gearhead.core.model import Field

    relief = 125 * 6894.757293168361
    f = Field("p", "Pressure", "pressure", "psi", max=relief)
    value = f.parse(typed)
    assert value <= relief and value == pytest.approx(relief, rel=1e-9)
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
