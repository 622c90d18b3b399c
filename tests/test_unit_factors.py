"""The stored unit factors are pint's, and cover every unit Gearhead declares."""

import subprocess
import sys

from gearhead.core import unit_factors, units


def test_every_declared_unit_is_stored():
    missing = sorted(u for u in unit_factors.declared_units() if units.stored_factor(*u) is None)
    assert not missing, f"run python -m gearhead.core.unit_factors (missing {missing})"


def test_stored_factors_equal_pints_exactly():
    assert units.stored_factors() == unit_factors.generate()


def test_a_solve_with_bare_numbers_never_loads_pint():
    code = (
        "import sys; from gearhead.core.model import solve; "
        "solve('gear_ratio', {'load': '40', 'radius': '0.75'}); solve('beam', {}); "
        "print('pint' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_a_typed_unit_still_goes_to_pint():
    import pytest

    pint_value = units.registry().Quantity(3, "furlong").to("m").magnitude
    assert units.parse("3 furlong", "m", "length", "x") == pytest.approx(pint_value, rel=1e-15)


def _pint_reading(text: str, kind: str) -> float:
    """What pint makes of a whole entry (the path every typed unit took before the table)."""
    s = units.normalise(text, "x", kind)
    return units._to_si(units._evaluate(s, "x", kind), s, "x", kind)


def test_a_number_and_a_stored_unit_read_as_pint_reads_the_whole_entry():
    """Each stored unit typed after a number ("20 in", "-3.5e2 lbf", "90%"): the table's value
    is pint's to the last bit or one rounding step (the product is rounded once either way)."""
    import math

    checked = 0
    for key in units.stored_factors():
        kind, unit = key.split("|", 1)
        for number in ("20", "-3.5e2", "0.0625", "7"):
            for text in (f"{number} {unit}", f"{number}{unit}"):
                typed = units._NUMBER_AND_UNIT.match(units.normalise(text, "x", kind))
                if typed is None or typed["unit"] != unit:  # a unit beginning with a digit: not read
                    continue
                got = units.parse(text, units.SI_UNITS[kind], kind, "x")  # read by the table
                want = _pint_reading(text, kind)
                assert math.isclose(got, want, rel_tol=2.3e-16, abs_tol=0), (text, kind, got, want)
                checked += 1
    assert checked > 1000


def test_common_typed_units_are_in_the_table():
    for kind, unit in [
        ("length", "in"),
        ("length", "inches"),
        ("length", "mm"),
        ("force", "lbf"),
        ("mass", "lb"),
        ("torque", "in*lbf"),
        ("pressure", "psi"),
        ("speed", "ft/s"),
        ("angular_speed", "rpm"),
        ("dimensionless", "%"),
    ]:
        assert units.stored_factor(unit, kind) is not None, (kind, unit)


def test_a_solve_with_typed_units_never_loads_pint():
    code = (
        "import sys; from gearhead.core.model import solve; "
        "solve('beam', {'length': '20 in'}); "
        "solve('gear_ratio', {'load': '40 lbf', 'radius': '0.75in', 'efficiency': '90 %'}); "
        "print('pint' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_what_the_table_cannot_read_still_goes_to_pint():
    import pytest

    from gearhead.core.errors import InputError

    # another kind's unit: pint's message, naming the kind expected
    with pytest.raises(InputError, match="is not a force"):
        units.parse("20 in", "N", "force", "load")
    # an expression, a unit pint knows but the table does not, a power, two numbers
    assert units.parse("2 ft + 3 in", "m", "length", "x") == pytest.approx(0.6858, rel=1e-15)
    assert units.parse("2 in**2", "m**2", "area", "x") == pytest.approx(2 * 0.0254**2, rel=1e-15)
    assert units._NUMBER_AND_UNIT.match("5 1/m") is None  # a unit begins with a letter, µ, ° or %
