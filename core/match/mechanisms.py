"""Mechanisms on the match's bus: the elevator's and the arm's full-voltage moves (core.sim.motion,
`mode = move`), the sprint (core.calculators.sprint, `_Sprint`: its traction and slip (B7)-(B8))
and the flywheel's spin-up (core.sim.shooter (F1), `_Flywheel`) integrated together with the
battery, every supply current drawn from one bus. Each is (B1) with its own terms: the sprint's
loss and rolling resistance its friction, its air drag a force growing with the speed; the
flywheel's q the wheel's angle, its move ending at the target speed.

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

A flywheel's burst (B11, `burst`): the card's (core.sim.shooter.burst) on the bus: its spin-up,
then its shots, the first when it reaches the target, then one every shot_interval, each an instant
drop ω → ω_after by the card's own shot model (shooter.shot: energy or momentum transfer, losses;
motor_during_shot, a shot of some length with the motor driving, is refused); between shots it
moves back to the target at full power and holds it there (B10), as the card's burst does. The
card's next move waits for its last shot and that shot's recovery. Each shot is listed
(MechanismResult.shots: time, ball speed, ω before and after).

A flywheel move given `carry` (B13) that starts when the card's move before it ends its hold
starts at the speed that move's wheel has then, not from rest; at or above its target it is there
at once (its burst's first shot then). After a `release` (the workbook's stop) the wheel is no
longer followed, so the next move starts from rest, as the card's scene does.

Channel breakers (B9): each move names its channel (the workbook: its card), each of the channel's
motors on its own breaker (40 A by default) carrying the per-motor supply current Σ I_s of the
channel's moves; the thermal state of breaker.py (M12) is advanced exactly over each step of the
records at the step's mean current (`advance`), as the main breaker's is, from cold at 0 s.

At the goal a mechanism's move ends (as the card's does). A move given `hold` then holds its goal
(B10) until the next move waiting for it starts or its `release` time (whichever is later than its
arrival); otherwise it draws nothing after. Holding, its motors carry the stator current I_h that
holds it, from its own equations: the elevator's or arm's I_h = −s·F_field(q_goal)/(η·N·Kt·n), the
field (gravity, counterbalance) cancelled at the goal, friction aside (the card's hold_current; a
kG as a current); the flywheel's I_h = i_f at its target speed, the motors' own loss. At the held
back-EMF E (0 at rest) the duty is u = (E + R·I_h)/V, so each motor's supply is
(E + R·I_h)·I_h/V: a constant-power load on the bus, p = N·(E + R·I_h)·I_h (R·I_h² at rest)   (B10)
(tests/test_match_hold.py derives it with sympy). Assumptions: the controller holds exactly (no
position error, no oscillation); a hold current above the stator limit is not held (the limited
motors and friction then decide at rest, (B1)); without hard stops a mechanism holds at every goal,
its start included (the workbook's `stop` ends a hold).
Hard stops (B12, `hard_stops`; the workbook's elevator and arm moves): the two ends of a move's span
(its start, p = 0, and its goal, p = 1) are hard stops that carry the mechanism: falling back onto
its start it stops there (an event: p falling through 0), and resting on either end while the net
force pushes it onto the stop it stays, the free event only away from it. So a held move whose
field pushes it onto its goal's stop (an elevator's return to the bottom) needs no holding current
(I_h = 0), and a carriage browned out at the top falls to its bottom stop, not through it.
In a brownout a held mechanism coasts like any (the elevator sags, falling under gravity less
friction; the flywheel slows on its loss); when the outputs return it moves back to its goal on
its move's own equations (full duty, its limits), and holds again when it arrives. A move of the
same card starting ends the hold where the mechanism is then: the next move starts from rest at
its own start, as the card's scene does (a sag not recovered is not carried over). Energy: dE_oc/dt = V_oc·I, dE_bus/dt = V·I, dE_R/dt = R·I² (battery (M5)), and
each mechanism's ∫V_oc·N·I_s dt (the card's energy, its EMF times its current, when V_oc = V_b).
The state's tail (after the moves' 4 + 3n) integrates what the match's outputs need besides: the
Peukert-weighted charge (battery (M4)) and ∫I²dt (the RMS current); each move's charge ∫N·I_s dt (its
share) is summed by the trapezoid rule on the trace (every accepted step and switch). A move given `after` (queued) starts at its time or when that earlier move reaches its goal.
A brownout's dwell with every move coasting at rest (or done) is stepped in closed form (B14, _Run._quiet):
nothing moves, the battery carries the base load alone. Bounded: every step is charged to the solve's budget (core.sim.integrate), at most MAX_PIECES
pieces and MAX_MECHANISMS mechanisms; every input checked (InputError names the field).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from gearhead.core.errors import InputError, shown
from gearhead.core.match.battery import Battery
from gearhead.core.match.breaker import CHANNEL_RATING, Breaker
from gearhead.core.match.brownout import Controller
from gearhead.core.match.bus import solve_bus
from gearhead.core.match.checks import number
from gearhead.core.sim import motion
from gearhead.core.sim.integrate import Event, Run, charge, integrate

MAX_MECHANISMS = 200
MAX_PIECES = 50_000
MAX_STEPS = 200_000  # per piece (DP54)
# a stiff piece between a recovery (the outputs back after a brownout) and the next brownout tries
# DP54 first with this many steps: in a brownout-bound match the bus falls again within a few of them
# (LSODA's own start costs about a hundred DP54 steps of this run's right-hand side); a longer piece
# is integrated again by LSODA. 0: LSODA at once (the integration before; tests/test_match_brownout_speed.py)
RECOVERY_STEPS = 64
MAX_LENGTH = 3600.0
LIMIT_EFFECTS = ("stator_limit", "supply_limit")
FULL, STATOR, SUPPLY, COAST, DONE = "full", "stator", "supply", "coast", "done"
SLIP = "slip"  # the sprint's wheels at the edge of slip: the motors draw I_slip (B7)
HOLD = "hold"  # at its goal, held there: the current that holds it (B10)


@dataclass(frozen=True)
class MechanismMove:
    """One card's move (core.sim.motion Setup, `mode = move`) started at `start` (s)."""

    name: str
    setup: Any
    start: float = 0.0
    brownout_disables: bool = True
    after: int | None = None  # the index of a move this one waits for (queued: starts at its arrival)
    channel: str | None = None  # its motors' breaker channel (a card's moves share one); None: its name
    hold: bool = False  # after its goal it holds there (B10) until the next move waiting for it starts
    release: float | None = None  # s: the hold ends here (or at its arrival, if later); None: never
    hard_stops: bool = False  # an elevator's or arm's: its move's span ends are hard stops (B12)
    carry: bool = False  # a flywheel's: it starts at the speed the move it waited for held (B13)


