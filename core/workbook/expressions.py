"""The workbook's expression language: a reference (`"= EXPR"`) or a requirement's check, parsed with
Python's `ast` and checked node by node (never eval), then evaluated on pint quantities, so units
follow the arithmetic; and the units and kinds of the values it gives."""

from __future__ import annotations

import ast
import io
import math
import re
import tokenize
from dataclasses import dataclass
from typing import Any

from .. import units
from ..errors import InputError, shown
from .book import Expr, Variable, Workbook

MAX_EXPRESSION_CHARS = 300  # a reference or check is one line of arithmetic
MAX_NESTING = 40  # parentheses deep; Python's parser would recurse further
_KEYWORD_PREFIX = "_kw_"  # a unit that is a Python keyword ('in') is renamed while parsing
_KEYWORD_UNITS = {"in"}  # the others ('if', 'not', 'lambda') keep their meaning and are refused
_COMPARISONS = {ast.Lt: "<", ast.LtE: "<=", ast.Gt: ">", ast.GtE: ">=", ast.Eq: "==", ast.NotEq: "!="}
_TYPESET = str.maketrans({"\u2212": "-", "·": "*", "⋅": "*", "×": "*", "÷": "/", "^": "**"})


# ---------------------------------------------------------------------------------------------
# Parsing: with ast, checked node by node


def parse_expression(text: str, where: str, source: str, compare: bool = False) -> Expr | list:
    """An Expr of `text`; with `compare`, (operands, operators) of a comparison. Every mistake is an
    InputError naming `where` in `source`."""

    def fail(why: str):
        raise InputError(where, f"{shown(text)} {why}", source)

    if not isinstance(text, str):
        raise InputError(where, f"must be a string, got {shown(text)}", source)
    if len(text) > MAX_EXPRESSION_CHARS:
        fail(f"is too long ({len(text)} characters; at most {MAX_EXPRESSION_CHARS})")
    body = text.translate(_TYPESET).replace("%", " percent ")
    if not body.isprintable():
        fail("contains a line break or an invisible character")
    if not body.strip():
        fail("is empty")
    if body.count("(") > MAX_NESTING:
        fail(f"has more than {MAX_NESTING} parentheses")
    python = _python_source(body, fail)
    try:
        tree = ast.parse(python, mode="eval").body
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        fail("is not a complete expression (write e.g. '= lift.time_to_goal * 2' or 'x < 1 s')")
    ops: list[str] = []
    if compare:
        if not isinstance(tree, ast.Compare):
            fail("is not a comparison (write e.g. 'lift.time_to_goal < 1 s')")
        for op in tree.ops:
            if type(op) not in _COMPARISONS:
                fail("compares with an operator other than <, <=, >, >=, ==, !=")
            ops.append(_COMPARISONS[type(op)])
        operands = [tree.left, *tree.comparators]
    else:
        operands = [tree]
    exprs = []
    for node in operands:
        names: set[str] = set()
        _check_node(node, fail, names)
        exprs.append(Expr(ast.unparse(node).replace(_KEYWORD_PREFIX, ""), node, frozenset(names)))
    if compare:
        return [exprs, ops]
    return Expr(text.strip(), tree, exprs[0].names)


