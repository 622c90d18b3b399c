"""The loop a card simulates is the loop its exported code runs (issue 40): each profiled card's
`wpilib-python` document (and the flywheel's) is executed as it is written, its objects driving
robotpy 2026.2.2's own plant simulation (SingleJointedArmSim, ElevatorSim, FlywheelSim) the way its
usage comment says, and the card's settle time, overshoot and peak stator current per motor are
compared with that run's.

Made to describe the same thing (as tests/test_profiled_wpilib.py): gravity 9.8 m/s², efficiency 1,
no friction, no current limit or sag, the motors with no free current (Gearhead's seed model's
loss torque has no term in WPILib's plants); the arm a uniform bar (I = 4/3·m·L², WPILib's rod of
length 2L). The sims step at 0.1 ms with the voltage held over the period; the sensor delay reads
the position delay/0.1 ms substeps back. The oracle samples every 0.1 ms (its settle time is the
first sample from which all later ones are within the tolerance; its peak current the largest
|getCurrentDraw()|/n over the samples and each update's instant), the card its integrator's
dense output: they agree to a substep in time and to the integrators' accuracy in size.

Run as a script, it prints the comparison table (card against the WPILib-run exported loop).
"""

import random

import pytest
from wpilib.simulation import ElevatorSim, FlywheelSim, SingleJointedArmSim
from wpimath.system.plant import DCMotor, LinearSystemId

from gearhead.core import motors
from gearhead.core.calculators import arm as arm_calc
from gearhead.core.calculators import elevator as elevator_calc
from gearhead.core.calculators import flywheel as flywheel_calc
from gearhead.core.model import get, solve

G_WPILIB = 9.8
SUB = 1e-4
FRC = ["Kraken X60", "Falcon 500", "NEO", "NEO Vortex", "Kraken X44", "CIM"]


def no_loss(motor):
    return motors.Motor(
        motor.name, motor.source, motor.v_spec, motor.free_speed, motor.stall_torque, motor.stall_current, 0.0
    )


def patch_world(setattr_):
    for calc in (elevator_calc, arm_calc, flywheel_calc):
        real = calc.lookup

        def lookup(name, source, real=real):
            m, note = real(name, source)
            return no_loss(m), note

        setattr_(calc, "lookup", lookup)
    setattr_(elevator_calc, "G", G_WPILIB)
    setattr_(arm_calc, "G", G_WPILIB)


@pytest.fixture
def oracle_world(monkeypatch):
    patch_world(monkeypatch.setattr)


def document(calc_id: str, sol, name: str = "wpilib-python") -> dict:
    """The exported document's text run as Python: its namespace (feedforward, controller, ...)."""
    doc = next(d for d in get(calc_id).documents if d.name == name)
    namespace: dict = {}
    exec(doc.build(sol), namespace)  # noqa: S102 - our own exported text
    return namespace


def values(sol) -> dict:
    out = {k: v.value for k, v in sol.outputs.items()}
    out.update({k: v.value for k, v in sol.inputs.items()})
    return out


def gearbox(motor: str, n: int) -> DCMotor:
    base, _ = motors.lookup(motor, "wpilib")
    return DCMotor(base.v_spec, base.stall_torque, base.stall_current, 0.0, base.free_speed, n)


def figures(history, currents, start, goal, tol):
    """Settle time (None: not settled at the end), overshoot past the goal, peak |current|."""
    s = 1.0 if goal >= start else -1.0
    settle = 0.0
    for i in range(len(history) - 1, -1, -1):
        if abs(history[i] - goal) > tol:
            settle = (i + 1) * SUB
            break
    if abs(history[-1] - goal) > tol:
        settle = None
    overshoot = max(0.0, max(s * (q - goal) for q in history))
    return {"settle_time": settle, "overshoot": overshoot, "peak_stator_current": max(currents)}


