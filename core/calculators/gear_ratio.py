"""Seed section 2: the mechanism gear-ratio calculator (eqs. 11-28, Appendix A).

G is the reduction: motor turns per output turn. The load F acts at radius r on the output.
Corrections to the seed (each derived again with sympy, see tests/test_gear_ratio.py):
- (14)/(15) are written for speeds in rev/s; in SI (rad/s) v = ω·r, no 2π.
- (17) must use the raw τs (not τ̃s, which already holds η, n and V/V_spec): V_s = V_spec·rF/(τs·η·n·G).
- (23) drops r: ω_load = ω̃f/G·(1 − rF/(τ̃s·G)).
- (26) must use the adjusted free current ĩf (the seed writes i_f): G = rF / (K_T(n·i − ĩf)).
- (28) hard-codes V_spec = 12 V; VEX 393 motors are specified at 7.2 V.

Outputs beyond the seed's equations:
    P_out = F·v_load = F·r·ω_load                                                   (GR1)
    "Load torque ÷ ratio" is τ = r·F/G ((92): τ_manip = G·τ_motor), the torque the motor tab takes
    as its operating torque for the same speed and current (its τ̃s and K_T hold η); the motors
    themselves give r·F/(G·η) in all, each 1/n of that.
"""

from __future__ import annotations

import math

from ..declarations import Calculator, Output, Result
from ..errors import InputError
from ..fields import Field
from ..motors import MotorSystem, motor_fields, system_from

MODES = (
    "max_power",
    "max_efficiency",
    "stall",
    "rotational_speed",
    "linear_speed",
    "current",
    "stall_load",
    "stall_voltage",
    "ratio",
)
MODE_LABELS = (
    "Maximum power",
    "Maximum efficiency",
    "At stall",
    "By rotational speed",
    "By linear speed",
    "By current per motor",
    "By stall load",
    "By stall voltage",
    "Given ratio (forward)",
)

FIELDS = motor_fields() + (
    Field(
        "load",
        "Load",
        "force",
        "lbf",
        default=150,
        min=0,
        min_exclusive=True,
        help="Force F the mechanism works against, at the load radius.",
    ),
    Field(
        "radius",
        "Load radius",
        "length",
        "in",
        default=1,
        min=0,
        min_exclusive=True,
        help="Radius r at which the load acts (spool, pulley or arm length).",
    ),
    Field(
        "mode",
        "Solve for ratio by",
        choices=MODES,
        choice_labels=MODE_LABELS,
        default="max_power",
        help="What the gear ratio is chosen to achieve (section 2.2).",
    ),
    Field(
        "target_rotational_speed",
        "Target speed under load",
        "angular_speed",
        "rpm",
        default=300,
        min=0,
        min_exclusive=True,
        modes=("rotational_speed",),
        help="Output speed wanted while carrying the load (eq. 24).",
    ),
    Field(
        "target_linear_speed",
        "Target linear speed under load",
        "speed",
        "ft/s",
        default=4,
        min=0,
        min_exclusive=True,
        modes=("linear_speed",),
        help="Linear speed at the load radius wanted while carrying the load (eq. 25).",
    ),
    Field(
        "target_current",
        "Target current per motor",
        "current",
        "A",
        default=40,
        min=0,
        min_exclusive=True,
        modes=("current",),
        help="Current each motor may draw at the load (eq. 26).",
    ),
    Field(
        "target_stall_load",
        "Target stall load",
        "force",
        "lbf",
        default=300,
        min=0,
        min_exclusive=True,
        modes=("stall_load",),
        help="Load at which the mechanism should stall (eq. 27).",
    ),
    Field(
        "target_stall_voltage",
        "Target stall voltage",
        "voltage",
        "V",
        default=6,
        min=0,
        min_exclusive=True,
        modes=("stall_voltage",),
        help="Voltage at which the load just stalls the mechanism (eq. 28).",
    ),
    Field(
        "ratio",
        "Gear ratio",
        "dimensionless",
        "",
        default=10,
        min=0,
        min_exclusive=True,
        modes=("ratio",),
        help="Reduction G (motor turns per output turn).",
    ),
)

