"""Elevator and arm scenes (core.sim.motion) on the effects API (core.sim.effects).

Reference values are worked out here by hand from the motor data (REFERENCE_DATA.md) or with
mpmath, never copied from the code's output; WPILib's own LQR test values are quoted from
wpimath/src/test/java/org/wpilib/math/controller/LinearQuadraticRegulatorTest.java.
"""

import json
import math

import mpmath as mp
import numpy as np
import pytest

from gearhead.core.calculators import arm, elevator
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import motion
from gearhead.core.sim.effects import Effects
from gearhead.core.sim.scene import LEVELS, ladder

G0 = 9.80665
RPM = 2 * math.pi / 60
LB = 0.45359237
INCH = 0.0254


def values(calc, **raw):
    return parse_inputs(get(calc), raw)[0]


NEO_FREE_CURRENT = 1.8  # A at 12 V


def neo():  # WPILib DCMotor.getNEO figures: 2.6 N·m, 105 A, 1.8 A, 5676 rpm at 12 V; Kt the seed's (7)
    R = 12 / 105
    return R, 5676 * RPM / (12 - R * 1.8), 2.6 / (105 - 1.8)


# --- closed forms --------------------------------------------------------------------------------


def elevator_closed_form_time(G, m, r, d, F_load, N=2, V=12.0):
    """m·ẇ = N·Kt·n·((V − n·w/Kv)/R − i_f) − F_load  ⇒  w = w_f(1 − e^{−t/τ}),
    x = w_f(t − τ(1 − e^{−t/τ})); x = d ⇔ T = D + 1 + W0(−e^{−(D+1)}) with T = t/τ, D = d/(w_f·τ)."""
    R, Kv, Kt = neo()
    n = G / r
    tau = mp.mpf(m) * R * Kv / (N * Kt * n * n)
    F = F_load + N * Kt * n * NEO_FREE_CURRENT * V / 12  # the motors' own loss (M3) on the load
    w_f = (V - F * R / (N * Kt * n)) * Kv / n
    D = d / (w_f * tau)
    return float(tau * (D + 1 + mp.lambertw(-mp.exp(-(D + 1))).real))


@pytest.mark.parametrize("G", [4.0, 10.0, 60.0])
@pytest.mark.parametrize("gravity", [False, True])
def test_elevator_matches_the_first_order_closed_form(G, gravity):
    m, r, d = 15 * LB, 0.75 * INCH, 40 * INCH
    v = values("elevator", ratio=G, effects="gravity" if gravity else "", accuracy="tight")
    got = elevator.simulate(v, 1e-11).values["time_to_goal"]
    want = elevator_closed_form_time(G, m, r, d, m * G0 if gravity else 0.0)
    assert got == pytest.approx(want, rel=1e-9)


@pytest.mark.parametrize("method", ["DP54", "LSODA"])
def test_both_integrators_agree_with_the_closed_form(method):
    m, r, d = 15 * LB, 0.75 * INCH, 40 * INCH
    v = values("elevator", ratio=4, effects="")
    mv = motion.move(elevator.setup(v), 1e-10, method=method)
    assert mv.time == pytest.approx(elevator_closed_form_time(4.0, m, r, d, 0.0), rel=1e-8)


@pytest.mark.parametrize("effects", ["", "gravity", "gravity, battery_sag, friction, counterbalance"])
@pytest.mark.parametrize("travel", ["40 in", "-40 in", "0.01 mm"])
def test_elevator_closed_form_equals_the_integrated_move(effects, travel):
    """With no current limit the elevator is answered in closed form (no integration): it must
    agree with the integrated scene (both integrators) in every output the move gives."""
    v = values("elevator", effects=effects, travel=travel, battery_resistance=0.05)
    s = elevator.setup(v)
    exact = motion.closed_form(s)
    assert exact is not None and exact.nfev == 0
    for method in ("DP54", "LSODA"):
        mv = motion.move(s, 1e-11, method=method)
        assert mv.time == pytest.approx(exact.time, rel=1e-8)
        assert mv.max_speed == pytest.approx(exact.max_speed, rel=1e-8)
        assert mv.energy == pytest.approx(exact.energy, rel=1e-7)
    out = elevator.simulate(v, 1e-6)
    assert out.nfev == 0 and any("closed form" in w for w in out.warnings)
    assert motion.closed_form(elevator.setup(values("elevator", effects="gravity, stator_limit"))) is None


