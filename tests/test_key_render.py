"""What a keystroke makes the app redraw (issue 12): one result row per changed value, the chart
once typing pauses, no layout for warnings of the same height, the entry taken in the key handler."""

from __future__ import annotations

import asyncio

from rich.text import Text
from textual.app import App
from textual.geometry import Region
from textual.widgets import Input

from gearhead.tui.components.result_table import ResultTable

ROWS = [("speed", "5000 rpm"), ("torque", "1.2 N·m"), ("current", "40 A"), ("power", "300 W")]


class TableApp(App):
    def compose(self):
        for name in ("updated", "fresh"):
            table = ResultTable(id=name, cursor_type="row", zebra_stripes=True)
            table.add_column("Result", key="label", width=10)
            table.add_column("Value", key="value", width=12)
            yield table


def _text(table: ResultTable) -> list[str]:
    width, height = table.size
    return [strip.text for strip in table.render_lines(Region(0, 0, width, height))]


async def test_result_table_update_repaints_one_cell_and_matches_a_fresh_table():
    """DataTable.update_cell re-rendered every cell of the table for one changed value. The
    updated table must show exactly what a table built with the new values shows, and only the
    changed cell may be rendered again."""
    app = TableApp()
    async with app.run_test(size=(40, 16)) as pilot:
        updated = app.query_one("#updated", ResultTable)
        fresh = app.query_one("#fresh", ResultTable)
        rendered: list[str] = []  # the cells Rich was asked to render, by their text

        class Cell(Text):
            def __rich_console__(self, console, options):
                rendered.append(self.plain)
                return super().__rich_console__(console, options)

        for name, value in ROWS:
            updated.add_row(Cell(name), Cell(value), key=name)
        await pilot.pause()
        updated.refresh()  # drawn again after the layout's resize (which renews every cache key)
        await pilot.pause()
        _text(updated)  # every cell rendered and cached
        rendered.clear()
        _text(updated)
        assert rendered == []  # nothing changed: all from the cache
        updated.update_cell("torque", "value", Cell("9.9 N·m"))
        after = _text(updated)
        assert rendered == ["9.9 N·m"]  # the changed cell only: not its row's label, no other row

        new_values = dict(ROWS, torque="9.9 N·m")
        for name, _ in ROWS:
            fresh.add_row(Text(name), Text(new_values[name]), key=name)
        await pilot.pause()
        assert after == _text(fresh)
        assert any("9.9 N·m" in line for line in after)


async def test_result_table_keeps_its_cells_when_only_its_height_changes():
    """The warnings box under the results comes and goes with the values typed: the table gets
    shorter or taller, which re-rendered every cell (26 ms on the pneumatics card); a new width
    may wrap cells differently and still renders them again."""
    rendered: list[str] = []

    class Cell(Text):
        def __rich_console__(self, console, options):
            rendered.append(self.plain)
            return super().__rich_console__(console, options)

    class Sized(App):
        CSS = "ResultTable { height: 10; width: 40; }"

        def compose(self):
            table = ResultTable()
            table.add_column("Result", key="label", width=10)
            table.add_column("Value", key="value", width=12)
            yield table

    app = Sized()
    async with app.run_test(size=(60, 20)) as pilot:
        table = app.query_one(ResultTable)
        for name, value in ROWS:
            table.add_row(Cell(name), Cell(value), key=name)
        await pilot.pause()
        table.refresh()
        await pilot.pause()
        rendered.clear()
        table.styles.height = 8
        await pilot.pause()
        assert table.size.height == 8
        table._styles_cache.clear()  # the lines drawn again, as after a layout
        _text(table)
        assert rendered == []
        table.styles.width = 36
        await pilot.pause()
        table._styles_cache.clear()
        _text(table)
        assert sorted(rendered) == sorted(text for row in ROWS for text in row)


async def test_result_table_styles_follow_a_class_change():
    """Styles are remembered within one render only: a class the stylesheet colours shows in
    the next render's row style."""
    app = TableApp()
    app.CSS = "ResultTable.dim > .datatable--even-row { color: red; }"
    async with app.run_test(size=(40, 16)) as pilot:
        table = app.query_one("#updated", ResultTable)
        for name, value in ROWS:
            table.add_row(Text(name), Text(value), key=name)
        await pilot.pause()
        before = table._get_row_style(0, table.rich_style)
        table.add_class("dim")
        await pilot.pause()
        after = table._get_row_style(0, table.rich_style)
        assert before != after
        assert after.color.triplet == (255, 0, 0)


