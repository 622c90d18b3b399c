"""The list a choice row of the sheet opens: Enter or a click picks, Esc leaves it unchanged,
letters jump to the next choice they begin (type-ahead, as on the row itself)."""

from __future__ import annotations

from collections.abc import Sequence
from time import monotonic

from rich.text import Text
from textual import events
from textual.app import ComposeResult
from textual.containers import Vertical
from textual.widgets import Label, OptionList
from textual.widgets.option_list import Option

from .dialog import Dialog

TYPE_AHEAD_S = 1.0


class TypeAhead:
    """Letters typed within TYPE_AHEAD_S of each other move an OptionList to the next entry whose
    label (or value) they begin, or whose words they begin; one letter repeated steps through the
    entries it begins; a space counts only within a search ("by l")."""

    def __init__(self) -> None:
        self._typed = ("", 0.0)

    def key(self, event: events.Key, options: OptionList, entries: Sequence[tuple[str, str]]) -> bool:
        """Handle `event` for `options`, whose entries are (value, label); False if it is no letter."""
        if not (event.is_printable and event.character) or not entries:
            return False
        typed, when = self._typed
        now = monotonic()
        typed = typed if now - when < TYPE_AHEAD_S else ""
        if event.character == " " and not typed:
            return False
        typed += event.character.lower()
        self._typed = (typed, now)
        at = options.highlighted or 0
        n = len(entries)
        repeat = len(set(typed)) == 1
        prefix = typed[0] if repeat else typed
        for step in range(1 if repeat else 0, n + 1):
            value, label = entries[(at + step) % n]
            if _matches(label, prefix) or value.lower().startswith(prefix):
                options.highlighted = (at + step) % n
                break
        return True


class ChoiceScreen(Dialog[str | None]):
    DEFAULT_CSS = """
    ChoiceScreen { align: center middle; }
    ChoiceScreen > Vertical {
        width: 60; max-width: 100%; height: auto; max-height: 80%;
        border: thick $primary; background: $surface; padding: 0 1;
    }
    ChoiceScreen OptionList { height: auto; max-height: 30; }
    """
    BINDINGS = [("escape", "dismiss_none", "Cancel")]

    def __init__(self, title: str, options: tuple[tuple[str, str], ...], current: str | None) -> None:
        super().__init__()
        self.title_text = title
        self.options = options
        self.current = current
        self.type_ahead = TypeAhead()

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label(Text(self.title_text, style="bold"))
            yield OptionList(*(Option(Text(label), id=value) for value, label in self.options))

    def on_mount(self) -> None:
        options = self.query_one(OptionList)
        values = [v for v, _ in self.options]
        options.highlighted = values.index(self.current) if self.current in values else 0
        options.focus()

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self.dismiss(event.option.id)

    def action_dismiss_none(self) -> None:
        self.dismiss(None)

    def on_key(self, event: events.Key) -> None:
        if self.type_ahead.key(event, self.query_one(OptionList), self.options):
            event.stop()


def _matches(label: str, typed: str) -> bool:
    """`typed` begins the label or one of its words, punctuation aside: "sds mk4i l3" and "swerve sds"
    both find "Swerve: SDS MK4i L3 (...)"."""
    if label.lower().startswith(typed):
        return True
    plain = " ".join("".join(c for c in label.lower() if c.isalnum() or c.isspace()).split())
    return f" {typed}" in f" {plain}"
