"""Seed 000 (flywheel study, VEX Nothing but Net 2015-16): energy to the ball, range error from the
ball-mass tolerance, spin-up and recovery, as a scene with effects.

The seed's model, in its order (equations numbered here (1)-(9) in the order the seed writes them):
    (1) R = V²/g · sin 2θ                                   vacuum range, release at ground level
    (2) V = r_w·ω_w/2,  ω_b = V/r_b                         hooded shooter: ball rolls on the hood
    (3) E_b = ½·m·V² + ½·I_b·ω_b² = ½·m·V²·(1 + k_b),  k_b = I_b/(m·r_b²) = 2/5 (solid sphere)
    (4) E_w = ½·I_w·ω_w²,  I_w = m_w·(0.84·r_w)²            radius of gyration 0.84·r_w
    (5) E_w,initial = E_w,final + E_b                       energy conservation, motor off in the shot
    (6) β = E_b/E_w,final = (1+k_b)·s²/k² · m/m_w           (s = V/(r_w·ω_w); seed: ".4954"·m/m_w)
    (7) R/R₀ = (1 + β₀)/(1 + β)                             R ∝ V² ∝ ω_final² ∝ E_w,final
    (8) e_r = −e_m/(m_w/(c·m₀) + 1 + e_m),  c = β·m_w/m     exact within the model
    (9) e_r ≈ −e_m/(n·6.06 + 1)                             the seed's table (e_m dropped below)

Where this module departs from or corrects the seed:
- (3) The seed's first version had (1 + 4/5); its own 5/29 correction to (1 + 2/5) is used, and k_b
  is a field (2/5 solid sphere, 2/3 thin shell; the real foam ball lies between).
- (6) The seed's ".4954" is a rounding slip: (1 + 2/5)·(1/2)²/0.84² = 0.35/0.7056 = 0.49603 (0.4954
  is 0.35/0.7065, the digits of 0.84² transposed). Its 2.02 (= 1/0.4954 = 2.0186) becomes 2.0160
  and its 6.06 = 3·2.02 becomes 6.048. The seed's linearised table (9) is unchanged at its two
  decimals (−1.42, −0.76, −0.52, −0.40, −0.32 % for 10 %): `range_error_linear_n`.
- (9) drops e_m from the denominator of (8); it is the first-order term. `range_error_n` gives the
  exact value beside it (n = 1: −1.399 % instead of −1.419 %). Linear: −e_m·β₀/(1 + β₀).
- (1) with a release height h ≥ 0: R = V·cosθ/g·(V·sinθ + √(V²·sin²θ + 2·g·h)); h = 0 is the seed.
  Range differences are formed without cancellation (see `range_gain`).
- The seed's own scene reaches its wheel speed with the motor off during the shot. The `momentum`
  effect replaces (5) by angular-impulse transfer with slip until the ball rolls (the Team 449
  model): I_w·(ω₀ − ω₁) = r_w·J, m_e·V = J/s  ⇒  ω₁ = ω₀/(1 + β); the slip dissipates energy, so
  the range error per unit mass error is about twice the energy model's.
- Two-wheel shooter: V = r_w·ω_w (s = 1), no spin (symmetric), all n wheels' inertia shared.
- `loss_fraction` f (friction, ball compression): energy model, E_b = (1−f)·(E_w,initial − E_w,final)
  ⇒ ω₁ = ω₀/√(1 + β/(1−f)); momentum model, the ball leaves with (1−f) of its energy (V·√(1−f)).

The physics is core.sim.shooter's: the layouts with a secondary wheel (D1)-(D7), the shot, the
slip phase of motor_during_shot, the burst, the limited spin-up and the grid's cells.

The motor side, labelled here (A = G·τ̃s the wheel torque at stall, B = A/ω_f,w, I all wheels):
    ω_f,w = ω̃f/G,  T = I/B = I·ω̃f/(G²·τ̃s)          wheel free speed, spin-up time constant (FW1)
    t(ω₁ → ω_t) = T·ln((ω_f,w − ω₁)/(ω_f,w − ω_t))    full power: spin-up ω₁ = 0, recovery (FW2)
    I·dω/dt = A − B·ω − r_w·F,  m_e·s·dV/dt = F  until r_w·ω = V/s:  the slip phase of
        motor_during_shot, its duration the contact time                                   (FW3)
    under a current limit A − B·ω is the limited τ_w(ω) of (F1), integrated (scipy's Radau
        when stiff)                                                                        (FW3')
    ω(t) = ω_f,w − (ω_f,w − ω)·e^(−t/T) between shots ((F1) integrated under a limit), each
        shot by (5) or the momentum model; the slowest ball is the least V of the burst    (FW4)
    τ_w(ω) = A·(I(E) − i_f)/(i_s − i_f),  E = G·ω/Kv  under a current limit, I(E) by
        core.sim.motor_limits (E1)-(E3); (FW2) is then integrated phase by phase           (F1)
    A' = A·(V/(R + R_bus) − i_f)/(i_s − i_f),  ω_f,w' = Kv·(V − i_f·(R + R_bus))/G:
        battery_sag alone, still linear in ω                                                (F2)
    peak stator current I(E = 0) per motor (it never rises with speed); peak supply current
        the largest u·I (E4) at rest, at the target and where a limit lets go; lowest bus
        voltage V_b − R_bus·(u·I)_peak                                                      (FW5)
Velocity loop (control = velocity_loop; issue 30): the wheel under robot code's feedforward plus
proportional feedback at the control period, core.sim.velocity_loop (VL1)-(VL9): the motor of (F1)
with the held duty of each period, kS/kV/kA per rad/s at the wheel (VL2), LQR's kP (VL9); the
setpoint a step to the target, or a ramp from rest at an entered acceleration or a fraction of the
stall acceleration (V_b − kS)/kA with WPILib's discrete feedforward (VL4a), as Motion Magic Velocity
and MAXMotion velocity run it. The shot
is the model chosen above ((5) or the momentum model), from the wheel's speed at the shot time, as
an instant drop (with motor_during_shot its slip phase runs at full power, as in the burst).
Current-limit grid (control = limit_grid; issue 30): for every stator × supply limit pair (per
motor; both limits on, with the other effects chosen) the ratio that spins the wheels up from rest
to the target quickest at full power:
    T(G) = J(G)·∫₀^ω_t dω/τ_w(ω; G)  ((F1) is autonomous: dt = J·dω/τ_w; scipy's quad on each
    smooth piece between the speeds where a limit lets go; J(G) with the rotors' N·J_r·G²)   (FW6)
    G* = argmin T over (G_max·10⁻², G_max), G_max the ratio whose free speed is the target: the
    best of 24 log-spaced ratios (the span moved down 2 decades while the best is its lowest:
    heavy rotors), then bounded Brent on ln G between its neighbours                          (FW7)
    at G*: peak stator and supply current (FW5), battery energy J·∫ N·V_b·u·I/τ_w dω; the pick
    is the quickest cell whose peak supply current is within the budget                     (FW8)
`range_error_linear` is the seed's (9) whatever transfer model, losses or height are chosen: the
momentum model's error is about twice it.
"""

