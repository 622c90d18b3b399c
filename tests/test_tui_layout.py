"""Pilot tests from the acceptance pass: small terminals, preset loading, dialogs that must fit."""

import pytest
from rich.text import Text
from textual.widgets import DataTable

from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
from tests.tui_helpers import settle


@pytest.mark.parametrize("calc_id", ["flywheel", "ratio_distance"])
async def test_results_are_reachable_on_an_80x24_terminal(calc_id):
    """At 80 columns the panes stack (they used to sit side by side and push the results off
    screen entirely); focusing the results table scrolls it into view, columns not clipped."""
    app = GearheadApp(blink=False, initial=calc_id, hide_timings=True)
    async with app.run_test(size=(80, 24)) as pilot:
        await settle(pilot)
        tab = app.query_one(f"#calc-{calc_id}", CalculatorTab)
        table = tab.query_one(".results", DataTable)
        table.focus()
        await settle(pilot)
        region = table.region
        assert region.height > 0 and region.right <= 80
        assert table.virtual_size.width <= table.size.width  # no sideways scrolling of values
        assert tab.query_one(".inputs-pane").region.right <= 80


async def test_results_columns_fit_side_by_side_at_120_columns():
    """The widest result labels (ratio & distance) with full values, without sideways scrolling."""
    app = GearheadApp(blink=False, initial="ratio_distance", hide_timings=True)
    async with app.run_test(size=(120, 35)) as pilot:
        await settle(pilot)
        table = app.query_one("#calc-ratio_distance .results", DataTable)
        assert (
            table.region.y == app.query_one("#calc-ratio_distance .inputs-pane").region.y + 1
        )  # side by side
        assert table.virtual_size.width <= table.size.width


