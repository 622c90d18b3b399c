"""A card's results as one list (Line API): label, value, equation number, and the worst case
and σ while any entry carries a tolerance.

The list draws what the card gives it and nothing else: `show(rows, state)` with the rows of a
solution of exactly the entries on screen ("fresh"), the same rows dimmed while an entry is
wrong ("stale", the status line says so), or the labels with a dimmed "…" while the entries'
solve is still running ("pending"). No result of other entries is ever drawn as current.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from rich.cells import cell_len
from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.binding import Binding
from textual.content import Content
from textual.geometry import Region, Size
from textual.strip import Strip

from .line_view import LineView
from .unit_text import fit_cells

# the rows are the solution of the entries on screen (fresh); of the last valid entries, the ones
# on screen being wrong (stale); of earlier entries while the current are solved (waiting: dimmed,
# then pending: "…" once the solve has taken a moment)
FRESH, STALE, WAITING, PENDING = "fresh", "stale", "waiting", "pending"


@dataclass(frozen=True)
class ResultRow:
    name: str
    label: str
    value: str
    equation: str = ""
    spread: str = ""


class ResultsList(LineView, can_focus=True):
    """The results of one card (module docstring)."""

    COMPONENT_CLASSES = {"results--header", "results--cursor", "results--equation", "results--dim"}

    DEFAULT_CSS = """
    ResultsList {
        height: 1fr;
        overflow-x: hidden;
        scrollbar-gutter: stable;
    }
    ResultsList > .results--header { text-style: bold; color: $text-primary; }
    ResultsList > .results--cursor { background: $panel-lighten-2; }
    ResultsList:focus > .results--cursor { background: $accent; color: $text; }
    ResultsList > .results--equation { color: $text-muted; }
    ResultsList > .results--dim { color: $text-muted; text-style: dim; }
    """

    BINDINGS = [Binding("enter", "next_unit", "Next unit")]

    VALUE_MIN = 12

    def __init__(
        self,
        on_select: Callable[[str], None],
        on_cursor: Callable[[str], None],
        is_current: Callable[[], bool] = lambda: True,
        **kwargs,
    ) -> None:
        super().__init__(**kwargs)
        self.on_select = on_select  # Enter or a click on a result: its next unit
        self.on_cursor = on_cursor  # the help line explains the result under the cursor
        # read when a line is drawn: fresh rows of entries no longer on screen are drawn dimmed
        # (waiting), so a frame drawn before the new entries' result lands never shows old
        # results as current, and one drawn after shows the new result once
        self.is_current = is_current
        self.rows: list[ResultRow] = []
        self.state = FRESH
        self.cursor = 0
        self.value_width = self.VALUE_MIN  # at least the widest value text the outputs can show
        self.equation_width = 0
        self._lines: list[tuple[int, int]] = []  # (row, line within it); row -1: the header
        self._label_lines: list[list[str]] = []
        self._widths = (0, 0, 0, 0)
        self._drawn_waiting = False  # a line was drawn dimmed for entries no longer on screen

    # ---- content ------------------------------------------------------------------------
    def show(self, rows: list[ResultRow], state: str) -> None:
        same_shape = [r.name for r in rows] == [r.name for r in self.rows] and (
            any(r.spread for r in rows) == any(r.spread for r in self.rows)
        )
        before, was = self.rows, self.state
        self.rows, self.state = rows, state
        if not same_shape or any(cell_len(r.value) > self._widths[1] for r in rows):
            self._layout()
            self.cursor = min(self.cursor, max(0, len(rows) - 1))
            self._drawn_waiting = False
            self.refresh()
        elif state != was or self._drawn_waiting:  # every line: those drawn dimmed too
            self._drawn_waiting = False
            self.refresh()
        else:  # the same rows: repaint the lines of those whose text changed
            changed = {i for i, (a, b) in enumerate(zip(before, rows)) if a != b}
            top = self.scroll_offset.y
            for y, (row, _) in enumerate(self._lines):
                if row in changed:
                    self.refresh(Region(0, y - top, self.size.width, 1))

    @property
    def current(self) -> str | None:
        return self.rows[self.cursor].name if 0 <= self.cursor < len(self.rows) else None

    def _layout(self) -> None:
        # the columns fit the region beside the scrollbar's gutter (size.width counts the gutter:
        # the equation column ran under the scrollbar, '(S11' for '(S11)')
        width = self.scrollable_content_region.width or 60
        value = max([self.value_width] + [cell_len(r.value) for r in self.rows])
        spread = max([0] + [cell_len(r.spread) for r in self.rows])
        spread = max(spread, len("Worst case  σ")) if spread else 0
        equation = self.equation_width
        room = width - 2 - value - (spread + 2 if spread else 0)  # 2: padding and the gaps
        label = max(8, room - (equation + 2 if equation else 0))
        if equation and label < 16:  # equation numbers give way to readable labels
            equation = max(3, room - 16 - 2)
            label = max(8, room - equation - 2)
        self._widths = (label, value, equation, spread)
        self._label_lines = [[line.plain for line in Content(r.label).wrap(label)] or [""] for r in self.rows]
        lines = [(-1, 0)]
        for i, wrapped in enumerate(self._label_lines):
            lines += [(i, k) for k in range(len(wrapped))]
        self._lines = lines
        self.virtual_size = Size(width, len(lines))

    def on_resize(self, event: events.Resize) -> None:
        self._layout()

    # ---- drawing ------------------------------------------------------------------------
    def render_line(self, y: int) -> Strip:
        width = self.size.width
        base = self.base_style
        index = y + self.scroll_offset.y
        if not (0 <= index < len(self._lines)):
            return Strip.blank(width, base)
        row, k = self._lines[index]
        label_w, value_w, eq_w, spread_w = self._widths
        style = self.get_component_rich_style
        if row < 0:
            cells = [("Result", label_w), ("Value", value_w)]
            if eq_w:
                cells.append(("Eq.", eq_w))
            if spread_w:
                cells.append(("Worst case  σ", spread_w))
            header = base + style("results--header")
            segments = [Segment(" ", base)]
            for text, w in cells:
                segments += [Segment(fit_cells(text, w), header), Segment(" ", base)]
            return Strip(segments).adjust_cell_length(width, base)
        r = self.rows[row]
        line_style = base
        if row == self.cursor:
            line_style = base + style("results--cursor")
        value_style = line_style
        state = self.state if self.state != FRESH or self.is_current() else WAITING
        self._drawn_waiting |= state == WAITING
        if state != FRESH:
            value_style = line_style + style("results--dim")
        label_style = value_style if state == STALE else line_style
        label = self._label_lines[row][k] if k < len(self._label_lines[row]) else ""
        value = (r.value if state != PENDING else "…") if k == 0 else ""
        segments = [
            Segment(" ", line_style),
            Segment(fit_cells(label, label_w), label_style),
            Segment(" ", line_style),
            Segment(fit_cells(value, value_w), value_style + Style(bold=k == 0 and state == FRESH)),
        ]
        if eq_w:
            eq = fit_cells(r.equation if k == 0 else "", eq_w)
            segments += [Segment(" ", line_style), Segment(eq, line_style + style("results--equation"))]
        if spread_w:
            spread = r.spread if k == 0 and state == FRESH else ""
            segments += [Segment(" ", line_style), Segment(fit_cells(spread, spread_w), value_style)]
        return Strip(segments).adjust_cell_length(width, line_style)

    # ---- the cursor ---------------------------------------------------------------------
    def move_to(self, row: int) -> None:
        if not self.rows:
            return
        self.cursor = max(0, min(row, len(self.rows) - 1))
        self.refresh()
        first = next(i for i, (r, _) in enumerate(self._lines) if r == self.cursor)
        count = len(self._label_lines[self.cursor])
        self.show_lines(first, count)
        self.on_cursor(self.rows[self.cursor].name)

    def _row_a_page_away(self, direction: int) -> int:
        """The row a page of lines (what is in sight) above or below the cursor's."""
        firsts = [
            next(i for i, (r, _) in enumerate(self._lines) if r == row) for row in range(len(self.rows))
        ]
        if not firsts:
            return 0
        goal = firsts[self.cursor] + direction * self.page_lines()
        if direction > 0:
            return next((i for i, line in enumerate(firsts) if line >= goal), len(firsts) - 1)
        return next((i for i in range(len(firsts) - 1, -1, -1) if firsts[i] <= goal), 0)

    def on_key(self, event: events.Key) -> None:
        moves = {"down": 1, "up": -1}
        if event.key in ("pagedown", "pageup"):
            self.move_to(self._row_a_page_away(1 if event.key == "pagedown" else -1))
        elif event.key in moves:
            self.move_to(self.cursor + moves[event.key])
        elif event.key == "home":
            self.move_to(0)
        elif event.key == "end":
            self.move_to(len(self.rows) - 1)
        elif event.key == "enter" and self.current is not None:
            self.on_select(self.current)
        else:
            return
        event.stop()
        event.prevent_default()

    def on_focus(self) -> None:
        self.refresh()
        if self.current is not None:
            self.on_cursor(self.current)

    def on_blur(self) -> None:
        self.refresh()

    def on_click(self, event: events.Click) -> None:
        offset = event.get_content_offset(self)
        if offset is None:
            return
        index = offset.y + self.scroll_offset.y
        if 0 <= index < len(self._lines) and self._lines[index][0] >= 0:
            self.move_to(self._lines[index][0])
            if self.current is not None:
                self.on_select(self.current)

    def action_next_unit(self) -> None:
        if self.current is not None:
            self.on_select(self.current)
