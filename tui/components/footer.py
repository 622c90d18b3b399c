"""The key bar, recomposed only when the keys it shows change."""

from __future__ import annotations

from time import monotonic

from textual.screen import Screen
from textual.widgets import Footer


def _shown(screen: Screen) -> tuple:
    """What the footer draws of a screen's bindings, read as Footer.compose reads them: each shown
    key with its display, label, action, group, tooltip and whether it is enabled, and the
    command palette's key."""
    app = screen.app
    bindings = screen.active_bindings
    palette = bindings.get(app.COMMAND_PALETTE_BINDING)
    return tuple(
        (
            binding.key,
            app.get_key_display(binding),
            binding.description,
            binding.action,
            binding.group,
            enabled,
            tooltip,
        )
        for _, binding, enabled, tooltip in [*bindings.values(), *([palette] if palette else [])]
        if binding.show or (palette is not None and binding is palette[1])
    )


class KeyFooter(Footer):
    """Textual's Footer recomposes every key whenever a screen's bindings are refreshed: on each
    focus move (twice per Tab between fields, about 20 ms each) and on each card switch, though
    the keys shown are almost always the same. This one recomposes only when they differ from
    the ones it drew or is about to draw: a card switch refreshes the bindings three times before
    the recompose it asked for runs, and each queued one more (and a layout each)."""

    _drawn: tuple | None = None  # _shown() when last composed
    _queued: tuple | None = None  # _shown() when a recompose was queued (None: composed since)
    _queued_at = 0.0
    # a queued recompose runs after the next refresh; Textual drops it if the screen it was queued
    # on closes first (a dialog): after this long, the same keys are queued again, not skipped
    QUEUED_FOR_S = 0.5

    def compose(self):
        if self._bindings_ready:
            self._drawn = _shown(self.screen)
            self._queued = None
        return super().compose()

    def bindings_changed(self, screen: Screen) -> None:
        if self._drawn is not None and self.is_attached and screen is self.screen:
            shown = _shown(screen)
            pending = self._queued is not None and monotonic() - self._queued_at < self.QUEUED_FOR_S
            if shown == (self._queued if pending else self._drawn):
                return
            if screen.app.app_focus:  # Footer queues its recompose only then
                self._queued, self._queued_at = shown, monotonic()
        super().bindings_changed(screen)
