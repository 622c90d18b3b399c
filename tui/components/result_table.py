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
        # the caches keyed by this row: its cells (key[0] is the row key), its lines (key[0]), its
        # renderables (key (update count, row index)); assembled lines are keyed by y: all dropped,
        # rebuilding them from the cached cells costs little
        for cache in (self._cell_render_cache, self._row_render_cache):
            for key in [k for k in cache.keys() if k[0] == row_key]:
                cache.discard(key)
        for key in [k for k in self._row_renderable_cache.keys() if k[1] == row_index]:
            self._row_renderable_cache.discard(key)
        self._line_cache.clear()
        self.refresh_row(row_index)

    # DataTable asks a row's style from its component styles for every row it renders, and each
    # ask walks the DOM up to the screen (61 walks and ~35 % of a full table render, cProfile).
    # Textual caches component rich styles the same way (Widget.get_component_rich_style), and
    # drops them when styles change (notify_style_update).
    _row_styles: dict[str, object] | None = None

    def notify_style_update(self) -> None:
        self._row_styles = None
        super().notify_style_update()

    def _get_row_style(self, row_index: int, base_style):
        if row_index == -1:
            name = "datatable--header"
        elif row_index < self.fixed_rows:
            name = "datatable--fixed"
        elif self.zebra_stripes:
            name = "datatable--odd-row" if row_index % 2 else "datatable--even-row"
        else:
            return base_style
        if self._row_styles is None:
            self._row_styles = {}
        if name not in self._row_styles:
            self._row_styles[name] = self.get_component_styles(name).rich_style
        return self._row_styles[name]

    # render_line asks the table's own rich style (another walk to the screen) for every line;
    # it cannot change within one render, so it is asked once per render_lines call
    _base_style = None

    @property
    def rich_style(self):
        return self._base_style if self._base_style is not None else super().rich_style

    def render_lines(self, crop):
        self._base_style = super().rich_style
        try:
            return super().render_lines(crop)
        finally:
            self._base_style = None
