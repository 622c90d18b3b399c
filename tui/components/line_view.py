"""What the card's Line-API widgets (the sheet, the results list) share."""

from __future__ import annotations

from rich.style import Style
from textual.geometry import Region
from textual.scroll_view import ScrollView
from textual.strip import Strip


class LineView(ScrollView):
    """A ScrollView whose `base_style` is the widget's rich style, asked once per render: it walks
    the DOM up to the screen, and asked per line it was most of a key's frame (19 of 43 ms)."""

    _base_style: Style | None = None

    @property
    def base_style(self) -> Style:
        return self._base_style or self.rich_style

    def render_lines(self, crop: Region) -> list[Strip]:
        self._base_style = self.rich_style
        try:
            return super().render_lines(crop)
        finally:
            self._base_style = None
