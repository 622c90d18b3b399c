"""Drivetrain sprint: how long a robot takes to cross a distance from rest at full voltage in a straight
line, and the ratio that crosses it first (issue 29). A scene with effects (core.sim.effects), on the
motor model every tab uses (core.sim.motion (M1)-(M3), the seed's eqs. 3, 7, 9).

N drive motors (all of them: a tank's both sides, a swerve's drive motors) through the reduction G
(motor turns per wheel turn) on wheels of radius r push the robot of mass m; per motor
    n = G/r                                   motor radians per metre of travel                    (S1)
    E = n·v/Kv,  I = (u·V_bus − E)/R          back-EMF and stator current; u, V_bus from the current
                                              limits and the battery sag (core.sim.motor_limits (E1)-(E3))
    F_m = η·N·Kt·n·(I − i_f)                  the motors' force at the wheels, Kt = τs/(Is − If),
                                              i_f = If·V_b/V_spec (the motors' own loss)           (S2)
    F_t = μ·m·g                               the most the wheels transmit (every wheel driven)    (S3)
                                              (weight_transfer: less, see `traction` (S3'))
    m·v̇ = min(F_m, F_t) − C_rr·m·g − ½·ρ·CdA·v²   (rolling resistance, air drag: effects)          (S4)
While F_m > F_t the wheels are at the edge of slipping (traction-limited): the robot accelerates at
(μ − C_rr)·g and the motors, spinning up until their force equals the traction, draw
    I_slip = F_t/(η·N·Kt·n) + i_f             per motor (the drivetrain tab's eq. 39)              (S5)
at the back-EMF E_slip where I(E_slip) = I_slip; that is also where the robot's own E reaches when
the traction phase ends, so the electrical state moves through E_slip → E(goal) and the supply
current and bus voltage are extreme at rest, at either end or at a branch point of the duty rule
(motor_limits.branch_emfs), as in core.sim.motion.extremes. (The wheels' and motors' rotating inertia
is not counted: it adds a few % to m at high ratios; add it to the mass if it matters.)

Closed form with no current limit and no drag (the battery sag keeps the motor force affine in v,
R_eff = R + R_bus):
    F_m(v) = η·N·Kt·n·((V_b − n·v/Kv)/R_eff − i_f)
    v_sw = (V_b − R_eff·(i_f + F_t/(η·N·Kt·n)))·Kv/n     traction lets go (0 if it never binds)     (S6)
    phase 1: a₁ = (μ − C_rr)·g;  t_sw = v_sw/a₁,  x_sw = v_sw²/(2·a₁)
    phase 2: m·v̇ = (m/τ)·(v_f − v),  τ = m·R_eff·Kv/(η·N·Kt·n²),
             v_f = (V_b − R_eff·(i_f + C_rr·m·g/(η·N·Kt·n)))·Kv/n
             x = x_sw + v_f·s − (v_f − v_sw)·τ·(1 − e^{−s/τ}),  s = t − t_sw                       (S7)
    x = d ⇔ X − a·(1 − e^{−X}) = D,  X = s/τ, a = (v_f − v_sw)/v_f, D = (d − x_sw)/(v_f·τ)
          ⇔ X = D + a + W₀(−a·e^{−(D+a)})                                                           (S8)
(derived by hand: X = D + a + w turns (S8) into w·e^w = −a·e^{−(D+a)}; W₀ since X ≥ 0), polished by
Newton on f(X) = (1 − a)·X + a·g(X) − D with g(X) = X + e^{−X} − 1 summed as its series for small X
(core.sim.motion._g), f' = 1 − a·e^{−X} > 0: for small D it starts from (1 − a)·X + a·X²/2 = D.
Otherwise (S4) is integrated (DP54, restarted where the traction lets go: the acceleration has a kink
there), with an event at the goal.
Outputs for control: kV = n/Kv, kA = m·R/(η·N·Kt·n), kS = R·i_f + C_rr·m·g·R/(η·N·Kt·n), per volt of
the drive (WPILib's SimpleMotorFeedforward for the whole robot, linear). Turning in place the wheels'
total force F acts at r_b = track/2: I·α = F·r_b, and V = F/(η·N·Kt·n/R) for the acceleration, so
kA_angular = V/α = I·R/(r_b·η·N·Kt·n) = kA·I/(m·r_b), volts per rad/s² (PathPlanner's estimate
I = m·r_b·kA_angular/kA inverts it)                                                            (S9)
Per motor, the supply current u·I, the battery's N·u·I and the bus V_b − R_bus·u·I, extreme at rest,
at the ends or at a branch point of the duty rule (core.sim.motor_limits (E4)-(E7))              (S11)
Energy drawn from the battery: ∫ V_b·N·u·I dt (I = I_slip while slipping); in closed form the
traction phase's u_slip·I_slip·t_sw plus (V_b·s − n·(d − x_sw)/Kv)/R_eff                       (S12)
Exports (PathPlanner settings.json, Choreo .chor; core.robot_config): the yaw inertia estimated as a
uniform plate over the bumper outline, I = m·(L² + W²)/12 (PathPlanner's "rough estimate"), or entered;
the attainable speed as the top speed; the stator limit (the stall current when off) per motor, and
one motor's torque there, Kt·(I_lim − i_f)·η                                                       (S13)
Voltage ramp (the controllers' open-loop ramp, T_r from 0 to full output): the duty is at most t/T_r,
    u = min(t/T_r, 1, u_st, u_sup)                                                                (S14)
so the electrical state depends on time as well as speed. The robot waits at rest while the motors'
force at v = 0 is below the loss and rolling resistance (drawing the stalled current); while slipping
the motors draw I_slip at the duty min(t/T_r, u_slip); the wheels may start slipping part-way up the
ramp. Nothing is closed-form then: (S4) is integrated in phases (rest, gripping, slipping), each run
on the ramp's own branch u = t/T_r while it binds, stopped where it meets the limits' bound; the
peak currents are the runs' maxima (each local maximum refined on the dense output).
Optimise: G* minimising the time to the distance: the time on 200 ratios (one numpy batch, core.sim.motion.batch_arrival) log-spaced over two decades
about the ratio at which the motors just slip the wheels at rest (G_t: F_m(0) = F_t), then bounded
Brent on the accurate solve, and the same for 1 m, 3 m, 5 m and the field's 16.54 m (the table).  (S10)
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..constants import G0 as G
from ..constants import INCH
from ..declarations import Calculator, Column, Document, Output, Plot, Result, Table
from ..errors import InputError
from ..fields import Field
from ..motors import lookup
from ..sim import motion
from ..sim.effects import Effect, Effects, Part, Slot, nothing
from ..sim.integrate import Event, integrate, integrate_stiff
from ..sim.motor_limits import braking_warning, branch_emfs, bus_resistance_of, electrical, electrical_effects
from ..sim.scene import STATS_OUTPUTS, SimRun, accuracy_field, compute_with_stats

if TYPE_CHECKING:
    from ..robot_config import RobotConfig

AIR_DENSITY = 1.2  # kg/m³, sea level at 20 °C
FIELD_LENGTH = 16.54  # m, the FRC field (2024-2026), alliance wall to alliance wall
TABLE_DISTANCES = (1.0, 3.0, 5.0, FIELD_LENGTH)
CURVE_RATIOS = 200  # ratios on the optimise curve (one numpy batch)
SAMPLES = 120
DP54_STEPS = 2_000  # beyond this the sprint is stiff: LSODA takes over
STIFF = 60.0  # sprint time over the speed's time constant above which LSODA is used (as core.sim.motion)

SLOTS = (
    Slot("resist", "sum", "force against the motion at speed v (N)"),
    Slot("duty", "min", "upper bound on the motor duty from a current limit, given the back-EMF E"),
)


def _rolling(values, ctx):
    F = values["rolling_coefficient"] * ctx.mass * G
    return Part(terms={"resist": lambda v: F})


def _drag(values, ctx):
    k = 0.5 * AIR_DENSITY * values["drag_area"]
    return Part(terms={"resist": lambda v: k * v * v})


# A robot always runs with current limits and a battery that sags, and the fastest ratio depends
# on them (with neither, four Kraken X60s would "win" 5 m at G = 2.2 drawing 220 A each): on by default.
EFFECTS = Effects(
    *[
        dataclasses.replace(e, default_on=True)
        for e in electrical_effects(limit_default=80.0, supply_default=60.0)
    ],
    Effect(
        "rolling_resistance",
        "a constant force C_rr·m·g against the motion (tread, bearings, belts)",
        _rolling,
        fields=(
            Field(
                "rolling_coefficient",
                "Rolling resistance C_rr",
                default=0.02,
                min=0,
                max=1,
                help="Rolling resistance over the weight (C_rr); 0.01-0.03 for FRC wheels on carpet.",
            ),
        ),
    ),
    Effect(
        "weight_transfer",
        "accelerating unloads the front wheels, which slip first (swerve, mecanum: four equal modules)",
        nothing,
        fields=(
            Field(
                "cg_height",
                "CG height",
                "length",
                "in",
                default=8,
                min=0,
                max=200,
                help="Height of the centre of mass above the floor (taken midway between the axles).",
            ),
        ),
    ),
    Effect(
        "voltage_ramp",
        "the controllers' open-loop ramp: the duty may rise from 0 to full over the ramp time (S14)",
        nothing,
        fields=(
            Field(
                "ramp_time",
                "Ramp time",
                "time",
                "s",
                default=0.25,
                min=0,
                max=10,
                help="Seconds from 0 to full output (REVLib openLoopRampRate, Phoenix 6 "
                "DutyCycleOpenLoopRampPeriod); it softens the start's current and wheel slip.",
            ),
        ),
    ),
    Effect(
        "air_drag",
        "½·ρ·CdA·v² against the motion (ρ = 1.2 kg/m³)",
        _drag,
        fields=(
            Field(
                "drag_area",
                "Drag area CdA",
                "area",
                "m**2",
                default=0.5,
                min=0,
                max=100,
                help="Drag coefficient × frontal area; a bumpered FRC robot ≈ 0.5 m².",
            ),
        ),
    ),
)

MODES = ("sprint", "optimise")
KINDS = ("swerve", "tank", "mecanum")
# COTS swerve modules: drive reduction and nominal wheel diameter (in), from the vendors' own code:
# SDS swerve-lib SdsModuleConfigurations.java (55f3f1a): MK4i L1 (50/14)(19/25)(45/15), L2 (50/14)(17/27)
# (45/15), L3 (50/14)(16/28)(45/15), 4 in wheels; REV MAXSwerve-Java-Template Constants.java (112ee68):
# (45·22)/(pinion·15) for the 12, 13 and 14 tooth pinions, 3 in wheels.
MODULES = {
    "sds_mk4i_l1": ("Swerve: SDS MK4i L1", (50 / 14) * (19 / 25) * (45 / 15), 4.0),
    "sds_mk4i_l2": ("Swerve: SDS MK4i L2", (50 / 14) * (17 / 27) * (45 / 15), 4.0),
    "sds_mk4i_l3": ("Swerve: SDS MK4i L3", (50 / 14) * (16 / 28) * (45 / 15), 4.0),
    "rev_maxswerve_12t": ("Swerve: REV MAXSwerve, 12T pinion", 45 * 22 / (12 * 15), 3.0),
    "rev_maxswerve_13t": ("Swerve: REV MAXSwerve, 13T pinion", 45 * 22 / (13 * 15), 3.0),
    "rev_maxswerve_14t": ("Swerve: REV MAXSwerve, 14T pinion", 45 * 22 / (14 * 15), 3.0),
}
DRIVES = KINDS + tuple(MODULES)
DRIVE_LABELS = ("Swerve (enter ratio and wheel)", "Tank (differential)", "Mecanum") + tuple(
    f"{label} ({G_:.4g}:1, {d:g} in wheels)" for label, G_, d in MODULES.values()
)
MODE_LABELS = ("Sprint at the given ratio", "Optimise: the ratio that arrives first")

FIELDS = (
    Field(
        "mode",
        "Solve",
        choices=MODES,
        choice_labels=MODE_LABELS,
        default="sprint",
        help="One sprint at the ratio you give, or the ratio that crosses the distance first "
        "(time against ratio plotted, and a table for 1 m, 3 m, 5 m and the field).",
    ),
    *motion.battery_motor_fields("Kraken X60", 4),
    Field(
        "drive",
        "Drive",
        choices=DRIVES,
        choice_labels=DRIVE_LABELS,
        default="swerve",
        help="Swerve, tank or mecanum with your ratio and wheel, or a COTS swerve module (its ratio and "
        "wheel, from the vendor's code). The sprint is the same straight line; the exports differ.",
    ),
    Field(
        "ratio",
        "Reduction G",
        default=6.75,
        min=0.05,
        max=1000,
        modes=("sprint",),
        when=(("drive", KINDS),),
        help="Motor turns per wheel turn (SDS MK4i L2: 6.75).",
    ),
    Field(
        "wheel_diameter",
        "Wheel diameter",
        "length",
        "in",
        default=4,
        min=0.5,
        max=40,
        when=(("drive", KINDS),),
        help="Nominal tread diameter (worn tread is smaller).",
    ),
    Field(
        "robot_mass",
        "Robot mass",
        "mass",
        "lb",
        default=135,
        min=1,
        max=2000,
        help="Everything that moves: robot, battery and bumpers.",
    ),
    Field(
        "wheel_cof",
        "Wheel friction μ",
        default=1.1,
        min=0.05,
        max=3,
        help="Wheel-to-floor coefficient of friction (new tread on carpet ≈ 1.1-1.3).",
    ),
    Field(
        "distance",
        "Distance",
        "length",
        "m",
        default=5,
        min=0,
        min_exclusive=True,
        max=1000,
        help="How far to sprint from rest (the FRC field is 16.54 m long).",
    ),
    Field(
        "trackwidth",
        "Track width",
        "length",
        "in",
        default=22.75,
        min=1,
        max=200,
        help="Left to right distance between the wheels' (modules') centres.",
    ),
    Field(
        "wheelbase",
        "Wheelbase",
        "length",
        "in",
        default=22.75,
        min=1,
        max=200,
        help="Front to back distance between the wheels' (modules') centres.",
    ),
    Field(
        "bumper_width",
        "Width with bumpers",
        "length",
        "in",
        default=34,
        min=1,
        max=300,
        help="Overall left to right, bumpers on (exports; the estimated inertia).",
    ),
    Field(
        "bumper_length",
        "Length with bumpers",
        "length",
        "in",
        default=34,
        min=1,
        max=300,
        help="Overall front to back, bumpers on (exports; the estimated inertia).",
    ),
    Field(
        "inertia_model",
        "Yaw inertia",
        choices=("estimated", "entered"),
        choice_labels=("Estimated: m·(L² + W²)/12 over the bumpers", "Entered (CAD, sysId)"),
        default="estimated",
        help="The robot's moment of inertia about its vertical axis, for the exports (S13).",
    ),
    Field(
        "moment_of_inertia",
        "Moment of inertia",
        "inertia",
        "kg*m**2",
        default=6,
        min=0,
        min_exclusive=True,
        max=1e4,
        when=(("inertia_model", ("entered",)),),
        help="About the robot's vertical axis through its centre (CAD mass properties or sysId).",
    ),
    EFFECTS.field(
        "stator_limit, supply_limit (per motor current limits); battery_sag (bus = battery − R × total "
        "supply current); rolling_resistance (C_rr·m·g); weight_transfer (front wheels slip first); "
        "air_drag (½ρ·CdA·v²); voltage_ramp (the duty rises from 0 to full over the ramp time)."
    ),
    *EFFECTS.fields(),
    accuracy_field(),
)
FIELDS = tuple(
    dataclasses.replace(
        f, default=0.9, help="Gearbox and wheel efficiency η, 0 to 1 (a swerve module ≈ 0.9)."
    )
    if f.name == "efficiency"
    else dataclasses.replace(
        f, label="Drive motors", help="All drive motors (a swerve's four, a tank's both sides)."
    )
    if f.name == "motor_count"
    else f
    for f in FIELDS
)

OUTPUTS = (
    Output(
        "best_ratio",
        "Fastest ratio",
        help="Optimise: the reduction G that arrives first (S10).",
        equation="(S10)",
    ),
    Output(
        "time_to_distance",
        "Time to distance",
        "time",
        "s",
        help="From rest (S4), (S7)-(S8).",
        equation="(S8)",
    ),
    Output(
        "speed_at_distance",
        "Speed at distance",
        "speed",
        "ft/s",
        help="When it crosses the distance.",
        equation="(S4)",
    ),
    Output(
        "free_speed",
        "Free speed",
        "speed",
        "ft/s",
        help="No load at the battery voltage: the motors' rated free speed through G and the wheel.",
        equation="(S2)",
    ),
    Output(
        "top_speed",
        "Attainable speed",
        "speed",
        "ft/s",
        help="Where the motors' force equals rolling resistance and drag (the free speed with neither).",
        equation="(S4)",
    ),
    Output(
        "traction_distance",
        "Distance traction-limited",
        "length",
        "m",
        help="Travelled at the edge of wheel slip (F_m > μ·m·g): from the start, or part-way up a ramp.",
        equation="(S6)",
    ),
    Output(
        "traction_time",
        "Time traction-limited",
        "time",
        "s",
        help="Spent at the edge of wheel slip.",
        equation="(S6)",
    ),
    Output(
        "start_acceleration",
        "Acceleration at the start",
        "acceleration",
        "m/s**2",
        help="min(F_m(0), μ·m·g)/m less rolling resistance, at full duty (a voltage ramp starts at 0) (S4).",
        equation="(S4)",
    ),
    Output(
        "traction_acceleration",
        "Traction limit",
        "acceleration",
        "m/s**2",
        help="The wheels' force at the edge of slip over the mass: μ·g, less with weight_transfer (S3).",
        equation="(S3)",
    ),
    Output(
        "slip_current",
        "Suggested stator limit",
        "current",
        "A",
        help="Per motor: the stator current at which the wheels just grip (S5); a limit at or below it stops slip.",
        equation="(S5)",
    ),
    Output("peak_stator_current", "Peak stator current", "current", "A", help="Per motor.", equation="(S5)"),
    Output(
        "peak_supply_current",
        "Peak supply current",
        "current",
        "A",
        help="Per motor: stator current × duty (S11).",
        equation="(S11)",
    ),
    Output(
        "peak_battery_current",
        "Peak battery current",
        "current",
        "A",
        help="All drive motors (S11).",
        equation="(S11)",
    ),
    Output(
        "min_bus_voltage",
        "Min bus voltage",
        "voltage",
        "V",
        help="Battery voltage minus the sag (S11).",
        equation="(S11)",
    ),
    Output(
        "energy",
        "Energy",
        "energy",
        "J",
        help="Drawn from the battery over the sprint, its EMF × current (S12).",
        equation="(S12)",
    ),
    Output(
        "moment_of_inertia",
        "Yaw inertia",
        "inertia",
        "kg*m**2",
        help="About the vertical axis: estimated m·(L² + W²)/12 over the bumpers, or as entered (S13).",
        equation="(S13)",
    ),
    Output(
        "kS",
        "kS",
        "voltage",
        "V",
        help="Volts to overcome the motors' loss and rolling resistance (S9).",
        equation="(S9)",
    ),
    Output(
        "kV", "kV", "voltage_per_speed", "V*s/m", help="Volts per m/s of the robot (S9).", equation="(S9)"
    ),
    Output(
        "kA",
        "kA",
        "voltage_per_acceleration",
        "V*s**2/m",
        help="Volts per m/s² of the robot (S9).",
        equation="(S9)",
    ),
    Output(
        "kA_angular",
        "kA angular",
        "voltage_per_angular_acceleration",
        "V*s**2/rad",
        help="Volts per rad/s² of yaw, turning in place: kA·I/(m·r_b), r_b half the track (S9).",
        equation="(S9)",
    ),
    *STATS_OUTPUTS,
)

TABLES = (
    Table(
        "distances",
        "Fastest ratio by distance",
        (
            Column("distance", "Distance", "length", "m", width=10),
            Column("best_ratio", "Fastest G", width=10),
            Column("time", "Time", "time", "s", width=10),
            Column("speed", "Speed there", "speed", "ft/s", width=12),
        ),
        modes=("optimise",),
    ),
)


@dataclasses.dataclass(frozen=True)
class Drive:
    """What the motors see in a sprint (the context the effects are built with)."""

    motor: Any
    count: int
    battery_voltage: float
    efficiency: float
    n: float  # motor rad per metre (S1)
    mass: float
    bus_resistance: float = 0.0
    xp: Any = motion.SCALAR

    R = motion.Mechanism.R
    Kv = motion.Mechanism.Kv
    Kt = motion.Mechanism.Kt
    free_current = motion.Mechanism.free_current

    @property
    def force_per_amp(self) -> float:
        return self.efficiency * self.count * self.Kt * self.n  # (S2)


@dataclasses.dataclass
class Setup:
    drive: Drive
    asm: Any
    values: Mapping[str, Any]
    distance: float
    traction: float  # F_t (S3)
    ramp: float = 0.0  # T_r (S14), 0 without the voltage_ramp effect

    def ceiling(self, t: float) -> float:
        """The duty the ramp allows at time t (S14)."""
        return min(1.0, t / self.ramp) if self.ramp > 0 and t < self.ramp else 1.0

    def resist(self):
        f = self.asm.slots["resist"]
        return f if f is not None else (lambda v: 0.0)


def geometry(v: Mapping[str, Any]) -> tuple[str, float, float]:
    """(kind, reduction G, wheel diameter m): a COTS module's own figures, else the entered ones."""
    if v["drive"] in MODULES:
        _, G_, d_in = MODULES[v["drive"]]
        return "swerve", G_, d_in * INCH
    return v["drive"], v.get("ratio", 1.0), v["wheel_diameter"]