def from_card(calc_id: str, raw: dict, name: str | None = None, start: float = 0.0) -> MechanismMove:
    """A MechanismMove from a card's inputs (`elevator` or `arm`, as model.solve takes them)."""
    from gearhead.core.calculators import arm, elevator
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get

    scenes = {"elevator": elevator, "arm": arm, "sprint": None, "flywheel": None}
    if calc_id not in scenes:
        raise InputError("card", f"must be one of {', '.join(scenes)}, got {shown(calc_id)}")
    v = parse_inputs(get(calc_id), raw)[0]
    return MechanismMove(name or calc_id, scene_of(calc_id, v), start)


def scene_of(calc_id: str, v) -> Any:
    """The scene the match runs for a card's parsed values: the elevator's or arm's move (mode =
    move), the sprint (mode = sprint), the flywheel's spin-up (`spin_up`)."""
    from gearhead.core.calculators import arm, elevator, sprint

    if calc_id == "flywheel":
        return spin_up(v)
    if calc_id == "sprint":
        if v["mode"] != "sprint":
            raise InputError(
                "mode", f"the match runs the card's sprint (mode = sprint), got {shown(v['mode'])}"
            )
        return sprint.setup(v)
    if v["mode"] != "move":
        raise InputError("mode", f"the match runs the card's move (mode = move), got {shown(v['mode'])}")
    return (elevator if calc_id == "elevator" else arm).setup(v)


class _Frozen(list):
    """A state vector made for one evaluation inside a piece (_reduced's full state), never changed
    after it is made: the bus computed on it may be kept (_Run.bus)."""


class _Mech:
    """A mechanism's terms, from its card's Setup (its equations, its limits)."""

    I_slip: float | None = None  # the sprint's (S5): its stator current at the edge of wheel slip
    shots, interval = 0, 0.0  # a flywheel burst's (B11)
    carry = False  # a flywheel's (B13)
    goal_speed: float | None = None  # the flywheel's target (rad/s): its move ends at a speed
    kind = "move"

    def drag(self, v: float) -> float:
        """A force against the motion that grows with the speed (the sprint's air drag), ≥ 0."""
        return 0.0

    def __init__(self, where: str, ev: MechanismMove, length: float):
        s = ev.setup
        self._common(where, ev, length)
        if not isinstance(s, motion.Setup):
            raise InputError(f"{where}.setup", f"must be a mechanism scene's Setup, got {shown(s)}")
        if s.asm.y0_extra or s.asm.events:
            raise InputError(
                f"{where}.effects", "an effect with states of its own is not on the match bus yet"
            )
        duty_from = {n for n, p in s.asm.parts.items() if "duty" in p.terms}
        if not duty_from <= set(LIMIT_EFFECTS):
            raise InputError(f"{where}.effects", f"{', '.join(sorted(duty_from))}: not on the match bus yet")
        motion.check_can_move(s)  # the card's own check: names the field
        m = s.mech
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
        self.I_hold = -self.field_force(self.d) / self.fpa  # (B10): cancels the field at the goal
        if self.hard_stops and self.I_hold <= 0:  # the field pushes it onto its stop there (B12)
            self.I_hold = 0.0
        # a stator limit below it: not held; the limited motors and friction decide at rest (B1)
        self.can_hold = self.I_st is None or abs(self.I_hold) <= self.I_st

    def _common(self, where: str, ev: MechanismMove, length: float) -> None:
        if not isinstance(ev.name, str) or not ev.name or ev.name == "base":
            raise InputError(
                f"{where}.name", f"must be a non-empty name other than 'base', got {shown(ev.name)}"
            )
        if not isinstance(ev.brownout_disables, bool):
            raise InputError(
                f"{where}.brownout_disables", f"must be true or false, got {shown(ev.brownout_disables)}"
            )
        self.start = number(f"{where}.start", ev.start, low=0.0, high=length)
        if ev.after is not None and (isinstance(ev.after, bool) or not isinstance(ev.after, int)):
            raise InputError(f"{where}.after", f"must be the index of an earlier move, got {shown(ev.after)}")
        self.after = ev.after
        self.name, self.disables = ev.name, ev.brownout_disables
        if ev.channel is not None and (not isinstance(ev.channel, str) or not ev.channel):
            raise InputError(f"{where}.channel", f"must be a non-empty name, got {shown(ev.channel)}")
        self.channel = ev.channel or ev.name
        if not isinstance(ev.hold, bool):
            raise InputError(f"{where}.hold", f"must be true or false, got {shown(ev.hold)}")
        self.hold = ev.hold
        self.release = None
        if ev.release is not None:
            self.release = number(f"{where}.release", ev.release, low=0.0, high=length)
        self.I_hold, self.w_hold = 0.0, 0.0  # (B10): the holding current per motor, the held speed
        if not isinstance(ev.hard_stops, bool):
            raise InputError(f"{where}.hard_stops", f"must be true or false, got {shown(ev.hard_stops)}")
        self.hard_stops = ev.hard_stops
        self.can_hold = True

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
        if branch == SLIP:  # (B7): a constant current
            return (N * self.slip_supply, 0.0, 0.0)
        if branch == HOLD:  # (B10): the stator current I_hold at the held speed: constant power
            return (0.0, 0.0, N * (E + R * self.I_hold) * self.I_hold)
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
        if branch == SLIP:
            return self.I_slip
        if branch == HOLD:
            return self.I_hold
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
        if self.I_slip is not None:  # where the gripping current reaches I_slip (B8)
            out.append(E + R * self.I_slip)
            if self.I_sup is not None and self.I_sup > 0:
                out.append(self.I_slip * (E + R * self.I_slip) / self.I_sup)
        return [x for x in out if x > 0 and math.isfinite(x)]

    def grip(self, E: float, V: float) -> str:
        """The branch (B2) gives at bus voltage V."""
        return min(self.branches(), key=lambda b: self.supply(b, E, V))

    def least(self, E: float, V: float) -> str:
        """The branch at bus voltage V: (B2), or the sprint's slip where it would pass I_slip (B7)."""
        br = self.grip(E, V)
        if self.I_slip is not None and self.stator(br, E, V) > self.I_slip:
            return SLIP
        return br

    def field_force(self, p: float) -> float:
        return self.s * self.force(self.q0 + self.s * p) if self.force is not None else 0.0


