"""The Match card's timeline: the workbook's `[[match.events]]` as rows of the app's sheet (sheet.py),
edited with its keys (typing replaces a cell, Enter edits it, Esc cancels, the arrows and Tab move),
each event's fields (at, card, action, every, count: core.workbook.match.EVENT_KEYS, and any other
key an event of the file has) one row each, labelled with the event's number. A left-out action or
count shows, dimmed, what the match runs for it ("move (default)", the card's first action: a
flywheel's is spin_up; "1 (default)", or "to the end (default)" beside an `every`), so every row
says what its event does.

The sheet is the card's own (one widget, its keys in order, the validation message under the row)
over a calculator made of these rows: a grid of its own would have been a second editor to keep in
step with it. The entries it shows are the events' tables held by the Match card (match_view.py);
every solve builds the workbook's match from them (core.workbook.edited(events=...)), and a save
writes them back (core.workbook.save(events=...)): there is no other copy.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

from rich.segment import Segment
from rich.style import Style
from textual import events

from gearhead.core.fields import Field
from gearhead.core.model import Calculator

from .sheet import Sheet

ADD_KEY, DELETE_KEY = "ctrl+n", "ctrl+d"
DEFAULT = " (default)"  # after a left-out cell's value, the one the match takes
_DIM = Style(dim=True)
_CELL = re.compile(r"^e(\d+)_(\w+)$")
_WHERE = re.compile(r"^match\.events\[(\d+)\]\.(\w+)$")


def field_name(index: int, key: str) -> str:
    """The sheet row of event `index` (1-based, the file's numbering) and key."""
    return f"e{index}_{key}"


def cell_of(name: str) -> tuple[int, str] | None:
    """(event index, key) of a sheet row's name."""
    m = _CELL.match(name)
    return (int(m.group(1)), m.group(2)) if m else None


_RUN = re.compile(r"^match\.events\[(\d+)\] \(")


def error_cell(where: str) -> str | None:
    """The row a match refusal names ('match.events[2].card' → 'e2_card'), else None."""
    m = _WHERE.match(where)
    return field_name(int(m.group(1)), m.group(2)) if m else None


def run_error_cell(message: str) -> str | None:
    """The row of a move the match could not run ('match.events[2] (lift at 17 s): the card lift
    could not be solved ...'): the event's card, whose entries or state it is about."""
    m = _RUN.match(message)
    return field_name(int(m.group(1)), "card") if m else None


class Cells(Mapping):
    """The sheet's entries over the events' tables: 'e2_card' is table 2's `card` ('' when the
    event leaves it out)."""

    def __init__(self, tables: list[dict[str, Any]]) -> None:
        self.tables = tables

    def __getitem__(self, name: str) -> Any:
        cell = cell_of(name)
        if cell is None or not 1 <= cell[0] <= len(self.tables):
            raise KeyError(name)
        return self.tables[cell[0] - 1].get(cell[1], "")

    def __iter__(self):
        keys = keys_of(self.tables)
        return (field_name(i, k) for i in range(1, len(self.tables) + 1) for k in keys)

    def __len__(self) -> int:
        return len(self.tables) * len(keys_of(self.tables))


def keys_of(tables: list[dict[str, Any]]) -> tuple[str, ...]:
    """The columns: the match's event keys, then any other key an event has (its refusal shown)."""
    from gearhead.core.workbook.match import EVENT_KEYS

    extra = [k for t in tables for k in t if k not in EVENT_KEYS]
    return (*EVENT_KEYS, *dict.fromkeys(extra))


def _blank(value: Any) -> bool:
    return isinstance(value, str) and not value.strip()  # left out (event_table drops it)


def default_text(table: Mapping[str, Any], key: str, calculators: Mapping[str, str]) -> str:
    """What the match takes for `key` of an event that leaves it out (core.workbook.match._event), as
    the timeline shows it: the card's first action, 1 move, or moves to the match's end beside an
    `every`; '' for any other key, or an action whose card is not known yet (the refusal says so)."""
    if key == "action":
        from gearhead.core.workbook.match import default_action

        card = table.get("card", "")
        calc = calculators.get(card.strip()) if isinstance(card, str) else None
        action = default_action(calc) if calc is not None else None
        return action + DEFAULT if action else ""
    if key == "count":
        return ("1" if _blank(table.get("every", "")) else "to the end") + DEFAULT
    return ""


def calculator(tables: list[dict[str, Any]]) -> Calculator:
    """A form whose rows are the events' cells (only their declarations: nothing is parsed here,
    the workbook's match reads the tables and names what is wrong)."""
    from gearhead.core.workbook.match import EVENT_TIMES

    fields = tuple(
        Field(field_name(i, key), f"Event {i} {key}", unit="s" if key in EVENT_TIMES else "", default="")
        for i in range(1, len(tables) + 1)
        for key in keys_of(tables)
    )
    return Calculator("match_timeline", "Timeline", "", fields, (), compute=_not_solved)


def _not_solved(values):
    raise NotImplementedError("the timeline's rows are read by the workbook's match, not solved")


class TimelineSheet(Sheet):
    """The sheet of the events; ctrl+n adds an event, ctrl+d deletes the one under the cursor, both
    handled in the key handler, in the order typed, as every key of the sheet is."""

    def __init__(
        self, *args, on_add, on_delete, calculators: Mapping[str, str] | None = None, **kwargs
    ) -> None:
        super().__init__(*args, **kwargs)
        self.on_add, self.on_delete = on_add, on_delete
        self.calculators = calculators or {}  # card name -> its calculator: the default action's

    def default_of(self, stop) -> str:
        """The default a left-out cell shows ('' when the cell holds a value, or has none)."""
        cell = cell_of(stop.field.name)
        entries = self._entries()
        if cell is None or not isinstance(entries, Cells) or not 1 <= cell[0] <= len(entries.tables):
            return ""
        table = entries.tables[cell[0] - 1]
        if not _blank(table.get(cell[1], "")):
            return ""
        return default_text(table, cell[1], self.calculators)

    def value_text(self, stop) -> str:
        return self.default_of(stop) or super().value_text(stop)

    def _value_segments(self, stop, on_cursor: bool, base: Style) -> list[Segment]:
        segments = super()._value_segments(stop, on_cursor, base)
        if (on_cursor and self.editing) or not self.default_of(stop):
            return segments
        return [Segment(s.text, (s.style or base) + _DIM, s.control) for s in segments]

    def set_calculator(self, calc: Calculator) -> None:
        """Rows added or removed: the form's declarations replaced, the cursor kept on its row
        (or the nearest above it, as when a card's mode hides rows)."""
        if self.editing:
            self.commit()
        self.calculator = calc
        self._specs = {f.name: f.kind.widget(f) for f in calc.fields}
        self.set_visible(calc.fields)

    async def on_key(self, event: events.Key) -> None:
        if event.key in (ADD_KEY, DELETE_KEY):
            event.stop()
            event.prevent_default()
            if self.editing:
                self.commit()
            (self.on_add if event.key == ADD_KEY else self.on_delete)()
            return
        await super().on_key(event)

    @property
    def current_event(self) -> int | None:
        """The event (1-based) under the cursor."""
        stop = self.current_stop
        cell = cell_of(stop.field.name) if stop is not None else None
        return cell[0] if cell else None
