"""Screen truth: whatever keys a user types, what a card shows is its entries and their results.

Random key sequences (printable keys, Tab, shift+Tab, arrows, Space, Enter, Esc, Backspace,
F-keys and digits, ctrl+g) are posted in bursts as a terminal delivers them. After each burst
settles, for every card built: each value the sheet draws is the card's entry for that row, and
every result the list draws equals `solve()` of exactly those entries, formatted the same way
(or, when an entry is wrong, the error names that field and the results are marked stale).

Sequences come from hypothesis (seeded, derandomized): one app runs many sequences, as a user's
session does, so the cards keep what earlier sequences left (a card built, a mode changed, a
value sent). A sequence that goes wrong is printed with the seed to replay it.
"""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from textual import events

from gearhead.core.errors import InputError
from gearhead.core.sim.scene import VOLATILE
from gearhead.core.solving import solve as solve_card
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.results import FRESH, STALE
from gearhead.tui.components.sheet import GAP, LABEL_CELLS
from gearhead.tui.components.unit_text import pretty_quantity
from tests.tui_helpers import settle

TYPED = list("0123456789.-e m") + ["space"]
MOVES = ["tab", "shift+tab", "up", "down", "left", "right"]
EDITS = ["enter", "escape", "backspace", "space", "ctrl+a"]
JUMPS = ["f1", "f2", "f3", "f4", "f5", "1", "2", "3", "ctrl+g"]
KEY = st.one_of(
    st.sampled_from(TYPED), st.sampled_from(MOVES), st.sampled_from(EDITS), st.sampled_from(JUMPS)
)
BURST = st.lists(KEY, min_size=1, max_size=12)
CHARS = {"space": " ", "enter": "\r", "escape": "\x1b", "backspace": "\x7f", "tab": "\t"}


def _key(k: str) -> events.Key:
    if len(k) == 1:
        return events.Key(k, k)
    return events.Key(k, CHARS.get(k))


def check_card(tab) -> None:
    """The card's screen against its entries and an independent solve of them."""
    sheet, calc = tab.sheet, tab.calculator
    # the sheet draws each row's value from the entries: read back what it draws
    for y, line in enumerate(sheet.lines):
        if line.stop is None or not line.first:
            continue
        stop = sheet.stops[line.stop]
        if sheet.editing and line.stop == sheet.cursor:
            continue  # an edit shows its buffer (checked below)
        drawn = (
            sheet.render_line(y - sheet.scroll_offset.y).text
            if 0 <= y - sheet.scroll_offset.y < sheet.size.height
            else None
        )
        if drawn is not None:
            want = sheet.value_text(stop)
            width = sheet.value_cells(stop)
            cell = drawn[1 + LABEL_CELLS + GAP + 1 : 1 + LABEL_CELLS + GAP + width].rstrip()
            same = cell == want or (cell.endswith("…") and want.startswith(cell[:-1]))
            assert same, (stop.field.name, want, drawn)
    if sheet.editing:
        name = sheet.current_field.name
        assert tab.entries[name] in (sheet.buffer, sheet._before_edit), (
            name,
            tab.entries[name],
            sheet.buffer,
        )
    # the results: those of exactly these entries
    try:  # the card's own solve (the one the CLI makes)
        solution = solve_card(calc, tab.entries, tab.display_units, tab.unit_system).solution
    except InputError as exc:
        assert tab.error is not None and tab.error.field == exc.field, (exc, tab.error)
        assert tab.results.state == STALE or tab.solution is None
        if exc.field in {f.name for f in sheet.shown_fields}:
            assert sheet.errors.get(exc.field) == exc.message
        return
    assert tab.error is None, tab.error
    assert tab.results.state == FRESH
    shown = tab.shown_values()
    assert list(shown) == list(solution.outputs), "the rows shown are not this solution's"
    for name, value in solution.outputs.items():
        if name in VOLATILE or name == "error_estimate":
            continue
        assert shown[name] == pretty_quantity(value.text), (name, shown[name], value.text)


async def check_toggle_keeps_cursor(pilot) -> None:
    """Where the burst left the cursor on a flag or a yes/no row: Space leaves the cursor on that
    very stop (field and flag), whatever rows the toggle shows or hides, and a second Space
    restores the entries (issue 40: the cursor jumped to the field's first flag)."""
    app = pilot.app
    if app.screen is not app.home or not app.card_ready(app.current_calculator):
        return
    tab = app.current_tab
    sheet = tab.sheet
    stop = sheet.current_stop
    if (
        stop is None
        or sheet.editing
        or app.focused is not sheet
        or stop.shape not in ("checkbox", "checkboxes")
    ):
        return
    place = (stop.field.name, stop.option)
    before = dict(tab.entries)
    for _ in range(2):
        app.post_message(_key("space"))
        await settle(pilot)
        here = sheet.current_stop
        assert (here.field.name, here.option) == place
    assert {k: str(v) for k, v in tab.entries.items() if k != place[0]} == {
        k: str(v) for k, v in before.items() if k != place[0]
    }


@pytest.mark.parametrize("start", ["motor", "elevator", "beam"])
def test_what_a_card_shows_is_its_entries_and_their_results(start):
    import asyncio

    runs = []

    async def session(bursts):
        app = GearheadApp(blink=False, initial=start, hide_timings=True)
        async with app.run_test(size=(140, 45)) as pilot:
            await settle(pilot)
            app.current_tab.sheet.focus()
            for keys in bursts:
                for k in keys:
                    app.post_message(_key(k))
                await settle(pilot)
                while app.screen is not app.home:  # a choice list left open
                    await pilot.press("escape")
                    await settle(pilot)
                await settle(pilot)
                for tab in list(app._cards.values()):
                    if app.card_ready(tab.calculator.id):
                        check_card(tab)
                await check_toggle_keeps_cursor(pilot)
            runs.append(len(bursts))

    @settings(
        max_examples=4,
        deadline=None,
        derandomize=True,
        phases=[Phase.explicit, Phase.generate],  # no shrinking: each example is a whole app session
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )
    @given(st.lists(BURST, min_size=10, max_size=25))
    def sequences(bursts):
        asyncio.run(session(bursts))

    sequences()
    assert sum(runs) >= 40  # the sequences did run
