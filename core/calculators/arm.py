"""Single-jointed arm: N motors through a reduction G swing the arm from rest at the start angle to
the goal angle at full voltage, as a scene with effects (core.sim.motion, core.sim.effects).

Coordinate θ: the arm's angle from the horizontal, up positive (θ = 90°: straight up).
    I·θ̈ = η·N·Kt·G·(I_m − i_f) − m·g·L·cos θ (gravity) + τ_cb·cos θ (counterbalance)
          − τ_f·sgn(θ̇) (friction)                                                             (AR1)
    I_m = (u·V_bus − G·θ̇/Kv)/R  per motor, u the duty (1 unless a current limit lowers it);
        R = V_spec/I_stall, Kv = ω_free/(V_spec − R·I_free), Kt = τ_stall/(I_stall − I_free),
        i_f = I_free·V_b/V_spec (the seed's motor model, eqs. 3, 7, 9, as every tab)            (AR2)
with L the pivot-to-centre-of-mass distance and I the moment of inertia about the pivot
    I = m·(2L)²/3 = 4/3·m·L²  (default: a uniform bar whose centre of mass is at L, so its length
        is 2L), or the entered I (at least m·L²)                                               (AR3)
(gearhead.core.sim.motion (M1)-(M4); the current limits and battery sag set u and V_bus, (E1)-(E3)).
Counterbalance (our choice, documented): an ideal zero-length spring (a spring and cable over a
pulley, or a spring whose pre-load equals its stiffness times its free length) from a point a
above the pivot to a point b along the arm stores U = ½k·(a² + b² − 2ab·sin θ), so it gives the
torque −dU/dθ = k·a·b·cos θ: the counterbalance_torque is k·a·b, its value at horizontal, and
it cancels gravity at every angle when it equals m·g·L. (A gas strut's torque varies less
simply; enter its torque at horizontal as an approximation.)
What a move reports:
    T: the first time θ reaches the goal, (AR1) integrated from rest at full voltage with an
       event at the goal                                                                       (AR4)
    ω_max = largest |θ̇| over the move (a peak inside it located as an event);
    ω_free = (V_b − R·i_f)·Kv/G = ω_free,motor·V_b/(V_spec·G) (no load, u = 1)                (AR5)
    peak stator current: |I_m| of (AR2) at rest (at top speed if the load drives the motor past
    free speed); supply current u·I_m per motor; battery current N·u·I_m; bus voltage
    V_bus = V_b − N·R_batt·u·I_m, lowest where the supply current peaks                        (AR6)
    E = ∫ V_b·N·u·I_m dt, the battery's EMF times its current                                   (AR7)
    I_hold = |(τ_cb − m·g·L)·cos θ_goal|/(η·N·Kt·G) per motor                                   (AR8)
Feedforward (WPILib ArmFeedforward: V = kS·sgn(ω) + kG·cos θ + kV·ω + kA·α), from (AR1), (AR2)
at u = 1, kG quoted at horizontal and net of the counterbalance:
    kG = (m·g·L − τ_cb)·R/(η·N·Kt·G),  kV = G/Kv,  kA = I·R/(η·N·Kt·G),
    kS = R·i_f + τ_f·R/(η·N·Kt·G)                                                              (AR9)
Feedback: WPILib's LQR on the plant (θ, θ̇),
    ẋ = [[0, 1], [0, −kV/kA]]·x + [0, 1/kA]·V, discretised over the control period,
    Q = diag(1/q_pos², 1/q_vel²), R = 1/r²: [kP, kD] from the discrete Riccati equation,
    latency-compensated (motion.lqr)                                                           (AR10)
Optimise: G* minimising T(G): 240 ratios log-spaced about the characteristic ratio, then
bounded Brent on the accurate move around the best (motion.optimise)                           (AR11)
Profiled move (core.sim.profiled (P1)-(P11)): the trapezoid in angle (or WPILib's exponential profile
on the angle's kV, kA (AR9) from an entered max input, (P12)-(P15)), the feedforward (AR9) as
WPILib 2026.2.2's ArmFeedforward.calculate(angle, velocity, nextVelocity) computes it at the
setpoint (P5a: kS·sgn ω + kV·ω + kA·Δω/dt + kG·cos θ for kA < 0.1 V·s²/rad, its RK4 inversion of
the arm's plant above; the exported code calls that class), PD feedback (the LQR gains (AR10) or
entered) every control period on the angle measured `sensor_delay` earlier, the voltage held and
clamped                                                                                      (AR12)
Current-limit grid (core.sim.limit_grid): for each stator × supply limit pair the fastest ratio of
the full-voltage swing (AR4), its time, peak currents and energy, the pick within a supply budget;
a pair whose motors at rest cannot beat gravity's largest torque on the path (m·g·L·cos θ at the
angle nearest horizontal, less the counterbalance) at any ratio up to 1e5 "cannot hold"       (AR13)
Return move: one solve runs both ways, the gravity helping one and loading the other (the down move
is where the loop brakes and the current limits bite): from rest at the goal back to the start with
the same gains and the same profile (a derived trapezoid keeps the first move's limits), its
figures reported as "Return move: …" beside the first move's, its warnings prefixed (P16)   (AR14)
"""

