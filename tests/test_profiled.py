"""The profiled move (core.sim.profiled, issue 30): its parts against hand numbers and WPILib's own
classes, its exponential per-period integrator (X1)-(X3) against the scene's DP54 on a nonlinear
plant, stiction, and the mode's outputs. The whole loop against WPILib's ElevatorSim is
tests/test_profiled_wpilib.py."""

import math
import random

import pytest
from wpimath.controller import ElevatorFeedforward
from wpimath.trajectory import TrapezoidProfile

from gearhead.core.calculators import arm as arm_calc
from gearhead.core.calculators import elevator as elevator_calc
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.motors import lookup
from gearhead.core.registry import get
from gearhead.core.sim import motion, profiled, profiles
from gearhead.core.sim.motion import Mechanism


def test_trapezoid_by_hand():
    # d = 1 m, v = 2 m/s, a = 4 m/s²: t_a = 0.5 s covers 0.5 m each way, so no cruise at v = 2;
    # a·t_a² = 1 = d exactly: the trapezoid has no cruise, T = 1 s
    p = profiles.Trapezoid(1.0, 2.0, 4.0)
    assert p.total_time == pytest.approx(1.0, rel=1e-15)
    assert p.at(0.25) == pytest.approx((4 * 0.25**2 / 2, 1.0), rel=1e-15)
    # d = 3 m: cruise (3 − 1)/2 = 1 s, T = 2 s; at 1 s: 0.5 + 2·0.5 = 1.5 m at 2 m/s
    p = profiles.Trapezoid(3.0, 2.0, 4.0)
    assert p.total_time == pytest.approx(2.0, rel=1e-15)
    assert p.at(1.0) == pytest.approx((1.5, 2.0), rel=1e-15)
    assert p.at(1.75) == pytest.approx((3 - 4 * 0.25**2 / 2, 1.0), rel=1e-15)
    assert p.at(5.0) == (3.0, 0.0)
    # a triangle: d = 0.25 m never reaches 2 m/s: t_a = √(0.25/4) = 0.25 s, peak 1 m/s, T = 0.5 s
    p = profiles.Trapezoid(0.25, 2.0, 4.0)
    assert (p.accel_time, p.peak_speed, p.total_time) == pytest.approx((0.25, 1.0, 0.5), rel=1e-15)


@pytest.mark.parametrize("seed", range(5))
def test_trapezoid_is_wpilibs(seed):
    """Sampled at the 20 ms updates, the closed form (P2) is WPILib's profile advanced one period at
    a time, as ProfiledPIDController does."""
    rng = random.Random(seed)
    d, v, a = rng.uniform(0.05, 2), rng.uniform(0.2, 3), rng.uniform(0.5, 40)
    mine = profiles.Trapezoid(d, v, a)
    wp = TrapezoidProfile(TrapezoidProfile.Constraints(v, a))
    state, goal = TrapezoidProfile.State(0, 0), TrapezoidProfile.State(d, 0)
    for k in range(1, round(mine.total_time / 0.02) + 5):
        state = wp.calculate(0.02, state, goal)
        p, pv = mine.at(k * 0.02)
        assert p == pytest.approx(state.position, abs=1e-12 * d)
        assert pv == pytest.approx(state.velocity, abs=1e-12 * v)


@pytest.mark.parametrize("seed", range(5))
def test_feedforward_is_wpilibs(seed):
    rng = random.Random(seed)
    kS, kG, kV, kA = rng.uniform(0, 0.5), rng.uniform(-1, 1), rng.uniform(1, 20), rng.uniform(0.001, 0.5)
    for ka in (kA, 0.0):
        loop = profiled.Loop(kS, lambda r: kG, kV, ka, 0, 0, 0.02, 0, 0.01)
        wp = ElevatorFeedforward(kS, kG, kV, ka, 0.02)
        for _ in range(5):
            v, vn = rng.uniform(-2, 2), rng.uniform(-2, 2)
            assert loop.feedforward(0.0, v, vn) == pytest.approx(wp.calculate(v, vn), rel=1e-12, abs=1e-12)


def test_driver_signed_and_limited():
    """A negative duty is the positive one mirrored; the stator limit holds |I| at its value while it
    binds (E2) toward the command's sign."""
    motor, _ = lookup("NEO", "wpilib")
    mech = Mechanism(motor, 2, 12.0, 1.0, 400.0, 5.0, 0.0, 1.0)
    on = ("stator_limit",)
    values = {"stator_current_limit": 40.0}
    asm = elevator_calc.EFFECTS.assemble(on, values, mech, motion.SLOTS, ("p", "w", "e"), minimum=min)
    drive = profiled.driver(mech, asm.slots["duty"])
    for u, E in ((0.7, 1.0), (0.3, -2.0), (1.0, 0.0), (0.0, 9.0), (-0.2, 11.0)):
        up, Ip = drive(u, E)
        un, In = drive(-u, -E)
        assert (un, In) == pytest.approx((-up, -Ip), rel=1e-15)
        assert abs(Ip) <= 40.0 * (1 + 1e-12)
    u, I = drive(1.0, 0.0)
    assert I == pytest.approx(40.0, rel=1e-12)  # at rest, full command: the limit binds
    assert u == pytest.approx(40.0 * mech.R / 12.0, rel=1e-12)  # (E2) without sag: W/V_b
    # braking: moving fast (E = 10 V) with the command at 0, the current would be −10/R ≈ −95 A;
    # the limit raises the duty to (E − R·I_st)/V_b, the current is −40 A
    u, I = drive(0.0, 10.0)
    assert I == pytest.approx(-40.0, rel=1e-12)
    assert u == pytest.approx((10.0 - mech.R * 40.0) / 12.0, rel=1e-12)


