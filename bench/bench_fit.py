"""`gearhead fit` on a robot's whole log (issue 44): figures only, never asserted. Targets: a 10-minute
log with 50 signals read and fitted ≤ 2 s; the replay of one test ≤ 50 ms.

The log is written once per run, to a temporary folder, with WPILib's own DataLogWriter (robotpy's
wpiutil, the test extra), as an AdvantageKit robot logs a practice session: 10 minutes, 50 entries:
- the main loop every 20 ms (± 1 ms): 30 signals at 50 Hz (the driver station's booleans, match time,
  joystick axes (float[]) and buttons (int64), the battery's voltage, the CAN bus, each swerve
  module's current and turn voltage, the pose (double[3] and struct:Pose2d), the module states
  (double[8]), the active command (string), the vision tag ids (int64[]), the elevator's own outputs);
- 10 signals at 100 Hz (the modules' drive velocity and turn position, the shooter, the intake),
  written by the main loop two at a time with their own timestamps;
- 6 signals at 200 Hz from an odometry thread (the gyro, each module's drive position), written by the
  main loop in batches of four, so their records come up to 20 ms behind the main loop's in the file
  (out of time order, as the format allows);
- a SysId routine (`sysid-test-state-elevator`, `voltage-`, `position-`, `velocity-lift-elevator`,
  Java's unit names) in the main loop: four tests spread over the session (quasistatic 6 s at
  1 V/s, dynamic 2 s at 7 V, from 95 s to 245 s) of an elevator the 50 Hz loop resolves
  (tests/test_fit_sysid.py's: kS 0.2 V, kV 10 V/(m/s), kA 1.2 V/(m/s²), kG 0.6 V, kA/kV = 0.12 s;
  the default card's own kA/kV, 2.8 ms, is far under the loop's step), velocity noise 0.001 m/s
  (0.1 % of its top speed), position noise 0.0001 m.

Measured:
- as a user meets it, each in a fresh process (median wall and CPU): `gearhead fit LOG --card
  elevator`, beside `python -c "import numpy"` and `gearhead solve elevator` run in turns with it
  (the machine's load cancels out of the ratios); the peak resident memory of `gearhead fit` of
  this log and of the example log, and of a process before and after it reads the log;
- in one warm process (median): reading the log (the picked signals, core.fit.signals.pick), the fit
  (SysId's preparation and both forms), the replay of one test (the longest, quasistatic-forward,
  with the favoured fit's gains), and the whole of core.fit.fit_log; the gains it fits.

- `--gigabyte`: also a 4.5-hour log of the same robot, about 1 GB (written in about a minute): one
  `gearhead fit` of it, its time and peak memory, and the reader's peak memory (bounded: a 1 GB log
  must not need 1 GB of memory).

    .venv/bin/python bench/bench_fit.py [--runs N] [--keep DIR] [--gigabyte]
"""

from __future__ import annotations

import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

RUNS = int(sys.argv[sys.argv.index("--runs") + 1]) if "--runs" in sys.argv else 5
KEEP = sys.argv[sys.argv.index("--keep") + 1] if "--keep" in sys.argv else None
GIGABYTE = "--gigabyte" in sys.argv
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
GEARHEAD = str(Path(sys.executable).with_name("gearhead"))
ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "elevator_sysid.wpilog"

LENGTH = 600.0  # s
LONG = 16300.0  # s: 4.5 hours of the same robot, about 1 GB (--gigabyte)
LOOP = 0.02  # s, the main loop
SEED = 44
# (state, start time s, length s, volts at s seconds into the test)
TESTS = (
    ("quasistatic-forward", 95.0, 6.0, lambda s: 1.0 * s),
    ("quasistatic-reverse", 140.0, 6.0, lambda s: -1.0 * s),
    ("dynamic-forward", 190.0, 2.0, lambda s: 7.0),
    ("dynamic-reverse", 240.0, 2.0, lambda s: -7.0),
)
VELOCITY_NOISE = 0.001  # m/s
POSITION_NOISE = 0.0001  # m


PLANT = {"kS": 0.2, "kV": 10.0, "kA": 1.2, "kG": 0.6}  # tests/test_fit_sysid.py's elevator


