"""WPILib (robotpy 2026.2.2) as an oracle: its DCMotor constants, ElevatorSim, SingleJointedArmSim,
DCMotorSim and FlywheelSim, its LinearSystemId plants and its LinearQuadraticRegulator against
Gearhead's elevator, arm and flywheel on seeded random FRC cases (issue 28).

How the two are made to describe the same thing:
- gravity: WPILib's sims use g = 9.8 m/s²; Gearhead's elevator and arm take standard gravity
  9.80665, so the test sets theirs to 9.8 (monkeypatch of the module's G);
- efficiency 100 % (WPILib has none), no friction, no counterbalance, no current limit or sag;
- the arm: WPILib's gravity term is 3g/(2ℓ)·cos θ, a uniform rod of length ℓ about its end, which is
  Gearhead's default uniform bar (I = 4/3·m·L², L the pivot-to-centre-of-mass distance) at ℓ = 2L;
- the arm without gravity is a DCMotorSim (a motor turning an inertia through G);
- the motor model: every Gearhead tab uses the seed's, τ = Kt·(I − i_f) with Kt = τs/(Is − If)
  (core.sim.motion (M1)-(M3)); WPILib's DCMotor has the same R and Kv but Kt = τs/Is and no loss
  torque. Two WPILib motors stand in for it exactly:
  * for the motion (time to goal, peak current at rest), at a constant voltage V: a DCMotor with
    the same four constants and no free current. Its line τ = Kt·(V − ω/Kv)/R = τs·(V/V_nom − ω/ω_f)
    is the seed's (τ = Kt'·((V − ω/Kv')/R − If·V/V_nom) reduces to the same), and its current at
    rest V/R is the same (the sims run at 12 V; the flywheel tab too);
  * for the linear plant (kV, kA, kG, LQR): a DCMotor whose stall torque is τs·Is/(Is − If), so its
    Kt is the seed's and R, Kv are unchanged: the same ẋ = A·x + B·u (the seed's constant loss is
    the kS term, checked by hand: kS = R·i_f).

Each sim is stepped at a fixed step h from rest at full voltage; the time the goal is reached is
located between two steps by the cubic through their positions and speeds. Its error is bounded by
running the sim again at 2h: every step of these linear plants is integrated to ~(h/τ)⁶ (RKDP, or
the exact matrix exponential in DCMotorSim and FlywheelSim; h/τ ≤ 1/50 by the choice of cases, see
_cases) and the cubic's error is O(h⁴), so the difference of the two runs bounds the error of the
run at h (for a 4th-order error the error at h is 1/15 of that difference): the tolerance of a time
is that difference plus Gearhead's own error estimate plus 1e-12 of rounding. Closed forms (peak
current at rest, kG/kV/kA) are compared to 1e-12, the LQR gains to LQR_TOL (see there).
Measured (10 cases each, with the seed model): time to goal elevator
1.7e-13, arm 1.3e-12, arm/DCMotorSim 7.0e-14, flywheel spin-up 1.0e-12; peak current 2.0e-16;
kS/kG/kV/kA ≤ 4.7e-16; kP/kD ≤ 1.3e-13.
"""

import math
import random

import numpy as np
import pytest
from wpilib.simulation import DCMotorSim, ElevatorSim, FlywheelSim, SingleJointedArmSim
from wpimath.controller import LinearQuadraticRegulator_2_1
from wpimath.system.plant import DCMotor, LinearSystemId

from gearhead.core import motors
from gearhead.core.calculators import arm as arm_calc
from gearhead.core.calculators import elevator as elevator_calc
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.sim.motion import Mechanism

G_WPILIB = 9.8  # m/s², WPILib's sims (measured: an unpowered carriage falls at 9.79999 m/s² over 1 µs)
STEP = 1e-4  # s, the sims' fixed step (0.1 ms)

