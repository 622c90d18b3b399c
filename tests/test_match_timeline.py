"""The Match card's timeline (tui/components/timeline.py): the workbook's [[match.events]] as rows of
the app's sheet, edited with its keys; every edit runs the match again through the workbook screen's
solve, and the outputs are those of a file with that edit; a wrong entry shows the match's named
refusal under its row, the other rows and the last good outputs (dimmed) kept; ctrl+n adds an event,
ctrl+d deletes one; ctrl+s writes the events back into the file, its comments kept. A real terminal
(tmux) at 140x45 and 80x24 with keys 30 to 150 ms apart."""

from __future__ import annotations

import copy
import time
from pathlib import Path

import pytest
import tomlkit

from gearhead.core import units, workbook
from gearhead.core.workbook.match import event_table
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.timeline import field_name
from tests.test_match_view import EXAMPLE, TMUX, Terminal, match_drawn, no_guarded_errors, summary  # noqa: F401
from tests.test_workbook_app import opened, settled
from tests.tui_helpers import keys_of


def file_events(path: Path) -> list[dict]:
    return [dict(t) for t in tomlkit.parse(path.read_text()).unwrap()["match"]["events"]]


def outputs_of(path: Path, events: list[dict]) -> dict:
    """The match's outputs of the workbook `path` with these [[match.events]] (a file so edited)."""
    data = tomlkit.parse(path.read_text()).unwrap()
    data["match"]["events"] = events
    book = workbook.from_text(tomlkit.dumps(data), str(path), path.parent)
    return workbook.solve(book).match.outputs


async def open_timeline(pilot, app):
    screen = await opened(pilot, app)
    await settled(pilot, screen)
    await pilot.press("ctrl+t")
    view = screen.match_view
    await match_drawn(pilot, view)
    await pilot.press("enter")  # the Match card's Enter: into the timeline
    await pilot.pause()
    assert app.focused is view.sheet
    return screen, view


async def edited(pilot, screen, view):
    await settled(pilot, screen)
    await pilot.pause(0.05)


async def test_editing_an_events_time_gives_the_match_of_a_file_with_that_time():
    events = file_events(EXAMPLE)
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE))
    async with app.run_test(size=(140, 45)) as pilot:
        screen, view = await open_timeline(pilot, app)
        before = dict(view.match.outputs)
        assert view.sheet.current_stop.field.name == field_name(1, "at")
        started = time.perf_counter()
        await pilot.press(*keys_of("2.5"), "enter")
        await edited(pilot, screen, view)
        took = await match_drawn(pilot, view)
        print(f"typed 2.5 s + Enter to the outputs and charts redrawn: {time.perf_counter() - started:.3f} s")
        assert view.tables[0]["at"] == "2.5" and event_table(view.tables[0])["at"] == "2.5 s"
        expected = outputs_of(EXAMPLE, [{**events[0], "at": "2.5 s"}, *events[1:]])
        assert view.match.outputs == expected != before
        assert f"{units.format_number(expected['min_bus_voltage'])} V" in summary(view)
        assert str(view.status.render()).startswith("✓ the match")
        assert took >= 0
        # the sheet shows what the model ran: the workbook's match holds these events
        assert [e.at for e in view.match.spec.events][:1] == [2.5]


async def test_a_bad_card_name_shows_the_named_refusal_and_keeps_the_rows_and_last_outputs():
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE))
    async with app.run_test(size=(140, 45)) as pilot:
        screen, view = await open_timeline(pilot, app)
        good = summary(view)
        tables = copy.deepcopy(view.tables)
        assert view.sheet.move_to_field(field_name(2, "card"))
        await pilot.press(*keys_of("lfit"), "enter")
        await edited(pilot, screen, view)
        status = str(view.status.render())
        assert "match.events[2].card: 'lfit' is not a card (cards: " in status, status
        assert view.sheet.errors[field_name(2, "card")].startswith(
            "match.events[2].card: 'lfit' is not a card"
        )
        assert view.tables == [*tables[:1], {**tables[1], "card": "lfit"}, *tables[2:]]  # nothing lost
        assert summary(view) == good  # the last good outputs stay, dimmed
        assert "dimmed" in status
        # fixed: the refusal goes, the match runs again
        assert view.sheet.move_to_field(field_name(2, "card"))
        await pilot.press(*keys_of(tables[1]["card"]), "enter")
        await edited(pilot, screen, view)
        await match_drawn(pilot, view)
        assert view.sheet.errors == {} and str(view.status.render()).startswith("✓ the match")
        assert summary(view) == good


