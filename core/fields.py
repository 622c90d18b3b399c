"""Field kinds: what sort of value a Field holds, and everything that depends on that sort.

Each kind is one class that owns, for a field of its kind: reading what a user entered (`parse`),
the text shown for an entry and for the default, the value a widget holds and a preset stores, how
a solved value is reported in JSON, its bounds in SI, and a description of the widget the generic
tab renders (`Widget`: an input with a unit label, a select, a set of checkboxes, one checkbox).
The model, the tab, presets, the CLI and the generated tests ask the field's kind; none switches
on a kind's name, so a new kind is one new class here (or anywhere: `Field(..., kind=MyKind())`).

Calculators declare fields as before (`Field("x", "X", "length", "mm", ...)`, `integer=True`,
`choices=(...)`, `boolean=True`, `flags=True`); `kind_of` maps that syntax to a kind once.
`Field` itself is here too, at the end: a field and its kind are read together.

Bounds convention: `min`, `max` and `default` are all in the field's display unit (`unit`), the
unit the author reads beside the field: `Field("wall", "Wall", "length", "in", default=0.0625,
min=0, max=1)` is 0 to 1 inch. A kind converts bounds to SI (`bound_si`) once, on first use.
"""

from __future__ import annotations

import decimal
import math
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from . import units
from .errors import InputError, as_text, shown

# Beyond these magnitudes (in SI) no robot part exists, and products of such values overflow
# or underflow; rejecting them keeps every formula finite without per-field guesswork.
MAGNITUDE_FLOOR = 1e-15
MAGNITUDE_CEILING = 1e15
# The largest whole number any integer field takes (a field's own max may be smaller): below 2**53,
# so every accepted count is exact as a float too, as the formulas use it
MAX_WHOLE = 10**15
BOUND_SLACK = 1e-12  # relative: unit conversion may land a typed bound one rounding step outside


@dataclass(frozen=True)
class Widget:
    """What the generic tab renders for a field; core never imports Textual.

    shape: "input" (a text entry), "select" (one of `options`), "checkboxes" (any of `options`,
    one checkbox each) or "checkbox" (one yes/no box). `options` are (value, label) pairs.
    `unit`: the label beside the widget; None when the widget takes the unit's column too.
    """

    shape: str
    options: tuple[tuple[str, str], ...] = ()
    unit: str | None = None


def flags_text(items: Any) -> str:
    if isinstance(items, str):
        items = [x for x in items.replace(",", " ").split() if x]
    return ", ".join(sorted(items))


def _flag_names(value: Any) -> set[str]:
    if isinstance(value, (list, tuple, set, frozenset)):
        return set(value)
    return {x for x in as_text(value).replace(",", " ").split() if x}