def setup(v: Mapping[str, Any], ratio: float | None = None, distance: float | None = None) -> Setup:
    on = v["effects"]
    motor, _ = lookup(v["motor"], v["source"])
    _, G_module, wheel = geometry(v)
    G_ = G_module if ratio is None else ratio
    drive = Drive(
        motor,
        v["motor_count"],
        v["voltage"],
        v["efficiency"],
        G_ / (wheel / 2),  # (S1)
        v["robot_mass"],
        bus_resistance_of(v, on),
    )
    asm = EFFECTS.assemble(on, v, drive, SLOTS, ("position", "speed", "energy"))
    d = v["distance"] if distance is None else distance
    return Setup(drive, asm, v, d, traction(v, on), v["ramp_time"] if "voltage_ramp" in on else 0.0)


def traction(v: Mapping[str, Any], on) -> float:
    """F_t (S3), or (S3') with weight_transfer: four equal modules, the centre of mass midway
    between the axles at height h. Accelerating, the front wheels carry m·g/2 − (F − F_rr)·h/L, and
    each module pushes F/4 ≤ μ·(its load), so the front ones slip first:
        F ≤ 2μ·(m·g/2 − (F − F_rr)·h/L)  ⇔  F ≤ (μ·m·g + k·F_rr)/(1 + k),  k = 2μ·h/L           (S3')
    (rolling resistance acts at the ground: no pitching moment about the contacts; drag's is left out)."""
    mu, m = v["wheel_cof"], v["robot_mass"]
    if "weight_transfer" not in on:
        return mu * m * G  # (S3)
    k = 2 * mu * v["cg_height"] / v["wheelbase"]
    F_rr = v["rolling_coefficient"] * m * G if "rolling_resistance" in on else 0.0
    return (mu * m * G + k * F_rr) / (1 + k)  # (S3')


