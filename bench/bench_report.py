"""`gearhead report` (issue 45): figures only, never asserted.

- the example workbook's report as a user runs it: `gearhead report builtin:robot_2027` in a fresh
  process (wall and CPU time, median), each format's size, beside `gearhead check` of the same
  workbook run in turns with it (its solve, the match included, is most of the report's time): the
  ratio of their wall times and the report's CPU over check's; and the same steps in one process
  (solve and document, matplotlib's import, charts, HTML) to show where the time goes. Target: ≤ 3 s.
- the app's first frame (bench/app_probe.py first-frame app, median) and whether matplotlib is among
  the modules loaded once the first card is drawn (it must not be: only the report imports it).

    .venv/bin/python bench/bench_report.py [--runs N]
"""

from __future__ import annotations

import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
RUNS = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 3
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
GEARHEAD = str(Path(sys.executable).with_name("gearhead"))

FIRST_FRAME_MODULES = """
import asyncio, json, sys
sys.path.insert(0, {bench!r})
import app_probe
asyncio.run(app_probe.first_frame("app", 0.0))
print(json.dumps(sorted(m for m in sys.modules if m.split(".")[0] == "matplotlib")))
"""


def timed(argv: list[str], check: bool = False) -> tuple[float, float]:
    """(wall, CPU) seconds of one fresh process: its CPU (user + system) is what the machine's other
    work does not change, where the wall time does (2 cores shared)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(argv, check=check, capture_output=True, env=ENV)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def cold(fmt: str, folder: Path) -> tuple[float, int, float]:
    out = folder / f"robot.{fmt}"
    wall, cpu = timed([GEARHEAD, "report", "builtin:robot_2027", "--out", str(out), "--overwrite"], True)
    size = out.stat().st_size + sum(p.stat().st_size for p in folder.glob("robot_charts/*.svg"))
    return wall, size, cpu


def main() -> None:
    print(f"gearhead report builtin:robot_2027 (median of {RUNS} fresh processes)")
    checks, htmls = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(RUNS):  # check (the baseline: the same workbook solved, nothing drawn) and the
            # HTML report in turns, so both see the same load
            checks.append(timed([GEARHEAD, "check", "builtin:robot_2027"]))
            htmls.append(cold("html", Path(tmp)))
        check_wall, check_cpu = (statistics.median(c[k] for c in checks) for k in (0, 1))
        print(
            f"  check {check_wall:6.2f} s   CPU {check_cpu:5.2f} s   "
            "(baseline: `gearhead check` of the same workbook)"
        )
        ratio = statistics.median(h[0] / c[0] for h, c in zip(htmls, checks))
        for fmt in ("html", "md", "pdf"):
            runs = (
                htmls if fmt == "html" else [cold(fmt, Path(tmp)) for _ in range(RUNS if fmt == "md" else 1)]
            )
            wall, cpu = (statistics.median(r[k] for r in runs) for k in (0, 2))
            note = (
                f"  (target ≤ 3 s; {ratio:.2f}x check's wall, paired; CPU {cpu - check_cpu:+.2f} s over check)"
                if fmt == "html"
                else ("  (one run: Chromium prints)" if fmt == "pdf" else "")
            )
            print(f"  {fmt:<5} {wall:6.2f} s   CPU {cpu:5.2f} s   {runs[-1][1] / 1000:8.1f} kB{note}")

    from gearhead.core import workbook
    from gearhead.core.report import charts, document, html

    t0 = time.perf_counter()
    report = document.from_workbook(workbook.load("builtin:robot_2027"))
    t1 = time.perf_counter()
    import matplotlib.figure  # noqa: F401  (its import timed alone)
    from matplotlib.backends import backend_svg  # noqa: F401

    t2 = time.perf_counter()
    svgs = [charts.svg(c) for c in report.charts()]
    t3 = time.perf_counter()
    html.write(report)
    t4 = time.perf_counter()
    print("  in one process (first call):")
    print(f"    solve and document   {(t1 - t0) * 1e3:7.0f} ms")
    print(f"    import matplotlib    {(t2 - t1) * 1e3:7.0f} ms")
    print(f"    {len(svgs)} charts            {(t3 - t2) * 1e3:7.0f} ms")
    print(f"    HTML (charts again)  {(t4 - t3) * 1e3:7.0f} ms")

    frames = []
    for _ in range(RUNS):
        out = subprocess.run(
            [sys.executable, str(HERE / "app_probe.py"), "first-frame", "app"],
            capture_output=True,
            text=True,
            env=ENV,
            check=True,
        )
        frames.append(json.loads(out.stdout.strip().splitlines()[-1])["first_frame"])
    print(f"the app's first frame: {statistics.median(frames):.0f} ms (median of {RUNS})")
    out = subprocess.run(
        [sys.executable, "-c", FIRST_FRAME_MODULES.format(bench=str(HERE))],
        capture_output=True,
        text=True,
        env=ENV,
        check=True,
    )
    loaded = json.loads(out.stdout.strip().splitlines()[-1])
    print(f"matplotlib modules loaded by the app's start: {len(loaded)} {loaded[:3]}")


if __name__ == "__main__":
    main()
