"""The command line of workbooks (core/workbook/): `check`, and `solve`/`sweep` given a .toml file.

    gearhead check ROBOT.toml [--set VAR=VALUE ...] [--worst-case] [--json]
    gearhead solve ROBOT.toml [--set VAR=VALUE ...] [--json]
    gearhead sweep ROBOT.toml --vary VAR=START..STOP[:N][:log] [--output REQUIREMENT ...] [--csv | --json]

`check` exits 0 when every requirement holds, 1 when one does not (or cannot be evaluated: a card it
reads could not be solved), 2 for a bad file (tui/cli.py's handler of InputError).
"""

from __future__ import annotations

import json
import sys

from gearhead.core.errors import InputError, printable, shown

EXIT_FAILS = 1


def _say(line: str = "") -> None:
    """One line of the text output. A workbook's names, notes, text variables and the messages
    quoting them come from the file: any control character in them is shown escaped (an ESC in
    `name` cleared the screen)."""
    print(printable(line, keep_newlines=True))


def is_workbook(argument: str | None) -> bool:
    """Whether `solve`/`sweep`'s first argument names a workbook file rather than a calculator id."""
    # no file-system look-up: a calculator id never ends in .toml nor holds a slash (and a look-up
    # of a 5000-character name raises)
    return bool(argument) and (
        argument.endswith(".toml") or "/" in argument or "\\" in argument or argument.startswith("builtin:")
    )


def add_parser(sub) -> None:
    c = sub.add_parser(
        "check", help="check a workbook's requirements: exit 0 all hold, 1 one fails, 2 bad file"
    )
    c.add_argument("workbook", help="a workbook file (TOML: variables, cards, requirements)")
    c.add_argument(
        "--set",
        dest="sets",
        action="append",
        default=[],
        metavar="VAR=VALUE",
        help="replace a variable's value",
    )
    c.add_argument(
        "--worst-case",
        action="store_true",
        help="hold each requirement over the variables' tolerances (worst case), not only at the nominal values",
    )
    c.add_argument("--json", action="store_true", help="one JSON object (margins also in SI)")


def _marks() -> tuple[str, str]:
    """✔/✘, or ok/FAIL where standard output cannot write them."""
    try:
        "✔✘".encode(sys.stdout.encoding or "ascii")
        return "✔", "✘"
    except (UnicodeEncodeError, LookupError):
        return "ok", "FAIL"


def _sets(args) -> dict[str, str]:
    out = {}
    for item in getattr(args, "sets", []):
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise InputError(name.strip() or "--set", f"--set takes VAR=VALUE, got {shown(item)}")
        out[name.strip()] = value.strip()
    return out


def _load(path: str, args):
    from gearhead.core import workbook

    if not path.strip():
        raise InputError("workbook", "is empty; give a workbook file")
    return workbook.load(path, _sets(args))


def check(args) -> int:
    from gearhead.core import workbook

    wb = _load(args.workbook, args)
    outcome = workbook.solve(wb)
    worst = None
    if args.worst_case:
        from gearhead.core.workbook import study as workbook_study

        worst = workbook_study.worst_case(wb)
    holds = outcome.all_hold and (
        worst is None or all(worst.holds(c.requirement.key) for c in outcome.checks)
    )
    if args.json:
        data = outcome.as_json()
        data["holds"] = holds
        if worst is not None:
            data["worst_case"] = worst.as_json()
        print(json.dumps(data, allow_nan=False))
        return 0 if holds else EXIT_FAILS
    yes, no = _marks()
    passed = sum(1 for c in outcome.checks if c.holds)
    failed = len(outcome.checks) - passed
    _say(
        f"{printable(wb.name)} ({printable(wb.source)}): {len(outcome.checks)} requirement{'s' if len(outcome.checks) != 1 else ''}, "
        f"{passed} hold{'s' if passed == 1 else ''}, {failed} fail{'s' if failed == 1 else ''}"
    )
    width = max(
        (len(printable(c.requirement.name or c.requirement.check)) for c in outcome.checks), default=0
    )
    for c in outcome.checks:
        r = c.requirement
        label = printable(r.name or r.check)
        line = f"  {yes if c.holds else no} {label:<{width}}  {c.text()}"
        if r.name:
            line += f"   [{printable(r.check)}]"
        _say(line)
        if worst is not None and c.holds is not None:
            low = worst.low(r.key)
            if worst.spread is not None and r.key in worst.spread.outputs:
                mark = yes if worst.holds(r.key) else no
                o = worst.calculator.output(r.key)
                from gearhead.core import units

                spread = worst.spread.outputs[r.key]
                shown_low = units.format_quantity(low, o.unit, o.quantity)
                _say(f"    {mark} worst case: margin {shown_low} ({spread.worst_case_method})")
                for why in spread.infeasible:  # a corner where the robot could not be solved
                    _say(f"      not solved in the tolerance box: {why}")
    for name, card in outcome.cards.items():
        if card.error:
            _say(f"  card {name} ({card.calculator}) not solved: {card.error}")
    if outcome.match_error is not None:
        _say(f"  match not run: {outcome.match_error}")
    for card in wb.cards.values():
        for warning in card.warnings:
            _say(f"  warning: {warning}")
    if worst is not None:
        if worst.spread is not None:
            _say(
                f"  tolerances: {', '.join(t.entry for t in worst.spread.tolerances)}; {worst.spread.cost.text()}"
            )
        for note in worst.notes:
            _say(f"  note: {note}")
    elif any(v.tolerance for v in wb.variables.values()):
        _say("  note: tolerances on variables are not analysed here: add --worst-case")
    return 0 if holds else EXIT_FAILS