def _motor_force(s: Setup):
    """(v, t) -> (F_m, u, I): (S2) with the duty and current of the limits that are on, under the
    ramp's ceiling at time t (S14; t omitted: full duty)."""
    dr = s.drive
    elec = electrical(dr, s.asm.slots["duty"])
    fpa, i_f, k_emf = dr.force_per_amp, dr.free_current, dr.n / dr.Kv

    if s.ramp > 0:
        ceiling = s.ceiling

        def f(v, t=math.inf):
            u, I = elec(k_emf * v, ceiling(t))
            return fpa * (I - i_f), u, I

        return f, elec

    def f(v, t=None):
        u, I = elec(k_emf * v)
        return fpa * (I - i_f), u, I

    return f, elec


def check_can_move(s: Setup) -> None:
    """An InputError naming the field when the robot cannot leave: the wheels' grip or the motors'
    force at rest does not beat rolling resistance."""
    F0 = _motor_force(s)[0](0.0)[0]
    F_rr = s.resist()(0.0)
    if s.traction <= F_rr:
        raise InputError(
            "wheel_cof",
            f"({s.values['wheel_cof']:.4g}) is no more than the rolling resistance "
            f"({s.values['rolling_coefficient']:.4g}): the wheels cannot push the robot",
        )
    if F0 > F_rr:
        return
    parts = s.asm.parts
    limits = [n for n in ("stator_limit", "supply_limit") if n in parts]
    if limits:
        binding = min(limits, key=lambda n: parts[n].terms["duty"](0.0))  # the lower duty bound at rest
        raise InputError(
            "stator_current_limit" if binding == "stator_limit" else "supply_current_limit",
            f"is too low: at rest the motors give {F0:.4g} N, rolling resistance takes {F_rr:.4g} N",
        )
    raise InputError(
        "ratio", f"is too low: the motors stall at {F0:.4g} N against {F_rr:.4g} N of rolling resistance"
    )


