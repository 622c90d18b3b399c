"""The intake (issue 31): hand values of (I1)-(I7), the round trip of the recommended reduction, the
table's order, and the refusals."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core import motors
from gearhead.core.constants import FOOT, INCH, LBF, RPM
from gearhead.core.errors import InputError
from gearhead.core.model import solve


def out(**inputs):
    sol = solve("intake", inputs)
    return sol, {k: v.value for k, v in sol.outputs.items()}


def test_kraken_x44_by_hand():
    # Kraken X44 (WPILib): 7758 rpm, 4.11 N·m, 279 A, 2 A; G = 3, d = 2 in, v_d = 15 ft/s, L = 12 in, 40 A
    sol, o = out(
        motor="Kraken X44",
        ratio=3,
        roller_diameter="2 in",
        drivetrain_speed="15 ft/s",
        pull_distance="12 in",
        efficiency=1,
        effects="stator_limit",
        stator_current_limit="40 A",
    )
    w_r = 7758 * 2 * math.pi / 60 / 3  # 270.8 rad/s (2586 rpm)
    v_s = w_r * 0.0254  # × d/2 = 1 in: 6.8785 m/s = 22.567 ft/s
    assert o["roller_speed"] == pytest.approx(w_r, rel=1e-12)
    assert o["surface_speed"] == pytest.approx(v_s, rel=1e-12)
    assert o["surface_speed"] / FOOT == pytest.approx(22.567, rel=1e-4)  # the figure read off by hand
    assert o["speed_ratio"] == pytest.approx(v_s / (15 * 0.3048), rel=1e-12)
    assert o["pull_time"] == pytest.approx(0.3048 / v_s, rel=1e-12)
    # G* = ω̃f·d/(2·k*·v_d) = 812.4 rad/s · 0.0508 m / (2·2·4.572 m/s) = 2.2567
    assert o["recommended_ratio"] == pytest.approx(7758 * RPM * 0.0508 / (4 * 4.572), rel=1e-12)
    assert o["target_roller_speed"] == pytest.approx(4 * 4.572 / 0.0508, rel=1e-12)  # 360 rad/s
    tau = 3 * 4.11 / 277 * 38  # G·Kt·(40 − 2)
    assert o["roller_torque_at_limit"] == pytest.approx(tau, rel=1e-12)
    assert o["pull_force_at_limit"] == pytest.approx(2 * tau / 0.0508, rel=1e-12)
    assert sol.warnings == []


def test_ftc_preset_values_by_hand():
    # goBILDA 1150 rpm direct on 72 mm wheels: v_s = 1150 rpm · 0.036 m = 4.3354 m/s; no limit: τ = τs
    _, o = out(
        motor="goBILDA Yellow Jacket 1150 rpm",
        ratio=1,
        roller_diameter="72 mm",
        drivetrain_speed="4 ft/s",
        effects="",
        efficiency=1,
    )
    assert o["surface_speed"] == pytest.approx(1150 * RPM * 0.036, rel=1e-12)
    assert o["roller_torque_at_limit"] == pytest.approx(7.9 * 0.0980665, rel=1e-12)


def test_gearbox_efficiency_and_motor_count_scale_the_torque():
    _, one = out(motor="NEO", efficiency=1, effects="stator_limit", stator_current_limit="40 A")
    _, two = out(
        motor="NEO", motor_count=2, efficiency=0.9, effects="stator_limit", stator_current_limit="40 A"
    )
    # n motors: Kt·(n·40 − n·1.8) (eqs. 3, 9): twice one motor's, times η
    assert two["roller_torque_at_limit"] == pytest.approx(2 * 0.9 * one["roller_torque_at_limit"], rel=1e-12)
    assert two["surface_speed"] == pytest.approx(one["surface_speed"], rel=1e-12)


def test_table_ranks_every_motor_by_torque_at_the_limit():
    sol = solve("intake", {"effects": "stator_limit", "stator_current_limit": "40 A"})
    table = sol.tables["ratios"]
    torques = [r["torque"].value for r in table]
    assert torques == sorted(torques, reverse=True)
    assert {r["motor"].value for r in table} == set(motors.motor_names())
    # each row: the reduction whose surface speed is k*·v_d, and its torque G*·Kt·(40 − ĩf)
    for r in table:
        m, _ = motors.lookup(r["motor"].value)
        G = r["ratio"].value
        free = m.free_speed * 12 / m.v_spec  # at 12 V (eq. 1): the VEX 393 and the Romi are rated lower
        assert free / G * 1 * INCH == pytest.approx(2 * 15 * FOOT, rel=1e-12)
    neo = next(r for r in table if r["motor"].value == "NEO")
    assert neo["torque"].value == pytest.approx(
        neo["ratio"].value * 2.6 / (105 - 1.8) * (40 - 1.8), rel=1e-12
    )
    assert neo["pull_force"].value == pytest.approx(2 * neo["torque"].value / (2 * INCH), rel=1e-12)


def test_a_motor_with_no_torque_at_the_limit_is_left_out_of_the_table():
    sol = solve(
        "intake", {"motor": "V5 100 rpm (red)", "effects": "stator_limit", "stator_current_limit": "1.5 A"}
    )
    names = {r["motor"].value for r in sol.tables["ratios"]}
    assert "V5 100 rpm (red)" in names and "Kraken X60" not in names  # 1.5 A < its 2 A free current


def test_no_torque_at_the_limit_names_the_field():
    with pytest.raises(InputError) as e:
        solve("intake", {"motor": "Kraken X60", "effects": "stator_limit", "stator_current_limit": "1 A"})
    assert e.value.field == "stator_current_limit"
    with pytest.raises(InputError) as e:
        solve("intake", {"motor": "Kraken X60", "effects": "supply_limit", "supply_current_limit": "0 A"})
    assert e.value.field == "supply_current_limit"


def test_low_voltage_motor_warns():
    sol = solve("intake", {"motor": "Romi"})
    assert any("specified at 4.5 V" in w for w in sol.warnings)


@settings(max_examples=60, deadline=None)
@given(
    motor=st.sampled_from(["Kraken X60", "NEO", "Minion (Adv Hall)", "Thrifty Pulsar", "V5 600 rpm (blue)"]),
    d_in=st.floats(0.5, 6),
    v_fts=st.floats(2, 25),
    k=st.floats(0.5, 4),
    volts=st.floats(6, 13),
)
def test_the_recommended_reduction_gives_the_target_ratio(motor, d_in, v_fts, k, volts):
    """(I5) then (I1)-(I3): setting G to the recommended reduction gives the target speed ratio."""
    base = {
        "motor": motor,
        "roller_diameter": f"{d_in!r} in",
        "drivetrain_speed": f"{v_fts!r} ft/s",
        "target_speed_ratio": k,
        "voltage": f"{volts!r} V",
        "effects": "",
    }
    G = solve("intake", base).outputs["recommended_ratio"].value
    if not 0.01 <= G <= 1000:
        return
    again = solve("intake", {**base, "ratio": G}).outputs
    assert again["speed_ratio"].value == pytest.approx(k, rel=1e-9)
    assert again["roller_speed"].value == pytest.approx(again["target_roller_speed"].value, rel=1e-9)


def test_pull_force_unit():
    _, o = out(motor="NEO", ratio=4, roller_diameter="2 in", effects="")
    assert o["pull_force_at_limit"] / LBF == pytest.approx(2 * 4 * 2.6 / (2 * INCH) / LBF, rel=1e-12)
