"""Start-up as a user meets it, each figure beside its baseline, run alternately in fresh
processes (medians; the machine is shared, so read the ratios):

- CLI: `gearhead solve gear_ratio --json` (bare numbers) vs `python -c "import numpy"`;
- first frame: the app's first screen vs a minimal Textual app with 13 empty tab panes.

- first visit: a few seconds after start, open the beam (another area) until its card is on
  screen, vs a pane's first visit in the minimal app.

Run alone:  .venv/bin/python bench/bench_startup.py [--app-only] [--root DIR] [--runs N] [--only 'first visit']
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# --root DIR: time the app of another checkout (e.g. `git archive cd298d1 | tar -x -C DIR`), with
# this venv; the scripts run in DIR, so its tui/ and core/ are the ones imported
APP_ROOT = Path(sys.argv[sys.argv.index("--root") + 1]).resolve() if "--root" in sys.argv else ROOT
RUNS = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 7

FIRST_FRAME = r"""
import time, asyncio
t0 = time.perf_counter()
from gearhead.tui.app import GearheadApp
class Timed(GearheadApp):
    async def on_ready(self):  # Textual sends Ready once the first frame is on screen
        self.first_frame = time.perf_counter() - t0
        then = getattr(super(), "on_ready", None)  # the app's own (builds the first card)
        if then is not None:
            await then()
async def main():
    app = Timed(blink=False)
    async with app.run_test(size=(140, 45)) as pilot:
        await pilot.pause()
        ready = getattr(app, "card_ready", None)  # closing mid-mount trips Textual: wait
        while ready is not None and not ready(app.current_calculator):
            await pilot.pause()
        await pilot.pause(0.3)
    print(app.first_frame)
asyncio.run(main())
"""

FIRST_RESULT = r"""
import time, asyncio
t0 = time.perf_counter()
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
async def main():
    app = GearheadApp(blink=False)
    async with app.run_test(size=(140, 45)) as pilot:
        while not any(t.solution is not None for t in app.query(CalculatorTab)):
            await asyncio.sleep(0.001)
        shown = time.perf_counter() - t0
        await pilot.pause()  # let the chart finish mounting before the app closes
    print(shown)
asyncio.run(main())
"""

# A first visit as a user makes it: the app has been on screen for a few seconds (the user reads
# the first card), then they open the beam (another area); timed until its card is on screen
# (the UI thread's part: its results follow from a solve thread).
FIRST_VISIT = r"""
import time, asyncio
from gearhead.tui.app import GearheadApp
async def main():
    try:
        app = GearheadApp(blink=False, warm_up=True)  # as run() starts it
    except TypeError:  # before the warm-up existed
        app = GearheadApp(blink=False)
    async with app.run_test(size=(140, 45)) as pilot:
        await pilot.pause(READ_S)
        t0 = time.perf_counter()
        app.show_calculator("beam")
        while True:
            await pilot.pause()
            card = app.query("#calc-beam")
            # the card on screen with its fields (its results come from a solve thread)
            if card and card.first().region.height and card.first().query("#in-length"):
                break
        shown = time.perf_counter() - t0
        app.warm_up = False  # closing mid-mount trips Textual: stop building, let mounts end
        await pilot.pause(1.0)
    print(shown)
asyncio.run(main())
"""

# the same in a minimal app: the first visit of an empty tab pane
MINIMAL_VISIT = r"""
import time, asyncio
from textual.app import App
from textual.widgets import Footer, Label, TabbedContent, TabPane
class Minimal(App):
    def compose(self):
        with TabbedContent():
            for i in range(13):
                yield TabPane(f"Tab {i}", Label(f"pane {i}", id=f"l{i}"), id=f"p{i}")
        yield Footer()
async def main():
    app = Minimal()
    async with app.run_test(size=(140, 45)) as pilot:
        await pilot.pause(READ_S)
        t0 = time.perf_counter()
        app.query_one(TabbedContent).active = "p12"
        while not app.query_one("#l12").region.height:
            await pilot.pause()
        print(time.perf_counter() - t0)
asyncio.run(main())
"""
READ_S = 8.0  # seconds the user spends on the first card before switching

MINIMAL_APP = r"""
import time, asyncio
t0 = time.perf_counter()
from textual.app import App
from textual.widgets import Footer, Header, TabbedContent, TabPane
class Minimal(App):
    def compose(self):
        yield Header()
        with TabbedContent():
            for i in range(13):
                yield TabPane(f"Tab {i}")
        yield Footer()
    def on_ready(self):
        self.first_frame = time.perf_counter() - t0
async def main():
    app = Minimal()
    async with app.run_test(size=(140, 45)) as pilot:
        await pilot.pause()
    print(app.first_frame)
asyncio.run(main())
"""


def wall(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True)
    return time.perf_counter() - t0


def reported(code: str) -> float:
    code = code.replace("READ_S", repr(READ_S))
    out = subprocess.run([sys.executable, "-c", code], cwd=APP_ROOT, capture_output=True, text=True)
    if out.returncode:
        raise RuntimeError(out.stderr[-2000:])
    return float(out.stdout.strip().splitlines()[-1])


def pair(name: str, ours, baseline, base_name: str) -> None:
    if "--only" in sys.argv and sys.argv[sys.argv.index("--only") + 1] not in name:
        return
    a, b = [], []
    for _ in range(RUNS):  # alternate, so load on the machine hits both alike
        a.append(ours())
        b.append(baseline())
    ma, mb = statistics.median(a), statistics.median(b)
    print(f"  {name:<38} {ma * 1e3:7.1f} ms   {base_name:<34} {mb * 1e3:7.1f} ms   ratio {ma / mb:4.2f}")


def main() -> None:
    print(f"start-up (median of {RUNS} fresh processes, alternating with the baseline):")
    gearhead = str(Path(sys.executable).with_name("gearhead"))
    numpy = lambda: wall([sys.executable, "-c", "import numpy"])  # noqa: E731
    minimal = lambda: reported(MINIMAL_APP)  # noqa: E731
    if "--app-only" not in sys.argv:
        pair(
            "gearhead solve gear_ratio --json",
            lambda: wall([gearhead, "solve", "gear_ratio", "--json"]),
            numpy,
            "python -c 'import numpy'",
        )
        pair(
            "gearhead solve beam --set length='20 in'",
            lambda: wall([gearhead, "solve", "beam", "--set", "length=20 in"]),
            numpy,
            "same (a typed unit loads pint)",
        )
    pair(
        "app: first frame (headless, 140x45)",
        lambda: reported(FIRST_FRAME),
        minimal,
        "minimal app, 13 empty tab panes",
    )
    pair("app: first results on screen", lambda: reported(FIRST_RESULT), minimal, "same")
    pair(
        "app: first visit of another tab",
        lambda: reported(FIRST_VISIT),
        lambda: reported(MINIMAL_VISIT),
        "minimal app, first visit of a pane",
    )


if __name__ == "__main__":
    main()
