"""Units at the boundary: parse what a user typed into SI, format SI for display.

pint is imported lazily (first call), so importing this module costs nothing at start-up.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from pathlib import Path

from .errors import InputError, shown

# SI factors of every unit Gearhead declares, generated from pint by core/unit_factors.py, so a solve
# with bare numbers never pays for pint's registry (~150 ms)
FACTOR_TABLE = Path(__file__).with_name("unit_factors.json")

# Quantity kind -> the SI unit core works in (written as DESIGN.md's JSON shows them).
SI_UNITS: dict[str, str] = {
    "dimensionless": "",
    "length": "m",
    "area": "m**2",
    "volume": "m**3",
    "area_moment": "m**4",
    "mass": "kg",
    "time": "s",
    "force": "N",
    "torque": "N*m",
    "energy": "J",
    "power": "W",
    "power_density": "W/kg",  # a motor's peak power per kilogram (the motors table)
    "speed": "m/s",
    "angular_speed": "rad/s",
    "angle": "rad",
    "current": "A",
    "voltage": "V",
    "resistance": "ohm",
    "pressure": "Pa",
    "modulus": "Pa",
    "torque_constant": "N*m/A",
    "inertia": "kg*m**2",
    "flow": "m**3/s",
    "density": "kg/m**3",
    "acceleration": "m/s**2",
    "angular_acceleration": "rad/s**2",
    "reciprocal_length": "1/m",
    # WPILib feedforward and feedback gains (elevator: per metre; arm: per radian)
    "voltage_per_speed": "V*s/m",
    "voltage_per_angular_speed": "V*s/rad",
    "voltage_per_acceleration": "V*s**2/m",
    "voltage_per_angular_acceleration": "V*s**2/rad",
    "voltage_per_length": "V/m",
    "voltage_per_angle": "V/rad",
}

# A bare decimal number (ASCII digits only: other scripts' digits are refused by `normalise`).
_NUMBER = re.compile(r"^\s*[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?\s*$")

# Limits that bound the work one entry can cause (9**9**9 once froze the app computing a
# 370-million-digit integer, and a 100 000-character paste took over a minute).
MAX_INPUT_CHARS = 200  # longer is a paste gone wrong; refused before any other work
MAX_EXPONENT = 100  # |n| in x**n: units need 4 at most, and 10**100 is far beyond any part
PARSE_BUDGET_S = 0.5  # CPU seconds of this thread to evaluate one entry (typically 0.1 ms)


# A garbage collection runs in the thread whose allocation set it off, and its time counts as
# that thread's: a full one in a large heap (a long test run) took over PARSE_BUDGET_S while
# '8 in' was read, which was refused as "takes too long". So the budget leaves it out.
class _CollectorTime:
    def __init__(self) -> None:
        import threading
        import time

        self.local = threading.local()  # per thread: the collection under way, seconds spent
        self.now = time.thread_time  # kept: collections run at interpreter exit, imports fail

    def __call__(self, phase: str, info: dict) -> None:
        if phase == "start":
            self.local.began = self.now()
        elif getattr(self.local, "began", None) is not None:
            self.local.spent = self.spent() + self.now() - self.local.began
            self.local.began = None

    def spent(self) -> float:
        """CPU seconds this thread has spent collecting garbage since the clock was set up."""
        return getattr(self.local, "spent", 0.0)


@lru_cache(maxsize=1)
def _collector_time() -> _CollectorTime:
    import gc

    clock = _CollectorTime()
    gc.callbacks.append(clock)
    return clock


@lru_cache(maxsize=1)
def stored_factors() -> dict[str, float]:
    """{"kind|unit": SI factor} as core/unit_factors.py stored them ({} without the file)."""
    import json  # lazily, as pint: importing this module costs nothing at start-up

    try:
        return json.loads(FACTOR_TABLE.read_text(encoding="utf-8"))
    except (OSError, ValueError):  # no table: every lookup falls back to pint
        return {}


def stored_factor(unit: str, kind: str) -> float | None:
    """The stored factor of `unit` as a `kind`, or None (then ask pint)."""
    return stored_factors().get(f"{kind}|{unit}")


@lru_cache(maxsize=1)
def registry():
    """The shared pint registry (built once, on first use)."""
    import pint

    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("links = []")  # placeholder dimensionless counts read naturally
    return ureg


@lru_cache(maxsize=256)
def factor(unit: str, kind: str) -> float:
    """Multiply a value in `unit` by this to get SI for `kind` (cached: pint is slow)."""
    if unit in ("", "1"):
        if kind != "dimensionless":
            raise ValueError(f"{_a(kind)} needs a unit")
        return 1.0
    known = stored_factor(unit, kind)  # every declared unit, generated from pint: no registry to build
    if known is not None:
        return known
    import pint

    # a unit typed by a user (--unit, "as entered"): read by the same bounded parser as values
    q = _evaluate(normalise(unit, "unit"), "unit", kind)
    if not isinstance(q, registry().Quantity) or q.magnitude != 1:
        raise ValueError(f"{shown(unit)} is a number, not a unit")
    try:
        return float(q.to(SI_UNITS[kind] or "dimensionless").magnitude)
    except pint.errors.DimensionalityError:
        raise ValueError(f"{shown(unit)} is not a unit of {_a(kind)}") from None


def parse(text: str | float | int, unit: str, kind: str, field: str) -> float:
    """SI value of what the user typed for `field`.

    A bare number, and any expression of plain numbers ("2+0", "(0.5)", "3*4"), is in the display
    `unit`; an expression with units ("3.5 in", "2 ft + 3 in", "pi rad") is converted by pint, so
    "2", "2+0" and "2 deg" in a deg field are the same angle. Raises InputError naming the field,
    in one line, quoting at most the start of what was typed.
    """
    if isinstance(text, bool):
        raise InputError(field, f"expected {_a(kind)}, got {text!r}")
    if isinstance(text, (int, float)):
        try:
            value = float(text) * factor(unit, kind)
        except OverflowError:  # an int beyond float range
            raise InputError(field, f"{shown(text)} is not a finite number") from None
    else:
        s = normalise(text, field, kind)
        raw = str(text).strip()  # messages quote this, not the form read ("kg·m²", not "kg*m**(2)")
        typed = _NUMBER_AND_UNIT.match(s)
        known = typed and typed["unit"] and stored_factor(typed["unit"], kind)  # "20 in": no pint
        if _NUMBER.match(s) or known:
            number = typed["number"] if known else s
            value = _literal(number, raw, field) * (known or factor(unit, kind))
            if value == 0 and float(number) != 0:  # a tiny number in a unit smaller than SI's
                raise InputError(field, f"{shown(raw)} {_UNDERFLOW}")
        else:
            try:
                q = _evaluate(s, field, kind, raw)
            except InputError as exc:
                if _UNDERFLOW in exc.message:  # "5e-400 m" in a mass: the unit is wrong too, say so
                    _check_kind_of_tiny(s, raw, field, kind)
                raise
            if isinstance(q, float):  # plain numbers only: in the display unit, like a bare number
                value = q * factor(unit, kind)
            else:
                value = _to_si(q, raw, field, kind)
    if not math.isfinite(value):
        raise InputError(field, f"{shown(text)} is not a finite number")
    return value


# A number then one unit of the stored table ("20 in", "25 lbf", "12 ft/s", "90 %"): read from the
# table (core/unit_factors.py, pint's own factors, each checked against pint's reading of the
# whole entry in tests/test_unit_factors.py), so a typed unit no longer pays for pint's registry
# (~0.3 s on the command line). A unit begins with a letter, µ, ° or %: "5 1/m" is not "5" and
# "1/m" (pint refuses two numbers in a row, and so does the table). Anything else goes to pint.
_NUMBER_AND_UNIT = re.compile(
    r"^\s*(?P<number>[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?)\s*(?P<unit>(?:[^\W\d_]|%)\S*)\s*$"
)

_NUMBER_TEXT = r"(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?"
_UNDERFLOW = "is too small to hold (it would read as 0); enter 0, or a size above 1e-300"


def _check_kind_of_tiny(s: str, raw: str, field: str, kind: str) -> None:
    """For an entry with a number too small to hold: an InputError saying both, when its units are
    not of the field's kind (each tiny number read as 1 to find its units); nothing otherwise."""
    import pint

    def one(m: re.Match) -> str:
        tiny = float(m.group()) == 0 and re.search(r"[1-9]", re.split("[eE]", m.group())[0])
        return "1" if tiny else m.group()

    try:
        q = _evaluate(re.sub(_NUMBER_TEXT, one, s), field, kind)
        if isinstance(q, float):
            return
        q.to(SI_UNITS[kind] or "dimensionless")
    except InputError as exc:  # another mistake besides (an unknown unit): both said
        raise InputError(field, f"{exc.message}; and the number {_UNDERFLOW}") from None
    except pint.errors.DimensionalityError:
        raise InputError(
            field,
            f"{shown(raw)} is not {_a(kind)} (expected units like {example_unit(kind)}), and its "
            f"number {_UNDERFLOW}",
        ) from None


