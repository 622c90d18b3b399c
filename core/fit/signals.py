"""Picking a SysId routine's signals from a log and putting them in the card's units (issue 44 item 2).

WPILib's SysIdRoutineLog (allwpilib wpilibj .../sysid/SysIdRoutineLog.java, wpilibc SysIdRoutineLog.cpp;
robotpy's wpilib.sysid wraps the C++) writes, for a routine `mech` and a motor `motor`:
    sysid-test-state-<mech>    string: quasistatic-forward, quasistatic-reverse, dynamic-forward,
                               dynamic-reverse, none
    voltage-<motor>-<mech>, position-<motor>-<mech>, velocity-<motor>-<mech>, current-<motor>-<mech>
                               double, the unit in the entry's metadata: Java writes the unit's
                               name ("Volt", "Meter", "Rotation", "Meter per Second", "Rotation per
                               Second", "Amp"), C++ and Python its singular name ("volt", "meter",
                               "turn", "meters_per_second", "turns_per_second", "ampere")      (S1)
AdvantageKit logs the state as a string entry ending in "SysIdTestState" (same values); its voltage,
position and velocity are named by the user (--voltage, --position, --velocity).
Runs as SysId's DataSelector::LoadTests splits them: a run of a state starts at its first record
and ends at the next record of another state; SysId analyses the first run of each state    (S2)
Units: positions to metres (elevator) or radians (arm, flywheel), velocities per second; an
elevator logged in rotations is taken as spool rotations (m = rad·r·k, the card's spool)     (S3)
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from . import logs

STATES = ("quasistatic-forward", "quasistatic-reverse", "dynamic-forward", "dynamic-reverse")
KINDS = ("elevator", "arm", "flywheel")
_PATTERN = re.compile(r"^(voltage|position|velocity|current)-(.+)-(.+)$")
BUS_SUFFIX = "SystemStats/BatteryVoltage"  # AdvantageKit's; WPILib's SysId routine logs no bus voltage

# (S1): the normalised unit name -> (quantity, factor to SI)
_UNITS = {
    "meter": ("length", 1.0),
    "m": ("length", 1.0),
    "rotation": ("angle", 2 * math.pi),
    "turn": ("angle", 2 * math.pi),
    "rev": ("angle", 2 * math.pi),
    "revolution": ("angle", 2 * math.pi),
    "radian": ("angle", 1.0),
    "rad": ("angle", 1.0),
    "degree": ("angle", math.pi / 180),
    "deg": ("angle", math.pi / 180),
}


def _normalise(unit: str) -> str:
    words = [w for w in re.split(r"[\s_]+", unit.strip().lower()) if w]
    return " ".join(w[:-1] if len(w) > 3 and w.endswith("s") else w for w in words)


def unit_factor(unit: str, rate: bool, where: str, source: str) -> tuple[str, float]:
    """(quantity, factor to SI) of a position (rate False) or velocity unit name (S1)."""
    u = _normalise(unit)
    if rate:
        for tail in (" per second", "/s", "ps"):
            if u.endswith(tail):
                u = u[: -len(tail)].strip()
                break
        else:
            u = {"mps": "m", "tps": "turn", "rps": "rotation"}.get(u, "?")
        u = {"t": "turn"}.get(u, u)
    if u not in _UNITS:
        raise InputError(
            where,
            f"has the unit {unit[:40]!r}, which cannot be converted (meters, rotations, radians or degrees"
            f"{' per second' if rate else ''}; give the unit with --units)",
            source,
        )
    return _UNITS[u]


@dataclass
class Run:
    """One test's samples (S2), in the card's SI units."""

    state: str
    t_voltage: np.ndarray
    voltage: np.ndarray
    t_position: np.ndarray
    position: np.ndarray
    t_velocity: np.ndarray
    velocity: np.ndarray


@dataclass
class Picked:
    source: str
    kind: str
    names: dict[str, str]  # role -> entry name
    units: dict[str, str]  # role -> the unit read
    runs: dict[str, Run]
    notes: list[str] = field(default_factory=list)
    current: tuple[np.ndarray, np.ndarray] | None = None  # the motor's (stator) current, A
    bus: tuple[np.ndarray, np.ndarray] | None = None  # the bus (battery) voltage, V


def _base(name: str) -> str:
    return name.rsplit("/", 1)[-1]


def _resolve(name: str, sigs) -> str:
    """A name given (--voltage ...) as the log's: as typed, else as shown (logs.shown_name: a name
    typed with its raw bytes, or with a backslash the log's name shows doubled)."""
    return name if name in sigs or logs.shown_name(name) not in sigs else logs.shown_name(name)


def _wanted(named: dict[str, str | None]):
    explicit = {v for v in named.values() if v} | {logs.shown_name(v) for v in named.values() if v}

    def wanted(name: str) -> bool:
        return (
            name in explicit
            or _base(name).startswith("sysid-test-state-")
            or name.endswith("SysIdTestState")
            or _PATTERN.match(_base(name)) is not None
            or name.endswith(BUS_SUFFIX)
        )

    return wanted


