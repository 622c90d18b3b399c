"""What every simulated calculator shares: effects, accuracy levels, cost reporting, the ladder.

A scene is a calculator whose `effects` field names the physics switched on. Its simulate
function takes the parsed inputs and a relative tolerance and returns a SimRun; the generic code
here times it, estimates its error against a run 100x tighter (10 000x if the two agree to the
last bit), and builds the accuracy ladder.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from ..declarations import Output, PendingEstimate, Result
from ..errors import InputError
from ..fields import Field
from .integrate import BudgetExceeded, budget

# Named accuracy levels -> relative tolerance. "default" sits where the error-vs-time curve bends
# (measured with bench/benchmark.py: tighter than this costs time for digits no design needs).
LEVELS: dict[str, float] = {"coarse": 1e-3, "default": 1e-6, "fine": 1e-9, "tight": 1e-11}
REFERENCE_RTOL = 1e-13
ESTIMATE_FACTOR = 100.0  # the error estimate compares with a run at rtol / 100
# The per-solve guard (core.sim.integrate.budget): the work one solve may do, error estimate
# included. The built-in presets take < 2 000 evaluations; 400 000 is about 1 s of the integrator.
SOLVE_NFEV = 400_000
# backstop for work the evaluation count does not see (root finders, numpy): CPU seconds of the
# solving thread, so a busy machine does not refuse a solve that needs little
SOLVE_SECONDS = 30.0
DEFAULT_ADVICE = ("accuracy", "try accuracy=coarse, or inputs that make the simulated motion shorter")


@contextmanager
def solve_budget(
    advice: tuple[str, str] = DEFAULT_ADVICE, max_nfev: int | None = None, max_seconds: float | None = None
) -> Iterator[None]:
    """Run one solve within the budget (SOLVE_NFEV and SOLVE_SECONDS unless given, read when the
    solve starts); past it, an InputError naming the field to change and how (never a hang).
    `advice` = (field, what to change), from the calculator: it knows what is long."""
    max_nfev = SOLVE_NFEV if max_nfev is None else max_nfev
    max_seconds = SOLVE_SECONDS if max_seconds is None else max_seconds
    try:
        with budget(max_nfev, max_seconds) as b:
            yield
    except BudgetExceeded as exc:
        if exc.budget is not b:
            raise
        name, hint = advice
        raise InputError(name, f"the simulation needs {exc} (the limit of one solve): {hint}") from None


def accuracy_field(default: str = "default") -> Field:
    return Field(
        "accuracy",
        "Accuracy",
        choices=tuple(LEVELS),
        default=default,
        choice_labels=tuple(f"{k} (±{v:.0e})" for k, v in LEVELS.items()),
        help="Solver tolerance. Each result shows its error estimate, wall time and "
        "right-hand-side evaluations; ctrl+r runs the accuracy-vs-time ladder.",
    )


STATS_OUTPUTS = (
    Output(
        "error_estimate",
        "Error estimate",
        help="Largest relative difference of the key results from a "
        "run at 100x tighter tolerance (10 000x if equal).",
    ),
    Output(
        "rhs_evaluations", "Solver work (evaluations)", help="Right-hand-side evaluations of the main run."
    ),
    Output(
        "wall_time", "Time of one run", "time", "ms", help="Wall time of the main run (not the estimate)."
    ),
)
VOLATILE = frozenset({"wall_time"})  # differs run to run: hidden from snapshots


@dataclass
class SimRun:
    """One simulation at one tolerance."""

    values: dict[str, Any]  # outputs (SI)
    key: dict[str, float]  # the results whose error is estimated (e.g. min and final pressure)
    nfev: int
    warnings: list[str] = field(default_factory=list)
    series: dict[str, tuple[list[float], list[float]]] = field(default_factory=dict)  # plots
    tables: dict[str, list[dict[str, Any]]] = field(default_factory=dict)  # rows of each Table
    heat_maps: dict[str, Any] = field(default_factory=dict)  # HeatMapData of each HeatMap


Simulate = Callable[[Mapping[str, Any], float], SimRun]


def timed(simulate: Simulate, values: Mapping[str, Any], rtol: float) -> tuple[SimRun, float]:
    t0 = time.perf_counter()
    run = simulate(values, rtol)
    return run, time.perf_counter() - t0


def relative_difference(a: Mapping[str, float], b: Mapping[str, float]) -> float:
    worst = 0.0
    for k, va in a.items():
        vb = b[k]
        scale = max(abs(va), abs(vb), 1e-300)
        worst = max(worst, abs(va - vb) / scale if scale > 1e-12 else abs(va - vb))
    return worst


def run_with_stats(
    simulate: Simulate,
    values: Mapping[str, Any],
    advice: tuple[str, str] = DEFAULT_ADVICE,
    estimate: str = "now",
) -> SimRun:
    """The run at the chosen accuracy, with error estimate, evaluations and wall time added, all
    within one solve's budget (`advice` says what to change when it is not enough).

    estimate="later": the error estimate is left as a PendingEstimate, a second step the caller
    runs once the results are shown (the app: the estimate's run at 100x tighter tolerance can
    cost more than the run itself, 36 of the pneumatics card's 62 ms a key). The CLI, sweeps and
    tolerances take it "now", with the results."""
    if estimate not in ("now", "later"):
        raise ValueError(f"estimate is 'now' or 'later', not {estimate!r}")
    with solve_budget(advice):
        return _run_with_stats(simulate, values, advice, later=estimate == "later")


def _run_with_stats(
    simulate: Simulate, values: Mapping[str, Any], advice: tuple[str, str], later: bool
) -> SimRun:
    rtol = LEVELS[values["accuracy"]]
    # Now: the check runs first, so it pays the one-off costs (lazy imports of scipy, caches) and
    # the wall time shown is what the chosen accuracy costs, not what starting up costs. (The app
    # asks "later" only once its card has solved once: the imports are paid by then.)
    check = None if later else simulate(values, rtol / ESTIMATE_FACTOR)
    run, wall = timed(simulate, values, rtol)
    if not run.nfev:
        run.values["error_estimate"] = 0.0  # closed form: nothing was integrated
    elif later:

        def estimate() -> float:
            with solve_budget(advice):
                return _estimate(simulate, values, rtol, run.key)

        run.values["error_estimate"] = PendingEstimate(estimate)
    else:
        run.values["error_estimate"] = _estimate(simulate, values, rtol, run.key, check.key)
    run.values["rhs_evaluations"] = run.nfev
    run.values["wall_time"] = wall
    return run


def _estimate(
    simulate: Simulate,
    values: Mapping[str, Any],
    rtol: float,
    key: Mapping[str, float],
    check_key: Mapping[str, float] | None = None,
) -> float:
    """The largest relative difference of the key results to a run at rtol / 100 (`check_key`
    when that run is done already)."""
    check_rtol = rtol / ESTIMATE_FACTOR
    if check_key is None:
        check_key = simulate(values, check_rtol).key
    estimate = relative_difference(key, check_key)
    if estimate == 0.0 and check_rtol / ESTIMATE_FACTOR >= REFERENCE_RTOL:
        # bit-identical key results say nothing about the error (both runs took the same steps
        # where it matters, or an event reset the state, e.g. a tank refilled to the switch-off
        # pressure): compare once more, 100x tighter again
        estimate = relative_difference(key, simulate(values, check_rtol / ESTIMATE_FACTOR).key)
    return estimate


def compute_with_stats(simulate: Simulate, advice: tuple[str, str] = DEFAULT_ADVICE):
    """A calculator's compute function that is just its scene run with the cost figures added."""

    def compute(values: Mapping[str, Any], estimate: str = "now") -> Result:
        run = run_with_stats(simulate, values, advice, estimate)
        return Result(run.values, run.warnings, run.series)

    return compute


@dataclass
class Rung:
    level: str
    rtol: float
    error: float
    wall_time: float
    nfev: int


def ladder(
    simulate: Simulate, values: Mapping[str, Any], repeats: int = 3, advice: tuple[str, str] = DEFAULT_ADVICE
) -> tuple[list[Rung], SimRun]:
    """Each accuracy level against a reference at REFERENCE_RTOL: error, wall time, evaluations.
    Each run has one solve's budget (the reference, 25x the default's work, is the one that needs it)."""
    with solve_budget(advice, max_nfev=4 * SOLVE_NFEV, max_seconds=4 * SOLVE_SECONDS):
        reference = simulate(values, REFERENCE_RTOL)
    rungs = []
    for level, rtol in LEVELS.items():
        best = None
        for _ in range(repeats):  # best of a few: wall time is noisy, the work is not
            with solve_budget(advice):
                run, wall = timed(simulate, values, rtol)
            best = wall if best is None else min(best, wall)
        rungs.append(Rung(level, rtol, relative_difference(run.key, reference.key), best, run.nfev))
    return rungs, reference
