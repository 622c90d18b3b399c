"""Flywheel hard cases: numerically delicate inputs, each against an mpmath reference (40 digits)
computed from the same SI inputs straight from the physics, not from the module's algebra."""

import math

import mpmath as mp
import pytest

from gearhead.core import presets
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import shooter as fw

mp.mp.dps = 40
SEED = presets.load(
    fw.__file__.rsplit("/core/", 1)[0] + "/presets/flywheel/nbn_seed_single_wheel.toml"
).inputs
G = mp.mpf("9.80665")


def vals(raw):
    return parse_inputs(get("flywheel"), raw)[0]


def mp_range(V, theta, h):
    """Root x > 0 of y(x) = h + x·tanθ − g·x²/(2V²cos²θ) (the trajectory itself)."""
    c2 = (V * mp.cos(theta)) ** 2
    t = mp.tan(theta)
    return (t + mp.sqrt(t * t + 2 * G * h / c2)) * c2 / G


def mp_ball_speed(v, m, model):
    """V from the transfer model written out in mpmath (lossless, motor off in the shot)."""
    r_w = mp.mpf(v["wheel_diameter"]) / 2
    I = (
        v["wheel_count"] * mp.mpf(v["wheel_mass"]) * (mp.mpf(v["gyration_fraction"]) * r_w) ** 2
        if v["mode"] == "radius_of_gyration"
        else v["wheel_count"] * mp.mpf(v["wheel_inertia"])
    )
    s = mp.mpf(1) / 2
    m_e = mp.mpf(m) * (1 + mp.mpf(v["ball_inertia_factor"]))
    w0 = mp.mpf(v["target_speed"])
    if model == "energy":  # ½Iω₀² = ½Iω₁² + ½m_e(s·r_w·ω₁)²
        w1 = w0 * mp.sqrt(I / (I + m_e * (s * r_w) ** 2))
    else:  # I(ω₀ − ω₁) = r_w·J, J = s·m_e·V, V = s·r_w·ω₁
        w1 = I * w0 / (I + m_e * (s * r_w) ** 2)
    return s * r_w * w1, w0 - w1


def test_tiny_mass_tolerance_from_a_release_height():
    """e_m = 1.234567e-12 with h = 1.5 m: R(heavy) − R(nominal) is 1e-13 of R, so forming the two
    ranges and subtracting loses every digit, and even m₀·(1 + e_m) carries a 1e-4 relative error
    in the mass change; the module works with the change dm = m₀·e_m and β(dm), and rationalises
    the difference of square roots."""
    raw = {
        **SEED,
        "ball_mass_tolerance": "1.234567e-10 %",
        "release_height": "1.5 m",
        "launch_angle": "20 deg",
    }
    v = vals(raw)
    o = solve("flywheel", raw).outputs
    V0, _ = mp_ball_speed(v, v["ball_mass"], "energy")
    V1, _ = mp_ball_speed(v, mp.mpf(v["ball_mass"]) * (1 + mp.mpf(v["ball_mass_tolerance"])), "energy")
    th, h = mp.mpf(v["launch_angle"]), mp.mpf(v["release_height"])
    ref = mp_range(V1, th, h) / mp_range(V0, th, h) - 1
    assert abs(ref) < 1e-12
    assert o["range_error"].value == pytest.approx(float(ref), rel=1e-11)
    naive = (
        fw.projectile_range(float(V1), v["launch_angle"], 1.5)
        / fw.projectile_range(float(V0), v["launch_angle"], 1.5)
        - 1
    )
    assert abs(naive - float(ref)) > 1e-5 * abs(float(ref))  # the naive subtraction loses ~4 digits more


