"""Flywheel scene (seed 000): both transfer models against hand values, the seed's table, limits,
spin-up against the first-order motor solution, the slip phase against its closed form, presets."""

import json
import math
import subprocess
import sys
from pathlib import Path

import mpmath as mp
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core import presets
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import shooter as fw
from gearhead.core.sim.integrate import Event, integrate

ROOT = Path(__file__).resolve().parents[1]
SEED = ROOT / "presets" / "flywheel" / "nbn_seed_single_wheel.toml"
IN = 0.0254
RPM = 2 * math.pi / 60
G = 9.80665

# The seed's scene by hand: 5 in wheel, 180 g, k = 0.84·r; ball 4 in, 60 g, solid (2/5).
R_W = 2.5 * IN  # 0.0635 m
I_1 = 0.180 * (0.84 * R_W) ** 2  # 0.18·(0.05334)² = 5.1213e-4 kg·m²
W_T = 2000 * RPM  # 209.4395 rad/s
# Two VEX 393 at 7.2 V (τs 1.67 N·m, 100 rpm each) through G = 0.04 (1:25 up):
A = 0.04 * 2 * 1.67  # G·τ̃s = 0.1336 N·m at the wheel
W_F = 100 * RPM / 0.04  # ω̃f/G = 261.80 rad/s
B = A / W_F  # G²·τ̃s/ω̃f


def out(raw=None, **kw):
    return solve("flywheel", {**(raw or {}), **kw}).outputs


def vals(**raw):
    return parse_inputs(get("flywheel"), raw)[0]


def seed_raw():
    return presets.load(SEED).inputs


def test_seed_table_linear_column_and_exact_beside_it():
    o = out(seed_raw())
    seed = [-1.42, -0.76, -0.52, -0.40, -0.32]  # the seed's table for e_m = 10 %
    for n, expected in enumerate(seed, start=1):
        assert round(o[f"range_error_linear_{n}"].value * 100, 2) == expected
        # exact (8): β₀ = 0.35/0.84²·(60/180)/n, e_r = −0.1·β₀/(1 + 1.1·β₀)
        b0 = 0.35 / 0.84**2 * (60 / 180) / n
        assert o[f"range_error_{n}"].value == pytest.approx(-0.1 * b0 / (1 + 1.1 * b0), rel=1e-12)
    # n = 1 by hand: β₀ = 0.496032/3 = 0.165344; −0.0165344/1.181878 = −0.013990 (seed: −0.0142)
    assert o["range_error_1"].value == pytest.approx(-0.013990, abs=5e-7)
    assert o["range_error"].value == o["range_error_1"].value
    # the seed's 0.4954 is 0.35/0.84² = 0.35/0.7056 = 0.49603 rounded wrongly
    assert o["mass_ratio_coefficient"].value == pytest.approx(0.496032, abs=1e-6)
    assert o["energy_ratio"].value == pytest.approx(0.165344, abs=1e-6)  # seed: ".165"


def test_energy_model_by_hand():
    o = out(seed_raw())
    # (5): ω₁ = ω₀/√(1 + β) = 209.4395/√1.165344 = 194.0133 rad/s
    w1 = W_T / math.sqrt(1 + 0.35 / 0.84**2 / 3)
    assert w1 == pytest.approx(194.0133, abs=1e-4)
    assert o["wheel_speed_after"].value == pytest.approx(w1, rel=1e-12)
    V = R_W * w1 / 2  # (2): 6.15992 m/s
    assert o["ball_speed"].value == pytest.approx(V, rel=1e-12)
    assert o["ball_spin"].value == pytest.approx(V / (2 * IN), rel=1e-12)
    assert o["ball_energy"].value == pytest.approx(0.7 * 0.06 * V**2, rel=1e-12)  # (3): 0.7·m·V²
    assert o["range"].value == pytest.approx(V**2 / G, rel=1e-12)  # (1) at 45°, h = 0: 3.8693 m
    assert o["rhs_evaluations"].value == 0 and o["error_estimate"].value == 0


