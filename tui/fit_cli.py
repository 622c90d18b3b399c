"""`gearhead fit LOG --card elevator|arm|flywheel|sprint`: a card's model fitted from the robot's SysId log
(core/fit): the signals found, kS/kV/kA/kG in SysId's continuous and discrete forms beside the
card's own, the entries they give (moving mass or inertia, friction, efficiency), and the logged
voltage replayed through the card's model. `--json` prints one object; `--apply` writes the fitted
entries into the card's file (core/fit/apply.py). A bad log or entry exits 2, nothing written
(tui/cli.py's handler of InputError)."""

from __future__ import annotations

import json
import math

from gearhead.core.errors import InputError, printable

PLOT_WIDTH = 64
PLOT_HEIGHT = 12
UNITS = {
    "elevator": ("m", "m/s"),
    "arm": ("rad", "rad/s"),
    "flywheel": ("rad", "rad/s"),
    "sprint": ("m", "m/s"),
}


# the card's move (core.fit.entries.MOVE_OUTPUTS), in SI: label and unit ("" the card's speed unit)
MOVES = {
    "time_to_goal": ("time to goal", "s"),
    "peak_stator_current": ("peak stator current", "A"),
    "max_speed": ("top speed", ""),
    "spin_up_time": ("spin-up time", "s"),
    "recovery_time": ("recovery time", "s"),
    "slowest_ball_speed": ("slowest ball", "m/s"),
    "time_to_distance": ("time to distance", "s"),
    "speed_at_distance": ("speed at distance", "m/s"),
    "top_speed": ("attainable speed", "m/s"),
}


def add_parser(sub) -> None:
    f = sub.add_parser("fit", help="fit a card's kS/kV/kA/kG and entries from a SysId log (.wpilog or .csv)")
    f.add_argument("log", help="a WPILog (.wpilog) or AdvantageScope CSV export (.csv) of a SysId routine")
    f.add_argument(
        "--card", required=True, choices=("elevator", "arm", "flywheel", "sprint"), help="the card to fit"
    )
    src = f.add_mutually_exclusive_group()
    src.add_argument("--preset", metavar="FILE", help="the card's entries from this preset")
    src.add_argument("--workbook", metavar="FILE", help="the card's entries from this workbook (with --name)")
    f.add_argument("--name", metavar="CARD", help="the workbook's card")
    f.add_argument(
        "--routine", help="the SysId routine (sysid-test-state-ROUTINE) when the log holds several"
    )
    f.add_argument("--motor", help="the motor's name in voltage-MOTOR-ROUTINE (default: the first)")
    for role in ("state", "voltage", "position", "velocity", "current", "bus-voltage"):
        f.add_argument(f"--{role}", metavar="ENTRY", help=f"the {role} signal's entry or column name")
    f.add_argument(
        "--units",
        help="the position's unit when the log gives none or a wrong one: meters, rotations, radians, degrees",
    )
    f.add_argument(
        "--scale", type=float, default=1.0, help="multiply position and velocity by this (SysId's scaling)"
    )
    f.add_argument("--json", action="store_true", help="one JSON object (SI units)")
    f.add_argument(
        "--apply",
        action="store_true",
        help="write the fitted entries into the --preset or --workbook card's file (comments kept; "
        "the diff is printed; linked fields and built-in presets are not changed)",
    )


def run(args) -> int:
    from gearhead.core import fit
    from gearhead.core.fit import entries

    if not (math.isfinite(args.scale) and args.scale > 0):
        raise InputError("--scale", f"is {args.scale!r}; give a positive number")
    for option in (
        "routine",
        "motor",
        "state",
        "voltage",
        "position",
        "velocity",
        "current",
        "bus_voltage",
        "units",
        "name",
    ):
        value = getattr(args, option)
        if value is not None and not value.strip():  # an unset shell variable: not "not given"
            raise InputError(f"--{option.replace('_', '-')}", "is empty; give a name or leave the option out")
    if args.name and not args.workbook:
        raise InputError("--name", "names a workbook's card: give --workbook too")
    card = entries.load_card(args.card, args.preset, args.workbook, args.name)
    report = fit.fit_log(
        args.log,
        args.card,
        card,
        routine=args.routine,
        motor=args.motor,
        voltage=args.voltage,
        position=args.position,
        velocity=args.velocity,
        state=args.state,
        current=args.current,
        bus_voltage=args.bus_voltage,
        units=args.units,
        scale=args.scale,
    )
    applied = None
    if args.apply:
        from gearhead.core.fit import apply

        best = report.fits[report.favoured].gains
        applied = apply.apply(card, best, preset=args.preset, workbook=args.workbook, name=args.name)
    if args.json:
        data = report.as_json()
        if applied is not None:
            data["applied"] = {
                "file": applied.path,
                "changes": applied.changes,
                "diff": applied.diff,
                "notes": applied.notes,
            }
        print(json.dumps(data, allow_nan=False))
        return 0
    for line in text(report):
        print(printable(line.rstrip()))
    if applied is not None:
        print()
        if applied.diff:
            print(printable(f"  written to {applied.path}:"))
            for line in applied.diff.splitlines():
                print(printable(f"    {line}"))
        else:
            print(printable(f"  {applied.path}: nothing to change"))
        for n in applied.notes:
            print(printable(f"  note: {n}"))
    return 0


