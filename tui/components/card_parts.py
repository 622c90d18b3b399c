"""Two parts of a card below its results: the tables of alternatives and the warnings box. Each
composes into the card's results pane and draws itself from a solution; the card only hands
them what it solved."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

from rich.text import Text
from textual.containers import VerticalScroll
from textual.widget import Widget
from textual.widgets import Static

from gearhead.core.model import Calculator, Solution

from . import card_text
from .result_table import ResultTable


class Tables:
    """A title and a scrollable ResultTable per declared Table (core.model.Table), each column's
    unit in its header; a table of another mode (the sprint's optimise table) is hidden."""

    def __init__(self, calculator: Calculator, entries: dict[str, Any], mount: Callable[..., object]) -> None:
        self.calculator = calculator
        self.entries = entries  # the card's at compose: a table of another mode is not mounted
        self.grids: dict[str, tuple[Static, ResultTable]] = {}
        self._mount = mount  # puts a table's title and grid into the pane (a mode that shows it)

    def compose(self) -> Iterator[Widget]:
        for t in self.calculator.tables:
            title = Static(
                Text(t.title, style="bold"), classes="result-table-title", id=f"table-title-{t.name}"
            )
            heads = [card_text.table_header(c) for c in t.columns if not c.hidden]
            widths = [max(c.width, len(h)) for c, h in zip((c for c in t.columns if not c.hidden), heads)]
            grid = ResultTable(list(zip(heads, widths)), classes="result-table", id=f"table-{t.name}")
            grid.tooltip = (
                "ctrl+g sends the row under the cursor to the calculator it feeds" if t.exports else None
            )
            self.grids[t.name] = (title, grid)
            # a table of another mode than the entries' is mounted when that mode is chosen (show):
            # two widgets fewer to compose and style on the card's first visit, and no layout to
            # hide it at the first solve
            if t.shown_in(self._parsed(t)):
                yield title
                yield grid

    def _parsed(self, table) -> dict[str, Any]:
        """The entries `table.shown_in` reads (its mode and `when` fields), parsed; a field that
        does not parse is left out (its table shows; the first solve decides)."""
        from gearhead.core.errors import InputError

        parsed = {}
        for name in ["mode"] * bool(table.modes) + [name for name, _ in table.when]:
            f = self.calculator.field(name)
            try:
                parsed[name] = f.parse(self.entries.get(name, f.default))
            except InputError:
                pass
        return parsed

    def show(self, solution: Solution, cells: dict[str, list[tuple[str, ...]]]) -> None:
        """Show `solution`'s tables: `cells`, table name -> its rows' cells (card_text.drawn)."""
        entries = solution.entries()
        for t in self.calculator.tables:
            title, grid = self.grids[t.name]
            shown = t.shown_in(entries)
            if grid.parent is None:
                if not shown:
                    continue
                self._mount(title, grid)
            elif grid.display != shown:
                grid.display = title.display = shown
            grid.show(cells[t.name])

    def selected_row(self, solution: Solution | None):
        """(Table, row of Values) under the cursor of the first table that sends rows, or None."""
        if solution is None:
            return None
        for t in self.calculator.tables:
            rows = solution.tables.get(t.name, [])
            grid = self.grids[t.name][1]
            if t.exports and 0 <= grid.cursor_row < len(rows):
                return t, rows[grid.cursor_row]
        return None


class Warnings:
    """The warnings box: it grows with its text, scrolls when long, and hides when empty. Mounted
    (by `mount`, before the status line) with the first warnings the card shows: most cards have
    none, and two widgets fewer to compose and style made a card's first visit cheaper."""

    def __init__(self, mount: Callable[[Widget], object]) -> None:
        self.text_widget = Static("", classes="warnings")
        self.box = VerticalScroll(self.text_widget, classes="warnings-box")
        self._mount = mount
        self.text = ""
        self.lines = 0  # lines the text took when last shown (-1: unknown, lay out)

    def show(self, text: str) -> None:
        if text == self.text:
            return
        # a layout repaints every widget of the screen, so only a text that takes another number
        # of lines asks for one (drivetrain's warnings quote numbers that change with each key)
        content = Text(text, style="yellow")
        width = self.text_widget.content_region.width
        lines = (
            len(content.wrap(self.text_widget.app.console, width))
            if width and text
            else (0 if not text else -1)
        )
        same_height = lines >= 0 and lines == self.lines and self.box.display == bool(text)
        self.text, self.lines = text, lines
        self.text_widget.update(content, layout=not same_height)
        if self.box.display != bool(text):
            self.box.display = bool(text)
        if text and self.box.parent is None:  # the first warnings: the box joins the pane
            self._mount(self.box)
