"""Where a first visit to each card spends the UI thread's time, core's share named: cProfile on
the event loop's thread (a profiler sees only the thread that enabled it, so the solve worker is
not counted) from the key until the frame that shows the card, the card's first solve and
chart finished meanwhile or not. Figures only (cProfile slows Python code ~1.5-2x: read shares,
not times).

    .venv/bin/python bench/profile_first_visit.py [--top N] [CARD ...]

Prints per card: the UI thread's time by owner (core, tui, textual, rich, other: a function's own
time, by the file it is in), and the core functions with the most cumulative time.
"""

from __future__ import annotations

import asyncio
import cProfile
import pstats
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from app_probe import SIZE, _until, key_event, visit_plan  # noqa: E402

TOP = int(sys.argv[sys.argv.index("--top") + 1]) if "--top" in sys.argv else 6
ONLY = [a for a in sys.argv[1:] if not a.startswith("--") and not a.isdigit()]


def owner(filename: str) -> str:
    for mark, name in (
        ("/core/", "core"),
        ("/tui/", "tui"),
        ("/textual/", "textual"),
        ("/rich/", "rich"),
    ):
        if mark in filename and (
            "gearhead" in filename or "/work/" in filename or name in ("textual", "rich")
        ):
            return name
    return "other"


def report(calc: str, profile: cProfile.Profile) -> None:
    stats = pstats.Stats(profile)
    by_owner: dict[str, float] = {}
    total = 0.0
    for (filename, _line, _name), (_cc, _nc, tt, _ct, _callers) in stats.stats.items():
        by_owner[owner(filename)] = by_owner.get(owner(filename), 0.0) + tt
        total += tt
    shares = "  ".join(f"{k} {v * 1e3:5.1f}" for k, v in sorted(by_owner.items(), key=lambda kv: -kv[1]))
    print(f"{calc:<18} {total * 1e3:6.1f} ms   {shares}")
    core = [
        (ct, f"{Path(fn).parent.name}/{Path(fn).name}:{line} {name}")
        for (fn, line, name), (_cc, _nc, _tt, ct, _callers) in stats.stats.items()
        if owner(fn) == "core"
    ]
    for ct, where in sorted(core, reverse=True)[:TOP]:
        print(f"    {ct * 1e3:6.1f} ms cumulative  {where}")


async def main() -> None:
    from gearhead.tui.app import GearheadApp

    app = GearheadApp(blink=False, hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await _until(lambda: app.card_ready(app.current_calculator))
        await pilot.pause(0.5)
        for calc, before, keys in visit_plan(True):
            if ONLY and calc not in ONLY:
                continue
            if before:
                await pilot.press(*before)
                await _until(lambda: app.card_ready(app.current_calculator))
                await pilot.pause(0.2)
            shown = lambda calc=calc: (  # noqa: E731
                app.current_calculator == calc
                and app.card_ready(calc)
                and app.current_tab.sheet.region.height > 0
            )
            profile = cProfile.Profile()
            profile.enable()
            for key in keys:
                app.post_message(key_event(key))
            await _until(shown)
            profile.disable()
            report(calc, profile)
            tab = app.current_tab
            await _until(lambda: not tab.busy)
            await pilot.pause(0.1)


if __name__ == "__main__":
    asyncio.run(main())
