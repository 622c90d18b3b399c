"""Drivetrain sprint (core/calculators/sprint.py, issue 29): hand values from the motor data and mpmath,
the closed form against the integrated scene, the optimiser's minimum, and what it refuses.

Hand model (the module's (S1)-(S8), written again here from the motor data, not from the code): per
motor R = 12/I_s, Kv = ω_f/(12 − R·I_f), Kt = τ_s/(I_s − I_f); the robot's force from the motors
F_m(v) = η·N·Kt·(G/r)·((V − (G/r)·v/Kv)/R − I_f), at most μ·m·g."""

import json
import math

import mpmath as mp
import pytest

from gearhead.core.calculators import sprint
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get

G0 = 9.80665
RPM = 2 * math.pi / 60
LB, INCH = 0.45359237, 0.0254
KRAKEN = (7.09, 366.0, 2.0, 6000 * RPM)  # WPILib DCMotor.krakenX60: τs N·m, Is A, If A, ωf rad/s


def values(**raw):
    return parse_inputs(get("sprint"), raw)[0]


def hand_time(G, d, N=4, eta=0.9, m=135 * LB, r=2 * INCH, mu=1.1, crr=0.0, V=12.0, motor=KRAKEN):
    """Time to d from rest by mpmath: constant acceleration (μ − C_rr)·g while F_m > μ·m·g, then
    m·v̇ = F_m(v) − C_rr·m·g integrated by mp.odefun and the crossing found by mp.findroot."""
    mp.mp.dps = 30
    ts, Is, If, wf = (mp.mpf(x) for x in motor)
    R = 12 / Is
    Kv, Kt = wf / (12 - R * If), ts / (Is - If)
    n = mp.mpf(G) / r
    fpa = eta * N * Kt * n

    def F_m(v):
        return fpa * ((V - n * v / Kv) / R - If * V / 12)

    Ft, Frr = mu * m * G0, crr * m * G0
    a1 = (Ft - Frr) / m
    v_sw = mp.findroot(lambda v: F_m(v) - Ft, 1.0) if F_m(0) > Ft else mp.mpf(0)
    t_sw, x_sw = v_sw / a1, v_sw**2 / (2 * a1)
    if x_sw >= d:
        return float(mp.sqrt(2 * d / a1))
    # phase 2 is linear: m·v̇ = (m/τ)(v_f − v), solved exactly here, the crossing by findroot
    tau = m * R * Kv / (fpa * n)
    v_f = mp.findroot(lambda v: F_m(v) - Frr, 1.0)
    x = lambda s: x_sw + v_f * s - (v_f - v_sw) * tau * (1 - mp.exp(-s / tau))  # noqa: E731
    s = mp.findroot(lambda s: x(s) - d, (d - x_sw) / v_f)
    return float(t_sw + s)


@pytest.mark.parametrize("G,d", [(6.75, 5.0), (5.36, 16.54), (8.14, 1.0), (20.0, 3.0), (4.0, 0.3)])
def test_time_to_distance_by_hand(G, d):
    out = solve("sprint", {"ratio": G, "distance": f"{d} m", "accuracy": "tight", "effects": ""}).outputs
    assert out["time_to_distance"].value == pytest.approx(hand_time(G, d), rel=1e-12)


def test_traction_only_sprint_is_uniform_acceleration():
    """A short sprint at a low gear never leaves the traction limit: T = √(2d/((μ − C_rr)·g))."""
    out = solve("sprint", {"ratio": 12, "distance": "0.2 m", "effects": "rolling_resistance"}).outputs
    a = (1.1 - 0.02) * G0
    assert out["traction_distance"].value == pytest.approx(0.2, rel=1e-15)
    assert out["time_to_distance"].value == pytest.approx(math.sqrt(2 * 0.2 / a), rel=1e-14)
    # the motors sit at the edge of slip the whole time: the supply current is the slip current
    assert out["peak_supply_current"].value == pytest.approx(out["slip_current"].value, rel=1e-12)


def test_slip_current_and_gains_by_hand():
    ts, Is, If, wf = KRAKEN
    R, Kt = 12 / Is, ts / (Is - If)
    Kv = wf / (12 - R * If)
    m, n = 135 * LB, 6.75 / (2 * INCH)
    fpa = 0.9 * 4 * Kt * n
    out = solve("sprint", {"effects": ""}).outputs
    assert out["slip_current"].value == pytest.approx(1.1 * m * G0 / fpa + If, rel=1e-14)  # (S5)
    assert out["kV"].value == pytest.approx(n / Kv, rel=1e-14)
    assert out["kA"].value == pytest.approx(m * R / fpa, rel=1e-14)
    assert out["kS"].value == pytest.approx(R * If, rel=1e-14)
    assert out["free_speed"].value == pytest.approx(wf / n, rel=1e-14)  # the rated free speed


