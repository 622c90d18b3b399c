"""The key bar is recomposed only when the keys it shows change (KeyFooter)."""

from __future__ import annotations

from textual.widgets._footer import FooterKey

from gearhead.tui.app import GearheadApp
from gearhead.tui.components.field_input import FieldInput
from gearhead.tui.components.footer import KeyFooter
from tests.tui_helpers import settle

SIZE = (140, 45)


def keys_shown(app) -> list[str]:
    return [key.description for key in app.query(FooterKey)]


async def test_moving_between_fields_keeps_the_footer_and_a_card_switch_updates_it():
    composed = []
    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        footer = app.query_one(KeyFooter)
        original = footer.recompose

        async def counting():
            composed.append(1)
            await original()

        footer.recompose = counting
        app.query_one("#in-voltage").focus()
        await settle(pilot)
        before = keys_shown(app)
        composed.clear()
        for _ in range(2):  # Tab from entry to entry: Textual refreshes the bindings each time
            await pilot.press("tab")
            await settle(pilot)
            assert isinstance(app.focused, FieldInput)
        assert composed == [] and keys_shown(app) == before

        # projectile has no "Send to…" but an accuracy setting: the bar follows
        assert "Accuracy" not in before
        app.show_calculator("projectile")
        await settle(pilot)
        assert composed and "Accuracy" in keys_shown(app)
