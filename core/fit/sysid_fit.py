"""kS, kV, kA, kG from a SysId routine as WPILib's SysId computes them (issue 44 item 3), after
allwpilib tools/sysid/src/main/native/cpp/analysis: AnalysisManager.cpp, FilteringUtils.cpp,
FeedforwardAnalysis.cpp, OLS.cpp. Units: the card's SI (metres or radians, seconds, volts).

Data preparation (AnalysisManager::PrepareGeneralData, FilteringUtils InitialTrimAndFilter):
    each test's first run; each voltage sample but the last with the position and velocity
    linearly interpolated (extrapolated at the ends) at its time, dt to the next voltage sample (D1)
    velocity threshold: the least noise floor of the quasistatic tests' velocity, the RMS of
    v[i−4] less the 9-sample moving average ending at i (GetNoiseFloor)                        (D2)
    quasistatic tests: samples with |u| = 0 or |v| below the threshold dropped                 (D3)
    ours, beyond SysId: the quasistatic threshold is MOVING noise floors, not one. The model holds
    only in motion; while friction holds the mechanism (the ramp below kS + kG) v is pure noise, and
    one floor (√(8/9)·σ_v for white noise: v[i−4] less a mean of 9 that holds it) lets 35 % of those
    samples in, with a = 0 and sgn v random, each a residual up to (kS + kG)/kA. On a mechanism
    faster than its log (kA/kV under the step) they outweigh the few samples that carry kA: at
    σ_v = 0.0002 m/s, 5 ms, kA/kV = 3.6 ms, SysId's one floor gives kA 4.7x (continuous) and 9.2x
    (discrete), kS 13 % low. Four floors (3.8 σ_v) let 1.6e-4 of them in                      (D3')
    acceleration a[i] = (v[i+1] − v[i−1])/(2·T̄), a[0] = (v[1] − v[0])/(2·T̄), a[last] = 0, T̄ the
    mean dt in (0, 0.5 s) (PrepareMechData's CentralFiniteDifference<1, 3>); cos θ, sin θ      (D4)
    dynamic tests: samples before the largest sgn(v)·a dropped; then cut after the step
    duration, the time to first exceed 0.9 of the test's top speed (set by the first dynamic test,
    no longer than the longest dynamic test) (TrimStepVoltageData)                              (D5)
    samples whose acceleration is exactly 0 dropped (AccelFilter)                               (D6)
Continuous form (FeedforwardAnalysis.cpp, OLS.cpp; numpy's lstsq):
    a = α·v + β·u + γ·sgn v  (+ δ elevator)  (+ δ·cos θ + ε·sin θ arm)                          (F1)
    kS = −γ/β,  kV = −α/β,  kA = 1/β,  kG = −δ/β (elevator),  kG = hypot(δ, ε)/β and
    offset = atan2(ε, −δ) (arm: gravity −kG/kA·cos(θ + offset))                                (F2)
    R̄² = 1 − (1 − R²)·(n − 1)/(n − p − 1),  RMSE = √(SSE/n)  (OLS.cpp)                         (F3)
    insufficient data: for each eigenpair (λ, w) of XᵀX, |λ·max|w|| ≤ 10 marks the gains of the
    variable where |w| is largest (β: all) (CheckOLSDataQuality)                                (F4)
Discrete form (SysId before 2023), over consecutive samples of the same prepared tests:
    v[k+1] = α·v[k] + β·u[k] + γ·sgn v[k] (+ δ) (+ δ·cos θ + ε·sin θ)                           (F5)
    with zero-order hold over T̄: α = e^(−T̄·kV/kA), β = (1 − α)/kV, so (derived with sympy)
        kV = (1 − α)/β,  kA = (α − 1)·T̄/(β·ln α) (0 < α < 1),  kS = −γ/β,  kG = −δ/β,
        arm: kG = hypot(δ, ε)/β, offset = atan2(ε, −δ)                                          (F6)
Discrete form with the logged steps (ours): where the steps differ, (F5) with each pair's own step
h_k in α_k = e^(−h_k·kV/kA), by nonlinear least squares from (F6) (see _per_step)               (F8)
Uncertainty: cov(coefficients) = s²·(XᵀX)⁻¹, s² = SSE/(n − p); each gain's standard deviation by
the delta method, its gradient in the coefficients by central differences                      (F7)
The discrete form by instrumental variables (ours, what `gearhead fit` shows as "discrete"; the
least squares above stay as fit_discrete(method="ols"), and the continuous form is SysId's own):
    the log holds y_k = v_k + e_k, e the velocity's noise, so (F5)/(F8) reads
        y_(k+1) = α_k·y_k + β_k·u_k + … + ε_k,  ε_k = e_(k+1) − α_k·e_k                      (F11)
    and its regressor y_k holds e_k, which ε_k holds too (E[y_k·ε_k] = −α·σ²): least squares
    shrink α to α·S/(S + σ²) (S: the noise-free v's variance beyond the other regressors), so kA
    = kV·T/(−ln α) falls: 9-17 % at 0.5 % noise, 69-91 % at 2 % (bench/fit_recovery.py). Any
    instruments b_k with E[b_k·ε_k] = 0 that move with y_k give instead, consistently,
        θ̂ = (BᵀX)⁻¹·Bᵀy   (Söderström & Stoica, Instrumental Variable Methods for System
        Identification, 1983; Ljung, System Identification, 2nd ed. 1999, §7.6)                 (F9)
    with, where the steps differ, (F8)'s residual r(q) in the p equations Bᵀ·r(q) = 0.
    Instruments: z_k = [x̂_k, u_k, sgn u_k, 1 (, cos θ_k, sin θ_k)], x̂ the velocity the model
    gives from the logged voltage alone (core/fit/replay.py (R1), from each test's first sample),
    with the previous estimate's gains (Young's auxiliary model; first SysId's discrete least
    squares; then each estimate's, until the gains move by less than 1e-6, at most ITERATIONS).
    The voltage is what the robot commanded, free of the velocity's noise, so x̂ is too, whatever
    the noise's colour (a velocity filter's correlated noise needs no lag, unlike a lagged y_(k−m)
    as instrument). cos θ, sin θ from the measured position are their own instruments (an
    encoder's position noise taken as negligible), and sgn u stands for sgn v (the same in each
    of SysId's tests once moving)                                                               (F10)
    Covariance A⁻¹·S·A⁻ᵀ, A = BᵀX (BᵀJ), S = Var(Bᵀ·ε) from (F11)'s structure: see _covariance (F12)
    Whitening (Young's refined IV: Young 1976, Int. J. Control 23(5); Young & Jakeman 1980, Int. J.
    Control 31(4)): for white e, ε is MA(1) and F: w_k = ε_k + α_k·w_(k−1) (restarted at each run
    of consecutive rows) makes it white; (F9) on the filtered equation with filtered instruments
    F·Z is (F9) with B = Fᵀ·F·Z. With α near 1 (kA/kV ≫ step) F weighs the slow, steady-state
    content the raw equation drowns: flywheel, 2 % noise, 10 seeds: spread of kS 96 → 28 %, kV
    2.5 → 0.86 %, kA 9.9 → 5.3 % (measured)                                                     (F13)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from .signals import Picked, Run

NOISE_WINDOW = 9  # kNoiseMeanWindow
QUALITY_THRESHOLD = 10.0
MOVED = 5.0  # a test's top speed must exceed this many times the noise floor (ours, not SysId's)
MOVING = 4.0  # (D3'): quasistatic samples slower than this many noise floors are taken as at rest
GAIN_NAMES = ("kS", "kV", "kA", "kG", "offset")
WHITEN = True  # (F13); False: (F9) with the instruments as they are (to compare)
ITERATIONS = 4  # (F10): instruments from the previous estimate's model, at most this many times


@dataclass
class Prepared:
    t: np.ndarray
    u: np.ndarray
    x: np.ndarray
    v: np.ndarray
    dt: np.ndarray
    a: np.ndarray = field(default_factory=lambda: np.zeros(0))
    cos: np.ndarray = field(default_factory=lambda: np.zeros(0))
    sin: np.ndarray = field(default_factory=lambda: np.zeros(0))
    i: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))  # each sample's index in its run
    run: Run | None = None  # the test's logged samples (the IV form's instruments, (F9))

    def take(self, keep) -> Prepared:
        def cut(y):
            return y[keep] if len(y) == len(self.t) else y

        return Prepared(
            *(cut(getattr(self, k)) for k in ("t", "u", "x", "v", "dt", "a", "cos", "sin", "i")), self.run
        )

    def __len__(self) -> int:
        return len(self.t)


@dataclass
class Fit:
    form: str  # "continuous" or "discrete"
    gains: dict[str, float]
    sigma: dict[str, float]
    adj_r2: float
    rmse: float  # of the regressed variable: acceleration (continuous) or velocity (discrete)
    samples: int
    bad: list[str]  # (F4): gains the data cannot separate
    coefficients: list[float]
    warnings: list[str] = field(default_factory=list)
    method: str = "ols"  # "ols" (SysId's least squares) or "iv" (instrumental variables, (F9))

    @property
    def usable(self) -> bool:
        """Finite gains and a positive kA: the model they make can be run."""
        return all(math.isfinite(v) for v in self.gains.values()) and self.gains["kA"] > 0


def _lerp(t_at, t, y):
    """(D1): SysId's Lerp: the segment of the first sample after `t_at` (first or last at the ends)."""
    nxt = np.clip(np.searchsorted(t, t_at, "right"), 1, len(t) - 1)
    prv = nxt - 1
    span = t[nxt] - t[prv]
    w = np.divide(t_at - t[prv], span, out=np.zeros_like(t_at), where=span != 0)
    return y[prv] + (y[nxt] - y[prv]) * w