def test_momentum_model_reproduces_team_449():
    """REFERENCE_DATA.md: 545.6 rad/s, 13.86 m/s, 184.6 rad/s, 30.49 J."""
    o = out(presets.load(ROOT / "presets" / "flywheel" / "frc_hooded_449.toml").inputs)
    assert o["wheel_speed_after"].value == pytest.approx(545.6, abs=0.05)
    assert o["ball_speed"].value == pytest.approx(13.86, abs=0.005)
    assert o["ball_spin"].value == pytest.approx(184.6, abs=0.05)
    assert o["ball_energy"].value == pytest.approx(30.49, abs=0.005)
    # by hand: m_e = 0.2268 + 5.111e-4/0.07506² = 0.317516; V = I·ω₀/(2I/r_w + r_w·m_e/2)
    V = 1.463e-3 * 622 / (2 * 1.463e-3 / 0.0508 + 0.0508 * 0.317516 / 2)  # 0.909986/0.065663 = 13.858
    assert o["ball_speed"].value == pytest.approx(V, rel=2e-5)  # k_b typed to 5 digits in the preset


def test_two_wheel_shooter_surface_speed_no_spin():
    raw = {**seed_raw(), "shooter": "two_wheel"}
    o = out(raw, effects="momentum")
    b = 0.06 * R_W**2 / I_1  # 0.06·0.0040323/5.1213e-4 = 0.47241 (no spin term)
    assert b == pytest.approx(0.47241, abs=1e-5)
    assert o["wheel_speed_after"].value == pytest.approx(W_T / (1 + b), rel=1e-12)  # 142.24 rad/s
    assert o["ball_speed"].value == pytest.approx(R_W * W_T / (1 + b), rel=1e-12)
    assert o["ball_spin"].value == 0
    e = out(raw, effects="energy")
    assert e["wheel_speed_after"].value == pytest.approx(W_T / math.sqrt(1 + b), rel=1e-12)


def test_momentum_range_error_is_about_twice_the_energy_one():
    b0 = 0.35 / 0.84**2 / 3
    o = out(seed_raw(), effects="momentum")
    # R ∝ V² ∝ 1/(1 + β)²: e_r = ((1 + β₀)/(1 + 1.1·β₀))² − 1
    assert o["range_error"].value == pytest.approx(((1 + b0) / (1 + 1.1 * b0)) ** 2 - 1, rel=1e-12)


def test_loss_fraction():
    b = 0.35 / 0.84**2 / 3
    o = out(seed_raw(), loss_fraction="20 %")
    assert o["wheel_speed_after"].value == pytest.approx(W_T / math.sqrt(1 + b / 0.8), rel=1e-12)
    m = out(seed_raw(), loss_fraction="20 %", effects="momentum")
    assert m["wheel_speed_after"].value == pytest.approx(W_T / (1 + b), rel=1e-12)
    assert m["ball_speed"].value == pytest.approx(R_W / 2 * W_T / (1 + b) * math.sqrt(0.8), rel=1e-12)


def test_limit_zero_ball_mass():
    for effects in ("energy", "momentum", "momentum, motor_during_shot"):
        o = out(seed_raw(), ball_mass=0, effects=effects)
        assert o["wheel_speed_after"].value == W_T
        assert o["ball_speed"].value == pytest.approx(R_W * W_T / 2, rel=1e-15)
        assert o["ball_energy"].value == 0
        assert o["range_error"].value == 0 and o["range_error_3"].value == 0
        assert o["recovery_time"].value == 0


