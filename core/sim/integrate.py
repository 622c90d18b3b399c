"""The ODE integrator of every scene (an interface in the manner of scipy.integrate.solve_ivp).

Dormand–Prince 5(4) with FSAL, 4th-order dense output and event location, on plain Python floats.
Written by hand because solve_ivp spends ~60 µs of numpy overhead per step on systems of 1-6
states; this costs a few µs, which is what keeps a 150 s match under 5 ms (bench/bench_integrators.py
measures the lead on the scenes' own right-hand sides). There is no second backend: the tests check
the scenes against scipy's solve_ivp (DOP853, tight) called directly on equations written out in the
test, an independent reference; a stiff scene calls solve_ivp itself (core.sim.motion's LSODA).

Every run returns its right-hand-side evaluation count, so the cost of accuracy is visible.
Events are located on the dense output with scipy.optimize.brentq to ~1e-13 of the step, not to
a step boundary.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Any

Vector = list[float]
RHS = Callable[[float, Vector], Vector]

# Dormand & Prince (1980) coefficients; dense output from Hairer, Nørsett & Wanner, DOPRI5.
_C = (0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0)
_A = (
    (),
    (1 / 5,),
    (3 / 40, 9 / 40),
    (44 / 45, -56 / 15, 32 / 9),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
    (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84),
)
_E = (71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40)
_D = (
    -12715105075 / 11282082432,
    0.0,
    87487479700 / 32700410799,
    -10690763975 / 1880347072,
    701980252875 / 199316789632,
    -1453857185 / 822651844,
    69997945 / 29380423,
)


# ---- the per-solve guard: a budget of work and wall time, and a way to cancel ------------------


class Stopped(Exception):
    """Integration stopped from outside the equations (not a RuntimeError, so the fallbacks that
    catch a solver failure, e.g. "step size underflow", do not swallow it)."""


class BudgetExceeded(Stopped):
    def __init__(self, budget: Budget, what: str):
        self.budget = budget
        super().__init__(what)


class Cancelled(Stopped):
    pass


def cpu_clock() -> float:
    """CPU seconds of the calling thread: what a solve has itself spent, whatever else runs. Wall
    time is not the solve's own: 200 solves at once on two cores refused correct entries that
    each need 0.64 s ("needs more than 30 s")."""
    return time.thread_time()


@dataclass
class Budget:
    """Work allowed to everything integrated inside `with budget(...)`: right-hand-side evaluations
    (deterministic: the same inputs fail the same way on any machine), CPU time of the solving
    thread (a backstop for work the count does not see; a busy machine does not count against
    it), and a `cancel` callable polled between steps (the app: "the entries changed, drop this
    solve")."""

    max_nfev: int | None = None
    max_seconds: float | None = None  # CPU seconds of the thread that made the budget
    cancel: Callable[[], bool] | None = None
    nfev: int = 0
    started: float = field(default_factory=lambda: cpu_clock())

    def charge(self, n: int) -> None:
        self.nfev += n
        if self.max_nfev is not None and self.nfev > self.max_nfev:
            raise BudgetExceeded(self, f"more than {self.max_nfev} right-hand-side evaluations")
        if self.cancel is not None and self.cancel():
            raise Cancelled("cancelled")
        if self.max_seconds is not None and cpu_clock() - self.started > self.max_seconds:
            raise BudgetExceeded(self, f"more than {self.max_seconds:g} s of computing")


_budgets: ContextVar[tuple[Budget, ...]] = ContextVar("gearhead_budgets", default=())


@contextmanager
def budget(
    max_nfev: int | None = None, max_seconds: float | None = None, cancel: Callable[[], bool] | None = None
) -> Iterator[Budget]:
    """Everything integrated inside is charged to this budget (and to any enclosing one).
    Context variables are per thread: a solve in the app's worker thread has its own."""
    b = Budget(max_nfev, max_seconds, cancel)
    token = _budgets.set(_budgets.get() + (b,))
    try:
        yield b
    finally:
        _budgets.reset(token)


def charge(n: int) -> None:
    """Charge n evaluations to every active budget (for work done outside `integrate`, e.g. a
    numpy batch); raises BudgetExceeded or Cancelled."""
    for b in _budgets.get():
        b.charge(n)


@dataclass
class Event:
    """g(t, y) = 0 crossing. direction +1: only rising, -1: only falling, 0: both."""

    name: str
    g: Callable[[float, Vector], float]
    direction: int = 0
    terminal: bool = True


@dataclass
class Run:
    t: list[float]
    y: list[Vector]
    nfev: int
    steps: int
    rejected: int
    event: str | None = None  # name of the terminal event that ended the run
    dense: list = field(default_factory=list)  # (t0, h, coefficients) per step, for DP54
    crossings: list = field(default_factory=list)  # (name, t, y) of non-terminal events, located

    def at(self, t: float) -> Vector:
        """Interpolated state (DP54 dense output, 4th order)."""
        for t0, h, rc in self.dense:
            if (h > 0 and t0 <= t <= t0 + h) or (h < 0 and t0 + h <= t <= t0):
                return _interp(rc, (t - t0) / h)
        raise ValueError(f"t = {t} outside the integrated span")


def _interp(rc, theta: float) -> Vector:
    r1, r2, r3, r4, r5 = rc
    one = 1 - theta
    return [a + theta * (b + one * (c + theta * (d + one * e))) for a, b, c, d, e in zip(r1, r2, r3, r4, r5)]


def integrate(
    rhs: RHS,
    t0: float,
    t1: float,
    y0: Sequence[float],
    rtol: float = 1e-6,
    atol: float = 1e-9,
    events: Sequence[Event] = (),
    max_steps: int = 100_000,
    first_step: float | None = None,
    dense: bool = False,
    restart: Sequence[str] = (),
) -> Run:
    """`restart`: names of events that were located at t0 and handled by the caller (a restart at an
    event). A crossing of one of them found again at t0 itself (within 1e-10 of the first step) is
    that same event, not a new one: it is not reported, so a caller that restarts cannot loop."""
    return _dp54(
        rhs,
        t0,
        t1,
        list(map(float, y0)),
        rtol,
        atol,
        events,
        max_steps,
        first_step,
        dense,
        frozenset(restart),
    )


# One stiff run's evaluations, whatever budget encloses it (the accuracy ladder's is 4 solves'):
# scipy's dense output keeps about 1 KB a step, two evaluations a step, so this caps it near 200 MB.
STIFF_NFEV = 400_000


def charged(rhs: RHS, cap: int = STIFF_NFEV) -> RHS:
    """`rhs` with every evaluation charged to the active budgets, as _dp54 charges its own, for a
    scipy solver (solve_ivp's loop has no other exit: an arm's optimise ran LSODA for minutes, its
    dense output to gigabytes); at most `cap` evaluations in this run. Charged 8 at a time: a
    budget's checks cost about what a small rhs does."""
    budgets = _budgets.get()
    calls = [0]

    def f(t, y):
        calls[0] += 1
        if calls[0] % 8 == 0:
            for b in budgets:
                b.charge(8)
            if calls[0] > cap:
                _over(budgets, f"more than {cap} right-hand-side evaluations in one stiff run")
        return rhs(t, y)

    return f


def _over(budgets: tuple[Budget, ...], what: str) -> None:
    """Stop a run past a cap of its own: charged to the innermost budget, whose solve names what to
    change (core.sim.scene.solve_budget); a RuntimeError when no budget is active."""
    if budgets:
        raise BudgetExceeded(budgets[-1], what)
    raise RuntimeError(what)


@dataclass
class StiffRun:
    """What a Run offers (t, y, nfev, event, crossings, at), from one of scipy's stiff solvers."""

    t: list
    y: list
    nfev: int
    event: str | None
    crossings: list
    sol: Any
    status: int = 0  # scipy's: -1 when the solver failed
    message: str = ""

    def at(self, t: float) -> list:
        return [float(x) for x in self.sol(t)]


def integrate_stiff(
    rhs: RHS,
    t0: float,
    t1: float,
    y0: Sequence[float],
    rtol: float,
    atol: float,
    events: Sequence[Event] = (),
    method: str = "LSODA",
    peak_from_steps: str | None = None,
) -> StiffRun:
    """The same problem as integrate, by scipy's solve_ivp with a stiff-capable method (LSODA,
    Radau, BDF), for a scene whose explicit steps are held far below its time scale. Our events
    map to solve_ivp's; dense output always. If scipy's event root finder finds no sign change on
    its own interpolant (a non-terminal event on a step the interpolant smooths over), the run is
    repeated without the non-terminal events and, when `peak_from_steps` names one, every step
    point is reported as its crossing instead."""
    from scipy.integrate import solve_ivp

    # LSODA's own complaints ("repeated convergence failures") would reach the terminal; its outcome
    # is in sol.status and sol.message, which the callers read (a process-wide filter, set once:
    # catch_warnings is not thread-safe, and solves run in threads)
    warnings.filterwarnings("ignore", category=UserWarning, module=r"scipy\.integrate\._ivp\.lsoda")
    fns = []
    for ev in events:
        fn = (lambda e: lambda t, y: e.g(t, y))(ev)
        fn.terminal, fn.direction = ev.terminal, ev.direction
        fns.append(fn)
    try:
        sol = solve_ivp(
            charged(rhs),
            (t0, t1),
            y0,
            method=method,
            rtol=rtol,
            atol=atol,
            events=fns,
            dense_output=True,
        )
    except ValueError:
        if peak_from_steps is None:
            raise
        kept = [ev for ev in events if ev.terminal]
        run = integrate_stiff(rhs, t0, t1, y0, rtol, atol, kept, method, None)
        run.crossings = [(peak_from_steps, t, y) for t, y in zip(run.t, run.y)]
        return run
    name, crossings = None, []
    for ev, te, ye in zip(events, sol.t_events, sol.y_events):
        if ev.terminal and len(te):
            name = ev.name
        elif not ev.terminal:
            crossings += [(ev.name, float(t), [float(x) for x in y]) for t, y in zip(te, ye)]
    ts = [float(x) for x in sol.t]
    ys = [[float(x) for x in col] for col in sol.y.T]
    return StiffRun(ts, ys, int(sol.nfev), name, crossings, sol.sol, int(sol.status), str(sol.message))


def _norm(v, y0, y1, rtol, atol) -> float:
    s = 0.0
    for e, a, b in zip(v, y0, y1):
        r = e / sc if (sc := atol + rtol * max(abs(a), abs(b))) else math.inf
        s += r * r  # not r ** 2: that raises OverflowError where r·r gives inf (a rejected step)
    return math.sqrt(s / len(v))


def _dp54(rhs, t0, t1, y, rtol, atol, events, max_steps, first_step, keep_dense, restart=frozenset()) -> Run:
    budgets = _budgets.get()
    n = len(y)
    direction = 1.0 if t1 >= t0 else -1.0
    span = abs(t1 - t0)
    ts, ys = [t0], [list(y)]
    dense = []
    if span == 0:
        return Run(ts, ys, 0, 0, 0)
    for b in budgets:
        b.charge(8)  # the call's own overhead (setup, initial step), about one step's worth
    k1 = rhs(t0, y)
    nfev = 1
    # initial step (Hairer's heuristic, one extra evaluation)
    if not first_step:  # None, or a zero step handed on (an event located at a step's start)
        d0 = _norm(y, y, y, rtol, atol) or 1e-5
        d1 = _norm(k1, y, y, rtol, atol) or 1e-5
        h0 = 0.01 * d0 / d1 if d0 > 1e-5 and d1 > 1e-5 else 1e-6
        h0 = min(h0, span)
        y1 = [a + direction * h0 * b for a, b in zip(y, k1)]
        k2 = rhs(t0 + direction * h0, y1)
        nfev += 1
        d2 = _norm([(b - a) for a, b in zip(k1, k2)], y, y, rtol, atol) / h0
        h1 = (0.01 / max(d1, d2)) ** 0.2 if max(d1, d2) > 1e-15 else max(1e-6, h0 * 1e-3)
        h = min(100 * h0, h1, span)
    else:
        h = min(abs(first_step), span)
    g_prev = [ev.g(t0, y) for ev in events]
    crossings: list = []
    t = t0
    steps = rejected = 0
    while True:
        if steps + rejected >= max_steps:
            raise RuntimeError(f"integration did not finish in {max_steps} steps (t = {t:.6g})")
        for b in budgets:
            b.charge(6)
        if abs(t1 - t) <= h * (1 + 1e-12):
            h = abs(t1 - t)
            last = True
        else:
            last = False
        hs = direction * h
        ks = [k1]
        for i in range(1, 7):
            a = _A[i]
            yi = [y[j] + hs * sum(a[m] * ks[m][j] for m in range(i)) for j in range(n)]
            ks.append(rhs(t + _C[i] * hs, yi))
        nfev += 6
        y_new = yi  # stage 7 sits at the 5th-order solution (FSAL)
        err_vec = [hs * sum(_E[m] * ks[m][j] for m in range(7)) for j in range(n)]
        err = _norm(err_vec, y, y_new, rtol, atol)
        if not math.isfinite(err):
            err = 1e10
        if err <= 1.0:
            t_new = t1 if last else t + hs
            rc = None
            if events or keep_dense:
                rc = ([*y], [b - a for a, b in zip(y, y_new)], None, None, None)
                r2 = rc[1]
                r3 = [hs * k - d for k, d in zip(ks[0], r2)]
                r4 = [d - hs * k - c for d, k, c in zip(r2, ks[6], r3)]
                r5 = [hs * sum(_D[m] * ks[m][j] for m in range(7)) for j in range(n)]
                rc = (rc[0], r2, r3, r4, r5)
                if keep_dense:
                    dense.append((t, hs, rc))
            # events on this step
            hit = None
            for idx, ev in enumerate(events):
                g_new = ev.g(t_new, y_new)
                g_old = g_prev[idx]
                crossed = (g_old < 0 <= g_new and ev.direction >= 0) or (
                    g_old > 0 >= g_new and ev.direction <= 0
                )
                if crossed:
                    te = _locate(ev, rc, t, hs, g_old, g_new)
                    if steps == 0 and ev.name in restart and abs(te - t0) <= 1e-10 * abs(hs):
                        pass  # the event the caller restarted at, found again at the same instant
                    elif ev.terminal:
                        if hit is None or (te - hit[0]) * direction < 0:
                            hit = (te, ev)
                    else:
                        crossings.append((ev.name, te, _interp(rc, (te - t) / hs)))
                g_prev[idx] = g_new
            steps += 1
            if hit is not None:
                te, ev = hit
                theta = (te - t) / hs
                ye = _interp(rc, theta)
                ts.append(te)
                ys.append(ye)
                crossings[:] = [c for c in crossings if (c[1] - te) * direction <= 0]
                return Run(ts, ys, nfev, steps, rejected, ev.name, dense, crossings)
            t, y, k1 = t_new, y_new, ks[6]
            ts.append(t)
            ys.append(y)
            if last:
                return Run(ts, ys, nfev, steps, rejected, None, dense, crossings)
            fac = 0.9 * err**-0.2 if err > 0 else 10.0
            h = h * min(10.0, max(0.2, fac))
        else:
            rejected += 1
            h = h * max(0.1, 0.9 * err**-0.2)
            # only a rejected step can underflow: an accepted tiny step (a tiny first_step handed on
            # from a previous segment) grows by up to 10x per step and is not a failure
            if h < 1e-14 * max(1.0, abs(t)):
                raise RuntimeError(f"step size underflow at t = {t:.6g}")


def _locate(ev: Event, rc, t: float, hs: float, g_old: float, g_new: float) -> float:
    from scipy.optimize import brentq

    if g_new == 0:
        return t + hs
    f = lambda theta: ev.g(t + theta * hs, _interp(rc, theta))  # noqa: E731
    g_end = f(1.0)  # the interpolant at θ = 1 can round to the other side of a tiny g_new
    if g_end == 0 or (g_end > 0) == (g_old > 0):
        return t + hs
    theta = brentq(f, 0.0, 1.0, xtol=1e-15, rtol=1e-15, maxiter=200)
    return t + theta * hs