class Kind:
    """A sort of value. Subclasses override what differs; one instance serves every field."""

    name = ""  # Field.type: what `gearhead calculators --json` and messages call the kind
    numeric = False  # has bounds and may be swept
    whole = False  # numeric values are whole numbers (a sweep steps through whole numbers)
    with_unit = False  # typed in any unit of f.quantity (a bare number: f.unit), SI inside; may carry ±

    # ---- reading ------------------------------------------------------------------------
    def parse(self, f: Field, raw: Any) -> Any:
        """The value (SI for a quantity) of what a user entered, or an InputError naming `f`."""
        raise NotImplementedError

    def holds(self, f: Field, value: Any) -> bool:
        """Whether `value` is one `parse` may return (the generated tests check every result)."""
        raise NotImplementedError

    def max_chars(self, f: Field) -> int:
        """Longest entry read: a value, or every choice listed (they may exceed a value's)."""
        return max(units.MAX_INPUT_CHARS, sum(len(c) + 2 for c in f.choices))

    def checked(self, f: Field, value: Any, typed: str) -> Any:
        """`value` as parsed from `typed`, checked against the field's bounds."""
        return check_bounds(f, value, typed)

    def bound_si(self, f: Field, bound: float) -> float:
        """A declared bound (display unit) in the unit `parse` returns."""
        return bound

    def bound_text(self, f: Field, si: float) -> str:
        """A bound as a message quotes it: in the field's display unit."""
        return units.format_number(si)

    def declaration_problem(self, f: Field) -> str | None:
        """What is wrong with a field's declaration for this kind (core.declarations asks), or None."""
        return None

    # ---- text ---------------------------------------------------------------------------
    def default_text(self, f: Field) -> str:
        return str(f.default)

    def preview_text(self, f: Field, saved: Any) -> str:
        """A value as a preset saved it, for a person to read (the load dialog's preview)."""
        return as_text(saved)

    def entry_text(self, f: Field, entered: Any) -> str:
        """The text shown (and reported in JSON) for what was entered."""
        if isinstance(entered, bool):
            return "true" if entered else "false"
        return as_text(entered)  # str() refuses an int past 4 300 digits

    def reported(self, f: Field, value: Any) -> tuple[Any, str]:
        """(value, SI unit) as JSON reports a parsed input."""
        return value, ""

    # ---- widget and presets -------------------------------------------------------------
    def widget(self, f: Field) -> Widget:
        return Widget("input", unit=f.unit)

    def entry_hint(self, f: Field) -> str:
        """How an entry of this kind may be written, for the help line under the form."""
        if self.with_unit:
            return f"bare number = {f.unit or 'plain number'}; any compatible unit may be typed"
        return ""

    def initial_entry(self, f: Field) -> Any:
        """The default as the widget holds it."""
        return self.default_text(f)

    def entry(self, f: Field, value: Any) -> Any:
        """A stored or sent value (preset, send-to) as the widget holds it."""
        return as_text(value)

    def stored(self, f: Field, entry: Any) -> Any:
        """What a preset stores for the widget's entry."""
        return entry

    def vocabulary(self, f: Field) -> tuple[str, ...]:
        """Words a user might type here (generated hostile entries mix them in)."""
        return tuple(f.choices) or ("true", "x")


class Quantity(Kind):
    """A number with a unit: a bare number means the display unit; any compatible unit may be
    typed. Parsed to SI."""

    name = "quantity"
    numeric = True
    with_unit = True

    def parse(self, f, raw):
        typed = as_text(raw)  # str() refuses an int past 4 300 digits, even inside a list
        return self.checked(
            f,
            units.parse(raw if isinstance(raw, (str, int, float)) else typed, f.unit, f.quantity, f.name),
            typed,
        )

    def checked(self, f, value, typed):
        if value != 0 and not (MAGNITUDE_FLOOR <= abs(value) <= MAGNITUDE_CEILING):
            raise InputError(
                f.name,
                f"{_typed(typed)} is out of range for a mechanism (magnitude {abs(value):.3g} in SI units)",
            )
        return check_bounds(f, value, typed)

    def holds(self, f, value):
        return isinstance(value, float) and math.isfinite(value)

    def bound_si(self, f, bound):
        return float(bound) * units.factor(f.unit, f.quantity)  # as a bare number typed is read

    def bound_text(self, f, si):
        return units.format_quantity(si, f.unit, f.quantity)

    def default_text(self, f):
        d = f.default
        return units.format_number(float(d)) if isinstance(d, (int, float)) else str(d)

    def entry_text(self, f, entered):
        if isinstance(entered, (int, float)) and not isinstance(entered, bool):
            return f"{units.format_number(float(entered))} {f.unit}".rstrip()
        if isinstance(entered, str) and units._NUMBER.match(entered):
            return f"{entered.strip()} {f.unit}".rstrip()
        return super().entry_text(f, entered)

    def reported(self, f, value):
        return value, units.SI_UNITS[f.quantity]

    def vocabulary(self, f):
        return tuple(u for u in (f.unit, *units.COMMON_UNITS.get(f.quantity, ())) if u) or ("%",)