async def test_ctrl_n_adds_an_event_and_ctrl_d_deletes_one():
    events = file_events(EXAMPLE)
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE))
    async with app.run_test(size=(140, 45)) as pilot:
        screen, view = await open_timeline(pilot, app)
        assert view.sheet.move_to_field(field_name(2, "card"))
        await pilot.press("ctrl+n")  # a copy of event 2's time and card, at the end
        await pilot.pause()
        n = len(events) + 1
        assert len(view.tables) == n and view.sheet.current_stop.field.name == field_name(n, "at")
        await pilot.press(*keys_of("100"), "enter")
        await edited(pilot, screen, view)
        await match_drawn(pilot, view)
        added = {"at": "100 s", "card": events[1]["card"]}
        assert view.event_tables()[-1] == added
        assert view.match.outputs == outputs_of(EXAMPLE, [*events, added])
        assert f"Event {n} at" in [f.label for f in view.sheet.calculator.fields]
        # delete event 1: the others keep their values, numbered from 1 again
        assert view.sheet.move_to_field(field_name(1, "card"))
        await pilot.press("ctrl+d")
        await edited(pilot, screen, view)
        await match_drawn(pilot, view)
        assert view.event_tables() == [event_table(e) for e in events[1:]] + [added]
        assert view.match.outputs == outputs_of(EXAMPLE, [*events[1:], added])
        assert screen.unsaved_changes() == 1


def cell_text(view, index: int, key: str) -> str:
    """The value cell of event `index`'s `key` as the timeline draws it."""
    sheet = view.sheet
    return sheet.value_text(next(s for s in sheet.stops if s.field.name == field_name(index, key)))


def drawn_line(view, index: int, key: str) -> str:
    """The sheet's line of that cell, as rendered (label, value)."""
    sheet = view.sheet
    stop = next(i for i, s in enumerate(sheet.stops) if s.field.name == field_name(index, key))
    sheet.move_to(stop)  # in sight
    y = sheet._first_line[stop] - sheet.scroll_offset.y
    return "".join(seg.text for seg in sheet.render_line(y))


async def test_a_left_out_action_or_count_shows_what_the_match_runs():
    # the action cell was blank for the default action: a reader of the timeline could not tell
    # what an event without `action` does (a sprint's, an elevator's move; a flywheel's spin_up)
    events = file_events(EXAMPLE)
    assert any("action" not in e for e in events) and any("count" not in e for e in events)
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE))
    async with app.run_test(size=(140, 45)) as pilot:
        screen, view = await open_timeline(pilot, app)
        ran = view.match.spec.events  # the match as run: each event's action and count
        assert len(ran) == len(events)
        for i, (e, ev) in enumerate(zip(events, ran, strict=True), start=1):
            action, count = cell_text(view, i, "action"), cell_text(view, i, "count")
            if "action" in e:
                assert action == e["action"]
            else:
                assert action == f"{ev.action} (default)", (i, action)
            if "count" in e:
                assert count == str(e["count"])
            else:
                assert "every" not in e and ev.count == 1 and count == "1 (default)", (i, count)
        plain = next(i for i, e in enumerate(events, 1) if "action" not in e)
        assert "move (default)" in drawn_line(view, plain, "action")
        # a flywheel's default is spin_up: its action left out, the cell says so, and the match runs it
        shot = next(i for i, e in enumerate(events, 1) if e["card"] == "shooter" and "every" not in e)
        view._take_entry(field_name(shot, "action"), "")
        await edited(pilot, screen, view)
        await match_drawn(pilot, view)
        assert cell_text(view, shot, "action") == "spin_up (default)"
        assert view.match.spec.events[shot - 1].action == "spin_up"
        assert "spin_up (default)" in drawn_line(view, shot, "action")
        # the card changed: its default follows (the row redrawn)
        view._take_entry(field_name(shot, "card"), "lift")
        await edited(pilot, screen, view)
        assert cell_text(view, shot, "action") == "move (default)"
        assert "move (default)" in drawn_line(view, shot, "action")
        # an `every` without count repeats to the end of the match
        view._take_entry(field_name(shot, "every"), "30")
        await edited(pilot, screen, view)
        assert cell_text(view, shot, "count") == "to the end (default)"
        ev = view.match.spec.events[shot - 1]
        assert ev.every == 30.0 and ev.at + (ev.count - 1) * 30.0 <= view.match.spec.values["length"]
        # a card that is not one: no default to show (the refusal names the card)
        view._take_entry(field_name(shot, "card"), "nothing")
        await edited(pilot, screen, view)
        assert cell_text(view, shot, "action") == ""
        # typed over, the cell shows what was typed, not the default
        view._take_entry(field_name(shot, "action"), "stop")
        assert cell_text(view, shot, "action") == "stop"


COMMENTED = "# my robot's match, with my notes\n"