def _convert(run: Run) -> Prepared:
    t = run.t_voltage[:-1]
    return Prepared(
        t,
        run.voltage[:-1],
        _lerp(t, run.t_position, run.position),
        _lerp(t, run.t_velocity, run.velocity),
        np.diff(run.t_voltage),
        i=np.arange(len(t)),
        run=run,
    )


def noise_floor(v: np.ndarray, window: int = NOISE_WINDOW) -> float:
    """(D2): LinearFilter.MovingAverage starts from zeros, so the first means average fewer samples."""
    step = window // 2
    c = np.concatenate(([0.0], np.cumsum(v)))
    i = np.arange(len(v))
    mean = (c[i + 1] - c[np.maximum(i + 1 - window, 0)]) / window
    dev = v[i[step:] - step] - mean[step:]
    return math.sqrt(float(np.sum(dev**2)) / (len(v) - step)) if len(v) > step else math.inf


def mean_dt(dts: np.ndarray) -> float:
    ok = dts[(dts > 0) & (dts < 0.5)]
    if len(ok) == 0:
        raise ValueError("no time step between 0 and 0.5 s")
    return float(np.mean(ok))


def ka_note(gains: dict[str, float], T: float) -> str | None:
    """A note naming kA when the fitted time constant τ = kA/kV is under the log's mean step T: the
    continuous form's central difference of the approach e^(−t/τ) over ±T is sinh(x)/x times its
    slope (x = T/τ), so its kA falls towards x/sinh x of the plant's; the discrete form's
    kA = kV·T/(−ln α) rests on α = e^(−x) alone, and jitter ±j in a step moves ln α, so kA, by j/T."""
    kA, kV = gains.get("kA", math.nan), gains.get("kV", math.nan)
    if not (math.isfinite(kA) and math.isfinite(kV) and kA > 0 and kV > 0 and T > 0):
        return None
    tau = kA / kV
    if tau >= T:
        return None
    x = T / tau
    return (
        f"kA: the fitted time constant kA/kV = {tau * 1000:.3g} ms is under the log's step {T * 1000:.3g} ms, "
        "so the log barely resolves kA: the continuous form's central difference gives about "
        f"{x / math.sinh(x):.2g} of it, the discrete form's rests on one step's decay e^(-T/τ) = "
        f"{math.exp(-x):.2g} (timestamp jitter ±j moves its kA by j/T); log faster than kA/kV to measure kA"
    )


