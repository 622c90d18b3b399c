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

Forward mode, effects (core.sim.motor_limits, the same definitions as the elevator, arm and
flywheel): `stator_limit` caps each motor's current, hence the pushing force (D1); `supply_limit`
caps stator current × duty; `battery_sag` feeds the motors from the battery voltage through the
circuit of (41) (per motor R_bus = n·(R_batt + R_main) + R_br) and reports the voltage at the
controllers while pushing (D2). See `pushing`:
    I₀ = I(E = 0);  F_stall = K_T·(n·I₀ − ĩf)·G/r;  pushing force = min(μ·W̃, F_stall)       (D1)
    supply current u·I per motor, battery n·u·I, V_controllers = V_b − R_bus·u·I             (D2)
with I the operating current per motor (ĩ_slip/n (39) if the wheels slip, else I₀) and u its duty.
Reverse mode's "fastest that slips at all" (the motors cannot draw i_tot) is (42) with i_max, as above.

Reverse mode with the same effects inverts (D1)-(D2) (derived with sympy): I₀ does not depend on G,
so F_stall ≥ μ·W̃ ⇔ G ≥ μ·W̃·r/(K_T·(n·I₀ − ĩf)), (42) with n·I₀; the battery current while
slipping is n·min(ĩ_slip/n, I_sup) (supply_limit) or ĩ_slip, and V_b − R_bus·(that)/n ≥ V_min ⇔
(that) ≤ i_tot of (41) (R_bus = n·R₄₁). So
    budget binds unless supply_limit is on with n·I_sup ≤ i_tot (then V ≥ V_min at any ratio)     (R1)
    i_max = n·I₀ with battery_sag (it is i_c at full duty), else min(n·I₀, i_c)                   (R2)
    G = (42) with min(i_tot, i_max) if the budget binds, else with i_max                          (R3)