def test_limit_infinite_wheel_inertia_gives_no_range_error():
    raw = {**seed_raw(), "mode": "moment_of_inertia", "wheel_inertia": "1e6 lb*in**2"}
    o = out(raw)
    b0 = 0.06 * 1.4 * (R_W / 2) ** 2 / (1e6 * 0.45359237 * IN**2)  # 1e6 lb·in² = 292.64 kg·m²: β₀ ≈ 2.9e-7
    assert abs(o["range_error"].value) < 1e-7
    assert o["range_error"].value == pytest.approx(-0.1 * b0, rel=1e-6)  # first order in β₀
    sc = fw.scene_from(vals(**raw))[0]
    for I in (1e10, 1e50, 1e200):
        huge = fw.Scene(**{**sc.__dict__, "I": I})
        s0, s1 = fw.shot(huge, W_T, 0.06, W_T, 1e-6), fw.shot(huge, W_T, 0.066, W_T, 1e-6)
        assert s0.omega_after == pytest.approx(W_T, rel=1e-9)
        assert abs(fw.speed_sq_change(huge, 0.06, 0.006, s0, s1)) < 1e-9


def test_spin_up_is_the_first_order_motor_solution():
    o = out(seed_raw())
    T = I_1 * W_F / A  # I·ω̃f/(G²·τ̃s) = 5.1213e-4·261.80/0.1336 = 1.00355 s
    assert o["time_constant"].value == pytest.approx(T, rel=1e-12)
    assert o["free_speed"].value == pytest.approx(W_F, rel=1e-12)
    assert o["spin_up_time"].value == pytest.approx(T * math.log(5), rel=1e-12)  # 2500/(2500−2000) = 5
    w1 = o["wheel_speed_after"].value
    assert o["recovery_time"].value == pytest.approx(T * math.log((W_F - w1) / (W_F - W_T)), rel=1e-12)
    # the plotted spin-up follows ω_f·(1 − e^(−t/T))
    ts, ws = solve("flywheel", seed_raw()).series["wheel speed"]
    for t, w in zip(ts[1:20], ws[1:20]):
        assert w == pytest.approx(W_F * (1 - math.exp(-t / T)), rel=1e-12)


def test_spin_up_integrated_matches_the_closed_form():
    o = out(seed_raw())
    run = integrate(
        lambda t, y: [(A - B * y[0]) / I_1],
        0.0,
        10.0,
        [0.0],
        rtol=1e-11,
        atol=1e-9,
        events=[Event("target", lambda t, y: y[0] - W_T, +1)],
    )
    assert run.event == "target"
    assert run.t[-1] == pytest.approx(o["spin_up_time"].value, rel=1e-9)


def slip_closed_form(I, A_, B_, F, s, m_e, r_w, w0):
    """Wheel decelerating under full power and the grip: ω(t) = ω_eq + (ω₀ − ω_eq)·e^(−B·t/I),
    V(t) = F·t/(s·m_e); the slip ends when V = s·r_w·ω (mpmath root)."""
    mp.mp.dps = 30
    w_eq = (A_ - r_w * F) / B_
    w = lambda t: w_eq + (w0 - w_eq) * mp.exp(-B_ * t / I)  # noqa: E731
    t_c = mp.findroot(lambda t: F * t / (s * m_e) - s * r_w * w(t), s * s * m_e * r_w * w0 / F)
    return float(t_c), float(w(t_c)), float(F * t_c / (s * m_e))


def test_motor_during_shot_slip_phase_matches_closed_form():
    raw = {**seed_raw(), "effects": "momentum, motor_during_shot", "accuracy": "fine"}
    o = out(raw)  # 393s cannot hold 2000 rpm against r_w·F = 0.0635·40 = 2.54 N·m > A − B·ω_t = 0.0267
    t_c, w1, V = slip_closed_form(I_1, A, B, 40.0, 0.5, 0.06 * 1.4, R_W, W_T)
    assert o["contact_time"].value == pytest.approx(t_c, rel=1e-8)
    assert o["wheel_speed_after"].value == pytest.approx(w1, rel=1e-8)
    assert o["ball_speed"].value == pytest.approx(V, rel=1e-8)
    assert o["rhs_evaluations"].value > 0
    assert o["error_estimate"].value < 1e-8
    # and the motor adds angular impulse: the ball is faster than with the motor off
    assert o["ball_speed"].value > out(raw, effects="momentum")["ball_speed"].value