def _prepared(raw):
    calc = get("elevator")
    v, _ = parse_inputs(calc, {"mode": "profiled", **raw})
    s = elevator_calc.setup(v)
    ff = motion.feedforward(s, s.mech.q1)
    loop, profile, _ = profiled.loop_of(s, v, ff, lambda q: ff["kG"])
    return s, loop, profile


NONLINEAR = {
    "effects": "gravity, stator_limit, supply_limit, battery_sag, friction",
    "stator_current_limit": "35 A",
    "supply_current_limit": "25 A",
    "friction_force": "3 lbf",
    "travel": "30 in",
    "sensor_delay": "10 ms",
    "velocity_fraction": 0.5,
    "acceleration_fraction": 0.4,
}


@pytest.mark.parametrize("raw", [NONLINEAR, {**NONLINEAR, "travel": "-30 in"}, {}])
def test_exponential_integrator_agrees_with_dp54(raw):
    """(X1)-(X3) against the scene's DP54 (tight) on the same loop: limits binding and releasing, sag,
    friction reversing; every output of the run agrees."""
    s, loop, profile = _prepared(raw)
    exp = profiled.profiled_move(s, loop, profile, 1e-9)
    dp = profiled.profiled_move(s, loop, profile, 1e-11, method="DP54")
    assert exp.settled == dp.settled
    for k, a in dp.values.items():
        # the peak currents are the largest at each method's own step points (P11): a peak inside a
        # step is seen a little lower, differently by each
        rel = 1e-4 if k.startswith("peak_") and k.endswith("current") or k == "min_bus_voltage" else 2e-6
        assert exp.values[k] == pytest.approx(a, rel=rel, abs=1e-9), k
    ts, q_exp = exp.series["position"]
    _, q_dp = dp.series["position"]
    assert max(abs(a - b) for a, b in zip(q_exp, q_dp)) < 1e-7


def test_current_limit_holds_in_the_loop():
    s, loop, profile = _prepared(NONLINEAR)
    run = profiled.profiled_move(s, loop, profile, 1e-6)
    assert run.values["peak_stator_current"] <= 35.0 * (1 + 1e-9)
    assert run.values["peak_supply_current"] <= 25.0 * (1 + 1e-9)
    # the bus: V_b − R_bus·max(u·I), R_bus = N·R_batt (E4)
    assert run.values["min_bus_voltage"] == pytest.approx(12 - 2 * 0.02 * run.values["peak_supply_current"])


def test_stiction_deadband():
    """A horizontal slide with friction stops where the PD's voltage no longer beats the friction:
    at rest after the profile ends the feedforward is kG = 0, so |kP·e| ≤ kS (the friction and the
    motors' loss in volts) holds it: |final error| ≤ kS/kP; the speed is exactly 0 there."""
    raw = {
        "incline": "90 deg",
        "effects": "friction",
        "friction_force": "4 lbf",
        "feedback": "entered",
        "feedback_kp": "0.5 V/in",
        "feedback_kd": "0 V*s/in",
        "settle_tolerance": "2 in",
    }
    sol = solve("elevator", {"mode": "profiled", **raw})
    out = {k: v.value for k, v in sol.outputs.items()}
    kS, kP = out["kS"], out["kP"]
    assert kS > 0.2
    assert abs(out["final_error"]) <= kS / kP * (1 + 1e-9)
    assert out["final_error"] != 0.0
    ts, vs = sol.series["speed"]
    assert vs[-1] == 0.0


def test_outputs_only_in_profiled_mode():
    move = solve("elevator", {})
    prof = solve("elevator", {"mode": "profiled"})
    assert "settle_time" not in move.outputs and "overshoot" not in move.outputs
    for name in ("settle_time", "overshoot", "final_error", "rms_tracking_error", "peak_tracking_error"):
        assert math.isfinite(prof.outputs[name].value)
    assert "time_to_goal" not in prof.outputs
    assert prof.outputs["settle_time"].value > 0.5 * prof.outputs["profile_time"].value


def test_entered_gains_are_used():
    prof = solve(
        "elevator",
        {"mode": "profiled", "feedback": "entered", "feedback_kp": "3 V/in", "feedback_kd": "0.1 V*s/in"},
    )
    assert prof.outputs["kP"].value == pytest.approx(3 / 0.0254)
    assert prof.outputs["kD"].value == pytest.approx(0.1 / 0.0254)


