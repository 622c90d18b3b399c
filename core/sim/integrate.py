"""The ODE integrator of every scene: one interface, `integrate(rhs, t0, t1, y0, ..., method=...)`,
in the manner of scipy.integrate.solve_ivp (several methods behind one call, events located on the
dense output, one Run returned), on plain Python floats. The methods:

- "DP54" (the default): Dormand–Prince 5(4) with FSAL, 4th-order dense output. Written by hand
  because solve_ivp spends ~60 µs of numpy overhead per step on systems of 1-6 states; this costs a
  few µs, which is what keeps a 150 s match under 5 ms (bench/bench_integrators.py measures the lead
  on the scenes' own right-hand sides). The tests check the scenes against scipy's solve_ivp
  (DOP853, tight) called directly on equations written out in the test, an independent reference.
- "EXP": exponential Rosenbrock-Euler in the speed of a plant ṗ = c·w, ẇ = f(p, w), ė = g(p, w)
  ((X1)-(X3) below): a motor's back-EMF damps its speed with a time constant far below a robot
  loop's control period, where DP54 is held to steps ≈ 3τ by stability (the profiled move, one call
  a period, core.sim.profiled).
- "RK4": classical RK4 at a fixed step (the reference the profiled move is measured against,
  bench/bench_profiled.py).
- "LSODA", "Radau", "BDF": scipy's solve_ivp with a stiff-capable method, for a scene whose
  explicit steps are held far below its time scale (integrate_stiff).

Every run returns its right-hand-side evaluation count, so the cost of accuracy is visible, and
every evaluation is charged to the budgets active around it (`with budget(...)`), whatever the
method: BudgetExceeded or Cancelled stops it between steps. DP54's and EXP's events are located by
scipy.optimize.brentq on the step's own interpolant to ~1e-13 of the step, not to a step boundary;
RK4's by linear interpolation between its steps; scipy's by its own root finder.
"""

from __future__ import annotations

import bisect
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
    """What every method returns: the accepted step points (t, y), the evaluations, the terminal
    event that ended the run, the non-terminal events located (name, t, y), and a dense output."""

    t: list[float]
    y: list[Vector]
    nfev: int
    steps: int = 0  # DP54's accepted steps, and those it rejected
    rejected: int = 0
    event: str | None = None  # name of the terminal event that ended the run
    dense: list = field(default_factory=list)  # (t0, h, the step's interpolant data) per step: DP54, EXP
    crossings: list = field(default_factory=list)  # (name, t, y) of non-terminal events, located
    status: int = 0  # scipy's: -1 when the solver failed
    message: str = ""
    sol: Callable[[float], Vector] | None = None  # the dense output of a method other than DP54

    def at(self, t: float) -> Vector:
        """Interpolated state: the method's dense output (DP54's is 4th order)."""
        if self.sol is not None:
            return self.sol(t)
        for t0, h, rc in self.dense:
            if (h > 0 and t0 <= t <= t0 + h) or (h < 0 and t0 + h <= t <= t0):
                return _interp(rc, (t - t0) / h)
        raise ValueError(f"t = {t} outside the integrated span")


def _interp(rc, theta: float) -> Vector:
    r1, r2, r3, r4, r5 = rc
    one = 1 - theta
    return [a + theta * (b + one * (c + theta * (d + one * e))) for a, b, c, d, e in zip(r1, r2, r3, r4, r5)]


STIFF_METHODS = ("LSODA", "Radau", "BDF")
# each method's own options (keyword arguments of integrate beyond the shared ones)
OPTIONS = {
    "DP54": (),
    "EXP": ("scale", "p_coupled"),
    "RK4": ("step",),
    **{m: ("peak_from_steps",) for m in STIFF_METHODS},
}
METHODS = tuple(OPTIONS)
REQUIRED = {"EXP": ("scale",), "RK4": ("step",)}
DP54_STEPS = 100_000  # the default caps of max_steps
EXP_STEPS = 200_000