from __future__ import annotations

import dataclasses
import math

from .. import gains_code
from ..constants import RPM
from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field
from ..motors import lookup, motor_fields, system_from
from ..sim import limit_grid, motion, motor_limits
from ..sim.scene import STATS_OUTPUTS, SimRun, accuracy_field, run_with_stats
from ..sim.shooter import (
    EFFECTS,
    SECONDARY,
    WITH_SPIN,
    Scene,
    Shots,
    TooFast,
    burst,
    check_limits,
    electrical_extremes,
    grid_cells,
    inertia_each,
    projectile_range,
    range_change,
    range_error_linear,
    recovery,
    rotor_reflected,
    scene_from,
    secondary_reflected,
    secondary_speed_ratio,
    shot,
    with_inertia,
)

TABLE_WHEELS = range(1, 7)
SLIP_LENGTH_WARN = 0.5  # m: longer than the contact path of any hood or wheel pair
TRANSFERS = ("energy", "momentum")
# Once effects; an entry or preset naming one among the effects means that transfer (effects.retire)
RETIRED = tuple((t, "transfer", t) for t in TRANSFERS)
TRANSFER_LABELS = (
    "Energy (seed: energy conservation, translation + spin)",
    "Momentum (angular impulse with slip, Team 449)",
)
SHOOTERS = ("hood", "two_wheel", "dual", "compound", "hood_secondary")
SHOOTER_LABELS = (
    "Single wheel with hood (ball at half surface speed)",
    "Two wheels (ball at surface speed)",
    "Dual: bottom and top wheels, each its own diameter and ratio",
    "Compound: hood section, then between the wheel and a secondary wheel",
    "Hood with a secondary wheel geared to it (inertia only)",
)
INERTIA_MODES = ("radius_of_gyration", "moment_of_inertia")
CONTROLS = ("full_power", "velocity_loop", "limit_grid")
CONTROL_LABELS = (
    "Full power (seed)",
    "Velocity loop: feedforward + kP at the control period",
    "Current-limit grid: the quickest ratio per stator × supply limit (full power)",
)


def _motor_fields():
    out = []
    for f in motor_fields(default_motor="VEX 393", default_count=2):
        if f.name == "voltage":
            f = dataclasses.replace(
                f,
                default=7.2,
                help="Applied voltage (VEX 393: 7.2 V; V5 and FRC: 12 V); motor data is scaled by V/V_spec.",
            )
        out.append(f)
    return tuple(out)


