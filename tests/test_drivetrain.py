"""Drivetrain calculator, seed section 4: hand values for each mode, reverse(forward) round trips,
and the shift speed checked against the force balance (99)-(100) it comes from."""

import math

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from gearhead.core import motors
from gearhead.core.errors import InputError
from gearhead.core.model import solve

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


def test_reverse_budget_the_motors_cannot_draw_gives_the_circuit_stall_ratio():
    # R = 0.001 + 0 + 0: i_tot = 5.7 V/0.001 Ω = 5700 A. The four motors are R_m = 12 V/1464 A
    # = 0.0081967 Ω (eq. 4), so stalled through the wiring they draw only
    # i_c = 12.7/(0.001 + 0.0081967) = 1380.93 A and the voltage stays at 12.7 − 1.381 = 11.32 V.
    # (42) with i_tot would give G = 37.2850/(0.0194780·(5700 − 8)) = 0.33630, where the motors
    # stall (force 28.36·0.33630/0.0508 = 187.7 N ≪ traction 733.96 N).
    # Fastest ratio that slips: (42) with i_c: 37.2850/(0.0194780·(1380.93 − 8)) = 1.39425
    s = sol(mode="reverse", battery_resistance="0.001 ohm", main_resistance=0, branch_resistance=0)
    o = {k: v.value for k, v in s.outputs.items()}
    assert o["total_current"] == pytest.approx(5700, rel=1e-12)
    assert o["max_ratio"] == pytest.approx(1.39425, rel=1e-5)
    assert o["pushing_force"] == pytest.approx(165 * LBF, rel=1e-12)
    assert o["slip_current_total"] == pytest.approx(1380.93, rel=1e-5)  # slips exactly at i_c
    assert any("cannot draw the allowed" in w and "11.3 V" in w for w in s.warnings)
    assert not any("stall before the wheels slip" in w for w in s.warnings)


def test_four_neo_default_wiring_cannot_reach_the_allowed_current():
    # 4 NEO (WPILib 2.6 N·m, 105 A, 1.8 A): τ̃s = 10.4 N·m, ĩs = 420 A, ĩf = 7.2 A,
    # K_T = 10.4/412.8 = 0.0251938 N·m/A, R_m = 12/420 = 0.0285714 Ω.
    # (41) i_tot = 5.7/0.0185 = 308.108 A, but at 7 V the stalled motors draw 7/0.0285714 = 245 A:
    # they cannot. Through the wiring i_c = 12.7/(0.0185 + 0.0285714) = 269.803 A.
    # (42) as printed: 37.2850/(0.0251938·300.908) = 4.91820 (motors stall before slipping there);
    # with i_c: 37.2850/(0.0251938·262.603) = 5.63561
    s = sol(mode="reverse", motor="NEO")
    o = {k: v.value for k, v in s.outputs.items()}
    assert o["total_current"] == pytest.approx(308.108, rel=1e-5)
    assert o["max_ratio"] == pytest.approx(5.63561, rel=1e-5)
    assert o["slip_current_total"] == pytest.approx(269.803, rel=1e-5)
    assert any("cannot draw the allowed" in w for w in s.warnings)
    # and at 4.92 (what (42) gives) the stalled motors' torque through the wiring, K_T·(i_c − ĩf),
    # is below the traction torque / G: the wheels would not slip
    assert 0.0251938 * (269.803 - 7.2) * 4.91820 < 37.2850


def test_reverse_battery_too_weak_to_push_names_a_field():
    # V_batt = 0.185 V, V_min = 0: i_tot = 10 A > ĩf = 8 A, but stalled the motors draw only
    # 0.185/(0.0185 + 0.0081967) = 6.93 A < ĩf
    with pytest.raises(InputError) as e:
        out(mode="reverse", battery_voltage="0.185 V", min_voltage=0)
    assert e.value.field == "battery_voltage"