def integrate(
    rhs: RHS,
    t0: float,
    t1: float,
    y0: Sequence[float],
    rtol: float = 1e-6,
    atol: float = 1e-9,
    events: Sequence[Event] = (),
    max_steps: int | None = None,
    first_step: float | None = None,
    dense: bool = False,
    restart: Sequence[str] = (),
    method: str = "DP54",
    **options: Any,
) -> Run:
    """Integrate y' = rhs(t, y) from t0 to t1 by `method` (one of METHODS), stopping at the first
    terminal event. The shared arguments, where the method has a use for them:
    - rtol, atol: the adaptive methods' tolerances (RK4's step is fixed);
    - max_steps: DP54's (default 100 000) and EXP's (default 200 000) cap; first_step: their first
      step (None or 0: DP54 picks one, EXP tries the whole span);
    - dense: DP54 keeps its dense output only when asked; the other methods always do;
    - restart: names of events that were located at t0 and handled by the caller (a restart at an
      event). A crossing of one of them found again at t0 itself (DP54, EXP: within 1e-10 of the
      step; RK4: on its first step) is that same event, not a new one: it is not reported, so a
      caller that restarts cannot loop. Not offered by scipy's methods.
    The methods' own options (OPTIONS): EXP's `scale` (c, required) and `p_coupled` (f depends on p:
    its pull is evaluated, one more evaluation a step); RK4's `step` (required); scipy's
    `peak_from_steps` (integrate_stiff)."""
    # refused as solve_ivp refuses them, before any work: a misspelt option must not pass silently
    if method not in OPTIONS:
        raise TypeError(f"integrate: no method {method!r} (one of {', '.join(METHODS)})")
    for name in options:
        if name not in OPTIONS[method]:
            raise TypeError(f"integrate: method {method} takes no option {name!r}")
    for name in REQUIRED.get(method, ()):
        if name not in options:
            raise TypeError(f"integrate: method {method} needs the option {name!r}")
    if method in STIFF_METHODS:
        if restart:
            raise TypeError(f"integrate: {method} takes no restart")
        return integrate_stiff(rhs, t0, t1, y0, rtol, atol, events, method, **options)
    y = list(map(float, y0))
    if method == "EXP":
        return _exp(
            rhs,
            options["scale"],
            t0,
            t1,
            y,
            rtol,
            atol,
            events,
            first_step,
            frozenset(restart),
            EXP_STEPS if max_steps is None else max_steps,
            options.get("p_coupled", False),
        )
    if method == "RK4":
        return _rk4(rhs, t0, t1, y, options["step"], events, frozenset(restart))
    return _dp54(
        rhs,
        t0,
        t1,
        y,
        rtol,
        atol,
        events,
        DP54_STEPS if max_steps is None else max_steps,
        first_step,
        dense,
        frozenset(restart),
    )


# ---- LSODA, Radau, BDF: scipy's solve_ivp, each evaluation charged -------------------------------

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


StiffRun = Run  # the name a stiff run had when it was a type of its own (core.sim.motion reads it)


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
) -> Run:
    """integrate's scipy methods (LSODA, Radau, BDF; integrate(..., method=...) calls this, and the
    scenes that named it before the one interface still do): the problem by scipy's solve_ivp, every
    evaluation charged (charged). Our events map to solve_ivp's; dense output always. If scipy's
    event root finder finds no sign change on its own interpolant (a non-terminal event on a step
    the interpolant smooths over), the run is repeated without the non-terminal events and, when
    `peak_from_steps` names one, every step point is reported as its crossing instead."""
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
    dense_output = sol.sol
    return Run(
        ts,
        ys,
        int(sol.nfev),
        event=name,
        crossings=crossings,
        status=int(sol.status),
        message=str(sol.message),
        sol=lambda t: [float(x) for x in dense_output(t)],
    )


# ---- DP54: Dormand–Prince 5(4) ------------------------------------------------------------------


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