LOOP = (("control", ("velocity_loop",)),)
SETPOINTS = ("step", "ramp")
SETPOINT_LABELS = ("Step to the target", "Ramp at an acceleration to the target")
RAMP = LOOP + (("setpoint_profile", ("ramp",)),)
LQR = LOOP + (("feedback", ("lqr",)),)
# the loop's period and delay and LQR's tolerances: the declarations every loop shares (one state,
# the wheel's speed, in rpm)
SHARED = {
    f.name: f
    for f in motion.feedback_fields(None, "", 0, "angular_speed", "rpm", 100, when=LOOP, lqr_when=LQR)
}
LOOP_FIELDS = (
    Field(
        "control",
        "Spin-up control",
        choices=CONTROLS,
        choice_labels=CONTROL_LABELS,
        default="full_power",
        help="Full power: the seed's spin-up at full voltage, held at the target (FW2). Velocity loop: "
        "feedforward + kP on the speed error every control period with the sensor delay, as robot "
        "code runs it (core.sim.velocity_loop (VL1)-(VL8)); adds the loop's outputs and charts. "
        "Current-limit grid: for each stator × supply limit pair the ratio that spins up quickest at "
        "full power (FW6)-(FW8), as a table and a heat map, the quickest within the supply budget picked.",
    ),
    SHARED["control_period"],
    SHARED["sensor_delay"],
    Field(
        "speed_tolerance",
        "Speed tolerance",
        "angular_speed",
        "rpm",
        default=50,
        min=0,
        min_exclusive=True,
        max=1e6,
        when=LOOP,
        help="Spun up (recovered): within this of the target from then on (VL6).",
    ),
    Field(
        "shot_time",
        "Shot at",
        "time",
        "s",
        default=3,
        min=0.001,
        max=60,
        when=LOOP,
        help="When the ball is shot (the wheel speed drops as the shot model says, at once); the loop "
        "is simulated to this time plus the larger of 1 s and it. A shot at a loop update comes after "
        "that update's measurement: a reading of that instant, then or through the delay, is the "
        "speed before the shot.",
    ),
    Field(
        "setpoint_profile",
        "Setpoint",
        choices=SETPOINTS,
        choice_labels=SETPOINT_LABELS,
        default="step",
        when=LOOP,
        help="Step: the loop asks for the target at once (VelocityVoltage, kVelocity). Ramp: the "
        "setpoint rises from rest at a set acceleration to the target, with kA's feedforward "
        "(VL4a; Motion Magic Velocity, MAXMotion velocity).",
    ),
    Field(
        "ramp_limit",
        "Ramp acceleration from",
        choices=("derived", "entered"),
        choice_labels=("A fraction of the stall acceleration", "Entered"),
        default="derived",
        when=RAMP,
        help="The ramp's acceleration: a fraction of the wheel's acceleration from rest at full "
        "voltage, (V_b − kS)/kA (no limit, no sag), or entered.",
    ),
    Field(
        "ramp_fraction",
        "Ramp fraction",
        "dimensionless",
        "",
        default=0.5,
        min=0,
        min_exclusive=True,
        max=1,
        when=RAMP + (("ramp_limit", ("derived",)),),
        help="The ramp's acceleration as a fraction of the stall acceleration (0-1); below 1 leaves "
        "voltage for the feedback.",
    ),
    Field(
        "ramp_acceleration",
        "Ramp acceleration",
        "angular_acceleration",
        "rpm/s",
        default=3000,
        min=0,
        min_exclusive=True,
        max=1e9,
        when=RAMP + (("ramp_limit", ("entered",)),),
        help="The wheel's setpoint acceleration (MotionMagicAcceleration, MAXMotion maxAcceleration).",
    ),
    Field(
        "feedback",
        "Feedback gain",
        choices=("lqr", "entered"),
        choice_labels=("LQR from the tolerances below", "Entered kP"),
        default="lqr",
        when=LOOP,
        help="The velocity loop's kP: WPILib's LQR for the 1-state velocity system (VL9), or your own.",
    ),
    SHARED["q_velocity"],
    SHARED["r_volts"],
    Field(
        "feedback_kp",
        "kP",
        "voltage_per_angular_speed",
        "V*s/rad",
        default=0.01,
        min=0,
        max=1e6,
        when=LOOP + (("feedback", ("entered",)),),
        help="Volts per rad/s of wheel-speed error (PIDController kP).",
    ),
)

GRID = (("control", ("limit_grid",)),)

GRID_FIELDS = limit_grid.fields((), GRID)  # core.sim.limit_grid's, shown by `control`