class Integer(Kind):
    """A whole number (teeth, stages): read with the same screening as a quantity ("３６")."""

    name = "int"
    numeric = True
    whole = True

    def parse(self, f, raw):
        if isinstance(raw, bool):
            raise InputError(f.name, f"expected a whole number, got {raw!r}")
        if isinstance(raw, numbers.Integral):
            value = int(raw)
        elif isinstance(raw, float):
            if not math.isfinite(raw) or raw != int(raw):
                raise InputError(f.name, f"{shown(raw)} is not a whole number")
            value = int(raw)
        else:
            text = units.normalise(as_text(raw), f.name)  # the same screening as a quantity: "−2", "３"
            # read exactly (Decimal, not float): 9007199254740993 stayed …992 through a float
            try:
                exact = decimal.Decimal(text)
            except (decimal.InvalidOperation, ValueError):
                raise InputError(f.name, f"{shown(text)} is not a whole number") from None
            if not exact.is_finite() or exact != exact.to_integral_value():
                raise InputError(f.name, f"{shown(text)} is not a whole number")
            if exact.adjusted() > len(str(MAX_WHOLE)):  # '1e999999999': no int of a billion digits
                raise InputError(
                    f.name, f"{shown(text)} is too large: a whole number here is at most {MAX_WHOLE}"
                )
            if abs(exact) > MAX_WHOLE:
                raise InputError(
                    f.name, f"{shown(text)} is too large: a whole number here is at most {MAX_WHOLE}"
                )
            value = int(exact)
        if abs(value) > MAX_WHOLE:  # before str(value): a TOML integer of 5 000 digits has no str
            digits = int(value.bit_length() * math.log10(2)) + 1
            raise InputError(
                f.name,
                f"a number of about {digits} digits is too large: a whole number here is at most {MAX_WHOLE}",
            )
        return self.checked(f, value, str(value))

    def checked(self, f, value, typed):
        if abs(value) > MAX_WHOLE:  # every whole-number field, whatever its own max
            raise InputError(f.name, f"{shown(typed)} is too large: must be at most {MAX_WHOLE}")
        return check_bounds(f, value, typed)

    def holds(self, f, value):
        return isinstance(value, int) and not isinstance(value, bool)

    def bound_text(self, f, si):
        return str(int(si))

    def declaration_problem(self, f):
        if any(b is not None and b != int(b) for b in (f.min, f.max)):
            return f"a whole number's bounds are whole numbers (min {f.min}, max {f.max})"
        return None

    def stored(self, f, entry):
        try:
            return int(str(entry).strip())  # a whole number as a TOML integer
        except ValueError:
            return entry


class Choice(Kind):
    """One of `choices` (a name, or its label in any case); shown as a select."""

    name = "choice"

    def parse(self, f, raw):
        text = str(raw).strip() if isinstance(raw, str) else None
        if text not in f.choices:
            lowered = {c.lower(): c for c in f.choices}  # accept the label too, in any case
            lowered.update({f.label_of(c).lower(): c for c in f.choices})
            if text is not None and text.lower() in lowered:
                return lowered[text.lower()]
            shown_choices = ", ".join(f.choices[:12]) + (", ..." if len(f.choices) > 12 else "")
            raise InputError(f.name, f"{shown(raw)} is not one of: {shown_choices}")
        return text

    def holds(self, f, value):
        return value in f.choices

    def preview_text(self, f, saved):
        return f.label_of(saved) if saved in f.choices else as_text(saved)  # a stale name as saved

    def widget(self, f):
        return Widget("select", tuple((c, f.label_of(c)) for c in f.choices), f.unit or None)

    def initial_entry(self, f):
        return f.default

    def entry(self, f, value):
        return value


