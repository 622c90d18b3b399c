"""How much of Gearhead one keystroke runs on the UI thread (printed, never asserted).

For a closed-form card (gear ratio) and a simulated one (elevator): one digit typed into a field
through Textual's pilot, then 0.3 s for the app to solve and draw on its own (no polling). cProfile
sees the thread that enables it, the UI thread: the solve itself runs in a worker thread and is
not counted. Printed: calls into Gearhead's own functions and the files they live in, and every
call on the UI thread (Textual's and Rich's included).

    .venv/bin/python bench/bench_keystroke_calls.py [-v]    # -v: the most-called functions

Gearhead calls per key (issue 42): 557 and 2 479 when filed; 348 and 528 with the solve in a
worker; 288 and 441 once the worker builds the texts the card draws (card_text.drawn); 376 and
503 at 7a2b39c and after the card-visit work (2 December 2026, same run; most called, -v:
unit_text.fit_cells, line_view.base_style, results.render_line).
"""

from __future__ import annotations

import asyncio
import cProfile
import pathlib
import pstats
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from gearhead.tui.app import GearheadApp  # noqa: E402
from tests.tui_helpers import card, settle  # noqa: E402

CASES = [("gear_ratio", "motor_count", "2"), ("elevator", "motor_count", "1")]


def ours(path: str) -> bool:
    return (
        path.startswith(str(ROOT))
        and "/tests/" not in path
        and "/.venv/" not in path
        and "/bench/" not in path
    )


async def one_key(calc_id: str, field: str, key: str, verbose: bool) -> None:
    app = GearheadApp(blink=False, initial=calc_id)
    async with app.run_test(size=(160, 50)) as pilot:
        await settle(pilot)
        tab = card(app, calc_id)
        tab.sheet.focus()
        await pilot.pause()
        assert tab.sheet.move_to_field(field)
        await settle(pilot)
        profile = cProfile.Profile()
        profile.enable()
        await pilot.press(key)
        await asyncio.sleep(0.3)
        profile.disable()
        assert not tab.busy and tab.error is None, "the key's solve did not end within 0.3 s"
        stats = pstats.Stats(profile).stats
        mine = {k: v for k, v in stats.items() if ours(k[0])}
        files = {k[0] for k in mine}
        print(
            f"{calc_id:<12} Gearhead calls {sum(v[1] for v in mine.values()):6d} in {len(files):2d} files;"
            f" all UI-thread calls {sum(v[1] for v in stats.values()):7d}"
        )
        if verbose:
            for k, v in sorted(mine.items(), key=lambda kv: -kv[1][1])[:15]:
                print(f"    {v[1]:6d}  {pathlib.Path(k[0]).relative_to(ROOT)}:{k[2]}")


def main() -> None:
    verbose = "-v" in sys.argv
    for case in CASES:
        asyncio.run(one_key(*case, verbose))


if __name__ == "__main__":
    main()
