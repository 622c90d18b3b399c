"""Drivetrain pushing force and currents under stator/supply limits and battery sag, by hand.

Swerve preset: 4 Kraken X60 (WPILib: τs 7.09 N·m, is 366 A, if 2 A at 12 V), G = 6.75, 4 in wheels,
135 lbf on the wheels, μ = 1.2: traction 162 lbf = 720.6 N. Seed torque (7), (9), all motors:
K_T = τ̃s/(ĩs − ĩf) = 4·7.09/(4·366 − 4·2) = 0.0194780 N·m/A; per motor R = 12/366 Ω.
"""

import math

import pytest

from gearhead.core.constants import INCH, LBF
from gearhead.core.errors import InputError
from gearhead.core.model import solve

KT = 4 * 7.09 / (4 * 366 - 4 * 2)
R = 12 / 366
G, r = 6.75, 2 * INCH
TRACTION = 1.2 * 135 * LBF


def out(**kw):
    raw = {
        "mode": "forward",
        "motor": "Kraken X60",
        "source": "wpilib",
        "motor_count": 4,
        "voltage": "12 V",
        "efficiency": 1,
        "wheel_diameter": "4 in",
        "ratio": G,
        "weight": "135 lbf",
        "friction": 1.2,
    }
    raw.update(kw)
    sol = solve("drivetrain", raw)
    return {k: v.value for k, v in sol.outputs.items()}, sol.warnings


def test_stator_limit_caps_the_force():
    o, w = out(effects="stator_limit", stator_current_limit="60 A")
    F = KT * (4 * 60 - 4 * 2) * G / r  # (D1): 0.019478·232·132.87 = 600.4 N = 135.0 lbf
    assert F == pytest.approx(600.4, abs=0.1)
    assert o["pushing_force"] == pytest.approx(F, rel=1e-12)
    assert o["push_current"] == pytest.approx(60, rel=1e-12)
    assert o["push_supply_current"] == pytest.approx(60 * R * 60 / 12, rel=1e-12)  # u = R·I_st/V (E2)
    assert o["push_battery_current"] == pytest.approx(4 * 60 * R * 60 / 12, rel=1e-12)
    assert "push_bus_voltage" not in o
    assert any("cap the pushing force" in x for x in w)


def test_high_stator_limit_lets_the_wheels_slip():
    o, w = out(effects="stator_limit", stator_current_limit="120 A")
    free, _ = out()
    assert o["pushing_force"] == pytest.approx(TRACTION, rel=1e-12)
    i_slip = TRACTION * r / (KT * G) + 4 * 2  # (39) all motors
    assert o["slip_current_total"] == pytest.approx(i_slip, rel=1e-12)
    assert o["push_current"] == pytest.approx(i_slip / 4, rel=1e-12)
    assert o["push_supply_current"] == pytest.approx(i_slip / 4, rel=1e-12)  # full duty
    assert o["slip_current"] == free["slip_current"]


def test_supply_limit_with_sag_changes_the_voltage():
    """V_b = 12.7 V, R_bus = 4·(0.015 + 0.002) + 0.006 = 0.074 Ω per motor, I_st 65 A, I_sup 40 A.
    At stall (E = 0): u_st = 2W/(V_b + √(V_b² − 4·I_st·R_bus·W)), W = R·I_st = 2.13115:
    √(161.29 − 41.004) = 10.9675, u_st = 4.2623/23.6675 = 0.18009; u_sup = √(I_sup·R/(V_b − I_sup·R_bus))
    = 0.36694; the stator limit binds: I = 65 A (4·65 = 260 A, below the 286.4 A that slips the
    wheels), supply 11.706 A, bus 12.7 − 0.074·11.706 = 11.834 V."""
    o, _ = out(
        effects="stator_limit, supply_limit, battery_sag",
        stator_current_limit="65 A",
        supply_current_limit="40 A",
        battery_voltage="12.7 V",
        battery_resistance="0.015 ohm",
        main_resistance="0.002 ohm",
        branch_resistance="0.006 ohm",
    )
    Vb, Rb, W = 12.7, 4 * 0.017 + 0.006, R * 65
    u_st = 2 * W / (Vb + math.sqrt(Vb**2 - 4 * 65 * Rb * W))
    assert u_st == pytest.approx(0.18009, abs=1e-5)
    assert math.sqrt(40 * R / (Vb - 40 * Rb)) == pytest.approx(0.36694, abs=1e-5)
    assert o["push_current"] == pytest.approx(65, rel=1e-12)
    assert o["push_supply_current"] == pytest.approx(65 * u_st, rel=1e-12)
    assert o["push_bus_voltage"] == pytest.approx(Vb - Rb * 65 * u_st, rel=1e-12)
    assert o["push_bus_voltage"] == pytest.approx(11.834, abs=1e-3)
    assert o["pushing_force"] == pytest.approx(KT * (4 * 65 - 8) * G / r, rel=1e-12)


