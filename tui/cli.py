"""The `gearhead` command line (DESIGN.md "Command line"). Textual loads only for the TUI."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence

from gearhead.core.errors import InputError, printable, shown

from . import cli_reach

EXIT_BAD_INPUT = 2
EXIT_BROKEN_PIPE = 141  # 128 + SIGPIPE, what a shell reports for a writer whose reader left
EXIT_INTERNAL = 70  # EX_SOFTWARE: a bug, not the user's input
EXIT_INTERRUPTED = 130  # 128 + SIGINT, as a shell reports a command stopped by Ctrl+C
EXIT_IO = 74  # EX_IOERR: the results could not be written (standard output closed or full)


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="gearhead", description="Mechanism design calculators for FRC and VEX.")
    sub = p.add_subparsers(dest="command")
    s = sub.add_parser("solve", help="solve one calculator and print its outputs")
    s.add_argument(
        "calculator", help="calculator id (see `gearhead calculators`), or a workbook file (.toml)"
    )
    s.add_argument(
        "--preset",
        metavar="FILE",
        help="start from this preset file (or a gh1: share code, or a ReCalc link)",
    )
    s.add_argument(
        "--set",
        dest="sets",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="set one input, e.g. --set load='25 lbf' (repeatable)",
    )
    s.add_argument(
        "--unit",
        dest="units",
        action="append",
        default=[],
        metavar="OUTPUT=UNIT",
        help="show an output in another unit, e.g. --unit center_distance=in (repeatable)",
    )
    s.add_argument("--json", action="store_true", help="print one JSON object (values in SI)")
    # tolerances ('--set "load=25 lbf ± 5 %"'): how each output's statistical spread is found
    s.add_argument(
        "--spread",
        choices=("auto", "first-order", "monte-carlo"),
        default="auto",
        help="statistical spread when inputs carry ± tolerances (default: first-order where exact enough)",
    )
    s.add_argument("--samples", type=int, default=1000, help="Monte Carlo samples (default 1000)")
    s.add_argument("--seed", type=int, default=0, help="Monte Carlo seed (default 0)")
    s.add_argument(
        "--preset-out",
        metavar="FILE",
        help="write the inputs solved as a preset: '-' prints it instead of the results "
        "(to chain: ... --preset-out - > x.toml); a FILE is never overwritten",
    )
    s.add_argument(
        "--document",
        "--export",
        dest="document",
        metavar="NAME",
        help="print a file for another tool instead of the results, e.g. `solve sprint --document "
        "pathplanner > settings.json`, `solve elevator --set mode=profiled --export phoenix6` "
        "(`calculators` lists each calculator's documents)",
    )
    a = sub.add_parser("accuracy", help="run a simulation at every accuracy level: error, time, evaluations")
    a.add_argument("calculator", help="a simulated calculator (e.g. pneumatics)")
    a.add_argument("--preset", metavar="FILE")
    a.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE")
    a.add_argument("--json", action="store_true")
    _sweep_parser(sub)
    pr = sub.add_parser("presets", help="list built-in and user presets")
    pr.add_argument("calculator", nargs="?", help="only this calculator's presets")
    c = sub.add_parser("calculators", help="list calculator ids, modes and fields")
    c.add_argument("--json", action="store_true")
    cli_reach.add_parsers(sub)
    from . import workbook_cli  # `check`, and solve/sweep of a workbook file

    workbook_cli.add_parser(sub)
    from . import match_cli  # `match`: a workbook's [match]

    match_cli.add_parser(sub)
    from . import report_cli  # `report`: a preset or workbook as HTML, Markdown or PDF

    report_cli.add_parser(sub)
    from . import fit_cli  # `fit`: a card fitted from the robot's SysId log

    fit_cli.add_parser(sub)
    return p


def _keep_quit_key() -> None:
    """The app is starting: ctrl+\\ typed before Textual puts the terminal in raw mode sent
    SIGQUIT and ended it (exit 131, seen in a key storm). Ignored from here on; once the app runs,
    the key is a key like any other."""
    import signal

    if hasattr(signal, "SIGQUIT") and sys.stdin is not None and sys.stdin.isatty():
        signal.signal(signal.SIGQUIT, signal.SIG_IGN)


def main(argv: Sequence[str] | None = None) -> int:

    given = list(sys.argv[1:] if argv is None else argv)
    workbook_named = given[:1] and (given[0].endswith(".toml") or given[0].startswith("builtin:"))
    if not given or (len(given) == 1 and workbook_named and not given[0].startswith("-")):
        _keep_quit_key()  # the app: first, before the parser's ~20 ms (a key typed at launch)
    if len(given) == 1 and workbook_named and not given[0].startswith("-"):
        return _workbook_app(given[0], argv)  # `gearhead robot.toml`: the app with that workbook
    args = _parser().parse_args(argv)
    if args.command is None:
        _keep_quit_key()
        if not _terminal():  # with no terminal the app waited for keys that never come
            _complain(
                "the app needs a terminal (standard input and output); from a script use "
                "`gearhead solve CALC ...` (see gearhead --help)"
            )
            return EXIT_BAD_INPUT
        from .app import run

        try:
            failure = run()
        except Exception as exc:  # before the app or after it (its settings, the terminal)
            return _internal(exc, argv)
        if failure is None:
            return 0
        return _app_failure(failure)
    if sys.stdout is None:  # closed (`>&-`): the results would vanish and the exit code say 0
        _complain("cannot write the results: standard output is closed")
        return EXIT_IO
    try:
        code = _command(args)
        sys.stdout.flush()  # a full disk (/dev/full) shows here, not after the exit code is set
        return code
    except InputError as exc:
        _complain(str(exc) + _logged(exc, argv))
        for error in exc.errors[1:]:  # several wrong entries: one line each, the first as before
            _complain(str(error))
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("gearhead: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # the reader left (`gearhead sweep ... | head`): stop quietly, as cat does
        _silence_stdout()
        return EXIT_BROKEN_PIPE
    except OSError as exc:
        if not _stdout_failed(exc):
            return _internal(exc, argv)
        _silence_stdout()
        _complain(f"cannot write the results ({exc.strerror or exc})")
        return EXIT_IO
    except Exception as exc:  # a bug: one line for the user, the traceback in the log for us
        return _internal(exc, argv)


def _workbook_app(path: str, argv) -> int:
    """`gearhead robot.toml`: the app, showing the workbook's cards (a bad file: exit 2, one line)."""
    from gearhead.core import workbook

    if not _terminal():
        _complain(
            "the app needs a terminal; from a script use `gearhead check FILE` or `gearhead solve FILE`"
        )
        return EXIT_BAD_INPUT
    try:
        book = workbook.load(path)
    except InputError as exc:
        _complain(str(exc))
        return EXIT_BAD_INPUT
    from .app import run

    try:
        failure = run(workbook=book)
    except Exception as exc:  # before the app or after it (its settings, the terminal)
        return _internal(exc, argv)
    return 0 if failure is None else _app_failure(failure)


