"""What the app's dialogs share."""

from __future__ import annotations

from typing import Generic, TypeVar

from textual.await_complete import AwaitComplete
from textual.screen import ModalScreen

Result = TypeVar("Result")


class Dialog(ModalScreen[Result], Generic[Result]):
    """A modal screen dismissed at most once.

    Textual's `dismiss` runs the result callback and pops whatever screen is on top: two keys in
    one burst that each dismiss (Enter Enter on a list, Enter then Esc) ran the callback twice
    and popped the screen below, or raised ScreenStackError on the last one and ended the app
    (issue 41). A dialog no longer on top has been dismissed: a second dismiss does nothing."""

    def dismiss(self, result: Result | None = None) -> AwaitComplete:
        if not self.is_active:
            return AwaitComplete.nothing()
        return super().dismiss(result)
