"""Current limits and battery sag of DC motors driven by a controller: the one definition every
motor calculator uses (the elevator and arm scenes in core.sim.motion, the flywheel's spin-up and
recovery, the drivetrain's pushing force, the motor tab's limited curves).

Motor (per motor; R and Kv as WPILib's DCMotor, wpimath DCMotor.java):
    R = V_nom/I_stall,  Kv = ω_free/(V_nom − R·I_free)                                  (M1)
    I = (u·V_bus − E)/R,  E = ω_m/Kv the back-EMF, u the duty (0..1)                      (M2)
The effects act on (u, I) only; every calculator turns the current into torque by the seed's
K_T·(I − i_f) (eqs. 3, 7, 9; core.sim.motion (M3)), one motor model on every tab.
- `battery_sag`: V_bus = V_b − R_bus·u·I, R_bus the resistance each motor's share of the supply
  current sees (N·R_batt for N motors on one battery). With (M2):
      I(u) = (u·V_b − E)/(R + u²·R_bus)                                                  (E1)
- `stator_limit` (|I| ≤ I_st): the controller lowers the duty until the current is at the limit.
  I(u) = I_st ⇔ I_st·R_bus·u² − V_b·u + W = 0, W = E + R·I_st; the duty is the SMALLER root
      u_st = 2W/(V_b + √(V_b² − 4·I_st·R_bus·W))     (= W/V_b without sag)               (E2)
  No real root: the current never reaches the limit, u = 1.
- `supply_limit` (u·I ≤ I_sup): (V_b − I_sup·R_bus)·u² − E·u − I_sup·R = 0, the positive root (E3)
- the duty is u = min(1, u_st, u_sup).
Per motor, the supply current drawn from the bus, and the bus voltage (R_bus the motor's share):
      I_supply = u·I,  V_bus = V_b − R_bus·u·I  (n motors: n·u·I from the battery)           (E4)
The limits let go (u = 1 from there on as the motor speeds up) at the back-EMF
      E_free = min{E ≥ 0 : min(1, u_st(E), u_sup(E)) = 1},  speed ω = Kv·E_free          (E5)
  (the limits that are on), found by bisection (`full_duty_emf`: with strong sag no closed form covers every case).
With sag, I(u) (E1) peaks at a duty below 1 when I_st·R_bus > V_b/2, and the two roots of (E2) merge
where its discriminant V_b² − 4·I_st·R_bus·W vanishes (derived with sympy):
      E_merge = V_b²/(4·I_st·R_bus) − R·I_st,  u_st(E_merge) = V_b/(2·I_st·R_bus)              (E6)
  Past E_merge the current cannot reach the limit at any duty: when u_st(E_merge) < 1 the duty
  jumps there from u_st to min(1, u_sup), the supply current u·I jumps up (to its peak) and the
  bus voltage down. The supply current's extremes over a run lie at rest, at top speed or at a
  branch point of the duty rule (branch_emfs): release_emfs, E6 (on both sides of the jump) and
  the supply limit's release u_sup = 1, E = V_b − I_sup·(R + R_bus) (E3 at u = 1)          (E7)
The context an effect is built with (`ctx`) needs R, battery_voltage, bus_resistance and xp (the
math namespace): core.sim.motion.Mechanism, or `Circuit` here.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..fields import Field
from .effects import Effect, Effects, Part, Slot, nothing


class _Array:
    """numpy stand-ins for the math functions the terms use, for a batch of candidates."""

    def __init__(self):
        import numpy as np

        self.np = np
        self.sqrt = np.sqrt
        self.cos = np.cos
        self.minimum = np.minimum

    def where(self, cond, a, b):
        return self.np.where(cond, a, b)

    def maximum(self, a, b):
        return self.np.maximum(a, b)


class _Scalar:
    sqrt = staticmethod(math.sqrt)
    cos = staticmethod(math.cos)
    minimum = staticmethod(min)
    maximum = staticmethod(max)

    @staticmethod
    def where(cond, a, b):
        return a if cond else b


SCALAR = _Scalar()


def _stator_build(values: Mapping[str, Any], mech: Any) -> Part:
    I_st, R, Vb, Rb, xp = (
        values["stator_current_limit"],
        mech.R,
        mech.battery_voltage,
        mech.bus_resistance,
        mech.xp,
    )
    if Rb == 0:

        def bound(E):
            return (E + R * I_st) / Vb  # (E2) without sag
    else:
        a = 4 * I_st * Rb

        def bound(E):
            W = E + R * I_st
            disc = Vb * Vb - a * W
            return xp.where(disc >= 0, 2 * W / (Vb + xp.sqrt(xp.maximum(disc, 0.0))), math.inf)  # (E2)

    return Part(terms={"duty": bound})


def _supply_build(values: Mapping[str, Any], mech: Any) -> Part:
    I_sup, R, Vb, Rb, xp = (
        values["supply_current_limit"],
        mech.R,
        mech.battery_voltage,
        mech.bus_resistance,
        mech.xp,
    )
    a = Vb - I_sup * Rb  # the bus voltage while the supply limit holds
    c = I_sup * R
    if not a > 0:  # the battery cannot deliver I_sup through its resistance: never binds
        return Part(terms={"duty": lambda E: math.inf + 0 * E})

    def bound(E):  # (E3), the positive root written without cancellation for either sign of E
        root = xp.sqrt(E * E + 4 * a * c)
        return xp.where(E >= 0, (E + root) / (2 * a), 2 * c / xp.maximum(root - E, 1e-300))

    return Part(terms={"duty": bound})


def electrical_effects(limit_default: float = 40.0, supply_default: float = 30.0) -> tuple[Effect, ...]:
    return (
        Effect(
            "stator_limit",
            "stator current limit per motor (|I| clipped; the duty drops to hold it)",
            _stator_build,
            fields=(
                Field(
                    "stator_current_limit",
                    "Stator current limit",
                    "current",
                    "A",
                    default=limit_default,
                    min=0,
                    max=2000,
                    help="Per motor: the controller lowers the duty so the motor current "
                    "never exceeds this (e.g. TalonFX StatorCurrentLimit, SPARK smart "
                    "current limit).",
                ),
            ),
        ),
        Effect(
            "supply_limit",
            "supply current limit per motor (supply current = stator current × duty)",
            _supply_build,
            fields=(
                Field(
                    "supply_current_limit",
                    "Supply current limit",
                    "current",
                    "A",
                    default=supply_default,
                    min=0,
                    max=2000,
                    help="Per motor: the current drawn from the battery, stator current × "
                    "duty, is held at or below this by lowering the duty.",
                ),
            ),
        ),
        Effect(
            "battery_sag",
            "battery and wiring resistance: the bus sags with the total supply current",
            nothing,
            fields=(
                Field(
                    "battery_resistance",
                    "Battery + wiring resistance",
                    "resistance",
                    "ohm",
                    default=0.02,
                    min=0,
                    max=10,
                    help="Total of the battery's internal resistance and the wiring to the "
                    "controllers (FRC battery ≈ 0.015-0.020 Ω, plus ≈ 0.005 Ω of "
                    "wiring). V_bus = V_b − R·(total supply current), solved exactly.",
                ),
            ),
        ),
    )


def bus_resistance_of(values: Mapping[str, Any], on) -> float:
    return values["motor_count"] * values["battery_resistance"] if "battery_sag" in on else 0.0


def electrical(mech: Any, duty):
    """(E, ceiling=1) -> (u, I): the duty and stator current per motor at back-EMF E, (E1)-(E3);
    `ceiling` caps the duty from outside the limits (an open-loop ramp: the duty it allows now)."""
    Vb, R, Rb = mech.battery_voltage, mech.R, mech.bus_resistance
    if duty is None:
        if Rb == 0:
            return lambda E, ceiling=1.0: (ceiling, (ceiling * Vb - E) / R)
        return lambda E, ceiling=1.0: (ceiling, (ceiling * Vb - E) / (R + ceiling * ceiling * Rb))
    minimum = mech.xp.minimum
    if Rb == 0:

        def f(E, ceiling=1.0):
            u = minimum(duty(E), ceiling)
            return u, (u * Vb - E) / R

        return f

    def f(E, ceiling=1.0):
        u = minimum(duty(E), ceiling)
        return u, (u * Vb - E) / (R + u * u * Rb)  # (E1)

    return f


@dataclass(frozen=True)
class Circuit:
    """One motor's electrical side, for calculators that are not a motion scene (ctx of the effects)."""

    R: float  # Ω, (M1)
    Kv: float  # rad/s per V, (M1)
    battery_voltage: float  # V_b at rest (or the applied voltage when nothing sags)
    bus_resistance: float = 0.0  # R_bus per motor, exactly 0 unless battery_sag is on
    xp: Any = SCALAR


