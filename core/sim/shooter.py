"""The flywheel shooter's scene (core/calculators/flywheel.py is its page): the shot (energy or
momentum transfer, the incoming ball, the compound layout, the slip phase and its closed form), the
range error, the burst and the recovery, the spin-up under current limits integrated phase by
phase, the electrical extremes and the current-limit grid's cells. The seed's equations (1)-(9),
the motor side (FW1)-(FW8), (F1), (F2) are written in the page's docstring; each is cited beside
its code here.

Shooter layouts with a secondary wheel (issue 31; ReCalc v2's shooter modes, tervay/recalc
app/lib/math/ballShot.ts at commit 03511cb4, the Team 449 paper's main body, §2.3 and Appendix A).
The secondary (top) wheels turn at ω₂ = G₂₁·ω₁ of the primary (bottom) wheels, each set geared to
the motors by its own ratio; everything is written at the primary wheel (r₁ = r_w, ω₁ = ω_w):
    (D1) G₂₁ = G/G₂ (motor turns per primary / per secondary turn),
         I = n₁·I₁ + G₂₁²·n₂·I₂ + N·J_r·G²                     all inertia seen at the primary wheel
    (D2) no slip at both contacts at release: V + r_b·ω_b = r₁·ω₁,  V − r_b·ω_b = G₂₁·r₂·ω₁
         ⇒ V = s·r₁·ω₁, s = (r₁ + G₂₁·r₂)/(2·r₁);  ω_b = c·V/r_b, c = (r₁ − G₂₁·r₂)/(r₁ + G₂₁·r₂)
         (hood: G₂₁ = 0, s = ½, c = 1 as (2); a same-speed pair: s = 1, c = 0; c < 0 is backspin)
    (D3) E_b = ½·m·V² + ½·I_b·ω_b² = ½·m_e·V²,  m_e = m·(1 + c²·k_b):  (3) and (6) with σ = c²,
         β = m_e·s²·r₁²/I; so both seed transfer models hold unchanged for the dual layout
    (D4) momentum, impulses J₁, J₂ of the two contacts on the ball, the wheels geared together:
         I·(ω₀ − ω₁) = r₁·J₁ + G₂₁·r₂·J₂,  m·(V − V_i) = J₁ + J₂,  I_b·(ω_b − ω_bi) = r_b·(J₁ − J₂)
         ⇒ ω₁ = (ω₀ + β·V_eq/(s·r₁))/(1 + β),  V_eq = (V_i + c·k_b·r_b·ω_bi)/(1 + c²·k_b)
         (V_i, ω_bi the ball's incoming speed and spin; ReCalc's rawDualShooter, rawSingleHooded)
    (D5) energy with an incoming ball: E_b − E_b,i = (1 − f)·½·I·(ω₀² − ω₁²),
         E_b,i = ½·m·(V_i² + k_b·r_b²·ω_bi²)  ⇒  ω₁² = (ω₀² + 2·E_b,i/((1 − f)·I))/(1 + β/(1 − f))
    (D6) compound: a hood section of the primary wheel (s = ½, c = 1), then the pair (D2); the first
         section's exit (V, ω_b) is the second's incoming (V_i, ω_bi), each section by (D4) or (D5)
         with its own loss f. Energy model: ω₁ = ω₀/√(1 + β_pair/(1 − f)), whatever the path
         (the sections' E_b = (1 − f)·ΔE_w add up); the momentum model's slip loses more.
    (D7) hood_secondary: a hood shooter with a secondary wheel geared to the primary that does not
         touch the ball (ReCalc's "Flywheel" section): (2)-(6) with I from (D1).
The incoming ball speed and spin (default 0) apply to every layout; motor_during_shot needs a ball
entering at rest and one contact section (not with an incoming ball or the compound layout). For the
dual layout its grip F is the generalised force of (D4) at the primary wheel: r₁·F is the torque
the ball takes from the geared wheels (r₁·J₁ + G₂₁·r₂·J₂ per unit time), so (FW3) holds with s, σ
of (D2)-(D3); how F divides between the two contacts is not modelled.

Motor (linear model, core.motors): the wheel set of inertia I is driven through reduction G (motor
turns per wheel turn) by n motors:  I·dω/dt = G·τ̃s·(1 − G·ω/ω̃f)  ⇒  ω(t) = ω_f,w·(1 − e^(−t/T)),
ω_f,w = ω̃f/G, T = I·ω̃f/(G²·τ̃s). Full power below the target speed, held at the target above it.
Spin-up and recovery are closed forms. Effect `motor_during_shot` (momentum model only): the motor
keeps driving while the ball slips under a constant grip force F (μ·N) until it rolls; that phase
is integrated (core.sim.integrate; events at the end of slip and where the controller reaches the
target) and tests check it against its closed form, which also answers when the phase is stiff
(wheel time constant far below the slip time: an explicit step would need thousands of steps).
With F → ∞ it tends to the impulse model; a motor strong enough to hold the target against r_w·F
launches the ball at the full s·r_w·ω_t (no range error). The model has no contact length: a warning
says when the ball would slip over more than 0.5 m (weak grip) and so leave before it rolls.
Range-error table (the seed's, n = 1..6): the same wheel, motor and target speed with n wheels.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from ..constants import G0 as G_ACC
from ..constants import RPM
from ..errors import InputError
from ..fields import Field
from ..motors import lookup, system_from
from . import limit_grid, motor_limits
from .effects import Effect, Effects, nothing
from .integrate import Event, integrate, integrate_stiff

# Slip phase: when the wheel's time constant is this many times shorter than the slip (b·τ_end), an
# explicit integrator needs ~b·τ_end/3 steps for stability alone; the closed form is used instead.
STIFF = 200.0
ELECTRICAL = ("stator_limit", "supply_limit", "battery_sag")
EFFECTS = Effects(
    Effect(
        "motor_during_shot",
        "momentum model: the motor keeps driving while the ball slips",
        nothing,
        fields=(
            Field(
                "grip_force",
                "Grip force μ·N (motor during shot)",
                "force",
                "N",
                default=40,
                min=0.1,
                max=1e5,
                help="Friction force of the wheels on the slipping ball; used by motor_during_shot only.",
            ),
        ),
    ),
    *motor_limits.electrical_effects(),
)
SECONDARY = ("dual", "compound", "hood_secondary")  # layouts with a secondary wheel set
WITH_SPIN = ("hood", "dual", "compound", "hood_secondary")  # the ball leaves spinning


@dataclasses.dataclass(eq=False)
class Drive:
    """The motors under a current limit (stator_limit, supply_limit; with or without battery_sag),
    per motor through core.sim.motor_limits (E1)-(E3); the torque is the seed's (7), (9):
        τ_w(ω) = A·(I(E) − i_f)/(i_s − i_f),  E = G·ω/Kv                                  (F1)
    A = G·τ̃s the unlimited wheel torque at stall, i_s, i_f the stall and free current per motor at
    the voltage field. With no limit I = (V − E)/R and (F1) is the seed's A·(1 − ω/ω_f) exactly."""

    A: float
    G: float
    i_s: float
    i_f: float
    circuit: motor_limits.Circuit
    elec: Any  # E -> (u, I)
    asm: Any  # the assembled electrical effects (their duty bounds, one by one)
    rtol: float
    boundaries: (
        tuple[float, ...] | None
    ) = ()  # wheel speeds where a limit lets go (kinks of τ_w); None: no limit
    nfev: int = 0

    def torque(self, w: float) -> float:
        _, I = self.elec(self.G * w / self.circuit.Kv)
        return self.A * (I - self.i_f) / (self.i_s - self.i_f)  # (F1)

    def emf(self, w: float) -> float:
        return self.G * w / self.circuit.Kv