def _accelerate(d: Prepared, arm: bool, source: str, state: str) -> Prepared:
    """(D4)."""
    if len(d) < 3:
        raise InputError(state, f"has {len(d)} usable samples; the acceleration needs at least 3", source)
    h = mean_dt(d.dt)
    v = d.v
    a = np.empty_like(v)
    a[0] = (v[1] - v[0]) / (2 * h)
    a[1:-1] = (v[2:] - v[:-2]) / (2 * h)
    a[-1] = 0.0
    d.a = a
    d.cos, d.sin = (np.cos(d.x), np.sin(d.x)) if arm else (np.zeros(len(d)), np.zeros(len(d)))
    return d


def prepare(picked: Picked) -> tuple[dict[str, Prepared], dict[str, float]]:
    """(D1)-(D6): the four tests ready to regress, and the threshold, step duration and mean dt.
    Values near the float limit overflow to inf here, harmlessly: the checks below refuse them."""
    with np.errstate(all="ignore"):
        return _prepare(picked)


def _prepare(picked: Picked) -> tuple[dict[str, Prepared], dict[str, float]]:
    src = picked.source
    arm = picked.kind == "arm"
    data = {s: _convert(r) for s, r in picked.runs.items()}
    threshold = min(noise_floor(data[s].v) for s in ("quasistatic-forward", "quasistatic-reverse"))  # (D2)
    if not math.isfinite(threshold):
        raise InputError(
            "log",
            "cannot measure the velocity's noise floor: the quasistatic tests have too few samples "
            f"(more than {NOISE_WINDOW // 2} each) or values too large",
            src,
        )
    max_step = max(r.t_voltage[-1] - r.t_voltage[0] for s, r in picked.runs.items() if "dynamic" in s)
    step_time = 0.0
    out = {}
    for s in ("quasistatic-forward", "quasistatic-reverse", "dynamic-forward", "dynamic-reverse"):
        d = data[s]
        top = float(np.max(np.abs(d.v)))
        if not top > MOVED * threshold:  # noise alone passes (D3): a test must rise clear of it
            raise InputError(
                s,
                f"did not move: its top speed {top:.3g} is within {MOVED:g} times the velocity noise floor "
                f"{threshold:.3g}",
                src,
            )
        if "quasistatic" in s:
            d = d.take((np.abs(d.u) > 0) & (np.abs(d.v) >= MOVING * threshold))  # (D3), (D3')
            if len(d) == 0:
                raise InputError(
                    s,
                    f"has no sample moving faster than {MOVING:g} noise floors {MOVING * threshold:.3g} with a "
                    "voltage applied "
                    "(the mechanism did not move)",
                    src,
                )
        d = _accelerate(d, arm, src, s)
        if "dynamic" in s:  # (D5)
            score = np.sign(d.v) * d.a
            first = int(np.argmax(score))
            keep = np.arange(len(d)) >= first
            d = d.take(keep)
            if step_time == 0.0:
                top = float(np.max(np.abs(d.v)))
                over = np.nonzero(np.abs(d.v) > 0.9 * top)[0]
                if len(over):
                    step_time = min(float(d.t[over[0]] - d.t[0]), max_step)
            if step_time > 0:
                d = d.take(d.t - d.t[0] <= step_time)
        d = d.take(d.a != 0.0)  # (D6)
        if len(d) == 0:
            raise InputError(s, "has no sample left after SysId's filtering", src)
        out[s] = d
    T = mean_dt(np.concatenate([r.dt for r in out.values()]))
    return out, {
        "velocity_threshold": threshold,
        "moving_threshold": MOVING * threshold,
        "step_time": step_time,
        "dt": T,
    }


