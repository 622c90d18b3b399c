"""The workbook's `[match]` table (issue 43): the robot's mechanisms on one battery for a match, run
on core.match.mechanisms' bus, its outputs readable by requirements as `match.OUTPUT`.

    [match]
    length = "150 s"                      # default 150 s
    controller = "roborio2"               # or "roborio1" (brownout 6.75 V / 6.3 V, frc-docs)
    brownout = "6.75 V"                   # optional: the controller's thresholds, edited
    recovery = "7.5 V"
    base_load = "3 A"                     # roboRIO, radio, sensors: never disabled
    resistance = "= battery_resistance"   # the battery's own (default 0.015 ohm)
    wiring_resistance = "0.003 ohm"       # default 0
    capacity = "18 A*h"                   # at the 20 h rate
    peukert = 1.25
    charge = 1.0                          # the starting state of charge (or "70 %")
    ocv = [[0.0, 11.94], [0.5, 12.54], [1.0, 12.72]]   # (state of charge, volts)
    main_breaker = [[2.0, 10.0], [5.0, 1.0]]           # trip table: multiple of 120 A, seconds
    channel_rating = "40 A"                            # each motor's channel breaker
    channel_breaker = [[1.5, 10.0], [3.0, 1.0]]        # its trip table: multiple of the rating, s

    [[match.events]]
    at = "2 s"                            # when the move is asked
    card = "lift"                         # an elevator or arm (mode = move), sprint or flywheel card
    action = "move"                       # move: start → goal; return: goal → start (a sprint: the
                                          # same sprint); a flywheel: spin_up (from rest to its
                                          # target) or burst (and its shots); stop: motors off
    every = "20 s"                        # optional: repeated every 20 s ...
    count = 7                             # ... 7 times in all (those past the end are dropped)

Every entry is a number (in the unit shown), a quantity (`"0.02 ohm"`) or, for the battery, the base
load and the thresholds, a reference `"= EXPR"` reading the workbook's variables. Events' `at` and
`every` are plain (a number of seconds or a time).

Events on one card are queued, never superposed: a move starts at its time or, if the card's previous
move has not reached its goal yet (a burst: its last shot and that shot's recovery), when it does.
An elevator, arm or flywheel then holds its goal (its speed) on the current that holds it until the
card's next move starts (a flywheel's then starts at the speed it held, B13), or until an event
with `action = "stop"` (core.match.mechanisms (B10)); an elevator's and arm's move ends are hard
stops (B12); a sprint draws nothing after its distance. A move that never arrives (stuck, browned
out to the end) holds the card's later moves back: they are counted in `match.unfinished`. Each move
starts from rest at its start (the elevator's return from the top of its travel), as the card's
scene does. Each moved card's channel breaker gives the outputs `match.CARD_breaker_load`,
`_margin` and `_trip` (B9).
The battery, controller and bus are core.match's (battery.py, brownout.py, mechanisms.py), with their
defaults and the sources of each given there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..errors import InputError, shown
from .book import MATCH_OUTPUTS as OUTPUTS  # noqa: F401 (tui/match_cli reads it here)
from .book import Expr, Workbook
from .book import match_output as output_info
from .expressions import Scope, evaluate, literal_value, parse_expression

NAME = "match"
MAX_EVENT_ROWS = 1000  # [[match.events]] tables read; more is refused before any expansion
MAX_MOVES = 200  # moves on the bus after `every`/`count` (core.match.mechanisms.MAX_MECHANISMS)
ACTIONS = ("move", "return")
# calculator: (its mode field and the mode the match runs, or None; the actions, the first the default)
ON_BUS = {
    "elevator": ("mode", "move", (*ACTIONS, "stop")),
    "arm": ("mode", "move", (*ACTIONS, "stop")),
    "sprint": ("mode", "sprint", ACTIONS),  # return: the same sprint, driven back
    "flywheel": (None, None, ("spin_up", "burst", "stop")),  # its `mode` is the inertia's
}
# held at their goal after a move (mechanisms.py (B10)) until the card's next move or a `stop`
HOLDING = ("elevator", "arm", "flywheel")
CARDS_ON_BUS = tuple(ON_BUS)
NOT_ON_BUS = (
    "not on the match bus yet: elevator and arm moves, sprints and flywheel spin-ups only "
    "(pneumatic cycles are not modelled)"
)
KEYS = {  # key: (unit, default, a reference allowed)
    "length": ("s", 150.0, False),
    "brownout": ("V", None, True),
    "recovery": ("V", None, True),
    "base_load": ("A", 0.0, True),
    "resistance": ("ohm", 0.015, True),
    "wiring_resistance": ("ohm", 0.0, True),
    "capacity": ("A*h", 18.0, True),
    "peukert": ("", 1.25, True),
    "charge": ("", 1.0, True),
    "channel_rating": ("A", 40.0, False),
}
EVENT_KEYS = ("at", "card", "action", "every", "count")


def default_action(calculator: str) -> str | None:
    """The action an event of a card of this calculator runs when it names none (ON_BUS's first),
    None for a calculator not on the bus."""
    return ON_BUS[calculator][2][0] if calculator in ON_BUS else None


EVENT_TIMES = ("at", "every")  # in seconds: a bare number typed in the app is written "N s"
EVENT_WORDS = ("card", "action")  # names, kept as typed


def event_table(entries: dict[str, Any]) -> dict[str, Any]:
    """One `[[match.events]]` table from an event's entries as the app's timeline holds them (the
    file's values, or text as typed): an empty entry leaves its key out (an optional one takes its
    default, `at` or `card` is then refused as missing); a bare number of seconds gets its unit; a
    card or an action stays the text typed; any other key (`count`, ...) is read as a TOML value
    (`10` a whole number, `true` a yes) and kept as typed when it is not one, so parse() names it."""
    import tomllib

    out: dict[str, Any] = {}
    for key, value in entries.items():
        if not isinstance(value, str):
            out[key] = value
            continue
        text = value.strip()
        if not text:
            continue
        if key in EVENT_TIMES:
            try:
                bare = math.isfinite(float(text))
            except ValueError:
                bare = False
            out[key] = f"{text} s" if bare else text
        elif key in EVENT_WORDS:
            out[key] = text
        else:
            try:
                out[key] = tomllib.loads(f"v = {text}")["v"]
            except tomllib.TOMLDecodeError:
                out[key] = text
    return out


@dataclass
class Event:
    index: int  # 1-based, in file order
    at: float  # s
    card: str
    action: str
    every: float | None
    count: int


@dataclass
class MatchSpec:
    values: dict[str, Any]  # key -> float (in KEYS' unit) or Expr
    controller: str
    ocv: tuple | None
    events: list[Event]
    source: str
    main_breaker: Any = None  # core.match.breaker.Breaker with the trip table entered, else None
    channel_table: tuple | None = None  # every channel breaker's trip table, else None (B9)

    def occurrences(self) -> list[tuple[float, Event]]:
        """Every move asked, (time, event), by time then file order; those past the end dropped."""
        length = self.values["length"]
        out = []
        for ev in self.events:
            for j in range(ev.count):
                t = ev.at + j * (ev.every or 0.0)
                if t < length:
                    out.append((t, ev))
        out.sort(key=lambda x: (x[0], x[1].index))
        return out


# ---------------------------------------------------------------------------------------------
# Reading the table


def parse(data: Any, wb: Workbook) -> MatchSpec:
    """The [match] table of `wb`'s file, every mistake an InputError naming the file and the field."""
    src = wb.source
    if not isinstance(data, dict):
        raise InputError(NAME, "must be a table ([match] ...)", src)
    allowed = set(KEYS) | {"controller", "ocv", "events", "main_breaker", "channel_breaker"}
    for key in data:
        if key not in allowed:
            raise InputError(f"{NAME}.{key}", f"unknown key of the match ({', '.join(sorted(allowed))})", src)
    if NAME in wb.cards or NAME in wb.variables:
        kind = "card" if NAME in wb.cards else "variable"
        raise InputError(
            f"{'cards' if kind == 'card' else 'variables'}.{NAME}",
            f"a {kind} named {NAME!r} would hide the [match] table's outputs; rename it",
            src,
        )
    for node in list(wb.variables.values()) + list(wb.cards.values()):
        exprs = (
            [node.expr] if hasattr(node, "expr") and node.expr else list(getattr(node, "links", {}).values())
        )
        for e in exprs:
            if NAME in e.names:
                where = f"variables.{node.name}" if hasattr(node, "expr") else f"cards.{node.name}"
                raise InputError(
                    where, "reads the match's outputs: only requirements may (the match runs last)", src
                )
    static = _static_scope(wb)
    values: dict[str, Any] = {}
    for key, (unit, default, ref) in KEYS.items():
        if key not in data:
            values[key] = default
            continue
        values[key] = _scalar(f"{NAME}.{key}", data[key], unit, ref, wb, static)
    controller = data.get("controller", "roborio2")
    from ..match.brownout import BROWNOUT_VOLTS

    if controller not in BROWNOUT_VOLTS:
        raise InputError(
            f"{NAME}.controller", f"must be one of {', '.join(BROWNOUT_VOLTS)}, got {shown(controller)}", src
        )
    ocv = data.get("ocv")
    if ocv is not None:
        from ..match.battery import Battery

        try:
            Battery(ocv_table=ocv)
        except InputError as exc:
            raise InputError(f"{NAME}.ocv", exc.message, src) from None
        except (TypeError, ValueError):
            raise InputError(f"{NAME}.ocv", "must be rows [state of charge, volts]", src) from None
        ocv = tuple(tuple(r) for r in ocv)
    main_breaker = None
    if "main_breaker" in data:  # a trip table ((multiple of 120 A, seconds), ...): no default (breaker.py)
        from ..match.breaker import MAIN_RATING, Breaker

        try:
            main_breaker = Breaker(MAIN_RATING, data["main_breaker"], name="main_breaker")
        except InputError as exc:
            raise InputError(f"{NAME}.{exc.field}", exc.message, src) from None
        except (TypeError, ValueError):
            raise InputError(
                f"{NAME}.main_breaker", "must be rows [multiple of 120 A, seconds]", src
            ) from None
        if not main_breaker.calibrated:
            raise InputError(
                f"{NAME}.main_breaker", "needs at least one row [multiple of 120 A, seconds]", src
            )
    channel_table = None
    if "channel_breaker" in data:  # every channel's trip table ((multiple of its rating, s), ...)
        from ..match.breaker import Breaker

        if not 0 < values["channel_rating"] <= 1e5:
            raise InputError(
                f"{NAME}.channel_rating", f"must be above 0 A, got {values['channel_rating']:g} A", src
            )
        try:
            brk = Breaker(values["channel_rating"], data["channel_breaker"], name="channel_breaker")
        except InputError as exc:
            raise InputError(f"{NAME}.{exc.field}", exc.message, src) from None
        except (TypeError, ValueError):
            raise InputError(
                f"{NAME}.channel_breaker", "must be rows [multiple of the channel rating, seconds]", src
            ) from None
        if not brk.calibrated:
            raise InputError(
                f"{NAME}.channel_breaker", "needs at least one row [multiple of the rating, seconds]", src
            )
        channel_table = brk.table
    elif not 0 < values["channel_rating"] <= 1e5:
        raise InputError(
            f"{NAME}.channel_rating", f"must be above 0 A, got {values['channel_rating']:g} A", src
        )
    rows = data.get("events", [])
    if not isinstance(rows, list) or not all(isinstance(r, dict) for r in rows):
        raise InputError(f"{NAME}.events", "must be [[match.events]] tables", src)
    if len(rows) > MAX_EVENT_ROWS:
        raise InputError(f"{NAME}.events", f"has {len(rows)} events; at most {MAX_EVENT_ROWS}", src)
    length = values["length"]
    from ..match.mechanisms import MAX_LENGTH

    if not 0 < length <= MAX_LENGTH:
        raise InputError(
            f"{NAME}.length", f"must be above 0 s and at most {MAX_LENGTH:g} s, got {length:g} s", src
        )
    events = [_event(i, r, wb, length) for i, r in enumerate(rows, 1)]
    for ev in events:  # its channel's outputs <card>_breaker_* beside the main breaker's main_breaker_*
        if ev.card == "main":
            raise InputError(
                f"{NAME}.events[{ev.index}].card",
                "a card named 'main' would give its channel breaker the main breaker's outputs "
                "(main_breaker_margin, ...); rename it",
                src,
            )
    spec = MatchSpec(values, controller, ocv, events, src, main_breaker, channel_table)
    moves = sum(1 for _ in spec.occurrences())
    if moves > MAX_MOVES:
        raise InputError(
            f"{NAME}.events", f"asks {moves} moves in {length:g} s; at most {MAX_MOVES} on the bus", src
        )
    return spec


def _static_scope(wb: Workbook) -> Scope:
    """The variables as the kinds check sees them (dimensions only), for checking references."""
    scope = Scope({}, {}, {}, static=True, workbook=wb)
    for node in wb.order:
        if node in wb.variables:
            v = wb.variables[node]
            if v.expr is not None:
                scope.variables[node] = evaluate(v.expr, scope, f"variables.{node}", wb.source)
            else:
                scope.variables[node] = literal_value(v)
    return scope


def _scalar(where: str, value: Any, unit: str, ref: bool, wb: Workbook, static: Scope | None) -> Any:
    """A float in `unit`, or (a reference) its Expr, checked for its kind now."""
    src = wb.source
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise InputError(
            where, f"must be a number or a quantity ({unit or 'no unit'}), got {shown(value)}", src
        )
    if isinstance(value, (int, float)):
        return _finite(where, value, src)
    text = value.strip()
    if text.startswith("="):
        if not ref:
            raise InputError(where, "takes a number or a quantity, not a reference", src)
        expr = parse_expression(text[1:], where, src)
        cards = expr.references(set(wb.cards))
        if cards:
            raise InputError(
                where, f"reads the card {sorted(cards)[0]}: the match's entries read variables", src
            )
        _in_unit(where, evaluate(expr, static, where, src), unit, src)
        return expr
    expr = parse_expression(text, where, src)
    if expr.references(set(wb.variables) | set(wb.cards)):
        raise InputError(where, f'names a variable: write it "= {text}"', src)
    return _in_unit(where, evaluate(expr, Scope({}, {}, {}), where, src), unit, src)


def _finite(where: str, x: Any, src: str) -> float:
    try:
        f = float(x)
    except OverflowError:
        raise InputError(where, f"{shown(x)} is too large for a number", src) from None
    if not math.isfinite(f):
        raise InputError(where, f"{shown(x)} is not a finite number", src)
    return f


def _in_unit(where: str, q: Any, unit: str, src: str) -> float:
    import pint

    if isinstance(q, (str, bool)):
        raise InputError(where, f"must be a number or a quantity ({unit or 'no unit'}), got {shown(q)}", src)
    if not hasattr(q, "to"):
        return _finite(where, q, src)
    try:
        return _finite(where, float(q.to(unit or "dimensionless").magnitude), src)
    except pint.errors.DimensionalityError:
        raise InputError(
            where, f"must be in {unit or 'no unit (a plain number or %)'}, got {q.units:~}", src
        ) from None


def _event(i: int, data: dict, wb: Workbook, length: float) -> Event:
    src = wb.source
    where = f"{NAME}.events[{i}]"
    for key in data:
        if key not in EVENT_KEYS:
            raise InputError(f"{where}.{key}", f"unknown key of an event ({', '.join(EVENT_KEYS)})", src)
    for key in ("at", "card"):
        if key not in data:
            raise InputError(f"{where}.{key}", "missing", src)
    at = _scalar(f"{where}.at", data["at"], "s", False, wb, None)
    if at < 0:
        raise InputError(f"{where}.at", f"must be ≥ 0 s, got {at:g} s", src)
    if at >= length:
        raise InputError(f"{where}.at", f"is {at:g} s, at or past the match's end ({length:g} s)", src)
    card = data["card"]
    if not isinstance(card, str) or card not in wb.cards:
        known = ", ".join(wb.cards) or "none"
        raise InputError(f"{where}.card", f"{shown(card)} is not a card (cards: {known})", src)
    calc = wb.cards[card].calculator
    if calc not in ON_BUS:
        why = NOT_ON_BUS
        if calc == "pneumatics":  # its card models the air (flow curves), not the compressor's current
            why += ": the pneumatics card has no compressor current to draw"
        raise InputError(f"{where}.card", f"{card} ({calc}) is {why}", src)
    mode_field, runs, actions = ON_BUS[calc]
    if mode_field is not None:
        mode = wb.cards[card].inputs.get(mode_field, runs)
        if mode_field not in wb.cards[card].links and mode != runs:
            raise InputError(
                f"{where}.card", f"{card} is in mode {shown(mode)}; the match runs mode = {runs}", src
            )
    action = data.get("action", default_action(calc))
    if action not in actions:
        raise InputError(
            f"{where}.action",
            f"must be one of {', '.join(actions)} for {card} ({calc}), got {shown(action)}",
            src,
        )
    every = None
    if "every" in data:
        every = _scalar(f"{where}.every", data["every"], "s", False, wb, None)
        if every <= 0:
            raise InputError(f"{where}.every", f"must be > 0 s, got {every:g} s", src)
    count = data.get("count", 1 if every is None else None)
    if count is None:  # every without count: until the end
        count = int(min((length - at) / every, 1e9)) + 1
        if count > MAX_MOVES:
            raise InputError(
                f"{where}.every",
                f"repeats {count} times in the match; at most {MAX_MOVES} moves on the bus",
                src,
            )
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise InputError(f"{where}.count", f"must be a whole number ≥ 1, got {shown(count)}", src)
    if count > 1 and every is None:
        raise InputError(f"{where}.every", "missing: a count above 1 needs the time between repeats", src)
    if count > MAX_MOVES:
        raise InputError(f"{where}.count", f"is {count}; at most {MAX_MOVES} moves on the bus", src)
    return Event(i, at, card, action, every, count)


# ---------------------------------------------------------------------------------------------
# Running it


@dataclass
class Brownout:
    start: float
    end: float
    running: tuple[str, ...]

    @property
    def length(self) -> float:
        return self.end - self.start


@dataclass
class MatchOutcome:
    """The match's run and its outputs (SI inside; Ah and Wh where named)."""

    spec: MatchSpec
    moves: list  # (time asked, Event, MechanismResult)
    bus: Any  # core.match.mechanisms.BusResult
    battery: Any
    controller: Any
    base_load: float
    outputs: dict[str, float] = field(default_factory=dict)
    running_at_min: tuple[str, ...] = ()
    brownouts: list[Brownout] = field(default_factory=list)
    shares: dict[str, float] = field(default_factory=dict)  # card (and "base") -> fraction of the charge
    channel_peaks: dict[str, float] = field(default_factory=dict)  # card -> peak supply A per motor

    def as_json(self) -> dict[str, Any]:
        cards = set(self.bus.channels)
        return {
            "outputs": {k: {"value": v, "unit": output_info(k, cards)[1]} for k, v in self.outputs.items()},
            "min_bus_running": list(self.running_at_min),
            "brownouts": [
                {"start": b.start, "end": b.end, "length": b.length, "running": list(b.running)}
                for b in self.brownouts
            ],
            "shares": self.shares,
            "channel_peak_supply_current": self.channel_peaks,
            "moves": [
                {
                    "card": ev.card,
                    "action": ev.action,
                    "event": ev.index,
                    "asked": t,
                    "start": r.start if r.trace else None,
                    "arrival": r.arrival,
                    "peak_stator_current": r.peak_stator_current,
                    "peak_supply_current": r.peak_supply_current,
                    **({"ball_speeds": [V for _, V, _, _ in r.shots]} if r.shots else {}),
                }
                for t, ev, r in self.moves
            ],
        }


def run(spec: MatchSpec, wb: Workbook, scope: Scope, cards: dict) -> MatchOutcome:
    """The match at the solved workbook (`scope` its values, `cards` its CardResults)."""
    from ..match.battery import Battery
    from ..match.brownout import BROWNOUT_VOLTS, RECOVERY_VOLTS, Controller
    from ..match.mechanisms import MechanismMatch, MechanismMove

    src = spec.source
    vals = {}
    for key, value in spec.values.items():
        if isinstance(value, Expr):
            value = _in_unit(f"{NAME}.{key}", evaluate(value, scope, f"{NAME}.{key}", src), KEYS[key][0], src)
        vals[key] = value
    try:
        battery = Battery(
            **({"ocv_table": spec.ocv} if spec.ocv is not None else {}),
            resistance=vals["resistance"],
            wiring_resistance=vals["wiring_resistance"],
            capacity_ah=vals["capacity"],
            peukert=vals["peukert"],
            start_soc=vals["charge"],
        )
    except InputError as exc:
        names = {"battery.capacity_ah": "capacity", "battery.start_soc": "charge"}
        key = names.get(exc.field, exc.field.removeprefix("battery."))
        raise InputError(f"{NAME}.{key}", exc.message, src) from None
    b = vals["brownout"] if vals["brownout"] is not None else BROWNOUT_VOLTS[spec.controller]
    r = vals["recovery"] if vals["recovery"] is not None else RECOVERY_VOLTS
    try:
        controller = Controller(brownout=b, recovery=r)
    except InputError as exc:
        raise InputError(f"{NAME}.{exc.field.removeprefix('controller.')}", exc.message, src) from None
    occ, stops, last = [], {}, {}
    for t, ev in spec.occurrences():
        if ev.action == "stop":  # the card's last move asked stops holding (B10); none yet: nothing to stop
            if ev.card in last:
                stops.setdefault(last[ev.card], t)
            continue
        last[ev.card] = len(occ)
        occ.append((t, ev))
    moves, last = [], {}
    for k, (t, ev) in enumerate(occ):
        where = f"{NAME}.events[{ev.index}] ({ev.card} at {t:g} s)"
        card = cards[ev.card]
        if card.error is not None:
            raise InputError(where, f"the card {ev.card} could not be solved ({card.error})", src)
        try:
            setup = _setup(card.calculator, card.entries, ev.action)
        except InputError as exc:
            raise InputError(where, f"{exc.field}: {exc.message}", src) from None
        moves.append(
            MechanismMove(
                f"{ev.card}#{k}",
                setup,
                t,
                after=last.get(ev.card),
                channel=ev.card,
                hold=card.calculator in HOLDING,
                release=stops.get(k),
                hard_stops=card.calculator in ("elevator", "arm"),
                carry=card.calculator == "flywheel",  # still spinning from its last move (B13)
            )
        )
        last[ev.card] = k
    from ..match.breaker import Breaker

    channel = Breaker(vals["channel_rating"], spec.channel_table or (), name="channel_breaker")
    match = MechanismMatch(
        tuple(moves), battery, controller, vals["length"], vals["base_load"], channel_breaker=channel
    )
    try:
        bus = match.run()
    except InputError as exc:
        raise InputError(_where_move(exc.field, occ), exc.message, src) from None
    return _outcome(spec, occ, bus, battery, controller, vals)


def _where_move(fieldname: str, occ) -> str:
    """moves[k].x → match.events[i] (card at t s).x"""
    if fieldname.startswith("moves[") and "]" in fieldname:
        k = int(fieldname[6 : fieldname.index("]")])
        t, ev = occ[k]
        return f"{NAME}.events[{ev.index}] ({ev.card} at {t:g} s){fieldname[fieldname.index(']') + 1 :]}"
    return f"{NAME}.{fieldname}"


def _setup(calc_id: str, raw: dict, action: str):
    """The card's scene from its solved entries (core.match.mechanisms.scene_of); an elevator's or
    arm's `return` swaps its start and goal (a sprint's is the same sprint, driven back)."""
    from ..match.mechanisms import burst, scene_of
    from ..model import parse_inputs
    from ..registry import get

    v = parse_inputs(get(calc_id), raw)[0]
    if action == "burst":  # the flywheel's: its spin-up, then its shots (mechanisms.py (B11))
        return burst(v)
    if action == "return":
        if calc_id == "elevator":
            v["travel"] = -v["travel"]
        elif calc_id == "arm":
            v["start_angle"], v["goal_angle"] = v["goal_angle"], v["start_angle"]
    return scene_of(calc_id, v)


def _below(trace, level: float) -> float:
    """Time the bus spent below `level`, linear between the trace's samples."""
    total = 0.0
    for (t0, v0, _), (t1, v1, _) in zip(trace, trace[1:]):
        if t1 <= t0:
            continue
        if v0 < level and v1 < level:
            total += t1 - t0
        elif (v0 < level) != (v1 < level):
            x = t0 + (level - v0) * (t1 - t0) / (v1 - v0)
            total += (x - t0) if v0 < level else (t1 - x)
    return total


def _running(moves, t: float) -> tuple[str, ...]:
    out = []
    for _, ev, r in moves:
        if r.trace and r.start <= t and (r.arrival is None or r.arrival >= t):
            label = f"{ev.card} {ev.action}"
            if label not in out:
                out.append(label)
    return tuple(out)


def _breaker(brk, trace) -> dict[str, float]:
    """The main breaker's thermal state (breaker.py (M12)) along the battery current: each step of
    the trace advanced exactly at the step's mean current (the trace holds every solver step and
    switch, so the current is nearly constant over one). Margin 1 − θ_max, in %; the first time θ
    reaches 1 (a trip; the run does not cut the load)."""
    if brk is None:
        return {}
    theta, top, trip = 0.0, 0.0, None
    for (t0, _, i0), (t1, _, i1) in zip(trace, trace[1:]):
        if t1 <= t0:
            continue
        theta = brk.advance(theta, 0.5 * (i0 + i1), t1 - t0)
        if theta > top:
            top = theta
        if trip is None and theta >= 1.0:
            trip = t1
    out = {"main_breaker_margin": 100.0 * (1.0 - top)}
    if trip is not None:
        out["main_breaker_trip"] = trip
    return out


def _outcome(spec, occ, bus, battery, controller, vals) -> MatchOutcome:
    from ..match.battery import AH
    from ..match.breaker import MAIN_RATING

    length = vals["length"]
    moves = [(t, ev, r) for (t, ev), r in zip(occ, bus.mechanisms)]
    trace = bus.trace
    peak = max((abs(i) for _, _, i in trace), default=vals["base_load"])
    end_soc = battery.soc(bus.charge)
    o = {
        "min_bus_voltage": bus.min_bus_voltage,
        "min_bus_time": bus.min_bus_time,
        "time_below_brownout": _below(trace, controller.brownout),
        "brownouts": len(bus.brownouts),
        "brownout_time": float(sum(e - s for s, e in bus.brownouts)),
        "charge_used": bus.charge / AH,
        "peukert_charge_used": bus.peukert_charge / AH,
        "energy": bus.energy_oc / 3600.0,
        "end_charge": 100.0 * end_soc,
        "end_available": 100.0 * battery.soc(bus.peukert_charge),
        "end_voltage": battery.ocv(end_soc),
        "peak_current": peak,
        "rms_current": math.sqrt(max(bus.current_squared, 0.0) / length),
        "main_breaker_load": 100.0 * peak / MAIN_RATING,
        **_breaker(spec.main_breaker, trace),
        "moves": sum(1 for *_, r in moves if r.arrival is not None),
        "unfinished": sum(1 for *_, r in moves if r.arrival is None),
    }
    for card, ch in bus.channels.items():  # (B9): match.<card>_breaker_load, _margin, _trip
        o[f"{card}_breaker_load"] = 100.0 * ch.peak / ch.rating
        if ch.theta_max is not None:
            o[f"{card}_breaker_margin"] = 100.0 * (1.0 - ch.theta_max)
        if ch.trip_time is not None:
            o[f"{card}_breaker_trip"] = ch.trip_time
    shares: dict[str, float] = {}
    peaks: dict[str, float] = {}
    for _, ev, r in moves:
        shares[ev.card] = shares.get(ev.card, 0.0) + r.charge
        peaks[ev.card] = max(peaks.get(ev.card, 0.0), r.peak_supply_current)
    shares["base"] = vals["base_load"] * length
    # of the parts' sum: the moves' charges are summed on the trace (mechanisms.py), within ~0.1 % of
    # the integrated whole, so the shares add up to 1 exactly
    total = sum(shares.values())
    shares = {k: (q / total if total > 0 else 0.0) for k, q in shares.items()}
    out = MatchOutcome(spec, moves, bus, battery, controller, vals["base_load"], o)
    out.running_at_min = _running(moves, bus.min_bus_time)
    out.brownouts = [Brownout(s, e, _running(moves, s)) for s, e in bus.brownouts]
    out.shares = shares
    out.channel_peaks = peaks
    return out


def summary(m) -> list[str]:
    """The match's outputs as lines (tui: `gearhead match` and `gearhead solve ROBOT.toml`): each output
    with its label, then each card's share of the charge and its channel breaker."""
    from .. import units
    from ..errors import printable

    o = m.outputs
    out: list[str] = []
    width = max(len(label) for label, _ in OUTPUTS.values())
    for key, (label, unit) in OUTPUTS.items():  # the channels' own outputs are shown with the shares
        if key not in o:  # the breaker's margin without a trip table, its trip time without a trip
            continue
        value = o[key]
        text = f"{value:d}" if isinstance(value, int) else f"{units.format_number(value)} {unit}".rstrip()
        if key == "min_bus_time" and m.running_at_min:
            text += f"  ({', '.join(m.running_at_min)} running)"
        out.append(f"  {label:<{width}}  {text}")
    rating = m.spec.values["channel_rating"]
    out.append(f"  Charge share; peak supply current per motor, either way (of a {rating:g} A breaker)")
    for k, v in m.shares.items():
        ch = m.bus.channels.get(k)  # either direction: a motor braking a falling load drives current back
        more = f"   peak {ch.peak:.4g} A ({ch.peak / rating * 100:.3g} %)" if ch is not None else ""
        if f"{k}_breaker_trip" in o:
            more += f"; trips at {units.format_number(o[f'{k}_breaker_trip'])} s"
        elif f"{k}_breaker_margin" in o:
            more += f"; margin {units.format_number(o[f'{k}_breaker_margin'])} %"
        out.append(f"    {printable(k):<12} {v * 100:6.3g} %{more}")
    if "main_breaker_margin" not in o and m.spec.channel_table is None:
        out.append("  (no breaker trip table entered, so no trip is predicted)")
    elif m.spec.channel_table is None:
        out.append("  (no channel breaker trip table entered: no channel trip is predicted)")
    elif "main_breaker_margin" not in o:
        out.append("  (no main breaker trip table entered: no main breaker trip is predicted)")
    return out
