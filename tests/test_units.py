"""Units at the boundary: any compatible unit in, SI out; wrong kinds name the field."""

import pytest

from gearhead.core import units
from gearhead.core.errors import InputError


@pytest.mark.parametrize(
    "text,unit,kind,si",
    [
        ("3.5 in", "in", "length", 0.0889),
        ("3.5", "in", "length", 0.0889),
        ("12 ft/s", "ft/s", "speed", 3.6576),
        ("60 psi", "psi", "pressure", 413685.43759),
        ("5 lbf*in", "N*m", "torque", 0.56492415),
        ("574 cc", "cc", "volume", 574e-6),
        ("5310 rpm", "rpm", "angular_speed", 556.06189968),
        ("45 deg", "deg", "angle", 0.78539816),
        ("45°", "deg", "angle", 0.78539816),
        ("90 %", "", "dimensionless", 0.9),
        ("0.9", "", "dimensionless", 0.9),
        ("2 lbf", "N", "force", 8.89644323),
    ],
)
def test_parse_to_si(text, unit, kind, si):
    assert units.parse(text, unit, kind, "x") == pytest.approx(si, rel=1e-8)


@pytest.mark.parametrize(
    "text,expect",
    [
        ("3 kg", "is not a length"),
        ("abc", "not a unit I know"),
        ("", "is empty"),
        ("1e999", "not a finite"),
        ("inf", "not a finite"),
        ("nan", "not a finite"),
        ("5 parsecs/", "not a complete expression"),
    ],
)
def test_bad_entries_name_field_and_text(text, expect):
    with pytest.raises(InputError) as e:
        units.parse(text, "in", "length", "radius")
    assert e.value.field == "radius"
    assert expect in e.value.message


def test_format_quantity_uses_display_unit():
    assert units.format_quantity(0.18733, "mm", "length") == "187.33 mm"
    assert units.format_quantity(556.0619, "rpm", "angular_speed") == "5310 rpm"
    assert units.format_number(1.23456789e-7) == "1.2346e-07"
    assert units.format_number(0.0) == "0"


def test_next_unit_walks_the_whole_ring_and_returns_home():
    from gearhead.core.units import COMMON_UNITS, next_unit

    seen, unit = [], "in"
    for _ in range(6):
        unit = next_unit(unit, "length", "in")
        seen.append(unit)
    assert seen == ["mm", "cm", "m", "ft", "in", "mm"]
    for kind, ring in COMMON_UNITS.items():  # every unit of every kind is reached
        home, unit, reached = ring[0], ring[0], set()
        for _ in range(len(ring)):
            unit = next_unit(unit, kind, home)
            reached.add(unit)
        assert reached == set(ring), kind


def test_units_shown_on_screen_read_back_as_typed():
    """The app shows mm⁴, m/s², N·m; typing what is shown must give the same value."""
    from gearhead.core.units import parse
    from gearhead.tui.components.unit_text import pretty_quantity, pretty_unit

    assert pretty_unit("mm**4") == "mm⁴" and pretty_unit("m/s**2") == "m/s²"
    assert pretty_unit("N*m/A") == "N·m/A" and pretty_unit("1/m**-1") == "1/m⁻¹"
    assert pretty_quantity("77425 mm**4") == "77425 mm⁴" and pretty_quantity("12") == "12"
    for plain, kind in [
        ("3 mm**4", "area_moment"),
        ("9.8 m/s**2", "acceleration"),
        ("5 in*lbf", "torque"),
        ("2 kg*m**2", "inertia"),
    ]:
        number, unit = plain.split(" ", 1)
        assert parse(f"{number} {pretty_unit(unit)}", unit, kind, "x") == parse(plain, unit, kind, "x")
