"""Regenerate docs/screenshot.svg (the README's picture): the trebuchet tab at 140x45.

.venv/bin/python docs/make_screenshot.py
"""

import asyncio
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


async def main() -> None:
    from gearhead.tui.app import GearheadApp
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="trebuchet", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        app.current_tab.sheet.focus()  # the sheet's cursor on its first row, the key bar its keys
        await settle(pilot)
        app.save_screenshot(str(ROOT / "docs" / "screenshot.svg"))


if __name__ == "__main__":
    asyncio.run(main())
