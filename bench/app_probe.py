"""What the app benches measure, with Textual's public API only (App.run_test, Pilot, post_message,
MessagePump.wait_for_refresh). Each probe runs in a fresh process (bench_startup.py starts them)
and prints one JSON object on its last line; times in ms.

- A key goes in as the terminal driver delivers it: `app.post_message(events.Key(...))`.
  (`pilot.press` also waits until every widget has answered a callback, ~130 on a card, which a
  real terminal does not: that wait would be counted in the figure.)
- "Drawn": the card's sheet (or the minimal app's pane) has a region on screen (`Widget.region`,
  the sheet's: the card widget itself is `visibility: hidden`, painted by its panes, so it has
  no region of its own on a wide screen; the sheet is placed by the same layout), set by
  the layout, whose frame is rendered in the same call, before any other task runs): the first
  frame that shows it. (`Screen.wait_for_refresh` waits for the refresh after the next, which on
  a card switch came 25-30 ms after the frame that showed the card.)
- "Stall": the longest the event loop was blocked (a 1 ms asyncio sleep that woke late), from the
  key until STALL_WINDOW_S after the frame: a key typed then waits that long.

- "GC": the longest full garbage collection (generation 2) in that window (gc.callbacks).
- "CPU": the process's CPU time from the key to the frame (all threads): what load on a shared
  machine changes least.

Run one alone: .venv/bin/python bench/app_probe.py visits [--no-gc-freeze] | minimal |
first-frame app|minimal
"""

from __future__ import annotations

import asyncio
import gc
import json
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

SIZE = (140, 45)
STALL_WINDOW_S = 0.3  # the card's first solve (a thread) and its chart follow the frame


async def _watch_stalls(into: list[float], stop: asyncio.Event) -> None:
    while not stop.is_set():
        t = time.perf_counter()
        await asyncio.sleep(0.001)
        into.append(time.perf_counter() - t - 0.001)


async def _until(condition, timeout: float = 20.0) -> None:
    deadline = time.perf_counter() + timeout
    while not condition():
        if time.perf_counter() > deadline:
            raise TimeoutError("the app never reached the state waited for")
        await asyncio.sleep(0.0005)


def key_event(key: str):
    from textual import events

    return events.Key(key, key if len(key) == 1 else None)


GC_PAUSES: list[tuple[int, float]] = []  # (generation, ms) of every collection while timing
_gc_started: list[float] = []
_timing = [False]


def _on_gc(phase: str, info: dict) -> None:
    if phase == "start":
        _gc_started[:] = [time.perf_counter()]
    elif _timing[0] and _gc_started:
        GC_PAUSES.append((info["generation"], (time.perf_counter() - _gc_started[0]) * 1e3))


gc.callbacks.append(_on_gc)


async def timed_keys(app, keys: list[str], done) -> tuple[float, float, float, float]:
    """(key -> `done()` holds, longest stall, longest full (generation 2) garbage collection, CPU
    time to `done()`), ms; the keys posted together."""
    stalls: list[float] = []
    GC_PAUSES.clear()
    _timing[0] = True
    stop = asyncio.Event()
    watcher = asyncio.create_task(_watch_stalls(stalls, stop))
    await asyncio.sleep(0.02)
    stalls.clear()
    c0, t0 = time.process_time(), time.perf_counter()
    for key in keys:
        app.post_message(key_event(key))
    try:
        await _until(done)
    except TimeoutError:
        print("timeout", keys, app.current_calculator, app.focused, app.screen, file=sys.stderr)
        raise
    drawn, cpu = time.perf_counter() - t0, time.process_time() - c0
    await asyncio.sleep(STALL_WINDOW_S)
    stop.set()
    await watcher
    _timing[0] = False
    full = max((ms for gen, ms in GC_PAUSES if gen == 2), default=0.0)
    return drawn * 1e3, max(stalls, default=0.0) * 1e3, full, cpu * 1e3


