"""Mechanisms on the match's bus: the elevator's and the arm's full-voltage moves (core.sim.motion,
`mode = move`) integrated together with the battery, every supply current drawn from one bus.

Each mechanism k (N_k motors alike, R, Kv, n, M, η·N·Kt·n = the card's force per amp) keeps its
card's state: p_k the travel toward its goal, w_k the speed toward it, E_k = w_k·n/Kv its back-EMF.
At each evaluation the bus voltage V is solved from ALL supply currents together (bus.py (M6-M9)),
then every mechanism's derivative is its card's (motion.py (M4)) at that bus voltage:

    M·ẇ = η·N·Kt·n·I + s·F_field(q) − F_friction·sgn(w)                                     (B1)

The duty rule per motor, written in V (the controller sees the bus it is on). At duty u the motor
takes I = (u·V − E)/R (motion (M2)) and the supply u·I; u·I = u·(u·V − E)/R rises with u wherever
I ≥ 0 (its u-derivative is (2u·V − E)/R ≥ (u·V − E)/R), so lowering the duty to meet a limit
lowers the supply current, and the supply current the rule gives is the least of its branches:

    I_s(V) = min( I_full(V), I_stator(V), I_supply(V) )   (the limits that are on)           (B2)
    full duty, u = 1:         I_full   = (V − E)/R                 affine:  a = −E/R, b = 1/R   (B3)
    stator limit, I = I_st:   u = (E + R·I_st)/V,  I_stator = u·I_st = (E + R·I_st)·I_st/V
                                                       constant power:  p = (E + R·I_st)·I_st   (B4)
    supply limit, u·I = I_sup: I_supply = I_sup     constant current:  a = I_sup
        (its stator current: R·I² + E·I − I_sup·V = 0, I = 2·I_sup·V/(E + √(E² + 4·R·I_sup·V)))  (B5)

(tests/test_match_mechanisms.py derives (B3)-(B5) with sympy.) With N motors each term is N times.
The card solves the same rule with its bus V = V_b − R_bus·u·I, R_bus = N·R_batt (motion (E1)-(E3)):
one card alone on a battery of V_oc = V_b and R = R_batt draws N·I_s from it, V = V_b − R·N·I_s,
the same equation; the card's smaller duty root of (E2) is the larger V root of (B4), and where its
roots merge (motion (E6)) the card's jump to full duty is the only root left (B6). So one mechanism
alone here is its card.

The bus: V = V_oc − R·(I_base + Σ_k N_k·I_s,k(V)), I_base the base load. G(V) = V − V_oc + R·ΣI is
continuous; between the breakpoints where two branches of a motor meet (V = E + R·I_st,
V = E + R·I_sup, V = (E + R·I_st)·I_st/I_sup) every motor's branch is fixed and the sum has the form
a + b·V + p/V of (M6), whose roots are bus.solve_bus's (M7-M8). Every root in its interval is
an operating point; the one taken is the nearest to the bus an instant before (M9; the highest at
the start, the card's choice):                                                               (B6)
the configuration (each motor's branch, which root of the quadratic) is then held for a piece of
the integration, and the integrator's events end the piece where it stops holding: a held branch
stops being the least (the other branch's value minus the held one's falls through 0), the held
quadratic's discriminant falls through 0 (roots merging), the bus crosses the brownout voltage, a
mechanism reaches its goal, a speed crosses 0 (friction turns). So every switch is located in time,
and the peaks of supply current (at a branch point, motion's extremes) are read at the switch.

Brownout (brownout.py (M10)): below the brownout voltage the roboRIO disables its outputs: a
mechanism whose event `brownout_disables` coasts, its controllers' bridges off: no stator current,
no supply current (conduction through the bridge's diodes when |E| exceeds the bus is not modelled),
only gravity (F_field) and friction act: the elevator falls if its weight beats its friction. After
at least the dwell, the bus rising past the recovery voltage enables them again (at the speed they
have then, falling or not). A mechanism at rest stays at rest while |η·N·Kt·n·I + s·F_field| ≤ its
friction (stuck; w = 0).
If the bus has no operating point at all (G > 0 for every V > 0: a motor driven backwards, E < 0,
so fast that at full duty it would draw more than the battery gives at any voltage) the bus is
taken to collapse: the outputs are disabled as in a brownout.

At the goal a mechanism's move ends (as the card's does): it draws nothing after (holding there is
not modelled here). Energy: dE_oc/dt = V_oc·I, dE_bus/dt = V·I, dE_R/dt = R·I² (battery (M5)), and
each mechanism's ∫V_oc·N·I_s dt (the card's energy, its EMF times its current, when V_oc = V_b).
The state's tail (after the moves' 4 + 3n) integrates what the match's outputs need besides: the
Peukert-weighted charge (battery (M4)) and ∫I²dt (the RMS current); each move's charge ∫N·I_s dt (its
share) is summed by the trapezoid rule on the trace (every accepted step and switch). A move given `after` (queued) starts at its time or when that earlier move reaches its goal.
Bounded: every step is charged to the solve's budget (core.sim.integrate), at most MAX_PIECES
pieces and MAX_MECHANISMS mechanisms; every input checked (InputError names the field).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from gearhead.core.errors import InputError, shown
from gearhead.core.match.battery import Battery
from gearhead.core.match.brownout import Controller
from gearhead.core.match.bus import solve_bus
from gearhead.core.match.checks import number
from gearhead.core.sim import motion
from gearhead.core.sim.integrate import Event, charge, integrate

MAX_MECHANISMS = 200
MAX_PIECES = 50_000
MAX_STEPS = 200_000  # per piece (DP54)
MAX_LENGTH = 3600.0
LIMIT_EFFECTS = ("stator_limit", "supply_limit")
FULL, STATOR, SUPPLY, COAST, DONE = "full", "stator", "supply", "coast", "done"


@dataclass(frozen=True)
class MechanismMove:
    """One card's move (core.sim.motion Setup, `mode = move`) started at `start` (s)."""

    name: str
    setup: Any
    start: float = 0.0
    brownout_disables: bool = True
    after: int | None = None  # the index of a move this one waits for (queued: starts at its arrival)