def _literal(number: str, typed: str, field: str) -> float:
    """float(number), or an InputError when a number with a non-zero digit would read as 0
    (5e-400: below the smallest float)."""
    value = float(number)
    if value == 0 and re.search(r"[1-9]", number.split("e")[0].split("E")[0]):
        raise InputError(field, f"{shown(typed)} {_UNDERFLOW}")
    return value


# ---- reading what was typed ------------------------------------------------------------------
# Characters are screened first (one pass, refusing whatever could be misread), then pint's own
# string preprocessing ("per", "squared", "%", "^", a space as a product) and its tree builder
# (pint.pint_eval) run on tokens from the small tokenizer below, and the tree is evaluated with
# checked operations. The tokenizer is ours because Python's, which pint uses, reads Python:
# "012" is two numbers (0*12 = 0), "1.2.3" is 1.2*.3, and quotes, "#" comments and line breaks
# have meanings there that a unit expression must not have.

_SUPERSCRIPTS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789-+")
_SUPERSCRIPT_RUN = re.compile(r"[⁻⁺]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+")
# Operators as typeset: the minus sign U+2212 is a minus; dot and cross are products.
_TYPESET = str.maketrans({"\u2212": "-", "·": "*", "⋅": "*", "×": "*", "÷": "/", "⁄": "/", "∕": "/"})
# Dashes are refused, not read as a minus: "3–5" is as often a range as a negative number.
_DASHES = set("\u2010\u2011\u2012\u2013\u2014\u2015")
_ALLOWED_MARKS = set(" .+-*/()^%_°")
# "3 4" (12 to pint) and "1 1/2" (0.5 to pint, 1.5 to a person) are refused; "20 1/in" is a number
# and a unit
_TWO_NUMBERS = re.compile(r"[0-9.]\s+(?!1\s*/\s*[^\W\d])[0-9.]")
_UNDERSCORED_NUMBER = re.compile(r"[0-9]_|_[0-9]")
_TWO_SIGNS = re.compile(r"[-+]\s*[-+]")  # "--5", "+ -5"; "-(-5)" is written out and stays