@dataclasses.dataclass(frozen=True)
class Scene:
    r_w: float  # wheel radius, m
    I: float  # all wheels, kg·m²
    r_b: float
    k_b: float
    s: float  # V / (r_w·ω_w) at release
    sigma: float  # c² (D3): 1 the ball spins at V/r_b (hood); 0: no spin
    f: float  # loss fraction
    model: str  # "energy" or "momentum"
    motor_on: bool  # motor_during_shot
    A: float  # G·τ̃s, N·m at the wheel at stall
    free_speed: float  # ω̃f/G, rad/s of the wheel
    grip: float  # N
    drive: Drive | None = dataclasses.field(default=None, compare=False)  # a current limit is on
    electric: Drive | None = dataclasses.field(default=None, compare=False)  # a limit or battery_sag is on
    spin_ratio: float = 1.0  # c = ω_b·r_b/V at release (D2): 1 hood, 0 a same-speed pair
    V_in: float = 0.0  # V_i, the ball's incoming speed, m/s (D4)
    spin_in: float = 0.0  # ω_bi, its incoming spin, rad/s
    first: Scene | None = None  # compound: the hood section before this one (D6)

    @property
    def incoming(self) -> bool:
        """The shot has no closed form in m alone: a ball entering moving, or two sections."""
        return self.first is not None or self.V_in != 0 or self.spin_in != 0

    @property
    def B(self) -> float:
        return self.A / self.free_speed  # G²·τ̃s/ω̃f, N·m·s

    @property
    def T(self) -> float:
        return self.I / self.B


def rotor_reflected(v) -> float:
    """N·J_r·G²: the motors' rotors seen at the wheel (kinetic energy ½·J_r·(G·ω)² each)."""
    return v["motor_count"] * v["rotor_inertia"] * v["ratio"] ** 2


def secondary_speed_ratio(v) -> float:
    """(D1) G₂₁ = ω₂/ω₁ = G/G₂."""
    return v["ratio"] / v["secondary_ratio"]


def secondary_reflected(v) -> float:
    """(D1) G₂₁²·n₂·I₂: the secondary wheels seen at the primary wheel (0 without them)."""
    if v["shooter"] not in SECONDARY:
        return 0.0
    if v["mode"] == "moment_of_inertia":
        each = v["secondary_inertia"]
    else:
        each = v["secondary_mass"] * (v["secondary_gyration_fraction"] * v["secondary_diameter"] / 2) ** 2
    return secondary_speed_ratio(v) ** 2 * v["secondary_count"] * each


def with_inertia(sc: Scene, I: float) -> Scene:
    """The scene with all wheels' inertia I (and its compound first section likewise)."""
    first = None if sc.first is None else dataclasses.replace(sc.first, I=I)
    return dataclasses.replace(sc, I=I, first=first)


def inertia_each(v) -> float:
    if v["mode"] == "moment_of_inertia":
        return v["wheel_inertia"]
    return v["wheel_mass"] * (v["gyration_fraction"] * v["wheel_diameter"] / 2) ** 2  # (4)


