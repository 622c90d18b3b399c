"""Declarations are checked when the registry loads: a broken one names the calculator and field.
And every declared output is produced somewhere, nothing undeclared is returned."""

import pytest

from gearhead.core import presets
from gearhead.core.declarations import DeclarationError, check, check_links
from gearhead.core.model import Calculator, Field, Output, Plot, Result, Table, parse_inputs
from gearhead.core.registry import calculators


def _calc(fields=(), outputs=(), **kw) -> Calculator:
    base = dict(
        id="toy",
        title="Toy",
        summary="",
        compute=lambda v: Result({}),
        fields=tuple(fields),
        outputs=tuple(outputs),
    )
    base.update(kw)
    return Calculator(**base)


MODE = Field("mode", "Mode", choices=("a", "b"), default="a")


@pytest.mark.parametrize(
    "calc,part,words",
    [
        (_calc([Field("x", "X", "lenght", "mm", default=1)]), "field 'x'", "unknown quantity kind 'lenght'"),
        (_calc([Field("x", "X", "length", "kg", default=1)]), "field 'x'", "cannot show a length"),
        (_calc([Field("x", "X", "length", "furlongz", default=1)]), "field 'x'", "cannot show a length"),
        (_calc([Field("x", "X", "length", "", default=1)]), "field 'x'", "needs a display unit"),
        (
            _calc([Field("x", "X", "length", "mm", default=5, min=10)]),
            "field 'x'",
            "default 5 is refused: 5 is too small: must be at least 10 mm",
        ),
        (_calc([Field("x", "X", "length", "mm", default=5, max=1)]), "field 'x'", "must be at most 1 mm"),
        (
            _calc([Field("x", "X", "length", "mm", default="1 in", max=20)]),
            "field 'x'",
            "must be at most 20 mm",
        ),
        (
            _calc([Field("x", "X", "length", "mm", default=5, min=1, max=0)]),
            "field 'x'",
            "above max 0 (both in mm)",
        ),
        (
            _calc([Field("x", "X", "length", "mm", default=5, max=float("inf"))]),
            "field 'x'",
            "not a finite number",
        ),
        (_calc([Field("x", "X", "length", "mm", default=5, max="9 in")]), "field 'x'", "not a finite number"),
        (_calc([Field("n", "N", integer=True, default=5, max=9.5)]), "field 'n'", "bounds are whole numbers"),
        (_calc([Field("c", "C", choices=("p", "q"), default="r")]), "field 'c'", "default 'r' is refused"),
        (
            _calc([Field("c", "C", choices=("p", "q"), choice_labels=("P",), default="p")]),
            "field 'c'",
            "1 choice labels",
        ),
        (_calc([MODE, Field("x", "X", default=1, modes=("c",))]), "field 'x'", "mode 'c'"),
        (
            _calc([MODE, Field("x", "X", default=1, when=(("kind", ("p",)),))]),
            "field 'x'",
            "not a choice field",
        ),
        (_calc([MODE, Field("x", "X", default=1, when=(("mode", ("z",)),))]), "field 'x'", "'z'"),
        (_calc([Field("x", "X", default=1), Field("x", "X2", default=2)]), "field 'x'", "more than once"),
        (_calc([MODE], tables=(Table("t", "T", (), modes=("c",)),)), "table 't'", "mode 'c'"),
        (_calc([MODE], tables=(Table("t", "T", (), when=(("x", ("p",)),)),)), "table 't'", "not a choice"),
        (_calc([MODE], tables=(Table("t", "T", (), when=(("mode", ("z",)),)),)), "table 't'", "'z'"),
        (_calc(outputs=[Output("y", "Y", "force", "lbz")]), "output 'y'", "cannot show a force"),
        (_calc(outputs=[Output("y", "Y", "forse", "N")]), "output 'y'", "unknown quantity kind"),
        (
            _calc(
                outputs=[Output("y", "Y")], plots=(Plot("P", ("s",), "t", "time", "s", "v", "speed", "rpm"),)
            ),
            "plot 'P' y axis",
            "cannot show a speed",
        ),
        (
            _calc(outputs=[Output("y", "Y")], exports={"gear_ratio": {"load": "z"}}),
            "export to gear_ratio.load",
            "'z' is not an output",
        ),
    ],
)
def test_broken_declaration_fails_naming_calculator_and_part(calc, part, words):
    with pytest.raises(DeclarationError) as info:
        check(calc)
    assert info.value.calc_id == "toy" and info.value.part == part
    assert words in str(info.value)
    assert str(info.value).startswith("calculator 'toy', ")


def test_every_builtin_declaration_passes():
    for calc in calculators().values():
        check(calc)  # raises on the first inconsistency


# Outputs no preset happens to reach (the third cylinder group is empty in every built-in preset;
# no ratio_finder preset needs three stages)
EXTRA = {
    "pneumatics": [{"c3_count": 1}],
    "ratio_finder": [{"target_ratio": 5000, "families": "gear_20dp"}],
    "flywheel": [{"control": "velocity_loop", "setpoint_profile": "ramp"}, {"control": "limit_grid"}],
}


def _runs(calc):
    """Defaults in every mode and every built-in preset of the calculator."""
    raws = [{}] + [{"mode": m} for m in calc.modes]
    raws += [p.inputs for p in presets.listing() if p.builtin and p.calculator == calc.id]
    raws += EXTRA.get(calc.id, [])
    for raw in raws:
        values, _ = parse_inputs(calc, raw)
        yield raw, calc.compute(values)


@pytest.mark.parametrize("calc_id", list(calculators()))
def test_outputs_returned_are_declared_and_each_declared_one_is_produced(calc_id):
    calc = calculators()[calc_id]
    declared = {o.name for o in calc.outputs}
    produced = set()
    for raw, result in _runs(calc):
        undeclared = set(result.values) - declared
        assert not undeclared, f"{calc_id} {raw}: returns undeclared outputs {sorted(undeclared)}"
        produced |= set(result.values)
    assert declared - produced == set(), f"{calc_id}: declared but never produced"


@pytest.mark.parametrize(
    "exports,part,words",
    [
        ({"nowhere": {"load": "y"}}, "export to 'nowhere'", "no such calculator"),
        ({"gear_ratio": {"lode": "y"}}, "export to gear_ratio.lode", "no such field"),
        ({"gear_ratio": {"radius": "y"}}, "export to gear_ratio.radius", "sends a force to a length field"),
    ],
)
def test_broken_link_between_calculators_fails_at_load(exports, part, words):
    toy = _calc(outputs=[Output("y", "Y", "force", "N")], exports=exports)
    with pytest.raises(DeclarationError) as info:
        check_links({**calculators(), "toy": toy})
    assert info.value.part == part and words in str(info.value)