from __future__ import annotations

import math
from dataclasses import replace

from .. import gains_code
from ..constants import G0 as G
from ..declarations import Calculator, Output, Result
from ..errors import InputError
from ..fields import Field
from ..motors import lookup
from ..sim import limit_grid, motion, profiled
from ..sim.effects import Effect, Effects, Part
from ..sim.motor_limits import braking_warning
from ..sim.scene import STATS_OUTPUTS, accuracy_field, run_with_stats

INERTIA_MODELS = ("uniform_bar", "entered")
INERTIA_LABELS = ("Uniform bar: I = 4/3·m·L² (bar of length 2L)", "Entered moment of inertia")


def _gravity(values, mech) -> Part:
    mgL = values["arm_mass"] * G * values["com_distance"]
    cos = mech.xp.cos
    return Part(terms={"force": lambda q: -mgL * cos(q)})


def _counterbalance(values, mech) -> Part:
    t_cb = values["counterbalance_torque"]
    cos = mech.xp.cos
    return Part(terms={"force": lambda q: t_cb * cos(q)})


EFFECTS = Effects(
    Effect("gravity", "the arm's weight, torque m·g·L·cos θ", _gravity, default_on=True),
    *motion.electrical_effects(),
    motion.friction_effect(
        "torque", "N*m", "friction_torque", "a constant torque against the motion (reported as kS)", 0.5
    ),
    Effect(
        "counterbalance",
        "a zero-length spring above the pivot: torque τ_cb·cos θ",
        _counterbalance,
        fields=(
            Field(
                "counterbalance_torque",
                "Counterbalance torque at horizontal",
                "torque",
                "N*m",
                default=5,
                min=0,
                max=1e6,
                help="k·a·b of a zero-length spring (or spring and cable) anchored a above the "
                "pivot and b along the arm: it lifts with τ_cb·cos θ, cancelling gravity "
                "at every angle when τ_cb = m·g·L.",
            ),
        ),
    ),
)


FIELDS = (
    motion.mode_field(profiled=True, grid=True),
    *motion.battery_motor_fields("Kraken X60", 1),
    Field(
        "ratio",
        "Reduction G",
        "dimensionless",
        "",
        default=75,
        min=0,
        min_exclusive=True,
        max=1e5,
        modes=("move", "profiled"),
        help="Motor turns per arm turn.",
    ),
    Field(
        "arm_mass",
        "Arm mass",
        "mass",
        "lb",
        default=8,
        min=0,
        min_exclusive=True,
        max=2.2e5,
        help="Everything that swings: arm, end effector, game piece.",
    ),
    Field(
        "com_distance",
        "Pivot to centre of mass",
        "length",
        "in",
        default=12,
        min=0,
        min_exclusive=True,
        max=3.9e4,
        help="L: distance from the pivot to the centre of mass of everything that swings.",
    ),
    Field(
        "inertia_model",
        "Moment of inertia",
        choices=INERTIA_MODELS,
        choice_labels=INERTIA_LABELS,
        default="uniform_bar",
        help="Uniform bar: I = 4/3·m·L², a bar of length 2L pivoted at its end. Otherwise enter I: "
        "from CAD (mass properties about the pivot axis), or add m_i·r_i² for each lump "
        "(end effector, game piece) to m·l²/3 for the bare tube of length l.",
    ),
    Field(
        "moment_of_inertia",
        "Moment of inertia about pivot",
        "inertia",
        "lb*in**2",
        default=1500,
        min=0,
        min_exclusive=True,
        max=3.4e12,
        when=(("inertia_model", ("entered",)),),
        help="About the pivot axis; must be at least m·L² (all mass at the centre of mass).",
    ),
    Field(
        "start_angle",
        "Start angle",
        "angle",
        "deg",
        default=-30,
        min=-360,
        max=360,
        help="From the horizontal, up positive (−90°: hanging straight down).",
    ),
    Field(
        "goal_angle",
        "Goal angle",
        "angle",
        "deg",
        default=90,
        min=-360,
        max=360,
        help="From the horizontal, up positive; below the start the arm swings down.",
    ),
    EFFECTS.field(
        "gravity (m·g·L·cos θ); stator_limit, supply_limit (per motor current limits); "
        "battery_sag (bus = battery − R × total supply current); friction (kS); "
        "counterbalance (zero-length spring, τ_cb·cos θ)."
    ),
    *EFFECTS.fields(),
    *motion.feedback_fields("angle", "deg", 2, "angular_speed", "deg/s", 20),
    *profiled.profile_fields(
        ("angle", "deg"),
        ("angular_speed", "deg/s", 90),
        ("angular_acceleration", "deg/s**2", 360),
        ("voltage_per_angle", "V/deg", 0.2),
        ("voltage_per_angular_speed", "V*s/deg", 0.01),
        1.0,
    ),
    *limit_grid.fields(),
    accuracy_field(),
)

