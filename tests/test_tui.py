"""Pilot tests: typing, mode switching, an invalid entry, and a preset round trip in the app."""

import asyncio

import pytest
from textual.widgets import Input, OptionList, Select, Static

from gearhead.core import presets
from gearhead.core.model import solve
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
from tests.tui_helpers import settle

SIZE = (140, 45)


async def replace_text(pilot, selector, text):
    entry = pilot.app.query_one(selector, Input)
    entry.focus()
    await pilot.pause()
    entry.value = ""
    await pilot.press(*list(text))
    await settle(pilot)


async def test_typing_updates_results():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        await replace_text(pilot, "#calc-gear_ratio #in-load", "200 lbf")
        expected = solve("gear_ratio", {"load": "200 lbf"}).outputs["ratio"].value
        assert tab.solution.outputs["ratio"].value == pytest.approx(expected, rel=1e-12)
        assert tab.solution.inputs["load"].text == "200 lbf"


async def test_mode_switch_shows_only_that_modes_target():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        assert not tab.query_one("#row-target_rotational_speed").display
        tab.query_one("#in-mode", Select).value = "rotational_speed"
        await settle(pilot)
        assert tab.query_one("#row-target_rotational_speed").display
        assert not tab.query_one("#row-target_current").display
        assert "ratio_alternative" in tab.solution.outputs
        assert tab.solution.outputs["loaded_speed"].text == "300 rpm"


async def test_invalid_entry_names_the_field_and_keeps_the_text():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        good = tab.solution
        # one edit (a paste): typing key by key would pass through the valid "3" on a slow machine
        tab.query_one("#in-radius", Input).value = "3 kg"
        await settle(pilot)
        error = tab.query_one("#err-radius", Static)
        assert error.display
        assert "is not a length" in str(error.render())
        assert tab.error.field == "radius"
        assert tab.query_one("#in-radius", Input).value == "3 kg"  # nothing typed is lost
        # the status line names the field as the form does ("Load radius"), not "radius"
        assert str(tab.query_one(".status", Static).render()).startswith("✗ Load radius: ")
        assert tab.solution is good  # last valid results stay, marked stale
        assert tab.stale and tab.query_one(".results").has_class("stale")
        await replace_text(pilot, "#calc-gear_ratio #in-radius", "2 in")
        assert not error.display and tab.error is None
        assert tab.solution.inputs["radius"].value == pytest.approx(0.0508)


async def test_preset_save_then_load_round_trip():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        await replace_text(pilot, "#calc-gear_ratio #in-load", "75 lbf")
        await pilot.press("ctrl+s")
        await pilot.pause()
        await pilot.press(*"Test lift")
        await pilot.press("enter")
        await settle(pilot)
        saved = presets.user_dir() / "gear_ratio" / "test_lift.toml"
        assert saved.exists()
        assert presets.load(saved).inputs["load"] == "75 lbf"
        await replace_text(pilot, "#calc-gear_ratio #in-load", "10 lbf")
        await pilot.press("ctrl+o")
        await pilot.pause()
        options = app.screen.query_one(OptionList)
        index = next(
            i
            for i in range(options.option_count)
            if "Test lift" in str(options.get_option_at_index(i).prompt)
        )
        options.highlighted = index
        await pilot.press("enter")
        await settle(pilot)
        assert tab.query_one("#in-load", Input).value == "75 lbf"
        assert tab.solution.inputs["load"].text == "75 lbf"
        # saving again under the same name refuses to overwrite silently
        await pilot.press("ctrl+s")
        await pilot.pause()
        await pilot.press(*"Test lift")
        await pilot.press("enter")
        await pilot.pause()
        assert "file exists" in str(app.screen.query_one("#save-error", Static).render())