def normalise(text: object, field: str, kind: str = "dimensionless") -> str:
    """What was typed, stripped, NFKC-normalised (a fullwidth "６ ㎜" is "6 mm"), typeset
    operators made ASCII; or an InputError for anything that could be misread: an over-long entry,
    control characters and line breaks, commas, brackets, dashes, quote marks, other scripts'
    digits, vulgar fractions."""
    import unicodedata

    s = str(text)
    if len(s) > MAX_INPUT_CHARS:
        raise InputError(field, f"is too long ({len(s)} characters; at most {MAX_INPUT_CHARS})")
    s = s.strip()
    if not s:
        raise InputError(field, f"is empty; enter {_a(kind)}")
    typed = s  # messages quote what was typed ("²"), not the form read below ("**(2)")
    for ch in s:  # before NFKC, which turns "½" into "1⁄2" and then "1½" would read as 11/2
        if unicodedata.category(ch) == "No" and ch not in "⁰¹²³⁴⁵⁶⁷⁸⁹":
            raise InputError(field, f"{shown(typed)}: write {ch!r} with the digits 0-9 (e.g. 1/2 for ½)")
    s = _SUPERSCRIPT_RUN.sub(lambda m: "**(" + m.group().translate(_SUPERSCRIPTS) + ")", s)
    s = unicodedata.normalize("NFKC", s).translate(_TYPESET)
    if len(s) > MAX_INPUT_CHARS:
        raise InputError(field, f"is too long ({len(s)} characters; at most {MAX_INPUT_CHARS})")
    for ch in s:
        if ch.isascii() and (ch.isalnum() or ch in _ALLOWED_MARKS):
            continue
        problem = _character_problem(ch)
        if problem:
            raise InputError(field, f"{shown(typed)} {problem}")
    if _TWO_NUMBERS.search(s):
        raise InputError(
            field,
            f"{shown(typed)} has two numbers in a row; write one number (1.5, not "
            f"1 1/2), or an operator between them (3*4)",
        )
    if _UNDERSCORED_NUMBER.search(s):
        raise InputError(field, f"{shown(typed)}: write numbers without '_' (1000, not 1_000)")
    signs = _TWO_SIGNS.search(s)
    if signs:  # "--5" read as +5: a doubled sign reverses what was meant as often as not
        raise InputError(
            field, f"{shown(typed)} has two signs in a row ({signs.group()!r}); write one sign (-5, not --5)"
        )
    for m in re.finditer("%", s):
        before = s[: m.start()].rstrip()
        if before.endswith("%"):  # "50 %%" read as 0.005
            raise InputError(field, f"{shown(typed)} has % twice; write it once (50 %)")
        if not before or before[-1] not in "0123456789.)":  # "%" alone read as 1 %
            raise InputError(field, f"{shown(typed)}: % needs a number before it (50 %)")
    return s


