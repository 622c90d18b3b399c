"""What core costs in a card's first visit, on the UI thread (building the card: its calculator's
import) and in the first solve that follows (the solve worker: the ratio finder's catalogue and
stage classes), beside another checkout's figures measured in the same run, alternating, in fresh
processes. Figures only, never asserted (medians; CPU is the thread's own time, which load on a
shared machine changes least).

    .venv/bin/python bench/bench_first_solve.py [--runs N] [--against OTHER/.venv/bin/python]
        [--visits | --ui-thread]

- import: `registry.get(id)` once the app's modules and the first card's calculator are loaded (as
  when the app builds that card), wall and thread CPU, and how many modules it loads;
- ratio_finder's first solve (`model.solve`, numpy already loaded as by the cards before it): the
  catalogue's read, its stage classes, the whole solve; and the full collections (generation 2)
  that fell inside it, after `gc.freeze()` as the app does once a card is built;
- --visits: the first visit to every card (bench/app_probe.py visits: key -> the frame showing
  the card, the longest event-loop stall and full collection in the 0.3 s after, CPU), each
  checkout's app in turn (which goes first alternates) and the minimal Textual app's pane after
  them, per run (as bench/bench_startup.py, with the two apps interleaved);
- --ui-thread: the same first visits, the UI thread's own CPU from the key to the frame (what the
  card's build and first paint cost there, the solve worker's time left out).
"""

from __future__ import annotations

import gc
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

RUNS = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 5
OTHER = sys.argv[sys.argv.index("--against") + 1] if "--against" in sys.argv else None
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}  # as bench_startup


def _timed(f, *args):
    t, c = time.perf_counter(), time.thread_time()
    out = f(*args)
    return out, (time.perf_counter() - t) * 1e3, (time.thread_time() - c) * 1e3


def probe_import(calc_id: str) -> dict:
    import gearhead.tui.app  # noqa: F401  what the app has loaded before any card is built
    import gearhead.tui.components.calculator_tab  # noqa: F401
    from gearhead.core.registry import ORDER, get

    get(ORDER[0])  # the first card
    before = len(sys.modules)
    _, wall, cpu = _timed(get, calc_id)
    return {"wall": wall, "cpu": cpu, "modules": len(sys.modules) - before}


def probe_ratio_finder() -> dict:
    import numpy  # noqa: F401  loaded by the cards visited before

    import gearhead.tui.app  # noqa: F401
    import gearhead.tui.components.calculator_tab  # noqa: F401
    from gearhead.core import model, parts
    from gearhead.core.parts import finder
    from gearhead.core.registry import get

    calc = get("ratio_finder")
    gc.collect()
    gc.freeze()
    full: list[float] = []
    started: list[float] = []

    def on_gc(phase: str, info: dict) -> None:
        if phase == "start":
            started[:] = [time.perf_counter()]
        elif info["generation"] == 2:
            full.append((time.perf_counter() - started[0]) * 1e3)

    gc.callbacks.append(on_gc)
    counts = [g["collections"] for g in gc.get_stats()]
    _, solve_wall, solve_cpu = _timed(model.solve, "ratio_finder")
    gc.callbacks.remove(on_gc)
    counts = [g["collections"] - n for g, n in zip(gc.get_stats(), counts)]
    out = {"solve_wall": solve_wall, "solve_cpu": solve_cpu, "full_gcs": len(full), "full_gc_ms": sum(full)}
    out["young_gcs"], out["middle_gcs"] = counts[0], counts[1]
    gc.collect()
    out["tracked_kept"] = len(gc.get_objects())  # what the solve left for later collections to walk
    # the phases again, each from cold (caches cleared; modules already loaded)
    parts.catalogue.cache_clear()
    _, out["catalogue_wall"], out["catalogue_cpu"] = _timed(parts.catalogue)
    from gearhead.core.calculators.ratio_finder import query_from

    q = query_from({f.name: f.parse(f.default) for f in calc.fields})
    _, out["classes_wall"], out["classes_cpu"] = _timed(finder.stage_classes, q)
    return out


def probe_ui_thread() -> dict:
    """Every card's first visit (bench/app_probe.py's plan and keys): the UI thread's own CPU from
    the key to the frame showing the card (time.thread_time: the solve worker's and other
    processes' time left out, so load changes it least), and the wall time."""
    import asyncio

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from app_probe import SIZE, _until, key_event, visit_plan

    from gearhead.tui.app import GearheadApp

    async def visits() -> dict:
        app = GearheadApp(blink=False, hide_timings=True)
        out = {}
        async with app.run_test(size=SIZE) as pilot:
            await _until(lambda: app.card_ready(app.current_calculator))
            await pilot.pause(0.5)
            for calc, before, keys in visit_plan(True):
                if before:
                    await pilot.press(*before)
                    await _until(lambda: app.card_ready(app.current_calculator))
                    await pilot.pause(0.2)
                shown = lambda calc=calc: (  # noqa: E731
                    app.current_calculator == calc
                    and app.card_ready(calc)
                    and app.current_tab.sheet.region.height > 0
                )
                c0, t0 = time.thread_time(), time.perf_counter()
                for key in keys:
                    app.post_message(key_event(key))
                await _until(shown)
                out[calc] = [(time.thread_time() - c0) * 1e3, (time.perf_counter() - t0) * 1e3]
                tab = app.current_tab
                await _until(lambda: not tab.busy)
                await pilot.pause(0.1)
        return out

    return asyncio.run(visits())


