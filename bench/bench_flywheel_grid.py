"""The flywheel's current-limit grid (control = limit_grid, issue 30): timings, printed, never asserted.

Run:  .venv/bin/python bench/bench_flywheel_grid.py
- the default grid (11 stator × 7 supply limits: 77 cells, each a log scan of 24 ratios and bounded
  Brent, every spin-up time a quadrature (FW6)), flywheel.simulate once, median of 3, beside one
  full-power solve of the same flywheel with both limits on (the baseline, measured in the same
  run); the issue's goal for a grid: ≤ 2 s;
- the same grid's spin-up time at one cell by quadrature against the scene's integrator
  (flywheel.recovery, DP54 phase by phase), median of 200 each.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)

CASES = {
    "2 Kraken X60, 3e-3 kg·m², 4000 rpm": {
        "motor": "Kraken X60",
        "voltage": "12 V",
        "motor_count": 2,
        "mode": "moment_of_inertia",
        "wheel_inertia": "0.003 kg*m**2",
        "target_speed": "4000 rpm",
    },
    "+ battery sag": {
        "motor": "Kraken X60",
        "voltage": "12 V",
        "motor_count": 2,
        "mode": "moment_of_inertia",
        "wheel_inertia": "0.003 kg*m**2",
        "target_speed": "4000 rpm",
        "effects": "battery_sag",
    },
}


def main() -> None:
    from gearhead.core.calculators import flywheel
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get
    from gearhead.core.sim.scene import LEVELS
    from gearhead.core.sim.shooter import grid_spin_up

    rtol = LEVELS["default"]
    calc = get("flywheel")
    print("The 11 × 7 grid, median of 3 (baseline: one full-power solve with both limits on):")
    for label, raw in CASES.items():
        on = raw.get("effects", "")
        limited = {**raw, "effects": ", ".join(x for x in (on, "stator_limit, supply_limit") if x)}
        v_base, _ = parse_inputs(calc, limited)
        v_grid, _ = parse_inputs(calc, {**raw, "control": "limit_grid"})
        t_base = median_seconds(lambda: flywheel.simulate(v_base, rtol), 3) * 1e3
        t_grid = median_seconds(lambda: flywheel.simulate(v_grid, rtol), 3) * 1e3
        print(f"  {label:<36} grid {t_grid:7.1f} ms  (one solve {t_base:6.2f} ms, x{t_grid / t_base:.0f})")

    v, _ = parse_inputs(
        calc, {**CASES["2 Kraken X60, 3e-3 kg·m², 4000 rpm"], "effects": "stator_limit, supply_limit"}
    )
    v = dict(v)
    t_quad = median_seconds(lambda: grid_spin_up(v, 1.2), 200) * 1e6
    sc, _ = flywheel.scene_from({**v, "ratio": 1.2}, rtol)
    t_ode = median_seconds(lambda: flywheel.recovery(sc, 0.0, v["target_speed"]), 200) * 1e6
    print(f"One cell's spin-up time: quadrature (scene included) {t_quad:6.1f} µs, DP54 {t_ode:6.1f} µs")


if __name__ == "__main__":
    main()
