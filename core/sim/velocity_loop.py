"""A flywheel under velocity control, as robot code runs it (issue 30): feedforward plus proportional
feedback on the speed error, evaluated every control period with a sensor delay, the voltage held
between updates (zero-order hold), saturating at the battery voltage, with the current limits and
sag of core.sim.motor_limits; a shot drops the wheel speed at an entered time.

The wheel (the flywheel's seed motor model, core.calculators.flywheel (F1), per motor; k the wheel
torque per amp of each motor, k = A/(i_s − i_f) = G·N·K_T, A the stall torque at the wheel):
    E = G·ω/Kv,  I = (u·V_b − E)/(R + u²·R_bus)                                     (E1), signed
    J·ω̇ = k·(I − i_f)          (ω > 0; the free current's loss torque against the motion)   (VL1)
The feedforward that holds ω with no limit and no sag ((VL1) at ω̇ = 0, and V = R·I + E):
    V = kS + kV·ω + kA·ω̇,  kS = R·i_f,  kV = G/Kv,  kA = R·J/k   (per rad/s at the wheel)  (VL2)
The robot code (WPILib SimpleMotorFeedforward + PIDController, I = D = 0), at t_k = k·dt:
    y_k = ω(t_k − δ)  (ω(0) = 0 before δ);  e_k = r − y_k                               (VL3)
    V_k = clamp(kS·sgn r + kV·r + kP·e_k, −V_b, V_b),  u_k = V_k/V_b held over the period  (VL4)
    (a step setpoint r: SimpleMotorFeedforward.calculate(r, r) is kS·sgn r + kV·r exactly)
A ramped setpoint (Motion Magic Velocity, MAXMotion velocity, or robot code stepping its setpoint
by a·dt each period): r(t) = min(r, a·t), r_k = r(t_k), and as core.sim.profiled (P4), (P5) with
WPILib's SimpleMotorFeedforward.calculate(r_k, r_{k+1}) (its discrete plant inversion, checked
against robotpy 2026.2.2 to 1e-15):
    e_k = r_{k+1} − y_k,  V_ff = kS·sgn r_k + (r_{k+1} − A_d·r_k)/B_d,
    A_d = e^(−kV·dt/kA),  B_d = (1 − A_d)/kV                                            (VL4a)
    (at r_k = r_{k+1} = r it is kS·sgn r + kV·r, the step's (VL4): the ramp's end joins it)
Between updates, u held, (VL1) is a scalar autonomous ODE: ω is monotone on each period. With no
current limit on (sag alone keeps I affine in E for a fixed u) it is linear and the period's
closed form is exact (the first-order case of core.sim.integrate's exponential step, method EXP (X1), written
out: no Jacobian to form):
    ω̇ = α − λ·ω,  λ = k·G/(Kv·R'·J),  α = k·(u·V_b/R' − i_f)/J,  R' = R + u²·R_bus
    ω(s) = ω_ss + (ω₀ − ω_ss)·e^(−λ·s),  ω_ss = α/λ                                      (VL5)
With a current limit the duty of each motor is the held command capped by the limits' shared
bound ((E2), (E3) through core.sim.profiled.driver), I no longer affine in E, and the period is
integrated by the scene's DP54 (core.sim.integrate) with dense output, or by scipy's Radau when the
period spans more than 200 of the wheel's time constants 1/λ (a light wheel: DP54 would be held to
steps ≈ 3/λ by stability).
A shot at an update instant comes after that update's measurement. The voltage chart is the loop's
held command V_k (a current limit or the sag gives the motor less).
The loop drives a wheel with a positive setpoint: it never spins it backwards; a wheel braked to
rest is held at rest for the rest of the period (the loss torque holds it; a reverse drive is not
modelled).
Outputs (the band |ω − r| ≤ tol):
    spin-up time: the last entry into the band before the shot, the wheel in it at the shot;
    recovery time: from the shot to the last entry into the band, in it at the window's end
    (window: the shot time plus the larger of 1 s and the shot time). Each entry is located inside
    its period (monotone: closed form on (VL5), bisection on the dense output otherwise)     (VL6)
    overshoot: max(ω) − r before the shot (≥ 0); the dip: min ω after the shot            (VL7)
    peak stator |I| and supply u·I per motor, lowest bus V_b − R_bus·max(u·I): at each period's
    ends and (limited) the integrator's step points (I is monotone in ω for a held u)        (VL8)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from .integrate import Event, integrate, integrate_stiff

WINDOW_AFTER_SHOT = 1.0  # s: at least this long is simulated after the shot
MAX_UPDATES = 5_000  # 100 s of a 20 ms loop (core.sim.profiled's budget)
SAMPLES = 4  # trace points inside each period (the plot)
STIFF = 200.0  # λ·period beyond which a limited period is integrated by Radau (as flywheel.STIFF)


@dataclass(frozen=True)
class Wheel:
    """The flywheel's drive, SI at the wheel; `drive(u_cmd, E) -> (u, I)` per motor."""

    J: float  # kg·m², all inertia at the wheel
    k: float  # N·m at the wheel per amp of each motor
    G: float  # motor turns per wheel turn
    Kv: float  # rad/s per V (M1)
    R: float  # Ω per motor (M1)
    i_f: float  # A, free current per motor at the battery voltage
    battery_voltage: float
    bus_resistance: float
    drive: Callable[[float, float], tuple[float, float]]
    limited: bool  # a current limit is on: (VL5) does not hold, DP54