OUTPUTS = (
    Output(
        "best_ratio",
        "Fastest ratio",
        help="Optimise: the reduction G that arrives first; ratios a few % "
        "either side are nearly as fast (AR11).",
        equation="(AR11)",
    ),
    Output(
        "moment_of_inertia",
        "Moment of inertia used",
        "inertia",
        "lb*in**2",
        help="About the pivot: 4/3·m·L² for the uniform bar, else as entered (AR3).",
        equation="(AR3)",
    ),
    *motion.common_outputs(
        "angle",
        "deg",
        "angular_speed",
        "deg/s",
        "V*s/rad",
        "V*s**2/rad",
        "V/rad",
        "Volts to hold the arm horizontal against gravity (minus the counterbalance); "
        "WPILib ArmFeedforward multiplies it by cos θ.",
    ),
    *EFFECTS.outputs(),
    *profiled.profile_outputs(
        ("angle", "deg"), ("angular_speed", "deg/s"), ("angular_acceleration", "deg/s**2")
    ),
    *profiled.return_outputs(("angle", "deg")),
    *limit_grid.outputs(),
    *STATS_OUTPUTS,
)
# what each shared output means here (equation, help), in this module's numbering
HOW = {
    "time_to_goal": ("(AR4)", "First time the arm reaches the goal angle from rest at full voltage (AR4)."),
    "max_speed": ("(AR5)", "Fastest the arm turns during the move (AR5)."),
    "free_speed": ("(AR5)", "Arm speed with no load at the battery voltage, ω_free·V_b/V_spec/G (AR5)."),
    "peak_stator_current": (
        "(AR2), (AR6)",
        "Largest motor (stator) current per motor: at rest, unless a limit holds it (AR6).",
    ),
    "peak_supply_current": ("(AR6)", "Largest battery-side current per motor: stator current × duty (AR6)."),
    "peak_battery_current": ("(AR6)", "Largest total battery current, N × supply current per motor (AR6)."),
    "min_bus_voltage": (
        "(AR6)",
        "Battery voltage minus the sag N·R_batt·(supply current); no sag: the battery's (AR6).",
    ),
    "energy": ("(AR7)", "Energy drawn from the battery over the move, ∫ V_b·N·u·I dt (AR7)."),
    "hold_current": (
        "(AR8)",
        "Per motor, to hold at the goal against gravity and counterbalance, friction aside (AR8).",
    ),
    "kG": (
        "(AR9)",
        "Volts to hold the arm horizontal, gravity minus counterbalance; WPILib uses kG·cos θ (AR9).",
    ),
    "kV": ("(AR9)", "Volts per unit of angular speed, G/Kv (WPILib kV) (AR9)."),
    "kA": ("(AR9)", "Volts per unit of angular acceleration, I·R/(η·N·Kt·G) (WPILib kA) (AR9)."),
    "kS": (
        "(AR9)",
        "Volts to overcome the motors' own loss and the friction, R·i_f + τ_f·R/(η·N·Kt·G) (WPILib kS) (AR9).",
    ),
    "kP": ("(AR10)", "LQR position gain for the plant kV, kA, as WPILib's LinearQuadraticRegulator (AR10)."),
    "kD": ("(AR10)", "LQR velocity gain for the plant kV, kA, as WPILib's LinearQuadraticRegulator (AR10)."),
}
OUTPUTS = tuple(
    replace(o, equation=HOW[o.name][0], help=HOW[o.name][1]) if o.name in HOW else o for o in OUTPUTS
)