def scene_from(v, rtol: float = 1e-6) -> tuple[Scene, list[str]]:
    effects = v["effects"]
    warnings: list[str] = []
    model = v["transfer"]
    motor_on = "motor_during_shot" in effects
    if motor_on and model == "energy":
        warnings.append(
            "motor_during_shot is ignored by the energy model (it has no shot duration); "
            "use the momentum model."
        )
        motor_on = False
    system, notes = system_from(v)
    warnings += notes
    G = v["ratio"]
    A, free = G * system.stall_torque, system.free_speed / G
    drive = electric = None
    if any(n in effects for n in ELECTRICAL):
        A, free, electric = electrical_drive(v, A, free, G, rtol)
        drive = electric if electric.boundaries is not None else None
    shooter = v["shooter"]
    incoming = v["ball_initial_speed"] != 0 or (shooter in WITH_SPIN and v["ball_initial_spin"] != 0)
    if motor_on and (incoming or shooter == "compound"):
        name = "shooter" if shooter == "compound" else "ball_initial_speed"
        if shooter != "compound" and v["ball_initial_speed"] == 0:
            name = "ball_initial_spin"
        raise InputError(
            name,
            "motor_during_shot models one contact section with the ball entering at rest: "
            "not with the compound layout or an incoming ball speed or spin (turn the effect off)",
        )
    r_w = v["wheel_diameter"] / 2
    if shooter in ("dual", "compound"):  # (D2)
        pair = r_w + secondary_speed_ratio(v) * v["secondary_diameter"] / 2
        s = pair / (2 * r_w)
        c = (r_w - secondary_speed_ratio(v) * v["secondary_diameter"] / 2) / pair
    elif shooter == "two_wheel":
        s, c = 1.0, 0.0
    else:  # hood, hood_secondary: (2)
        s, c = 0.5, 1.0
    I = v["wheel_count"] * inertia_each(v)
    if shooter in SECONDARY:
        I += secondary_reflected(v)  # (D1)
    if v["rotor_inertia"] > 0:
        I += rotor_reflected(v)
    if incoming and model == "energy":
        warnings.append(
            "The energy model counts the incoming ball's kinetic energy whatever the direction of "
            "its spin (D5); the momentum model (ReCalc v2, Team 449) accounts for it (D4)."
        )
    sc = Scene(
        r_w=r_w,
        I=I,
        r_b=v["ball_diameter"] / 2,
        k_b=v["ball_inertia_factor"],
        s=s,
        sigma=c * c,
        f=v["loss_fraction"],
        model=model,
        motor_on=motor_on,
        A=A,
        free_speed=free,
        grip=v["grip_force"],
        drive=drive,
        electric=electric,
        spin_ratio=c,
        V_in=v["ball_initial_speed"],
        spin_in=v["ball_initial_spin"] if shooter in WITH_SPIN else 0.0,
    )
    if shooter == "compound":  # (D6): the hood section meets the incoming ball
        hood = dataclasses.replace(sc, s=0.5, sigma=1.0, spin_ratio=1.0)
        sc = dataclasses.replace(sc, V_in=0.0, spin_in=0.0, first=hood)
    return sc, warnings


def electrical_drive(v, A: float, free: float, G: float, rtol: float) -> tuple[float, float, Drive | None]:
    """The wheel's stall torque and free speed with battery_sag (still linear in speed, through
    R + R_bus), and the limited drive when stator_limit or supply_limit is on (None otherwise).
    With sag alone, I = (V − E)/(R + R_bus) in (F1):
        A' = A·(V/(R + R_bus) − i_f)/(i_s − i_f),  ω_f' = Kv·(V − i_f·(R + R_bus))/G          (F2)"""
    on = v["effects"]
    motor, _ = lookup(v["motor"], v["source"])
    V = v["voltage"]
    Rb = motor_limits.bus_resistance_of(v, on)
    circuit = motor_limits.circuit_of(motor, V, Rb)
    i_s = motor.stall_current * V / motor.v_spec  # (4), per motor
    i_f = motor.free_current * V / motor.v_spec  # (3), per motor
    A_sag = A
    if Rb > 0:
        I0 = V / (circuit.R + Rb)
        if I0 <= i_f:
            raise InputError(
                "battery_resistance",
                f"sags the bus so far that the stalled motors draw "
                f"{I0:.4g} A each, not above their free current "
                f"{i_f:.4g} A: they give no torque",
            )
        A_sag = A * (I0 - i_f) / (i_s - i_f)  # (F2)
        free = circuit.Kv * (V - i_f * (circuit.R + Rb)) / G  # (F2)
    elec, asm = motor_limits.limits(EFFECTS, on, v, circuit)
    if asm.slots["duty"] is None:  # sag alone: closed forms with A', ω_f'; boundaries None
        return A_sag, free, Drive(A, G, i_s, i_f, circuit, elec, asm, rtol, None)
    Es = motor_limits.release_emfs(circuit, v, on)
    if "supply_limit" in on:  # the supply limit lets go to full duty: u = 1, I = I_sup   (E3)
        Es.append(V - v["supply_current_limit"] * (circuit.R + Rb))
    boundaries = tuple(sorted({E * circuit.Kv / G for E in Es if E > 0}))
    return A_sag, free, Drive(A, G, i_s, i_f, circuit, elec, asm, rtol, boundaries)


def beta(sc: Scene, m: float) -> float:
    """(6): E_b/E_w,final in the lossless energy model = m_e·s²·r_w²/I, m_e = m·(1 + σ·k_b)."""
    return m * (1 + sc.sigma * sc.k_b) * (sc.s * sc.r_w) ** 2 / sc.I