async def test_field_input_hands_over_the_entry_before_its_changed_message():
    """The card takes a typed entry in the key handler (FieldInput.edited), so the result can be
    in the frame that echoes the key; Input.Changed arrives after that frame."""
    from gearhead.tui.components.field_input import FieldInput

    order: list[tuple[str, str]] = []

    class Harness(App):
        def compose(self):
            entry = FieldInput("12")
            entry.edited = lambda e: order.append(("edited", e.value))
            yield entry

        def on_input_changed(self, event: Input.Changed) -> None:
            order.append(("changed", event.value))

    app = Harness()
    async with app.run_test(size=(40, 5)) as pilot:
        entry = app.query_one(FieldInput)
        entry.focus()
        entry.cursor_position = 2
        await pilot.pause()
        order.clear()
        await pilot.press("backspace")  # a binding: run inline by FieldInput
        await pilot.press("5")  # a printable key
        await pilot.press("left")  # moves the cursor: no new value, no hand-over
        await pilot.pause()
    assert order == [("edited", "1"), ("changed", "1"), ("edited", "15"), ("changed", "15")]


async def test_chart_waits_for_a_pause_and_draws_once_for_a_burst():
    """A chart costs more than a frame: it follows the results once typing pauses, drawn once
    for a burst of keys, and the tab counts as busy until it is drawn (tests wait for that)."""
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab
    from gearhead.tui.components.plot_panel import PlotPanel
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-motor", CalculatorTab)
        panel = tab.query_one(PlotPanel)
        drawn = []
        show = panel.show

        async def counting(solution):
            drawn.append(solution.inputs["voltage"].value)
            await show(solution)

        panel.show = counting
        panel.QUIET_S = 1.0  # a pause that a loaded machine cannot pass between two keys
        entry = tab.query_one("#in-voltage", Input)
        entry.focus()
        entry.cursor_position = len(entry.value)
        from textual import events

        for key, char in (("backspace", "\x7f"), ("backspace", "\x7f"), ("1", "1"), ("1", "1")):
            app.post_message(events.Key(key, char))  # as the driver delivers a fast typist's keys
            await asyncio.sleep(0.02)
        for _ in range(100):  # the keys are handled (the entry holds them all)
            if entry.value == "11":
                break
            await asyncio.sleep(0.01)
        assert tab.busy  # the chart is pending
        await settle(pilot)
        assert not tab.busy
        assert drawn == [11.0]  # once, with the last entry


async def test_warnings_of_the_same_height_do_not_lay_the_screen_out():
    """A layout repaints every field of the card (25 ms on the drivetrain card); warnings whose
    numbers change with each key keep their height and only need a repaint."""
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        warnings = tab._parts.warnings
        calls = []
        update = warnings.update

        def spying(content="", *, layout=True):
            calls.append(layout)
            return update(content, layout=layout)

        warnings.update = spying
        tab._show_warnings(["speed 1 is high"])  # the box appears: its width is known after
        await pilot.pause()
        tab._show_warnings(["speed 2 is high"])  # the first at a known width: laid out once more
        await pilot.pause()
        tab._show_warnings(["speed 3 is high"])  # same height
        tab._show_warnings(["speed 3 is high"])  # same text: nothing to do
        tab._show_warnings(["speed 2 is high", "and a second line"])
        await pilot.pause()
        tab._show_warnings([])
        await asyncio.sleep(0)
    assert calls == [True, True, False, True, True]


async def test_closing_while_a_chart_is_pending_or_mounting_is_quiet():
    """A chart is drawn 80 ms after the results, so the app may close meanwhile (ctrl+q right
    after a key, or a card warmed up in idle time): the pending chart is dropped, and one whose
    widget was still mounting draws nothing, instead of a traceback on the way out."""
    from gearhead.core.model import Plot, Solution
    from gearhead.tui.components.plot_panel import PlotPanel

    plots = (Plot("Force", ("a",), "x", "length", "m", "F", "force", "N"),)
    solution = Solution("x", {}, {}, [], {"a": ([0.0, 1.0], [0.0, 1.0])})

    class Harness(App):
        def compose(self):
            yield PlotPanel(plots)

    for wait in (0.0, 0.002, 0.005, 0.01, 0.02):
        app = Harness()
        async with app.run_test(size=(80, 24)):
            panel = app.query_one(PlotPanel)
            panel.QUIET_S = 0.005
            panel.show_soon(solution)
            await asyncio.sleep(wait)
        # leaving run_test raised if a task of the app failed
        assert app.return_code in (None, 0)
