"""Beam figures (printed, never asserted): solve times per section, and the cost and accuracy of
the rectangular-tube torsion constant (finite-element bounds, core/beams.py) and their gap."""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)


def main() -> None:
    from gearhead.core import beams
    from gearhead.core.model import solve

    print("  warm solve per section (median of 50; tube torsion cached by its side/wall ratios):")
    for section in beams.SECTIONS:
        print(
            f"    {section:<18} {median_seconds(lambda: solve('beam', {'section': section})) * 1e6:9.1f} µs"
        )
    print("  rectangular-tube torsion constant, uncached (stress-function and warping bounds):")
    for W, H in [
        (32.0, 16.0),
        (16.0, 16.0),
        (4.0, 4.0),
        (2.5, 2.2),
        (1000.0, 1000.0),
        (3000.0, 4.0),
        (1e5, 4.0),
    ]:
        beams._tube_torsion_bounds.cache_clear()
        t0 = time.perf_counter()
        lower, upper = beams._tube_torsion_bounds(W, H)
        elapsed = time.perf_counter() - t0
        J = (lower + upper) / 2
        bredt = 2 * (W - 1) ** 2 * (H - 1) ** 2 / (W + H - 2)
        print(
            f"    {W:g} x {H:g} (wall 1): {elapsed * 1e3:7.1f} ms, "
            f"bounds within ±{(upper - lower) / (upper + lower):.1e}, Bredt error {bredt / J - 1:+.2%}"
        )


if __name__ == "__main__":
    main()
