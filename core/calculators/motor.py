"""Seed section 1: the motor system (eqs. 1-10) and its maximum-efficiency point (Appendix A).

With a current limit or battery sag (effects, core.sim.motor_limits, the same definitions as the
elevator, arm, flywheel and drivetrain) the curves are the limited motor's, traced over speed:
per motor (E1)-(E3) give the duty u and stator current I at back-EMF E = ω/Kv, and the torque at the
gearbox output is the seed's (7), (9) with all n motors:
    τ(ω) = K_T·(n·I(ω/Kv) − ĩf)                                                         (L1)
(K_T after η). Under a stator limit τ is constant, K_T·(n·I_st − ĩf), up to the speed where the
limit lets go; then the unlimited line (8). The operating point at a torque τ is the fastest speed
with τ(ω) = τ (τ never rises with ω). Electrical power is drawn from the battery's EMF: V_b·n·u·I.
"""

from __future__ import annotations

from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field
from ..motors import lookup, motor_fields, system_from
from ..sim import motor_limits
from ..sim.effects import Effects

EFFECTS = Effects(*motor_limits.electrical_effects())

FIELDS = motor_fields() + (
    Field(
        "torque",
        "Operating torque",
        "torque",
        "N*m",
        default=0.05,  # under every motor's stall torque (REV HD Hex: 0.105 N*m): any motor chosen solves
        min=0,
        help="Torque τ at the gearbox output for the operating point (eqs. 8-10).",
    ),
    EFFECTS.field(
        "stator_limit, supply_limit (per motor current limits of the controller); battery_sag "
        "(the voltage field is the battery at rest; the bus sags with the total supply current). "
        "The curves and the operating point are then the limited motor's."
    ),
    *EFFECTS.fields(),
)

OUTPUTS = (
    Output(
        "free_speed",
        "Free speed",
        "angular_speed",
        "rpm",
        help="Motor free speed scaled to the voltage, ω̃f = ωf·V/V_spec (eq. 1).",
        equation="(1)",
    ),
    Output(
        "stall_torque",
        "Stall torque",
        "torque",
        "N*m",
        help="All motors together at the gearbox output, after its efficiency η (eq. 2).",
        equation="(2)",
    ),
    Output("stall_current", "Stall current", "current", "A", help="All motors together.", equation="(4)"),
    Output("free_current", "Free current", "current", "A", help="All motors together.", equation="(3)"),
    Output(
        "peak_power",
        "Peak power",
        "power",
        "W",
        help="At half stall torque, gearbox included (eq. 6).",
        equation="(6)",
    ),
    Output(
        "kt",
        "Kt at gearbox output (after η)",
        "torque_constant",
        "N*m/A",
        help="K_T (7) = τ̃s/(ĩs − ĩf): output torque per amp above the free current, η included (motor's own: K_T/η).",
        equation="(7)",
    ),
    Output(
        "max_efficiency",
        "Max efficiency",
        "dimensionless",
        "%",
        help="Highest output power over electrical power, motors and gearbox together (Appendix A).",
        equation="(10), (91)",
    ),
    Output(
        "max_efficiency_torque",
        "Torque at max efficiency",
        "torque",
        "N*m",
        help="τ at the efficiency peak, τ̃s·√ĩf/(√ĩf + √ĩs) (91).",
        equation="(91)",
    ),
    Output(
        "max_efficiency_speed",
        "Speed at max efficiency",
        "angular_speed",
        "rpm",
        help="Speed (8) at the max-efficiency torque (91).",
        equation="(8), (91)",
    ),
    Output(
        "max_efficiency_current",
        "Current at max efficiency",
        "current",
        "A",
        help="Current (9), all motors, at the max-efficiency torque (91).",
        equation="(9), (91)",
    ),
    Output(
        "speed",
        "Speed at torque",
        "angular_speed",
        "rpm",
        help="Speed at the operating torque on the line (8); with a limit or sag, the limited curve (L1).",
        equation="(8)",
    ),
    Output(
        "current",
        "Current at torque",
        "current",
        "A",
        help="Stator current of all motors at the operating torque (9).",
        equation="(9)",
    ),
    Output(
        "output_power",
        "Output power at torque",
        "power",
        "W",
        help="Operating torque times its speed (8).",
        equation="(8)",
    ),
    Output(
        "efficiency_at_torque",
        "Efficiency at torque",
        "dimensionless",
        "%",
        help="Output power over electrical power at the operating torque, gearbox included (10).",
        equation="(10)",
    ),
    Output(
        "supply_current",
        "Supply current at torque",
        "current",
        "A",
        help="All motors, stator current × duty (with a limit or sag).",
        equation="(E4)",
    ),
    Output(
        "bus_voltage",
        "Bus voltage at torque",
        "voltage",
        "V",
        help="Battery voltage minus the sag at the operating point (battery_sag).",
        equation="(E4)",
    ),
    Output(
        "limited_stall_torque",
        "Stall torque, limited",
        "torque",
        "N*m",
        help="All motors at rest with the current limits and sag: K_T·(n·I(0) − ĩf) (L1).",
        equation="(7), (9)",
    ),
    Output(
        "limited_peak_power",
        "Peak power, limited",
        "power",
        "W",
        help="Largest τ(ω)·ω of the limited curve (L1).",
        equation="(7), (9)",
    ),
    Output(
        "limit_release_speed",
        "Speed where the limits let go",
        "angular_speed",
        "rpm",
        help="Above it the duty is 1: no current limit binds and the unlimited line (8) holds.",
        equation="(E5)",
    ),
)


def compute(v) -> Result:
    if v["effects"]:
        return compute_limited(v)
    return compute_free(v)


