"""The key bar, recomposed only when the keys it shows change."""

from __future__ import annotations

from textual.screen import Screen
from textual.widgets import Footer


def _shown(screen: Screen) -> tuple:
    """What the footer shows of a screen's bindings: each key, its label and whether it is
    enabled (Footer.compose draws from the same fields)."""
    return tuple(
        (binding.key, binding.action, binding.description, binding.key_display, enabled, tooltip)
        for _, binding, enabled, tooltip in screen.active_bindings.values()
        if binding.show
    )


class KeyFooter(Footer):
    """Textual's Footer recomposes every key whenever a screen's bindings are refreshed: on each
    focus move (twice per Tab between fields, about 20 ms each) and on each card switch, though
    the keys shown are almost always the same. This one recomposes only when they differ from
    the ones it drew."""

    _drawn: tuple | None = None  # _shown() when last composed

    def compose(self):
        if self._bindings_ready:
            self._drawn = _shown(self.screen)
        return super().compose()

    def bindings_changed(self, screen: Screen) -> None:
        if (
            self._drawn is not None
            and self.is_attached
            and screen is self.screen
            and _shown(screen) == self._drawn
        ):
            return
        super().bindings_changed(screen)
