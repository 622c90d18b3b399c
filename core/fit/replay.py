"""The logged voltage replayed through the card's model (issue 44 item 5): the model of the card,
V = kS·sgn q̇ + kG(q) + kV·q̇ + kA·q̈ (entries (E1)), with the design's gains or the fitted ones,
from each test's first measured position and speed, the voltage held from each sample to the next:
    q̈ = (u − kS·sgn q̇ − g(q) − kV·q̇)/kA,  g = kG (elevator), kG·cos(q + offset) (arm), 0 (flywheel)
integrated exactly over substeps of at most 1 ms with g frozen (q̇(h) = (q̇ + c/A)·e^(A·h) − c/A,
A = −kV/kA), friction holding it at rest while |u − g| ≤ kS                                    (R1)
RMSE of the predicted position and velocity against the measured ones at the voltage samples   (R2)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .signals import Run
from .sysid_fit import _lerp

SUBSTEP = 1e-3


def simulate(kind: str, gains: dict[str, float], t: np.ndarray, u: np.ndarray, q0: float, v0: float):
    """(R1): predicted position and velocity at each time in t (u[k] held over [t[k], t[k+1]))."""
    kS, kV, kA = gains["kS"], gains["kV"], gains["kA"]
    kG, off = gains.get("kG", 0.0), gains.get("offset", 0.0)
    A = -kV / kA
    q, v = q0, v0
    qs = np.empty(len(t))
    vs = np.empty(len(t))
    for k in range(len(t)):
        qs[k], vs[k] = q, v
        if k + 1 == len(t):
            break
        span = t[k + 1] - t[k]
        n = max(1, math.ceil(span / SUBSTEP))
        h = span / n
        e = math.exp(A * h)
        for _ in range(n):
            g = kG if kind == "elevator" else kG * math.cos(q + off) if kind == "arm" else 0.0
            drive = u[k] - g
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
    return qs, vs


@dataclass
class Replay:
    position_rmse: float
    velocity_rmse: float
    per_test: dict[str, tuple[float, float]]
    traces: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]]  # t, q, v, q̂, v̂


def replay(kind: str, gains: dict[str, float], runs: dict[str, Run]) -> Replay:
    """(R2) over the four tests; not a number when the gains make no model that runs (kA ≤ 0, not
    finite) or the model runs away past the float range."""
    if not (all(math.isfinite(x) for x in gains.values()) and gains["kA"] > 0):
        return Replay(math.nan, math.nan, {}, {})
    try:
        return _replay(kind, gains, runs)
    except OverflowError:
        return Replay(math.nan, math.nan, {}, {})


def _replay(kind: str, gains: dict[str, float], runs: dict[str, Run]) -> Replay:
    per, traces = {}, {}
    sq = sv = 0.0
    n = 0
    for s, r in runs.items():
        t, u = r.t_voltage, r.voltage
        q = _lerp(t, r.t_position, r.position)
        v = _lerp(t, r.t_velocity, r.velocity)
        qh, vh = simulate(kind, gains, t, u, float(q[0]), float(v[0]))
        eq, ev = float(np.sum((qh - q) ** 2)), float(np.sum((vh - v) ** 2))
        per[s] = (math.sqrt(eq / len(t)), math.sqrt(ev / len(t)))
        traces[s] = (t, q, v, qh, vh)
        sq += eq
        sv += ev
        n += len(t)
    return Replay(math.sqrt(sq / n), math.sqrt(sv / n), per, traces)
