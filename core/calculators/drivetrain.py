"""Seed section 4: the drivetrain calculator (eqs. 37-42, Appendix C), after JVN's calculator.

G is the total reduction (motor turns per wheel turn); n the number of drive motors, all geared
to the wheels; W̃ the weight resting on the driven wheels. Every relation was re-derived with
sympy (see tests/test_drivetrain.py for hand values):
- wheel slip: the wheels push μ·W̃ at radius d/2, so the motors (after η) give μ·W̃·d/(2G) and,
  by (7)/(9), draw ĩ = μ·W̃·d/(2·K_T·G) + ĩf in all; (39) is that divided by n. Correct as printed.
- (41): the battery, main wiring and the n parallel branches (one per motor, R_br each, carrying
  ĩ/n) are in series, so V_batt − V_min = ĩ·(R_batt + R_main + R_br/n). Correct as printed;
  V_min is therefore the voltage at the motor controllers (the end of each branch), which is
  stricter than measuring it at the distribution panel.
- (42) is (39) solved for G with n·i_slip = i_tot. Correct as printed. It is the *smallest*
  reduction (the fastest gearing) whose wheel-slip current keeps the voltage above V_min; any
  larger reduction slips the wheels with less current. "Maximum" in the seed means fastest.
- Shifting (40): equal wheel force in both gears at v_shift = ωf·r/(G_low + G_high) = v1·v2/(v1+v2),
  confirmed from (100)-(101) with sympy.

Corrections to the seed:
- (37) is written for ω in rev/s; in SI (rad/s) v_free = ω̃f·(d/2)/G.
- The symbol list after (40) reads "v_2 = Gear 1 Free Speed": that is v_1.
- (42) assumes the motors can draw the allowed current i_tot. One model serves forward and
  reverse mode alike: the "Voltage" field V is the most the controllers apply to the motors (as in
  forward mode, where the stall force is τ̃s(V)·G/r), and a controller cannot put out more than
  reaches it through the wiring. By (4) the motors are a resistance R_m = V/ĩs = V_spec/(n·i_s),
  the same at every voltage, so stalled they draw at most
      i_max = min(ĩs(V), i_c),  ĩs(V) = V/R_m,  i_c = V_batt/(R_batt + R_main + R_br/n + R_m),
  ĩs(V) being the stall current at the applied voltage and i_c that of the stalled motors fed the
  full battery through the wiring of (41). (42) holds while i_tot ≤ i_max. Beyond that the battery
  never sags to V_min: the ratio (42) gives would stall the motors before the wheels slip, and
  the fastest ratio that slips them is (42) with i_max in place of i_tot (stall torque equal to
  traction); it is reported, with a warning naming the limit. (The two agree when i_tot = i_max.)
  So the ratio reverse mode returns, fed to forward mode, pushes the same force (traction) at the
  same slip current. This matters for real drives: four NEOs with the default wiring allow
  i_tot = 308 A but stalled draw only 270 A, and (42) as printed gives 4.92 where 5.64 is the
  fastest ratio that slips; two CIMs at 8 V draw at most 177 A stalled, so 11.56, not the 10.49
  a battery-fed stall current of 195 A would give.
"""

from __future__ import annotations

import dataclasses

from ..errors import InputError
from ..model import Calculator, Field, Output, Plot, Result
from ..motors import MotorSystem, motor_fields, system_from
from ..units import format_quantity

MODES = ("forward", "reverse", "shifting")
MODE_LABELS = ("Forward: given ratio", "Reverse: fastest ratio that slips", "Two-speed shifting")


def _drive_motor_fields():
    fields = list(motor_fields(default_motor="Kraken X60", default_count=4))
    for i, f in enumerate(fields):
        if f.name == "motor_count":
            fields[i] = dataclasses.replace(
                f, label="Drive motors (total)",
                help="All motors driving the wheels, both sides together (n in eqs. 39, 41).")
        elif f.name == "voltage":
            fields[i] = dataclasses.replace(
                f, help="Voltage V the controllers apply to the motors; motor data is scaled by V/V_spec "
                        "(eqs. 1-4). Reverse mode: the stalled motors draw at most ĩs at V, and no more "
                        "than the battery can push through the wiring.")
    return tuple(fields)


