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
from typing import Any

from .. import gains_code
from ..constants import G0 as G_ACC
from ..constants import RPM
from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field
from ..motors import lookup, motor_fields, system_from
from ..sim import limit_grid, motion, motor_limits, velocity_loop
from ..sim.effects import Effect, Effects, nothing
from ..sim.integrate import Event, integrate, integrate_stiff
from ..sim.scene import STATS_OUTPUTS, SimRun, accuracy_field, run_with_stats

TABLE_WHEELS = range(1, 7)
# Slip phase: when the wheel's time constant is this many times shorter than the slip (b·τ_end), an
# explicit integrator needs ~b·τ_end/3 steps for stability alone; the closed form is used instead.
STIFF = 200.0
SLIP_LENGTH_WARN = 0.5  # m: longer than the contact path of any hood or wheel pair
TRANSFERS = ("energy", "momentum")
# Once effects; an entry or preset naming one among the effects means that transfer (effects.retire)
RETIRED = tuple((t, "transfer", t) for t in TRANSFERS)
TRANSFER_LABELS = (
    "Energy (seed: energy conservation, translation + spin)",
    "Momentum (angular impulse with slip, Team 449)",
)
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
SHOOTERS = ("hood", "two_wheel", "dual", "compound", "hood_secondary")
SHOOTER_LABELS = (
    "Single wheel with hood (ball at half surface speed)",
    "Two wheels (ball at surface speed)",
    "Dual: bottom and top wheels, each its own diameter and ratio",
    "Compound: hood section, then between the wheel and a secondary wheel",
    "Hood with a secondary wheel geared to it (inertia only)",
)
SECONDARY = ("dual", "compound", "hood_secondary")  # layouts with a secondary wheel set
WITH_SPIN = ("hood", "dual", "compound", "hood_secondary")  # the ball leaves spinning
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
    """Shots of one simulate call, each computed once (the table and the burst reuse them)."""

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
    positive at omega_to (checked in simulate), so a phase ending at ω_b is over before
    I·(ω_b − ω)/τ_w(ω_b): the span integrated."""
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
    from ..sim import profiled

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


# --- the current-limit grid (control = limit_grid) ----------------------------------------------

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


# the pick's columns -> the flywheel's outputs (FW8), and the error when no cell gets there
GRID_PICK = {"ratio": "best_ratio", "time": "grid_spin_up_time"}
GRID_NONE = "no pair of limits in the grid spins the wheels up to the target"


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
