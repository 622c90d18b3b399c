"""The discrete form by instrumental variables (ours; issue 44): what `gearhead fit` shows as
"discrete". core/fit/sysid_fit.py's (F5), (F6), (F8) are SysId's discrete form, fitted there by least
squares (sysid_fit.fit_discrete, kept to compare with SysId); the continuous form is SysId's own.

the log holds y_k = v_k + e_k, e the velocity's noise, so (F5)/(F8) reads
    y_(k+1) = α_k·y_k + β_k·u_k + … + ε_k,  ε_k = e_(k+1) − α_k·e_k                      (F11)
and its regressor y_k holds e_k, which ε_k holds too (E[y_k·ε_k] = −α·σ²): least squares
shrink α to α·S/(S + σ²) (S: the noise-free v's variance beyond the other regressors), so kA
= kV·T/(−ln α) falls: 12-17 % at 0.5 % noise, 69-91 % at 2 % (bench/fit_recovery.py, worst of 5 seeds per log). Any
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

import numpy as np

from .replay import simulate
from .sysid_fit import (
    Fit,
    Prepared,
    _arm_gains,
    _gains_discrete,
    _lerp,
    _names,
    _pairs,
    _per_step_model,
    _sigmas,
)
from .sysid_fit import fit_discrete as least_squares_fit

WHITEN = True  # (F13); False: (F9) with the instruments as they are (to compare)
ITERATIONS = 4  # (F10): instruments from the previous estimate's model, at most this many times


def fit_discrete(prepared: dict[str, Prepared], kind: str, T: float, source: str) -> Fit:
    """(F5), (F6), (F8) by instrumental variables (F9)-(F13), from SysId's least squares."""
    fit = least_squares_fit(prepared, kind, T, source)
    X, y, h, where, tests = _pairs(prepared, kind)
    return _instrumented(fit, prepared, X, y, h, where, tests, kind, T, np.ptp(h) > 1e-9 * T)


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


def _simulated(prepared: dict[str, Prepared], kind: str, gains: dict[str, float], where) -> list | None:
    """(F10): each test's velocity as the model with `gains` runs it from the logged voltage alone
    (core/fit/replay.py's exact solution (R1)), at the rows' samples; None if it does not run."""
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