def pick(
    path,
    kind: str,
    *,
    routine: str | None = None,
    motor: str | None = None,
    voltage: str | None = None,
    position: str | None = None,
    velocity: str | None = None,
    state: str | None = None,
    current: str | None = None,
    bus_voltage: str | None = None,
    units: str | None = None,
    scale: float = 1.0,
    spool: float | None = None,
) -> Picked:
    """The routine's signals found (S1) or as named, split into runs (S2), in SI (S3).
    `units`: the position unit when the log has none (a CSV) or to override it; `scale`: SysId's
    position/velocity scaling; `spool`: metres per spool radian (an elevator logged in rotations)."""
    source = str(path)
    named = {
        "voltage": voltage,
        "position": position,
        "velocity": velocity,
        "state": state,
        "current": current,
        "bus_voltage": bus_voltage,
    }
    sigs, entries, warnings = logs.read(path, _wanted(named))
    notes = list(warnings)
    states = [n for n in sigs if _base(n).startswith("sysid-test-state-") or n.endswith("SysIdTestState")]
    if state is None:
        if routine is not None:
            mine = [n for n in states if _base(n) == f"sysid-test-state-{routine}"]
            state = mine[0] if mine else f"sysid-test-state-{routine}"
        elif len(states) == 1:
            state = states[0]
        elif not states:
            raise InputError(
                "log", "has no SysId test state (sysid-test-state-…); name it with --state", source
            )
        else:
            raise InputError(
                "log",
                f"holds {len(states)} SysId routines ({', '.join(sorted(states))}); choose one with --routine",
                source,
            )
    state = _resolve(state, sigs)
    if state not in sigs:
        raise InputError("--state", f"{logs.quoted(state)} is not in the log", source)
    base = _base(state)
    prefix = state[: len(state) - len(base)]  # a CSV export may put the log's entries under a folder
    mech = base.removeprefix("sysid-test-state-") if base.startswith("sysid-test-state-") else None
    found: dict[str, list[tuple[str, str]]] = {}
    for name in sigs:
        m = _PATTERN.match(_base(name))
        if m and mech is not None and m[3] == mech and name.startswith(prefix):
            found.setdefault(m[2], []).append((m[1], name))
    if motor is None and found and not all(named[r] for r in ("voltage", "position", "velocity")):
        with_voltage = sorted(k for k, v in found.items() if any(r == "voltage" for r, _ in v))
        if not with_voltage:
            raise InputError("log", f"routine {logs.quoted(mech)} logs no voltage-<motor>-{mech}", source)
        motor = with_voltage[0]
        if len(with_voltage) > 1:
            notes.append(
                f"motors logged: {', '.join(with_voltage)}; fitted from {logs.quoted(motor)} (choose with --motor)"
            )
    names = {"state": state}
    for role in ("voltage", "position", "velocity", "current"):
        name = named[role] or (f"{prefix}{role}-{motor}-{mech}" if motor and mech else None)
        if name is not None:
            name = _resolve(name, sigs)
        if name is None or name not in sigs:
            if role == "current":
                continue
            if role == "position" and kind == "flywheel" and name is None:
                continue
            raise InputError(
                f"--{role}",
                f"no entry {logs.quoted(name)} in the log"
                if name
                else f"no {role} signal found; name it with --{role}",
                source,
            )
        names[role] = name
    for role, name in names.items():
        s = sigs[name]
        if role == "state":
            if s.numeric():
                raise InputError(state, "holds numbers, not the test's state names", source)
        elif not s.numeric():
            k = next((k for k, v in enumerate(s.values) if not logs.is_number(v)), 0)
            at = f": {s.values[k][:40]!r} at t = {s.times[k]:g} s" if s.values else ""
            raise InputError(name, f"holds text, not the {role}'s numbers{at}", source)
    unit_names: dict[str, str] = {}
    factors: dict[str, float] = {}
    for role, rate in (("position", False), ("velocity", True)):
        if role not in names:
            continue
        meta = sigs[names[role]].metadata.strip()
        if units:
            unit = units + (" per second" if rate else "")
        elif meta and not meta.startswith("{"):
            unit = meta
        else:
            unit = {"elevator": "meter", "sprint": "meter"}.get(kind, "rotation") + (
                " per second" if rate else ""
            )
            notes.append(f"{names[role]}: no unit in the log; taken as {unit} (give --units)")
        quantity, k = unit_factor(unit, rate, names[role], source)
        if kind in ("elevator", "sprint") and quantity == "angle":
            if spool is None:
                raise InputError(
                    names[role], f"is in {unit}; an {kind} needs a length (give --units)", source
                )
            k *= spool
            of = "the spool, × r·k" if kind == "elevator" else "the wheel, × its radius"
            notes.append(f"{names[role]}: {unit} of {of} = {spool:.4g} m per radian")
        elif kind not in ("elevator", "sprint") and quantity == "length":
            raise InputError(names[role], f"is in {unit}; an {kind} turns: give its angle", source)
        unit_names[role] = unit
        factors[role] = k * scale
    meta = sigs[names["voltage"]].metadata.strip().lower()
    if meta and not meta.startswith("{") and _normalise(meta) not in ("volt", "v"):
        raise InputError(names["voltage"], f"has the unit {meta!r}; a voltage in volts is needed", source)
    if "current" in names:
        _unit_is(sigs[names["current"]], ("amp", "ampere", "a"), "a current in amps", source)
    runs = _runs(sigs, names, factors, source)
    cur = None
    if "current" in names:
        c = sigs[names["current"]]
        cur = (np.asarray(c.times, dtype=float), np.asarray(c.values, dtype=float))
    bus = None
    found_bus = [n for n in sigs if n.endswith(BUS_SUFFIX)]
    bus_name = bus_voltage or (found_bus[0] if len(found_bus) == 1 else None)
    if bus_name is not None:
        bus_name = _resolve(bus_name, sigs)
        if bus_name not in sigs:
            raise InputError("--bus-voltage", f"no entry {logs.quoted(bus_name)} in the log", source)
        b = sigs[bus_name]
        if not b.numeric():
            raise InputError(bus_name, "holds text, not the bus voltage's numbers", source)
        _unit_is(b, ("volt", "v"), "a voltage in volts", source)
        names["bus_voltage"] = bus_name
        bus = (np.asarray(b.times, dtype=float), np.asarray(b.values, dtype=float))
    return Picked(source, kind, names, unit_names, runs, notes, cur, bus)