def _slip_point(s: Setup, elec) -> tuple[float, float]:
    """(I_slip (S5), E_slip): the current at which the motors' force equals the traction, and the
    back-EMF where the motors draw it (bisection: I(E) never rises with E)."""
    dr = s.drive
    I_slip = s.traction / dr.force_per_amp + dr.free_current  # (S5)
    if elec(0.0)[1] <= I_slip:
        return I_slip, 0.0
    lo, hi = 0.0, dr.battery_voltage
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if elec(mid)[1] > I_slip:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * dr.battery_voltage:
            break
    return I_slip, hi


def _g_and_slope(X: float, a: float) -> tuple[float, float]:
    return (1 - a) * X + a * motion._g(X), 1 - a * math.exp(-X)


def phase_two_time(D: float, a: float) -> float:
    """X ≥ 0 with X − a·(1 − e^{−X}) = D (S8), 0 ≤ a ≤ 1: Lambert W₀ for D ≥ 0.01, else the root of
    (1 − a)·X + a·X²/2 = D; then Newton (f convex and increasing: it converges from either side)."""
    if D <= 0:
        return 0.0
    if D < 0.01:
        X = 2 * D / ((1 - a) + math.sqrt((1 - a) ** 2 + 2 * a * D))
    else:
        from scipy.special import lambertw

        X = D + a + float(lambertw(-a * math.exp(-(D + a))).real)  # (S8)
    for _ in range(6):
        f, slope = _g_and_slope(X, a)
        if not slope > 0:
            break
        step = (f - D) / slope
        X -= step
        if abs(step) <= 1e-16 * X:
            break
    return X


