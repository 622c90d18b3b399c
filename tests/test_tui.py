"""Pilot tests: typing, mode switching, an invalid entry, and a preset round trip in the app."""

import asyncio

import pytest
from textual.widgets import Input, OptionList, Static

from gearhead.core import presets
from gearhead.core.model import solve
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
from tests.tui_helpers import card, settle, shown_rows, toggle, type_into

SIZE = (140, 45)


async def test_typing_updates_results():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        await type_into(pilot, "load", "200 lbf")
        assert tab.entries["load"] == "200 lbf"
        expected = solve("gear_ratio", {"load": "200 lbf"}).outputs["ratio"].value
        assert tab.solution.outputs["ratio"].value == pytest.approx(expected, rel=1e-12)
        assert tab.solution.inputs["load"].text == "200 lbf"


async def test_mode_switch_shows_only_that_modes_target():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        assert "target_rotational_speed" not in shown_rows(tab)
        # the mode row's list: Enter opens it, the choice highlighted and Enter picks it
        tab.sheet.focus()
        tab.sheet.move_to_field("mode")
        await pilot.press("enter")
        await settle(pilot)
        options = app.screen.query_one(OptionList)
        options.highlighted = next(
            i for i in range(options.option_count) if options.get_option_at_index(i).id == "rotational_speed"
        )
        await pilot.press("enter")
        await settle(pilot)
        assert tab.entries["mode"] == "rotational_speed"
        assert "target_rotational_speed" in shown_rows(tab)
        assert "target_current" not in shown_rows(tab)
        assert "ratio_alternative" in tab.solution.outputs
        assert tab.solution.outputs["loaded_speed"].text == "300 rpm"


async def test_invalid_entry_names_the_field_and_keeps_the_text():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        good = tab.solution
        # one edit (a paste): typing key by key would pass through the valid "3" on a slow machine
        tab._take_entry("radius", "3 kg")
        await settle(pilot)
        assert "is not a length" in tab.sheet.errors["radius"]
        assert any("is not a length" in line.error for line in tab.sheet.lines)  # drawn under the row
        assert tab.error.field == "radius"
        assert tab.entries["radius"] == "3 kg"  # nothing typed is lost
        # the status line names the field as the form does ("Load radius"), not "radius"
        assert str(tab.query_one(".status", Static).render()).startswith("✗ Load radius: ")
        assert tab.solution is good  # last valid results stay, marked stale
        assert tab.results.state == "stale"
        await type_into(pilot, "radius", "2 in")
        assert "radius" not in tab.sheet.errors and tab.error is None
        assert tab.results.state == "fresh"
        assert tab.solution.inputs["radius"].value == pytest.approx(0.0508)


async def test_every_wrong_entry_is_marked_on_its_row():
    """Two wrong entries: both rows carry their message (parse_inputs reports every bad field);
    the status line names the first and counts the rest. Only the first was marked before."""
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        tab._take_entry("radius", "3 kg")
        tab._take_entry("load", "banana")
        await settle(pilot)
        assert set(tab.sheet.errors) == {"radius", "load"}
        assert sum(1 for line in tab.sheet.lines if line.error) >= 2  # both drawn under their rows
        assert "(and 1 more)" in str(tab.query_one(".status", Static).render())
        await type_into(pilot, "load", "20 lbf")
        assert set(tab.sheet.errors) == {"radius"}


async def test_preset_save_then_load_round_trip():
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        await type_into(pilot, "load", "75 lbf")
        await pilot.press("ctrl+s")
        await pilot.pause()
        await pilot.press(*"Test lift")
        await pilot.press("enter")
        await settle(pilot)
        saved = presets.user_dir() / "gear_ratio" / "test_lift.toml"
        assert saved.exists()
        assert presets.load(saved).inputs["load"] == "75 lbf"
        await type_into(pilot, "load", "10 lbf")
        await pilot.press("ctrl+o")
        await pilot.pause()
        await pilot.press("down")  # from the path box to the list
        options = app.screen.query_one(OptionList)
        index = next(
            i
            for i in range(options.option_count)
            if "Test lift" in str(options.get_option_at_index(i).prompt)
        )
        options.highlighted = index
        await pilot.press("enter")
        await settle(pilot)
        assert tab.entries["load"] == "75 lbf"
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
    app = Probe(blink=False)
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


async def test_tabs_are_built_on_first_visit_and_work():
    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        assert not app.query("#calc-pneumatics")
        app.show_calculator("pneumatics")
        await settle(pilot)
        tab = app.query_one("#calc-pneumatics", CalculatorTab)
        assert tab.solution is not None and "min_pressure" in tab.solution.outputs
        # switching an effect off re-solves without integrating
        assert "compressor" in tab.entries["effects"]
        await toggle(pilot, "effects", "compressor")
        assert "compressor" not in tab.entries["effects"]
        assert tab.solution.outputs["rhs_evaluations"].value == 0