def _columns(d: Prepared, kind: str, v: np.ndarray) -> list[np.ndarray]:
    cols = [v, d.u, np.copysign(1.0, v)]
    if kind == "elevator":
        cols.append(np.ones(len(v)))
    elif kind == "arm":
        cols += [d.cos, d.sin]
    return cols


def ols(X: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, float]:
    """(F3), (F7): coefficients, their covariance, adjusted R², RMSE."""
    n, p = X.shape
    beta, *_ = np.linalg.lstsq(X, y, rcond=None)
    r = y - X @ beta
    sse = float(r @ r)
    ssto = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - sse / ssto if ssto > 0 else 0.0
    adj = 1.0 - (1.0 - r2) * ((n - 1.0) / (n - p - 1.0)) if n > p + 1 else math.nan
    s2 = sse / (n - p) if n > p else math.inf
    try:
        cov = s2 * np.linalg.inv(X.T @ X)
    except np.linalg.LinAlgError:
        cov = np.full((p, p), math.inf)
    return beta, cov, adj, math.sqrt(sse / n)


def quality(X: np.ndarray, kind: str) -> list[str]:
    """(F4), as CheckOLSDataQuality."""
    lam, vec = np.linalg.eigh(X.T @ X)
    bad: set[int] = set()
    for k in range(len(lam)):
        idx = int(np.argmax(np.abs(vec[:, k])))
        if abs(lam[k] * np.abs(vec[idx, k])) <= QUALITY_THRESHOLD:
            if idx == 1:
                return list(GAIN_NAMES[: 4 if kind == "elevator" else 5 if kind == "arm" else 3])
            bad |= {0: {1}, 2: {0}, 3: {3} if kind == "elevator" else {3, 4}, 4: {3, 4}}[idx]
    return [GAIN_NAMES[i] for i in sorted(bad)]


def _gains_continuous(c, kind: str, T: float) -> dict[str, float]:
    al, be, ga = c[0], c[1], c[2]
    g = {"kS": -ga / be, "kV": -al / be, "kA": 1.0 / be}  # (F2)
    if kind == "elevator":
        g["kG"] = -c[3] / be
    elif kind == "arm":
        g["kG"] = math.hypot(c[3], c[4]) / be
        g["offset"] = math.atan2(c[4], -c[3])
    return g


def _gains_discrete(c, kind: str, T: float) -> dict[str, float]:
    al, be, ga = c[0], c[1], c[2]
    ka = (al - 1.0) * T / (be * math.log(al)) if 0 < al < 1 else math.nan  # (F6)
    g = {"kS": -ga / be, "kV": (1.0 - al) / be, "kA": ka}
    if kind == "elevator":
        g["kG"] = -c[3] / be
    elif kind == "arm":
        g["kG"] = math.hypot(c[3], c[4]) / be
        g["offset"] = math.atan2(c[4], -c[3])
    return g


def _sigmas(fn, c: np.ndarray, cov: np.ndarray, kind: str, T: float) -> dict[str, float]:
    """(F7)."""
    base = fn(c, kind, T)
    J = np.zeros((len(base), len(c)))
    for j in range(len(c)):
        h = 1e-6 * max(abs(c[j]), 1e-9)
        up, dn = c.copy(), c.copy()
        up[j] += h
        dn[j] -= h
        gu, gd = fn(up, kind, T), fn(dn, kind, T)
        J[:, j] = [(gu[k] - gd[k]) / (2 * h) for k in base]
    var = np.einsum("ij,jk,ik->i", J, cov, J)
    return {k: float(math.sqrt(v)) if v >= 0 else math.nan for k, v in zip(base, var)}