# ---- EXP: exponential in the speed, for a motor's plant over one control period -----------------
#
# The back-EMF damps the speed with the mechanical time constant τ = kA/kV, often far below the
# control period (0.2-6 ms against 20 ms in FRC elevators): an explicit method (the scene's DP54)
# is held to steps ≈ 3τ by stability there, hundreds of evaluations a period. The plant is
#     ṗ = c·w,  ẇ = f(p, w),  ė = g(p, w)   (scaled position, speed, energy)
# with f affine in w except where a current limit or the sag bends it. Exponential Rosenbrock-Euler
# in w (J = ∂f/∂w at the step's start, by a difference quotient), with the position's pull on f
# taken as a forcing growing linearly over the step, b = c·w·∂f/∂p (an arm's gravity; 0 and not
# evaluated when the field force does not vary, as on an elevator):
#     ẇ ≈ f₀ + J·(w − w₀) + b·s  ⇒  w(s) = w₀ + s·φ₁(sJ)·f₀ + s²·φ₂(sJ)·b,
#     p(s) = p₀ + c·(w₀·s + s²·φ₂(sJ)·f₀ + s³·φ₃(sJ)·b),
#     φ₁(z) = (e^z − 1)/z,  φ₂(z) = (e^z − 1 − z)/z²,  φ₃(z) = (e^z − 1 − z − z²/2)/z³        (X1)
# is exact for f affine in w and independent of p (an elevator with no limit binding: one step a
# period), second order otherwise. Its error is what the linear model misses: with the defect at
# the step's end δ = f(p₁, w₁) − (f₀ + J·(w₁ − w) + b·h) (it sees a limit letting go inside the step,
# the sag's curve and an arm's gravity changing with p), e_w = δ·min(h, 1/|J|) and
# e_p = c·e_w·h; the step adapted as h·(tol/err)^(1/2) (X2). The energy rate g is linearised in w
# like f, G = ∂g/∂w: ∫g dt = g₀·h + G·(Δp/c − w·h), exact where (X1) is, its error h·δ_g (X3).
# Events are located on (X1) of the step (the speed is monotone on it: at most one stop). Cost:
# f at the step's end (the next step's start) and the difference quotients: 2 evaluations a step
# (3 with b).


def _phi(z: float) -> tuple[float, float, float]:
    """φ₁, φ₂, φ₃ of (X1): φ₃(z) = (e^z − 1 − z − z²/2)/z³; their series near 0."""
    if abs(z) < 2e-3:
        return (
            1 + z / 2 + z * z / 6 + z**3 / 24,
            0.5 + z / 6 + z * z / 24 + z**3 / 120,
            1 / 6 + z / 24 + z * z / 120 + z**3 / 720,
        )
    e1 = math.expm1(z)
    return e1 / z, (e1 - z) / (z * z), (e1 - z - z * z / 2) / (z * z * z)


def _beyond_noise(defect: float, f: float, dw: float, w: float) -> float:
    return max(0.0, abs(defect) - 1e-9 * abs(f) * abs(dw) / (abs(w) + 1.0) - 1e-15 * abs(f))


def _exp_state(s: float, p, w, f0, J, c, b=0.0) -> list[float]:
    ph1, ph2, ph3 = _phi(s * J)
    return [p + c * (s * w + s * s * (ph2 * f0 + s * ph3 * b)), w + s * (ph1 * f0 + s * ph2 * b)]


def _exp_dense(dense: list) -> Callable[[float], Vector]:
    """EXP's dense output: (X1) of the step holding t."""

    def at(t: float) -> list[float]:
        for t0, h, seg in dense:
            if t0 <= t <= t0 + h:
                return _exp_state(t - t0, *seg)
        raise ValueError(f"t = {t} outside the integrated span")

    return at