def from_card(calc_id: str, raw: dict, name: str | None = None, start: float = 0.0) -> MechanismMove:
    """A MechanismMove from a card's inputs (`elevator` or `arm`, as model.solve takes them)."""
    from gearhead.core.calculators import arm, elevator
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get

    scenes = {"elevator": elevator, "arm": arm}
    if calc_id not in scenes:
        raise InputError("card", f"must be one of {', '.join(scenes)}, got {shown(calc_id)}")
    v = parse_inputs(get(calc_id), raw)[0]
    if v["mode"] != "move":
        raise InputError("mode", f"the match runs the card's move (mode = move), got {shown(v['mode'])}")
    return MechanismMove(name or calc_id, scenes[calc_id].setup(v), start)


class _Mech:
    """A mechanism's terms, from its card's Setup (its equations, its limits)."""

    def __init__(self, where: str, ev: MechanismMove, length: float):
        s = ev.setup
        if not isinstance(s, motion.Setup):
            raise InputError(f"{where}.setup", f"must be a mechanism scene's Setup, got {shown(s)}")
        if not isinstance(ev.name, str) or not ev.name or ev.name == "base":
            raise InputError(
                f"{where}.name", f"must be a non-empty name other than 'base', got {shown(ev.name)}"
            )
        if not isinstance(ev.brownout_disables, bool):
            raise InputError(
                f"{where}.brownout_disables", f"must be true or false, got {shown(ev.brownout_disables)}"
            )
        if s.asm.y0_extra or s.asm.events:
            raise InputError(
                f"{where}.effects", "an effect with states of its own is not on the match bus yet"
            )
        duty_from = {n for n, p in s.asm.parts.items() if "duty" in p.terms}
        if not duty_from <= set(LIMIT_EFFECTS):
            raise InputError(f"{where}.effects", f"{', '.join(sorted(duty_from))}: not on the match bus yet")
        self.start = number(f"{where}.start", ev.start, low=0.0, high=length)
        if ev.after is not None and (isinstance(ev.after, bool) or not isinstance(ev.after, int)):
            raise InputError(f"{where}.after", f"must be the index of an earlier move, got {shown(ev.after)}")
        self.after = ev.after
        motion.check_can_move(s)  # the card's own check: names the field
        m = s.mech
        self.name, self.disables = ev.name, ev.brownout_disables
        self.N, self.R, self.n_kv, self.fpa, self.M = m.count, m.R, m.n / m.Kv, m.force_per_amp, m.inertia
        self.s, self.d, self.q0 = m.s, m.distance, m.q0
        self.v_ref = m.free_speed
        self.force = s.asm.slots["force"]
        self.F_fric = motion.friction_of(s)
        on = s.asm.on
        self.I_st = s.values["stator_current_limit"] if "stator_limit" in on else None
        self.I_sup = s.values["supply_current_limit"] if "supply_limit" in on else None
        self.stiff = motion.estimated_time(s) / motion.time_constant(m) >= motion.STIFF
        self.e_ref = 1e-3 * m.count * m.battery_voltage**2 / m.R * self.d / self.v_ref

    def branches(self) -> tuple[str, ...]:
        return (
            (FULL,)
            + ((STATOR,) if self.I_st is not None else ())
            + ((SUPPLY,) if self.I_sup is not None else ())
        )

    def terms(self, branch: str, E: float) -> tuple[float, float, float]:
        """(a, b, p) of (M6) for the N motors on `branch` (B3)-(B5)."""
        N, R = self.N, self.R
        if branch == FULL:
            return (-N * E / R, N / R, 0.0)
        if branch == STATOR:
            return (0.0, 0.0, N * (E + R * self.I_st) * self.I_st)
        if branch == SUPPLY:
            return (N * self.I_sup, 0.0, 0.0)
        return (0.0, 0.0, 0.0)

    def supply(self, branch: str, E: float, V: float) -> float:
        """Per-motor supply current on `branch` at bus voltage V (B3)-(B5)."""
        a, b, p = self.terms(branch, E)
        return (a + b * V + p / V) / self.N

    def stator(self, branch: str, E: float, V: float) -> float:
        """Per-motor stator current on `branch` (motion (M2); B4; B5)."""
        if branch == FULL:
            return motion.stator_current(self.R, E, 1.0, V)
        if branch == STATOR:
            return self.I_st
        if branch == SUPPLY:
            c = 4.0 * self.R * self.I_sup * V
            root = math.sqrt(E * E + c)
            return 2.0 * self.I_sup * V / (E + root) if E > 0 else (root - E) / (2.0 * self.R)
        return 0.0

    def breakpoints(self, E: float) -> list[float]:
        """Bus voltages where two of the motor's branches meet (the intervals of (B6))."""
        R, out = self.R, []
        if self.I_st is not None:
            out.append(E + R * self.I_st)
        if self.I_sup is not None:
            out.append(E + R * self.I_sup)
            if self.I_st is not None and self.I_sup > 0:
                out.append((E + R * self.I_st) * self.I_st / self.I_sup)
        return [x for x in out if x > 0 and math.isfinite(x)]

    def least(self, E: float, V: float) -> str:
        """The branch (B2) gives at bus voltage V."""
        return min(self.branches(), key=lambda b: self.supply(b, E, V))

    def field_force(self, p: float) -> float:
        return self.s * self.force(self.q0 + self.s * p) if self.force is not None else 0.0


