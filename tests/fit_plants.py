"""Synthetic SysId logs from known plants for tests/test_fit_*.py, written with robotpy's real
DataLogWriter under SysIdRoutineLog's naming and Java's unit metadata (wpilibj SysIdRoutineLog.java).

Plant (SI, q in m or rad): kA·q̈ = u − kS·sgn q̇ − g(q) − kV·q̇, g = kG (elevator),
kG·cos(q + offset) (arm), 0 (flywheel); integrated exactly over 0.5 ms substeps with the forcing
frozen (v(h) = (v + c/A)·e^(A·h) − c/A, A = −kV/kA), friction holding it at rest when |u − g| ≤ kS.
The robot's loop logs every `period` (± `jitter`, uniform) the voltage it applies until the next
loop, the position and velocity measured (Gaussian noise, the velocity a moving average of
`velocity_filter` samples; with `filter_noise` the noise too, so correlated over them), and the
test state, as SysIdRoutine does."""

from __future__ import annotations

import math

import numpy as np


def simulate(
    path,
    kind: str,
    gains: dict[str, float],
    *,
    period: float = 0.01,
    jitter: float = 0.0,
    noise: float = 0.0,
    velocity_filter: int = 1,
    filter_noise: bool = False,
    seed: int = 0,
    mech: str = "mech",
    motor: str = "motor",
    ramp: float = 1.0,
    step: float = 7.0,
    quasistatic_time: float = 6.0,
    dynamic_time: float = 2.0,
    rest: float = 1.0,
    csv_path=None,
    battery: tuple[float, float, int, float, float] | None = None,
    card_model: bool = False,
):
    """`card_model`: the plant is the replay's own model (core.fit.replay.simulate, steps on the
    log's microsecond stamps) instead of the 0.5 ms substeps below.
    `battery` = (E, R, N, R_m, k_m): log the motor current I = (u − k_m·q̇)/R_m (Amp) and the bus
    voltage V_b of E − R·N·I·u/V_b (AdvantageKit's /SystemStats/BatteryVoltage, Volt)."""
    import wpiutil
    from wpiutil import log as wlog

    rng = np.random.default_rng(seed)
    kS, kV, kA = gains["kS"], gains["kV"], gains["kA"]
    kG, off = gains.get("kG", 0.0), gains.get("offset", 0.0)
    linear = kind in ("elevator", "sprint")
    to_log = 1.0 if linear else 1 / (2 * math.pi)  # metres, or rotations as Java's angularPosition writes

    def load(q):
        return kG if kind == "elevator" else kG * math.cos(q + off) if kind == "arm" else 0.0

    w = wpiutil.DataLogWriter(str(path))
    state = wlog.StringLogEntry(w, f"sysid-test-state-{mech}", "", 1)
    ev = wlog.DoubleLogEntry(w, f"voltage-{motor}-{mech}", "Volt", 1)
    ep = wlog.DoubleLogEntry(w, f"position-{motor}-{mech}", "Meter" if linear else "Rotation", 1)
    ew = wlog.DoubleLogEntry(
        w, f"velocity-{motor}-{mech}", "Meter per Second" if linear else "Rotation per Second", 1
    )
    if battery is not None:
        ec = wlog.DoubleLogEntry(w, f"current-{motor}-{mech}", "Amp", 1)
        eb = wlog.DoubleLogEntry(w, "/SystemStats/BatteryVoltage", "Volt", 1)
    rows = []
    q = -math.pi / 2 - off if kind == "arm" else 0.0  # an arm starts hanging down
    v = 0.0
    t = 1.0
    A = -kV / kA
    recent: list[float] = []
    tests = [
        ("quasistatic-forward", quasistatic_time, lambda s: ramp * s),
        ("quasistatic-reverse", quasistatic_time, lambda s: -ramp * s),
        ("dynamic-forward", dynamic_time, lambda s: step),
        ("dynamic-reverse", dynamic_time, lambda s: -step),
    ]
    count = 0
    for name, length, volts in tests:
        for label, span, fn in (("none", rest, lambda s: 0.0), (name, length, volts)):
            t0 = t
            if label == "none":
                v = 0.0  # between tests the mechanism is brought to rest (a brake, a hand)
            while t - t0 < span:
                u = fn(t - t0)
                dt = period + (rng.uniform(-jitter, jitter) if jitter else 0.0)
                stamp = int(round(t * 1e6))
                if filter_noise:  # the sensor's noise inside the filter: correlated over its samples
                    recent = (recent + [v + (rng.normal(0, noise) if noise else 0.0)])[-velocity_filter:]
                    mv = sum(recent) / len(recent)
                else:
                    recent = (recent + [v])[-velocity_filter:]
                    mv = sum(recent) / len(recent) + (rng.normal(0, noise) if noise else 0.0)
                mq = q + (rng.normal(0, noise * 0.1) if noise else 0.0)
                state.append(label, stamp)
                if label != "none":
                    ev.append(u, stamp)
                    ep.append(mq * to_log, stamp)
                    ew.append(mv * to_log, stamp)
                    if battery is not None:
                        E, Rb, N, Rm, km = battery
                        current = (u - km * v) / Rm
                        ec.append(current, stamp)
                        eb.append((E + math.sqrt(E * E - 4 * Rb * N * current * u)) / 2, stamp)
                    rows.append((t, label, u, mq * to_log, mv * to_log))
                count += 1
                if count % 500 == 0:
                    w.flush()
                if card_model:
                    from gearhead.core.fit.replay import simulate as model

                    dt = round((t + dt) * 1e6) / 1e6 - stamp / 1e6
                    t = stamp / 1e6
                    qs, vs = model(kind, gains, np.array([0.0, dt]), np.array([u, u]), q, v)
                    q, v = float(qs[1]), float(vs[1])
                    t += dt
                    continue
                n_sub = max(1, int(round(dt / 5e-4)))
                h = dt / n_sub
                for _ in range(n_sub):
                    drive = u - load(q)
                    if v == 0.0:
                        if abs(drive) <= kS:
                            continue
                        s = math.copysign(1.0, drive)
                    else:
                        s = math.copysign(1.0, v)
                    c = (drive - kS * s) / kA
                    e = math.exp(A * h)
                    v1 = (v + c / A) * e - c / A
                    x1 = q + (v + c / A) * (e - 1) / A - c / A * h
                    if v != 0.0 and math.copysign(1.0, v1) != s:
                        v1 = 0.0
                    q, v = x1, v1
                t += dt
    state.append("none", int(round(t * 1e6)))
    w.flush()
    w.stop()
    del w
    if csv_path is not None:
        with open(csv_path, "w") as f:
            f.write(
                f"Timestamp,sysid-test-state-{mech},voltage-{motor}-{mech},position-{motor}-{mech},velocity-{motor}-{mech}\n"
            )
            for t_, label, u, p, vv in rows:
                f.write(f"{round(t_ * 1e6) / 1e6!r},{label},{u!r},{p!r},{vv!r}\n")
            f.write(f"{round(t * 1e6) / 1e6!r},none,,,\n")
    return path
