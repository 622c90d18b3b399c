"""Pilot tests from the acceptance pass: small terminals, preset loading, dialogs that must fit."""

import pytest

from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
from tests.tui_helpers import settle, toggle


@pytest.mark.parametrize("calc_id", ["flywheel", "ratio_distance"])
async def test_results_are_reachable_on_an_80x24_terminal(calc_id):
    """At 80 columns the panes stack (they used to sit side by side and push the results off
    screen entirely); focusing the results list scrolls it into view, columns not clipped."""
    app = GearheadApp(blink=False, initial=calc_id, hide_timings=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        tab = app.query_one(f"#calc-{calc_id}", CalculatorTab)
        table = tab.results
        table.focus()
        await settle(pilot)
        region = table.region
        assert region.height > 0 and region.right <= 80 and region.y < 24
        assert table.virtual_size.width <= table.size.width  # no sideways scrolling of values
        assert tab.query_one(".inputs-pane").region.right <= 80


async def test_results_columns_fit_side_by_side_at_120_columns():
    """The widest result labels (ratio & distance) with full values, without sideways scrolling."""
    app = GearheadApp(blink=False, initial="ratio_distance", hide_timings=True)
    async with app.run_test(size=(120, 35)) as pilot:
        await settle(pilot)
        table = app.query_one("#calc-ratio_distance", CalculatorTab).results
        assert (
            table.region.y == app.query_one("#calc-ratio_distance .inputs-pane").region.y + 1
        )  # side by side
        assert table.virtual_size.width <= table.size.width


async def test_loading_a_preset_resets_the_fields_it_omits():
    """'Pumpkin chunker' omits gravity: after typing moon gravity, loading it must solve exactly
    what the CLI solves for that preset (it used to keep 1.62 and show a different range)."""
    from textual.widgets import OptionList

    from gearhead.core import presets
    from gearhead.core.model import solve

    preset = next(p for p in presets.listing("trebuchet") if p.name == "Pumpkin chunker")
    assert "gravity" not in preset.inputs
    app = GearheadApp(blink=False, initial="trebuchet", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-trebuchet", CalculatorTab)
        tab._take_entry("gravity", "1.62")
        await settle(pilot)
        assert tab.solution.inputs["gravity"].value == pytest.approx(1.62)
        await pilot.press("ctrl+o")
        await pilot.pause()
        await pilot.press("down")  # from the path box to the list
        options = app.screen.query_one(OptionList)
        options.highlighted = next(
            i
            for i in range(options.option_count)
            if "Pumpkin chunker" in str(options.get_option_at_index(i).prompt)
        )
        await pilot.press("enter")
        await settle(pilot)
        assert tab.entries["gravity"] == tab.initial_entry(tab.calculator.field("gravity"))
        assert (
            tab.sheet.value_text(tab.sheet.stops[[s.field.name for s in tab.sheet.stops].index("gravity")])
            == "9.81"
        )
        expected = solve("trebuchet", preset.inputs).outputs["range"].value
        assert tab.solution.outputs["range"].value == pytest.approx(expected, rel=1e-12)


async def test_accuracy_view_fits_a_small_terminal_and_closes():
    from textual_plot import PlotWidget

    app = GearheadApp(blink=False, initial="trebuchet", hide_timings=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+r")
        await settle(pilot)
        await settle(pilot)
        dialog = app.screen.query_one(".accuracy-dialog")
        assert dialog.region.right <= 80 and dialog.region.bottom <= 24
        assert app.screen.query_one(PlotWidget).region.height >= 6
        await pilot.press("escape")
        await pilot.pause()
        assert not app.screen.query(".accuracy-dialog")


async def test_accuracy_view_of_a_closed_form_scene_says_so_instead_of_a_flat_plot():
    """Projectile without effects is the seed's closed form: nothing to integrate at any level."""
    from textual.widgets import Static

    app = GearheadApp(blink=False, initial="projectile", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+r")
        await settle(pilot)
        await settle(pilot)
        assert "closed form" in str(app.screen.query_one("#ladder-status", Static).render())
        assert not app.screen.query("PlotWidget")


async def test_long_field_help_and_labels_are_shown_whole():
    """Projectile's target angle help is ~270 characters; the help line had room for two lines.
    Flywheel's 'Grip force μ·N (motor during shot)' is longer than the label column."""
    from textual.widgets import Static

    from gearhead.tui.components.sheet import GAP, LABEL_CELLS

    app = GearheadApp(blink=False, initial="projectile", hide_timings=True)
    async with app.run_test(size=(120, 35)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-projectile", CalculatorTab)
        tab._take_entry("mode", "reverse")  # the target angle is a reverse-mode field
        await settle(pilot)
        tab.sheet.focus()
        assert tab.sheet.move_to_field("target_angle")
        await settle(pilot)
        help_line = tab.query_one(".help-line", Static)
        text = str(help_line.render())
        lines_needed = -(-len(text) // help_line.content_size.width)
        assert help_line.content_size.height >= lines_needed
        assert tab.calculator.field("target_angle").help in text
        app.show_calculator("flywheel")
        await settle(pilot)
        await toggle(pilot, "effects", "motor_during_shot")
        sheet = app.query_one("#calc-flywheel", CalculatorTab).sheet
        sheet.move_to_field("grip_force")
        await settle(pilot)
        first = sheet._first_line[sheet.cursor]
        drawn = [sheet.render_line(y).text for y in range(sheet.size.height)]
        y = first - sheet.scroll_offset.y
        assert 0 <= y < sheet.size.height  # on screen
        # the label wraps within its column, the value follows it
        labels = [drawn[y][1 : 1 + LABEL_CELLS].rstrip()]
        while y + len(labels) < len(drawn) and sheet.lines[first + len(labels)].stop == sheet.cursor:
            labels.append(drawn[y + len(labels)][1 : 1 + LABEL_CELLS].rstrip())
        assert " ".join(labels).startswith("Grip force μ·N (motor during shot)")
        value_at = 1 + LABEL_CELLS + GAP
        stop = sheet.current_stop
        assert drawn[y][value_at + 1 :].startswith(sheet.value_text(stop))


@pytest.mark.parametrize("size", [(120, 35), (140, 45), (80, 24)])
async def test_every_unit_is_in_sight(size):
    """The unit sits one cell after the value column, on screen, at the narrowest side-by-side
    width (120), the usual one, and stacked at 80 columns."""
    from gearhead.tui.components.sheet import GAP, LABEL_CELLS
    from gearhead.tui.components.unit_text import pretty_unit

    app = GearheadApp(blink=False, initial="flywheel", hide_timings=True)
    async with app.run_test(size=size) as pilot:
        await settle(pilot)
        sheet = app.query_one("#calc-flywheel", CalculatorTab).sheet
        for y in range(sheet.size.height):
            line = (
                sheet.lines[y + sheet.scroll_offset.y]
                if y + sheet.scroll_offset.y < len(sheet.lines)
                else None
            )
            if line is None or line.stop is None or not line.first:
                continue
            stop = sheet.stops[line.stop]
            unit = stop.spec.unit
            if unit:
                unit_at = 1 + LABEL_CELLS + GAP + sheet.value_cells(stop) + GAP
                assert unit_at + len(pretty_unit(unit)) <= sheet.size.width, (sheet.size, unit)
                drawn = sheet.render_line(y).text
                assert drawn[unit_at:].startswith(pretty_unit(unit)), (sheet.size, drawn)


async def test_plot_panel_handles_bracketed_titles_and_missing_or_degenerate_series():
    """A title like 'Force [N]' lost '[N]' to markup in the plot selector; a plot without data
    showed an empty frame and legend; one point or all-equal values must not crash."""
    from textual.app import App

    from gearhead.core.model import Plot, Solution
    from gearhead.tui.components.plot_panel import ChartChooser, PlotPanel

    plots = (
        Plot("Force [N]", ("a", "b"), "x", "length", "mm", "F", "force", "lbf"),
        Plot("Other", ("c",), "x", "length", "m", "y", "length", "m"),
    )

    class Harness(App):
        def compose(self):
            yield PlotPanel(plots)

    app = Harness()
    async with app.run_test(size=(80, 24)) as pilot:
        panel = app.query_one(PlotPanel)
        assert panel.query_one(ChartChooser).render_line(0).text.startswith("Force [N] ")
        assert not panel.empty and "No data" not in panel.render().plain  # nothing solved yet
        await panel.show(Solution("x", {}, {}, [], {}))
        await pilot.pause()
        assert panel.empty
        # the panel's own line, under the chooser: on screen, where the chart would be
        lines = [app.screen.get_widget_at(x, y) for x, y in ((1, 2), (5, 2))]
        assert all(w is panel for w, _ in lines), lines
        assert "No data to plot for these inputs." in "".join(
            s.text for s in panel.render_lines(panel.region.reset_offset)[2:3]
        )
        for series in (
            {"a": ([1.0], [2.0])},
            {"a": ([1.0, 2.0, 3.0], [5.0, 5.0, 5.0])},
            {"a": ([], [])},
            {"a": ([0.0, 1.0], [0.0, 1.0]), "b": ([0.0, 1.0], [1.0, 0.0])},
        ):
            await panel.show(Solution("x", {}, {}, [], series))
            await pilot.pause()
        assert not panel.empty


async def test_field_help_keeps_brackets():
    """Help and labels are not markup: help mentioning "[psi]" must keep it on the help line (it
    was a tooltip), and a label "[x]" its brackets on the sheet."""
    from textual.app import App
    from textual.widgets import Static

    from gearhead.core.model import Calculator, Field, Output, Result

    fields = (
        Field("p", "Pressure [gauge]", "pressure", "psi", default=60, help="gauge pressure [psi]"),
        Field("n", "Count", integer=True, default=1, help="how many [each]"),
        Field("c", "Kind", choices=("a", "b"), default="a", help="pick one [a/b]"),
        Field("e", "Effects", choices=("x", "y"), flags=True, default=(), help="switch [on]"),
    )
    calc = Calculator(
        "toy_brackets", "Toy", "Brackets [b]", fields, (Output("z", "Z"),), lambda v: Result({"z": 1})
    )

    class Harness(App):
        def compose(self):
            yield CalculatorTab(calc, blink=False, hide_timings=True)

    app = Harness()
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        tab = app.query_one(CalculatorTab)
        tab.sheet.focus()
        for f in fields:
            tab.sheet.move_to_field(f.name)
            await pilot.pause()
            line = str(tab.query_one(".help-line", Static).render())
            assert line.startswith(f"{f.label}: {f.help}")
        assert tab.sheet.render_line(0).text.startswith(" Pressure [gauge] ")


async def test_long_warnings_scroll_and_keep_the_status_line_in_the_pane(monkeypatch):
    """Three long warnings used to push the status line below the results pane at 120x35."""
    import dataclasses

    from gearhead.core.registry import calculators

    calc = calculators()["flywheel"]
    original = calc.compute

    def compute(values):
        result = original(values)
        result.warnings += ["a long warning the mentor must be able to read in full " * 4] * 3
        return result

    monkeypatch.setitem(calculators(), "flywheel", dataclasses.replace(calc, compute=compute))
    app = GearheadApp(blink=False, initial="flywheel", hide_timings=True)
    async with app.run_test(size=(120, 35)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-flywheel", CalculatorTab)
        pane = tab.query_one(".results-pane").region
        status = tab.query_one(".status").region
        box = tab.query_one(".warnings-box")
        assert box.display and box.region.bottom <= status.y
        assert status.height and status.bottom <= pane.bottom - 1  # inside the border
        assert box.max_scroll_y > 0  # the rest is a scroll away, not cut off


async def test_result_labels_keep_their_room_when_equation_numbers_are_long():
    """The beam's equation numbers run to 34 cells ("(43), (45), (47), (49), (51)…"); they took
    the room and left the labels 8 cells, wrapped onto four lines ("Thin-wal / l J /
    (estimat / e)"). The labels now keep 16 cells and the numbers are cut with "…"."""

    app = GearheadApp(blink=False, initial="beam", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-beam", CalculatorTab)
        table = tab.results
        label, value, equation, spread = table._widths
        assert label >= 16 and equation >= 3
        gaps = 1 + 3  # the leading cell and one after each column
        assert label + value + equation + gaps <= table.size.width
        assert max(len(lines) for lines in table._label_lines) <= 2
        rendered = "\n".join(table.render_line(y).text for y in range(table.size.height))
        assert "Area moment of" in rendered and "(43), (45)" in rendered and "…" in rendered


async def test_the_chart_chooser_opens_its_list_and_shows_the_chart_picked():
    """The chart chooser (one line, 'Title ▼'): Enter opens the list of charts, ↓ Enter shows the
    next, Esc leaves the chart as it was; Space opens it too."""
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.choice_screen import ChoiceScreen
    from gearhead.tui.components.key_bar import KeyBar
    from gearhead.tui.components.plot_panel import ChartChooser
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.current_tab
        titles = [p.title for p in tab.calculator.plots]
        chooser = tab.query_one("#plot-choice", ChartChooser)
        assert chooser.render_line(0).text.startswith(titles[0])
        chooser.focus()
        await pilot.pause()
        assert ("⏎", "Charts", "enter") in app.screen.query_one(KeyBar).keys, (
            "the key bar says what Enter does"
        )
        await pilot.press("enter")
        await pilot.pause()
        assert isinstance(app.screen, ChoiceScreen)
        await pilot.press("down", "enter")
        await settle(pilot)
        assert tab.plot.current.title == titles[1]
        assert chooser.render_line(0).text.startswith(titles[1])
        await pilot.press("space")
        await pilot.pause()
        assert isinstance(app.screen, ChoiceScreen)
        await pilot.press("down", "escape")
        await settle(pilot)
        assert tab.plot.current.title == titles[1] and app.focused is chooser


async def test_a_result_table_keeps_its_cursor_and_repaints_only_the_rows_that_changed():
    """The ratio finder's table (one Line-API widget): ↓/End/Home move the row cursor, a new solve
    of as many rows keeps it and repaints only the lines whose text changed; the header stays."""
    from textual.geometry import Region

    from gearhead.tui.components.result_table import ResultTable

    app = GearheadApp(blink=False, initial="ratio_finder", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.current_tab
        grid = tab.query_one("#table-combinations", ResultTable)
        rows = tab.solution.tables["combinations"]
        assert grid.row_count == len(rows) > 3
        assert grid.render_line(0).text.split()[:2] == ["#", "Ratio"]
        grid.focus()
        await pilot.press("down", "down")
        assert grid.cursor_row == 2
        await pilot.press("end")
        assert grid.cursor_row == len(rows) - 1
        await pilot.press("home", "down")
        assert grid.cursor_row == 1
        repainted: list[Region | None] = []
        refresh = grid.refresh

        def spying(*regions, **kwargs):
            repainted.extend(regions or [None])
            return refresh(*regions, **kwargs)

        grid.refresh = spying
        same = list(grid.rows)
        changed = [same[0], ("x",) * len(same[1]), *same[2:]]
        grid.show(changed)
        assert repainted == [Region(0, 2, grid.size.width, 1)]  # row 1, below the header
        assert grid.cursor_row == 1 and grid.render_line(2).text.split()[0] == "x"
