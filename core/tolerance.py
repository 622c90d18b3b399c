"""Tolerances: an entry such as '3.5 in ± 0.01 in' or '12 V ± 5 %', and each output's spread.

Reading. An entry is split at '±' (or ASCII '+-', '+/-'); the nominal is read by Field.parse as any
entry is, the tolerance by the same unit parser:
    3.5 in ± 0.01 in     absolute, any unit of the field's kind
    3.5 in ± 0.01        a bare tolerance is in the nominal's unit (here inches), whatever its
                         form ('± (0.01)', '± 0.01*1'); after an expression ('2 ft + 3 in ± 1')
                         it is refused: it needs its unit
    20 ± 1 mm            refused as ambiguous on a field with a unit (20 of the field's unit
                         ± 1 mm, or (20 ± 1) mm?): give the value its unit
    12 V ± 5 %           a tolerance in % is relative to the nominal...
    10 % ± 2 %           ...unless the nominal is itself in % (then it is percentage points)
The whole box nominal ± tolerance must lie inside the field's bounds.

Spread. With the toleranced inputs x_i each anywhere in [low_i, high_i]:
- worst case: the lowest and highest value of each output over the box. At the 2^k corners
  (k <= MAX_CORNER_INPUTS) when the output is monotone along every input (checked at five points
  per input); otherwise a bounded optimiser (scipy Powell) searches the box from the best point
  found, and the method says so.
- statistical: each input uniform on its interval (σ_i = (high_i − low_i)/√12). First-order
  propagation σ_y² = Σ (∂y/∂x_i·σ_i)² with ∂y/∂x_i the central secant over the interval, when the
  linear model reproduces every corner to within LINEAR_ENOUGH of the worst-case span; otherwise a
  seeded Monte Carlo, which also gives a 95 % interval and a 95 % confidence interval on σ.
- the input that contributes most: the largest share of the first-order variance.
"""

from __future__ import annotations

import itertools
import math
import numbers
import re
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from dataclasses import field as dc_field
from typing import Any

# model.solve and integrate.cpu_clock are read at each use: tests stand in for them
from . import model, units
from .errors import InputError
from .model import Calculator, choice_values, parse_inputs
from .registry import get
from .sim import integrate
from .sweep import STATS, Cost, Outcome, evaluate, numeric_outputs

_PLUS_MINUS = re.compile(r"±|\+/-|\+-")
_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")
_NUMBER_THEN_UNIT = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*(?P<unit>.*?)\s*$")
MAX_CORNER_INPUTS = 10  # 2^10 = 1024 corners; beyond, the corners the sensitivities point to
LINEAR_ENOUGH = (
    0.01  # first-order σ is used when the linear model misses no corner by more than 1 % of the span
)
DEFAULT_SAMPLES = 1000
DEFAULT_SEED = 0
MIN_SAMPLES = 100  # a time budget never cuts Monte Carlo below this
# The budget of one spread, whatever the calculator costs per solve (a default beam's rectangular
# tube is 0.23 s a solve: its spread took 202 s CPU). Counted across every phase (the points along
# each input, the corners, the optimiser, Monte Carlo); the optimiser may use half of it.
SPREAD_SOLVES = 110_000  # calculator solves (Monte Carlo at its most, and the points before it)
SPREAD_SECONDS = 30.0  # CPU seconds of the spreading thread (core.sim.integrate.cpu_clock)
SPREAD_RHS_EVALUATIONS = 4_000_000  # a simulation's right-hand-side evaluations, main runs
MAX_SAMPLES = 100_000  # --samples: σ's 95 % interval is ±0.4 % there; more only costs memory
Z95 = 1.959963984540054  # two-sided 95 % normal quantile


@dataclass(frozen=True)
class Tolerance:
    name: str
    entry: str  # as typed, e.g. '60 g ± 10 %'
    nominal: float  # SI
    low: float
    high: float

    @property
    def sigma(self) -> float:
        """Standard deviation of a uniform distribution on [low, high]."""
        return (self.high - self.low) / math.sqrt(12.0)