def _python_source(body: str, fail) -> str:
    """`body` as Python: a quantity written as a number then its unit ('9.8 m/s**2', '2 ft',
    '3 lbf ft', '2 m**2') becomes one parenthesised product, so it binds as written ('x / 2 s' is x
    divided by two seconds); any other juxtaposition is a product; the inch ('in', a Python
    keyword) gets a name Python accepts."""
    try:
        raw = list(tokenize.generate_tokens(io.StringIO(body).readline))
    except (tokenize.TokenError, SyntaxError, IndentationError):
        fail("is not a complete expression")
    tokens = []
    for tok in raw:
        if tok.type in (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER, tokenize.INDENT, tokenize.DEDENT):
            continue
        if tok.type == tokenize.ERRORTOKEN and tok.string.isspace():
            continue
        if tok.type not in (tokenize.NUMBER, tokenize.NAME, tokenize.OP):
            fail(f"contains {tok.string!r}, which is not part of a number, unit or name")
        text = tok.string
        if tok.type == tokenize.NAME and text in _KEYWORD_UNITS:
            text = _KEYWORD_PREFIX + text
        tokens.append((tok.type, text))

    def is_(k: int, kind: int, text: str | None = None) -> bool:
        return k < len(tokens) and tokens[k][0] == kind and (text is None or tokens[k][1] == text)

    out: list[str] = []
    previous = None  # 'value' after a NUMBER, NAME or ')': a value next is a product
    k = 0
    while k < len(tokens):
        kind, text = tokens[k]
        starts_value = kind in (tokenize.NUMBER, tokenize.NAME) or text == "("
        if starts_value and previous == "value" and not (out and out[-1] == "."):
            out.append("*")
        if kind == tokenize.NUMBER and is_(k + 1, tokenize.NAME) and not is_(k + 2, tokenize.OP, "."):
            group = [text]
            k += 1
            while is_(k, tokenize.NAME) and not is_(k + 1, tokenize.OP, "."):  # its units, and powers
                group += ["*", tokens[k][1]]
                k += 1
                if is_(k, tokenize.OP, "**"):
                    sign = ["-"] if is_(k + 1, tokenize.OP, "-") else []
                    if is_(k + 1 + len(sign), tokenize.NUMBER):
                        group += ["**", *sign, tokens[k + 1 + len(sign)][1]]
                        k += 2 + len(sign)
            out += ["(", *group, ")"]
            previous = "value"
            continue
        out.append(text)
        previous = "value" if (kind in (tokenize.NUMBER, tokenize.NAME) or text == ")") else "op"
        k += 1
    return " ".join(out)


_BINARY = (ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow)


def _check_node(node: ast.AST, fail, names: set[str]) -> None:
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            fail(f"contains {shown(node.value)}: only numbers, units and names")
        return
    if isinstance(node, ast.Name):
        names.add(node.id.removeprefix(_KEYWORD_PREFIX))
        return
    if isinstance(node, ast.Attribute):
        depth, inner = 1, node.value
        while isinstance(inner, ast.Attribute):
            depth, inner = depth + 1, inner.value
        if not isinstance(inner, ast.Name) or depth > 2:
            fail("names something other than CARD.OUTPUT or CARD.TABLE.COLUMN")
        names.add(inner.id)
        return
    if isinstance(node, ast.BinOp) and isinstance(node.op, _BINARY):
        _check_node(node.left, fail, names)
        _check_node(node.right, fail, names)
        return
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        _check_node(node.operand, fail, names)
        return
    if isinstance(node, ast.Compare):
        fail("has a comparison where a value belongs (comparisons are for [[requirements]] checks)")
    fail("uses something other than + - * / **, parentheses, numbers, units and names")


# ---------------------------------------------------------------------------------------------
# Units and kinds of values


OFFSET_UNITS = ("degree_Celsius", "degree_Fahrenheit", "degree_Reaumur")


class OffsetUnitError(InputError):
    """A unit with an offset used where pint would read it as an absolute temperature."""


def _has_offset(x: Any) -> bool:
    """Whether a quantity's units hold a unit with an offset (degC, degF)."""
    return is_quantity(x) and any(name in OFFSET_UNITS for name, _ in x.unit_items())


