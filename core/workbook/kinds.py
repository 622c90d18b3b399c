"""Kinds: a linked value fits its field (a mass into a mass, a whole number into a count, a word into
a choice) and a requirement compares values of one kind; checked when the file loads with each
output standing for a quantity of its declared kind (no solve), and again on the solved values."""

from __future__ import annotations

from typing import Any

from .. import units
from ..errors import InputError, shown
from .book import Expr, Requirement, Workbook
from .expressions import (
    UNKNOWN,
    Scope,
    as_quantity,
    calculator_of,
    evaluate,
    is_quantity,
    kind_of,
    literal_value,
    units_of,
)

# ---------------------------------------------------------------------------------------------
# Into a card's field


def entry_for(f, value: Any, where: str, src: str, static: bool = False) -> Any:
    """A referenced value as an entry of field `f` (what a user would type): a quantity in the
    field's display unit, a whole number, or a word. InputError when the kind does not fit.
    `static`: the kinds check, where a plain number may stand for a card's text output."""
    if value is UNKNOWN:
        return value
    if static and not f.kind.numeric and is_quantity(value) and value.dimensionless:
        return value
    if f.kind.with_unit:
        if isinstance(value, (str, bool)):
            raise InputError(where, f"takes {_kind_words(f.quantity)}, got {shown(value)}", src)
        si_unit = units.SI_UNITS[f.quantity] or "dimensionless"
        if is_quantity(value):
            import pint

            try:
                si = float(value.to(si_unit).magnitude)
            except pint.errors.DimensionalityError:
                raise InputError(
                    where,
                    f"takes {_kind_words(f.quantity)} ({f.unit or 'a plain number'}); the reference gives "
                    f"{_dimension_words(value)}",
                    src,
                ) from None
        elif f.quantity == "dimensionless":
            si = float(value)
        else:
            raise InputError(
                where,
                f"takes {_kind_words(f.quantity)}; the reference gives a plain number (give it a unit)",
                src,
            )
        return si / units.factor(f.unit, f.quantity) if f.unit else si
    if f.kind.whole:
        if isinstance(value, (str, bool)):
            raise InputError(where, f"takes a whole number, got {shown(value)}", src)
        if is_quantity(value):
            if not value.dimensionless:
                raise InputError(
                    where, f"takes a whole number; the reference gives {_dimension_words(value)}", src
                )
            value = float(value.to("dimensionless").magnitude)
        if abs(value - round(value)) > 1e-9 * max(1.0, abs(value)):
            raise InputError(
                where, f"takes a whole number; the reference gives {units.format_number(value)}", src
            )
        return int(round(value))
    if not isinstance(value, (str, bool, list, tuple, frozenset, set)):
        raise InputError(where, f"takes a {f.type} ({', '.join(f.choices) or 'yes/no'}), not a number", src)
    return value


def _kind_words(kind: str) -> str:
    return "a plain number" if kind == "dimensionless" else units._a(kind)


def _dimension_words(q: Any) -> str:
    kind = kind_of(q)
    if kind:
        return f"{_kind_words(kind)} ({units.SI_UNITS[kind] or 'no unit'})"
    return f"a quantity in {q.to_base_units().units:~}"


# ---------------------------------------------------------------------------------------------
# The kinds check, before any solve


def check_kinds(wb: Workbook) -> None:
    """Every reference fits its field and every comparison compares one kind, checked with each
    output standing for a quantity of its declared kind (no solve)."""
    scope = Scope({}, {}, {}, static=True, workbook=wb)
    for node in wb.order:
        if node in wb.variables:
            v = wb.variables[node]
            where = f"variables.{node}"
            if v.expr is not None:
                scope.variables[node] = evaluate(v.expr, scope, where, wb.source)
            else:
                scope.variables[node] = literal_value(v)
            continue
        card = wb.cards[node]
        calc = calculator_of(wb, node)
        for field_name, expr in card.links.items():
            where = f"cards.{node}.{field_name}"
            value = evaluate(expr, scope, where, wb.source)
            try:
                entry_for(calc.field(field_name), value, where, wb.source, static=True)
            except InputError as exc:
                raise InputError(where, exc.message + _read_as_units(wb, [expr]), wb.source) from None
    for r in wb.requirements:
        where = f"requirements[{r.index}].check"
        sides = [evaluate(e, scope, where, wb.source) for e in r.operands]
        try:
            compare_kinds(sides, r, where, wb.source, static=True)
        except InputError as exc:
            raise InputError(where, exc.message + _read_as_units(wb, r.operands), wb.source) from None


def _read_as_units(wb: Workbook, exprs: list[Expr]) -> str:
    """'; read as units: mas' when a name that is no variable or card was taken for a unit (a typo
    of a variable's name may be one of pint's many units), else ''."""
    known = set(wb.variables) | set(wb.cards)
    guessed = sorted({n for e in exprs for n in e.names if n not in known and len(n) > 1})
    return f" (read as units: {', '.join(guessed)})" if guessed else ""


def compare_kinds(sides: list, r: Requirement, where: str, src: str, static: bool = False) -> None:
    import pint

    for (a, b), op in zip(zip(sides, sides[1:]), r.ops):
        if a is UNKNOWN or b is UNKNOWN:
            continue
        texts = isinstance(a, (str, bool)) or isinstance(b, (str, bool))
        if texts and static and any(is_quantity(x) and x.dimensionless for x in (a, b)):
            continue  # a card's dimensionless output may be text
        if texts:
            if op not in ("==", "!=") or type(a) is not type(b):
                raise InputError(
                    where,
                    f"{shown(r.check)}: text and yes/no compare only with == and != to their own kind",
                    src,
                )
            continue
        qa = a if is_quantity(a) else units.registry().Quantity(float(a), "dimensionless")
        try:
            qa.to(units_of(b))
        except pint.errors.DimensionalityError:
            raise InputError(
                where,
                f"{shown(r.check)}: compares {_dimension_words(qa)} with {_dimension_words(as_quantity(b))}",
                src,
            ) from None