class Flags(Kind):
    """Any set of `choices` (e.g. the effects a scene switches on): "a, b" or a list."""

    name = "flags"

    def parse(self, f, raw):
        if isinstance(raw, str):
            items = [x for x in raw.replace(",", " ").split() if x]
        elif isinstance(raw, (list, tuple, set, frozenset)) and all(isinstance(x, str) for x in raw):
            items = list(raw)
        else:
            raise InputError(f.name, f"expected names from: {', '.join(f.choices)}")
        unknown = [x for x in items if x not in f.choices]
        if unknown:
            more = f" and {len(unknown) - 3} more" if len(unknown) > 3 else ""
            raise InputError(
                f.name,
                f"unknown {', '.join(map(shown, unknown[:3]))}{more}; choose from: {', '.join(f.choices)}",
            )
        return frozenset(items)

    def holds(self, f, value):
        return isinstance(value, frozenset) and value <= set(f.choices)

    def default_text(self, f):
        return flags_text(f.default)

    def entry_text(self, f, entered):
        if isinstance(entered, (str, list, tuple, set, frozenset)):
            return flags_text(entered)
        return as_text(entered)

    def reported(self, f, value):
        return sorted(value), ""

    def widget(self, f):
        return Widget("checkboxes", tuple((c, f.label_of(c)) for c in f.choices), f.unit or None)

    def entry(self, f, value):
        chosen = _flag_names(value)
        return ", ".join(c for c in f.choices if c in chosen)


class Boolean(Kind):
    """Yes or no: true/false, yes/no, on/off, 1/0; shown as one checkbox."""

    name = "bool"

    def parse(self, f, raw):
        if isinstance(raw, bool):
            return raw
        text = as_text(raw).strip().lower()
        if text in ("true", "yes", "on", "1"):
            return True
        if text in ("false", "no", "off", "0"):
            return False
        raise InputError(f.name, f"{shown(raw)} is not true or false")

    def holds(self, f, value):
        return isinstance(value, bool)

    def default_text(self, f):
        return "true" if f.default else "false"

    def vocabulary(self, f):
        return ("true", "false", "yes", "no", "on", "off", "1", "0")

    def widget(self, f):
        return Widget("checkbox", unit=f.unit or None)

    def initial_entry(self, f):
        return bool(f.default)

    def entry(self, f, value):
        return value if isinstance(value, bool) else as_text(value).lower() in ("true", "yes", "1", "on")


QUANTITY, INTEGER, CHOICE, FLAGS, BOOLEAN = Quantity(), Integer(), Choice(), Flags(), Boolean()


def kind_of(f: Field) -> Kind:
    """The kind the declaration syntax names: flags=True, choices=(...), boolean=True,
    integer=True, else a quantity. (A field may also name its kind: `kind=`.)"""
    if f.flags:
        return FLAGS
    if f.choices:
        return CHOICE
    if f.boolean:
        return BOOLEAN
    if f.integer:
        return INTEGER
    return QUANTITY


def _typed(typed: str) -> str:
    typed = typed.strip()
    return typed if len(typed) <= 40 and typed.isprintable() else shown(typed)


def check_bounds(f: Field, value: float, typed: str) -> float:
    """The value, or an InputError; a value within rounding of an inclusive bound (e.g. 125 psi
    typed against a bound set in another unit) is that bound, so formulas never see it a hair
    outside. Messages quote the bound in the field's display unit."""
    typed = _typed(typed)
    lo, hi = f.bounds_si()
    if lo is not None:
        if not f.min_exclusive and value < lo and value >= lo - BOUND_SLACK * abs(lo):
            value = lo
        if value < lo or (f.min_exclusive and value == lo):
            word = "greater than" if f.min_exclusive else "at least"
            raise InputError(f.name, f"{typed} is too small: must be {word} {f.kind.bound_text(f, lo)}")
    if hi is not None:
        if not f.max_exclusive and value > hi and value <= hi + BOUND_SLACK * abs(hi):
            value = hi
        if value > hi or (f.max_exclusive and value == hi):
            word = "less than" if f.max_exclusive else "at most"
            raise InputError(f.name, f"{typed} is too large: must be {word} {f.kind.bound_text(f, hi)}")
    return value


_BUILTIN_KINDS = (QUANTITY, INTEGER, CHOICE, FLAGS, BOOLEAN)


