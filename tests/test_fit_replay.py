"""The replay's model (core/fit/replay.py (R1)-(R1b)) against an independent solver, and a log made
by that model replayed through the whole path (written, read, prepared, fitted, replayed) with the
gains it was made from (issue 44's test: RMSE at the solver's tolerance)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearhead.core import fit
from gearhead.core.fit import entries
from gearhead.core.fit.replay import replay, simulate
from tests.fit_plants import simulate as write_log


def solve_ivp_model(kind, g, t, u, q0, v0):
    """q̈ = (u − kS·sgn q̇ − g(q) − kV·q̇)/kA by scipy's DOP853 at rtol 1e-12, a terminal event where
    q̇ reaches 0, then held while |u − g(q)| ≤ kS, else started off the other way."""
    from scipy.integrate import solve_ivp

    kS, kV, kA = g["kS"], g["kV"], g["kA"]
    kG, off = g.get("kG", 0.0), g.get("offset", 0.0)

    def grav(q):
        return kG if kind == "elevator" else kG * math.cos(q + off) if kind == "arm" else 0.0

    q, v = q0, v0
    qs, vs = [q], [v]
    for k in range(len(t) - 1):
        t0, t1 = float(t[k]), float(t[k + 1])
        while t0 < t1:
            if v == 0.0:
                if abs(u[k] - grav(q)) <= kS:
                    break  # at rest, g(q) fixed with q
                s = math.copysign(1.0, u[k] - grav(q))
            else:
                s = math.copysign(1.0, v)

            def rhs(_, y, s=s, uk=u[k]):
                return [y[1], (uk - kS * s - grav(y[0]) - kV * y[1]) / kA]

            def stop(_, y):
                return y[1]

            stop.terminal, stop.direction = True, -s
            sol = solve_ivp(rhs, (t0, t1), [q, v], method="DOP853", rtol=1e-12, atol=1e-14, events=stop)
            q, v = float(sol.y[0, -1]), float(sol.y[1, -1])
            if sol.status != 1:
                break
            t0, q, v = float(sol.t_events[0][0]), float(sol.y_events[0][0][0]), 0.0
        qs.append(q)
        vs.append(v)
    return np.array(qs), np.array(vs)


def voltages(kind: str, g: dict, seed: int = 1):
    """A SysId-like drive on jittered 15-25 ms samples: ramps both ways, steps both ways, rests
    between (stops and friction holding), as a routine drives it."""
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.015, 0.025, 400))
    t -= t[0]
    u = (
        np.where(t < 2, t, 0.0)
        + np.where((t > 3) & (t < 5), -(t - 3), 0.0)
        + np.where((t > 6) & (t < 6.6), 7.0, 0.0)
        + np.where((t > 7.2) & (t < 7.8), -7.0, 0.0)
    )
    return t, u + (g["kG"] if kind == "elevator" else 0.0)


def gains(kind: str) -> dict:
    g = dict(entries.load_card(kind).design)
    if kind == "arm":
        g["offset"] = 0.2
    return g


@pytest.mark.parametrize("kind, bound", [("elevator", 1e-11), ("flywheel", 1e-11), ("arm", 1e-5)])
def test_the_replays_model_is_the_ode_solved(kind, bound):
    """Elevator and flywheel: exact pieces (R1), stops at (R1a), so at scipy's tolerance; an arm's
    g(q) at each 1 ms substep's midpoint (R1b): second order, 1.9e-6 of top speed measured."""
    g = gains(kind)
    t, u = voltages(kind, g)
    q_ref, v_ref = solve_ivp_model(kind, g, t, u, 0.0, 0.0)
    q, v = simulate(kind, g, t, u, 0.0, 0.0)
    top = np.max(np.abs(v_ref))
    assert np.sum(v_ref == 0.0) > 5  # the drive stops and holds: the events are exercised
    assert np.max(np.abs(v - v_ref)) < bound * top
    assert np.max(np.abs(q - q_ref)) < bound * max(1.0, np.max(np.abs(q_ref)))


def test_the_arms_substeps_are_second_order(monkeypatch):
    from gearhead.core.fit import replay as module

    g = gains("arm")
    t, u = voltages("arm", g)
    _, v_ref = solve_ivp_model("arm", g, t, u, 0.0, 0.0)
    err = []
    for h in (2e-3, 1e-3, 5e-4):
        monkeypatch.setattr(module, "SUBSTEP", h)
        err.append(np.max(np.abs(simulate("arm", g, t, u, 0.0, 0.0)[1] - v_ref)))
    assert 3.0 < err[0] / err[1] < 5.0 and 3.0 < err[1] / err[2] < 5.0, err


@pytest.mark.parametrize("kind", ["elevator", "arm", "flywheel"])
def test_a_log_of_the_model_replays_at_the_solvers_tolerance(tmp_path, kind):
    """The card's design gains fitted from a log, then a log made by the model with those fitted
    gains (jittered stamps), read and replayed with them: what comes back is what went in."""
    card = entries.load_card(kind)
    first = fit.fit_log(write_log(tmp_path / "a.wpilog", kind, gains(kind), jitter=0.001), kind, card)
    fitted = first.fits[first.favoured].gains
    again = fit.fit_log(
        write_log(tmp_path / "b.wpilog", kind, fitted, jitter=0.001, card_model=True), kind, card
    )
    r = replay(kind, fitted, again.picked.runs)
    top = max(abs(x) for tr in r.traces.values() for x in tr[2])
    assert r.velocity_rmse < 1e-9 * top, r.velocity_rmse / top