@pytest.mark.parametrize(
    "raw,field",
    [
        ({"min_voltage": "13 V"}, "min_voltage"),  # above the battery
        ({"battery_resistance": 0, "main_resistance": 0, "branch_resistance": 0}, "battery_resistance"),
        ({"battery_resistance": "5 ohm"}, "min_voltage"),  # 5.7 V / 5 Ω < the 8 A free current
    ],
)
def test_reverse_impossible_budgets_name_a_field(raw, field):
    with pytest.raises(InputError) as e:
        out(mode="reverse", **raw)
    assert e.value.field == field


motor_names = st.sampled_from(["CIM", "NEO", "Kraken X60", "Falcon 500", "NEO Vortex", "V5 200 rpm (green)"])


# a drivetrain of any motor, size and wiring: what both round trips below draw from
DRIVETRAINS = dict(
    motor=motor_names,
    n=st.integers(1, 8),
    V=st.floats(6, 13),
    d=st.floats(0.03, 0.2),
    W=st.floats(10, 3000),
    mu=st.floats(0.2, 1.6),
    G=st.floats(1, 40),
    V_min=st.floats(3, 9),
    R_br=st.one_of(st.just(0.0), st.floats(1e-5, 0.05)),
)


@settings(max_examples=150, deadline=None)
@given(**DRIVETRAINS, eta=st.floats(0.5, 1))
def test_reverse_of_forward_returns_the_ratio(motor, n, V, eta, d, W, mu, G, V_min, R_br):
    """Forward slip current at G; a battery budget allowing exactly that current gives G back."""
    base = dict(
        motor=motor,
        motor_count=n,
        voltage=f"{V!r} V",
        efficiency=eta,
        wheel_diameter=f"{d!r} m",
        weight=f"{W!r} N",
        friction=mu,
    )
    fwd = out(**base, ratio=G)
    i_tot = fwd["slip_current_total"]
    m = motors.system(motors.lookup(motor, "wpilib")[0], n, V, eta)
    R_m = V / m.stall_current  # (4): the motors' resistance
    assume(i_tot * R_m < V_min * (1 - 1e-9))  # else they cannot draw i_tot at V_min (tests above)
    assume(i_tot * R_m < V * (1 - 1e-9))  # nor at the applied voltage (test_hard_drivetrain.py)
    assert i_tot == pytest.approx(fwd["slip_current"] * n, rel=1e-12)
    R_batt, R_main = 0.015, 0.002
    V_batt = V_min + i_tot * (R_batt + R_main + R_br / n)  # (41) solved for V_batt
    rev = out(
        **base,
        mode="reverse",
        battery_voltage=f"{V_batt!r} V",
        min_voltage=f"{V_min!r} V",
        battery_resistance=R_batt,
        main_resistance=R_main,
        branch_resistance=f"{R_br!r} ohm",
    )
    assert rev["total_current"] == pytest.approx(i_tot, rel=1e-9)
    assert rev["max_ratio"] == pytest.approx(G, rel=1e-8)
    assert rev["free_speed"] == pytest.approx(fwd["free_speed"], rel=1e-8)
    # and the free speed inverts (37): G = ω̃f·(d/2)/v_free
    assert m.free_speed * d / 2 / fwd["free_speed"] == pytest.approx(G, rel=1e-12)