def unit_of(written: str, q: Any) -> tuple[str, str]:
    """(display unit, quantity kind) of a quantity as written: '60 kg' -> ('kg', 'mass')."""
    if not is_quantity(q):
        return "", "dimensionless"
    kind = kind_of(q)
    if not kind:  # a unit pint knows that no field takes (degC, K, mol): kept as written, kind ''
        return f"{q.units:~}", ""
    m = re.match(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*(?P<unit>.*?)\s*$", written)
    unit = m.group("unit") if m else ""
    if unit:
        try:
            units.factor(unit, kind)
            return unit, kind
        except Exception:  # an expression ('2 ft + 3 in'): shown in the kind's SI unit
            pass
    return units.SI_UNITS[kind], kind


def kind_of(q: Any) -> str:
    """The core.units.SI_UNITS kind of a pint quantity's dimensionality (the first that matches:
    torque before energy, pressure before modulus; angles are dimensionless to pint)."""
    ureg = units.registry()
    wanted = q.dimensionality
    for kind, si in units.SI_UNITS.items():
        if ureg.Quantity(1.0, si or "dimensionless").dimensionality == wanted:
            return kind
    return ""


def is_quantity(x: Any) -> bool:
    return hasattr(x, "magnitude") and hasattr(x, "units")


def as_quantity(x: Any):
    return x if is_quantity(x) else units.registry().Quantity(float(x), "dimensionless")


def units_of(q: Any):
    return q.units if is_quantity(q) else units.registry().dimensionless


# ---------------------------------------------------------------------------------------------
# Evaluation


class _Unknown:
    """A value of known dimension only (the kinds check before any solve): a card's dimensionless
    output may be a number or text, so anything goes with it."""

    def __repr__(self) -> str:
        return "<unknown>"


UNKNOWN = _Unknown()


@dataclass
class Scope:
    """What names mean while evaluating: variables' values, cards' solutions (or the reason a card
    has none), and `static` for the kinds check (outputs stand for quantities of their kind)."""

    variables: dict[str, Any]
    cards: dict[str, Any]  # name -> core.model.Solution
    failed: dict[str, str]  # name -> why it has no solution
    static: bool = False
    workbook: Workbook | None = None


class NotSolved(Exception):
    """A value needs a card that could not be solved: the message says which and why."""


class Missing:
    """A variable whose reference reads a card with no solution: reading it says why."""

    def __init__(self, why: str):
        self.why = why


def evaluate(expr: Expr, scope: Scope, where: str, src: str) -> Any:
    """The value of `expr`: a pint Quantity, a number, text or yes/no; InputError on a mistake in
    the file, NotSolved when a card it reads has no solution."""
    ureg = units.registry()

    def fail(why: str):
        raise InputError(where, f"{shown(expr.text)}: {why}", src)

    def number(x, what: str):
        if isinstance(x, (str, bool)):
            fail(f"{what} is {shown(x)}, not a number: arithmetic needs numbers")
        return x

    def tidy(x):
        if scope.static and is_quantity(x):
            return ureg.Quantity(1.0, x.units)  # only the dimension is known
        m = x.magnitude if is_quantity(x) else x
        if isinstance(m, int) and not isinstance(m, bool):
            m = float(m) if abs(m) < 1e300 else math.inf  # a card's whole-number outputs multiplied
        if isinstance(m, float) and not math.isfinite(m):
            fail("is not a finite number")
        return x

    def walk(node):
        if isinstance(node, ast.Constant):  # a float, so no product of integers grows without bound
            try:
                return float(node.value)
            except OverflowError:
                fail("is not a finite number")
        if isinstance(node, ast.Name):
            return name(node.id.removeprefix(_KEYWORD_PREFIX))
        if isinstance(node, ast.Attribute):
            parts = []
            inner = node
            while isinstance(inner, ast.Attribute):
                parts.append(inner.attr)
                inner = inner.value
            return output(inner.id, parts[::-1])
        if isinstance(node, ast.UnaryOp):
            x = walk(node.operand)
            if x is UNKNOWN:
                return x
            number(x, ast.unparse(node.operand))
            return -x if isinstance(node.op, ast.USub) else x
        left, right = walk(node.left), walk(node.right)
        if isinstance(node.op, ast.Pow) and right is UNKNOWN and is_quantity(left) and not left.dimensionless:
            fail("raises a quantity with a unit to a power that is not a plain number")
        if left is UNKNOWN or right is UNKNOWN:
            return UNKNOWN
        number(left, ast.unparse(node.left).replace(_KEYWORD_PREFIX, ""))
        number(right, ast.unparse(node.right).replace(_KEYWORD_PREFIX, ""))
        if _has_offset(left) or _has_offset(right):
            # only '20 degC' (a number times the unit, the whole entry): pint reads degC inside a
            # compound or a product as an absolute temperature ('5 degC/s' was 278.15 K/s)
            top = expr.tree.operand if isinstance(expr.tree, ast.UnaryOp) else expr.tree
            plain_product = (
                node is top
                and isinstance(node.op, ast.Mult)
                and (isinstance(left, float) or isinstance(right, float))
            )
            if not plain_product:
                raise OffsetUnitError(
                    where,
                    f"{shown(expr.text)}: uses a unit with an offset (degC, degF) in arithmetic or a "
                    "compound unit: write the temperature alone, or in K or degR (delta_degC for a "
                    "difference)",
                    src,
                )
        import pint

        try:
            if isinstance(node.op, ast.Add):
                return tidy(left + right)
            if isinstance(node.op, ast.Sub):
                return tidy(left - right)
            if isinstance(node.op, ast.Mult):
                return tidy(left * right)
            if isinstance(node.op, ast.Div):
                if (right.magnitude if is_quantity(right) else right) == 0:
                    if scope.static:
                        return ureg.Quantity(1.0, (left / ureg.Quantity(1.0, units_of(right))).units)
                    fail("divides by zero")
                return tidy(left / right)
            return tidy(power(node, left, right))
        except InputError:
            raise
        except pint.errors.DimensionalityError as exc:
            fail(f"{_kinds_text(exc)}: the terms of + and - must be of one kind")
        except pint.errors.OffsetUnitCalculusError:
            fail("does arithmetic on a unit with an offset (degC, degF): write the temperature in K or degR")
        except (OverflowError, ZeroDivisionError, ValueError, ArithmeticError):
            fail("is not a finite number")

    def power(node, base, exponent):
        if is_quantity(exponent):
            if not exponent.dimensionless:
                fail("has a unit in an exponent")
            exponent = float(exponent.to("dimensionless").magnitude)
        has_unit = is_quantity(base) and not base.dimensionless
        if scope.static and has_unit and _reads_names(node.right, scope):
            fail("raises a quantity with a unit to a power that is not a plain number")
        if abs(exponent) > units.MAX_EXPONENT:
            fail(f"has an exponent of {exponent:.3g}; at most {units.MAX_EXPONENT} in size")
        b = base.magnitude if is_quantity(base) else base
        if scope.static:
            b = abs(b) or 1.0
            base = ureg.Quantity(b, base.units) if is_quantity(base) else b
        if b < 0 and exponent != int(exponent):
            fail("takes a fractional power of a negative number")
        if b == 0 and exponent < 0:
            fail("divides by zero")
        return base**exponent

    def name(n: str):
        if n in scope.variables:
            value = scope.variables[n]
            if isinstance(value, Missing):  # it reads a card that could not be solved
                raise NotSolved(value.why)
            return value
        if n in ("true", "false"):  # for yes/no outputs: clear.axle_clears == true
            return n == "true"
        wb = scope.workbook
        if wb is not None and n in wb.cards:
            outs = ", ".join(o.name for o in calculator_of(wb, n).outputs)
            fail(f"{n} is a card: name one of its outputs, {n}.OUTPUT ({outs})")
        try:
            return ureg.Quantity(1.0, ureg.get_name(n))
        except Exception:  # pint raises several types for a name it does not know
            pass
        known = sorted(scope.variables) + (sorted(wb.cards) if wb else [])
        fail(f"{shown(n)} is not a variable, card or unit (known: {', '.join(known) or 'none'})")

    def output(card: str, path: list[str]):
        wb = scope.workbook
        if card == "match" and wb is not None and wb.match is not None:  # the [match] table's outputs
            return _match_output(scope, path, fail)
        if wb is None or card not in wb.cards:
            known = ", ".join(sorted(wb.cards)) if wb else "none"
            fail(f"{shown(card)} is not a card (cards: {known or 'none'})")
        calc = calculator_of(wb, card)
        is_input = False
        if len(path) == 1:
            try:
                kind = calc.output(path[0]).quantity
            except KeyError:
                try:  # an input of the card (e.g. the shooter's launch angle), after its outputs
                    f = calc.field(path[0])
                except KeyError:
                    fail(
                        f"{shown(path[0])} is not an output or input of {card} ({calc.id}; outputs: "
                        f"{', '.join(o.name for o in calc.outputs)})"
                    )
                kind = f.quantity if f.kind.with_unit else "dimensionless"
                is_input = True
        else:
            table = next((t for t in calc.tables if t.name == path[0]), None)
            if table is None:
                fail(f"{card} ({calc.id}) has no table {shown(path[0])}")
            try:
                kind = table.column(path[1]).quantity
            except KeyError:
                fail(f"{shown(path[1])} is not a column of {card}.{path[0]}")
        if scope.static:  # a dimensionless output may also be text: check_kinds lets it pass as either
            return ureg.Quantity(1.0, units.SI_UNITS[kind] or "dimensionless")
        if card in scope.failed:
            raise NotSolved(f"{card} could not be solved ({scope.failed[card]})")
        solution = scope.cards[card]
        if len(path) == 1:
            given = solution.inputs if is_input else solution.outputs
            if path[0] not in given:
                raise NotSolved(f"{card}.{path[0]} is not given with these inputs (another mode's output?)")
            value = given[path[0]].value
            if isinstance(value, frozenset):  # a set of flags
                value = sorted(value)
        else:
            rows = solution.tables.get(path[0], [])
            row = next((r for r in rows if path[1] in r), None)
            if row is None:
                raise NotSolved(f"no row of {card}.{path[0]} has {path[1]}")
            value = row[path[1]].value
        if kind != "dimensionless" and isinstance(value, (int, float)) and not isinstance(value, bool):
            return ureg.Quantity(float(value), units.SI_UNITS[kind])
        return value

    return walk(expr.tree)


def _match_output(scope: Scope, path: list[str], fail) -> Any:
    """`match.NAME`: an output of the workbook's [match] (core/workbook/match.py), run after the cards."""
    from .book import MATCH_OUTPUTS, match_output

    ureg = units.registry()
    moved = {ev.card for ev in scope.workbook.match.events}
    info = match_output(path[0], moved) if len(path) == 1 else None
    if info is None:
        more = ", CARD_breaker_load, _margin, _trip" if moved else ""
        fail(
            f"{shown('.'.join(path))} is not an output of the match (outputs: {', '.join(MATCH_OUTPUTS)}{more})"
        )
    name = path[0]
    unit = info[1]
    unit = "percent" if unit == "%" else unit
    if scope.static:
        return ureg.Quantity(1.0, unit) if unit else 1.0
    if "match" in scope.failed:
        raise NotSolved(f"the match could not be run ({scope.failed['match']})")
    given = scope.cards["match"].outputs
    if name not in given:
        if name.endswith("_trip"):
            why = "no trip"
        elif name == "main_breaker_margin":
            why = "no trip table (match.main_breaker)"
        else:
            why = "no trip table (match.channel_breaker)"
        raise NotSolved(f"match.{name} is not given: {why}")
    value = float(given[name])
    return ureg.Quantity(value, unit) if unit else value


def _reads_names(node: ast.AST, scope: Scope) -> bool:
    """Whether a subtree reads a variable or card (its value is unknown before solving)."""
    for sub in ast.walk(node):
        if isinstance(sub, ast.Name) and (
            sub.id in scope.variables or (scope.workbook and sub.id in scope.workbook.cards)
        ):
            return True
    return False


def _kinds_text(exc: Exception) -> str:
    dims = [str(getattr(exc, "dim1", "")), str(getattr(exc, "dim2", ""))]
    words = [d.strip("[]") or "a plain number" for d in dims]
    return f"adds or compares {words[0]} and {words[1]}"


def calculator_of(wb: Workbook, card: str):
    from ..registry import get

    return get(wb.cards[card].calculator)


def literal_value(v: Variable) -> Any:
    if v.text or not isinstance(v.nominal, str):
        return v.nominal
    return evaluate(
        parse_expression(v.nominal, v.name, "<variable>"), Scope({}, {}, {}), v.name, "<variable>"
    )
