"""The screen that shows cards: the app's home screen (the strips and the calculator cards) and a
workbook's (its cards)."""

from __future__ import annotations

from textual.reactive import Reactive
from textual.screen import Screen
from textual.widget import Widget


class CardScreen(Screen):
    """A focus move repaints only the widgets whose look it changes (Textual refreshes the widget
    focused and the one blurred, and restyles their :focus-within ancestors), not the whole
    screen: Screen.focused is a repainting reactive, and each card switch (the focus to the shown
    card's sheet) drew every line of the screen again after the layout's paint, a second full
    render in the same tick."""

    focused: Reactive[Widget | None] = Reactive(None, repaint=False)
