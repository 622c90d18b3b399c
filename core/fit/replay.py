"""The logged voltage replayed through the card's model (issue 44 item 5): the model of the card,
V = kS·sgn q̇ + kG(q) + kV·q̇ + kA·q̈ (entries (E1)), with the design's gains or the fitted ones,
from each test's first measured position and speed, the voltage held from each sample to the next:
    q̈ = (u − kS·sgn q̇ − g(q) − kV·q̇)/kA,  g = kG (elevator), kG·cos(q + offset) (arm), 0 (flywheel)
With the forcing d = u − g and the direction s constant, it is solved exactly:
    q̇(τ) = v∞ + (q̇ − v∞)·e^(Aτ),  q(τ) = q + v∞·τ + (q̇ − v∞)·(e^(Aτ) − 1)/A,
    A = −kV/kA,  v∞ = (d − kS·s)/kV                                                           (R1)
and it stops where q̇ reaches 0 (when s·v∞ < 0), at e^(Aτ*) = v∞/(v∞ − q̇)                    (R1a)
then friction holds it at rest while |d| ≤ kS, else it starts off the other way. An elevator's and
a flywheel's forcing is constant over a sample: one exact piece (two at a stop) per sample; an arm's
g is frozen over substeps of at most 1 ms (its only approximation, O(substep))
RMSE of the predicted position and velocity against the measured ones at the voltage samples   (R2)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .signals import Run
from .sysid_fit import _lerp

SUBSTEP = 1e-3  # an arm's: g(q) frozen over it


def _piece(q: float, v: float, d: float, h: float, kS: float, kV: float, A: float):
    """(R1), (R1a): position and speed after h under the constant forcing d (kV > 0: at most a
    run, a stop and a start the other way)."""
    for _ in range(3):
        if v == 0.0:
            if abs(d) <= kS:
                return q, 0.0  # held by friction for the rest of the piece
            s = math.copysign(1.0, d)
        else:
            s = math.copysign(1.0, v)
        v_inf = (d - kS * s) / kV
        tau = h
        stops = s * v_inf < 0.0
        if stops:
            tau = min(h, math.log(v_inf / (v_inf - v)) / A)  # (R1a)
        e = math.exp(A * tau)
        q += v_inf * tau + (v - v_inf) * (e - 1.0) / A
        v = 0.0 if stops and tau < h else v_inf + (v - v_inf) * e
        h -= tau
        if v != 0.0 or h <= 0.0:
            return q, v
    return q, v


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
        span = float(t[k + 1] - t[k])
        if kind != "arm":
            q, v = _piece(q, v, u[k] - (kG if kind == "elevator" else 0.0), span, kS, kV, A)
            continue
        n = max(1, math.ceil(span / SUBSTEP))
        h = span / n
        for _ in range(n):  # g at the substep's predicted midpoint (R1b): second order in h
            q, v = _piece(q, v, u[k] - kG * math.cos(q + 0.5 * h * v + off), h, kS, kV, A)
    return qs, vs


@dataclass
class Replay:
    position_rmse: float
    velocity_rmse: float
    per_test: dict[str, tuple[float, float]]
    traces: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]]  # t, q, v, q̂, v̂


def replay(kind: str, gains: dict[str, float], runs: dict[str, Run]) -> Replay:
    """(R2) over the four tests; not a number when the gains make no model that runs (kA ≤ 0, kV ≤ 0
    (a motor that speeds itself up), not finite) or the model runs away past the float range."""
    if not (all(math.isfinite(x) for x in gains.values()) and gains["kA"] > 0 and gains["kV"] > 0):
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
        with np.errstate(over="ignore"):  # a log's value near the float limit: inf, said by fit_log
            eq, ev = float(np.sum((qh - q) ** 2)), float(np.sum((vh - v) ** 2))
        per[s] = (math.sqrt(eq / len(t)), math.sqrt(ev / len(t)))
        traces[s] = (t, q, v, qh, vh)
        sq += eq
        sv += ev
        n += len(t)
    return Replay(math.sqrt(sq / n), math.sqrt(sv / n), per, traces)