def _exp(
    rhs,
    c: float,
    t0: float,
    t1: float,
    y0,
    rtol: float,
    atol: float,
    events,
    first_step,
    restart,
    max_steps: int,
    p_coupled: bool,
) -> Run:
    """(X1)-(X3) from t0 to t1; rhs(t, y) -> [c·w, f, g] (the scene's own right-hand side). Dense:
    (t, h, (p, w, f0, J, c, b)) per step."""
    run = Run([], [], 0)
    run.sol = _exp_dense(run.dense)
    t, y = t0, list(y0)
    run.t.append(t)
    run.y.append(list(y))
    h = min(first_step or (t1 - t0), t1 - t0)
    k0 = rhs(t, y)
    g_prev = [ev.g(t, y) for ev in events]

    def slope(tt, yy, kk):
        """(∂f/∂w, ∂g/∂w, b = c·w·∂f/∂p) by difference quotients (b only when f depends on p)."""
        dw = 1e-6 * (abs(yy[1]) + 1.0)
        k2 = rhs(tt, [yy[0], yy[1] + dw, yy[2]])
        if not p_coupled:
            return (k2[1] - kk[1]) / dw, (k2[2] - kk[2]) / dw, 0.0
        dp = 1e-6 * (abs(yy[0]) + 1.0)
        k3 = rhs(tt, [yy[0] + dp, yy[1], yy[2]])
        return (k2[1] - kk[1]) / dw, (k2[2] - kk[2]) / dw, c * yy[1] * (k3[1] - kk[1]) / dp

    extra = 2 if p_coupled else 1
    J0, G0, b0 = slope(t, y, k0)
    nfev = 1 + extra
    for _ in range(max_steps):
        charge(2)
        last = t + h >= t1 - 1e-15 * max(1.0, abs(t1))
        if last:
            h = t1 - t
        end = _exp_state(h, y[0], y[1], k0[1], J0, c, b0)
        t_end = t1 if last else t + h
        k1 = rhs(t_end, end + [0.0])
        nfev += 1
        dw = end[1] - y[1]
        # (X2): the defect of the linear model at the step's end
        e_w = _beyond_noise(k1[1] - k0[1] - J0 * dw - b0 * h, k0[1], dw, y[1]) * min(
            h, 1.0 / max(abs(J0), 1e-300)
        )
        e_e = _beyond_noise(k1[2] - k0[2] - G0 * dw, k0[2], dw, y[1]) * h
        err = max(
            e_w / (atol + rtol * max(abs(end[1]), abs(dw))),
            c * e_w * h / (atol + rtol * max(abs(end[0]), abs(end[0] - y[0]))),
            e_e / (atol + rtol * max(abs(y[2]), h * abs(k0[2]))),
        )
        if err > 1.0 and h > 1e-12 * max(1.0, abs(t)):
            h *= max(0.2, 0.9 * err**-0.5)
            continue
        seg = (y[0], y[1], k0[1], J0, c, b0)
        hit = None
        for idx, ev in enumerate(events):
            g_old, g_new = g_prev[idx], ev.g(t_end, end)
            if (g_old < 0 <= g_new and ev.direction >= 0) or (g_old > 0 >= g_new and ev.direction <= 0):
                te = _locate_exp(ev, t, h, seg, g_old)
                if ev.name in restart and abs(te - t0) <= 1e-10 * (t1 - t0):
                    pass
                elif ev.terminal:
                    if hit is None or te < hit[0]:
                        hit = (te, ev)
                else:
                    run.crossings.append((ev.name, te, _exp_state(te - t, *seg)))
            g_prev[idx] = g_new
        if hit is not None:
            te = hit[0]
            s_ = te - t
            run.dense.append((t, s_, seg))
            ye = _exp_state(s_, *seg)
            run.t.append(te)
            run.y.append(ye + [y[2] + s_ * k0[2] + G0 * ((ye[0] - y[0]) / c - y[1] * s_)])  # (X3)
            run.crossings = [cr for cr in run.crossings if cr[1] <= te]
            run.event = hit[1].name
            run.nfev = nfev
            return run
        run.dense.append((t, h, seg))
        energy = y[2] + h * k0[2] + G0 * ((end[0] - y[0]) / c - y[1] * h)  # (X3)
        t, y, k0 = t_end, end + [energy], k1
        run.t.append(t)
        run.y.append(y)
        if last:
            run.nfev = nfev
            return run
        J0, G0, b0 = slope(t, y, k0)
        nfev += extra
        h *= min(4.0, max(0.2, 0.9 * err**-0.5)) if err > 0 else 4.0
    raise RuntimeError(f"integration did not finish in {max_steps} steps (t = {t:.6g})")


