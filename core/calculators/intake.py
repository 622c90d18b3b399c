"""A roller intake (issue 31, as ReCalc's intake tab): how fast the rollers' surface runs against the
drivetrain, how long a game piece takes to be pulled in, and, for every motor, the reduction that runs
the rollers at a target multiple of the drivetrain's speed, ranked by the torque it gives at the limit.

The motors are the shared model (core.motors, seed eqs. 1-9); the torque at the limit is the motor
tab's (core.calculators.motor (L1)) through core.calculators.motors (C5). n motors, voltage V,
gearbox efficiency η, reduction G (motor turns per roller turn), roller diameter d, drivetrain speed
v_d, target surface-to-drive ratio k*:
    ω_r = ω̃f/G                     roller free speed, ω̃f = ωf·V/V_spec (eq. 1)          (I1)
    v_s = ω_r·d/2                   roller surface speed at free speed                   (I2)
    k = v_s/v_d                     surface speed over the drivetrain's                   (I3)
    t = L/v_s                       time to pull a game piece a distance L               (I4)
        (the piece moves with the roller's surface at free speed from first touch: no slip, no
        load slowing the rollers, no spin-up; a lower bound on the real time)
    ω* = 2·k*·v_d/d                 the roller speed for v_s = k*·v_d                     (I5)
    G* = ω̃f/ω* = ω̃f·d/(2·k*·v_d)    the reduction for it: (I1)-(I3) solved for G          (I5)
    τ_r = G·τ_lim                   roller torque at rest with the limits, τ_lim (C5)      (I6)
    F = 2·τ_r/d                     the pull at the roller's surface from that torque     (I7)
The table: (I5), (I6), (I7) for every motor of the database (n of each, the same V, η and limits),
largest τ_r first.
"""

from __future__ import annotations

from ..declarations import Calculator, Column, Output, Result, Table
from ..errors import InputError
from ..fields import Field
from ..motors import lookup, motor_fields, motor_names
from .motors import EFFECTS, SOURCE_NAMES, limited_system

FIELDS = motor_fields(default_motor="Kraken X44") + (
    Field(
        "roller_diameter",
        "Roller diameter",
        "length",
        "in",
        default=2,
        min=0.1,
        max=20,
        help="d: outside diameter of the rollers where they touch the game piece (I2).",
    ),
    Field(
        "ratio",
        "Reduction G",
        default=3,
        min=0.01,
        max=1000,
        help="Motor turns per roller turn (I1); below 1 the rollers turn faster than the motor.",
    ),
    EFFECTS.field(
        "stator_limit (per motor, on by default: the torque at the limit), supply_limit (per motor)."
    ),
    *EFFECTS.fields(),
    Field(
        "drivetrain_speed",
        "Drivetrain speed",
        "speed",
        "ft/s",
        default=15,
        min=0,
        min_exclusive=True,
        max=100,
        help="v_d: the robot's speed as it drives onto a game piece (I3), e.g. its free speed.",
    ),
    Field(
        "pull_distance",
        "Pull distance",
        "length",
        "in",
        default=12,
        min=0,
        max=1000,
        help="L: how far the rollers must carry the game piece (I4).",
    ),
    Field(
        "target_speed_ratio",
        "Target surface / drive speed",
        default=2,
        min=0,
        min_exclusive=True,
        max=100,
        help="k*: the roller surface speed wanted, as a multiple of the drivetrain's (I5); "
        "2 is the common rule (touch it, own it).",
    ),
)