FIELDS = (
    Field(
        "mode",
        "Wheel inertia from",
        choices=INERTIA_MODES,
        default="radius_of_gyration",
        choice_labels=("Mass and radius of gyration", "Moment of inertia"),
        help="How the wheel's moment of inertia is given.",
    ),
    Field(
        "wheel_diameter",
        "Wheel diameter",
        "length",
        "in",
        default=5,
        min=0,
        min_exclusive=True,
        max=79,
        help="Flywheel diameter 2·r_w.",
    ),
    Field(
        "wheel_mass",
        "Wheel mass (each)",
        "mass",
        "g",
        default=180,
        min=0,
        min_exclusive=True,
        max=50_000,
        modes=("radius_of_gyration",),
        help="Mass m_w of one wheel (VEX 5 in wheel: 180 g).",
    ),
    Field(
        "gyration_fraction",
        "Radius of gyration / radius",
        "dimensionless",
        "",
        default=0.84,
        min=0,
        min_exclusive=True,
        max=1,
        modes=("radius_of_gyration",),
        help="k/r_w with I = m_w·(k·r_w)² (seed: 0.84 for the VEX 5 in wheel; disc 0.707; rim 1).",
    ),
    Field(
        "wheel_inertia",
        "Wheel inertia (each)",
        "inertia",
        "lb*in**2",
        default=1.75,
        min=0,
        min_exclusive=True,
        max=3.4e9,
        modes=("moment_of_inertia",),
        help="Moment of inertia of one wheel about its axle (with its share of shaft and gears).",
    ),
    Field(
        "wheel_count",
        "Wheels",
        integer=True,
        default=1,
        min=1,
        max=20,
        help="Wheels spinning together (all wheels of both sides for a two-wheel shooter; the "
        "primary shaft's for the layouts with a secondary wheel).",
    ),
    Field(
        "shooter",
        "Shooter",
        choices=SHOOTERS,
        choice_labels=SHOOTER_LABELS,
        default="hood",
        help="Hood: the ball rolls on the hood and leaves at half the surface speed with spin V/r_b. "
        "Two wheels: surface speed, no spin. Dual: between the primary (bottom) and secondary (top) "
        "wheels, V = (r₁·ω₁ + r₂·ω₂)/2 (D2). Compound: a hood section, then dual (D6). Hood with a "
        "secondary wheel: its inertia adds to the hood shooter's (D7).",
    ),
    Field(
        "ball_diameter",
        "Ball diameter",
        "length",
        "in",
        default=4,
        min=0,
        min_exclusive=True,
        max=79,
        when=(("shooter", WITH_SPIN),),
        help="2·r_b: sets the spin c·V/r_b of the ball (D2); c = 1 rolling on the hood.",
    ),
    Field(
        "secondary_diameter",
        "Secondary wheel diameter",
        "length",
        "in",
        default=4,
        min=0,
        min_exclusive=True,
        max=79,
        when=(("shooter", SECONDARY),),
        help="2·r₂ of the secondary (top) wheel (D2); for hood_secondary only its inertia counts.",
    ),
    Field(
        "secondary_mass",
        "Secondary wheel mass (each)",
        "mass",
        "g",
        default=180,
        min=0,
        min_exclusive=True,
        max=50_000,
        modes=("radius_of_gyration",),
        when=(("shooter", SECONDARY),),
        help="Mass of one secondary wheel.",
    ),
    Field(
        "secondary_gyration_fraction",
        "Secondary radius of gyration / radius",
        "dimensionless",
        "",
        default=0.84,
        min=0,
        min_exclusive=True,
        max=1,
        modes=("radius_of_gyration",),
        when=(("shooter", SECONDARY),),
        help="k₂/r₂ with I₂ = m₂·(k₂·r₂)² (disc 0.707, ReCalc's m·r²/2).",
    ),
    Field(
        "secondary_inertia",
        "Secondary wheel inertia (each)",
        "inertia",
        "lb*in**2",
        default=1.75,
        min=0,
        min_exclusive=True,
        max=3.4e9,
        modes=("moment_of_inertia",),
        when=(("shooter", SECONDARY),),
        help="Moment of inertia of one secondary wheel about its axle.",
    ),
    Field(
        "secondary_count",
        "Secondary wheels",
        integer=True,
        default=1,
        min=1,
        max=20,
        when=(("shooter", SECONDARY),),
        help="Secondary wheels spinning together on their shaft.",
    ),
    Field(
        "secondary_ratio",
        "Secondary ratio (motor : secondary)",
        "dimensionless",
        "",
        default=0.04,
        min=1e-4,
        max=1e4,
        when=(("shooter", SECONDARY),),
        help="G₂, motor turns per secondary wheel turn; the secondary turns at G/G₂ of the primary (D1).",
    ),
    Field(
        "ball_initial_speed",
        "Ball incoming speed",
        "speed",
        "m/s",
        default=0,
        min=0,
        max=100,
        help="V_i: the ball's speed along the shot as it meets the wheel (ReCalc v2; 0: at rest) (D4), (D5).",
    ),
    Field(
        "ball_initial_spin",
        "Ball incoming spin",
        "angular_speed",
        "rpm",
        default=0,
        min=-1e6,
        max=1e6,
        when=(("shooter", WITH_SPIN),),
        help="ω_bi, positive in the sense the primary wheel spins the ball (a hood shot's) (D4), (D5).",
    ),
    Field(
        "ball_mass",
        "Ball mass",
        "mass",
        "g",
        default=60,
        min=0,
        max=5000,
        help="Nominal ball mass m₀ (NbN ball: 60 g).",
    ),
    Field(
        "ball_inertia_factor",
        "Ball I/(m·r²)",
        "dimensionless",
        "",
        default=0.4,
        min=0,
        max=0.67,
        when=(("shooter", WITH_SPIN),),
        help="k_b = I_b/(m·r_b²): 2/5 solid sphere (seed, ReCalc's default), 2/3 thin shell.",
    ),
    Field(
        "ball_mass_tolerance",
        "Ball mass tolerance",
        "dimensionless",
        "%",
        default=10,
        min=0,
        max=90,
        help="e_m: balls up to m₀·(1 ± e_m); range errors are for the heavy ball, as in the seed.",
    ),
    Field(
        "target_speed",
        "Wheel target speed",
        "angular_speed",
        "rpm",
        default=2000,
        min=0,
        min_exclusive=True,
        help="Wheel speed the controller spins up to and holds; the shot starts at it.",
    ),
    Field(
        "launch_angle",
        "Launch angle",
        "angle",
        "deg",
        default=45,
        min=0,
        min_exclusive=True,
        max=90,
        max_exclusive=True,
        help="Elevation θ of the release above horizontal.",
    ),
    Field(
        "release_height",
        "Release height above target",
        "length",
        "m",
        default=0,
        min=0,
        max=100,
        help="h: the release point above the landing height (0: the seed's R = V²·sin2θ/g).",
    ),
    *_motor_fields(),
    Field(
        "ratio",
        "Gear ratio (motor : wheel)",
        "dimensionless",
        "",
        default=0.04,
        min=0,
        min_exclusive=True,
        max=1e4,
        help="G, motor turns per wheel turn (a speed-up is below 1: 1:25 is 0.04).",
    ),
    Field(
        "rotor_inertia",
        "Rotor inertia (each motor)",
        "inertia",
        "kg*m**2",
        default=0,
        min=0,
        max=1,
        help="J_r of one motor's rotor, reflected to the wheels as N·J_r·G² (the rotor turns G times per "
        "wheel turn) and spun up and slowed by the shot with them; 0 neglects it, as WPILib's "
        "DCMotor does.",
    ),
    Field(
        "loss_fraction",
        "Loss fraction",
        "dimensionless",
        "%",
        default=0,
        min=0,
        max=100,
        max_exclusive=True,
        help="f: friction and ball compression (energy model: of the energy the wheel gives up; "
        "momentum model: of the ball's energy).",
    ),
    Field("shots", "Shots in the burst", integer=True, default=4, min=1, max=50),
    Field(
        "shot_interval",
        "Shot interval",
        "time",
        "s",
        default=0.5,
        min=0.01,
        max=60,
        help="Cadence of the burst: time from one shot to the next.",
    ),
    Field(
        "transfer",
        "Transfer model",
        choices=TRANSFERS,
        choice_labels=TRANSFER_LABELS,
        default="energy",
        help="How the wheel's spin reaches the ball: energy conservation (the seed) or angular impulse "
        "with slip until the ball rolls (Team 449).",
    ),
    EFFECTS.field(
        "motor_during_shot (momentum model only): the motor drives during the slip; stator_limit, "
        "supply_limit (per motor current limits) and battery_sag (bus = battery − R × total supply "
        "current) act on the spin-up and the recovery between shots.",
        retired=RETIRED,
    ),
    *EFFECTS.fields(),
    *LOOP_FIELDS,
    *GRID_FIELDS,
    accuracy_field(),
)