def _finish(form, fn, X, y, kind, T, src) -> Fit:
    if len(y) <= X.shape[1]:
        raise InputError(
            "log", f"leaves {len(y)} samples for the {form} fit of {X.shape[1]} coefficients", src
        )
    if not np.all(np.isfinite(X.T @ X)):  # values near the float limit (a hostile log) overflow
        raise InputError("log", f"holds values too large for the {form} fit (its sums overflow)", src)
    try:
        with np.errstate(all="ignore"):
            bad = quality(X, kind)
            c, cov, adj, rmse = ols(X, y)
    except np.linalg.LinAlgError as exc:
        raise InputError("log", f"the {form} fit cannot be computed ({exc})", src) from None
    with np.errstate(all="ignore"):
        gains = {k: float(v) for k, v in fn(c, kind, T).items()}
        sigma = _sigmas(fn, c, cov, kind, T)
    warnings = []
    if bad:
        warnings.append(
            f"{form} fit: SysId's insufficient-data check flags {', '.join(bad)} (it wants 2 steady speeds, "
            "1 acceleration, motion enough for gravity; SysId's analyzer computes it without refusing)"
        )
    broken = [k for k, v in gains.items() if not math.isfinite(v)]
    if broken:
        warnings.append(
            f"{form} fit: no finite {', '.join(broken)} (the data do not fit this form); not used"
        )
    for k in ("kS", "kV", "kG"):
        if gains.get(k, 0.0) < 0:
            warnings.append(f"{form} fit: {k} = {gains[k]:.4g} is negative (it should be ≥ 0)")
    if gains["kA"] <= 0:
        warnings.append(f"{form} fit: kA = {gains['kA']:.4g} is not positive")
    return Fit(form, gains, sigma, adj, rmse, len(y), bad, [float(x) for x in c], warnings)


def fit_continuous(prepared: dict[str, Prepared], kind: str, T: float, source: str) -> Fit:
    """(F1)-(F4), (F7)."""
    X = np.column_stack(
        [np.concatenate(col) for col in zip(*(_columns(d, kind, d.v) for d in prepared.values()))]
    )
    y = np.concatenate([d.a for d in prepared.values()])
    return _finish("continuous", _gains_continuous, X, y, kind, T, source)


def _pairs(prepared: dict[str, Prepared], kind: str):
    """(F5)'s rows: pairs of samples next to each other in the log (a dropped sample breaks a pair):
    the regressors at k, v[k+1], the step h_k, and for each row its test and the sample's index
    in the test's run."""
    rows, ys, steps, where, tests = [], [], [], [], []
    for n, d in enumerate(prepared.values()):
        nxt = np.nonzero(np.isclose(d.t[1:] - d.t[:-1], d.dt[:-1], rtol=1e-9, atol=1e-9))[0]
        e = d.take(nxt)
        rows.append(np.column_stack(_columns(e, kind, e.v)))
        ys.append(d.v[nxt + 1])
        steps.append(d.dt[nxt])
        where.append(e.i)
        tests.append(np.full(len(nxt), n))
    return (
        np.concatenate(rows),
        np.concatenate(ys),
        np.concatenate(steps),
        where,
        np.concatenate(tests),
    )


def fit_discrete(prepared: dict[str, Prepared], kind: str, T: float, source: str, method: str = "iv") -> Fit:
    """(F5), (F6), (F8) where the logged steps differ; by instrumental variables (F9)-(F12) unless
    method = "ols" (SysId's least squares before 2023, kept for the bench: bench/fit_recovery.py)."""
    X, y, h, where, tests = _pairs(prepared, kind)
    fit = _finish("discrete", _gains_discrete, X, y, kind, T, source)
    jittered = np.ptp(h) > 1e-9 * T
    if fit.usable and fit.gains["kV"] > 0 and jittered:
        fit = _per_step(fit, X, y, h, kind)
    if method == "ols":
        return fit
    return _instrumented(fit, prepared, X, y, h, where, tests, kind, T, jittered)


def _simulated(prepared: dict[str, Prepared], kind: str, gains: dict[str, float], where) -> list | None:
    """(F10): each test's velocity as the model with `gains` runs it from the logged voltage alone
    (core/fit/replay.py's exact solution (R1)), at the rows' samples; None if it does not run."""
    from .replay import simulate

    out = []
    for d, k in zip(prepared.values(), where):
        run = d.run
        if run is None:
            return None
        t0 = run.t_voltage[:1]
        q0 = float(_lerp(t0, run.t_position, run.position)[0])
        v0 = float(_lerp(t0, run.t_velocity, run.velocity)[0])
        try:
            _, vs = simulate(kind, gains, run.t_voltage, run.voltage, q0, v0)
        except (OverflowError, ValueError, ZeroDivisionError):
            return None
        if not np.all(np.isfinite(vs)):
            return None
        out.append(vs[k])
    return out


