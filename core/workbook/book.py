"""The workbook as read: its parsed expressions, variables, cards and requirements (plain data;
core.workbook.file reads them from the TOML, core.workbook.solving solves them)."""

from __future__ import annotations

import ast
from dataclasses import dataclass
from dataclasses import field as dc_field
from pathlib import Path
from typing import Any


@dataclass(frozen=True)
class Expr:
    text: str  # as written, without the leading '='
    tree: ast.expr
    names: frozenset[str]  # every root name (variable, card or unit)

    def references(self, known: set[str]) -> set[str]:
        """The variables and cards this expression reads."""
        return {n for n in self.names if n in known}


@dataclass
class Variable:
    name: str
    entry: Any  # as written (tolerance included)
    nominal: Any  # without its tolerance
    tolerance: str | None
    expr: Expr | None  # a reference ('= ...'), else None
    unit: str = ""  # the unit it is shown in ('' for numbers and text)
    kind: str = "dimensionless"  # core.units.SI_UNITS key of a quantity
    text: bool = False  # a word, e.g. a motor's name: passed to choice fields as it is


@dataclass
class Card:
    name: str
    calculator: str
    inputs: dict[str, Any]  # entries as written (the preset's, then the card's own), links excluded
    links: dict[str, Expr]  # field -> reference
    preset: str | None = None
    warnings: list[str] = dc_field(default_factory=list)


@dataclass
class Requirement:
    index: int  # 1-based, in file order
    name: str
    check: str
    note: str
    operands: list[Expr]
    ops: list[str]
    key: str = ""  # a column name: the name's words joined by _, else check_N (unique in the file)


@dataclass
class Workbook:
    source: str
    name: str
    description: str
    variables: dict[str, Variable]
    cards: dict[str, Card]
    requirements: list[Requirement]
    order: list[str]  # variables and cards, each after what it reads
    data: dict = dc_field(default_factory=dict, repr=False, compare=False)  # the TOML as read
    folder: Path | None = None  # where a card's relative preset path starts
    _cache: dict = dc_field(default_factory=dict, repr=False, compare=False)
    match: Any = None  # core.workbook.match.MatchSpec: the [match] table, if the file has one


# the [match] table's outputs (core/workbook/match.py), read by requirements as match.NAME
MATCH_OUTPUTS = {  # name: (label, unit shown and read by requirements)
    "min_bus_voltage": ("Lowest bus voltage", "V"),
    "min_bus_time": ("  at", "s"),
    "time_below_brownout": ("Time below brownout", "s"),
    "brownouts": ("Brownouts", ""),
    "brownout_time": ("Outputs disabled for", "s"),
    "charge_used": ("Charge used", "A*h"),
    "peukert_charge_used": ("Charge used, Peukert-weighted", "A*h"),
    "energy": ("Energy from the cells", "W*h"),
    "end_charge": ("End state of charge", "%"),
    "end_available": ("End charge available (Peukert)", "%"),
    "end_voltage": ("End open-circuit voltage", "V"),
    "peak_current": ("Peak battery current", "A"),
    "rms_current": ("RMS battery current", "A"),
    "main_breaker_load": ("Main breaker peak (of 120 A)", "%"),
    "main_breaker_margin": ("Main breaker margin (1 − θ)", "%"),
    "main_breaker_trip": ("Main breaker would trip at", "s"),
    "moves": ("Moves finished", ""),
    "unfinished": ("Moves not finished", ""),
}
# each moved card's channel breaker, match.<card>_breaker_load etc. (core/workbook/match.py)
MATCH_CHANNEL_OUTPUTS = {
    "breaker_load": ("breaker peak (of its rating)", "%"),
    "breaker_margin": ("breaker margin (1 − θ)", "%"),
    "breaker_trip": ("breaker would trip at", "s"),
}


def match_output(name: str, cards) -> tuple[str, str] | None:
    """(label, unit) of the match's output `name`: one of MATCH_OUTPUTS, or `<card>_breaker_...`
    for a card of `cards` (the cards the match moves); None if it is neither."""
    if name in MATCH_OUTPUTS:
        return MATCH_OUTPUTS[name]
    for suffix, (label, unit) in MATCH_CHANNEL_OUTPUTS.items():
        card = name.removesuffix(f"_{suffix}")
        if card != name and card in cards:
            return (f"{card} {label}", unit)
    return None