# Gearhead name -> WPILib DCMotor factory: every motor both have
FACTORIES = {
    "CIM": "CIM",
    "MiniCIM": "miniCIM",
    "BAG": "bag",
    "775pro": "vex775Pro",
    "AndyMark RS775-125": "RS775_125",
    "BaneBots RS775": "banebotsRS775",
    "AndyMark 9015": "andymark9015",
    "BaneBots RS550": "banebotsRS550",
    "NEO": "NEO",
    "NEO 550": "NEO550",
    "Falcon 500": "falcon500",
    "Falcon 500 FOC": "falcon500FOC",
    "Kraken X60": "krakenX60",
    "Kraken X60 FOC": "krakenX60FOC",
    "Kraken X44": "krakenX44",
    "Kraken X44 FOC": "krakenX44FOC",
    "Minion": "minion",
    "NEO Vortex": "neoVortex",
    "Romi": "romiBuiltIn",  # 4.5 V (issue 31)
}
FRC = ["Kraken X60", "Kraken X60 FOC", "Falcon 500", "NEO", "NEO Vortex", "Kraken X44", "Minion", "CIM"]
CASES = 10  # random cases per calculator (seeded)


def wpilib_motor(name: str, count: int = 1):
    return getattr(DCMotor, FACTORIES[name])(count)


def line_motor(name: str, count: int = 1):
    """WPILib's DCMotor with the same four constants and no free current: at a constant voltage its
    torque line and its current at rest are the seed model's (see the module's docstring)."""
    m = wpilib_motor(name)
    return DCMotor(m.nominalVoltage, m.stallTorque, m.stallCurrent, 0.0, m.freeSpeed, count)


def plant_motor(name: str, count: int = 1):
    """WPILib's DCMotor with the seed's Kt = τs/(Is − If) and WPILib's R and Kv: the same linear plant."""
    m = wpilib_motor(name)
    ts = m.stallTorque * m.stallCurrent / (m.stallCurrent - m.freeCurrent)
    return DCMotor(m.nominalVoltage, ts, m.stallCurrent, m.freeCurrent, m.freeSpeed, count)


def test_every_motor_both_have_is_theirs_constant_by_constant():
    """Every WPILib motor Gearhead lists: nominal voltage, stall torque, stall and free current,
    free speed, and the derived R, Kv (M1) to 1e-12 (both are the same decimal figures, the
    free speed through one rpm → rad/s factor); Kt is the seed's τs/(Is − If) from theirs."""
    assert {m.name for m in motors.MOTORS if m.source == "wpilib"} == set(FACTORIES)
    for name in FACTORIES:
        mine, _ = motors.lookup(name, "wpilib")
        theirs = wpilib_motor(name)
        mech = Mechanism(mine, 1, 12.0, 1.0, 1.0, 1.0, 0.0, 1.0)
        pairs = {
            "nominal voltage": (mine.v_spec, theirs.nominalVoltage),
            "stall torque": (mine.stall_torque, theirs.stallTorque),
            "stall current": (mine.stall_current, theirs.stallCurrent),
            "free current": (mine.free_current, theirs.freeCurrent),
            "free speed": (mine.free_speed, theirs.freeSpeed),
            "R": (mech.R, theirs.R),
            "Kv": (mech.Kv, theirs.Kv),
            "Kt": (mech.Kt, theirs.stallTorque / (theirs.stallCurrent - theirs.freeCurrent)),
            "Kt (plant motor)": (mech.Kt, plant_motor(name).Kt),
        }
        for what, (a, b) in pairs.items():
            assert a == pytest.approx(b, rel=1e-12), f"{name}: {what} {a} here, {b} in WPILib"


def _time_to(sim, read, goal: float, h: float, t_max: float = 5.0) -> tuple[float, float]:
    """Step `sim` at h from rest until read(sim) = (position, speed) passes goal; the crossing time
    from the cubic Hermite through the two steps around it, and the largest current drawn."""
    x0, v0 = read(sim)
    peak = abs(sim.getCurrentDraw())
    t = 0.0
    while t < t_max:
        sim.update(h)
        t += h
        x1, v1 = read(sim)
        peak = max(peak, abs(sim.getCurrentDraw()))
        if x1 >= goal:
            # Hermite basis on s in [0, 1]: solve p(s) = goal by Newton from the linear guess
            s = (goal - x0) / (x1 - x0)
            for _ in range(30):
                h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
                h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
                p = h00 * x0 + h10 * h * v0 + h01 * x1 + h11 * h * v1
                dp = (6 * s**2 - 6 * s) * x0 + (3 * s**2 - 4 * s + 1) * h * v0
                dp += (-6 * s**2 + 6 * s) * x1 + (3 * s**2 - 2 * s) * h * v1
                ds = (p - goal) / dp
                s -= ds
                if abs(ds) < 1e-15:
                    break
            return t - h + s * h, peak
        x0, v0 = x1, v1
    raise AssertionError("the WPILib sim did not reach the goal")


