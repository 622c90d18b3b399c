"""Flywheel scene timings (printed, never asserted).

Run:  .venv/bin/python bench/bench_flywheel.py
- the scene (spin-up, shot, recovery, range table, burst) at the default accuracy, closed form
  (energy and momentum) and integrated (momentum with motor_during_shot), median of 200 runs;
- the full solve (with the 100x-tighter error estimate when something is integrated);
- the accuracy ladder of the integrated scene: error against a 1e-13 reference, time, evaluations.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)

SCENES = {
    "energy (seed)": {"effects": "energy"},
    "momentum": {"effects": "momentum"},
    "momentum + motor_during_shot": {"effects": "momentum, motor_during_shot"},
}


def main() -> None:
    from gearhead.core.calculators import flywheel as fw
    from gearhead.core.model import parse_inputs, solve
    from gearhead.core.registry import get
    from gearhead.core.sim.scene import LEVELS, ladder

    calc = get("flywheel")
    for label, raw in SCENES.items():
        values, _ = parse_inputs(calc, raw)
        run = fw.simulate(values, LEVELS["default"])
        scene = median_seconds(lambda: fw.simulate(values, LEVELS["default"]), 200) * 1e3
        full = median_seconds(lambda: solve("flywheel", raw), 200) * 1e3
        print(f"  {label:<30} scene {scene:7.3f} ms  solve {full:7.3f} ms  rhs evaluations {run.nfev}")
    values, _ = parse_inputs(calc, SCENES["momentum + motor_during_shot"])
    rungs, _ = ladder(fw.simulate, values)
    print("  accuracy ladder (momentum + motor_during_shot):")
    for r in rungs:
        print(
            f"    {r.level:<8} rtol {r.rtol:.0e}  error {r.error:.2e}  time {r.wall_time * 1e3:7.3f} ms  nfev {r.nfev}"
        )


if __name__ == "__main__":
    main()
