"""Hard-case catalogue: numerically delicate inputs, each against a closed form or an mpmath reference.

Every case states why it is delicate. This file holds the motor, gear-ratio, pneumatics and
integrator cases; each other calculator keeps its own in tests/test_hard_<calculator>.py, and the
simulations' robustness cases (hangs, budgets, cancel, energy balance) are in tests/test_hard_sims.py
(`pytest tests/test_hard_*.py` runs the whole catalogue).
"""

import math

import mpmath as mp
import pytest

from gearhead.core import motors
from gearhead.core.calculators import pneumatics as pn
from gearhead.core.calculators.gear_ratio import ratio_for_loaded_speed
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim.integrate import Event, integrate

mp.mp.dps = 40
PSI = pn.PSI


def kraken():
    return motors.system(motors.lookup("Kraken X60", "wpilib")[0], 1, 12.0, 1.0)


def test_gear_ratio_target_exactly_at_peak_power():
    """Discriminant of (24) is exactly zero: sqrt of a rounding-negative number must not give NaN."""
    m = kraken()
    r, F = 0.0254, 500.0
    w = m.free_speed * m.stall_torque / (4 * r * F)
    hi, lo = ratio_for_loaded_speed(m, r, F, w, "x")
    exact = mp.mpf(2) * r * F / mp.mpf(m.stall_torque)
    assert hi == pytest.approx(float(exact), rel=1e-7) and lo == pytest.approx(float(exact), rel=1e-7)


def test_gear_ratio_tiny_speed_small_root_without_cancellation():
    """x = 4rFω/(τs·ωf) ~ 1e-12: the small root 1 − sqrt(1 − x) cancels catastrophically in (24)."""
    m = kraken()
    r, F = 0.0254, 1.0
    w = 1e-12 * m.free_speed * m.stall_torque / (4 * r * F)
    hi, lo = ratio_for_loaded_speed(m, r, F, w, "x")
    wf, ts = mp.mpf(m.free_speed), mp.mpf(m.stall_torque)
    x = 4 * r * F * mp.mpf(w) / (ts * wf)
    lo_exact = wf / (2 * mp.mpf(w)) * (1 - mp.sqrt(1 - x))
    assert lo == pytest.approx(float(lo_exact), rel=1e-12)


def test_motor_efficiency_at_zero_torque_with_zero_free_current():
    """(10) is 0/0 at τ = 0 when ĩf = 0; its limit is ω̃f·τ̃s/(V·ĩs)."""
    m = motors.system(motors.Motor("ideal", "t", 12.0, 600.0, 1.5, 80.0, 0.0), 1, 12.0, 1.0)
    assert m.max_efficiency == pytest.approx(600 * 1.5 / (12 * 80), rel=1e-15)
    assert m.max_efficiency_torque == 0.0


def test_max_efficiency_with_tiny_free_current_matches_mpmath():
    """ĩf/ĩs = 1e-14: the sqrt ratio is huge; (91) and η_max stay accurate."""
    mot = motors.Motor("x", "t", 12.0, 500.0, 2.0, 100.0, 1e-12)
    m = motors.system(mot, 1, 12.0, 1.0)
    rf, rs = mp.sqrt(mp.mpf("1e-12")), mp.sqrt(mp.mpf(100))
    assert m.max_efficiency_torque == pytest.approx(float(2 * rf / (rf + rs)), rel=1e-13)
    assert m.max_efficiency == pytest.approx(float(500 * 2 / (12 * (rf + rs) ** 2)), rel=1e-13)


def test_gear_ratio_extreme_but_legal_magnitudes():
    """A 1 mm spool with a 10 kN load on sixteen motors at 0.5 V: ratios far from unity stay exact."""
    o = solve(
        "gear_ratio",
        {
            "motor": "Kraken X60 FOC",
            "motor_count": 16,
            "voltage": "0.5 V",
            "efficiency": 0.05,
            "load": "10 kN",
            "radius": "1 mm",
            "mode": "max_power",
        },
    ).outputs
    ts = mp.mpf("9.37") * mp.mpf("0.05") * 16 * mp.mpf("0.5") / 12
    assert o["ratio"].value == pytest.approx(float(2 * mp.mpf("0.001") * 10000 / ts), rel=1e-12)


def test_pneumatics_tank_that_empties_stays_at_atmospheric():
    """Consumption far beyond the tank: pressure clamps at 0 gauge, never negative or NaN."""
    sol = solve(
        "pneumatics",
        {
            "effects": "",
            "c1_count": 50,
            "c1_bore": "3 in",
            "c1_stroke": "20 in",
            "c1_period": 0.1,
            "c1_start": 0,
        },
    )
    assert sol.outputs["final_pressure"].value == 0.0 and sol.outputs["tank_empty"].value


