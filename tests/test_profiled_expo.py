"""WPILib's exponential profile as the profiled move's choice (core.sim.profiles.Exponential, (P12)-(P15),
issue 30): one case against mpmath (the plant integrated by its Taylor series and the switch found by
root-finding, not the closed form), seeded random cases against robotpy's ExponentialProfileMeterVolts,
the whole loop against WPILib's parts (ElevatorSim / SingleJointedArmSim, ExponentialProfile re-planned
every period as robot code runs it, PIDController, ElevatorFeedforward) as tests/test_profiled_wpilib.py
does for the trapezoid, the exports, and the entries that must be refused.

Measured (200 random profiles, D = d/(v_m·τ) from 0.002 to 9e4): Gearhead's closed form within 1e-14 of
the move (8e-12 of it in one long move) of mpmath at 50 digits; WPILib's within 8e-12 of the scale
(the distance, v_m) while D ≤ 10, up to 2.2e-8 beyond: WPILib finds the switch time from
ln(1 − v_i/v_m), which loses the digits of v_i/v_m → 1 (a long move), where (P15) writes
1 − w = e^{−D}/(1 + w). Total times agree within 3.2e-10 (relative).
The whole loop (the oracle world of tests/test_profiled_wpilib.py, Gearhead at accuracy "fine"), measured:
5 elevator cases (τ = 0.7-2.5 ms, delays 5-20 ms): positions at the updates within 3.1e-12 of the
travel, settle times 0.02-0.08 ms before the oracle's 0.1 ms sample; 3 arm cases: within 4.5e-9 of
the swing, settle times 0.02-0.05 ms before. WPILib's profile is re-planned from the last setpoint
each period, Gearhead's (P13)-(P14) read at t_k: the same profile (the rest of a time-optimal
bang-bang move is the time-optimal move from where it is).
"""

import math
import random
from dataclasses import replace

import mpmath as mp
import pytest
from wpilib.simulation import ElevatorSim, SingleJointedArmSim
from wpimath.controller import ArmFeedforward, ElevatorFeedforward, PIDController
from wpimath.system.plant import DCMotor
from wpimath.trajectory import ExponentialProfileMeterVolts as WpiExponential

from gearhead.core import gains_code, motors
from gearhead.core.calculators import arm as arm_calc
from gearhead.core.calculators import elevator as elevator_calc
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.sim.profiles import Exponential
from tests.test_profiled_wpilib import FRC, PERIOD_MS, SUB, TRACE_TOL, oracle_world  # noqa: F401

PERIOD = PERIOD_MS / 1000


def test_one_case_against_mpmath():
    """d = 0.8 m, U = 10 V, kV = 6 V·s/m, kA = 0.25 V·s²/m (v_m = 1.6667 m/s, τ = 41.7 ms, D = 11.52):
    the plant kA·v̇ + kV·v = ±U integrated by mpmath's Taylor-series ODE solver, the switch time the
    root where the braking phase stops exactly at d."""
    d, U, kV, kA = 0.8, 10.0, 6.0, 0.25
    mp.mp.dps = 30
    try:
        accel = mp.odefun(lambda t, y: [y[1], (U - kV * y[1]) / kA], 0, [mp.mpf(0), mp.mpf(0)])

        def brake_from(t_s):
            x_s, v_s = accel(t_s)
            brake = mp.odefun(lambda t, y: [y[1], (-U - kV * y[1]) / kA], t_s, [x_s, v_s])
            t_stop = mp.findroot(lambda t: brake(t)[1], t_s + kA / kV * mp.log(2))
            return brake, t_stop

        def overshoot(t_s):
            brake, t_stop = brake_from(t_s)
            return brake(t_stop)[0] - d

        t_switch = mp.findroot(overshoot, mp.mpf("0.5"))
        brake, T = brake_from(t_switch)
        mine = Exponential(d, U, kV, kA)
        assert mine.inflection_time == pytest.approx(float(t_switch), rel=1e-13)
        assert mine.total_time == pytest.approx(float(T), rel=1e-13)
        for t in (0.01, 0.2, float(t_switch) - 1e-3, float(t_switch) + 1e-3, float(T) - 0.01):
            x, v = accel(t) if t < t_switch else brake(t)
            p, pv = mine.at(t)
            assert p == pytest.approx(float(x), abs=1e-13 * d), t
            assert pv == pytest.approx(float(v), abs=1e-13 * U / kV), t
    finally:
        mp.mp.dps = 15
    # the long-move limit of (P15): T → d/v_m + 2τ·ln 2 (here e^{−D} = 1e-5 off it)
    assert mine.total_time == pytest.approx(d / (U / kV) + 2 * kA / kV * math.log(2), rel=1e-5)
    assert mine.at(-1.0) == (0.0, 0.0) and mine.at(10.0) == (d, 0.0)


