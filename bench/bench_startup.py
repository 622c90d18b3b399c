"""Start-up and card switches as a user meets them, each beside its baseline measured in the same
run, in fresh processes (medians; the machine may be shared, so read the ratios). Figures only,
never asserted.

- CLI: `gearhead solve …` vs `python -c "import numpy"` (wall time of the whole process);
- first frame: the app's vs a minimal Textual app with 13 tab panes (bench/app_probe.py);
- first visit to every card (F-key, or F-key then digit: key -> the frame that shows the card),
  and the longest event-loop stall and full garbage collection from the key until 0.3 s after
  that frame, vs a key showing a tab pane of the minimal app for the first time;
- repeat visit: the same keys once every card has been seen;
- the same visits with tui/app.py's gc.freeze() switched off (--gc), to show what it is worth.

Issue 42's targets: first visit ≤ 3x the minimal app's with no stall over 16 ms, repeat ≤ 2x.

What a visit is made of (2 December 2026, scratch timers on Compositor.reflow/render_update and
Stylesheet.update_nodes, cProfile; elevator, 140x45, 2-core machine under load 5-6, so read the
shares, not the ms):
- repeat visit: the key's handling (the strips' -active classes and the focus moving from one
  sheet to the other: four style updates of one node each, 0.4-1.4 ms) 7-9 ms, then one layout
  (1.5-3 ms) and one paint of the whole screen (11-20 ms), and a second small paint (3 ms) before
  the bench sees the card. The paint is most of it: every visible widget (~45: the card's 21-23,
  the two strips' tabs, the key bar) renders its lines and the compositor cuts them at every
  widget's edge (Strip.divide, _render_chops: ~80% of a profiled layout-and-paint); of the
  widgets' own rendering (~4 ms a paint) the sheet is the largest (~1 ms). No re-solve, no row
  refresh and no style recomputation of the card run on show. A pane of the minimal app is one
  Label: its switch paints one widget.
- first visit: the card's mount is one block of the event loop (the longest stall): importing its
  calculator's core modules (elevator: 15-45 ms, importtime), composing its widgets and applying
  the stylesheet to them (66 nodes styled with the area's strip); then the first layout and paint
  (4-5 ms + 19-26 ms); then the first solve's result, a layout more when the results outgrow their
  pane (a scrollbar appears), and the chart's mount (two layouts, ~80 ms later).
What did not pay (measured, reverted): importing the calculator in a thread (asyncio.to_thread,
frames held by batch_update) made the elevator's first visit 474-526 ms instead of 147-225 ms and
left stalls of 25 ms and more (the import holds the GIL; the loop gets it back every switch
interval); showing the chart's "no data" line and the chart only when their display differs (the
chart's own mount asks for the same layout: 4 layouts in the first visit either way).

Run from a clean clone (after `python3 -m venv .venv && .venv/bin/pip install -e '.[test]'`):
    .venv/bin/python bench/bench_startup.py [--app-only] [--runs N] [--gc]
Before/after: run this file with another checkout's .venv/bin/python (its editable install imports
that checkout's app; bench/app_probe.py is taken from this checkout).
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
RUNS = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 3
# as a user runs it: with bytecode caches (pip writes them at install). A shell that sets
# PYTHONDONTWRITEBYTECODE made every start compile gearhead's modules from source, ~45 ms that the
# baselines (installed packages, compiled) never paid
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
med = statistics.median


def wall(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, env=ENV)
    return time.perf_counter() - t0


def probe(*args: str) -> dict:
    out = subprocess.run(
        [sys.executable, str(HERE / "app_probe.py"), *args], capture_output=True, text=True, env=ENV
    )
    if out.returncode:
        raise RuntimeError(out.stderr[-2000:])
    return json.loads(out.stdout.strip().splitlines()[-1])


def row(label: str, ours: float, base: float, base_label: str, unit: str = "ms") -> None:
    print(
        f"  {label:<44} {ours:7.1f} {unit}   {base_label:<28} {base:7.1f} {unit}   ratio {ours / base:5.2f}"
    )


def cli() -> None:
    gearhead = str(Path(sys.executable).with_name("gearhead"))
    base = [sys.executable, "-c", "import numpy"]
    print(f"CLI, whole process (median of {2 * RUNS + 1}, alternating with the baseline):")
    for label, cmd in (
        ("gearhead solve gear_ratio --json", ["solve", "gear_ratio", "--json"]),
        ("gearhead solve gear_ratio --set load='40 lbf'", ["solve", "gear_ratio", "--set", "load=40 lbf"]),
        ("gearhead solve beam", ["solve", "beam"]),  # the tube's finite-element J (numpy)
        ("gearhead solve beam ... '0.005 furlong'", ["solve", "beam", "--set", "length=0.005 furlong"]),
        ("gearhead solve elevator", ["solve", "elevator"]),
    ):
        wall([gearhead, *cmd]), wall(base)  # warm-up: caches written, files in the page cache
        a, b = [], []
        for _ in range(2 * RUNS + 1):
            a.append(wall([gearhead, *cmd]))
            b.append(wall(base))
        row(label, med(a) * 1e3, med(b) * 1e3, "python -c 'import numpy'")


def visits(label: str, runs: list[dict], base: tuple[float, float, float]) -> None:
    """Per card, the median over runs of (drawn, stall, full GC, CPU); the worst card last."""
    baseline, base_stall, base_cpu = base
    print(f"{label} (median of {len(runs)} fresh apps; baseline: the minimal app, median over panes)")
    print(
        f"  {'card':<18} {'key -> drawn':>12} {'x minimal':>9} {'longest stall':>14} {'full GC':>8}"
        f" {'CPU':>9} {'x minimal':>9}"
    )
    worst = (0.0, 0.0)
    ratios = []
    for calc in runs[0]:
        drawn, stall, full, cpu = (med(r[calc][i] for r in runs) for i in range(4))
        worst = max(worst[0], drawn / baseline), max(worst[1], stall)
        ratios.append(drawn / baseline)
        print(
            f"  {calc:<18} {drawn:9.1f} ms {drawn / baseline:8.2f}x {stall:11.1f} ms {full:5.1f} ms"
            f" {cpu:6.1f} ms {cpu / base_cpu:8.2f}x"
        )
    print(
        f"  minimal app        {baseline:9.1f} ms {1:8.2f}x {base_stall:11.1f} ms         "
        f" {base_cpu:6.1f} ms {1:8.2f}x"
    )
    print(f"  median card {med(ratios):.2f}x; worst card {worst[0]:.2f}x, longest stall {worst[1]:.1f} ms")


def app() -> None:
    print(f"app, headless 140x45 (fresh processes, {RUNS} runs alternating with the baseline):")
    a, b = [], []
    for _ in range(RUNS):
        a.append(probe("first-frame", "app")["first_frame"])
        b.append(probe("first-frame", "minimal")["first_frame"])
    row("first frame (start -> Ready)", med(a), med(b), "minimal app, 13 tab panes")
    kinds = ["on"] + (["off"] if "--gc" in sys.argv else [])
    runs: dict[str, list[dict]] = {kind: [] for kind in kinds}
    base: list[list[float]] = []
    for _ in range(RUNS):
        for kind in kinds:
            runs[kind].append(probe("visits", *(["--no-gc-freeze"] if kind == "off" else [])))
        base.extend(probe("minimal")["first"])
    baseline = med(x[0] for x in base), med(x[1] for x in base), med(x[3] for x in base)
    for kind in kinds:
        note = "" if kind == "on" else ", gc.freeze() switched off"
        visits(f"first visit to each card{note}", [r["first"] for r in runs[kind]], baseline)
        visits(f"repeat visit{note}", [r["repeat"] for r in runs[kind]], baseline)


def main() -> None:
    if "--app-only" not in sys.argv:
        cli()
    app()


if __name__ == "__main__":
    main()
