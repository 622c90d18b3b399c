"""A profiled closed-loop move: the mechanism of core.sim.motion driven the way robot code drives
it, a trapezoid profile with feedforward plus PD feedback evaluated every control period, the
voltage held between updates (zero-order hold), saturating at the battery voltage, with the
current-limit and sag effects of core.sim.motor_limits.

The robot code (WPILib's ProfiledPIDController + ElevatorFeedforward, as its examples use them), at
the updates t_k = k·dt, k = 0, 1, ...:
    (r_k, ṙ_k) = profile(t_k),  (r_{k+1}, ṙ_{k+1}) = profile(t_{k+1})            (P1), (P2)
    y_k = q(t_k − δ)   the measured position, δ the sensor delay (q(0) before δ)      (P3)
    e_k = r_{k+1} − y_k,  V_fb = kP·e_k + kD·(e_k − e_{k−1})/dt,  e_{−1} = 0         (P4)
          (WPILib PIDController.Calculate: the derivative is the error's difference)
    V_ff = kS·sgn(ṙ_k) + kG(r_k) + (ṙ_{k+1} − A_d·ṙ_k)/B_d,  A = −kV/kA, B = 1/kA,
           A_d = e^{A·dt}, B_d = (A_d − 1)·B/A   (ElevatorFeedforward.Calculate(current, next);
           kS·sgn(ṙ_{k+1}) + kG + kV·ṙ_{k+1} when kA < 1e-9)                         (P5)
    an arm's, kG(r) = kG·cos r, is WPILib's ArmFeedforward.Calculate(r_k, ṙ_k, ṙ_{k+1}) instead, as
    2026.2.2 computes it: kS·sgn(ṙ_k) + kV·ṙ_k + kA·(ṙ_{k+1} − ṙ_k)/dt + kG·cos r_k when kA < 0.1
    (no inversion of the plant: a period's lag the feedback makes up), else that refined by its
    Newton iteration on one RK4 step of the arm's plant (arm_feedforward)                (P5a)
    V_k = clamp(V_fb + V_ff, −V_b, V_b),  duty u_k = V_k/V_b, held over [t_k, t_{k+1})  (P6)
The profile r(t): WPILib's TrapezoidProfile (P1), (P2), its limits entered or derived from the
mechanism (P17), or its ExponentialProfile (P12)-(P15), all in core.sim.profiles.
The plant between updates (per motor; the duty signed, a limit lowers its magnitude):
    E = n·q̇/Kv,  u = clamp(u_k, −b(−E), b(E)),  b the shared duty bound of the limits on
    ((E2), (E3), the duty a limit lets a driving motor rise to; mirrored for a current the other
    way, so the stator limit holds |I| while the loop brakes too, as a controller's current loop
    does; the full-voltage move of core.sim.motion never brakes against its command)
    I = (u·V_b − E)/(R + u²·R_bus)                                                 (E1), signed
    M·q̈ = η·N·Kt·n·I + F_field(q) − F_fric·sgn(q̇)                                     (P7)
F_fric is the motors' own loss (M3) plus the friction effect (Coulomb, against the motion). At
q̇ = 0 the mechanism sticks while |η·N·Kt·n·I + F_field| ≤ F_fric (both constant there for the rest
of the period: the duty is held, E = 0 and q does not change), else moves toward that force. Each
period is integrated from t_k to t_{k+1} by core.sim.integrate's EXP method ((X1)-(X3), exponential
in the speed: DP54 is held to steps ≈ 3τ there), with a terminal event where q̇ passes 0 (the
friction changes sign there) and the band events below.
Outputs:
    settle time: the first t after which |q − goal| ≤ tol up to the end of the window, the band
    edges located as events on the dense output (continuous, not on the update grid)      (P8)
    window: the profile's time T plus max(1 s, T)
    overshoot = max(0, max_t s·(q − goal));  final error = s·(goal − q) at the window's end
    (positive: short of the goal)                                                        (P9)
    tracking error at the updates: r(t_k) − q(t_k) (RMS and peak over the window)       (P10)
    peak stator |I| and supply u·I per motor, lowest bus V_b − R_bus·max(u·I): over the
    integrator's step points and each period's ends (the current jumps at an update)    (P11)
    energy = ∫ N·V_b·u·I dt (regeneration negative)
The return move (an arm's way back): (P1)-(P11) from rest at the goal to the start, q0 ↔ q1,
with the same loop and profile                                                         (P16)
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from ..errors import InputError
from .integrate import Event, integrate
from .scene import SimRun

if TYPE_CHECKING:
    from .profiles import Exponential, Trapezoid

SETTLE_EXTRA = 1.0  # s: the window is the profile's time plus the larger of this and that time
MAX_PIECES = 50  # friction reversals within one period beyond which the mechanism is held stuck
STEP_CAP = 20_000  # DP54 steps per period (stiff: held to ≈ 3τ by stability)
FIXED_STEP = 1e-4  # s: the reference's step (method RK4, bench/bench_profiled.py)


@dataclass(frozen=True)
class Loop:
    """The robot code's constants, in SI per unit of q (P4)-(P6)."""

    kS: float
    kG: Any  # q -> volts (constant for an elevator)
    kV: float
    kA: float
    kP: float
    kD: float
    period: float
    delay: float
    tolerance: float
    arm: bool = False  # kG(q) = kG·cos q: WPILib ArmFeedforward's calculate (P5a), not (P5)

    def feedforward(self, r: float, v: float, v_next: float) -> float:
        """(P5): WPILib ElevatorFeedforward.Calculate(currentVelocity, nextVelocity), kG at r;
        an arm's (P5a), ArmFeedforward.Calculate(currentAngle, currentVelocity, nextVelocity)."""
        if self.arm:
            # kG(q) is kG·cos q for an arm: its value at horizontal is ArmFeedforward's kG
            return arm_feedforward(self.kS, self.kG(0.0), self.kV, self.kA, self.period, r, v, v_next)
        kG = self.kG(r)
        if self.kA < 1e-9:
            return self.kS * _sgn(v_next) + kG + self.kV * v_next
        A = -self.kV / self.kA
        B = 1.0 / self.kA
        A_d = math.exp(A * self.period)
        B_d = B * self.period if A > -1e-9 else (A_d - 1.0) * B / A
        return kG + self.kS * _sgn(v) + (v_next - A_d * v) / B_d


