"""Golden file of every built-in preset's outputs: refactors must keep them, each to its accuracy.

    python -m tests.golden_outputs          # rewrite tests/golden/<calculator>.json

Regenerate only when an output is meant to change, and say why in the commit.

Each output is compared at the accuracy its solution states (tolerance()), not bit for bit: the
closed forms to 1e-12 relative; a simulation's results to its error estimate; the beam's
finite-element torsion constant J (and what is computed from it) to the J accuracy. The last two
carry rounding that depends on the CPU's kernels (numpy's and OpenBLAS's SIMD paths: a sparse
LU on another x86-64 machine moves J by 1.1e-9), which a bit-level comparison would call a change.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from gearhead.core import beams, presets
from gearhead.core.model import solve
from gearhead.core.sim.scene import VOLATILE

GOLDEN_DIR = Path(__file__).with_name("golden")


def current() -> dict[str, dict[str, dict]]:
    """{calculator: {preset file name: {"outputs": {name: value}, "warnings": [...]}}}."""
    out: dict[str, dict[str, dict]] = {}
    for p in presets.listing():
        if not p.builtin:
            continue
        sol = solve(p.calculator, p.inputs)
        values = {k: v.value for k, v in sol.outputs.items() if k not in VOLATILE}
        record = {"outputs": values, "warnings": sol.warnings}
        if sol.tables:  # e.g. the ratio finder's combinations, cell by cell (SI values)
            record["tables"] = {
                name: [{k: v.value for k, v in row.items()} for row in rows]
                for name, rows in sol.tables.items()
            }
        out.setdefault(p.calculator, {})[p.path.name] = record
    return out


CLOSED_FORM_RTOL = 1e-12  # an exact formula: only the last few bits of its floating point may move
# A simulation's results carry the rounding of its steps, which follows the CPU's BLAS kernel: the
# elevator's two_neo_exponential (solved exactly between control updates: error estimate 0) moved
# 9.5e-12 between an AMD EPYC (AVX2) and CI's machine over its 133 updates and feedback.
SIM_ROUNDING_RTOL = 1e-10
# What a finite-element J moves, as a multiple of J's relative error (core/calculators/beam.py):
# J and the twist T·l/(G·J) by that error relatively; the thin-wall error B/J − 1 by (1 + it) times
# it, absolutely. J's stated accuracy is itself half the gap of two bounds, each carrying the
# solves' rounding (beams.TUBE_ROUNDING), so it is compared to that rounding, absolutely.
J_RELATIVE = frozenset({"torsion_constant", "twist_angle"})


def tolerance(name: str, want: dict, got: dict) -> tuple[float, float]:
    """(relative, absolute) tolerance of output `name` between two solutions' outputs of one preset.

    Each solution states how far its results may be from the truth: a simulation by its error
    estimate (relative, of its key results: the difference to a run at 100x tighter tolerance),
    a rectangular tube's J by its accuracy (relative). Two runs each within their accuracy of the
    truth differ by at most the sum of the two, which is the tolerance; never below 1e-12 (1e-10
    for a simulation: SIM_ROUNDING_RTOL).
    """
    if "torsion_constant_error" in want and "torsion_constant_error" in got:
        j_accuracy = want["torsion_constant_error"] + got["torsion_constant_error"]
        if name in J_RELATIVE:
            return j_accuracy, 0.0
        if name == "thin_wall_error":
            return CLOSED_FORM_RTOL, (1 + abs(want[name])) * j_accuracy
        if name == "torsion_constant_error":
            return CLOSED_FORM_RTOL, beams.TUBE_ROUNDING
    if "error_estimate" in want and "error_estimate" in got:
        if name == "error_estimate":
            # a difference of two runs: it carries their rounding (~1e-15 of the results) absolutely
            return CLOSED_FORM_RTOL, CLOSED_FORM_RTOL
        return max(SIM_ROUNDING_RTOL, want["error_estimate"] + got["error_estimate"]), 0.0
    return CLOSED_FORM_RTOL, 0.0


def write() -> None:
    GOLDEN_DIR.mkdir(exist_ok=True)
    for calc, table in sorted(current().items()):
        text = json.dumps(dict(sorted(table.items())), indent=1, sort_keys=True, ensure_ascii=False)
        (GOLDEN_DIR / f"{calc}.json").write_text(text + "\n", encoding="utf-8")


def stored() -> dict[str, dict[str, dict]]:
    return {p.stem: json.loads(p.read_text(encoding="utf-8")) for p in sorted(GOLDEN_DIR.glob("*.json"))}


if __name__ == "__main__":
    write()
    print(f"wrote {len(list(GOLDEN_DIR.glob('*.json')))} files to {GOLDEN_DIR}", file=sys.stderr)