def test_motor_during_shot_strong_motor_holds_the_target():
    # two Kraken X60 through G = 0.2: A = 0.2·14.18 = 2.836 N·m, ω_f = 3141.6 rad/s,
    # A − B·ω_t = 2.836·(1 − 209.44/3141.6) = 2.647 N·m ≥ r_w·F = 0.0635·40 = 2.54 N·m: the wheel holds ω_t
    raw = {
        **seed_raw(),
        "effects": "momentum, motor_during_shot",
        "motor": "Kraken X60",
        "voltage": 12,
        "ratio": 0.2,
        "accuracy": "fine",
    }
    o = out(raw)
    assert o["wheel_speed_after"].value == pytest.approx(W_T, rel=1e-9)
    assert o["ball_speed"].value == pytest.approx(R_W / 2 * W_T, rel=1e-9)
    # t_c = s²·m_e·r_w·ω_t/F = 0.25·0.084·0.0635·209.44/40 = 6.982 ms
    assert o["contact_time"].value == pytest.approx(0.25 * 0.084 * R_W * W_T / 40, rel=1e-9)
    assert o["range_error"].value == pytest.approx(0, abs=1e-9)


def test_motor_during_shot_with_infinite_grip_is_the_impulse_model():
    raw = {**seed_raw(), "grip_force": "1e5 N"}
    fast = out(raw, effects="momentum, motor_during_shot")
    instant = out(raw, effects="momentum")
    assert fast["wheel_speed_after"].value == pytest.approx(instant["wheel_speed_after"].value, rel=1e-4)


def test_energy_model_ignores_motor_during_shot_with_a_warning():
    sol = solve("flywheel", {**seed_raw(), "effects": "energy, motor_during_shot"})
    assert any("motor_during_shot" in w for w in sol.warnings)
    assert sol.outputs["ball_speed"].value == out(seed_raw())["ball_speed"].value


def test_burst_recovery_between_shots_is_closed_form():
    o = out(seed_raw(), shots=2, shot_interval="0.1 s")
    T = I_1 * W_F / A
    k = 1 / math.sqrt(1 + 0.35 / 0.84**2 / 3)
    w1 = W_T * k
    w2 = W_F - (W_F - w1) * math.exp(-0.1 / T)  # full power for 0.1 s, still below the target
    assert o["slowest_ball_speed"].value == pytest.approx(R_W / 2 * w2 * k, rel=1e-12)
    assert out(seed_raw(), shot_interval="2 s")["slowest_ball_speed"].value == o["ball_speed"].value


def test_range_from_release_height():
    o = out(seed_raw(), release_height="1 m", launch_angle="30 deg")
    V, th, h = o["ball_speed"].value, math.radians(30), 1.0
    # root of y(x) = h + x·tanθ − g·x²/(2V²cos²θ): x = (tanθ + √(tan²θ + 2gh/(V²cos²θ)))·V²cos²θ/g
    c2 = (V * math.cos(th)) ** 2
    x = (math.tan(th) + math.sqrt(math.tan(th) ** 2 + 2 * G * h / c2)) * c2 / G
    assert o["range"].value == pytest.approx(x, rel=1e-12)


@pytest.mark.parametrize(
    "raw,field",
    [
        ({"target_speed": "2500 rpm"}, "target_speed"),  # exactly the free speed: never reached
        ({"effects": "energy, momentum"}, "effects"),  # an old preset naming both transfer models
        ({"transfer": "impulse"}, "transfer"),
    ],
)
def test_errors_name_the_field(raw, field):
    with pytest.raises(InputError) as e:
        solve("flywheel", {**seed_raw(), **raw})
    assert e.value.field == field


scene_params = st.fixed_dictionaries(
    {
        "I": st.floats(1e-6, 10),
        "m": st.floats(0, 5),
        "r_w": st.floats(0.01, 0.3),
        "f": st.floats(0, 0.9),
        "w0": st.floats(1, 2000),
        "hood": st.booleans(),
        "k_b": st.floats(0, 0.67),
    }
)