def _character_problem(ch: str) -> str | None:
    """Why a non-ASCII or unusual character is refused, or None if it may stay (a letter)."""
    import unicodedata

    category = unicodedata.category(ch)
    if ch in "\n\r\v\f\u2028\u2029\x85":
        return "contains a line break; enter one line"
    if ch == "\t":
        return "contains a tab"
    if category[0] == "C":  # control, format (zero-width, direction marks), unassigned
        return f"contains an invisible character (U+{ord(ch):04X})"
    if ch == ",":
        return "contains a comma: use a point for decimals (3.5) and no thousands separators"
    if ch in "[]{}":
        return "contains brackets: enter one value, grouped with ( ) if needed"
    if ch in _DASHES:
        return f"contains a dash (U+{ord(ch):04X}): type - for a minus sign"
    if ch in "'\"′″":
        return "contains a quote mark: write feet and inches as ft and in (5 ft + 3 in)"
    if category == "Nd":
        return f"contains the digit {ch!r}: use the digits 0-9"
    if ch.isalpha() or ch == "°":
        return None  # unit names such as µm, Ω, Å
    return f"contains {ch!r}, which is not part of a number or unit"


_TOKEN = re.compile(
    r"\s*(?:(?P<number>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?)"
    r"|(?P<name>[^\W\d]\w*)|(?P<op>\*\*|[-+*/()]))"
)


def _tokens(s: str, field: str, kind: str, typed: str | None = None) -> list:
    """pint-style tokens (tokenize.TokenInfo) of a screened, preprocessed expression."""
    import token as tokenlib
    from tokenize import TokenInfo

    quoted = shown(s if typed is None else typed)
    out, pos = [], 0
    types = {"number": tokenlib.NUMBER, "name": tokenlib.NAME, "op": tokenlib.OP}
    while pos < len(s):
        m = _TOKEN.match(s, pos)
        if not m:
            if s[pos:].isspace():
                break
            raise InputError(field, f"cannot read {quoted} as {_a(kind)}: unexpected {s[pos]!r}")
        kind_of = m.lastgroup
        if kind_of == "number" and out and out[-1].type == tokenlib.NUMBER:
            raise InputError(field, f"{quoted} is not a number (two numbers run together)")
        out.append(TokenInfo(types[kind_of], m.group(kind_of), (1, m.start(kind_of)), (1, m.end()), s))
        pos = m.end()
    out.append(TokenInfo(tokenlib.ENDMARKER, "", (1, len(s)), (1, len(s)), s))
    return out


def is_plain_number(text: str, field: str, kind: str = "dimensionless") -> bool:
    """Whether an entry is a number without a unit, whatever its form ('0.1', '(0.1)', '0.1*1',
    'pi'): what a tolerance is when it takes its value's unit. An InputError when it cannot be read."""
    s = normalise(text, field, kind)
    return bool(_NUMBER.match(s)) or isinstance(_evaluate(s, field, kind), float)


