"""A workbook in the app (tui/components/workbook_screen.py): its cards as the cards they are,
linked fields read-only with their reference shown, a change flowing to every dependent card, and
the Robot card's requirements live. (tests/test_keystrokes.py-style tmux check: see the commit.)"""

from pathlib import Path

import pytest
from textual.widgets import Input

from gearhead.core import workbook
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.workbook_screen import LINK_MARK, WorkbookScreen
from tests.tui_helpers import keys_of, started

LBF = 4.4482216152605

TEXT = """
name = "pilot robot"

[variables]
mass = "10 lb"
motor_name = "NEO"

[cards.lift]
calculator = "gear_ratio"
inputs = { load = "= mass * 9.80665 m/s**2", radius = "0.75 in", motor = "= motor_name" }

[cards.stage]
calculator = "gear_ratio"
inputs = { mode = "ratio", ratio = "= lift.ratio * 2" }

[[requirements]]
name = "Lift ratio"
check = "lift.ratio < 1"
"""


async def settled(pilot, screen: WorkbookScreen) -> None:
    """Until the workbook and every card on it have solved what is on screen."""
    for _ in range(400):
        await pilot.pause(0.02)
        if screen.outcome is not None and not screen.busy and not any(t.busy for t in screen.cards.values()):
            await pilot.pause()
            if not screen.busy:
                return
    raise AssertionError("the workbook never settled")


async def opened(pilot, app) -> WorkbookScreen:
    """The workbook's screen, once the app has started and pushed it."""
    await started(pilot)
    for _ in range(200):
        if isinstance(app.screen, WorkbookScreen):
            break
        await pilot.pause()
    assert isinstance(app.screen, WorkbookScreen)
    return app.screen


def requirement_line(screen: WorkbookScreen) -> str:
    return str(screen.robot.requirements.render()).splitlines()[0]


async def test_a_variable_change_flows_to_every_card_and_the_requirements():
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(TEXT, "pilot.toml"))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        lift, stage = screen.cards["lift"], screen.cards["stage"]
        assert lift.solution.inputs["load"].value == approx(10 * LBF)
        assert lift.solution.outputs["ratio"].value < 1  # holds at 10 lb...
        assert requirement_line(screen).startswith("✔ Lift ratio")
        # the linked rows carry their reference in the label; the others do not
        assert lift.calculator.field("load").label.endswith(f"{LINK_MARK} = mass * 9.80665 m/s**2")
        assert LINK_MARK not in lift.calculator.field("radius").label
        # the user types a new mass on the Robot card, as on any sheet
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("mass")
        await pilot.press(*keys_of("40 lb"), "enter")
        await settled(pilot, screen)
        assert lift.solution.inputs["load"].value == approx(40 * LBF)
        lift_ratio = lift.solution.outputs["ratio"].value
        assert stage.solution.inputs["ratio"].value == approx(2 * lift_ratio)
        # and each card shows exactly what a solve of those entries gives
        direct = workbook.solve(workbook.from_text(TEXT.replace('"10 lb"', '"40 lb"'), "pilot.toml"))
        assert lift_ratio == approx(direct.cards["lift"].solution.outputs["ratio"].value)
        assert lift_ratio > 1  # ...and fails at 40 lb, live
        assert requirement_line(screen).startswith("✘ Lift ratio")


async def test_a_linked_field_is_read_only_and_a_card_edit_flows_on():
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(TEXT, "pilot.toml"))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        await pilot.press("ctrl+right")  # to the lift card
        await pilot.pause()
        lift, stage = screen.cards["lift"], screen.cards["stage"]
        assert lift.sheet.has_focus
        before = lift.entries["load"]
        assert lift.sheet.move_to_field("load")
        await pilot.press("9", "enter")
        await settled(pilot, screen)
        assert lift.entries["load"] == before  # refused, with a notification
        assert not lift.sheet.editing  # Enter on a linked row does not open it either
        assert lift.sheet.move_to_field("radius")
        await pilot.press("2", "enter")
        await settled(pilot, screen)
        assert lift.solution.inputs["radius"].value == approx(2 * 0.0254)
        assert stage.solution.inputs["ratio"].value == approx(2 * lift.solution.outputs["ratio"].value)
        await pilot.press("escape")  # back to the calculator cards
        await pilot.pause()
        assert not isinstance(app.screen, WorkbookScreen)


