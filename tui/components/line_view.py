"""What the card's Line-API widgets (the sheet, the results list) share."""

from __future__ import annotations

from rich.style import Style
from textual.geometry import Region, Size
from textual.reactive import Reactive
from textual.screen import Screen
from textual.scroll_view import ScrollView
from textual.strip import Strip
from textual.widget import Widget


class LineView(ScrollView):
    """A ScrollView whose `base_style` is the widget's rich style, asked once per render: it walks
    the DOM up to the screen, and asked per line it was most of a key's frame (19 of 43 ms)."""

    _base_style: Style | None = None

    # Widget's virtual_size asks for a layout of the whole screen on every change: a reflow and a
    # repaint of every widget on screen. A card's first solve set three of them (results and table
    # rows; the sheet's and the list's width once sized), a second layout in its first visit, and
    # a table whose row count follows the entries did it on keys. Here a change repaints the view
    # and asks for a layout only when one can move something: the view is sized by its content
    # (height: auto, as on a narrow screen) or a scrollbar shows, before or after.
    virtual_size = Reactive(Size(0, 0), layout=False)

    def watch_virtual_size(self, old: Size, new: Size) -> None:
        styles, region = self.styles, self.scrollable_content_region
        auto = (styles.height is not None and styles.height.is_auto and old.height != new.height) or (
            styles.width is not None and styles.width.is_auto and old.width != new.width
        )
        tall = styles.overflow_y != "hidden" and max(old.height, new.height) > region.height
        wide = styles.overflow_x != "hidden" and max(old.width, new.width) > region.width
        if auto or tall or wide:
            self.refresh(layout=True)

    @property
    def base_style(self) -> Style:
        return self._base_style or self.rich_style

    def render_lines(self, crop: Region) -> list[Strip]:
        self._base_style = self.rich_style
        try:
            return super().render_lines(crop)
        finally:
            self._base_style = None

    def show_lines(self, top: int, count: int) -> None:
        """Scroll lines top..top+count into view: in this widget, and on a narrow screen, where
        the card scrolls as a whole and this widget is as tall as its lines, in the nearest
        scrolling container (Textual's scroll_visible shows a widget, not a line of it)."""
        self.scroll_to_region(Region(0, top, 1, count), animate=False, force=True)
        self.call_after_refresh(self._show_lines_in_container, top, count)

    def _show_lines_in_container(self, top: int, count: int) -> None:
        if not self.is_mounted:
            return
        container = next(
            (node for node in self.ancestors if isinstance(node, Widget) and node.allow_vertical_scroll), None
        )
        if container is None or isinstance(container, Screen):
            return
        screen_y = self.content_region.y + top - self.scroll_offset.y
        y = screen_y - container.content_region.y + container.scroll_offset.y
        container.scroll_to_region(Region(0, y, 1, count), animate=False, force=True)

    def page_lines(self) -> int:
        """How many lines PageUp/PageDown move: the part of this widget in sight (its own height,
        or on a narrow screen its scrolling container's)."""
        container = next(
            (node for node in self.ancestors if isinstance(node, Widget) and node.allow_vertical_scroll), None
        )
        visible = self.scrollable_content_region.height
        if container is not None and not isinstance(container, Screen):
            visible = min(visible, container.scrollable_content_region.height)
        return max(1, visible - 1)