@pytest.mark.parametrize(
    "raw",
    [
        {"effects": ""},
        {"effects": "rolling_resistance"},
        {"effects": "battery_sag, rolling_resistance", "battery_resistance": 0.02},
        {"ratio": 20, "distance": "3 m", "effects": ""},
        {"distance": "0.05 m", "ratio": 5, "effects": "battery_sag"},
    ],
)
def test_closed_form_equals_the_integrated_scene(raw):
    """(S6)-(S8) against (S4) integrated at 1e-12 (both phases, restarted where the wheels grip)."""
    s = sprint.setup(values(**raw))
    exact = sprint.closed_form(s)
    assert exact is not None
    got, run, _ = sprint.integrated(s, 1e-12)
    for k in ("time", "speed", "traction_time", "traction_distance"):
        assert got[k] == pytest.approx(exact[k], rel=1e-9, abs=1e-12), k
    assert got["energy"] == pytest.approx(sprint._energy_closed(s, exact, *_slip(s)), rel=1e-9)


def _slip(s):
    _, elec = sprint._motor_force(s)
    I_slip, E_slip = sprint._slip_point(s, elec)
    return I_slip, elec(E_slip)[0]


def test_stator_limit_below_the_slip_current_by_hand():
    """A 40 A limit (slip at 72.9 A): the wheels never slip; constant force η·N·Kt·n·(I_st − I_f)
    until the full-voltage current falls to I_st at v₁ = (V − R·I_st)·Kv/n, then the first-order
    approach to the free speed."""
    ts, Is, If, wf = KRAKEN
    R, Kt = 12 / Is, ts / (Is - If)
    Kv = wf / (12 - R * If)
    m, n, I_st, d = 135 * LB, 6.75 / (2 * INCH), 40.0, 5.0
    fpa = 0.9 * 4 * Kt * n
    a = fpa * (I_st - If) / m
    v1 = (12 - R * I_st) * Kv / n
    t1, x1 = v1 / a, v1 * v1 / (2 * a)
    tau = m * R * Kv / (fpa * n)
    v_f = (12 - R * If) * Kv / n
    s = mp.findroot(lambda s: x1 + v_f * s - (v_f - v1) * tau * (1 - mp.exp(-s / tau)) - d, 1.0)
    out = solve(
        "sprint", {"effects": "stator_limit", "stator_current_limit": 40, "accuracy": "tight"}
    ).outputs
    assert out["traction_distance"].value == 0
    assert out["time_to_distance"].value == pytest.approx(t1 + float(s), rel=1e-9)
    assert out["peak_stator_current"].value == pytest.approx(I_st, rel=1e-12)


def test_optimise_finds_the_minimum():
    out = solve("sprint", {"mode": "optimise", "distance": "5 m"})
    G_best = out.outputs["best_ratio"].value
    T_best = out.outputs["time_to_distance"].value
    for k in (0.98, 1.02):
        T = solve("sprint", {"ratio": G_best * k, "distance": "5 m"}).outputs["time_to_distance"].value
        assert T > T_best
    rows = out.tables["distances"]
    assert [r["distance"].value for r in rows] == pytest.approx([1.0, 3.0, 5.0, 16.54])
    assert rows[2]["best_ratio"].value == pytest.approx(G_best, rel=1e-4)
    for r in rows:  # each row's ratio is no slower than its neighbours 2 % either side
        d, G_, T_ = r["distance"].value, r["best_ratio"].value, r["time"].value
        for k in (0.98, 1.02):
            T = solve("sprint", {"ratio": G_ * k, "distance": f"{d} m"}).outputs["time_to_distance"].value
            assert T >= T_ * (1 - 1e-9), (d, k)


def test_a_flat_optimum_reports_the_least_reduction_that_ties():
    """With no current limit four Kraken X60s keep the wheels at the edge of slip for the whole
    metre at many ratios: the time is √(2d/(μ·g)) for all of them, and the least reduction that
    does it is reported (a slightly lower one leaves the traction limit before the metre)."""
    out = solve("sprint", {"mode": "optimise", "distance": "1 m", "effects": ""}).outputs
    G_best = out["best_ratio"].value
    assert out["time_to_distance"].value == pytest.approx(math.sqrt(2 / (1.1 * G0)), rel=1e-12)
    below = solve("sprint", {"ratio": G_best * (1 - 1e-6), "distance": "1 m", "effects": ""}).outputs
    assert below["traction_distance"].value < 1.0


@pytest.mark.parametrize(
    "raw,field",
    [
        ({"wheel_cof": 0.05, "effects": "rolling_resistance", "rolling_coefficient": 0.1}, "wheel_cof"),
        ({"effects": "stator_limit", "stator_current_limit": 1.5}, "stator_current_limit"),
        ({"supply_current_limit": 0}, "supply_current_limit"),  # both limits on: the one that binds
        (
            {"effects": "rolling_resistance", "rolling_coefficient": 0.9, "wheel_cof": 2, "ratio": 0.05},
            "ratio",
        ),
    ],
)
def test_cannot_move_names_the_field(raw, field):
    with pytest.raises(InputError) as e:
        solve("sprint", raw)
    assert e.value.field == field