@dataclasses.dataclass
class Shot:
    omega_after: float  # rad/s
    drop: float  # ω₀ − ω₁, formed without cancellation where the model has a closed form
    V: float  # ball speed, m/s
    spin: float  # rad/s
    energy: float  # J
    contact_time: float  # s (0: instantaneous)
    nfev: int


def shot(sc: Scene, omega0: float, m: float, target: float, rtol: float) -> Shot:
    """The ball leaves a wheel set spinning at omega0: wheel speed after, ball speed, spin, energy."""
    if sc.incoming:
        return shot_incoming(sc, omega0, m)
    b = beta(sc, m)
    m_e = m * (1 + sc.sigma * sc.k_b)
    t_c, nfev = 0.0, 0
    if sc.model == "energy":
        x = b / (1 - sc.f)
        root = math.sqrt(1 + x)
        omega1 = omega0 / root  # (5) with losses: E_b = (1−f)·ΔE_w
        drop = omega0 * x / (root * (1 + root))  # ω₀·(1 − 1/√(1+x)), rationalised
        V = sc.s * sc.r_w * omega1  # (2)
    elif not sc.motor_on or m_e == 0 or omega0 <= 0:
        # (ω₀ = 0: a wheel stopped by the previous shot meets the ball at rest: no impulse, the ball is
        # not thrown, V = 0; the slip phase's scaling t₀ ∝ ω₀ has no meaning there)
        omega1 = omega0 / (1 + b)  # angular impulse: I·(ω₀ − ω₁) = r_w·J, J = s·m_e·V, V = s·r_w·ω₁
        drop = omega0 * b / (1 + b)
        V = sc.s * sc.r_w * omega1 * math.sqrt(1 - sc.f)
    else:
        omega1, V, t_c, nfev = slip_phase(sc, omega0, m_e, target, rtol)
        drop = omega0 - omega1
        V *= math.sqrt(1 - sc.f)
    spin = sc.spin_ratio * V / sc.r_b  # (2), (D2)
    return Shot(omega1, drop, V, spin, 0.5 * m_e * V * V, t_c, nfev)  # (3)


def shot_incoming(sc: Scene, omega0: float, m: float) -> Shot:
    """A shot whose ball meets the wheels moving (V_i, ω_bi), by (D4) or (D5); compound (D6): the
    hood section first, its exit the pair's incoming ball. No slip phase (checked in scene_from)."""
    if sc.first is not None:
        one = shot_incoming(sc.first, omega0, m)
        two = section(sc, one.omega_after, m, one.V, one.spin)
    else:
        two = section(sc, omega0, m, sc.V_in, sc.spin_in)
    return dataclasses.replace(two, drop=omega0 - two.omega_after)


def section(sc: Scene, omega0: float, m: float, V_in: float, spin_in: float) -> Shot:
    """One contact section with an incoming ball: (D4) momentum or (D5) energy, losses f."""
    b = beta(sc, m)
    m_e = m * (1 + sc.sigma * sc.k_b)
    if sc.model == "energy":
        E_in = 0.5 * m * (V_in * V_in + sc.k_b * (sc.r_b * spin_in) ** 2)  # (D5)
        omega1 = math.sqrt((omega0 * omega0 + 2 * E_in / ((1 - sc.f) * sc.I)) / (1 + b / (1 - sc.f)))
        V = sc.s * sc.r_w * omega1  # (D2)
    else:
        V_eq = (V_in + sc.spin_ratio * sc.k_b * sc.r_b * spin_in) / (1 + sc.sigma * sc.k_b)  # (D4)
        omega1 = (omega0 + b * V_eq / (sc.s * sc.r_w)) / (1 + b)  # (D4)
        if omega1 < 0:
            raise InputError(
                "ball_initial_spin",
                "spins the ball against the wheels so hard that they would turn backwards (D4): "
                "the ball would not be thrown",
            )
        V = sc.s * sc.r_w * omega1 * math.sqrt(1 - sc.f)
    spin = sc.spin_ratio * V / sc.r_b  # (D2)
    return Shot(omega1, omega0 - omega1, V, spin, 0.5 * m_e * V * V, 0.0, 0)  # (D3)


