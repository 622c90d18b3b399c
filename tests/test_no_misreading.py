"""No silent misreading (issue 41, item 3): a tolerance without a unit takes its value's unit
whatever its form; a unit-less value with a unit-bearing tolerance on a field with a unit is refused
as ambiguous; whole-number fields have an upper bound and keep every digit they accept."""

import pytest

from gearhead.core import tolerance
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.registry import get
from gearhead.tui.cli import main

INCH = 0.0254


def half_width(calc_id: str, field: str, entry: str) -> float:
    _, _, tols, _ = tolerance.parse(get(calc_id), {field: entry})
    (t,) = tols
    return (t.high - t.low) / 2


@pytest.mark.parametrize("tol", ["0.1", "(0.1)", "0.1*1", "1/10", "( 0.1 )", "0.1 mm"])
def test_a_bare_tolerance_takes_the_values_unit_whatever_its_form(tol):
    """`50.8 mm ± 0.1` was ±0.1 mm but `50.8 mm ± (0.1)` ±0.1 in (the radius field's unit)."""
    assert half_width("gear_ratio", "radius", f"50.8 mm ± {tol}") == pytest.approx(0.0001, rel=1e-9)


@pytest.mark.parametrize("tol", ["0.1", "(0.1)", "0.1*1"])
def test_a_bare_tolerance_on_a_bare_value_is_in_the_fields_unit(tol):
    assert half_width("gear_ratio", "radius", f"2 ± {tol}") == pytest.approx(0.1 * INCH, rel=1e-9)


@pytest.mark.parametrize("tol", ["1", "(1)", "1*1"])
def test_a_bare_tolerance_after_an_expression_is_refused_whatever_its_form(tol):
    with pytest.raises(InputError, match="has no unit"):
        half_width("gear_ratio", "radius", f"2 ft + 3 in ± {tol}")


def test_a_bare_value_with_a_unit_bearing_tolerance_is_refused_as_ambiguous(capsys):
    """`20 ± 1 mm` on the radius (inches) was read as 20 in ± 1 mm."""
    with pytest.raises(InputError, match="ambiguous") as caught:
        half_width("gear_ratio", "radius", "20 ± 1 mm")
    assert "'20 mm ± 1 mm'" in caught.value.message and "'20 in ± 1 mm'" in caught.value.message
    assert main(["solve", "gear_ratio", "--set", "radius=20 ± 1 mm"]) == 2
    assert "radius" in capsys.readouterr().err
    # written unambiguously, both readings are taken as written
    assert half_width("gear_ratio", "radius", "20 mm ± 1 mm") == pytest.approx(0.001)
    assert half_width("gear_ratio", "radius", "20 in ± 1 mm") == pytest.approx(0.001)
    assert half_width("gear_ratio", "radius", "20 ± 5 %") == pytest.approx(20 * INCH * 0.05)


def test_links_keep_every_digit_or_are_refused():
    """9007199254740993 links came back as …992 (read through a float); 1e308 links gave a C-C
    distance of 9.8e306 in. The field now has a maximum (100 000) and the kind reads exactly."""
    assert get("chain_belt").field("links").max == 100_000
    for entry in ("9007199254740993", 9007199254740993, "1e308", 1e308, 10**5000, "1e999999999", 100_001):
        with pytest.raises(InputError, match="too large") as caught:
            solve("chain_belt", {"links": entry})
        assert caught.value.field == "links"
    assert solve("chain_belt", {"links": "100000"}).outputs  # the bound itself is accepted


def test_the_integer_kind_reads_exactly_up_to_its_bound():
    from gearhead.core.fields import MAX_WHOLE, Field

    f = Field("n", "N", integer=True)  # no max of its own: the kind's bound applies
    assert f.parse(str(MAX_WHOLE)) == MAX_WHOLE and f.parse(str(MAX_WHOLE - 1)) == MAX_WHOLE - 1
    assert f.parse("999999999999999") == 999_999_999_999_999
    assert f.parse("1e3") == 1000 and f.parse("36.0") == 36 and f.parse("３６") == 36
    for bad in (str(MAX_WHOLE + 1), MAX_WHOLE + 1, "1.5", "nan", "inf", "1e16"):
        with pytest.raises(InputError):
            f.parse(bad)