def plant_substeps(q: float, v: float, u: float, h: float, n: int) -> tuple[float, float]:
    """PLANT from position q, velocity v over n substeps of h s with u volts held, integrated
    exactly (tests/fit_plants.py's plant: static friction holds it at rest)."""
    kS, kV, kA, kG = PLANT["kS"], PLANT["kV"], PLANT["kA"], PLANT["kG"]
    A = -kV / kA
    e = math.exp(A * h)
    for _ in range(n):
        drive = u - kG
        if v == 0.0:
            if abs(drive) <= kS:
                continue
            s = math.copysign(1.0, drive)
        else:
            s = math.copysign(1.0, v)
        c = (drive - kS * s) / kA
        v1 = (v + c / A) * e - c / A
        q += (v + c / A) * (e - 1) / A - c / A * h
        v = 0.0 if v != 0.0 and math.copysign(1.0, v1) != s else v1
    return q, v


def _sysid_samples(loop_times: np.ndarray, rng) -> list[tuple[int, str, float, float, float]]:
    """(main-loop index, state, volts, position, velocity) of the routine's records: PLANT
    integrated exactly over 0.5 ms substeps with the voltage held for each loop
    (tests/fit_plants.py's plant), measured with noise."""
    q = v = 0.0
    out = []
    for state, start, length, volts in TESTS:
        v = 0.0  # at rest before each test
        first = int(np.searchsorted(loop_times, start))
        k = first
        while loop_times[k] - loop_times[first] < length:
            u = volts(loop_times[k] - loop_times[first])
            out.append(
                (
                    k,
                    state,
                    u,
                    q + rng.normal(0, POSITION_NOISE),
                    v + rng.normal(0, VELOCITY_NOISE),
                )
            )
            dt = loop_times[k + 1] - loop_times[k]
            n = max(1, round(dt / 5e-4))
            q, v = plant_substeps(q, v, u, dt / n, n)
            k += 1
        out.append((k, "none", math.nan, math.nan, math.nan))
    return out


BLOCK = 3000  # main loops generated at a time (60 s): a log of hours is written in bounded memory