@dataclass(frozen=True)
class Field:
    """One input. `default`, `min` and `max` are what the user would type: numbers in the display
    unit `unit` (the unit the author reads beside the field; a string default may carry its own
    unit), e.g. `Field("wall", "Wall", "length", "in", default=0.0625, min=0, max=1)` is 0 to 1 in.
    Parsed values are SI; `bounds_si` gives the bounds in SI. What sort of value it holds (a
    quantity, whole number, choice, set of flags, yes/no) is its `kind` (core/fields.py), named
    by the declaration syntax (`integer=True`, `choices=(...)`, `boolean=True`, `flags=True`;
    else a quantity) or given as `kind=`."""

    name: str
    label: str
    quantity: str = "dimensionless"  # a key of units.SI_UNITS
    unit: str = ""  # display unit; a bare number typed by the user means this unit
    default: Any = 0
    min: float | None = None
    max: float | None = None
    min_exclusive: bool = False
    max_exclusive: bool = False
    choices: tuple[str, ...] = ()
    choice_labels: tuple[str, ...] = ()
    integer: bool = False
    boolean: bool = False
    flags: bool = False  # a set of the choices (e.g. the effects a scene switches on)
    help: str = ""
    modes: tuple[str, ...] = ()  # shown and used only in these modes; empty means all
    # shown and used only when other choice fields hold one of these values (for a flags field:
    # when one of them is on), e.g. (("section", ("round_tube", "rectangular_tube")),) for a wall
    when: tuple[tuple[str, tuple[str, ...]], ...] = ()
    kind: Kind | None = None  # after construction always the field's Kind

    def __post_init__(self) -> None:
        legacy = kind_of(self)
        # a built-in kind follows the syntax (so dataclasses.replace(f, integer=True) re-kinds f);
        # any other kind object given is kept
        declared = self.kind
        if declared is None or (declared in _BUILTIN_KINDS and legacy is not QUANTITY):
            declared = legacy
        object.__setattr__(self, "kind", declared)

    @property
    def type(self) -> str:
        """The kind's name ("quantity", "int", "choice", "flags", "bool", ...)."""
        return self.kind.name

    def label_of(self, choice: str) -> str:
        if self.choice_labels:
            return self.choice_labels[self.choices.index(choice)]
        return choice.replace("_", " ")

    def active(self, mode: str | None, choices: Mapping[str, Any] | None = None) -> bool:
        """Whether this field is shown and used, given the mode and the other choices made."""
        if self.modes and mode is not None and mode not in self.modes:
            return False
        if choices is not None:
            for name, allowed in self.when:
                if name not in choices:
                    continue
                chosen = choices[name]
                if isinstance(chosen, frozenset):  # a flags field: any of the allowed is on
                    if not chosen & set(allowed):
                        return False
                elif chosen not in allowed:
                    return False
        return True

    def default_text(self) -> str:
        return self.kind.default_text(self)

    def entry_text(self, entered: Any) -> str:
        """The text shown for what was entered."""
        return self.kind.entry_text(self, entered)

    def parse(self, raw: Any) -> Any:
        """SI value (float), int, bool, choice string or set of flags (as the kind reads it) from
        what a user entered; or an InputError naming this field, in one line, quoting at most the
        start of what was typed."""
        limit = self.kind.max_chars(self)
        if isinstance(raw, str) and len(raw) > limit:
            raise InputError(self.name, f"is too long ({len(raw)} characters; at most {limit})")
        return self.kind.parse(self, raw)

    def _check_bounds(self, value: float, typed: str) -> float:
        """`value` (SI) checked against the bounds (and, for a quantity, the magnitude limits)."""
        return self.kind.checked(self, value, typed)

    def bounds_si(self) -> tuple[float | None, float | None]:
        """(min, max) in the unit `parse` returns (SI), None where unbounded; `min` and `max` are
        declared in the display unit (converted once, on first use, as a bare number typed)."""
        try:
            return self.__dict__["_bounds_si"]
        except KeyError:
            pass
        bounds = tuple(None if b is None else self.kind.bound_si(self, b) for b in (self.min, self.max))
        object.__setattr__(self, "_bounds_si", bounds)
        return bounds