def scene(p, model):
    hood = p["hood"]
    return fw.Scene(
        r_w=p["r_w"],
        I=p["I"],
        r_b=0.05,
        k_b=p["k_b"],
        s=0.5 if hood else 1.0,
        sigma=1.0 if hood else 0.0,
        f=p["f"],
        model=model,
        motor_on=False,
        A=1.0,
        free_speed=1e3,
        grip=10.0,
    )


@settings(max_examples=200, deadline=None)
@given(scene_params)
def test_energy_model_balances_and_reverses(p):
    sc = scene(p, "energy")
    s = fw.shot(sc, p["w0"], p["m"], p["w0"], 1e-6)
    E0, E1 = 0.5 * sc.I * p["w0"] ** 2, 0.5 * sc.I * s.omega_after**2
    assert E0 == pytest.approx(E1 + s.energy / (1 - p["f"]), rel=1e-12)  # (5) with losses
    assert s.omega_after * math.sqrt(1 + fw.beta(sc, p["m"]) / (1 - p["f"])) == pytest.approx(
        p["w0"], rel=1e-13
    )


@settings(max_examples=200, deadline=None)
@given(scene_params)
def test_momentum_model_conserves_angular_impulse(p):
    sc = scene(p, "momentum")
    s = fw.shot(sc, p["w0"], p["m"], p["w0"], 1e-6)
    m_e = p["m"] * (1 + sc.sigma * sc.k_b)
    J = sc.s * m_e * s.V / math.sqrt(1 - p["f"])  # impulse on the ball before the compression loss
    assert sc.I * (p["w0"] - s.omega_after) == pytest.approx(sc.r_w * J, rel=1e-9, abs=1e-12 * sc.I * p["w0"])


@settings(max_examples=200, deadline=None)
@given(st.floats(1e-3, 1e3), st.floats(0, 1e3), st.floats(0.01, 10))
def test_recovery_reverses_free_run(w_frac, dt, T_scale):
    sc = fw.Scene(
        r_w=0.05,
        I=T_scale * 1e-3,
        r_b=0.05,
        k_b=0.4,
        s=0.5,
        sigma=1.0,
        f=0.0,
        model="energy",
        motor_on=False,
        A=1.0,
        free_speed=1e3,
        grip=10.0,
    )  # free speed 1000 rad/s, T = T_scale s
    w0 = min(w_frac, 999.0)
    dt = dt * sc.T / 100
    w1 = fw.free_run(sc, w0, dt)
    if w1 < sc.free_speed * (1 - 1e-9):
        assert fw.recovery(sc, w0, w1) == pytest.approx(dt, rel=1e-7, abs=1e-12)


def test_presets_load_and_solve():
    found = [p for p in presets.listing("flywheel") if p.builtin]
    assert len(found) == 8  # issue 31 added dual, compound and hood_secondary; issue 30 the velocity loop
    for p in found:
        sol = solve("flywheel", p.inputs)
        assert sol.outputs["ball_speed"].value > 0


def test_cli_json_reproduces_the_seed_table():
    cmd = [sys.executable, "-m", "gearhead.tui", "solve", "flywheel", "--preset", str(SEED), "--json"]
    data = json.loads(subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=True).stdout)
    o = data["outputs"]
    assert [round(o[f"range_error_linear_{n}"]["value"] * 100, 2) for n in range(1, 6)] == [
        -1.42,
        -0.76,
        -0.52,
        -0.40,
        -0.32,
    ]
    for name in (
        "ball_speed",
        "ball_spin",
        "ball_energy",
        "energy_ratio",
        "wheel_speed_after",
        "range",
        "range_error",
        "range_error_linear",
        "spin_up_time",
        "recovery_time",
        "range_error_6",
    ):
        assert name in o
    assert o["ball_speed"]["unit"] == "m/s" and o["range_error"]["unit"] == ""