def split(text: Any, name: str = "") -> tuple[Any, str | None]:
    """('3.5 in', '0.01 in') from '3.5 in ± 0.01 in'; (text, None) when there is no tolerance."""
    if not isinstance(text, str):
        return text, None
    parts = _PLUS_MINUS.split(text)
    if len(parts) == 1:
        return text, None
    if len(parts) > 2:
        raise InputError(name, f"{text!r} has more than one ±")
    nominal, tol = parts[0].strip(), parts[1].strip()
    if not nominal:
        raise InputError(name, f"{text!r} has no value before ±")
    if not tol:
        raise InputError(name, f"{text!r} has no tolerance after ±")
    return nominal, tol


def split_inputs(calc: Calculator, raw: Mapping[str, Any]) -> tuple[dict[str, Any], dict[str, str]]:
    """The entries with tolerances removed (what `solve` reads) and each tolerance as typed."""
    nominal: dict[str, Any] = {}
    tols: dict[str, str] = {}
    for name, value in raw.items():
        base, tol = split(value, name)
        nominal[name] = base
        if tol is not None:
            try:
                f = calc.field(name)
            except KeyError:
                raise InputError(name, f"unknown field for {calc.id}") from None
            if not f.kind.with_unit:  # the tolerance is read in a unit of the field's quantity
                raise InputError(
                    name,
                    f"a {'whole number' if f.kind.whole else f.type} cannot carry a "
                    f"tolerance; only quantities can",
                )
            tols[name] = tol
    return nominal, tols


def parse(
    calc: Calculator, raw: Mapping[str, Any]
) -> tuple[dict[str, Any], dict[str, Any], list[Tolerance], list[str]]:
    """(nominal entries, SI values, tolerances, notes). Every mistake is an InputError naming the field.

    A tolerance on a field the current choices do not use is dropped with a note (it changes nothing).
    """
    nominal_raw, tols = split_inputs(calc, raw)
    values, _ = parse_inputs(calc, nominal_raw)
    mode = values.get("mode")
    choices = choice_values(calc, nominal_raw)
    out: list[Tolerance] = []
    notes: list[str] = []
    for name, tol_text in tols.items():
        f = calc.field(name)
        if not f.active(mode, choices):
            notes.append(f"tolerance on {name} ignored: the field is not used with these choices")
            continue
        nominal = values[name]
        half = _half_width(f, str(nominal_raw[name]), tol_text, nominal)
        if half == 0:
            notes.append(f"tolerance on {name} is zero")
            continue
        low, high = nominal - half, nominal + half
        if not low < nominal < high:  # '25 lbf ± 1e-20 lbf': below the nominal's last digit
            notes.append(f"tolerance on {name} is too small to change the value (treated as zero)")
            continue
        for end, word in ((low, "low"), (high, "high")):
            shown = units.format_quantity(end, f.unit, f.quantity)
            try:
                f._check_bounds(end, shown)  # the box must be inside the field's bounds
            except InputError as exc:
                raise InputError(
                    name, f"the {word} end of {raw[name]!r} is outside the field: {exc.message}"
                ) from None
        out.append(Tolerance(name, str(raw[name]), nominal, low, high))
    return nominal_raw, values, out, notes


_EXPONENT = re.compile(r"(\*\*|\^)\s*(\(\s*[-+]?\d+\s*\)|[-+]?\d+)")


def _plain_unit(unit: str, m: re.Match | None) -> bool:
    """Whether a nominal is a number then one unit ('3.5 in', '2 m/s**2', '20 1/in'): then a bare
    tolerance is in that unit. An expression ('2 ft + 3 in', '3.5 in * 2', '(2 ft)') is not."""
    if m is None or not unit:
        return m is not None
    rest = _EXPONENT.sub("", unit)
    rest = re.sub(r"^1\s*/", "", rest)
    return not re.search(r"[\d+\-()]", rest)