FIELDS = _drive_motor_fields() + (
    Field("mode", "Calculate", choices=MODES, choice_labels=MODE_LABELS, default="forward",
          help="Forward: speeds and slip current for a ratio (4.1). Reverse: the fastest ratio that "
               "can slip the wheels before the battery sags below the minimum voltage (4.2). "
               "Shifting: the speed at which to change gear (eq. 40)."),
    Field("wheel_diameter", "Wheel diameter", "length", "in", default=4, min=0, min_exclusive=True,
          help="Drive wheel diameter d (worn tread is smaller)."),
    Field("speed_loss", "Speed loss constant", "dimensionless", "", default=0.81, min=0,
          min_exclusive=True, max=1, modes=("forward", "reverse"),
          help="k_SL: real top speed over free speed (JVN uses 0.81 for friction, voltage sag, turning)."),
    Field("ratio", "Gear ratio", "dimensionless", "", default=6.12, min=0, min_exclusive=True,
          modes=("forward",), help="Total reduction G, motor turns per wheel turn."),
    Field("weight", "Weight on driven wheels", "force", "lbf", default=150, min=0, min_exclusive=True,
          modes=("forward", "reverse"),
          help="W̃: the part of the robot's weight resting on driven wheels (all of it for most drives)."),
    Field("friction", "Wheel friction", "dimensionless", "", default=1.1, min=0, min_exclusive=True,
          modes=("forward", "reverse"),
          help="Coefficient of friction μ of the tread on the floor (≈1.0-1.3 for FRC treads on carpet)."),
    Field("battery_voltage", "Battery voltage", "voltage", "V", default=12.7, min=0, min_exclusive=True,
          modes=("reverse",), help="Battery resting (open-circuit) voltage V_batt."),
    Field("min_voltage", "Minimum voltage", "voltage", "V", default=7, min=0, modes=("reverse",),
          help="Lowest voltage allowed at the motor controllers while pushing (eq. 41)."),
    Field("battery_resistance", "Battery resistance", "resistance", "ohm", default=0.015, min=0,
          modes=("reverse",), help="Battery internal resistance R_batt (≈0.015-0.020 Ω for an FRC battery)."),
    Field("main_resistance", "Main wiring resistance", "resistance", "ohm", default=0.002, min=0,
          modes=("reverse",), help="Main leads, breaker and distribution panel, R_main."),
    Field("branch_resistance", "Branch resistance", "resistance", "ohm", default=0.006, min=0,
          modes=("reverse",),
          help="Each motor's branch (breaker, controller, wires), R_br; the n branches are in parallel."),
    Field("low_ratio", "Low gear ratio", "dimensionless", "", default=15, min=0, min_exclusive=True,
          modes=("shifting",), help="Reduction G in low (pushing) gear."),
    Field("high_ratio", "High gear ratio", "dimensionless", "", default=6, min=0, min_exclusive=True,
          modes=("shifting",), help="Reduction G in high (fast) gear."),
)

OUTPUTS = (
    Output("max_ratio", "Fastest ratio that slips", "dimensionless", "",
           help="Smallest reduction G_slip whose slip current keeps the voltage above V_min (42), "
                "or, if the motors cannot draw that much, the fastest that slips the wheels at all."),
    Output("total_current", "Allowed total current", "current", "A",
           help="Total current at which the motors see the minimum voltage (41)."),
    Output("free_speed", "Free speed", "speed", "ft/s", help="Top speed with no losses (37)."),
    Output("adjusted_speed", "Adjusted speed", "speed", "ft/s",
           help="Expected real top speed, free speed times the speed-loss constant (38)."),
    Output("slip_current", "Slip current per motor", "current", "A",
           help="Current each motor draws when the wheels just slip (39)."),
    Output("slip_current_total", "Slip current, all motors", "current", "A"),
    Output("pushing_force", "Pushing force", "force", "lbf",
           help="Most the drive can push: wheel traction, or the motors' stall force if lower."),
    Output("low_free_speed", "Low gear free speed", "speed", "ft/s"),
    Output("high_free_speed", "High gear free speed", "speed", "ft/s"),
    Output("shift_speed", "Shift speed", "speed", "ft/s",
           help="Speed at which both gears push equally hard: shift up above it (40)."),
)


def free_speed(m: MotorSystem, d, G):
    return m.free_speed * (d / 2) / G  # (37) in SI


def slip_current_total(m: MotorSystem, W, mu, d, G):
    """n·i_slip: all motors together when the wheels just slip, (39) times n."""
    return W * mu * d / (2 * m.kt * G) + m.free_current


def max_ratio(m: MotorSystem, W, mu, d, i_tot):
    return mu * d * W / (2 * m.kt * (i_tot - m.free_current))  # (42)


def circuit_stall_current(m: MotorSystem, V_batt, R):
    """Current of the stalled motors fed the full battery through the wiring: they are a
    resistance R_m = V/ĩs by (4)."""
    return V_batt / (R + m.voltage / m.stall_current)


def total_current(V_batt, V_min, R_batt, R_main, R_br, n):
    return (V_batt - V_min) / (R_batt + R_main + R_br / n)  # (41)


def shift_speed(v1, v2):
    return v1 * v2 / (v1 + v2)  # (40)


def force_curve(m: MotorSystem, d, G, points=60):
    """Wheel force over speed, (99): τ̃s·G/r·(1 − v·G/(r·ω̃f)), from stall to free speed."""
    r = d / 2
    v_free = free_speed(m, d, G)
    vs = [v_free * k / points for k in range(points + 1)]
    return vs, [m.stall_torque * G / r * (1 - v / v_free) for v in vs]