def visit_plan(first: bool) -> list[tuple[str, list[str], list[str]]]:
    """(card, keys not timed, keys timed) for every card but the one shown at start: F-key, then
    the digit timed; on an area's first visit its first card is shown by the F-key alone (timed)."""
    from gearhead.core.registry import AREAS, ORDER

    plan = []
    for n, (_title, ids) in enumerate(AREAS.values(), 1):
        for m, calc in enumerate(ids, 1):
            if calc == ORDER[0]:
                continue
            if m == 1 and first:
                plan.append((calc, [], [f"f{n}"]))
            else:
                plan.append((calc, [f"f{n}"], [str(m)]))
    return plan


async def visits() -> dict:
    """Every card's first visit, then every card's second, in one app."""
    from gearhead.tui.app import GearheadApp

    app = GearheadApp(blink=False, hide_timings=True)
    out: dict[str, dict[str, list[float]]] = {"first": {}, "repeat": {}}
    async with app.run_test(size=SIZE) as pilot:
        await _until(lambda: app.card_ready(app.current_calculator))
        await pilot.pause(0.5)
        for kind in ("first", "repeat"):
            for calc, before, keys in visit_plan(kind == "first"):
                if before:  # not timed: pilot.press waits until the app has taken them
                    await pilot.press(*before)
                    await _until(lambda: app.card_ready(app.current_calculator))
                    await pilot.pause(0.2)
                shown = lambda calc=calc: (  # noqa: E731
                    app.current_calculator == calc
                    and app.card_ready(calc)
                    and app.current_tab.sheet.region.height > 0
                )
                out[kind][calc] = list(await timed_keys(app, keys, shown))
                tab = app.current_tab
                await _until(lambda: not tab.busy)  # its first solve and chart: the next key waits
                await pilot.pause(0.1)
    return out


async def minimal() -> dict:
    """The baseline: a minimal Textual app, 13 tab panes, each F-key shows a pane (first time)."""
    from textual.app import App
    from textual.widgets import Footer, Label, TabbedContent, TabPane

    class Minimal(App):
        BINDINGS = [(f"f{n}", f"pane({n})", "") for n in range(2, 13)]

        def compose(self):
            with TabbedContent():
                for i in range(13):
                    yield TabPane(f"Tab {i}", Label(f"pane {i}"), id=f"p{i}")
            yield Footer()

        def action_pane(self, n: int) -> None:
            self.query_one(TabbedContent).active = f"p{n}"

    app = Minimal()
    shown = []
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause(0.5)
        for n in range(2, 13):
            label = app.query_one(f"#p{n} Label")
            done = lambda label=label: label.region.height > 0  # noqa: E731
            shown.append(list(await timed_keys(app, [f"f{n}"], done)))
    return {"first": shown}


FIRST_FRAME_MINIMAL = """
from textual.app import App
from textual.widgets import Footer, Header, TabbedContent, TabPane
class Minimal(App):
    def compose(self):
        yield Header()
        with TabbedContent():
            for i in range(13):
                yield TabPane(f"Tab {i}")
        yield Footer()
"""


async def first_frame(which: str, t0: float) -> dict:
    """Process start -> the first frame (Textual's Ready, sent once it is on screen)."""
    if which == "app":
        from gearhead.tui.app import GearheadApp as App
    else:
        scope: dict = {}
        exec(FIRST_FRAME_MINIMAL, scope)
        App = scope["Minimal"]
    ready: list[float] = []

    class Timed(App):
        def on_ready(self) -> None:
            ready.append(time.perf_counter() - t0)

    app = Timed()
    async with app.run_test(size=SIZE) as pilot:
        await _until(lambda: bool(ready))
        if which == "app":  # closing mid-mount of the first card trips Textual: let it finish
            await _until(lambda: app.card_ready(app.current_calculator))
        await pilot.pause(0.2)
    return {"first_frame": ready[0] * 1e3}


def main() -> None:
    t0 = time.perf_counter()
    what = sys.argv[1]
    if "--no-gc-freeze" in sys.argv:  # what tui/app.py's gc.freeze() after each card is worth
        gc.freeze = lambda: None
    if what == "visits":
        result = asyncio.run(visits())
    elif what == "minimal":
        result = asyncio.run(minimal())
    else:
        result = asyncio.run(first_frame(sys.argv[2], t0))
    print(json.dumps(result))


def median_of(rows: list[list[float]], i: int) -> float:
    return statistics.median(r[i] for r in rows)


if __name__ == "__main__":
    main()
