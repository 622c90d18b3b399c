"""Drivetrain figures (printed, never asserted): warm solve time per mode (incl. the plot series)."""

from __future__ import annotations

from timing import median_seconds


def main() -> None:
    from gearhead.core.model import solve

    for mode in ("forward", "reverse", "shifting"):
        raw = {"mode": mode}
        seconds = median_seconds(lambda: solve("drivetrain", raw), 300)
        print(f"  drivetrain {mode:<17} {seconds * 1e6:8.1f} µs")
