"""Asked before unsaved edits are left behind: save, discard, or stay."""

from __future__ import annotations

from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.widgets import Button, Label, Static

from .dialog import Dialog

SAVE, DISCARD, STAY = "save", "discard", "stay"


class LeaveScreen(Dialog[str]):
    """Dismissed with SAVE, DISCARD or STAY (Esc)."""

    # priority: answered as the key arrives, before a key typed after it (a non-priority binding
    # runs once the key has bubbled up: ctrl+p typed after d opened the palette first and d was lost)
    BINDINGS = [
        Binding("escape", f"dismiss('{STAY}')", "Stay", priority=True),
        Binding("s", f"dismiss('{SAVE}')", "Save", show=False, priority=True),
        Binding("d", f"dismiss('{DISCARD}')", "Discard", show=False, priority=True),
    ]
    DEFAULT_CSS = """
    LeaveScreen { align: center middle; }
    """

    def __init__(self, what: str, changes: int) -> None:
        super().__init__()
        self.what, self.changes = what, changes

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog"):
            yield Label(Text(f"{self.what} has unsaved changes"), classes="dialog-title")
            yield Static(
                Text(
                    f"{self.changes} entr{'y' if self.changes == 1 else 'ies'} changed since it was "
                    "opened or last saved. s saves them to its file, d discards them, Esc stays."
                )
            )
            with Horizontal(classes="dialog-buttons"):
                yield Button("Save", variant="primary", id=SAVE)
                yield Button("Discard", variant="error", id=DISCARD)
                yield Button("Stay", id=STAY)

    def on_mount(self) -> None:
        self.query_one(f"#{STAY}", Button).focus()  # Enter by habit keeps the work

    @on(Button.Pressed)
    def _pressed(self, event: Button.Pressed) -> None:
        self.dismiss(event.button.id or STAY)
