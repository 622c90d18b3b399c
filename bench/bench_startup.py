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

What a repeat visit runs (2 December 2026, after the tab strips below; scratch timers on
Compositor.reflow/render_update/_render_chops and Stylesheet.update_nodes, thread CPU time per
widget, all 18 cards, 140x45, 2-core machine shared with other sessions, load 2-6):
- the key's handling (show_calculator: the strips' active tab, two cards' display, the focus to
  the shown sheet) 2-5 ms; two style updates of one node each (the sheets' blur and focus) 1-4 ms
  each; one layout (reflow 1-3 ms); then, in the same tick of the screen's update timer, a paint
  of the card's region (13-50 ms: most of the visit) and a repaint of the whole screen (2-4 ms,
  every widget's lines cached: moving the focus refreshes the Screen, whose `focused` is a
  repainting Reactive, textual/screen.py:229, set in set_focus, :1133),
  before the bench sees the card; a small paint (the sheet, a scrollbar) follows. No re-solve, no
  chart re-render, no second layout, no full collection (gc.freeze).
- that paint, per widget (render + the compositor's cut at every widget edge of each line): the
  Screen's own 45 lines, refreshed by the focus move and cut again (~6 ms a paint), the sheet
  drawn whole (Textual's Widget._on_focus refreshes a widget that takes focus, widget.py:4765:
  ~3 ms), a visible scrollbar (~2.5 ms on the cards with one), the key bar (~1 ms); the card's
  other widgets come from their caches. A pane of the minimal app is one Label.
- the longest stall is key -> drawn less ~1 ms: the handling, style updates, layout and paint run
  in consecutive loop iterations, and asyncio runs a task woken meanwhile (a key read, the stall
  watcher) only after the handles already queued, the paint among them.
What paid (measured, kept): the two Tabs strips as one Line-API widget each
(tui/components/tab_strip.py, drawn cell for cell as Tabs: tests/test_tab_strip.py). Tabs is a
widget per tab in three containers with an Underline: visible widgets 31 -> 13 (gear_ratio), 43 ->
24 (elevator); the first paint's CPU over the 18 repeat visits (render + cut) 593 and 640 ms ->
515 and 541 ms (two runs each); and Tabs' underline animation, 0.3 s of repaints after every
switch (~19 frames of 1.5-5 ms), is gone. Repeat visits, this file's probes, 3 fresh apps each,
main's checkout (fe7a920) and this one interleaved with the minimal app (28.2 ms, CPU 16.0 ms), load
5-5.6: median card 4.71x -> 3.22x, worst 9.67x -> 5.51x, longest stall 271 -> 154 ms; CPU median
54.5 -> 36.8 ms (3.40x -> 2.30x the minimal app's), worst 104.0 -> 76.4 ms. Above the 2x target
still; first visits unchanged within the noise (6.80x -> 7.04x median).
What is left, not changed: the sheet's whole redraw and the Screen's on a focus move are
Textual's (above), and the shown card's sheet must take the keys.
What a first visit runs (an earlier session's timers, same method):
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

First visits, 2 December 2026, afternoon (scratch timers: UI-thread CPU, time.thread_time, per
event-loop callback; 18 cards, sums of per-card medians over 5 fresh apps alternating with the
commit before; machine under load 4-6, so read the ratios):
- the longest block of a first visit is its first full paint, the same block as a repeat visit's
  (median longest block, wall/CPU: first 30/24 ms, repeat 28/27 ms), so the stall target falls
  with the repeat visit's paint. In that paint every visible widget renders its whole region, the
  containers under their children too: the two bordered panes 1.8 and 1.3 ms, the Screen 1.0, the
  card 0.8, the sheet 1.7, the results 0.9 (of 11.4 ms of render_lines, 20 ms of layout + paint).
- before the first frame, beyond that paint, the CPU is Textual's mounting of each widget
  (compose, register, style: about 2 ms a widget here, hidden ones too: the A/B below) and styles (10 ms a visit,
  4 of them the sheet styled three times, at mount, focus and the old sheet's blur, 8 component
  classes each); the calculator's import is 0.5-17 ms (elevator 9-17: dataclass creation in
  sim/motion, sim/profiled, gains_numbers), importing modules that only solving needs. Splitting
  every calculator's description from its solving (motion.plots, limit_grid.table(),
  gains_code.mechanism_documents are declared at module level) was not done here.
- after it, 2-7 layouts: Textual sets each new widget's virtual_size (a layout reactive) in the
  first layout, so a second one always follows; the first warnings shrink the results list (its
  scrollbar: one more); the chart's mount (PlotWidget, Grid, 4 Canvas, Legend) two, its legend
  placed in render one.
- ratio_finder: its first solve (worker thread) parses the parts catalogue (tomllib, ~1100 inline
  tables, 24-30 ms) and builds the stage classes (~55 ms profiled), pure Python: the GIL it holds
  stretches the first paint (wall/CPU 30/25 ms) and its allocations set off the full collection (12 ms)
  in the window. Not changed (the data format and the search keep the golden outputs).
What paid (kept): fewer widgets per card, nothing drawn differently (snapshots unchanged): the
panes are the card's own children (no Horizontal the size of the card under them), the warnings
box is mounted with the first warnings (two widgets), a table of another mode when that mode is
chosen (two), the chart panel draws "no data" as its own text (one Static), the glance line is
composed only on a narrow screen (one): 12-24 widgets a card before, 8-21 after (settled, chart
included). CPU key -> drawn 1426 -> 1293 ms (-9%), longest block 669 -> 605 (-10%), CPU until
settled 3590 -> 3339 (-7%), 14 of 18 cards lower (an earlier pair of runs: -11%, -11%, -10%);
the Horizontal alone was within the noise (1168 -> 1156), the hidden widgets made the rest. The
wall-clock figures of this bench, same runs alternating, were not conclusive at load 6 (minimal
app 32 ms, stalls 75-250 ms either way).
What did not pay (measured, reverted): composing the chart's PlotWidget with the card once
textual-plot is loaded: shown, the first paint grew (37-56 ms CPU against 27-42, its empty axes
drawn); hidden until its data, the layouts stayed 78 over the 18 first visits (its display
toggled instead of its mount) and the CPU within the noise (1124 against 1145 ms). Textual's
textual.lazy.Lazy (the framework's own deferral) was not used for the chart: the chart is already
mounted after the first frame, and a Lazy panel (16 rows) would come a frame after the card and
lay the results list out twice. Importing tomllib in core/parts only when reading: the app has
it at start (its settings), so only this bench would have gained.

What paid, 2 December evening (kept; snapshots unchanged). A repeat visit painted the card's
region, then, in the same tick, the whole screen again; per line, every widget's strip was cut at
every widget edge (Strip.divide), and each Strip Textual makes carries 7 FIFOCaches (15 tracked
objects): ~830 Strips a visit, ~20 young collections, and a full one every ~4 visits (over the
~20-35k unfrozen objects, mostly widgets' cached Strips and the event loop's cyclic garbage).
- the home and workbook screens are CardScreens (tui/components/card_screen.py: Screen.focused
  with repaint=False), so the focus move no longer repaints the screen: no second, full render,
  and the Screen's 45 lines are not rendered and cut afresh;
- the card is `visibility: hidden` with visible panes: the card's blank background (repainted by
  every show) is no longer rendered under the panes nor cut at their edges;
- the sheet is not restyled on a focus move (watch_has_focus; its focused cursor is a component
  class of its own): 2 x 9 nodes restyled a switch;
- the cards sit in a box (#cards, not painted) instead of the screen: a mount repainted the
  screen, a second full render in every first visit.
Strips a visit (18 cards, mean) repeat 833 -> 193, first 1243 -> 673; over the 17 repeat visits,
collections gen0/1/2 474/43/4 -> 161/14/1. This file, --app-only --runs 3, twice alternating with
7a2b39c on a quiet machine (minimal app 19.8-22.7 ms): repeat visit median 2.01x, 1.99x -> 0.88x,
0.86x, worst card 2.60x, 3.50x -> 1.19x, 1.53x, longest stall 58-68 -> 26-32 ms, no full
collection in a repeat window (7a2b39c: sprint, chain_belt, ratio_finder 10-34 ms); first visit
median 3.75x, 3.64x -> 3.09x, 3.04x, longest stall 76-106 -> 69-93 ms (ratio_finder's first solve,
the card's mount in one block).
What is left: a first visit's mount is one block of the loop (compose, style, first paint, and
the calculator's import) over 16 ms on every card; on a repeat visit the sheet's whole redraw
(Textual refreshes a widget taking or losing focus) and a ScrollView's scrollbars, repainted on
every layout (ScrollView._size_updated compares the compositor's virtual size, none for a
Line-API view, with its own, so it calls _scroll_update every time: Textual's); the chart's
PlotPanel, PlotWidget and Grid, containers covered whole by their canvases, are still painted
(their tint shows a stale chart).

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
        ("gearhead solve beam", ["solve", "beam"]),  # its tube's J bounds read from a table: no numpy
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