OUTPUTS = (
    Output(
        "ratio",
        "Gear ratio",
        help="Reduction G (motor turns per output turn) that meets the chosen mode (19)-(28).",
        equation="(19)-(28)",
    ),
    Output(
        "ratio_alternative",
        "Other ratio (less efficient)",
        help="The other root of (24): same loaded speed, motor past half stall, so less efficient.",
        equation="(24)",
    ),
    Output(
        "free_speed",
        "Free speed",
        "angular_speed",
        "rpm",
        help="Adjusted motor free speed divided by the ratio, ω̃f/G (11).",
        equation="(11)",
    ),
    Output(
        "loaded_speed",
        "Loaded speed",
        "angular_speed",
        "rpm",
        help="Free speed × (1 − load/stall load): the motors slow along their torque-speed line (13).",
        equation="(13)",
    ),
    Output(
        "linear_free_speed",
        "Linear free speed",
        "speed",
        "ft/s",
        help="Free speed × load radius, v = ω·r (14, with ω in rad/s).",
        equation="(14)",
    ),
    Output(
        "linear_loaded_speed",
        "Linear loaded speed",
        "speed",
        "ft/s",
        help="Loaded speed × load radius, v = ω·r (15, with ω in rad/s).",
        equation="(15)",
    ),
    Output(
        "current_per_motor",
        "Current per motor",
        "current",
        "A",
        help="Load torque at the motor side over K_T, plus the free current, shared by the n motors (16).",
        equation="(16)",
    ),
    Output(
        "stall_load",
        "Stall load",
        "force",
        "lbf",
        help="Load that stops the mechanism: stall torque (after η) × ratio ÷ radius, τ̃s·G/r (12).",
        equation="(12)",
    ),
    Output(
        "stall_voltage",
        "Stall voltage",
        "voltage",
        "V",
        help="Voltage at which this load just stalls the motors, V_spec·r·F/(τs·η·n·G) (17, corrected).",
        equation="(17)",
    ),
    Output(
        "motor_torque",
        "Load torque ÷ ratio (after η)",
        "torque",
        "N*m",
        help="r·F/G, the motor tab's operating torque (η already off: the motors give r·F/(G·η) in all) (92).",
        equation="(92)",
    ),
    Output(
        "output_power",
        "Output power",
        "power",
        "W",
        help="Load × linear loaded speed, F·r·ω_load (GR1).",
        equation="(GR1)",
    ),
    Output(
        "system_efficiency",
        "Efficiency at load",
        "dimensionless",
        "%",
        help="Output power ÷ electrical power V·i, motors and gearbox together (10).",
        equation="(10)",
    ),
)


def ratio_for_loaded_speed(m: MotorSystem, r: float, F: float, omega: float, field: str):
    """(24) both roots, efficient one first. Product of roots avoids cancellation in the small one."""
    x = 4 * r * F * omega / (m.stall_torque * m.free_speed)
    if x > 1:
        if x - 1 <= 1e-12:  # exactly the peak-power point, lost to rounding
            x = 1.0
        else:
            peak = m.peak_power
            raise InputError(
                field,
                f"unreachable: the load needs {r * F * omega:.4g} W at that speed, "
                f"above the motors' peak power {peak:.4g} W",
            )
    g_high = m.free_speed / (2 * omega) * (1 + math.sqrt(1 - x))  # (24), efficient root
    g_low = (m.free_speed * r * F / (m.stall_torque * omega)) / g_high  # G+·G− = ω̃f·rF/(τ̃s·ω)
    return g_high, g_low


