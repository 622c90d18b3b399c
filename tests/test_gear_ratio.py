"""Gear-ratio calculator, seed section 2: every mode against hand-derived values, and inverse
modes reproduce their target through the forward equations (11)-(17)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core import motors
from gearhead.core.errors import InputError
from gearhead.core.model import solve

LBF = 4.4482216152605
IN = 0.0254
RPM = 2 * math.pi / 60


def out(**raw):
    return {k: v.value for k, v in solve("gear_ratio", raw).outputs.items()}


def kraken(n=1, V=12.0, eta=1.0):
    return motors.system(motors.lookup("Kraken X60", "wpilib")[0], n, V, eta)


def test_max_power_hand_values():
    # Kraken X60: τs = 7.09 N*m, 150 lbf at 1 in: G = 2rF/τs (19)
    o = out(load="150 lbf", radius="1 in", mode="max_power")
    G = 2 * IN * 150 * LBF / 7.09
    assert o["ratio"] == pytest.approx(G, rel=1e-12)
    assert o["loaded_speed"] == pytest.approx(o["free_speed"] / 2, rel=1e-12)  # (18)
    assert o["output_power"] == pytest.approx(6000 * RPM * 7.09 / 4, rel=1e-12)  # peak power


def test_max_efficiency_ratio_eq20():
    o = out(load="150 lbf", radius="1 in", mode="max_efficiency")
    G = IN * 150 * LBF / 7.09 * (1 + math.sqrt(366 / 2))
    assert o["ratio"] == pytest.approx(G, rel=1e-12)


def test_stall_mode_loaded_speed_is_zero():
    o = out(mode="stall")
    assert o["loaded_speed"] == pytest.approx(0, abs=1e-12)
    assert o["stall_load"] == pytest.approx(150 * LBF, rel=1e-12)


def test_rotational_speed_both_roots_and_efficient_one_first():
    o = out(load="150 lbf", radius="1 in", mode="rotational_speed", target_rotational_speed="300 rpm")
    w, F, r = 300 * RPM, 150 * LBF, IN
    wf, ts = 6000 * RPM, 7.09
    disc = math.sqrt(1 - 4 * r * F * w / (ts * wf))
    assert o["ratio"] == pytest.approx(wf / (2 * w) * (1 + disc), rel=1e-12)  # (24) corrected with r
    assert o["ratio_alternative"] == pytest.approx(wf / (2 * w) * (1 - disc), rel=1e-9)
    assert o["loaded_speed"] == pytest.approx(w, rel=1e-12)
    alt = out(load="150 lbf", radius="1 in", mode="ratio", ratio=o["ratio_alternative"])
    assert alt["loaded_speed"] == pytest.approx(w, rel=1e-9)
    assert alt["current_per_motor"] > o["current_per_motor"]  # the shown root is the efficient one


def test_speed_exactly_at_peak_power_gives_one_ratio():
    m = kraken()
    F, r = 150 * LBF, IN
    w_peak = m.free_speed * m.stall_torque / (4 * r * F)
    o = out(load="150 lbf", radius="1 in", mode="rotational_speed", target_rotational_speed=f"{w_peak} rad/s")
    assert o["ratio"] == pytest.approx(2 * r * F / m.stall_torque, rel=1e-7)
    assert math.isfinite(o["ratio"])


def test_unreachable_speed_is_a_message_not_nan():
    with pytest.raises(InputError) as e:
        out(load="150 lbf", radius="1 in", mode="rotational_speed", target_rotational_speed="3000 rpm")
    assert e.value.field == "target_rotational_speed" and "peak power" in e.value.message


def test_linear_speed_mode_eq25():
    o = out(load="40 lbf", radius="0.75 in", mode="linear_speed", target_linear_speed="5 ft/s")
    assert o["linear_loaded_speed"] == pytest.approx(5 * 0.3048, rel=1e-12)


def test_current_mode_uses_adjusted_free_current():
    # with n = 2 and V = 10 V the seed's (26) with raw i_f would miss the target; ĩf hits it
    o = out(motor_count=2, voltage="10 V", mode="current", target_current="30 A")
    assert o["current_per_motor"] == pytest.approx(30, rel=1e-12)
    m = kraken(2, 10.0)
    G_seed = IN * 150 * LBF / (m.kt * (2 * 30 - 2.0))  # (26) as printed, raw i_f = 2 A
    assert abs(G_seed - o["ratio"]) / o["ratio"] > 1e-3


def test_stall_voltage_uses_raw_stall_torque_and_motor_spec_voltage():
    o = out(
        motor="VEX 393",
        motor_count=2,
        voltage="7.2 V",
        efficiency=0.8,
        load="10 lbf",
        radius="1 in",
        mode="stall_voltage",
        target_stall_voltage="3 V",
    )
    # at 3 V the stall load must equal the load: run forward at 3 V with that ratio
    at_vs = out(
        motor="VEX 393",
        motor_count=2,
        voltage="3 V",
        efficiency=0.8,
        load="10 lbf",
        radius="1 in",
        mode="ratio",
        ratio=o["ratio"],
    )
    assert at_vs["stall_load"] == pytest.approx(10 * LBF, rel=1e-12)
    assert o["stall_voltage"] == pytest.approx(3, rel=1e-12)


@pytest.mark.parametrize(
    "mode,field,value",
    [
        ("current", "target_current", "1 A"),  # below free current per motor
        ("current", "target_current", "400 A"),  # above stall current
        ("stall_load", "target_stall_load", "100 lbf"),  # below the load
        ("stall_voltage", "target_stall_voltage", "13 V"),  # above applied voltage
    ],
)
def test_impossible_targets_name_their_field(mode, field, value):
    with pytest.raises(InputError) as e:
        out(mode=mode, **{field: value})
    assert e.value.field == field


motor_names = st.sampled_from(["CIM", "NEO", "Kraken X60", "Falcon 500", "775pro", "V5 100 rpm (red)"])


@settings(max_examples=120, deadline=None)
@given(
    motor=motor_names,
    n=st.integers(1, 4),
    V=st.floats(6, 13),
    eta=st.floats(0.5, 1),
    F=st.floats(1, 2000),
    r=st.floats(0.005, 0.5),
    frac=st.floats(0.01, 0.99),
)
def test_inverse_modes_reproduce_their_targets(motor, n, V, eta, F, r, frac):
    base = dict(motor=motor, motor_count=n, voltage=V, efficiency=eta, load=f"{F} N", radius=f"{r} m")
    m = motors.system(motors.lookup(motor, "wpilib")[0], n, V, eta)
    # speed: a fraction of the fastest reachable loaded speed
    w = frac * m.free_speed * m.stall_torque / (4 * r * F)
    o = out(**base, mode="rotational_speed", target_rotational_speed=f"{w} rad/s")
    assert o["loaded_speed"] == pytest.approx(w, rel=1e-9)
    v = w * r
    o = out(**base, mode="linear_speed", target_linear_speed=f"{v} m/s")
    assert o["linear_loaded_speed"] == pytest.approx(v, rel=1e-9)
    i = (m.free_current + frac * (m.stall_current - m.free_current)) / n
    o = out(**base, mode="current", target_current=f"{i} A")
    assert o["current_per_motor"] == pytest.approx(i, rel=1e-9)
    Fs = F * (1 + 10 * frac)
    o = out(**base, mode="stall_load", target_stall_load=f"{Fs} N")
    assert o["stall_load"] == pytest.approx(Fs, rel=1e-9)
    Vs = V * frac
    o = out(**base, mode="stall_voltage", target_stall_voltage=f"{Vs} V")
    assert o["stall_voltage"] == pytest.approx(Vs, rel=1e-9)
    assert o["stall_load"] == pytest.approx(F * V / Vs, rel=1e-9)  # F_s/F = V/V_s
    o = out(**base, mode="max_power")
    assert o["output_power"] == pytest.approx(m.peak_power, rel=1e-9)


def test_max_power_linear_speed_and_efficiency_at_10_volts_by_hand():
    # Kraken X60 at 10 V: ω̃f = 523.599 rad/s, τ̃s = 7.09·10/12 = 5.90833 N*m,
    # ĩs = 305 A, ĩf = 1.66667 A; F = 150 lbf = 667.233 N.
    # (19) G = 2rF/τ̃s, so (14) v_free = ω̃f·r/G = ω̃f·τ̃s/(2F) = 3093.58/1334.47 = 2.31823 m/s
    # at Fs = 2F the input torque is τ̃s/2: i = (ĩs − ĩf)/2 + ĩf = 153.333 A in all;
    # P = ω̃f·τ̃s/4 = 773.399 W;  η = P/(V·i) = 773.399/(10·153.333) = 0.504391
    o = out(voltage="10 V", mode="max_power")
    assert o["linear_free_speed"] == pytest.approx(2.31823, rel=1e-5)
    assert o["system_efficiency"] == pytest.approx(0.504391, rel=1e-5)


@pytest.mark.parametrize("motor", ["CIM", "NEO", "V5 100 rpm (red)"])
def test_max_efficiency_mode_lands_on_the_motor_max_efficiency_point(motor):
    # (20) is (91) seen from the output: the gearbox input torque rF/G must be τ_ηmax and the
    # efficiency there the Appendix A maximum, at any n, V, η
    system = dict(motor=motor, motor_count=3, voltage="11 V", efficiency=0.8)
    g = out(**system, mode="max_efficiency")
    m = motors.system(motors.lookup(motor, "wpilib")[0], 3, 11.0, 0.8)
    assert g["motor_torque"] == pytest.approx(m.max_efficiency_torque, rel=1e-12)
    assert g["system_efficiency"] == pytest.approx(m.max_efficiency, rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(
    motor=motor_names,
    n=st.integers(1, 6),
    V=st.floats(3, 13),
    eta=st.floats(0.3, 1),
    F=st.floats(1, 1000),
    r=st.floats(0.001, 1),
)
def test_stall_mode_is_exactly_stalled_and_not_back_driven(motor, n, V, eta, F, r):
    # G = rF/τ̃s (22) makes F_s = F exactly; F/F_s rounding to 1 + 1 ulp used to show a loaded
    # speed of −3e-17 rpm and the "back-driven" warning beside "holds the load" (10 % of inputs)
    s = solve(
        "gear_ratio",
        dict(
            motor=motor,
            motor_count=n,
            voltage=f"{V!r} V",
            efficiency=eta,
            load=f"{F!r} N",
            radius=f"{r!r} m",
            mode="stall",
        ),
    )
    assert s.outputs["loaded_speed"].value == 0 and s.outputs["output_power"].value == 0
    assert not any("back-driven" in w for w in s.warnings)
    assert s.outputs["stall_load"].value == pytest.approx(F, rel=1e-14)