@pytest.mark.parametrize("b", [1e-3, 1.0, 150.0])
@pytest.mark.parametrize("a_over_b,u_t", [(0.3, 1.0), (5.0, 1.0), (5.0, 1.4), (1.2, 1.4), (-2.0, 1.2)])
def test_slip_phase_integrated_equals_its_closed_form(b, a_over_b, u_t):
    """The integrated slip (DP54 with the controller's switch, event at rolling) against the closed
    form the stiff branch uses, on both sides of the switch and below the stiffness threshold."""
    span = max(1.0, u_t) * (1 + 1e-9) + 1e-12
    a = a_over_b * b
    tau, u = fw.slip_closed_form(a, b, u_t, span)
    rhs = lambda t, y: [min(a - b * y[0], 0.0) if y[0] >= u_t else a - b * y[0], 1.0]  # noqa: E731
    run = integrate(
        rhs,
        0.0,
        span,
        [1.0, 0.0],
        rtol=1e-11,
        atol=1e-14,
        events=[Event("rolling", lambda t, y: y[0] - y[1], -1)],
    )
    assert run.event == "rolling"
    assert run.t[-1] == pytest.approx(tau, rel=1e-8)
    assert run.y[-1][0] == pytest.approx(u, rel=1e-8)


def test_stiff_slip_uses_the_closed_form_and_stays_finite():
    # a wheel of 1e-9 lb·in² on two Krakens: its time constant is ~1e-10 s against a ~7 ms slip
    raw = {
        **seed_raw(),
        "mode": "moment_of_inertia",
        "wheel_inertia": "1e-9 lb*in**2",
        "motor": "Kraken X60",
        "voltage": 12,
        "ratio": 0.2,
        "effects": "momentum, motor_during_shot",
    }
    o = out(raw)
    assert o["rhs_evaluations"].value == 0
    # held at the target (A − B·ω_t = 2.647 N·m ≥ r_w·F = 2.54 N·m): V = s·r_w·ω_t
    assert o["ball_speed"].value == pytest.approx(R_W / 2 * W_T, rel=1e-12)


@pytest.mark.parametrize("omega0_frac,grip", [(0.7, 40.0), (0.95, 2.0), (0.5, 400.0), (1.0, 40.0)])
def test_module_slip_phase_below_the_target_matches_the_closed_form(omega0_frac, grip):
    """A shot in an unrecovered burst starts below the target: the wheel may reach the target during
    the slip (event "target") and is then held; compare with the closed form at rtol 1e-11."""
    sc = fw.Scene(
        r_w=R_W,
        I=I_1,
        r_b=2 * IN,
        k_b=0.4,
        s=0.5,
        sigma=1.0,
        f=0.0,
        model="momentum",
        motor_on=True,
        A=2.836,
        free_speed=3141.6,
        grip=grip,
    )
    w0, m_e = W_T * omega0_frac, 0.06 * 1.4
    w1, V, t_c, nfev = fw.slip_phase(sc, w0, m_e, W_T, 1e-11)
    t0 = 0.25 * m_e * R_W * w0 / grip
    a, b, u_t = t0 * (sc.A - R_W * grip) / (I_1 * w0), t0 * sc.B / I_1, W_T / w0
    tau, u = fw.slip_closed_form(a, b, u_t, max(1.0, u_t) * (1 + 1e-9) + 1e-12)
    assert t_c == pytest.approx(tau * t0, rel=1e-9)
    assert w1 == pytest.approx(u * w0, rel=1e-9)
    assert V == pytest.approx(0.5 * R_W * w1, rel=1e-9)  # rolling at the end
    assert w1 <= W_T * (1 + 1e-12)


