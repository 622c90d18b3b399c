"""Beam figures (printed, never asserted): `gearhead solve beam` as a whole process beside
`python -c 'import numpy'` (fresh processes, alternating; min/median/max and the ratio pair by
pair), with a tube off the shipped table (its J solved: numpy imported) and `gearhead solve
gear_ratio --json` (no numpy) beside it; solve times per section; the cost and accuracy of the
rectangular-tube torsion constant (finite-element bounds, core/beams.py) and their gap, and the
cost of reading a common tube's bounds from TUBE_TABLE instead.

Run:  .venv/bin/python bench/bench_beam.py [--runs N] [--vs OTHER/.venv/bin/gearhead]
--vs runs another checkout's `gearhead` in the same alternation (before/after in one run).
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
OTHER = sys.argv[sys.argv.index("--vs") + 1] if "--vs" in sys.argv else None
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def _wall(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, env=ENV)
    return time.perf_counter() - t0


def cli_vs_numpy() -> None:
    """The default beam (a 2x1x1/16 in rectangular tube: its J bounds read from TUBE_TABLE), a tube
    off the table (2x1x0.09 in: the finite-element solve, numpy imported) and a calculator that
    never imports numpy, each beside `import numpy` in one alternation."""
    gearhead = str(Path(sys.executable).with_name("gearhead"))
    numpy = [sys.executable, "-c", "import numpy"]
    cases = [
        ("solve beam", ["solve", "beam"]),
        ("solve beam, 0.09 in wall", ["solve", "beam", "--set", "wall=0.09 in"]),
        ("solve gear_ratio --json", ["solve", "gear_ratio", "--json"]),
    ]
    cmds = {"import numpy": numpy}
    for label, args in cases:
        cmds[label] = [gearhead, *args]
        if OTHER:
            cmds[f"{label} (--vs)"] = [OTHER, *args]
    for cmd in cmds.values():
        _wall(cmd)  # warm-up: bytecode caches written, files in the page cache
    times: dict[str, list[float]] = {label: [] for label in cmds}
    for _ in range(RUNS):  # alternating, so load on the machine hits every command alike
        for label, cmd in cmds.items():
            times[label].append(_wall(cmd))
    base = times["import numpy"]
    print(f"  whole process, wall (min / median / max of {RUNS}, alternating); ratio to import numpy,")
    print("  pair by pair (min / median / max):")
    for label, xs in times.items():
        ratios = [x / y for x, y in zip(xs, base)]
        print(
            f"    {label:<36} {min(xs) * 1e3:5.0f} {statistics.median(xs) * 1e3:5.0f} {max(xs) * 1e3:5.0f} ms"
            f"   {min(ratios):5.2f} {statistics.median(ratios):5.2f} {max(ratios):5.2f}"
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
    row = beams.TUBE_TABLE[0]
    print(
        f"  a common tube's bounds read from TUBE_TABLE: "
        f"{median_seconds(lambda: beams._tube_bounds(row[0], row[1])) * 1e6:.1f} µs"
    )
    print(
        "  rectangular-tube torsion constant, solved uncached (median of 3; stress-function and warping bounds):"
    )
    for W, H in [
        (32.0, 16.0),
        (16.0, 16.0),
        (4.0, 4.0),
        (2.5, 2.2),
        (1000.0, 1000.0),
        (3000.0, 4.0),
        (1e5, 4.0),
    ]:
        lower, upper = beams._tube_torsion_bounds.__wrapped__(W, H)
        elapsed = median_seconds(lambda: beams._tube_torsion_bounds.__wrapped__(W, H), runs=3)
        J = (lower + upper) / 2
        bredt = 2 * (W - 1) ** 2 * (H - 1) ** 2 / (W + H - 2)
        print(
            f"    {W:g} x {H:g} (wall 1): {elapsed * 1e3:7.1f} ms, "
            f"bounds within ±{(upper - lower) / (upper + lower):.1e}, Bredt error {bredt / J - 1:+.2%}"
        )


if __name__ == "__main__":
    main()