def closed_form(s: Setup) -> dict[str, float] | None:
    """(S6)-(S8) when nothing needs integrating (no current limit, no drag, no ramp); None otherwise."""
    if s.asm.slots["duty"] is not None or "air_drag" in s.asm.on or s.ramp > 0:
        return None
    dr = s.drive
    m, d = dr.mass, s.distance
    R_eff = dr.R + dr.bus_resistance
    fpa = dr.force_per_amp
    F_rr = s.resist()(0.0)
    a1 = (s.traction - F_rr) / m
    v_sw = max(
        0.0, (dr.battery_voltage - R_eff * (dr.free_current + s.traction / fpa)) * dr.Kv / dr.n
    )  # (S6)
    t_sw, x_sw = v_sw / a1, v_sw * v_sw / (2 * a1)
    if x_sw >= d:
        T = math.sqrt(2 * d / a1)
        return {"time": T, "speed": a1 * T, "traction_time": T, "traction_distance": d}
    tau = m * R_eff * dr.Kv / (fpa * dr.n)  # (S7)
    v_f = (dr.battery_voltage - R_eff * (dr.free_current + F_rr / fpa)) * dr.Kv / dr.n
    a = (v_f - v_sw) / v_f
    X = phase_two_time((d - x_sw) / (v_f * tau), a)
    speed = v_f - (v_f - v_sw) * math.exp(-X)
    return {"time": t_sw + X * tau, "speed": speed, "traction_time": t_sw, "traction_distance": x_sw}


class _Pieces:
    """Runs one after another (each a phase: at rest, slipping or gripping), answering `at(t)`,
    `phase_at(t)` and `y[-1]`."""

    def __init__(self, runs, phases):
        self.runs = runs
        self.phases = phases
        self.y = runs[-1].y
        self.nfev = sum(r.nfev for r in runs)

    def _piece(self, t: float) -> int:
        return next((k for k, r in enumerate(self.runs) if t <= r.t[-1]), len(self.runs) - 1)

    def at(self, t: float):
        return self.runs[self._piece(t)].at(t)

    def phase_at(self, t: float) -> str:
        return self.phases[self._piece(t)]


def integrated(s: Setup, rtol: float, dense: bool = False):
    """(S4) integrated to the goal, one run per phase: at rest while the ramp's force is below what
    holds the robot (S14), slipping (at the edge of slip: the traction pushes, the motors draw I_slip
    (S5)), gripping. A run also stops where the duty rule changes branch (a current limit letting
    go, the ramp's ceiling meeting the limits' bound) and starts again, so no step straddles a kink
    (straddled, the supply limit's release cost 50x the accuracy asked: energy 5.8e-5 at rtol 1e-6);
    while the ramp binds, each run integrates the ramp's own smooth branch u = t/T_r, so the event
    that ends it is located on a smooth solution. Without a ramp the wheels never slip again once
    they grip: F_m falls as v rises. (values, run, scales)."""
    dr = s.drive
    force, elec = _motor_force(s)
    resist = s.resist()
    F_t, m, d, T_r = s.traction, dr.mass, s.distance, s.ramp
    I_slip, E_slip = _slip_point(s, elec)
    u_slip = elec(E_slip)[0]
    v_ref = (dr.battery_voltage - dr.R * dr.free_current) * dr.Kv / dr.n
    e_ref = dr.count * dr.battery_voltage * I_slip * d / v_ref
    Vb_N = dr.battery_voltage * dr.count
    F_rest = resist(0.0)
    fpa, i_f, k_emf = dr.force_per_amp, dr.free_current, dr.n * v_ref / dr.Kv
    at_duty = electrical(dr, None)  # (E, u) -> (u, I) at a duty given outright (E1)

    def ramp_force(v, t):  # the ramp's branch u = t/T_r (S14), smooth past where it stops binding
        u, I = at_duty(k_emf * v / v_ref, t / T_r)
        return fpa * (I - i_f), u, I

    def make_phase(phase: str, binds: bool):
        f = ramp_force if binds else force

        def slipping(t, y):  # (S4) at the edge of slip; under a ramp the duty is min(t/T_r, u_slip) (S14)
            v = y[1] * v_ref
            u = t / T_r if binds else u_slip
            return [v / d, (F_t - resist(v)) / (m * v_ref), Vb_N * u * I_slip / e_ref]

        def gripping(t, y):
            v = y[1] * v_ref
            F_m, u, I = f(v, t)
            return [v / d, (F_m - resist(v)) / (m * v_ref), Vb_N * u * I / e_ref]

        def resting(t, y):  # the ramp's force does not yet beat the loss and rolling resistance (S14)
            _, u, I = f(0.0, t)
            return [0.0, 0.0, Vb_N * u * I / e_ref]

        events = [Event("goal", lambda t, y: y[0] - 1.0, +1)]
        if phase == "rest":
            events.append(Event("leave", lambda t, y: f(0.0, t)[0] - F_rest, +1))
        elif phase == "slip":
            events.append(Event("grip", lambda t, y: f(y[1] * v_ref, t)[0] - F_t, -1))
        elif binds:
            events.append(Event("slip", lambda t, y: f(y[1] * v_ref, t)[0] - F_t, +1))
        if binds and phase != "slip":  # the ceiling meets the limits' bound (or full duty)
            events.append(Event("cap", lambda t, y: t / T_r - ceiling_bound(y[1]), +1))
        return {"rest": resting, "slip": slipping, "grip": gripping}[phase], events

    duty = s.asm.slots["duty"]

    def ceiling_bound(w):
        return 1.0 if duty is None else min(1.0, duty(k_emf * w))

    to_scaled = dr.Kv / (dr.n * v_ref)
    kinks = sorted({E * to_scaled for E in branch_emfs(dr, s.values, s.asm.on) if E * to_scaled > 0})
    opts = {"rtol": rtol, "atol": rtol, "max_steps": DP54_STEPS, "dense": dense}
    # the speed settles with τ = m·R·Kv/(η·N·Kt·n²) (S7); an explicit step must stay near 3τ, so a
    # sprint many τ long is stiff: scipy's LSODA (same events, dense output) takes it
    tau = m * (dr.R + dr.bus_resistance) * dr.Kv / (dr.force_per_amp * dr.n)
    stiff = d / v_ref > STIFF * tau
    binds = T_r > 0  # at t = 0 the ramp allows no duty at all
    F0 = (ramp_force if binds else force)(0.0, 0.0)[0]
    phase = "rest" if binds and F0 < F_rest else "slip" if F0 > F_t else "grip"
    runs, phases = [], []
    t0, y0, last = 0.0, [0.0, 0.0, 0.0], ()
    while True:
        if phase == "rest" and force(0.0, t0)[0] >= F_rest:
            phase = "grip"  # (only by rounding: the force rises through F_rest before the ceiling stops)
        if phase == "slip" and binds and not u_slip * T_r > t0:
            binds = False
        rhs, events = make_phase(phase, binds)
        t1 = 3600.0
        if phase == "slip" and binds:
            t1 = u_slip * T_r  # the slip's duty stops rising: a kink at a known time
        elif phase == "grip" and not binds:
            while kinks and kinks[0] <= y0[1]:
                kinks.pop(0)
            if kinks:
                events.append(Event("kink", lambda t, y, w=kinks[0]: y[1] - w, +1))
        try:
            if stiff and phase == "grip":
                raise RuntimeError("stiff")
            run = integrate(rhs, t0, t1, y0, events=events, restart=last, **opts)
        except RuntimeError:  # stiffer than estimated: LSODA takes over
            run = integrate_stiff(rhs, t0, t1, y0, rtol, rtol, events, "LSODA")
            if run.status == -1:
                raise InputError("ratio", f"the sprint could not be integrated ({run.message})") from None
        runs.append(run)
        phases.append(phase)
        if run.event == "goal" or (run.event is None and t1 == 3600.0):
            break
        if run.event == "kink":
            kinks.pop(0)
        t0, y0, last = run.t[-1], list(run.y[-1]), (run.event,) if run.event else ()
        if run.event in ("cap", None):
            binds = False  # past the ceiling's meeting point (or the slip's known one) the limits rule
        phase = {"leave": "grip", "slip": "slip", "grip": "grip"}.get(run.event, phase)
        if run.event == "grip" and binds:  # the ramp may have stopped binding while the wheels slipped
            binds = t0 / T_r < ceiling_bound(y0[1])
    if runs[-1].event != "goal":
        raise InputError("ratio", "the robot does not cross the distance within an hour: change the ratio")
    piece = _Pieces(runs, phases)
    end = piece.y[-1]
    slip_runs = [r for r, p in zip(runs, phases) if p == "slip"]
    values = {
        "time": runs[-1].t[-1],
        "speed": end[1] * v_ref,
        "traction_time": sum(r.t[-1] - r.t[0] for r in slip_runs),
        "traction_distance": sum((r.y[-1][0] - r.y[0][0] for r in slip_runs), 0.0) * d,
        "energy": end[2] * e_ref,
    }
    return values, piece, (d, v_ref, e_ref)