def circuit_of(motor: Any, battery_voltage: float, bus_resistance: float = 0.0) -> Circuit:
    """(M1) from a core.motors.Motor's data at its specification voltage."""
    R = motor.v_spec / motor.stall_current
    return Circuit(
        R, motor.free_speed / (motor.v_spec - R * motor.free_current), battery_voltage, bus_resistance
    )


DUTY = (Slot("duty", "min", "upper bound on the motor duty from a current limit, given the back-EMF E"),)


def limits(effects: Effects, on, values: Mapping[str, Any], circuit: Any):
    """E -> (u, I) for the electrical effects that are on (assembled from the same Effect parts
    the scenes use), and the assembly (its parts answer the duty bounds one by one)."""
    names = [n for n in on if n in ("stator_limit", "supply_limit", "battery_sag")]
    asm = effects.assemble(names, values, circuit, DUTY, minimum=circuit.xp.minimum)
    return electrical(circuit, asm.slots["duty"]), asm


def release_emfs(circuit: Any, values: Mapping[str, Any], on) -> list[float]:
    """Back-EMFs at which a limit lets go as the motor speeds up (where the supply current and the
    bus voltage have their extremes): the stator limit toward full duty, E = V_b − I_st·(R + R_bus),
    or toward the supply limit, at u = I_sup/I_st: E = u·V_b − I_st·(R + u²·R_bus)."""
    Vb, R, Rb = circuit.battery_voltage, circuit.R, circuit.bus_resistance
    Es = []
    if "stator_limit" in on:
        I_st = values["stator_current_limit"]
        Es.append(Vb - I_st * (R + Rb))
        if "supply_limit" in on and I_st > 0:
            u = values["supply_current_limit"] / I_st
            if u <= 1:
                Es.append(u * Vb - I_st * (R + u * u * Rb))
    return Es


