"""The match (issue 43): figures only, never asserted. Targets: a 150 s match with 40 events ≤ 1 s of
core; `gearhead check` of a workbook with a match ≤ 2 s.

- the example workbook's match core (core.match.mechanisms.MechanismMatch.run: 48 moves from 15
  event rows), on a fresh battery and on a tired one (0.025 ohm, 70 %), in one warm process: CPU
  and wall (median), its pieces of integration, moves and brownouts; and two brownout-bound ones:
  the README's 0.05 ohm (7496 brownouts; its `gearhead check` target ≤ 2 s) and the tired battery
  with a 60 A drive supply limit (7147 brownouts, the lift's stiff pieces; target ≤ ~3 s CPU, where
  it took 28 s), the latter once (`--runs` does not repeat it);
- the commands as a user runs them, each in a fresh process: `gearhead match`, fresh and tired,
  `gearhead check` and `gearhead check --worst-case` (wall and the child's CPU, median);
- every figure also as a ratio to `python -c "import numpy"` timed in the same run (the machine's
  speed and load cancel out of the ratio).
- `--stall`: also `gearhead match` of the 60 A case in a fresh process, once.

    .venv/bin/python bench/bench_match.py [--runs N] [--stall]
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

RUNS = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 3
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
GEARHEAD = str(Path(sys.executable).with_name("gearhead"))
BOOK = "builtin:robot_2027"
TIRED = ["--set", "battery_resistance=0.025 ohm", "--set", "battery_charge=70 %"]
STALL = [*TIRED, "--set", "drive_supply_limit=60 A"]
WEAK = ["--set", "battery_resistance=0.05 ohm"]


def sets_of(args: list[str]) -> dict[str, str]:
    return dict(s.split("=", 1) for s in args[1::2])


def process(args: list[str]) -> tuple[float, float]:
    """(wall, CPU) seconds of one fresh process running `args` (its exit code is not checked: a
    failing requirement exits 1)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(args, capture_output=True, env=ENV)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def median_process(args: list[str], runs: int = RUNS) -> tuple[float, float]:
    got = [process(args) for _ in range(runs)]
    return statistics.median(g[0] for g in got), statistics.median(g[1] for g in got)


def core(sets: dict[str, str], runs: int = RUNS) -> dict:
    """The match core alone (MechanismMatch.run) of the example at `sets`, a fresh workbook each run
    (the workbook caches its match)."""
    from gearhead.core import workbook
    from gearhead.core.match import mechanisms

    timed: list[tuple[float, float]] = []
    last = {}
    original = mechanisms.MechanismMatch.run

    def run(self):
        c0, t0 = time.process_time(), time.perf_counter()
        out = original(self)
        timed.append((time.process_time() - c0, time.perf_counter() - t0))
        last["bus"], last["moves"] = out, len(self.moves)
        return out

    mechanisms.MechanismMatch.run = run
    try:
        for _ in range(runs):
            workbook.solve(workbook.load(BOOK, sets))
    finally:
        mechanisms.MechanismMatch.run = original
    bus = last["bus"]
    return {
        "cpu": statistics.median(c for c, _ in timed),
        "wall": statistics.median(w for _, w in timed),
        "pieces": bus.pieces,
        "moves": last["moves"],
        "brownouts": len(bus.brownouts),
    }


def main() -> None:
    numpy = median_process([sys.executable, "-c", "import numpy"], max(RUNS, 5))
    print(f'baseline: python -c "import numpy"  {numpy[0] * 1e3:6.0f} ms wall, {numpy[1] * 1e3:6.0f} ms CPU')
    print(f"the example's match core, warm process (median of {RUNS}; target ≤ 1 s):")
    for name, sets, runs in (
        ("fresh", {}, RUNS),
        ("tired", sets_of(TIRED), RUNS),
        ("0.05 ohm", sets_of(WEAK), RUNS),
        ("60 A", sets_of(STALL), 1),
    ):
        c = core(sets, runs)
        print(
            f"  {name:<8} {c['cpu']:6.3f} s CPU ({c['cpu'] / numpy[1]:5.1f}x numpy), {c['wall']:6.3f} s wall; "
            f"{c['moves']} moves, {c['pieces']} pieces, {c['brownouts']} brownouts"
        )
    print(f"commands, fresh process each (median of {RUNS}; check target ≤ 2 s):")
    for label, args in (
        ("gearhead match", ["match", BOOK]),
        ("gearhead match, tired", ["match", BOOK, *TIRED]),
        ("gearhead check", ["check", BOOK]),
        ("gearhead check, tired", ["check", BOOK, *TIRED]),
        ("gearhead check, 0.05 ohm", ["check", BOOK, *WEAK]),
        ("gearhead check --worst-case", ["check", BOOK, "--worst-case"]),
    ):
        wall, cpu = median_process([GEARHEAD, *args])
        print(
            f"  {label:<28} {wall:6.2f} s wall ({wall / numpy[0]:5.1f}x numpy), "
            f"{cpu:6.2f} s CPU ({cpu / numpy[1]:5.1f}x)"
        )
    if "--stall" in sys.argv:
        wall, cpu = process([GEARHEAD, "match", BOOK, *STALL])
        print(f"  gearhead match, tired, 60 A drive supply (one run): {wall:6.1f} s wall, {cpu:6.1f} s CPU")


if __name__ == "__main__":
    main()