def _internal(exc: Exception, argv) -> int:
    _complain(f"internal error ({type(exc).__name__}: {exc})" + _logged(exc, argv))
    return EXIT_INTERNAL


def _app_failure(report: str) -> int:
    """The app stopped on an exception Textual caught (app.run): its report to the log, one line
    to the user (the exception's own line, the last of Textual's traceback)."""
    import re

    from . import bug_log

    text = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", report)  # Textual's colours
    path = bug_log.record_text(text, "gearhead (the app)")
    _complain(f"internal error ({_exception_line(text)})" + (f" (traceback in {path})" if path else ""))
    return EXIT_INTERNAL


def _exception_line(traceback: str) -> str:
    """`TypeError: message` from a traceback as Rich draws it: the lines after its last frame box
    (a long message wraps), without Textual's note on how many errors there were."""
    lines = [line.strip() for line in traceback.splitlines()]
    boxes = [n for n, line in enumerate(lines) if line.startswith("╰")]
    tail = lines[boxes[-1] + 1 :] if boxes else lines
    words = " ".join(line for line in tail if line and not line.startswith("NOTE:"))
    return words[:300] or "the app stopped"


def _command(args) -> int:
    from . import workbook_cli

    if args.command == "check":
        return workbook_cli.check(args)
    if args.command == "match":
        from . import match_cli

        return match_cli.run(args)
    if args.command == "report":
        from . import report_cli

        return report_cli.run(args)
    if args.command == "fit":
        from . import fit_cli

        return fit_cli.run(args)
    if args.command in ("solve", "sweep") and workbook_cli.is_workbook(args.calculator):
        return workbook_cli.solve(args) if args.command == "solve" else workbook_cli.sweep(args)
    if args.command == "solve":
        return _solve(args)
    if args.command == "presets":
        return _presets(args)
    if args.command == "accuracy":
        return _accuracy(args)
    if args.command == "sweep":
        return _sweep(args)
    if args.command in cli_reach.COMMANDS:
        return cli_reach.run(args)
    return _calculators(args)


