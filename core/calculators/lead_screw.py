"""Seed section 3: the lead screw calculator (eqs. 29-36, Appendix B).

Power-screw torques from Shigley §8-2 with the thread angle (normal force raised by sec α):
    T_R = F·dm/2 · (l + π·μ·dm·sec α) / (π·dm − μ·l·sec α),
    T_L = F·dm/2 · (π·μ·dm·sec α − l) / (π·dm + μ·l·sec α),
with lead l = n·p and α half the thread angle; multiplying through by cos α gives (31), (32).
Each form was re-derived from the force balance on the thread with sympy.

Departures from / corrections to the seed:
- (31)-(33) write d_p, a symbol the seed never defines; it is the mean diameter d_m of (30).
- (29) is written for ω in rev/s; in SI (rad/s) v = ω·n·p/(2π) = ω·r_eq.
- A screw whose (31) denominator π·dm·cos α − μ·l is at or below zero cannot be driven (friction
  locks it however hard it is turned): it is reported as such, with no raise torque, not as a
  negative or infinite one; its efficiency (the limit of (33)) is 0.
- (33) is evaluated in its closed form (independent of F), so a zero load still has an efficiency.
- Backdrivable exactly when T_L < 0 (seed), i.e. μ < l·cos α/(π·dm); the sign is taken from the
  numerator of (32), which decides it without the F·dm/2 factor's rounding.

Outputs beyond the seed's equations:
    P_R = T_R·ω                    power to raise the load at the screw speed ω (rad/s)  (LS1)
"""

from __future__ import annotations

import math

from ..constants import INCH
from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field

FIELDS = (
    Field(
        "diameter",
        "Screw diameter",
        "length",
        "in",
        default=0.5,
        min=0,
        min_exclusive=True,
        help="Major (outside) diameter d of the thread.",
    ),
    Field(
        "pitch",
        "Pitch",
        "length",
        "in",
        default=0.1,
        min=0,
        min_exclusive=True,
        help="Axial distance p between neighbouring threads (1/TPI); 1/2-10 Acme has p = 0.1 in.",
    ),
    Field(
        "starts",
        "Starts",
        integer=True,
        default=1,
        min=1,
        max=16,
        help="Number of thread starts n; the lead (travel per turn) is n·p.",
    ),
    Field(
        "thread_angle",
        "Thread angle",
        "angle",
        "deg",
        default=29,
        min=0,
        max=180,
        max_exclusive=True,
        help="Full included thread angle 2α: 29° Acme, 30° metric trapezoidal, 0° square, 60° V thread.",
    ),
    Field(
        "friction",
        "Thread friction",
        "dimensionless",
        "",
        default=0.15,
        min=0,
        help="Coefficient of friction μ between screw and nut (≈0.1-0.2 steel on bronze or plastic).",
    ),
    Field(
        "force",
        "Axial load",
        "force",
        "lbf",
        default=100,
        min=0,
        help="Axial force F the nut carries (e.g. the weight being lifted).",
    ),
    Field(
        "rotational_speed",
        "Screw speed",
        "angular_speed",
        "rpm",
        default=300,
        min=0,
        help="Rotational speed ω of the screw (eq. 29).",
    ),
)

OUTPUTS = (
    Output(
        "lead",
        "Lead (travel per turn)",
        "length",
        "in",
        help="Travel of the nut per screw turn: starts × pitch, l = n·p (29).",
        equation="(29)",
    ),
    Output(
        "mean_diameter",
        "Mean diameter",
        "length",
        "in",
        help="Diameter halfway up the thread, d_m = d − p/2 (30).",
        equation="(30)",
    ),
    Output(
        "drivable",
        "Can be driven to raise",
        help="Whether any torque raises the load: the denominator of (31), π·d_m·cos α − μ·l, is positive.",
        equation="(31)",
    ),
    Output(
        "raise_torque",
        "Raise torque",
        "torque",
        "N*m",
        help="Torque to raise the load against thread friction, from the force balance on the thread (31).",
        equation="(31)",
    ),
    Output(
        "lower_torque",
        "Lower torque",
        "torque",
        "N*m",
        help="Torque to lower the load (32); negative means the load turns the screw by itself.",
        equation="(32)",
    ),
    Output(
        "backdrivable",
        "Backdrivable",
        help="True when the load alone turns the screw: T_L < 0, i.e. μ < l·cos α/(π·d_m) (32).",
        equation="(32)",
    ),
    Output(
        "efficiency",
        "Efficiency",
        "dimensionless",
        "%",
        help="Raise torque without friction ÷ raise torque with it; independent of the load (33).",
        equation="(33)",
    ),
    Output(
        "linear_speed",
        "Linear speed",
        "speed",
        "in/s",
        help="Nut speed: screw speed × lead, v = ω·n·p/(2π) with ω in rad/s (29).",
        equation="(29)",
    ),
    Output(
        "raise_power",
        "Power to raise",
        "power",
        "W",
        help="Raise torque × screw speed, P = T_R·ω (LS1).",
        equation="(LS1)",
    ),
    Output(
        "equivalent_radius",
        "Equivalent radius",
        "length",
        "in",
        help="Spool radius with the same travel per turn, n·p/(2π); send it to the gear-ratio tab (34).",
        equation="(34)",
    ),
    Output(
        "equivalent_raise_load",
        "Equivalent raise load",
        "force",
        "lbf",
        help="Raise torque ÷ equivalent radius: the load a spool would carry for the same work (35).",
        equation="(35)",
    ),
    Output(
        "equivalent_lower_load",
        "Equivalent lower load",
        "force",
        "lbf",
        help="Lower torque ÷ equivalent radius (36).",
        equation="(36)",
    ),
)