MERGE_STEP = 1e-12  # relative: past E6 by this, (E2)'s discriminant is < 0 whatever its rounding


def branch_emfs(circuit: Any, values: Mapping[str, Any], on) -> list[float]:
    """Every back-EMF where the duty rule min(1, u_st, u_sup) changes branch: release_emfs, the
    stator limit's merge point (E6) and, just past it, the jump's far side (MERGE_STEP: the duty
    there is min(1, u_sup), evaluated to ~1e-12 of the jump's right-hand limit), and the supply
    limit's release (E7). The supply current and bus voltage have their extremes at these points
    (or at rest or top speed): between them both are monotone in E."""
    Vb, R, Rb = circuit.battery_voltage, circuit.R, circuit.bus_resistance
    Es = list(release_emfs(circuit, values, on))
    if "stator_limit" in on and Rb > 0:
        I_st = values["stator_current_limit"]
        if I_st > 0:
            E_merge = Vb * Vb / (4 * I_st * Rb) - R * I_st  # (E6)
            Es += [E_merge, E_merge + MERGE_STEP * max(abs(E_merge), Vb)]
    if "supply_limit" in on:
        Es.append(Vb - values["supply_current_limit"] * (R + Rb))  # (E7)
    return Es


def full_duty_emf(elec, E_top: float) -> float:
    """The back-EMF from which the duty is 1 (no limit binds), by bisection on [0, E_top] (the
    duty never falls as E rises; with strong sag the stator limit's root (E2) can stay below 1
    past V_b − I_st·(R + R_bus), so no closed form covers every case); 0 when nothing binds at
    rest, E_top when a limit still binds there."""
    if elec(0.0)[0] >= 1.0:
        return 0.0
    if elec(E_top)[0] < 1.0:
        return E_top
    lo, hi = 0.0, E_top
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if elec(mid)[0] >= 1.0:
            hi = mid
        else:
            lo = mid
        if hi - lo <= 1e-15 * max(1.0, hi):
            break
    return hi


def braking_warning(values: Mapping[str, Any], run: Any) -> None:
    """Warn (on `run`, a SimRun of a move) when the peak stator current passes the stator limit:
    the load back-drives the motor past its free speed and it brakes, a current the limit (which
    acts on the drive) does not hold down here. Shown, not hidden: 7.8 A beside a 5 A limit."""
    on = values.get("effects", ())
    peak = run.values.get("peak_stator_current")
    limit = values.get("stator_current_limit")
    if "stator_limit" not in on or peak is None or limit is None or not peak > limit * (1 + 1e-9):
        return
    run.warnings.append(
        f"The peak stator current ({peak:.4g} A) is above the stator current limit ({limit:.4g} A): "
        f"the load back-drives the motor past its free speed, and that braking current is not "
        f"limited in this model."
    )