def compute(v) -> Result:
    m, warnings = system_from(v)
    F, r, mode = v["load"], v["radius"], v["mode"]
    alternative = None
    if mode == "max_power":
        G = 2 * r * F / m.stall_torque  # (19)
    elif mode == "max_efficiency":
        if m.free_current <= 0:
            raise InputError("mode", "max efficiency needs a nonzero free current")
        G = r * F / m.stall_torque * (1 + math.sqrt(m.stall_current / m.free_current))  # (20)
    elif mode == "stall":
        G = r * F / m.stall_torque  # (22)
        warnings.append("At stall the mechanism holds the load but does not move.")
    elif mode in ("rotational_speed", "linear_speed"):
        if mode == "rotational_speed":
            field, omega = "target_rotational_speed", v["target_rotational_speed"]
        else:
            field, omega = "target_linear_speed", v["target_linear_speed"] / r  # (25), SI
        G, alternative = ratio_for_loaded_speed(m, r, F, omega, field)
        if alternative == G:
            alternative = None
    elif mode == "current":
        i = v["target_current"]
        n = m.count
        if n * i <= m.free_current:
            raise InputError(
                "target_current", f"must exceed the free current per motor ({m.free_current / n:.4g} A)"
            )
        if n * i >= m.stall_current:
            raise InputError(
                "target_current", f"must be below the stall current per motor ({m.stall_current / n:.4g} A)"
            )
        G = r * F / (m.kt * (n * i - m.free_current))  # (26), with ĩf
    elif mode == "stall_load":
        Fs = v["target_stall_load"]
        if Fs <= F:
            raise InputError("target_stall_load", "must exceed the load, or the mechanism cannot move it")
        G = r * Fs / m.stall_torque  # (27)
    elif mode == "stall_voltage":
        Vs = v["target_stall_voltage"]
        if Vs >= m.voltage:
            raise InputError(
                "target_stall_voltage",
                f"must be below the applied voltage ({m.voltage:.4g} V), or the load never moves",
            )
        mot = m.motor
        G = mot.v_spec * r * F / (mot.stall_torque * m.efficiency * m.count * Vs)  # (28), V_spec of the motor
    else:  # "ratio"
        G = v["ratio"]

    values = forward(m, G, r, F)
    if mode == "stall":  # F_s = F by construction: F/F_s may round to 1 + 1 ulp, never "−3e-17 rpm"
        values.update(loaded_speed=0.0, linear_loaded_speed=0.0, output_power=0.0, system_efficiency=0.0)
    if values["loaded_speed"] < 0:
        warnings.append("The load exceeds the stall load at this ratio: the motors are back-driven.")
    if alternative is not None:
        values["ratio_alternative"] = alternative
        warnings.append(
            f"Two ratios reach this speed: {G:.4g} (efficient, shown) and "
            f"{alternative:.4g} (motor past half stall, less efficient)."
        )
    return Result(values, warnings)


def forward(m: MotorSystem, G: float, r: float, F: float) -> dict:
    """Eqs. (11)-(17) for a given ratio."""
    mot = m.motor
    omega_free = m.free_speed / G  # (11)
    Fs = m.stall_torque * G / r  # (12)
    omega_load = omega_free * (1 - F / Fs)  # (13)
    tau = r * F / G  # the load torque referred through the ratio; K_T (7) holds η, so (9) takes it
    current_total = tau / m.kt + m.free_current
    values = {
        "ratio": G,
        "free_speed": omega_free,
        "loaded_speed": omega_load,
        "linear_free_speed": omega_free * r,  # (14) in SI
        "linear_loaded_speed": omega_load * r,  # (15) in SI
        "current_per_motor": current_total / m.count,  # (16)
        "stall_load": Fs,
        "stall_voltage": mot.v_spec * r * F / (mot.stall_torque * m.efficiency * m.count * G),  # (17)
        "motor_torque": tau,
        "output_power": F * omega_load * r,
        "system_efficiency": max(0.0, F * omega_load * r) / (m.voltage * current_total),
    }
    return values


CALCULATOR = Calculator(
    id="gear_ratio",
    title="Gear ratio",
    summary="Pick the reduction for a mechanism lifting or pushing a load.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="2",
    exports={"ratio_finder": {"target_ratio": "ratio"}},  # which parts give that reduction
)