def test_supply_limit_alone_binds_at_stall_with_sag():
    """I_sup 10 A with the same circuit: u = √(c/a) at E = 0, a = V_b − I_sup·R_bus, c = I_sup·R
    (E3): √(0.32787/11.96) = 0.16557, I = I_sup/u = 60.40 A; the wheels do not slip (n·I = 241.6 A
    below the slip current 286.4 A)."""
    o, _ = out(
        effects="supply_limit, battery_sag",
        supply_current_limit="10 A",
        battery_voltage="12.7 V",
        battery_resistance="0.015 ohm",
        main_resistance="0.002 ohm",
        branch_resistance="0.006 ohm",
    )
    Vb, Rb = 12.7, 4 * 0.017 + 0.006
    u = math.sqrt(10 * R / (Vb - 10 * Rb))
    assert u == pytest.approx(0.16557, abs=1e-5)
    assert o["push_current"] == pytest.approx(10 / u, rel=1e-12)
    assert o["push_supply_current"] == pytest.approx(10, rel=1e-12)
    assert o["push_bus_voltage"] == pytest.approx(Vb - Rb * 10, rel=1e-12)
    assert o["pushing_force"] == pytest.approx(KT * (4 * 10 / u - 8) * G / r, rel=1e-12)


def test_sag_alone_stall_current_through_the_wiring():
    o, _ = out(
        effects="battery_sag",
        ratio=20,
        battery_voltage="12.7 V",
        battery_resistance="0.015 ohm",
        main_resistance="0.002 ohm",
        branch_resistance="0.006 ohm",
    )
    # G = 20: the wheels slip at ĩ_slip = 720.6·0.0508/(0.019478·20) + 8 = 101.97 A, well below stall
    i_slip = TRACTION * r / (KT * 20) + 8
    assert o["push_current"] == pytest.approx(i_slip / 4, rel=1e-12)
    assert o["push_bus_voltage"] == pytest.approx(12.7 - (4 * 0.017 + 0.006) * i_slip / 4, rel=1e-12)


@pytest.mark.parametrize(
    "kw,field",
    [
        ({"effects": "stator_limit", "stator_current_limit": 0}, "stator_current_limit"),
        (
            {"effects": "stator_limit", "stator_current_limit": "2 A"},
            "stator_current_limit",
        ),  # = free current
        ({"effects": "supply_limit", "supply_current_limit": 0}, "supply_current_limit"),
        ({"effects": "battery_sag", "branch_resistance": "10 ohm"}, "battery_resistance"),
    ],
)
def test_limits_too_low_name_the_field(kw, field):
    with pytest.raises(InputError) as e:
        out(**kw)
    assert e.value.field == field