def _attainable(s: Setup) -> float:
    """Top speed: F_m(v) = resist(v) (S4); the free speed when nothing resists."""
    force, _ = _motor_force(s)
    resist = s.resist()
    dr = s.drive
    v_free = (dr.battery_voltage - (dr.R + dr.bus_resistance) * dr.free_current) * dr.Kv / dr.n

    def net(v):
        return force(v)[0] - resist(v)

    if s.asm.slots["resist"] is None or net(v_free) >= 0:
        return v_free  # F_m(v_free) = 0 at full duty (the limits do not bind at the free current)
    from scipy.optimize import brentq

    return float(brentq(net, 0.0, v_free, xtol=1e-14 * v_free, rtol=1e-15))


def sprint(s: Setup, rtol: float, plots: bool = False) -> SimRun:
    """Every output of one sprint at one ratio (closed form when nothing needs integrating)."""
    check_can_move(s)
    dr = s.drive
    force, elec = _motor_force(s)
    I_slip, E_slip = _slip_point(s, elec)
    exact = closed_form(s)
    run = scales = None
    nfev = 0
    if exact is None:
        exact, run, scales = integrated(s, rtol, dense=plots or s.ramp > 0)
        nfev = run.nfev
    else:
        exact["energy"] = _energy_closed(s, exact, I_slip, elec(E_slip)[0])
    if s.ramp > 0:
        I0, peak_sup = _ramp_peaks(s, run, scales, I_slip, elec(E_slip)[0])
    else:
        traction_limited = exact["traction_time"] > 0
        E_start = E_slip if traction_limited else 0.0
        # while slipping the motors sit at E_slip whatever the robot's speed (S5); after, E rises with v
        E_end = max(E_start, dr.n * exact["speed"] / dr.Kv)
        Es = [E_start, E_end] + [E for E in branch_emfs(dr, s.values, s.asm.on) if E_start < E < E_end]
        sup = []
        for E in Es:
            u, I = elec(E)
            if traction_limited and E == E_start:
                I = I_slip
            sup.append(u * I)
        I0 = I_slip if traction_limited else elec(0.0)[1]
        peak_sup = max(sup)
    v_free = (dr.battery_voltage - (dr.R + dr.bus_resistance) * dr.free_current) * dr.Kv / dr.n
    F_rr = s.resist()(0.0)
    fpv = dr.force_per_amp / dr.R
    values = {
        "time_to_distance": exact["time"],
        "speed_at_distance": exact["speed"],
        "free_speed": v_free,
        "top_speed": _attainable(s),
        "traction_distance": exact["traction_distance"],
        "traction_time": exact["traction_time"],
        "start_acceleration": (min(force(0.0)[0], s.traction) - F_rr) / dr.mass,
        "traction_acceleration": s.traction / dr.mass,
        "slip_current": I_slip,
        "peak_stator_current": I0,
        "peak_supply_current": peak_sup,
        "peak_battery_current": peak_sup * dr.count,
        "min_bus_voltage": dr.battery_voltage - dr.bus_resistance * peak_sup,
        "energy": exact["energy"],
        "moment_of_inertia": yaw_inertia(s.values),  # (S13)
        "kS": dr.R * dr.free_current + F_rr / fpv,  # (S9)
        "kV": dr.n / dr.Kv,
        "kA": dr.mass / fpv,
        "kA_angular": dr.mass / fpv * yaw_inertia(s.values) / (dr.mass * s.values["trackwidth"] / 2),  # (S9)
    }
    key = {"time_to_distance": exact["time"], "speed_at_distance": exact["speed"], "energy": exact["energy"]}
    series = _samples(s, run, scales, exact, I_slip, elec) if plots else {}
    return SimRun(values, key, nfev, [], series)


def _ramp_peaks(s: Setup, run: _Pieces, scales, I_slip: float, u_slip: float) -> tuple[float, float]:
    """(peak stator, peak supply current) per motor under a ramp (S14): the electrical state now
    depends on time as well as speed, so the extremes are found along the run: at every step and
    phase boundary, each local maximum then refined by bounded Brent on the dense output."""
    from scipy.optimize import minimize_scalar

    force, _ = _motor_force(s)
    _, v_ref, _ = scales

    def currents(t: float, phase: str, y) -> tuple[float, float]:
        if phase == "slip":  # at the edge of slip the motors draw I_slip at the ramp's duty (S5), (S14)
            return I_slip, min(s.ceiling(t), u_slip) * I_slip
        _, u, I = force(0.0 if phase == "rest" else y[1] * v_ref, t)
        return I, u * I

    peaks = [0.0, 0.0]
    for r, phase in zip(run.runs, run.phases):
        for k in (0, 1):
            values = [currents(t, phase, y)[k] for t, y in zip(r.t, r.y)]
            peaks[k] = max(peaks[k], *values)
            for i in range(1, len(values) - 1):
                if values[i] >= values[i - 1] and values[i] >= values[i + 1]:
                    best = minimize_scalar(
                        lambda t: -currents(t, phase, r.at(t))[k],
                        bounds=(r.t[i - 1], r.t[i + 1]),
                        method="bounded",
                        options={"xatol": 1e-12 * r.t[-1]},
                    )
                    peaks[k] = max(peaks[k], -float(best.fun))
    return peaks[0], peaks[1]


