"""Keystroke -> result shown, as a user meets it: the pilot types one character into a field and
we time until the tab has put the new result into its table, and until the frame that shows it
has been drawn (median over many keystrokes). The baseline is measured the same way: a key into a
plain Input of a minimal app, until its Changed handler ran and until the next frame was drawn.
The machine may be shared: compare the ratios to the baseline of the same run, and the CPU time
the process spent from the key to the drawn frame (all threads; what load on the machine changes
least).

Run alone:  .venv/bin/python bench/bench_keystroke.py [--keys N] [--only motor,pneumatics]
"""

from __future__ import annotations

import asyncio
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

# closed-form calculators, then simulated scenes at their default accuracy (--only a,b: those)
CALCULATORS = [
    "gear_ratio",
    "beam",
    "motor",
    "drivetrain",
    "pneumatics",
    "projectile",
    "flywheel",
    "trebuchet",
]
if "--only" in sys.argv:
    CALCULATORS = sys.argv[sys.argv.index("--only") + 1].split(",")


def typing_field(calc_id: str) -> str:
    """The first quantity field whose default stays valid with its last digit deleted, so every
    keystroke of the benchmark (delete, retype) is a new valid value, never an error."""
    from gearhead.core.errors import InputError
    from gearhead.core.model import choice_values, solve
    from gearhead.core.registry import get

    calc = get(calc_id)
    mode = calc.field("mode").default if any(f.name == "mode" for f in calc.fields) else None
    for f in calc.fields:
        text = f.default_text()
        if not f.active(mode, choice_values(calc, {})):
            continue  # a row the default mode hides
        if not f.kind.numeric or not text[-1:].isdigit() or len(text) < 2:
            continue
        try:
            solve(calc_id, {f.name: text[:-1]})
        except InputError:
            continue
        return f.name
    raise LookupError(f"no field of {calc_id} to type into")


KEYS = int(sys.argv[sys.argv.index("--keys") + 1]) if "--keys" in sys.argv else 30


cpu_at = [0.0]  # process_time() at the end of the last frame drawn


def _frames(app) -> list[float]:
    """perf_counter() at the end of each frame the screen draws (Textual's compositor refresh)."""
    drawn: list[float] = []
    screen = app.screen
    refresh = screen._compositor_refresh

    def timed_refresh() -> None:
        refresh()
        drawn.append(time.perf_counter())
        cpu_at[0] = time.process_time()

    screen._compositor_refresh = timed_refresh
    return drawn


async def _frame_after(drawn: list[float], t: float, timeout: float = 1.0) -> float | None:
    """The end of the first frame drawn after `t` (None if none came: nothing changed)."""
    deadline = time.perf_counter() + timeout
    while time.perf_counter() < deadline:
        later = [d for d in drawn if d > t]
        if later:
            return later[0]
        await asyncio.sleep(0.0002)
    return None


async def type_key(app, key: str) -> None:
    """The key as the terminal driver delivers it. pilot.press also waits until every widget
    has run a callback, which on a card of ~130 widgets costs more than the frame itself and
    would be counted in it (a real terminal has no such wait)."""
    await app._press_keys([key])


async def _latencies(calc_id: str, field: str) -> tuple[list[float], list[float], list[float]]:
    from textual.widgets import Input

    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab

    app = GearheadApp(blink=False, initial=calc_id, hide_timings=True)
    shown_at: list[float] = []
    async with app.run_test(size=(140, 45)) as pilot:
        await app.card(calc_id)  # built right after the first frame
        tab = app.query_one(f"#calc-{calc_id}", CalculatorTab)
        show = tab._show

        def timed_show(*args):
            show(*args)
            shown_at.append(time.perf_counter())

        tab._show = timed_show
        drawn = _frames(app)
        sheet = getattr(tab, "sheet", None)
        if sheet is not None:  # the sheet (issue 27): the row's value edited with the caret at its end
            sheet.focus()
            if not sheet.move_to_field(field):  # a row this mode hides (its Input existed before)
                raise LookupError(f"{field} is not shown on the {calc_id} card")
            await pilot.pause()
            last = str(tab.entries[field])[-1]
            await type_key(app, "enter")
        else:  # before it: one Input per field
            entry = tab.query_one(f"#in-{field}", Input)
            entry.focus()
            entry.cursor_position = len(entry.value)
            last = entry.value[-1]
        while tab.busy:
            await asyncio.sleep(0.001)
        await pilot.pause()
        out, painted, cpu = [], [], []
        for i in range(KEYS):
            # delete the last digit then type it again: every keystroke is a new valid value
            key = "backspace" if i % 2 == 0 else last
            before = len(shown_at)
            c0, t0 = time.process_time(), time.perf_counter()
            await type_key(app, key)
            while len(shown_at) == before:
                await asyncio.sleep(0.0002)
            shown = shown_at[before]  # the first result shown after the key (a scene's estimate may follow)
            out.append(shown - t0)
            frame = await _frame_after(drawn, shown)
            if frame is not None:
                painted.append(frame - t0)
                cpu.append(cpu_at[0] - c0)
            while tab.busy:
                await asyncio.sleep(0.0002)
            await pilot.pause()
    return out, painted, cpu


async def _baseline() -> tuple[list[float], list[float], list[float]]:
    """The floor Textual itself sets, measured the same way: a key into a plain Input of a minimal
    app, until its Changed handler has run (no solve, no table)."""
    from textual.app import App
    from textual.widgets import Input

    handled: list[float] = []

    class Minimal(App):
        def compose(self):
            yield Input("1234")

        def on_input_changed(self, event: Input.Changed) -> None:
            handled.append(time.perf_counter())

    app = Minimal()
    out, painted, cpu = [], [], []
    async with app.run_test(size=(140, 45)) as pilot:
        drawn = _frames(app)
        entry = app.query_one(Input)
        entry.focus()
        entry.cursor_position = len(entry.value)
        await pilot.pause()
        for i in range(KEYS):
            before = len(handled)
            c0, t0 = time.process_time(), time.perf_counter()
            await type_key(app, "backspace" if i % 2 == 0 else "4")
            while len(handled) == before:
                await asyncio.sleep(0.0002)
            out.append(handled[-1] - t0)
            frame = await _frame_after(drawn, handled[-1])
            if frame is not None:
                painted.append(frame - t0)
                cpu.append(cpu_at[0] - c0)
            await pilot.pause()
    return out, painted, cpu


def main() -> None:
    med = statistics.median
    print("keystroke -> result in the table, -> the frame showing it drawn, and the process's CPU time")
    print(f"from the key to that frame (pilot, median of {KEYS} keys; x: the ratio to this run's baseline)")
    base, base_drawn, base_cpu = asyncio.run(_baseline())
    b, bd, bc = med(base), med(base_drawn), med(base_cpu)
    print(
        f"  {'baseline: plain Input, minimal app':<34} handled {b * 1e3:6.2f} ms"
        f"          drawn {bd * 1e3:6.2f} ms           cpu {bc * 1e3:6.2f} ms"
    )
    for calc_id in CALCULATORS:
        field = typing_field(calc_id)
        lat, drawn, cpu = asyncio.run(_latencies(calc_id, field))
        print(
            f"  {calc_id:<14} {field:<19} table   {med(lat) * 1e3:6.2f} ms ({med(lat) / b:4.1f}x)"
            f"   drawn {med(drawn) * 1e3:6.2f} ms ({med(drawn) / bd:4.1f}x)"
            f"   cpu {med(cpu) * 1e3:6.2f} ms ({med(cpu) / bc:4.1f}x)"
        )


if __name__ == "__main__":
    main()