async def test_command_palette_offers_presets_and_every_calculator():
    app = GearheadApp(blink=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        titles = [c.title for c in app.get_system_commands(app.screen)]
        assert "Save preset" in titles and "Load preset" in titles
        assert "Open Gear ratio" in titles and "Open Motor" in titles


async def test_accuracy_view_tabulates_every_level():
    from textual.widgets import DataTable

    from gearhead.core.sim.scene import LEVELS

    app = GearheadApp(blink=False, initial="pneumatics", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+r")
        await settle(pilot)
        table = app.screen.query_one("#ladder", DataTable)
        assert table.row_count == len(LEVELS)
        errors = [float(table.get_row(level)[2]) for level in LEVELS]
        assert errors[-1] < errors[0]  # tighter levels are more accurate
        assert table.get_row("default")[3] == "(hidden)"


FIRST_FRAME_PROBE = r"""
import asyncio, sys
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
class Probe(GearheadApp):
    async def on_ready(self):  # Ready: the first frame is on screen
        self.seen = (sorted(m for m in sys.modules if m.startswith("gearhead.core.calculators.")),
                     len(self.query(CalculatorTab)))
        await super().on_ready()
async def main():
    app = Probe(blink=False, warm_up=False)
    async with app.run_test(size=(140, 45)) as pilot:
        await pilot.pause()
        built = app.card_ready(app.current_calculator)
    print(app.seen, built)
asyncio.run(main())
"""


def test_first_frame_imports_no_calculator_and_the_first_card_follows():
    import subprocess
    import sys
    from pathlib import Path

    out = subprocess.run(
        [sys.executable, "-c", FIRST_FRAME_PROBE],
        capture_output=True,
        text=True,
        cwd=Path(__file__).resolve().parents[1],
        timeout=120,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split()[-3:] == ["([],", "0)", "True"]


async def test_idle_builds_every_card_and_a_key_postpones_it():
    """While the user does nothing the other cards are built, so a first visit finds its card
    ready; keys arriving hold the warm-up back."""
    from textual import events

    from gearhead.core.registry import ORDER

    app = GearheadApp(blink=False, initial="motor", hide_timings=True, warm_up=True)
    app.IDLE_BEFORE_BUILD_S = 3.0  # margin: on a loaded machine a 0.1 s pause once took > 1 s
    async with app.run_test(size=SIZE) as pilot:
        for _ in range(30):  # typing, a key every 0.1 s: nothing is built meanwhile
            app.post_message(events.Key("shift", None))
            await pilot.pause(0.1)
        assert [cid for cid in ORDER if app.card_ready(cid)] == ["motor"]
        app.IDLE_BEFORE_BUILD_S = 0.1
        for _ in range(600):
            if all(app.card_ready(cid) for cid in ORDER):
                break
            await pilot.pause(0.05)
        assert [cid for cid in ORDER if not app.card_ready(cid)] == []
        await settle(pilot)
        assert app.current_calculator == "motor"  # warming up never switched the tab
        app.show_calculator("trebuchet")
        await settle(pilot)
        assert app.query_one("#calc-trebuchet", CalculatorTab).solution is not None


async def test_the_real_app_freezes_its_heap_and_releases_it_on_exit():
    """With the warm-up (the real app) everything alive once a card is built is moved out of the
    garbage collector's walk, so a full collection no longer stalls the UI for the whole heap;
    the app releases it when it closes. A test app (no warm-up) leaves the collector alone, and
    a card built out of sight does not recompose the footer."""
    import gc

    assert gc.get_freeze_count() == 0
    app = GearheadApp(blink=False, initial="motor", hide_timings=True, warm_up=True)
    app.IDLE_BEFORE_BUILD_S = 60.0  # no warm-up builds: only the first card
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        assert app.card_ready("motor")
        frozen = gc.get_freeze_count()
        assert frozen > 10_000  # the first card's widgets and the imported modules at least
        refreshed = []
        app.refresh_bindings = lambda: refreshed.append(1)
        await app.card("beam")  # out of sight: the footer's bindings are the motor card's
        assert refreshed == []
    assert gc.get_freeze_count() == 0

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        assert app.card_ready("motor") and gc.get_freeze_count() == 0


async def test_a_pause_collects_what_came_after_the_freeze_before_freezing_it():
    """What a visit leaves behind is tidied in a pause: garbage promoted to the oldest generation
    since the last freeze is collected, not frozen with the rest (it would stay until exit), and
    full collections are rarer meanwhile; the collector's own settings come back at exit."""
    import gc
    import weakref

    class Node:
        pass

    threshold = gc.get_threshold()
    app = GearheadApp(blink=False, initial="motor", hide_timings=True, warm_up=True)
    app.IDLE_BEFORE_BUILD_S = 60.0  # no warm-up builds
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        assert gc.get_threshold()[2] == app.FULL_COLLECTION_EVERY
        cycle = Node()
        cycle.me = cycle
        alive = weakref.ref(cycle)
        gc.collect(1)  # it survives a young collection: promoted to the oldest generation
        assert gc.get_count()[2] and any(o is cycle for o in gc.get_objects(2))
        del cycle
        assert alive() is not None  # a cycle: only the collector frees it
        app._tidy_heap()
        assert alive() is None
        assert gc.get_objects(2) == []  # the rest is frozen
    assert gc.get_threshold() == threshold and gc.get_freeze_count() == 0


async def test_a_calculator_picked_while_its_strip_is_mounting_is_shown():
    """The warm-up mounts an area's strip out of sight; a key that opens a calculator of that area
    before the strip's tabs exist used to raise (NoMatches, then "No Tab with id"). The pick is
    kept and shown once the strip is built."""
    import asyncio

    from gearhead.core.registry import AREAS, area_of

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        area = area_of("beam")
        other = [cid for cid in AREAS[area][1] if cid != "beam"][0]  # not the strip's first tab
        mounting = asyncio.ensure_future(app.strip(area))  # as the warm-up does
        await asyncio.sleep(0)
        assert area in app._mounting and area not in app._strips_built  # the gap a key can fall in
        app.show_calculator(other)
        await mounting
        await settle(pilot)
        assert app.current_calculator == other
        assert app._strips[area].active == f"tab-{other}"
        assert app.card_ready(other)
    assert app.return_code in (0, None) and app._exception is None


async def test_tabs_are_built_on_first_visit_and_work():
    app = GearheadApp(blink=False, initial="motor", warm_up=False)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        assert not app.query("#calc-pneumatics")
        app.show_calculator("pneumatics")
        await settle(pilot)
        tab = app.query_one("#calc-pneumatics", CalculatorTab)
        assert tab.solution is not None and "min_pressure" in tab.solution.outputs
        # switching an effect off re-solves without integrating
        from textual.widgets import Checkbox

        tab.query_one("#flag-effects--compressor", Checkbox).value = False
        await settle(pilot)
        assert tab.solution.outputs["rhs_evaluations"].value == 0


async def test_enter_on_a_result_shows_it_in_the_next_unit():
    """Display units are the user's: Enter on "Free speed" turns rpm into rad/s, value unchanged."""
    from textual.widgets import DataTable

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        before = tab.solution.outputs["free_speed"]
        assert before.text.endswith(" rpm")
        table = tab.query_one(".results", DataTable)
        table.focus()
        table.move_cursor(row=table.get_row_index("free_speed"))
        await pilot.press("enter")
        await settle(pilot)
        after = tab.solution.outputs["free_speed"]
        assert after.value == before.value and after.text.endswith(" rad/s")
        shown = float(after.text.split()[0])
        assert shown == pytest.approx(before.value, rel=1e-4)  # SI value is rad/s
        assert table.cursor_row == table.get_row_index("free_speed")  # the cursor stays put


async def test_fields_follow_the_choices_they_depend_on():
    """Choosing a hex section hides the tube's wall; ticking air drag shows the drag coefficient."""
    app = GearheadApp(blink=False, initial="beam")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        beam = app.query_one("#calc-beam", CalculatorTab)
        assert beam.query_one("#row-wall").display and not beam.query_one("#row-outer_size").display
        beam.query_one("#in-section", Select).value = "hex"
        await settle(pilot)
        assert not beam.query_one("#row-wall").display and beam.query_one("#row-outer_size").display
        assert not beam.query_one("#row-youngs_modulus").display  # 6061-T6: no custom figures
        app.show_calculator("projectile")
        await settle(pilot)
        proj = app.query_one("#calc-projectile", CalculatorTab)
        assert not proj.query_one("#row-drag_coefficient").display
        proj.query_one("#flag-effects--air_drag").value = True
        await settle(pilot)
        assert proj.query_one("#row-drag_coefficient").display
        assert not proj.query_one("#row-spin").display
        assert proj.solution.inputs["effects"].value == ["air_drag"]


async def test_notices_render_without_crashing():
    """The 'Preset saved' and 'Sent to' notices can be drawn: a rich Text handed to notify() with
    markup on crashed the app when its toast rendered (headless runs draw no toasts, so each
    message is turned into content here the way Textual's Toast.render does it)."""
    from textual.content import Content

    app = GearheadApp(blink=False, initial="lead_screw")
    notified = []  # every notice (app._notifications drops them after their timeout, which a
    notify = app.notify  # loaded machine can pass before the check)

    def keep(message, *args, **kwargs):
        notified.append((message, kwargs.get("markup", True)))
        return notify(message, *args, **kwargs)

    app.notify = keep
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+s")
        await pilot.pause()
        await pilot.press(*"Odd [name]")
        await pilot.press("enter")
        await settle(pilot)
        await pilot.press("ctrl+g")
        await settle(pilot)
        shown = [
            str(Content.from_markup(message) if markup else Content(message)) for message, markup in notified
        ]
        assert any(s.startswith("Saved ") and s.endswith("odd_name.toml") for s in shown), shown
        assert any("load = " in s and "radius = " in s for s in shown), shown


async def test_fast_typing_coalesces_solves_and_shows_only_the_latest(monkeypatch):
    """Keys typed while a (slow) solve runs do not queue a solve each: the running one finishes,
    its now-stale result is dropped, and the latest entries are solved once."""

    import gearhead.core.model

    real_solve = gearhead.core.model.solve
    solved: list[str] = []

    import threading

    release = threading.Event()  # the test lets the first slow solve finish (no timing race)

    def slow_solve(calc_id, raw=None, display_units=None):
        solved.append((raw or {}).get("voltage"))
        release.wait(10)
        return real_solve(calc_id, raw, display_units)

    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        monkeypatch.setattr(gearhead.core.model, "solve", slow_solve)
        tab = app.query_one("#calc-motor", CalculatorTab)
        shown = []
        show = tab._show
        tab._show = lambda solution, error: (shown.append(solution), show(solution, error))
        entry = app.query_one("#in-voltage", Input)
        entry.focus()
        entry.cursor_position = len(entry.value)
        from textual import events

        for key, char in [
            ("backspace", "\x7f"),
            ("backspace", "\x7f"),
            ("1", "1"),
            ("1", "1"),
            ("full_stop", "."),
            ("5", "5"),
        ]:
            app.post_message(events.Key(key, char))  # as the driver delivers a fast typist's keys
            await asyncio.sleep(0.02)
        for _ in range(200):  # the solve is held: after 0.1 s the busy marker is up
            if "solving" in str(tab.query_one(".status", Static).render()):
                break
            await asyncio.sleep(0.02)
        assert "solving" in str(tab.query_one(".status", Static).render())
        release.set()
        await settle(pilot)
        assert entry.value == "11.5"
        assert len(solved) <= 3, solved  # not one per key
        assert solved[-1] == "11.5"
        assert len(shown) == 1 and shown[0].inputs["voltage"].value == 11.5  # no stale result shown
        assert "solved" in str(tab.query_one(".status", Static).render())


@pytest.mark.parametrize(
    "focused",
    [
        "#calc-trebuchet Checkbox",
        "#calc-trebuchet #in-accuracy",
        "#calc-trebuchet #plot-choice",
        "#calc-trebuchet DataTable",
    ],
)
async def test_palette_open_switches_tab_wherever_focus_is(focused):
    """'Open Motor' from the palette used to do nothing with focus on a checkbox or the chart
    selector: the focused widget in the old pane pulled its tab back."""
    app = GearheadApp(blink=False, initial="trebuchet")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        app.query(focused).first().focus()
        await pilot.pause()
        await pilot.press("ctrl+p")
        await pilot.press(*"Open Motor")
        await pilot.pause(0.3)
        await pilot.press("enter")
        await settle(pilot)
        assert app.current_calculator == "motor"


async def test_footer_shows_send_and_accuracy_only_where_they_act():
    app = GearheadApp(blink=False, initial="lead_screw")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        shown = {b.binding.action for b in app.active_bindings.values() if b.enabled}
        assert "send" in shown and "accuracy" not in shown  # lead screw sends to gear ratio
        app.show_calculator("trebuchet")
        await settle(pilot)
        shown = {b.binding.action for b in app.active_bindings.values() if b.enabled}
        assert "accuracy" in shown and "send" not in shown


async def test_enter_on_a_result_walks_every_unit_of_its_kind():
    """Enter used to bounce between two units (762 mm <-> 76.2 cm)."""
    from textual.widgets import DataTable

    from gearhead.core.units import COMMON_UNITS

    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-motor", CalculatorTab)
        table = tab.query_one(".results", DataTable)
        table.focus()
        row = list(tab.solution.outputs).index("free_speed")
        table.move_cursor(row=row)
        shown = []
        for _ in range(len(COMMON_UNITS["angular_speed"])):
            await pilot.press("enter")
            await settle(pilot)
            shown.append(tab.solution.outputs["free_speed"].text.split()[-1])
        assert shown == ["rad/s", "deg/s", "rpm"]


async def test_any_calculator_in_two_keys_from_anywhere():
    """F1-F5 pick an area (even from inside an entry), then a digit picks the calculator."""
    from gearhead.core.registry import AREAS

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        for n, (_, ids) in enumerate(AREAS.values(), 1):
            for i, calc_id in enumerate(ids, 1):
                app.query_one("#calc-gear_ratio #in-load", Input).focus()  # typing in a field
                await pilot.pause()
                await pilot.press(f"f{n}", str(i))
                await settle(pilot)
                assert app.current_calculator == calc_id
                assert app.current_tab.solution is not None  # built and solved on first visit
        entry = app.query_one("#calc-gear_ratio #in-load", Input)
        app.show_calculator("gear_ratio")
        await settle(pilot)
        entry.focus()
        entry.value = ""
        await pilot.press("1", "2")  # digits typed into a field stay in the field
        assert entry.value == "12" and app.current_calculator == "gear_ratio"


def test_every_calculator_is_in_exactly_one_area():
    from gearhead.core.registry import AREAS, calculators

    placed = [cid for _, ids in AREAS.values() for cid in ids]
    assert sorted(placed) == sorted(calculators())


async def test_ctrl_y_copies_the_tab_as_a_preset_that_loads_back():
    import tomllib

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await replace_text(pilot, "#calc-gear_ratio #in-load", "31 lbf")
        await pilot.press("ctrl+y")
        await pilot.pause()
        preset = presets.from_dict(tomllib.loads(app.clipboard))
        assert preset.calculator == "gear_ratio" and preset.inputs["load"] == "31 lbf"
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        assert solve("gear_ratio", preset.inputs).outputs == tab.solution.outputs


async def test_ctrl_e_exports_results_and_plot_data(tmp_path, monkeypatch):
    import csv
    import io

    from textual.widgets import Button, OptionList

    monkeypatch.chdir(tmp_path)
    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-motor", CalculatorTab)
        await pilot.press("ctrl+e")
        await settle(pilot)
        await pilot.click("#copy")  # first choice: Markdown to the clipboard
        await settle(pilot)
        assert app.clipboard.splitlines()[2] == "| Result | Value | Eq. |"
        for _ in range(2):  # the results CSV saved twice: the second time it refuses to overwrite
            await pilot.press("ctrl+e")
            await settle(pilot)
            app.screen.query_one(OptionList).highlighted = 1
            await settle(pilot)
            app.screen.query_one("#save", Button).press()
            await settle(pilot)
        assert "exists" in str(app.screen.query_one("#export-error").render())
        await pilot.press("escape")
        rows = list(csv.DictReader(io.StringIO((tmp_path / "motor_results.csv").read_text())))
        assert {r["output"] for r in rows} == set(tab.solution.outputs)
        await pilot.press("ctrl+e")
        await settle(pilot)
        app.screen.query_one(OptionList).highlighted = 2
        await settle(pilot)
        app.screen.query_one("#save", Button).press()
        await settle(pilot)
        assert (tmp_path / "motor_plot.csv").read_text().startswith("series,")


async def test_save_dialog_offers_the_loaded_presets_name_and_description():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        builtin = next(p for p in presets.listing("gear_ratio") if p.builtin)
        await pilot.press("ctrl+o")
        await settle(pilot)
        app.screen.dismiss(builtin)
        await settle(pilot)
        await pilot.press("ctrl+s")
        await settle(pilot)
        assert app.screen.query_one("#preset-name", Input).value == builtin.name
        assert app.screen.query_one("#preset-description", Input).value == builtin.description


@pytest.mark.parametrize(
    "text,loads",
    [
        (None, True),  # what ctrl+y copied on another tab of the same calculator
        ('calculator = "gear_ratio"\nname = "x"\n[inputs]\nload = "3 kg"\n', False),  # wrong unit
        ('calculator = "gear_ratio"\n' + "x = " + "[" * 5000 + "]" * 5000 + "\n", False),  # too deep
        ('calculator = "beam"\nname = "x"\n', False),  # another calculator
    ],
)
async def test_pasting_a_preset_into_the_load_dialog(text, loads):
    from textual import events

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        if text is None:
            await replace_text(pilot, "#calc-gear_ratio #in-load", "33 lbf")
            await pilot.press("ctrl+y")
            text = app.clipboard
            await replace_text(pilot, "#calc-gear_ratio #in-load", "10 lbf")
        await pilot.press("ctrl+o")
        await settle(pilot)
        dialog = app.screen
        dialog.query_one("#preset-path").post_message(events.Paste(text))
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        if loads:
            assert app.screen is not dialog and tab.entries["load"] == "33 lbf"
        else:
            assert app.screen is dialog
            message = str(dialog.query_one("#load-error").render())
            assert message.strip() and "\n" not in message.strip()
            assert tab.entries["load"] != "3 kg"


async def test_result_under_the_cursor_is_explained():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        from textual.widgets import DataTable

        table = tab.query_one(".results", DataTable)
        table.focus()
        await pilot.pause()
        table.move_cursor(row=list(tab.solution.outputs).index("ratio"))
        await settle(pilot)
        line = str(tab.query_one(".help-line", Static).render())
        assert line.startswith(tab.calculator.output("ratio").label)
        assert tab.calculator.output("ratio").help in line


async def test_a_stale_chart_draws_before_its_canvas_has_a_size():
    """A chart whose results went stale (a bad entry) still draws while its canvases have no size
    yet (a card shown for the first time): with opacity, Textual raised AttributeError on the
    canvas's unstyled blank line and the app closed (typing fast while a card first showed)."""
    from textual.geometry import Region, Size
    from textual_hires_canvas import Canvas

    app = GearheadApp(blink=False, initial="beam", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app._cards["beam"]
        tab._mark_stale(True)
        await settle(pilot)
        canvases = list(tab.query(Canvas))
        assert canvases
        for canvas in canvases:
            canvas._canvas_size = Size(0, 0)  # as before its first resize
            canvas._styles_cache.clear()
            assert len(canvas.render_lines(Region(0, 0, 10, 1))) == 1


async def test_quitting_while_a_strip_or_card_is_mounting_ends_cleanly():
    """F2 then ctrl+q in one burst printed a traceback: the quit pruned the Mechanisms strip
    while it was mounting (its tab bar found no tabs; the card's build found no panes), and an
    F-key after ctrl+q (a priority binding) found no strips. A quit now lets the mounts end
    first, takes no other key, and whatever awaited a mount ends quietly. Keys are posted as a
    terminal delivers them, at several spacings; run_test raises what the app raised."""
    from textual import events

    for keys in (["f2", "ctrl+q"], ["f2", "ctrl+q", "f3", "f4"], ["ctrl+q", "f5"]):
        for delay in (0.0, 0.003, 0.01, 0.02):
            app = GearheadApp(blink=False, initial="motor", hide_timings=True)
            async with app.run_test(size=(140, 45)) as pilot:
                await settle(pilot)
                for key in keys:
                    app.post_message(events.Key(key, None))
                    await asyncio.sleep(delay)
                for _ in range(500):
                    if not app.is_running:
                        break
                    await asyncio.sleep(0.01)
            assert app.return_code == 0, (keys, delay)