def solve(args) -> int:
    """Every card of a workbook, in dependency order, then its requirements."""
    from gearhead.core import workbook
    from gearhead.core.registry import get

    for option in ("preset", "preset_out", "document"):
        if getattr(args, option, None) is not None:
            raise InputError(f"--{option.replace('_', '-')}", "is for one calculator, not a workbook")
    if getattr(args, "units", None):
        raise InputError("--unit", "is for one calculator, not a workbook")
    wb = _load(args.calculator, args)
    outcome = workbook.solve(wb)
    if args.json:
        data = outcome.as_json(with_cards=True)
        if outcome.match is not None:  # the [match]'s outputs (`gearhead match --json` for the rest)
            data["match"] = outcome.match.as_json()["outputs"]
        print(json.dumps(data, allow_nan=False))
        return 0
    _say(f"{printable(wb.name)} ({printable(wb.source)})")
    for name, card in outcome.cards.items():
        calc = get(card.calculator)
        _say(f"\n[{printable(name)}] {calc.title} ({calc.id})")
        for field_name, ref in card.links.items():
            entry = (
                card.solution.inputs[field_name].text if card.solution else card.entries.get(field_name, "")
            )
            _say(f"  {calc.field(field_name).label} {ref}  → {entry}")
        if card.error:
            _say(f"  not solved: {card.error}")
            continue
        width = max((len(calc.output(k).label) for k in card.solution.outputs), default=0)
        for key, value in card.solution.outputs.items():
            _say(f"  {calc.output(key).label:<{width}}  {value.text}")
        for w in card.solution.warnings:
            _say(f"  warning: {w}")
    if wb.match is not None:  # its outputs (`gearhead match` adds the brownouts and the plot)
        from gearhead.core.workbook.match import summary

        _say("\n[match] the robot on one battery (gearhead match: brownouts, plot)")
        if outcome.match is None:
            _say(f"  not run: {printable(outcome.match_error or '')}")
        for line in summary(outcome.match) if outcome.match is not None else ():
            _say(line)
    yes, no = _marks()
    if outcome.checks:
        _say("\nRequirements")
    for c in outcome.checks:
        _say(f"  {yes if c.holds else no} {printable(c.requirement.name or c.requirement.check)}  {c.text()}")
    return 0


def sweep(args) -> int:
    from gearhead.core.sweep import text_table
    from gearhead.core.workbook import study as workbook_study

    if args.preset is not None or args.units:
        raise InputError(
            "--preset" if args.preset is not None else "--unit", "is for one calculator, not a workbook"
        )
    wb = _load(args.calculator, args)
    result = workbook_study.run_sweep(wb, args.varies, args.outputs)
    if args.json:
        print(json.dumps(result.as_json(), allow_nan=False))
    elif args.csv:
        sys.stdout.write(printable(result.csv_text(), keep_newlines=True))  # names from the file
    else:
        _say(text_table(result, None))
        _say("(each column: the requirement's margin; negative where it fails)")
    for note in result.notes:
        if not args.json:
            print(f"gearhead: note: {printable(note)}", file=sys.stderr)
    return 0