@settings(max_examples=100, deadline=None)
@given(
    **DRIVETRAINS,
    stator=st.one_of(st.none(), st.floats(5, 200)),
    supply=st.one_of(st.none(), st.floats(5, 150)),
    sag=st.booleans(),
    V_batt=st.floats(10, 13.5),
)
def test_reverse_of_forward_returns_the_ratio_with_limits_and_sag(
    motor, n, V, d, W, mu, G, V_min, R_br, stator, supply, sag, V_batt
):
    """The round trip above with stator_limit, supply_limit and battery_sag: forward mode at G slips
    the wheels drawing a battery current i_b (D2); a budget allowing exactly i_b (41) (with sag: the
    minimum voltage set to forward's voltage at the controllers, the same thing) gives G back when
    the budget is what binds; in every case the ratio reverse finds, fed to forward mode with the
    same effects, slips the wheels (pushing force = traction) within the budget."""
    on = [e for e, x in (("stator_limit", stator), ("supply_limit", supply), ("battery_sag", sag)) if x]
    assume(on)
    R_batt, R_main = 0.015, 0.002
    R41 = R_batt + R_main + R_br / n
    base = dict(
        motor=motor,
        motor_count=n,
        voltage=f"{V!r} V",
        wheel_diameter=f"{d!r} m",
        weight=f"{W!r} N",
        friction=mu,
        effects=", ".join(on),
        stator_current_limit=f"{(stator or 40)!r} A",
        supply_current_limit=f"{(supply or 30)!r} A",
        battery_resistance=R_batt,
        main_resistance=R_main,
        branch_resistance=f"{R_br!r} ohm",
    )
    try:
        fwd = out(**base, ratio=G, battery_voltage=f"{V_batt!r} V")
    except InputError:  # limits too low to push at all (tests in test_limits_drivetrain.py)
        assume(False)
    assume(fwd["pushing_force"] == pytest.approx(W * mu, rel=1e-12))  # forward slips the wheels at G
    i_b = fwd["push_battery_current"]
    if sag:  # (D2): the controllers' voltage while pushing is (41) at i_b
        assert fwd["push_bus_voltage"] == pytest.approx(V_batt - i_b * R41, rel=1e-12)
        V_min = fwd["push_bus_voltage"]
        assume(V_min > 0.5)
    supply_held = supply is not None and fwd["push_supply_current"] < fwd["push_current"] * (1 - 1e-12)
    if supply_held:  # a budget of exactly n·I_sup is the edge where any ratio keeps within it; just above
        i_b *= 1 + 1e-6
        if sag:
            V_min = V_batt - i_b * R41
    if not sag:
        V_batt = V_min + i_b * R41  # (41) solved for V_batt
    m = motors.system(motors.lookup(motor, "wpilib")[0], n, V, 1.0)
    i_c = V_batt / (R41 + V / m.stall_current)  # stalled through the wiring (no sag: reverse's cap)
    # (without sag a battery that stalled through the wiring gives no more than the free current is
    # refused, naming battery_voltage: test_reverse_battery_too_weak_to_push_names_a_field)
    assume(sag or i_c > m.free_current * (1 + 1e-9))
    rev = out(**base, mode="reverse", battery_voltage=f"{V_batt!r} V", min_voltage=f"{V_min!r} V")
    assert rev["total_current"] == pytest.approx(i_b, rel=1e-9)
    back = out(**base, ratio=repr(rev["max_ratio"]), battery_voltage=f"{V_batt!r} V")
    assert back["pushing_force"] == pytest.approx(W * mu, rel=1e-12)
    assert back["push_battery_current"] <= i_b * (1 + 1e-9)
    if sag or i_c >= fwd["slip_current_total"]:  # (else the wiring caps reverse's stall current)
        if not supply_held:  # the budget binds at G: reverse finds G, the fastest ratio within it
            assert rev["max_ratio"] == pytest.approx(G, rel=1e-8)
        else:  # the supply limit holds the battery current at n·I_sup: any faster ratio that still
            assert rev["max_ratio"] <= G * (1 + 1e-9)  # slips is within the budget


@settings(max_examples=150, deadline=None)
@given(
    motor=motor_names, n=st.integers(1, 8), d=st.floats(0.03, 0.2), G1=st.floats(1, 40), G2=st.floats(1, 40)
)
def test_shift_speed_is_where_both_gears_push_equally(motor, n, d, G1, G2):
    """(40) against its source, the wheel force (99): τ̃s·G/r·(1 − v·G/(r·ω̃f)) equal in both gears."""
    o = out(
        mode="shifting", motor=motor, motor_count=n, wheel_diameter=f"{d!r} m", low_ratio=G1, high_ratio=G2
    )
    m = motors.system(motors.lookup(motor, "wpilib")[0], n, 12.0, 1.0)
    r, v = d / 2, o["shift_speed"]

    def force(G):
        return m.stall_torque * G / r * (1 - v * G / (r * m.free_speed))

    scale = m.stall_torque * max(G1, G2) / r
    assert force(G1) == pytest.approx(force(G2), abs=1e-12 * scale)
    assert 0 < v < min(o["low_free_speed"], o["high_free_speed"])


