"""Start-up as a user meets it, each figure beside its baseline, run alternately in fresh
processes (medians; the machine is shared, so read the ratios):

- CLI: `gearhead solve gear_ratio --json` (bare numbers) vs `python -c "import numpy"`; typed
  units (read from the stored table), the beam bare, and a unit only pint reads (furlong), each
  vs the same baseline;
- first frame: the app's first screen vs a minimal Textual app with 13 empty tab panes.

- first visit: F3 opens the beam (another area) 8 s after start (the warm-up under way) and
  25 s after start (warm-up done): key -> the first frame that shows its card, and the longest
  stall of the UI thread in the 2 s after the key, vs F3 showing a pane for the first time in
  the minimal app;
- repeat visit: the same F3 at 25 s after the beam was shown once (F3, F1): what any switch
  costs, the floor a first visit can reach;
- warm-up: the longest stall of the UI thread in the first 25 s without a key (the longest a
  key typed while the user reads can wait), vs the minimal app sitting idle.

Run alone:  .venv/bin/python bench/bench_startup.py [--app-only] [--runs N] [--only 'first visit']
Before/after: run this file with another checkout's .venv/bin/python (its editable install imports
that checkout's app).
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
APP_ROOT = ROOT  # the scripts run here; `gearhead` is whatever the running venv installed
RUNS = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 7
# as a user runs it: with bytecode caches (pip writes them at install). A shell that sets
# PYTHONDONTWRITEBYTECODE (this machine's does) made every start compile gearhead's modules from
# source, ~45 ms that the baselines (installed packages, compiled) never paid
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
WRITE_CACHES = """
import compileall, os, gearhead.core, gearhead.tui
for package in (gearhead.core, gearhead.tui):
    compileall.compile_dir(os.path.dirname(package.__file__), quiet=1)
"""

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
# the first card), then they press F3 (Structure: the beam, another area). Two figures, printed
# as "drawn stall" in ms:
# - drawn: key -> the end of the first frame that shows the card (its results follow from a
#   solve thread);
# - stall: the longest a message posted to the app waited to be handled in the 2 s after the key
#   (a probe posts one every 5 ms): a key typed then waits that long.
# Keys go in as the terminal driver delivers them (pilot.press would also wait for every widget).
# the stall probe, shared by the visit and warm-up scripts
STALLS = r"""
async def stalls(app, into):  # a key typed at t waits as long: the loop's stall, then the queue
    while True:
        t = time.perf_counter()
        await asyncio.sleep(0.005)
        handled = asyncio.Event()
        # the time the app takes it (the probe itself may resume a frame later)
        app.call_later(lambda: (into.append(time.perf_counter() - t - 0.005), handled.set()))
        await handled.wait()
""".strip()

VISIT_PROBE = r"""
import time, asyncio
from textual.screen import Screen
drawn = []
def watch(widget_of):  # the end of the first frame in which widget_of() is on screen
    refresh = Screen._compositor_refresh
    def hooked(self):
        refresh(self)
        if drawn or not self.app.is_running:
            return
        w = widget_of(self.app)
        if w is not None and w.region.height:
            drawn.append(time.perf_counter())
    Screen._compositor_refresh = hooked
STALLS
async def visit(app, press, pilot, read_s):
    await pilot.pause(read_s)
    late = []
    probe = asyncio.create_task(stalls(app, late))
    await asyncio.sleep(0.05)
    late.clear()
    drawn.clear()
    t0 = time.perf_counter()
    await press()
    while not drawn and time.perf_counter() - t0 < 20:
        await asyncio.sleep(0.002)
    await asyncio.sleep(max(0.0, t0 + 2.0 - time.perf_counter()))
    probe.cancel()
    print((drawn[0] - t0) * 1e3, max(late) * 1e3)
"""

FIRST_VISIT = (
    VISIT_PROBE
    + r"""
from gearhead.tui.app import GearheadApp
def card(app):  # a dict lookup: a query per frame walks every widget (60-80 ms with all cards)
    if app.current_calculator != "CALC":  # a rehearsal draws it beneath the card on screen
        return None
    return app._cards.get("CALC")
