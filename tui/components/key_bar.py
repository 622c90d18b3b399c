"""The key bar: one line naming the keys that act now (the focused widget's and the app's).

Textual's Footer is a widget per key, recomposed whenever the screen's bindings are refreshed:
every focus change and card switch (8 recomposes and ~20 key widgets laid out again on a first
card visit). This bar is one Line-API widget that redraws its line when the keys it shows
change (the screen's public `bindings_updated_signal`), and runs a key's action on a click.
"""

from __future__ import annotations

from rich.cells import cell_len
from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.strip import Strip
from textual.widget import Widget


class KeyBar(Widget):
    COMPONENT_CLASSES = {"key-bar--key", "key-bar--label"}

    DEFAULT_CSS = """
    KeyBar {
        dock: bottom;
        height: 1;  /* 2 when the keys need it (_fit_height) */
        background: $footer-background;
        color: $footer-foreground;
    }
    KeyBar > .key-bar--key { color: $footer-key-foreground; text-style: bold; }
    KeyBar > .key-bar--label { color: $footer-description-foreground; }
    """

    def __init__(self, **kwargs) -> None:
        super().__init__(**kwargs)
        self.keys: tuple[tuple[str, str, str], ...] = ()  # (key shown, label, key) left to right
        self._spans: list[tuple[int, int, str, int]] = []  # (x from, x to, key, line) for clicks

    def on_mount(self) -> None:
        self.screen.bindings_updated_signal.subscribe(self, self._bindings_changed)
        self.call_after_refresh(self._bindings_changed, self.screen)  # once the strips are composed

    def on_unmount(self) -> None:
        self.screen.bindings_updated_signal.unsubscribe(self)

    def _bindings_changed(self, screen) -> None:
        app = self.app
        shown = []
        for key, active in screen.active_bindings.items():
            binding = active.binding
            if binding.show and active.enabled:
                shown.append((app.get_key_display(binding), binding.description, key))
        palette = app.COMMAND_PALETTE_BINDING if app.ENABLE_COMMAND_PALETTE else None
        if palette and palette in screen.active_bindings:
            shown.append((app.get_key_display(screen.active_bindings[palette].binding), "palette", palette))
        keys = tuple(shown)
        if keys != self.keys:  # a focus move between rows of the sheet changes nothing here
            self.keys = keys
            self._spans = []
            self._fit_height()
            self.refresh()

    def _rows(self, width: int) -> list[list[tuple[str, str, str]]]:
        """The keys packed into lines of `width` cells: a narrow terminal gets a second line
        rather than losing the keys at the end (at 80 columns ^w and ^p were cut off)."""
        rows: list[list[tuple[str, str, str]]] = [[]]
        used = 0
        for item in self.keys:
            cells = cell_len(f" {item[0]} {item[1]} ")
            if rows[-1] and used + cells > width:
                rows.append([])
                used = 0
            rows[-1].append(item)
            used += cells
        return rows

    def _fit_height(self) -> None:
        height = len(self._rows(self.size.width)) if self.size.width else 1
        if self.styles.height is None or self.styles.height.value != height:
            self.styles.height = height

    def on_resize(self, event: events.Resize) -> None:
        self._fit_height()

    def render_line(self, y: int) -> Strip:
        base = self.rich_style
        key_style = base + self.get_component_rich_style("key-bar--key")
        label_style = base + self.get_component_rich_style("key-bar--label")
        rows = self._rows(self.size.width)
        segments: list[Segment] = []
        spans = []
        x = 0
        for shown, label, key in rows[y] if y < len(rows) else []:
            cells = [Segment(f" {shown} ", key_style), Segment(f"{label} ", label_style)]
            width = sum(s.cell_length for s in cells)
            spans.append((x, x + width, key))
            segments += cells
            x += width
        self._spans = [*(span for span in self._spans if span[3] != y), *((a, b, k, y) for a, b, k in spans)]
        return Strip(segments).adjust_cell_length(self.size.width, base or Style())

    def on_click(self, event: events.Click) -> None:
        for start, end, key, line in self._spans:
            if line == event.y and start <= event.x < end:
                self.app.simulate_key(key)  # as if typed: the focused widget's key first
                return