def _sgn(x: float) -> float:
    return (x > 0) - (x < 0)


ARM_KA_SOLVE = 0.1  # V·s²/rad: ArmFeedforward uses the plain formula below this (P5a)


def arm_feedforward(kS, kG, kV, kA, dt, angle, v, v_next) -> float:
    """(P5a): WPILib 2026.2.2 ArmFeedforward::Calculate(currentAngle, currentVelocity, nextVelocity)
    (wpimath/src/main/native/cpp/controller/ArmFeedforward.cpp at v2026.2.2; Java's
    calculateWithVelocities calls it through JNI), kG the volts at horizontal:
    - kA < 0.1: kS·sgn(v) + kV·v + kA·(v_next − v)/dt + kG·cos θ, no inversion of the plant;
    - else that formula as the first guess of u, refined by WPILib's own Newton iteration on the
      squared miss c(u) = (v_next − ω₁(u))², ω₁ the speed after one RK4 step over dt of
      θ̇ = ω, kA·ω̇ = u − kS·sgn ω − kV·ω − kG·cos θ from (θ, v): u ← u − c'/max(c'', 1e-4), the
      step halved while c grows, at most 50 times, stopping when |c'| no longer falls by 1e-10 of
      itself. Its derivatives are exact (sgn's taken as 0, as Sleipnir's autodiff does); the
      regularised c'' leaves u short of the root when (dt/kA)² < 5e-5, as WPILib's does."""
    guess = kS * _sgn(v) + kV * v + kA * (v_next - v) / dt + kG * math.cos(angle)
    if kA < ARM_KA_SOLVE:
        return guess

    # second-order forward derivatives in u: each quantity as (value, d/du, d²/du²)
    def f(x0, x1, u):
        c, sn = math.cos(x0[0]), math.sin(x0[0])
        cos = (c, -sn * x0[1], -c * x0[1] ** 2 - sn * x0[2])
        ks = kS * _sgn(x1[0])
        acc = tuple(
            ((u if i == 0 else (1.0 if i == 1 else 0.0)) - kV * x1[i] - kG * cos[i]) / kA for i in range(3)
        )
        acc = (acc[0] - ks / kA, acc[1], acc[2])
        return x1, acc

    def add(x, k, h):
        return tuple(x[i] + h * k[i] for i in range(3))

    def cost(u):
        th, om = (angle, 0.0, 0.0), (v, 0.0, 0.0)
        a1, b1 = f(th, om, u)
        a2, b2 = f(add(th, a1, dt / 2), add(om, b1, dt / 2), u)
        a3, b3 = f(add(th, a2, dt / 2), add(om, b2, dt / 2), u)
        _, b4 = f(add(th, a3, dt), add(om, b3, dt), u)
        w = tuple(v * (i == 0) + dt / 6 * (b1[i] + 2 * b2[i] + 2 * b3[i] + b4[i]) for i in range(3))
        r = v_next - w[0]
        return r * r, -2 * r * w[1], 2 * w[1] ** 2 - 2 * r * w[2]

    u = guess
    c, g, H = cost(u)
    error_k, error_k1 = math.inf, abs(g)
    for _ in range(50):
        if not error_k1 < (1.0 - 1e-10) * error_k:
            break
        error_k = error_k1
        step = -g / max(H, 1e-4)
        alpha, trial = 1.0, u + step
        c_trial = cost(trial)[0]
        for _ in range(1100):  # halving to below a double's resolution of any step
            if not c_trial > c:
                break
            alpha *= 0.5
            trial = u + alpha * step
            c_trial = cost(trial)[0]
        u = trial
        c, g, H = cost(u)
        error_k1 = abs(g)
    return u


