"""A line view's virtual size asks for a layout of the screen only when it can move something
(components/line_view.py): a table whose rows change and still fit, or a list or sheet sized the
first time, is a repaint; rows that need a scrollbar, or a view sized by its content, lay out."""

from __future__ import annotations

from textual.app import App, ComposeResult

from gearhead.tui.components.result_table import ResultTable


class TableApp(App):
    CSS = "ResultTable { height: 10; }  #auto { height: auto; max-height: 100; }"

    def compose(self) -> ComposeResult:
        yield ResultTable([("A", 6), ("B", 6)], id="fixed")
        yield ResultTable([("A", 6), ("B", 6)], id="auto")


def rows(n: int) -> list[tuple[str, ...]]:
    return [(str(i), str(2 * i)) for i in range(n)]


async def test_rows_that_fit_repaint_without_a_layout_and_a_scrollbar_lays_out() -> None:
    app = TableApp()
    layouts: list[object] = []
    async with app.run_test(size=(60, 40)) as pilot:
        app.screen.screen_layout_refresh_signal.subscribe(app, layouts.append)
        table = app.query_one("#fixed", ResultTable)
        table.show(rows(3))
        await pilot.pause(0.1)
        layouts.clear()
        table.show(rows(5))  # 6 lines in 10: no scrollbar before or after
        await pilot.pause(0.1)
        assert layouts == []
        assert table.virtual_size.height == 6
        table.show(rows(30))  # a scrollbar appears: the screen is laid out again
        await pilot.pause(0.1)
        assert layouts
        assert table.show_vertical_scrollbar
        layouts.clear()
        table.show(rows(4))  # and goes
        await pilot.pause(0.1)
        assert layouts
        assert not table.show_vertical_scrollbar


async def test_a_view_sized_by_its_rows_lays_out() -> None:
    app = TableApp()
    async with app.run_test(size=(60, 40)) as pilot:
        table = app.query_one("#auto", ResultTable)
        table.show(rows(3))
        await pilot.pause(0.1)
        assert table.size.height == 4
        table.show(rows(7))
        await pilot.pause(0.1)
        assert table.size.height == 8