def _evaluate(s: str, field: str, kind: str, raw: str | None = None):
    """A float (only plain numbers were typed) or a pint Quantity, from a screened entry; every
    operation checked, and the whole bounded by MAX_EXPONENT and PARSE_BUDGET_S. Messages quote
    `raw` (what was typed) when given."""
    import time

    import pint
    from pint.pint_eval import build_eval_tree
    from pint.util import string_preprocessor

    ureg = registry()
    Quantity = ureg.Quantity
    collecting = _collector_time()
    deadline = time.thread_time() - collecting.spent() + PARSE_BUDGET_S
    typed = shown(s if raw is None else raw)
    s_typed = s if raw is None else raw

    def fail(why: str):
        raise InputError(field, f"{typed} {why}")

    def tick():  # this thread's CPU time, less its garbage collections (_CollectorTime)
        if time.thread_time() - collecting.spent() > deadline:
            fail("takes too long to work out; simplify it")

    def magnitude(x):
        return x.magnitude if isinstance(x, Quantity) else x

    def checked(x):
        m = magnitude(x)
        if isinstance(m, complex) or not math.isfinite(m):
            fail("is not a finite number")
        return x

    def kept(x, *operands):  # a product or quotient of non-zero numbers that rounds to 0
        if magnitude(x) == 0 and all(magnitude(o) != 0 for o in operands):
            fail(_UNDERFLOW)
        return x

    def define(token):
        tick()
        if token.type == tokenize_number:
            return checked(_literal(token.string, s_typed, field))
        name = token.string
        if name.lower() in ("inf", "infinity", "nan"):
            fail("is not a finite number")
        try:
            return Quantity(1.0, ureg.get_name(name))
        except Exception:  # pint raises several types for names it does not know
            power_hint = re.fullmatch(r"([^\W\d_]+)([0-9]+)", name)
            hint = f"; for a power write {power_hint[1]}**{power_hint[2]}" if power_hint else ""
            raise InputError(
                field, f"{shown(name)} is not a unit I know (units of {_a(kind)}: {example_unit(kind)}){hint}"
            ) from None

    def power(base, exponent):
        tick()
        if isinstance(exponent, Quantity):
            if not exponent.unitless:
                fail("has a unit in an exponent")
            exponent = float(exponent.to("dimensionless").magnitude)
        if abs(exponent) > MAX_EXPONENT:
            fail(f"has an exponent of {exponent:.3g}; at most {MAX_EXPONENT} in size")
        b = magnitude(base)
        if b < 0 and exponent != int(exponent):
            fail("takes a fractional power of a negative number")
        if b == 0 and exponent < 0:
            fail("divides by zero")
        try:
            return kept(checked(base**exponent), base)
        except (OverflowError, ZeroDivisionError):
            fail("is not a finite number")

    def divide(a, b):
        tick()
        if magnitude(b) == 0:
            fail("divides by zero")
        return kept(checked(a / b), a)

    def multiply(a, b):
        tick()
        return kept(checked(a * b), a, b)

    def add(sign):
        def op(a, b):
            tick()
            try:
                return checked(a + b if sign > 0 else a - b)
            except pint.errors.DimensionalityError:
                fail("adds quantities of different kinds (give every term a unit)")

        return op

    import token as tokenlib

    tokenize_number = tokenlib.NUMBER
    if s.count("(") != s.count(")"):
        fail("has unbalanced parentheses")
    for pre in ureg.preprocessors:  # "%" -> " percent "
        s = pre(s)
    tokens = _tokens(string_preprocessor(s), field, kind, raw)
    try:
        tree = build_eval_tree(tokens)
    except Exception:  # pint's tree builder raises several types on an incomplete expression
        fail(f"is not a complete expression of {_a(kind)}")
    binary = {"**": power, "*": multiply, "": multiply, "/": divide, "+": add(1), "-": add(-1)}
    unary = {"+": lambda x: x, "-": lambda x: x * -1}
    try:
        result = tree.evaluate(define, binary, unary)
    except InputError:
        raise
    except Exception:  # an operator pint's tree allows but an entry may not use (a unary "*"),
        fail(f"cannot be read as {_a(kind)}")  # or arithmetic on a temperature scale
    return float(result) if isinstance(result, (int, float)) else result


def _to_si(q, s: str, field: str, kind: str) -> float:
    import pint

    target = SI_UNITS[kind] or "dimensionless"
    try:
        value = float(q.to(target).magnitude)
        if value == 0 and q.magnitude != 0:  # 1e-300 nm: a size no float holds in metres
            raise InputError(field, f"{shown(s)} {_UNDERFLOW}")
    except pint.errors.DimensionalityError:
        raise InputError(
            field, f"{shown(s)} is not {_a(kind)} (expected units like {example_unit(kind)})"
        ) from None
    except (ArithmeticError, TypeError, ValueError):
        raise InputError(field, f"{shown(s)} is not a finite number") from None
    return value