def driver(mech, duty_bound):
    """(u_cmd, E) -> (u, I) per motor for a signed duty command: the shared duty bound b(E) of the
    limits that are on ((E2), (E3): what the duty may rise to while driving) caps it, and its mirror
    −b(−E) floors it (I(−u, −E) = −I(u, E): the same limits on a current the other way, e.g. the
    stator current while the loop brakes), then (E1)."""
    Vb, R, Rb = mech.battery_voltage, mech.R, mech.bus_resistance
    if duty_bound is None:

        def drive(u_cmd: float, E: float) -> tuple[float, float]:
            return u_cmd, (u_cmd * Vb - E) / (R + u_cmd * u_cmd * Rb)

        return drive

    def drive(u_cmd: float, E: float) -> tuple[float, float]:
        # a current forward (u·V_b > E) meets the cap only, one backward the floor only
        u = min(u_cmd, duty_bound(E)) if u_cmd * Vb > E else max(u_cmd, -duty_bound(-E))
        u = min(max(u, -1.0), 1.0)
        return u, (u * Vb - E) / (R + u * u * Rb)

    return drive


@dataclass
class ProfiledRun:
    values: dict
    series: dict
    nfev: int
    updates: int
    saturated: int
    settled: bool
    key: dict


def profiled_move(
    setup, loop: Loop, profile: Trapezoid | Exponential, rtol: float, method: str = "EXP"
) -> ProfiledRun:
    """Simulate the loop (P1)-(P7) over the window and report (P8)-(P11). `method`: the periods'
    integrator (core.sim.integrate): EXP, or DP54 or RK4 (a fixed 0.1 ms step) as references."""
    m = setup.mech
    s, d_move, q0, q1 = m.s, m.distance, m.q0, m.q1
    from .motion import field_force, friction_of

    field = setup.asm.slots["force"]
    F_fric = friction_of(setup)
    drive = driver(m, setup.asm.slots["duty"])
    fpa, M, Vb, Rb, N = m.force_per_amp, m.inertia, m.battery_voltage, m.bus_resistance, m.count
    n_kv = m.n / m.Kv
    d = d_move  # position scale
    v_ref = m.free_speed
    e_ref = 1e-3 * N * Vb * Vb / m.R * d / v_ref
    dt = loop.period
    T_prof = profile.total_time
    T_end = T_prof + max(SETTLE_EXTRA, T_prof)
    K = math.ceil(T_end / dt - 1e-9)
    T_end = K * dt
    goal_s = s  # goal in scaled position (q1 − q0)/d
    tol_s = loop.tolerance / d
    ff_field = field_force(setup)
    # the method's own options: EXP's plant ṗ = c·w in these scaled units, an arm's gravity pulling
    # on the speed; DP54's step cap a period; RK4's fixed step
    options = {
        "EXP": {"scale": v_ref / d, "p_coupled": field is not None and setup.varying},
        "DP54": {"max_steps": STEP_CAP},
        "RK4": {"step": FIXED_STEP},
    }.get(method, {})

    def net_force_at_rest(u_cmd: float, q: float) -> float:
        _, I = drive(u_cmd, 0.0)
        return fpa * I + ff_field(q)

    def make_rhs(u_cmd: float, dirn: float):
        F_f = dirn * F_fric
        e_scale = N * Vb / e_ref
        a_scale = 1.0 / (M * v_ref)
        p_scale = v_ref / d
        if field is None:

            def rhs(t, y):
                u, I = drive(u_cmd, n_kv * v_ref * y[1])
                return [y[1] * p_scale, (fpa * I - F_f) * a_scale, u * I * e_scale]
        else:

            def rhs(t, y):
                u, I = drive(u_cmd, n_kv * v_ref * y[1])
                F = fpa * I + field(q0 + d * y[0]) - F_f
                return [y[1] * p_scale, F * a_scale, u * I * e_scale]

        return rhs

    band = [
        Event("band_hi", lambda t, y: y[0] - goal_s - tol_s, 0, terminal=False),
        Event("band_lo", lambda t, y: y[0] - goal_s + tol_s, 0, terminal=False),
    ]
    # history of the position for the delayed measurement: piece starts, and (run or constant)
    starts: list[float] = []
    pieces: list[tuple[float, float, Any, list]] = []

    def q_scaled_at(t: float) -> float:
        if t <= 0:
            return 0.0
        i = bisect.bisect_right(starts, t) - 1
        ta, tb, run, y = pieces[i]
        if run is None or t >= tb:
            return y[0] if run is None else run.y[-1][0]
        return run.at(t)[0]

    y = [0.0, 0.0, 0.0]
    nfev = 0
    h = None
    e_prev = 0.0
    saturated = 0
    crossings: list[float] = []
    track: list[float] = []
    ts_out, q_out, r_out, v_out = [], [], [], []
    volt_t, volt_v = [], []
    cur_t, cur_st, cur_sup, cur_bus = [], [], [], []
    peak_stator = peak_supply = 0.0
    max_over = 0.0
    max_speed = 0.0

    def note_current(t, u_cmd, yy):
        nonlocal peak_stator, peak_supply
        u, I = drive(u_cmd, n_kv * v_ref * yy[1])
        peak_stator = max(peak_stator, abs(I))
        peak_supply = max(peak_supply, u * I)
        cur_t.append(t)
        cur_st.append(I)
        cur_sup.append(u * I)
        cur_bus.append(Vb - Rb * u * I)

    for k in range(K):
        t_k, t_next = k * dt, (k + 1) * dt
        p_k, pv_k = profile.at(t_k)
        p_n, pv_n = profile.at(t_next)
        r_k, rv_k = q0 + s * p_k, s * pv_k
        r_n, rv_n = q0 + s * p_n, s * pv_n
        meas = q0 + d * q_scaled_at(t_k - loop.delay)  # (P3)
        e = r_n - meas  # (P4)
        V = loop.kP * e + loop.kD * (e - e_prev) / dt + loop.feedforward(r_k, rv_k, rv_n)
        e_prev = e
        if not math.isfinite(V):
            raise InputError("kP", "the loop's voltage is not a number: the gains are too large")
        if abs(V) > Vb:
            saturated += 1
            V = math.copysign(Vb, V)  # (P6)
        u_cmd = V / Vb
        q_k = q0 + d * y[0]
        track.append(r_k - q_k)  # (P10)
        ts_out.append(t_k)
        q_out.append(q_k)
        r_out.append(r_k)
        v_out.append(v_ref * y[1])
        volt_t += [t_k, t_next]
        volt_v += [V, V]
        note_current(t_k, u_cmd, y)
        # integrate the period, piece by piece between reversals of the motion
        t = t_k
        restart: tuple[str, ...] = ()
        for _ in range(MAX_PIECES):
            if y[1] == 0.0:
                F0 = net_force_at_rest(u_cmd, q0 + d * y[0])
                if abs(F0) <= F_fric:  # stuck for the rest of the period (P7)
                    u, I = drive(u_cmd, 0.0)
                    y = [y[0], 0.0, y[2] + N * Vb * u * I / e_ref * (t_next - t)]
                    starts.append(t)
                    pieces.append((t, t_next, None, y))
                    t = t_next
                    break
                dirn = 1.0 if F0 > 0 else -1.0
            else:
                dirn = 1.0 if y[1] > 0 else -1.0
            stop = Event("stop", (lambda dn: lambda t_, yy: dn * yy[1])(dirn), -1, terminal=True)
            run = integrate(
                make_rhs(u_cmd, dirn),
                t,
                t_next,
                y,
                rtol=rtol,
                atol=rtol,
                events=[stop, *band],
                first_step=h,
                dense=True,
                restart=restart,
                method=method,
                **options,
            )
            nfev += run.nfev
            if run.dense:
                h = min(dt, max(abs(hs) for _, hs, _ in run.dense))
            starts.append(t)
            pieces.append((t, run.t[-1], run, run.y[-1]))
            crossings += [c[1] for c in run.crossings]
            for tt, yy in zip(run.t[1:], run.y[1:]):
                note_current(tt, u_cmd, yy)
                max_over = max(max_over, s * (yy[0] - goal_s) * d)
                max_speed = max(max_speed, abs(yy[1]) * v_ref)
            y = list(run.y[-1])
            t = run.t[-1]
            if run.event == "stop":
                y[1] = 0.0
                restart = ("stop",)
                if t >= t_next * (1 - 1e-15):
                    break
                continue
            break
        else:
            y = [y[0], 0.0, y[2]]  # chattering about zero speed: held at rest for the period
            t = t_next
    q_end = q0 + d * y[0]
    ts_out.append(T_end)
    q_out.append(q_end)
    r_out.append(q1)
    v_out.append(v_ref * y[1])
    track.append(q1 - q_end)
    err_end = q_end - q1
    settled = abs(err_end) <= loop.tolerance
    settle = None
    if settled:
        settle = max(crossings) if crossings else 0.0  # (P8)
    rms = math.sqrt(sum(x * x for x in track) / len(track))
    values = {
        "profile_time": T_prof,
        "profile_max_velocity": profile.v_max,
        "profile_max_acceleration": profile.a_max,
        "overshoot": max_over,
        "final_error": -s * err_end,
        "rms_tracking_error": rms,
        "peak_tracking_error": max(abs(x) for x in track),
        "peak_stator_current": peak_stator,
        "peak_supply_current": peak_supply,
        "peak_battery_current": N * peak_supply,
        "min_bus_voltage": Vb - Rb * peak_supply,
        "energy": y[2] * e_ref,
        "max_speed": max_speed,
        "control_updates": K,
    }
    if settle is not None:
        values["settle_time"] = settle
    key = {
        "peak_tracking_error": values["peak_tracking_error"],
        "overshoot": max_over,
        "peak_stator_current": peak_stator,
    }
    if settle is not None:
        key["settle_time"] = settle
    series = {
        "position": (ts_out, q_out),
        "profile": (ts_out, r_out),
        "speed": (ts_out, v_out),
        "voltage": (volt_t, volt_v),
        "stator_current": (cur_t, cur_st),
        "supply_current": (cur_t, cur_sup),
        "bus_voltage": (cur_t, cur_bus),
    }
    return ProfiledRun(values, series, nfev, K, saturated, settled, key)