def run_mechanism(sim, ns: dict, out: dict, start: float, goal: float, arm: bool, window: float):
    """The exported document's loop, as its usage comment says, on the sim."""
    from wpimath.trajectory import TrapezoidProfile

    controller, feedforward = ns["controller"], ns["feedforward"]
    period = ns["PERIOD"]
    expo = "profile" in ns  # the exponential profile's document: the profile advanced by the code
    if expo:
        State = type(ns["profile"]).State
        setpoint, target = State(start, 0.0), State(goal, 0.0)
    else:
        controller.reset(start, 0.0)
        controller.setGoal(TrapezoidProfile.State(goal, 0.0))
    per = round(period / SUB)
    delay_sub = round(out["sensor_delay"] / SUB)
    Vb, n = out["voltage"], out["motor_count"]
    history, currents = [start], []
    read = sim.getAngle if arm else sim.getPosition
    for k in range(round(window / period)):
        measured = history[max(k * per - delay_sub, 0)]
        if expo:  # as its comment: nxt = profile.calculate(PERIOD, setpoint, goal); PID to nxt
            sp = setpoint
            nxt = ns["profile"].calculate(period, setpoint, target)
            u = controller.calculate(measured, nxt.position)
            setpoint = nxt
        else:
            sp = controller.getSetpoint()
            u = controller.calculate(measured)
            nxt = controller.getSetpoint()
        if arm:
            volts = u + feedforward.calculate(sp.position, sp.velocity, nxt.velocity)
        else:
            volts = u + feedforward.calculate(sp.velocity, nxt.velocity)
        sim.setInputVoltage(max(-Vb, min(Vb, volts)))
        currents.append(abs(sim.getCurrentDraw()) / n)
        for _ in range(per):
            sim.update(SUB)
            history.append(read())
            currents.append(abs(sim.getCurrentDraw()) / n)
    return figures(history, currents, start, goal, out["settle_tolerance"])


def arm_oracle(raw: dict) -> tuple[dict, dict]:
    sol = solve("arm", raw)
    out = values(sol)
    ns = document("arm", sol)
    L = out["com_distance"]
    start, goal = out["start_angle"], out["goal_angle"]
    sim = SingleJointedArmSim(
        gearbox(out["motor"], out["motor_count"]),
        out["ratio"],
        sol.outputs["moment_of_inertia"].value,  # the card's (4/3·m·L² for its uniform bar)
        2 * L,
        -100.0,
        100.0,
        True,
        start,
        [0.0, 0.0],
    )
    window = sol.series["position"][0][-1]
    return out, run_mechanism(sim, ns, out, start, goal, True, window)


def elevator_oracle(raw: dict) -> tuple[dict, dict]:
    sol = solve("elevator", raw)
    out = values(sol)
    ns = document("elevator", sol)
    sim = ElevatorSim(
        gearbox(out["motor"], out["motor_count"]),
        out["ratio"],
        out["load_mass"],
        out["spool_diameter"] / 2,
        -100.0,
        100.0,
        True,
        0.0,
        [0.0, 0.0],
    )
    window = sol.series["position"][0][-1]
    return out, run_mechanism(sim, ns, out, 0.0, out["travel"], False, window)


def flywheel_oracle(raw: dict, J: float) -> tuple[dict, dict]:
    """The exported flywheel loop (a step setpoint) on FlywheelSim up to the shot: spin-up time,
    overshoot past the target, peak current."""
    sol = solve("flywheel", raw)
    out = values(sol)
    ns = document("flywheel", sol)
    box = gearbox(out["motor"], out["motor_count"])
    sim = FlywheelSim(LinearSystemId.flywheelSystem(box, J, out["ratio"]), box)
    period, r = ns["PERIOD"], ns["TARGET_SPEED"]
    per = round(period / SUB)
    delay_sub = round(out["sensor_delay"] / SUB)
    Vb, n = out["voltage"], out["motor_count"]
    history, currents = [0.0], []
    for k in range(round(out["shot_time"] / period)):
        measured = history[max(k * per - delay_sub, 0)]
        volts = ns["feedforward"].calculate(r) + ns["controller"].calculate(measured, r)
        sim.setInputVoltage(max(-Vb, min(Vb, volts)))
        currents.append(abs(sim.getCurrentDraw()) / n)
        for _ in range(per):
            sim.update(SUB)
            history.append(sim.getAngularVelocity())
            currents.append(abs(sim.getCurrentDraw()) / n)
    theirs = figures(history, currents, 0.0, r, out["speed_tolerance"])
    mine = {
        "settle_time": out.get("loop_spin_up_time"),
        "overshoot": out["loop_overshoot"],
        "peak_stator_current": out["loop_peak_stator_current"],
    }
    return mine, theirs


