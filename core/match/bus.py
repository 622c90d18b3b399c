"""The bus voltage from every supply current together: one battery (V_oc behind R) feeding every
motor controller, base load and stator-limited motor at once.

Each load's supply current is written as a function of the bus voltage V:

    I(V) = a + b·V + p/V                                                                      (M6)

  - a motor controller at duty u (|u| ≤ 1) driving a motor at speed ω (its own equation, no current
    limit binding): the bridge applies u·V, the motor takes I_m = (u·V − k_e·ω)/R_m, and a lossless
    bridge's power balance V·I_s = (u·V)·I_m gives the supply current
        I_s = u·I_m = (u²/R_m)·V − u·k_e·ω/R_m,   so  a = −n·u·k_e·ω/R_m,  b = n·u²/R_m ≥ 0
    for n motors alike: affine in V (`motor_terms`; tests/test_match_bus.py derives it with sympy);
  - a constant current (roboRIO, radio, sensors: the base load): a = I, b = p = 0;
  - a motor whose stator current limit binds holds its stator current I_st at the speed ω, so its
    power u·V·I_st = (R_m·I_st + k_e·ω)·I_st does not depend on V: a constant-power load p.

Summing A = Σa, B = Σb, P = Σp, the bus is V = V_oc − R·(A + B·V + P/V). Without constant power:

    V = (V_oc − R·A)/(1 + R·B)                                                                (M7)

(1 + R·B > 0 since B ≥ 0). With P ≠ 0, multiply by V: with W = V_oc − R·A, α = 1 + R·B,

    α·V² − W·V + R·P = 0,   D = W² − 4·α·R·P,   V = (W ± √D)/(2α)                             (M8)

(for A = B = 0 this is V·(V_oc − V) = R·P). For P > 0 both roots are positive and bracket the vertex
V* = W/(2α): the upper root in [V*, W/α], the lower in (0, V*]. They are computed without
cancellation (q = (W + √D)/2, V_upper = q/α, V_lower = R·P/q). D < 0 means the loads ask more power
than the battery can deliver at any voltage (the most is W²/(4αR) at V*): the bus collapses; the
point returned is then V* with `collapsed` set (the caller decides what the loads do).

    While D > 0 the two roots are continuous in the loads and the battery, so the branch followed
    through time is the root nearest the previous bus voltage (the upper one at the start)     (M9)

A negative P (a constant-power regenerating load) gives R·P < 0, one positive root and one
negative: the positive one is taken.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class BusPoint:
    """The bus at one instant: the voltage taken, both roots of (M8) where they exist, and whether
    the bus collapsed (no operating point: D < 0, or a voltage that would be ≤ 0)."""

    voltage: float
    upper: float | None = None
    lower: float | None = None
    collapsed: bool = False


def motor_terms(duty: float, omega: float, k_e: float, r_motor: float, count: int = 1) -> tuple[float, float]:
    """(a, b) of (M6) for `count` motors alike at duty `duty`, speed `omega` (rad/s), back-EMF
    constant `k_e` (V·s/rad) and winding resistance `r_motor` (Ω)."""
    return (-count * duty * k_e * omega / r_motor, count * duty * duty / r_motor)


def solve_bus(
    v_oc: float, r: float, a: float, b: float = 0.0, p: float = 0.0, previous: float | None = None
) -> BusPoint:
    """The bus voltage for open-circuit voltage `v_oc`, series resistance `r` and the summed load
    terms A = `a`, B = `b` (≥ 0), P = `p` (M7-M9). `previous`: the bus voltage an instant before,
    whose branch is followed (M9)."""
    w = v_oc - r * a
    alpha = 1.0 + r * b
    if p == 0.0:
        v = w / alpha  # (M7)
        return BusPoint(v, v, None) if v > 0 else BusPoint(0.0, None, None, True)
    c = r * p
    d = w * w - 4.0 * alpha * c  # (M8)
    if d < 0 or (w <= 0 and c >= 0):
        return BusPoint(max(w / (2.0 * alpha), 0.0), None, None, True)
    q = 0.5 * (w + math.sqrt(d))
    upper = q / alpha
    lower = c / q
    if lower <= 0:  # a regenerating P < 0: only the positive root is a bus voltage
        return BusPoint(upper, upper, None)
    if previous is None or abs(previous - upper) <= abs(previous - lower):  # (M9)
        return BusPoint(upper, upper, lower)
    return BusPoint(lower, upper, lower)


def current(v: float, a: float, b: float = 0.0, p: float = 0.0) -> float:
    """The summed supply current (M6) at bus voltage `v`."""
    return a + b * v + (p / v if p else 0.0)
