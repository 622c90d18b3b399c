"""Lead screw calculator, seed section 3: hand values, the textbook lead-angle form of the
power-screw torques as an independent check, the locked and backdriving cases, and the export
of the equivalent load and radius to the gear-ratio calculator (Appendix B)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core.model import solve
from gearhead.core.registry import get

IN = 0.0254
LBF = 4.4482216152605
RPM = 2 * math.pi / 60


def out(**raw):
    return {k: v.value for k, v in solve("lead_screw", raw).outputs.items()}


def tan_form(F, d, p, n, thread_angle, mu):
    """Independent textbook form: T = F·dm/2·tan(λ ± φ'), tan λ = l/(π·dm), tan φ' = μ·sec α.

    (31)/(32) are this with tan(a ± b) expanded; the efficiency is tan λ / tan(λ + φ').
    """
    dm = d - p / 2
    lam = math.atan(n * p / (math.pi * dm))
    phi = math.atan(mu / math.cos(thread_angle / 2))
    return (
        F * dm / 2 * math.tan(lam + phi),
        F * dm / 2 * math.tan(phi - lam),
        math.tan(lam) / math.tan(lam + phi),
    )


def test_default_half_inch_acme_by_hand():
    # 1/2-10 Acme, μ = 0.15, 100 lbf = 444.822 N, α = 14.5°, cos α = 0.968148
    # dm = 0.5 − 0.05 = 0.45 in = 0.01143 m (30); l = 0.1 in = 0.00254 m
    # (31): num = π·0.15·0.01143 + 0.00254·0.968148 = 0.0053862 + 0.0024591 = 0.0078453
    #       den = π·0.01143·0.968148 − 0.15·0.00254 = 0.0347651 − 0.000381 = 0.0343841
    #       T_R = 444.822·0.01143/2 · 0.0078453/0.0343841 = 2.54216·0.228166 = 0.58003 N·m
    # (33): η = F·l/(2π·T_R) = 1.129848/3.64454 = 0.31001
    o = out()
    assert o["raise_torque"] == pytest.approx(0.58003, rel=1e-4)
    assert o["efficiency"] == pytest.approx(0.31001, rel=1e-4)
    assert o["mean_diameter"] == pytest.approx(0.45 * IN, rel=1e-12)
    assert o["backdrivable"] is False  # μ = 0.15 > l·cos α/(π·dm) = 0.0685
    assert o["drivable"] is True
    # (29): 300 rpm · 0.1 in per turn = 30 in/min = 0.5 in/s
    assert o["linear_speed"] == pytest.approx(0.5 * IN, rel=1e-12)
    # (34): r_eq = 0.1 in / 2π = 0.0159155 in
    assert o["equivalent_radius"] == pytest.approx(0.0159155 * IN, rel=1e-5)


def test_shigley_example_square_thread():
    # Shigley Ex. 8-1 (thread part): 32 mm square thread, p = 4 mm, double start, f = 0.08, F = 6.4 kN.
    # dm = 30 mm, l = 8 mm. T_R = 6400·0.030/2·(8 + π·0.08·30)/(π·30 − 0.08·8)
    #    = 96·15.5398/93.6078 = 15.937 N·m;  T_L = 96·(7.5398 − 8)/(94.2478 + 0.64) = −0.4656 N·m
    # η = 6400·0.008/(2π·15.937) = 51.2/100.135 = 0.5113
    o = out(diameter="32 mm", pitch="4 mm", starts=2, thread_angle="0 deg", friction=0.08, force="6.4 kN")
    assert o["raise_torque"] == pytest.approx(15.937, rel=1e-4)
    assert o["lower_torque"] == pytest.approx(-0.4656, rel=1e-3)
    assert o["efficiency"] == pytest.approx(0.5113, rel=1e-3)
    assert o["backdrivable"] is True


def test_t8_leadscrew_backdrives_by_hand():
    # T8x8 (d = 8 mm, p = 2 mm, 4 starts, 30° trapezoidal), μ = 0.1, F = 100 N:
    # dm = 7 mm, l = 8 mm; l·cos 15°/(π·dm) = 0.3514 > 0.1, so it backdrives.
    # (32): (π·0.1·0.007 − 0.008·0.965926)/(π·0.007·0.965926 + 0.1·0.008) = −0.0055283/0.0220418
    #       = −0.250810; × 100·0.007/2 = −0.087784 N·m
    o = out(diameter="8 mm", pitch="2 mm", starts=4, thread_angle="30 deg", friction=0.1, force="100 N")
    assert o["lower_torque"] == pytest.approx(-0.087784, rel=1e-4)
    assert o["backdrivable"] is True
    assert o["equivalent_lower_load"] == pytest.approx(o["lower_torque"] / (0.008 / (2 * math.pi)), rel=1e-12)


def test_locked_screw_is_reported_not_negative_or_infinite():
    # 16 starts of 0.1 in: l = 1.6 in, dm = 0.45 in; locks when μ ≥ π·0.45·cos 14.5°/1.6 = 0.8554
    sol = solve("lead_screw", {"starts": 16, "friction": 1.0})
    o = {k: v.value for k, v in sol.outputs.items()}
    assert o["drivable"] is False
    assert "raise_torque" not in o and "equivalent_raise_load" not in o
    assert o["efficiency"] == 0
    assert any("cannot be driven" in w and "0.8554" in w for w in sol.warnings)
    assert out(starts=16, friction=0.85)["drivable"] is True


def test_pitch_too_coarse_names_pitch():
    from gearhead.core.errors import InputError

    with pytest.raises(InputError) as e:
        out(diameter="0.5 in", pitch="1 in")
    assert e.value.field == "pitch"


def test_export_to_gear_ratio_gives_the_raise_torque():
    calc = get("lead_screw")
    assert calc.exports == {"gear_ratio": {"load": "equivalent_raise_load", "radius": "equivalent_radius"}}
    sol = solve("lead_screw", {"force": "250 lbf", "rotational_speed": "600 rpm"})
    T_R = sol.outputs["raise_torque"].value
    sent = {field: sol.outputs[name] for field, name in calc.exports["gear_ratio"].items()}
    # exact SI values: at G = 1 and η = 1 the motor torque is r·F = r_eq·L_R,eq = T_R (35)
    exact = solve(
        "gear_ratio",
        {
            "mode": "ratio",
            "ratio": 1,
            "efficiency": 1,
            **{k: f"{v.value!r} {v.unit}" for k, v in sent.items()},
        },
    )
    assert exact.outputs["motor_torque"].value == pytest.approx(T_R, rel=1e-12)
    # at G = 5 the gearbox input sees T_R/5, and the load speed equals the screw's linear speed
    geared = solve(
        "gear_ratio",
        {
            "mode": "ratio",
            "ratio": 5,
            "efficiency": 1,
            **{k: f"{v.value!r} {v.unit}" for k, v in sent.items()},
        },
    )
    assert geared.outputs["motor_torque"].value == pytest.approx(T_R / 5, rel=1e-12)
    # what the TUI sends (ctrl+g) is the displayed text, 5 significant figures each: each is
    # off by at most half a unit in the 5th figure (≤ 5e-5 relative), so the product by ≤ 1e-4
    shown = solve(
        "gear_ratio", {"mode": "ratio", "ratio": 1, "efficiency": 1, **{k: v.text for k, v in sent.items()}}
    )
    assert shown.outputs["motor_torque"].value == pytest.approx(T_R, rel=1e-4)


def zero_or(lo, hi):
    """0 itself or a value in [lo, hi] (entries between 0 and 1e-15 SI are rejected as typos)."""
    return st.one_of(st.just(0.0), st.floats(lo, hi))


inputs = dict(
    d=st.floats(0.002, 0.1),
    p_frac=st.floats(0.01, 0.9),
    n=st.integers(1, 8),
    angle=zero_or(1e-6, math.radians(120)),
    mu=zero_or(1e-6, 0.5),
    F=zero_or(1e-3, 1e5),
)


@settings(max_examples=200, deadline=None)
@given(**inputs)
def test_seed_forms_match_the_lead_angle_form(d, p_frac, n, angle, mu, F):
    p = p_frac * d
    o = out(
        diameter=f"{d!r} m",
        pitch=f"{p!r} m",
        starts=n,
        thread_angle=f"{angle!r} rad",
        friction=mu,
        force=f"{F!r} N",
    )
    T_R, T_L, eta = tan_form(F, d, p, n, angle, mu)
    if not o["drivable"]:
        # locked: λ + φ' ≥ 90°, where tan(λ + φ') has no positive value
        lam = math.atan(n * p / (math.pi * (d - p / 2)))
        assert lam + math.atan(mu / math.cos(angle / 2)) >= math.pi / 2 - 1e-9
        return
    assert o["raise_torque"] == pytest.approx(T_R, rel=1e-9, abs=1e-12)
    assert o["lower_torque"] == pytest.approx(T_L, rel=1e-9, abs=1e-9 * abs(T_R) + 1e-12)
    assert o["efficiency"] == pytest.approx(eta, rel=1e-9)
    # backdriving is a property of the screw (φ' < λ), whatever the load; with a load, T_L < 0
    lam = math.atan(n * p / (math.pi * (d - p / 2)))
    phi = math.atan(mu / math.cos(angle / 2))
    if abs(phi - lam) > 1e-12:
        assert o["backdrivable"] == (phi < lam)
    if F > 0 and o["lower_torque"] != 0:
        assert o["backdrivable"] == (o["lower_torque"] < 0)


@settings(max_examples=150, deadline=None)
@given(**inputs, omega=zero_or(1e-3, 5000))
def test_equivalent_wheel_reverses_the_screw(d, p_frac, n, angle, mu, F, omega):
    """Appendix B both ways: ω·r_eq is the nut speed, r_eq·L_eq the torque, and L_R,eq = F/η."""
    p = p_frac * d
    o = out(
        diameter=f"{d!r} m",
        pitch=f"{p!r} m",
        starts=n,
        thread_angle=f"{angle!r} rad",
        friction=mu,
        force=f"{F!r} N",
        rotational_speed=f"{omega!r} rad/s",
    )
    r = o["equivalent_radius"]
    assert o["linear_speed"] / r == pytest.approx(omega, rel=1e-12, abs=1e-300)
    assert r * o["equivalent_lower_load"] == pytest.approx(o["lower_torque"], rel=1e-12, abs=1e-300)
    if o["drivable"]:
        assert r * o["equivalent_raise_load"] == pytest.approx(o["raise_torque"], rel=1e-12, abs=1e-300)
        assert o["equivalent_raise_load"] * o["efficiency"] == pytest.approx(F, rel=1e-9, abs=1e-9)
        # frictionless the same screw needs exactly F·l/(2π) both ways
    ideal = out(
        diameter=f"{d!r} m",
        pitch=f"{p!r} m",
        starts=n,
        thread_angle=f"{angle!r} rad",
        friction=0,
        force=f"{F!r} N",
    )
    assert ideal["raise_torque"] == pytest.approx(F * n * p / (2 * math.pi), rel=1e-12, abs=1e-300)
    assert ideal["lower_torque"] == pytest.approx(-F * n * p / (2 * math.pi), rel=1e-12, abs=1e-300)
    assert ideal["efficiency"] == pytest.approx(1, rel=1e-12)


def test_builtin_presets_load_and_solve():
    from gearhead.core import presets

    found = presets.listing("lead_screw")
    assert len(found) >= 3 and presets.problems("lead_screw") == []
    by_name = {p.name: {k: v.value for k, v in solve("lead_screw", p.inputs).outputs.items()} for p in found}
    # T8x8 with μ = 0.2: l·cos 15°/(π·dm) = 8·0.96593/(π·7) = 0.3514 > 0.2, so it backdrives
    assert by_name["T8x8 lift (backdrivable)"]["backdrivable"] is True
    assert by_name["Climber, 1/2-10 Acme 2-start"]["backdrivable"] is False


async def test_ctrl_g_sends_equivalent_load_and_radius_to_gear_ratio():
    """The TUI path: ctrl+g on the lead screw tab fills the gear-ratio tab's load and radius."""
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="lead_screw")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        screw_out = app.query_one("#calc-lead_screw", CalculatorTab).solution.outputs
        await pilot.press("ctrl+g")
        await settle(pilot)
        gear = app.query_one("#calc-gear_ratio", CalculatorTab)
        # every digit is sent (in the display unit), not the 5-figure display text
        assert gear.solution.inputs["load"].value == pytest.approx(
            screw_out["equivalent_raise_load"].value, rel=1e-14
        )
        assert gear.solution.inputs["radius"].value == pytest.approx(
            screw_out["equivalent_radius"].value, rel=1e-14
        )
        # the sheet shows them with at most 6 significant digits, in the field's unit
        for stop in gear.sheet.stops:
            if stop.field.name in ("load", "radius"):
                shown = gear.sheet.value_text(stop)
                assert len(shown.replace(".", "").lstrip("0")) <= 6 and " " not in shown, shown
        assert gear.results.state == "fresh"  # the results of exactly those entries
        # at the default ratio G the gearbox input sees T_R/G
        G = gear.solution.outputs["ratio"].value
        assert gear.solution.outputs["motor_torque"].value == pytest.approx(
            screw_out["raise_torque"].value / G, rel=1e-12
        )


def test_friction_sweep_plot_series():
    """The plots: efficiency 1 at μ = 0 falling with μ; the lower torque changes sign at the
    backdrive limit l·cos α/(π·dm) = 0.0685 (default screw); the sweep stops short of locking."""
    s = solve("lead_screw", {}).series
    mus, eta = s["efficiency"]
    assert mus[0] == 0 and eta[0] == pytest.approx(1, rel=1e-15) and mus[-1] == pytest.approx(0.3)
    assert all(a > b for a, b in zip(eta, eta[1:]))
    mus, T_L = s["lower torque"]
    limit = 0.1 * IN * math.cos(math.radians(14.5)) / (math.pi * 0.45 * IN)  # 0.06851
    assert all((t < 0) == (m < limit) for m, t in zip(mus, T_L))
    steep = solve("lead_screw", {"starts": 16, "friction": 0.8}).series["raise torque"]
    assert steep[0][-1] == pytest.approx(0.95 * math.pi * 0.45 * math.cos(math.radians(14.5)) / 1.6)
    assert all(math.isfinite(t) and t > 0 for t in steep[1])


def test_raise_power_is_load_power_over_efficiency():
    # default 1/2-10 Acme at 300 rpm: F·v = 444.822 N · 0.0127 m/s = 5.64924 W; η = 0.31001,
    # so the screw needs 5.64924/0.31001 = 18.223 W = T_R·ω (0.58003 N*m · 31.4159 rad/s)
    o = out()
    assert o["raise_power"] == pytest.approx(18.223, rel=1e-4)
    assert o["raise_power"] * o["efficiency"] == pytest.approx(100 * LBF * 0.5 * IN, rel=1e-12)