def _terminal() -> bool:
    """Whether standard input and output are a terminal the app can run in."""
    try:
        return sys.stdin is not None and sys.stdout is not None and sys.stdin.isatty() and sys.stdout.isatty()
    except (OSError, ValueError):  # a closed stream
        return False


def _stdout_failed(exc: OSError) -> bool:
    """Whether an OSError came from writing the results (a full disk, a closed descriptor)."""
    import errno

    return exc.errno in (errno.ENOSPC, errno.EBADF, errno.EIO, errno.EDQUOT) and exc.filename is None


def _silence_stdout() -> None:
    """Point standard output at the null device, so the interpreter's flush at exit says nothing."""
    import os

    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError):
        pass


def _logged(exc: BaseException, argv) -> str:
    """' (traceback in FILE)' after recording an unexpected failure, else ''."""
    from . import bug_log

    if not bug_log.is_bug(exc):
        return ""
    path = bug_log.record(exc, f"gearhead {' '.join(sys.argv[1:] if argv is None else argv)}")
    return f" (traceback in {path})" if path else ""


def _complain(message: str, kind: str = "") -> None:
    """One line on stderr, whatever the message holds (an InputError is one line already; this
    keeps it so for any text that reaches here)."""
    # line breaks become spaces; any other control character (an ESC in a file's text) is shown
    line = printable(" ".join(message.split())) if not message.isprintable() else message
    print(f"gearhead: {kind}{line}", file=sys.stderr)


def _raw_inputs(args, calc) -> dict:
    """Inputs from --preset then --set, as typed; a preset's warnings go to stderr, one line each."""
    from gearhead.core import share

    raw: dict = {}
    if args.preset is not None:
        if not args.preset.strip():  # `--preset ""` (an unset shell variable) was ignored
            raise InputError("--preset", "is empty; give a preset file")
        preset = share.load_any(args.preset)  # a file, or a share code or ReCalc link
        if preset.calculator != calc.id:
            raise InputError(
                "calculator", f"preset is for {shown(preset.calculator)}, not {calc.id!r}", args.preset
            )
        for warning in preset.warnings:
            _complain(warning, "warning: ")
        raw.update(preset.inputs)
    for item in args.sets:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise InputError(
                name or "--set", f"--set takes NAME=VALUE (e.g. --set load='25 lbf'), got {shown(item)}"
            )
        raw[name] = value
    return raw


def _unused_sets(calc, args, raw: dict) -> list[str]:
    """A warning for each --set of a field the other choices leave unused (a ratio typed beside a
    COTS module, a mode's field in another mode): it is kept, not read, and the user must know."""
    from gearhead.core.model import choice_values

    choices = choice_values(calc, raw)
    mode = None
    if "mode" in {f.name for f in calc.fields}:
        try:
            mode = calc.field("mode").parse(raw.get("mode", calc.field("mode").default))
        except InputError:
            return []
    named = {item.partition("=")[0].strip() for item in args.sets}
    out = []
    for f in calc.fields:
        if f.name in named and not f.active(mode, choices):
            out.append(f"{f.name}: not used with these choices (set, but it changes nothing here)")
    return out


