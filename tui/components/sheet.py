"""A card's form as one sheet: every field a row (label, value, unit), drawn by one widget.

The sheet is a Line-API widget (as Textual's DataTable): it draws its rows from the calculator's
field declarations and the card's entries, and holds a cursor that Tab, shift+Tab and the arrows
move without moving Textual's focus. It keeps the keys of a spreadsheet cell:

- typing on a row replaces its value; Enter edits it in place (cursor at the end), Esc
  cancels the edit, Enter commits and moves down, Tab and the arrows commit and move;
- Space toggles a yes/no row or a flag (one line each), and only the row under the cursor;
- Enter on a choice row opens its list; typing on it picks the next choice starting with what
  was typed (type-ahead);
- Backspace or Delete on a row starts an empty edit; a click selects a row, a click on its value
  edits it (toggles a flag, opens a list).

Every key is handled here, in the order typed, in this widget's own key handler: no key goes
through a binding that runs after the keys queued behind it (Textual runs a non-priority binding
only once its key has bubbled to the app: a Tab then a digit put the digit in the row left).
The BINDINGS below only name the keys on the key bar (a click there runs the same action).

An entry changes on every key (results update as you type): `on_entry(name, text)` is called
at once, and the card solves it. What the sheet shows is always the card's entries.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from time import monotonic
from typing import Any

from rich.cells import cell_len
from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.binding import Binding
from textual.content import Content
from textual.geometry import Region, Size
from textual.strip import Strip

from gearhead.core import units
from gearhead.core.fields import Widget as FieldWidget
from gearhead.core.model import Calculator, Field

from .line_view import LineView
from .unit_text import fit_cells, pretty_unit

LABEL_CELLS = 32  # the label column; longer labels wrap by word
VALUE_CELLS = 26  # the value column (an entry scrolls inside it while edited)
GAP = 1  # between columns
TYPE_AHEAD_S = 1.0  # letters typed on a choice row within this long search together
SHOWN_DIGITS = 6  # an entry's number is shown with at most this many significant digits


@dataclass(frozen=True)
class Stop:
    """A place the cursor can be: a field's row, or one flag of a flags field."""

    field: Field
    spec: FieldWidget
    option: str | None = None  # the flag's value, on a flags field

    @property
    def shape(self) -> str:
        return self.spec.shape


@dataclass(frozen=True)
class Line:
    """One drawn line: a stop's line (its first draws the value), or an error line."""

    stop: int | None  # index into Sheet.stops; None for an error line
    label: str = ""
    first: bool = False  # draws the value and the unit
    error: str = ""


_ENTRY = re.compile(r"^\s*([-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?)\s*(.*?)\s*$")


_UNIT_WORD = re.compile(r"^[^\W\d_][^\s+\-()]*$")  # a unit as typed: "in", "lbf*in", "m/s²", "%"


def shown_entry(field: Field, text: str) -> str:
    """An entry as the sheet shows it: a number with at most the digits typed or 6 significant,
    and no unit when it is the one beside the value (`1.5999999999999999 in` → `1.6`). Anything
    else (an expression, `0x10`, a tolerance, a bad entry) is shown as typed."""
    match = _ENTRY.match(text)
    if match is None:
        return text
    number, unit = match.groups()
    odd_unit = unit != field.unit and (not _UNIT_WORD.match(unit) or re.match(r"^x[0-9a-fA-F]", unit))
    if unit and (unit == "%" or odd_unit):
        return text if unit != "%" else text.strip()
    try:
        x = float(number)
    except ValueError:
        return text
    digits = len(re.sub(r"[^0-9]", "", re.split(r"[eE]", number)[0]).lstrip("0"))
    if digits > SHOWN_DIGITS:
        number = units.format_number(x, SHOWN_DIGITS)
    if not unit or unit == field.unit:
        return number
    return f"{number} {unit}"


def flag_names(entry: Any) -> set[str]:
    if isinstance(entry, (list, tuple, set, frozenset)):
        return set(entry)
    return {x for x in str(entry).replace(",", " ").split() if x}


