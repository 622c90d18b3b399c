""" "Fit from log" on a workbook's card (issue 44 item 7, tui/components/workbook_screen.py and
fit_screen.py): the palette offers it for the elevator, arm or flywheel card on screen, named; the
fit runs against the card's entries as the workbook resolves them; Apply puts the fitted entries
into the card's own fields as if typed (the workbook re-checks its requirements and is unsaved;
ctrl+s writes them) and leaves a linked field as it is, the screen saying what the fit gives."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gearhead.core import units, workbook
from gearhead.tui.app import GearheadApp
from gearhead.tui.cli import main
from gearhead.tui.components.fit_screen import FitScreen
from gearhead.tui.components.workbook_screen import WorkbookScreen
from tests.test_fit_app import fit
from tests.test_fit_example import LOG
from tests.test_workbook_app import opened, settled

SIZE = (140, 45)

# the default elevator card (the example log's plant is its mechanism with a heavier carriage),
# its load linked to a variable; a card the fit does not take; a requirement the fitted friction
# breaks (the design reaches the top in 0.923 s, the mechanism as logged in about 0.95 s)
TEXT = """
name = "fit robot"

[variables]
carriage = "{carriage}"

[cards.lift]
calculator = "elevator"
inputs = {{ {lift} }}

[cards.gears]
calculator = "gear_ratio"

[[requirements]]
name = "Lift to the top"
check = "lift.time_to_goal < 0.935 s"
"""


def book_file(tmp_path: Path, carriage: str = "15 lb", lift: str = 'load_mass = "= carriage"') -> Path:
    path = tmp_path / "robot.toml"
    path.write_text(TEXT.format(carriage=carriage, lift=lift), encoding="utf-8")
    return path


async def show(pilot, screen: WorkbookScreen, card: str) -> None:
    screen.query_one("#workbook-tabs").active = f"wbtab-{card}"
    await pilot.pause()
    await settled(pilot, screen)


def fit_titles(app) -> list[str]:
    return [c.title for c in app.get_system_commands(app.screen) if "from log" in c.title]


async def open_fit(pilot, typed: str = "Fit from log") -> FitScreen:
    """ctrl+p, the command's words, Enter: as a user opens it."""
    await pilot.press("ctrl+p")
    await pilot.press(*typed)
    await pilot.pause(0.3)
    await pilot.press("enter")
    for _ in range(100):
        await pilot.pause(0.01)
        if isinstance(pilot.app.screen, FitScreen):
            return pilot.app.screen
    raise AssertionError(f"the palette's fit command opened {pilot.app.screen!r}")


def lb(text: str, kind: str = "mass") -> float:
    """An entry as SI (kg, N)."""
    return units.parse(text, "lb" if kind == "mass" else "lbf", kind, "entry")


async def test_the_palette_offers_the_fit_for_the_workbook_card_on_screen_only(tmp_path):
    # the calculator card behind the workbook is an elevator: its own fit is not offered over it
    app = GearheadApp(
        blink=False, initial="elevator", hide_timings=True, workbook=workbook.load(book_file(tmp_path))
    )
    async with app.run_test(size=SIZE) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        assert fit_titles(app) == []  # the Robot card
        await show(pilot, screen, "gears")
        assert fit_titles(app) == []
        await show(pilot, screen, "lift")
        assert fit_titles(app) == ["Fit lift from log…"]
        dialog = await open_fit(pilot)
        assert "lift (Elevator): fit from a SysId log" in str(dialog.query_one(".fit-title").render())
        await pilot.press("escape")
        await pilot.pause()
        assert app.screen is screen and screen.unsaved_changes() == 0


