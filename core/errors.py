"""The one error type every bad input raises."""


class InputError(ValueError):
    """A user entry is wrong. `field` names it, `message` says what is wrong."""

    def __init__(self, field: str, message: str, source: str | None = None):
        self.field = field
        self.message = message
        self.source = source  # e.g. a preset file path
        where = f"{source}: " if source else ""
        super().__init__(f"{where}{field}: {message}")