def as_sim_run(
    pr: ProfiledRun, extra: dict, loop: Loop, slower: str = "lower the fractions or limits"
) -> SimRun:
    warnings = []
    if not pr.settled:
        warnings.append(
            f"The move does not settle within ±{loop.tolerance:.4g} of the goal by the end of the "
            f"window ({pr.updates} updates): no settle time. Raise the gains or the tolerance, or slow the profile."
        )
    if pr.saturated:
        warnings.append(
            f"The loop's voltage saturated at the battery voltage in {pr.saturated} of {pr.updates} "
            f"updates: the profile asks for more than the motors give ({slower})."
        )
    values = dict(pr.values)
    values.update(extra)
    return SimRun(values, pr.key, pr.nfev, warnings, pr.series)


# --- the mode's fields, outputs and run, shared by the motor scenes ------------------------------

PROFILED = ("profiled",)
PROFILE_CHOICES = ("trapezoid", "exponential")
PROFILE_LABELS = (
    "Trapezoid: max velocity and acceleration (WPILib TrapezoidProfile)",
    "Exponential: max input volts on the plant's kV, kA (WPILib ExponentialProfile)",
)
TRAPEZOID = (("profile_type", ("trapezoid",)),)
LIMIT_CHOICES = ("derived", "entered")
LIMIT_LABELS = (
    "Derived: fractions of the free speed and of the acceleration at the stator limit",
    "Entered: max velocity and acceleration",
)
FEEDBACK_CHOICES = ("lqr", "entered")
FEEDBACK_LABELS = ("LQR gains (as shown: kP, kD)", "Entered kP and kD")


