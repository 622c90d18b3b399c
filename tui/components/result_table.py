"""A card's table of alternatives as one Line-API widget: a fixed header line, a row per
alternative, zebra stripes and a row cursor, styled as Textual's DataTable.

Why not DataTable: any change to a DataTable (clear, add_row, update_cell) drops its render
caches, and it then renders every cell again through Rich (padding, wrapping): 40-85 ms per key
on the ratio finder's 40-row table, the most of a key's frame. Here a line is a few segments of
plain text, and a new solve repaints only the lines whose text changed.
"""

from __future__ import annotations

from rich.segment import Segment
from textual import events
from textual.geometry import Region, Size
from textual.strip import Strip

from .line_view import LineView
from .unit_text import fit_cells


class ResultTable(LineView, can_focus=True):
    """Columns (header text, width in cells) and rows of cell texts; `cursor_row` is the row
    under the cursor (ctrl+g sends it)."""

    COMPONENT_CLASSES = {
        "result-table--header",
        "result-table--cursor",
        "result-table--even-row",
    }

    # DataTable's look (its DEFAULT_CSS, the rules a row-cursor table with stripes uses)
    DEFAULT_CSS = """
    ResultTable {
        background: $surface;
        color: $foreground;
        height: auto;
        max-height: 100%;
        &:focus {
            background-tint: $foreground 5%;
            & > .result-table--cursor {
                background: $block-cursor-background;
                color: $block-cursor-foreground;
                text-style: $block-cursor-text-style;
            }
            & > .result-table--header {
                background-tint: $foreground 5%;
            }
        }
        &:dark > .result-table--even-row {
            background: $surface-darken-1 40%;
        }
        & > .result-table--header {
            text-style: bold;
            background: $panel;
            color: $foreground;
        }
        &:ansi > .result-table--header {
            background: ansi_bright_blue;
            color: ansi_default;
        }
        & > .result-table--even-row {
            background: $surface-lighten-1 50%;
        }
        & > .result-table--cursor {
            background: $block-cursor-blurred-background;
            color: $block-cursor-blurred-foreground;
            text-style: $block-cursor-blurred-text-style;
        }
    }
    """

    PADDING = 1  # cells each side of a column, as DataTable's cell_padding

    def __init__(self, columns: list[tuple[str, int]], **kwargs) -> None:
        super().__init__(**kwargs)
        self.columns = columns
        self.rows: list[tuple[str, ...]] = []
        self.cursor_row = 0
        self._width = sum(w + 2 * self.PADDING for _, w in columns)
        self.virtual_size = Size(self._width, 1)

    @property
    def row_count(self) -> int:
        return len(self.rows)

    def show(self, rows: list[tuple[str, ...]]) -> None:
        """Draw these rows; the cursor stays on its row while there is one."""
        before, self.rows = self.rows, rows
        if len(rows) != len(before):
            self.virtual_size = Size(self._width, len(rows) + 1)
            self.cursor_row = min(self.cursor_row, max(0, len(rows) - 1))
            self.refresh()
            return
        top = self.scroll_offset.y
        for i, (a, b) in enumerate(zip(before, rows)):
            if a != b and 0 <= i + 1 - top < self.size.height:
                self.refresh(Region(0, i + 1 - top, self.size.width, 1))

    def move_cursor(self, row: int, animate: bool = False) -> None:
        """Put the cursor on `row` and scroll it into sight (below the fixed header)."""
        if not self.rows:
            return
        self.cursor_row = max(0, min(row, len(self.rows) - 1))
        self.refresh()
        self.scroll_to_region(Region(0, self.cursor_row, 1, 2), animate=animate, force=True)

    # ---- drawing ------------------------------------------------------------------------
    def _cells(self, texts, style) -> list[Segment]:
        pad = " " * self.PADDING
        return [Segment(f"{pad}{fit_cells(t, w)}{pad}", style) for t, (_, w) in zip(texts, self.columns)]

    def render_line(self, y: int) -> Strip:
        width, base = self.size.width, self.base_style
        x = self.scroll_offset.x
        if y == 0:  # the header stays in sight while the rows scroll
            style = base + self.get_component_rich_style("result-table--header")
            strip = Strip(self._cells([h for h, _ in self.columns], style))
        else:
            index = y - 1 + self.scroll_offset.y
            if not 0 <= index < len(self.rows):
                return Strip.blank(width, base)
            style = base
            if index % 2 == 0:
                style += self.get_component_rich_style("result-table--even-row")
            if index == self.cursor_row:
                style += self.get_component_rich_style("result-table--cursor")
            strip = Strip(self._cells(self.rows[index], style))
        return strip.crop(x, x + width).adjust_cell_length(width, base)

    # ---- keys and the mouse ---------------------------------------------------------------
    def on_key(self, event: events.Key) -> None:
        page = max(1, self.scrollable_content_region.height - 2)
        moves = {"down": 1, "up": -1, "pagedown": page, "pageup": -page}
        if event.key in moves:
            self.move_cursor(self.cursor_row + moves[event.key])
        elif event.key == "home":
            self.move_cursor(0)
        elif event.key == "end":
            self.move_cursor(len(self.rows) - 1)
        elif event.key in ("left", "right"):
            self.scroll_relative(x=-4 if event.key == "left" else 4, animate=False)
        else:
            return
        event.stop()
        event.prevent_default()

    def on_click(self, event: events.Click) -> None:
        offset = event.get_content_offset(self)
        if offset is not None and offset.y > 0:
            index = offset.y - 1 + self.scroll_offset.y
            if 0 <= index < len(self.rows):
                self.move_cursor(index)