def slip_phase(
    sc: Scene, omega0: float, m_e: float, target: float, rtol: float
) -> tuple[float, float, float, int]:
    """Motor on while the ball slips, until it rolls (r_w·ω = V/s):
        I·dω/dt = A − B·ω − r_w·F   below the target speed (full power); at the target the
                                    controller holds it (never exceeds it)
        m_e·s·dV/dt = F             (the grip F at the wheel contact, moving at V/s once rolling).
    Scaled: u = ω/ω₀, v = V/(s·r_w·ω₀), τ = t/t₀ with t₀ = s²·m_e·r_w·ω₀/F, so dv/dτ = 1 and the
    slip ends at u = v. The controller's switch is an event ("target"), not a kink in the
    right-hand side: once held, u = u_t until v reaches it. Returns (ω₁, V, contact time, evaluations).
    """
    F = sc.grip
    t0 = sc.s * sc.s * m_e * sc.r_w * omega0 / F
    a = t0 * (sc.A - sc.r_w * F) / (sc.I * omega0)
    b = t0 * sc.B / sc.I
    u_t = target / omega0  # ≥ 1: a shot starts at or below the target
    span = max(1.0, u_t) * (1 + 1e-9) + 1e-12  # u stays in [0, u_t], so u = τ happens before this
    if sc.drive is not None:  # a current limit: the torque is (F1), not linear in ω
        return slip_phase_limited(sc, omega0, t0, b, u_t, span, rtol)
    if u_t <= 1.0 and a - b >= 0:  # at the target and the motor can hold it: no slip of the wheel
        return omega0, sc.s * sc.r_w * omega0, t0, 0
    if b * span > STIFF:
        tau, u = slip_closed_form(a, b, u_t, span)
        return u * omega0, sc.s * sc.r_w * omega0 * tau, tau * t0, 0
    events = [Event("rolling", lambda t, y: y[0] - y[1], -1)]
    if u_t > 1.0:
        events.append(Event("target", lambda t, y: y[0] - u_t, +1))
    try:
        run = integrate(
            lambda t, y: [a - b * y[0], 1.0],
            0.0,
            span,
            [1.0, 0.0],
            rtol=rtol,
            atol=rtol * 1e-3,
            events=events,
        )
    except RuntimeError:  # beyond what a step-size controller can follow: the closed form answers
        tau, u = slip_closed_form(a, b, u_t, span)
        return u * omega0, sc.s * sc.r_w * omega0 * tau, tau * t0, 0
    u, v_end = run.y[-1]
    if run.event == "target":  # held at the target until the ball catches up: v = τ = u_t
        u = v_end = u_t
    elif run.event != "rolling":  # cannot happen by the bound on span; the end point is the answer
        u = v_end = min(u, v_end)
    return u * omega0, sc.s * sc.r_w * omega0 * v_end, v_end * t0, run.nfev


def slip_phase_limited(
    sc: Scene, omega0: float, t0: float, b: float, u_t: float, span: float, rtol: float
) -> tuple[float, float, float, int]:
    """(FW3) under a current limit: the motor torque is the limited τ_w(ω) of (F1) (core.sim.
    motor_limits (E1)-(E5), the same as the spin-up and the recovery), in slip_phase's scaling:
        du/dτ = t₀/(I·ω₀)·(τ_w(u·ω₀) − r_w·F),  dv/dτ = 1,  until u = v (rolling)          (FW3')
    held at u_t once there (the torque there exceeds r_w·F, as it got there). τ_w is continuous
    with kinks where a limit lets go; the integrator's step control takes them. Stiff (b·span
    beyond STIFF, b the full-duty slope), scipy's Radau integrates it instead (integrate_stiff)."""
    d = sc.drive
    k = t0 / (sc.I * omega0)
    rw_F = sc.r_w * sc.grip

    def rhs(t, y):
        return [k * (d.torque(y[0] * omega0) - rw_F), 1.0]

    if u_t <= 1.0 and rhs(0.0, [u_t, 0.0])[0] >= 0:  # at the target and the motor can hold it
        return omega0, sc.s * sc.r_w * omega0, t0, 0
    events = [Event("rolling", lambda t, y: y[0] - y[1], -1)]
    if u_t > 1.0:
        events.append(Event("target", lambda t, y: y[0] - u_t, +1))
    run = None
    if b * span <= STIFF:
        try:
            run = integrate(rhs, 0.0, span, [1.0, 0.0], rtol=rtol, atol=rtol * 1e-3, events=events)
        except RuntimeError:  # beyond what a step-size controller can follow: Radau below
            run = None
    if run is None:
        tol = max(rtol, 1e-12)
        run = integrate_stiff(rhs, 0.0, span, [1.0, 0.0], tol, tol * 1e-3, events, "Radau")
    (u, v_end), event = run.y[-1], run.event
    if event == "target":  # held at the target until the ball catches up: v = τ = u_t
        u = v_end = u_t
    elif event != "rolling":  # cannot happen by the bound on span; the end point is the answer
        u = v_end = min(u, v_end)
    return u * omega0, sc.s * sc.r_w * omega0 * v_end, v_end * t0, run.nfev


def slip_closed_form(a: float, b: float, u_t: float, span: float) -> tuple[float, float]:
    """The slip phase in closed form (used when it is stiff): u(τ) = u_eq + (1 − u_eq)·e^(−b·τ),
    u_eq = a/b, held at u_t from the time it reaches it; the slip ends at the root of u(τ) = τ."""
    from scipy.optimize import brentq

    u_eq = a / b
    if u_eq > u_t:  # rises to the target and is held there
        tau_hit = math.log((u_eq - 1) / (u_eq - u_t)) / b if u_t > 1 else 0.0
    else:
        tau_hit = math.inf

    def u(tau: float) -> float:
        return u_t if tau >= tau_hit else u_eq + (1 - u_eq) * math.exp(-b * tau)

    tau = brentq(lambda x: u(x) - x, 0.0, span, xtol=1e-300, rtol=1e-15, maxiter=500)
    return tau, u(tau)


def projectile_range(V: float, theta: float, h: float) -> float:
    """(1) from release height h: R = V·cosθ/g·(V·sinθ + √(V²·sin²θ + 2·g·h))."""
    sn, cs = math.sin(theta), math.cos(theta)
    return V * cs / G_ACC * (V * sn + math.sqrt((V * sn) ** 2 + 2 * G_ACC * h))