def profile_fields(
    pos: tuple[str, str],
    speed: tuple[str, str, float],
    accel: tuple[str, str, float],
    kp: tuple[str, str, float],
    kd: tuple[str, str, float],
    tolerance: float,
) -> tuple:
    """The profiled move's fields: (quantity, unit[, default]) of each kind of the scene's q."""
    from ..fields import Field

    return (
        Field(
            "profile_type",
            "Profile",
            choices=PROFILE_CHOICES,
            choice_labels=PROFILE_LABELS,
            default="trapezoid",
            modes=PROFILED,
            help="Trapezoid: constant acceleration to a cruise velocity. Exponential: the plant's own "
            "response to a fixed voltage, forward then back (WPILib ExponentialProfile, Phoenix 6 "
            "Motion Magic Expo): quick off the line, slowing as the back-EMF grows.",
        ),
        Field(
            "max_input",
            "Profile max input",
            "voltage",
            "V",
            default=10,
            min=0,
            min_exclusive=True,
            max=1000,
            modes=PROFILED,
            when=(("profile_type", ("exponential",)),),
            help="The exponential profile's voltage (ExponentialProfile.Constraints maxInput), on top "
            "of kS and kG; at most the battery voltage. Below it leaves voltage for the feedback.",
        ),
        Field(
            "profile_limits",
            "Profile limits",
            choices=LIMIT_CHOICES,
            choice_labels=LIMIT_LABELS,
            default="derived",
            modes=PROFILED,
            when=TRAPEZOID,
            help="The trapezoid's max velocity and acceleration: fractions of what the mechanism can "
            "do (free speed; acceleration from rest against the load at the stator current "
            "limit), or entered.",
        ),
        Field(
            "velocity_fraction",
            "Velocity fraction",
            "dimensionless",
            "",
            default=0.6,
            min=0,
            min_exclusive=True,
            max=1,
            modes=PROFILED,
            when=(*TRAPEZOID, ("profile_limits", ("derived",))),
            help="Profile max velocity as a fraction of the free speed (0-1). Velocity and acceleration "
            "fractions summing below 1 leave voltage for the feedback.",
        ),
        Field(
            "acceleration_fraction",
            "Acceleration fraction",
            "dimensionless",
            "",
            default=0.1,
            min=0,
            min_exclusive=True,
            max=1,
            modes=PROFILED,
            when=(*TRAPEZOID, ("profile_limits", ("derived",))),
            help="Profile max acceleration as a fraction (0-1) of the acceleration from rest against "
            "the load with each motor at its stator current limit (the stator_limit effect's "
            "entry when that effect is on, else 40 A; the stall current if lower). The default 0.1 keeps the default elevator's and arm's moves within a 40 A "
            "stator limit (peaks 36 A, 23 A): the feedforward's step each period and the feedback "
            "draw more than the profile's acceleration alone.",
        ),
        Field(
            "max_velocity",
            "Max velocity",
            speed[0],
            speed[1],
            default=speed[2],
            min=0,
            min_exclusive=True,
            max=1e6,
            modes=PROFILED,
            when=(*TRAPEZOID, ("profile_limits", ("entered",))),
            help="The trapezoid profile's cruise velocity (TrapezoidProfile.Constraints maxVelocity).",
        ),
        Field(
            "max_acceleration",
            "Max acceleration",
            accel[0],
            accel[1],
            default=accel[2],
            min=0,
            min_exclusive=True,
            max=1e7,
            modes=PROFILED,
            when=(*TRAPEZOID, ("profile_limits", ("entered",))),
            help="The trapezoid profile's acceleration (TrapezoidProfile.Constraints maxAcceleration).",
        ),
        Field(
            "feedback",
            "Feedback gains",
            choices=FEEDBACK_CHOICES,
            choice_labels=FEEDBACK_LABELS,
            default="lqr",
            modes=PROFILED,
            help="The PD gains of the loop: the LQR gains computed from the tolerances below, or your own.",
        ),
        Field(
            "feedback_kp",
            "kP",
            kp[0],
            kp[1],
            default=kp[2],
            min=0,
            max=1e6,
            modes=PROFILED,
            when=(("feedback", ("entered",)),),
            help="Proportional gain, volts per unit of position error (PIDController kP).",
        ),
        Field(
            "feedback_kd",
            "kD",
            kd[0],
            kd[1],
            default=kd[2],
            min=0,
            max=1e6,
            modes=PROFILED,
            when=(("feedback", ("entered",)),),
            help="Derivative gain, volts per unit of speed error (PIDController kD, on the error's "
            "difference over the period).",
        ),
        Field(
            "settle_tolerance",
            "Settle tolerance",
            pos[0],
            pos[1],
            default=tolerance,
            min=0,
            min_exclusive=True,
            max=1e6,
            modes=PROFILED,
            help="Settled: within this of the goal from then to the end of the simulated window "
            "(the profile's time plus the larger of 1 s and that time).",
        ),
    )


