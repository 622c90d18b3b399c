"""Hard cases for the lead screw (section 3) and drivetrain (section 4) calculators.

Each case states why it is delicate and compares with an mpmath reference evaluated (at 40
digits, with the true π) on exactly the doubles the calculator parsed. Tolerances are the
problem's own condition number times a few units of rounding, stated in each case.
"""

import math

import mpmath as mp
import pytest

from gearhead.core import motors
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get

mp.mp.dps = 40


def screw(**raw):
    values = parse_inputs(get("lead_screw"), raw)[0]
    outputs = {k: v.value for k, v in solve("lead_screw", raw).outputs.items()}
    return values, outputs


def mp_torques(v):
    """(30)-(32) in 40-digit arithmetic from the parsed SI doubles."""
    F, d, p = (mp.mpf(v[k]) for k in ("force", "diameter", "pitch"))
    mu, n = mp.mpf(v["friction"]), v["starts"]
    dm, l, c = d - p / 2, n * p, mp.cos(mp.mpf(v["thread_angle"]) / 2)
    T_R = F * dm / 2 * (mp.pi * mu * dm + l * c) / (mp.pi * dm * c - mu * l)
    T_L = F * dm / 2 * (mp.pi * mu * dm - l * c) / (mp.pi * dm * c + mu * l)
    return T_R, T_L, mp.pi * mu * dm - l * c


SQUARE = dict(diameter="0.0127 m", pitch="0.00254 m", starts=16, thread_angle=0, force="1000 N")


def test_raise_torque_at_the_edge_of_locking():
    """(31)'s denominator π·dm − μ·l is 1e-9 of its terms: T_R is a billion times the frictionless
    torque and every rounding in the two products is amplified 1e9-fold (condition ~1e9, so a
    few 1e-7 relative is the best doubles can do; measured 7e-8, 5e-6 allowed). A hair further the screw locks
    and must be reported as locked, never as a negative torque."""
    mu_lock = math.pi * (0.0127 - 0.00127) / (16 * 0.00254)  # π·dm/l = 0.883573
    v, o = screw(**SQUARE, friction=repr(mu_lock * (1 - 1e-9)))
    T_R, _, _ = mp_torques(v)
    assert T_R > 0 and o["drivable"] is True
    assert o["raise_torque"] == pytest.approx(float(T_R), rel=5e-6)
    assert o["raise_torque"] > 1e8 * 1000 * 16 * 0.00254 / (2 * math.pi)  # ≫ frictionless F·l/2π
    v, o = screw(**SQUARE, friction=repr(mu_lock * (1 + 1e-9)))
    assert mp_torques(v)[0] < 0  # the formula's "torque" is negative: locked
    assert o["drivable"] is False and "raise_torque" not in o and o["efficiency"] == 0


def test_backdriving_sign_a_hair_either_side_of_the_limit():
    """μ within 1e-12 of l·cos α/(π·dm): the numerator of (32) is a difference of two nearly equal
    products, 1e-12 of each. Its sign (backdrivable or not) must still be right on both sides, and
    at 1e-10 from the limit T_L itself must match to the conditioning (~1e10·4 ulp ≈ 1e-5; 1e-4)."""
    base = dict(diameter="0.5 in", pitch="0.1 in", starts=1, thread_angle="29 deg", force="100 lbf")
    v0 = parse_inputs(get("lead_screw"), base)[0]
    dm, l = v0["diameter"] - v0["pitch"] / 2, v0["pitch"]
    mu_b = float(mp.mpf(l) * mp.cos(mp.mpf(v0["thread_angle"]) / 2) / (mp.pi * mp.mpf(dm)))
    for rel, backdrives in ((-1e-12, True), (1e-12, False)):
        v, o = screw(**base, friction=repr(mu_b * (1 + rel)))
        assert (mp_torques(v)[2] < 0) is backdrives
        assert o["backdrivable"] is backdrives
    for rel in (-1e-10, 1e-10):
        v, o = screw(**base, friction=repr(mu_b * (1 + rel)))
        T_L = mp_torques(v)[1]
        assert abs(T_L) < 1e-9  # N·m: tiny against T_R ≈ 0.2 N·m
        assert o["lower_torque"] == pytest.approx(float(T_L), rel=1e-4)