async def test_ctrl_o_opens_a_workbook_file(tmp_path: Path):
    path = tmp_path / "robot.toml"
    path.write_text(TEXT, encoding="utf-8")
    app = GearheadApp(blink=False, hide_timings=True)
    async with app.run_test(size=(140, 40)) as pilot:
        await started(pilot)
        await pilot.press("ctrl+o")
        await pilot.pause()
        entry = app.screen.query_one("#preset-path", Input)
        entry.focus()
        entry.value = str(path)
        await pilot.press("enter")
        for _ in range(200):
            if isinstance(app.screen, WorkbookScreen):
                break
            await pilot.pause()
        assert isinstance(app.screen, WorkbookScreen)
        await settled(pilot, app.screen)
        assert app.screen.book.name == "pilot robot"


def approx(x):
    return pytest.approx(x, rel=1e-9)


async def test_a_text_variable_is_a_choice_on_the_robot_card():
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(TEXT, "pilot.toml"))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        lift = screen.cards["lift"]
        assert lift.solution.inputs["motor"].value == "NEO"
        field = screen.robot.calculator.field("motor_name")
        assert "Kraken X60" in field.choices  # the gear-ratio card's own motor list
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("motor_name")
        await pilot.press("k")  # letters on a choice row pick the next that begins with them
        await settled(pilot, screen)
        chosen = screen.robot.entries["motor_name"]
        assert chosen.lower().startswith("k") and chosen != "NEO"
        assert lift.solution.inputs["motor"].value == chosen


async def test_a_bare_number_on_the_robot_card_is_in_the_unit_the_row_shows():
    """'40' typed on 'mass … lb' is 40 lb, as on any card (the workbook took it for a plain number
    and refused it: 'takes a mass; the reference gives a plain number', found in tmux)."""
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(TEXT, "pilot.toml"))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("mass")
        await pilot.press(*keys_of("40"), "enter")
        await settled(pilot, screen)
        assert screen.cards["lift"].solution.inputs["load"].value == approx(40 * LBF)
        assert requirement_line(screen).startswith("✘ Lift ratio")


async def test_ctrl_s_writes_the_changes_into_the_file_keeping_its_comments(tmp_path: Path):
    """A variable typed on the Robot card and an input typed on a card, saved with ctrl+s: the file
    holds both, its comments and links as they were, and reads back to the same solve."""
    path = tmp_path / "robot.toml"
    commented = TEXT.replace('mass = "10 lb"', 'mass = "10 lb"  # the carriage, weighed').replace(
        "[cards.lift]", "# the lift stage\n[cards.lift]"
    )
    path.write_text(commented, encoding="utf-8")
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("mass")
        await pilot.press(*keys_of("40"), "enter")
        await settled(pilot, screen)
        lift = screen.cards["lift"]
        lift.sheet.focus()
        assert lift.sheet.move_to_field("radius")
        await pilot.press(*keys_of("1.5"), "enter")
        await settled(pilot, screen)
        want = lift.solution.outputs["ratio"].value
        await pilot.press("ctrl+s")
        await pilot.pause()
    text = path.read_text(encoding="utf-8")
    assert "# the carriage, weighed" in text and "# the lift stage" in text
    assert 'mass = "40 lb"' in text
    assert 'load = "= mass * 9.80665 m/s**2"' in text  # the link kept
    again = workbook.solve(workbook.load(path))
    assert again.cards["lift"].solution.outputs["ratio"].value == approx(want)
    assert again.cards["lift"].solution.inputs["radius"].value == approx(1.5 * 0.0254)


@pytest.mark.parametrize("answer", ["escape", "d", "s"])
async def test_leaving_a_workbook_with_unsaved_edits_asks(tmp_path: Path, answer):
    """Esc on an edited workbook asks: Esc stays (the edit kept), d discards and closes, s saves
    and closes (Esc dropped every edit with no question). Unedited, Esc closes at once."""
    from gearhead.tui.components.leave_screen import LeaveScreen

    path = tmp_path / "robot.toml"
    path.write_text(TEXT, encoding="utf-8")
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("mass")
        await pilot.press(*keys_of("40"), "enter")
        await settled(pilot, screen)
        await pilot.press("escape")
        await pilot.pause()
        assert isinstance(app.screen, LeaveScreen)
        await pilot.press(answer)
        await pilot.pause()
        await pilot.pause()
        if answer == "escape":
            assert app.screen is screen and screen.robot.entries["mass"] == "40"
            await pilot.press("ctrl+s")  # saved: Esc now closes without a question
            await pilot.pause()
            await pilot.press("escape")
            await pilot.pause()
        assert not isinstance(app.screen, (WorkbookScreen, LeaveScreen))
    saved = 'mass = "40 lb"' in path.read_text(encoding="utf-8")
    assert saved == (answer != "d")