def test_stator_limit_constant_current_phase_then_exponential():
    """No gravity, no sag: at the limit I_st the force is constant, a = N·Kt·n·(I_st − i_f)/m, until
    the full-voltage current falls to I_st at E₁ = V − R·I_st; then the first-order approach to the
    free speed (V − R·i_f)·Kv/n."""
    I_st, G, m, r = 30.0, 10.0, 15 * LB, 0.75 * INCH
    R, Kv, Kt = neo()
    n = G / r
    a = 2 * Kt * n * (I_st - NEO_FREE_CURRENT) / m
    w1 = (12 - R * I_st) * Kv / n
    t1, x1 = w1 / a, w1 * w1 / (2 * a)
    tau = m * R * Kv / (2 * Kt * n * n)
    w_f = (12 - R * NEO_FREE_CURRENT) * Kv / n
    for d in (0.5 * x1, 3 * x1 + 0.5):
        v = values("elevator", ratio=G, effects="stator_limit", stator_current_limit=I_st, travel=f"{d} m")
        got = elevator.simulate(v, 1e-11).values
        if d < x1:
            want = math.sqrt(2 * d / a)
        else:
            dt = mp.findroot(lambda s: x1 + w_f * s - (w_f - w1) * tau * (1 - mp.exp(-s / tau)) - d, 0.5)
            want = t1 + float(dt)
        assert got["time_to_goal"] == pytest.approx(want, rel=1e-9)
        assert got["peak_stator_current"] == pytest.approx(I_st, rel=1e-12)


def test_feedforward_gains_by_hand():
    R, Kv, Kt = neo()
    m, r, G, eta = 15 * LB, 0.75 * INCH, 10.0, 0.9
    n = G / r
    out = elevator.simulate(values("elevator", efficiency=eta), 1e-6).values
    assert out["kV"] == pytest.approx(n / Kv, rel=1e-12)
    assert out["kA"] == pytest.approx(m * R / (eta * 2 * Kt * n), rel=1e-12)
    assert out["kG"] == pytest.approx(m * G0 * R / (eta * 2 * Kt * n), rel=1e-12)
    # arm: one Kraken X60 (WPILib 7.09 N·m, 366 A, 2 A, 6000 rpm), kG at horizontal
    Rk = 12 / 366
    Kvk, Ktk = 6000 * RPM / (12 - Rk * 2), 7.09 / (366 - 2)
    ma, L, Ga = 8 * LB, 12 * INCH, 75.0
    o = arm.simulate(values("arm"), 1e-6).values
    assert o["kG"] == pytest.approx(ma * G0 * L * Rk / (Ktk * Ga), rel=1e-12)
    assert o["kV"] == pytest.approx(Ga / Kvk, rel=1e-12)
    assert o["kA"] == pytest.approx(4 / 3 * ma * L * L * Rk / (Ktk * Ga), rel=1e-12)
    assert o["kS"] == pytest.approx(Rk * 2, rel=1e-12)  # R·i_f: the motor's own loss
    assert out["kS"] == pytest.approx(R * NEO_FREE_CURRENT, rel=1e-12)
    # counterbalance and friction: kG net of the spring, kS = R·i_f + friction over force per volt
    o = arm.simulate(
        values(
            "arm", effects="gravity, counterbalance, friction", counterbalance_torque=3, friction_torque=0.5
        ),
        1e-6,
    ).values
    assert o["kG"] == pytest.approx((ma * G0 * L - 3) * Rk / (Ktk * Ga), rel=1e-12)
    assert o["kS"] == pytest.approx(Rk * 2 + 0.5 * Rk / (Ktk * Ga), rel=1e-12)


# --- LQR against WPILib's own tests ----------------------------------------------------------------


def _775pro(count):  # WPILib getVex775Pro: 0.71 N·m, 134 A, 0.7 A, 18730 rpm
    R = 12 / 134
    Kv = 18730 * RPM / (12 - R * 0.7)
    Kt = 0.71 / 134
    return R / count, Kv, Kt  # WPILib's combined motor: R/N, same Kv and Kt


def _elevator_gains(count, m, r, G):
    R, Kv, Kt = _775pro(count)
    # Models.elevatorFromPhysicalConstants: A11 = −G²Kt/(R·Kv·r²·m), B1 = G·Kt/(R·r·m)
    A11, B1 = -G * G * Kt / (R * Kv * r * r * m), G * Kt / (R * r * m)
    return -A11 / B1, 1 / B1  # kV, kA


