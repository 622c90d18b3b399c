"""Hard cases for the drivetrain (seed section 4): reverse mode's ratio must be one forward mode
agrees slips the wheels, whatever limits the current (the allowed budget of (41), the stall current
at the applied voltage, or the battery through the wiring)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core.model import solve

LBF = 4.4482216152605


def out(**raw):
    s = solve("drivetrain", raw)
    return {k: v.value for k, v in s.outputs.items()}, s.warnings


def test_two_cims_at_8_volts_are_capped_by_their_stall_current_at_8_volts():
    """The Voltage field used to feed free speed only; the slip-current cap used the battery's 12.7 V.
    By hand (WPILib CIM 2.42 N·m, 133 A, 2.7 A at 12 V), n = 2, V = 8 V, η = 1:
      ĩs = 2·133·8/12 = 177.333 A, ĩf = 2·2.7·8/12 = 3.6 A, τ̃s = 2·2.42·8/12 = 3.22667 N·m,
      K_T = 3.22667/173.733 = 0.0185725 N·m/A;
      i_tot (41) = 5.7/(0.015 + 0.002 + 0.006/2) = 285 A;
      battery-fed stall i_c = 12.7/(0.020 + 12/266) = 12.7/0.0651128 = 195.045 A > ĩs.
      So i_max = 177.333 A and G = μ·W̃·d/(2·K_T·(i_max − ĩf)) = 74.5703/(2·0.0185725·173.733)
      = 11.5552 (the old 10.486 came from 195 A, where forward mode says the motors stall at
      149.73 lbf)."""
    o, w = out(mode="reverse", motor="CIM", motor_count=2, voltage=8)
    assert o["max_ratio"] == pytest.approx(11.5552, rel=1e-5)
    assert o["slip_current_total"] == pytest.approx(177.333, rel=1e-5)
    assert o["pushing_force"] == pytest.approx(165 * LBF, rel=1e-12)
    assert any("at 8 V (the Voltage field) the stalled motors draw at most 177.3 A" in x for x in w)
    f, fw = out(mode="forward", motor="CIM", motor_count=2, voltage=8, ratio=repr(o["max_ratio"]))
    assert f["pushing_force"] == pytest.approx(165 * LBF, rel=1e-12)
    assert not any("stall before" in x for x in fw)


motors_ = st.sampled_from(
    [
        "CIM",
        "NEO",
        "Kraken X60",
        "Falcon 500",
        "MiniCIM",
        "BAG",
        "775pro",
        "V5 100 rpm (red)",
        "V5 600 rpm (blue)",
        "VEX 393",
    ]
)


@settings(max_examples=300, deadline=None)
@given(
    motor=motors_,
    n=st.integers(1, 8),
    V=st.floats(1, 14),
    eta=st.floats(0.5, 1),
    d=st.floats(0.03, 0.2),
    W=st.floats(10, 3000),
    mu=st.floats(0.2, 1.6),
    V_batt=st.floats(7, 13.5),
    V_min_frac=st.floats(0, 0.9),
    R_batt=st.floats(0.001, 0.05),
    R_br=st.one_of(st.just(0.0), st.floats(1e-5, 0.05)),
)
def test_reverse_ratio_fed_to_forward_gives_the_same_force_and_current(
    motor, n, V, eta, d, W, mu, V_batt, V_min_frac, R_batt, R_br
):
    """One model for both modes: at reverse's ratio forward mode slips the wheels (pushing force =
    traction, no 'stall before slip') at the same slip current. Old code: 107 of 300 random cases
    (VEX motors, low voltages) disagreed."""
    base = dict(
        motor=motor,
        motor_count=n,
        voltage=f"{V!r} V",
        efficiency=eta,
        wheel_diameter=f"{d!r} m",
        weight=f"{W!r} N",
        friction=mu,
    )
    try:
        rev, _ = out(
            **base,
            mode="reverse",
            battery_voltage=f"{V_batt!r} V",
            min_voltage=f"{V_batt * V_min_frac!r} V",
            battery_resistance=f"{R_batt!r} ohm",
            branch_resistance=f"{R_br!r} ohm",
        )
    except Exception as e:  # a budget that cannot push at all is an InputError naming a field
        from gearhead.core.errors import InputError

        assert isinstance(e, InputError) and e.field in ("min_voltage", "battery_voltage")
        return
    fwd, fw = out(**base, ratio=repr(rev["max_ratio"]))
    assert math.isclose(fwd["pushing_force"], W * mu, rel_tol=1e-12)
    assert math.isclose(rev["pushing_force"], fwd["pushing_force"], rel_tol=1e-12)
    assert math.isclose(rev["slip_current_total"], fwd["slip_current_total"], rel_tol=1e-12)
    assert not any("stall before" in x for x in fw)
    # and never more current than the budget allows
    assert rev["slip_current_total"] <= rev["total_current"] * (1 + 1e-12)