def test_not_settling_is_said_not_hidden():
    sol = solve(
        "elevator",
        {
            "mode": "profiled",
            "feedback": "entered",
            "feedback_kp": 0,
            "feedback_kd": 0,
            "settle_tolerance": "0.001 in",
        },
    )
    assert "settle_time" not in sol.outputs
    assert any("does not settle" in w for w in sol.warnings)


def test_too_long_a_window_names_the_period():
    with pytest.raises(InputError) as exc:
        solve("elevator", {"mode": "profiled", "control_period": "0.1 ms", "travel": "400 in"})
    assert exc.value.field == "control_period"


def test_saturation_is_said():
    sol = solve("elevator", {"mode": "profiled", "velocity_fraction": 0.9, "acceleration_fraction": 0.9})
    assert any("saturated" in w for w in sol.warnings)


def test_arm_exponential_integrator_agrees_with_dp54():
    """The arm's gravity changes with the angle (the b term of (X1)); limits, sag and friction on; the
    down move, where gravity helps."""
    calc = get("arm")
    raw = {
        "mode": "profiled",
        "effects": "gravity, stator_limit, battery_sag, friction",
        "start_angle": "80 deg",
        "goal_angle": "-20 deg",
        "sensor_delay": "10 ms",
    }
    v, _ = parse_inputs(calc, raw)
    s = arm_calc.setup(v)
    ff = motion.feedforward(s, 0.0)
    loop, profile, _ = profiled.loop_of(s, v, ff, lambda q: ff["kG"] * math.cos(q), arm=True)
    exp = profiled.profiled_move(s, loop, profile, 1e-9)
    dp = profiled.profiled_move(s, loop, profile, 1e-11, method="DP54")
    assert exp.settled and dp.settled
    for k in ("settle_time", "overshoot", "final_error", "peak_tracking_error"):
        assert exp.values[k] == pytest.approx(dp.values[k], rel=2e-6, abs=1e-9), k
    # the net energy nearly cancels (the load drives the motors down): compared on the gross scale,
    # N·V_b·(peak supply current)·(window)
    gross = 2 * 12 * dp.values["peak_supply_current"] * dp.updates * loop.period
    assert exp.values["energy"] == pytest.approx(dp.values["energy"], abs=1e-7 * gross)


def test_derived_acceleration_is_a_fraction_of_what_the_stator_limit_gives():
    """(P17): the default profile a team would use. Before, the elevator's default asked 0.3 of the
    full-voltage stall acceleration (117 m/s², 12 g, peak 84 A per NEO); now acceleration_fraction
    (0.1) of the acceleration from rest with each motor at the 40 A stator limit, by hand:
    (η·N·Kt·n·(40 A − i_f) − m·g)/m, and the default move stays within 40 A."""
    sol = solve("elevator", {"mode": "profiled"})
    out = {k: x.value for k, x in sol.outputs.items()}
    v = {k: x.value for k, x in sol.inputs.items()}
    s = elevator_calc.setup(v)
    m = s.mech
    by_hand = (m.force_per_amp * 40.0 - m.loss_force - v["load_mass"] * 9.80665) / m.inertia
    assert v["acceleration_fraction"] == 0.1
    assert out["profile_max_acceleration"] == pytest.approx(0.1 * by_hand, rel=1e-12)
    assert out["profile_max_acceleration"] < 2 * 9.80665  # under 2 g (was 12 g)
    assert out["peak_stator_current"] < 40.0
    arm = solve("arm", {"mode": "profiled"})
    assert arm.outputs["peak_stator_current"].value < 40.0  # was 186 A on the default Kraken
    # a cap that cannot lift the load is said, naming the field
    heavy = {"mode": "profiled", "load_mass": "60 lb", "stator_current_limit": "5 A"}
    heavy["effects"] = "gravity, stator_limit"  # a hidden row changes nothing: the limit is the effect's
    with pytest.raises(InputError) as err:
        solve("elevator", heavy)
    assert err.value.field == "stator_current_limit" and "5 A" in err.value.message
    # with the effect off, 40 A per motor; 400 lb is more than 2 NEOs lift at 40 A on this ratio
    with pytest.raises(InputError) as err:
        solve("elevator", {"mode": "profiled", "load_mass": "400 lb"})
    assert err.value.field == "acceleration_fraction" and "40 A" in err.value.message


@pytest.mark.parametrize("method", ["EXP", "DP54", "RK4"])
def test_every_period_goes_through_the_shared_integrator(monkeypatch, method):
    """The profiled move keeps no integrator of its own: each of its methods is core.sim.integrate's."""
    s, loop, profile = _prepared({})
    seen = []
    real = profiled.integrate

    def spy(*args, **kwargs):
        seen.append(kwargs["method"])
        return real(*args, **kwargs)

    monkeypatch.setattr(profiled, "integrate", spy)
    run = profiled.profiled_move(s, loop, profile, 1e-6, method=method)
    assert len(seen) >= run.updates and set(seen) == {method}