def write_log(path: Path, length: float = LENGTH) -> dict:
    """The session's log (module docstring), `length` seconds long; returns its size, record count
    and entry count."""
    import struct

    import wpiutil
    from wpiutil import log as wl

    rng = np.random.default_rng(SEED)
    w = wpiutil.DataLogWriter(str(path), "AdvantageKit")
    n_loops = int(length / LOOP)
    loop_times = 1.0 + np.arange(n_loops + 2) * LOOP + rng.uniform(-0.001, 0.001, n_loops + 2)
    last: dict[str, float] = {}

    def walk(name, n, step, start=0.0):  # a smooth random signal, continued from block to block
        x = last.get(name, start) + np.cumsum(rng.normal(0, step, n))
        last[name] = float(x[-1])
        return x

    def uniform(lo, hi):
        return lambda t, name: rng.uniform(lo, hi, len(t)).tolist()

    def steady(x):
        return lambda t, name: [x] * len(t)

    def walking(step, start=0.0, f=lambda x: x):
        return lambda t, name: f(walk(name, len(t), step, start)).tolist()

    def pose(t, name):
        return np.column_stack([walk(f"{name}{k}", len(t), 0.01, 3.0 + k) for k in range(3)])

    def states(t, name):
        return np.column_stack([walk(f"{name}{k}", len(t), 0.05) for k in range(8)])

    d, b, i = wl.DoubleLogEntry, wl.BooleanLogEntry, wl.IntegerLogEntry
    da, ia, fa = wl.DoubleArrayLogEntry, wl.IntegerArrayLogEntry, wl.FloatArrayLogEntry
    commands = ["", "DriveWithJoysticks", "AutoAlign", "ElevatorToGoal", "SysIdRoutine"]
    # (entry, values for the times t): 30 at the main loop's 50 Hz
    main = [
        (b, "/DriverStation/Enabled", lambda t, n: ((t > 20) & (t < length - 20)).tolist()),
        (b, "/DriverStation/Autonomous", lambda t, n: ((t > 20) & (t < 35)).tolist()),
        (b, "/DriverStation/FMSAttached", steady(False)),
        (b, "/DriverStation/DSAttached", steady(True)),
        (d, "/DriverStation/MatchTime", lambda t, n: np.maximum(0.0, 150.0 - t).tolist()),
        (fa, "/DriverStation/Joystick0/AxisValues", lambda t, n: rng.uniform(-1, 1, (len(t), 6)).tolist()),
        (i, "/DriverStation/Joystick0/ButtonValues", lambda t, n: rng.integers(0, 1 << 12, len(t)).tolist()),
        (
            d,
            "/SystemStats/BatteryVoltage",
            lambda t, n: (12.5 - 0.4 * ((t > 20) & (t < length - 20)) + rng.normal(0, 0.03, len(t))).tolist(),
        ),
        (b, "/SystemStats/BrownedOut", steady(False)),
        (d, "/SystemStats/CANBus/Utilization", uniform(0.4, 0.7)),
        (d, "/RealOutputs/LoggedRobot/UserCodeMS", uniform(2, 6)),
        (d, "/RealOutputs/LoggedRobot/FullCycleMS", uniform(5, 9)),
        (da, "/RealOutputs/Odometry/Robot", lambda t, n: pose(t, n).tolist()),
        (
            lambda w, n, m, ts: wl.RawLogEntry(w, n, m, "struct:Pose2d", ts),
            "/RealOutputs/Odometry/RobotStruct",
            lambda t, n: [struct.pack("<3d", *p) for p in pose(t, n).tolist()],
        ),
        (da, "/RealOutputs/SwerveStates/Measured", lambda t, n: states(t, n).tolist()),
        (da, "/RealOutputs/SwerveStates/Setpoints", lambda t, n: states(t, n).tolist()),
        (wl.StringLogEntry, "/RealOutputs/ActiveCommand", lambda t, n: [commands[int(x / 7) % 5] for x in t]),
        (ia, "/RealOutputs/Vision/TagIds", lambda t, n: [[int(x) % 16 + 1, 7] for x in t]),
        *[(d, f"/Drive/Module{m}/DriveCurrentAmps", walking(0.5, 10)) for m in range(4)],
        *[(d, f"/Drive/Module{m}/TurnAppliedVolts", walking(0.1)) for m in range(4)],
        (d, "/Elevator/GoalMeters", walking(0.01, f=lambda x: np.round(x, 1))),
        (d, "/Elevator/CurrentAmps", walking(0.2, 5)),
        (b, "/Elevator/AtGoal", lambda t, n: (rng.random(len(t)) < 0.8).tolist()),
        (b, "/Vision/Camera0/Connected", steady(True)),
    ]
    # 10 at 100 Hz: two samples a loop, each with its own time
    fast = [
        *[(d, f"/Drive/Module{m}/DriveVelocityRadPerSec", walking(0.2)) for m in range(4)],
        *[(d, f"/Drive/Module{m}/TurnPositionRad", walking(0.02)) for m in range(4)],
        (d, "/Shooter/VelocityRPM", walking(5.0, 3000)),
        (d, "/Intake/CurrentAmps", walking(0.3, f=np.abs)),
    ]
    # 6 at 200 Hz from the odometry thread: four samples a loop, logged at the loop's end
    odometry = [
        (d, "/Drive/Gyro/YawRad", walking(0.001)),
        (d, "/Drive/Gyro/YawVelocityRadPerSec", walking(0.01)),
        *[(d, f"/Drive/Module{m}/OdometryDrivePositionRad", walking(0.01)) for m in range(4)],
    ]
    groups = [[(kind(w, name, "", 1), name, fn) for kind, name, fn in g] for g in (main, fast, odometry)]
    mech = "elevator"
    state = wl.StringLogEntry(w, f"sysid-test-state-{mech}", "", 1)
    volts = d(w, f"voltage-lift-{mech}", "Volt", 1)
    pos = d(w, f"position-lift-{mech}", "Meter", 1)
    vel = d(w, f"velocity-lift-{mech}", "Meter per Second", 1)
    sysid = {k: (s, u, q, v) for k, s, u, q, v in _sysid_samples(loop_times, rng)}
    count = 0
    for k0 in range(0, n_loops, BLOCK):
        t = loop_times[k0 : min(k0 + BLOCK, n_loops)]
        times = (
            t,
            np.column_stack((t, t + 0.01)).ravel(),
            (t[:, None] - 0.02 + 0.005 * np.arange(1, 5)).ravel(),
        )
        stamps = [np.round(x * 1e6).astype(np.int64).tolist() for x in times]
        values = [[(e, fn(x, name)) for e, name, fn in g] for g, x in zip(groups, times)]
        for j in range(len(t)):
            ts = stamps[0][j]
            for m, (e, v) in enumerate(values[0]):
                e.append(v[j], ts + 3 * m)  # each a few µs after the last, as the loop logs them
            for per, (group, st) in enumerate(zip(values[1:], stamps[1:]), start=1):
                for e, v in group:
                    for r in range(2 * per * j, 2 * per * (j + 1)):
                        e.append(v[r], st[r])
            count += len(main) + 2 * len(fast) + 4 * len(odometry)
            k = k0 + j
            if k in sysid:
                s_, u, q, v_ = sysid[k]
                state.append(s_, ts + 200)
                count += 1
                if s_ != "none":
                    volts.append(u, ts + 201)
                    pos.append(q, ts + 202)
                    vel.append(v_, ts + 203)
                    count += 3
            if k % 50 == 0:
                w.flush()  # DataLogWriter blocks once its buffers fill until they are written
    w.flush()
    w.stop()
    del w
    entries = len(main) + len(fast) + len(odometry) + 4
    return {"bytes": path.stat().st_size, "records": count, "entries": entries}