watch(card)
async def main():
    try:
        app = GearheadApp(blink=False, warm_up=True)  # as run() starts it
    except TypeError:  # before the warm-up existed
        app = GearheadApp(blink=False)
    async with app.run_test(size=(140, 45)) as pilot:
        if REPEAT:  # the beam seen once already: F3, back with F1, then the F3 measured
            await pilot.pause(READ_S)
            for key in ("KEY", "f1"):
                await app._press_keys([key])
                await pilot.pause(1.5)
        await visit(app, lambda: app._press_keys(["KEY"]), pilot, 0.5 if REPEAT else READ_S)
        app.warm_up = False  # closing mid-mount trips Textual: stop building, let mounts end
        await pilot.pause(1.0)
asyncio.run(main())
"""
)

# the same in a minimal app: F3 shows an empty tab pane for the first time
MINIMAL_VISIT = (
    VISIT_PROBE
    + r"""
from textual.app import App
from textual.widgets import Footer, Label, TabbedContent, TabPane
class Minimal(App):
    BINDINGS = [("f3", "pane", "")]
    def compose(self):
        with TabbedContent():
            for i in range(13):
                yield TabPane(f"Tab {i}", Label(f"pane {i}", id=f"l{i}"), id=f"p{i}")
        yield Footer()
    def action_pane(self):
        self.query_one(TabbedContent).active = "p12"
def label(app):
    return app.query_one("#p12").children[0] if app.query_one("#p12").children else None
watch(label)
async def main():
    app = Minimal()
    async with app.run_test(size=(140, 45)) as pilot:
        await visit(app, lambda: app._press_keys(["f3"]), pilot, 2.0)  # no warm-up: no wait
asyncio.run(main())
"""
)
READ_S = 8.0  # seconds the user spends on the first card before switching
WARMED_S = 25.0  # by then every card is built and rehearsed (about 18 s idle; 21 s before the F-key cards came first)

# The warm-up as a user who reads meets it: the longest a message posted to the app waited in
# the first WARMED_S seconds (a key typed then waits that long), printed in ms.
WARM_UP_STALL = r"""
import time, asyncio
STALLS
APP
async def main():
    app = make()
    async with app.run_test(size=(140, 45)) as pilot:
        await pilot.pause(1.0)  # the first card (first frame and results: their own rows)
        late = []
        probe = asyncio.create_task(stalls(app, late))
        await asyncio.sleep(WAIT_S)
        probe.cancel()
        app.warm_up = False
        await pilot.pause(1.0)
    print(max(late) * 1e3)
asyncio.run(main())
"""
WARM_UP_APP = """
from gearhead.tui.app import GearheadApp
def make():
    try:
        return GearheadApp(blink=False, warm_up=True)
    except TypeError:  # before the warm-up existed
        return GearheadApp(blink=False)
"""
MINIMAL_IDLE_APP = """
from textual.app import App
from textual.widgets import Footer, Label, TabbedContent, TabPane
class Minimal(App):
    def compose(self):
        with TabbedContent():
            for i in range(13):
                yield TabPane(f"Tab {i}", Label(f"pane {i}"))
        yield Footer()
def make():
    return Minimal()
"""

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
    subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, env=ENV)
    return time.perf_counter() - t0


def reported(code: str) -> float:
    return reported_all(code)[0]


def reported_all(
    code: str, read_s: float = READ_S, repeat: bool = False, key: str = "f3", calc: str = "beam"
) -> list[float]:
    """The figures a script prints on its last line (seconds, or ms for the visit probe); a
    visit presses `key`, which opens `calc`'s card."""
    code = code.replace("STALLS", STALLS).replace("READ_S", repr(read_s)).replace("REPEAT", repr(repeat))
    code = code.replace('"KEY"', repr(key)).replace('"CALC"', repr(calc))
    out = subprocess.run([sys.executable, "-c", code], cwd=APP_ROOT, capture_output=True, text=True, env=ENV)
    if out.returncode:
        raise RuntimeError(out.stderr[-2000:])
    return [float(x) for x in out.stdout.strip().splitlines()[-1].split()]


