"""Drivetrain calculator, seed section 4: hand values for each mode, reverse(forward) round trips,
and the shift speed checked against the force balance (99)-(100) it comes from."""

import math

import pytest
from hypothesis import assume, given, settings, strategies as st

from core import motors
from core.errors import InputError
from core.model import solve

IN = 0.0254
FT = 0.3048
LBF = 4.4482216152605
RPM = 2 * math.pi / 60


def sol(**raw):
    return solve("drivetrain", raw)


def out(**raw):
    return {k: v.value for k, v in sol(**raw).outputs.items()}


def test_forward_defaults_by_hand():
    # 4 Kraken X60 (WPILib: 6000 rpm, 7.09 N·m, 366 A, 2 A), 12 V, η = 1, 4 in wheels, G = 6.12
    # (37) v_free = 628.3185 rad/s · 0.0508 m / 6.12 = 5.21546 m/s = 17.1111 ft/s
    # (38) v_adj = 0.81 · 5.21546 = 4.22452 m/s = 13.8600 ft/s
    # (7)  K_T = 4·7.09 / (4·366 − 4·2) = 28.36/1456 = 0.0194780 N·m/A
    # (39) μ·W̃ = 1.1 · 667.233 N = 733.957 N; ·d/2 = 37.2850 N·m; /G = 6.09232 N·m;
    #      /K_T = 312.78 A; + ĩf = 8 A → 320.78 A in all, 80.195 A per motor
    o = out()
    assert o["free_speed"] == pytest.approx(17.1111 * FT, rel=1e-5)
    assert o["adjusted_speed"] == pytest.approx(13.8600 * FT, rel=1e-5)
    assert o["slip_current"] == pytest.approx(80.195, rel=1e-4)
    assert o["slip_current_total"] == pytest.approx(320.78, rel=1e-4)
    # traction 733.96 N = 165 lbf, below the stall force 28.36·6.12/0.0508 = 3416.6 N
    assert o["pushing_force"] == pytest.approx(165 * LBF, rel=1e-12)


def test_reverse_defaults_by_hand():
    # (41) i_tot = (12.7 − 7) / (0.015 + 0.002 + 0.006/4) = 5.7/0.0185 = 308.108 A
    # (42) G = 1.1·0.1016·667.233 / (2·0.0194780·(308.108 − 8)) = 74.5703/11.6910 = 6.3784
    o = out(mode="reverse")
    assert o["total_current"] == pytest.approx(308.108, rel=1e-5)
    assert o["max_ratio"] == pytest.approx(6.3784, rel=1e-4)
    # at that ratio the wheels slip exactly at the allowed current
    assert o["slip_current_total"] == pytest.approx(o["total_current"], rel=1e-12)


def test_shifting_defaults_by_hand():
    # v1 = 628.3185·0.0508/15 = 2.12792 m/s = 6.9813 ft/s; v2 = ·/6 = 5.31980 m/s = 17.453 ft/s
    # (40) v_shift = v1·v2/(v1 + v2) = ωf·r/(G1 + G2) = 31.9186/21 = 1.51993 m/s = 4.9867 ft/s
    o = out(mode="shifting")
    assert o["low_free_speed"] == pytest.approx(6.9813 * FT, rel=1e-4)
    assert o["high_free_speed"] == pytest.approx(17.453 * FT, rel=1e-4)
    assert o["shift_speed"] == pytest.approx(4.9867 * FT, rel=1e-4)


def test_cli_names_in_each_mode():
    assert {"free_speed", "adjusted_speed", "slip_current"} <= set(out())
    assert {"total_current", "max_ratio", "free_speed", "adjusted_speed"} <= set(out(mode="reverse"))
    assert {"shift_speed"} <= set(out(mode="shifting"))


def test_motors_stall_before_the_wheels_slip():
    # G = 1: stall force 28.36/0.0508 = 558.3 N < traction 733.96 N
    s = sol(ratio=1)
    assert s.outputs["pushing_force"].value == pytest.approx(28.36 / 0.0508, rel=1e-12)
    assert any("stall before the wheels slip" in w for w in s.warnings)


def test_reverse_budget_above_stall_current_gives_the_stall_ratio():
    # R = 0.001 + 0 + 0: i_tot = 5.7 V/0.001 Ω = 5700 A > ĩs = 4·366 = 1464 A.
    # (42) would give G = 74.5703/(2·0.0194780·(5700 − 8)) = 0.33630, where the stall force
    # 28.36·0.33630/0.0508 = 187.7 N is far below traction 733.96 N: the motors stall first.
    # Fastest ratio that slips: G = μ·W̃·r/τ̃s = 733.957·0.0508/28.36 = 1.31470
    s = sol(mode="reverse", battery_resistance="0.001 ohm", main_resistance=0, branch_resistance=0)
    o = {k: v.value for k, v in s.outputs.items()}
    assert o["total_current"] == pytest.approx(5700, rel=1e-12)
    assert o["max_ratio"] == pytest.approx(1.31470, rel=1e-5)
    assert o["pushing_force"] == pytest.approx(165 * LBF, rel=1e-12)
    assert o["slip_current_total"] == pytest.approx(4 * 366, rel=1e-12)  # slips exactly at stall
    assert any("stall current" in w for w in s.warnings)
    assert not any("stall before the wheels slip" in w for w in s.warnings)


