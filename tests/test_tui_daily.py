"""Daily use: the load and save dialogs, a result in sight at 80x24, one-line status."""

from __future__ import annotations

import pytest
from textual.widgets import Input, OptionList, Static

from gearhead.core import presets
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
from tests.tui_helpers import settle, type_into


def text_of(widget: Static) -> str:
    return str(widget.render())


async def test_load_dialog_previews_the_highlighted_preset():
    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=(120, 40)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+o")
        await settle(pilot)
        listing = app.screen.query_one("#preset-list", OptionList)
        found = presets.listing("motor")
        listing.highlighted = 1
        await pilot.pause()
        shown = text_of(app.screen.query_one("#preset-preview", Static))
        assert found[1].description and found[1].description in shown
        # inputs by their labels on the form, not the internal names
        assert "Motors " in shown and "motor_count" not in shown


async def test_a_path_with_a_nul_byte_is_a_message_not_a_crash():
    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=(120, 40)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+o")
        await settle(pilot)
        entry = app.screen.query_one("#preset-path", Input)
        entry.value = "/tmp/a\x00b.toml"
        entry.focus()
        await pilot.press("enter")
        await settle(pilot)
        error = text_of(app.screen.query_one("#load-error", Static))
        assert "NUL" in error
        assert app.screen.query("#preset-path")  # the dialog is still up, the app too


async def test_browse_opens_the_file_picker_and_loads_the_file_chosen(tmp_path):
    from textual_fspicker import FileOpen

    text = presets.load(presets.listing("motor")[0].path)
    target = tmp_path / "mine.toml"
    target.write_text((presets.listing("motor")[0].path).read_text())
    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=(120, 40)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+o")
        await settle(pilot)
        await pilot.click("#browse")
        await settle(pilot)
        assert isinstance(app.screen, FileOpen)
        app.screen.dismiss(target)  # what the picker returns on Open
        await settle(pilot)
        assert app.current_tab.preset_meta[0] == text.name


async def test_save_dialog_proposes_the_file_name_and_warns_before_overwriting():
    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=(120, 40)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+s")
        await settle(pilot)
        await pilot.press(*"Arm 2 NEO")
        await pilot.pause()
        target = text_of(app.screen.query_one("#save-target", Static))
        assert target.replace("\n", "").endswith("arm_2_neo.toml") and "exists" not in target
        await pilot.press("enter")
        await settle(pilot)
        saved = presets.user_dir() / "motor" / "arm_2_neo.toml"
        assert saved.exists()
        before = saved.read_text()
        await pilot.press("ctrl+s")
        await settle(pilot)
        await pilot.press(*"Arm 2 NEO")
        await pilot.pause()
        assert "exists" in text_of(app.screen.query_one("#save-target", Static))
        await pilot.press("enter")  # without ticking Overwrite: refused, file unchanged
        await settle(pilot)
        assert "exists" in text_of(app.screen.query_one("#save-error", Static))
        assert saved.read_text() == before


async def test_at_80x24_a_result_stays_in_sight_while_typing():
    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        await type_into(pilot, "load", "60 lbf", commit=False)  # still editing
        assert tab.sheet.editing and tab.entries["load"] == "60 lbf"
        glance = tab.query_one(".glance", Static)
        first = next(iter(tab.solution.outputs))
        assert glance.display and glance.region.height == 1
        sheet = tab.sheet
        row_y = sheet.region.y + sheet._first_line[sheet.cursor] - sheet.scroll_offset.y
        assert sheet.region.y <= row_y < sheet.region.bottom  # the row typed in is on screen
        assert glance.region.y < app.size.height - 1 and row_y < app.size.height  # both on screen
        assert tab.calculator.output(first).label in text_of(glance)
        assert tab.solution.outputs[first].text.split()[0] in text_of(glance)
        await type_into(pilot, "load", "3 kg", commit=False)
        assert "✗" in text_of(glance) and "Load" in text_of(glance)


