"""A row of tabs drawn as one widget (Textual's Line API, as DataTable draws its cells).

Textual's Tabs is a widget per tab inside three containers, with an Underline widget below: 10-11
widgets a strip, ~20 for the app's two, each rendered and cut at its edges by the compositor on
every frame that shows a card, and the underline animated over 0.3 s (a repaint a frame, ~19 of
them after each card switch). This strip draws the same two lines itself (the labels, then the
bar under the active tab) and behaves as Tabs does for the keys and the mouse: ← → move to the
previous / next tab (wrapping), a click on a label or on the bar under it focuses the strip and
activates that tab, a tab under the pointer is highlighted; a change of the active tab posts
`TabStrip.TabActivated` (a message, as Tabs posts Tabs.TabActivated). It looks as Tabs looks (its
CSS below restates Tabs', Tab's and Underline's rules as component classes), without the bar's
animation.
"""

from __future__ import annotations

from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.binding import Binding
from textual.geometry import Region, clamp
from textual.message import Message
from textual.reactive import reactive
from textual.strip import Strip
from textual.widget import Widget

BAR, HALF_BAR_LEFT, HALF_BAR_RIGHT = "━", "╺", "╸"  # textual.renderables.bar.Bar's


class TabStrip(Widget, can_focus=True):
    """Tabs as one widget: `tabs` is ((id, label), ...) left to right, `active` the active id."""

    ALLOW_SELECT = False
    COMPONENT_CLASSES = {"tab-strip--tab", "tab-strip--hover", "tab-strip--active", "tab-strip--bar"}
    # Tabs' own rules (textual/widgets/_tabs.py: Tabs, Tab, Underline), on component classes
    DEFAULT_CSS = """
    TabStrip {
        width: 100%;
        height: 2;
        pointer: pointer;
        & > .tab-strip--tab { color: $foreground 50%; }
        & > .tab-strip--hover { color: $foreground; }
        & > .tab-strip--active { color: $foreground; }
        & > .tab-strip--bar { color: $block-cursor-background; background: $foreground 10%; }
        &:focus {
            & > .tab-strip--bar { background: $foreground 30%; }
            & > .tab-strip--active {
                text-style: $block-cursor-text-style;
                color: $block-cursor-foreground;
                background: $block-cursor-background;
            }
        }
        &:ansi {
            & > .tab-strip--tab { text-style: dim; }
            & > .tab-strip--hover { text-style: dim; }
            & > .tab-strip--active { text-style: not dim bold; }
            & > .tab-strip--bar { color: $block-cursor-background; background: $border-blurred; }
        }
    }
    """
    BINDINGS = [
        Binding("left", "previous_tab", "Previous tab", show=False),
        Binding("right", "next_tab", "Next tab", show=False),
    ]

    active: reactive[str] = reactive("", init=False)
    hovered: reactive[int | None] = reactive(None, init=False)

    class TabActivated(Message):
        """The active tab changed (a key, a click, or `active` set): `tab_id` on `strip`."""

        def __init__(self, strip: TabStrip, tab_id: str) -> None:
            super().__init__()
            self.strip, self.tab_id = strip, tab_id

        @property
        def control(self) -> TabStrip:
            return self.strip

    def __init__(self, tabs: list[tuple[str, str]], active: str, **kwargs) -> None:
        super().__init__(**kwargs)
        self.tabs = tuple(tabs)
        self._scroll = 0  # cells scrolled off the left (a strip wider than the terminal)
        self.set_reactive(TabStrip.active, active)

    # ---- geometry -------------------------------------------------------------------------
    def _spans(self) -> list[tuple[int, int]]:
        """(start, end) cells of each tab, its one-cell padding either side included."""
        spans, x = [], 0
        for _id, label in self.tabs:
            width = len(label) + 2
            spans.append((x, x + width))
            x += width
        return spans

    def _rescroll(self) -> None:
        """Scroll the active tab into view as Tabs does (Widget.scroll_to_center from the current
        offset: the tab's centre to the strip's, int() of the difference + 0.5, its left edge kept
        in view), within the tabs' extent; 0 while every tab fits."""
        spans, width = self._spans(), self.size.width
        index = self._index(self.active)
        if index is None or not width:
            return
        total = spans[-1][1]
        start, end = spans[index]
        scroll = self._scroll
        new = clamp(scroll + int(start + (end - start) / 2 - (scroll + width / 2) + 0.5), 0, total - width)
        if not new <= start < new + width:  # origin_visible: the least scroll that shows the tab
            fits = scroll <= start and min(end, start + width) <= scroll + width
            left, right = start - scroll, start - (scroll + width - min(end - start, width))
            new = clamp(scroll + (0 if fits else min(left, right, key=abs)), 0, total - width)
        self._scroll = max(0, new)

    def _index(self, tab_id: str) -> int | None:
        return next((i for i, (tid, _) in enumerate(self.tabs) if tid == tab_id), None)

    def span(self, tab_id: str) -> tuple[int, int]:
        """The cells a tab takes on the strip (its padding included), before any scroll."""
        index = self._index(tab_id)
        if index is None:
            raise KeyError(tab_id)
        return self._spans()[index]

    def tab_at(self, x: int) -> str | None:
        """The id of the tab at cell x of the strip (either line), or None."""
        spans = self._spans()
        x += self._scroll
        return next((self.tabs[i][0] for i, (a, b) in enumerate(spans) if a <= x < b), None)

    # ---- drawing --------------------------------------------------------------------------
    def render_line(self, y: int) -> Strip:
        spans = self._spans()
        scroll = self._scroll
        width = self.size.width
        base = self.rich_style
        blank = Style(bgcolor=base.bgcolor)  # Tab's padding: the background alone
        active = self._index(self.active)
        if y == 0:
            segments: list[Segment] = []
            for i, (_id, label) in enumerate(self.tabs):
                if i == active:
                    style = self.get_component_rich_style("tab-strip--active")
                    pad = Style(bgcolor=style.bgcolor)
                elif i == self.hovered:
                    style, pad = self.get_component_rich_style("tab-strip--hover"), blank
                else:
                    style, pad = self.get_component_rich_style("tab-strip--tab"), blank
                segments += [Segment(" ", pad), Segment(label, style), Segment(" ", pad)]
            line = Strip(segments)
        elif y == 1:
            line = Strip(self._bar(spans, active, max(width + scroll, spans[-1][1] if spans else 0)))
        else:
            return Strip.blank(width, base)
        if scroll:
            line = line.crop(scroll, scroll + width)
        return line.adjust_cell_length(width, blank)

    def _bar(self, spans: list[tuple[int, int]], active: int | None, width: int) -> list[Segment]:
        """The bar as textual.renderables.Bar draws it for Underline: the active tab's label
        highlighted, a half bar either side of it in the bar's own colour."""
        bar = self.get_component_rich_style("tab-strip--bar")
        base = Style(bgcolor=self.rich_style.bgcolor)
        back = base + Style.from_color(bar.bgcolor)
        if active is None:
            return [Segment(BAR * width, back)]
        start, end = spans[active][0] + 1, spans[active][1] - 1  # the label, padding aside
        segments = [Segment(BAR * (start - 1), back)] if start > 1 else []
        if start > 0:
            segments.append(Segment(HALF_BAR_RIGHT, back))
        segments.append(Segment(BAR * (end - start), base + Style.from_color(bar.color)))
        if end != width:
            segments.append(Segment(HALF_BAR_LEFT + BAR * (width - end - 1), back))
        return segments

    # ---- behaviour ------------------------------------------------------------------------
    def watch_active(self, active: str) -> None:
        self._rescroll()
        self.refresh()
        if active:
            self.post_message(self.TabActivated(self, active))

    def watch_hovered(self) -> None:
        self.refresh(Region(0, 0, self.size.width, 1))  # the labels' line

    def _move(self, step: int) -> None:
        if not self.tabs:
            return
        index = self._index(self.active)
        index = (0 if step > 0 else -1) if index is None else (index + step) % len(self.tabs)
        self.active = self.tabs[index][0]

    def action_next_tab(self) -> None:
        self._move(+1)

    def action_previous_tab(self) -> None:
        self._move(-1)

    def on_click(self, event: events.Click) -> None:
        event.stop()
        self.focus()
        tab_id = self.tab_at(event.x)
        if tab_id is not None:
            self.active = tab_id

    def on_mouse_move(self, event: events.MouseMove) -> None:
        tab_id = self.tab_at(event.x) if event.y == 0 else None
        self.hovered = None if tab_id is None else self._index(tab_id)

    def on_leave(self, event: events.Leave) -> None:
        self.hovered = None

    def on_resize(self, event: events.Resize) -> None:
        self._rescroll()
        self.refresh()