def test_nearly_infinite_wheel_inertia_momentum_model():
    """I = 1e6 lb·in² (292.6 kg·m²) against a 60 g ball: β ≈ 3e-7, the wheel loses 3e-7 of its
    speed and the range error is ~1e-8; 1/(1+β) − 1 and q² − 1 must not be formed by subtraction."""
    raw = {
        **SEED,
        "mode": "moment_of_inertia",
        "wheel_inertia": "1e6 lb*in**2",
        "effects": "momentum",
        "release_height": "0.8 m",
    }
    v = vals(raw)
    o = solve("flywheel", raw).outputs
    m0 = mp.mpf(v["ball_mass"])
    V0, drop = mp_ball_speed(v, m0, "momentum")
    V1, _ = mp_ball_speed(v, m0 * (1 + mp.mpf(v["ball_mass_tolerance"])), "momentum")
    th, h = mp.mpf(v["launch_angle"]), mp.mpf(v["release_height"])
    ref = mp_range(V1, th, h) / mp_range(V0, th, h) - 1
    assert o["range_error"].value == pytest.approx(float(ref), rel=1e-9)
    # the recovery time uses the drop ω₀ − ω₁ ≈ 6e-5 rad/s of 209 rad/s, formed without cancellation
    sc = fw.scene_from(v)[0]
    w_f, w_t = mp.mpf(sc.free_speed), mp.mpf(v["target_speed"])
    ref_rec = mp.mpf(sc.T) * mp.log((w_f - (w_t - drop)) / (w_f - w_t))
    assert o["recovery_time"].value == pytest.approx(float(ref_rec), rel=1e-9)


def test_target_a_millionth_below_the_free_speed():
    """ω_t = ω_f·(1 − 1e-6): spin-up time T·ln(ω_f/(ω_f − ω_t)) hinges on a difference of nearly
    equal speeds; 1 − ω_t/ω_f and the log must keep their digits (condition ~1e6·ulp)."""
    v0 = vals(SEED)
    sc0 = fw.scene_from(v0)[0]
    target = sc0.free_speed * (1 - 1e-6)
    raw = {**SEED, "target_speed": f"{target!r} rad/s"}
    v = vals(raw)
    o = solve("flywheel", raw).outputs
    # reference from the motor data in mpmath: ω_f = ω̃f/G, T = I·ω̃f/(G²·τ̃s)
    wf_motor = mp.mpf(100) * 2 * mp.pi / 60
    Gr = mp.mpf(v["ratio"])
    tau = 2 * mp.mpf("1.67")
    I = mp.mpf("0.180") * (mp.mpf("0.84") * mp.mpf("0.0635")) ** 2
    w_f = wf_motor / Gr
    T = I * wf_motor / (Gr**2 * tau)
    ref = T * mp.log(w_f / (w_f - mp.mpf(v["target_speed"])))
    assert o["spin_up_time"].value == pytest.approx(float(ref), rel=1e-8)
    assert o["spin_up_time"].value == pytest.approx(float(T) * math.log(1e6), rel=1e-6)


def test_grip_exactly_at_what_the_motor_can_hold():
    """r_w·F = (A − B·ω_t)·(1 + 1e-7): the controller's switch sits at the initial state and the wheel
    sinks by ~1e-7; the integrator must follow the slow exponential, not chatter on the kink."""
    v0 = vals({**SEED, "motor": "Kraken X60", "voltage": 12, "ratio": 0.2})
    sc = fw.scene_from({**v0, "effects": frozenset({"momentum", "motor_during_shot"})})[0]
    w_t = v0["target_speed"]
    F = (sc.A - sc.B * w_t) / sc.r_w * (1 + 1e-7)
    raw = {
        **SEED,
        "motor": "Kraken X60",
        "voltage": 12,
        "ratio": 0.2,
        "grip_force": f"{F!r} N",
        "effects": "momentum, motor_during_shot",
        "accuracy": "tight",
    }
    v = vals(raw)
    o = solve("flywheel", raw).outputs
    I, A, B = mp.mpf(sc.I), mp.mpf(sc.A), mp.mpf(sc.A) / mp.mpf(sc.free_speed)
    r_w, s, m_e, Fm = (
        mp.mpf(sc.r_w),
        mp.mpf(1) / 2,
        mp.mpf(v["ball_mass"]) * mp.mpf("1.4"),
        mp.mpf(v["grip_force"]),
    )
    w_eq = (A - r_w * Fm) / B
    w = lambda t: w_eq + (w_t - w_eq) * mp.exp(-B * t / I)  # noqa: E731
    t_c = mp.findroot(lambda t: Fm * t / (s * m_e) - s * r_w * w(t), s * s * m_e * r_w * w_t / Fm)
    assert o["contact_time"].value == pytest.approx(float(t_c), rel=1e-9)
    assert w_t - o["wheel_speed_after"].value == pytest.approx(float(w_t - w(t_c)), rel=1e-4)
