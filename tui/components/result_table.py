"""The results table: Textual's DataTable, with an update of one cell that repaints only its row.

DataTable.update_cell bumps a counter that is part of every render cache's key, so one changed
value re-renders every cell of the table: 30 ms of a 45 ms frame on the gear ratio tab (11 rows,
pilot, profiled). A keystroke changes a few values; here only their rows' cache entries are
dropped and only their rows' region is repainted. This reaches into DataTable's caches (textual
is pinned in pyproject.toml); tests/test_key_render.py checks the repaint against a fresh table.
"""

from __future__ import annotations

from textual.widgets import DataTable
from textual.widgets._data_table import ColumnKey, RowKey


class ResultTable(DataTable):
    def update_cell(
        self,
        row_key: RowKey | str,
        column_key: ColumnKey | str,
        value,
        *,
        update_width: bool = False,
    ) -> None:
        row_key = RowKey(row_key) if isinstance(row_key, str) else row_key
        column_key = ColumnKey(column_key) if isinstance(column_key, str) else column_key
        if update_width or row_key not in self._row_locations or column_key not in self._column_locations:
            # widths move (every row may change) or no such cell (DataTable raises): the full path
            super().update_cell(row_key, column_key, value, update_width=update_width)
            return
        self._data[row_key][column_key] = value
        row_index = self._row_locations.get(row_key)
        # what holds this cell: its rendering (key[:2] is the row and column key; the row's other
        # cells stay cached), the row's lines (key[0] is the row key) and renderables (key (update
        # count, row index)); assembled lines are keyed by y: all dropped, rebuilt from the
        # cached cells at little cost
        for key in [k for k in self._cell_render_cache.keys() if k[0] == row_key and k[1] == column_key]:
            self._cell_render_cache.discard(key)
        for key in [k for k in self._row_render_cache.keys() if k[0] == row_key]:
            self._row_render_cache.discard(key)
        for key in [k for k in self._row_renderable_cache.keys() if k[1] == row_index]:
            self._row_renderable_cache.discard(key)
        self._line_cache.clear()
        self.refresh_row(row_index)

    # DataTable renews every cache key on any resize; only a new width can change a cell (it may
    # wrap). A new height (the warnings box under the table came or went: a layout) keeps them.
    _cells_width: int | None = None

    def _on_resize(self, event) -> None:
        # Textual runs every class's handler along the MRO: DataTable's (the bump) runs unless
        # the default is prevented
        if event.size.width == self._cells_width:
            event.prevent_default()
        self._cells_width = event.size.width

    # Within one render nothing changes the table's styles or size, yet DataTable asks them per
    # line or per row, and each ask walks the DOM up to the screen: its own rich style and size
    # for every line, a component's styles (header, even/odd row) for every row (~35 % of a table
    # render, cProfile). While render_lines runs, each is asked once; outside it, as Textual does.
    _memo: dict | None = None

    def render_lines(self, crop):
        self._memo = {}
        try:
            return super().render_lines(crop)
        finally:
            self._memo = None

    def _remembered(self, key, compute):
        memo = self._memo
        if memo is None:
            return compute()
        if key not in memo:
            memo[key] = compute()
        return memo[key]

    @property
    def rich_style(self):
        return self._remembered("rich_style", lambda: DataTable.rich_style.fget(self))

    @property
    def size(self):
        return self._remembered("size", lambda: DataTable.size.fget(self))

    def get_component_styles(self, *names):
        return self._remembered(
            names, lambda: _RenderedStyles(super(ResultTable, self).get_component_styles(*names))
        )


class _RenderedStyles:
    """A component's styles within one render: its rich style computed once."""

    def __init__(self, styles) -> None:
        self._styles = styles
        self.rich_style = styles.rich_style

    def __getattr__(self, name):
        return getattr(self._styles, name)