def inertia(v) -> float:
    m, L = v["arm_mass"], v["com_distance"]
    if v["inertia_model"] == "uniform_bar":
        return 4.0 / 3.0 * m * L * L
    I = v["moment_of_inertia"]
    if I < m * L * L * (1 - 1e-12):
        raise InputError(
            "moment_of_inertia",
            f"is below m·L² = {m * L * L:.4g} kg·m², the least an arm of "
            f"this mass and centre of mass can have",
        )
    return I


def critical_angles(a: float, b: float) -> tuple[float, ...]:
    """Multiples of π between a and b: where cos θ (gravity and counterbalance) is extreme."""
    lo, hi = sorted((a, b))
    return tuple(k * math.pi for k in range(math.ceil(lo / math.pi), math.floor(hi / math.pi) + 1))


def setup(v, ratio=None, xp=motion.SCALAR) -> motion.Setup:
    on = v["effects"]
    if v["goal_angle"] == v["start_angle"]:
        raise InputError("goal_angle", "equals the start angle: nothing to move")
    motor, _ = lookup(v["motor"], v["source"])
    G_ = v["ratio"] if ratio is None else ratio
    mech = motion.Mechanism(
        motor,
        v["motor_count"],
        v["voltage"],
        v["efficiency"],
        G_,
        inertia(v),
        v["start_angle"],
        v["goal_angle"],
        motion.bus_resistance_of(v, on),
        xp,
    )
    asm = EFFECTS.assemble(on, v, mech, motion.SLOTS, ("angle", "speed", "energy"), minimum=xp.minimum)
    varying = asm.slots["force"] is not None
    return motion.Setup(
        mech,
        EFFECTS,
        asm,
        varying=varying,
        values=v,
        critical=critical_angles(v["start_angle"], v["goal_angle"]),
        names={
            "force_unit": "N·m",
            "friction": "friction_torque",
            "where": lambda q: f" at {math.degrees(q):.4g}°",
        },
    )


def simulate(v, rtol: float):
    _, note = lookup(v["motor"], v["source"])
    if v["mode"] == "optimise":
        run = motion.optimise(
            lambda G_, xp=motion.SCALAR: setup(v, G_, xp), v["ratio"], rtol, 1.0, hold_q=0.0
        )
    elif v["mode"] == "limit_grid":
        run = limit_grid.run_mode(setup, v, rtol, 1.0)  # (AR13)
    elif v["mode"] == "profiled":
        s = setup(v)
        ff = motion.feedforward(s, 0.0)  # (AR9): kG at horizontal
        kG = lambda q: ff["kG"] * math.cos(q)  # noqa: E731
        run = profiled.run_profiled(s, v, rtol, ff, kG, return_move=True, arm=True)  # (AR12), (AR14)
    else:
        run = motion.run_move(setup(v), rtol, hold_q=0.0)
    run.values["moment_of_inertia"] = inertia(v)
    braking_warning(v, run)
    if note:
        run.warnings.insert(0, note)
    return run


def compute(values, estimate: str = "now") -> Result:
    return profiled.mechanism_result(
        run_with_stats(simulate, values, estimate=estimate)
    )  # the return plot's legend: (P16)


def gains_of(solution) -> gains_code.Gains:
    """The profiled move's gains for the exports, in radians from horizontal (L = 2π a turn)."""
    return gains_code.profiled_gains(solution, lambda v: 2 * math.pi, title="Arm", arm=True)


DOCUMENTS = gains_code.mechanism_documents("Arm", gains_of, phoenix_note=", Arm_Cosine")

CALCULATOR = Calculator(
    id="arm",
    title="Arm",
    summary="Time for a single-jointed arm to swing to its goal, currents, kG/kV/kA and LQR gains.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    simulate=simulate,
    exports={"ratio_finder": {"target_ratio": "best_ratio"}},  # optimise mode: the parts for that ratio
    documents=DOCUMENTS,  # profiled mode: the gains as code
    plots=motion.plots("angle", "angle", "deg", "angular_speed", "deg/s")
    + profiled.profile_plots("angle", "angle", "deg")
    + profiled.return_plots("angle", "angle", "deg")
    + (limit_grid.heat_map_plot(),),
    tables=(limit_grid.table(),),
)