async def test_enter_on_a_result_shows_it_in_the_next_unit():
    """Display units are the user's: Enter on "Free speed" turns rpm into rad/s, value unchanged."""
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        before = tab.solution.outputs["free_speed"]
        assert before.text.endswith(" rpm")
        row = list(tab.solution.outputs).index("free_speed")
        tab.results.focus()
        tab.results.move_to(row)
        await pilot.press("enter")
        await settle(pilot)
        after = tab.solution.outputs["free_speed"]
        assert after.value == before.value and after.text.endswith(" rad/s")
        shown = float(after.text.split()[0])
        assert shown == pytest.approx(before.value, rel=1e-4)  # SI value is rad/s
        assert tab.shown_values()["free_speed"].endswith(" rad/s")  # and the list shows it
        assert tab.results.cursor == row  # the cursor stays put


async def test_fields_follow_the_choices_they_depend_on():
    """Choosing a hex section hides the tube's wall; ticking air drag shows the drag coefficient."""
    app = GearheadApp(blink=False, initial="beam")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        beam = app.query_one("#calc-beam", CalculatorTab)
        assert "wall" in shown_rows(beam) and "outer_size" not in shown_rows(beam)
        beam._take_entry("section", "hex")
        await settle(pilot)
        assert "wall" not in shown_rows(beam) and "outer_size" in shown_rows(beam)
        assert "youngs_modulus" not in shown_rows(beam)  # 6061-T6: no custom figures
        app.show_calculator("projectile")
        await settle(pilot)
        proj = app.query_one("#calc-projectile", CalculatorTab)
        assert "drag_coefficient" not in shown_rows(proj)
        await toggle(pilot, "effects", "air_drag")
        assert "drag_coefficient" in shown_rows(proj)
        assert "spin" not in shown_rows(proj)
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
        assert any("Load = " in s and "Load radius = " in s for s in shown), shown