@pytest.mark.parametrize("raw,field", [
    ({"min_voltage": "13 V"}, "min_voltage"),  # above the battery
    ({"battery_resistance": 0, "main_resistance": 0, "branch_resistance": 0}, "battery_resistance"),
    ({"battery_resistance": "5 ohm"}, "min_voltage"),  # 5.7 V / 5 Ω < the 8 A free current
])
def test_reverse_impossible_budgets_name_a_field(raw, field):
    with pytest.raises(InputError) as e:
        out(mode="reverse", **raw)
    assert e.value.field == field


motor_names = st.sampled_from(["CIM", "NEO", "Kraken X60", "Falcon 500", "NEO Vortex", "V5 200 rpm (green)"])


@settings(max_examples=150, deadline=None)
@given(motor=motor_names, n=st.integers(1, 8), V=st.floats(6, 13), eta=st.floats(0.5, 1),
       d=st.floats(0.03, 0.2), W=st.floats(10, 3000), mu=st.floats(0.2, 1.6), G=st.floats(1, 40),
       V_min=st.floats(3, 9), R_br=st.one_of(st.just(0.0), st.floats(1e-5, 0.05)))
def test_reverse_of_forward_returns_the_ratio(motor, n, V, eta, d, W, mu, G, V_min, R_br):
    """Forward slip current at G; a battery budget allowing exactly that current gives G back."""
    base = dict(motor=motor, motor_count=n, voltage=f"{V!r} V", efficiency=eta,
                wheel_diameter=f"{d!r} m", weight=f"{W!r} N", friction=mu)
    fwd = out(**base, ratio=G)
    i_tot = fwd["slip_current_total"]
    m = motors.system(motors.lookup(motor, "wpilib")[0], n, V, eta)
    assume(i_tot < m.stall_current * (1 - 1e-9))  # else the motors stall first (next test)
    assert i_tot == pytest.approx(fwd["slip_current"] * n, rel=1e-12)
    R_batt, R_main = 0.015, 0.002
    V_batt = V_min + i_tot * (R_batt + R_main + R_br / n)  # (41) solved for V_batt
    rev = out(**base, mode="reverse", battery_voltage=f"{V_batt!r} V", min_voltage=f"{V_min!r} V",
              battery_resistance=R_batt, main_resistance=R_main, branch_resistance=f"{R_br!r} ohm")
    assert rev["total_current"] == pytest.approx(i_tot, rel=1e-9)
    assert rev["max_ratio"] == pytest.approx(G, rel=1e-8)
    assert rev["free_speed"] == pytest.approx(fwd["free_speed"], rel=1e-8)
    # and the free speed inverts (37): G = ω̃f·(d/2)/v_free
    assert m.free_speed * d / 2 / fwd["free_speed"] == pytest.approx(G, rel=1e-12)


@settings(max_examples=150, deadline=None)
@given(motor=motor_names, n=st.integers(1, 8), d=st.floats(0.03, 0.2), G1=st.floats(1, 40), G2=st.floats(1, 40))
def test_shift_speed_is_where_both_gears_push_equally(motor, n, d, G1, G2):
    """(40) against its source, the wheel force (99): τ̃s·G/r·(1 − v·G/(r·ω̃f)) equal in both gears."""
    o = out(mode="shifting", motor=motor, motor_count=n, wheel_diameter=f"{d!r} m", low_ratio=G1, high_ratio=G2)
    m = motors.system(motors.lookup(motor, "wpilib")[0], n, 12.0, 1.0)
    r, v = d / 2, o["shift_speed"]

    def force(G):
        return m.stall_torque * G / r * (1 - v * G / (r * m.free_speed))

    scale = m.stall_torque * max(G1, G2) / r
    assert force(G1) == pytest.approx(force(G2), abs=1e-12 * scale)
    assert 0 < v < min(o["low_free_speed"], o["high_free_speed"])


def test_builtin_presets_load_and_solve():
    from core import presets

    found = presets.listing("drivetrain")
    assert len(found) >= 3 and presets.problems("drivetrain") == []
    modes = set()
    for p in found:
        s = solve("drivetrain", p.inputs)
        modes.add(p.inputs["mode"])
        assert s.outputs and not s.warnings
    assert modes == {"forward", "reverse", "shifting"}
    # swerve: 6000 rpm · π · 4 in / 6.75 = 628.3185·0.0508/6.75 = 4.72867 m/s = 15.514 ft/s
    swerve = next(p for p in found if "Swerve" in p.name)
    assert solve("drivetrain", swerve.inputs).outputs["free_speed"].value == pytest.approx(4.72867, rel=1e-5)


def test_speed_loss_constant_scales_the_adjusted_speed():
    # (38) with k_SL = 0.7: 17.1111 ft/s · 0.7 = 11.9778 ft/s
    o = out(speed_loss=0.7)
    assert o["adjusted_speed"] == pytest.approx(11.9778 * FT, rel=1e-5)


def test_reverse_budget_just_above_stall_current_gives_the_stall_ratio():
    # R = 0.0038 Ω: i_tot = 5.7/0.0038 = 1500 A, just above ĩs = 1464 A. (42) would give
    # 74.5703/(2·0.0194780·1492) = 1.28299; the stall ratio μ·W̃·r/τ̃s = 1.31470 is reported.
    o = out(mode="reverse", battery_resistance="0.0038 ohm", main_resistance=0, branch_resistance=0)
    assert o["total_current"] == pytest.approx(1500, rel=1e-12)
    assert o["max_ratio"] == pytest.approx(1.31470, rel=1e-5)
