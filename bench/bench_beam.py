"""Beam figures (printed, never asserted): `gearhead solve beam` as a whole process beside
`python -c 'import numpy'` (fresh processes, alternating; min/median/max and the ratio pair by
pair), solve times per section, and the cost and accuracy of the rectangular-tube torsion constant
(finite-element bounds, core/beams.py) and their gap.

Run:  .venv/bin/python bench/bench_beam.py [--runs N]
The processes run with bytecode caches, as an installed package does (a shell that sets
PYTHONDONTWRITEBYTECODE would make every start compile gearhead's modules, which the numpy
baseline never pays)."""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)

RUNS = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 9
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def _wall(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, env=ENV)
    return time.perf_counter() - t0


def cli_vs_numpy() -> None:
    """The default beam (a 2x1x1/16 in rectangular tube: its J is the finite-element solve)."""
    gearhead = str(Path(sys.executable).with_name("gearhead"))
    ours, base = [gearhead, "solve", "beam"], [sys.executable, "-c", "import numpy"]
    _wall(ours), _wall(base)  # warm-up: bytecode caches written, files in the page cache
    a, b = [], []
    for _ in range(RUNS):  # alternating, so load on the machine hits both alike
        a.append(_wall(ours))
        b.append(_wall(base))
    ratios = [x / y for x, y in zip(a, b)]
    print(f"  whole process, wall (min / median / max of {RUNS}, alternating):")
    for label, xs in (("gearhead solve beam", a), ("python -c 'import numpy'", b)):
        print(
            f"    {label:<26} {min(xs) * 1e3:6.0f} {statistics.median(xs) * 1e3:6.0f} {max(xs) * 1e3:6.0f} ms"
        )
    print(
        f"    {'ratio, pair by pair':<26} {min(ratios):6.2f} {statistics.median(ratios):6.2f} {max(ratios):6.2f}"
    )


def main() -> None:
    cli_vs_numpy()
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