async def test_fast_typing_coalesces_solves_and_shows_only_the_latest(monkeypatch):
    """Keys typed while a (slow) solve runs: each new key cancels the card's running solve through
    its worker (the solve stops at its next budget check), so only the latest entries are solved
    to the end and only their result is drawn."""

    import threading

    import gearhead.core.model
    from gearhead.core.sim.integrate import charge

    real_solve = gearhead.core.model.solve
    started: list[str] = []
    finished: list[str] = []
    release = threading.Event()  # the test lets the slow solves go on (no timing race)

    def slow_solve(calc_id, raw=None, *args):
        voltage = (raw or {}).get("voltage")
        started.append(voltage)
        while not release.wait(0.005):
            charge(0)  # a long solve checks its budget: Cancelled here once a newer key came
        finished.append(voltage)
        return real_solve(calc_id, raw, *args)

    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        monkeypatch.setattr(gearhead.core.model, "solve", slow_solve)
        tab = app.query_one("#calc-motor", CalculatorTab)
        shown = []
        show = tab._show_solved
        tab._show_solved = lambda solved, key, drawn: (shown.append(solved), show(solved, key, drawn))
        tab.sheet.focus()
        await pilot.pause()
        tab.sheet.move_to_field("voltage")
        from textual import events

        for key, char in [
            ("backspace", "\x7f"),  # an empty edit
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
        assert tab.busy
        release.set()
        await settle(pilot)
        assert tab.entries["voltage"] == "11.5"
        assert started[-1] == "11.5" and len(started) >= 2, started
        assert finished == ["11.5"], finished  # every older solve was cancelled before its end
        # no stale result shown
        assert len(shown) == 1 and shown[0].solution.inputs["voltage"].value == 11.5
        assert tab.results.state == "fresh"
        assert "solved" in str(tab.query_one(".status", Static).render())


@pytest.mark.parametrize("focused", ["flag", "editing", "#plot-choice", "results"])
async def test_palette_open_switches_tab_wherever_focus_is(focused):
    """'Open Motor' from the palette used to do nothing with focus on a checkbox or the chart
    selector: the focused widget in the old pane pulled its tab back."""
    app = GearheadApp(blink=False, initial="trebuchet")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = card(app)
        if focused == "flag":  # the sheet, its cursor on a flag
            tab.sheet.focus()
            tab.sheet.move_to_field("effects")
        elif focused == "editing":  # the sheet, a value being edited
            tab.sheet.focus()
            tab.sheet.move_to(next(i for i, s in enumerate(tab.sheet.stops) if s.shape == "input"))
            await pilot.pause()
            await pilot.press("enter")
            assert tab.sheet.editing
        elif focused == "results":
            tab.results.focus()
        else:
            tab.query_one(focused).focus()
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
    from gearhead.core.units import COMMON_UNITS

    app = GearheadApp(blink=False, initial="motor")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-motor", CalculatorTab)
        tab.results.focus()
        tab.results.move_to(list(tab.solution.outputs).index("free_speed"))
        shown = []
        for _ in range(len(COMMON_UNITS["angular_speed"])):
            await pilot.press("enter")
            await settle(pilot)
            shown.append(tab.shown_values()["free_speed"].split()[-1])
        assert shown == ["rad/s", "deg/s", "rpm"]


async def test_any_calculator_in_two_keys_from_anywhere():
    """F1-F5 pick an area (even from inside an entry), then a digit picks the calculator."""
    from gearhead.core.registry import AREAS

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        for n, (_, ids) in enumerate(AREAS.values(), 1):
            for i, calc_id in enumerate(ids, 1):
                tab = app.current_tab
                tab.sheet.focus()  # typing in a field: its edit open
                await pilot.pause()
                tab.sheet.move_to(next(n for n, s in enumerate(tab.sheet.stops) if s.shape == "input"))
                await pilot.press("enter")
                assert tab.sheet.editing
                await pilot.press(f"f{n}", str(i))
                await settle(pilot)
                assert app.current_calculator == calc_id
                assert app.current_tab.solution is not None  # built and solved on first visit
        app.show_calculator("gear_ratio")
        await settle(pilot)
        tab = card(app, "gear_ratio")
        tab.sheet.focus()
        await pilot.pause()
        tab.sheet.move_to_field("load")
        await pilot.press("1", "2")  # digits typed into a field stay in the field
        assert tab.entries["load"] == "12" and app.current_calculator == "gear_ratio"


def test_every_calculator_is_in_exactly_one_area():
    from gearhead.core.registry import AREAS, calculators

    placed = [cid for _, ids in AREAS.values() for cid in ids]
    assert sorted(placed) == sorted(calculators())


async def test_ctrl_y_copies_the_tab_as_a_share_code_that_loads_back():
    import tomllib

    from gearhead.core import share

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await type_into(pilot, "load", "31 lbf")
        await pilot.press("ctrl+y")
        await pilot.pause()
        assert app.clipboard.startswith("gh1:") and "\n" not in app.clipboard
        preset = share.decode(app.clipboard)
        assert preset.calculator == "gear_ratio" and preset.inputs["load"] == "31 lbf"
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        assert solve("gear_ratio", preset.inputs).outputs == tab.solution.outputs
        await app.action_copy_preset()  # the palette's "Copy as preset TOML": the file's text, as before
        assert presets.from_dict(tomllib.loads(app.clipboard)).inputs == preset.inputs


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
        (None, True),  # what ctrl+y copied on another tab of the same calculator (a share code)
        ("gh1:AAAA", False),  # a damaged share code
        ("http://127.0.0.1:8000/?p=gh2:AAAA", False),  # a newer Gearhead's code in a served link
        ('calculator = "gear_ratio"\nname = "x"\n[inputs]\nload = "3 kg"\n', False),  # wrong unit
        ('calculator = "gear_ratio"\n' + "x = " + "[" * 5000 + "]" * 5000 + "\n", False),  # too deep
        ('calculator = "beam"\nname = "x"\n', True),  # another calculator's: opens that one
    ],
)
async def test_pasting_a_preset_into_the_load_dialog(text, loads):
    from textual import events

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        beam = text is not None and '"beam"' in text
        if text is None:
            await type_into(pilot, "load", "33 lbf")
            await pilot.press("ctrl+y")
            text = app.clipboard
            await type_into(pilot, "load", "10 lbf")
        await pilot.press("ctrl+o")
        await settle(pilot)
        dialog = app.screen
        dialog.query_one("#preset-path").post_message(events.Paste(text))
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        if loads and beam:
            assert app.screen is not dialog and app.current_calculator == "beam"
            assert card(app, "beam").preset_meta[0] == "x"
            assert tab.entries == {f.name: tab.initial_entry(f) for f in tab.calculator.fields}
        elif loads:
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
        tab.results.focus()
        await pilot.pause()
        tab.results.move_to(list(tab.solution.outputs).index("ratio"))
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
        tab._take_entry("length", "3 kg")  # a bad entry: the chart is dimmed
        await settle(pilot)
        assert tab.plot.has_class("stale")
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