def _covariance(A: np.ndarray, B: np.ndarray, r: np.ndarray, a: np.ndarray, brk: np.ndarray, p: int):
    """(F12): cov = A⁻¹·S·A⁻ᵀ, S = Var(Bᵀ·ε) for (F11)'s error ε_k = e_(k+1) − α_k·e_k of the velocity's
    noise e, taken as stationary with autocovariance c_e(m), m = 0..M (white noise: M = 0; a filter of
    n samples: M = n − 1):
        S = Σ_m c_e(m)·Σ_j (C_j·C_(j+m)ᵀ + C_(j+m)·C_jᵀ)/(1 + [m = 0]),  C_j = B_(j−1) − α_j·B_j
    the coefficient of e_j in Bᵀ·ε (B_(j−1) = 0 at a run's first sample, B_j = 0 past its last), over
    each run of consecutive rows. c_e from the residuals' autocovariance γ̂_ℓ = Σ r_k·r_(k−ℓ)/(n − p)
    within runs, ℓ = 0..M + 1, by least squares through
        γ_ℓ = (1 + ᾱ²)·c_e(ℓ) − ᾱ·(c_e(ℓ − 1) + c_e(ℓ + 1)),  c_e(−m) = c_e(m), c_e(m > M) = 0
    with ᾱ the mean α_k; M + 1 the last lag whose |γ̂_ℓ/γ̂_0| ≥ 2/√n (at most 20) of the first run of
    such lags. Not the free (Newey-West-like) sum Σ γ̂_ℓ·Σ B_k·B_(k−ℓ)ᵀ: with α near 1 its lag terms
    nearly cancel lag 0, so the few-% error of γ̂_1 made σ 3.6 times too large (kS, 2 % noise,
    measured); nor White's r_k² per row, which a test of one or two rows (a fast mechanism's
    dynamic step) fits exactly, making σ(kA) 24 times too small (measured)."""
    n = len(r)
    dof = max(n - p, 1)
    run = np.cumsum(brk)
    gam = [float(r @ r) / dof]
    L = 0
    for lag in range(1, min(21, n)):
        same = run[lag:] == run[:-lag]
        g = float(r[lag:][same] @ r[:-lag][same]) / dof
        if gam[0] <= 0 or abs(g / gam[0]) < 2 / math.sqrt(n):
            break
        gam.append(g)
        L = lag
    Ai = np.linalg.inv(A)
    if L == 0:  # ε itself white: no measurement noise carried from row to row
        return gam[0] * Ai @ (B.T @ B) @ Ai.T, 0
    M = L - 1
    al = float(np.mean(a))
    E = np.zeros((L + 1, M + 1))  # rows ℓ = 0..L, columns c_e(0..M)
    for ell in range(L + 1):
        for m, w in ((ell, 1 + al * al), (ell - 1, -al), (ell + 1, -al)):
            if abs(m) <= M:
                E[ell, abs(m)] += w
    ce = np.linalg.lstsq(E, np.array(gam[: L + 1]), rcond=None)[0]
    # C: the noise samples of each run (its rows and one more), row k's pair at base_k, base_k + 1
    base = np.arange(n) + run - 1
    C = np.zeros((n + int(run[-1]), B.shape[1]))
    np.add.at(C, base + 1, B)
    np.add.at(C, base, -a[:, None] * B)
    crun = np.zeros(len(C), dtype=int)
    np.add.at(crun, base, run)
    crun[base + 1] = run
    S = ce[0] * (C.T @ C)
    for m in range(1, M + 1):
        same = crun[m:] == crun[:-m]
        G = C[m:][same].T @ C[:-m][same]
        S += ce[m] * (G + G.T)
    w, V = np.linalg.eigh(S)
    S = (V * np.maximum(w, 0.0)) @ V.T
    return Ai @ S @ Ai.T, L


def _instrumented(fit, prepared, X, y, h, where, tests, kind, T, jittered) -> Fit:
    """(F9)-(F12): the discrete form by instrumental variables, from the least-squares fit."""
    if not (fit.usable and fit.gains["kV"] > 0):
        fit.warnings.append(
            "discrete fit: SysId's least squares give no model that runs, so no instruments: "
            "its gains are shown, biased by the velocity's noise"
        )
        return fit
    gains = dict(fit.gains)
    best = None
    idx = np.concatenate(where)
    brk = np.ones(len(y), dtype=bool)  # row k starts a run of consecutive pairs
    brk[1:] = (tests[1:] != tests[:-1]) | (idx[1:] != idx[:-1] + 1)
    for _ in range(ITERATIONS):  # (F10)'s refinement
        sim = _simulated(prepared, kind, gains, where)
        if sim is None:
            break
        Z = X.copy()
        Z[:, 0] = np.concatenate(sim)
        Z[:, 2] = np.copysign(1.0, X[:, 1])  # (F10): sgn u, the logged (noise-free) voltage's
        a = np.exp(-h * gains["kV"] / gains["kA"])
        B = _adjoint(_whiten(Z, a, brk), a, brk) if WHITEN else Z  # (F13)
        got = _iv(fit, X, y, h, B, np.exp(-h * gains["kV"] / gains["kA"]), brk, kind, T, jittered)
        if got is None:
            break
        change = max(abs(got.gains[k] - gains[k]) / max(abs(gains[k]), 1e-12) for k in gains)
        best, gains = got, dict(got.gains)
        if change < 1e-6:
            break
    if best is None:
        fit.warnings.append(
            "discrete fit: the instrumental-variables estimate could not be computed (its model does not "
            "run on the logged voltage); SysId's least squares shown, biased by the velocity's noise"
        )
        return fit
    return best