@pytest.mark.parametrize("rpm", [2000, 2389])  # 2389: t_spin·24/24 rounds below t_spin
def test_burst_plot_starts_at_the_target_then_drops_by_the_first_shot(rpm):
    sol = solve("flywheel", {**seed_raw(), "target_speed": f"{rpm} rpm"})
    ts, ws = sol.series["burst"]
    w_t = rpm * RPM
    T = I_1 * W_F / A
    t_spin = T * math.log(W_F / (W_F - w_t))  # full power from rest: ω_f·(1 − e^(−t/T)) = ω_t
    assert ts[0] == pytest.approx(t_spin, rel=1e-12) and ws[0] == pytest.approx(w_t, rel=1e-12)
    # energy model, contact time 0: the drop is vertical, to ω_t/√(1 + β)
    assert ts[1] == pytest.approx(t_spin, rel=1e-12)
    assert ws[1] == pytest.approx(w_t / math.sqrt(1 + 0.35 / 0.84**2 / 3), rel=1e-12)
    assert all(b >= a for a, b in zip(ts, ts[1:]))


def test_range_spread_and_range_error_with_losses_by_hand():
    b0 = 0.35 / 0.84**2 / 3  # β₀ = 0.165344
    o = out(seed_raw())
    # R ∝ 1/(1 + β): light ball (1 − e_m) minus heavy ball (1 + e_m), R₀ = V²/g at 45°
    # = R₀·(1 + β₀)·(1/(1 + 0.9·β₀) − 1/(1 + 1.1·β₀)) = 3.8693·1.165344·0.028386 = 0.10982 m
    spread = o["range"].value * (1 + b0) * (1 / (1 + 0.9 * b0) - 1 / (1 + 1.1 * b0))
    assert o["range_spread"].value == pytest.approx(spread, rel=1e-12)
    assert o["range_spread"].value == pytest.approx(0.10982, abs=1e-5)
    # energy model with 20 % loss: ω₁² ∝ 1/(1 + β/0.8), so e_r = (1 + β₀/0.8)/(1 + 1.1·β₀/0.8) − 1
    lossy = out(seed_raw(), loss_fraction="20 %")
    assert lossy["range_error"].value == pytest.approx((1 + b0 / 0.8) / (1 + 1.1 * b0 / 0.8) - 1, rel=1e-12)
    assert lossy["range_error_2"].value == pytest.approx((1 + b0 / 1.6) / (1 + 1.1 * b0 / 1.6) - 1, rel=1e-12)


def test_motor_during_shot_range_error_and_wheel_table_against_the_closed_form():
    """393s cannot hold the target against the grip, so each shot is the decelerating slip of
    `slip_closed_form` (mpmath); R ∝ V² at 45°, h = 0; n wheels: I = n·I₁ with the same motor."""
    raw = {**seed_raw(), "effects": "momentum, motor_during_shot", "accuracy": "fine"}
    o = out(raw)
    for n in (1, 2, 6):
        _, _, V0 = slip_closed_form(n * I_1, A, B, 40.0, 0.5, 0.06 * 1.4, R_W, W_T)
        _, _, V1 = slip_closed_form(n * I_1, A, B, 40.0, 0.5, 0.066 * 1.4, R_W, W_T)
        assert o[f"range_error_{n}"].value == pytest.approx((V1 / V0) ** 2 - 1, rel=1e-6)
    assert o["range_error"].value == o["range_error_1"].value


