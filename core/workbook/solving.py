"""Solving: variables and cards in dependency order (graphlib), each card through core.model.solve
(cached by its entries), then every requirement's verdict and margin; and the workbook seen as one
calculator (variables in, margins out) for core.sweep and core.tolerance."""

from __future__ import annotations

import ast
import graphlib
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .. import units
from ..errors import InputError
from .book import Expr, Requirement, Variable, Workbook
from .expressions import (
    Missing,
    NotSolved,
    Scope,
    as_quantity,
    calculator_of,
    evaluate,
    is_quantity,
    kind_of,
    literal_value,
)
from .kinds import compare_kinds, entry_for

EQUAL_WITHIN = 1e-9  # == and != on measured quantities: equal within this relative difference


# ---------------------------------------------------------------------------------------------
# The order: each variable and card after what it reads


def dependency_order(wb: Workbook) -> list[str]:
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
    match: Any = None  # core.workbook.match.MatchOutcome, when the workbook has a [match] that ran
    match_error: str | None = None  # why the [match] could not be run

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
        if self.match_error is not None:
            out["match_error"] = self.match_error
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
    if is_quantity(v):
        kind = kind_of(v)
        si = units.SI_UNITS.get(kind, "") if kind else ""
        value = float(v.to(si or "dimensionless").magnitude) if kind else float(v.to_base_units().magnitude)
        return {"value": value, "unit": si}
    return {"value": v, "unit": ""}


def solve(wb: Workbook, overrides: Mapping[str, Any] | None = None) -> Outcome:
    """Every card in dependency order, then every requirement. `overrides`: variables' values in SI
    (a sweep's or a tolerance study's point) in place of what the file says."""
    from ..model import solve as solve_card

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
                    scope.variables[node] = Missing(str(exc))
                except InputError as exc:  # e.g. a division by zero at these values
                    scope.variables[node] = Missing(f"{node}: {exc.message}")
            else:
                scope.variables[node] = literal_value(v)
            continue
        card = wb.cards[node]
        calc = calculator_of(wb, node)
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
    match, match_error = _run_match(wb, scope, results) if wb.match is not None else (None, None)
    checks = [_check(wb, scope, r) for r in wb.requirements]
    variables = {k: v for k, v in scope.variables.items() if not isinstance(v, Missing)}
    return Outcome(wb, variables, results, checks, evaluations, match, match_error)


def _run_match(wb: Workbook, scope: Scope, results: dict[str, CardResult]):
    """The [match] at these values (cached by what it reads), into the scope as `match`."""
    from .match import NAME, run

    spec = wb.match
    read = set().union(*(v.names for v in spec.values.values() if hasattr(v, "names")))
    moved = {ev.card for ev in spec.events}
    key = (  # what the match reads: its references' variables and the cards it moves
        NAME,
        tuple(sorted((n, repr(scope.variables.get(n))) for n in read if n in scope.variables)),
        tuple((n, repr(sorted(c.entries.items())), c.error) for n, c in results.items() if n in moved),
        repr(wb.data.get(NAME)),  # the table itself: the app edits its events (timeline.py)
    )
    cached = wb._cache.get(key)
    if cached is None:
        try:
            cached = (run(wb.match, wb, scope, results), None)
        except NotSolved as exc:
            cached = (None, str(exc))
        except InputError as exc:
            cached = (None, f"{exc.field}: {exc.message}")
        wb._cache[key] = cached
    outcome, error = cached
    if error is not None:
        scope.failed[NAME] = error
    else:
        scope.cards[NAME] = outcome
    return outcome, error


def _link_entry(wb: Workbook, scope: Scope, expr: Expr, f, where: str, overrides) -> Any:
    tree = expr.tree
    if isinstance(tree, ast.Name) and tree.id in wb.variables and tree.id not in overrides:
        v = wb.variables[tree.id]
        if v.expr is None:
            return v.nominal  # as written: the field reads it, shows it and names it itself
    for n in expr.names:
        value = scope.variables.get(n)
        if isinstance(value, Missing):
            raise NotSolved(value.why)
    return entry_for(f, evaluate(expr, scope, where, wb.source), where, wb.source)


def _check(wb: Workbook, scope: Scope, r: Requirement) -> CheckResult:
    where = f"requirements[{r.index}].check"
    for n in set().union(*(e.names for e in r.operands)):
        value = scope.variables.get(n)
        if isinstance(value, Missing):
            return CheckResult(r, None, [], "", None, None, "", f"not evaluated: {value.why}")
    try:
        sides = [evaluate(e, scope, where, wb.source) for e in r.operands]
        compare_kinds(sides, r, where, wb.source)  # text against a number shows only now
    except NotSolved as exc:
        return CheckResult(r, None, [], "", None, None, "", f"not evaluated: {exc}")
    except InputError as exc:  # e.g. a division by zero at these values
        return CheckResult(r, None, [], "", None, None, "", f"not evaluated: {exc.message}")
    if any(isinstance(s, (str, bool)) for s in sides):
        holds = all((a == b) if op == "==" else (a != b) for (a, b), op in zip(zip(sides, sides[1:]), r.ops))
        return CheckResult(r, holds, [str(s) for s in sides], "", None, None, "")
    unit = _display_unit(wb, r)
    qs = [as_quantity(s) for s in sides]
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
    names = set(wb.variables) | set(wb.cards) | ({"match"} if wb.match is not None else set())
    for e in r.operands:
        if not (e.names & names):
            q = evaluate(e, Scope({}, {}, {}), "check", wb.source)
            if is_quantity(q) and not q.unitless:
                return f"{q.units:~}".replace(" ", "")
            if is_quantity(q) and "percent" in str(q.units):
                return "%"
    for e in r.operands:
        for node in ast.walk(e.tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
                if node.value.id in wb.cards:
                    try:
                        return calculator_of(wb, node.value.id).output(node.attr).unit
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
    from ..declarations import Calculator, Output, Result
    from ..fields import Field

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
            kind = (
                kind_of(as_quantity(units.registry().Quantity(1.0, unit or "dimensionless")))
                or "dimensionless"
            )
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
