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
"""

from __future__ import annotations

import ast
import graphlib
import io
import keyword
import math
import re
import tokenize
from collections.abc import Mapping
from dataclasses import dataclass
from dataclasses import field as dc_field
from pathlib import Path
from typing import Any

from . import units
from .errors import InputError, shown

FORMAT = 1
MAX_EXPRESSION_CHARS = 300  # a reference or check is one line of arithmetic
MAX_NESTING = 40  # parentheses deep; Python's parser would recurse further
MAX_CARDS = 100
MAX_VARIABLES = 500
MAX_REQUIREMENTS = 500
EQUAL_WITHIN = 1e-9  # == and != on measured quantities: equal within this relative difference
BUILTIN_PREFIX = "builtin:"
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_KEYWORD_PREFIX = "_kw_"  # a unit that is a Python keyword ('in') is renamed while parsing
_KEYWORD_UNITS = {"in"}  # the others ('if', 'not', 'lambda') keep their meaning and are refused
_COMPARISONS = {ast.Lt: "<", ast.LtE: "<=", ast.Gt: ">", ast.GtE: ">=", ast.Eq: "==", ast.NotEq: "!="}
_TYPESET = str.maketrans({"\u2212": "-", "·": "*", "⋅": "*", "×": "*", "÷": "/", "^": "**"})


# ---------------------------------------------------------------------------------------------
# Expressions: parsed with ast, checked node by node


@dataclass(frozen=True)
class Expr:
    text: str  # as written, without the leading '='
    tree: ast.expr
    names: frozenset[str]  # every root name (variable, card or unit)

    def references(self, known: set[str]) -> set[str]:
        """The variables and cards this expression reads."""
        return {n for n in self.names if n in known}


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
# The workbook as read


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


def load(path: str | Path, sets: Mapping[str, Any] | None = None) -> Workbook:
    """Read, check and order a workbook file; any problem is an InputError naming the file.
    `sets`: variables' entries that replace the file's (the command line's --set NAME=VALUE)."""
    from . import builtin, presets

    src = str(path)  # messages name the workbook as given ("builtin:robot_2027")
    if builtin.is_builtin(path):  # an example workbook, wherever pip put it
        path = builtin.workbook_path(src)
    try:
        text = presets.read_text(path)
    except InputError as exc:
        raise InputError("workbook", exc.message, src) from None
    return from_dict(presets.parse_text(text, src), src, Path(path).parent, sets)


def from_text(text: str, source: str = "<workbook>", folder: Path | None = None) -> Workbook:
    from . import presets

    return from_dict(presets.parse_text(text, source), source, folder or Path.cwd())


def from_dict(
    data: Mapping[str, Any], src: str, folder: Path, sets: Mapping[str, Any] | None = None
) -> Workbook:
    fmt = data.get("format", FORMAT)
    if not isinstance(fmt, int) or isinstance(fmt, bool) or fmt < 1:
        raise InputError("format", f"must be a whole number from 1 (this Gearhead writes {FORMAT})", src)
    if fmt > FORMAT:
        raise InputError(
            "format", f"version {fmt} is newer than this Gearhead reads ({FORMAT}); upgrade Gearhead", src
        )
    for key in data:
        if key not in ("format", "name", "description", "variables", "cards", "requirements"):
            hint = " (a preset? use `gearhead solve CALC --preset FILE`)" if key == "calculator" else ""
            raise InputError(key, f"unknown top-level key of a workbook{hint}", src)
    name = data.get("name", Path(src).stem)
    description = data.get("description", "")
    for key, value in (("name", name), ("description", description)):
        if not isinstance(value, str):
            raise InputError(key, "must be a string", src)
    raw_vars = dict(_table(data, "variables", src))
    for key, value in (sets or {}).items():
        if key not in raw_vars:
            raise InputError(
                key, f"--set names no variable (variables: {', '.join(raw_vars) or 'none'})", src
            )
        raw_vars[key] = value
    raw_cards = _table(data, "cards", src)
    raw_reqs = data.get("requirements", [])
    if not isinstance(raw_reqs, list) or not all(isinstance(r, dict) for r in raw_reqs):
        raise InputError("requirements", "must be [[requirements]] tables", src)
    if len(raw_vars) > MAX_VARIABLES or len(raw_cards) > MAX_CARDS or len(raw_reqs) > MAX_REQUIREMENTS:
        raise InputError(
            "workbook",
            f"at most {MAX_VARIABLES} variables, {MAX_CARDS} cards, {MAX_REQUIREMENTS} requirements",
            src,
        )
    for kind, table in (("variables", raw_vars), ("cards", raw_cards)):
        for key in table:
            _check_name(key, f"{kind}.{key}", src)
    both = sorted(set(raw_vars) & set(raw_cards))
    if both:
        raise InputError(f"cards.{both[0]}", "a variable has the same name; rename one of them", src)
    variables = {k: _variable(k, v, src) for k, v in raw_vars.items()}
    cards = {k: _card(k, v, src, folder) for k, v in raw_cards.items()}
    requirements = [_requirement(i, r, src) for i, r in enumerate(raw_reqs, 1)]
    keys = [r.key for r in requirements]
    for r in requirements:
        if keys.count(r.key) > 1:
            r.key = f"check_{r.index}"
    import copy

    wb = Workbook(
        src, name, description, variables, cards, requirements, [], copy.deepcopy(dict(data)), folder
    )
    wb.data["variables"] = dict(raw_vars)
    wb.order = _order(wb)
    _check_kinds(wb)
    return wb


def edited(
    wb: Workbook,
    variables: Mapping[str, Any] | None = None,
    inputs: Mapping[str, Mapping[str, Any]] | None = None,
) -> Workbook:
    """The workbook with variables' entries and cards' own inputs replaced (the app's edits),
    checked as a file is; a card's linked fields keep their references. Cards whose entries did
    not change are not solved again (the solve cache is shared)."""
    import copy

    data = copy.deepcopy(wb.data)
    known = data.setdefault("variables", {})
    for name, value in (variables or {}).items():
        if name in known:
            known[name] = value
    for name, values in (inputs or {}).items():
        card = data.get("cards", {}).get(name)
        if not isinstance(card, dict):
            continue
        own = dict(card.get("inputs", {}))
        for key, value in values.items():
            if not (isinstance(own.get(key), str) and own[key].lstrip().startswith("=")):
                own[key] = value
        card["inputs"] = own
    new = from_dict(data, wb.source, wb.folder or Path.cwd())
    new._cache = wb._cache
    return new


def save(
    path: str | Path,
    variables: Mapping[str, Any] | None = None,
    inputs: Mapping[str, Mapping[str, Any]] | None = None,
) -> None:
    """Write the app's edits into the workbook file: each variable's entry and each card's own
    input given here, the rest of the file (comments, order, layout) as it was (tomlkit). A card
    read from a preset gets an inputs table for what was changed on it. The file is replaced
    whole (core.atomic_file: written beside it, then renamed; its mode kept; a symlink written
    through to its target), never left half written; a failure raises atomic_file.WriteError."""
    import tomlkit

    from . import atomic_file

    path = Path(path)
    doc = tomlkit.parse(path.read_text(encoding="utf-8"))
    if variables:
        table = doc.setdefault("variables", tomlkit.table())
        for name, value in variables.items():
            table[name] = value
    for card, values in (inputs or {}).items():
        if not values:
            continue
        table = doc["cards"][card]
        if "inputs" not in table:
            table["inputs"] = tomlkit.table()
        for key, value in values.items():
            table["inputs"][key] = value
    atomic_file.write_text(path, tomlkit.dumps(doc), overwrite=True, field="workbook")


def is_workbook_file(path: str | Path) -> bool:
    """Whether a file reads as a workbook (variables, cards or requirements; not a preset)."""
    from . import presets

    try:
        data = presets.parse_text(presets.read_text(path), str(path))
    except InputError:
        return False
    return "calculator" not in data and any(k in data for k in ("variables", "cards", "requirements"))


def _table(data, key: str, src: str) -> dict:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise InputError(key, f"must be a table ([{key}] ...)", src)
    return value


def _check_name(name: str, where: str, src: str) -> None:
    if not _NAME.match(name) or keyword.iskeyword(name):
        raise InputError(
            where, "a name is letters, digits and _ (not starting with a digit, not a Python word)", src
        )
    if len(name) <= 3 and _is_unit(name):  # 's', 'g', 'in', 'psi' would hide the unit in every check
        raise InputError(where, f"{name!r} is a unit; choose a longer name", src)


def _is_unit(name: str) -> bool:
    try:
        units.registry().get_name(name)
        return True
    except Exception:  # pint raises several types for a name it does not know
        return False


def _variable(name: str, value: Any, src: str) -> Variable:
    where = f"variables.{name}"
    if isinstance(value, bool):
        return Variable(name, value, value, None, None, text=True)
    if isinstance(value, (int, float)):
        try:
            finite = math.isfinite(value)
        except OverflowError:  # an int past float's range (a 400-digit TOML integer)
            raise InputError(
                where, f"{shown(value)} is too large for a number (at most about 1.8e308)", src
            ) from None
        if not finite:
            raise InputError(where, f"{shown(value)} is not a finite number", src)
        return Variable(name, value, value, None, None)
    if not isinstance(value, str):
        raise InputError(where, f"must be a string, number or boolean, got {type(value).__name__}", src)
    if value.lstrip().startswith("="):
        return Variable(name, value, value, None, parse_expression(value.lstrip()[1:], where, src))
    from . import tolerance

    try:
        nominal, tol = tolerance.split(value, where)
    except InputError as exc:
        raise exc.from_source(src) from None
    try:
        q = evaluate(parse_expression(nominal, where, src), Scope({}, {}, {}), where, src)
    except OffsetUnitError:
        raise  # a quantity pint would misread, not a word
    except InputError:
        if tol is None:  # a word ('Kraken X60', '775pro', a material): a field that takes it reads it
            return Variable(name, value, value, None, None, text=True)
        raise
    if isinstance(q, str):
        return Variable(name, value, value, None, None, text=True)
    unit, kind = _unit_of(nominal, q)
    return Variable(name, value, nominal, tol, None, unit, kind)


OFFSET_UNITS = ("degree_Celsius", "degree_Fahrenheit", "degree_Reaumur")


class OffsetUnitError(InputError):
    """A unit with an offset used where pint would read it as an absolute temperature."""


def _has_offset(x: Any) -> bool:
    """Whether a quantity's units hold a unit with an offset (degC, degF)."""
    return _is_quantity(x) and any(name in OFFSET_UNITS for name, _ in x.unit_items())


def _unit_of(written: str, q: Any) -> tuple[str, str]:
    """(display unit, quantity kind) of a quantity as written: '60 kg' -> ('kg', 'mass')."""
    if not _is_quantity(q):
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


def _card(name: str, data: Any, src: str, folder: Path) -> Card:
    from . import presets
    from .registry import calculators, get

    where = f"cards.{name}"
    if not isinstance(data, dict):
        raise InputError(where, "must be a table ([cards.NAME] with calculator and inputs, or preset)", src)
    for key in data:
        if key not in ("calculator", "preset", "inputs"):
            raise InputError(f"{where}.{key}", "unknown key of a card (calculator, preset, inputs)", src)
    inputs: dict[str, Any] = {}
    calc_id = data.get("calculator")
    preset_path = data.get("preset")
    warnings: list[str] = []
    if preset_path is not None:
        if not isinstance(preset_path, str) or not preset_path.strip():
            raise InputError(f"{where}.preset", "must be a file path", src)
        path = _preset_path(preset_path, folder)
        try:
            preset = presets.load(path)
        except InputError as exc:
            raise InputError(f"{where}.preset", str(exc), src) from None
        if calc_id is not None and calc_id != preset.calculator:
            raise InputError(
                f"{where}.calculator", f"{shown(calc_id)}, but the preset is for {preset.calculator}", src
            )
        calc_id = preset.calculator
        inputs.update(preset.inputs)
        warnings.extend(preset.warnings)
    if not isinstance(calc_id, str):
        raise InputError(f"{where}.calculator", "missing (give a calculator id or a preset)", src)
    if calc_id not in calculators():
        raise InputError(f"{where}.calculator", f"unknown calculator {shown(calc_id)}", src)
    calc = get(calc_id)
    own = data.get("inputs", {})
    if not isinstance(own, dict):
        raise InputError(f"{where}.inputs", "must be a table", src)
    links: dict[str, Expr] = {}
    for key, value in own.items():
        field_where = f"{where}.{key}"
        try:
            calc.field(key)
        except KeyError:
            known = ", ".join(f.name for f in calc.fields)
            raise InputError(field_where, f"is not an input of {calc_id} (inputs: {known})", src) from None
        if isinstance(value, str) and value.lstrip().startswith("="):
            links[key] = parse_expression(value.lstrip()[1:], field_where, src)
            inputs.pop(key, None)
        elif isinstance(value, (str, int, float, bool)) or (
            isinstance(value, list) and all(isinstance(x, str) for x in value)
        ):
            inputs[key] = value
        else:
            raise InputError(
                field_where, f"wrong type ({type(value).__name__}); use a string, number or boolean", src
            )
    from . import tolerance
    from .model import parse_inputs

    try:
        nominal, tols = tolerance.split_inputs(calc, inputs)
        parse_inputs(calc, nominal)  # every literal entry, checked now (a link is checked when solved)
    except InputError as exc:
        raise_in(exc, where, src)
    for field_name in tols:
        warnings.append(
            f"{where}.{field_name}: the tolerance is not analysed on a card (solved at the nominal); "
            f"put the value in [variables] and link it to have it analysed"
        )
    return Card(name, calc_id, nominal, links, preset_path, warnings)


def raise_in(exc: InputError, where: str, src: str):
    """An error from a card's calculator, each field named inside the card and the file."""
    from .errors import raise_all

    raise_all([InputError(f"{where}.{e.field}", e.message, src) for e in exc.errors])
    raise exc  # unreachable: raise_all raised


def _preset_path(text: str, folder: Path) -> Path:
    from . import builtin

    if text.startswith(BUILTIN_PREFIX):  # builtin:CALC/NAME, or builtin:NAME when only one has it
        try:
            return builtin.preset_path(text)
        except InputError:
            pass  # the card's preset is then reported missing, with the file and card, as before
    path = Path(text).expanduser()
    return path if path.is_absolute() else folder / path


def _requirement(index: int, data: dict, src: str) -> Requirement:
    where = f"requirements[{index}]"
    for key in data:
        if key not in ("name", "check", "note"):
            raise InputError(f"{where}.{key}", "unknown key of a requirement (name, check, note)", src)
    name, note, check = data.get("name", ""), data.get("note", ""), data.get("check")
    for key, value in (("name", name), ("note", note)):
        if not isinstance(value, str):
            raise InputError(f"{where}.{key}", "must be a string", src)
    if check is None:
        raise InputError(f"{where}.check", 'missing (e.g. check = "lift.time_to_goal < 1 s")', src)
    operands, ops = parse_expression(check, f"{where}.check", src, compare=True)
    slug = re.sub(r"\W+", "_", name.lower()).strip("_")[:40]
    key = slug if slug and not slug[0].isdigit() else f"check_{index}"
    return Requirement(index, name, check.strip(), note, operands, ops, key)


def _order(wb: Workbook) -> list[str]:
    """Variables and cards, each after every one it reads (graphlib); a cycle is an InputError."""
    known = set(wb.variables) | set(wb.cards)
    graph: dict[str, set[str]] = {}
    for v in wb.variables.values():
        graph[v.name] = v.expr.references(known) if v.expr else set()
    for c in wb.cards.values():
        graph[c.name] = set().union(*(e.references(known) for e in c.links.values()))
    sorter = graphlib.TopologicalSorter(graph)
    position = {name: i for i, name in enumerate(graph)}
    try:
        sorter.prepare()
    except graphlib.CycleError as exc:
        cycle = exc.args[1]  # [a, b, ..., a]
        first = cycle[0]
        where = _where_reads(wb, first, cycle[1])
        raise InputError(where, f"a cycle of references: {' → '.join(reversed(cycle))}", wb.source) from None
    order: list[str] = []
    ready: set[str] = set()
    while sorter.is_active():  # of the ready ones, the first in the file: cards print in file order
        ready.update(sorter.get_ready())
        node = min(ready, key=position.__getitem__)
        ready.remove(node)
        order.append(node)
        sorter.done(node)
    return order


def _where_reads(wb: Workbook, node: str, target: str) -> str:
    """The field of `node` (a card or variable) that reads `target`."""
    if node in wb.variables:
        return f"variables.{node}"
    for field_name, expr in wb.cards[node].links.items():
        if target in expr.names:
            return f"cards.{node}.{field_name}"
    return f"cards.{node}"


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


def _is_quantity(x: Any) -> bool:
    return hasattr(x, "magnitude") and hasattr(x, "units")


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
        if scope.static and _is_quantity(x):
            return ureg.Quantity(1.0, x.units)  # only the dimension is known
        m = x.magnitude if _is_quantity(x) else x
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
        if (
            isinstance(node.op, ast.Pow)
            and right is UNKNOWN
            and _is_quantity(left)
            and not left.dimensionless
        ):
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
                if (right.magnitude if _is_quantity(right) else right) == 0:
                    if scope.static:
                        return ureg.Quantity(1.0, (left / ureg.Quantity(1.0, _units(right))).units)
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
        if _is_quantity(exponent):
            if not exponent.dimensionless:
                fail("has a unit in an exponent")
            exponent = float(exponent.to("dimensionless").magnitude)
        has_unit = _is_quantity(base) and not base.dimensionless
        if scope.static and has_unit and _reads_names(node.right, scope):
            fail("raises a quantity with a unit to a power that is not a plain number")
        if abs(exponent) > units.MAX_EXPONENT:
            fail(f"has an exponent of {exponent:.3g}; at most {units.MAX_EXPONENT} in size")
        b = base.magnitude if _is_quantity(base) else base
        if scope.static:
            b = abs(b) or 1.0
            base = ureg.Quantity(b, base.units) if _is_quantity(base) else b
        if b < 0 and exponent != int(exponent):
            fail("takes a fractional power of a negative number")
        if b == 0 and exponent < 0:
            fail("divides by zero")
        return base**exponent

    def name(n: str):
        if n in scope.variables:
            value = scope.variables[n]
            if isinstance(value, _Missing):  # it reads a card that could not be solved
                raise NotSolved(value.why)
            return value
        if n in ("true", "false"):  # for yes/no outputs: clear.axle_clears == true
            return n == "true"
        wb = scope.workbook
        if wb is not None and n in wb.cards:
            outs = ", ".join(o.name for o in _calc(wb, n).outputs)
            fail(f"{n} is a card: name one of its outputs, {n}.OUTPUT ({outs})")
        try:
            return ureg.Quantity(1.0, ureg.get_name(n))
        except Exception:  # pint raises several types for a name it does not know
            pass
        known = sorted(scope.variables) + (sorted(wb.cards) if wb else [])
        fail(f"{shown(n)} is not a variable, card or unit (known: {', '.join(known) or 'none'})")

    def output(card: str, path: list[str]):
        wb = scope.workbook
        if wb is None or card not in wb.cards:
            known = ", ".join(sorted(wb.cards)) if wb else "none"
            fail(f"{shown(card)} is not a card (cards: {known or 'none'})")
        calc = _calc(wb, card)
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
        if scope.static:  # a dimensionless output may also be text: _check_kinds lets it pass as either
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


def _units(q: Any):
    return q.units if _is_quantity(q) else units.registry().dimensionless


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


def _calc(wb: Workbook, card: str):
    from .registry import get

    return get(wb.cards[card].calculator)


# ---------------------------------------------------------------------------------------------
# Into a card's field


def entry_for(f, value: Any, where: str, src: str, static: bool = False) -> Any:
    """A referenced value as an entry of field `f` (what a user would type): a quantity in the
    field's display unit, a whole number, or a word. InputError when the kind does not fit.
    `static`: the kinds check, where a plain number may stand for a card's text output."""
    if value is UNKNOWN:
        return value
    if static and not f.kind.numeric and _is_quantity(value) and value.dimensionless:
        return value
    if f.kind.with_unit:
        if isinstance(value, (str, bool)):
            raise InputError(where, f"takes {_kind_words(f.quantity)}, got {shown(value)}", src)
        si_unit = units.SI_UNITS[f.quantity] or "dimensionless"
        if _is_quantity(value):
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
        if _is_quantity(value):
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


def _check_kinds(wb: Workbook) -> None:
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
                scope.variables[node] = _literal_value(v)
            continue
        card = wb.cards[node]
        calc = _calc(wb, node)
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
            _compare_kinds(sides, r, where, wb.source, static=True)
        except InputError as exc:
            raise InputError(where, exc.message + _read_as_units(wb, r.operands), wb.source) from None


def _read_as_units(wb: Workbook, exprs: list[Expr]) -> str:
    """'; read as units: mas' when a name that is no variable or card was taken for a unit (a typo
    of a variable's name may be one of pint's many units), else ''."""
    known = set(wb.variables) | set(wb.cards)
    guessed = sorted({n for e in exprs for n in e.names if n not in known and len(n) > 1})
    return f" (read as units: {', '.join(guessed)})" if guessed else ""


def _literal_value(v: Variable) -> Any:
    if v.text or not isinstance(v.nominal, str):
        return v.nominal
    return evaluate(
        parse_expression(v.nominal, v.name, "<variable>"), Scope({}, {}, {}), v.name, "<variable>"
    )


def _compare_kinds(sides: list, r: Requirement, where: str, src: str, static: bool = False) -> None:
    import pint

    for (a, b), op in zip(zip(sides, sides[1:]), r.ops):
        if a is UNKNOWN or b is UNKNOWN:
            continue
        texts = isinstance(a, (str, bool)) or isinstance(b, (str, bool))
        if texts and static and any(_is_quantity(x) and x.dimensionless for x in (a, b)):
            continue  # a card's dimensionless output may be text
        if texts:
            if op not in ("==", "!=") or type(a) is not type(b):
                raise InputError(
                    where,
                    f"{shown(r.check)}: text and yes/no compare only with == and != to their own kind",
                    src,
                )
            continue
        qa = a if _is_quantity(a) else units.registry().Quantity(float(a), "dimensionless")
        try:
            qa.to(_units(b))
        except pint.errors.DimensionalityError:
            raise InputError(
                where,
                f"{shown(r.check)}: compares {_dimension_words(qa)} with {_dimension_words(_as_q(b))}",
                src,
            ) from None


def _as_q(x: Any):
    return x if _is_quantity(x) else units.registry().Quantity(float(x), "dimensionless")


# ---------------------------------------------------------------------------------------------
# Solving


@dataclass
class CardResult:
    name: str
    calculator: str
    solution: Any | None  # core.model.Solution
    error: str | None
    links: dict[str, str]  # field -> '= reference' as written
    entries: dict[str, Any]  # what was solved (links resolved)


@dataclass
class CheckResult:
    requirement: Requirement
    holds: bool | None  # None: it could not be evaluated (a card it reads has no solution)
    sides: list[str]  # each operand as text, in the comparison's unit
    unit: str
    margin: float | None  # in `unit`; positive: holds by so much
    margin_si: float | None
    kind: str  # of the margin (core.units.SI_UNITS key)
    error: str | None = None

    @property
    def ok(self) -> bool:
        return bool(self.holds)

    def text(self) -> str:
        if self.error:
            return self.error
        shown_sides = [self.sides[0]]
        for op, side in zip(self.requirement.ops, self.sides[1:]):
            shown_sides += [op, side]
        out = " ".join(shown_sides)
        if self.margin is not None:
            out += f"  (margin {units.format_number(self.margin)}{(' ' + self.unit) if self.unit else ''})"
        return out

    def as_json(self) -> dict[str, Any]:
        r = self.requirement
        return {
            "name": r.name,
            "check": r.check,
            "note": r.note,
            "holds": self.holds,
            "values": self.sides,
            "unit": self.unit,
            "margin": self.margin,
            "margin_si": self.margin_si,
            "si_unit": units.SI_UNITS.get(self.kind, ""),
            "error": self.error,
        }


@dataclass
class Outcome:
    workbook: Workbook
    variables: dict[str, Any]
    cards: dict[str, CardResult]
    checks: list[CheckResult]
    rhs_evaluations: int = 0  # of the simulated cards solved for this outcome

    @property
    def all_hold(self) -> bool:
        return all(c.holds for c in self.checks)

    def as_json(self, with_cards: bool = False) -> dict[str, Any]:
        wb = self.workbook
        out: dict[str, Any] = {
            "workbook": wb.name,
            "file": wb.source,
            "holds": self.all_hold,
            "requirements": [c.as_json() for c in self.checks],
            "card_errors": {n: c.error for n, c in self.cards.items() if c.error},
        }
        if with_cards:
            out["variables"] = {n: _json_value(v) for n, v in self.variables.items()}
            out["cards"] = {
                n: {
                    "calculator": c.calculator,
                    "links": c.links,
                    "error": c.error,
                    **({"solution": c.solution.as_json()} if c.solution else {}),
                }
                for n, c in self.cards.items()
            }
        return out


def _json_value(v: Any) -> dict[str, Any]:
    if _is_quantity(v):
        kind = kind_of(v)
        si = units.SI_UNITS.get(kind, "") if kind else ""
        value = float(v.to(si or "dimensionless").magnitude) if kind else float(v.to_base_units().magnitude)
        return {"value": value, "unit": si}
    return {"value": v, "unit": ""}


def solve(wb: Workbook, overrides: Mapping[str, Any] | None = None) -> Outcome:
    """Every card in dependency order, then every requirement. `overrides`: variables' values in SI
    (a sweep's or a tolerance study's point) in place of what the file says."""
    from .model import solve as solve_card

    overrides = dict(overrides or {})
    scope = Scope({}, {}, {}, workbook=wb)
    results: dict[str, CardResult] = {}
    evaluations = 0  # right-hand-side evaluations of the scenes solved now (not from the cache)
    src = wb.source
    ureg = units.registry()
    for node in wb.order:
        if node in wb.variables:
            v = wb.variables[node]
            if node in overrides:
                x = overrides[node]
                scope.variables[node] = (
                    ureg.Quantity(x, units.SI_UNITS[v.kind]) if v.kind != "dimensionless" else x
                )
            elif v.expr is not None:
                try:
                    scope.variables[node] = evaluate(v.expr, scope, f"variables.{node}", src)
                except NotSolved as exc:
                    scope.variables[node] = _Missing(str(exc))
                except InputError as exc:  # e.g. a division by zero at these values
                    scope.variables[node] = _Missing(f"{node}: {exc.message}")
            else:
                scope.variables[node] = _literal_value(v)
            continue
        card = wb.cards[node]
        calc = _calc(wb, node)
        raw = dict(card.inputs)
        error = None
        for field_name, expr in card.links.items():
            where = f"cards.{node}.{field_name}"
            try:
                raw[field_name] = _link_entry(wb, scope, expr, calc.field(field_name), where, overrides)
            except NotSolved as exc:
                error = f"{field_name}: not solved: {exc}"
                break
            except InputError as exc:  # the reference cannot be worked out at these values
                error = f"{field_name}: {exc.message}"
                break
        links = {k: "= " + e.text for k, e in card.links.items()}
        if error is None:
            key = (node, tuple(sorted((k, repr(v)) for k, v in raw.items())))
            cached = wb._cache.get(key)
            if cached is None:
                try:
                    cached = (solve_card(calc.id, raw), None)
                    work = cached[0].outputs.get("rhs_evaluations")
                    evaluations += int(work.value) if work is not None else 0
                except InputError as exc:
                    cached = (None, f"{exc.field}: {exc.message}")
                if len(wb._cache) > 4096:
                    wb._cache.clear()
                wb._cache[key] = cached
            solution, error = cached
        else:
            solution = None
        if error is not None:
            scope.failed[node] = error
        else:
            scope.cards[node] = solution
        results[node] = CardResult(node, calc.id, solution, error, links, raw)
    checks = [_check(wb, scope, r) for r in wb.requirements]
    variables = {k: v for k, v in scope.variables.items() if not isinstance(v, _Missing)}
    return Outcome(wb, variables, results, checks, evaluations)


class _Missing:
    """A variable whose reference reads a card with no solution: reading it says why."""

    def __init__(self, why: str):
        self.why = why


def _link_entry(wb: Workbook, scope: Scope, expr: Expr, f, where: str, overrides) -> Any:
    tree = expr.tree
    if isinstance(tree, ast.Name) and tree.id in wb.variables and tree.id not in overrides:
        v = wb.variables[tree.id]
        if v.expr is None:
            return v.nominal  # as written: the field reads it, shows it and names it itself
    for n in expr.names:
        value = scope.variables.get(n)
        if isinstance(value, _Missing):
            raise NotSolved(value.why)
    return entry_for(f, evaluate(expr, scope, where, wb.source), where, wb.source)


def _check(wb: Workbook, scope: Scope, r: Requirement) -> CheckResult:
    where = f"requirements[{r.index}].check"
    for n in set().union(*(e.names for e in r.operands)):
        value = scope.variables.get(n)
        if isinstance(value, _Missing):
            return CheckResult(r, None, [], "", None, None, "", f"not evaluated: {value.why}")
    try:
        sides = [evaluate(e, scope, where, wb.source) for e in r.operands]
        _compare_kinds(sides, r, where, wb.source)  # text against a number shows only now
    except NotSolved as exc:
        return CheckResult(r, None, [], "", None, None, "", f"not evaluated: {exc}")
    except InputError as exc:  # e.g. a division by zero at these values
        return CheckResult(r, None, [], "", None, None, "", f"not evaluated: {exc.message}")
    if any(isinstance(s, (str, bool)) for s in sides):
        holds = all((a == b) if op == "==" else (a != b) for (a, b), op in zip(zip(sides, sides[1:]), r.ops))
        return CheckResult(r, holds, [str(s) for s in sides], "", None, None, "")
    unit = _display_unit(wb, r)
    qs = [_as_q(s) for s in sides]
    kind = kind_of(qs[0])
    # a kind Gearhead has no name for (kg/s): the margin in SI base units, shown as a number
    si_unit = (units.SI_UNITS[kind] or "dimensionless") if kind else qs[0].to_base_units().units
    target = unit or si_unit
    mags = [float(q.to(target).magnitude) for q in qs]
    si_mags = [float(q.to(si_unit).magnitude) for q in qs]
    kind = kind or "dimensionless"
    if not kind_of(qs[0]):
        unit = ""
        mags = si_mags
    margins, si_margins, holds = [], [], True
    for (a, b), (sa, sb), op in zip(zip(mags, mags[1:]), zip(si_mags, si_mags[1:]), r.ops):
        ok, m = _holds(a, b, op)
        _, sm = _holds(sa, sb, op)
        holds = holds and ok
        margins.append(m)
        si_margins.append(sm)
    if not all(math.isfinite(x) for x in margins + si_margins):  # 1e300 m > -1e300 m
        return CheckResult(
            r, None, [], "", None, None, "", "not evaluated: the values are too large to compare"
        )
    sides_text = [f"{units.format_number(m)} {unit}".rstrip() for m in mags]
    return CheckResult(r, holds, sides_text, unit, min(margins), min(si_margins), kind)


def _holds(a: float, b: float, op: str) -> tuple[bool, float]:
    """Whether `a op b`, and by how much (negative: fails by so much)."""
    if op in ("<", "<="):
        return (a < b if op == "<" else a <= b), b - a
    if op in (">", ">="):
        return (a > b if op == ">" else a >= b), a - b
    # the margin's sign is the verdict's, as for the inequalities (a worst case is the least margin):
    # equal means within EQUAL_WITHIN, relative
    band = EQUAL_WITHIN * max(abs(a), abs(b))
    close = abs(a - b) <= band
    if op == "==":
        return close, band - abs(a - b)
    return not close, abs(a - b) - band


def _display_unit(wb: Workbook, r: Requirement) -> str:
    """The comparison's unit: that of a side written as a plain quantity ('1 s'), else of the first
    side's first variable or output."""
    names = set(wb.variables) | set(wb.cards)
    for e in r.operands:
        if not (e.names & names):
            q = evaluate(e, Scope({}, {}, {}), "check", wb.source)
            if _is_quantity(q) and not q.unitless:
                return f"{q.units:~}".replace(" ", "")
            if _is_quantity(q) and "percent" in str(q.units):
                return "%"
    for e in r.operands:
        for node in ast.walk(e.tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
                if node.value.id in wb.cards:
                    try:
                        return _calc(wb, node.value.id).output(node.attr).unit
                    except KeyError:
                        pass
            if isinstance(node, ast.Name) and node.id in wb.variables:
                return wb.variables[node.id].unit
    return ""


# ---------------------------------------------------------------------------------------------
# The workbook as one calculator: variables in, requirement margins out (sweeps and tolerances)


def studied(v: Variable) -> bool:
    """Whether a sweep or worst case can vary `v`: its unit is one of a kind Gearhead's fields
    take (a temperature in degC or K, an amount in mol are compared, not varied)."""
    return v.kind in units.SI_UNITS


def as_calculator(wb: Workbook):
    """A Calculator whose fields are the workbook's plain variables (numbers and quantities) and
    whose outputs are the requirements' margins (SI), so core.sweep and core.tolerance study a
    whole robot as they study one calculator."""
    from .declarations import Calculator, Output, Result
    from .fields import Field

    fields = []
    for v in wb.variables.values():
        if v.expr is not None or v.text or not studied(v):
            continue
        if isinstance(v.nominal, int) and not isinstance(v.nominal, bool):
            fields.append(Field(v.name, v.name, default=v.nominal, integer=True))
        else:
            fields.append(Field(v.name, v.name, v.kind, v.unit, default=v.nominal))
    outputs = []
    for r in wb.requirements:
        unit = _display_unit(wb, r)
        try:
            kind = kind_of(_as_q(units.registry().Quantity(1.0, unit or "dimensionless"))) or "dimensionless"
        except Exception:  # a unit pint cannot read back: the margin in SI
            kind, unit = "dimensionless", ""
        if kind == "dimensionless" and unit not in ("", "%"):
            unit = unit if _factor_ok(unit) else ""
        outputs.append(
            Output(r.key, r.name or r.check, kind, unit if unit else units.SI_UNITS[kind], help=r.check)
        )
    # a study's cost line counts the scenes' work (core.sweep.STATS: never a column)
    outputs.append(Output("rhs_evaluations", "Solver work (evaluations)"))

    def compute(values: Mapping[str, Any]) -> Result:
        overrides = {f.name: values[f.name] for f in fields if f.name in values}
        outcome = solve(wb, overrides)
        out: dict[str, Any] = {"rhs_evaluations": outcome.rhs_evaluations}
        for c in outcome.checks:
            if c.margin_si is not None:
                out[c.requirement.key] = c.margin_si
            elif c.error:
                # a robot that cannot be solved here is no robot that meets its requirements: the
                # point fails (a tolerance corner is counted infeasible, never left out of the worst case)
                raise InputError(c.requirement.key, c.error)
        return Result(out)

    return Calculator("workbook", wb.name, wb.description, tuple(fields), tuple(outputs), compute)


def _factor_ok(unit: str) -> bool:
    try:
        units.factor(unit, "dimensionless")
        return True
    except Exception:  # not a dimensionless unit
        return False
