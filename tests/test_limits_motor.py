"""Motor tab with current limits and battery sag, by hand.

Two Kraken X60 FOC (WPILib: τs 9.37 N·m, is 483 A, if 2 A, 5800 rpm at 12 V) through η = 0.95.
Seed (7): K_T = τ̃s/(ĩs − ĩf) = 2·9.37·0.95/(966 − 4) = 0.0185062 N·m/A. Per motor R = 12/483 Ω,
Kv = ωf/(12 − 2R). Limited torque (L1): τ = K_T·(n·I − ĩf).
"""

import math

import pytest

from gearhead.core.constants import RPM
from gearhead.core.errors import InputError
from gearhead.core.model import solve

KT = 2 * 9.37 * 0.95 / (966 - 4)
R = 12 / 483
WF = 5800 * RPM
KV = WF / (12 - 2 * R)
TS = 2 * 9.37 * 0.95


def out(**kw):
    raw = {
        "motor": "Kraken X60 FOC",
        "source": "wpilib",
        "motor_count": 2,
        "voltage": "12 V",
        "efficiency": 0.95,
        "torque": "1 N*m",
    }
    raw.update(kw)
    sol = solve("motor", raw)
    return {k: v.value for k, v in sol.outputs.items()}, sol.series


def test_stator_limit_caps_the_torque_and_lets_go_at_the_hand_speed():
    o, series = out(effects="stator_limit", stator_current_limit="40 A")
    tau_c = KT * (2 * 40 - 4)
    assert tau_c == pytest.approx(1.40647, abs=1e-5)
    assert o["limited_stall_torque"] == pytest.approx(tau_c, rel=1e-12)
    w_k = KV * (12 - R * 40)  # E = V − R·I_st (E2 at u = 1)
    assert o["limit_release_speed"] == pytest.approx(w_k, rel=1e-12)
    # below the limit the operating point is the seed's line (8)
    free, _ = out()
    assert o["speed"] == pytest.approx(free["speed"], rel=1e-12)
    assert o["current"] == pytest.approx(free["current"], rel=1e-12)
    # the release speed is past ω̃f/2, so the limited peak power is at the kink: τ_c·ω_k
    assert w_k > WF / 2
    assert o["limited_peak_power"] == pytest.approx(tau_c * w_k, rel=1e-9)
    # the curve: torque never above τ_c, and the flat part (speeds 0..ω_k at τ_c) is drawn
    taus, speeds = series["speed"]
    assert max(taus) == pytest.approx(tau_c, rel=1e-12)
    flat = [w for t, w in zip(taus, speeds) if t == pytest.approx(tau_c, rel=1e-12)]
    assert min(flat) == 0 and max(flat) <= w_k


def test_operating_point_on_the_flat_part_is_its_fastest_speed():
    tau_c = KT * (2 * 40 - 4)
    o, _ = out(effects="stator_limit", stator_current_limit="40 A", torque=f"{tau_c!r} N*m")
    assert o["speed"] == pytest.approx(KV * (12 - R * 40), rel=1e-9)


def test_peak_power_before_the_kink_is_the_parabola_top():
    # 300 A: the limit lets go at ω_k = Kv·(12 − 300R) below ω̃f/2, so the peak is the seed's τ̃s·ω̃f/4 (6)
    o, _ = out(effects="stator_limit", stator_current_limit="300 A")
    w_k = KV * (12 - R * 300)
    assert w_k < WF / 2
    assert o["limited_peak_power"] == pytest.approx(TS * WF / 4, rel=1e-9)


def test_sag_lowers_the_speed_and_the_bus():
    o, _ = out(effects="battery_sag", battery_resistance="0.02 ohm")
    Rb = 2 * 0.02
    I = (1 / KT + 4) / 2  # per motor at 1 N·m
    assert o["current"] == pytest.approx(2 * I, rel=1e-12)
    assert o["bus_voltage"] == pytest.approx(12 - Rb * I, rel=1e-12)
    assert o["speed"] == pytest.approx(KV * (12 - I * (R + Rb)), rel=1e-9)
    assert o["efficiency_at_torque"] == pytest.approx(1 * o["speed"] / (12 * 2 * I), rel=1e-9)
    assert "limit_release_speed" not in o


def test_supply_limit_with_sag_at_the_operating_point():
    """At 1 N·m each motor needs I = 29.018 A of stator current; with I_sup = 20 A the duty is
    u = I_sup/I and the speed follows from E = u·V_b − I·(R + u²·R_bus) (E1)."""
    o, _ = out(
        effects="supply_limit, battery_sag", supply_current_limit="20 A", battery_resistance="0.02 ohm"
    )
    Rb = 2 * 0.02
    I = (1 / KT + 4) / 2
    u = 20 / I
    assert o["supply_current"] == pytest.approx(2 * 20, rel=1e-9)
    assert o["bus_voltage"] == pytest.approx(12 - Rb * 20, rel=1e-9)
    assert o["speed"] == pytest.approx(KV * (u * 12 - I * (R + u * u * Rb)), rel=1e-9)


@pytest.mark.parametrize(
    "kw,field",
    [
        ({"effects": "stator_limit", "stator_current_limit": 0}, "stator_current_limit"),
        ({"effects": "supply_limit", "supply_current_limit": 0}, "supply_current_limit"),
        ({"effects": "battery_sag", "battery_resistance": "10 ohm"}, "battery_resistance"),
        ({"effects": "stator_limit", "stator_current_limit": "40 A", "torque": "2 N*m"}, "torque"),
    ],
)
def test_bad_limits_name_the_field(kw, field):
    with pytest.raises(InputError) as e:
        out(**kw)
    assert e.value.field == field


def test_every_value_finite_for_a_limit_just_above_the_free_current():
    o, series = out(
        effects="stator_limit, supply_limit",
        stator_current_limit="2.001 A",
        supply_current_limit="0.01 A",
        torque=0,
    )
    assert all(math.isfinite(x) for x in o.values() if isinstance(x, float))