@dataclass(frozen=True)
class FlywheelSpin:
    """A flywheel card's spin-up from rest to its target speed at full power, with its current
    limits (core.sim.shooter's Scene and the card's parsed values): `spin_up(values)` builds it."""

    scene: Any
    values: Any
    target: float  # rad/s of the wheel
    shots: int = 0  # a burst: shots at the target, the first on arrival, then every `interval` (B11)
    interval: float = 0.0  # s


def burst(v) -> FlywheelSpin:
    """The flywheel card's burst (core.sim.shooter.burst): its spin-up, then its `shots` shots every
    `shot_interval`, each an instant drop by the card's shot model (B11)."""
    if "motor_during_shot" in v["effects"] and v["transfer"] == "momentum":
        raise InputError(
            "effects", "motor_during_shot (a shot with the motor driving): not on the match bus yet"
        )
    spin = spin_up(v)
    return FlywheelSpin(spin.scene, v, spin.target, v["shots"], v["shot_interval"])


def spin_up(v) -> FlywheelSpin:
    """The flywheel card's spin-up (its control full power), its own checks naming the field."""
    from gearhead.core.sim import shooter

    if v["control"] == "velocity_loop":
        raise InputError(
            "control",
            "the match spins the flywheel up at full power; the velocity loop is not on the bus yet",
        )
    sc, _ = shooter.scene_from(v)
    target = v["target_speed"]
    if target >= sc.free_speed:  # the card's own check (flywheel._simulate)
        raise InputError("target_speed", "the wheels cannot reach it: it is at or above their free speed")
    if sc.drive is not None:
        shooter.check_limits(sc, target)
    return FlywheelSpin(sc, v, target)


class _Sprint(_Mech):
    """The sprint card's drive (core.calculators.sprint (S1)-(S5)) on the bus: N motors through n
    (motor rad per metre) push the robot of mass m; its wheels transmit at most F_t (S3, S3'), and
    while the gripping motors would pass it they sit at the edge of slip drawing I_slip (S5):

        m·v̇ = min(η·N·Kt·n·(I − i_f), F_t) − resist(v)                                      (S4)
    written as (B1): the motors' loss η·N·Kt·n·i_f and rolling resistance resist(0) the constant
    friction against the motion, resist(v) − resist(0) (air drag) the part that grows with v, and

        slipping: stator current I_slip, duty u = min(1, I_sup/I_slip), supply min(I_slip, I_sup):
        a constant current                                                                    (B7)
        the gripping branch (B2) passes I_slip where (V − E)/R = I_slip: V = E + R·I_slip, or on
        the supply limit's (B5) where I_slip·(E + R·I_slip) = I_sup·V                          (B8)
    (tests/test_match_sprint.py derives (B7)-(B8) with sympy). The slip starts where the gripping
    branch's stator current rises through I_slip and ends where it falls through it (events), as the
    card's phases do. The voltage ramp (S14, time-dependent duty) is not on the bus yet."""

    kind = "sprint"

    def __init__(self, where: str, ev: MechanismMove, length: float):
        from gearhead.core.calculators import sprint

        s = ev.setup
        self._common(where, ev, length)
        if s.ramp > 0:
            raise InputError(f"{where}.effects", "voltage_ramp: not on the match bus yet")
        if self.hold:
            raise InputError(f"{where}.hold", "a sprint ends at its distance; it does not hold there")
        if self.hard_stops:
            raise InputError(f"{where}.hard_stops", "a sprint has no hard stops")
        sprint.check_can_move(s)  # the card's own check: names the field
        dr = s.drive
        self.N, self.R, self.n_kv, self.fpa, self.M = dr.count, dr.R, dr.n / dr.Kv, dr.force_per_amp, dr.mass
        self.s, self.d, self.q0 = 1.0, s.distance, 0.0
        self.v_ref = (dr.battery_voltage - dr.R * dr.free_current) * dr.Kv / dr.n
        self.force = None
        self._resist = s.resist()
        self.F_rr = self._resist(0.0)
        self.F_fric = dr.force_per_amp * dr.free_current + self.F_rr
        on = s.asm.on
        self.I_st = s.values["stator_current_limit"] if "stator_limit" in on else None
        self.I_sup = s.values["supply_current_limit"] if "supply_limit" in on else None
        self.I_slip = s.traction / dr.force_per_amp + dr.free_current  # (S5)
        self.slip_supply = self.I_slip if self.I_sup is None else min(self.I_slip, self.I_sup)  # (B7)
        tau = dr.mass * (dr.R + dr.bus_resistance) * dr.Kv / (dr.force_per_amp * dr.n)  # the card's rule
        self.stiff = s.distance / self.v_ref > sprint.STIFF * tau
        self.e_ref = 1e-3 * dr.count * dr.battery_voltage**2 / dr.R * self.d / self.v_ref

    def drag(self, v: float) -> float:
        return self._resist(abs(v)) - self.F_rr


