"""`gearhead match WORKBOOK`: the workbook's [match] (core/workbook/match.py) run and shown: the
summary, the brownouts and a text plot of the bus voltage; `--json` the outputs, `--csv` the trace
(t, bus voltage, battery current). A bad file exits 2 (tui/cli.py's handler of InputError); a match
that cannot be run (a card it moves could not be solved) exits 1 with the reason."""

from __future__ import annotations

import csv
import io
import json
import sys

from gearhead.core.errors import InputError, printable

PLOT_WIDTH = 64
PLOT_HEIGHT = 12


def add_parser(sub) -> None:
    m = sub.add_parser("match", help="run a workbook's [match]: bus voltage, brownouts, charge")
    m.add_argument("workbook", help="a workbook file with a [match] table")
    m.add_argument(
        "--set",
        dest="sets",
        action="append",
        default=[],
        metavar="VAR=VALUE",
        help="replace a variable's value",
    )
    out = m.add_mutually_exclusive_group()
    out.add_argument("--json", action="store_true", help="the outputs as one JSON object")
    out.add_argument(
        "--csv", action="store_true", help="the trace: t (s), bus voltage (V), battery current (A)"
    )


def run(args) -> int:
    from gearhead.core import workbook
    from gearhead.core.workbook.match import summary

    from .workbook_cli import _load, _say

    wb = _load(args.workbook, args)
    if wb.match is None:
        raise InputError("match", "the workbook has no [match] table", wb.source)
    outcome = workbook.solve(wb)
    if outcome.match is None:
        print(
            f"gearhead: {printable(wb.source)}: match: {printable(outcome.match_error or '')}",
            file=sys.stderr,
        )
        return 1
    m = outcome.match
    if args.json:
        data = {"workbook": wb.name, "file": wb.source, **m.as_json()}
        print(json.dumps(data, allow_nan=False))
        return 0
    if args.csv:
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["t_s", "bus_voltage_V", "battery_current_A"])
        for t, v, i in m.bus.trace:
            w.writerow([f"{t:.6g}", f"{v:.6g}", f"{i:.6g}"])
        sys.stdout.write(buf.getvalue())
        return 0
    length = m.spec.values["length"]
    _say(f"{printable(wb.name)} ({printable(wb.source)})")
    _say(
        f"  match of {length:g} s, {len(m.moves)} moves; battery {m.battery.R * 1000:.4g} mΩ, "
        f"{m.battery.start_soc * 100:.4g} % charged; brownout {m.controller.brownout:g} V"
    )
    for line in summary(m):
        _say(line)
    if m.brownouts:
        _say(f"Brownouts ({len(m.brownouts)})")
        for b in m.brownouts[:20]:
            _say(f"  {b.start:8.3f} s  {b.length * 1000:7.1f} ms  {', '.join(b.running) or '-'}")
        if len(m.brownouts) > 20:
            _say(f"  ... {len(m.brownouts) - 20} more")
    else:
        _say("Brownouts: none")
    for line in plot(m.bus.trace, length, m.controller.brownout):
        _say(line)
    return 0


def plot(trace, length: float, brownout: float, width: int = PLOT_WIDTH, height: int = PLOT_HEIGHT):
    """The bus voltage as rows of text (plain ASCII, 8 + width columns): each column spans its
    lowest to highest voltage with '*'; '-' marks the brownout level."""
    lows: list = [None] * width
    highs: list = [None] * width
    ends: list = [None] * width  # the column's last sample
    for t, v, _ in trace:
        c = min(width - 1, max(0, int(t / length * width)))
        lows[c] = v if lows[c] is None else min(lows[c], v)
        highs[c] = v if highs[c] is None else max(highs[c], v)
        ends[c] = v
    for c in range(1, width):  # a column with no sample (a long step): the voltage carried on
        if lows[c] is None:
            lows[c] = highs[c] = ends[c] = ends[c - 1]
    vals = [v for v in lows + highs if v is not None]
    if not vals:
        return []
    top = max(vals)
    low = min(min(vals), brownout)
    step = max(top - low, 1e-9) / (height - 1)
    rows = []
    for r in range(height):
        level = top - step * r
        cells = []
        for lo, hi in zip(lows, highs):
            if lo is not None and lo - step / 2 <= level and level <= hi + step / 2:
                cells.append("*")
            elif abs(level - brownout) <= step / 2:
                cells.append("-")
            else:
                cells.append(" ")
        rows.append(f"{level:6.2f} |{''.join(cells)}")
    rows.append("       +" + "-" * width)
    rows.append(f"        0 s{'':<{width - 14}}{length:g} s")
    return ["Bus voltage (V) over the match; - the brownout level", *rows]
