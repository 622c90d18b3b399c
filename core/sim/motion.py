"""A mechanism driven by DC motors from rest to a goal at full voltage: the scene shared by the
elevator and the arm (one coordinate q: metres of carriage travel, or radians of arm angle).

Motor: the seed's model (section 1, eqs. 3, 7, 9), the one every tab uses; per motor:
    R = V_nom/I_stall,  Kv = ω_free/(V_nom − R·I_free),  Kt = τ_stall/(I_stall − I_free)    (M1)
    I = (u·V_bus − ω_m/Kv)/R                  stator current, u the duty (0..1)         (M2)
    i_f = I_free·V_b/V_nom                    free current at the battery voltage (eq. 3)
    n = motor radians per unit of q (G/(r·k) for a spool of radius r and rigging k; G for an arm)
    F_motor = η·N·Kt·n·(I − i_f)              gearbox efficiency η on the output torque (M3)
i.e. a DC motor whose own losses are a constant torque Kt·i_f against the motion: it runs at its
rated free speed with no load (I = i_f) and gives its rated stall torque at the stall current, the
datasheet's two points, as (8) and (9). (WPILib's DCMotor has the same R and Kv but Kt = τs/Is and
no loss torque: its free speed is Kv·V, above the rated one, and its stall torque the rated one.)
Everything is written toward the goal: s = sign(q_goal − q_start), p = s·(q − q_start) ≥ 0,
w = s·q̇, E = w·n/Kv (back-EMF, V). Then
    M·ẇ = η·N·Kt·n·I(E) + s·F_field(q) − F_friction                                    (M4)
where F_field is the sum of the position-dependent forces of the effects on (gravity,
counterbalance, signed in +q) and F_friction the constant force against the motion: the motors'
loss η·N·Kt·n·i_f of (M3) plus the friction effect's (`friction`).
Electrical effects (all per motor, solved exactly at each evaluation, no lag):
- `battery_sag`: V_bus = V_b − R_bus·u·I with R_bus = N·R_batt (N motors share the battery
  resistance). With (M2): I(u) = (u·V_b − E)/(R + u²·R_bus)                            (E1)
- `stator_limit` (|I| ≤ I_st): the controller lowers the duty until the current is at the limit.
  I(u) = I_st ⇔ I_st·R_bus·u² − V_b·u + W = 0, W = E + R·I_st; the duty is the SMALLER root
      u_st = 2W/(V_b + √(V_b² − 4·I_st·R_bus·W))     (= W/V_b without sag)               (E2)
  (the stable operating point of a current loop that raises the duty from 0; with strong sag
  I(u) peaks below u = 1, and the larger root is the unstable one). No real root: the current
  never reaches the limit, u = 1.
- `supply_limit` (u·I ≤ I_sup): u·(u·V_b − E) = I_sup·(R + u²·R_bus) ⇔
      (V_b − I_sup·R_bus)·u² − E·u − I_sup·R = 0,  u_sup = the positive root              (E3)
- the duty is u = min(1, u_st, u_sup): the first limit met as the duty rises.
All derived again with sympy (tests/test_motion.py checks (E1)-(E3) against a direct solve).
The stator current depends on speed only and never rises with speed, so its peak is at rest; the
supply current rises while the stator limit holds and falls after, so its peak (and the bus
minimum) is at a branch point of the duty rule, each in closed form (core.sim.motor_limits (E5)-(E7):
with strong sag the duty jumps to 1 where the roots of (E2) merge, (E6), and the peak is there). The motion is monotone toward the goal
(checked before the run: the force at rest beats the load everywhere on the path), so friction
is a constant against it. Energy drawn from the battery: ∫ V_b·N·u·I dt (the battery's EMF times
its current; what the battery's own resistance burns is included).
State (scaled to O(1) so one tolerance fits all): p/d, w/v_ref, energy/E_ref.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any

from ..declarations import Output, Plot
from ..errors import InputError
from ..fields import Field
from ..motors import Motor, motor_fields
from .effects import Effect, Effects, Part, Slot
from .integrate import Event, StiffRun, charge, integrate, integrate_stiff
from .motor_limits import (  # noqa: F401 (shared)
    SCALAR,
    _Array,
    branch_emfs,
    bus_resistance_of,
    electrical,
    electrical_effects,
    release_emfs,
)
from .scene import SimRun

T_MAX = 3600.0  # s: a move longer than an hour is not a mechanism, it is an error
DP54_STEPS = 2_000  # beyond this the move is stiff: LSODA takes over
SAMPLES = 120  # points per plotted curve

SLOTS = (
    Slot("force", "sum", "generalised force along +q from the field the mechanism sits in (N or N·m)"),
    Slot("friction", "sum", "constant force or torque against the motion (N or N·m)"),
    Slot("duty", "min", "upper bound on the motor duty from a current limit, given the back-EMF E"),
)


@dataclass(frozen=True)
class Mechanism:
    """What the motors see. `n` may be a numpy array (a batch of candidate ratios)."""

    motor: Motor
    count: int
    battery_voltage: float  # V_b, at rest
    efficiency: float
    n: Any  # motor rad per unit of q
    inertia: float  # M: kg (elevator) or kg·m² (arm)
    q0: float
    q1: float
    bus_resistance: float = 0.0  # R_bus = N·R_batt when battery_sag is on, else exactly 0
    xp: Any = SCALAR

    @property
    def R(self) -> float:
        return self.motor.v_spec / self.motor.stall_current  # (M1)

    @property
    def Kv(self) -> float:
        m = self.motor
        return m.free_speed / (m.v_spec - self.R * m.free_current)  # (M1)

    @property
    def Kt(self) -> float:
        m = self.motor
        return m.stall_torque / (m.stall_current - m.free_current)  # (M1), seed eq. 7

    @property
    def free_current(self) -> float:
        return self.motor.free_current * self.battery_voltage / self.motor.v_spec  # i_f, seed eq. 3

    @property
    def loss_force(self):
        return self.force_per_amp * self.free_current  # (M3): the motors' own loss, against the motion

    @property
    def s(self) -> float:
        return 1.0 if self.q1 >= self.q0 else -1.0

    @property
    def distance(self) -> float:
        return abs(self.q1 - self.q0)

    @property
    def force_per_amp(self):
        return self.efficiency * self.count * self.Kt * self.n  # (M3), per amp of each motor

    @property
    def force_per_volt(self):
        return self.force_per_amp / self.R  # at stall

    @property
    def free_speed(self):
        # of q, at V_b with no load: I = i_f in (M2), = ω_free·V_b/V_nom/n (seed eq. 1)
        return (self.battery_voltage - self.R * self.free_current) * self.Kv / self.n

    def q_at(self, p):
        return self.q0 + self.s * p


def friction_effect(quantity: str, unit: str, name: str, help: str, default: float) -> Effect:
    def build(values, mech):
        F = values[name]
        return Part(terms={"friction": lambda: F})

    return Effect(
        "friction",
        help,
        build,
        fields=(
            Field(
                name,
                "Friction",
                quantity,
                unit,
                default=default,
                min=0,
                max=2.2e5,
                help="Constant force or torque against the motion (Coulomb friction), added to kS.",
            ),
        ),
    )


# --- the assembled right-hand side ---------------------------------------------------------------


@dataclass
class Setup:
    mech: Mechanism
    effects: Effects
    asm: Any  # effects.Assembly
    varying: bool  # the field force changes along the path (an arm): max speed may be inside
    critical: tuple[float, ...] = ()  # q where the field force may be extreme (besides the ends)
    values: Mapping[str, Any] = field(default_factory=dict)  # the parsed inputs
    names: Mapping[str, Any] = field(default_factory=dict)  # calculator-specific words and field names


def stator_current(R: float, E: float, u: float, v_bus: float) -> float:
    """(M2) per motor: I = (u·V_bus − E)/R, at duty u on a bus at v_bus (the match solves v_bus
    from every mechanism's supply current together, core.match.mechanisms)."""
    return (u * v_bus - E) / R


def field_force(setup: Setup):
    """q -> F_field (0 when no effect exerts one)."""
    f = setup.asm.slots["force"]
    return f if f is not None else (lambda q: 0.0)


def effect_friction(setup: Setup) -> float:
    """The friction effect's force against the motion (0 when off)."""
    f = setup.asm.slots["friction"]
    return f() if f is not None else 0.0


def friction_of(setup: Setup):
    """F_friction of (M4): the motors' own loss (M3) plus the friction effect's."""
    return setup.mech.loss_force + effect_friction(setup)


def build_rhs(setup: Setup):
    """The scaled right-hand side, specialised once to the effects on, and the acceleration."""
    m = setup.mech
    s, d, q0 = m.s, m.distance, m.q0
    v_ref = m.free_speed
    # energy: a quadrature that may cross zero (regeneration moving down); scaled small so that
    # the relative tolerance, not the absolute one, governs it
    e_ref = 1e-3 * m.count * m.battery_voltage**2 / m.R * d / v_ref
    k_emf = v_ref * m.n / m.Kv  # E per unit of scaled speed
    k_force = m.force_per_amp
    M = m.inertia
    a_scale = 1.0 / (M * v_ref)
    p_scale = v_ref / d
    e_scale = m.count * m.battery_voltage / e_ref
    elec = electrical(m, setup.asm.slots["duty"])
    F_fric = friction_of(setup)
    force = setup.asm.slots["force"]
    if force is None:
        F_const = -F_fric

        def accel(ph, wh):
            u, I = elec(k_emf * wh)
            return (k_force * I + F_const) * a_scale, u * I
    else:

        def accel(ph, wh):
            u, I = elec(k_emf * wh)
            return (k_force * I + s * force(q0 + s * d * ph) - F_fric) * a_scale, u * I

    def rhs(t, y):
        a, i_sup = accel(y[0], y[1])
        return [y[1] * p_scale, a, i_sup * e_scale]

    return setup.asm.rhs(rhs), accel, (d, v_ref, e_ref, k_emf)


def check_can_move(setup: Setup) -> None:
    """InputError naming the reason and the field when the force at rest does not beat the load
    somewhere between start and goal (the mechanism would stop, or never leave). The motors'
    own loss (M3) is counted on their side: what they give is η·N·Kt·n·(I − i_f)."""
    m = setup.mech
    names = setup.names
    force = field_force(setup)
    F_fric = effect_friction(setup)
    lo, hi = sorted((m.q0, m.q1))
    points = [m.q0, m.q1] + [q for q in setup.critical if lo < q < hi]
    load = max(-m.s * force(q) + F_fric for q in points)  # the most the field and friction resist
    q_worst = max(points, key=lambda q: -m.s * force(q))
    u0, I0 = electrical(m, setup.asm.slots["duty"])(0.0)

    def given(I):  # what the motors give at rest with stator current I each (M3)
        return m.force_per_amp * I - m.loss_force

    F0 = given(I0)
    if F0 > load:
        return
    unit = names.get("force_unit", "N")
    need_I = load / m.force_per_amp + m.free_current
    where = names.get("where", lambda q: "")(q_worst)
    if "stator_limit" in setup.asm.on or "supply_limit" in setup.asm.on:
        _, I_free = electrical(m, None)(0.0)
        if given(I_free) > load:
            field_name = "stator_current_limit"
            if "supply_limit" in setup.asm.on:
                sup = setup.asm.parts["supply_limit"].terms["duty"](0.0)
                st = (
                    setup.asm.parts["stator_limit"].terms["duty"](0.0)
                    if "stator_limit" in setup.asm.on
                    else math.inf
                )
                if sup <= st:
                    field_name = "supply_current_limit"
            raise InputError(
                field_name,
                f"is too low to move it: at rest the motors give {F0:.4g} {unit} "
                f"({I0:.4g} A each), and the load{where} needs more than {load:.4g} {unit} "
                f"({need_I:.4g} A each)",
            )
    if m.bus_resistance > 0:
        _, I_nosag = electrical(replace(m, bus_resistance=0.0), None)(0.0)
        if given(I_nosag) > load:
            raise InputError(
                "battery_resistance",
                f"sags the battery so far at stall that the motors give only "
                f"{F0:.4g} {unit}; the load{where} needs {load:.4g} {unit}",
            )
    if F_fric > 0 and F0 > load - F_fric:
        raise InputError(
            names.get("friction", "friction"),
            f"({F_fric:.4g} {unit}) with the load is more than the motors' stall force {F0:.4g} {unit}",
        )
    raise InputError(
        "ratio",
        f"is too low: the motors stall at {F0:.4g} {unit} and the load{where} needs "
        f"{load:.4g} {unit} ({need_I:.4g} A each, more than the stall current): raise "
        f"the ratio or the motor count, or lighten the load",
    )


@dataclass
class Move:
    time: float
    max_speed: float
    energy: float
    nfev: int
    run: Any
    scales: tuple
    method: str = "DP54"  # the integrator that ran


STIFF = 60.0  # move time over the mechanical time constant above which LSODA is used (see move)


def time_constant(m: Mechanism) -> float:
    """τ = kA/kV = M·R·Kv/(η·N·Kt·n²): how fast the speed settles (the stiffness of the move)."""
    return m.inertia * m.R * m.Kv / (m.force_per_amp * m.n)


def estimated_time(setup: Setup) -> float:
    """A rough move time: travel at free speed, plus settling, plus accelerating from rest with
    the net force at the start."""
    m = setup.mech
    _, I0 = electrical(m, setup.asm.slots["duty"])(0.0)
    F0 = m.force_per_amp * I0 + m.s * field_force(setup)(m.q0) - friction_of(setup)  # (M4) at rest
    accel_time = math.sqrt(2 * m.distance * m.inertia / F0) if F0 > 0 else math.inf
    return m.distance / m.free_speed + time_constant(m) + accel_time


def move(setup: Setup, rtol: float, dense: bool = False, method: str | None = None) -> Move:
    """Integrate from rest to the goal (terminal event: the first arrival).

    The back-EMF makes the speed relax with the time constant τ (time_constant); a move takes
    T ≈ distance/free speed + τ. An explicit method needs a step below ≈ 3τ for stability, so
    our DP54 (core.sim.integrate) is used when T/τ < STIFF, and scipy's LSODA (stiff-capable,
    same events and dense output) beyond: a highly geared move has T/τ ~ 10⁶."""
    rhs, accel, scales = build_rhs(setup)
    d, v_ref, e_ref, _ = scales
    goal = Event("goal", lambda t, y: y[0] - 1.0, +1)
    peak = Event("peak", lambda t, y: accel(y[0], y[1])[0], -1, terminal=False)
    events = [goal] + list(setup.asm.events) + ([peak] if setup.varying else [])
    y0 = [0.0, 0.0, 0.0] + list(setup.asm.y0_extra)
    m = setup.mech
    if method is None:
        method = "DP54" if estimated_time(setup) / time_constant(m) < STIFF else "LSODA"
    if method == "DP54":
        try:
            run = integrate(
                rhs, 0.0, T_MAX, y0, rtol=rtol, atol=rtol, events=events, max_steps=DP54_STEPS, dense=dense
            )
        except RuntimeError:  # stiffer than estimated (explicit steps held at ≈ 3τ): hand it on
            run, method = _lsoda(rhs, y0, rtol, events), "LSODA after DP54"
    else:
        run = _lsoda(rhs, y0, rtol, events)
    if run.event != "goal":
        raise InputError(
            "ratio",
            f"the mechanism does not reach the goal within {T_MAX:.0f} s "
            f"(it only just beats the load): raise the ratio or the motors",
        )
    end = run.y[-1]
    peak_w = max([end[1]] + [c[2][1] for c in run.crossings if c[0] == "peak"])
    return Move(run.t[-1], peak_w * v_ref, end[2] * e_ref, run.nfev, run, scales, method)


def _lsoda(rhs, y0, rtol, events) -> StiffRun:
    # a peak event on a step LSODA's interpolant smooths over (a feather-light arm): the peak
    # speed is then the largest at the step points
    run = integrate_stiff(rhs, 0.0, T_MAX, y0, rtol, rtol, events, "LSODA", peak_from_steps="peak")
    if run.status == -1:
        raise InputError("ratio", f"the move could not be integrated ({run.message})")
    return run


def extremes(setup: Setup, w_max: float) -> dict[str, float]:
    """Peak stator and supply current per motor and the lowest bus voltage over speeds 0..w_max
    (every speed in between is visited: the motion starts at rest). The stator current never
    rises with speed (its largest magnitude is at rest, or at top speed when a load moving down
    drives the motor past free speed and it brakes); the supply current peaks at a branch point of
    the duty rule (motor_limits.branch_emfs: where the stator limit lets go toward full duty or
    the supply limit (E5), where with strong sag the duty jumps to full (E6), or (E7))."""
    m = setup.mech
    elec = electrical(m, setup.asm.slots["duty"])
    E_max = w_max * m.n / m.Kv
    if not (E_max >= 0 and math.isfinite(E_max)):  # never from a move that reached its goal
        raise InputError("ratio", "the move's top speed is not a number at this ratio: change the ratio")
    Es = [0.0] + [E for E in [E_max] + branch_emfs(m, setup.values, setup.asm.on) if 0.0 < E <= E_max]
    sup = []
    for E in Es:
        u, I = elec(E)
        sup.append(u * I)
    u0, I0 = elec(0.0)
    _, I_end = elec(E_max)  # negative when the load drives the motor past free speed (regeneration)
    peak_sup = max(sup)
    return {
        "peak_stator_current": max(I0, -I_end),
        "peak_supply_current": peak_sup,
        "min_bus_voltage": m.battery_voltage - m.bus_resistance * peak_sup,
    }


def samples(setup: Setup, mv: Move, count: int = SAMPLES) -> dict[str, tuple[list[float], list[float]]]:
    """Position, speed, currents and bus voltage over time, from the dense output."""
    m = setup.mech
    d, v_ref, _, k_emf = mv.scales
    elec = electrical(m, setup.asm.slots["duty"])
    run = mv.run
    T = mv.time
    ts, q, v, i_st, i_sup, bus = [], [], [], [], [], []
    for k in range(count + 1):
        t = T * k / count
        y = run.y[-1] if k == count else run.at(t)
        u, I = elec(k_emf * y[1])
        ts.append(t)
        q.append(m.q_at(y[0] * d))
        v.append(m.s * y[1] * v_ref)
        i_st.append(I)
        i_sup.append(u * I)
        bus.append(m.battery_voltage - m.bus_resistance * u * I)
    return {
        "position": (ts, q),
        "speed": (ts, v),
        "stator_current": (ts, i_st),
        "supply_current": (ts, i_sup),
        "bus_voltage": (ts, bus),
    }


# --- feedforward and feedback (WPILib conventions) -----------------------------------------------


def feedforward(setup: Setup, q_hold: float) -> dict[str, float]:
    """kS, kG, kV, kA in volts per unit of q: V = kS·sgn(q̇) + kG + kV·q̇ + kA·q̈ from (M2)-(M4) at
    full bus voltage: kV = n/Kv, kA = M·R/(η·N·Kt·n), kG = −F_field(q_hold)·R/(η·N·Kt·n),
    kS = F_friction·R/(η·N·Kt·n) = R·i_f + (the friction effect's share)."""
    m = setup.mech
    fpv = m.force_per_volt
    return {
        "kS": friction_of(setup) / fpv,
        "kG": -field_force(setup)(q_hold) / fpv,
        "kV": m.n / m.Kv,
        "kA": m.inertia / fpv,
    }


@lru_cache(maxsize=256)
def lqr(
    kV: float, kA: float, q_position: float, q_velocity: float, r_volts: float, dt: float, delay: float
) -> tuple[float, float]:
    """kP, kD as WPILib's LinearQuadraticRegulator computes them (LinearQuadraticRegulator.java):
    plant ẋ = [[0, 1], [0, −kV/kA]]·x + [0, 1/kA]·u, discretised with a zero-order hold over dt;
    Q = diag(1/q_pos², 1/q_vel²), R = 1/r²; S from the discrete algebraic Riccati equation;
    K = (BᵀSB + R)⁻¹·BᵀSA; latency compensation K ← K·(A − B·K)^(delay/dt)."""
    import numpy as np

    # closed forms of the 2-state case (small_math.py L1-L3; scipy's expm, solve_discrete_are and
    # fractional_matrix_power gave the same to 1e-12, tests/test_small_math.py): no scipy import
    from .small_math import dare, matrix_power_2x2, zero_order_hold

    Ad, Bd = zero_order_hold(kV / kA, 1.0 / kA, dt)  # exp([[A, B], [0, 0]]·dt) = [[Ad, Bd], [0, I]]
    Q = np.diag([1.0 / q_position**2, 1.0 / q_velocity**2])
    R = np.array([[1.0 / r_volts**2]])
    S = dare(Ad, Bd, Q, R)
    K = np.linalg.solve(Bd.T @ S @ Bd + R, Bd.T @ S @ Ad)
    if not np.all(np.abs(np.linalg.eigvals(Ad - Bd @ K)) <= 1 + 1e-9):
        # Q and R many decades apart: the Riccati solve lost its digits and K destabilises the loop
        raise ValueError("the LQR gains do not stabilise the loop")
    if delay > 0:
        with np.errstate(all="ignore"):  # (A − BK)^(delay/dt) may overflow: non-finite, refused by the caller
            closed = matrix_power_2x2(Ad - Bd @ K, delay / dt)
            K = K @ np.real(closed)
    return float(K[0, 0]), float(K[0, 1])


# --- one move, as a scene run --------------------------------------------------------------------


class _ClosedRun:
    """The closed-form move, answering `at(t)` and `y[-1]` in the scaled state like a solver run."""

    def __init__(self, w_f, tau, T, scales, energy_of):
        self.w_f, self.tau, self.scales, self.energy_of = w_f, tau, scales, energy_of
        self.y = [self.at(T)]

    def at(self, t: float) -> list:
        d, v_ref, e_ref, _ = self.scales
        x = -t / self.tau
        p = self.w_f * (t + self.tau * math.expm1(x))  # (C1): w_f·(t − τ(1 − e^{−t/τ}))
        w = -self.w_f * math.expm1(x)  # w_f·(1 − e^{−t/τ})
        return [p / d, w / v_ref, self.energy_of(t, p) / e_ref]


SERIES_BELOW = 0.1  # x below which g(x) = x + e^{−x} − 1 is summed as its series (C4)


def _g(x: float) -> float:
    """x + e^{−x} − 1 (C2), as the series (C4) below SERIES_BELOW (20 terms: 0.1²⁰/20! ≪ 1e-16 of
    x²/2), where the direct form loses the digits x²/2 has (relative error ~2e-16/x)."""
    if x >= SERIES_BELOW:
        return x + math.expm1(-x)
    term, total = x * x / 2, 0.0
    for k in range(3, 23):
        total += term
        term *= -x / k
    return total


def close_time(D: float, lambert) -> float:
    """x = T/τ with g(x) = D (C2): from (C4) for D < 0.01 (W₀ near its branch point cancels there),
    else from lambert(D) (C2); then Newton on g (convex and increasing: it converges from either
    side, quadratically; 4 steps polish either start to rounding)."""
    if D < 0.01:
        s = math.sqrt(2 * D)
        x = s * (1 + s / 6)  # (C4)
    else:
        x = lambert(D)
    for _ in range(4):
        slope = -math.expm1(-x)
        if not slope > 0:
            break
        step = (_g(x) - D) / slope
        x -= step
        if abs(step) <= 1e-16 * x:
            break
    return x


def closed_form(setup: Setup) -> Move | None:
    """The move in closed form when nothing in it needs integrating: a force independent of
    position (elevator: gravity, friction, counterbalance) and no current limit (the motor force
    is then affine in speed, with or without battery sag: R_eff = R + R_bus):
        M·ẇ = η·N·Kt·n·(V_b − n·w/Kv)/R_eff + F_c,   F_c = s·F_field − F_friction
        w_f = (V_b + F_c·R_eff/(η·N·Kt·n))·Kv/n,   τ = M·R_eff·Kv/(η·N·Kt·n²)
        w = w_f·(1 − e^{−t/τ}),  p = w_f·(t − τ·(1 − e^{−t/τ}))                              (C1)
        p(T) = d ⇔ T/τ − 1 + e^{−T/τ} = D = d/(w_f·τ) ⇔ T/τ = D + 1 + W₀(−e^{−(D+1)})           (C2)
        energy = N·V_b·∫I dt = N·V_b·(V_b·t − n·p/Kv)/R_eff                                     (C3)
    (C2) is polished by Newton steps on g(x) = x + expm1(−x) = D, x = T/τ (close_time). For small D
    (a mechanism geared so high that it never nears its free speed) W₀ cancels to nothing and g
    itself cancels (x ≈ √(2D)), so there x starts from the series and g is summed as one:
        g(x) = Σ_{k≥2} (−x)^k/k! = D  ⇒  x = s + s²/6 + O(s³),  s = √(2D)                      (C4)
    None when the scene must be integrated."""
    if setup.varying or setup.asm.slots["duty"] is not None:
        return None
    from .small_math import lambert_w0  # scipy.special.lambertw's principal branch, without scipy

    m = setup.mech
    R_eff = m.R + m.bus_resistance
    fpa = m.force_per_amp
    F_c = m.s * field_force(setup)(m.q0) - friction_of(setup)
    w_f = (m.battery_voltage + F_c * R_eff / fpa) * m.Kv / m.n
    tau = m.inertia * R_eff * m.Kv / (fpa * m.n)
    D = m.distance / w_f / tau
    u = close_time(D, lambda D: D + 1 + lambert_w0(-math.exp(-(D + 1))))  # (C2)
    T = u * tau
    if not (T > 0 and math.isfinite(T) and math.isfinite(-w_f * math.expm1(-u))):
        raise InputError("ratio", "the move is out of floating-point range at this ratio: change the ratio")
    if T > T_MAX:  # as move(): an integrated move stops there
        raise InputError(
            "ratio",
            f"the mechanism does not reach the goal within {T_MAX:.0f} s "
            f"(it only just beats the load): raise the ratio or the motors",
        )
    _, _, scales = build_rhs(setup)
    n_kv = m.n / m.Kv

    def energy(t, p):
        return m.count * m.battery_voltage * (m.battery_voltage * t - n_kv * p) / R_eff  # (C3)

    run = _ClosedRun(w_f, tau, T, scales, energy)
    w_T = -w_f * math.expm1(-u)
    return Move(T, w_T, energy(T, m.distance), 0, run, scales, "closed form")


def run_move(setup: Setup, rtol: float, hold_q: float | None = None) -> SimRun:
    """Every output of one move; kG is quoted at hold_q (None: the goal). Closed form when nothing
    needs integrating (closed_form), else integrated (move)."""
    check_can_move(setup)
    m = setup.mech
    mv = closed_form(setup) or move(setup, rtol, dense=True)
    values: dict[str, Any] = {"time_to_goal": mv.time, "max_speed": mv.max_speed, "energy": mv.energy}
    values.update(extremes(setup, mv.max_speed))
    values["peak_battery_current"] = values["peak_supply_current"] * m.count
    hold_force = field_force(setup)(m.q1)
    if abs(hold_force) < 1e-12 * max(abs(field_force(setup)(q)) for q in (m.q0, m.q1, 0.0)):
        hold_force = 0.0  # cos(90°) in floating point: an arm straight up needs no holding
    values["hold_current"] = abs(hold_force) / m.force_per_amp
    values["free_speed"] = m.free_speed
    ff = feedforward(setup, m.q1 if hold_q is None else hold_q)
    values.update(ff)
    values.update(setup.asm.report(mv))
    v = setup.values
    try:
        kP, kD = lqr(
            ff["kV"],
            ff["kA"],
            v["q_position"],
            v["q_velocity"],
            v["r_volts"],
            v["control_period"],
            v["sensor_delay"],
        )
    except (ValueError, ArithmeticError, Exception) as exc:  # noqa: BLE001 - scipy raises LinAlgError
        raise InputError(
            "q_position", f"no LQR solution for these tolerances ({type(exc).__name__})"
        ) from None
    if not (math.isfinite(kP) and math.isfinite(kD)):
        raise InputError("q_position", "the LQR gains are not finite for these tolerances")
    values.update(kP=kP, kD=kD)
    warnings: list[str] = []
    if mv.method == "closed form":
        warnings.append(
            "Nothing in this move needs integrating (a constant load, no current limit): "
            "closed form, no integration."
        )
    if "stator_limit" in setup.asm.on and values["hold_current"] > v["stator_current_limit"]:
        warnings.append(
            "The stator current limit is below the current needed to hold at the goal: "
            "it arrives, but cannot stay there."
        )
    key = {"time_to_goal": mv.time, "max_speed": mv.max_speed, "energy": abs(mv.energy)}
    return SimRun(values, key, mv.nfev, warnings, samples(setup, mv))


# --- fields every motor scene shares -------------------------------------------------------------

MODES = ("move", "optimise")
MODE_LABELS = ("One move at the given ratio", "Optimise: the ratio that arrives first")


def battery_motor_fields(default_motor: str, default_count: int) -> tuple[Field, ...]:
    """The motor fields, the voltage being the battery's at rest (a move runs at full voltage)."""
    return tuple(
        replace(
            f,
            label="Battery voltage",
            default=12,
            help="Battery voltage at rest (open circuit); full voltage toward the goal.",
        )
        if f.name == "voltage"
        else f
        for f in motor_fields(default_motor=default_motor, default_count=default_count)
    )


PROFILED_LABEL = "Profiled move: trapezoid, feedforward + PD at the control period"


GRID_LABEL = "Current-limit grid: the fastest ratio for each stator × supply limit"


def mode_field(profiled: bool = False, grid: bool = False) -> Field:
    """`profiled`: the scene offers core.sim.profiled's closed-loop move as a mode; `grid`: the
    current-limit grid of core.sim.limit_grid."""
    return Field(
        "mode",
        "Solve",
        choices=MODES + (("profiled",) if profiled else ()) + (("limit_grid",) if grid else ()),
        choice_labels=MODE_LABELS + ((PROFILED_LABEL,) if profiled else ()) + ((GRID_LABEL,) if grid else ()),
        default="move",
        help="One move at the ratio you give, or the ratio that reaches the goal fastest "
        "(time against ratio plotted)"
        + (", or the move as robot code runs it (profile, feedforward, feedback)." if profiled else "."),
    )


def feedback_fields(
    position_quantity: str | None,
    position_unit: str,
    q_pos: float,
    speed_quantity: str,
    speed_unit: str,
    q_vel: float,
    *,
    when: tuple = (),
    lqr_when: tuple | None = None,
) -> tuple[Field, ...]:
    """The LQR tolerances and the loop's period and delay, one declaration for every loop (the
    mechanisms' position loop, the flywheel's velocity loop): their names, labels, limits and help
    are the same wherever they appear (tests/test_shared_fields.py). `position_quantity` None: a
    velocity loop, whose one state is the speed (no q_position). `when`: shown only then;
    `lqr_when`: the tolerances' own condition (default `when`)."""
    lqr_when = when if lqr_when is None else lqr_when
    position = (
        ()
        if position_quantity is None
        else (
            Field(
                "q_position",
                "LQR position tolerance",
                position_quantity,
                position_unit,
                default=q_pos,
                min=0,
                min_exclusive=True,
                max=3.9e4,
                when=lqr_when,
                help="LQR state tolerance on position (WPILib qelms[0]): the error you accept.",
            ),
        )
    )
    return (
        *position,
        Field(
            "q_velocity",
            "LQR velocity tolerance",
            speed_quantity,
            speed_unit,
            default=q_vel,
            min=0,
            min_exclusive=True,
            max=3.9e5,
            when=lqr_when,
            help="LQR state tolerance on velocity (WPILib's qelms entry for it): the speed error you "
            "accept, Q = 1/q².",
        ),
        Field(
            "r_volts",
            "LQR control effort",
            "voltage",
            "V",
            default=12,
            min=0,
            min_exclusive=True,
            max=100,
            when=lqr_when,
            help="LQR input tolerance (WPILib relms): the voltage you are willing to apply, R = 1/r².",
        ),
        Field(
            "control_period",
            "Control period",
            "time",
            "ms",
            default=20,
            min=0.1,
            max=1000,
            when=when,
            help="Loop period dt: the gains are discretised for it and the voltage is held between "
            "updates (roboRIO: 20 ms; on a motor controller: 1 ms).",
        ),
        Field(
            "sensor_delay",
            "Sensor delay",
            "time",
            "ms",
            default=0,
            min=0,
            max=1000,
            when=when,
            help="Measurement latency: the loop acts on the state measured this long ago; the LQR "
            "gains are latency-compensated as WPILib's LinearQuadraticRegulator.latencyCompensate "
            "does (0: none).",
        ),
    )


def common_outputs(
    position_q: str,
    position_u: str,
    speed_q: str,
    speed_u: str,
    per_speed_u: str,
    per_accel_u: str,
    per_pos_u: str,
    kg_help: str,
) -> tuple[Output, ...]:
    return (
        Output(
            "time_to_goal",
            "Time to goal",
            "time",
            "s",
            help="First arrival at the goal, from rest at "
            "full voltage (an event located on the solver's dense output, not a step grid).",
        ),
        Output("max_speed", "Max speed", speed_q, speed_u),
        Output("free_speed", "Free speed", speed_q, speed_u, help="At the battery voltage, no load."),
        Output(
            "peak_stator_current", "Peak stator current", "current", "A", help="Per motor (at the start)."
        ),
        Output(
            "peak_supply_current",
            "Peak supply current",
            "current",
            "A",
            help="Per motor: stator current × duty.",
        ),
        Output("peak_battery_current", "Peak battery current", "current", "A", help="All motors."),
        Output(
            "min_bus_voltage",
            "Min bus voltage",
            "voltage",
            "V",
            help="Battery voltage minus the sag (battery_sag); the battery voltage when that effect is off.",
        ),
        Output(
            "energy",
            "Energy",
            "energy",
            "J",
            help="Drawn from the battery over the move (its EMF × current).",
        ),
        Output(
            "hold_current",
            "Hold current",
            "current",
            "A",
            help="Per motor, to hold at the goal "
            "against the field (gravity, counterbalance); friction not counted on.",
        ),
        Output(
            "kS",
            "kS",
            "voltage",
            "V",
            help="WPILib kS: volts to overcome the motors' own loss (R·i_f) and the friction effect.",
        ),
        Output("kG", "kG", "voltage", "V", help=kg_help),
        Output("kV", "kV", f"voltage_per_{speed_q}", per_speed_u, help="WPILib kV: volts per unit of speed."),
        Output(
            "kA",
            "kA",
            f"voltage_per_{'angular_' if speed_q == 'angular_speed' else ''}acceleration",
            per_accel_u,
            help="WPILib kA: volts per unit of acceleration.",
        ),
        Output(
            "kP",
            "kP",
            f"voltage_per_{position_q}",
            per_pos_u,
            help="LQR position gain (WPILib LinearQuadraticRegulator, latency-compensated).",
        ),
        Output("kD", "kD", f"voltage_per_{speed_q}", per_speed_u, help="LQR velocity gain."),
    )


# --- optimise: the ratio that arrives first ------------------------------------------------------

CANDIDATES = 240
BATCH_STEPS = 150  # steps per candidate over its estimated move time (0.3 % on the time: a screen)


def plots(
    position_label: str, position_q: str, position_u: str, speed_q: str, speed_u: str
) -> tuple[Plot, ...]:
    """The charts of a move (position, speed, currents, bus voltage over time) and of optimise."""
    return (
        Plot(
            position_label.capitalize(),
            ("position",),
            "time",
            "time",
            "s",
            position_label,
            position_q,
            position_u,
        ),
        Plot("Speed", ("speed",), "time", "time", "s", "speed", speed_q, speed_u),
        Plot(
            "Current (per motor)",
            ("stator_current", "supply_current"),
            "time",
            "time",
            "s",
            "current",
            "current",
            "A",
        ),
        Plot("Bus voltage", ("bus_voltage",), "time", "time", "s", "voltage", "voltage", "V"),
        Plot(
            "Time vs ratio (optimise)",
            ("time_vs_ratio",),
            "ratio",
            "dimensionless",
            "",
            "time to goal",
            "time",
            "s",
        ),
    )


def characteristic_n(m: Mechanism) -> float:
    """The transmission n at which the move's distance equals free speed × time constant:
    d = (V·Kv/n)·(M·R·Kv/(η·N·Kt·n²)) ⇒ n = (V·Kv²·M·R/(η·N·Kt·d))^(1/3). The fastest ratio lies
    within a decade or so of it (short moves gear down, long moves gear up)."""
    return (m.battery_voltage * m.Kv**2 * m.inertia * m.R / (m.efficiency * m.count * m.Kt * m.distance)) ** (
        1 / 3
    )


def batch_times(setup: Setup) -> Any:
    """Time to goal of every candidate of a batch setup (mech.n an array), numpy over candidates;
    nan where a candidate cannot move. Exponential Euler on the speed with the local slope
    J = ∂a/∂w (exact for an acceleration affine in speed, stable however stiff), position by the
    matching φ2 term; the arrival is located on the cubic Hermite through the last step."""
    np = setup.mech.xp.np
    m = setup.mech
    s, d, q0, M = m.s, m.distance, m.q0, m.inertia
    n = np.asarray(m.n, dtype=float)
    elec = electrical(m, setup.asm.slots["duty"])
    force = setup.asm.slots["force"]
    F_fric = friction_of(setup)
    fpa = m.force_per_amp
    k_emf = n / m.Kv

    def accel(p, w):
        _, I = elec(k_emf * w)
        F = fpa * I - F_fric
        if force is not None:
            F = F + s * force(q0 + s * p)
        return F / M

    lo, hi = sorted((m.q0, m.q1))
    points = [m.q0, m.q1] + [q for q in setup.critical if lo < q < hi]
    F_field = field_force(setup)
    load = max(float(np.max(-s * np.asarray(F_field(q)) + 0 * n)) for q in points) + F_fric
    _, I0 = elec(0.0 * n)
    movable = fpa * I0 > load
    tau = M * m.R * m.Kv / (fpa * n)
    F_net = np.where(movable, fpa * I0 - load, np.nan)
    T_est = d / m.free_speed + tau + np.sqrt(2 * d * M / F_net)
    h = np.where(movable, T_est / BATCH_STEPS, 0.0)
    return batch_arrival(accel, d, h, ~movable, m.free_speed)


def batch_arrival(accel, d: float, h: Any, done: Any, w_scale: Any, timed: bool = False) -> Any:
    """When each candidate of a batch, from rest, first covers the distance d: `accel(p, w)` over
    numpy arrays (nan where done from the start; `accel(p, w, t)` when `timed`), h the step of each
    candidate, w_scale a speed scale for the slope's difference quotient. Exponential Euler on the speed with the local slope
    J = ∂a/∂w (exact for an acceleration affine in speed, stable however stiff), position by the
    matching φ2 term; the arrival is located on the cubic Hermite through the last step."""
    import numpy as np

    # candidates that cannot move are nan from the start, and stay so: no warning for them
    with np.errstate(divide="ignore", invalid="ignore"):
        return _batch_arrival(accel, d, h, done, w_scale, timed)


def _batch_arrival(accel, d: float, h: Any, done: Any, w_scale: Any, timed: bool) -> Any:
    import numpy as np

    p = np.zeros_like(h)
    w = np.zeros_like(h)
    t = np.zeros_like(h)
    arrival = np.full_like(h, np.nan)
    for _ in range(40 * BATCH_STEPS):
        if done.all():
            break
        # a time-dependent acceleration is taken at the step's middle (second order for a forcing
        # linear in time, as a ramp is)
        step_accel = (lambda p_, w_, mid=t + h / 2: accel(p_, w_, mid)) if timed else accel
        # three accelerations a step, each over every candidate counted as one (as the trebuchet's
        # batch_ranges): the solve's CPU backstop and cancel are polled each step
        charge(3)
        a = step_accel(p, w)
        dw = 1e-7 * (np.abs(w) + w_scale)
        J = (step_accel(p, w + dw) - a) / dw
        # across a kink (a current limit letting go) within the step the local slope says too
        # little: take the secant over the step's predicted change when it damps more
        jump = np.where(np.abs(h * a) > dw, h * a, dw)
        J = np.minimum(J, (step_accel(p, w + jump) - a) / jump)
        z = np.minimum(h * J, -1e-12)  # J < 0: the back-EMF damps; never amplify
        ez = np.exp(z)
        phi1 = np.where(z < -1e-4, (ez - 1) / np.where(z < -1e-4, z, 1.0), 1 + z / 2 + z * z / 6)
        phi2 = np.where(z < -1e-4, (ez - 1 - z) / np.where(z < -1e-4, z * z, 1.0), 0.5 + z / 6 + z * z / 24)
        w1 = w + h * phi1 * a
        p1 = p + h * w + h * h * phi2 * a
        arrived = (~done) & (p1 >= d)
        if arrived.any():
            # cubic Hermite p(θ) on [t, t + h] through (p, w) and (p1, w1): solve p(θ) = d by Newton
            th = np.clip((d - p) / np.maximum(p1 - p, 1e-300), 0.0, 1.0)
            for _ in range(6):
                h00, h10, h01, h11 = (
                    2 * th**3 - 3 * th**2 + 1,
                    th**3 - 2 * th**2 + th,
                    -2 * th**3 + 3 * th**2,
                    th**3 - th**2,
                )
                f = h00 * p + h10 * h * w + h01 * p1 + h11 * h * w1 - d
                df = (
                    (6 * th**2 - 6 * th) * p
                    + (3 * th**2 - 4 * th + 1) * h * w
                    + (-6 * th**2 + 6 * th) * p1
                    + (3 * th**2 - 2 * th) * h * w1
                )
                th = np.clip(th - f / np.where(np.abs(df) > 1e-300, df, 1e-300), 0.0, 1.0)
            arrival = np.where(arrived, t + th * h, arrival)
            done = done | arrived
        live = ~done
        p = np.where(live, p1, p)
        w = np.where(live, w1, w)
        t = np.where(live, t + h, t)
    return arrival


def optimise(
    make_setup, ratio_hint: float, rtol: float, length_scale: float, hold_q: float | None = None
) -> SimRun:
    """The reduction G that reaches the goal first: a batch of CANDIDATES ratios (log-spaced over
    two and a half decades each side of the characteristic ratio, numpy over candidates), then the
    best one refined with scipy's bounded Brent on the accurate move, and the full move there.
    make_setup(G, xp) -> Setup; n = G/length_scale."""
    import numpy as np
    from scipy.optimize import minimize_scalar

    probe = make_setup(ratio_hint)
    G_char = characteristic_n(probe.mech) * length_scale
    lo_G, hi_G = G_char * 10**-2.5, G_char * 10**2.5
    # below G_hold the stall force (∝ G; the current at rest does not depend on G) loses to the load
    pm = probe.mech
    lo_q, hi_q = sorted((pm.q0, pm.q1))
    points = [pm.q0, pm.q1] + [q for q in probe.critical if lo_q < q < hi_q]
    load = max(-pm.s * field_force(probe)(q) for q in points) + effect_friction(probe)
    _, I0 = electrical(pm, probe.asm.slots["duty"])(0.0)
    if load > 0 and I0 > pm.free_current:  # the motors give η·N·Kt·n·(I0 − i_f) ∝ G at rest (M3)
        G_hold = ratio_hint * load / (pm.force_per_amp * (I0 - pm.free_current))
        lo_G = max(lo_G, 1.001 * G_hold)
        hi_G = max(hi_G, 100 * lo_G)
    ratios = np.geomspace(lo_G, hi_G, CANDIDATES)
    batch = make_setup(ratios, _Array())
    times = batch_times(batch)
    ok = np.isfinite(times)
    if not ok.any():
        check_can_move(make_setup(float(ratios[-1])))  # names the reason (a limit, the sag, the load)
        raise InputError("ratio", "no ratio moves this load to the goal")
    i = int(np.nanargmin(np.where(ok, times, np.nan)))
    # the batch is good to a few 0.1 %; near the optimum the curve is flat, so bracket generously
    lo, hi = float(ratios[max(i - 5, 0)]), float(ratios[min(i + 5, CANDIDATES - 1)])
    nfev = [0]

    def time_at(G):
        try:
            mv = move(make_setup(float(G)), rtol)
        except InputError:
            return math.inf
        nfev[0] += mv.nfev
        return mv.time

    best = minimize_scalar(time_at, bounds=(lo, hi), method="bounded", options={"xatol": 1e-6 * lo})
    G_best = float(best.x)
    run = run_move(make_setup(G_best), rtol, hold_q)
    run.values["best_ratio"] = G_best
    run.nfev += nfev[0]
    run.key["best_ratio"] = G_best
    run.series["time_vs_ratio"] = ([float(r) for r in ratios[ok]], [float(x) for x in times[ok]])
    if i in (0, CANDIDATES - 1):
        run.warnings.append(
            f"The fastest ratio is at the edge of the range searched ({ratios[0]:.3g} to {ratios[-1]:.3g})."
        )
    return run