def pair(name: str, ours, baseline, base_name: str, names: tuple[str, ...] = ("",), scale=1e3) -> None:
    """Medians of `ours` and `baseline`, run alternately; each may return several figures (one
    row per name)."""
    if "--only" in sys.argv and sys.argv[sys.argv.index("--only") + 1] not in name:
        return
    a, b = [], []
    for _ in range(RUNS):  # alternate, so load on the machine hits both alike
        a.append(ours())
        b.append(baseline())
    for i, part in enumerate(names):
        if len(names) == 1:
            ma, mb = statistics.median(a), statistics.median(b)
        else:
            ma, mb = statistics.median(x[i] for x in a), statistics.median(x[i] for x in b)
        label = f"{name}{part}"
        print(
            f"  {label:<38} {ma * scale:7.1f} ms   {base_name:<34} {mb * scale:7.1f} ms   ratio {ma / mb:4.2f}"
        )


def main() -> None:
    subprocess.run([sys.executable, "-c", WRITE_CACHES], cwd=APP_ROOT, check=True, env=ENV)
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
        # typed units are read from core/unit_factors.json (pint only for what it cannot read):
        # typed costs what bare costs. The beam's default section (a rectangular tube) pays for
        # its finite-element J (scipy.sparse), bare or typed; gear_ratio shows the units alone
        for label, cmd in (
            (
                "gearhead solve gear_ratio --set load='40 lbf'",
                ["solve", "gear_ratio", "--set", "load=40 lbf"],
            ),
            ("gearhead solve beam --set length='20 in'", ["solve", "beam", "--set", "length=20 in"]),
            ("gearhead solve beam --set length=20", ["solve", "beam", "--set", "length=20"]),
            (
                "gearhead solve beam ... length='0.005 furlong'",
                ["solve", "beam", "--set", "length=0.005 furlong"],
            ),
            # the elevator's closed-form move and LQR without scipy (core/sim/small_math.py)
            ("gearhead solve elevator", ["solve", "elevator"]),
        ):
            pair(label, lambda cmd=cmd: wall([gearhead, *cmd]), numpy, "python -c 'import numpy'")
    pair(
        "app: first frame (headless, 140x45)",
        lambda: reported(FIRST_FRAME),
        minimal,
        "minimal app, 13 empty tab panes",
    )
    pair("app: first results on screen", lambda: reported(FIRST_RESULT), minimal, "same")
    for when, read_s in (("8 s", READ_S), ("25 s", WARMED_S)):
        pair(
            f"app: first visit (F3) at {when}, ",
            lambda read_s=read_s: reported_all(FIRST_VISIT, read_s),
            lambda: reported_all(MINIMAL_VISIT),
            "minimal app, F3 shows a new pane",
            names=("key -> drawn", "longest stall"),
            scale=1,
        )
    # the same first visit to a card whose first solve imports nothing more (the lead screw's closed
    # form): what the card costs, without the beam's finite-element J loading scipy.sparse (~400 ms
    # of import in the solve thread, whose allocations set off a full garbage collection)
    pair(
        f"app: first visit (F2, lead screw) at {WARMED_S:.0f} s, ",
        lambda: reported_all(FIRST_VISIT, WARMED_S, key="f2", calc="lead_screw"),
        lambda: reported_all(MINIMAL_VISIT),
        "minimal app, F3 shows a new pane",
        names=("key -> drawn", "longest stall"),
        scale=1,
    )
    pair(  # what any switch costs: the floor for a first visit
        f"app: repeat visit (F3 F1 F3) at {WARMED_S:.0f} s, ",
        lambda: reported_all(FIRST_VISIT, WARMED_S, repeat=True),
        lambda: reported_all(MINIMAL_VISIT),
        "minimal app, F3 shows a new pane",
        names=("key -> drawn", "longest stall"),
        scale=1,
    )
    pair(
        f"app: warm-up, longest stall in {WARMED_S:.0f} s",
        lambda: reported(WARM_UP_STALL.replace("APP", WARM_UP_APP).replace("WAIT_S", repr(WARMED_S - 1))),
        lambda: reported(
            WARM_UP_STALL.replace("APP", MINIMAL_IDLE_APP).replace("WAIT_S", repr(WARMED_S - 1))
        ),
        "minimal app idle, same time",
        scale=1,
    )


if __name__ == "__main__":
    main()