def test_reverse_stator_limit_sets_the_ratio_by_hand():
    """Reverse defaults (150 lbf, μ 1.1, 4 in, 4 Krakens at 12 V): i_tot (41) = 5.7/0.0185 = 308.108 A,
    but a 60 A stator limit holds the stalled motors at 4·60 = 240 A. The fastest ratio that slips:
    (42) with 240 A: μ·W̃·r/(K_T·(240 − 8)) = 733.957·0.0508/(0.0194780·232) = 37.2850/4.51890 = 8.2509
    (the old code ignored the limit and gave 6.3784, where forward mode with the limit pushes only
    0.0194780·232·6.3784/0.0508 = 567.4 N < 734 N)."""
    o, w = out(
        mode="reverse", weight="150 lbf", friction=1.1, effects="stator_limit", stator_current_limit="60 A"
    )
    assert o["max_ratio"] == pytest.approx(8.2509, rel=1e-4)
    assert o["slip_current_total"] == pytest.approx(240, rel=1e-12)
    assert any("stator current limit holds each stalled motor at 60 A" in x for x in w)
    f, fw = out(
        weight="150 lbf",
        friction=1.1,
        effects="stator_limit",
        stator_current_limit="60 A",
        ratio=repr(o["max_ratio"]),
    )
    assert f["pushing_force"] == pytest.approx(1.1 * 150 * LBF, rel=1e-12)
    assert not any("cap the pushing force" in x or "stall before" in x for x in fw)


def test_reverse_with_sag_ends_at_the_minimum_voltage():
    """battery_sag in reverse mode: the ratio found, fed to forward mode with the same sag, pushes at
    exactly V_min at the controllers (D2) = (41): 12.7 − 0.074·308.108/4 = 7 V."""
    o, w = out(mode="reverse", weight="150 lbf", friction=1.1, effects="battery_sag")
    assert o["push_bus_voltage"] == pytest.approx(7.0, rel=1e-12)
    assert o["max_ratio"] == pytest.approx(6.3784, rel=1e-4)  # as without sag: i_c = 1287 A > i_tot


def test_reverse_supply_limit_keeps_the_voltage_up_at_any_ratio():
    """Supply limit 40 A with sag: the battery never gives more than 4·40 = 160 A < i_tot = 308.1 A,
    so the budget never binds. Stalled (E = 0), (E3): u² = I_sup·R/(V_b − I_sup·R_bus) with
    R = 12/366, R_bus = 4·0.017 + 0.006 = 0.074: u = √(1.31148/9.74) = 0.366944, I₀ = 40/u = 109.008 A;
    G = 37.2850/(0.0194780·(436.033 − 8)) = 4.4721; forward there: supply 40 A, bus 12.7 − 0.074·40 = 9.74 V."""
    o, w = out(
        mode="reverse",
        weight="150 lbf",
        friction=1.1,
        effects="supply_limit, battery_sag",
        supply_current_limit="40 A",
    )
    u = math.sqrt(40 * R / (12.7 - 40 * 0.074))
    assert u == pytest.approx(0.366944, abs=1e-6)
    assert o["slip_current_total"] == pytest.approx(4 * 40 / u, rel=1e-12)
    assert o["max_ratio"] == pytest.approx(1.1 * 150 * LBF * r / (KT * (4 * 40 / u - 8)), rel=1e-12)
    assert o["max_ratio"] == pytest.approx(4.4721, rel=1e-4)
    assert o["push_bus_voltage"] == pytest.approx(9.74, rel=1e-12)
    assert any("supply current limit keeps the battery current" in x for x in w)


@pytest.mark.parametrize(
    "kw,field",
    [
        ({"effects": "stator_limit", "stator_current_limit": "2 A"}, "stator_current_limit"),
        ({"effects": "supply_limit", "supply_current_limit": "0.01 A"}, "supply_current_limit"),
        # i_tot = 12.7/1.58 = 8.04 A > ĩf = 8 A, but stalled through 1.58 Ω: 12.7/1.5882 = 7.997 A
        (
            {
                "effects": "battery_sag",
                "battery_resistance": "1.58 ohm",
                "main_resistance": 0,
                "branch_resistance": 0,
                "min_voltage": 0,
            },
            "battery_resistance",
        ),
    ],
)
def test_reverse_limits_too_low_name_the_field(kw, field):
    with pytest.raises(InputError) as e:
        out(mode="reverse", **kw)
    assert e.value.field == field and "\n" not in e.value.message