def _half_width(f, nominal_text: str, tol_text: str, nominal: float) -> float:
    m = _NUMBER_THEN_UNIT.match(nominal_text)
    nominal_unit = (m.group("unit") if m else "") or ""
    if not re.search(r"[^\W\d_%]", nominal_text):  # plain numbers ('10*5'): in the field's unit
        m, nominal_unit = _NUMBER_THEN_UNIT.match("0"), ""
    in_percent = nominal_unit == "%" or (not nominal_unit and f.unit == "%")
    if tol_text.endswith("%") and not in_percent:
        number = tol_text[:-1].strip()
        if not _NUMBER.match(number):
            raise InputError(f.name, f"cannot read the tolerance {tol_text!r} (expected e.g. '5 %')")
        half = float(number) / 100 * abs(nominal)  # relative to the nominal
    else:
        # a tolerance without a unit, whatever its form ('0.1', '(0.1)', '0.1*1'): '50.8 mm ± (0.1)'
        # was ± 0.1 in on an inch field while '50.8 mm ± 0.1' was ± 0.1 mm
        bare = not tol_text.endswith("%") and units.is_plain_number(tol_text, f.name, f.quantity)
        if bare and not _NUMBER.match(nominal_text) and not _plain_unit(nominal_unit, m):
            # '2 ft + 3 in ± 1' took "ft + 3 in" as the unit (± 15 in), '3.5 in * 2 ± 0.1' "in * 2"
            raise InputError(
                f.name,
                f"the tolerance {tol_text!r} has no unit and {nominal_text!r} is an expression: "
                f"give the tolerance its unit (± {tol_text.strip()} {f.unit or '%'})",
            )
        if not bare and not nominal_unit and f.unit not in ("", "%") and not tol_text.endswith("%"):
            # '20 ± 1 mm' on an inch field read as 20 in ± 1 mm: refused, the two readings differ
            t = _NUMBER_THEN_UNIT.match(tol_text)
            other = t.group("unit") if t and t.group("unit") else "its unit"
            raise InputError(
                f.name,
                f"'{nominal_text} ± {tol_text}' is ambiguous: the value has no unit and the tolerance "
                f"has one; write '{nominal_text} {other} ± {tol_text}' or '{nominal_text} {f.unit} ± {tol_text}'",
            )
        if bare and nominal_unit:  # a bare tolerance is in the nominal's unit
            number = tol_text.strip() if _NUMBER.match(tol_text) else f"({tol_text.strip()})"
            tol_text = f"{number} {nominal_unit}"
        half = units.parse(tol_text, f.unit, f.quantity, f.name)
    if not math.isfinite(half) or half < 0:
        raise InputError(f.name, f"the tolerance {tol_text!r} must be a positive amount")
    return half


# ---------------------------------------------------------------------------------------------
# The spread of every output over the tolerance box


@dataclass
class OutputSpread:
    name: str
    nominal: float
    low: float  # worst case
    high: float
    worst_case_method: str
    std: float  # statistical
    mean: float
    statistical_method: str
    sensitivities: dict[str, float]  # ∂y/∂x_i, SI, central secant over the interval
    shares: dict[str, float]  # fraction of the first-order variance
    main_input: str | None
    interval: tuple[float, float] | None = None  # Monte Carlo: 2.5 % and 97.5 % quantiles
    std_interval: tuple[float, float] | None = None  # Monte Carlo: 95 % confidence interval on σ
    infeasible: list[str] = dc_field(default_factory=list)

    def as_json(self) -> dict[str, Any]:
        return {
            "worst_case": {"low": self.low, "high": self.high, "method": self.worst_case_method},
            "statistical": {
                "mean": self.mean,
                "std": self.std,
                "method": self.statistical_method,
                "interval_95": list(self.interval) if self.interval else None,
                "std_confidence_95": list(self.std_interval) if self.std_interval else None,
            },
            "sensitivities": self.sensitivities,
            "variance_shares": self.shares,
            "main_input": self.main_input,
            "infeasible": self.infeasible,
        }