async def test_apply_writes_the_cards_own_fields_leaves_the_link_and_the_workbook_rechecks(tmp_path, capsys):
    path = book_file(tmp_path)
    assert (
        main(["fit", str(LOG), "--card", "elevator", "--workbook", str(path), "--name", "lift", "--json"])
        == 0
    )
    want = json.loads(capsys.readouterr().out)
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    async with app.run_test(size=SIZE) as pilot:
        screen = await opened(pilot, app)
        await show(pilot, screen, "lift")
        lift = screen.cards["lift"]
        assert str(screen.robot.requirements.render()).startswith("✔ Lift to the top")
        dialog = await open_fit(pilot)
        await fit(pilot, dialog, str(LOG))
        r = dialog.report
        assert r is not None, str(dialog.query_one("#fit-status").render())
        # the card as the CLI reads the workbook's: its design gains and fit agree
        for k, v in want["design_gains"].items():
            assert r.card.design[k] == pytest.approx(v, rel=1e-12)
        assert r.favoured == want["favoured"]
        best = r.fits[r.favoured].gains
        mass = best["kA"] * r.card.f
        friction = best["kS"] * r.card.f - r.card.loss
        # the link is not in what Apply writes; the screen says it is linked and what the fit gives
        assert set(dialog.changes) == {"friction_force", "effects"}
        diff = str(dialog.query_one("#fit-diff").render())
        note = next(line for line in diff.splitlines() if "linked" in line)
        assert "Load mass is linked (= carriage): not written; the fit gives" in note, diff
        assert lb(note.split("the fit gives ")[1]) == pytest.approx(mass, rel=1e-5)
        assert mass == pytest.approx(
            next(e["fitted"] for e in want["entries"] if e["entry"] == "moving mass"), rel=1e-12
        )
        await pilot.click("#fit-apply")
        await settled(pilot, screen)
        assert app.screen is screen
        # the sheet's fields hold the fitted values; the linked one its workbook value
        assert lb(lift.entries["friction_force"], "force") == pytest.approx(friction, rel=1e-12)
        assert "friction" in lift.entries["effects"]
        assert lb(lift.entries["load_mass"]) == pytest.approx(lb("15 lb"), rel=1e-12)
        assert lift.solution.inputs["friction_force"].value == pytest.approx(friction, rel=1e-12)
        # re-checked as after any edit: the mechanism as logged misses the requirement
        outcome = screen.outcome.cards["lift"]
        assert outcome.entries["friction_force"] == lift.own_inputs()["friction_force"]
        assert str(screen.robot.requirements.render()).startswith("✘ Lift to the top")
        assert screen.unsaved_changes() == 2  # friction and effects: ctrl+s writes them
        await pilot.press("ctrl+s")
        await pilot.pause()
        assert screen.unsaved_changes() == 0
    saved = workbook.load(path)
    lift_saved = saved.cards["lift"]
    assert lift_saved.links["load_mass"].text == "carriage"
    assert lb(lift_saved.inputs["friction_force"], "force") == pytest.approx(friction, rel=1e-9)
    assert workbook.solve(saved).checks[0].holds is False


async def test_an_unlinked_load_is_written_and_the_link_resolved_is_what_is_fitted(tmp_path):
    """A carriage of 20 lb through the link: the fit's card has 20 lb (not the elevator's 15 lb
    default); the second workbook types its load, so Apply writes it."""
    for lift, linked in (('load_mass = "= carriage"', True), ('load_mass = "20 lb"', False)):
        path = book_file(tmp_path, carriage="20 lb", lift=lift)
        app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
        async with app.run_test(size=SIZE) as pilot:
            screen = await opened(pilot, app)
            await show(pilot, screen, "lift")
            dialog = await open_fit(pilot)
            await fit(pilot, dialog, str(LOG))
            r = dialog.report
            assert r is not None, str(dialog.query_one("#fit-status").render())
            assert r.card.values["load_mass"] == pytest.approx(lb("20 lb"), rel=1e-12)
            mass = r.fits[r.favoured].gains["kA"] * r.card.f
            assert ("load_mass" in dialog.changes) is not linked
            await pilot.click("#fit-apply")
            await settled(pilot, screen)
            got = lb(screen.cards["lift"].entries["load_mass"])
            assert got == pytest.approx(lb("20 lb") if linked else mass, rel=1e-12)
            assert screen.unsaved_changes() == (2 if linked else 3)


async def test_a_card_whose_link_has_no_value_is_not_fitted(tmp_path):
    path = book_file(tmp_path, carriage="= 15 lb / 0")
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    said: list[str] = []
    notify = app.notify

    def keep(message, *args, **kwargs):
        said.append(str(message))
        return notify(message, *args, **kwargs)

    app.notify = keep
    async with app.run_test(size=SIZE) as pilot:
        screen = await opened(pilot, app)
        await show(pilot, screen, "lift")
        assert fit_titles(app) == ["Fit lift from log…"]
        await pilot.press("ctrl+p")
        await pilot.press(*"Fit lift")
        await pilot.pause(0.3)
        await pilot.press("enter")
        await pilot.pause(0.2)
        assert app.screen is screen
        assert any("load_mass" in m and "no value" in m for m in said), said