def _energy_closed(s: Setup, exact, I_slip: float, u_slip: float) -> float:
    """∫ V_b·N·u·I dt in closed form: traction phase at I_slip, then (M2) at full duty,
    I = (V_b − n·v/Kv)/R_eff, so ∫ I dt = (V_b·s − n·(x − x_sw)/Kv)/R_eff."""
    dr = s.drive
    R_eff = dr.R + dr.bus_resistance
    t2 = exact["time"] - exact["traction_time"]
    x2 = s.distance - exact["traction_distance"]
    charge = u_slip * I_slip * exact["traction_time"] + (dr.battery_voltage * t2 - dr.n * x2 / dr.Kv) / R_eff
    return dr.count * dr.battery_voltage * charge


def _samples(s: Setup, run, scales, exact, I_slip: float, elec) -> dict[str, tuple[list, list]]:
    """Distance, speed and current over time: from the dense output, or from (S6)-(S7)."""
    dr = s.drive
    force, _ = _motor_force(s)
    T = exact["time"]
    if run is not None:
        d, v_ref, _ = scales

        def state(t, last):
            y = run.y[-1] if last else run.at(t)
            return y[0] * d, y[1] * v_ref
    else:
        m, R_eff, fpa = dr.mass, dr.R + dr.bus_resistance, dr.force_per_amp
        a1 = (s.traction - s.resist()(0.0)) / m
        t_sw, x_sw = exact["traction_time"], exact["traction_distance"]
        v_sw = a1 * t_sw
        tau = m * R_eff * dr.Kv / (fpa * dr.n)  # (S7)
        v_f = (dr.battery_voltage - R_eff * (dr.free_current + s.resist()(0.0) / fpa)) * dr.Kv / dr.n

        def state(t, last):
            if t <= t_sw:
                return a1 * t * t / 2, a1 * t
            x = -(t - t_sw) / tau
            return x_sw + v_f * (t - t_sw) + (v_f - v_sw) * tau * math.expm1(x), v_f - (
                v_f - v_sw
            ) * math.exp(x)

    ts, xs, vs, cur = [], [], [], []
    for k in range(SAMPLES + 1):
        t = T * k / SAMPLES
        x, v = state(t, k == SAMPLES)
        F_m, _, I = force(v, t)
        ts.append(t)
        xs.append(x)
        vs.append(v)
        cur.append(I_slip if F_m > s.traction else I)
    return {"position": (ts, xs), "speed": (ts, vs), "stator_current": (ts, cur)}


def slip_ratio(v: Mapping[str, Any], distance: float | None = None) -> float:
    """G_t: the ratio at which the motors' force at rest equals the traction (S10's centre)."""
    probe = setup(v, 1.0, distance)
    dr = probe.drive
    _, I0 = electrical(dr, probe.asm.slots["duty"])(0.0)
    if I0 <= dr.free_current:
        check_can_move(probe)
    return probe.traction / (dr.force_per_amp * (I0 - dr.free_current))


def batch_times(v: Mapping[str, Any], ratios: Any, distance: float) -> Any:
    """Time to the distance at every ratio of a numpy array at once, to a few 0.1 % (a screen for the
    optimiser: core.sim.motion.batch_arrival, fixed steps, numpy over the ratios); nan where the robot
    cannot leave."""
    import numpy as np

    xp = motion._Array()
    on = v["effects"]
    motor, _ = lookup(v["motor"], v["source"])
    n = np.asarray(ratios, dtype=float) / (geometry(v)[2] / 2)  # (S1)
    dr = Drive(
        motor,
        v["motor_count"],
        v["voltage"],
        v["efficiency"],
        n,
        v["robot_mass"],
        bus_resistance_of(v, on),
        xp,
    )
    asm = EFFECTS.assemble(on, v, dr, SLOTS, ("position", "speed", "energy"), minimum=xp.minimum)
    elec = electrical(dr, asm.slots["duty"])
    resist = asm.slots["resist"] or (lambda w: 0.0 * w)
    fpa, i_f, k_emf, m = dr.force_per_amp, dr.free_current, n / dr.Kv, dr.mass
    F_t = traction(v, on)

    T_r = v["ramp_time"] if "voltage_ramp" in on else 0.0

    def accel(p, w, t=None):
        _, I = elec(k_emf * w) if t is None else elec(k_emf * w, np.minimum(1.0, t / T_r))  # (S14)
        a = (np.minimum(fpa * (I - i_f), F_t) - resist(w)) / m  # (S4)
        return a if t is None else np.where((w <= 0) & (a < 0), 0.0, a)  # held at rest (S14)

    _, I0 = elec(0.0 * n)
    F0 = np.minimum(fpa * (I0 - i_f), F_t) - resist(0.0 * n)
    movable = F0 > 0
    R_eff = dr.R + dr.bus_resistance
    v_free = (dr.battery_voltage - R_eff * i_f) * dr.Kv / n
    tau = m * R_eff * dr.Kv / (fpa * n)
    T_est = distance / v_free + tau + np.sqrt(2 * distance * m / np.where(movable, F0, np.nan)) + T_r
    h = np.where(movable, T_est / motion.BATCH_STEPS, 0.0)
    return motion.batch_arrival(accel, distance, h, ~movable, v_free, timed=T_r > 0)


def _time_and_grip(s: Setup, rtol: float) -> tuple[float, float]:
    """(time to the distance, distance traction-limited) of one sprint, nothing else computed."""
    check_can_move(s)
    exact = closed_form(s)
    if exact is None:
        exact, _, _ = integrated(s, rtol)
    return exact["time"], exact["traction_distance"]


