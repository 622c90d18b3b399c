"""Trust in the card's keys (issue 40): what a key does is what the user sees it do.

- Space (or Enter) on a flag or a yes/no row leaves the cursor on that row, whatever rows the
  toggle shows or hides (it jumped to the first flag of the field: a second Space then turned
  gravity off, silently).
"""

from __future__ import annotations

import pytest

from gearhead.core.registry import calculators, get
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.sheet import flag_names
from tests.tui_helpers import card, settle

TOGGLED = [
    cid
    for cid in calculators()
    if any(f.kind.widget(f).shape in ("checkbox", "checkboxes") for f in get(cid).fields)
]


@pytest.mark.parametrize(
    "calc_id,key",
    [(c, "space") for c in TOGGLED] + [(c, "enter") for c in ("motor", "elevator", "sprint")],
)
async def test_a_toggle_leaves_the_cursor_on_its_row(calc_id, key):
    app = GearheadApp(blink=False, hide_timings=True, initial=calc_id)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = card(app)
        sheet = tab.sheet
        sheet.focus()
        await pilot.pause()
        checked = 0
        i = 0
        while i < len(sheet.stops):
            stop = sheet.stops[i]
            if stop.shape not in ("checkbox", "checkboxes"):
                i += 1
                continue
            place = (stop.field.name, stop.option)
            before = dict(tab.entries)
            sheet.move_to(i)
            for press in (1, 2):
                await pilot.press(key)
                await settle(pilot)
                here = sheet.current_stop
                assert (here.field.name, here.option) == place, (calc_id, place, press)
                assert app.focused is sheet
            # two toggles: as it was (a flags field's order may be the declaration's now)
            assert {k: flag_names(v) if k == place[0] else v for k, v in tab.entries.items()} == {
                k: flag_names(v) if k == place[0] else v for k, v in before.items()
            }, (calc_id, place)
            checked += 1
            i = sheet.cursor + 1
        # a card whose flags are all hidden by its mode (chain/belt) has none to check
        assert checked or not any(s.shape in ("checkbox", "checkboxes") for s in sheet.stops)


async def test_the_load_dialog_types_into_its_path_box_and_enter_loads_only_what_is_shown(tmp_path):
    """ctrl+o: typing goes to the path box (the list had the keys: a typed path vanished into
    its type-ahead, and Enter loaded the highlighted preset over the entries)."""
    from textual.widgets import Input, OptionList, Static

    preset = tmp_path / "p.toml"
    preset.write_text('calculator = "gear_ratio"\nname = "typed"\n[inputs]\nload = "44 lbf"\n')
    app = GearheadApp(blink=False, hide_timings=True, initial="gear_ratio")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = card(app)
        before = dict(tab.entries)
        await pilot.press("ctrl+o")
        await settle(pilot)
        path = app.screen.query_one("#preset-path", Input)
        assert app.screen.focused is path
        await pilot.press("enter")  # nothing typed: nothing loaded, a message says what to do
        await settle(pilot)
        assert app.screen is not app.home and tab.entries == before
        assert "path" in str(app.screen.query_one("#load-error", Static).render())
        for ch in str(preset):
            await pilot.press(
                ch if ch.isalnum() else {"/": "slash", ".": "full_stop", "_": "underscore", "-": "minus"}[ch]
            )
        assert path.value == str(preset)
        await pilot.press("enter")
        await settle(pilot)
        assert app.screen is app.home
        assert tab.entries["load"] == "44 lbf"
        # ↓ reaches the list; Enter there loads the preset highlighted
        await pilot.press("ctrl+o")
        await settle(pilot)
        await pilot.press("down")
        assert app.screen.focused is app.screen.query_one("#preset-list", OptionList)


def _line_text(widget, y: int = 0) -> str:
    return "".join(segment.text for segment in widget.render_line(y))


async def test_tick_boxes_read_x_or_blank_without_colour():
    """Save's Overwrite and the sweep's log and outputs: `[x]` on, `[ ]` off (Textual's `▐X▌` is
    the same text either way: under NO_COLOR a tick could not be seen)."""
    from textual.widgets import Checkbox, SelectionList

    app = GearheadApp(blink=False, hide_timings=True, initial="motor")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+s")
        await settle(pilot)
        box = app.screen.query_one("#overwrite", Checkbox)
        assert "[ ] Overwrite" in str(box.render())
        box.value = True
        await pilot.pause()
        assert "[x] Overwrite" in str(box.render())
        await pilot.press("escape")
        await settle(pilot)
        card(app).sheet.move_to_field("voltage")
        await pilot.press("ctrl+w")
        await settle(pilot)
        log = app.screen.query_one("#sweep-log", Checkbox)
        assert "[ ]" in str(log.render())
        outputs = app.screen.query_one("#sweep-outputs", SelectionList)
        lines = [_line_text(outputs, y) for y in range(min(outputs.option_count, outputs.size.height))]
        picked = {outputs.get_option_at_index(i).value for i in range(len(lines))} & set(outputs.selected)
        assert lines and all(line.startswith(("[x]", "[ ]")) for line in lines), lines
        for i, line in enumerate(lines):
            assert line.startswith("[x]") == (outputs.get_option_at_index(i).value in picked), line