@dataclass(frozen=True)
class Loop:
    kS: float  # V
    kV: float  # V·s/rad
    kP: float  # V·s/rad (volts per rad/s of error)
    period: float
    delay: float
    tolerance: float  # rad/s
    kA: float = 0.0  # V·s²/rad: used by a ramped setpoint only (VL4a)
    acceleration: float | None = None  # rad/s², the ramp's; None: a step setpoint (VL4)

    def setpoint(self, t: float, target: float) -> float:
        """r(t): the target, or the ramp toward it from rest at t = 0 (VL4a)."""
        if self.acceleration is None:
            return target
        return min(target, self.acceleration * t)

    def command(self, k: int, target: float, measured: float) -> float:
        """The loop's voltage at update k before the clamp: (VL4), or (VL4a) on a ramp."""
        if self.acceleration is None:
            sign = (target > 0) - (target < 0)
            return self.kS * sign + self.kV * target + self.kP * (target - measured)
        dt = self.period
        r, r_next = self.setpoint(k * dt, target), self.setpoint((k + 1) * dt, target)
        A_d = math.exp(-self.kV * dt / self.kA)
        B_d = -math.expm1(-self.kV * dt / self.kA) / self.kV
        ff = self.kS * ((r > 0) - (r < 0)) + (r_next - A_d * r) / B_d
        return ff + self.kP * (r_next - measured)


def feedforward_gains(w: Wheel) -> dict[str, float]:
    """(VL2)."""
    return {"kS": w.R * w.i_f, "kV": w.G / w.Kv, "kA": w.R * w.J / w.k}


def lqr_kp(kV: float, kA: float, q_velocity: float, r_volts: float, dt: float, delay: float) -> float:
    """kP of WPILib's LinearQuadraticRegulator for the velocity system ẋ = −(kV/kA)·x + u/kA
    (LinearSystemId.identifyVelocitySystem), discretised with a zero-order hold over dt,
    Q = 1/q², R = 1/r²; the scalar discrete Riccati equation
        B²·P² + (R·(1 − A²) − Q·B²)·P − Q·R = 0  (its positive root),  K = A·B·P/(R + B²·P)  (VL9)
    and the latency compensation K ← K·(A − B·K)^(δ/dt) (LinearQuadraticRegulator.latencyCompensate;
    the real part, as Eigen's matrix power of a negative 1×1 matrix, as core.sim.motion.lqr does)."""
    a = -kV / kA
    A = math.exp(a * dt)
    B = -math.expm1(a * dt) / kV  # (A − 1)/a · 1/kA
    Q, R = 1.0 / q_velocity**2, 1.0 / r_volts**2
    c = R * (1 - A) * (1 + A) - Q * B * B
    # the positive root without cancellation: P = 2·Q·R/(c + √(c² + 4·B²·Q·R)) when c > 0
    disc = math.sqrt(c * c + 4 * B * B * Q * R)
    P = 2 * Q * R / (c + disc) if c > 0 else (disc - c) / (2 * B * B)
    K = A * B * P / (R + B * B * P)
    if delay > 0:
        K *= (complex(A - B * K) ** (delay / dt)).real
    return K