LABELS = {("continuous", "ols"): "continuous (SysId)", ("discrete", "iv"): "discrete (IV)"}


def _g(x: float) -> str:
    return f"{x:.4g}" if math.isfinite(x) else "-"


def text(r) -> list[str]:
    from gearhead.core.fit import favoured_reason
    from gearhead.core.fit.entries import MOVE_OUTPUTS
    from gearhead.core.fit.logs import quoted

    pos, vel = UNITS[r.kind]
    p = r.picked
    out = [f"{r.source}: {r.kind}, card from {r.card.label}"]
    # a name read is shown escaped (core.fit.logs.shown_name): quoted as is, never repr'd again
    out.append("  signals: " + ", ".join(f"{k} {quoted(v)}" for k, v in p.names.items()))
    if p.units:
        out.append("  units: " + ", ".join(f"{k} {v}" for k, v in p.units.items()))
    out.append(
        "  samples: "
        + ", ".join(f"{s} {len(run.t_voltage)}" for s, run in p.runs.items())
        + f"; mean step {r.info['dt'] * 1000:.3g} ms, velocity noise floor {_g(r.info['velocity_threshold'])} {vel} (at rest below "
        + f"{_g(r.info['moving_threshold'])})"
    )
    gains = list(r.fits["continuous"].gains)
    unit = {"kS": "V", "kG": "V", "kV": f"V/({vel})", "kA": f"V/({vel}/s)", "offset": "rad"}
    out.append("")
    heads = [LABELS.get((f, x.method), f) for f, x in r.fits.items()]
    out.append(f"  {'gain':<7} {'card':>10}   {heads[0]:>22}   {heads[1]:>22}")
    for k in gains:
        c = r.card.design.get(k, 0.0 if k == "offset" else math.nan)
        cells = [f"{_g(f.gains[k])} ± {_g(f.sigma[k])}" for f in r.fits.values()]
        out.append(f"  {k:<7} {_g(c):>10}   {cells[0]:>22}   {cells[1]:>22}  {unit[k]}")
    for label, key in (("adj. R²", "adj_r2"), ("RMSE", "rmse"), ("samples", "samples")):
        cells = [_g(getattr(f, key)) for f in r.fits.values()]
        out.append(f"  {label:<7} {'':>10}   {cells[0]:>22}   {cells[1]:>22}")
    out.append(f"  favoured: {r.favoured} ({favoured_reason(r)})")
    out.append("")
    out.append(f"  {'entry':<30} {'card':>10}   {'fitted':>22}")
    for name, card_value, value, sigma, u in r.entries:
        out.append(f"  {name:<30} {_g(card_value):>10}   {_g(value) + ' ± ' + _g(sigma):>22}  {u}")
    out.append("")
    out.append(f"  replay of the logged voltage: RMSE of position ({pos}), velocity ({vel})")
    for k, rp in r.replays.items():
        label = "design's entries" if k == "design" else f"fitted ({k})"
        out.append(f"    {label:<22} {_g(rp.position_rmse):>10}   {_g(rp.velocity_rmse):>10}")
    if r.moves:
        out.append("")
        out.append(f"  the card's move, with its entries and the fitted ones ({r.favoured})")
        for k in MOVE_OUTPUTS[r.kind]:
            if not any(k in r.moves.get(m, {}) for m in ("design", "fitted")):
                continue  # an output the card gives only with some effects (a flywheel's current)
            label, u = MOVES[k]
            cells = [_g(r.moves[m][k]) if k in r.moves.get(m, {}) else "-" for m in ("design", "fitted")]
            out.append(f"    {label:<22} {cells[0]:>10}   {cells[1]:>10}  {u or vel}")
    out += plot(r)
    for n in r.notes:
        out.append(f"  note: {n}")
    return out


def plot(r, state: str = "dynamic-forward", width: int = PLOT_WIDTH, height: int = PLOT_HEIGHT) -> list[str]:
    """The measured velocity ('*') and the favoured fit's replay ('o') of one test, as text."""
    if state not in r.replays[r.favoured].traces or state not in r.replays["design"].traces:
        return []
    t, _, v, _, vh = r.replays[r.favoured].traces[state]
    _, _, _, _, vd = r.replays["design"].traces[state]
    if len(t) < 2:
        return []
    lo = min(float(min(v)), float(min(vh)), float(min(vd)))
    hi = max(float(max(v)), float(max(vh)), float(max(vd)))
    span = max(hi - lo, 1e-12)
    grid = [[" "] * width for _ in range(height)]
    for series, mark in ((vd, "d"), (vh, "o"), (v, "*")):
        for k in range(len(t)):
            c = min(width - 1, int((t[k] - t[0]) / max(t[-1] - t[0], 1e-12) * (width - 1)))
            row = min(height - 1, int((hi - series[k]) / span * (height - 1)))
            grid[row][c] = mark
    rows = [f"  {hi - span * i / (height - 1):8.3g} |{''.join(g)}" for i, g in enumerate(grid)]
    return [
        "",
        f"  {state}: velocity measured (*), replayed with the {r.favoured} fit (o) and the design (d)",
        *rows,
        "           +" + "-" * width,
        f"            0 s{'':<{width - 14}}{t[-1] - t[0]:.3g} s",
    ]
