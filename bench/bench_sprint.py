"""Drivetrain sprint figures (printed, never asserted; issue 29's goals: a sprint ≤ 5 ms median, the
optimiser ≤ 100 ms). Each beside the drivetrain tab's forward solve, measured in the same run, as a
baseline the machine's speed cancels from.

Run: .venv/bin/python bench/bench_sprint.py
"""

from __future__ import annotations

import time

from timing import median_seconds


def main() -> None:
    from gearhead.core.calculators import sprint
    from gearhead.core.model import parse_inputs, solve
    from gearhead.core.registry import get

    base = median_seconds(lambda: solve("drivetrain", {}), 200)
    print(f"  baseline: drivetrain forward solve        {base * 1e3:8.3f} ms")
    cases = {
        "sprint, closed form (no limits)": {"effects": ""},
        "sprint, limits + sag (integrated)": {},
        "sprint, limits + sag + voltage ramp": {
            "effects": "stator_limit, supply_limit, battery_sag, voltage_ramp"
        },
        "sprint, every effect": {
            "effects": "stator_limit, supply_limit, battery_sag, rolling_resistance, air_drag, voltage_ramp"
        },
    }
    for label, raw in cases.items():
        s = median_seconds(lambda raw=raw: solve("sprint", raw), 100)
        print(f"  {label:<40} {s * 1e3:8.3f} ms  ({s / base:5.1f}x baseline)")
    v = parse_inputs(get("sprint"), {})[0]
    ramped = parse_inputs(
        get("sprint"), {"effects": "stator_limit, supply_limit, battery_sag, voltage_ramp"}
    )[0]
    for label, fn in (
        ("optimise one distance (200-ratio batch + Brent)", lambda: sprint.fastest(v, 1e-6, 5.0)),
        ("the same under a voltage ramp", lambda: sprint.fastest(ramped, 1e-6, 5.0)),
        ("optimise mode, whole solve (4-distance table)", lambda: solve("sprint", {"mode": "optimise"})),
    ):
        t0 = time.perf_counter()
        fn()
        first = time.perf_counter() - t0
        s = median_seconds(fn, 5)
        print(f"  {label:<40} {s * 1e3:8.1f} ms  (first {first * 1e3:.1f} ms; {s / base:6.0f}x baseline)")


if __name__ == "__main__":
    main()