def _locate_exp(ev: Event, t: float, h: float, seg, g_old: float) -> float:
    """The event's time on the step's (X1), by Brent's method (the speed is monotone on it)."""
    from scipy.optimize import brentq

    f = lambda th: ev.g(t + th, _exp_state(th, *seg))  # noqa: E731
    f_end = f(h)
    if f_end == 0 or (f_end > 0) == (f(0.0) > 0):
        return t + h
    return t + brentq(f, 0.0, h, xtol=1e-15, rtol=1e-15, maxiter=200)


# ---- RK4: a fixed step, the reference the profiled move is measured against ---------------------


def _linear_dense(run: Run) -> Callable[[float], Vector]:
    """RK4's dense output: the state linear between the step points (what its events see)."""

    def at(t: float) -> list[float]:
        i = max(0, min(bisect.bisect_right(run.t, t) - 1, len(run.t) - 2))
        t0, t1 = run.t[i], run.t[i + 1]
        th = (t - t0) / (t1 - t0) if t1 > t0 else 0.0
        return [a + th * (b - a) for a, b in zip(run.y[i], run.y[i + 1])]

    return at


def _rk4(rhs, t0: float, t1: float, y0, step: float, events, restart) -> Run:
    """Classical RK4 at a fixed step (the last one shortened to end at t1); an event is located by
    linear interpolation between the steps it falls between."""
    run = Run([], [], 0)
    run.sol = _linear_dense(run)
    t, y = t0, list(y0)
    run.t.append(t)
    run.y.append(list(y))
    g_prev = [ev.g(t, y) for ev in events]
    n = max(1, math.ceil((t1 - t0) / step - 1e-9))
    for i in range(n):
        charge(4)
        h = (t1 - t) if i == n - 1 else step
        k1 = rhs(t, y)
        k2 = rhs(t + h / 2, [a + h / 2 * b for a, b in zip(y, k1)])
        k3 = rhs(t + h / 2, [a + h / 2 * b for a, b in zip(y, k2)])
        k4 = rhs(t + h, [a + h * b for a, b in zip(y, k3)])
        y1 = [a + h / 6 * (b + 2 * c + 2 * d + e) for a, b, c, d, e in zip(y, k1, k2, k3, k4)]
        run.nfev += 4
        t_new = t1 if i == n - 1 else t + h
        hit = None
        for idx, ev in enumerate(events):
            g_old, g_new = g_prev[idx], ev.g(t_new, y1)
            if (g_old < 0 <= g_new and ev.direction >= 0) or (g_old > 0 >= g_new and ev.direction <= 0):
                th = g_old / (g_old - g_new) if g_old != g_new else 1.0
                te = t + th * h
                ye = [a + th * (b - a) for a, b in zip(y, y1)]
                if ev.name in restart and i == 0 and th < 1e-9:
                    pass
                elif ev.terminal:
                    if hit is None or te < hit[0]:
                        hit = (te, ev, ye)
                else:
                    run.crossings.append((ev.name, te, ye))
            g_prev[idx] = g_new
        if hit is not None:
            run.t.append(hit[0])
            run.y.append(hit[2])
            run.crossings = [c for c in run.crossings if c[1] <= hit[0]]
            run.event = hit[1].name
            return run
        t, y = t_new, y1
        run.t.append(t)
        run.y.append(list(y))
    return run
