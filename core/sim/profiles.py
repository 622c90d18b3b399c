"""The motion profiles of the profiled move (core.sim.profiled): what the robot code asks the
mechanism to follow, WPILib's TrapezoidProfile and ExponentialProfile, from rest to rest over the
move's distance, and the trapezoid's limits derived from the mechanism.

Trapezoid from rest to rest over the distance d with limits v_max, a_max (WPILib TrapezoidProfile):
    t_a = v_max/a_max;  if a_max·t_a² > d: t_a = √(d/a_max) (a triangle), v_peak = a_max·t_a;
    t_c = (d − a_max·t_a²)/v_peak;  T = 2·t_a + t_c                                     (P1)
    p(t) = a·t²/2 (t < t_a);  a·t_a²/2 + v_peak·(t − t_a) (t < t_a + t_c);  d − a·(T − t)²/2 (t ≤ T)
                                                                                       (P2)
Or WPILib's ExponentialProfile (Constraints.fromCharacteristics(U, kV, kA)): the response of the
plant kA·v̇ + kV·v = u to the input u = +U, then −U from the switch (the inflection) on, so that it
arrives at rest at d; the feedforward's kS and kG come on top, as in WPILib (derived with sympy and
checked against mpmath and robotpy's ExponentialProfileMeterVolts, tests/test_profiled_expo.py):
    v_m = U/kV (Constraints.maxVelocity, approached, never reached),  τ = kA/kV,
    a_0 = U/kA (the acceleration at rest)                                               (P12)
    accelerating from rest:  v = v_m·(1 − e^{−t/τ}),  p = v_m·t − τ·v                  (P13)
    braking into the goal, s = T − t:  v = v_m·(e^{s/τ} − 1),  p = d + v_m·s − τ·v       (P14)
    the two meet where −ln(1 − w²) = D, D = d/(v_m·τ), w = v_i/v_m:  w = √(1 − e^{−D});
    t_i = τ·(D + ln(1 + w)) (from 1 − w = e^{−D}/(1 + w): no cancellation as w → 1),
    T = t_i + τ·ln(1 + w)  (→ d/v_m + 2τ·ln 2 for a long move)                         (P15)
A derived trapezoid: v_max = velocity_fraction·(free speed), a_max = acceleration_fraction·(the
acceleration from rest against the load at the start with each motor's current at the stator
current limit entry, or its stall current if lower: (M4) with I capped)                 (P17)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

from ..errors import InputError


@dataclass(frozen=True)
class Trapezoid:
    """Rest-to-rest trapezoid over `distance` ≥ 0 (P1), (P2)."""

    distance: float
    v_max: float
    a_max: float

    @cached_property
    def accel_time(self) -> float:
        t_a = self.v_max / self.a_max
        return math.sqrt(self.distance / self.a_max) if self.a_max * t_a * t_a > self.distance else t_a

    @cached_property
    def peak_speed(self) -> float:
        return self.a_max * self.accel_time

    @cached_property
    def cruise_time(self) -> float:
        t_a = self.accel_time
        return max(0.0, self.distance - self.a_max * t_a * t_a) / self.peak_speed

    @cached_property
    def total_time(self) -> float:
        return 2 * self.accel_time + self.cruise_time

    def at(self, t: float) -> tuple[float, float]:
        """(p, ṗ) at time t (P2)."""
        a, t_a, T = self.a_max, self.accel_time, self.total_time
        if t <= 0:
            return 0.0, 0.0
        if t < t_a:
            return a * t * t / 2, a * t
        if t < t_a + self.cruise_time:
            v = self.peak_speed
            return a * t_a * t_a / 2 + v * (t - t_a), v
        if t <= T:
            left = T - t
            return self.distance - a * left * left / 2, a * left
        return self.distance, 0.0


@dataclass(frozen=True)
class Exponential:
    """Rest-to-rest WPILib ExponentialProfile over `distance` ≥ 0, input `max_input` volts on the
    plant kV, kA (P12)-(P15); the loop reads at(t) and total_time as of a Trapezoid."""

    distance: float
    max_input: float
    kV: float
    kA: float

    @cached_property
    def v_max(self) -> float:
        return self.max_input / self.kV  # (P12)

    @cached_property
    def a_max(self) -> float:
        return self.max_input / self.kA  # (P12)

    @cached_property
    def tau(self) -> float:
        return self.kA / self.kV  # (P12)

    @cached_property
    def switch_fraction(self) -> float:
        """w = v_i/v_m = √(1 − e^{−D}) (P15)."""
        return math.sqrt(-math.expm1(-self.distance / (self.v_max * self.tau)))

    @cached_property
    def inflection_time(self) -> float:
        D = self.distance / (self.v_max * self.tau)
        return self.tau * (D + math.log1p(self.switch_fraction))  # (P15)

    @cached_property
    def total_time(self) -> float:
        return self.inflection_time + self.tau * math.log1p(self.switch_fraction)  # (P15)

    def at(self, t: float) -> tuple[float, float]:
        """(p, ṗ) at time t (P13), (P14)."""
        vm, tau, T = self.v_max, self.tau, self.total_time
        if t <= 0:
            return 0.0, 0.0
        if t < self.inflection_time:
            z = t / tau
            return vm * tau * (z + math.expm1(-z)), -vm * math.expm1(-z)  # (P13)
        if t < T:
            z = (T - t) / tau
            return self.distance - vm * tau * (math.expm1(z) - z), vm * math.expm1(z)  # (P14)
        return self.distance, 0.0


def stall_acceleration(setup, current_cap: float | None = None) -> float:
    """Acceleration toward the goal from rest at full voltage against the load at the start (M4);
    with `current_cap`, each motor's current at most that (A) (P17)."""
    from .motion import electrical, field_force, friction_of

    m = setup.mech
    _, I0 = electrical(m, setup.asm.slots["duty"])(0.0)
    if current_cap is not None:
        I0 = min(I0, current_cap)
    return (m.force_per_amp * I0 + m.s * field_force(setup)(m.q0) - friction_of(setup)) / m.inertia


