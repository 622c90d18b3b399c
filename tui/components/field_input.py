"""An Input that applies every key in the order it was typed.

Textual's Input inserts printable characters in its own key handler, but its editing keys
(backspace, ctrl+u, arrows, delete…) are bindings: their event first bubbles up through every
ancestor's message queue to the app, which then runs the action. In a real terminal a burst such
as Backspace, Backspace, 3 arrives in one read, so the 3 is inserted while the backspaces are still
bubbling, and they then delete it: `12` became `1`, and ctrl+u then `12` left the field empty.
(Textual issue #6605, fix proposed in PR #6631, not released in the version we pin.)

FieldInput runs its own non-priority bindings inline, in its key handler, so a bound key takes
effect before the next key is read. It reads the widget's bindings and the app's keymap through
`_bindings` and `_keymap`: the one private use kept in tui/, to be deleted when Textual ships the fix.
The card's sheet needs none of this: it handles its keys in its own handler (sheet.py). Dialogs
(the preset name and path, the sweep range, the export file) use this entry. Priority bindings (the app's ctrl+q, ctrl+s…) are still
checked by the app before the key reaches the widget, exactly as before.
"""

from __future__ import annotations

from collections.abc import Callable

from textual import events
from textual.geometry import Size
from textual.reactive import Reactive
from textual.widgets import Input


class FieldInput(Input):
    # Input sets its virtual size (the text's width) on every key, and Widget's virtual_size asks
    # for a layout of the whole screen (~3 ms a key on a card). An entry's size is fixed by the
    # stylesheet (Input lays out again itself when it is auto-sized), and scrolling reads the
    # value directly: a repaint is enough.
    virtual_size = Reactive(Size(0, 0), layout=False)

    # Called with this entry, in its key handler, when a key changed its value: the owner can
    # show the key's result in the frame that echoes the key (Input.Changed arrives after that
    # frame has been drawn, and the result a frame later, 17 ms)
    edited: Callable[[FieldInput], None] | None = None

    def __init__(self, *args, **kwargs) -> None:
        # Entries are checked by the calculator (core.fields), never by Textual validators. With
        # validation on, Input marks itself -valid on its first value: a class change that
        # re-applies the stylesheet to a widget not even mounted yet (about a third of a card's
        # build, pyinstrument)
        kwargs.setdefault("validate_on", ())
        super().__init__(*args, **kwargs)

    async def _on_key(self, event: events.Key) -> None:
        before = self.value
        if not event.is_printable and await self._run_own_binding(event.key):
            event.stop()
            event.prevent_default()
            self._restart_blink()
        else:
            await super()._on_key(event)
        if self.value != before and self.edited is not None:
            self.edited(self)

    async def _run_own_binding(self, key: str) -> bool:
        """Run the action this widget binds to `key` now; False if it binds none (the key
        then bubbles as usual, e.g. ctrl+g to the app)."""
        bindings = self._bindings.copy()
        keymap = self.app._keymap
        if keymap:
            bindings.apply_keymap(keymap)
        for binding in bindings.key_to_bindings.get(key, ()):
            if binding.priority:
                continue
            if await self.app.run_action(binding.action, self):
                return True
        return False