def range_gain(V0: float, V1: float, dV2_rel: float, theta: float, h: float) -> float:
    """(R(V1) − R(V0))/R(V0) with dV2_rel = (V1² − V0²)/V0² given without cancellation.

    R1 − R0 = cosθ/g·(V1² − V0²)·[sinθ + (sin²θ·(V1² + V0²) + 2gh)/(V1·S1 + V0·S0)], S = √(V²sin²θ + 2gh)
    (the difference of square roots rationalised).
    """
    R0 = projectile_range(V0, theta, h)
    if R0 <= 0:
        return 0.0
    sn, cs = math.sin(theta), math.cos(theta)
    S0 = math.sqrt((V0 * sn) ** 2 + 2 * G_ACC * h)
    S1 = math.sqrt((V1 * sn) ** 2 + 2 * G_ACC * h)
    den = V1 * S1 + V0 * S0
    bracket = sn + ((sn * sn) * (V1 * V1 + V0 * V0) + 2 * G_ACC * h) / den if den > 0 else 2 * sn
    return cs / G_ACC * V0 * V0 * dV2_rel * bracket / R0


def speed_sq_change(sc: Scene, m0: float, dm: float, shot0: Shot, shot1: Shot) -> float:
    """(V1² − V0²)/V0² when the ball mass goes from m0 to m0 + dm; where the model has a closed form
    the change of β is β(dm) (β is linear in m), so nothing is formed by subtraction."""
    if shot0.V == 0:
        return 0.0
    if sc.incoming:  # no closed form in the mass alone
        return (shot1.V - shot0.V) * (shot1.V + shot0.V) / (shot0.V * shot0.V)
    m1 = m0 + dm
    if sc.model == "energy":  # V² ∝ 1/(1 + β/(1−f)):  (7)
        b1 = beta(sc, m1) / (1 - sc.f)
        return -(beta(sc, dm) / (1 - sc.f)) / (1 + b1)
    if not sc.motor_on or m0 == 0 or m1 == 0:  # V ∝ 1/(1 + β): q² − 1 = (q − 1)(q + 1)
        q_minus_1 = -beta(sc, dm) / (1 + beta(sc, m1))
        return q_minus_1 * (q_minus_1 + 2)
    return (shot1.V - shot0.V) * (shot1.V + shot0.V) / (shot0.V * shot0.V)


class Shots:
    """Shots of one simulate call (the page's), each computed once (the table and the burst reuse
    them)."""

    def __init__(self, target: float, rtol: float):
        self.target, self.rtol = target, rtol
        self.done: dict[tuple, Shot] = {}
        self.nfev = 0

    def __call__(self, sc: Scene, omega0: float, m: float) -> Shot:
        key = (sc, omega0, m)
        if key not in self.done:
            self.done[key] = shot(sc, omega0, m, self.target, self.rtol)
            self.nfev += self.done[key].nfev
        return self.done[key]


def range_change(sc: Scene, v, shots: Shots, dm: float) -> float:
    """Exact relative range change when the ball mass goes from m₀ to m₀ + dm (shots at the target)."""
    m0, target = v["ball_mass"], shots.target
    s0, s1 = shots(sc, target, m0), shots(sc, target, m0 + dm)
    return range_gain(s0.V, s1.V, speed_sq_change(sc, m0, dm, s0, s1), v["launch_angle"], v["release_height"])


def range_error_linear(sc: Scene, m0: float, e_m: float) -> float:
    """(9): the seed's −e_m/(m_w/(c·m₀) + 1) = −e_m·β₀/(1 + β₀) (lossless energy model, R ∝ V²)."""
    b0 = beta(sc, m0)
    return -e_m * b0 / (1 + b0)


def recovery(sc: Scene, omega_from: float, omega_to: float, gap: float | None = None) -> float:
    """Full-power time from omega_from up to omega_to (< free speed): T·ln((ω_f − ω₁)/(ω_f − ω_t)),
    as T·log1p(gap/(ω_f − ω_t)) with gap = ω_t − ω₁ (given when known without cancellation).
    Under a current limit, integrated (limited_run)."""
    if gap is None:
        gap = omega_to - omega_from
    if gap <= 0:
        return 0.0
    if sc.drive is not None:
        return limited_run(sc, omega_from, omega_to).t[-1]
    return sc.T * math.log1p(gap / (sc.free_speed - omega_to))


class LimitedRun:
    """Wheel speed from a limited spin-up, integrated phase by phase (see limited_run)."""

    def __init__(self):
        self.pieces: list[tuple[float, Any]] = []  # (start time, core.sim.integrate.Run)
        self.t = [0.0]
        self.y = [[0.0]]
        self.event = None

    def at(self, t: float) -> list:
        for t0, run in reversed(self.pieces):
            if t >= t0:
                return run.at(min(t - t0, run.t[-1]))
        return self.pieces[0][1].at(0.0)


