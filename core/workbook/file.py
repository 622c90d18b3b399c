"""The workbook file: reading the TOML (every mistake an InputError naming the file and the field,
a name that would hide a unit refused), the app's edits checked as a file is, and writing them back
with the file's comments and layout kept."""

from __future__ import annotations

import keyword
import math
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .. import units
from ..errors import InputError, shown
from .book import Card, Expr, Requirement, Variable, Workbook
from .expressions import OffsetUnitError, Scope, evaluate, parse_expression, unit_of
from .kinds import check_kinds
from .solving import dependency_order

FORMAT = 1
MAX_CARDS = 100
MAX_VARIABLES = 500
MAX_REQUIREMENTS = 500
BUILTIN_PREFIX = "builtin:"
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def load(path: str | Path, sets: Mapping[str, Any] | None = None) -> Workbook:
    """Read, check and order a workbook file; any problem is an InputError naming the file.
    `sets`: variables' entries that replace the file's (the command line's --set NAME=VALUE)."""
    from .. import builtin, presets

    src = str(path)  # messages name the workbook as given ("builtin:robot_2027")
    if builtin.is_builtin(path):  # an example workbook, wherever pip put it
        path = builtin.workbook_path(src)
    try:
        text = presets.read_text(path)
    except InputError as exc:
        raise InputError("workbook", exc.message, src) from None
    return from_dict(presets.parse_text(text, src), src, Path(path).parent, sets)


def from_text(text: str, source: str = "<workbook>", folder: Path | None = None) -> Workbook:
    from .. import presets

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
        if key not in ("format", "name", "description", "variables", "cards", "requirements", "match"):
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
    wb.order = dependency_order(wb)
    if "match" in data:  # before the kinds check: requirements may read match.OUTPUT
        from .match import parse as parse_match

        wb.match = parse_match(data["match"], wb)
    check_kinds(wb)
    return wb


def edited(
    wb: Workbook,
    variables: Mapping[str, Any] | None = None,
    inputs: Mapping[str, Mapping[str, Any]] | None = None,
    events: list[Mapping[str, Any]] | None = None,
) -> Workbook:
    """The workbook with variables' entries and cards' own inputs replaced (the app's edits),
    checked as a file is; a card's linked fields keep their references. `events`: the match's
    `[[match.events]]` tables in place of the file's (the app's timeline). Cards whose entries did
    not change are not solved again (the solve cache is shared)."""
    import copy

    data = copy.deepcopy(wb.data)
    if events is not None and isinstance(data.get("match"), dict):
        data["match"]["events"] = [dict(e) for e in events]
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
    events: list[tuple[int | None, Mapping[str, Any]]] | None = None,
) -> None:
    """Write the app's edits into the workbook file: each variable's entry and each card's own
    input given here, the rest of the file (comments, order, layout) as it was (tomlkit). A card
    read from a preset gets an inputs table for what was changed on it. `events`: the match's
    timeline, each table with the index (0-based) of the file's `[[match.events]]` table it was
    read from (None: added), in the file's order then the added ones: a kept table is changed in
    place (its comments kept), a table no longer there is removed, an added one appended. The file is replaced
    whole (core.atomic_file: written beside it, then renamed; its mode kept; a symlink written
    through to its target), never left half written; a failure raises atomic_file.WriteError."""
    import tomlkit

    from .. import atomic_file

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
    if events is not None:
        _write_events(doc, events)
    atomic_file.write_text(path, tomlkit.dumps(doc), overwrite=True, field="workbook")


def _write_events(doc, events: list[tuple[int | None, Mapping[str, Any]]]) -> None:
    import tomlkit

    match = doc.setdefault("match", tomlkit.table())
    if "events" not in match:
        match["events"] = tomlkit.aot()
    aot = match["events"]
    kept = [origin for origin, _ in events if origin is not None]
    for i in range(len(aot) - 1, -1, -1):  # from the end: the indices before stay valid
        if i not in kept:
            del aot[i]
    position = {origin: k for k, origin in enumerate(sorted(kept))}
    for origin, values in events:
        if origin is None:
            table = tomlkit.table()
            table.update(dict(values))
            table.trivia.indent = "\n"  # a blank line before its header, as the file's tables have
            table.add(tomlkit.nl())  # and after it, before whatever table follows in the file
            aot.append(table)
            continue
        table = aot[position[origin]]
        for key in [k for k in table if k not in values]:
            del table[key]
        for key, value in values.items():
            if key not in table or table[key] != value:
                table[key] = value


def is_workbook_file(path: str | Path) -> bool:
    """Whether a file reads as a workbook (variables, cards or requirements; not a preset)."""
    from .. import presets

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
    from .. import tolerance

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
    unit, kind = unit_of(nominal, q)
    return Variable(name, value, nominal, tol, None, unit, kind)


def _card(name: str, data: Any, src: str, folder: Path) -> Card:
    from .. import presets
    from ..registry import calculators, get

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
    from .. import tolerance
    from ..model import parse_inputs

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
    from ..errors import raise_all

    raise_all([InputError(f"{where}.{e.field}", e.message, src) for e in exc.errors])
    raise exc  # unreachable: raise_all raised


def _preset_path(text: str, folder: Path) -> Path:
    from .. import builtin

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
