"""Work the UI skips: the key bar recomposed only when its keys change (KeyFooter), entries styled
once mounted rather than while built (StyledWhenMounted)."""

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


async def test_entries_are_styled_once_mounted_not_while_built():
    """A card's entries change CSS classes as they are constructed (compact, and Input's -valid);
    Textual re-applied the whole stylesheet to each, mounted or not (3.6 ms an entry with every
    card built). Ours skip it until mounted, and mounting styles them with every class."""
    from textual.containers import Vertical
    from textual.widgets import Input

    from gearhead.tui.components.field_input import FieldCheckbox, FieldSelect

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        styled = []
        update = app.update_styles
        app.update_styles = lambda node=None, animate=True: (styled.append(node), update(node, animate))
        entries = [
            FieldInput(value="12", compact=True),
            FieldSelect([("a", 1), ("b", 2)], value=1, allow_blank=False, compact=True),
            FieldCheckbox("flag", compact=True),
        ]
        assert styled == []
        plain = Input(value="12", compact=True)  # Textual's own: styled while being built
        assert plain in styled
        box = Vertical(id="probe")
        await app.screen.mount(box)
        await box.mount_all(entries)
        await settle(pilot)
        for entry in entries:
            assert entry.has_class("-textual-compact")
            assert entry.styles.border_top[0] in ("", "none")  # the compact rule applied
        assert entries[0].styles.height.value == 1


async def test_a_focus_move_does_not_repaint_the_whole_screen():
    """Textual's Screen repaints itself whole when focus moves; HomeScreen leaves it to the two
    widgets concerned (tests/test_keystrokes.py checks in tmux that nothing is left stale)."""
    from gearhead.tui.app import HomeScreen

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = app.screen
        assert isinstance(screen, HomeScreen)
        whole = []
        refresh = screen.refresh

        def counting(*regions, **kwargs):
            if not regions:
                whole.append(kwargs)
            return refresh(*regions, **kwargs)

        screen.refresh = counting
        for entry in ("#in-voltage", "#in-efficiency", "#in-torque"):
            app.query_one(entry).focus()
            await settle(pilot)
        assert app.focused.id == "in-torque"
        assert whole == []
