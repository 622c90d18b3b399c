"""The shipped torsion bounds of common rectangular tubes (core/beams.py TUBE_TABLE): every row is
what the finite-element solve gives, every listed tube reads its row whatever unit it is typed in,
and `gearhead solve beam` (the 2×1×1/16 in default) then never imports numpy (issue 42 item 6:
numpy's import and the solve were ~120 ms of its start). The solve's shipped element matrices
(TUBE_REFERENCE) are the code's own, and their rounding stays inside J's stated error (checked
against the exact integrals, 40-digit mpmath)."""

from __future__ import annotations

import subprocess
import sys

import mpmath as mp
import numpy as np
import pytest

from gearhead.core import beams
from gearhead.core.model import solve
from tests import tube_table


@pytest.mark.parametrize("row", beams.TUBE_TABLE, ids=lambda row: f"{row[0]:.4g}x{row[1]:.4g}")
def test_every_row_is_the_finite_element_solve(row):
    """Recomputed: each bound, and J (their midpoint), within the solves' stated rounding of J."""
    W, H, lower, upper = row
    fe_lower, fe_upper = beams._tube_torsion_bounds.__wrapped__(W, H)
    J = (fe_lower + fe_upper) / 2
    assert abs(lower - fe_lower) <= beams.TUBE_ROUNDING * J
    assert abs(upper - fe_upper) <= beams.TUBE_ROUNDING * J
    assert abs((lower + upper) / 2 - J) <= beams.TUBE_ROUNDING * J


def test_the_table_holds_the_listed_tubes_and_nothing_else():
    """Rows are written by `python -m tests.tube_table`: one per side/wall ratio pair, none shadowing
    another in the lookup."""
    assert [row[:2] for row in beams.TUBE_TABLE] == sorted(tube_table.ratios())
    assert len(beams._TUBE_ROWS) == len(beams.TUBE_TABLE)


def _no_solve(W, H):
    raise AssertionError(f"solved {W}x{H} instead of reading the table")


@pytest.mark.parametrize("unit,per_inch", [("in", 1.0), ("mm", 25.4), ("m", 0.0254)])
def test_every_listed_tube_reads_its_row_in_any_unit(unit, per_inch, monkeypatch):
    monkeypatch.setattr(beams, "_tube_torsion_bounds", _no_solve)
    for _name, x, y, t in tube_table.TUBES:
        for height, width in ((x, y), (y, x)):
            inputs = {
                "section": "rectangular_tube",
                "height": f"{height * per_inch!r} {unit}",
                "width": f"{width * per_inch!r} {unit}",
                "wall": f"{t * per_inch!r} {unit}",
            }
            assert solve("beam", inputs).outputs["torsion_constant"].value > 0
    assert solve("beam", {}).outputs["torsion_constant"].value > 0  # the default tube


def test_a_ratio_off_every_row_is_solved():
    """Beyond TUBE_TABLE_MATCH of a row the bounds are the solve's (a 2×1×1/16 in tube 1e-9 wider)."""
    W, H = 32.0 * (1 + 1e-9), 16.0
    assert beams._tube_bounds(W, H) == beams._tube_torsion_bounds(W, H)
    assert beams._tube_bounds(W, H) != beams._tube_bounds(32.0, 16.0)
    near = beams._tube_bounds(32.0 * (1 + 1e-13), 16.0 * (1 - 1e-13))
    assert near == beams._tube_bounds(32.0, 16.0) == beams._TUBE_ROWS[(32.0, 16.0)][2:]


def test_default_beam_solve_does_not_import_numpy():
    code = (
        "import sys, io, contextlib\n"
        "from gearhead.tui.cli import main\n"
        "sys.argv = ['gearhead', 'solve', 'beam']\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    try:\n"
        "        main()\n"
        "    except SystemExit:\n"
        "        pass\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('numpy', 'scipy')))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_shipped_element_matrices_are_the_codes_own():
    """TUBE_REFERENCE is _spectral_reference(TUBE_DEGREE) to the rounding OpenBLAS's kernels give it
    (7.6e-13 at most, on stiffness entries up to 42; bit for bit on Haswell and Zen)."""
    for shipped, computed in zip(
        beams._tube_reference(), beams._spectral_reference.__wrapped__(beams.TUBE_DEGREE)
    ):
        assert shipped.shape == computed.shape
        assert np.max(np.abs(shipped - computed)) <= 1e-12


def _exact_reference(p: int):
    """_spectral_reference in 40 digits: Lobatto nodes (roots of P_p'), then every integral of the
    Lagrange basis from its polynomial coefficients, exactly; rounded to floats once."""
    with mp.workdps(40):
        legendre = [[mp.mpf(1)], [mp.mpf(0), mp.mpf(1)]]  # ascending coefficients, Bonnet's recurrence
        for n in range(1, p):
            a = [mp.mpf(0)] + [c * (2 * n + 1) for c in legendre[n]]
            b = legendre[n - 1] + [mp.mpf(0)] * 2
            legendre.append([(a[i] - n * b[i]) / (n + 1) for i in range(n + 2)])
        slope = [legendre[p][i] * i for i in range(1, p + 1)]
        roots = sorted(mp.re(r) for r in mp.polyroots(slope[::-1], maxsteps=200, extraprec=200))
        s = [(x + 1) / 2 for x in [mp.mpf(-1), *roots, mp.mpf(1)]]  # on [0, 1]

        def times(a, b):
            out = [mp.mpf(0)] * (len(a) + len(b) - 1)
            for i, u in enumerate(a):
                for j, v in enumerate(b):
                    out[i + j] += u * v
            return out

        def integral(c):  # over [0, 1]
            return mp.fsum(v / (k + 1) for k, v in enumerate(c))

        basis = []
        for i in range(p + 1):
            c = [mp.mpf(1)]
            for j in range(p + 1):
                if j != i:
                    c = times(c, [-s[j] / (s[i] - s[j]), 1 / (s[i] - s[j])])
            basis.append(c)
        slopes = [[c[k] * k for k in range(1, len(c))] for c in basis]
        stiffness = [[integral(times(a, b)) for b in slopes] for a in slopes]
        mass = [[integral(times(a, b)) for b in basis] for a in basis]
        weights = [integral(c) for c in basis]
        moments = [integral(times(c, [0, 1])) for c in basis]
        return tuple(np.array(x, dtype=float) for x in (s, stiffness, mass, weights, moments))


def test_element_matrix_rounding_stays_inside_the_stated_error(monkeypatch):
    """The shipped matrices are ~30 ulps from the exact integrals (2.7e-13 on the stiffness); solved
    from the exact ones, every row's J moves by less than its stated error (0.43x at most, 2×1×0.040
    in; 3.6e-9 on 2×2×1/16 in, beyond the solves' rounding TUBE_ROUNDING)."""
    exact = _exact_reference(beams.TUBE_DEGREE)
    for shipped, want in zip(beams._tube_reference(), exact):
        assert np.max(np.abs(shipped - want)) <= 5e-13
    monkeypatch.setattr(beams, "_tube_reference", lambda: exact)
    for W, H, lower, upper in beams.TUBE_TABLE:
        J = (lower + upper) / 2
        stated = max((upper - lower) / (upper + lower), beams.TUBE_ROUNDING)
        J_exact = sum(beams._tube_torsion_bounds.__wrapped__(W, H)) / 2
        assert abs(J_exact / J - 1) < stated, (W, H)