def test_lqr_matches_wpilib_elevator_and_arm_tests():
    kV, kA = _elevator_gains(2, 5.0, 0.0181864, 1.0)
    assert motion.lqr(kV, kA, 0.02, 0.4, 12.0, 0.005, 0.0) == pytest.approx(
        (522.87006795347486, 38.239878385020411), abs=1e-6
    )
    kV, kA = _elevator_gains(4, 8.0, 0.75 * 25.4 / 1000, 14.67)
    assert motion.lqr(kV, kA, 0.1, 0.2, 12.0, 0.020, 0.0) == pytest.approx((10.381, 0.6929), abs=1e-2)
    assert motion.lqr(kV, kA, 0.1, 0.2, 12.0, 0.020, 0.01) == pytest.approx(
        (8.97115941, 0.07904881), abs=1e-3
    )
    R, Kv, Kt = _775pro(2)
    I, G = 4.0 * 0.4 * 0.4 / 3, 100.0
    A11, B1 = -G * G * Kt / (Kv * R * I), G * Kt / (R * I)  # Models.singleJointedArmFromPhysicalConstants
    assert motion.lqr(-A11 / B1, 1 / B1, 0.01745, 0.08726, 12.0, 0.005, 0.0) == pytest.approx(
        (19.339349883583761, 3.3542559517421582), abs=1e-6
    )


def test_lqr_through_the_elevator_calculator():
    v = values(
        "elevator",
        motor="775pro",
        motor_count=2,
        load_mass="5 kg",
        spool_diameter=f"{2 * 0.0181864} m",
        ratio=1,
        q_position="0.02 m",
        q_velocity="0.4 m/s",
        r_volts=12,
        control_period="5 ms",
        travel="0.2 m",
    )
    out = elevator.simulate(v, 1e-6).values
    # the plant of WPILib's test, with the seed's Kt = τs/(Is − If) (M1) in place of WPILib's τs/Is
    # (motion.lqr itself is checked against WPILib's numbers above)
    R, Kv, _ = _775pro(2)
    Kt = 0.71 / (134 - 0.7)
    r, m = 0.0181864, 5.0
    kV, kA = 1 / (r * Kv), R * r * m / Kt
    assert out["kV"] == pytest.approx(kV, rel=1e-12) and out["kA"] == pytest.approx(kA, rel=1e-12)
    assert (out["kP"], out["kD"]) == pytest.approx(motion.lqr(kV, kA, 0.02, 0.4, 12.0, 0.005, 0.0), rel=1e-12)


# --- the algebraic loop ------------------------------------------------------------------------------


@pytest.mark.parametrize("E", [0.0, 2.0, 7.5, 11.0])
def test_current_limits_with_sag_solve_the_loop_exactly(E):
    """(E1)-(E3) against a direct solve: duty u, bus V = V_b − R_bus·u·I, I = (u·V − E)/R."""
    v = values(
        "elevator",
        effects="stator_limit, supply_limit, battery_sag",
        stator_current_limit=60,
        supply_current_limit=25,
        battery_resistance=0.03,
        motor_count=4,
    )
    s = elevator.setup(v)
    m = s.mech
    u, I = motion.electrical(m, s.asm.slots["duty"])(E)
    V = m.battery_voltage - 4 * 0.03 * u * I
    assert I == pytest.approx((u * V - E) / m.R, rel=1e-12, abs=1e-12)
    assert I <= 60 * (1 + 1e-12) and u * I <= 25 * (1 + 1e-12) and 0 < u <= 1

    def current(x):  # the loop solved for the current at duty x (mpmath, 40 digits)
        mp.mp.dps = 40
        return mp.findroot(lambda i: i - (x * (m.battery_voltage - 0.12 * x * i) - E) / m.R, 50)

    # the duty is the first one (rising from 0) at which a limit is met
    binding = [x for x in np.linspace(1e-3, 1, 2000) if current(x) > 60 or x * current(x) > 25]
    if binding:
        assert u == pytest.approx(binding[0], abs=1e-3)
    else:
        assert u == 1.0


# --- effects: off means absent --------------------------------------------------------------------

