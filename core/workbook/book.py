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