async def test_the_arm_and_flywheel_cards_are_offered_by_name_and_the_arms_fit_applies(tmp_path):
    """Each fitted kind (core.fit.KINDS) is offered on a workbook; the arm's fit applies to its card
    (the flywheel's is shown, not applied: fit_screen.py)."""
    pytest.importorskip("wpiutil")
    from gearhead.core.fit import entries
    from tests.fit_plants import simulate

    path = tmp_path / "robot.toml"
    path.write_text(
        'name = "kinds"\n[cards.pivot]\ncalculator = "arm"\n[cards.wheel]\ncalculator = "flywheel"\n',
        encoding="utf-8",
    )
    design = entries.load_card("arm").design
    plant = {"kS": design["kS"] * 2, "kV": design["kV"], "kA": design["kA"] * 1.3, "kG": design["kG"] * 1.25}
    log = simulate(tmp_path / "arm.wpilog", "arm", {**plant, "offset": 0.0}, period=0.005)
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(path))
    async with app.run_test(size=SIZE) as pilot:
        screen = await opened(pilot, app)
        await show(pilot, screen, "wheel")
        assert fit_titles(app) == ["Fit wheel from log…"]
        await show(pilot, screen, "pivot")
        assert fit_titles(app) == ["Fit pivot from log…"]
        dialog = await open_fit(pilot)
        await fit(pilot, dialog, str(log))
        r = dialog.report
        assert r is not None, str(dialog.query_one("#fit-status").render())
        await pilot.click("#fit-apply")
        await settled(pilot, screen)
        pivot = screen.cards["pivot"]
        got = pivot.solution.inputs
        assert got["moment_of_inertia"].value == pytest.approx(
            r.fits[r.favoured].gains["kA"] * r.card.f, rel=1e-9
        )
        assert got["inertia_model"].value == "entered"
        assert {"arm_mass", "moment_of_inertia", "friction_torque"} <= pivot.edited
        assert screen.unsaved_changes() == len(pivot.edited)


async def test_a_workbooks_palette_offers_its_own_commands_not_the_hidden_cards(tmp_path):
    """The calculator cards' commands (presets, share codes, export, sweep, units, open, send) act on
    the card hidden behind a workbook, and their keys say so there: the palette does not offer them
    either. Its own commands do what their keys do."""
    app = GearheadApp(
        blink=False, initial="elevator", hide_timings=True, workbook=workbook.load(book_file(tmp_path))
    )
    async with app.run_test(size=SIZE) as pilot:
        screen = await opened(pilot, app)
        await settled(pilot, screen)
        titles = [c.title for c in app.get_system_commands(app.screen)]
        for hidden in ("Save preset", "Load preset", "Copy share code", "Export results", "Sweep…"):
            assert hidden not in titles
        assert not [t for t in titles if t.startswith(("Open ", "Send ", "Units: "))], titles
        assert {"Save workbook", "Next card", "Previous card", "Close workbook"} <= set(titles)
        tabs = screen.query_one("#workbook-tabs")
        await pilot.press("ctrl+p", *"Next card")
        await pilot.pause(0.3)
        await pilot.press("enter")
        await pilot.pause(0.1)
        assert tabs.active == "wbtab-lift"
    # back on the calculator cards, they are offered again
    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        titles = [c.title for c in app.get_system_commands(app.screen)]
        assert "Save preset" in titles and "Save workbook" not in titles


async def test_a_sprint_with_its_mass_linked_takes_rolling_resistance_at_the_cards_mass(tmp_path):
    """The example's drive links robot_mass: Apply leaves it, says what the fit gives, and writes
    the rolling resistance at the card's mass, so the card gives the fitted kS (as --apply)."""
    import sys

    from gearhead.core.fit import entries

    sys.path.insert(0, str(Path(__file__).parent))
    from fit_plants import simulate

    book = tmp_path / "robot.toml"
    book.write_text(
        (Path(__file__).parents[1] / "examples/robot_2027.toml").read_text(encoding="utf-8"), encoding="utf-8"
    )
    card = entries.load_card("sprint", workbook=str(book), name="drive")
    plant = {k: card.design[k] * s for k, s in (("kS", 1.5), ("kV", 1.0), ("kA", 1.15))}
    log = simulate(tmp_path / "drive.wpilog", "sprint", plant, period=0.02, step=4.0, dynamic_time=1.5)
    app = GearheadApp(blink=False, hide_timings=True, workbook=workbook.load(book))
    async with app.run_test(size=SIZE) as pilot:
        screen = await opened(pilot, app)
        await show(pilot, screen, "drive")
        dialog = await open_fit(pilot, "Fit drive")
        await fit(pilot, dialog, str(log))
        r = dialog.report
        assert r is not None, str(dialog.query_one("#fit-status").render())
        diff = str(dialog.query_one("#fit-diff").render())
        assert "Robot mass is linked (= robot_mass): not written; the fit gives" in diff, diff
        assert "robot mass is held at the card's" in diff
        assert "robot_mass" not in dialog.changes
        await pilot.click("#fit-apply")
        await settled(pilot, screen)
        outs = screen.cards["drive"].solution.outputs
        assert outs["kS"].value == pytest.approx(r.fits[r.favoured].gains["kS"], rel=1e-9)
        assert outs["kA"].value == pytest.approx(card.design["kA"], rel=1e-9)