def fastest(v: Mapping[str, Any], rtol: float, distance: float) -> tuple[float, float, list, list, bool]:
    """(G*, T*, curve ratios, curve times, at the edge) for one distance (S10): the batch over
    CURVE_RATIOS ratios, then bounded Brent on the accurate sprint around the batch's best."""
    import numpy as np
    from scipy.optimize import minimize_scalar

    G_t = slip_ratio(v, distance)
    ratios = np.geomspace(G_t / 30, G_t * 3, CURVE_RATIOS)
    times_arr = batch_times(v, ratios, distance)
    ok = np.isfinite(times_arr)
    if not ok.any():
        check_can_move(setup(v, float(ratios[-1]), distance))
        raise InputError("ratio", "no ratio moves the robot")
    i = int(np.nanargmin(np.where(ok, times_arr, np.nan)))
    lo, hi = float(ratios[max(i - 3, 0)]), float(ratios[min(i + 3, CURVE_RATIOS - 1)])

    def time_at(G_):
        try:
            return _time_and_grip(setup(v, float(G_), distance), rtol)[0]
        except InputError:
            return math.inf

    def traction_only(G_):
        try:
            return _time_and_grip(setup(v, float(G_), distance), rtol)[1] >= distance * (1 - 1e-12)
        except InputError:
            return False

    best = minimize_scalar(time_at, bounds=(lo, hi), method="bounded", options={"xatol": 1e-7 * lo})
    G_best, T_best = float(best.x), float(best.fun)
    if traction_only(G_best):
        # the time is (μ − C_rr)·g's alone for every ratio that keeps the wheels at the edge of slip
        # to the distance: a flat optimum. The least reduction of them (the most top speed) by
        # bisection from a ratio that leaves the traction limit before the distance.
        lo_G = float(ratios[0])
        if not traction_only(lo_G):
            hi_G = G_best
            for _ in range(60):
                mid = math.sqrt(lo_G * hi_G)
                if traction_only(mid):
                    hi_G = mid
                else:
                    lo_G = mid
                if hi_G / lo_G - 1 < 1e-9:
                    break
            G_best = hi_G
            T_best = time_at(G_best)
    return (
        G_best,
        T_best,
        [float(r) for r in ratios[ok]],
        [float(t) for t in times_arr[ok]],
        i in (0, CURVE_RATIOS - 1),
    )


def simulate(v: Mapping[str, Any], rtol: float) -> SimRun:
    _, note = lookup(v["motor"], v["source"])
    if v["mode"] == "optimise":
        G_best, _, ratios, times, edge = fastest(v, rtol, v["distance"])
        run = sprint(setup(v, G_best), rtol, plots=True)
        run.values["best_ratio"] = G_best
        run.key["best_ratio"] = G_best
        run.series["time_vs_ratio"] = (ratios, times)
        run.series["fastest"] = ([G_best], [run.values["time_to_distance"]])  # the optimum, marked
        if edge:
            run.warnings.append(
                f"The fastest ratio is at the edge of the range searched ({ratios[0]:.3g} to {ratios[-1]:.3g})."
            )
    else:
        run = sprint(setup(v), rtol, plots=True)
    braking_warning(v, run)
    if note:
        run.warnings.insert(0, note)
    return run


def compute(values: Mapping[str, Any], estimate: str = "now") -> Result:
    result_of = compute_with_stats(simulate)
    result = result_of(values, estimate)
    if values["mode"] == "optimise":
        rtol = 1e-6
        rows = []
        for d in TABLE_DISTANCES:
            try:
                G_best, T, _, _, _ = fastest(values, rtol, d)
            except InputError:
                continue
            speed = sprint(setup(values, G_best, d), rtol).values["speed_at_distance"]
            rows.append({"distance": d, "best_ratio": G_best, "time": T, "speed": speed})
        result.tables["distances"] = rows
    return Result(result.values, result.warnings, result.series, result.tables)


def yaw_inertia(v: Mapping[str, Any]) -> float:
    # core.robot_config (with json and core.gains_numbers, ~8 ms of dataclasses and modules) is
    # loaded by the solve and the exports, not by the card's description
    from ..robot_config import estimated_moi

    if v["inertia_model"] == "entered":
        return v["moment_of_inertia"]
    return estimated_moi(v["robot_mass"], v["bumper_length"], v["bumper_width"])  # (S13)


def robot_config_of(solution) -> RobotConfig:
    """The drivetrain a solved sprint describes, as the path planners see it (S13). A ValueError says
    what cannot be exported (PathPlanner and Choreo check their own limits: core.robot_config)."""
    from ..robot_config import RobotConfig, motor_limits

    v = {name: value.value for name, value in solution.inputs.items()}
    out = {name: value.value for name, value in solution.outputs.items()}
    kind, G_module, wheel = geometry(v)
    G_ = out.get("best_ratio", G_module)
    motor, _ = lookup(v["motor"], v["source"])
    stall = motor.stall_current * v["voltage"] / motor.v_spec  # (4)
    limit = v["stator_current_limit"] if "stator_limit" in v["effects"] else stall
    # one motor at the battery voltage: free speed (1) and torque at the limit Kt·(I − i_f)·η (S13)
    free_speed, torque = motor_limits(
        v["motor"], limit, voltage=v["voltage"], efficiency=v["efficiency"], source=v["source"]
    )
    if not torque > 0:
        i_f = motor.free_current * v["voltage"] / motor.v_spec
        raise ValueError(
            f"the stator current limit {limit:.4g} A is below the free current {i_f:.4g} A: no torque to export"
        )
    return RobotConfig(
        kind=kind,
        mass=v["robot_mass"],
        moi=out["moment_of_inertia"],
        wheel_radius=wheel / 2,
        gearing=G_,
        motor=v["motor"],
        motor_count=v["motor_count"],
        current_limit=limit,
        wheel_cof=v["wheel_cof"],
        max_speed=min(out["top_speed"], out["free_speed"]),
        trackwidth=v["trackwidth"],
        wheelbase=v["wheelbase"],
        bumper_width=v["bumper_width"],
        bumper_length=v["bumper_length"],
        motor_free_speed=free_speed,
        motor_max_torque=torque,
    )


def _pathplanner(solution) -> str:
    import json

    from ..robot_config import pathplanner_settings

    return json.dumps(pathplanner_settings(robot_config_of(solution)), indent=2) + "\n"


def _choreo(solution) -> str:
    import json

    from ..robot_config import choreo_project

    return json.dumps(choreo_project(robot_config_of(solution), "Gearhead sprint"), indent=1) + "\n"


DOCUMENTS = (
    Document("pathplanner", "PathPlanner robot config (settings.json)", "settings.json", _pathplanner),
    Document("choreo", "Choreo project with this robot (.chor)", "robot.chor", _choreo),
)


CALCULATOR = Calculator(
    id="sprint",
    title="Drivetrain sprint",
    summary="Time for a robot to cross a distance from rest, and the ratio that crosses it first.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    simulate=simulate,
    tables=TABLES,
    documents=DOCUMENTS,
    plots=(
        Plot("Distance", ("position",), "time", "time", "s", "distance", "length", "m"),
        Plot("Speed", ("speed",), "time", "time", "s", "speed", "speed", "ft/s"),
        Plot("Current (per motor)", ("stator_current",), "time", "time", "s", "current", "current", "A"),
        Plot(
            "Time vs ratio (optimise)",
            ("time_vs_ratio", "fastest"),
            "ratio",
            "dimensionless",
            "",
            "time",
            "time",
            "s",
        ),
    ),
)