def _kind_words(kind: str) -> str:
    return "number" if kind == "dimensionless" else kind.replace("_", " ")


def _a(kind: str) -> str:
    """The kind with its article: "a length", "an angular speed", "a number"."""
    words = _kind_words(kind)
    return ("an " if words[0] in "aeiou" else "a ") + words


_EXAMPLES = {
    "length": "mm, in, ft",
    "force": "N, lbf",
    "torque": "N*m, in*lbf",
    "speed": "m/s, ft/s",
    "angular_speed": "rpm, rad/s",
    "angle": "deg, rad",
    "current": "A",
    "voltage": "V",
    "pressure": "psi, kPa",
    "mass": "kg, lb",
    "volume": "cc, in**3, L",
    "time": "s, min",
    "power": "W, hp",
    "resistance": "ohm",
    "modulus": "GPa, psi",
    "dimensionless": "a plain number, %",
}


# Units a results table cycles through for each kind (the calculator's own unit comes first).
COMMON_UNITS: dict[str, tuple[str, ...]] = {
    "length": ("mm", "cm", "m", "in", "ft"),
    "area": ("mm**2", "in**2", "m**2"),
    "volume": ("cc", "in**3", "L", "m**3"),
    "area_moment": ("mm**4", "in**4", "m**4"),
    "mass": ("g", "kg", "lb"),
    "time": ("ms", "s", "min"),
    "force": ("N", "lbf", "kN"),
    "torque": ("N*m", "in*lbf", "ft*lbf"),
    "energy": ("J", "ft*lbf", "kJ"),
    "power": ("W", "hp", "kW"),
    "power_density": ("W/kg", "W/lb"),
    "speed": ("m/s", "ft/s", "in/s", "km/h", "mph"),
    "angular_speed": ("rpm", "rad/s", "deg/s"),
    "angle": ("deg", "rad"),
    "current": ("A", "mA"),
    "voltage": ("V",),
    "resistance": ("ohm", "mohm"),
    "pressure": ("psi", "kPa", "bar", "Pa"),
    "modulus": ("GPa", "MPa", "ksi", "psi"),
    "inertia": ("kg*m**2", "lb*in**2"),
    "flow": ("L/s", "ft**3/min"),
    "density": ("kg/m**3", "g/cc"),
    "acceleration": ("m/s**2", "ft/s**2"),
    "angular_acceleration": ("deg/s**2", "rad/s**2"),
    "dimensionless": ("", "%"),
}


def next_unit(current: str, kind: str, home: str) -> str:
    """The unit after `current` in the ring of a kind's common units, which starts at the output's
    own unit `home`: Enter on a result walks the whole ring (mm → cm → m → in → ft → mm) instead of
    bouncing between the first two."""
    ring = (home,) + tuple(u for u in COMMON_UNITS.get(kind, ()) if u != home)
    if current not in ring:
        return ring[0]
    return ring[(ring.index(current) + 1) % len(ring)]


def check_unit(unit: str, kind: str, name: str) -> str:
    """`unit` if it can show a `kind`, else an InputError naming `name`."""
    try:
        factor(unit, kind)
    except Exception:  # unknown unit or wrong dimension: both mean "cannot show it in that"
        raise InputError(
            name, f"cannot show {_a(kind)} in {shown(unit)} (units like {example_unit(kind)})"
        ) from None
    return unit


def example_unit(kind: str) -> str:
    return _EXAMPLES.get(kind, SI_UNITS.get(kind, "") or "a plain number")


def to_unit(value_si: float, unit: str, kind: str) -> float:
    return value_si / factor(unit, kind)


def format_number(x: float, sig: int = 5) -> str:
    """A compact, human number: 5 significant figures, no exponent for everyday sizes."""
    if x == 0 or not math.isfinite(x):
        return "0" if x == 0 else str(x)
    mag = abs(x)
    if 1e-4 <= mag < 1e7:
        decimals = max(0, sig - 1 - int(math.floor(math.log10(mag))))
        s = f"{x:.{decimals}f}"
        if "." in s:
            s = s.rstrip("0").rstrip(".")
        return s
    return f"{x:.{sig - 1}e}"


def format_quantity(value_si: float, unit: str, kind: str) -> str:
    """'187.33 mm' from 0.18733 (m) and display unit 'mm'."""
    v = to_unit(value_si, unit, kind)
    return f"{format_number(v)} {unit}".rstrip()