@dataclass
class Spread:
    tolerances: list[Tolerance]
    outputs: dict[str, OutputSpread]
    cost: Cost
    notes: list[str] = dc_field(default_factory=list)
    samples: int = 0
    seed: int | None = None


class _Spent(Exception):
    """The spread's budget (or the share of it a phase may use) is spent; says which limit."""


class _Probe:
    """Evaluates the calculator at points of the box (a dict of the toleranced SI values), within
    the spread's budget: `share` (0-1] is the part of it the current phase may reach."""

    def __init__(
        self,
        calc: Calculator,
        values: Mapping[str, Any],
        tolerances: list[Tolerance],
        cost: Cost,
        cancelled: Callable[[], bool] | None,
    ):
        self.calc, self.base, self.tols, self.cost = calc, dict(values), tolerances, cost
        self.cancelled = cancelled
        self.clock = integrate.cpu_clock
        self.started = integrate.cpu_clock()
        self.share = 1.0

    def check(self) -> None:
        """Raise _Spent when the next solve would pass the budget (a solve is itself bounded)."""
        if self.cost.solves >= self.share * SPREAD_SOLVES:
            raise _Spent(f"more than {self.share * SPREAD_SOLVES:.0f} solves")
        if self.cost.rhs_evaluations > self.share * SPREAD_RHS_EVALUATIONS:
            raise _Spent(f"more than {self.share * SPREAD_RHS_EVALUATIONS:.0f} right-hand-side evaluations")
        if self.clock() - self.started > self.share * SPREAD_SECONDS:
            raise _Spent(f"more than {self.share * SPREAD_SECONDS:g} s of computing")

    def __call__(self, xs: tuple[float, ...]) -> Outcome:
        if self.cancelled is not None and self.cancelled():
            raise integrate.Cancelled("cancelled")  # the one cancellation every solve raises
        self.check()
        values = dict(self.base)
        for t, x in zip(self.tols, xs):
            values[t.name] = x
        outcome = evaluate(self.calc, values)
        self.cost.add(outcome)
        return outcome


def _number(v: Any) -> float | None:
    kind = type(v)  # exact-type fast path: this runs per output per Monte Carlo sample
    if kind is float:
        return v
    if kind is int:
        return float(v)
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        return None
    return float(v)


def spread(
    calc: Calculator,
    values: Mapping[str, Any],
    tolerances: list[Tolerance],
    outputs: list[str] | None = None,
    method: str = "auto",
    samples: int = DEFAULT_SAMPLES,
    seed: int = DEFAULT_SEED,
    cancelled: Callable[[], bool] | None = None,
    budget_s: float | None = None,
) -> Spread:
    """Worst case and statistical spread of `outputs` (default: every numeric output) over the box.

    method: 'auto' (first-order where it is exact enough, else Monte Carlo), 'first-order', or
    'monte-carlo'. Raises integrate.Cancelled if `cancelled()` turns true. With `budget_s`, Monte Carlo stops
    once the run has taken that long (after at least MIN_SAMPLES samples) and says so.
    """
    if method not in ("auto", "first-order", "monte-carlo"):
        raise InputError("method", f"{method!r} is not auto, first-order or monte-carlo")
    if samples < 2:
        raise InputError("samples", f"needs at least 2 samples, got {samples}")
    if samples > MAX_SAMPLES:  # 4.4 GB in 120 s for a number typed with a few zeros too many
        raise InputError(
            "samples", f"at most {MAX_SAMPLES} samples (got {samples}); σ is within ±0.4 % there"
        )
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise InputError("seed", f"a seed is a whole number, 0 or more (got {seed!r})")
    t0 = time.perf_counter()
    cost = Cost()
    probe = _Probe(calc, values, tolerances, cost, cancelled)
    try:
        return _spread(calc, tolerances, outputs, method, samples, seed, budget_s, t0, cost, probe)
    except _Spent as spent:  # in the points every answer needs: no answer within the budget
        raise InputError(
            tolerances[0].name,
            f"the tolerance spread needs {spent} (the limit of one spread): give fewer inputs a "
            f"tolerance, or choose entries that solve faster (e.g. accuracy=coarse)",
        ) from None