def limited_curve(v, m):
    """τ(ω) (L1) and (u, I)(ω) of the limited motor, and the speed at which its torque is zero."""
    on, n = v["effects"], m.count
    motor, _ = lookup(v["motor"], v["source"])
    circuit = motor_limits.circuit_of(motor, v["voltage"], motor_limits.bus_resistance_of(v, on))
    elec, asm = motor_limits.limits(EFFECTS, on, v, circuit)
    Kv = circuit.Kv

    def point(w):
        u, I = elec(w / Kv)
        return m.kt * (n * I - m.free_current), u, I  # (L1)

    # zero torque: n·I = ĩf at full duty (no limit binds that low), I = (V_b − E)/(R + R_bus)
    w_zero = Kv * (circuit.battery_voltage - m.free_current / n * (circuit.R + circuit.bus_resistance))
    return point, circuit, elec, w_zero


def compute_limited(v) -> Result:
    m, warnings = system_from(v)
    on, n, tau = v["effects"], m.count, v["torque"]
    point, circuit, elec, w_zero = limited_curve(v, m)
    tau0, u0, I0 = point(0.0)
    if tau0 <= 0 or w_zero <= 0:
        name = (
            "battery_resistance"
            if w_zero <= 0 or u0 >= 1
            else "stator_current_limit"
            if "stator_limit" in on and I0 >= v["stator_current_limit"] * (1 - 1e-12)
            else "supply_current_limit"
        )
        raise InputError(
            name,
            f"leaves the stalled motors {I0:.4g} A each, not above their free current "
            f"{m.free_current / n:.4g} A: they give no torque",
        )
    if tau > tau0:
        raise InputError(
            "torque", f"is above what the motors give with these limits ({tau0:.4g} N*m at stall)"
        )
    # the fastest speed with τ(ω) ≥ τ: bisection (τ never rises with ω; flat under a stator limit)
    lo, hi = 0.0, w_zero
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if point(mid)[0] >= tau:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * w_zero:
            break
    w = lo
    _, u, I = point(w)
    ws = [w_zero * k / 200 for k in range(201)]
    pts = [point(x) for x in ws]
    powers = [p[0] * x for p, x in zip(pts, ws)]
    k = max(range(len(ws)), key=powers.__getitem__)
    from scipy.optimize import minimize_scalar

    a, b = ws[max(k - 1, 0)], ws[min(k + 1, len(ws) - 1)]
    best = minimize_scalar(
        lambda x: -point(x)[0] * x, bounds=(a, b), method="bounded", options={"xatol": 1e-10 * w_zero}
    )
    # the peak is inside a smooth phase (the optimiser) or where a limit lets go (a kink)
    kinks = [E * circuit.Kv for E in motor_limits.release_emfs(circuit, v, on) if 0 < E * circuit.Kv < w_zero]
    if "stator_limit" in on or "supply_limit" in on:
        kinks.append(motor_limits.full_duty_emf(elec, circuit.battery_voltage) * circuit.Kv)
    peak = max([powers[k], -float(best.fun)] + [point(x)[0] * x for x in kinks])
    Vb, Rb = circuit.battery_voltage, circuit.bus_resistance
    P_in = Vb * n * u * I
    values = {
        **system_values(m),
        "speed": w,
        "current": n * I,
        "supply_current": n * u * I,
        "bus_voltage": Vb - Rb * u * I,
        "output_power": tau * w,
        "efficiency_at_torque": tau * w / P_in if P_in > 0 else 0.0,
        "limited_stall_torque": tau0,
        "limited_peak_power": peak,
    }
    if "stator_limit" in on or "supply_limit" in on:
        values["limit_release_speed"] = kinks[-1]
    taus = [p[0] for p in pts]
    series = {
        "speed": (taus, ws),
        "current": (taus, [n * p[2] for p in pts]),
        "supply current": (taus, [n * p[1] * p[2] for p in pts]),
        "power": (taus, powers),
        "efficiency": (
            [t for t, x in zip(taus, ws) if x > 0],
            [t * x / (Vb * n * p[1] * p[2]) for t, x, p in zip(taus, ws, pts) if x > 0 and p[1] * p[2] > 0],
        ),
    }
    if len(series["efficiency"][0]) != len(series["efficiency"][1]):
        series.pop("efficiency")
    return Result(values, warnings, series)


def system_values(m) -> dict:
    """The motor system's own figures (eqs. 1-7 and Appendix A), with or without limits."""
    t_eff = m.max_efficiency_torque
    return {
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
    }


def compute_free(v) -> Result:
    m, warnings = system_from(v)
    tau = v["torque"]
    if tau > m.stall_torque:
        raise InputError("torque", f"is above the system's stall torque ({m.stall_torque:.4g} N*m)")
    values = {
        **system_values(m),
        "speed": m.speed(tau),
        "current": m.current(tau),
        "output_power": tau * m.speed(tau),
        # (10); at τ = 0 with ĩf = 0 it is 0/0, and its limit is the max-efficiency value
        "efficiency_at_torque": m.efficiency_at(tau) if (tau > 0 or m.free_current > 0) else m.max_efficiency,
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
        Plot(
            "Current vs torque",
            ("current", "supply current"),
            "torque",
            "torque",
            "N*m",
            "current",
            "current",
            "A",
        ),
        Plot("Power vs torque", ("power",), "torque", "torque", "N*m", "output power", "power", "W"),
        Plot(
            "Efficiency vs torque",
            ("efficiency",),
            "torque",
            "torque",
            "N*m",
            "efficiency",
            "dimensionless",
            "%",
        ),
    ),
)
