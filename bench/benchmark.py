"""Speed figures for Gearhead (printed, never asserted: timing belongs here, not in tests).

Run:  .venv/bin/python bench/benchmark.py
- first frame: wall time from process start to the app's first screen being ready (headless);
- one `solve` per calculator: median of repeated calls after a warm-up (pint loaded);
- cold solve: the first call in a fresh process (pays for pint's registry).
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

FIRST_FRAME = r"""
import time, asyncio
t0 = time.perf_counter()
from gearhead.tui.app import GearheadApp
class Timed(GearheadApp):
    def on_ready(self):  # Textual sends Ready once the first frame is on screen
        self.first_frame = time.perf_counter() - t0
async def main():
    app = Timed(blink=False)
    async with app.run_test(size=(140, 45)) as pilot:
        await pilot.pause()
    print(app.first_frame)
asyncio.run(main())
"""

COLD_SOLVE = r"""
import time
t0 = time.perf_counter()
from gearhead.core.model import solve
solve("gear_ratio", {})
print(time.perf_counter() - t0)
"""


def in_fresh_process(code: str, runs: int = 5) -> float:
    times = []
    for _ in range(runs):
        out = subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True
        )
        times.append(float(out.stdout.strip().splitlines()[-1]))
    return statistics.median(times)


def main() -> None:
    from gearhead.core.model import solve
    from gearhead.core.registry import calculators

    print(
        f"first frame (headless, median of 5 fresh processes): {in_fresh_process(FIRST_FRAME) * 1e3:8.1f} ms"
    )
    print(
        f"cold first solve incl. pint registry (median of 5):  {in_fresh_process(COLD_SOLVE) * 1e3:8.1f} ms"
    )
    print("warm solve, median of 200 calls:")
    for cid in calculators():
        solve(cid, {})
        samples = []
        for _ in range(200):
            t0 = time.perf_counter()
            solve(cid, {})
            samples.append(time.perf_counter() - t0)
        print(f"  {cid:<18} {statistics.median(samples) * 1e6:9.1f} µs")


def simulations() -> None:
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import calculators
    from gearhead.core.sim.scene import LEVELS, ladder

    print(
        "simulations at the default accuracy (median of 50; the scene alone, then the full solve "
        "including the 100x-tighter error estimate):"
    )
    from gearhead.core.model import solve

    for cid, calc in calculators().items():
        if calc.simulate is None:
            continue
        values, _ = parse_inputs(calc, {})
        calc.simulate(values, LEVELS["default"])
        one, full = [], []
        for _ in range(50):
            t0 = time.perf_counter()
            calc.simulate(values, LEVELS["default"])
            one.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            solve(cid, {})
            full.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        ladder(calc.simulate, values)
        view = time.perf_counter() - t0
        print(
            f"  {cid:<18} scene {statistics.median(one) * 1e3:7.3f} ms   solve {statistics.median(full) * 1e3:7.3f} ms"
            f"   accuracy view {view * 1e3:8.1f} ms"
        )


def extras() -> None:
    """Figures of one calculator beyond the generic ones: each bench/bench_<calc>.py has main()."""
    import importlib.util

    for path in sorted(Path(__file__).parent.glob("bench_*.py")):
        spec = importlib.util.spec_from_file_location(path.stem, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        print(f"{path.stem.removeprefix('bench_')}:")
        module.main()


if __name__ == "__main__":
    main()
    simulations()
    extras()
