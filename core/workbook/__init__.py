"""Workbooks: one TOML file of linked cards, shared variables and requirements (DESIGN.md "Workbooks").

    format = 1
    name = "2027 robot"

    [variables]
    robot_mass = "125 lb ± 5 lb"        # a quantity (tolerance allowed), a number, a yes/no or text
    drive_motor = "Kraken X60"          # text: a choice another card takes
    weight = "= robot_mass * 9.80665 m/s**2"

    [cards.lift]                        # a calculator and its inputs...
    calculator = "elevator"
    inputs = { load_mass = "15 lb", motor = "= drive_motor" }

    [cards.drive]                       # ...or a preset file (its folder, or builtin:CALC/NAME)
    preset = "builtin:sprint/swerve_mk4i_l3"
    inputs = { robot_mass = "= robot_mass" }

    [[requirements]]
    name = "Elevator to the top in under a second"
    check = "lift.time_to_goal < 1 s"

An input or variable written `"= EXPR"` is a reference: EXPR is arithmetic (+ - * / **, unary minus,
parentheses) of numbers, units (a number then its unit, `9.80665 m/s**2`), variables, a card's
output `CARD.OUTPUT`, or a column of a card's table `CARD.TABLE.COLUMN` (the first row that has it:
tables list the best first, e.g. the ratio finder's pick). EXPR is read by Python's `ast` and only
those nodes are evaluated (never eval); values are pint quantities, so units follow the arithmetic.
A requirement's `check` is a comparison (<, <=, >, >=, ==, !=; chains such as `a < b < c`) of such
expressions. Its margin is how far it holds (negative: how far it fails), in the unit of the
comparison: right − left for < and <=, left − right for > and >=.

Cards and variables are solved in dependency order (graphlib); a cycle, an unknown name, a reference
of the wrong kind for its field (a mass into a force) or a comparison of two kinds is refused when
the file loads, naming the file, the card and the field. A card whose solve fails (a referenced
value out of its field's range, a load the motors cannot lift) is reported, with the cards and
requirements that depend on it, as not holding: that is the design failing, not the file.

The package by concern: `expressions` (the language: parsing, evaluating, units), `file` (the TOML
read and written), `kinds` (a linked value fits its field, a comparison one kind), `solving` (the
order and the solve), `book` (the parsed workbook as data), `match` (the [match] table: the robot's
moves on one battery, run after the cards, its outputs `match.OUTPUT` read by requirements) and
`study` (sweeps and worst cases:
imported on its own, as it loads core.sweep and core.tolerance). What other modules use is named
here.
"""

from .book import Card, Expr, Requirement, Variable, Workbook
from .expressions import (
    MAX_EXPRESSION_CHARS,
    MAX_NESTING,
    OFFSET_UNITS,
    UNKNOWN,
    NotSolved,
    OffsetUnitError,
    Scope,
    evaluate,
    kind_of,
    parse_expression,
)
from .file import (
    BUILTIN_PREFIX,
    FORMAT,
    MAX_CARDS,
    MAX_REQUIREMENTS,
    MAX_VARIABLES,
    edited,
    from_dict,
    from_text,
    is_workbook_file,
    load,
    raise_in,
    save,
)
from .kinds import entry_for
from .solving import EQUAL_WITHIN, CardResult, CheckResult, Outcome, as_calculator, solve, studied

__all__ = [
    "BUILTIN_PREFIX",
    "EQUAL_WITHIN",
    "FORMAT",
    "MAX_CARDS",
    "MAX_EXPRESSION_CHARS",
    "MAX_NESTING",
    "MAX_REQUIREMENTS",
    "MAX_VARIABLES",
    "OFFSET_UNITS",
    "UNKNOWN",
    "Card",
    "CardResult",
    "CheckResult",
    "Expr",
    "NotSolved",
    "OffsetUnitError",
    "Outcome",
    "Requirement",
    "Scope",
    "Variable",
    "Workbook",
    "as_calculator",
    "edited",
    "entry_for",
    "evaluate",
    "from_dict",
    "from_text",
    "is_workbook_file",
    "kind_of",
    "load",
    "parse_expression",
    "raise_in",
    "save",
    "solve",
    "studied",
]
