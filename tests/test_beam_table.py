"""The shipped torsion bounds of common rectangular tubes (core/beams.py TUBE_TABLE): every row is
what the finite-element solve gives, every listed tube reads its row whatever unit it is typed in,
and `gearhead solve beam` (the 2×1×1/16 in default) then never imports numpy (issue 42 item 6:
numpy's import and the solve were ~120 ms of its start)."""

from __future__ import annotations

import subprocess
import sys

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