class _Flywheel(_Mech):
    """The flywheel card's spin-up (core.sim.shooter (F1)) on the bus: N motors through G (motor
    turns per wheel turn) spin the wheels of inertia I from rest to the target ω_t at full power,
    under the card's current limits:

        I·ω̇ = A·(I_m(E) − i_f)/(i_s − i_f),  E = G·ω/Kv                                     (F1)
    i.e. (B1) with q the wheel's angle, n = G, force per amp A/(i_s − i_f) (A = G·τ̃s at the card's
    voltage, i_s = V_b/R its stall current) and the motors' loss A·i_f/(i_s − i_f) the friction; no
    field. (At E = 0 and V = V_b, I_m = i_s and the torque is A; it is 0 at ω = Kv·(V_b − R·i_f)/G,
    the card's free speed: tests/test_match_flywheel.py.) The move ends when ω reaches ω_t."""

    kind = "flywheel"

    def __init__(self, where: str, ev: MechanismMove, length: float):
        from gearhead.core.motors import lookup, system_from
        from gearhead.core.sim import motor_limits

        s = ev.setup
        self._common(where, ev, length)
        if self.hard_stops:
            raise InputError(f"{where}.hard_stops", "a flywheel has no hard stops")
        if not isinstance(ev.carry, bool):
            raise InputError(f"{where}.carry", f"must be true or false, got {shown(ev.carry)}")
        self.carry = ev.carry
        v = s.values
        motor, _ = lookup(v["motor"], v["source"])
        Vb = v["voltage"]
        c = motor_limits.circuit_of(motor, Vb)
        i_s = motor.stall_current * Vb / motor.v_spec  # (4)
        i_f = motor.free_current * Vb / motor.v_spec  # (3)
        G = v["ratio"]
        A = G * system_from(v)[0].stall_torque
        self.N, self.R, self.n_kv, self.M = v["motor_count"], c.R, G / c.Kv, s.scene.I
        self.fpa = A / (i_s - i_f)  # per amp of each motor (F1)
        self.v_ref = c.Kv * (Vb - c.R * i_f) / G
        tau = self.M * c.R * c.Kv / (self.fpa * G)  # the wheel's time constant at stall
        self.s, self.d, self.q0 = 1.0, self.v_ref * tau, 0.0
        self.force = None
        self.F_fric = self.fpa * i_f
        on = v["effects"]
        self.I_st = v["stator_current_limit"] if "stator_limit" in on else None
        self.I_sup = v["supply_current_limit"] if "supply_limit" in on else None
        self.goal_speed = s.target
        self.I_hold, self.w_hold = i_f, s.target  # (B10): at its speed the motors carry their own loss
        self.shots = int(number(f"{where}.setup.shots", s.shots, low=0, high=1000))
        self.interval = number(f"{where}.setup.interval", s.interval, low=0.0, high=length)
        scene, m0 = s.scene, v.get("ball_mass", 0.0)

        def shot(w):  # (B11): the card's own shot (core.sim.shooter.shot), instant (no motor during it)
            from gearhead.core.sim.shooter import shot as card_shot

            return card_shot(scene, w, m0, s.target, 1e-9)

        self.shot = shot
        self.stiff = False  # DP54, LSODA where it runs out of steps (_piece)
        self.e_ref = 1e-3 * self.N * Vb**2 / c.R * tau


def _mech_of(where: str, ev: MechanismMove, length: float) -> _Mech:
    from gearhead.core.calculators import sprint

    if isinstance(ev.setup, sprint.Setup):
        return _Sprint(where, ev, length)
    if isinstance(ev.setup, FlywheelSpin):
        return _Flywheel(where, ev, length)
    return _Mech(where, ev, length)


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
    shots: list = field(default_factory=list)  # a burst's: (t, ball speed m/s, ω before, ω after) (B11)
    # (i, t, N·I_s): its supply current (A, all its motors) at the bus trace's sample i while it draws
    # (its move, and its hold after the goal): the match's current stacked by mechanism
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
    channels: dict = field(default_factory=dict)  # channel name -> ChannelResult (B9)