def _whiten(M: np.ndarray, a: np.ndarray, brk: np.ndarray) -> np.ndarray:
    """(F13): w_k = m_k + a_k·w_(k−1), restarted (w = m) where brk; the inverse of (F11)'s e_(k+1) − α_k·e_k."""
    out = np.array(M, dtype=float, copy=True)
    for k in range(1, len(out)):
        if not brk[k]:
            out[k] += a[k] * out[k - 1]
    return out


def _adjoint(M: np.ndarray, a: np.ndarray, brk: np.ndarray) -> np.ndarray:
    """(F13): the transpose of _whiten: b_k = m_k + a_(k+1)·b_(k+1) unless row k+1 starts a run."""
    out = np.array(M, dtype=float, copy=True)
    for k in range(len(out) - 2, -1, -1):
        if not brk[k + 1]:
            out[k] += a[k + 1] * out[k + 1]
    return out


def _iv(fit, X, y, h, Z, a, brk, kind, T, jittered) -> Fit | None:
    """(F9), (F11), (F12) for the instruments Z; None when it cannot be solved."""
    with np.errstate(all="ignore"):
        try:
            A = Z.T @ X
            c = np.linalg.solve(A, Z.T @ y)  # (F9)
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(c)):
            return None
        gains = {k: float(v) for k, v in _gains_discrete(c, kind, T).items()}
        r = y - X @ c
        if jittered and all(math.isfinite(v) for v in gains.values()) and gains["kV"] > 0 and gains["kA"] > 0:
            return _per_step_iv(fit, X, y, h, Z, a, brk, kind, gains)
        try:
            cov, L = _covariance(A, Z, r, a, brk, X.shape[1])
        except np.linalg.LinAlgError:
            return None
        sigma = _sigmas(_gains_discrete, c, cov, kind, T)
    if not (all(math.isfinite(v) for v in gains.values()) and gains["kA"] > 0):
        return None
    return _with(fit, gains, sigma, r, y, X.shape[1], [float(x) for x in c], L)


def _with(fit: Fit, gains, sigma, r, y, p, coefficients, L) -> Fit:
    n = len(y)
    sse = float(r @ r)
    ssto = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - sse / ssto if ssto > 0 else 0.0
    warnings = [w for w in fit.warnings if "is negative" not in w and "not positive" not in w]
    warnings = [w.replace("discrete fit: each pair", "discrete fit (IV): each pair") for w in warnings]
    for k in ("kS", "kV", "kG"):
        if gains.get(k, 0.0) < 0:
            warnings.append(f"discrete fit: {k} = {gains[k]:.4g} is negative (it should be ≥ 0)")
    return Fit(
        "discrete",
        gains,
        sigma,
        1.0 - (1.0 - r2) * ((n - 1.0) / (n - p - 1.0)) if n > p + 1 else math.nan,
        math.sqrt(sse / n),
        n,
        fit.bad,
        coefficients,
        warnings,
        method="iv",
    )


def _per_step_model(X: np.ndarray, y: np.ndarray, h: np.ndarray, kind: str):
    """(F8)'s residual and its Jacobian in (kS, kV, kA (, kG (, offset)))."""
    v, u, sg = X[:, 0], X[:, 1], X[:, 2]

    def gravity(q):
        if kind == "elevator":
            return q[3]
        if kind == "arm":  # (F2)'s cos θ, sin θ columns: kG·cos(θ + offset)
            return q[3] * (X[:, 3] * math.cos(q[4]) - X[:, 4] * math.sin(q[4]))
        return 0.0

    def residual(q):
        a = np.exp(-h * q[1] / q[2])
        return a * v + (1 - a) / q[1] * (u - q[0] * sg - gravity(q)) - y

    def jacobian(q):  # analytic: a 10-minute log's pairs in tens of ms, not the half second of differences
        kV, kA = q[1], q[2]
        a = np.exp(-h * kV / kA)
        w = u - q[0] * sg - gravity(q)
        k = (1 - a) / kV
        J = np.empty((len(y), len(q)))
        J[:, 0] = -k * sg
        J[:, 1] = -h / kA * a * (v - w / kV) - k / kV * w
        J[:, 2] = h * kV / kA**2 * a * (v - w / kV)
        if kind == "elevator":
            J[:, 3] = -k
        elif kind == "arm":
            c, sn = X[:, 3], X[:, 4]
            J[:, 3] = -k * (c * math.cos(q[4]) - sn * math.sin(q[4]))
            J[:, 4] = -k * q[3] * (-c * math.sin(q[4]) - sn * math.cos(q[4]))
        return J

    return residual, jacobian