def _powered(sim, volts: float = 12.0):
    sim.setInputVoltage(volts)
    return sim


def _oracle(make, read, goal):
    """(time at STEP, its error bound: the difference to the run at 2·STEP), peak current."""
    t1, peak = _time_to(_powered(make()), read, goal, STEP)
    t2, _ = _time_to(_powered(make()), read, goal, 2 * STEP)
    return t1, abs(t1 - t2), peak


def _lqr(plant, q_pos, q_vel, r, dt, delay):
    reg = LinearQuadraticRegulator_2_1(plant.A(), plant.B(), (q_pos, q_vel), (r,), dt)
    if delay > 0:
        reg.latencyCompensate(plant, dt, delay)
    K = np.asarray(reg.K()).reshape(1, 2)
    return float(K[0, 0]), float(K[0, 1])


def _agree(calc: str, what: str, mine: float, theirs: float, tol: float) -> None:
    rel = abs(mine - theirs) / abs(theirs)
    assert rel <= tol, f"{calc} {what}: {mine} here, {theirs} in WPILib ({rel:.2e} > {tol:.2e})"


def _cases(seed: int, draw, calc: str, tau_of):
    """CASES seeded draws that Gearhead solves (a draw it refuses, e.g. a motor too weak for the
    load, is drawn again) and that the fixed step resolves: the plant's time constant τ = −1/A₂₂ at
    least MIN_TAU_STEPS steps. Stiffer cases are not a test of Gearhead: WPILib's RKDP holds each
    step to its 1e-6 error target, not to its order, when h/τ nears 1 (4 × Kraken X60 at 20:1 on a
    2 cm drum, τ = 0.12 ms: its time to goal is 1.2e-5 off the exact one, which Gearhead's closed
    form and scipy's Radau at 1e-12 both give to 1e-16)."""
    rng = random.Random(seed)
    out = []
    while len(out) < CASES:
        case = draw(rng)
        if tau_of(case) < MIN_TAU_STEPS * STEP:
            continue
        try:
            sol = solve(calc, case["raw"])
        except InputError:
            continue
        out.append((case, {k: v.value for k, v in sol.outputs.items()}))
    return out


MIN_TAU_STEPS = 50


def _tau(plant) -> float:
    return -1 / float(np.asarray(plant.A()).reshape(-1)[-1])


def _AB(plant):
    A, B = np.asarray(plant.A()), np.asarray(plant.B())
    n = B.size
    return A.reshape(n, n), B.reshape(n, 1)


def _feedback(rng):
    return {
        "q_position": rng.uniform(0.005, 0.1),
        "q_velocity": rng.uniform(0.05, 2.0),
        "r_volts": rng.uniform(4.0, 12.0),
        "control_period": rng.choice([0.005, 0.01, 0.02]),
        "sensor_delay": rng.choice([0.0, 0.0, 0.005, 0.02]),
    }


def _draw_elevator(rng):
    name, N = rng.choice(FRC), rng.randint(1, 4)
    G, m, r = rng.uniform(4, 25), rng.uniform(3, 30), rng.uniform(0.01, 0.03)
    d = rng.uniform(0.3, 1.5)
    fb = _feedback(rng)
    raw = {"motor": name, "motor_count": N, "ratio": G, "load_mass": f"{m!r} kg"}
    raw |= {"spool_diameter": f"{2 * r!r} m", "travel": f"{d!r} m", "efficiency": 1.0, "voltage": "12 V"}
    raw |= {"effects": "gravity", "rigging": "continuous", "accuracy": "tight"}
    raw |= {k: f"{v!r} {u}" for k, v, u in zip(fb, fb.values(), ("m", "m/s", "V", "s", "s"))}
    return {"raw": raw, "name": name, "N": N, "G": G, "m": m, "r": r, "d": d, **fb}