@pytest.mark.parametrize("newline", ["\n", "\r\n", "\r"])
async def test_a_pasted_preset_loads_whatever_its_line_breaks(newline):
    """Some terminals deliver a paste's line breaks as CR: the text became one line and was
    taken for a path."""
    from textual import events

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        text = newline.join(
            ['calculator = "gear_ratio"', 'name = "pasted"', "[inputs]", 'load = "44 lbf"', ""]
        )
        await pilot.press("ctrl+o")
        await settle(pilot)
        app.screen.query_one("#preset-path").post_message(events.Paste(text))
        await settle(pilot)
        assert app.screen is app.home
        assert card(app).entries["load"] == "44 lbf"


@pytest.mark.parametrize("kind", ["preset text", "path"])
async def test_a_paste_while_the_list_has_the_keys_reaches_the_path_box(kind):
    """The load dialog invites pasting a preset's text: a paste while its list has the keys (↓ from
    the path box) was dropped (tmux: ctrl+o, then a paste, did nothing)."""
    from textual import events
    from textual.widgets import OptionList

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+o")
        await settle(pilot)
        await pilot.press("down")
        listing = app.screen.query_one("#preset-list", OptionList)
        assert app.screen.focused is listing
        if kind == "path":
            listing.post_message(events.Paste("/tmp/robot.toml"))
            await settle(pilot)
            path = app.screen.query_one("#preset-path", Input)
            assert path.value == "/tmp/robot.toml" and app.screen.focused is path
            return
        text = "\n".join(['calculator = "gear_ratio"', 'name = "pasted"', "[inputs]", 'load = "44 lbf"', ""])
        listing.post_message(events.Paste(text))
        await settle(pilot)
        assert app.screen is app.home
        assert card(app).entries["load"] == "44 lbf"


async def test_a_one_line_paste_into_the_path_box_is_inserted_once():
    from textual import events

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+o")
        await settle(pilot)
        path = app.screen.query_one("#preset-path", Input)
        path.focus()
        await pilot.pause()
        path.post_message(events.Paste("/tmp/robot.toml"))
        await settle(pilot)
        assert path.value == "/tmp/robot.toml"


async def test_the_key_bar_names_the_keys_that_act_now():
    """The key bar draws the sheet's keys while the sheet has focus, ctrl+g only where a card
    sends, and a click on a key runs it."""
    from gearhead.tui.components.key_bar import KeyBar

    app = GearheadApp(blink=False, initial="lead_screw")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        bar = app.query_one(KeyBar)
        card(app).sheet.focus()
        await settle(pilot)
        drawn = bar.render_line(0).text
        assert "Edit" in drawn and "Toggle" in drawn and "Send to" in drawn and "Sweep row" in drawn
        app.show_calculator("beam")
        await settle(pilot)
        drawn = bar.render_line(0).text
        assert "Send to" not in drawn and "Edit" in drawn  # the beam's sheet has the keys at once
        start = drawn.index("^o")
        await pilot.click(KeyBar, offset=(start + 1, 0))
        await settle(pilot)
        assert app.screen is not app.home  # the load dialog


async def test_a_choice_list_picks_by_the_words_typed():
    """Enter on a choice row opens its list; "by l" (space included) picks "By linear speed"."""
    from gearhead.tui.components.choice_screen import ChoiceScreen

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = card(app)
        tab.sheet.focus()
        tab.sheet.move_to_field("mode")
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, ChoiceScreen)
        await pilot.press("b", "y", "space", "l", "enter")
        await settle(pilot)
        assert tab.entries["mode"] == "linear_speed"
        assert "target_linear_speed" in [f.name for f in tab.sheet.shown_fields]


async def test_a_choice_list_matches_a_word_inside_a_label():
    """ "sds mk4i l3" picks "Swerve: SDS MK4i L3 (...)": the words typed may begin any word of the label,
    punctuation aside (only the label's start matched before)."""
    from gearhead.tui.components.choice_screen import ChoiceScreen

    app = GearheadApp(blink=False, initial="sprint")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = card(app)
        tab.sheet.focus()
        tab.sheet.move_to_field("drive")
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, ChoiceScreen)
        await pilot.press(*"sds", "space", *"mk4i", "space", "l", "3", "enter")
        await settle(pilot)
        assert tab.entries["drive"] == "sds_mk4i_l3"
        assert "ratio" not in [f.name for f in tab.sheet.shown_fields]  # the module's ratio is used


async def test_letters_on_the_load_list_pick_the_preset_they_name():
    """ctrl+o, ↓ to the list, then "vex" and Enter loads "VEX lift, 2 V5 red" (the third): the
    load list has the choice lists' type-ahead (letters did nothing there, and Enter loaded the
    first preset)."""
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = card(app)
        await pilot.press("ctrl+o")
        await settle(pilot)
        await pilot.press("down", "v", "e", "x", "enter")
        await settle(pilot)
        assert tab.entries["motor"] == "V5 100 rpm (red)"