@dataclass
class Period:
    """One held period [t0, t1): its start speed and how to evaluate ω inside it."""

    t0: float
    t1: float
    w0: float
    u_cmd: float
    at: Callable[[float], float]  # absolute t in [t0, t1] -> ω
    w1: float


@dataclass
class LoopRun:
    periods: list[Period] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    speeds: list[float] = field(default_factory=list)
    volt_t: list[float] = field(default_factory=list)
    volts: list[float] = field(default_factory=list)
    peak_stator: float = 0.0
    peak_supply: float = 0.0
    overshoot: float = 0.0
    dip: float = math.inf
    spin_up_time: float | None = None
    recovery_time: float | None = None
    speed_at_shot: float = 0.0
    speed_after_shot: float = 0.0
    final_error: float = 0.0
    updates: int = 0
    nfev: int = 0

    def speed(self, t: float) -> float:
        """ω(t) as a sample taken at t reads it (0 before the start): at a shot's instant the speed
        before the shot, as a measurement at that instant comes before the shot (module docstring),
        whether it is read then or a whole number of periods later through the delay. So the
        period ending at t, not the one starting there (t − δ lands on a period's start to within
        rounding: k·dt − m·dt, hence the margin)."""
        if t <= 0 or not self.periods:
            return 0.0
        t_before = t - 1e-12 * max(1.0, abs(t))
        lo, hi = 0, len(self.periods) - 1
        while lo < hi:  # the last period starting before t
            mid = (lo + hi + 1) // 2
            if self.periods[mid].t0 < t_before:
                lo = mid
            else:
                hi = mid - 1
        p = self.periods[lo]
        return p.at(min(t, p.t1))


def _period_exact(w: Wheel, u_cmd: float, t0: float, t1: float, w0: float):
    """(VL5) over [t0, t1] from w0 (no limit): ω(t), ω(t1)."""
    u, _ = w.drive(u_cmd, 0.0)  # no limit: the duty is the command
    Rp = w.R + u * u * w.bus_resistance
    lam = w.k * w.G / (w.Kv * Rp * w.J)
    alpha = w.k * (u * w.battery_voltage / Rp - w.i_f) / w.J
    w_ss = alpha / lam
    if w0 <= 0 and alpha <= 0:  # at rest and not driven forward past the loss: held
        return (lambda t: 0.0), 0.0
    stop = math.inf
    if w_ss < 0:  # braked to rest inside the period at t0 + stop: held there (module docstring)
        stop = math.log((w0 - w_ss) / -w_ss) / lam

    def at(t: float) -> float:
        s = t - t0
        if s >= stop:
            return 0.0
        return w_ss + (w0 - w_ss) * math.exp(-lam * s)

    return at, at(t1)


def _period_limited(w: Wheel, u_cmd: float, t0: float, t1: float, w0: float, rtol: float, run: LoopRun):
    """(VL1) with the limits by DP54 over [t0, t1]; a terminal event where ω reaches 0."""

    def rhs(t, y):
        if y[0] <= 0:
            _, I = w.drive(u_cmd, 0.0)
            return [max(0.0, w.k * (I - w.i_f) / w.J)]
        _, I = w.drive(u_cmd, w.G * y[0] / w.Kv)
        return [w.k * (I - w.i_f) / w.J]

    if w0 <= 0 and rhs(t0, [0.0])[0] <= 0:
        return (lambda t: 0.0), 0.0, ()
    events = [Event("rest", lambda t, y: y[0], -1)]
    atol = rtol * max(abs(w0), 1.0)
    # the unlimited decay rate bounds the slope of (VL1) (a limit only flattens it): a period of
    # many time constants holds DP54 to steps ≈ 3/λ by stability alone, so Radau takes it
    lam = w.k * w.G / (w.Kv * w.R * w.J)
    if lam * (t1 - t0) > STIFF:
        r = integrate_stiff(rhs, 0.0, t1 - t0, [max(w0, 0.0)], rtol, atol, events, method="Radau")
    else:
        r = integrate(rhs, 0.0, t1 - t0, [max(w0, 0.0)], rtol=rtol, atol=atol, events=events, dense=True)
    run.nfev += r.nfev
    end = r.t[-1]
    stopped = r.event == "rest"

    def at(t: float) -> float:
        s = t - t0
        if s >= end:
            return 0.0 if stopped else r.y[-1][0]
        return max(r.at(s)[0], 0.0)

    return at, at(t1), [y[0] for y in r.y]