DERIVED_CURRENT_CAP = 40.0  # A per motor: the derived profile's current with no stator limit on


def derived_acceleration(setup, v) -> float:
    """(P17): the derived trapezoid's max acceleration, acceleration_fraction of the acceleration
    from rest against the load at the start with each motor at its stator current limit (the
    stator_current_limit entry with the stator_limit effect on, else DERIVED_CURRENT_CAP; its
    stall current when lower). A team sets a stator limit (40 A by default here) and profiles within it: the
    full-voltage stall acceleration of a light load on FRC motors is tens of g at hundreds of amps."""
    # the limit entered when the stator_limit effect is on (its row is shown); else a team's
    # usual 40 A: a hidden row must change nothing (the CLI says so of a value set there)
    limited = "stator_limit" in (v.get("effects") or ())
    cap = v["stator_current_limit"] if limited else DERIVED_CURRENT_CAP
    a = stall_acceleration(setup, cap)
    if not a > 0:
        raise InputError(
            "stator_current_limit" if limited else "acceleration_fraction",
            f"the derived profile accelerates from rest with each motor at {cap:.4g} A"
            f"{' (the stator current limit)' if limited else ''}, which cannot move the load at the "
            "start: "
            + (
                "raise stator_current_limit"
                if limited
                else "turn on the stator_limit effect and raise its limit"
            )
            + " or enter the profile limits (profile_limits = entered)",
        )
    return v["acceleration_fraction"] * a


def exponential_of(setup, v, ff: dict) -> Exponential:
    """(P12)-(P15) from the entered max input on the plant's kV, kA (ff, per unit of q)."""
    U, Vb = v["max_input"], setup.mech.battery_voltage
    if U > Vb:
        raise InputError(
            "max_input",
            f"must be at most the battery voltage, {Vb:.6g} V (entered {U:.6g} V): the loop cannot apply more",
        )
    profile = Exponential(setup.mech.distance, U, ff["kV"], ff["kA"])
    if not (profile.kV > 0 and profile.kA > 0 and math.isfinite(profile.v_max * profile.a_max)):
        raise InputError("max_input", "the plant's kV and kA give no exponential profile")
    return profile