The ratio fed to forward mode with the same effects slips the wheels (pushing force = traction)
with the battery current within i_tot (with sag: the controllers at V_min when the budget binds).
n·I₀ ≤ ĩf (no ratio pushes) is refused naming the limit's field.
"""

from __future__ import annotations

import dataclasses

from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field
from ..motors import MotorSystem, motor_fields, system_from
from ..sim import motor_limits
from ..sim.effects import Effect, Effects, nothing
from ..units import format_quantity

MODES = ("forward", "reverse", "shifting")
MODE_LABELS = ("Forward: given ratio", "Reverse: fastest ratio that slips", "Two-speed shifting")


def _drive_motor_fields():
    fields = list(motor_fields(default_motor="Kraken X60", default_count=4))
    for i, f in enumerate(fields):
        if f.name == "motor_count":
            fields[i] = dataclasses.replace(
                f,
                label="Drive motors (total)",
                help="All motors driving the wheels, both sides together (n in eqs. 39, 41).",
            )
        elif f.name == "voltage":
            fields[i] = dataclasses.replace(
                f,
                help="Voltage V the controllers apply to the motors; motor data is scaled by V/V_spec "
                "(eqs. 1-4). Reverse mode: the stalled motors draw at most ĩs at V, and no more "
                "than the battery can push through the wiring.",
            )
    return tuple(fields)


FIELDS = _drive_motor_fields() + (
    Field(
        "mode",
        "Calculate",
        choices=MODES,
        choice_labels=MODE_LABELS,
        default="forward",
        help="Forward: speeds and slip current for a ratio (4.1). Reverse: the fastest ratio that "
        "can slip the wheels before the battery sags below the minimum voltage (4.2). "
        "Shifting: the speed at which to change gear (eq. 40).",
    ),
    Field(
        "wheel_diameter",
        "Wheel diameter",
        "length",
        "in",
        default=4,
        min=0,
        min_exclusive=True,
        help="Drive wheel diameter d (worn tread is smaller).",
    ),
    Field(
        "speed_loss",
        "Speed loss constant",
        "dimensionless",
        "",
        default=0.81,
        min=0,
        min_exclusive=True,
        max=1,
        modes=("forward", "reverse"),
        help="k_SL: real top speed over free speed (JVN uses 0.81 for friction, voltage sag, turning).",
    ),
    Field(
        "ratio",
        "Gear ratio",
        "dimensionless",
        "",
        default=6.12,
        min=0,
        min_exclusive=True,
        modes=("forward",),
        help="Total reduction G, motor turns per wheel turn.",
    ),
    Field(
        "weight",
        "Weight on driven wheels",
        "force",
        "lbf",
        default=150,
        min=0,
        min_exclusive=True,
        modes=("forward", "reverse"),
        help="W̃: the part of the robot's weight resting on driven wheels (all of it for most drives).",
    ),
    Field(
        "friction",
        "Wheel friction",
        "dimensionless",
        "",
        default=1.1,
        min=0,
        min_exclusive=True,
        modes=("forward", "reverse"),
        help="Coefficient of friction μ of the tread on the floor (≈1.0-1.3 for FRC treads on carpet).",
    ),
    Field(
        "battery_voltage",
        "Battery voltage",
        "voltage",
        "V",
        default=12.7,
        min=0,
        min_exclusive=True,
        modes=("forward", "reverse"),
        help="Battery resting (open-circuit) voltage V_batt (reverse mode; forward mode with battery_sag).",
    ),
    Field(
        "min_voltage",
        "Minimum voltage",
        "voltage",
        "V",
        default=7,
        min=0,
        modes=("reverse",),
        help="Lowest voltage allowed at the motor controllers while pushing (eq. 41).",
    ),
    Field(
        "battery_resistance",
        "Battery resistance",
        "resistance",
        "ohm",
        default=0.015,
        min=0,
        modes=("forward", "reverse"),
        help="Battery internal resistance R_batt (≈0.015-0.020 Ω for an FRC battery); reverse mode and "
        "battery_sag.",
    ),
    Field(
        "main_resistance",
        "Main wiring resistance",
        "resistance",
        "ohm",
        default=0.002,
        min=0,
        modes=("forward", "reverse"),
        help="Main leads, breaker and distribution panel, R_main.",
    ),
    Field(
        "branch_resistance",
        "Branch resistance",
        "resistance",
        "ohm",
        default=0.006,
        min=0,
        modes=("forward", "reverse"),
        help="Each motor's branch (breaker, controller, wires), R_br; the n branches are in parallel.",
    ),
    Field(
        "low_ratio",
        "Low gear ratio",
        "dimensionless",
        "",
        default=15,
        min=0,
        min_exclusive=True,
        modes=("shifting",),
        help="Reduction G in low (pushing) gear.",
    ),
    Field(
        "high_ratio",
        "High gear ratio",
        "dimensionless",
        "",
        default=6,
        min=0,
        min_exclusive=True,
        modes=("shifting",),
        help="Reduction G in high (fast) gear.",
    ),
)

# Forward mode: the controllers' current limits and the battery's sag while pushing (core.sim.motor_limits).
# battery_sag reads the circuit of (41): each motor's share of the supply current sees
# R_bus = n·(R_batt + R_main) + R_br (the battery and main wiring carry all n motors, its branch one).
EFFECTS = Effects(
    *[
        e
        for e in motor_limits.electrical_effects(limit_default=60.0, supply_default=40.0)
        if e.name != "battery_sag"
    ],
    Effect(
        "battery_sag",
        "the bus sags through the battery and wiring of (41), from the battery voltage",
        nothing,
    ),
)
FIELDS = FIELDS + (
    dataclasses.replace(
        EFFECTS.field(
            "stator_limit, supply_limit (per motor current limits: they cap the "
            "pushing force); battery_sag (the motors are fed from the battery "
            "voltage through the battery, main and branch resistances)."
        ),
        modes=("forward", "reverse"),
    ),
    *[dataclasses.replace(f, modes=("forward", "reverse")) for f in EFFECTS.fields()],
)

OUTPUTS = (
    Output(
        "max_ratio",
        "Fastest ratio that slips",
        "dimensionless",
        "",
        help="Fastest gearing that slips the wheels with the voltage above V_min (42); else the fastest that slips at all.",
        equation="(42)",
    ),
    Output(
        "total_current",
        "Allowed total current",
        "current",
        "A",
        help="Total current at which the motors see the minimum voltage (41).",
        equation="(41)",
    ),
    Output(
        "free_speed", "Free speed", "speed", "ft/s", help="Top speed with no losses (37).", equation="(37)"
    ),
    Output(
        "adjusted_speed",
        "Adjusted speed",
        "speed",
        "ft/s",
        help="Expected real top speed, free speed times the speed-loss constant (38).",
        equation="(38)",
    ),
    Output(
        "slip_current",
        "Slip current per motor",
        "current",
        "A",
        help="Current each motor draws when the wheels just slip (39).",
        equation="(39)",
    ),
    Output(
        "slip_current_total",
        "Slip current, all motors",
        "current",
        "A",
        help="n times the per-motor slip current (39).",
        equation="(39)",
    ),
    Output(
        "pushing_force",
        "Pushing force",
        "force",
        "lbf",
        help="Most the drive can push: wheel traction, or the motors' stall force if lower.",
        equation="(98)",
    ),
    Output(
        "push_current",
        "Stator current pushing, per motor",
        "current",
        "A",
        help="Forward mode with a limit or sag: the slip current if the wheels slip, else the (limited) "
        "stall current.",
        equation="(39)",
    ),
    Output(
        "push_supply_current",
        "Supply current pushing, per motor",
        "current",
        "A",
        help="Stator current × duty while pushing (a limit or sag on).",
        equation="(D2)",
    ),
    Output(
        "push_battery_current",
        "Battery current pushing",
        "current",
        "A",
        help="All motors: n × the supply current while pushing.",
        equation="(D2)",
    ),
    Output(
        "push_bus_voltage",
        "Voltage at the controllers pushing",
        "voltage",
        "V",
        help="Battery voltage minus the sag of (41) at the pushing current (battery_sag).",
        equation="(41)",
    ),
    Output(
        "low_free_speed",
        "Low gear free speed",
        "speed",
        "ft/s",
        help="Free speed (37) in the low gear.",
        equation="(37), (102)",
    ),
    Output(
        "high_free_speed",
        "High gear free speed",
        "speed",
        "ft/s",
        help="Free speed (37) in the high gear.",
        equation="(37), (102)",
    ),
    Output(
        "shift_speed",
        "Shift speed",
        "speed",
        "ft/s",
        help="Speed at which both gears push equally hard: shift up above it (40).",
        equation="(40)",
    ),
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


def electrical(v, m: MotorSystem):
    """One motor's circuit for the effects that are on (core.sim.motor_limits), the same in forward
    and reverse mode: per motor R = V_spec/i_s (M1), fed the Voltage field, or with battery_sag the
    battery voltage through R_bus = n·(R_batt + R_main) + R_br (the circuit of (41)).
    Returns (E -> (u, I) per motor (E1)-(E3), circuit, V_b, R_bus)."""
    n = m.count
    sag = "battery_sag" in v["effects"]
    Vb = v["battery_voltage"] if sag else m.voltage
    Rb = n * (v["battery_resistance"] + v["main_resistance"]) + v["branch_resistance"] if sag else 0.0
    circuit = motor_limits.circuit_of(m.motor, Vb, Rb)
    elec, _ = motor_limits.limits(EFFECTS, v["effects"], v, circuit)
    return elec, circuit, Vb, Rb


def binding_field(v, u0, I0) -> str:
    """The field of the effect that holds the stalled motors' current I0 (at duty u0)."""
    on = v["effects"]
    if "stator_limit" in on and I0 >= v["stator_current_limit"] * (1 - 1e-12):
        return "stator_current_limit"
    if "supply_limit" in on and u0 < 1:
        return "supply_current_limit"
    return "battery_resistance"