def profile_outputs(pos: tuple[str, str], speed: tuple[str, str], accel: tuple[str, str]) -> tuple:
    from ..declarations import Output

    return (
        Output(
            "settle_time",
            "Settle time",
            "time",
            "s",
            help="Profiled: from the start until the position stays within the tolerance of the goal (P8).",
            equation="(P8)",
        ),
        Output(
            "profile_time",
            "Profile time",
            "time",
            "s",
            help="The profile's duration: the trapezoid's (P1) or the exponential's (P15).",
            equation="(P1), (P15)",
        ),
        Output(
            "profile_max_velocity",
            "Profile max velocity",
            speed[0],
            speed[1],
            help="The trapezoid's velocity limit used (P1); exponential: max input/kV, approached "
            "and never reached (P12).",
            equation="(P1), (P12)",
        ),
        Output(
            "profile_max_acceleration",
            "Profile max acceleration",
            accel[0],
            accel[1],
            help="The trapezoid's acceleration limit used (P1); exponential: max input/kA, its "
            "acceleration at rest (P12).",
            equation="(P1), (P12)",
        ),
        Output(
            "overshoot",
            "Overshoot",
            pos[0],
            pos[1],
            help="Farthest past the goal (0 when it never passes it) (P9).",
            equation="(P9)",
        ),
        Output(
            "final_error",
            "Steady-state error",
            pos[0],
            pos[1],
            help="Goal minus position at the end of the window, toward the goal (positive: short) (P9).",
            equation="(P9)",
        ),
        Output(
            "rms_tracking_error",
            "RMS tracking error",
            pos[0],
            pos[1],
            help="Profile position minus position at the control updates, RMS over the window (P10).",
            equation="(P10)",
        ),
        Output(
            "peak_tracking_error",
            "Peak tracking error",
            pos[0],
            pos[1],
            help="Largest |profile position − position| at the control updates (P10).",
            equation="(P10)",
        ),
        Output(
            "control_updates",
            "Control updates",
            help="Periods simulated over the window (each one integrator call or more) (P6).",
            equation="(P6)",
        ),
    )