@dataclass(frozen=True)
class ChannelResult:
    """One mechanism channel's breaker (each of its motors on its own breaker of `rating`, all
    carrying the per-motor supply current): the peak, and with a trip table the thermal state's
    highest (breaker.py (M12)) and the first time it reached 1 (B9)."""

    name: str
    rating: float  # A
    peak: float  # A per motor, the largest supply current
    theta_max: float | None = None  # None without a trip table
    trip_time: float | None = None  # s, the first time θ reached 1 (the run does not cut the motors)

    @property
    def margin(self) -> float | None:
        """1 − θ_max (None without a trip table)."""
        return None if self.theta_max is None else 1.0 - self.theta_max


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
    channel_breaker: Breaker | None = None  # every channel's rating and trip table; None: 40 A, no table

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
            mk = _mech_of(f"moves[{i}]", ev, self.length)
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
        brk = match.channel_breaker
        if brk is None:
            brk = Breaker(CHANNEL_RATING, name="channel_breaker")
        elif not isinstance(brk, Breaker):
            raise InputError("channel_breaker", f"must be a Breaker, got {shown(brk)}")
        self.brk = brk
        # per channel: [θ, θ_max, trip, peak, t, I] along the records (B9)
        self.chan = {mk.channel: [0.0, 0.0, None, 0.0, None, 0.0] for mk in self.mechs}
        self._drawing_cache: dict[tuple, tuple] = {}
        self._bus_memo: tuple = (None, None, None, 0.0)
        self._recovery_step: float | None = None  # the last step of the last piece DP54 took after a recovery

    # --- the bus at a state, with a held configuration -------------------------------------------
    def _emf(self, k, y):
        mk = self.mechs[k]
        return y[5 + 3 * k] * mk.v_ref * mk.n_kv

    def _drawing(self, config):
        """The moves that draw in `config` (not coasting, not done), in order, cached per
        configuration: the bus is solved at every evaluation, and looping there over every move of
        the match (most of them done) was about a sixth of a run's work."""
        key = tuple(config)
        found = self._drawing_cache.get(key)
        if found is None:
            found = self._drawing_cache[key] = tuple(
                (k, br) for k, br in enumerate(key) if br not in (COAST, DONE)
            )
        return found

    def _sums(self, y, config):
        a, b, p = self.base, 0.0, 0.0
        mechs = self.mechs
        for k, br in self._drawing(config):  # coasting or done: draws nothing
            da, db, dp = mechs[k].terms(br, self._emf(k, y))
            a, b, p = a + da, b + db, p + dp
        return a, b, p

    def _voc(self, y):
        return self.battery.ocv(self.battery.soc(y[0] * self.q_scale))

    def bus(self, y, config, root):
        """V with each motor's branch and the quadratic's root held (B6). A piece's state made by
        _reduced (a _Frozen, never changed after it is made) keeps its last bus: the events and the
        right-hand side ask it of the same state, each once (the same arithmetic, done once)."""
        if type(y) is _Frozen:
            memo = self._bus_memo
            if memo[0] is y and memo[1] is config and memo[2] == root:
                return memo[3]
            v = self._bus(y, config, root)
            self._bus_memo = (y, config, root, v)
            return v
        return self._bus(y, config, root)

    def _bus(self, y, config, root):
        v_oc, r = self._voc(y), self.battery.R
        a, b, p = self._sums(y, config)
        pt = solve_bus(v_oc, r, a, b, p)
        if pt.collapsed or pt.upper is None:
            return pt.voltage
        return pt.lower if (root == "lower" and pt.lower is not None) else pt.upper

    def choose(self, y, config, last_v, held=None, prefer=None):
        """Each drawing motor's branch and the root (B6): every operating point, the nearest to
        last_v (the highest when None). None when there is none (the bus collapses)."""
        drawing = [k for k, br in enumerate(config) if br not in (COAST, DONE, HOLD)]  # HOLD is held
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
        released = [False] * n  # (B10): its hold is over (the next move began, or its release time)
        at_goal = self.at_goal = [False] * n  # holding, still at its goal (not sagged in a brownout)
        pending: list[list[float]] = [[] for _ in range(n)]  # a burst's shot times to come (B11)
        self.wall = [0] * n  # resting on its lower (−1) or upper (+1) hard stop (B12)
        finished = [False] * n  # at its goal with no shot to come: the card's next move may start
        recovered = False  # the outputs came back after a brownout: the pieces until the next one try DP54
        while t < self.length:
            pieces += 1
            charge(1)
            if pieces > MAX_PIECES:
                raise InputError("moves", f"more than {MAX_PIECES} switches (brownouts, limits) in one run")
            arrived = [r.arrival is not None for r in self.results]
            for k, mk in enumerate(self.mechs):  # a queued move starts when the one before arrives
                if (
                    k not in begun
                    and mk.start <= t
                    and (mk.after is None or finished[mk.after])
                    and not arrived[k]
                ):
                    begun.add(k)
                    self.results[k].start = max(mk.start, t)
                    if mk.after is not None:
                        j = mk.after
                        if mk.carry and not released[j]:  # (B13): the wheel still spinning at its speed
                            self._carry(k, j, t, y, at_goal, pending, finished)
                        released[j] = True  # the move before stops holding (B10)
            for k, mk in enumerate(self.mechs):  # a burst's shots due now: instant drops (B11)
                while pending[k] and pending[k][0] <= t * (1 + 1e-12):
                    pending[k].pop(0)
                    if released[k]:
                        continue
                    w0 = y[5 + 3 * k] * mk.v_ref
                    one = mk.shot(w0)
                    y[5 + 3 * k] = one.omega_after / mk.v_ref
                    self.results[k].shots.append((t, one.V, w0, one.omega_after))
                    at_goal[k] = False
            arrived = [r.arrival is not None for r in self.results]
            for k, mk in enumerate(self.mechs):
                if arrived[k] and mk.release is not None and t >= mk.release:
                    released[k] = True
            base_cfg = []
            for k, mk in enumerate(self.mechs):
                if k not in begun or released[k] or (finished[k] and not mk.hold):
                    base_cfg.append(DONE)
                elif not enabled and mk.disables:
                    base_cfg.append(COAST)
                elif arrived[k] and at_goal[k] and mk.can_hold:
                    base_cfg.append(HOLD)
                else:
                    base_cfg.append(FULL)
            pick = self.choose(y, base_cfg, last_v, held, prefer)
            if pick is None:  # no operating point: the bus collapses, the outputs are disabled
                if enabled:
                    enabled, ready, b_start, recovered = False, t + self.ctl.dwell, t, False
                    continue
                raise InputError(
                    "moves", f"the bus has no operating point at {t:.6g} s even with the outputs off"
                )
            V, config, root = pick
            if enabled and V < self.ctl.brownout and any(c not in (COAST, DONE) for c in config):
                # below at once: the dip is recorded (its voltage and currents, for no time), then
                # the outputs switch off now
                self._record(t, y, config, V, trace)
                enabled, ready, b_start, recovered = False, t + self.ctl.dwell, t, False
                continue
            if not enabled and t >= ready and V > self.ctl.recovery:
                enabled = True
                brownouts.append((b_start, t))
                recovered = True
                continue
            for k in range(n):
                if config[k] == DONE:
                    continue
                w = y[5 + 3 * k]
                dirs[k] = 1 if w > 0 else -1 if w < 0 else self._rest_dir(k, y, config[k], V)
                self.wall[k] = 0
                if self.mechs[k].hard_stops and config[k] != HOLD:  # on a stop, pushed onto it (B12)
                    p = y[4 + 3 * k]
                    if (p <= 0.0 and dirs[k] < 0) or (p >= 1.0 and dirs[k] > 0 and at_goal[k]):
                        self.wall[k] = dirs[k]
                        dirs[k] = 0
                        y[5 + 3 * k] = 0.0
            last_v = V
            self._record(t, y, config, V, trace)
            t1 = min(
                [self.length]
                + [mk.start for mk in self.mechs if mk.start > t]
                + [mk.release for mk in self.mechs if mk.release is not None and mk.release > t]
                + [p[0] for p in pending if p and p[0] > t]
                + ([ready] if not enabled and ready > t else [])
            )
            events = self._events(config, root, dirs, enabled, t >= ready)
            rhs = self._rhs(config, root, dirs)
            stiff = any(self.mechs[k].stiff for k, c in enumerate(config) if c not in (COAST, DONE, HOLD))
            run = None
            quiet = all(c == DONE or (c == COAST and dirs[k] == 0) for k, c in enumerate(config))
            if not enabled and t < ready and quiet:
                run = self._quiet(t, t1, y)  # the dwell with every move at rest: closed form (B14)
            if run is None:
                run = self._reduced(rhs, t, t1, y, events, restart, stiff, config, recovered)
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
                if other == "grip":
                    prefer = lambda cfg, k=k: cfg[k] != SLIP  # noqa: E731
                else:
                    prefer = lambda cfg, k=k, o=other: cfg[k] == o  # noqa: E731
            elif run.event == "merge":
                prefer = lambda cfg, h=config: cfg != h  # noqa: E731
            if run.event == "brownout":
                enabled, ready, b_start, recovered = False, t + self.ctl.dwell, t, False
            elif run.event == "recovery":
                enabled = True
                brownouts.append((b_start, t))
                recovered = True
            elif run.event is not None and run.event.startswith("turn"):
                y[5 + 3 * int(run.event[4:])] = 0.0  # the located stop: the rest rule decides (B1)
            elif run.event is not None and run.event.startswith("wall"):
                k = int(run.event[4:])  # on its lower hard stop (B12): stopped there
                y[4 + 3 * k], y[5 + 3 * k] = 0.0, 0.0
            elif run.event is not None and run.event.startswith("goal"):
                k = int(run.event[4:])
                mk = self.mechs[k]
                if self.results[k].arrival is None:
                    self.results[k].arrival = t
                    pending[k] = [t + j * mk.interval for j in range(mk.shots)]
                finished[k] = not pending[k]
                at_goal[k] = True  # (B10): held there from now (or, not holding, done)
                y[5 + 3 * k] = mk.w_hold / mk.v_ref  # the move ends at its goal (and speed)
                if mk.goal_speed is None:
                    y[4 + 3 * k] = 1.0
            for k, c in enumerate(config):  # a brownout moved it off its goal: it moves back (B10)
                if c != HOLD and at_goal[k]:
                    mk = self.mechs[k]
                    at_goal[k] = y[5 + 3 * k] == mk.w_hold / mk.v_ref and (
                        mk.goal_speed is not None or y[4 + 3 * k] == 1.0
                    )
            if run.event is None and t < t1 - 1e-12 * max(1.0, t1):
                raise InputError(
                    "moves", f"the integration stopped at {t:.6g} s ({run.message or 'step limit'})"
                )
        if not enabled:
            brownouts.append((b_start, self.length))
        for k, res in enumerate(self.results):
            res.energy = y[6 + 3 * k] * self.e_scale
        on = self.brk.calibrated
        channels = {
            name: ChannelResult(name, self.brk.rating, c[3], c[1] if on else None, c[2])
            for name, c in self.chan.items()
        }
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
            channels,
        )

    def _carry(self, k, j, t, y, at_goal, pending, finished):
        """(B13): move k starts at the speed move j (the card's last, holding until now) has; at or
        above k's target it is there at once (held at it: its controller brakes a faster wheel to
        its target, not modelled), and a burst's first shot is now."""
        mk, mj = self.mechs[k], self.mechs[j]
        w = y[5 + 3 * j] * mj.v_ref
        if w <= 0:
            return
        y[5 + 3 * k] = w / mk.v_ref
        if mk.goal_speed is not None and w >= mk.goal_speed:
            self.results[k].arrival = t
            at_goal[k] = True
            y[5 + 3 * k] = mk.w_hold / mk.v_ref
            pending[k] = [t + i * mk.interval for i in range(mk.shots)]
            finished[k] = not pending[k]

    def _quiet(self, t, t1, y):
        """(B14) The outputs disabled, waiting for the dwell, every move coasting at rest or done:
        nothing moves and the battery carries the base load I alone, so over [t, t1]
            Q += I·Δt,  Q_p += rate(I)·Δt,  ∫I²dt += I²·Δt,  E_R += R·I²·Δt,
            E_oc += I·∫V_oc dt,  E_bus += I·(∫V_oc dt − R·I·Δt),
            ∫V_oc dt = Δt·(V_oc(t) + V_oc(t1))/2,
        exact while V_oc is linear in the charge (M1: between two rows of its table, checked; else
        None and the piece is integrated). DP54 gives the same to rounding (the solution is a
        polynomial of degree 2 in t) at 8 evaluations, the events and their set-up. No event can
        fall in it: at rest in coast a move's forces do not change (its position does not), and
        the recovery waits for the dwell's end."""
        bat, I, dt = self.battery, self.base, t1 - t
        R = bat.R
        q0 = y[0] * self.q_scale
        q1 = q0 + I * dt
        table = getattr(bat, "ocv_table", None)
        if table is not None:
            s0, s1 = bat.soc(q0), bat.soc(q1)
            if any(min(s0, s1) < row[0] < max(s0, s1) for row in table):
                return None
        v0, v1 = bat.ocv(bat.soc(q0)), bat.ocv(bat.soc(q1))
        if v0 - R * I <= 0 or v1 - R * I <= 0:  # the bus collapses even so: integrated (named there)
            return None
        voc_dt = 0.5 * (v0 + v1) * dt
        rate = getattr(bat, "peukert_rate", lambda current: current)
        out = list(y)
        out[0] = q1 / self.q_scale
        out[1] = y[1] + I * voc_dt / self.e_scale
        out[2] = y[2] + I * (voc_dt - R * I * dt) / self.e_scale
        out[3] = y[3] + R * I * I * dt / self.e_scale
        out[self.tail] = y[self.tail] + rate(I) * dt / self.q_scale
        out[self.tail + 1] = y[self.tail + 1] + I * I * dt / self.i2_scale
        return Run([t, t1], [list(y), out], 0)

    def _reduced(self, rhs, t, t1, y, events, restart, stiff, config, recovered=False):
        """_piece on the states that change in it: the battery's, the tail's and those of the moves
        not done (a done move's states are constant): a piece's work (LSODA's finite-difference
        Jacobian above all, one evaluation per state) grows with the moves running, not with every
        move of the match; and the integrator's RMS error norm is not averaged over states that
        do not move.

        A stiff piece after a recovery (`recovered`, _piece: DP54 first) has its integrals (charge,
        energies, ∫I²dt, each move's energy) integrated as this piece's increments from 0, added to
        the totals after it. The step control weighs a state's error against rtol times the state:
        against the totals DP54 took a brownout-bound match's millisecond pieces, the current
        spiking as the motors come back, in one step, the piece's whole charge within the
        tolerance (measured on the example at 60 A, 25 mΩ, 70 %: the match's charge 2.4 % off the
        reference at rtol 1e-8); against the increment it is held to rtol (0.16 % off, as LSODA's)."""
        idx = [0, 1, 2, 3]
        for k, c in enumerate(config):
            if c != DONE:
                idx += [4 + 3 * k, 5 + 3 * k, 6 + 3 * k]
        idx += [self.tail, self.tail + 1]
        quad: set[int] = set()
        if stiff and recovered and RECOVERY_STEPS:
            quad = {0, 1, 2, 3, self.tail, self.tail + 1} | {i for i in idx if i >= 4 and (i - 4) % 3 == 2}
            quad &= set(range(self.tail + 2))
        elif len(idx) == len(y):
            return self._piece(rhs, t, t1, y, events, restart, stiff, recovered)
        base = list(y)
        plan = [(i, i in quad) for i in idx]
        last: list = [None, None]

        def full(yr):
            """The full state of a reduced one: the states not held at the piece's start, an
            integral increment (quad) added to its total there."""
            if yr is last[0]:  # the events of one step ask the same state (DP54's lists: never changed)
                return last[1]
            f = _Frozen(base)
            for (i, q), v in zip(plan, yr):
                f[i] = base[i] + v if q else v
            if type(yr) is list:
                last[0], last[1] = yr, f
            return f

        def rhs_r(tt, yr):
            d = rhs(tt, full(yr))
            return [d[i] for i in idx]

        evs = [Event(e.name, lambda tt, yr, g=e.g: g(tt, full(yr)), e.direction, e.terminal) for e in events]
        y0 = [0.0 if q else y[i] for i, q in plan]
        run = self._piece(rhs_r, t, t1, y0, evs, restart, stiff, recovered)
        run.y = [full(yk) for yk in run.y]
        return run

    def _piece(self, rhs, t, t1, y, events, restart, stiff, recovered=False):
        """One piece: DP54 (its restart skips the switch just handled), or scipy's LSODA where a
        mechanism is stiff by its card's own rule (motion.move: estimated time over the time
        constant ≥ motion.STIFF), or where DP54 runs out of steps (stiffer than estimated). A stiff
        piece after a recovery (until the next brownout) tries DP54 for RECOVERY_STEPS steps first (its accuracy is
        DP54's, the same tolerance; stiffness only makes DP54 slow): in a brownout-bound match it
        ends at the next brownout within a few steps, where LSODA's start alone cost ~3 ms."""
        if stiff and recovered and RECOVERY_STEPS:
            try:
                run = integrate(
                    rhs,
                    t,
                    t1,
                    y,
                    rtol=self.rtol,
                    atol=self.rtol,
                    events=events,
                    max_steps=RECOVERY_STEPS,
                    restart=restart,
                    first_step=self._recovery_step,
                )
            except RuntimeError:
                pass
            else:  # the next such piece starts with the step this one ended on (rejections spared)
                if len(run.t) > 1:
                    self._recovery_step = run.t[-1] - run.t[-2]
                return run
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

        live = [(k, self.mechs[k], config[k]) for k in range(len(config)) if config[k] != DONE]

        def rhs(t, y):
            V = self.bus(y, config, root)
            v_oc = self._voc(y)
            I = self.base
            dy = [0.0] * (tail + 2)
            for k, mk, br in live:  # a done move's states are constant
                E = self._emf(k, y)
                i_s = mk.N * mk.supply(br, E, V)
                I += i_s
                if dirs[k] == 0 or br == HOLD:
                    acc = 0.0
                else:
                    drag = mk.drag(y[5 + 3 * k] * mk.v_ref)
                    acc = (self._drive(k, y, br, V) - dirs[k] * (mk.F_fric + drag)) / mk.M  # (B1)
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
        if any(c in (STATOR, HOLD) for c in config):

            def disc(t, y):
                a, b, pp = self._sums(y, config)
                w = self._voc(y) - self.battery.R * a
                return w * w - 4.0 * (1.0 + self.battery.R * b) * self.battery.R * pp

            evs.append(Event("merge", disc, -1))
        for k, mk in enumerate(self.mechs):
            br = config[k]
            if br in (DONE, HOLD):  # held: nothing of its own switches (B10)
                continue
            i_w = 5 + 3 * k
            if self.at_goal[k]:
                pass  # at its goal, coasting or not able to hold there: it can only leave it
            elif mk.goal_speed is not None:  # the flywheel: its target speed
                w_goal = mk.goal_speed / mk.v_ref
                evs.append(Event(f"goal{k}", lambda t, y, i=i_w, g=w_goal: y[i] - g, +1))
            else:
                evs.append(Event(f"goal{k}", lambda t, y, i=i_w - 1: y[i] - 1.0, +1))
            if br == SLIP:  # (B7): grip again where the gripping branch falls through I_slip
                evs.append(
                    Event(
                        f"branch{k}:grip",
                        lambda t, y, k=k, mk=mk: (
                            mk.stator(
                                mk.grip(self._emf(k, y), bus(y, config, root)),
                                self._emf(k, y),
                                bus(y, config, root),
                            )
                            - mk.I_slip
                        ),
                        -1,
                    )
                )
            elif br != COAST and mk.I_slip is not None:  # (B8): the held branch rises through I_slip
                evs.append(
                    Event(
                        f"branch{k}:{SLIP}",
                        lambda t, y, k=k, mk=mk, b=br: (
                            mk.stator(b, self._emf(k, y), bus(y, config, root)) - mk.I_slip
                        ),
                        +1,
                    )
                )
            if br not in (COAST, SLIP):
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
                if dirs[k] < 0 and mk.hard_stops:  # falling back onto its start's hard stop (B12)
                    evs.append(Event(f"wall{k}", lambda t, y, i=i_w - 1: y[i], -1))
            else:
                for sign in (1, -1):
                    if sign == self.wall[k]:  # held by the stop that way
                        continue
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
        per_motor = dict.fromkeys(self.chan, 0.0)
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
            per_motor[mk.channel] += i_s
        trace.append((t, V, I))
        self._channels(t, per_motor)

    def _channels(self, t, per_motor):
        """(B9): each channel's breaker along the records, as the main breaker's (workbook match
        _breaker): θ advanced exactly (breaker.py `advance`) over each step at the step's mean
        per-motor supply current (the records hold every solver step and switch); a step of zero
        length (a switch) only changes the current the next step starts from."""
        brk, on = self.brk, self.brk.calibrated
        for name, i in per_motor.items():
            c = self.chan[name]
            c[3] = max(c[3], abs(i))
            if on and c[4] is not None and t > c[4]:
                c[0] = brk.advance(c[0], 0.5 * (c[5] + i), t - c[4])
                if c[0] > c[1]:
                    c[1] = c[0]
                if c[2] is None and c[0] >= 1.0:
                    c[2] = t
            c[4], c[5] = t, i