async def test_a_card_built_wide_shows_the_glance_line_once_the_terminal_narrows():
    """The glance line is composed only on a narrow screen (a card built wide has none: a widget
    fewer on its first visit); narrowed below 120 columns, the card shown and a card built wide
    while hidden both show it, with their key result, and widened it goes."""
    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        hidden = await app.card("ratio_distance")  # built wide, not shown
        await settle(pilot)
        assert not tab.query(".glance") and not hidden.query(".glance")
        await pilot.resize_terminal(80, 24)
        await settle(pilot)
        for card in (tab, None):
            if card is None:  # the card built while wide, shown now
                app.show_calculator("ratio_distance")
                await settle(pilot)
                card = hidden
            glance = card.query_one(".glance", Static)
            first = next(iter(card.solution.outputs))
            assert glance.display and glance.region.height == 1 and glance.region.y == card.region.y
            assert card.solution.outputs[first].text.split()[0] in text_of(glance)
        await pilot.resize_terminal(140, 45)
        await settle(pilot)
        assert not glance.display and glance.region.height == 0


async def test_status_is_one_line_whatever_the_message():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        tab._take_entry("load", "3 kg " + "x" * 2000)
        await settle(pilot)
        assert tab.error is not None and "load" in tab.sheet.errors
        assert tab.query_one(".status", Static).region.height == 1
        assert 1 <= len([line for line in tab.sheet.lines if line.stop is None]) <= 2  # the error line


async def test_status_shows_the_whole_solve_time(monkeypatch):
    """An optimiser's search takes a second while its 'Wall time' result is one throw's: the
    status line gives the time of the whole solve."""
    import re
    import time

    import gearhead.core.model

    real = gearhead.core.model.solve

    def slow_solve(*args, **kwargs):
        time.sleep(0.6)
        return real(*args, **kwargs)

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        monkeypatch.setattr(gearhead.core.model, "solve", slow_solve)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        tab._take_entry("load", "31 lbf")
        await settle(pilot)
        status = text_of(tab.query_one(".status", Static))
        found = re.search(r"solved in ([\d.]+) (ms|s)", status)
        assert found, status
        seconds = float(found[1]) / (1000 if found[2] == "ms" else 1)
        assert seconds >= 0.6


async def test_f_key_then_digit_typed_at_once_opens_the_calculator():
    """F5 then 3 in one read (a fast typist, a loaded machine): the strip of an area not yet
    visited has no focus when the digit arrives; the digit still picks the trebuchet."""
    from textual import events

    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        app.post_message(events.Key("f5", None))  # in one burst, as a terminal delivers them
        app.post_message(events.Key("3", "3"))
        await settle(pilot)
        assert app.current_calculator == "trebuchet"
        assert app.query_one("#calc-trebuchet", CalculatorTab).solution is not None


@pytest.mark.parametrize("character", ["²", "³", "①", "٣"])
async def test_a_digit_like_character_on_a_strip_is_ignored(character):
    """'²' passes str.isdigit() and int() refuses it: on a tab strip it killed the app. After an
    F-key it picks nothing (it ends the chord and goes to the card); on a strip focused by a click
    it is ignored; a real digit after an F-key still picks."""
    from textual import events

    from gearhead.tui.components.tab_strip import TabStrip

    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        app.post_message(events.Key("f1", None))
        app.post_message(events.Key(character, character))
        await settle(pilot)
        assert app.current_calculator == "motor"
        app.home.set_focus(app.query_one("#calcs-gearing", TabStrip))
        app.post_message(events.Key(character, character))
        await settle(pilot)
        assert app.current_calculator == "motor"
        app.post_message(events.Key("f1", None))
        app.post_message(events.Key("2", "2"))
        await settle(pilot)
        assert app.current_calculator == "gear_ratio"


async def test_an_f_key_under_a_dialog_leaves_the_card_alone():
    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+o")
        await pilot.pause()
        dialog = app.screen
        assert dialog is not app.home
        await pilot.press("f3")
        await pilot.pause()
        assert app.screen is dialog and app.current_calculator == "motor"
