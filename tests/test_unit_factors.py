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
