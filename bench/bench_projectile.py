"""Projectile scene timings (printed, never asserted).

Run:  .venv/bin/python bench/bench_projectile.py
- closed form (no effects), forward and reverse with drag, drag + Magnus: the scene alone at the
  default accuracy and the full solve (which adds the run at 100x tighter tolerance);
- the accuracy ladder (core.sim.scene.ladder) of the drag shot: error vs a 1e-13 reference, time, work.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)

CASES = {
    "vacuum forward (closed form)": {},
    "vacuum reverse (closed form)": {"mode": "reverse"},
    "drag forward": {"effects": "air_drag"},
    "drag reverse (root finding)": {"effects": "air_drag", "mode": "reverse"},
    "drag + magnus forward": {"effects": "air_drag, magnus", "spin": "2000 rpm"},
    "drag + magnus reverse": {"effects": "air_drag, magnus", "spin": "2000 rpm", "mode": "reverse"},
}


def scene_rows(calc_id: str, cases: dict) -> None:
    """One line a case: the scene alone at the default accuracy, the full solve, the scene's nfev."""
    from gearhead.core.model import parse_inputs, solve
    from gearhead.core.registry import get
    from gearhead.core.sim.scene import LEVELS

    calc = get(calc_id)
    print("  default accuracy (rtol 1e-6), median of 50; nfev of the scene alone:")
    for name, raw in cases.items():
        values, _ = parse_inputs(calc, raw)
        scene = median_seconds(lambda: calc.simulate(values, LEVELS["default"]), 50) * 1e3
        full = median_seconds(lambda: solve(calc_id, raw), 50) * 1e3
        nfev = calc.simulate(values, LEVELS["default"]).nfev
        print(f"    {name:<30} scene {scene:7.3f} ms   solve {full:7.3f} ms   nfev {nfev:6d}")


def main() -> None:
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get
    from gearhead.core.sim.scene import ladder

    calc = get("projectile")
    scene_rows("projectile", CASES)
    for name in ("drag forward", "drag reverse (root finding)"):
        values, _ = parse_inputs(calc, CASES[name])
        t0 = time.perf_counter()
        rungs, _ = ladder(calc.simulate, values)
        total = time.perf_counter() - t0
        print(f"  accuracy ladder, {name} (whole ladder incl. reference: {total * 1e3:.1f} ms):")
        for r in rungs:
            print(
                f"    {r.level:<8} rtol {r.rtol:7.0e}   error {r.error:9.2e}   {r.wall_time * 1e3:8.3f} ms"
                f"   nfev {r.nfev:6d}"
            )


if __name__ == "__main__":
    main()