def _spread(calc, tolerances, outputs, method, samples, seed, budget_s, t0, cost, probe) -> Spread:
    k = len(tolerances)
    nominal_x = tuple(t.nominal for t in tolerances)
    center = probe(nominal_x)
    if center.error is not None:
        raise InputError(center.error.partition(":")[0], center.error.partition(": ")[2] or center.error)
    names = outputs or [
        n for n in numeric_outputs(calc, center.outputs) if _number(center.outputs.get(n)) is not None
    ]
    names = [n for n in names if n not in STATS and _number(center.outputs.get(n)) is not None]
    y0 = {n: _number(center.outputs[n]) for n in names}

    # Every evaluated point and its outputs: the worst case takes the extremes over all of them.
    seen: list[tuple[tuple[float, ...], Outcome]] = [(nominal_x, center)]

    def at(xs: tuple[float, ...]) -> Outcome:
        o = probe(xs)
        seen.append((xs, o))
        return o

    # Five points along each input through the nominal: secant sensitivity and a monotonicity check.
    sens: dict[str, dict[str, float]] = {n: {} for n in names}
    line_points: list[tuple[tuple[float, ...], Outcome]] = []
    bends: dict[str, list[str]] = {n: [] for n in names}  # inputs along which an output is not monotone
    for i, t in enumerate(tolerances):
        line = [t.low, (t.low + t.nominal) / 2, t.nominal, (t.nominal + t.high) / 2, t.high]
        outs = []
        for x in line:
            if x == t.nominal:
                outs.append(center)
                continue
            xs = list(nominal_x)
            xs[i] = x
            outs.append(at(tuple(xs)))
            line_points.append((tuple(xs), outs[-1]))
        for n in names:
            ys = [_number(o.outputs.get(n)) if o.error is None else None for o in outs]
            if ys[0] is None or ys[-1] is None:
                sens[n][t.name] = 0.0
                continue
            sens[n][t.name] = (ys[-1] - ys[0]) / (t.high - t.low)
            if None in ys or not _is_monotone(ys):
                bends[n].append(t.name)

    # Corners: all of them for few inputs, else the two each output's sensitivities point to.
    if k <= MAX_CORNER_INPUTS:
        corners = list(itertools.product(*[(t.low, t.high) for t in tolerances]))
        corner_note = f"corners (all {len(corners)})"
    else:
        chosen = set()
        for n in names:
            for sign in (1, -1):
                chosen.add(tuple(t.high if sign * sens[n][t.name] >= 0 else t.low for t in tolerances))
        corners = sorted(chosen)
        corner_note = f"corners the sensitivities point to ({len(corners)} of 2^{k})"
    corner_outcomes = [at(c) for c in corners]

    result: dict[str, OutputSpread] = {}
    sigma2 = {n: {t.name: (sens[n][t.name] * t.sigma) ** 2 for t in tolerances} for n in names}
    need_mc = method == "monte-carlo"
    linear_ok: dict[str, bool] = {}
    for n in names:
        span_lo, span_hi = _extremes(seen, n)
        worst = max(span_hi - span_lo, 0.0)
        residual = 0.0
        # the linear model must reproduce the corners and the points along each input (with one
        # input the corners are the secant's own ends: the half-way points are the test)
        for c, o in list(zip(corners, corner_outcomes)) + line_points:
            y = _number(o.outputs.get(n)) if o.error is None else None
            if y is None:
                residual = math.inf
                break
            predicted = y0[n] + sum(sens[n][t.name] * (x - t.nominal) for t, x in zip(tolerances, c))
            residual = max(residual, abs(y - predicted))
        noise = 1e-12 * max(abs(span_lo), abs(span_hi))  # an output that only moves by rounding is constant
        linear_ok[n] = not bends[n] and residual <= LINEAR_ENOUGH * worst + noise
        if method == "auto" and not linear_ok[n]:
            need_mc = True

    # Optimiser for outputs that are not monotone along some input: corners may miss the extremes.
    optimised: dict[str, tuple[float, float]] = {}
    cut_short: list[str] = []  # outputs whose optimiser search the budget stopped
    probe.share = 0.5
    for n in names:
        if bends[n]:
            try:
                optimised[n] = _optimise(at, tolerances, seen, n)
            except _Spent as spent:
                cut_short.append(n)
                why = str(spent)
    probe.share = 1.0

    mc: dict[str, Any] = {}
    mc_bad: list[str] = []  # the first failure's message (a count is kept, not every message)
    bad_count = 0
    stopped_at = samples
    spent_on = ""  # why Monte Carlo stopped early, when the spread's budget stopped it
    if need_mc:
        from array import array

        import numpy as np

        rng = np.random.default_rng(seed)
        lows = np.array([t.low for t in tolerances])
        highs = np.array([t.high for t in tolerances])
        ys = {n: array("d") for n in names}  # 8 bytes a value: 100 000 samples of 30 outputs, 24 MB
        i = 0
        while i < samples and not spent_on:
            # drawn in chunks (the same seeded sequence as one draw): memory does not grow with samples
            chunk = lows + (highs - lows) * rng.random((min(1000, samples - i), k))
            for row in chunk.tolist():
                if budget_s is not None and i >= MIN_SAMPLES and time.perf_counter() - t0 > budget_s:
                    spent_on = f"time budget {budget_s:g} s"
                    break
                try:
                    o = probe(tuple(row))
                except _Spent as spent:
                    spent_on = f"the spread's budget: {spent}"
                    break
                i += 1
                if o.error is not None:
                    bad_count += 1
                    mc_bad[:] = mc_bad or [o.error]
                    continue
                for n in names:
                    v = _number(o.outputs.get(n))
                    if v is not None:
                        ys[n].append(v)
        stopped_at = i  # the first i samples of the seeded sequence: still reproducible
        for n in names:
            arr = np.array(ys[n])
            if len(arr) < 2 or (spent_on and stopped_at < MIN_SAMPLES):
                continue  # too few samples to stand for the spread: first-order is shown instead
            mean = float(arr.mean())
            var = float(arr.var(ddof=1))
            m4 = float(((arr - mean) ** 4).mean())
            # asymptotic 95 % interval on the variance: Var(s²) ≈ (μ4 − σ⁴)/n (any distribution)
            half = Z95 * math.sqrt(max(m4 - var * var, 0.0) / len(arr))
            mc[n] = (
                mean,
                math.sqrt(var),
                (float(np.quantile(arr, 0.025)), float(np.quantile(arr, 0.975))),
                (math.sqrt(max(var - half, 0.0)), math.sqrt(var + half)),
            )

    for n in names:
        # worst case over the nominal and the corners (the optimiser's finds added where it ran)
        lo, hi = _extremes([(nominal_x, center)] + list(zip(corners, corner_outcomes)), n)
        how = corner_note
        if n in optimised:
            lo, hi = min(lo, optimised[n][0]), max(hi, optimised[n][1])
            how = f"{corner_note} and a bounded optimiser (not monotone in {', '.join(bends[n])})"
        elif n in cut_short:  # every point the stopped searches tried (all lie in the box)
            lo, hi = _extremes(seen, n)
            how = f"{corner_note} and an optimiser stopped at the budget (not monotone in {', '.join(bends[n])})"
        total = sum(sigma2[n].values())
        shares = {name: (v / total if total > 0 else 0.0) for name, v in sigma2[n].items()}
        main = max(shares, key=shares.get) if total > 0 else None
        infeasible = sorted({o.error for _, o in seen if o.error})
        use_mc = n in mc and (method == "monte-carlo" or not linear_ok[n])
        if use_mc:
            mean, std, interval, std_ci = mc[n]
            stat = f"Monte Carlo ({stopped_at} samples, seed {seed}, inputs uniform)"
        else:
            mean = y0[n] + sum(sens[n][t.name] * ((t.low + t.high) / 2 - t.nominal) for t in tolerances)
            std, interval, std_ci = math.sqrt(total), None, None
            stat = "first-order (sensitivities; inputs uniform)"
        result[n] = OutputSpread(
            n, y0[n], lo, hi, how, std, mean, stat, dict(sens[n]), shares, main, interval, std_ci, infeasible
        )
    cost.wall_time = time.perf_counter() - t0
    notes = []
    # a yes/no or named result (e.g. 'backdrivable') that flips inside the box matters as much as a spread
    for n, v in center.outputs.items():
        if (outputs and n not in outputs) or not isinstance(v, (bool, str)):
            continue
        seen_values = {o.outputs.get(n) for _, o in seen if o.error is None and n in o.outputs}
        if len(seen_values) > 1:
            shown = sorted(("yes" if x else "no") if isinstance(x, bool) else str(x) for x in seen_values)
            notes.append(
                f"{n} changes within the tolerances: {' / '.join(shown)} (nominal: "
                f"{('yes' if v else 'no') if isinstance(v, bool) else v})"
            )
    if mc_bad:
        notes.append(
            f"{bad_count} of {stopped_at} Monte Carlo samples could not be solved "
            f"(left out), e.g. {mc_bad[0]}"
        )
    if need_mc and stopped_at < samples:
        shown = "; σ is first-order" if stopped_at < MIN_SAMPLES and spent_on.startswith("the") else ""
        notes.append(f"Monte Carlo stopped at {stopped_at} of {samples} samples ({spent_on}){shown}")
    if cut_short:
        notes.append(
            f"worst case of {', '.join(cut_short)} is over the points tried: the optimiser stopped at "
            f"half the spread's budget ({why}); fewer tolerances give a full search"
        )
    return Spread(
        list(tolerances), result, cost, notes, stopped_at if need_mc else 0, seed if need_mc else None
    )