CASES = [
    (elevator, "gravity, stator_limit, supply_limit, battery_sag, friction, counterbalance"),
    (arm, "gravity, stator_limit, supply_limit, battery_sag, friction, counterbalance"),
]
TERMS = {
    "gravity": "force",
    "counterbalance": "force",
    "friction": "friction",
    "stator_limit": "duty",
    "supply_limit": "duty",
    "battery_sag": None,
}


@pytest.mark.parametrize("calc,all_on", CASES)
@pytest.mark.parametrize("effect", list(TERMS))
def test_an_effect_off_adds_no_state_no_term_and_changes_nothing(calc, all_on, effect):
    others = ", ".join(e for e in all_on.split(", ") if e != effect)
    v_off = values(calc.CALCULATOR.id, effects=others)
    v_on = values(calc.CALCULATOR.id, effects=all_on)
    off, on = calc.setup(v_off), calc.setup(v_on)
    assert off.asm.states == on.asm.states == off.asm.states[:3]  # no effect here adds state
    slot = TERMS[effect]
    if slot:
        assert effect in on.asm.contributors[slot] and effect not in off.asm.contributors[slot]
        assert on.asm.n_terms == off.asm.n_terms + 1
    else:  # battery_sag contributes a resistance, not a term: off, it is exactly zero
        assert on.mech.bus_resistance > 0 and off.mech.bus_resistance == 0.0
        assert on.asm.n_terms == off.asm.n_terms
    # a scene that never heard of the effect gives bit-identical outputs
    without = Effects(*[e for e in calc.EFFECTS.effects if e.name != effect])
    asm = without.assemble(v_off["effects"], v_off, off.mech, motion.SLOTS, off.asm.states[:3])
    bare = motion.Setup(off.mech, without, asm, off.varying, off.critical, v_off, off.names)
    hold = 0.0 if calc is arm else None
    assert motion.run_move(bare, 1e-6, hold).values == motion.run_move(off, 1e-6, hold).values


@pytest.mark.parametrize("calc", [elevator, arm])
def test_neutral_settings_of_an_effect_change_nothing_and_real_ones_change_only_their_outputs(calc):
    cid = calc.CALCULATOR.id
    base = solve(cid, {"effects": "gravity"}).outputs
    neutral = solve(
        cid,
        {
            "effects": "gravity, battery_sag, friction, counterbalance, stator_limit, supply_limit",
            "battery_resistance": 0,
            "friction_force" if calc is elevator else "friction_torque": 0,
            "counterbalance_force" if calc is elevator else "counterbalance_torque": 0,
            "stator_current_limit": 2000,
            "supply_current_limit": 2000,
        },
    ).outputs
    for k in (
        "time_to_goal",
        "max_speed",
        "energy",
        "kS",
        "kG",
        "kV",
        "kA",
        "kP",
        "kD",
        "peak_stator_current",
    ):
        assert neutral[k].value == pytest.approx(base[k].value, rel=1e-5, abs=1e-12), k
    sag = solve(cid, {"effects": "gravity, battery_sag", "battery_resistance": 0.02}).outputs
    n = solve(cid, {}).inputs["motor_count"].value
    assert sag["min_bus_voltage"].value == pytest.approx(
        12 - n * 0.02 * sag["peak_supply_current"].value, rel=1e-12
    )
    assert sag["time_to_goal"].value > base["time_to_goal"].value
    for k in ("kG", "kV", "kA", "hold_current"):  # sag changes the move, not the model's gains
        assert sag[k].value == base[k].value
    sup = solve(cid, {"effects": "gravity, supply_limit", "supply_current_limit": 20}).outputs
    assert sup["peak_supply_current"].value == pytest.approx(20, rel=1e-9)
    off = solve(cid, {"effects": ""}).outputs
    assert off["kG"].value == 0 and off["hold_current"].value == 0


# --- hard cases and bad input ------------------------------------------------------------------------


def _accurate(cid, raw):
    """The default-accuracy answer against a run 1e5 tighter: finite and within 1e-5."""
    v = values(cid, **raw)
    calc = elevator if cid == "elevator" else arm
    a = calc.simulate(v, LEVELS["default"]).values
    b = calc.simulate(v, 1e-11).values
    for k, tol in (("time_to_goal", 1e-5), ("max_speed", 1e-5), ("energy", 5e-5)):
        assert math.isfinite(a[k])
        assert a[k] == pytest.approx(b[k], rel=tol), k
    return a


