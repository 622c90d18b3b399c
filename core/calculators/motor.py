"""Seed section 1: the motor system (eqs. 1-10) and its maximum-efficiency point (Appendix A)."""

from __future__ import annotations

from ..errors import InputError
from ..model import Calculator, Field, Output, Plot, Result
from ..motors import motor_fields, system_from

FIELDS = motor_fields() + (
    Field("torque", "Operating torque", "torque", "N*m", default=0.2, min=0,
          help="Torque τ at the gearbox output for the operating point (eqs. 8-10)."),
)

OUTPUTS = (
    Output("free_speed", "Free speed", "angular_speed", "rpm"),
    Output("stall_torque", "Stall torque", "torque", "N*m",
           help="All motors together at the gearbox output, after its efficiency η (eq. 2)."),
    Output("stall_current", "Stall current", "current", "A", help="All motors together."),
    Output("free_current", "Free current", "current", "A", help="All motors together."),
    Output("peak_power", "Peak power", "power", "W", help="At half stall torque, gearbox included (eq. 6)."),
    Output("kt", "Kt at gearbox output (after η)", "torque_constant", "N*m/A",
           help="K_T of eq. (7), τ̃s/(ĩs − ĩf): gearbox-output torque per amp of total current above "
                "the free current. It includes the gearbox efficiency η; the motor's own constant is K_T/η."),
    Output("max_efficiency", "Max efficiency", "dimensionless", "%",
           help="Highest output power over electrical power, motors and gearbox together (Appendix A)."),
    Output("max_efficiency_torque", "Torque at max efficiency", "torque", "N*m"),
    Output("max_efficiency_speed", "Speed at max efficiency", "angular_speed", "rpm"),
    Output("max_efficiency_current", "Current at max efficiency", "current", "A"),
    Output("speed", "Speed at torque", "angular_speed", "rpm"),
    Output("current", "Current at torque", "current", "A"),
    Output("output_power", "Output power at torque", "power", "W"),
    Output("efficiency_at_torque", "Efficiency at torque", "dimensionless", "%",
           help="Output power over electrical power at the operating torque, gearbox included (10)."),
)


def compute(v) -> Result:
    m, warnings = system_from(v)
    tau = v["torque"]
    if tau > m.stall_torque:
        raise InputError("torque", f"is above the system's stall torque ({m.stall_torque:.4g} N*m)")
    t_eff = m.max_efficiency_torque
    values = {
        "free_speed": m.free_speed,
        "stall_torque": m.stall_torque,
        "stall_current": m.stall_current,
        "free_current": m.free_current,
        "peak_power": m.peak_power,
        "kt": m.kt,
        "max_efficiency": m.max_efficiency,
        "max_efficiency_torque": t_eff,
        "max_efficiency_speed": m.speed(t_eff),
        "max_efficiency_current": m.current(t_eff),
        "speed": m.speed(tau),
        "current": m.current(tau),
        "output_power": tau * m.speed(tau),
        # (10); at τ = 0 with ĩf = 0 it is 0/0, and its limit is the max-efficiency value
        "efficiency_at_torque": m.efficiency_at(tau) if (tau > 0 or m.free_current > 0)
        else m.max_efficiency,
    }
    # motor curve: (8), (9), output power and (10) over the torque range, for the plots
    taus = [m.stall_torque * k / 100 for k in range(101)]
    series = {
        "speed": (taus, [m.speed(t) for t in taus]),
        "current": (taus, [m.current(t) for t in taus]),
        "power": (taus, [t * m.speed(t) for t in taus]),
        "efficiency": (taus[1:], [m.efficiency_at(t) for t in taus[1:]]),
    }
    return Result(values, warnings, series)


CALCULATOR = Calculator(
    id="motor",
    title="Motor",
    summary="Motor system: n motors at voltage V through a gearbox of efficiency η.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="1",
    plots=(
        Plot("Speed vs torque", ("speed",), "torque", "torque", "N*m", "speed", "angular_speed", "rpm"),
        Plot("Current vs torque", ("current",), "torque", "torque", "N*m", "current", "current", "A"),
        Plot("Power vs torque", ("power",), "torque", "torque", "N*m", "output power", "power", "W"),
        Plot("Efficiency vs torque", ("efficiency",), "torque", "torque", "N*m", "efficiency", "dimensionless", "%"),
    ),
)