def timed(argv: list[str]) -> tuple[float, float]:
    """(wall, CPU) seconds of one fresh process; a failure is shown, not timed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(argv, capture_output=True, env=ENV, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"{' '.join(argv)} exited {done.returncode}:\n{done.stdout}{done.stderr}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def median_ms(fn, runs: int) -> tuple[float, float]:
    """(CPU, wall) milliseconds of one call, the median of `runs` after a warm-up call."""
    fn()
    cpu, wall = [], []
    for _ in range(runs):
        c0, t0 = time.process_time(), time.perf_counter()
        fn()
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - t0)
    return statistics.median(cpu) * 1e3, statistics.median(wall) * 1e3


PEAK = """
import resource, subprocess, sys
subprocess.run(sys.argv[1:], capture_output=True, check=True)
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
"""


def peak_mb(argv: list[str]) -> float:
    """The peak resident memory (MB) of one fresh process, the only child of a small parent of its
    own (Linux carries a parent's peak into a child it forks: this one's is small)."""
    out = subprocess.run([sys.executable, "-c", PEAK, *argv], capture_output=True, text=True, check=True)
    return int(out.stdout) / 1024  # ru_maxrss: KiB on Linux


READ = "import sys; from gearhead.core.fit import signals; signals.pick(sys.argv[1], 'elevator')"


def read_peak(log: Path) -> tuple[float, float]:
    """The peak resident memory (MB) of a fresh process that imports the reader, and of one that
    also reads the log."""
    imported = peak_mb([sys.executable, "-c", "from gearhead.core.fit import signals"])
    return imported, peak_mb([sys.executable, "-c", READ, str(log)])


def in_process(log: Path, runs: int) -> dict:
    from gearhead.core import fit
    from gearhead.core.calculators.elevator import spool_factor
    from gearhead.core.fit import entries, iv, replay, signals, sysid_fit

    card = entries.load_card("elevator")
    spool = spool_factor(card.values)
    picked = signals.pick(log, "elevator", spool=spool)

    def fits():
        p, i = sysid_fit.prepare(picked)
        return (
            sysid_fit.fit_continuous(p, "elevator", i["dt"], str(log)),
            iv.fit_discrete(p, "elevator", i["dt"], str(log)),
        )

    report = fit.fit_log(log, "elevator", card)
    gains = report.fits[report.favoured].gains
    test = {"quasistatic-forward": picked.runs["quasistatic-forward"]}
    return {
        "read": median_ms(lambda: signals.pick(log, "elevator", spool=spool), runs),
        "fit": median_ms(fits, runs),
        "replay": median_ms(lambda: replay.replay("elevator", gains, test), runs),
        "replay_samples": len(test["quasistatic-forward"].t_voltage),
        "fit_log": median_ms(lambda: fit.fit_log(log, "elevator", card), runs),
        "favoured": report.favoured,
        "gains": gains,
    }


def main() -> None:
    folder = Path(KEEP) if KEEP else Path(tempfile.mkdtemp(prefix="bench_fit_"))
    folder.mkdir(parents=True, exist_ok=True)
    log = folder / "session.wpilog"
    t0 = time.perf_counter()
    made = write_log(log)
    print(
        f"log: {made['entries']} entries, {made['records']} records, {made['bytes'] / 1e6:.1f} MB, "
        f"{LENGTH / 60:.0f} minutes (written in {time.perf_counter() - t0:.1f} s by DataLogWriter)"
    )
    numpy, solve, fitted = [], [], []
    for _ in range(RUNS):  # in turns: a burst of load on the machine touches all three alike
        numpy.append(timed([sys.executable, "-c", "import numpy"]))
        solve.append(timed([GEARHEAD, "solve", "elevator"]))
        fitted.append(timed([GEARHEAD, "fit", str(log), "--card", "elevator"]))

    def med(xs, k):
        return statistics.median(x[k] for x in xs)

    print(f"fresh processes, median of {RUNS} (target: read and fitted ≤ 2 s):")
    for label, xs in (
        ('python -c "import numpy"', numpy),
        ("gearhead solve elevator", solve),
        ("gearhead fit LOG --card elevator", fitted),
    ):
        print(
            f"  {label:<34} {med(xs, 0):6.2f} s wall ({med(xs, 0) / med(numpy, 0):4.1f}x numpy, "
            f"{med(xs, 0) / med(solve, 0):4.2f}x solve), {med(xs, 1):6.2f} s CPU "
            f"({med(xs, 1) / med(numpy, 1):4.1f}x numpy)"
        )
    print(
        f"  peak memory: gearhead fit {peak_mb([GEARHEAD, 'fit', str(log), '--card', 'elevator']):.0f} MB, "
        f"of the {EXAMPLE.stat().st_size / 1e3:.0f} kB example log {peak_mb([GEARHEAD, 'fit', str(EXAMPLE), '--card', 'elevator']):.0f} MB, "
        f"gearhead solve elevator {peak_mb([GEARHEAD, 'solve', 'elevator']):.0f} MB"
    )
    before, after = read_peak(log)
    print(
        f"  peak memory: the reader imported {before:.0f} MB, and the log read (signals.pick) {after:.0f} MB"
    )
    inner = in_process(log, RUNS)
    print(f"one warm process, median of {RUNS}: CPU (wall)")
    n = inner["replay_samples"]
    for label, key in (
        ("read: the log scanned, 5 signals kept (signals.pick)", "read"),
        ("fit: SysId's preparation, continuous and discrete", "fit"),
        (f"replay of one test ({n} samples; target ≤ 50 ms)", "replay"),
        ("core.fit.fit_log: all, 3 replays, the card's moves", "fit_log"),
    ):
        cpu, wall = inner[key]
        print(f"  {label:<54} {cpu:7.1f} ms ({wall:7.1f})")
    gains = ", ".join(f"{k} {x:.4g} ({PLANT[k]:g})" for k, x in inner["gains"].items())
    print(f"  fitted, {inner['favoured']} (favoured), the plant's in brackets: {gains}")
    if GIGABYTE:
        big = folder / "long.wpilog"
        t0 = time.perf_counter()
        made = write_log(big, LONG)
        print(
            f"--gigabyte: {LONG / 3600:.1f} hours, {made['records']} records, {made['bytes'] / 1e9:.2f} GB "
            f"(written in {time.perf_counter() - t0:.0f} s); one fresh process each:"
        )
        wall, cpu = timed([GEARHEAD, "fit", str(big), "--card", "elevator"])
        print(f"  gearhead fit LOG --card elevator  {wall:6.1f} s wall, {cpu:6.1f} s CPU")
        before, after = read_peak(big)
        print(
            f"  peak memory: gearhead fit {peak_mb([GEARHEAD, 'fit', str(big), '--card', 'elevator']):.0f} MB; "
            f"the reader imported {before:.0f} MB, and the log read {after:.0f} MB"
        )
        big.unlink()
    if not KEEP:
        log.unlink()
        folder.rmdir()


if __name__ == "__main__":
    main()