def _display_units(args) -> dict[str, str]:
    """--unit OUTPUT=UNIT options as {output: unit}."""
    display_units: dict[str, str] = {}
    for item in args.units:
        name, sep, unit = item.partition("=")
        if not sep or not name.strip():
            raise InputError(
                name.strip() or "--unit",
                f"--unit takes OUTPUT=UNIT (e.g. --unit free_speed=rad/s), got {shown(item)}",
            )
        display_units[name.strip()] = unit.strip()
    return display_units


def _solve(args) -> int:
    from gearhead.core import solving
    from gearhead.core.registry import get

    calc = get(args.calculator)
    if args.preset_out is not None and not args.preset_out.strip():  # was ignored: no preset written
        raise InputError("--preset-out", "is empty; give a file name, or - to print the preset")
    display_units = _display_units(args)
    raw = _raw_inputs(args, calc)
    # the card's own solve (a bad input exits 2 before any preset is written)
    solved = solving.solve(calc, raw, display_units, method=args.spread, samples=args.samples, seed=args.seed)
    solution, spread = solved.solution, solved.spread
    said = {w.partition(":")[0] for w in solution.warnings}  # an invalid unused entry is said already
    solution.warnings.extend(w for w in _unused_sets(calc, args, raw) if w.partition(":")[0] not in said)
    if args.preset_out is not None:
        return _preset_out(args, calc, raw, solution)
    if args.document is not None:
        return _document(calc, args.document, solution)
    if args.json:
        if spread is None:
            data = solution.as_json()
        else:
            from gearhead.core import tolerance

            data = tolerance.as_json(solution, spread)
        print(json.dumps(data, allow_nan=False))
        return 0
    width = max(len(calc.output(k).label) for k in solution.outputs)
    print(f"{calc.title} ({calc.id})")
    for name, value in solution.outputs.items():
        print(f"  {calc.output(name).label:<{width}}  {value.text}")
    for w in solution.warnings:
        print(f"  warning: {w}")
    entries = solution.entries()
    for table in calc.tables:
        if table.shown_in(entries):
            _print_table(table, solution.tables.get(table.name, []))
    if solution.heat_maps:
        _print_heat_maps(calc, solution)
    if spread is not None:
        from gearhead.core import tolerance

        print("\n".join(tolerance.spread_lines(calc, solution, spread, width)))
    return 0


def _document(calc, name: str, solution) -> int:
    """--document NAME: the calculator's file for another tool (core.declarations.Document), on stdout."""
    docs = {d.name: d for d in calc.documents}
    if name not in docs:
        have = ", ".join(docs) if docs else "none"
        raise InputError("--document", f"{name!r} is not a document of {calc.id} (it has: {have})")
    try:
        text = docs[name].build(solution)
    except ValueError as exc:
        raise InputError("--document", f"{name}: {exc}") from None
    sys.stdout.write(text)
    return 0


# --- sweep (core.sweep) -----------------------------------------------------------------------


def _sweep_parser(sub) -> None:
    w = sub.add_parser("sweep", help="solve over a range of one input (a table) or two (a grid)")
    w.add_argument("calculator", help="calculator id (see `gearhead calculators`)")
    w.add_argument(
        "--vary",
        dest="varies",
        action="append",
        default=[],
        required=True,
        metavar="NAME=START..STOP[:N][:log]",
        help="the input to vary, e.g. --vary ratio=3..12:50 or --vary 'spool_diameter=1 in..2 in:21' "
        "(give two for a grid)",
    )
    w.add_argument("--preset", metavar="FILE", help="start from this preset file")
    w.add_argument("--set", dest="sets", action="append", default=[], metavar="NAME=VALUE")
    w.add_argument(
        "--output",
        dest="outputs",
        action="append",
        default=[],
        metavar="NAME",
        help="an output to tabulate (repeatable; default: every numeric output)",
    )
    w.add_argument("--unit", dest="units", action="append", default=[], metavar="OUTPUT=UNIT")
    form = w.add_mutually_exclusive_group()
    form.add_argument("--csv", action="store_true", help="CSV in display units, a status column per row")
    form.add_argument("--json", action="store_true", help="one JSON object, values in SI")


