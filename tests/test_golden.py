"""Every built-in preset still gives the outputs recorded in tests/golden (see golden_outputs.py)."""

import math

import pytest

from tests import golden_outputs

STORED = golden_outputs.stored()
NOW = golden_outputs.current()
CASES = sorted((calc, name) for calc, table in NOW.items() for name in table)


def test_every_builtin_preset_has_a_golden_record():
    assert sorted((c, n) for c, t in STORED.items() for n in t) == CASES


def _same(a, b) -> bool:
    if isinstance(a, float) or isinstance(b, float):
        if not (isinstance(a, (int, float)) and isinstance(b, (int, float))):
            return False
        return math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-300)
    return a == b


@pytest.mark.parametrize("calc,name", CASES)
def test_preset_outputs_unchanged(calc, name):
    want = STORED.get(calc, {}).get(name)
    assert want is not None, f"no golden record for {calc}/{name}: run python -m tests.golden_outputs"
    got = NOW[calc][name]
    assert sorted(got["outputs"]) == sorted(want["outputs"]), "outputs added or removed"
    changed = {
        k: (want["outputs"][k], v) for k, v in got["outputs"].items() if not _same(v, want["outputs"][k])
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