def random_profile(seed: int) -> tuple[float, float, float, float]:
    rng = random.Random(seed)
    d = rng.choice([1e-3, 0.05, 0.3, 1.0, 3.0]) * rng.uniform(0.5, 2)
    return d, rng.uniform(1, 12), rng.uniform(0.5, 20), 10 ** rng.uniform(-3, 0)


@pytest.mark.parametrize("seed", range(40))
def test_profile_is_wpilibs(seed):
    """At 300 times over the move (WPILib's calculate(t, start, goal)) and at the 20 ms updates as
    robot code advances it (calculate(0.02, setpoint, goal) each period): the same positions and
    velocities, and the same total time (timeLeftUntil)."""
    d, U, kV, kA = random_profile(seed)
    mine = Exponential(d, U, kV, kA)
    wp = WpiExponential(WpiExponential.Constraints.fromCharacteristics(U, kV, kA))
    assert wp.timeLeftUntil(WpiExponential.State(0, 0), WpiExponential.State(d, 0)) == pytest.approx(
        mine.total_time, rel=1e-9
    )
    # WPILib's switch time loses digits as v_i/v_m → 1 (module docstring): 1e-10 of the scale while
    # D ≤ 10, 1e-7 in longer moves (measured 8e-12 and 2.2e-8)
    tol = 1e-10 if d / (mine.v_max * mine.tau) <= 10 else 1e-7
    start, goal = WpiExponential.State(0, 0), WpiExponential.State(d, 0)
    for k in range(1, 300):
        t = k * mine.total_time / 280
        state = wp.calculate(t, start, goal)
        p, v = mine.at(t)
        assert p == pytest.approx(state.position, abs=tol * d), t
        assert v == pytest.approx(state.velocity, abs=tol * mine.v_max), t
    state = start
    for k in range(1, round(mine.total_time / PERIOD) + 5):
        state = wp.calculate(PERIOD, state, goal)
        p, v = mine.at(k * PERIOD)
        assert p == pytest.approx(state.position, abs=tol * d), k
        assert v == pytest.approx(state.velocity, abs=tol * mine.v_max), k


# --- the whole loop against WPILib's parts (the oracle world of tests/test_profiled_wpilib.py) ------


def expo_loop(out: dict, sim, start: float, goal: float, window: float, read, feedforward):
    """Robot code with an exponential profile (WPILib's ElevatorExponentialProfile example, the PID on
    the roboRIO as ProfiledPIDController runs it): each period next = profile.calculate(dt, setpoint,
    goal); volts = pid.calculate(measured, next.position) + feedforward(setpoint, next), WPILib's
    ElevatorFeedforward or ArmFeedforward as the exported documents call them."""
    profile = WpiExponential(
        WpiExponential.Constraints.fromCharacteristics(out["max_input"], out["kV"], out["kA"])
    )
    pid = PIDController(out["kP"], 0.0, out["kD"], PERIOD)
    setpoint, target = WpiExponential.State(start, 0.0), WpiExponential.State(goal, 0.0)
    delay_sub = round(out["sensor_delay"] / SUB)
    per = round(PERIOD / SUB)
    history = [start]
    at_updates = []
    for k in range(round(window / PERIOD)):
        at_updates.append(history[-1])
        measured = history[max(k * per - delay_sub, 0)]
        nxt = profile.calculate(PERIOD, setpoint, target)
        volts = pid.calculate(measured, nxt.position)
        volts += feedforward(setpoint, nxt)
        setpoint = nxt
        sim.setInputVoltage(max(-12.0, min(12.0, volts)))
        for _ in range(per):
            sim.update(SUB)
            history.append(read(sim))
    at_updates.append(history[-1])
    settle = 0.0
    for i in range(len(history) - 1, -1, -1):
        if abs(history[i] - goal) > out["settle_tolerance"]:
            settle = (i + 1) * SUB
            break
    return at_updates, (settle if abs(history[-1] - goal) <= out["settle_tolerance"] else None)


def gearbox(c: dict) -> DCMotor:
    base, _ = motors.lookup(c["motor"], "wpilib")
    return DCMotor(base.v_spec, base.stall_torque, base.stall_current, 0.0, base.free_speed, c["motor_count"])