def test_nearly_flat_thread_angle():
    """Thread angle π − 2e-8 rad: α = π/2 − 1e-8, so cos α ≈ 1e-8 and sec α ≈ 1e8 multiplies the
    friction. cos α is the small gap between α and π/2: math.cos resolves it to full relative
    precision (its argument reduction carries extra digits of π), where a form such as
    sqrt(1 − sin²α) would lose 8 digits to cancellation. Given an exact cos α, (31)-(33) are well
    conditioned and match to ~1e-13 (measured: 2e-17)."""
    ta = math.pi - 2e-8
    v, o = screw(
        diameter="0.5 in",
        pitch="0.1 in",
        starts=1,
        thread_angle=f"{ta!r} rad",
        friction="1e-10",
        force="100 lbf",
    )
    T_R, T_L, _ = mp_torques(v)
    assert o["raise_torque"] == pytest.approx(float(T_R), rel=1e-12)
    assert o["lower_torque"] == pytest.approx(float(T_L), rel=1e-12)
    F, l = mp.mpf(v["force"]), mp.mpf(v["pitch"])
    assert o["efficiency"] == pytest.approx(float(F * l / (2 * mp.pi * T_R)), rel=1e-12)
    # μ·sec α ≈ 1e-2: the friction is felt although μ is 1e-10
    assert 0.5 < o["efficiency"] < 0.99


def test_drivetrain_reverse_with_allowed_current_a_hair_above_free_current():
    """(42) divides by i_tot − ĩf. With the budget allowing only 1e-9 more than the 8 A free
    current of four Kraken X60s, G_slip is ~1e9 times the usual size and the rounding of i_tot
    (a few ulp) is amplified 1e9-fold (so ~1e-6 relative; 1e-5 allowed). Just below the free
    current it must be an error naming a field, not a negative ratio."""
    m = motors.system(motors.lookup("Kraken X60", "wpilib")[0], 4, 12.0, 1.0)
    R = 0.015 + 0.002 + 0.006 / 4
    base = dict(mode="reverse", motor_count=4, battery_voltage="12.7 V")
    target = m.free_current * (1 + 1e-9)
    raw = dict(base, min_voltage=f"{12.7 - target * R!r} V")
    v = parse_inputs(get("drivetrain"), raw)[0]
    o = {k: x.value for k, x in solve("drivetrain", raw).outputs.items()}
    mot = m.motor
    n = mp.mpf(4)
    tau_s, i_s, i_f = (
        mp.mpf(mot.stall_torque) * n,
        mp.mpf(mot.stall_current) * n,
        mp.mpf(mot.free_current) * n,
    )
    Kt = tau_s / (i_s - i_f)  # (7) at 12 V, η = 1
    i_tot = (mp.mpf(v["battery_voltage"]) - mp.mpf(v["min_voltage"])) / (
        mp.mpf(v["battery_resistance"]) + mp.mpf(v["main_resistance"]) + mp.mpf(v["branch_resistance"]) / n
    )  # (41)
    G = (
        mp.mpf(v["friction"]) * mp.mpf(v["wheel_diameter"]) * mp.mpf(v["weight"]) / (2 * Kt * (i_tot - i_f))
    )  # (42)
    assert i_tot - i_f > 0
    assert o["total_current"] == pytest.approx(float(i_tot), rel=1e-14)
    assert o["max_ratio"] == pytest.approx(float(G), rel=1e-5)
    assert o["max_ratio"] > 1e8
    with pytest.raises(InputError) as e:
        solve("drivetrain", dict(base, min_voltage=f"{12.7 - m.free_current * (1 - 1e-9) * R!r} V"))
    assert e.value.field == "min_voltage"