async def test_loading_a_preset_resets_the_fields_it_omits():
    """'Pumpkin chunker' omits gravity: after typing moon gravity, loading it must solve exactly
    what the CLI solves for that preset (it used to keep 1.62 and show a different range)."""
    from textual.widgets import Input, OptionList

    from gearhead.core import presets
    from gearhead.core.model import solve

    preset = next(p for p in presets.listing("trebuchet") if p.name == "Pumpkin chunker")
    assert "gravity" not in preset.inputs
    app = GearheadApp(blink=False, initial="trebuchet", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-trebuchet", CalculatorTab)
        tab.query_one("#in-gravity", Input).value = "1.62"
        await settle(pilot)
        await pilot.press("ctrl+o")
        await pilot.pause()
        options = app.screen.query_one(OptionList)
        options.highlighted = next(
            i
            for i in range(options.option_count)
            if "Pumpkin chunker" in str(options.get_option_at_index(i).prompt)
        )
        await pilot.press("enter")
        await settle(pilot)
        assert tab.query_one("#in-gravity", Input).value == "9.81"
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
    from textual.widgets import Input, Static

    from gearhead.tui.components.calculator_tab import LABEL_CELLS, FieldRow

    app = GearheadApp(blink=False, initial="projectile", hide_timings=True)
    async with app.run_test(size=(120, 35)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-projectile", CalculatorTab)
        tab.query_one("#in-target_angle", Input).focus()
        await settle(pilot)
        help_line = tab.query_one(".help-line", Static)
        text = str(help_line.render())
        lines_needed = -(-len(text) // help_line.content_size.width)
        assert help_line.content_size.height >= lines_needed
        app.show_calculator("flywheel")
        await settle(pilot)
        app.query_one("#calc-flywheel #flag-effects--motor_during_shot").value = True
        await settle(pilot)
        row = app.query_one("#calc-flywheel #row-grip_force", FieldRow)
        # the entry starts where the row's label column ends (LABEL_CELLS; its margin in the
        # stylesheet), and the unit one cell after the entry
        entry = row.children[0]
        assert entry.region.x - row.content_region.x == LABEL_CELLS
        shown = [line[:LABEL_CELLS].rstrip() for line in str(row.render()).splitlines()]
        unit_at = entry.region.right - row.content_region.x + 1
        assert str(row.render()).splitlines()[0][unit_at:].startswith(row.unit_text)
        assert " ".join(shown[: row.size.height]).startswith("Grip force μ·N (motor during shot)")


async def test_plot_panel_handles_bracketed_titles_and_missing_or_degenerate_series():
    """A title like 'Force [N]' lost '[N]' to markup in the plot selector; a plot without data
    showed an empty frame and legend; one point or all-equal values must not crash."""
    from textual.app import App
    from textual.widgets import Select, Static

    from gearhead.core.model import Plot, Solution
    from gearhead.tui.components.plot_panel import PlotPanel

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
        assert str(panel.query_one(Select).query_one("SelectCurrent #label").render()) == "Force [N]"
        empty = panel.query_one("#plot-empty", Static)
        await panel.show(Solution("x", {}, {}, [], {}))
        await pilot.pause()
        assert empty.display
        for series in (
            {"a": ([1.0], [2.0])},
            {"a": ([1.0, 2.0, 3.0], [5.0, 5.0, 5.0])},
            {"a": ([], [])},
            {"a": ([0.0, 1.0], [0.0, 1.0]), "b": ([0.0, 1.0], [1.0, 0.0])},
        ):
            await panel.show(Solution("x", {}, {}, [], series))
            await pilot.pause()
        assert not empty.display


async def test_field_help_tooltips_keep_brackets():
    """Tooltips are markup when given a str: help mentioning "[psi]" must keep it."""
    from textual.app import App

    from gearhead.core.model import Field
    from gearhead.tui.components.calculator_tab import FieldRow

    fields = [
        Field("p", "Pressure", "pressure", "psi", default=60, help="gauge pressure [psi]"),
        Field("n", "Count", integer=True, default=1, help="how many [each]"),
        Field("c", "Kind", choices=("a", "b"), default="a", help="pick one [a/b]"),
        Field("e", "Effects", choices=("x", "y"), flags=True, default=(), help="switch [on]"),
    ]

    class Harness(App):
        def compose(self):
            for f in fields:
                yield FieldRow(f, f.default_text() if f.type != "choice" else f.default, blink=False)

    app = Harness()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        for f in fields:
            widgets = app.query(f"#flag-{f.name}--x") if f.type == "flags" else app.query(f"#in-{f.name}")
            tooltip = widgets.first().tooltip
            assert isinstance(tooltip, Text) and str(tooltip) == f.help


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
    (estimat / e)"). The labels now keep LABEL_MIN cells and the numbers are cut with "…"."""

    from gearhead.tui.components.calculator_tab import LABEL_MIN

    app = GearheadApp(blink=False, initial="beam", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-beam", CalculatorTab)
        table = tab.query_one(".results", DataTable)
        widths = {key.value: column.width for key, column in table.columns.items()}
        assert widths["label"] >= LABEL_MIN
        room = table.size.width - 2 - 2 * table.cell_padding * len(table.columns)
        assert sum(widths.values()) <= room
        assert max(row.height for row in table.rows.values()) <= 2
        rendered = "\n".join(strip.text for strip in table.render_lines(table.region.reset_offset))
        assert "Area moment of" in rendered and "(43), (45)" in rendered and "…" in rendered


def test_column_widths_give_labels_their_room_first():
    """Hand-worked splits of a results table's room."""
    from gearhead.tui.components.calculator_tab import column_widths

    # room, others (value), longest label, widest equations -> (label, equations)
    assert column_widths(48, 18, 29, 34) == (16, 14)  # beam at 140 columns: the numbers give way
    assert column_widths(48, 20, 30, 10) == (18, 10)  # motor: the numbers fit beside 18 cells
    assert column_widths(48, 20, 12, 10) == (12, 10)  # short labels: everything fits
    assert column_widths(30, 18, 29, 34) == (9, 3)  # narrow: "(4…", the label the rest
    assert column_widths(48, 18, 29, 0) == (29, 0)  # no equation column
