"""Every built-in preset still gives the outputs recorded in tests/golden (see golden_outputs.py)."""

import math

import pytest

from tests import golden_outputs

STORED = golden_outputs.stored()
NOW = golden_outputs.current()
CASES = sorted((calc, name) for calc, table in NOW.items() for name in table)


def test_every_builtin_preset_has_a_golden_record():
    assert sorted((c, n) for c, t in STORED.items() for n in t) == CASES


def _same(a, b, tol: tuple[float, float] = (golden_outputs.CLOSED_FORM_RTOL, 0.0)) -> bool:
    """Equal, floats within (relative, absolute) tolerance `tol` (golden_outputs.tolerance)."""
    if isinstance(a, float) or isinstance(b, float):
        if not (isinstance(a, (int, float)) and isinstance(b, (int, float))):
            return False
        rel, abs_ = tol
        return math.isclose(a, b, rel_tol=rel, abs_tol=max(abs_, 1e-300))
    return a == b


@pytest.mark.parametrize("calc,name", CASES)
def test_preset_outputs_unchanged(calc, name):
    want = STORED.get(calc, {}).get(name)
    assert want is not None, f"no golden record for {calc}/{name}: run python -m tests.golden_outputs"
    got = NOW[calc][name]
    assert sorted(got["outputs"]) == sorted(want["outputs"]), "outputs added or removed"
    was, now = want["outputs"], got["outputs"]
    changed = {
        k: (was[k], v) for k, v in now.items() if not _same(v, was[k], golden_outputs.tolerance(k, was, now))
    }
    assert not changed, f"outputs changed (golden, now): {changed}"
    assert got["warnings"] == want["warnings"]
    assert sorted(got.get("tables", {})) == sorted(want.get("tables", {}))
    for name, rows in got.get("tables", {}).items():
        assert len(rows) == len(want["tables"][name]), f"{name}: rows added or removed"
        for n, (row, was) in enumerate(zip(rows, want["tables"][name])):
            assert sorted(row) == sorted(was) and all(_same(row[k], was[k]) for k in row), (
                f"{name} row {n} changed (golden, now): {was}, {row}"
            )


def test_each_output_is_compared_at_its_accuracy():
    """Closed forms to 1e-12; a finite-element J (and the twist and thin-wall error from it) to the
    two runs' J accuracies; a simulation's results to the two runs' error estimates."""
    tube = {
        "torsion_constant": 6.1e-8,
        "twist_angle": 0.1,
        "thin_wall_error": -0.02,
        "torsion_constant_error": 2e-9,
    }
    moved = {**tube, "torsion_constant_error": 3e-9}
    for name, scale in (("torsion_constant", 1 + 4e-9), ("twist_angle", 1 - 4e-9)):
        tol = golden_outputs.tolerance(name, tube, moved)
        assert _same(tube[name], tube[name] * scale, tol)  # the 1.1e-9 to 4.3e-9 kernels give
        assert not _same(tube[name], tube[name] * (1 + 1e-8), tol)
    tol = golden_outputs.tolerance("thin_wall_error", tube, moved)
    assert _same(-0.02, -0.02 + 4e-9, tol) and not _same(-0.02, -0.02 + 1e-8, tol)
    tol = golden_outputs.tolerance("torsion_constant_error", tube, moved)
    assert _same(2e-9, 3e-9, tol) and not _same(2e-9, 2e-8, tol)
    sim = {"time_to_goal": 1.0, "error_estimate": 2e-7}
    tol = golden_outputs.tolerance("time_to_goal", sim, sim)
    assert _same(1.0, 1 + 3e-7, tol) and not _same(1.0, 1 + 5e-7, tol)
    tol = golden_outputs.tolerance("error_estimate", sim, sim)
    assert _same(2e-7, 2e-7 + 1e-15, tol) and not _same(2e-7, 2.1e-7, tol)
    closed = {"free_speed": 600.0}
    tol = golden_outputs.tolerance("free_speed", closed, closed)
    assert _same(600.0, 600.0 * (1 + 1e-13), tol) and not _same(600.0, 600.0 * (1 + 1e-11), tol)
