"""The command palette: Textual's, with PageUp/PageDown safe while its list is still filling.

Textual 8.2.8's CommandPalette passes PageUp/PageDown to its option list, whose page move reads
the line of the highlighted option from a table built when the list is next drawn: ctrl+p then
PageDown within ~50 ms raised KeyError 0 there and ended the app (issue 41; seen in 8 of 12 exits
of a key storm). Until that is fixed upstream, a page move the list cannot make yet goes to the
first or last command instead.

Enter pressed again before the palette has gone (Enter Enter in one burst, a key storm) submitted
its input a second time: Textual's palette dismissed itself again, popping the screen below it
(a workbook closed) and running the command twice, then raised ScreenStackError on the last
screen and ended the app. A palette no longer on top has been dismissed: its input's and buttons'
events are dropped and a second dismiss does nothing (as tui/components/dialog.py).
"""

from __future__ import annotations

from textual import on
from textual.await_complete import AwaitComplete
from textual.binding import Binding
from textual.command import CommandList, CommandPalette
from textual.widgets import Button, Input, OptionList


class GearheadCommandPalette(CommandPalette):
    BINDINGS = [
        Binding("pagedown", "page(1)", "Next page", show=False),
        Binding("pageup", "page(-1)", "Previous page", show=False),
    ]

    def action_page(self, direction: int) -> None:
        commands = self.query_one(CommandList)
        if not commands.option_count:
            return
        try:
            commands.action_page_down() if direction > 0 else commands.action_page_up()
        except KeyError:  # the list's lines are not laid out yet (module docstring)
            commands.action_last() if direction > 0 else commands.action_first()

    @on(Input.Submitted)
    @on(Button.Pressed)
    @on(OptionList.OptionSelected)
    def _gone(self, event) -> None:
        if not self.is_active:  # dismissed already (module docstring): not Textual's handler too
            event.stop()
            event.prevent_default()

    def dismiss(self, result=None) -> AwaitComplete:
        if not self.is_active:
            return AwaitComplete.nothing()
        return super().dismiss(result)