def solved(calc: str, raw: dict) -> tuple[dict, list, list]:
    sol = solve(calc, {"mode": "profiled", "effects": "gravity", "efficiency": 1, "accuracy": "fine", **raw})
    out = {k: v.value for k, v in sol.outputs.items()}
    out.update({k: v.value for k, v in sol.inputs.items()})
    assert out["kS"] == 0.0  # no free current: no loss torque, as WPILib's plant
    ts, qs = sol.series["position"]
    return out, ts, qs


def elevator_cases():
    rng = random.Random(3012)
    return [
        {
            "profile_type": "exponential",
            "max_input": f"{rng.uniform(4, 10):.4g} V",
            "motor": rng.choice(FRC),
            "motor_count": rng.randint(1, 3),
            "ratio": rng.uniform(6, 25),
            "load_mass": f"{rng.uniform(5, 30):.6g} lb",
            "spool_diameter": f"{rng.uniform(1.0, 2.0):.6g} in",
            "travel": f"{rng.choice([-1, 1]) * rng.uniform(10, 50):.6g} in",
            "sensor_delay": f"{rng.choice([0, 5, 10, 20])} ms",
            "q_position": f"{rng.uniform(0.2, 1.0):.4g} in",
            "q_velocity": f"{rng.uniform(5, 30):.4g} in/s",
        }
        for _ in range(5)
    ]


def arm_cases():
    rng = random.Random(3013)
    out = []
    for _ in range(3):
        start = rng.uniform(-60, 60)
        out.append(
            {
                "profile_type": "exponential",
                "max_input": f"{rng.uniform(4, 9):.4g} V",
                "motor": rng.choice(FRC),
                "motor_count": rng.randint(1, 2),
                "ratio": rng.uniform(40, 120),
                "arm_mass": f"{rng.uniform(2, 8):.6g} lb",
                "com_distance": f"{rng.uniform(6, 20):.6g} in",
                "start_angle": f"{start:.6g} deg",
                "goal_angle": f"{start + rng.choice([-1, 1]) * rng.uniform(30, 90):.6g} deg",
                "sensor_delay": f"{rng.choice([0, 5, 10, 20])} ms",
            }
        )
    return out


def check_against(out, ts, qs, at_updates, settle, span):
    assert len(at_updates) == len(qs)
    worst = max(abs(a - b) for a, b in zip(at_updates, qs))
    assert worst <= TRACE_TOL * span, (worst, span)
    mine = out.get("settle_time")
    assert (mine is None) == (settle is None)
    if mine is not None:
        assert abs(mine - settle) <= SUB + 1e-9, (mine, settle)
        assert abs(mine - settle) <= PERIOD
    return worst / span


@pytest.mark.parametrize("index", range(5))
def test_exponential_elevator_loop_matches_wpilib(oracle_world, index):  # noqa: F811
    c = elevator_cases()[index]
    out, ts, qs = solved("elevator", c)
    sim = ElevatorSim(
        gearbox(c),
        c["ratio"],
        out["load_mass"],
        out["spool_diameter"] / 2,
        -10.0,
        10.0,
        True,
        0.0,
        [0.0, 0.0],
    )
    ff = ElevatorFeedforward(out["kS"], out["kG"], out["kV"], out["kA"], PERIOD)
    at_updates, settle = expo_loop(
        out,
        sim,
        0.0,
        out["travel"],
        ts[-1],
        lambda s: s.getPosition(),
        lambda sp, nxt: ff.calculate(sp.velocity, nxt.velocity),
    )
    check_against(out, ts, qs, at_updates, settle, abs(out["travel"]))


@pytest.mark.parametrize("index", range(3))
def test_exponential_arm_loop_matches_wpilib(oracle_world, index):  # noqa: F811
    """The arm's profile is on its angle's kV, kA; the feedforward WPILib's ArmFeedforward (P5a)."""
    c = arm_cases()[index]
    out, ts, qs = solved("arm", c)
    m, L = out["arm_mass"], out["com_distance"]
    start, goal = out["start_angle"], out["goal_angle"]
    sim = SingleJointedArmSim(
        gearbox(c), c["ratio"], 4 / 3 * m * L * L, 2 * L, -10.0, 10.0, True, start, [0.0, 0.0]
    )
    ff = ArmFeedforward(out["kS"], out["kG"], out["kV"], out["kA"], PERIOD)
    at_updates, settle = expo_loop(
        out,
        sim,
        start,
        goal,
        ts[-1],
        lambda s: s.getAngle(),
        lambda sp, nxt: ff.calculate(sp.position, sp.velocity, nxt.velocity),
    )
    check_against(out, ts, qs, at_updates, settle, abs(goal - start))