def _is_monotone(ys: list[float]) -> bool:
    scale = max(abs(y) for y in ys) or 1.0
    eps = 1e-12 * scale
    diffs = [b - a for a, b in zip(ys, ys[1:])]
    return all(d >= -eps for d in diffs) or all(d <= eps for d in diffs)


def _extremes(seen, name: str) -> tuple[float, float]:
    ys = [_number(o.outputs.get(name)) for _, o in seen if o.error is None]
    ys = [y for y in ys if y is not None]
    return (min(ys), max(ys)) if ys else (math.nan, math.nan)


def _optimise(at, tolerances: list[Tolerance], seen, name: str) -> tuple[float, float]:
    """Lowest and highest value found by scipy's bounded Powell search from the best points so far."""
    from scipy.optimize import minimize

    bounds = [(t.low, t.high) for t in tolerances]
    found = []
    for sign in (1.0, -1.0):
        feasible = [(xs, _number(o.outputs.get(name))) for xs, o in seen if o.error is None]
        feasible = [(xs, y) for xs, y in feasible if y is not None]
        start = min(feasible, key=lambda p: sign * p[1])
        penalty = sign * start[1] + abs(start[1]) + 1.0

        def objective(x, sign=sign, penalty=penalty):
            o = at(tuple(min(max(float(v), lo), hi) for v, (lo, hi) in zip(x, bounds)))
            y = _number(o.outputs.get(name)) if o.error is None else None
            return penalty if y is None else sign * y

        res = minimize(
            objective,
            list(start[0]),
            method="Powell",
            bounds=bounds,
            options={"xtol": 1e-10, "ftol": 1e-13, "maxfev": 400},
        )
        found.append(sign * float(res.fun))
    return found[0], found[1]