def arm_cases():
    rng = random.Random(4040)
    out = []
    for _ in range(4):
        start = rng.uniform(-60, 60)
        goal = start + rng.choice([-1, 1]) * rng.uniform(30, 90)
        out.append(
            {
                "motor": rng.choice(FRC),
                "motor_count": rng.randint(1, 2),
                "ratio": rng.uniform(40, 120),
                "arm_mass": f"{rng.uniform(2, 8):.6g} lb",
                "com_distance": f"{rng.uniform(6, 20):.6g} in",
                "start_angle": f"{start:.6g} deg",
                "goal_angle": f"{goal:.6g} deg",
                "sensor_delay": f"{rng.choice([0, 5, 10, 20])} ms",
                "velocity_fraction": round(rng.uniform(0.3, 0.6), 3),
                "acceleration_fraction": round(rng.uniform(0.05, 0.3), 3),
            }
        )
    # kA ≥ 0.1 V·s²/rad: ArmFeedforward's other branch (its RK4 inversion); a heavy, long arm on a
    # low reduction
    out.append(
        {
            "motor": "Kraken X60",
            "motor_count": 1,
            "ratio": 25,
            "arm_mass": "12 lb",
            "com_distance": "20 in",
            "start_angle": "-30 deg",
            "goal_angle": "45 deg",
            "sensor_delay": "5 ms",
            # the limits the derived profile gives at a 150 A stator limit (0.4 and 0.2 of it): a
            # derived profile reads that limit only with the stator_limit effect on, and this test
            # world has gravity alone (40 A cannot lift this arm)
            "profile_limits": "entered",
            "max_velocity": "10.053096491487338 rad/s",
            "max_acceleration": "5.188252111653548 rad/s**2",
        }
    )
    return out


def elevator_cases():
    rng = random.Random(4041)
    return [
        {
            "motor": rng.choice(FRC),
            "motor_count": rng.randint(1, 3),
            "ratio": rng.uniform(6, 25),
            "load_mass": f"{rng.uniform(5, 30):.6g} lb",
            "spool_diameter": f"{rng.uniform(1.0, 2.0):.6g} in",
            "travel": f"{rng.choice([-1, 1]) * rng.uniform(10, 50):.6g} in",
            "sensor_delay": f"{rng.choice([0, 5, 10, 20])} ms",
            "velocity_fraction": round(rng.uniform(0.3, 0.7), 3),
            "acceleration_fraction": round(rng.uniform(0.05, 0.3), 3),
        }
        for _ in range(4)
    ]


def flywheel_cases():
    rng = random.Random(4042)
    out = []
    for _ in range(3):
        name, n, G = rng.choice(FRC[:4]), rng.randint(1, 2), rng.uniform(0.6, 1.5)
        base, _ = motors.lookup(name, "wpilib")
        J = rng.uniform(1e-3, 6e-3)
        raw = {
            "mode": "moment_of_inertia",
            "wheel_inertia": f"{J!r} kg*m**2",
            "wheel_count": 1,
            "wheel_diameter": "4 in",
            "motor": name,
            "motor_count": n,
            "ratio": G,
            "voltage": "12 V",
            "efficiency": 1,
            "effects": "",
            "control": "velocity_loop",
            "target_speed": f"{rng.uniform(0.4, 0.8) * base.free_speed / G!r} rad/s",
            "sensor_delay": f"{rng.choice([0, 5, 15])} ms",  # off whole periods (another issue)
            "q_velocity": f"{rng.uniform(2, 40):.4g} rad/s",
            "speed_tolerance": f"{rng.uniform(1, 10):.4g} rad/s",
            "shot_time": "2.0037 s",
            "accuracy": "fine",
        }
        out.append((raw, J))
    return out


PROFILED = {"mode": "profiled", "effects": "gravity", "efficiency": 1, "accuracy": "fine"}


def assert_agree(mine: dict, theirs: dict, span: float):
    assert (mine["settle_time"] is None) == (theirs["settle_time"] is None), (mine, theirs)
    if mine["settle_time"] is not None:
        # the card's settle time is continuous, the oracle's the next 0.1 ms sample
        assert -1e-9 <= theirs["settle_time"] - mine["settle_time"] <= SUB + 1e-9, (mine, theirs)
    assert mine["overshoot"] == pytest.approx(theirs["overshoot"], abs=1e-6 * span), (mine, theirs)
    assert mine["peak_stator_current"] == pytest.approx(theirs["peak_stator_current"], rel=1e-4), (
        mine,
        theirs,
    )