def test_pneumatics_start_exactly_at_switch_off():
    """P0 = switch-off pressure: the compressor must not start (no zero-length integration)."""
    v = parse_inputs(get("pneumatics"), {"c1_count": 0})[0]
    run = pn.simulate(v, 1e-6)
    assert run.nfev == 0 and run.values["compressor_duty"] == 0.0


def test_pneumatics_fill_time_against_mpmath_quadrature():
    """The switch-off event located to the solver's tolerance: t(P) = ∫ V dP / (P_atm V̇(P)), V̇ the
    vendor table through scipy's PchipInterpolator, integrated piece by piece."""
    from scipy.interpolate import PchipInterpolator

    knots = [k * PSI for k in pn.CURVE_PSI]
    q = PchipInterpolator(knots, [c * pn.CFM for c in pn.COMPRESSORS["Thomas 215 12 V"]])
    exact = mp.quad(lambda p: mp.mpf("1148e-6") / (pn.P_ATM * float(q(float(p)))), knots)
    v = parse_inputs(
        get("pneumatics"), {"c1_count": 0, "start_pressure": 0, "compressor_model": "Thomas 215 12 V"}
    )[0]
    run = pn.simulate(v, 1e-11)
    assert run.values["compressor_duty"] * 150 == pytest.approx(float(exact), rel=1e-9)


def test_pneumatics_fastest_cycling_is_bounded_work():
    """1500 firings in a match: work grows linearly, the result stays finite."""
    v = parse_inputs(
        get("pneumatics"),
        {"c1_period": 0.1, "c1_start": 0, "c1_bore": "0.5 in", "c1_rod": "0.125 in", "c1_stroke": "0.5 in"},
    )[0]
    run = pn.simulate(v, 1e-6)
    assert run.values["firings"] == 1500
    assert math.isfinite(run.values["final_pressure"]) and run.nfev < 200_000


def test_integrator_stiff_decay_has_bounded_steps():
    """y' = −1e4·y over 1 s: explicit DP54 is stability-limited, but finishes and stays accurate."""
    run = integrate(lambda t, y: [-1e4 * y[0]], 0.0, 1.0, [1.0], rtol=1e-6, atol=1e-12)
    assert abs(run.y[-1][0]) < 1e-10 and run.steps < 10_000


def test_integrator_event_grazing_zero_from_above():
    """g = 1 − cos t touches zero at 2π without crossing: no spurious event, no hang."""
    run = integrate(
        lambda t, y: [1.0],
        0.1,
        8.0,
        [0.0],
        rtol=1e-9,
        atol=1e-12,
        events=[Event("touch", lambda t, y: 1 - math.cos(t) + 0.0, -1)],
    )
    assert run.event is None and run.t[-1] == 8.0


def test_integrator_event_at_the_very_first_step_end():
    """The event lies on the end of the span: it is found, located exactly at t1."""
    run = integrate(
        lambda t, y: [1.0],
        0.0,
        1.0,
        [0.0],
        rtol=1e-9,
        atol=1e-12,
        events=[Event("reach", lambda t, y: y[0] - 1.0, +1)],
    )
    assert run.t[-1] == pytest.approx(1.0, abs=1e-12)


def test_motor_side_torque_and_kt_say_they_include_the_gearbox_efficiency():
    """Gear ratio's motor-side torque is r·F/G (η already taken off, as the motor tab's operating
    torque), and the motor tab's Kt is τ̃s/(ĩs − ĩf) with η in it. The labels used to read 'Torque
    at gearbox input' (which would be r·F/(G·η)) and 'Torque constant Kt' (the motor's own is Kt/η).
    Fed across, the two tabs agree: same current and speed at η = 0.7, 3 NEOs."""
    system = dict(motor="NEO", motor_count=3, voltage="12 V", efficiency=0.7)
    g = solve("gear_ratio", {**system, "mode": "ratio", "ratio": 12, "load": "90 lbf", "radius": "1.5 in"})
    tau = g.outputs["motor_torque"].value
    assert tau == pytest.approx(90 * 4.4482216152605 * 1.5 * 0.0254 / 12, rel=1e-12)  # r·F/G
    m = solve("motor", {**system, "torque": f"{tau!r} N*m"})
    assert 3 * g.outputs["current_per_motor"].value == pytest.approx(m.outputs["current"].value, rel=1e-12)
    assert 12 * g.outputs["loaded_speed"].value == pytest.approx(m.outputs["speed"].value, rel=1e-12)
    kt = get("motor").output("kt")
    torque = get("gear_ratio").output("motor_torque")
    assert "η" in kt.label and "K_T/η" in kt.help
    assert "η" in torque.label and "r·F/(G·η)" in torque.help