async def test_ctrl_s_writes_the_events_back_keeping_the_comments(tmp_path):
    path = tmp_path / "robot.toml"
    # the first event of the second card the match moves gets a comment (the example's events change)
    card = next(e["card"] for e in file_events(EXAMPLE) if e["card"] != file_events(EXAMPLE)[0]["card"])
    text = EXAMPLE.read_text().replace("[match]", COMMENTED + "[match]")
    line = f'card = "{card}"\n'
    assert text.count(line) >= 1 and text.index(line) > text.index("[[match.events]]")
    text = text.replace(line, f'card = "{card}"                            # the arm event\n', 1)
    path.write_text(text)
    comments = [line.split("#", 1)[1] for line in text.splitlines() if "#" in line]
    events = file_events(path)
    arm = next(i for i, e in enumerate(events, 1) if e["card"] == card)
    gone = next(i for i in range(len(events), 0, -1) if i != arm)  # an event deleted, its comment with it
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    async with app.run_test(size=(140, 45)) as pilot:
        screen, view = await open_timeline(pilot, app)
        assert view.sheet.move_to_field(field_name(arm, "at"))
        await pilot.press(*keys_of("4"), "enter")
        assert view.sheet.move_to_field(field_name(gone, "at"))
        await pilot.press("ctrl+d")
        await pilot.press("ctrl+n")
        await pilot.press(*keys_of("120"), "enter")
        await edited(pilot, screen, view)
        assert screen.unsaved_changes() == 1
        shown = view.event_tables()
        await pilot.press("ctrl+s")
        await pilot.pause()
        assert screen.unsaved_changes() == 0
    saved = path.read_text()
    assert file_events(path) == shown
    assert [e.at for e in workbook.load(path).match.events] == [float(e["at"].split()[0]) for e in shown]
    kept = [c for c in comments if c in saved]
    lost = [c for c in comments if c not in saved]
    assert "# the arm event" in saved and COMMENTED in saved
    assert '\n\n[[match.events]]\nat = "120 s"\n' in saved  # the added event laid out as the others
    # only the deleted event's own comment may go (its header's)
    gone_text = text.split("[[match.events]]")[gone]
    assert all(c in gone_text for c in lost), lost
    assert len(kept) >= len(comments) - 1
    before = workbook.solve(workbook.load(path)).match.outputs
    assert before == outputs_of(path, shown)


# ---- the real terminal ---------------------------------------------------------------------


@pytest.mark.parametrize("size", [(140, 45), (80, 24)])
def test_editing_a_cell_in_a_real_terminal(tmp_path, size):
    if TMUX is None:
        pytest.skip("tmux is not installed (.ci/run installs it)")
    events = file_events(EXAMPLE)
    expected = outputs_of(EXAMPLE, [{**events[0], "at": "2.5 s"}, *events[1:]])
    lowest = f"{units.format_number(expected['min_bus_voltage'])} V"
    term = Terminal(tmp_path, size)
    try:
        term.wait_for(lambda s: "requirements hold" in s, "the workbook solved (its match too)")
        term.keys("C-t", gap=0.15)
        term.wait_for(lambda s: "Event 1 at" in s, "ctrl+t: the Match card and its timeline")
        term.keys("Enter", gap=0.1)  # into the timeline
        for gap in (0.03, 0.15, 0.08):  # the same cell typed over, keys 30 to 150 ms apart
            term.keys("2", ".", "5", gap=gap)
            term.keys("Enter", "Up", gap=gap)
        term.keys("PageUp", gap=0.1)
        started = time.monotonic()
        screen = term.wait_for(lambda s: lowest in s and "✓ the match" in s, f"the edited match ({lowest})")
        print(f"{size}: outputs of the edit on screen {time.monotonic() - started:.2f} s after the last key")
        assert "Traceback" not in screen and term.alive(), screen
        assert all(len(line) <= size[0] for line in screen.splitlines())
        term.keys("C-q", gap=0.3)  # unsaved: the leave dialog asks; discard
        term.wait_for(lambda s: "Discard" in s or not term.alive(), "ctrl+q: the leave question")
        if term.alive():
            term.keys("d", gap=0.3)
    finally:
        term.close()


HOSTILE = {
    "at": ["-1", "1e999", "nan", "abc", "200", "", "2 kg"],
    "card": ["", "main", "air", "x" * 500, "lift\nlift"],
    "action": ["jump", "spin_up"],
    "every": ["0", "-5 s", "1e-300"],
    "count": ["0", "1e999", "2.5", '"3"', "[1,", "9999"],
}


async def test_hostile_entries_in_the_timeline_are_named_never_a_traceback():
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(EXAMPLE))
    async with app.run_test(size=(80, 24)) as pilot:
        screen, view = await open_timeline(pilot, app)
        good = summary(view)
        first = dict(view.tables[0])
        for key, entries in HOSTILE.items():
            for text in entries:
                view._take_entry(field_name(1, key), text)  # as typed (or pasted) in the cell
                await edited(pilot, screen, view)
                status = str(view.status.render())
                assert "Traceback" not in status and "internal error" not in status, (key, text, status)
                if (key, text) == ("every", "1e-300") and first.get("count"):  # count moves at once: queued
                    assert status.startswith("✓ the match"), status
                    continue
                assert status.startswith("✗") and "match.events" in status, (key, text, status)
                assert summary(view) == good, (key, text)
            view._take_entry(field_name(1, key), first.get(key, ""))
            await edited(pilot, screen, view)
            assert str(view.status.render()).startswith("✓ the match"), str(view.status.render())
            assert summary(view) == good
        assert view.tables[0] == {**first, **{k: first.get(k, "") for k in HOSTILE}}