def mean_diameter(d, p):
    return d - p / 2  # (30)


def raise_denominator(d_m, l, mu, cos_alpha):
    """Denominator of (31); at or below zero the screw cannot be driven."""
    return math.pi * d_m * cos_alpha - mu * l


def raise_torque(F, d_m, l, mu, cos_alpha):
    return (
        F * d_m / 2 * (math.pi * mu * d_m + l * cos_alpha) / raise_denominator(d_m, l, mu, cos_alpha)
    )  # (31)


def lower_numerator(d_m, l, mu, cos_alpha):
    """Numerator of (32): its sign is the sign of T_L (the denominator is always positive)."""
    return math.pi * mu * d_m - l * cos_alpha


def lower_torque(F, d_m, l, mu, cos_alpha):
    return F * d_m / 2 * lower_numerator(d_m, l, mu, cos_alpha) / (math.pi * d_m * cos_alpha + mu * l)  # (32)


def efficiency(d_m, l, mu, cos_alpha):
    """(33) = T_R(μ=0)/T_R = F·l/(2π·T_R), in closed form; 0 for a screw that cannot be driven."""
    den = raise_denominator(d_m, l, mu, cos_alpha)
    if den <= 0:
        return 0.0
    return l / (math.pi * d_m) * den / (math.pi * mu * d_m + l * cos_alpha)


def friction_sweep(F, d_m, l, mu, cos_alpha, points=60):
    """(31)-(33) over friction from 0 to twice the entered μ (at least 0.3), stopping short of
    the locking friction π·dm·cos α/l where (31) has no value: how sensitive the screw is to μ."""
    mu_lock = math.pi * d_m * cos_alpha / l
    top = max(2 * mu, 0.3)
    if top >= mu_lock:
        top = 0.95 * mu_lock
    mus = [top * k / points for k in range(points + 1)]
    return {
        "efficiency": (mus, [efficiency(d_m, l, m, cos_alpha) for m in mus]),
        "raise torque": (mus, [raise_torque(F, d_m, l, m, cos_alpha) for m in mus]),
        "lower torque": (mus, [lower_torque(F, d_m, l, m, cos_alpha) for m in mus]),
    }


def compute(v) -> Result:
    d, p, n = v["diameter"], v["pitch"], v["starts"]
    alpha = v["thread_angle"] / 2  # the seed's α is half the thread angle
    mu, F, omega = v["friction"], v["force"], v["rotational_speed"]
    d_m = mean_diameter(d, p)
    if d_m <= 0:
        raise InputError(
            "pitch", f"must be less than twice the diameter (mean diameter d − p/2 is {d_m / INCH:.4g} in)"
        )
    warnings = []
    if p >= d:
        warnings.append("Pitch is at least the diameter: an Acme thread this coarse has no core left.")
    l = n * p  # lead
    cos_alpha = math.cos(alpha)
    r_eq = l / (2 * math.pi)  # (34)
    values = {
        "lead": l,
        "linear_speed": omega * l / (2 * math.pi),  # (29) in SI
        "mean_diameter": d_m,
        "drivable": raise_denominator(d_m, l, mu, cos_alpha) > 0,
    }
    if values["drivable"]:
        T_R = raise_torque(F, d_m, l, mu, cos_alpha)  # (31)
        values["raise_torque"] = T_R
        values["raise_power"] = T_R * omega
    else:
        limit = math.pi * d_m * cos_alpha / l
        warnings.append(
            f"The screw cannot be driven: with friction {mu:.4g} ≥ {limit:.4g} "
            f"(π·dm·cos α / lead) no torque raises the load."
        )
    T_L = lower_torque(F, d_m, l, mu, cos_alpha)  # (32)
    values["lower_torque"] = T_L
    values["backdrivable"] = lower_numerator(d_m, l, mu, cos_alpha) < 0  # T_L < 0
    values["efficiency"] = efficiency(d_m, l, mu, cos_alpha)  # (33)
    values["equivalent_radius"] = r_eq
    if values["drivable"]:
        values["equivalent_raise_load"] = T_R / r_eq  # (35)
    values["equivalent_lower_load"] = T_L / r_eq  # (36)
    return Result(values, warnings, friction_sweep(F, d_m, l, mu, cos_alpha))


CALCULATOR = Calculator(
    id="lead_screw",
    title="Lead screw",
    summary="Torque, efficiency and backdriving of a power screw.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="3",
    exports={"gear_ratio": {"load": "equivalent_raise_load", "radius": "equivalent_radius"}},
    plots=(
        Plot(
            "Efficiency vs friction",
            ("efficiency",),
            "friction μ",
            "dimensionless",
            "",
            "efficiency",
            "dimensionless",
            "%",
        ),
        Plot(
            "Torques vs friction",
            ("raise torque", "lower torque"),
            "friction μ",
            "dimensionless",
            "",
            "torque",
            "torque",
            "N*m",
        ),
    ),
)
