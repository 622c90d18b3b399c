"""Keystroke -> result shown, as a user meets it: the pilot types one character into a field and
we time until the tab has put the new result into its table (median over many keystrokes).

Run alone:  .venv/bin/python bench/bench_keystroke.py
"""

from __future__ import annotations

import asyncio
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

# closed-form calculators, then simulated scenes at their default accuracy
CALCULATORS = ["gear_ratio", "beam", "motor", "drivetrain", "pneumatics", "projectile", "flywheel",
               "trebuchet"]


def typing_field(calc_id: str) -> str:
    """The first quantity field whose default stays valid with its last digit deleted, so every
    keystroke of the benchmark (delete, retype) is a new valid value, never an error."""
    from gearhead.core.errors import InputError
    from gearhead.core.model import solve
    from gearhead.core.registry import get

    for f in get(calc_id).fields:
        text = f.default_text()
        if f.type != "quantity" or not text[-1:].isdigit() or len(text) < 2:
            continue
        try:
            solve(calc_id, {f.name: text[:-1]})
        except InputError:
            continue
        return f.name
    raise LookupError(f"no field of {calc_id} to type into")


KEYS = 30


async def _latencies(calc_id: str, field: str) -> list[float]:
    from textual.widgets import Input

    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab

    app = GearheadApp(blink=False, initial=calc_id, hide_timings=True)
    shown_at: list[float] = []
    async with app.run_test(size=(140, 45)) as pilot:
        await app.card(calc_id)  # built right after the first frame
        tab = app.query_one(f"#calc-{calc_id}", CalculatorTab)
        show = tab._show

        def timed_show(solution, error):
            show(solution, error)
            shown_at.append(time.perf_counter())

        tab._show = timed_show
        entry = tab.query_one(f"#in-{field}", Input)
        entry.focus()
        entry.cursor_position = len(entry.value)
        while tab.busy:
            await asyncio.sleep(0.001)
        await pilot.pause()
        out = []
        last = entry.value[-1]
        for i in range(KEYS):
            # delete the last digit then type it again: every keystroke is a new valid value
            key = "backspace" if i % 2 == 0 else last
            before = len(shown_at)
            t0 = time.perf_counter()
            await pilot.press(key)
            while len(shown_at) == before or tab.busy:
                await asyncio.sleep(0.0002)
            out.append(shown_at[-1] - t0)
            await pilot.pause()
    return out


async def _baseline() -> list[float]:
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
    out = []
    async with app.run_test(size=(140, 45)) as pilot:
        entry = app.query_one(Input)
        entry.focus()
        entry.cursor_position = len(entry.value)
        await pilot.pause()
        for i in range(KEYS):
            before = len(handled)
            t0 = time.perf_counter()
            await pilot.press("backspace" if i % 2 == 0 else "4")
            while len(handled) == before:
                await asyncio.sleep(0.0002)
            out.append(handled[-1] - t0)
            await pilot.pause()
    return out


def main() -> None:
    print(f"keystroke -> result in the table (pilot, median and max of {KEYS} keys):")
    base = asyncio.run(_baseline())
    print(f"  {'baseline: a key reaching a plain Input (minimal app)':<31} median "
          f"{statistics.median(base) * 1e3:7.2f} ms   max {max(base) * 1e3:7.2f} ms")
    for calc_id in CALCULATORS:
        field = typing_field(calc_id)
        lat = asyncio.run(_latencies(calc_id, field))
        print(f"  {calc_id:<14} {field:<16} median {statistics.median(lat) * 1e3:7.2f} ms"
              f"   max {max(lat) * 1e3:7.2f} ms")


if __name__ == "__main__":
    main()
