"""The exact factors in core.constants agree with pint's definitions."""

import math

import pint
import pytest

from gearhead.core import constants as c

UREG = pint.UnitRegistry()


@pytest.mark.parametrize(
    "name,unit",
    [
        ("INCH", "inch"),
        ("FOOT", "foot"),
        ("LB", "lb"),
        ("LBF", "lbf"),
        ("PSI", "psi"),
        ("RPM", "rpm"),
        ("G0", "standard_gravity"),
    ],
)
def test_constant_matches_pint(name, unit):
    si = UREG.Quantity(1, unit).to_base_units().magnitude
    assert math.isclose(getattr(c, name), si, rel_tol=1e-15)