LOOP_OUTPUTS = (
    Output(
        "loop_spin_up_time",
        "Spin-up time (velocity loop)",
        "time",
        "s",
        help="From rest until the wheel stays within the speed tolerance of the target up to the shot (VL6).",
        equation="(VL6)",
    ),
    Output(
        "loop_overshoot",
        "Overshoot (velocity loop)",
        "angular_speed",
        "rpm",
        help="Fastest above the target before the shot (0 when it never passes it) (VL7).",
        equation="(VL7)",
    ),
    Output(
        "loop_speed_at_shot",
        "Speed at the shot (velocity loop)",
        "angular_speed",
        "rpm",
        help="Wheel speed when the ball is shot.",
        equation="(VL5)",
    ),
    Output(
        "loop_speed_dip",
        "Lowest speed after the shot",
        "angular_speed",
        "rpm",
        help="The shot's drop (the shot model from the speed at the shot) and anything the delay adds (VL7).",
        equation="(5), (VL7)",
    ),
    Output(
        "loop_recovery_time",
        "Recovery time (velocity loop)",
        "time",
        "s",
        help="From the shot until the wheel stays within the speed tolerance to the window's end (VL6).",
        equation="(VL6)",
    ),
    Output(
        "loop_final_error",
        "Steady-state error (velocity loop)",
        "angular_speed",
        "rpm",
        help="Target minus wheel speed at the window's end (positive: short).",
        equation="(VL4)",
    ),
    Output(
        "loop_peak_stator_current",
        "Peak stator current (loop)",
        "current",
        "A",
        help="Per motor, the largest |I| over the run (VL8).",
        equation="(VL8)",
    ),
    Output(
        "loop_peak_supply_current",
        "Peak supply current (loop)",
        "current",
        "A",
        help="Per motor, the largest duty × stator current over the run (VL8).",
        equation="(VL8)",
    ),
    Output(
        "loop_min_bus_voltage",
        "Min bus voltage (loop)",
        "voltage",
        "V",
        help="Battery voltage minus R_bus × the peak supply current (battery_sag; else the battery voltage).",
        equation="(VL8)",
    ),
    Output(
        "kS",
        "kS",
        "voltage",
        "V",
        help="Static gain R·i_f: the voltage the free current's loss takes (VL2).",
        equation="(VL2)",
    ),
    Output(
        "kV",
        "kV (per wheel rad/s)",
        "voltage_per_angular_speed",
        "V*s/rad",
        help="G/Kv, volts per rad/s of the wheel (VL2).",
        equation="(VL2)",
    ),
    Output(
        "kA",
        "kA (per wheel rad/s²)",
        "voltage_per_angular_acceleration",
        "V*s**2/rad",
        help="R·J/k, volts per rad/s² of the wheel (VL2).",
        equation="(VL2)",
    ),
    Output(
        "kP",
        "kP (per wheel rad/s)",
        "voltage_per_angular_speed",
        "V*s/rad",
        help="The loop's proportional gain: LQR (VL9) or entered.",
        equation="(VL9)",
    ),
    Output(
        "loop_ramp_acceleration",
        "Ramp acceleration (velocity loop)",
        "angular_acceleration",
        "rpm/s",
        help="The setpoint's acceleration on a ramp: entered, or the fraction of (V_b − kS)/kA (VL4a).",
        equation="(VL4a)",
    ),
    Output(
        "control_updates",
        "Control updates",
        help="Periods simulated (VL4).",
        equation="(VL4)",
    ),
)