def _sweep(args) -> int:
    from gearhead.core import sweep, tolerance
    from gearhead.core.registry import get

    calc = get(args.calculator)
    display_units = _display_units(args)
    raw, tolerances = tolerance.split_inputs(calc, _raw_inputs(args, calc))
    result = sweep.run(calc, raw, args.varies, args.outputs, display_units)
    if tolerances:
        result.notes.append(
            f"tolerances on {', '.join(tolerances)} are not swept: the nominal values are used"
        )
    if args.json:
        print(json.dumps(result.as_json(), allow_nan=False))
    elif args.csv:
        sys.stdout.write(result.csv_text())
    else:
        print(sweep.text_table(result, None if args.outputs else 6))
    for note in result.notes:
        if not args.json:
            print(f"gearhead: note: {note}", file=sys.stderr)
    return 0


def _print_heat_maps(calc, solution) -> None:
    """Each heat map with data, as the card draws it less the colours (values, the pick in [ ])."""
    from gearhead.core.model import HeatMap

    from .components.heat_map_layout import layout, plain_lines

    for spec in calc.plots:
        if isinstance(spec, HeatMap) and spec.name in solution.heat_maps:
            print(f"{spec.title}:")
            print("\n".join(plain_lines(layout(spec, solution.heat_maps[spec.name]))))


def _print_table(table, rows) -> None:
    """A declared table (e.g. the ratio finder's combinations) as aligned text columns."""
    columns = [c for c in table.columns if not c.hidden]
    heads = [f"{c.label} [{c.unit}]" if c.unit else c.label for c in columns]
    cells = [[row[c.name].text if c.name in row else "" for c in columns] for row in rows]
    widths = [max([len(h)] + [len(r[i]) for r in cells]) for i, h in enumerate(heads)]
    print(f"{table.title}:")
    print("  " + "  ".join(h.ljust(w) for h, w in zip(heads, widths)).rstrip())
    for r in cells:
        print("  " + "  ".join(x.ljust(w) for x, w in zip(r, widths)).rstrip())


def _preset_out(args, calc, raw: dict, solution) -> int:
    """--preset-out: the solved inputs as a whole preset (every field: defaults for those not
    given), '-' to stdout alone so it pipes into a file or another tool, else a new file."""
    from gearhead.core import atomic_file, share
    from gearhead.core.export import preset_toml

    inputs = {f.name: f.kind.initial_entry(f) for f in calc.fields}
    inputs.update(raw)
    # as the app saves them (whole numbers as TOML integers)
    inputs = {f.name: f.kind.stored(f, inputs[f.name]) for f in calc.fields}
    name = share.load_any(args.preset).name if args.preset else f"{calc.title} (command line)"
    text = preset_toml(calc.id, inputs, name)
    if args.preset_out == "-":
        sys.stdout.write(text)
        return 0
    # whole or not at all: a full disk used to leave a 0-byte file (then "exists" on a retry)
    path = atomic_file.write_text(args.preset_out, text, field="--preset-out")
    width = max(len(calc.output(k).label) for k in solution.outputs)
    print(f"{calc.title} ({calc.id}): preset written to {printable(path)}", file=sys.stderr)
    if args.json:
        print(json.dumps(solution.as_json(), allow_nan=False))
        return 0
    for name_, value in solution.outputs.items():
        print(f"  {calc.output(name_).label:<{width}}  {value.text}")
    return 0


