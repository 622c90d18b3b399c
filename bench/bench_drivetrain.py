"""Drivetrain figures (printed, never asserted): warm solve time per mode (incl. the plot series)."""

from __future__ import annotations

import statistics
import time


def main() -> None:
    from core.model import solve

    for mode in ("forward", "reverse", "shifting"):
        raw = {"mode": mode}
        solve("drivetrain", raw)
        samples = []
        for _ in range(300):
            t0 = time.perf_counter()
            solve("drivetrain", raw)
            samples.append(time.perf_counter() - t0)
        print(f"  drivetrain {mode:<17} {statistics.median(samples) * 1e6:8.1f} µs")