def test_the_mode_reports_the_profile():
    sol = solve("elevator", {"mode": "profiled", "profile_type": "exponential", "max_input": "8 V"})
    out = {k: v.value for k, v in sol.outputs.items()}
    profile = Exponential(abs(sol.inputs["travel"].value), 8.0, out["kV"], out["kA"])
    assert out["profile_time"] == pytest.approx(profile.total_time, rel=1e-15)
    assert out["profile_max_velocity"] == pytest.approx(8.0 / out["kV"], rel=1e-15)  # (P12)
    assert out["profile_max_acceleration"] == pytest.approx(8.0 / out["kA"], rel=1e-15)
    assert math.isfinite(out["settle_time"]) and out["settle_time"] > 0.5 * out["profile_time"]
    # the trapezoid's fields are not asked for, the max input only with the exponential
    calc_fields = {f.name: f for f in elevator_calc.FIELDS}
    choices = {"profile_type": "exponential", "profile_limits": "derived", "feedback": "lqr"}
    assert calc_fields["max_input"].active("profiled", choices)
    assert not calc_fields["velocity_fraction"].active("profiled", choices)
    assert not calc_fields["profile_limits"].active("profiled", choices)
    assert not calc_fields["max_input"].active("profiled", {**choices, "profile_type": "trapezoid"})


@pytest.mark.parametrize(
    "calc, raw, said",
    [
        ("elevator", {"max_input": "0 V"}, "greater than 0"),
        ("elevator", {"max_input": "-3 V"}, "greater than 0"),
        ("elevator", {"max_input": "12.5 V"}, "at most the battery voltage"),  # the battery is 12 V
        ("elevator", {"max_input": "nan"}, "not a finite number"),
        ("elevator", {"max_input": "inf"}, "not a finite number"),
        ("elevator", {"max_input": "1e-300 V"}, "out of range"),
        ("elevator", {"max_input": "1e-9 V", "effects": ""}, "control updates"),  # T ≈ 2e10 s
        # a huge kA (a ton of load through a huge reduction): the profile too long for the window
        ("elevator", {"effects": "", "load_mass": "2e5 lb", "ratio": 1e5}, "control updates"),
        ("arm", {"max_input": "13 V"}, "at most the battery voltage"),
        ("arm", {"effects": "", "arm_mass": "2e5 lb", "com_distance": "3.9e4 in"}, "control updates"),
    ],
)
def test_bad_entries_name_the_field(calc, raw, said):
    with pytest.raises(InputError) as exc:
        solve(calc, {"mode": "profiled", "profile_type": "exponential", **raw})
    assert exc.value.field == "max_input" and said in str(exc.value), exc.value


@pytest.mark.parametrize(
    "calc, raw", [("elevator", {"load_mass": "2e5 lb"}), ("arm", {"arm_mass": "2e5 lb"})]
)
def test_huge_ka_is_slow_and_finite(calc, raw):
    """A mass at the field's bound (no gravity, which the motors could not hold): a slow profile and
    every number finite."""
    sol = solve(calc, {"mode": "profiled", "profile_type": "exponential", "effects": "", **raw})
    assert sol.outputs["profile_time"].value > 5
    for name, value in sol.outputs.items():
        if isinstance(value.value, float):
            assert math.isfinite(value.value), name


# --- the exports follow the choice ------------------------------------------------------------------


def test_wpilib_python_runs_against_robotpy():
    sol = solve(
        "elevator",
        {"mode": "profiled", "profile_type": "exponential", "max_input": "9 V", "travel": "-20 in"},
    )
    out = {k: v.value for k, v in sol.outputs.items()}
    text = gains_code.wpilib_python(elevator_calc.gains_of(sol))
    assert "TrapezoidProfile" not in text
    namespace: dict = {}
    exec(text, namespace)  # noqa: S102 - our own text
    ff, pid, profile = namespace["feedforward"], namespace["controller"], namespace["profile"]
    assert (ff.getKs(), ff.getKg(), ff.getKv(), ff.getKa()) == tuple(
        map(gains_code.export_number, (out["kS"], out["kG"], out["kV"], out["kA"]))
    )
    assert (pid.getP(), pid.getD(), pid.getPeriod()) == (
        gains_code.export_number(out["kP"]),
        gains_code.export_number(out["kD"]),
        0.02,
    )
    c = namespace["constraints"]
    assert (c.maxInput, c.A, c.B) == pytest.approx((9.0, -out["kV"] / out["kA"], 1.0 / out["kA"]), rel=1e-11)
    assert c.maxVelocity() == pytest.approx(out["profile_max_velocity"], rel=1e-11)  # (GC11)
    d = -sol.inputs["travel"].value
    T = profile.timeLeftUntil(WpiExponential.State(0, 0), WpiExponential.State(d, 0))
    assert T == pytest.approx(out["profile_time"], rel=1e-9)