def test_motor_during_shot_burst_waits_the_interval_from_shot_to_shot():
    """Shot 1 from ω_t slips for t_c; the motor then has 0.1 s − t_c at full power before shot 2,
    which starts below the target and (393s, u_eq < 0) keeps decelerating until the ball rolls."""
    sol = solve(
        "flywheel",
        {
            **seed_raw(),
            "effects": "momentum, motor_during_shot",
            "accuracy": "fine",
            "shots": 2,
            "shot_interval": "0.1 s",
        },
    )
    T = I_1 * W_F / A
    t_c, w1, V1 = slip_closed_form(I_1, A, B, 40.0, 0.5, 0.084, R_W, W_T)
    w2 = W_F - (W_F - w1) * math.exp(-(0.1 - t_c) / T)
    assert w2 < W_T
    _, _, V2 = slip_closed_form(I_1, A, B, 40.0, 0.5, 0.084, R_W, w2)
    assert sol.outputs["ball_speed"].value == pytest.approx(V1, rel=1e-8)
    assert sol.outputs["slowest_ball_speed"].value == pytest.approx(V2, rel=1e-8)
    assert any("does not recover" in w for w in sol.warnings)
    ts, ws = sol.series["burst"]
    assert ts[1] - ts[0] == pytest.approx(t_c, rel=1e-8)  # the slip, then the recovery ramp
    drops = [i for i in range(len(ws) - 1) if ws[i + 1] < ws[i]]  # the two slips
    assert len(drops) == 2 and drops[0] == 0
    i2 = drops[1]
    assert ts[i2] == pytest.approx(ts[0] + 0.1, rel=1e-12)  # shot 2 starts one interval after shot 1
    assert ws[i2] == pytest.approx(w2, rel=1e-8)
    calm = solve("flywheel", {**seed_raw(), "effects": "momentum, motor_during_shot", "shot_interval": "2 s"})
    assert not any("does not recover" in w for w in calm.warnings)


def test_momentum_model_warns_that_the_seed_linear_column_is_the_energy_model():
    sol = solve("flywheel", {**seed_raw(), "effects": "momentum"})
    b0 = 0.35 / 0.84**2 / 3
    assert sol.outputs["range_error_linear"].value == pytest.approx(-0.1 * b0 / (1 + b0), rel=1e-12)
    assert any("seed linear" in w for w in sol.warnings)
    assert not any("seed linear" in w for w in solve("flywheel", seed_raw()).warnings)


def test_weak_grip_warns_that_the_ball_leaves_while_slipping():
    # F = 1 N: the 393s cannot hold the target; the slip lasts ~0.26 s and the ball, accelerating
    # uniformly from rest, covers V·t_c/2 ≈ 6.13·0.2575/2 ≈ 0.79 m before rolling
    raw = {**seed_raw(), "effects": "momentum, motor_during_shot", "grip_force": "1 N"}
    sol = solve("flywheel", raw)
    t_c, _, V = slip_closed_form(I_1, A, B, 1.0, 0.5, 0.084, R_W, W_T)
    assert V * t_c / 2 == pytest.approx(0.79, abs=0.01)
    assert any("slips 0.79" in w for w in sol.warnings)
    assert not any("slips" in w for w in solve("flywheel", {**raw, "grip_force": "40 N"}).warnings)


def test_fields_shown_only_where_used():
    calc = get("flywheel")
    grip, k_b = calc.field("grip_force"), calc.field("ball_inertia_factor")
    assert not grip.active("radius_of_gyration", {"effects": frozenset({"energy"}), "shooter": "hood"})
    assert grip.active(
        "radius_of_gyration", {"effects": frozenset({"momentum", "motor_during_shot"}), "shooter": "hood"}
    )
    assert k_b.active("radius_of_gyration", {"effects": frozenset({"energy"}), "shooter": "hood"})
    assert not k_b.active("radius_of_gyration", {"effects": frozenset({"energy"}), "shooter": "two_wheel"})


def test_mass_bounds_are_physical_in_si():
    """Bounds are SI (kg): a 6 kg game piece or a 60 kg wheel is a typo, refused naming the field;
    the heaviest real game pieces (a 2023 cone, 0.65 kg) are accepted."""
    from gearhead.core.errors import InputError
    from gearhead.core.model import solve

    solve("flywheel", {"ball_mass": "650 g"})
    with pytest.raises(InputError) as info:
        solve("flywheel", {"ball_mass": "6 kg"})
    assert info.value.field == "ball_mass"
    with pytest.raises(InputError) as info:
        solve("flywheel", {"mode": "radius_of_gyration", "wheel_mass": "60 kg"})
    assert info.value.field == "wheel_mass"