@dataclass
class MechanismResult:
    name: str
    start: float
    arrival: float | None = None  # s, the match time it reached its goal (None: it did not)
    peak_stator_current: float = 0.0  # A per motor, largest |I|
    peak_supply_current: float = 0.0  # A per motor
    energy: float = 0.0  # J, ∫V_oc·N·I_s dt
    charge: float = 0.0  # C, ∫N·I_s dt (its share of the battery's charge): the trapezoid rule on the trace
    trace: list = field(default_factory=list)  # (t, position q, speed toward the goal)
    # (i, t, N·I_s): its supply current (A, all its motors) at the bus trace's sample i, from its start
    # to its goal (it draws nothing outside them): the match's current stacked by mechanism
    supply_trace: list = field(default_factory=list)

    @property
    def time_to_goal(self) -> float | None:
        return None if self.arrival is None else self.arrival - self.start


@dataclass
class BusResult:
    mechanisms: list[MechanismResult]
    min_bus_voltage: float
    min_bus_time: float
    brownouts: list[tuple[float, float]]  # (start, end) s
    energy_oc: float  # J from the cells, ∫V_oc·I dt
    energy_bus: float  # J to the bus, ∫V·I dt
    energy_r: float  # J burnt in R, ∫I²R dt
    charge: float  # C
    trace: list  # (t, V, I) at every accepted step and switch
    pieces: int
    switches: list = field(default_factory=list)  # (t, event): every located switch, in order
    peukert_charge: float = 0.0  # C, ∫I·(I/I_H)^(k−1) dt (battery (M4)); the plain charge on a source
    current_squared: float = 0.0  # A²·s, ∫I² dt (the RMS current's numerator)