GRID_OUTPUTS = {o.name: o for o in limit_grid.outputs()}  # the pick's limits and the cell count
OUTPUTS = (
    Output(
        "ball_speed",
        "Ball speed",
        "speed",
        "m/s",
        help="Release speed V at the target wheel speed.",
        equation="(2)",
    ),
    Output(
        "ball_spin",
        "Ball spin",
        "angular_speed",
        "rpm",
        help="c·V/r_b (D2): V/r_b rolling on the hood (2), 0 for two wheels, negative for backspin.",
        equation="(2), (D2)",
    ),
    Output(
        "secondary_speed",
        "Secondary wheel speed",
        "angular_speed",
        "rpm",
        help="G₂₁·ω_t: the secondary wheels at the primary's target speed (layouts with one).",
        equation="(D1)",
    ),
    Output("ball_energy", "Ball energy", "energy", "J", help="Translation plus spin.", equation="(3)"),
    Output(
        "energy_ratio",
        "Ball / wheel energy after",
        help="E_b/E_w,final (seed: .165 for one wheel).",
        equation="(6)",
    ),
    Output(
        "wheel_speed_after",
        "Wheel speed after shot",
        "angular_speed",
        "rpm",
        help="ω₁ after the first shot: ω₀/√(1+β) (energy, 5) or ω₀/(1+β) (momentum).",
        equation="(5)",
    ),
    Output(
        "contact_time",
        "Slip time of the shot",
        "time",
        "ms",
        help="From contact until the ball rolls, the slip phase integrated (motor_during_shot only).",
        equation="(FW3)",
    ),
    Output(
        "wheel_inertia_total",
        "Wheel inertia (all)",
        "inertia",
        "lb*in**2",
        help="n·I of one wheel (I = m_w·(k·r_w)² in radius-of-gyration mode (4)) plus the rotors' N·J_r·G².",
        equation="(4)",
    ),
    Output(
        "mass_ratio_coefficient",
        "β per ball/wheel mass ratio",
        help="(1+k_b)·s²/k²: E_b/E_w,final per ball-to-wheel mass ratio (radius-of-gyration mode); "
        "the seed's .4954.",
        equation="(6)",
    ),
    Output("range", "Range", "length", "m", help="Vacuum range from the release height.", equation="(1)"),
    Output(
        "range_error",
        "Range error (heavy ball)",
        "dimensionless",
        "%",
        help="Exact, for m₀·(1+e_m), with the effects and losses chosen.",
        equation="(7), (8)",
    ),
    Output(
        "range_error_linear",
        "Range error, spreadsheet estimate",
        "dimensionless",
        "%",
        help="The seed's −e_m/(m_w/(c·m₀) + 1), c exact: lossless energy model at h = 0, whatever model is chosen.",
        equation="(9)",
    ),
    Output(
        "range_spread",
        "Range spread light to heavy",
        "length",
        "m",
        help="R(m₀·(1−e_m)) − R(m₀·(1+e_m)).",
        equation="(1), (7)",
    ),
    *[
        Output(
            f"range_error_{n}",
            f"Range error, {n} wheel{'s' if n > 1 else ''}",
            "dimensionless",
            "%",
            help="Exact (8) with n wheels, the same wheel, motor and target speed.",
            equation="(8)",
        )
        for n in TABLE_WHEELS
    ],
    *[
        Output(
            f"range_error_linear_{n}",
            f"Spreadsheet est., {n} wheel{'s' if n > 1 else ''}",
            "dimensionless",
            "%",
            help="The seed's table (9): lossless energy model, h = 0, whatever model is chosen.",
            equation="(9)",
        )
        for n in TABLE_WHEELS
    ],
    Output(
        "free_speed",
        "Wheel free speed",
        "angular_speed",
        "rpm",
        help="ω̃f/G (with battery_sag: where the sagged torque is zero, (F2)).",
        equation="(FW1), (F2)",
    ),
    Output("time_constant", "Spin-up time constant", "time", "s", help="T = I·ω̃f/(G²·τ̃s).", equation="(FW1)"),
    Output(
        "spin_up_time",
        "Spin-up time",
        "time",
        "s",
        equation="(FW2), (F1)",
        help="From rest to the target at full power: T·ln(ω_f/(ω_f − ω_t)); with a current limit, integrated (F1).",
    ),
    Output(
        "recovery_time",
        "Recovery time",
        "time",
        "s",
        equation="(FW2), (F1)",
        help="After one shot back to the target: T·ln((ω_f − ω₁)/(ω_f − ω_t)); under a current limit integrated (F1).",
    ),
    Output(
        "slowest_ball_speed",
        "Slowest ball in burst",
        "speed",
        "m/s",
        help="The slowest release over the burst (the wheel not back to speed between shots).",
        equation="(FW4)",
    ),
    Output(
        "peak_stator_current",
        "Peak stator current",
        "current",
        "A",
        help="Per motor, over the spin-up (at rest); stator_limit, supply_limit or battery_sag only.",
        equation="(FW5)",
    ),
    Output(
        "peak_supply_current",
        "Peak supply current",
        "current",
        "A",
        help="Per motor, stator current × duty, largest over the spin-up; with a limit or sag only.",
        equation="(FW5)",
    ),
    Output(
        "min_bus_voltage",
        "Min bus voltage",
        "voltage",
        "V",
        help="Battery voltage minus the sag at the peak supply current (battery_sag).",
        equation="(FW5)",
    ),
    *LOOP_OUTPUTS,
    GRID_OUTPUTS["pick_stator_limit"],
    GRID_OUTPUTS["pick_supply_limit"],
    Output(
        "best_ratio",
        "Pick: best ratio",
        help="The picked cell's ratio (motor turns per wheel turn) that spins up quickest (FW7).",
        equation="(FW7)",
    ),
    Output(
        "grid_spin_up_time",
        "Pick: spin-up time",
        "time",
        "s",
        help="From rest to the target at full power with the picked limits and ratio (FW6).",
        equation="(FW6)",
    ),
    GRID_OUTPUTS["grid_cells"],
    *STATS_OUTPUTS,
)

GRID_TABLE = limit_grid.table(  # the flywheel's `mode` is the inertia's: shown by `control`
    "Current-limit grid: the ratio quickest to spin up per stator × supply limit", "Spin-up", (), GRID
)


def simulate(v, rtol: float) -> SimRun:
    try:
        return _simulate(v, rtol)
    except TooFast as exc:  # was "(result): step size underflow", naming no field
        name = "wheel_inertia" if v["mode"] == "moment_of_inertia" else "wheel_mass"
        raise InputError(
            name,
            f"the wheels' inertia ({inertia_each(v) * v['wheel_count'] + rotor_reflected(v):.3g} kg·m², "
            f"the motors' rotors included) is too small to simulate the spin-up with current limits "
            f"({exc}); enter the wheel's real {'moment of inertia' if name == 'wheel_inertia' else 'mass'} "
            f"(or the rotor_inertia)",
        ) from None