@pytest.mark.parametrize(
    "raw",
    [
        {"travel": "0.1 mm"},
        {"ratio": 2000},  # a 3 minute crawl: LSODA, not 10⁹ explicit steps
        {"travel": "2 in", "ratio": 3},  # ~0.1 s
        {"ratio": 300, "travel": "60 in"},  # ~60 s
        {"effects": "gravity, stator_limit, supply_limit, battery_sag", "travel": "-40 in"},
        {"incline": "90 deg"},
        {"incline": "120 deg", "travel": "10 in"},
        {"rigging": "cascade", "stages": 3},
    ],
)
def test_elevator_hard_cases_stay_finite_and_accurate(raw):
    _accurate("elevator", raw)


@pytest.mark.parametrize(
    "raw",
    [
        {"goal_angle": "-60 deg"},  # goal behind the start: swings down
        {"start_angle": "-90 deg", "goal_angle": "270 deg"},  # over the top
        {"ratio": 5000},
        {"goal_angle": "-29.9 deg"},  # tiny move
        {"effects": "gravity, stator_limit, supply_limit, battery_sag, friction, counterbalance"},
    ],
)
def test_arm_hard_cases_stay_finite_and_accurate(raw):
    _accurate("arm", raw)


def test_limit_barely_above_the_current_to_move():
    """Moving up takes the hold current plus the motors' own loss current i_f (1.8 A per NEO at 12 V)."""
    move = solve("elevator", {"effects": "gravity"}).outputs["hold_current"].value + NEO_FREE_CURRENT
    out = _accurate(
        "elevator", {"effects": "gravity, stator_limit", "stator_current_limit": f"{move * 1.01} A"}
    )
    assert out["time_to_goal"] > 1.0  # slow, but it arrives
    with pytest.raises(InputError) as e:
        solve("elevator", {"effects": "gravity, stator_limit", "stator_current_limit": f"{move * 0.99} A"})
    assert e.value.field == "stator_current_limit"


@pytest.mark.parametrize(
    "cid,raw,field",
    [
        ("elevator", {"load_mass": "700 lb"}, "ratio"),
        ("elevator", {"effects": "gravity, stator_limit", "stator_current_limit": 0}, "stator_current_limit"),
        ("elevator", {"effects": "gravity, supply_limit", "supply_current_limit": 0}, "supply_current_limit"),
        (
            "elevator",
            {"effects": "gravity, battery_sag", "battery_resistance": 5, "load_mass": "50 lb"},
            "battery_resistance",
        ),
        ("elevator", {"travel": 0}, "travel"),
        ("arm", {"arm_mass": "500 lb"}, "ratio"),
        ("arm", {"goal_angle": "-30 deg"}, "goal_angle"),
        ("arm", {"inertia_model": "entered", "moment_of_inertia": "10 lb*in**2"}, "moment_of_inertia"),
    ],
)
def test_a_mechanism_that_cannot_move_names_the_reason_and_field(cid, raw, field):
    with pytest.raises(InputError) as e:
        solve(cid, raw)
    assert e.value.field == field


def test_arm_gravity_beats_the_motor_only_past_horizontal():
    """From −90° to −30° the worst angle is −30°; a goal past horizontal meets the full m·g·L."""
    v = dict(arm_mass="120 lb", ratio=20, start_angle="-90 deg")
    solve("arm", {**v, "goal_angle": "-60 deg"})  # cos(−60°) = 0.5: the motor wins
    with pytest.raises(InputError) as e:
        solve("arm", {**v, "goal_angle": "45 deg"})
    assert e.value.field == "ratio" and "0°" in e.value.message


def test_goal_behind_the_start_moves_the_other_way():
    up = solve("elevator", {"effects": "", "travel": "30 in"}).outputs
    down = solve("elevator", {"effects": "", "travel": "-30 in"}).outputs
    assert down["time_to_goal"].value == pytest.approx(up["time_to_goal"].value, rel=1e-9)
    series = solve("elevator", {"travel": "-30 in"}).series
    assert series["position"][1][-1] == pytest.approx(-30 * INCH, rel=1e-9)
    assert max(series["speed"][1]) <= 0


# --- accuracy, optimise, CLI ----------------------------------------------------------------------


