"""Elevator and arm scene timings (printed, never asserted).

Run:  .venv/bin/python bench/bench_motion.py
- one move at the default accuracy (integration only, and the whole scene: samples for the plots,
  LQR gains, outputs), median of 100 runs; target ≤ 5 ms;
- the right-hand-side evaluations of a 3 s move, beside the 30 000 steps a fixed 0.1 ms step takes;
- the optimisation: ≥ 200 candidate ratios batched in numpy (target ≤ 200 ms), and the whole
  optimise mode (batch, bounded Brent on the accurate move, the move at the best ratio).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)

SCENES = {
    "elevator, gravity": ("elevator", {}),
    "elevator, limits + sag": ("elevator", {"effects": "gravity, stator_limit, supply_limit, battery_sag"}),
    "arm, gravity": ("arm", {}),
    "arm, all effects": (
        "arm",
        {"effects": "gravity, stator_limit, supply_limit, battery_sag, friction, counterbalance"},
    ),
}


def main() -> None:
    import numpy as np

    from gearhead.core.calculators import arm, elevator
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get
    from gearhead.core.sim import motion
    from gearhead.core.sim.scene import LEVELS

    mods = {"elevator": elevator, "arm": arm}
    rtol = LEVELS["default"]
    print("One move at the default accuracy (rtol 1e-6), median of 100:")
    for label, (cid, raw) in SCENES.items():
        v, _ = parse_inputs(get(cid), raw)
        mod = mods[cid]
        setup = mod.setup(v)
        mv = motion.move(setup, rtol)
        t_move = median_seconds(lambda: motion.move(mod.setup(v), rtol), 100) * 1e3
        t_scene = median_seconds(lambda: mod.simulate(v, rtol), 100) * 1e3
        print(
            f"  {label:<24} move {t_move:6.2f} ms  scene {t_scene:6.2f} ms  rhs {mv.nfev:5d}  "
            f"time to goal {mv.time:.4f} s  ({mv.method})"
        )

    print("A 3 s move (elevator, 2 NEO, 15 lb, ratio 34): right-hand-side evaluations")
    v, _ = parse_inputs(get("elevator"), {"ratio": 34})
    for method in ("DP54", "LSODA", None):
        mv = motion.move(elevator.setup(v), rtol, method=method)
        print(
            f"  asked {method or 'auto':<6} ran {mv.method:<17} {mv.nfev:6d} evaluations for {mv.time:.3f} s"
        )
    print(f"  fixed 0.1 ms step: {round(3.0 / 1e-4):6d} steps (x4 evaluations for RK4)")

    print("Optimise:")
    for cid in ("elevator", "arm"):
        v, _ = parse_inputs(get(cid), {"mode": "optimise", "effects": "gravity, stator_limit, battery_sag"})
        mod = mods[cid]
        probe = mod.setup(v)
        G_char = motion.characteristic_n(probe.mech) * (
            elevator.spool_factor(v) if cid == "elevator" else 1.0
        )
        ratios = G_char * np.geomspace(0.05, 20, motion.CANDIDATES)
        batch = mod.setup(v, ratios, motion._Array())
        t_batch = median_seconds(lambda: motion.batch_times(batch), 10) * 1e3
        t_all = median_seconds(lambda: mod.simulate(v, rtol), 5) * 1e3
        run = mod.simulate(v, rtol)
        print(
            f"  {cid:<9} {motion.CANDIDATES} candidates batched {t_batch:6.1f} ms; whole optimise "
            f"{t_all:6.1f} ms (best ratio {run.values['best_ratio']:.4g}, {run.nfev} evaluations)"
        )


if __name__ == "__main__":
    main()
