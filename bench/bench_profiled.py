"""The profiled move (core.sim.profiled, issue 30): timings and solver work, printed, never asserted.

Run:  .venv/bin/python bench/bench_profiled.py
- one profiled move (elevator.simulate at the default accuracy: the loop at 20 ms, outputs, plots),
  median of 30, beside the full-voltage move of the same elevator measured in the same run (the
  baseline); goal: ≤ 20 ms median; the same move with the exponential profile (max input 10 V)
  beside the trapezoid's;
- the right-hand-side evaluations a 20 ms period costs with the per-period exponential integrator
  (the default), the scene's DP54 per period, and a fixed 0.1 ms RK4 step (800 a period), with what
  each gives for the settle time (the 0.1 ms RK4 and the exponential integrator at 1e-10 as the
  reference);
- the current-limit grid (11 stator × 7 supply limits, the elevator's and the arm's simulate once, no
  error estimate), median of 3, beside one optimise-mode solve of the same mechanism (the baseline);
  goal ≤ 2 s;
- the arm's profiled solve (arm.simulate at the default accuracy), which runs the return move too
  (P16), median of 30, beside the one-way solve it replaced (the same setup and run_profiled without
  the return, measured in the same run: the baseline);
- the flywheel's velocity loop (core.sim.velocity_loop: closed form per period, DP54 per period
  with a current limit), median of 30, beside the full-power spin-up of the same flywheel (the
  baseline, the default mode).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)

CASES = {
    "elevator, gravity": {},
    "elevator, limits + sag + friction": {
        "effects": "gravity, stator_limit, supply_limit, battery_sag, friction",
        "stator_current_limit": "35 A",
        "supply_current_limit": "25 A",
        "sensor_delay": "10 ms",
    },
}


def main() -> None:
    from gearhead.core.calculators import elevator
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get
    from gearhead.core.sim import motion, profiled
    from gearhead.core.sim.scene import LEVELS

    rtol = LEVELS["default"]
    calc = get("elevator")
    print("One move at the default accuracy (rtol 1e-6), median of 30 (baseline: the full-voltage move):")
    for label, raw in CASES.items():
        v_move, _ = parse_inputs(calc, raw)
        v_prof, _ = parse_inputs(calc, {**raw, "mode": "profiled"})
        t_move = median_seconds(lambda: elevator.simulate(v_move, rtol), 30) * 1e3
        t_prof = median_seconds(lambda: elevator.simulate(v_prof, rtol), 30) * 1e3
        run = elevator.simulate(v_prof, rtol)
        print(
            f"  {label:<36} profiled {t_prof:6.2f} ms  (full-voltage move {t_move:6.2f} ms, "
            f"x{t_prof / t_move:.1f})  {run.values['control_updates']} updates, rhs {run.nfev}"
        )
        v_expo, _ = parse_inputs(calc, {**raw, "mode": "profiled", "profile_type": "exponential"})
        t_expo = median_seconds(lambda: elevator.simulate(v_expo, rtol), 30) * 1e3
        run = elevator.simulate(v_expo, rtol)
        print(
            f"  {'':<36} exponential {t_expo:6.2f} ms  (the trapezoid's {t_prof:6.2f} ms, "
            f"x{t_expo / t_prof:.2f})  {run.values['control_updates']} updates, rhs {run.nfev}"
        )

    print("Right-hand-side evaluations per 20 ms period, and the settle time each gives:")
    for label, raw in CASES.items():
        v, _ = parse_inputs(calc, {**raw, "mode": "profiled"})
        s = elevator.setup(v)
        ff = motion.feedforward(s, s.mech.q1)
        loop, profile, _ = profiled.loop_of(s, v, ff, lambda q: ff["kG"])
        ref = profiled.profiled_move(s, loop, profile, 1e-10).values["settle_time"]
        print(f"  {label} (settle time at 1e-10: {ref:.9f} s)")
        for method, tol in (("EXP", 1e-6), ("EXP", 1e-9), ("DP54", 1e-6), ("DP54", 1e-9), ("RK4", 0.0)):
            run = profiled.profiled_move(s, loop, profile, tol, method=method)
            wall = median_seconds(lambda: profiled.profiled_move(s, loop, profile, tol, method=method), 3)
            name = "RK4, fixed 0.1 ms" if method == "RK4" else f"{method}, rtol {tol:.0e}"
            print(
                f"    {name:<20} {run.nfev / run.updates:7.1f} per period  {wall * 1e3:8.1f} ms  "
                f"settle error {run.values['settle_time'] - ref:+.2e} s"
            )


def grid() -> None:
    from gearhead.core.calculators import arm, elevator
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get
    from gearhead.core.sim.scene import LEVELS

    rtol = LEVELS["default"]
    for module in (elevator, arm):
        name = module.CALCULATOR.id
        calc = get(name)
        for label, effects in (("gravity", "gravity"), ("gravity + sag", "gravity, battery_sag")):
            v_grid, _ = parse_inputs(calc, {"mode": "limit_grid", "effects": effects})
            v_opt, _ = parse_inputs(
                calc, {"mode": "optimise", "effects": effects + ", stator_limit, supply_limit"}
            )
            t_opt = median_seconds(lambda: module.simulate(v_opt, rtol), 3)
            t_grid = median_seconds(lambda: module.simulate(v_grid, rtol), 3)
            run = module.simulate(v_grid, rtol)
            print(
                f"  {name:<8} grid 11 x 7, {label:<14} {t_grid:6.3f} s  (one optimise solve "
                f"{t_opt * 1e3:6.1f} ms)  {run.values['grid_cells']} cells, rhs {run.nfev}"
            )


def flywheel_loop() -> None:
    from gearhead.core.calculators import flywheel
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get
    from gearhead.core.sim.scene import LEVELS

    rtol = LEVELS["default"]
    calc = get("flywheel")
    frc = {
        "motor": "Kraken X60",
        "motor_count": 2,
        "voltage": "12 V",
        "ratio": 0.6667,
        "target_speed": "5000 rpm",
        "sensor_delay": "10 ms",
        "shot_time": "1.5 s",
    }
    cases = {
        "VEX 393 defaults": {},
        "Kraken x2, no limit": frc,
        "Kraken x2, limits + sag": {**frc, "effects": "stator_limit, supply_limit, battery_sag"},
    }
    for label, raw in cases.items():
        v_full, _ = parse_inputs(calc, raw)
        v_loop, _ = parse_inputs(calc, {**raw, "control": "velocity_loop"})
        t_full = median_seconds(lambda: flywheel.simulate(v_full, rtol), 30) * 1e3
        t_loop = median_seconds(lambda: flywheel.simulate(v_loop, rtol), 30) * 1e3
        run = flywheel.simulate(v_loop, rtol)
        print(
            f"  {label:<26} velocity loop {t_loop:6.2f} ms  (full power {t_full:6.2f} ms)  "
            f"{run.values['control_updates']} updates, rhs {run.nfev}"
        )


ARM_CASES = {
    "arm, gravity": {},
    "arm, limits + sag + friction + spring": {
        "effects": "gravity, stator_limit, supply_limit, battery_sag, friction, counterbalance",
        "stator_current_limit": "60 A",
        "supply_current_limit": "40 A",
        "sensor_delay": "10 ms",
    },
    "arm, exponential 8 V": {"profile_type": "exponential", "max_input": "8 V"},
}


def arm_return() -> None:
    import math

    from gearhead.core.calculators import arm
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get
    from gearhead.core.sim import motion, profiled
    from gearhead.core.sim.motor_limits import braking_warning
    from gearhead.core.sim.scene import LEVELS

    rtol = LEVELS["default"]
    calc = get("arm")

    def one_way(v):  # arm.simulate's profiled branch before the return move
        s = arm.setup(v)
        ff = motion.feedforward(s, 0.0)
        run = profiled.run_profiled(s, v, rtol, ff, lambda q: ff["kG"] * math.cos(q))
        braking_warning(v, run)
        return run

    for label, raw in ARM_CASES.items():
        v, _ = parse_inputs(calc, {**raw, "mode": "profiled"})
        t_one = median_seconds(lambda: one_way(v), 30) * 1e3
        t_both = median_seconds(lambda: arm.simulate(v, rtol), 30) * 1e3
        n_one, n_both = one_way(v).nfev, arm.simulate(v, rtol).nfev
        print(
            f"  {label:<40} both ways {t_both:6.2f} ms  (one way {t_one:6.2f} ms, x{t_both / t_one:.2f})  "
            f"rhs {n_both} (one way {n_one})"
        )


if __name__ == "__main__":
    main()
    print("Arm profiled solve with the return move, median of 30 (baseline: the one-way solve, same arm):")
    arm_return()
    print("Current-limit grid (median of 3):")
    grid()
    print("Flywheel velocity loop, median of 30 (baseline: the full-power spin-up, same flywheel):")
    flywheel_loop()
