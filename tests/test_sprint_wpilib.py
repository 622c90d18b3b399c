"""WPILib's DifferentialDrivetrainSim (robotpy 2026.2.2) as a peer of the drivetrain sprint (issue 29):
seeded random tank drives in a straight line, both sides at 12 V, no current limit, no sag, efficiency
100 % (WPILib has none) and a traction limit that never binds (μ = 3 and the stall force below it).

The motor: WPILib's DCMotor with the same four constants and no free current (tests/test_wpilib_oracle
line_motor): at a constant voltage its torque line and its current at rest are the seed model's that
the sprint uses. The sim's state is stepped at a fixed 0.1 ms (its RKDP); the time the left side
reaches the distance is located between two steps by a cubic (test_wpilib_oracle._time_to), its error
bounded by the run at 2 steps (see there). Measured (10 cases): worst relative difference 1.4e-13 in
the time, 1.3e-16 in the current at rest; the same cases with WPILib's own DCMotor (Kt = τs/Is, no loss
torque) differ by up to 2.6 % (a CIM: I_free/I_stall = 2 %), the two motor models' difference.
"""

import random

from wpilib.simulation import DifferentialDrivetrainSim

from gearhead.core.errors import InputError
from gearhead.core.model import solve
from tests.test_wpilib_oracle import STEP, _agree, _time_to, line_motor

MOTORS = ["CIM", "MiniCIM", "NEO", "Falcon 500", "Kraken X60", "NEO Vortex"]
CASES = 10


def _draw(rng):
    name, per_side = rng.choice(MOTORS), rng.choice([1, 2, 3])
    G, m, r = rng.uniform(6, 15), rng.uniform(40, 70), rng.uniform(0.04, 0.08)
    d = rng.uniform(1.0, 10.0)
    raw = {"motor": name, "motor_count": 2 * per_side, "ratio": G, "robot_mass": f"{m!r} kg"}
    raw |= {"wheel_diameter": f"{2 * r!r} m", "distance": f"{d!r} m", "wheel_cof": 3, "efficiency": 1}
    raw |= {"effects": "", "voltage": "12 V", "accuracy": "tight"}
    return {"raw": raw, "name": name, "per_side": per_side, "G": G, "m": m, "r": r, "d": d}


def test_tank_sprint_against_differentialdrivetrainsim():
    rng = random.Random(2901)
    done = 0
    while done < CASES:
        c = _draw(rng)
        try:
            out = {k: v.value for k, v in solve("sprint", c["raw"]).outputs.items()}
        except InputError:
            continue
        if out["traction_time"] > 0:  # the wheels would slip: not what WPILib's sim models
            continue
        motor = line_motor(c["name"], c["per_side"])

        def make():
            sim = DifferentialDrivetrainSim(motor, c["G"], 5.0, c["m"], c["r"], 0.6)
            sim.setInputs(12.0, 12.0)
            return sim

        read = lambda s: (s.getLeftPosition(), s.getLeftVelocity())  # noqa: E731
        t1, peak = _time_to(make(), read, c["d"], STEP, t_max=30.0)
        t2, _ = _time_to(make(), read, c["d"], 2 * STEP, t_max=30.0)
        _agree("sprint (tank)", "time to distance", out["time_to_distance"], t1, abs(t1 - t2) + 1e-12)
        # the sim's current: both sides, all motors; ours per motor, at rest
        _agree("sprint (tank)", "peak current", out["peak_stator_current"] * 2 * c["per_side"], peak, 1e-12)
        done += 1