def test_a_stiff_sprint_is_handed_to_lsoda():
    """A 1 lb robot on 1000:1: the speed settles in τ ≈ 5 ns over a 31 s sprint (T/τ ~ 1e10), which no
    explicit step crosses; LSODA does, and the time is the closed form's (no drag: (S8))."""
    raw = {"robot_mass": "1 lb", "ratio": 1000, "distance": "1 m"}
    stiff = solve("sprint", raw | {"effects": "air_drag", "drag_area": 0}).outputs
    exact = solve("sprint", raw | {"effects": ""}).outputs
    assert stiff["rhs_evaluations"].value > 0 and exact["rhs_evaluations"].value == 0
    assert stiff["time_to_distance"].value == pytest.approx(exact["time_to_distance"].value, rel=1e-5)


def test_weight_transfer_by_hand():
    """Four equal modules, CG midway at h: the front ones carry m·g/2 − m·a·h/L, and slip when
    m·a/4 > μ·(m·g/2 − m·a·h/L)/2, so a traction-limited robot accelerates at a = μ·g/(1 + 2μ·h/L):
    μ = 1.1, h = 8 in, L = 22.75 in gives 6.0818 m/s² (μ·g = 10.787), checked on a 0.2 m sprint."""
    a = 1.1 * G0 / (1 + 2 * 1.1 * 8 / 22.75)
    raw = {
        "ratio": 12,
        "distance": "0.2 m",
        "effects": "weight_transfer",
        "wheelbase": "22.75 in",
        "cg_height": "8 in",
    }
    out = solve("sprint", raw).outputs
    assert out["traction_acceleration"].value == pytest.approx(a, rel=1e-14)
    assert out["time_to_distance"].value == pytest.approx(math.sqrt(2 * 0.2 / a), rel=1e-14)
    # with no height nothing transfers
    flat = solve("sprint", raw | {"cg_height": 0}).outputs
    assert flat["traction_acceleration"].value == pytest.approx(1.1 * G0, rel=1e-15)


def test_angular_ka_by_hand():
    """Turning in place the wheels' total force F acts at r_b = track/2: I·α = F·r_b; the voltage for a
    force is F/(force per volt) = F·kA/m, so V/α = kA·I/(m·r_b) (V·s²/rad). PathPlanner's
    I = m·r_b·kA_angular/kA inverts it; checked for an entered I."""
    out = solve(
        "sprint", {"inertia_model": "entered", "moment_of_inertia": "5 kg*m**2", "trackwidth": "0.6 m"}
    )
    o = out.outputs
    m = 135 * LB
    assert o["kA_angular"].value == pytest.approx(o["kA"].value * 5 / (m * 0.3), rel=1e-14)
    assert m * 0.3 * o["kA_angular"].value / o["kA"].value == pytest.approx(5, rel=1e-14)


@pytest.mark.parametrize(
    "drive,G,wheel_in",
    [
        ("sds_mk4i_l1", 8.142857142857142, 4),  # (50/14)(19/25)(45/15)
        ("sds_mk4i_l2", 6.746031746031746, 4),  # (50/14)(17/27)(45/15)
        ("sds_mk4i_l3", 6.122448979591837, 4),  # (50/14)(16/28)(45/15)
        ("rev_maxswerve_12t", 5.5, 3),  # 45·22/(12·15)
        ("rev_maxswerve_13t", 5.076923076923077, 3),
        ("rev_maxswerve_14t", 4.714285714285714, 3),
    ],
)
def test_a_cots_module_is_its_ratio_and_wheel(drive, G, wheel_in):
    module = solve("sprint", {"drive": drive}).outputs
    entered = solve("sprint", {"ratio": G, "wheel_diameter": f"{wheel_in} in"}).outputs
    for k in ("time_to_distance", "free_speed", "slip_current"):
        assert module[k].value == pytest.approx(entered[k].value, rel=1e-12), k


def test_a_ratio_set_beside_a_module_is_reported_unused(capsys):
    from gearhead.tui.cli import main

    assert main(["solve", "sprint", "--set", "drive=sds_mk4i_l2", "--set", "ratio=9", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert any(w.startswith("ratio: not used") for w in out["warnings"])


def test_default_accuracy_is_kept_across_the_supply_limits_release():
    """The default sprint (stator and supply limits, sag) at rtol 1e-6 against 1e-13: the time within
    1e-6. Steps that straddled the supply limit's release (a kink in the acceleration) gave 4.2e-6;
    the run now stops and restarts at each branch point of the duty rule."""
    s = sprint.setup(values())
    ref, _, _ = sprint.integrated(s, 1e-13)
    got, _, _ = sprint.integrated(s, 1e-6)
    assert abs(got["time"] - ref["time"]) <= 1e-6 * ref["time"]
