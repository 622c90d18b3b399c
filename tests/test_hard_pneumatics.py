"""Hard cases for the pneumatics compressor curves: the accurate run must follow the vendor table
(through every point, monotone between them), while the seed's 4th-degree fit stays the seed's
comparison. References are scipy's PchipInterpolator and mpmath quadrature, not core's code."""

import mpmath as mp
import numpy as np
import pytest

from gearhead.core.calculators import pneumatics as pn
from gearhead.core.model import parse_inputs
from gearhead.core.registry import get

PSI = pn.PSI
NAMES = list(pn.COMPRESSORS)


def scipy_curve(name):
    from scipy.interpolate import PchipInterpolator

    return PchipInterpolator([k * PSI for k in pn.CURVE_PSI], [c * pn.CFM for c in pn.COMPRESSORS[name]])


@pytest.mark.parametrize("name", NAMES)
def test_curve_is_scipys_pchip_and_passes_through_the_table(name):
    ref = scipy_curve(name)
    curve = pn.flow_curve(name)
    for P in np.linspace(0, 125 * PSI, 2001):
        assert pn.flow_through(curve, float(P)) == pytest.approx(float(ref(P)), rel=1e-14, abs=1e-20)
    for psi, cfm in zip(pn.CURVE_PSI, pn.COMPRESSORS[name]):
        assert pn.flow_through(curve, psi * PSI) == pytest.approx(cfm * pn.CFM, rel=1e-15)


@pytest.mark.parametrize("name", NAMES)
def test_curve_stays_between_neighbouring_table_points(name):
    """Every table falls with pressure; PCHIP keeps each piece within its two points (no wiggle).
    The 4th-degree fit does not: e.g. the AndyMark 1.1 at 5-10 psi, the VIAIR 90C past 100 psi."""
    curve = pn.flow_curve(name)
    data = pn.COMPRESSORS[name]
    for k in range(len(data) - 1):
        lo, hi = sorted((data[k], data[k + 1]))
        for P in np.linspace(pn.CURVE_PSI[k], pn.CURVE_PSI[k + 1], 41) * PSI:
            assert lo * pn.CFM * (1 - 1e-15) <= pn.flow_through(curve, float(P)) <= hi * pn.CFM * (1 + 1e-15)


def test_the_seeds_fit_misses_its_own_table_points():
    """Why the accurate run no longer uses it: 7.5 % off at AndyMark's own 0 psi point."""
    c = pn.flow_fit("AndyMark 1.1 12 V")
    miss = max(
        abs(pn.flow(c, psi * PSI) / (cfm * pn.CFM) - 1)
        for psi, cfm in zip(pn.CURVE_PSI, pn.COMPRESSORS["AndyMark 1.1 12 V"])
    )
    assert miss > 0.07


@pytest.mark.parametrize("name", ["AndyMark 1.1 12 V", "VIAIR 90C 12 V"])
def test_fill_from_empty_follows_the_table(name):
    """Fill 1148 cc from 0 to 120 psi: t = ∫ V dP/(P_atm·V̇(P)), V̇ scipy's PCHIP through the table,
    by mpmath quadrature per piece. With the seed's fit (the old accurate run) the time was off by
    several percent for these two compressors."""
    ref = scipy_curve(name)
    knots = [k * PSI for k in pn.CURVE_PSI]
    exact = float(mp.quad(lambda p: 1148e-6 / (pn.P_ATM * float(ref(float(p)))), knots))
    v = parse_inputs(get("pneumatics"), {"c1_count": 0, "start_pressure": 0, "compressor_model": name})[0]
    run = pn.simulate(v, 1e-11)
    assert run.values["compressor_duty"] * 150 == pytest.approx(exact, rel=1e-8)