def _accuracy(args) -> int:
    from gearhead.core.model import last_resort, parse_inputs
    from gearhead.core.registry import calculators, get
    from gearhead.core.sim.scene import DEFAULT_ADVICE, REFERENCE_RTOL, ladder

    calc = get(args.calculator)
    if calc.simulate is None:
        sims = ", ".join(c.id for c in calculators().values() if c.simulate is not None)
        raise InputError("calculator", f"{calc.id} is not a simulation (simulations: {sims})")
    values, _ = parse_inputs(calc, _raw_inputs(args, calc))
    # what to change when a run needs more than one solve's budget: the calculator module's ADVICE
    advice = getattr(sys.modules.get(calc.simulate.__module__), "ADVICE", DEFAULT_ADVICE)
    with last_resort():  # the same guard as core.model.solve: a message, never a traceback
        rungs, reference = ladder(calc.simulate, values, advice=advice)
    if args.json:
        print(
            json.dumps(
                {
                    "calculator": calc.id,
                    "reference": {
                        "rtol": REFERENCE_RTOL,
                        "rhs_evaluations": reference.nfev,
                        "key": reference.key,
                    },
                    "levels": [
                        {
                            "level": r.level,
                            "rtol": r.rtol,
                            "error": r.error,
                            "wall_time": r.wall_time,
                            "rhs_evaluations": r.nfev,
                        }
                        for r in rungs
                    ],
                },
                allow_nan=False,
            )
        )
        return 0
    print(f"{calc.title}: accuracy vs time (error relative to a run at rtol {REFERENCE_RTOL:.0e})")
    print(f"  {'level':<9}{'rtol':>8}{'error':>12}{'wall time':>12}{'RHS evals':>11}")
    for r in rungs:
        print(f"  {r.level:<9}{r.rtol:>8.0e}{r.error:>12.2e}{r.wall_time * 1e3:>10.3f} ms{r.nfev:>11}")
    return 0


def _presets(args) -> int:
    from gearhead.core import presets
    from gearhead.core.registry import get

    if args.calculator:
        get(args.calculator)
    for p in presets.listing(args.calculator):
        kind = "built-in" if p.builtin else "user"
        # a name or path may hold terminal escape sequences: shown escaped, never sent raw
        print(f"{p.calculator:<18} {kind:<8} {_printable(p.name):<28} {_printable(str(p.path))}")
    for problem in presets.problems(args.calculator):
        _complain(str(problem), "skipped ")
    return 0


def _bounds(f) -> dict:
    """A numeric field's bounds for `calculators --json`: as declared (display unit) and in SI,
    null where unbounded; nothing for a field that is not a number."""
    if not f.kind.numeric:
        return {}
    lo, hi = f.bounds_si()
    return {
        "min": f.min,
        "max": f.max,
        "min_si": lo,
        "max_si": hi,
        "min_exclusive": f.min_exclusive,
        "max_exclusive": f.max_exclusive,
    }


_printable = printable  # core.errors.printable: the one function every print of file text uses


def _calculators(args) -> int:
    from gearhead.core.registry import calculators
    from gearhead.core.units import SI_UNITS

    described = []
    for calc in calculators().values():
        described.append(
            {
                "id": calc.id,
                "title": calc.title,
                "modes": list(calc.modes),
                "fields": [
                    {
                        "name": f.name,
                        "type": f.type,
                        "unit": f.unit,
                        "si_unit": SI_UNITS[f.quantity] if f.kind.with_unit else "",
                        "default": f.default,
                        "choices": list(f.choices),
                        "modes": list(f.modes),
                        "help": f.help,
                        **_bounds(f),
                    }
                    for f in calc.fields
                ],
                "outputs": [
                    {"name": o.name, "unit": o.unit, "si_unit": SI_UNITS[o.quantity]} for o in calc.outputs
                ],
                "documents": [
                    {"name": d.name, "label": d.label, "filename": d.filename} for d in calc.documents
                ],
            }
        )
    if args.json:
        print(json.dumps(described, allow_nan=False))
        return 0
    for d in described:
        print(f"{d['id']}: {d['title']}")
        if d["modes"]:
            print(f"  modes:   {', '.join(d['modes'])}")
        print(f"  fields:  {', '.join(f['name'] for f in d['fields'])}")
        print(f"  outputs: {', '.join(o['name'] for o in d['outputs'])}")
        if d["documents"]:
            print(f"  documents (solve --document NAME): {', '.join(x['name'] for x in d['documents'])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