def limited_run(
    sc: Scene, omega_from: float, omega_to: float, t_end: float | None = None, dense: bool = False
) -> LimitedRun:
    """I·dω/dt = τ_w(ω) (F1) from omega_from until ω = omega_to (event "target") or t_end, one
    phase at a time: τ_w has a kink where a limit lets go (motor_limits.release_emfs, and
    E = V_b − I_sup·(R + R_bus) where the supply limit lets go to full duty), so each phase is
    integrated up to its boundary (an event) and the next starts there, every piece smooth.
    τ_w never rises with ω (each phase's current falls or stays as the back-EMF grows) and is
    positive at omega_to (check_limits, from the page's simulate), so a phase ending at ω_b is
    over before I·(ω_b − ω)/τ_w(ω_b): the span integrated."""
    d = sc.drive
    I = sc.I
    ends = sorted(w for w in d.boundaries if omega_from < w < omega_to) + [omega_to]
    out = LimitedRun()
    t, w = 0.0, omega_from
    out.y = [[w]]
    for w_b in ends:
        span = I * (w_b - w) / d.torque(w_b) * (1 + 1e-6) + 1e-12
        if t_end is not None:
            span = min(span, t_end - t)
        if span <= 0:
            break
        try:
            run = integrate(
                lambda t_, y: [d.torque(y[0]) / I],
                0.0,
                span,
                [w],
                rtol=d.rtol,
                atol=d.rtol * omega_to,
                events=[Event("target", lambda t_, y, w_b=w_b: y[0] - w_b, +1)],
                dense=dense,
            )
        except RuntimeError as exc:  # a phase of ~1e-10 s: steps below the integrator's floor
            raise TooFast(f"a phase of {span:.3g} s: {exc}") from None
        d.nfev += run.nfev
        out.pieces.append((t, run))
        t, w = t + run.t[-1], run.y[-1][0]
        out.t, out.y = [t], [[w]]
        if run.event != "target":
            break
        w = w_b  # on the boundary (the event's located state is w_b to the tolerance)
        out.y = [[w]]
        if w_b == omega_to:
            out.event = "target"
    return out


def free_run(sc: Scene, omega: float, dt: float) -> float:
    """Speed after dt at full power from omega: ω_f − (ω_f − ω)·e^(−dt/T)."""
    wf = sc.free_speed
    return wf - (wf - omega) * math.exp(-dt / sc.T)


def burst(sc: Scene, v, shots: Shots):
    """Spin-up from rest, then `shots` shots at the cadence; closed form between shots."""
    m0 = v["ball_mass"]
    interval, target = v["shot_interval"], shots.target
    T = sc.T
    t_spin = recovery(sc, 0.0, target)
    ts: list[float] = []
    ws: list[float] = []

    def ramp(t_start: float, w_start: float, duration: float) -> None:
        """Full power toward the target for `duration`, holding the target once reached (sampled)."""
        t_hit = recovery(sc, w_start, target)
        if t_hit > 0:
            reach = min(t_hit, duration)
            if sc.drive is not None:
                run = limited_run(sc, w_start, target, reach if reach < t_hit else None, dense=True)
                end = run.t[-1]

                def speed(dt):
                    return run.y[-1][0] if dt >= end else run.at(dt)[0]
            else:

                def speed(dt):
                    return free_run(sc, w_start, dt)

            for i in range(1, 25):
                dt = reach * i / 24 if i < 24 else reach  # reach·24/24 need not round to reach
                ts.append(t_start + dt)
                ws.append(min(speed(dt), target))
        if duration > t_hit:
            ts.append(t_start + duration)
            ws.append(target)

    ts.append(0.0)
    ws.append(0.0)
    ramp(0.0, 0.0, t_spin)
    first_shot = len(ts) - 1  # the burst plot starts at the end of the spin-up (not found by time:
    t, w = t_spin, target  # the last sample's reach·24/24 can round below t_spin)
    slowest = math.inf
    for k in range(v["shots"]):
        one = shots(sc, w, m0)
        slowest = min(slowest, one.V)
        t_end = t + one.contact_time
        w = one.omega_after
        ts.append(t_end)
        ws.append(w)
        if k + 1 < v["shots"]:
            wait = max(interval - one.contact_time, 0.0)
            ramp(t_end, w, wait)
            w = ws[-1]
            t = t_end + wait
        else:
            ramp(t_end, w, recovery(sc, w, target) + 0.25 * T)
    return (ts, ws), slowest, t_spin, first_shot


def check_limits(sc: Scene, target: float) -> None:
    """InputError naming the limit that leaves the motors no torque at the target speed."""
    d = sc.drive
    if d.torque(target) > 1e-9 * d.A:  # (below it the spin-up would take 10⁹ stall-torque times)
        return
    E = d.emf(target)
    bounds = {n: p.terms["duty"](E) for n, p in d.asm.parts.items() if "duty" in p.terms}
    name = min(bounds, key=bounds.get)
    u, I = d.elec(E)
    field_name = "stator_current_limit" if name == "stator_limit" else "supply_current_limit"
    raise InputError(
        field_name,
        f"is too low to spin the wheels up to {target / RPM:.4g} rpm: there the "
        f"motors draw {I:.4g} A each (duty {u:.3g}), not above their free current "
        f"{d.i_f:.4g} A, so they give no torque",
    )


def electrical_extremes(sc: Scene, target: float, v) -> dict[str, float]:
    """Peak stator and supply current per motor and the lowest bus voltage over a spin-up from rest
    to the target: the stator current never rises with speed (peak at rest); the supply current's
    peak is at rest, at the target or at a branch point of the duty rule (core.sim.motor_limits
    .branch_emfs, (E5)-(E7): with strong sag the duty jumps to full where (E2)'s roots merge, E6)."""
    d = sc.electric
    E_t = d.emf(target)
    branch = motor_limits.branch_emfs(d.circuit, v, v["effects"])
    Es = [0.0] + [E for E in [E_t, *branch] if 0.0 < E <= E_t]
    peak_sup = max(u * I for u, I in map(d.elec, Es))
    return {
        "peak_stator_current": d.elec(0.0)[1],
        "peak_supply_current": peak_sup,
        "min_bus_voltage": d.circuit.battery_voltage - d.circuit.bus_resistance * peak_sup,
    }