def _unit_is(sig, ok: tuple[str, ...], what: str, source: str) -> None:
    """Refuse a signal whose unit metadata (S1) names another quantity (a current read as volts)."""
    m = sig.metadata.strip()
    if m and not m.startswith("{") and _normalise(m) not in ok:
        raise InputError(sig.name, f"has the unit {m[:40]!r}; {what} is needed", source)


def _runs(sigs, names, factors, source) -> dict[str, Run]:
    """The first run of each state (S2)."""
    st = sigs[names["state"]]
    texts = st.values if isinstance(st.values, logs.Texts) else logs.Texts.of(st.values)
    codes, table = texts.codes, texts.table
    # each signal is sorted by time: its last sample is its latest
    last = max((sigs[n].times[-1] if len(sigs[n].times) else 0.0) for n in names.values()) + 1.0
    # the runs: where the state changes; a run ends at the next run's first record (S2)
    starts = np.flatnonzero(np.concatenate(([True], codes[1:] != codes[:-1]))) if len(codes) else codes
    at = starts.tolist()
    first: dict[str, tuple[float, float]] = {}
    for r, c in enumerate(codes[starts].tolist()):
        state = table[c]
        if state in STATES and state not in first:
            end = st.times[at[r + 1]] if r + 1 < len(at) else last
            first[state] = (st.times[at[r]], end)
            if len(first) == len(STATES):
                break
    missing = [s for s in STATES if s not in first]
    if missing:
        seen = sorted(set(table)) or ["none"]
        raise InputError(
            names["state"],
            f"never runs {', '.join(missing)} (states logged: {', '.join(seen)}); SysId needs all four tests",
            source,
        )

    def cut(role, a, b):
        if role not in names:
            return np.zeros(0), np.zeros(0)
        s = sigs[names[role]]
        t = np.asarray(s.times, dtype=float)
        v = np.asarray(s.values, dtype=float)
        i, j = np.searchsorted(t, a, "left"), np.searchsorted(t, b, "left")
        with np.errstate(over="ignore"):
            got = v[i:j] * factors.get(role, 1.0)
        if not np.all(np.isfinite(got)):  # --scale (or a unit's factor) past the float range
            raise InputError(
                names[role],
                f"overflows when scaled to SI (× {factors.get(role, 1.0):.3g}, --scale included): "
                f"its values reach {float(np.max(np.abs(v[i:j]))):.3g}",
                source,
            )
        return t[i:j].copy(), got

    out = {}
    for s, (a, b) in first.items():
        tv, vv = cut("voltage", a, b)
        tp, pp = cut("position", a, b)
        tw, ww = cut("velocity", a, b)
        if "position" not in names:  # a flywheel without position: the velocity's integral stands in
            tp, pp = tw, np.concatenate(([0.0], np.cumsum(0.5 * (ww[1:] + ww[:-1]) * np.diff(tw))))
        for role, t in (("voltage", tv), ("position", tp), ("velocity", tw)):
            if len(t) < 2:
                raise InputError(
                    names.get(role, role),
                    f"has {len(t)} samples in the {s} test; at least 2 are needed",
                    source,
                )
        out[s] = Run(s, tv, vv, tp, pp, tw, ww)
    return out