# ---------------------------------------------------------------------------------------------
# solve with tolerances (CLI and app)


def solve(
    calc_id: str,
    raw: Mapping[str, Any],
    display_units: Mapping[str, str] | None = None,
    method: str = "auto",
    samples: int = DEFAULT_SAMPLES,
    seed: int = DEFAULT_SEED,
    cancelled: Callable[[], bool] | None = None,
    budget_s: float | None = None,
):
    """(Solution at the nominal values, exactly core.model.solve's; Spread or None; notes)."""
    calc = get(calc_id)
    nominal_raw, values, tols, notes = parse(calc, raw)
    solution = model.solve(calc_id, nominal_raw, display_units)
    for t in tols:
        entered = solution.inputs[t.name]
        solution.inputs[t.name] = type(entered)(entered.value, entered.unit, t.entry)
    if not tols:
        return solution, None, notes
    result = spread(
        calc, values, tols, [n for n in solution.outputs], method, samples, seed, cancelled, budget_s
    )
    result.notes = notes + result.notes
    return solution, result, result.notes


def shown_unit(calc: Calculator, solution, name: str) -> str:
    """The unit an output is shown in (its text's unit when that is a plain unit, else its own)."""
    o = calc.output(name)
    text = solution.outputs[name].text
    unit = text.split(" ", 1)[1] if " " in text else o.unit
    try:
        units.factor(unit, o.quantity)
    except Exception:  # the shown text carries no plain unit
        unit = o.unit
    return unit