def _simulate(v, rtol: float) -> SimRun:
    sc, warnings = scene_from(v, rtol)
    target = v["target_speed"]
    if target >= sc.free_speed:
        raise InputError(
            "target_speed",
            f"the wheels cannot reach it: their free speed is "
            f"{sc.free_speed / RPM:.4g} rpm with this motor and ratio",
        )
    if sc.drive is not None:
        check_limits(sc, target)
    m0, e_m = v["ball_mass"], v["ball_mass_tolerance"]
    shots = Shots(target, rtol)
    first = shots(sc, target, m0)
    E_w_after = 0.5 * sc.I * first.omega_after**2
    R = projectile_range(first.V, v["launch_angle"], v["release_height"])
    values = {
        "ball_speed": first.V,
        "ball_spin": first.spin,
        "ball_energy": first.energy,
        "energy_ratio": first.energy / E_w_after if E_w_after > 0 else 0.0,
        "wheel_speed_after": first.omega_after,
        "wheel_inertia_total": sc.I,
        "range": R,
        "range_error": range_change(sc, v, shots, m0 * e_m),  # (8), with h and the chosen model
        "range_error_linear": range_error_linear(sc, m0, e_m),
        "range_spread": R * (range_change(sc, v, shots, -m0 * e_m) - range_change(sc, v, shots, m0 * e_m)),
    }
    if v["shooter"] in SECONDARY:
        values["secondary_speed"] = secondary_speed_ratio(v) * target  # (D1)
    if sc.motor_on:
        values["contact_time"] = first.contact_time
        # the grip is constant, so the ball accelerates uniformly from rest: it slips over V·t_c/2
        slip_length = first.V / math.sqrt(1 - sc.f) * first.contact_time / 2
        if slip_length > SLIP_LENGTH_WARN:
            warnings.append(
                f"The ball slips {slip_length:.3g} m before it rolls, longer than a shooter's "
                f"contact path: it would leave while still slipping. Raise the grip force."
            )
    if sc.model == "momentum":
        warnings.append(
            "The 'seed linear' range errors are the seed's energy model; the momentum model's "
            "exact range errors are about twice them (R ∝ 1/(1 + β)² instead of 1/(1 + β))."
        )
    if v["mode"] == "radius_of_gyration" and v["shooter"] not in SECONDARY:
        values["mass_ratio_coefficient"] = (
            (1 + sc.sigma * sc.k_b) * sc.s**2 / v["gyration_fraction"] ** 2
        )  # (6)
    for n in TABLE_WHEELS:  # the seed's table; the free speed ω̃f/G does not depend on n
        sc_n = (
            sc
            if n == v["wheel_count"]
            else with_inertia(sc, n * inertia_each(v) + secondary_reflected(v) + rotor_reflected(v))
        )
        values[f"range_error_{n}"] = range_change(sc_n, v, shots, m0 * e_m)
        values[f"range_error_linear_{n}"] = range_error_linear(sc_n, m0, e_m)
    trace, slowest, t_spin, first_shot = burst(sc, v, shots)
    values.update(
        {
            "free_speed": sc.free_speed,
            "time_constant": sc.T,
            "spin_up_time": t_spin,
            "recovery_time": recovery(sc, first.omega_after, target, first.drop),
            "slowest_ball_speed": slowest,
        }
    )
    if slowest == 0.0:
        warnings.append(
            "The shots stop the wheel and the motor cannot spin it up again between them: a later "
            "ball meets a wheel at rest and is not thrown (slowest ball 0 m/s). Use a heavier wheel, "
            "a stronger drive (motor, ratio) or a longer shot interval."
        )
    elif slowest < first.V * (1 - 1e-9):
        warnings.append(
            f"The wheel does not recover between shots: the slowest ball leaves at "
            f"{slowest:.3g} m/s instead of {first.V:.3g} m/s."
        )
    series = {"wheel speed": trace, "burst": (trace[0][first_shot:], trace[1][first_shot:])}
    key = {"ball_speed": first.V, "wheel_speed_after": first.omega_after, "slowest_ball_speed": slowest}
    nfev = shots.nfev
    if sc.electric is not None:
        values.update(electrical_extremes(sc, target, v))
    if sc.drive is not None:
        key.update(spin_up_time=t_spin, recovery_time=values["recovery_time"])
        nfev += sc.drive.nfev
    if v["control"] == "limit_grid":
        grid = limit_grid.run_cells(v, rtol, grid_cells, GRID_PICK, GRID_NONE)
        values.update(grid.values)
        if "grid_spin_up_time" in grid.values:
            key["grid_spin_up_time"] = grid.values["grid_spin_up_time"]
        # the grid's chart is its heat map alone (the card shows it by itself when no line chart
        # has data): the spin-up at the entered ratio is not what this mode asks
        return SimRun(
            values, key, nfev, warnings + grid.warnings, tables=grid.tables, heat_maps=grid.heat_maps
        )
    if v["control"] == "velocity_loop":
        lr = velocity_loop_run(sc, v, rtol, values, warnings)
        series["loop speed"] = (lr.times, lr.speeds)
        series["loop target"] = loop_target(v, values, target, lr.times[-1])
        series["loop voltage"] = (lr.volt_t, lr.volts)
        nfev += lr.nfev
        if "loop_spin_up_time" in values:
            key["loop_spin_up_time"] = values["loop_spin_up_time"]
    return SimRun(values, key, nfev, warnings, series)


def loop_target(v, values: dict, target: float, t_end: float) -> tuple[list, list]:
    """The setpoint over the run, for the chart: the step's level, or the ramp and then the level."""
    a = values.get("loop_ramp_acceleration")
    if a is None:
        return [0.0, t_end], [target, target]
    t_top = min(target / a, t_end)
    return [0.0, t_top, t_end], [0.0, a * t_top, a * t_top]


def loop_wheel(sc: Scene, v):
    """The flywheel's drive for core.sim.velocity_loop (VL1): k = A/(i_s − i_f) at the wheel per amp
    of each motor (A = G·τ̃s, the stall torque before sag), the circuit (M1) and the limits."""
    from ..sim import profiled, velocity_loop  # the solve's: the card's description needs neither

    on = v["effects"]
    motor, _ = lookup(v["motor"], v["source"])
    system, _ = system_from(v)
    V = v["voltage"]
    i_s = motor.stall_current * V / motor.v_spec  # (4), per motor
    i_f = motor.free_current * V / motor.v_spec  # (3), per motor
    circuit = motor_limits.circuit_of(motor, V, motor_limits.bus_resistance_of(v, on))
    _, asm = motor_limits.limits(EFFECTS, on, v, circuit)
    bound = asm.slots["duty"]
    return velocity_loop.Wheel(
        J=sc.I,
        k=v["ratio"] * system.stall_torque / (i_s - i_f),
        G=v["ratio"],
        Kv=circuit.Kv,
        R=circuit.R,
        i_f=i_f,
        battery_voltage=V,
        bus_resistance=circuit.bus_resistance,
        drive=profiled.driver(circuit, bound),
        limited=bound is not None,
    )


