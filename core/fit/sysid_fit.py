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
The discrete form by instrumental variables, what `gearhead fit` shows as "discrete", is ours:
core/fit/iv.py (F9)-(F13); fit_discrete here is SysId's discrete least squares.
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
    run: Run | None = None  # the test's logged samples (core/fit/iv.py's instruments (F10))

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
    method: str = "ols"  # "ols" (SysId's least squares) or "iv" (core/fit/iv.py's instrumental variables)

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


def fit_discrete(prepared: dict[str, Prepared], kind: str, T: float, source: str) -> Fit:
    """(F5), (F6): SysId's discrete least squares over pairs of samples next to each other in the
    log; then (F8) where the logged steps differ. Biased by the velocity's noise (core/fit/iv.py
    (F11)): `gearhead fit` shows core.fit.iv.fit_discrete, which starts from it."""
    X, y, h, _, _ = _pairs(prepared, kind)
    fit = _finish("discrete", _gains_discrete, X, y, kind, T, source)
    if fit.usable and fit.gains["kV"] > 0 and np.ptp(h) > 1e-9 * T:
        return _per_step(fit, X, y, h, kind)
    return fit


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