def spread_text(calc: Calculator, solution, s: OutputSpread) -> str:
    """'3.8151 .. 3.925 m  σ 0.0317' for a results table."""
    o = calc.output(s.name)
    unit = shown_unit(calc, solution, s.name)

    def q(v: float) -> str:
        return units.format_number(units.to_unit(v, unit, o.quantity))

    if s.low == s.high:
        return "unaffected"
    worst, stat = short_method(s)
    return f"{q(s.low)} .. {q(s.high)}  σ{'*' if stat == 'Monte Carlo' else ''} {q(s.std)}"


def as_json(solution, result: Spread | None) -> dict[str, Any]:
    """solve --json's object, with each output's spread and each tolerance when there are any."""
    data = solution.as_json()
    if result is None:
        return data
    for t in result.tolerances:
        data["inputs"][t.name]["tolerance"] = {"low": t.low, "high": t.high, "distribution": "uniform"}
    for name, s in result.outputs.items():
        if name in data["outputs"]:
            data["outputs"][name]["spread"] = s.as_json()
    data["tolerance_cost"] = result.cost.as_json()
    data["notes"] = list(result.notes)
    return data


def short_method(s: OutputSpread) -> tuple[str, str]:
    """('corners' or 'optimiser', 'first-order' or 'Monte Carlo') for a compact line."""
    return (
        "optimiser" if "optimiser" in s.worst_case_method else "corners",
        "Monte Carlo" if s.statistical_method.startswith("Monte Carlo") else "first-order",
    )


def spread_lines(calc: Calculator, solution, result: Spread, width: int) -> list[str]:
    """Plain-text lines for `gearhead solve` when tolerances are present."""
    lines = [f"  tolerances: {', '.join(t.entry for t in result.tolerances)} (each uniform over its range)"]
    unaffected = []
    for name, s in result.outputs.items():
        o = calc.output(name)
        if s.low == s.high:
            unaffected.append(name)
            continue
        unit = shown_unit(calc, solution, name)

        def q(v: float) -> str:
            return units.format_number(units.to_unit(v, unit, o.quantity))

        u = f" {unit}" if unit else ""
        worst, stat = short_method(s)
        main = f"; mostly {s.main_input} ({s.shares[s.main_input] * 100:.0f} %)" if s.main_input else ""
        lines.append(
            f"  {o.label:<{width}}  {q(s.low)} .. {q(s.high)}{u} ({worst}); σ {q(s.std)}{u} ({stat}){main}"
        )
    if unaffected:
        lines.append(f"  unaffected: {', '.join(unaffected)}")
    methods = sorted({s.worst_case_method for s in result.outputs.values()})
    lines.append(f"  worst case over the box: {'; '.join(methods)}")
    if result.samples:
        lines.append(
            f"  Monte Carlo where first order is not exact enough: {result.samples} samples, seed {result.seed}"
        )
    lines.append(f"  cost: {result.cost.text()}")
    lines += [f"  note: {n}" for n in result.notes]
    return lines