def _names(kind: str) -> list[str]:
    return ["kS", "kV", "kA"] + (["kG"] if kind == "elevator" else ["kG", "offset"] if kind == "arm" else [])


def _arm_gains(gains: dict[str, float], kind: str) -> dict[str, float]:
    if kind == "arm" and gains["kG"] < 0:  # the same gravity, kG ≥ 0 as (F2) gives it
        gains["kG"], gains["offset"] = -gains["kG"], gains["offset"] + math.pi
    if kind == "arm":
        gains["offset"] = math.remainder(gains["offset"], 2 * math.pi)
    return gains


def _per_step_iv(fit, X, y, h, Z, a, brk, kind, start) -> Fit | None:
    """(F8) by instrumental variables: the p equations Zᵀ·r(q) = 0 of (F9) with (F8)'s residual r,
    solved (scipy's least_squares, each instrument scaled to unit RMS) from the linear (F9)'s gains;
    covariance (F12) with A = Zᵀ·J."""
    from scipy.optimize import least_squares

    residual, jacobian = _per_step_model(X, y, h, kind)
    names = _names(kind)
    scale = np.where((s := np.sqrt(np.mean(Z**2, axis=0))) > 0, s, 1.0)
    Zs = Z / scale
    q0 = np.array([start[k] for k in names])
    try:
        with np.errstate(all="ignore"):
            sol = least_squares(
                lambda q: Zs.T @ residual(q),
                q0,
                jac=lambda q: Zs.T @ jacobian(q),
                x_scale=np.maximum(np.abs(q0), 1e-12),
                xtol=1e-12,
                ftol=1e-12,
            )
            q = sol.x
            r = -residual(q)  # y − ŷ
            J = jacobian(q)
            cov, L = _covariance(Zs.T @ J, Zs, r, a, brk, len(names))
    except (ValueError, np.linalg.LinAlgError):
        return None
    if not np.all(np.isfinite(q)) or q[1] <= 0 or q[2] <= 0:
        return None
    gains = _arm_gains(dict(zip(names, (float(x) for x in q))), kind)
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    return _with(fit, gains, {k: float(x) for k, x in zip(names, sd)}, r, y, len(names), fit.coefficients, L)


def _per_step(fit: Fit, X: np.ndarray, y: np.ndarray, h: np.ndarray, kind: str) -> Fit:
    """(F8): (F5) with each pair's own logged step h_k, the exact zero-order hold of (F1):
        v[k+1] = α_k·v[k] + (1 − α_k)/kV·(u[k] − kS·sgn v[k] − g_k),  α_k = e^(−h_k·kV/kA),
        g_k = kG (elevator), kG·cos(θ_k + offset) (arm), 0,
    by nonlinear least squares (scipy) from (F6)'s gains; with one step it is (F5) itself. The mean
    step T̄ in (F6) misplaces kA by up to the jitter j over T̄ (each pair's ln α_k is off by
    (h_k − T̄)/τ), which the few pairs after a fast step do not average out (0.5 ms on 5 ms: kA −8 %
    measured). Covariance s²·(JᵀJ)⁻¹ at the solution, s² = SSE/(n − p)."""
    from scipy.optimize import least_squares

    residual, jacobian = _per_step_model(X, y, h, kind)
    names = _names(kind)
    q0 = np.array([fit.gains[k] for k in names])
    try:
        with np.errstate(all="ignore"):
            r = least_squares(
                residual, q0, jac=jacobian, x_scale=np.maximum(np.abs(q0), 1e-12), xtol=1e-12, ftol=1e-12
            )
            J = r.jac
            n, p = J.shape
            sse = float(r.fun @ r.fun)
            cov = sse / (n - p) * np.linalg.inv(J.T @ J)
    except (ValueError, np.linalg.LinAlgError):
        r = None
    if r is None or not np.all(np.isfinite(r.x)) or r.x[1] <= 0 or r.x[2] <= 0:
        fit.warnings.append(
            "discrete fit: the logged steps differ but the fit with each step did not converge"
        )
        return fit
    ssto = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - sse / ssto if ssto > 0 else 0.0
    gains = _arm_gains(dict(zip(names, (float(x) for x in r.x))), kind)
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    fit.gains = gains
    fit.sigma = {k: float(x) for k, x in zip(names, sd)}
    fit.adj_r2 = 1.0 - (1.0 - r2) * ((n - 1.0) / (n - p - 1.0)) if n > p + 1 else math.nan
    fit.rmse = math.sqrt(sse / n)
    fit.warnings.append(
        f"discrete fit: each pair with its own logged step ({h.min() * 1000:.3g}-{h.max() * 1000:.3g} ms), "
        "the zero-order hold exact for each"
    )
    return fit
