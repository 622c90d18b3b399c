"""The one error type every bad input raises, and how a message shows what was typed."""

ECHO_CHARS = 40  # a message quotes at most this much of an entry, so it stays one short line


def shown(text: object, limit: int = ECHO_CHARS) -> str:
    """What the user typed, quoted for a message: at most `limit` characters then "…", with line
    breaks and control characters escaped (repr), so a message is always one line."""
    s = str(text)
    if len(s) > limit:
        s = s[:limit] + "…"
    return repr(s)


class InputError(ValueError):
    """A user entry is wrong. `field` names it, `message` says what is wrong."""

    def __init__(self, field: str, message: str, source: str | None = None):
        self.field = field
        self.message = message
        self.source = source  # e.g. a preset file path
        where = f"{source if source.isprintable() else repr(source)}: " if source else ""
        # a field name may itself be what the user typed (an unknown --set NAME): cap it in the text
        name = field if len(field) <= ECHO_CHARS and field.isprintable() else shown(field)
        super().__init__(f"{where}{name}: {message}")
