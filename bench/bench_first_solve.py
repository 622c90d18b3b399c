"""What core costs in a card's first visit, on the UI thread (building the card: its calculator's
import) and in the first solve that follows (the solve worker: the ratio finder's catalogue and
stage classes), beside another checkout's figures measured in the same run, alternating, in fresh
processes. Figures only, never asserted (medians; CPU is the thread's own time, which load on a
shared machine changes least).

    .venv/bin/python bench/bench_first_solve.py [--runs N] [--against OTHER/.venv/bin/python]

- import: `registry.get(id)` once the app's modules and the first card's calculator are loaded (as
  when the app builds that card), wall and thread CPU, and how many modules it loads;
- ratio_finder's first solve (`model.solve`, numpy already loaded as by the cards before it): the
  catalogue's read, its stage classes, the whole solve; and the full collections (generation 2)
  that fell inside it, after `gc.freeze()` as the app does once a card is built.
"""

from __future__ import annotations

import gc
import json
import os
import statistics
import subprocess
import sys
import time

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


def run(python: str, *args: str) -> dict:
    out = subprocess.run([python, __file__, *args], capture_output=True, text=True, env=ENV)
    if out.returncode:
        raise RuntimeError(out.stderr[-2000:])
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    if "--probe" in sys.argv:
        what = sys.argv[sys.argv.index("--probe") + 1]
        result = probe_ratio_finder() if what == "ratio_finder_solve" else probe_import(what)
        print(json.dumps(result))
        return
    from gearhead.core.registry import ORDER

    pythons = {"this": sys.executable} | ({"other": OTHER} if OTHER else {})
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