def profile_plots(label: str, pos_q: str, pos_u: str) -> tuple:
    from ..declarations import Plot

    return (
        Plot(
            f"{label.capitalize()} vs profile (profiled)",
            ("position", "profile"),
            "time",
            "time",
            "s",
            label,
            pos_q,
            pos_u,
        ),
        Plot("Voltage (profiled)", ("voltage",), "time", "time", "s", "voltage", "voltage", "V"),
    )


def return_outputs(pos: tuple[str, str]) -> tuple:
    """The return move's figures (P16), each beside the first move's of the same name."""
    from ..declarations import Output

    back = "Goal back to start, same gains and profile (P16)"
    figures = (
        ("settle_time", "settle time", "time", "s", "until it stays within the tolerance of the start (P8)"),
        ("overshoot", "overshoot", *pos, "farthest past the start (P9)"),
        ("final_error", "steady-state error", *pos, "start minus position at the end (positive: short) (P9)"),
        ("peak_tracking_error", "peak tracking error", *pos, "largest |profile − position| (P10)"),
        ("peak_stator_current", "peak stator current", "current", "A", "per motor (P11)"),
        ("peak_supply_current", "peak supply current", "current", "A", "per motor (P11)"),
        ("min_bus_voltage", "min bus voltage", "voltage", "V", "battery minus the sag (P11)"),
        ("energy", "energy", "energy", "J", "from the battery, regeneration negative (P11)"),
    )
    return tuple(
        Output(
            RETURN_PREFIX + name,
            f"Return move: {label}",
            quantity,
            unit,
            help=f"{back}: {what}.",
            equation="(P16)",
        )
        for name, label, quantity, unit, what in figures
    )


def return_plots(label: str, pos_q: str, pos_u: str) -> tuple:
    """The return move's position against its profile, time from the return's start (P16)."""
    from ..declarations import Plot

    return (
        Plot(
            f"Return move: {label} vs profile (profiled)",
            (RETURN_PREFIX + "position", RETURN_PREFIX + "profile"),
            "time",
            "time",
            "s",
            label,
            pos_q,
            pos_u,
        ),
    )


def loop_of(setup, v, ff: dict, kG, arm: bool = False) -> tuple[Loop, Trapezoid | Exponential, dict]:
    """The loop and profile from the entries; kP, kD from LQR (motion.lqr) or entered."""
    from .motion import check_can_move, lqr

    # the profiles' dataclasses load with the first solve, not with the card's description
    from .profiles import Trapezoid, derived_acceleration, exponential_of

    check_can_move(setup)
    m = setup.mech
    exponential = v.get("profile_type") == "exponential"
    if exponential:
        v_max = a_max = math.nan  # (P12): the profile's, below
    elif v["profile_limits"] == "derived":
        v_max = v["velocity_fraction"] * m.free_speed
        a_max = derived_acceleration(setup, v)  # (P17)
    else:
        v_max, a_max = v["max_velocity"], v["max_acceleration"]
    if v["feedback"] == "lqr":
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
        except Exception as exc:  # noqa: BLE001 - scipy raises LinAlgError
            raise InputError(
                "q_position", f"no LQR solution for these tolerances ({type(exc).__name__})"
            ) from None
        if not (math.isfinite(kP) and math.isfinite(kD)):
            raise InputError("q_position", "the LQR gains are not finite for these tolerances")
    else:
        kP, kD = v["feedback_kp"], v["feedback_kd"]
    loop = Loop(
        ff["kS"],
        kG,
        ff["kV"],
        ff["kA"],
        kP,
        kD,
        v["control_period"],
        v["sensor_delay"],
        v["settle_tolerance"],
        arm,
    )
    profile = exponential_of(setup, v, ff) if exponential else Trapezoid(m.distance, v_max, a_max)
    T = profile.total_time
    speed_field = "max_input" if exponential else "max_velocity"
    if not (math.isfinite(T) and T > 0):
        raise InputError(speed_field, "the profile's time is not a positive number")
    updates = (T + max(SETTLE_EXTRA, T)) / v["control_period"]
    if updates > MAX_UPDATES:
        field_name = "control_period" if T < 600 else speed_field
        raise InputError(
            field_name,
            f"the move needs {updates:.3g} control updates (more than {MAX_UPDATES}): "
            "lengthen the control period or speed up the profile",
        )
    return loop, profile, {"kP": kP, "kD": kD}