def cannot_push(m: MotorSystem, I0) -> str:
    return (
        f"leaves the stalled motors {I0:.4g} A each, not above their free current "
        f"{m.free_current / m.count:.4g} A: they cannot push"
    )


def pushing(v, m: MotorSystem, G, d, i_slip, traction) -> dict:
    """Forward mode with stator_limit, supply_limit or battery_sag: the stall current per motor
    through core.sim.motor_limits (E1)-(E3) at E = 0, per motor R = V_spec/i_s (M1), fed the Voltage
    field, or with battery_sag the battery voltage through R_bus = n·(R_batt + R_main) + R_br.
    The wheel force is the seed's (7), (9): F = K_T·(n·I − ĩf)·G/r (K_T after η, all motors).
        I₀ = I(E = 0);  F_stall = K_T·(n·I₀ − ĩf)·G/r;  pushing force = min(μ·W̃, F_stall)       (D1)
    The wheels slip when n·I₀ ≥ ĩ_slip (39): the operating current is then ĩ_slip/n, at duty
    u = min(1, I_sup/I) (the stator limit, at or above it, does not bind); else I₀ at its duty u₀.
        supply current u·I per motor, battery n·u·I, V_controllers = V_b − R_bus·u·I             (D2)"""
    on, n = v["effects"], m.count
    elec, circuit, Vb, Rb = electrical(v, m)
    sag = "battery_sag" in on
    u0, I0 = elec(0.0)
    F_stall = m.kt * (n * I0 - m.free_current) * G / (d / 2)  # (D1)
    if F_stall <= 0:
        raise InputError(binding_field(v, u0, I0), cannot_push(m, I0))
    if n * I0 >= i_slip:  # the wheels slip
        I = i_slip / n
        u = min(1.0, v["supply_current_limit"] / I) if "supply_limit" in on else 1.0
    else:
        I, u = I0, u0
    out = {
        "stall_force": F_stall,
        "push_current": I,
        "push_supply_current": u * I,
        "push_battery_current": n * u * I,
    }
    # the limited force over speed, (D1) at the back-EMF of each speed: E = (v·G/r)/Kv
    v_top = circuit.Kv * Vb * (d / 2) / G
    vs = [v_top * k / 120 for k in range(121)]
    Fs = [m.kt * (n * elec(x * G / (d / 2) / circuit.Kv)[1] - m.free_current) * G / (d / 2) for x in vs]
    keep = [k for k, F in enumerate(Fs) if F >= 0]
    out["curve"] = ([vs[k] for k in keep], [Fs[k] for k in keep])
    if sag:
        out["push_bus_voltage"] = Vb - Rb * u * I  # (D2)
    return out


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
            raise InputError(
                "battery_resistance",
                "the circuit needs some resistance (battery, main or branch) to limit the current",
            )
        i_tot = total_current(
            V_batt, V_min, v["battery_resistance"], v["main_resistance"], v["branch_resistance"], n
        )
        on = v["effects"]
        # (R1): with supply_limit the battery current while slipping is n·min(ĩ_slip/n, I_sup), so
        # when n·I_sup ≤ i_tot the controllers never drop below V_min, whatever the ratio
        budget = not ("supply_limit" in on and n * v["supply_current_limit"] <= i_tot)
        if budget and i_tot <= m.free_current:
            raise InputError(
                "min_voltage",
                f"the allowed current {i_tot:.4g} A is not above the motors' "
                f"free current {m.free_current:.4g} A: lower the minimum "
                f"voltage or the resistances",
            )
        i_c = circuit_stall_current(m, V_batt, R)
        i_max = min(m.stall_current, i_c)  # most the stalled motors draw (module docstring)
        held = ""  # what holds the stalled motors' current, when a current limit or the sag does
        if on:  # forward mode's limited stall current (D1), all motors (R2)
            u0, I0 = electrical(v, m)[0](0.0)
            if n * I0 <= m.free_current:
                raise InputError(binding_field(v, u0, I0), cannot_push(m, I0))
            sag = "battery_sag" in on
            # with sag n·I₀ is the stall current through the wiring (i_c at full duty); without,
            # the limits only lower ĩs(V) and the wiring's cap i_c stays
            i_max = n * I0 if sag else min(n * I0, i_c)
            if i_max == n * I0 and (u0 < 1 or sag):
                held = (
                    f"the {binding_field(v, u0, I0).replace('_', ' ')} holds each stalled motor at {I0:.4g} A"
                    if u0 < 1
                    else f"fed the battery through the wiring (battery_sag) each stalled motor draws {I0:.4g} A"
                )
        if i_max <= m.free_current:
            raise InputError(
                "battery_voltage",
                f"stalled through this wiring the motors draw only "
                f"{i_c:.4g} A, not above their free current "
                f"{m.free_current:.4g} A: they cannot push",
            )
        if held:
            limit = held
        elif m.stall_current <= i_c:
            limit = (
                f"at {m.voltage:.3g} V (the Voltage field) the stalled motors draw at most "
                f"{m.stall_current:.4g} A"
            )
        else:
            limit = (
                f"stalled through this wiring they draw at most {i_c:.4g} A and the voltage "
                f"at the controllers stays above {V_batt - i_c * R:.3g} V"
            )
        if budget and i_tot <= i_max:
            G = max_ratio(m, W, mu, d, i_tot)  # (42): the wheels slip at the allowed current
        else:
            # The motors cannot draw i_tot (or, supply-limited, never exceed it): (42)'s ratio
            # stalls them before the wheels slip. The fastest ratio that slips at all has the most
            # they draw stalled producing the traction.
            G = max_ratio(m, W, mu, d, i_max)  # (42) with i_max (R3)
            warnings.append(
                (
                    f"The motors cannot draw the allowed {i_tot:.4g} A at the minimum voltage: "
                    if budget
                    else f"The supply current limit keeps the battery current within the allowed "
                    f"{i_tot:.4g} A at any ratio: "
                )
                + f"{limit}. The ratio shown is the fastest at which that current still slips the wheels."
            )
        if m.voltage > V_batt:
            warnings.append(
                f"The Voltage field ({m.voltage:.3g} V) is above the battery's "
                f"{V_batt:.3g} V: the controllers cannot apply it, so the free speed "
                f"shown is not reached."
            )
        values.update(total_current=i_tot, max_ratio=G)
        stall_torque = m.kt * (i_max - m.free_current)  # (9) inverted, at the stall current reached
    else:
        G = v["ratio"]

    i_slip = slip_current_total(m, W, mu, d, G)
    v_free = free_speed(m, d, G)
    stall_force = stall_torque * G / (d / 2)  # (98) at stall
    limited = None
    if v["effects"]:  # forward, or reverse at the ratio it found (the same model: (D1), (D2))
        limited = pushing(v, m, G, d, i_slip, traction)
        stall_force = limited.pop("stall_force")
        series["limited motor force"] = limited.pop("curve")
        values.update(limited)
    values.update(
        free_speed=v_free,
        adjusted_speed=v_free * k_SL,  # (38)
        slip_current=i_slip / m.count,  # (39)
        slip_current_total=i_slip,
        pushing_force=min(traction, stall_force),
    )
    if (
        limited is not None
        and stall_force < traction * (1 - 1e-12)
        and limited["push_current"] < m.stall_current / m.count
    ):
        warnings.append(
            f"The current limits or the sag cap the pushing force: the motors push "
            f"{format_quantity(stall_force, 'lbf', 'force')} ({limited['push_current']:.4g} A each) "
            f"but traction allows {format_quantity(traction, 'lbf', 'force')}: the wheels do not slip."
        )
    elif stall_force < traction * (1 - 1e-12):  # (not when equal but for rounding: reverse mode's limit)
        warnings.append(
            f"The motors stall before the wheels slip: they push "
            f"{format_quantity(stall_force, 'lbf', 'force')} but traction allows "
            f"{format_quantity(traction, 'lbf', 'force')} (the slip current is not reached)."
        )
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
        Plot(
            "Force at the wheels vs speed",
            ("motor force", "limited motor force", "traction limit", "low gear", "high gear"),
            "speed",
            "speed",
            "ft/s",
            "force",
            "force",
            "lbf",
        ),
    ),
)