OUTPUTS = (
    Output(
        "surface_speed",
        "Surface speed",
        "speed",
        "ft/s",
        equation="(I2)",
        help="v_s = ω_r·d/2 at free speed.",
    ),
    Output(
        "speed_ratio",
        "Surface / drive speed",
        equation="(I3)",
        help="k = v_s/v_d: how much faster the rollers' surface runs than the robot drives.",
    ),
    Output(
        "pull_time",
        "Time to pull the piece",
        "time",
        "s",
        equation="(I4)",
        help="t = L/v_s: the piece at the surface speed from first touch (no slip, no load, no spin-up).",
    ),
    Output(
        "recommended_ratio",
        "Reduction for the target",
        equation="(I5)",
        help="G* = ω̃f·d/(2·k*·v_d): the reduction at which the surface runs at the target multiple.",
    ),
    Output(
        "target_roller_speed",
        "Roller speed for the target",
        "angular_speed",
        "rpm",
        equation="(I5)",
        help="ω* = 2·k*·v_d/d: every motor's reduction G* gives the rollers this free speed.",
    ),
    Output("roller_speed", "Roller free speed", "angular_speed", "rpm", equation="(I1)", help="ω_r = ω̃f/G."),
    Output(
        "roller_torque_at_limit",
        "Roller torque at the limit",
        "torque",
        "N*m",
        equation="(I6)",
        help="τ_r = G·τ_lim: the motors' torque at rest with the current limits (C5), through G and η.",
    ),
    Output(
        "pull_force_at_limit",
        "Surface pull at the limit",
        "force",
        "lbf",
        equation="(I7)",
        help="F = 2·τ_r/d: the force the rollers' surface can pull with at rest (the grip permitting).",
    ),
)

TABLES = (
    Table(
        "ratios",
        "Reduction for the target, every motor (most torque first)",
        (
            Column("motor", "Motor", width=30),
            Column("data", "Data", width=7),
            Column("ratio", "G*", width=8),
            Column("torque", "τ at limit", "torque", "N*m", width=10),
            Column("pull_force", "Pull", "force", "lbf", width=8),
        ),
    ),
)


def recommended_ratio(free_speed: float, d: float, k_target: float, v_drive: float) -> float:
    return free_speed * d / (2 * k_target * v_drive)  # (I5)


def compute(v) -> Result:
    d, v_d, n, eta = v["roller_diameter"], v["drivetrain_speed"], v["motor_count"], v["efficiency"]
    k_target = v["target_speed_ratio"]
    _, note = lookup(v["motor"], v["source"])
    s, _, _, tau_lim = limited_system(v, v["motor"], n, eta)
    warnings = [note] if note else []
    if v["voltage"] > 1.25 * s.motor.v_spec:
        warnings.append(
            f"{s.motor.name} is specified at {s.motor.v_spec:.3g} V: at {v['voltage']:.3g} V its data are "
            f"scaled up {v['voltage'] / s.motor.v_spec:.3g}× (eqs. 1-4), beyond its rating."
        )
    if tau_lim <= 0:
        field = "stator_current_limit" if "stator_limit" in v["effects"] else "supply_current_limit"
        raise InputError(field, f"leaves {s.motor.name} at or below its free current at rest: no torque")
    G = v["ratio"]
    w_r = s.free_speed / G  # (I1)
    v_s = w_r * d / 2  # (I2)
    tau_r = G * tau_lim  # (I6)
    values = {
        "surface_speed": v_s,
        "speed_ratio": v_s / v_d,  # (I3)
        "pull_time": v["pull_distance"] / v_s,  # (I4)
        "recommended_ratio": recommended_ratio(s.free_speed, d, k_target, v_d),
        "target_roller_speed": 2 * k_target * v_d / d,  # (I5)
        "roller_speed": w_r,
        "roller_torque_at_limit": tau_r,
        "pull_force_at_limit": 2 * tau_r / d,  # (I7)
    }
    rows = []
    for name in motor_names():
        sm, _, _, t_lim = limited_system(v, name, n, eta)
        if t_lim <= 0:  # no torque at rest with these limits: nothing to rank
            continue
        G_star = recommended_ratio(sm.free_speed, d, k_target, v_d)  # (I5)
        rows.append(
            {
                "motor": name,
                "data": SOURCE_NAMES.get(sm.motor.source, sm.motor.source),
                "ratio": G_star,
                "torque": G_star * t_lim,  # (I6)
                "pull_force": 2 * G_star * t_lim / d,  # (I7)
            }
        )
    rows.sort(key=lambda r: r["torque"], reverse=True)
    return Result(values, warnings, tables={"ratios": rows})


CALCULATOR = Calculator(
    id="intake",
    title="Intake",
    summary="Roller intake: surface speed against the drivetrain's, time to pull a game piece in, and the "
    "reduction for a target speed ratio for every motor, ranked by torque at the current limit.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="issue 31 (I1)-(I7)",
    tables=TABLES,
)