def test_builtin_presets_load_and_solve():
    from gearhead.core import presets

    found = presets.listing("drivetrain")
    assert len(found) >= 3 and presets.problems("drivetrain") == []
    modes = set()
    for p in found:
        s = solve("drivetrain", p.inputs)
        modes.add(p.inputs["mode"])
        # (the limits preset shows on purpose that its stator limit, not traction, sets the force)
        assert s.outputs and not [w for w in s.warnings if "cap the pushing force" not in w]
    assert modes == {"forward", "reverse", "shifting"}
    # swerve: 6000 rpm · π · 4 in / 6.75 = 628.3185·0.0508/6.75 = 4.72867 m/s = 15.514 ft/s
    swerve = next(p for p in found if "Swerve" in p.name)
    assert solve("drivetrain", swerve.inputs).outputs["free_speed"].value == pytest.approx(4.72867, rel=1e-5)


def test_speed_loss_constant_scales_the_adjusted_speed():
    # (38) with k_SL = 0.7: 17.1111 ft/s · 0.7 = 11.9778 ft/s
    o = out(speed_loss=0.7)
    assert o["adjusted_speed"] == pytest.approx(11.9778 * FT, rel=1e-5)


def test_reverse_budget_just_above_circuit_stall_current():
    # R = 0.0038 Ω: i_tot = 5.7/0.0038 = 1500 A; i_c = 12.7/(0.0038 + 0.0081967) = 1058.62 A.
    # (42) would give 37.2850/(0.0194780·1492) = 1.28299; with i_c: 37.2850/(0.0194780·1050.62)
    # = 1.82198. Just below, at i_tot = i_c exactly, both agree.
    o = out(mode="reverse", battery_resistance="0.0038 ohm", main_resistance=0, branch_resistance=0)
    assert o["total_current"] == pytest.approx(1500, rel=1e-12)
    assert o["max_ratio"] == pytest.approx(1.82198, rel=1e-5)
    # i_tot = i_c when (V_batt − V_min)·(R + R_m) = V_batt·R: R = 5.7·(12/1464)/7 = 0.00667465 Ω;
    # either side of it the two branches give the same ratio
    R_eq = 5.7 * (12 / 1464) / 7
    sides = [
        out(mode="reverse", battery_resistance=f"{R_eq * k!r} ohm", main_resistance=0, branch_resistance=0)[
            "max_ratio"
        ]
        for k in (1 - 1e-9, 1 + 1e-9)
    ]
    assert sides[0] == pytest.approx(sides[1], rel=1e-7)


def test_reverse_mode_never_says_the_motors_stall_first():
    # Voltage field 1 V: stalled at 1 V the four Krakens draw ĩs = 4·366/12 = 122 A, below the
    # allowed i_tot = 308.108 A, so the fastest ratio that slips is (42) with 122 A:
    # G = 37.2850/(0.0194780·(122 − 8/12)) = 15.7765, where the stall force τ̃s(1 V)·G/r equals
    # traction. (The old model fed the motors the battery's 12.7 V here, against the field.)
    s = sol(mode="reverse", voltage="1 V")
    assert not any("stall before the wheels slip" in w for w in s.warnings)
    assert any("at 1 V (the Voltage field)" in w for w in s.warnings)
    assert s.outputs["pushing_force"].value == pytest.approx(165 * LBF, rel=1e-12)
    assert s.outputs["max_ratio"].value == pytest.approx(15.7765, rel=1e-5)
