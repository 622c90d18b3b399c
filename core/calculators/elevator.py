"""Elevator (or linear slide): N motors through a reduction G on a spool lift the carriage from rest
to the goal at full voltage, as a scene with effects (core.sim.motion, core.sim.effects).

Coordinate x: carriage travel along the rail, up positive; the rail leans `incline` from vertical.
    r = spool_diameter/2;  k = 1 (continuous rigging) or the stage count (cascade: the carriage
    moves k times the first stage, which the spool pulls)
    n = G/(r·k)                        motor radians per metre of carriage travel              (EL1)
    m·ẍ = η·N·Kt·n·(I − i_f) − m·g·cos(incline) (gravity) + F_cb (counterbalance)
          − F_f·sgn(ẋ) (friction)                                                             (EL2)
    I = (u·V_bus − n·ẋ/Kv)/R  per motor, u the duty (1 unless a current limit lowers it);
        R = V_spec/I_stall, Kv = ω_free/(V_spec − R·I_free), Kt = τ_stall/(I_stall − I_free),
        i_f = I_free·V_b/V_spec (the seed's motor model, eqs. 3, 7, 9, as every tab)            (EL3)
(gearhead.core.sim.motion (M1)-(M4); the current limits and battery sag set u and V_bus, (E1)-(E3)).
The rigging's own stage masses are not modelled (add them to load_mass, scaled by their speed ratio
squared, if they matter).
Closed form with no limits, no sag and a constant load F (the motors' loss η·N·Kt·n·i_f included;
the check in tests/test_motion.py):
    τ = m·R·Kv/(η·N·Kt·n²),  v_f = (V·Kv/n)·(1 − F/F_stall),  F_stall = η·N·Kt·n·V/R,
    v(t) = v_f·(1 − e^{−t/τ}),  x(t) = v_f·(t − τ·(1 − e^{−t/τ}))                              (EL4)
What a move reports:
    T: the first time x reaches the travel, from rest at full voltage: (EL4) solved for T (motion
       (C2), Lambert W) when it applies, else (EL2) integrated with an event at the goal       (EL5)
    v_max = largest |ẋ| over the move;  v_free = (V_b − R·i_f)·Kv/n = ω_free·V_b/(V_spec·n)  (EL6)
    peak stator current: |I| of (EL3) at rest (at top speed if the load drives the motor past
    free speed); supply current u·I per motor; battery current N·u·I; bus voltage
    V_bus = V_b − N·R_batt·u·I, lowest where the supply current peaks                          (EL7)
    E = ∫ V_b·N·u·I dt, the battery's EMF times its current                                     (EL8)
    I_hold = |F_field(goal)|/(η·N·Kt·n) per motor, F_field = −m·g·cos(incline) + F_cb          (EL9)
Effects: gravity (on by default), stator_limit, supply_limit, battery_sag, friction (a constant
force against the motion, added to kS), counterbalance (a constant-force spring pulling up).
Feedforward in WPILib's convention, V = kS·sgn(ẋ) + kG + kV·ẋ + kA·ẍ from (EL2), (EL3) at u = 1:
    kG = −F_field·R/(η·N·Kt·n),  kV = n/Kv,  kA = m·R/(η·N·Kt·n),  kS = R·i_f + F_f·R/(η·N·Kt·n)
                                                                                              (EL10)
(kG: gravity minus the counterbalance). Note: ReCalc scales only the voltage input by η, so its
kV is this kV/η (they agree at η = 1). Feedback: WPILib's LQR on the plant (x, ẋ),
    ẋ = [[0, 1], [0, −kV/kA]]·x + [0, 1/kA]·V, discretised over the control period,
    Q = diag(1/q_pos², 1/q_vel²), R = 1/r²: [kP, kD] from the discrete Riccati equation,
    latency-compensated (motion.lqr)                                                           (EL11)
Optimise: G* minimising T(G): 240 ratios log-spaced about the characteristic ratio
(d = v_free·τ), then bounded Brent on the accurate move around the best (motion.optimise)       (EL12)
Profiled move: the loop robot code runs (core.sim.profiled (P1)-(P11)): a trapezoid from rest to rest
(limits entered, or fractions of v_free and of the acceleration from rest at the stator current
limit, (P17)), or
WPILib's exponential profile from an entered max input on kV, kA (EL10) ((P12)-(P15)), the
feedforward (EL10) with kG constant, PD feedback (the LQR gains (EL11) or entered) on the position
measured `sensor_delay` earlier, every `control_period`, the voltage held between updates and
clamped at the battery voltage; (EL2) with friction against the motion in either direction    (EL13)
and the way back, goal to start with the same gains and profile (P16): gravity loads the carriage
one way and helps it the other, where the loop brakes against it                                 (EL15)
Current-limit grid: for each stator × supply limit pair the fastest ratio of the full-voltage move,
its time, peak currents and energy; the pick within a supply budget (core.sim.limit_grid)     (EL14)
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

RIGGINGS = ("continuous", "cascade")
RIGGING_LABELS = (
    "Continuous (carriage moves with the rope)",
    "Cascade (carriage moves stages × the first stage)",
)


def _gravity(values, mech) -> Part:
    F = -values["load_mass"] * G * math.cos(values["incline"])
    return Part(terms={"force": lambda q: F + 0 * q})


def _counterbalance(values, mech) -> Part:
    F = values["counterbalance_force"]
    return Part(terms={"force": lambda q: F + 0 * q})


EFFECTS = Effects(
    Effect("gravity", "the load's weight along the rail", _gravity, default_on=True),
    *motion.electrical_effects(),
    motion.friction_effect(
        "force", "lbf", "friction_force", "a constant force against the motion (reported as kS)", 2.0
    ),
    Effect(
        "counterbalance",
        "a constant-force spring pulling the carriage up",
        _counterbalance,
        fields=(
            Field(
                "counterbalance_force",
                "Counterbalance force",
                "force",
                "lbf",
                default=10,
                min=0,
                max=2.2e5,
                help="Upward pull of constant-force springs on the carriage.",
            ),
        ),
    ),
)


FIELDS = (
    motion.mode_field(profiled=True, grid=True),
    *motion.battery_motor_fields("NEO", 2),
    Field(
        "ratio",
        "Reduction G",
        "dimensionless",
        "",
        default=10,
        min=0,
        min_exclusive=True,
        max=1e5,
        modes=("move", "profiled"),
        help="Motor turns per spool turn.",
    ),
    Field(
        "load_mass",
        "Load mass",
        "mass",
        "lb",
        default=15,
        min=0,
        min_exclusive=True,
        max=2.2e5,
        help="Carriage plus game piece (plus moving stages, scaled by their speed ratio squared).",
    ),
    Field(
        "spool_diameter",
        "Spool diameter",
        "length",
        "in",
        default=1.5,
        min=0,
        min_exclusive=True,
        max=3900,
        help="Pitch diameter of the spool, drum or sprocket that pulls the first stage.",
    ),
    Field(
        "travel",
        "Travel",
        "length",
        "in",
        default=40,
        min=-3.9e5,
        max=3.9e5,
        help="From start to goal along the rail; up is positive, negative moves down.",
    ),
    Field(
        "incline",
        "Incline from vertical",
        "angle",
        "deg",
        default=0,
        min=0,
        max=180,
        help="0: vertical; 90°: horizontal slide (no gravity along it); beyond 90° the rail points down.",
    ),
    Field(
        "rigging",
        "Rigging",
        choices=RIGGINGS,
        choice_labels=RIGGING_LABELS,
        default="continuous",
        help="Continuous: the carriage moves with the rope. Cascade: each stage doubles up, the carriage "
        "moves `stages` times the first stage.",
    ),
    Field(
        "stages",
        "Moving stages",
        integer=True,
        default=2,
        min=1,
        max=10,
        when=(("rigging", ("cascade",)),),
        help="Cascade: the carriage moves this many times the first stage's travel.",
    ),
    EFFECTS.field(
        "gravity (on: vertical or inclined lift); stator_limit, supply_limit (per motor current "
        "limits); battery_sag (bus = battery − R × total supply current); friction (kS); "
        "counterbalance (constant-force spring)."
    ),
    *EFFECTS.fields(),
    *motion.feedback_fields("length", "in", 0.5, "speed", "in/s", 10),
    *profiled.profile_fields(
        ("length", "in"),
        ("speed", "ft/s", 3),
        ("acceleration", "ft/s**2", 10),
        ("voltage_per_length", "V/in", 2),
        ("voltage_per_speed", "V*s/in", 0.05),
        0.25,
    ),
    *limit_grid.fields(),
    accuracy_field(),
)

OUTPUTS = (
    Output(
        "best_ratio",
        "Fastest ratio",
        help="Optimise: the reduction G that arrives first; ratios a few % "
        "either side are nearly as fast (EL12).",
        equation="(EL12)",
    ),
    *motion.common_outputs(
        "length",
        "in",
        "speed",
        "ft/s",
        "V*s/m",
        "V*s**2/m",
        "V/m",
        "Volts to hold the load against gravity (minus the counterbalance).",
    ),
    *profiled.profile_outputs(("length", "in"), ("speed", "ft/s"), ("acceleration", "ft/s**2")),
    *profiled.return_outputs(("length", "in")),
    *limit_grid.outputs(),
    *EFFECTS.outputs(),
    *STATS_OUTPUTS,
)
# what each shared output means here (equation, help), in this module's numbering
HOW = {
    "time_to_goal": (
        "(EL4), (EL5)",
        "First time the carriage reaches the goal from rest at full voltage (EL5).",
    ),
    "max_speed": ("(EL6)", "Fastest the carriage moves during the move (EL6)."),
    "free_speed": ("(EL6)", "Carriage speed with no load at the battery voltage, ω_free·V_b/V_spec/n (EL6)."),
    "peak_stator_current": (
        "(EL3), (EL7)",
        "Largest motor (stator) current per motor: at rest, unless a limit holds it (EL7).",
    ),
    "peak_supply_current": ("(EL7)", "Largest battery-side current per motor: stator current × duty (EL7)."),
    "peak_battery_current": ("(EL7)", "Largest total battery current, N × supply current per motor (EL7)."),
    "min_bus_voltage": (
        "(EL7)",
        "Battery voltage minus the sag N·R_batt·(supply current); no sag: the battery's (EL7).",
    ),
    "energy": ("(EL8)", "Energy drawn from the battery over the move, ∫ V_b·N·u·I dt (EL8)."),
    "hold_current": (
        "(EL9)",
        "Per motor, to hold at the goal against gravity and counterbalance, friction aside (EL9).",
    ),
    "kG": ("(EL10)", "Volts to hold the load against gravity, minus the counterbalance (WPILib kG) (EL10)."),
    "kV": ("(EL10)", "Volts per unit of speed, n/Kv (WPILib kV) (EL10)."),
    "kA": ("(EL10)", "Volts per unit of acceleration, m·R/(η·N·Kt·n) (WPILib kA) (EL10)."),
    "kS": (
        "(EL10)",
        "Volts to overcome the motors' own loss and the friction, R·i_f + F_f·R/(η·N·Kt·n) (WPILib kS) (EL10).",
    ),
    "kP": ("(EL11)", "LQR position gain for the plant kV, kA, as WPILib's LinearQuadraticRegulator (EL11)."),
    "kD": ("(EL11)", "LQR velocity gain for the plant kV, kA, as WPILib's LinearQuadraticRegulator (EL11)."),
}
OUTPUTS = tuple(
    replace(o, equation=HOW[o.name][0], help=HOW[o.name][1]) if o.name in HOW else o for o in OUTPUTS
)


def spool_factor(v) -> float:
    """r·k: metres of carriage travel per spool radian."""
    k = v["stages"] if v["rigging"] == "cascade" else 1
    return v["spool_diameter"] / 2 * k


def setup(v, ratio=None, xp=motion.SCALAR) -> motion.Setup:
    on = v["effects"]
    if v["travel"] == 0:
        raise InputError("travel", "is zero: enter the distance from start to goal (negative moves down)")
    motor, _ = lookup(v["motor"], v["source"])
    G_ = v["ratio"] if ratio is None else ratio
    mech = motion.Mechanism(
        motor,
        v["motor_count"],
        v["voltage"],
        v["efficiency"],
        G_ / spool_factor(v),
        v["load_mass"],
        0.0,
        v["travel"],
        motion.bus_resistance_of(v, on),
        xp,
    )
    asm = EFFECTS.assemble(on, v, mech, motion.SLOTS, ("position", "speed", "energy"), minimum=xp.minimum)
    return motion.Setup(
        mech, EFFECTS, asm, varying=False, values=v, names={"force_unit": "N", "friction": "friction_force"}
    )


def simulate(v, rtol: float):
    from ..motors import lookup as _lookup

    _, note = _lookup(v["motor"], v["source"])
    if v["mode"] == "optimise":
        run = motion.optimise(
            lambda G_, xp=motion.SCALAR: setup(v, G_, xp), v["ratio"], rtol, spool_factor(v)
        )
    elif v["mode"] == "limit_grid":
        run = limit_grid.run_mode(setup, v, rtol, spool_factor(v))  # (EL14)
    elif v["mode"] == "profiled":
        s = setup(v)
        ff = motion.feedforward(s, s.mech.q1)  # (EL10): kG the same all along the rail
        run = profiled.run_profiled(s, v, rtol, ff, lambda q: ff["kG"], return_move=True)  # (EL13), (EL15)
    else:
        run = motion.run_move(setup(v), rtol)
    braking_warning(v, run)
    if note:
        run.warnings.insert(0, note)
    return run


def compute(values, estimate: str = "now") -> Result:
    return profiled.mechanism_result(
        run_with_stats(simulate, values, estimate=estimate)
    )  # the return plot's legend: (P16)


def gains_of(solution) -> gains_code.Gains:
    """The profiled move's gains for the exports, in metres of carriage travel (L = 2π·r·k a drum turn)."""
    return gains_code.profiled_gains(solution, lambda v: 2 * math.pi * spool_factor(v))


DOCUMENTS = gains_code.mechanism_documents("Elevator", gains_of)

CALCULATOR = Calculator(
    id="elevator",
    title="Elevator",
    summary="Time for an elevator or linear slide to reach its goal, currents, kG/kV/kA and LQR gains.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    simulate=simulate,
    exports={"ratio_finder": {"target_ratio": "best_ratio"}},  # optimise mode: the parts for that ratio
    documents=DOCUMENTS,  # profiled mode: the gains as code
    tables=(limit_grid.table(),),
    plots=motion.plots("position", "length", "in", "speed", "ft/s")
    + profiled.profile_plots("position", "length", "in")
    + profiled.return_plots("position", "length", "in")
    + (limit_grid.heat_map_plot(),),
)