async def test_at_80x24_the_robot_cards_requirements_sit_above_the_key_bar():
    """The requirements box ends above the key bar, so End on it shows the last requirement (the
    panes were as tall as their content: the last requirements fell under the key bar)."""
    from importlib.resources import files

    from gearhead.tui.components.key_bar import KeyBar

    book = workbook.load(Path(str(files("gearhead.examples") / "robot_2027.toml")))
    app = GearheadApp(blink=False, hide_timings=True, workbook=book)
    async with app.run_test(size=(80, 24)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        box = screen.query_one("#requirements-box")
        bar = screen.query_one(KeyBar)
        await pilot.pause()
        assert box.region.height >= 3
        assert box.region.bottom <= bar.region.y, (box.region, bar.region)
        assert screen.region.contains_region(box.region)


async def test_a_slow_workbook_solve_says_so_and_a_newer_one_cancels_it(monkeypatch):
    """The workbook solves in a worker: while a solve takes a moment the Robot card says the checks
    shown are those of the last entries (a match runs for seconds), and a newer request cancels
    the running one through its worker's budget."""
    import threading

    from gearhead.core.sim.integrate import Cancelled, charge

    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.from_text(TEXT, "pilot.toml"))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        release, outcomes = threading.Event(), []
        real = workbook.solve

        def slow(book):
            try:
                while not release.wait(0.005):
                    charge(0)  # as an integration does: Cancelled once a newer request came
            except Cancelled:
                outcomes.append("cancelled")
                raise
            outcomes.append("solved")
            return real(book)

        monkeypatch.setattr(workbook, "solve", slow)
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("mass")
        await pilot.press(*keys_of("20 lb"), "enter")
        await pilot.pause(0.3)
        status = str(screen.robot.status.render())
        assert status.startswith("… solving") and screen.busy
        assert screen.robot.sheet.move_to_field("mass")
        await pilot.press(*keys_of("40 lb"), "enter")  # while the first still runs
        await pilot.pause(0.1)
        release.set()
        await settled(pilot, screen)
        assert outcomes[0] == "cancelled" and outcomes[-1] == "solved", outcomes
        assert screen.cards["lift"].solution.inputs["load"].value == approx(40 * LBF)
        assert "requirements hold" in str(screen.robot.status.render())


async def test_discard_then_a_key_in_the_same_burst_still_closes_the_workbook(tmp_path: Path):
    """d (discard) and ctrl+p in one burst, as a terminal delivers them: the workbook closes, the
    calculator cards are left on screen (the close popped whatever screen was on top: the palette
    opened by ctrl+p, leaving the workbook open, its edits discarded)."""
    from textual import events

    from gearhead.tui.components.leave_screen import LeaveScreen

    path = tmp_path / "robot.toml"
    path.write_text(TEXT, encoding="utf-8")
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        screen.robot.sheet.focus()
        assert screen.robot.sheet.move_to_field("mass")
        await pilot.press(*keys_of("40"), "enter")
        await settled(pilot, screen)
        await pilot.press("escape")
        await pilot.pause()
        assert isinstance(app.screen, LeaveScreen)
        for key, char in (("d", "d"), ("ctrl+p", None)):
            app.post_message(events.Key(key, char))
        for _ in range(20):
            await pilot.pause(0.02)
        assert screen not in app.screen_stack, app.screen_stack
    assert 'mass = "40 lb"' not in path.read_text(encoding="utf-8")


async def test_a_key_right_after_ctrl_arrow_goes_to_the_card_switched_to(tmp_path: Path):
    """ctrl+→ then ↓ in one burst, as a terminal delivers them: the ↓ moves the next card's cursor,
    not the card left (ctrl+→ was a binding run once its key had bubbled up from the sheet, after
    the sheet had read the ↓; in CI's real terminal, Home after ctrl+← scrolled the old card)."""
    from textual import events

    path = tmp_path / "robot.toml"
    path.write_text(TEXT, encoding="utf-8")
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    async with app.run_test(size=(140, 40)) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        first = next(iter(screen.cards))
        robot_row = screen.robot.sheet.current_field
        card_row = screen.cards[first].sheet.current_field
        for key in ("ctrl+right", "down"):
            app.post_message(events.Key(key, None))
        for _ in range(10):
            await pilot.pause(0.02)
        assert screen.query_one("#workbook-tabs").active == f"wbtab-{first}"
        assert screen.robot.sheet.current_field == robot_row
        assert screen.cards[first].sheet.current_field != card_row
        assert app.focused is screen.cards[first].sheet