def test_arm_python_runs_against_robotpy():
    sol = solve("arm", {"mode": "profiled", "profile_type": "exponential"})
    out = {k: v.value for k, v in sol.outputs.items()}
    namespace: dict = {}
    exec(gains_code.wpilib_python(arm_calc.gains_of(sol)), namespace)  # noqa: S102 - our own text
    c = namespace["constraints"]
    assert (c.maxInput, c.A, c.B) == pytest.approx((10.0, -out["kV"] / out["kA"], 1.0 / out["kA"]), rel=1e-11)


def test_java_phoenix_revlib_follow_the_choice():
    sol = solve("elevator", {"mode": "profiled", "profile_type": "exponential", "max_input": "8 V"})
    g = elevator_calc.gains_of(sol)
    java = gains_code.wpilib_java(g)
    assert "ExponentialProfile.Constraints.fromCharacteristics(kMaxInput, kV, kA)" in java
    assert "TrapezoidProfile" not in java and "ProfiledPIDController" not in java
    assert java.count("{") == java.count("}") and java.count("(") == java.count(")")
    phoenix = gains_code.phoenix6_java(replace(g, motor="Kraken X60"))  # a Talon FX's (GC10)
    assert "MotionMagicExpoVoltage" in phoenix and "MotionMagicAcceleration" not in phoenix
    # (GC6): Expo_kV = kV·L·V_b/U per rps, so the supply voltage over it is the profile's U/kV
    v = gains_code.phoenix6_values(g)
    L = g.metres_per_rotation
    assert g.battery_voltage / v["MotionMagicExpo_kV"] * L == pytest.approx(8.0 / g.kV, rel=1e-14)
    assert g.battery_voltage / v["MotionMagicExpo_kA"] * L == pytest.approx(8.0 / g.kA, rel=1e-14)
    assert f"MotionMagicExpo_kV = {gains_code.export_number(v['MotionMagicExpo_kV'])!r};" in phoenix
    revlib = gains_code.revlib_java(g)  # the default elevator's NEO
    assert "no exponential profile" in revlib and "kMAXMotionTrapezoidal" in revlib
    # Java's discrete feedforward: calculate(v, next) would read next as an acceleration (the review
    # measured 0.345 V where the loop needs 8.32 V)
    assert "feedforward.calculateWithVelocities(setpoint.velocity, next.velocity)" in java
    assert "feedforward.calculate(" not in java
    # the roboRIO sends the whole feedforward as the arbitrary feedforward: the SPARK adds none
    assert ".kS(" not in revlib and ".kG(" not in revlib and "config.closedLoop.feedForward" not in revlib


def test_arm_java_and_revlib_with_the_exponential_profile():
    g = arm_calc.gains_of(solve("arm", {"mode": "profiled", "profile_type": "exponential"}))
    java = gains_code.wpilib_java(g)
    assert "calculateWithVelocities(setpoint.position, setpoint.velocity, next.velocity)" in java
    revlib = gains_code.revlib_java(replace(g, motor="NEO"))  # a SPARK MAX's (GC10)
    assert ".kCos(" not in revlib and "kMAXMotionPositionControl" not in revlib
    trapezoid = gains_code.revlib_java(
        replace(arm_calc.gains_of(solve("arm", {"mode": "profiled"})), motor="NEO")
    )
    assert ".kCos(" in trapezoid and "kMAXMotionPositionControl" in trapezoid


def test_phoenix_says_when_expo_ka_is_out_of_ctres_range():
    sol = solve("elevator", {"mode": "profiled", "profile_type": "exponential", "motor": "Kraken X60"})
    g = elevator_calc.gains_of(sol)
    assert "outside CTRE's documented range" not in gains_code.phoenix6_java(g)
    heavy = replace(g, kA=1e4)  # 1e4 V·s²/m × 0.12 m a rotation × 12/10: 1440 V per rps/s
    assert "outside CTRE's documented range" in gains_code.phoenix6_java(heavy)