@dataclass(frozen=True)
class IdealSource:
    """A bus held at `voltage` whatever the current (R = 0): the card with battery_sag off. (A
    Battery refuses R = 0: no battery is one.)"""

    voltage: float = 12.0
    R = 0.0
    start_soc = 1.0

    def __post_init__(self):
        object.__setattr__(
            self, "voltage", number("battery.voltage", self.voltage, low=0.0, low_open=True, high=100.0)
        )

    def ocv(self, soc: float) -> float:
        return self.voltage

    def soc(self, charge: float) -> float:
        return 1.0


@dataclass(frozen=True)
class MechanismMatch:
    """Mechanisms' moves on one battery (B1-B6), from 0 to `length` s."""

    moves: tuple
    battery: Battery | IdealSource = Battery()
    controller: Controller = Controller()
    length: float = 10.0
    base_load: float = 0.0
    rtol: float = 1e-6

    def run(self) -> BusResult:
        return _Run(self).result()


class _Run:
    def __init__(self, match: MechanismMatch):
        if not isinstance(match.battery, (Battery, IdealSource)):
            raise InputError("battery", f"must be a Battery or an IdealSource, got {shown(match.battery)}")
        if not isinstance(match.controller, Controller):
            raise InputError("controller", f"must be a Controller, got {shown(match.controller)}")
        self.length = number("length", match.length, low=0.0, low_open=True, high=MAX_LENGTH)
        self.base = number("base_load", match.base_load, low=0.0, high=1000.0)
        self.rtol = number("rtol", match.rtol, low=1e-12, high=1e-3)
        moves = match.moves
        if isinstance(moves, (str, bytes)) or not hasattr(moves, "__len__"):
            raise InputError("moves", f"must be a list of mechanism moves, got {shown(moves)}")
        if len(moves) > MAX_MECHANISMS:
            raise InputError("moves", f"has {len(moves)} moves; at most {MAX_MECHANISMS}")
        self.mechs: list[_Mech] = []
        names = set()
        for i, ev in enumerate(moves):
            if not isinstance(ev, MechanismMove):
                raise InputError(f"moves[{i}]", f"must be a MechanismMove, got {shown(ev)}")
            mk = _Mech(f"moves[{i}]", ev, self.length)
            if mk.name in names:
                raise InputError(f"moves[{i}].name", f"{shown(mk.name)} names two moves")
            if mk.after is not None and not 0 <= mk.after < i:
                raise InputError(f"moves[{i}].after", f"must be the index of an earlier move, got {mk.after}")
            names.add(mk.name)
            self.mechs.append(mk)
        self.battery, self.ctl = match.battery, match.controller
        v0 = self.battery.ocv(self.battery.start_soc)
        self.e_scale = sum(mk.e_ref for mk in self.mechs) or 1e-3 * v0
        self.q_scale = self.e_scale / v0
        # the tail of the state (after the 4 + 3n the moves need): Q_p and ∫I²dt, scaled as the
        # charge is (∫I²dt by a typical 100 A) so the step control sees them alike. Each move's
        # charge is summed on the trace instead (a state per move made the run 2.5 times slower)
        self.i2_scale = self.q_scale * 100.0
        self.tail = 4 + 3 * len(self.mechs)
        self.results = [MechanismResult(mk.name, mk.start) for mk in self.mechs]
        self.last_supply: list = [None] * len(self.mechs)  # (t, N·I_s) at the last record

    # --- the bus at a state, with a held configuration -------------------------------------------
    def _emf(self, k, y):
        mk = self.mechs[k]
        return y[5 + 3 * k] * mk.v_ref * mk.n_kv

    def _sums(self, y, config):
        a, b, p = self.base, 0.0, 0.0
        for k, br in enumerate(config):
            if br in (COAST, DONE):  # draws nothing
                continue
            da, db, dp = self.mechs[k].terms(br, self._emf(k, y))
            a, b, p = a + da, b + db, p + dp
        return a, b, p

    def _voc(self, y):
        return self.battery.ocv(self.battery.soc(y[0] * self.q_scale))

    def bus(self, y, config, root):
        """V with each motor's branch and the quadratic's root held (B6)."""
        v_oc, r = self._voc(y), self.battery.R
        a, b, p = self._sums(y, config)
        pt = solve_bus(v_oc, r, a, b, p)
        if pt.collapsed or pt.upper is None:
            return pt.voltage
        return pt.lower if (root == "lower" and pt.lower is not None) else pt.upper

    def choose(self, y, config, last_v, held=None, prefer=None):
        """Each drawing motor's branch and the root (B6): every operating point, the nearest to
        last_v (the highest when None). None when there is none (the bus collapses)."""
        drawing = [k for k, br in enumerate(config) if br not in (COAST, DONE)]
        E = {k: self._emf(k, y) for k in drawing}
        cuts = sorted({x for k in drawing for x in self.mechs[k].breakpoints(E[k])})
        edges = [0.0] + cuts + [math.inf]
        v_oc, r = self._voc(y), self.battery.R
        found = []
        for lo, hi in zip(edges, edges[1:]):
            mid = 0.5 * (lo + hi) if math.isfinite(hi) else lo + 1.0
            trial = list(config)
            for k in drawing:
                trial[k] = self.mechs[k].least(E[k], mid)
            a, b, p = self._sums(y, trial)
            pt = solve_bus(v_oc, r, a, b, p)
            if pt.collapsed:
                continue
            slack = 1e-7 * max(1.0, lo) if prefer is not None else 0.0
            for which, v in (("upper", pt.upper), ("lower", pt.lower)):
                if v is not None and lo - slack <= v <= hi + slack and v > 0:
                    found.append((v, tuple(trial), which, lo <= v <= hi))
        # a piece ended at a switch: the configuration it switches to (its root at the breakpoint
        # may be a rounding outside its interval: the event is located, not exact)
        chosen = [f for f in found if prefer is not None and prefer(f[1])]
        found = chosen or [f for f in found if f[3]]
        found = [f[:3] for f in found]
        if not found:
            return None
        if last_v is None:
            top = max(f[0] for f in found)
            near = [f for f in found if f[0] >= top - 1e-9 * top]
        else:
            gap = min(abs(f[0] - last_v) for f in found)
            near = [f for f in found if abs(f[0] - last_v) <= gap + 1e-9 * max(1.0, abs(last_v))]
        # at a breakpoint two intervals give the same root: the piece that just ended did so because
        # its configuration stopped holding, so the other one is taken
        return max(near, key=lambda f: (f[1] != held, f[0]))

    # --- the pieces --------------------------------------------------------------------------------
    def result(self) -> BusResult:
        n = len(self.mechs)
        y = [0.0, 0.0, 0.0, 0.0] + [0.0] * (3 * n) + [0.0, 0.0]
        t = 0.0
        enabled, ready, b_start = True, 0.0, 0.0
        brownouts: list[tuple[float, float]] = []
        trace: list = []
        dirs = [0] * n
        last_v = None
        self.vmin, self.tmin = math.inf, 0.0
        pieces = 0
        restart: tuple[str, ...] = ()
        held = None
        prefer = None
        last_event = None
        switches: list = []
        begun: set[int] = set()
        while t < self.length:
            pieces += 1
            charge(1)
            if pieces > MAX_PIECES:
                raise InputError("moves", f"more than {MAX_PIECES} switches (brownouts, limits) in one run")
            started = [
                mk.start <= t
                and self.results[k].arrival is None
                and (mk.after is None or self.results[mk.after].arrival is not None)
                for k, mk in enumerate(self.mechs)
            ]
            for k, mk in enumerate(self.mechs):  # a queued move starts when the one before arrives
                if started[k] and k not in begun:
                    begun.add(k)
                    self.results[k].start = max(mk.start, t)
            base_cfg = []
            for k, mk in enumerate(self.mechs):
                if not started[k]:
                    base_cfg.append(DONE)
                elif not enabled and mk.disables:
                    base_cfg.append(COAST)
                else:
                    base_cfg.append(FULL)
            pick = self.choose(y, base_cfg, last_v, held, prefer)
            if pick is None:  # no operating point: the bus collapses, the outputs are disabled
                if enabled:
                    enabled, ready, b_start = False, t + self.ctl.dwell, t
                    continue
                raise InputError(
                    "moves", f"the bus has no operating point at {t:.6g} s even with the outputs off"
                )
            V, config, root = pick
            if enabled and V < self.ctl.brownout and any(c not in (COAST, DONE) for c in config):
                enabled, ready, b_start = False, t + self.ctl.dwell, t  # below at once: switch now
                continue
            if not enabled and t >= ready and V > self.ctl.recovery:
                enabled = True
                brownouts.append((b_start, t))
                continue
            for k in range(n):
                if config[k] == DONE:
                    continue
                w = y[5 + 3 * k]
                dirs[k] = 1 if w > 0 else -1 if w < 0 else self._rest_dir(k, y, config[k], V)
            last_v = V
            self._record(t, y, config, V, trace)
            t1 = min(
                [self.length]
                + [mk.start for mk in self.mechs if mk.start > t]
                + ([ready] if not enabled and ready > t else [])
            )
            events = self._events(config, root, dirs, enabled, t >= ready)
            rhs = self._rhs(config, root, dirs)
            stiff = any(self.mechs[k].stiff for k, c in enumerate(config) if c not in (COAST, DONE))
            run = self._piece(rhs, t, t1, y, events, restart, stiff)
            if run.t[-1] <= t and run.event is not None and run.event == last_event:
                raise InputError("moves", f"the run makes no progress at {t:.6g} s (switch {run.event})")
            last_event = run.event
            if run.event is not None:
                switches.append((run.t[-1], run.event))
            for tk, yk in zip(run.t[1:], run.y[1:]):
                self._record(tk, yk, config, self.bus(yk, config, root), trace)
            t, y = run.t[-1], list(run.y[-1])
            last_v = self.bus(y, config, root)
            restart = tuple(e.name for e in events)
            held = config if run.event is not None and run.event.startswith(("branch", "merge")) else None
            prefer = None
            if run.event is not None and run.event.startswith("branch"):
                index, other = run.event[len("branch") :].split(":")
                k = int(index)
                prefer = lambda cfg, k=k, o=other: cfg[k] == o  # noqa: E731
            elif run.event == "merge":
                prefer = lambda cfg, h=config: cfg != h  # noqa: E731
            if run.event == "brownout":
                enabled, ready, b_start = False, t + self.ctl.dwell, t
            elif run.event == "recovery":
                enabled = True
                brownouts.append((b_start, t))
            elif run.event is not None and run.event.startswith("turn"):
                y[5 + 3 * int(run.event[4:])] = 0.0  # the located stop: the rest rule decides (B1)
            elif run.event is not None and run.event.startswith("goal"):
                k = int(run.event[4:])
                self.results[k].arrival = t
                y[5 + 3 * k] = 0.0  # the move ends at its goal (not held: draws nothing after)
            if run.event is None and t < t1 - 1e-12 * max(1.0, t1):
                raise InputError(
                    "moves", f"the integration stopped at {t:.6g} s ({run.message or 'step limit'})"
                )
        if not enabled:
            brownouts.append((b_start, self.length))
        for k, res in enumerate(self.results):
            res.energy = y[6 + 3 * k] * self.e_scale
        return BusResult(
            self.results,
            self.vmin,
            self.tmin,
            brownouts,
            y[1] * self.e_scale,
            y[2] * self.e_scale,
            y[3] * self.e_scale,
            y[0] * self.q_scale,
            trace,
            pieces,
            switches,
            y[self.tail] * self.q_scale,
            y[self.tail + 1] * self.i2_scale,
        )

    def _piece(self, rhs, t, t1, y, events, restart, stiff):
        """One piece: DP54 (its restart skips the switch just handled), or scipy's LSODA where a
        mechanism is stiff by its card's own rule (motion.move: estimated time over the time
        constant ≥ motion.STIFF), or where DP54 runs out of steps (stiffer than estimated)."""
        if not stiff:
            try:
                return integrate(
                    rhs,
                    t,
                    t1,
                    y,
                    rtol=self.rtol,
                    atol=self.rtol,
                    events=events,
                    max_steps=MAX_STEPS,
                    restart=restart,
                )
            except RuntimeError:
                pass
        run = integrate(rhs, t, t1, y, rtol=self.rtol, atol=self.rtol, events=events, method="LSODA")
        if run.status == -1:
            raise InputError("moves", f"the run could not be integrated at {t:.6g} s ({run.message})")
        return run

    def _drive(self, k, y, br, V):
        """η·N·Kt·n·I + s·F_field: the force toward the goal before friction (B1)."""
        mk = self.mechs[k]
        E = self._emf(k, y)
        return mk.fpa * mk.stator(br, E, V) + mk.field_force(y[4 + 3 * k] * mk.d)

    def _rest_dir(self, k, y, br, V):
        F = self._drive(k, y, br, V)
        F_fric = self.mechs[k].F_fric
        return 1 if F > F_fric else -1 if F < -F_fric else 0

    def _rhs(self, config, root, dirs):
        R = self.battery.R
        tail = self.tail
        rate = getattr(self.battery, "peukert_rate", lambda current: current)

        def rhs(t, y):
            V = self.bus(y, config, root)
            v_oc = self._voc(y)
            I = self.base
            dy = [0.0] * (tail + 2)
            for k, mk in enumerate(self.mechs):
                br = config[k]
                if br == DONE:
                    continue
                E = self._emf(k, y)
                i_s = mk.N * mk.supply(br, E, V)
                I += i_s
                if dirs[k] == 0:
                    acc = 0.0
                else:
                    acc = (self._drive(k, y, br, V) - dirs[k] * mk.F_fric) / mk.M  # (B1)
                dy[4 + 3 * k] = y[5 + 3 * k] * mk.v_ref / mk.d
                dy[5 + 3 * k] = acc / mk.v_ref
                dy[6 + 3 * k] = v_oc * i_s / self.e_scale
            dy[0] = I / self.q_scale
            dy[1] = v_oc * I / self.e_scale
            dy[2] = V * I / self.e_scale
            dy[3] = R * I * I / self.e_scale
            dy[tail] = rate(I) / self.q_scale
            dy[tail + 1] = I * I / self.i2_scale
            return dy

        return rhs

    def _events(self, config, root, dirs, enabled, ready):
        evs = []
        bus = self.bus
        drawing = any(c not in (COAST, DONE) for c in config)
        if enabled and drawing:
            evs.append(Event("brownout", lambda t, y: bus(y, config, root) - self.ctl.brownout, -1))
        if not enabled and ready:
            evs.append(Event("recovery", lambda t, y: bus(y, config, root) - self.ctl.recovery, +1))
        if any(c == STATOR for c in config):

            def disc(t, y):
                a, b, pp = self._sums(y, config)
                w = self._voc(y) - self.battery.R * a
                return w * w - 4.0 * (1.0 + self.battery.R * b) * self.battery.R * pp

            evs.append(Event("merge", disc, -1))
        for k, mk in enumerate(self.mechs):
            br = config[k]
            if br == DONE:
                continue
            i_w = 5 + 3 * k
            evs.append(Event(f"goal{k}", lambda t, y, i=i_w - 1: y[i] - 1.0, +1))
            if br != COAST:
                for other in mk.branches():
                    if other != br:
                        evs.append(
                            Event(
                                f"branch{k}:{other}",
                                lambda t, y, k=k, o=other, b=br, mk=mk: (
                                    mk.supply(o, self._emf(k, y), bus(y, config, root))
                                    - mk.supply(b, self._emf(k, y), bus(y, config, root))
                                ),
                                -1,
                            )
                        )
            if dirs[k] != 0:
                evs.append(Event(f"turn{k}", lambda t, y, i=i_w: y[i], -dirs[k]))
            else:
                for sign in (1, -1):
                    evs.append(
                        Event(
                            f"free{k}{sign}",
                            lambda t, y, k=k, s=sign, b=br: (
                                s * self._drive(k, y, b, bus(y, config, root)) - self.mechs[k].F_fric
                            ),
                            +1,
                        )
                    )
        return evs

    def _record(self, t, y, config, V, trace):
        if V < self.vmin:
            self.vmin, self.tmin = V, t
        I = self.base
        for k, mk in enumerate(self.mechs):
            br = config[k]
            if br == DONE:
                continue
            E = self._emf(k, y)
            res = self.results[k]
            i_s = mk.supply(br, E, V)
            I += mk.N * i_s
            last = self.last_supply[k]
            if last is not None:
                res.charge += 0.5 * (last[1] + mk.N * i_s) * (t - last[0])
            self.last_supply[k] = (t, mk.N * i_s)
            res.supply_trace.append((len(trace), t, mk.N * i_s))
            res.peak_supply_current = max(res.peak_supply_current, i_s)
            res.peak_stator_current = max(res.peak_stator_current, abs(mk.stator(br, E, V)))
            res.trace.append((t, mk.q0 + mk.s * y[4 + 3 * k] * mk.d, y[5 + 3 * k] * mk.v_ref))
        trace.append((t, V, I))