def ramp_acceleration(v, ff: dict) -> float | None:
    """The ramped setpoint's acceleration (rad/s² at the wheel), None for a step (VL4a): entered, or
    the fraction of the stall acceleration (V_b − kS)/kA = k·(i_s − i_f)/J of (VL1)."""
    if v["setpoint_profile"] != "ramp":
        return None
    if v["ramp_limit"] == "entered":
        return v["ramp_acceleration"]
    a = v["ramp_fraction"] * (v["voltage"] - ff["kS"]) / ff["kA"]
    if not (math.isfinite(a) and a > 0):
        raise InputError("ramp_fraction", "the motors cannot accelerate the wheel from rest: no ramp to take")
    return a


def velocity_loop_run(sc: Scene, v, rtol: float, values: dict, warnings: list):
    """The velocity-loop mode's outputs (core.sim.velocity_loop), added to `values`."""
    from ..sim import velocity_loop

    w = loop_wheel(sc, v)
    ff = velocity_loop.feedforward_gains(w)
    dt, delay = v["control_period"], v["sensor_delay"]
    if v["feedback"] == "lqr":
        kP = velocity_loop.lqr_kp(ff["kV"], ff["kA"], v["q_velocity"], v["r_volts"], dt, delay)
        if not (math.isfinite(kP) and kP >= 0):
            raise InputError(
                "q_velocity", "the LQR gain is not a finite positive number for these tolerances"
            )
    else:
        kP = v["feedback_kp"]
    shot_time = v["shot_time"]
    updates = (shot_time + max(velocity_loop.WINDOW_AFTER_SHOT, shot_time)) / dt
    if updates > velocity_loop.MAX_UPDATES:
        raise InputError(
            "control_period",
            f"the run needs {updates:.3g} control updates (more than {velocity_loop.MAX_UPDATES}): "
            "lengthen the control period or shoot earlier",
        )
    target = v["target_speed"]
    acceleration = ramp_acceleration(v, ff)
    loop = velocity_loop.Loop(
        ff["kS"], ff["kV"], kP, dt, delay, v["speed_tolerance"], kA=ff["kA"], acceleration=acceleration
    )
    m0 = v["ball_mass"]

    def after_shot(omega: float) -> float:
        return shot(sc, omega, m0, target, rtol).omega_after if omega > 0 else omega

    lr = velocity_loop.run_loop(w, loop, target, shot_time, after_shot, rtol)
    values.update(
        {
            **ff,
            "kP": kP,
            "loop_overshoot": lr.overshoot,
            "loop_speed_at_shot": lr.speed_at_shot,
            "loop_speed_dip": lr.dip,
            "loop_final_error": lr.final_error,
            "loop_peak_stator_current": lr.peak_stator,
            "loop_peak_supply_current": lr.peak_supply,
            "loop_min_bus_voltage": v["voltage"] - w.bus_resistance * lr.peak_supply,
            "control_updates": lr.updates,
        }
    )
    if acceleration is not None:
        values["loop_ramp_acceleration"] = acceleration
        if target / acceleration > shot_time:
            warnings.append(
                f"The ramp reaches the target at {target / acceleration:.3g} s, after the shot at "
                f"{shot_time:.3g} s: raise the ramp's acceleration or shoot later."
            )
    if lr.spin_up_time is not None:
        values["loop_spin_up_time"] = lr.spin_up_time
    else:
        warnings.append(
            f"The velocity loop has not spun the wheel up to within the speed tolerance by the shot "
            f"({lr.speed_at_shot / RPM:.4g} rpm at {shot_time:.3g} s): no spin-up time. Shoot later, "
            f"raise kP or the tolerance."
        )
    if lr.recovery_time is not None:
        values["loop_recovery_time"] = lr.recovery_time
    else:
        warnings.append(
            "The velocity loop has not brought the wheel back within the speed tolerance by the end of "
            "the window after the shot: no recovery time (a proportional loop leaves a steady error "
            "when the limits or the sag hold the voltage below the feedforward's; widen the tolerance)."
        )
    return lr


def compute(values, estimate: str = "now") -> Result:
    run = run_with_stats(simulate, values, estimate=estimate)
    return Result(
        run.values,
        run.warnings,
        run.series,
        run.tables,
        heat_maps=run.heat_maps,
    )


# the pick's columns -> the flywheel's outputs (FW8), and the error when no cell gets there
GRID_PICK = {"ratio": "best_ratio", "time": "grid_spin_up_time"}
GRID_NONE = "no pair of limits in the grid spins the wheels up to the target"


gains_of = gains_code.velocity_loop_gains  # the velocity loop's gains for the exports (GC4)-(GC8)
DOCUMENTS = gains_code.flywheel_documents(gains_of)


CALCULATOR = Calculator(
    id="flywheel",
    title="Flywheel",
    summary="Flywheel shooter: energy to the ball, range error from ball-mass tolerance, spin-up and recovery.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="seed 000",
    simulate=simulate,
    plots=(
        Plot(
            "Wheel speed over the burst",
            ("burst",),
            "time",
            "time",
            "s",
            "wheel speed",
            "angular_speed",
            "rpm",
        ),
        Plot(
            "Spin-up and burst", ("wheel speed",), "time", "time", "s", "wheel speed", "angular_speed", "rpm"
        ),
        Plot(
            "Wheel speed (velocity loop)",
            ("loop speed", "loop target"),
            "time",
            "time",
            "s",
            "wheel speed",
            "angular_speed",
            "rpm",
        ),
        Plot("Voltage (velocity loop)", ("loop voltage",), "time", "time", "s", "voltage", "voltage", "V"),
        limit_grid.heat_map_plot("Spin-up time per current-limit pair (grid)", "spin-up time"),
    ),
    documents=DOCUMENTS,  # velocity-loop mode: the gains as code
    tables=(GRID_TABLE,),
)
