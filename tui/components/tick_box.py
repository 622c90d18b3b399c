"""One look for every tick box: `[x]` on, `[ ]` off, as the sheet draws its flags.

Textual's Checkbox and SelectionList draw `▐X▌` both on and off, told apart by colour only: under
NO_COLOR (and for a colour-blind user) a ticked Overwrite looked like an unticked one (issue 40).
"""

from __future__ import annotations

from rich.segment import Segment
from textual.strip import Strip
from textual.widgets import Checkbox, SelectionList
from textual.widgets.option_list import OptionDoesNotExist
from textual.widgets.selection_list import SelectionType

ON, OFF = "x", " "


class TickBox(Checkbox):
    """A Checkbox drawn `[x]` / `[ ]`."""

    BUTTON_LEFT = "["
    BUTTON_RIGHT = "]"

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.BUTTON_INNER = ON if self.value else OFF

    def watch_value(self) -> None:
        self.BUTTON_INNER = ON if self.value else OFF  # the class's is one character for both
        super().watch_value()


class TickList(SelectionList[SelectionType]):
    """A SelectionList whose boxes read `[x]` / `[ ]` (it draws Textual's `▐X▌` otherwise)."""

    def render_line(self, y: int) -> Strip:
        line = super().render_line(y)
        try:
            option = self.get_option_at_index(self.scroll_offset.y + y)
        except OptionDoesNotExist:
            return line
        segments = list(line)
        if len(segments) < 3:
            return line
        inner = ON if option.value in self.selected else OFF
        style = segments[1].style
        ticks = [Segment("[", style), Segment(inner, style), Segment("]", style)]
        return Strip([*ticks, *segments[3:]])