@pytest.fixture
def wpilib_gravity(monkeypatch):
    monkeypatch.setattr(elevator_calc, "G", G_WPILIB)
    monkeypatch.setattr(arm_calc, "G", G_WPILIB)


def _elevator_plant(c, motor=plant_motor):
    return LinearSystemId.elevatorSystem(motor(c["name"], c["N"]), c["m"], c["r"], c["G"])


def test_elevator_against_elevatorsim(wpilib_gravity):
    for c, out in _cases(2801, _draw_elevator, "elevator", lambda c: _tau(_elevator_plant(c, line_motor))):
        motor = line_motor(c["name"], c["N"])

        def make():
            return ElevatorSim(motor, c["G"], c["m"], c["r"], -1.0, 10.0, True, 0.0)

        t, err, peak = _oracle(make, lambda s: (s.getPosition(), s.getVelocity()), c["d"])
        est = out["error_estimate"]
        _agree("elevator", "time to goal", out["time_to_goal"], t, err + est + 1e-12)
        _agree("elevator", "peak current", out["peak_stator_current"] * c["N"], peak, 1e-12)
        plant = _elevator_plant(c)
        A, B = _AB(plant)
        _agree("elevator", "kV", out["kV"], -A[1, 1] / B[1, 0], 1e-12)
        _agree("elevator", "kA", out["kA"], 1 / B[1, 0], 1e-12)
        _agree("elevator", "kG", out["kG"], G_WPILIB / B[1, 0], 1e-12)
        _agree("elevator", "kS", out["kS"], plant_motor(c["name"]).R * _free_current(c), 1e-12)
        kP, kD = _lqr(
            plant, c["q_position"], c["q_velocity"], c["r_volts"], c["control_period"], c["sensor_delay"]
        )
        _agree("elevator", "kP", out["kP"], kP, LQR_TOL)
        _agree("elevator", "kD", out["kD"], kD, LQR_TOL)


# kP/kD: both solve the same discrete algebraic Riccati equation for the same zero-order-hold plant
# (WPILib in Eigen, Gearhead with scipy's solve_discrete_are) and raise the same closed loop to the
# power delay/dt; they differ by the rounding of two algorithms, measured at most 1.3e-13 over these
# draws. 1e-9 leaves that rounding room on a worse-conditioned draw and is 1e5 below what a wrong
# constant moves (the Vortex's 3.6 A free current moved kP/kD by 3.7e-4).
LQR_TOL = 1e-9


def _draw_arm(rng, gravity=True):
    name, N = rng.choice(FRC), rng.randint(1, 4)
    G, m, L = rng.uniform(30, 150), rng.uniform(1, 8), rng.uniform(0.15, 0.6)
    start = rng.uniform(-60, 30)
    goal = start + rng.uniform(20, 120)
    fb = _feedback(rng)
    fb["q_position"] *= 5  # radians, not metres
    raw = {"motor": name, "motor_count": N, "ratio": G, "arm_mass": f"{m!r} kg", "com_distance": f"{L!r} m"}
    raw |= {
        "start_angle": f"{start!r} deg",
        "goal_angle": f"{goal!r} deg",
        "efficiency": 1.0,
        "voltage": "12 V",
    }
    raw |= {"effects": "gravity" if gravity else "", "inertia_model": "uniform_bar", "accuracy": "tight"}
    raw |= {k: f"{v!r} {u}" for k, v, u in zip(fb, fb.values(), ("rad", "rad/s", "V", "s", "s"))}
    J = 4 / 3 * m * L * L  # (AR3): a uniform bar of length 2L about its end
    return {"raw": raw, "name": name, "N": N, "G": G, "m": m, "L": L, "J": J, **fb} | {
        "start": math.radians(start),
        "goal": math.radians(goal),
    }


def _arm_plant(c, motor=plant_motor):
    return LinearSystemId.singleJointedArmSystem(motor(c["name"], c["N"]), c["J"], c["G"])


def _free_current(c) -> float:
    return wpilib_motor(c["name"]).freeCurrent  # i_f at 12 V, per motor