class Sheet(LineView, can_focus=True):
    """The form of one card (module docstring)."""

    COMPONENT_CLASSES = {
        "sheet--label",
        "sheet--label-cursor",
        "sheet--value",
        "sheet--cursor",
        "sheet--cursor-focused",
        "sheet--editing",
        "sheet--invalid",
        "sheet--unit",
        "sheet--error",
    }

    DEFAULT_CSS = """
    Sheet {
        height: 1fr;
        overflow-x: hidden;
        scrollbar-gutter: stable;
        background: $surface;
    }
    Sheet > .sheet--label { color: $text; }
    Sheet > .sheet--label-cursor { color: $text; text-style: bold; }
    Sheet > .sheet--value { background: $boost; }
    Sheet > .sheet--cursor { background: $panel-lighten-2; text-style: bold; }
    Sheet > .sheet--cursor-focused { background: $accent; color: $text; text-style: bold; }
    Sheet > .sheet--editing { background: $primary-background; color: $text; text-style: underline; }
    Sheet > .sheet--invalid { background: $error 40%; }
    Sheet > .sheet--unit { color: $text-muted; }
    Sheet > .sheet--error { color: $text-error; text-style: bold; }
    """

    # shown on the key bar; the keys themselves are handled in on_key (module docstring)
    BINDINGS = [
        Binding("enter", "edit", "Edit"),
        Binding("space", "toggle", "Toggle"),
    ]

    def __init__(
        self,
        calculator: Calculator,
        entries: Callable[[], dict[str, Any]],
        on_entry: Callable[[str, Any], None],
        on_cursor: Callable[[Field], None],
        on_choose: Callable[[Field], None],
        **kwargs,
    ) -> None:
        super().__init__(**kwargs)
        self.calculator = calculator
        self._entries = entries  # the card's entries, read at every draw
        self.on_entry = on_entry
        self.on_cursor = on_cursor
        self.on_choose = on_choose  # a choice row's list is wanted (the card opens it)
        self.shown_fields: tuple[Field, ...] = calculator.fields
        self.errors: dict[str, str] = {}
        self.stops: list[Stop] = []
        self.lines: list[Line] = []
        self._first_line: list[int] = []  # stop -> its first line
        self.cursor = 0
        self.editing = False
        self.buffer = ""  # the edited text
        self.caret = 0  # where in it the next key goes
        self._all_selected = False  # ctrl+a: the next key replaces the whole buffer
        self._before_edit: Any = None  # the entry when the edit began (Esc restores it)
        self._shown_before_edit = ""
        self._typed = ("", 0.0)  # type-ahead on a choice row: letters and when
        self._laid_out_width = -1
        self._specs = {f.name: f.kind.widget(f) for f in calculator.fields}
        units_shown = [pretty_unit(spec.unit) for spec in self._specs.values() if spec.unit]
        self._unit_cells = max((cell_len(u) for u in units_shown), default=0)
        self._build()

    # ---- what is drawn ----------------------------------------------------------------
    def set_visible(self, fields: tuple[Field, ...]) -> None:
        """The fields the mode and choices show. The cursor stays on its stop (the field and, on
        a flags field, the flag) whatever rows appear or vanish around it; if its field is
        hidden, on the nearest shown stop above it."""
        if fields == self.shown_fields:
            return
        before = [(s.field.name, s.option) for s in self.stops]
        at = self.cursor
        self.shown_fields = fields
        self._build()
        after = [(s.field.name, s.option) for s in self.stops]
        for place in [before[i] for i in range(min(at, len(before) - 1), -1, -1)]:
            if place in after:
                self.cursor = after.index(place)
                break
        else:
            self.cursor = 0
        self.cursor = min(self.cursor, max(0, len(self.stops) - 1))
        self.scroll_to_cursor()

    def set_errors(self, errors: dict[str, str]) -> None:
        if errors != self.errors:
            self.errors = dict(errors)
            self._build()
            if self.current_field is not None and self.has_focus:
                self.on_cursor(self.current_field)  # the help line shows the row's error whole

    def _build(self) -> None:
        """Stops and lines from the visible fields, their labels wrapped to the label column."""
        stops: list[Stop] = []
        lines: list[Line] = []
        first: list[int] = []
        for f in self.shown_fields:
            spec = self._specs[f.name]
            label = [line.plain for line in Content(f.label).wrap(LABEL_CELLS)] or [""]
            options = [value for value, _ in spec.options] if spec.shape == "checkboxes" else [None]
            for j, option in enumerate(options):
                first.append(len(lines))
                stops.append(Stop(f, spec, option))
                lines.append(Line(len(stops) - 1, label[j] if j < len(label) else "", first=True))
            for extra in label[len(options) :]:
                lines.append(Line(len(stops) - 1, extra))
            message = self.errors.get(f.name)
            if message:
                width = max(20, (self.scrollable_content_region.width or 100) - LABEL_CELLS - 2 * GAP - 1)
                wrapped = Content("⚠ " + message).wrap(width)
                for line in wrapped:  # the whole message (the view follows the cursor to it)
                    lines.append(Line(None, error=line.plain))
        self.stops, self.lines, self._first_line = stops, lines, first
        self._laid_out_width = self.size.width
        self.virtual_size = Size(self.size.width, len(lines))
        self.refresh()

    def on_resize(self, event: events.Resize) -> None:
        if event.size.width != self._laid_out_width and self.errors:
            self._build()  # error lines wrap to the width
        self.virtual_size = Size(event.size.width, len(self.lines))

    @property
    def current_stop(self) -> Stop | None:
        return self.stops[self.cursor] if 0 <= self.cursor < len(self.stops) else None

    @property
    def current_field(self) -> Field | None:
        stop = self.current_stop
        return stop.field if stop is not None else None

    def value_text(self, stop: Stop) -> str:
        """The value cell of a stop as drawn (an edit shows its buffer)."""
        entry = self._entries().get(stop.field.name, "")
        shape = stop.shape
        if shape == "checkboxes":
            label = dict(stop.spec.options)[stop.option]
            return f"[{'x' if stop.option in flag_names(entry) else ' '}] {label}"
        if shape == "checkbox":
            return f"[{'x' if entry is True or str(entry).lower() in ('true', 'yes', '1', 'on') else ' '}]"
        if shape == "select":
            return f"{dict(stop.spec.options).get(entry, str(entry))} ▾"
        return shown_entry(stop.field, str(entry))

    def value_cells(self, stop: Stop) -> int:
        """The value cell's width: VALUE_CELLS, less on a narrow sheet so the widest unit of the
        card stays in sight (at 120 columns the form is 59 cells wide); a row without a unit (a
        choice, a flag, a yes/no) takes the unit's column too."""
        room = self.scrollable_content_region.width - (1 + LABEL_CELLS + GAP) - 1  # beside the gutter
        cells = max(10, min(VALUE_CELLS, room - GAP - self._unit_cells))
        return cells if stop.spec.unit else max(cells, room)

    def render_line(self, y: int) -> Strip:
        width = self.size.width
        index = y + self.scroll_offset.y
        base = self.base_style
        if not (0 <= index < len(self.lines)):
            return Strip.blank(width, base)
        line = self.lines[index]
        style = self.get_component_rich_style
        if line.stop is None:
            segments = [
                Segment(" " * (1 + LABEL_CELLS + GAP), base),
                Segment(line.error, base + style("sheet--error")),
            ]
            return Strip(segments).adjust_cell_length(width, base)
        on_cursor = line.stop == self.cursor
        stop = self.stops[line.stop]
        label_style = base + style("sheet--label-cursor" if on_cursor else "sheet--label")
        segments = [Segment(" ", base), Segment(fit_cells(line.label, LABEL_CELLS), label_style)]
        if line.first:
            segments.append(Segment(" " * GAP, base))
            segments += self._value_segments(stop, on_cursor, base)
            unit = stop.spec.unit
            if unit:
                segments += [
                    Segment(" " * GAP, base),
                    Segment(pretty_unit(unit), base + style("sheet--unit")),
                ]
        return Strip(segments).adjust_cell_length(width, base)

    def _value_segments(self, stop: Stop, on_cursor: bool, base: Style) -> list[Segment]:
        style = self.get_component_rich_style
        cell = base + style("sheet--value")
        if stop.field.name in self.errors and stop.shape == "input":
            cell += style("sheet--invalid")
        if on_cursor:
            cursor = "sheet--cursor-focused" if self.has_focus else "sheet--cursor"
            cell += style("sheet--editing" if self.editing else cursor)
        width = self.value_cells(stop)
        if not (on_cursor and self.editing):
            return [Segment(" " + fit_cells(self.value_text(stop), width - 1), cell)]
        # the edit: the buffer scrolled so the caret is in sight, the caret drawn reversed
        text, caret = self.buffer.replace("\n", "⏎").replace("\r", "⏎"), self.caret
        room = width - 2
        start = max(0, caret - room + 1)
        shown = text[start : start + room]
        at = caret - start
        caret_style = cell + Style(reverse=True)
        before, under, after = shown[:at], (shown[at : at + 1] or " "), shown[at + 1 :]
        if self._all_selected:
            return [Segment(" ", cell), Segment(fit_cells(shown, width - 1), caret_style)]
        pad = width - 1 - cell_len(before) - cell_len(under) - cell_len(after)
        return [
            Segment(" " + before, cell),
            Segment(under, caret_style),
            Segment(after + " " * max(0, pad), cell),
        ]

    def refresh_stop(self, stop: int) -> None:
        """Repaint the lines of one stop (a key changes one row: the screen repaints that row)."""
        if not 0 <= stop < len(self.stops):
            return
        first = self._first_line[stop]
        last = first + 1
        while last < len(self.lines) and self.lines[last].stop == stop and not self.lines[last].first:
            last += 1
        self.refresh(Region(0, first - self.scroll_offset.y, self.size.width, last - first))

    def refresh_field(self, name: str) -> None:
        for i, s in enumerate(self.stops):
            if s.field.name == name:
                self.refresh_stop(i)

    # ---- the cursor -------------------------------------------------------------------
    def move_to(self, stop: int) -> None:
        if not self.stops:
            return
        stop = max(0, min(stop, len(self.stops) - 1))
        left = self.cursor
        self.cursor = stop
        self.refresh_stop(left)
        self.refresh_stop(stop)
        self.scroll_to_cursor()
        self.on_cursor(self.stops[stop].field)

    def move_to_field(self, name: str) -> bool:
        for i, s in enumerate(self.stops):
            if s.field.name == name:
                self.move_to(i)
                return True
        return False

    def _stop_a_page_away(self, direction: int) -> int:
        """The stop a page of lines (what is in sight) above or below the cursor's."""
        if not self.stops:
            return 0
        goal = self._first_line[self.cursor] + direction * self.page_lines()
        if direction > 0:
            return next((i for i, line in enumerate(self._first_line) if line >= goal), len(self.stops) - 1)
        return next((i for i in range(len(self.stops) - 1, -1, -1) if self._first_line[i] <= goal), 0)

    def scroll_to_cursor(self) -> None:
        if not self.stops:
            return
        top = self._first_line[self.cursor]
        bottom = top + 1
        while bottom < len(self.lines) and (
            self.lines[bottom].stop == self.cursor or self.lines[bottom].stop is None
        ):
            bottom += 1
        self.show_lines(top, bottom - top)

    def watch_has_focus(self, has_focus: bool) -> None:
        """No restyle when the focus comes or goes: the sheet's look under focus is the cursor's
        alone, a component class of its own picked as the line is drawn (render_line), and the
        focus and blur refresh the sheet. Textual restyles a widget on every focus change (the
        sheet and its component classes, each a node styled afresh): 2-5 ms of each card switch,
        once for the sheet left and once for the sheet shown."""

    def on_focus(self) -> None:
        self.refresh()
        if self.current_field is not None:
            self.on_cursor(self.current_field)

    def on_blur(self) -> None:
        if self.editing:
            self.commit()
        self.refresh()

    # ---- keys ---------------------------------------------------------------------------
    async def on_key(self, event: events.Key) -> None:
        handled = self._editing_key(event) if self.editing else self._cell_key(event)
        if handled:
            event.stop()
            event.prevent_default()

    def _cell_key(self, event: events.Key) -> bool:
        stop = self.current_stop
        key = event.key
        moves = {"tab": 1, "down": 1, "shift+tab": -1, "up": -1}
        if key in ("pagedown", "pageup"):
            self.move_to(self._stop_a_page_away(1 if key == "pagedown" else -1))
            return True
        if key in moves:
            target = self.cursor + moves[key]
            if key in ("tab", "shift+tab") and not 0 <= target < len(self.stops):
                return False  # off the end: Tab leaves the sheet (the screen moves focus)
            self.move_to(target)
            return True
        if key in ("home", "ctrl+home"):
            self.move_to(0)
            return True
        if key in ("end", "ctrl+end"):
            self.move_to(len(self.stops) - 1)
            return True
        if stop is None:
            return False
        shape = stop.shape
        if key == "space" or (key == "enter" and shape in ("checkbox", "checkboxes")):
            if shape in ("checkbox", "checkboxes"):
                self.toggle()
            elif shape == "select":
                self.on_choose(stop.field)
            else:
                self.begin_edit()
            return True
        if key == "enter":  # (a spreadsheet's F2 is the app's F-key to the Mechanisms area)
            if shape == "select":
                self.on_choose(stop.field)
            elif shape == "input":
                self.begin_edit()
            return True
        if key in ("left", "right") and shape == "select":
            self.step_choice(1 if key == "right" else -1)
            return True
        if key in ("backspace", "delete") and shape == "input":
            self.begin_edit(replace_with="")
            return True
        if event.is_printable and event.character:
            if shape == "input":
                self.begin_edit(replace_with=event.character)
            elif shape == "select":
                self.type_ahead(event.character)
            return True  # a letter on a yes/no row does nothing, and goes nowhere else
        return False

    def _editing_key(self, event: events.Key) -> bool:
        key = event.key
        if key == "escape":
            self.cancel()
            return True
        if key in ("enter", "down", "tab"):
            self.commit()
            if self.cursor + 1 < len(self.stops):
                self.move_to(self.cursor + 1)
            return True
        if key in ("up", "shift+tab"):
            self.commit()
            self.move_to(self.cursor - 1)
            return True
        text, caret = self.buffer, self.caret
        if self._all_selected and (key in ("backspace", "delete") or event.is_printable):
            text, caret = "", 0
            self._all_selected = False
            if key in ("backspace", "delete"):
                self._set_buffer(text, caret)
                return True
        self._all_selected = self._all_selected and key == "ctrl+a"
        if event.is_printable and event.character:
            self._set_buffer(text[:caret] + event.character + text[caret:], caret + len(event.character))
        elif key == "backspace":
            if caret:
                self._set_buffer(text[: caret - 1] + text[caret:], caret - 1)
        elif key == "delete":
            self._set_buffer(text[:caret] + text[caret + 1 :], caret)
        elif key == "left":
            self._set_buffer(text, max(0, caret - 1))
        elif key == "right":
            self._set_buffer(text, min(len(text), caret + 1))
        elif key == "home":
            self._set_buffer(text, 0)
        elif key == "end":
            self._set_buffer(text, len(text))
        elif key == "ctrl+a":  # as in a spreadsheet's cell: select it all, the next key replaces it
            self._all_selected = True
            self._set_buffer(text, len(text))
        elif key == "ctrl+u":
            self._set_buffer(text[caret:], 0)
        elif key == "ctrl+k":
            self._set_buffer(text[:caret], caret)
        else:
            return False  # the app's keys (ctrl+s, ctrl+o…) act on the card as it is
        return True

    def on_paste(self, event: events.Paste) -> None:
        """A paste goes into the row under the cursor, as typed (line breaks are kept: the entry
        is then refused with a message, never cut silently)."""
        event.stop()
        stop = self.current_stop
        if stop is None or stop.shape != "input":
            return
        text = event.text.rstrip("\r\n")
        if not self.editing:
            self.begin_edit(replace_with=text)
            return
        if self._all_selected:
            self.buffer, self.caret, self._all_selected = "", 0, False
        self._set_buffer(self.buffer[: self.caret] + text + self.buffer[self.caret :], self.caret + len(text))

    # ---- editing ----------------------------------------------------------------------
    def begin_edit(self, replace_with: str | None = None) -> None:
        stop = self.current_stop
        if stop is None or stop.shape != "input":
            return
        entry = self._entries().get(stop.field.name, "")
        self._before_edit = entry
        self._shown_before_edit = shown_entry(stop.field, str(entry))
        self.editing = True
        self._all_selected = False
        if replace_with is None:
            self._set_buffer(self._shown_before_edit, len(self._shown_before_edit), take=False)
        else:
            self._set_buffer(replace_with, len(replace_with))

    def _set_buffer(self, text: str, caret: int, take: bool = True) -> None:
        changed = text != self.buffer
        self.buffer, self.caret = text, caret
        self.refresh_stop(self.cursor)
        stop = self.current_stop
        if take and changed and stop is not None:
            # the shown text of an entry kept at full precision (a sent value) is that entry
            value = self._before_edit if text == self._shown_before_edit else text
            self.on_entry(stop.field.name, value)

    def commit(self) -> None:
        self.editing = False
        self._all_selected = False
        self.refresh_stop(self.cursor)

    def cancel(self) -> None:
        stop = self.current_stop
        self.editing = False
        self._all_selected = False
        if stop is not None and self._entries().get(stop.field.name) != self._before_edit:
            self.on_entry(stop.field.name, self._before_edit)
        self.refresh_stop(self.cursor)

    # ---- toggles and choices ----------------------------------------------------------
    def toggle(self) -> None:
        stop = self.current_stop
        if stop is None:
            return
        entry = self._entries().get(stop.field.name)
        if stop.shape == "checkbox":
            on = entry is True or str(entry).lower() in ("true", "yes", "1", "on")
            self.on_entry(stop.field.name, not on)
        elif stop.shape == "checkboxes":
            chosen = flag_names(entry) ^ {stop.option}
            self.on_entry(stop.field.name, ", ".join(c for c, _ in stop.spec.options if c in chosen))
        self.refresh()

    def step_choice(self, step: int) -> None:
        stop = self.current_stop
        values = [v for v, _ in stop.spec.options]
        entry = self._entries().get(stop.field.name)
        at = values.index(entry) if entry in values else 0
        self.on_entry(stop.field.name, values[(at + step) % len(values)])
        self.refresh()

    def type_ahead(self, character: str) -> None:
        """Letters typed on a choice row within a second pick the next choice they begin."""
        stop = self.current_stop
        typed, when = self._typed
        now = monotonic()
        typed = (typed if now - when < TYPE_AHEAD_S else "") + character.lower()
        self._typed = (typed, now)
        options = list(stop.spec.options)
        entry = self._entries().get(stop.field.name)
        at = next((i for i, (v, _) in enumerate(options) if v == entry), 0)
        # a repeated first letter steps through the choices it begins; more letters narrow it
        order = options[at + 1 :] + options[: at + 1] if len(set(typed)) == 1 else options[at:] + options[:at]
        prefix = typed[0] if len(set(typed)) == 1 else typed
        for value, label in order:
            if label.lower().startswith(prefix) or value.lower().startswith(prefix):
                if value != entry:
                    self.on_entry(stop.field.name, value)
                self.refresh()
                return

    # ---- mouse --------------------------------------------------------------------------
    def on_click(self, event: events.Click) -> None:
        offset = event.get_content_offset(self)
        if offset is None:
            return
        index = offset.y + self.scroll_offset.y
        if not (0 <= index < len(self.lines)) or self.lines[index].stop is None:
            return
        target = self.lines[index].stop
        if self.editing and target != self.cursor:
            self.commit()
        self.move_to(target)
        on_value = offset.x >= 1 + LABEL_CELLS + GAP
        if on_value and not self.editing:
            shape = self.stops[target].shape
            if shape in ("checkbox", "checkboxes"):
                self.toggle()
            elif shape == "select":
                self.on_choose(self.stops[target].field)
            else:
                self.begin_edit()

    # the key bar's actions (a click on it): the same as the keys
    def action_edit(self) -> None:
        stop = self.current_stop
        if stop is not None and stop.shape == "select":
            self.on_choose(stop.field)
        elif stop is not None and stop.shape in ("checkbox", "checkboxes"):
            self.toggle()
        else:
            self.begin_edit()

    def action_toggle(self) -> None:
        self.toggle()