class TooFast(Exception):
    """A spin-up phase too short for the integrator to resolve (a wheel of almost no inertia)."""


# --- the current-limit grid's cells (control = limit_grid; core.sim.limit_grid runs the grid) -----

GRID_SCAN = 24  # ratios log-spaced over the scan, before Brent refines the best
GRID_DECADES = 2.0  # the scan spans G_max·10^-2 .. G_max: below, the spin-up lengthens unless
GRID_EXTENSIONS = 4  # the rotors dominate; then it moves down 2 decades at a time, at most this often


def grid_spin_up(v, ratio: float) -> tuple[float, Scene] | None:
    """(FW6): the full-power spin-up time from rest to the target at this ratio under the cell's
    limits, J·∫₀^ω_t dω/τ_w(ω) (scipy's quad on each smooth piece between the speeds where a limit
    lets go); None when the motors cannot reach the target."""
    from scipy.integrate import quad

    w = {**v, "ratio": ratio}
    sc, _ = scene_from(w)
    target = v["target_speed"]
    if target >= sc.free_speed or sc.drive.torque(target) <= 1e-9 * sc.drive.A:
        return None
    d = sc.drive
    edges = [0.0, *sorted(b for b in d.boundaries if 0.0 < b < target), target]
    total = 0.0
    for a, b in zip(edges, edges[1:], strict=False):
        part, _ = quad(lambda x: 1.0 / d.torque(x), a, b, epsabs=0.0, epsrel=1e-10, limit=200)
        total += part
    return sc.I * total, sc


def grid_energy(sc: Scene, v) -> float:
    """Battery energy over the spin-up, ∫ N·V_b·u·I dt = J·∫ N·V_b·u·I/τ_w dω (a change of variable:
    dt = J·dω/τ_w)."""
    from scipy.integrate import quad

    d, target, N, Vb = sc.drive, v["target_speed"], v["motor_count"], v["voltage"]
    edges = [0.0, *sorted(b for b in d.boundaries if 0.0 < b < target), target]

    def power_per_torque(x: float) -> float:
        u, I = d.elec(d.emf(x))
        return N * Vb * u * I / d.torque(x)

    return sc.I * sum(
        quad(power_per_torque, a, b, epsabs=0.0, epsrel=1e-10, limit=200)[0]
        for a, b in zip(edges, edges[1:], strict=False)
    )


def grid_best_ratio(v, G_max: float) -> tuple[float, float, Scene] | None:
    """(FW7): the ratio below G_max with the least spin-up time (first in (G_max·10^-2, G_max),
    lower while the best is the span's lowest): the best of a log scan,
    then bounded Brent on ln G between its neighbours."""
    from scipy.optimize import minimize_scalar

    lo, hi = math.log(G_max) - GRID_DECADES * math.log(10), math.log(G_max)

    def time_at(x: float) -> float:
        r = grid_spin_up(v, math.exp(x))
        return math.inf if r is None else r[0]

    xs = [lo + (hi - lo) * i / GRID_SCAN for i in range(GRID_SCAN)]  # G_max itself never reaches
    times = [time_at(x) for x in xs]
    i = min(range(len(xs)), key=times.__getitem__)
    # the quickest at the scan's lowest ratio (heavy rotors: each motor's own inertia grows as G²):
    # the optimum lies below, so the scan moves down a span at a time until it is inside
    for _ in range(GRID_EXTENSIONS):
        if i > 0 or not math.isfinite(times[0]):
            break
        hi, lo = xs[1], lo - GRID_DECADES * math.log(10)
        xs = [lo + (hi - lo) * k / GRID_SCAN for k in range(GRID_SCAN)]
        times = [time_at(x) for x in xs]
        i = min(range(len(xs)), key=times.__getitem__)
    if not math.isfinite(times[i]):
        return None
    a, b = xs[max(i - 1, 0)], xs[i + 1] if i + 1 < len(xs) else hi
    best = minimize_scalar(time_at, bounds=(a, b), method="bounded", options={"xatol": 1e-6})
    x = best.x if best.fun < times[i] else xs[i]
    G = math.exp(x)
    t, sc = grid_spin_up(v, G)
    return G, t, sc


def grid_cells(base: dict, stators: list[float], supplies: list[float], rtol: float):
    """(FW6)-(FW8)'s cells for core.sim.limit_grid (its axes, pick, table and heat map): the
    quickest ratio per stator × supply limit pair, its spin-up time, peak currents and energy."""
    probe, _ = scene_from(base)
    G_max = probe.free_speed * base["ratio"] / base["target_speed"]  # ω_f(G) ∝ 1/G: ω_f(G_max) = ω_t
    rows = []
    for sup in supplies:
        for st in stators:
            row: dict[str, Any] = {"stator_limit": st, "supply_limit": sup}
            cell = {**base, "stator_current_limit": st, "supply_current_limit": sup}
            found = grid_best_ratio(cell, G_max)
            if found is not None:
                G, t, sc = found
                ex = electrical_extremes(sc, base["target_speed"], cell)
                row.update(
                    ratio=G,
                    time=t,
                    peak_stator_current=ex["peak_stator_current"],
                    peak_supply_current=ex["peak_supply_current"],
                    energy=grid_energy(sc, cell),
                )
            else:
                row["note"] = limit_grid.NO_ARRIVAL  # no ratio below the target's free speed gets there
            rows.append(row)
    return rows, 0  # scipy's quad and Brent: no integrator evaluations to charge
