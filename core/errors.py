"""The one error type every bad input raises, and how a message shows what was typed."""

from __future__ import annotations

import sys
from collections.abc import Iterable

ECHO_CHARS = 40  # a message quotes at most this much of an entry, so it stays one short line


def shown(text: object, limit: int = ECHO_CHARS) -> str:
    """What the user typed, quoted for a message: at most `limit` characters then "…", with line
    breaks and control characters escaped (repr), so a message is always one line."""
    s = as_text(text)
    if len(s) > limit:
        s = s[:limit] + "…"
    return repr(s)


def as_text(value: object) -> str:
    """str(value), except an integer past Python's int-to-str limit (4 300 digits, where str
    raises ValueError), alone or in a container, which is described instead."""
    try:
        return str(value)
    except ValueError:  # only the int-to-str limit raises it here (also inside a list: [10**5000])
        digits = f"an integer of more than {sys.get_int_max_str_digits()} digits"
        return f"<{digits}>" if isinstance(value, int) else f"<a {type(value).__name__} holding {digits}>"


def printable(text: object, keep_newlines: bool = False) -> str:
    """`text` with every control or other invisible character made visible (ESC as \\x1b, a
    line break as \\n unless `keep_newlines`), so text read from a file (a workbook's name, a
    requirement's note, a preset's name) cannot act on the terminal it is printed to. Every CLI
    print of such text goes through here."""
    s = str(text)
    if s.isprintable():
        return s
    if keep_newlines:
        return "\n".join(printable(line) for line in s.split("\n"))
    return "".join(ch if ch.isprintable() else ascii(ch)[1:-1] for ch in s)


class InputError(ValueError):
    """A user entry is wrong. `field` names it, `message` says what is wrong."""

    def __init__(self, field: str, message: str, source: str | None = None):
        self.field = field
        self.message = message
        self.source = source  # e.g. a preset file path
        where = f"{source if source.isprintable() else repr(source)}: " if source else ""
        # a field name may itself be what the user typed (an unknown --set NAME): cap it in the text
        # (or, through the Python API, not a string at all: solve("motor", {1: 2}))
        plain = isinstance(field, str) and len(field) <= ECHO_CHARS and field.isprintable()
        name = field if plain else shown(field)
        super().__init__(f"{where}{name}: {message}")

    @property
    def errors(self) -> tuple[InputError, ...]:
        """Every wrong entry this error reports, one per field: itself (InputErrors: several)."""
        return (self,)

    def from_source(self, source: str) -> InputError:
        """The same wrong entries, said of `source` (e.g. the preset file they came from)."""
        return InputError(self.field, self.message, source)


class InputErrors(InputError):
    """Several wrong entries at once: core.model.parse_inputs reads every field before it refuses,
    so a form can mark each bad field, not only the first. `errors` holds one InputError per wrong
    entry, in the order parsing meets them (unknown names, then the calculator's fields in order).
    The first is the primary: this error's field, message, source and text are its own, so a
    caller that reads one error sees exactly what it saw when parsing stopped at the first."""

    def __init__(self, errors: Iterable[InputError]):
        found = tuple(errors)
        if len(found) < 2:
            raise ValueError("InputErrors holds two or more errors (raise a single one as it is)")
        first = found[0]
        super().__init__(first.field, first.message, first.source)
        self._errors = tuple(e for error in found for e in error.errors)  # flat: each one entry

    @property
    def errors(self) -> tuple[InputError, ...]:
        return self._errors

    def from_source(self, source: str) -> InputError:
        return InputErrors(e.from_source(source) for e in self._errors)


def raise_all(errors: list[InputError]) -> None:
    """Nothing when `errors` is empty; the one error as it is; else InputErrors of them all."""
    if len(errors) == 1:
        raise errors[0]
    if errors:
        raise InputErrors(errors)