def _entry(at, t0: float, t1: float, inside) -> float:
    """The time in [t0, t1] where the monotone ω(t) enters the band (outside at t0, inside at t1)."""
    lo, hi = t0, t1
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if inside(at(mid)):
            hi = mid
        else:
            lo = mid
        if hi - lo <= 1e-12 * max(1.0, t1):
            break
    return hi


def run_loop(
    w: Wheel, loop: Loop, setpoint: float, shot_time: float, after_shot: Callable[[float], float], rtol: float
) -> LoopRun:
    """(VL3)-(VL8) from rest; the shot at shot_time takes ω to after_shot(ω)."""
    out = LoopRun()
    dt, Vb = loop.period, w.battery_voltage
    t_end = shot_time + max(WINDOW_AFTER_SHOT, shot_time)
    n = math.ceil(t_end / dt - 1e-9)
    tol = loop.tolerance

    def inside(x: float) -> bool:
        return abs(x - setpoint) <= tol

    def electrics(u_cmd: float, omega: float) -> None:
        u, I = w.drive(u_cmd, w.G * omega / w.Kv)
        out.peak_stator = max(out.peak_stator, abs(I))
        out.peak_supply = max(out.peak_supply, u * I)

    omega = 0.0
    since: float | None = 0.0 if inside(0.0) else None
    shot_done = False
    out.times.append(0.0)
    out.speeds.append(0.0)
    for k in range(n):
        tk = k * dt
        measured = out.speed(tk - loop.delay)  # (VL3)
        V = min(max(loop.command(k, setpoint, measured), -Vb), Vb)  # (VL4), (VL4a)
        u_cmd = V / Vb
        out.volt_t += [tk, min((k + 1) * dt, t_end)]
        out.volts += [V, V]
        out.updates += 1
        # the period, split at the shot when it falls inside it
        edges = [tk, min((k + 1) * dt, t_end)]
        if not shot_done and tk < shot_time < edges[1]:
            edges.insert(1, shot_time)
        for a, b in zip(edges, edges[1:], strict=False):
            if not shot_done and a >= shot_time:
                out.speed_at_shot = omega
                out.spin_up_time = since if inside(omega) else None
                omega = after_shot(omega)
                out.speed_after_shot = omega
                out.dip = omega
                shot_done = True
                since = a if inside(omega) else None
            electrics(u_cmd, omega)
            if w.limited:
                at, w1, steps = _period_limited(w, u_cmd, a, b, omega, rtol, out)
                for y in steps:
                    electrics(u_cmd, y)
            else:
                at, w1 = _period_exact(w, u_cmd, a, b, omega)
            electrics(u_cmd, w1)
            out.periods.append(Period(a, b, omega, u_cmd, at, w1))
            if since is None and inside(w1):  # (VL6): entered inside this period
                since = a if inside(omega) else _entry(at, a, b, inside)
            elif not inside(w1):
                since = None
            if shot_done:
                out.dip = min(out.dip, w1)
            else:
                out.overshoot = max(out.overshoot, w1 - setpoint)
            for i in range(1, SAMPLES + 1):
                t = a + (b - a) * i / SAMPLES
                out.times.append(t)
                out.speeds.append(at(t) if i < SAMPLES else w1)
            omega = w1
    if not shot_done:  # the shot at the window's end (not reached: shot_time ≥ t_end never holds)
        out.speed_at_shot = omega
        out.spin_up_time = since if inside(omega) else None
    out.recovery_time = since - shot_time if since is not None and shot_done else None
    out.final_error = setpoint - omega
    return out