def compute(v) -> Result:
    m, warnings = system_from(v)
    mode, d, k_SL = v["mode"], v["wheel_diameter"], v["speed_loss"]
    values: dict = {}
    series: dict = {}
    if mode == "shifting":
        G1, G2 = v["low_ratio"], v["high_ratio"]
        v1, v2 = free_speed(m, d, G1), free_speed(m, d, G2)
        values.update(low_free_speed=v1, high_free_speed=v2, shift_speed=shift_speed(v1, v2))
        if G1 == G2:
            warnings.append("Both gears are the same ratio: they push equally at every speed.")
        elif G1 < G2:
            warnings.append("The low gear is the faster one here; the shift speed is the same either way.")
        series["low gear"] = force_curve(m, d, G1)
        series["high gear"] = force_curve(m, d, G2)
        return Result(values, warnings, series)

    W, mu = v["weight"], v["friction"]
    traction = mu * W
    stall_torque = m.stall_torque  # at the applied voltage; in reverse mode also capped by the wiring
    if mode == "reverse":
        n = m.count
        V_batt, V_min = v["battery_voltage"], v["min_voltage"]
        if V_min >= V_batt:
            raise InputError("min_voltage", f"must be below the battery voltage ({V_batt:.4g} V)")
        R = v["battery_resistance"] + v["main_resistance"] + v["branch_resistance"] / n
        if R <= 0:
            raise InputError("battery_resistance", "the circuit needs some resistance "
                                                   "(battery, main or branch) to limit the current")
        i_tot = total_current(V_batt, V_min, v["battery_resistance"], v["main_resistance"],
                              v["branch_resistance"], n)
        if i_tot <= m.free_current:
            raise InputError("min_voltage", f"the allowed current {i_tot:.4g} A is not above the motors' "
                                            f"free current {m.free_current:.4g} A: lower the minimum "
                                            f"voltage or the resistances")
        i_c = circuit_stall_current(m, V_batt, R)
        i_max = min(m.stall_current, i_c)  # most the stalled motors draw (module docstring)
        if i_max <= m.free_current:
            raise InputError("battery_voltage", f"stalled through this wiring the motors draw only "
                                                f"{i_c:.4g} A, not above their free current "
                                                f"{m.free_current:.4g} A: they cannot push")
        if i_tot <= i_max:
            G = max_ratio(m, W, mu, d, i_tot)  # (42)
        else:
            # The motors cannot draw i_tot: (42)'s ratio stalls them before the wheels slip. The
            # fastest ratio that slips at all has the most they draw stalled producing the traction.
            G = max_ratio(m, W, mu, d, i_max)  # (42) with i_max
            if m.stall_current <= i_c:
                limit = (f"at {m.voltage:.3g} V (the Voltage field) the stalled motors draw at most "
                         f"{m.stall_current:.4g} A")
            else:
                limit = (f"stalled through this wiring they draw at most {i_c:.4g} A and the voltage "
                         f"at the controllers stays above {V_batt - i_c * R:.3g} V")
            warnings.append(f"The motors cannot draw the allowed {i_tot:.4g} A at the minimum voltage: "
                            f"{limit}. The ratio shown is the fastest at which that current still "
                            f"slips the wheels.")
        if m.voltage > V_batt:
            warnings.append(f"The Voltage field ({m.voltage:.3g} V) is above the battery's "
                            f"{V_batt:.3g} V: the controllers cannot apply it, so the free speed "
                            f"shown is not reached.")
        values.update(total_current=i_tot, max_ratio=G)
        stall_torque = m.kt * (i_max - m.free_current)  # (9) inverted, at the stall current reached
    else:
        G = v["ratio"]

    i_slip = slip_current_total(m, W, mu, d, G)
    v_free = free_speed(m, d, G)
    stall_force = stall_torque * G / (d / 2)  # (98) at stall
    values.update(
        free_speed=v_free,
        adjusted_speed=v_free * k_SL,  # (38)
        slip_current=i_slip / m.count,  # (39)
        slip_current_total=i_slip,
        pushing_force=min(traction, stall_force),
    )
    if stall_force < traction * (1 - 1e-12):  # (not when equal but for rounding: reverse mode's limit)
        warnings.append(f"The motors stall before the wheels slip: they push "
                        f"{format_quantity(stall_force, 'lbf', 'force')} but traction allows "
                        f"{format_quantity(traction, 'lbf', 'force')} (the slip current is not reached).")
    series["motor force"] = force_curve(m, d, G)
    series["traction limit"] = ([0.0, v_free], [traction, traction])
    return Result(values, warnings, series)


CALCULATOR = Calculator(
    id="drivetrain",
    title="Drivetrain",
    summary="Top speed, wheel-slip current and shifting for a robot drive.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="4",
    exports={"ratio_finder": {"target_ratio": "max_ratio"}},  # parts for the fastest slipping ratio
    plots=(
        Plot("Force at the wheels vs speed", ("motor force", "traction limit", "low gear", "high gear"),
             "speed", "speed", "ft/s", "force", "force", "lbf"),
    ),
)