@pytest.mark.parametrize("cid", ["elevator", "arm"])
def test_accuracy_ladder_tightens(cid):
    calc = get(cid)
    v = values(cid, effects="gravity, stator_limit, battery_sag")
    rungs, _ = ladder(calc.simulate, v, repeats=1)
    errors = {r.level: r.error for r in rungs}
    assert errors["default"] < 1e-5
    assert errors["tight"] < 1e-8
    assert errors["coarse"] >= errors["tight"]


@pytest.mark.parametrize("calc", [elevator, arm])
def test_batch_agrees_with_the_scalar_scene_and_optimise_finds_a_minimum(calc):
    cid = calc.CALCULATOR.id
    v = values(cid, effects="gravity, stator_limit, supply_limit, battery_sag")
    ratios = np.array([20.0, 60.0, 150.0]) if calc is arm else np.array([2.0, 5.0, 20.0])
    batch = motion.batch_times(calc.setup(v, ratios, motion._Array()))
    scalar = [motion.move(calc.setup(v, float(G)), 1e-10).time for G in ratios]
    assert batch == pytest.approx(scalar, rel=1e-2)
    out = solve(cid, {"mode": "optimise", "effects": "gravity, stator_limit, supply_limit, battery_sag"})
    G = out.outputs["best_ratio"].value
    t = out.outputs["time_to_goal"].value
    for f in (0.97, 1.03):
        assert motion.move(calc.setup(v, G * f), 1e-10).time >= t * (1 - 1e-6)
    assert len(out.series["time_vs_ratio"][0]) >= 200


@pytest.mark.parametrize("cid", ["elevator", "arm"])
def test_cli_solve_json(cid, capsys):
    from gearhead.tui.cli import main

    code = main(["solve", cid, "--set", "effects=gravity, stator_limit", "--json"])
    assert code in (0, None)
    out = json.loads(capsys.readouterr().out)
    assert out["calculator"] == cid
    assert out["outputs"]["time_to_goal"]["unit"] == "s" and out["outputs"]["time_to_goal"]["value"] > 0
    assert out["outputs"]["kV"]["unit"] == ("V*s/m" if cid == "elevator" else "V*s/rad")


def test_feedforward_against_recalcs_formulas():
    """ReCalc (wpilib/patches/wpilibc/wasm/feedforward_gains.h): kA = kA_ideal/η, kV = kV_ideal/η,
    linear kG = kA·g·sin(angle above horizontal), arm kG = kA·g·L·m/I, with kA_ideal = 1/B and
    kV_ideal = −A11/B of WPILib's ideal plant. Ours scales the output torque by η (back-EMF
    torque included), so kV differs by exactly 1/η (equal at η = 1); ReCalc's Kt is WPILib's τs/Is,
    ours the seed's τs/(Is − If) (M1), so our kA and kG are ReCalc's × (Is − If)/Is."""
    R, Kv, _ = neo()
    Kt = 2.6 / 105  # WPILib's, as ReCalc
    eta, m, r, G, incline = 0.8, 15 * LB, 0.75 * INCH, 10.0, math.radians(30)
    n = G / r
    B = 2 * Kt * n / (R * m)  # ElevatorFromPhysicalConstants with 2 NEOs (R/2 combined)
    A11 = -2 * Kt * n * n / (R * Kv * m)
    kA_rc, kV_rc = 1 / B / eta, -A11 / B / eta
    kG_rc = kA_rc * G0 * math.sin(math.pi / 2 - incline)
    out = elevator.simulate(values("elevator", efficiency=eta, incline="30 deg"), 1e-6).values
    assert out["kA"] == pytest.approx(kA_rc * (105 - 1.8) / 105, rel=1e-12)
    assert out["kG"] == pytest.approx(kG_rc * (105 - 1.8) / 105, rel=1e-12)
    assert out["kV"] == pytest.approx(kV_rc * eta, rel=1e-12)
    Rk, Ktk = 12 / 366, 7.09 / 366
    ma, L, Ga = 8 * LB, 12 * INCH, 75.0
    I = 4 / 3 * ma * L * L
    kA_arm = I * Rk / (Ktk * Ga) / eta
    o = arm.simulate(values("arm", efficiency=eta), 1e-6).values
    assert o["kA"] == pytest.approx(kA_arm * (366 - 2) / 366, rel=1e-12)
    assert o["kG"] == pytest.approx(kA_arm * G0 * L * ma / I * (366 - 2) / 366, rel=1e-12)