MAX_UPDATES = 5_000  # 100 s of a 20 ms loop: within one solve's budget (scene.SOLVE_NFEV)


def run_profiled(setup, v, rtol: float, ff: dict, kG, return_move: bool = False, arm: bool = False) -> SimRun:
    """Every output of the profiled mode (the gains shown are those the loop used); with
    `return_move`, the move back as well (P16); `arm`: kG(q) = kG·cos q, ArmFeedforward's (P5a)."""
    from .profiles import Exponential

    loop, profile, gains = loop_of(setup, v, ff, kG, arm)
    pr = profiled_move(setup, loop, profile, rtol)
    extra = {**ff, **gains, "free_speed": setup.mech.free_speed}
    slower = "lower the max input" if isinstance(profile, Exponential) else "lower the fractions or limits"
    run = as_sim_run(pr, extra, loop, slower)
    if return_move:
        add_return_move(run, setup, v, loop, profile, rtol, slower)
    return run


# --- the return move: back from the goal to the start with the same loop and profile -------------
#
# Robot code holds one set of gains and one profile's constraints for both ways; the mechanism
# leaves the goal at rest (exactly at it, not where the first move ended: the return's figures are
# then those of a solve with start and goal swapped and the same profile, whatever the first move's
# final error) and the loop runs the same profile toward the start:
#     the return move = (P1)-(P11) with q0 ↔ q1, the same Loop and the same profile        (P16)
# A derived trapezoid keeps the first move's limits (the fractions of the acceleration at the stator
# limit against the load at the start, (P17)): a separate solve of the way back would derive its own.

RETURN_PREFIX = "return_"
RETURN_FIGURES = (
    "settle_time",
    "overshoot",
    "final_error",
    "peak_tracking_error",
    "peak_stator_current",
    "peak_supply_current",
    "min_bus_voltage",
    "energy",
)
RETURN_WARNING = "Return move (goal → start): "
RETURN_SERIES_LABELS = {RETURN_PREFIX + "position": "position", RETURN_PREFIX + "profile": "profile"}


def mechanism_result(run: SimRun):
    """An elevator's or arm's Result from its scene's run: the grid's tables and heat map, and the
    return plot's legend (P16) when the way back was run."""
    from ..declarations import Result

    result = Result(
        run.values,
        run.warnings,
        run.series,
        run.tables,
        heat_maps=run.heat_maps,
    )
    if RETURN_PREFIX + "position" in result.series:
        result.series_labels.update(RETURN_SERIES_LABELS)
    return result


def reversed_setup(setup):
    """The same mechanism and effects moving from the goal back to the start (q0 and q1 swapped).
    The effects' parts (the field force of q, the limits, the sag) do not depend on the direction,
    so the assembly is shared."""
    m = setup.mech
    return replace(setup, mech=replace(m, q0=m.q1, q1=m.q0))


def return_move(setup, v, loop: Loop, profile: Trapezoid | Exponential, rtol: float, slower: str) -> SimRun:
    """(P16): the move back as a SimRun of its own (its warnings unprefixed), or InputError when the
    mechanism cannot make it (check_can_move: e.g. a counterbalance the motors cannot pull down)."""
    from .motion import check_can_move
    from .motor_limits import braking_warning

    back = reversed_setup(setup)
    check_can_move(back)
    run = as_sim_run(profiled_move(back, loop, profile, rtol), {}, loop, slower)
    braking_warning(v, run)
    return run


def add_return_move(
    run: SimRun, setup, v, loop: Loop, profile: Trapezoid | Exponential, rtol: float, slower: str
) -> None:
    """Add the return move's figures (as return_<name>), its key results, work, position and
    profile series and its warnings (prefixed) to `run`, the first move's."""
    try:
        back = return_move(setup, v, loop, profile, rtol, slower)
    except InputError as exc:
        run.warnings.append(f"{RETURN_WARNING}not simulated: {exc.field} {exc.message}.")
        return
    for name in RETURN_FIGURES:
        if name in back.values:
            run.values[RETURN_PREFIX + name] = back.values[name]
    run.key.update({RETURN_PREFIX + k: x for k, x in back.key.items()})
    run.nfev += back.nfev
    run.series[RETURN_PREFIX + "position"] = back.series["position"]
    run.series[RETURN_PREFIX + "profile"] = back.series["profile"]
    run.warnings += [RETURN_WARNING + w[0].lower() + w[1:] for w in back.warnings]