def test_arm_against_singlejointedarmsim(wpilib_gravity):
    for c, out in _cases(2802, _draw_arm, "arm", lambda c: _tau(_arm_plant(c, line_motor))):
        motor = line_motor(c["name"], c["N"])

        def make():
            return SingleJointedArmSim(motor, c["G"], c["J"], 2 * c["L"], -100.0, 100.0, True, c["start"])

        t, err, peak = _oracle(make, lambda s: (s.getAngle(), s.getVelocity()), c["goal"])
        _agree("arm", "time to goal", out["time_to_goal"], t, err + out["error_estimate"] + 1e-12)
        _agree("arm", "peak current", out["peak_stator_current"] * c["N"], peak, 1e-12)
        plant = _arm_plant(c)
        A, B = _AB(plant)
        _agree("arm", "kV", out["kV"], -A[1, 1] / B[1, 0], 1e-12)
        _agree("arm", "kA", out["kA"], 1 / B[1, 0], 1e-12)
        _agree("arm", "kG", out["kG"], c["m"] * G_WPILIB * c["L"] / c["J"] / B[1, 0], 1e-12)
        _agree("arm", "kS", out["kS"], plant_motor(c["name"]).R * _free_current(c), 1e-12)
        kP, kD = _lqr(
            plant, c["q_position"], c["q_velocity"], c["r_volts"], c["control_period"], c["sensor_delay"]
        )
        _agree("arm", "kP", out["kP"], kP, LQR_TOL)
        _agree("arm", "kD", out["kD"], kD, LQR_TOL)


def test_arm_without_gravity_against_dcmotorsim():
    """A motor turning an inertia through G: DCMotorSim (LinearSystemSim: each step the exact
    matrix exponential of the plant) against Gearhead's arm with no effect on."""
    for c, out in _cases(
        2803, lambda rng: _draw_arm(rng, gravity=False), "arm", lambda c: _tau(_arm_plant(c, line_motor))
    ):
        motor = line_motor(c["name"], c["N"])

        def make():
            return DCMotorSim(LinearSystemId.DCMotorSystem(motor, c["J"], c["G"]), motor)

        read = lambda s: (s.getAngularPosition(), s.getAngularVelocity())  # noqa: E731
        t, err, peak = _oracle(make, read, c["goal"] - c["start"])
        _agree(
            "arm (DCMotorSim)", "time to goal", out["time_to_goal"], t, err + out["error_estimate"] + 1e-12
        )
        _agree("arm (DCMotorSim)", "peak current", out["peak_stator_current"] * c["N"], peak, 1e-12)


def _draw_flywheel(rng):
    name, N = rng.choice(FRC), rng.randint(1, 4)
    G, J = rng.uniform(0.5, 2.0), rng.uniform(5e-4, 5e-3)
    raw = {"mode": "moment_of_inertia", "wheel_inertia": f"{J!r} kg*m**2", "wheel_count": 1}
    raw |= {"motor": name, "motor_count": N, "ratio": G, "voltage": "12 V", "efficiency": 1.0, "effects": ""}
    mine, _ = motors.lookup(name, "wpilib")
    free_wheel = mine.free_speed / G
    raw |= {"target_speed": f"{rng.uniform(0.3, 0.9) * free_wheel!r} rad/s", "accuracy": "tight"}
    return {"raw": raw, "name": name, "N": N, "G": G, "J": J, "motor": mine}


def _seed_line_motor(c):
    return line_motor(c["name"], c["N"])


def test_flywheel_spin_up_against_flywheelsim():
    def tau(c):
        return _tau(LinearSystemId.flywheelSystem(_seed_line_motor(c), c["J"], c["G"]))

    for c, out in _cases(2804, _draw_flywheel, "flywheel", tau):
        motor = _seed_line_motor(c)

        def make():
            return FlywheelSim(LinearSystemId.flywheelSystem(motor, c["J"], c["G"]), motor)

        read = lambda s: (s.getAngularVelocity(), s.getAngularAcceleration())  # noqa: E731
        target = c["raw"]["target_speed"]
        t, err, _ = _oracle(make, read, float(target.split()[0]))
        _agree("flywheel", "spin-up time", out["spin_up_time"], t, err + out["error_estimate"] + 1e-12)