@pytest.mark.parametrize("index", range(5))
def test_arm_card_runs_its_exported_loop(oracle_world, index):
    """The arm's exported Python (ArmFeedforward.calculate(angle, v, v_next), WPILib 2026.2.2's
    discrete feedforward, both of its kA branches) on SingleJointedArmSim settles, overshoots and
    draws current as the card says."""
    out, theirs = arm_oracle(PROFILED | arm_cases()[index])
    assert (out["kA"] >= 0.1) == (index == 4)  # the last case takes ArmFeedforward's RK4 branch
    assert_agree(out, theirs, abs(out["goal_angle"] - out["start_angle"]))


@pytest.mark.parametrize("calc", ["arm", "elevator"])
def test_exponential_documents_run_as_the_card(oracle_world, calc):
    """The exponential profile's wpilib-python document (ExponentialProfile advanced by the code,
    PIDController to the next setpoint, the feedforward from the setpoint to the next) as well."""
    expo = {"profile_type": "exponential", "max_input": "8 V"}
    if calc == "arm":
        out, theirs = arm_oracle(PROFILED | arm_cases()[1] | expo)
        span = abs(out["goal_angle"] - out["start_angle"])
    else:
        out, theirs = elevator_oracle(PROFILED | elevator_cases()[0] | expo)
        span = abs(out["travel"])
    assert_agree(out, theirs, span)


@pytest.mark.parametrize("index", range(4))
def test_elevator_card_runs_its_exported_loop(oracle_world, index):
    out, theirs = elevator_oracle(PROFILED | elevator_cases()[index])
    assert_agree(out, theirs, abs(out["travel"]))


@pytest.mark.parametrize("index", range(3))
def test_flywheel_card_runs_its_exported_loop(oracle_world, index):
    raw, J = flywheel_cases()[index]
    mine, theirs = flywheel_oracle(raw, J)
    assert_agree(mine, theirs, 1.0)


def _row(name, mine, theirs):
    def f(x, scale=1.0, fmt="{:.4f}"):
        return "—" if x is None else fmt.format(x * scale)

    def pct(a, b):
        return "—" if a is None or b is None or b == 0 else f"{100 * (b - a) / a:+.1f} %"

    return (
        f"| {name} | {f(mine['settle_time'])} | {f(theirs['settle_time'])} | {pct(mine['settle_time'], theirs['settle_time'])} "
        f"| {f(mine['overshoot'], 1, '{:.3e}')} | {f(theirs['overshoot'], 1, '{:.3e}')} "
        f"| {f(mine['peak_stator_current'], 1, '{:.2f}')} | {f(theirs['peak_stator_current'], 1, '{:.2f}')} "
        f"| {pct(mine['peak_stator_current'], theirs['peak_stator_current'])} |"
    )


def main():
    patch_world(setattr)
    print(
        "| case | card settle s | WPILib settle s | Δ | card overshoot | WPILib overshoot | card peak A | WPILib peak A | Δ |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for i, c in enumerate(arm_cases()):
        out, theirs = arm_oracle(PROFILED | c)
        print(_row(f"arm {i} (kA {out['kA']:.3g})", out, theirs))
    for name in ("single_kraken", "two_kraken_limits_sag"):
        # the built-in presets' arms, their own effects off (the oracle's world has none)
        import tomllib

        from gearhead.core.presets import builtin_dir  # noqa: PLC0415

        raw = tomllib.loads((builtin_dir() / "arm" / f"{name}.toml").read_text())
        raw = {k: v for k, v in raw.get("inputs", raw).items() if not isinstance(v, dict)}
        out, theirs = arm_oracle(raw | PROFILED)
        print(_row(f"arm preset {name} (kA {out['kA']:.3g})", out, theirs))
    for i, c in enumerate(elevator_cases()):
        out, theirs = elevator_oracle(PROFILED | c)
        print(_row(f"elevator {i}", out, theirs))
    for i, (raw, J) in enumerate(flywheel_cases()):
        mine, theirs = flywheel_oracle(raw, J)
        print(_row(f"flywheel {i}", mine, theirs))


if __name__ == "__main__":
    main()
