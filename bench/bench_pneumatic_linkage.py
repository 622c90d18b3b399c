"""Pneumatic linkage figures: warm solve time per mode, the raw geometry calls, and the accuracy of
the closed forms against mpmath near dead centre (printed, never asserted).

Run from the repository root:  .venv/bin/python bench/bench_pneumatic_linkage.py
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)


def main() -> None:
    import mpmath as mp

    from gearhead.core.calculators import pneumatic_linkage as pl
    from gearhead.core.model import solve

    print(
        f"  solve forward (defaults, with the 61-point torque curve) {median_seconds(lambda: solve('pneumatic_linkage', {}), 300) * 1e6:8.1f} µs"
    )
    print(
        f"  solve reverse (defaults)                                {median_seconds(lambda: solve('pneumatic_linkage', {'mode': 'reverse'}), 300) * 1e6:8.1f} µs"
    )
    print(
        f"  forward() geometry alone                                {median_seconds(lambda: pl.forward(6.0, -14.0, 5.0, 0.0, 11.0, 6.0), 300) * 1e6:8.2f} µs"
    )
    print(
        f"  reverse() geometry alone                                {median_seconds(lambda: pl.reverse(-0.8, 0.8, 5.0, 0.0, 11.0, 6.0), 300) * 1e6:8.2f} µs"
    )

    mp.mp.dps = 50
    print("  γ error near dead centre, ℓ = d + r − δ (d = 5, r = 2): closed form vs plain acos, rad")
    for k in (10, 20, 30, 40, 48):
        delta = 2.0**-k
        ell = 7 - delta
        exact = mp.acos((29 - mp.mpf(ell) ** 2) / 20)
        ours = abs(mp.mpf(pl.pivot_angle(2.0, 5.0, ell)) - exact)
        naive = abs(mp.mpf(math.acos(max(-1.0, (29 - ell * ell) / 20))) - exact)
        print(f"    δ = 2^-{k:<3} ours {float(ours):9.2e}   acos {float(naive):9.2e}")


if __name__ == "__main__":
    main()