def ui_thread(pythons: dict[str, str]) -> None:
    med = statistics.median
    runs: dict[str, list[dict]] = {k: [] for k in pythons}
    for n in range(RUNS):
        order = list(pythons.items())
        for k, py in order if n % 2 == 0 else order[::-1]:
            runs[k].append(run(py, "--probe", "ui_thread"))
    print(f"first visit, the UI thread's CPU from the key to the frame (median of {RUNS} fresh apps)")
    print(f"  {'card':<18}" + "".join(f" {k + ': UI CPU':>15} {'wall':>9}" for k in pythons))
    total = {k: 0.0 for k in pythons}
    for calc in runs[next(iter(pythons))][0]:
        line = f"  {calc:<18}"
        for k in pythons:
            cpu, wall = (med(r[calc][i] for r in runs[k]) for i in range(2))
            total[k] += cpu
            line += f" {cpu:12.1f} ms {wall:6.1f} ms"
        print(line)
    print("  sum of the cards' medians: " + ", ".join(f"{k} {v:.0f} ms" for k, v in total.items()))


def run(python: str, *args: str, script: str = __file__) -> dict:
    out = subprocess.run([python, script, *args], capture_output=True, text=True, env=ENV)
    if out.returncode:
        raise RuntimeError(out.stderr[-2000:])
    return json.loads(out.stdout.strip().splitlines()[-1])


def visits(pythons: dict[str, str]) -> None:
    probe = str(Path(__file__).with_name("app_probe.py"))
    med = statistics.median
    runs: dict[str, list[dict]] = {k: [] for k in pythons}
    minimal: list[list[float]] = []
    for n in range(RUNS):
        order = list(pythons.items())
        for k, py in order if n % 2 == 0 else order[::-1]:  # neither always first
            runs[k].append(run(py, "visits", script=probe)["first"])
        minimal.extend(run(sys.executable, "minimal", script=probe)["first"])
    base = [med(x[i] for x in minimal) for i in range(4)]
    print(
        f"first visit to each card (median of {RUNS} fresh apps; minimal app's pane {base[0]:.1f} ms, CPU {base[3]:.1f} ms)"
    )
    print(
        f"  {'card':<18}"
        + "".join(f" {k + ': drawn':>14} {'x min':>6} {'stall':>6} {'GC':>5} {'CPU':>6}" for k in pythons)
    )
    ratios: dict[str, list[float]] = {k: [] for k in pythons}
    stalls: dict[str, list[float]] = {k: [] for k in pythons}
    for calc in runs[next(iter(pythons))][0]:
        line = f"  {calc:<18}"
        for k in pythons:
            drawn, stall, full, cpu = (med(r[calc][i] for r in runs[k]) for i in range(4))
            ratios[k].append(drawn / base[0])
            stalls[k].append(stall)
            line += f" {drawn:11.1f} ms {drawn / base[0]:5.2f}x {stall:6.1f} {full:5.1f} {cpu:6.1f}"
        print(line)
    for k in pythons:
        print(
            f"  {k}: median card {med(ratios[k]):.2f}x, worst {max(ratios[k]):.2f}x; median stall"
            f" {med(stalls[k]):.1f} ms, longest {max(stalls[k]):.1f} ms; all cards, sum of each one's"
            f" medians: drawn {sum(ratios[k]) * base[0]:.0f} ms, stall {sum(stalls[k]):.0f} ms"
        )


def main() -> None:
    if "--probe" in sys.argv:
        what = sys.argv[sys.argv.index("--probe") + 1]
        if what == "ui_thread":
            result = probe_ui_thread()
        else:
            result = probe_ratio_finder() if what == "ratio_finder_solve" else probe_import(what)
        print(json.dumps(result))
        return
    from gearhead.core.registry import ORDER

    pythons = {"this": sys.executable} | ({"other": OTHER} if OTHER else {})
    if "--visits" in sys.argv:
        visits(pythons)
        return
    if "--ui-thread" in sys.argv:
        ui_thread(pythons)
        return
    med = statistics.median
    print(f"import of each calculator when its card is built (median of {RUNS} fresh processes)")
    print(
        f"  {'calculator':<18}" + "".join(f" {k + ' wall':>11} {k + ' CPU':>10} {'mods':>4}" for k in pythons)
    )
    for cid in ORDER[1:]:
        runs = {k: [] for k in pythons}
        for _ in range(RUNS):
            for k, py in pythons.items():  # alternating
                runs[k].append(run(py, "--probe", cid))
        line = f"  {cid:<18}"
        for k in pythons:
            r = runs[k]
            line += f" {med(x['wall'] for x in r):8.2f} ms {med(x['cpu'] for x in r):7.2f} ms {r[0]['modules']:4d}"
        print(line)
    print(f"ratio_finder's first solve (median of {RUNS} fresh processes)")
    runs = {k: [] for k in pythons}
    for _ in range(RUNS):
        for k, py in pythons.items():
            runs[k].append(run(py, "--probe", "ratio_finder_solve"))
    for key in runs["this"][0]:
        print(f"  {key:<16}" + "".join(f" {k}: {med(x[key] for x in runs[k]):8.2f}" for k in pythons))


if __name__ == "__main__":
    main()
