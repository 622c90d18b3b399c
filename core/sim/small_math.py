"""Small closed forms that spare a move's first solve scipy's import (~0.4 s, scipy.special and
scipy.linalg alike: most of it is scipy's shared base): Lambert's W₀ for the closed-form move (C2)
and the 2-state LQR of core/sim/motion.py `lqr`. Each falls back to scipy where its own accuracy
would not be certain; tests/test_small_math.py checks both against scipy to 1e-12.

    W₀(x), −1/e ≤ x < 0: Halley's iteration on w·e^w = x (W1), started from the branch-point
        series w = −1 + p − p²/3 + 11p³/72, p = √(2(e·x + 1)), for x < −1/4, else from the
        Maclaurin series w = x − x² + 3x³/2                                                      (W2)
    Zero-order hold of ẋ = [[0, 1], [0, −a]]·x + [0, b]·u over dt (E = e^{−a·dt}):
        A_d = [[1, (1 − E)/a], [0, E]],  B_d = b·[(dt − (1 − E)/a)/a, (1 − E)/a]               (L1)
        (series in a·dt below 1e-4, where (1 − E)/a and (dt − (1 − E)/a)/a cancel)
    Discrete algebraic Riccati equation S = AᵀSA − AᵀSB(R + BᵀSB)⁻¹BᵀSA + Q by the structured
        doubling algorithm (Chu, Fan, Lin 2005), quadratically convergent: A₀ = A, G₀ = BR⁻¹Bᵀ,
        H₀ = Q; W = I + G·H;  A' = A·W⁻¹·A,  G' = G + A·W⁻¹·G·Aᵀ,  H' = H + Aᵀ·H·W⁻¹·A → S     (L2)
    then two Newton (Hewer) steps: K = (R + BᵀSB)⁻¹BᵀSA, A_c = A − BK, S' = A_cᵀS'A_c + Q + KᵀRK  (L4)
    Principal power Mᵗ of a 2×2 matrix with eigenvalues λ₁ ≠ λ₂ (Sylvester):
        Mᵗ = (λ₁ᵗ·(M − λ₂I) − λ₂ᵗ·(M − λ₁I))/(λ₁ − λ₂),  λᵗ = e^{t·log λ} (principal log)        (L3)
"""

from __future__ import annotations

import math

_BRANCH = -1 / math.e


def lambert_w0(x: float) -> float:
    """The principal branch W₀(x) for −1/e ≤ x ≤ 0 (W1, W2)."""
    if not (_BRANCH - 1e-17 <= x <= 0):
        raise ValueError(f"lambert_w0 takes −1/e ≤ x ≤ 0, got {x!r}")
    if x == 0:
        return 0.0
    if x < -0.25:
        p = math.sqrt(max(2 * (math.e * x + 1), 0.0))
        w = -1 + p - p * p / 3 + 11 * p**3 / 72  # (W2)
    else:
        w = x - x * x + 1.5 * x**3  # (W2)
    for _ in range(40):  # (W1): cubic convergence; a handful of steps from these starts
        ew = math.exp(w)
        f = w * ew - x
        if f == 0 or w == -1:
            break
        step = f / (ew * (w + 1) - (w + 2) * f / (2 * w + 2))
        w -= step
        if abs(step) <= 4e-16 * abs(w):
            break
    return w


def zero_order_hold(a: float, b: float, dt: float):
    """A_d (2×2) and B_d (2×1) of ẋ = [[0, 1], [0, −a]]·x + [0, b]·u held over dt (L1)."""
    import numpy as np

    s = a * dt
    if abs(s) < 1e-4:  # series: (1 − E)/a = dt(1 − s/2 + s²/6 − s³/24), (dt − (1 − E)/a)/a likewise
        decay_integral = dt * (1 - s / 2 + s * s / 6 - s**3 / 24)
        double_integral = dt * dt * (0.5 - s / 6 + s * s / 24 - s**3 / 120)
    else:
        decay_integral = -math.expm1(-s) / a
        double_integral = (dt - decay_integral) / a
    Ad = np.array([[1.0, decay_integral], [0.0, math.exp(-s)]])
    Bd = np.array([[b * double_integral], [b * decay_integral]])
    return Ad, Bd


def dare(A, B, Q, R):
    """S of the discrete algebraic Riccati equation by structured doubling (L2); scipy's
    solve_discrete_are if doubling does not converge in 64 steps."""
    import numpy as np

    I = np.eye(A.shape[0])
    G = B @ np.linalg.solve(R, B.T)
    H = Q.astype(float)
    Ak = A.astype(float)
    for _ in range(64):
        W = I + G @ H
        WA = np.linalg.solve(W, Ak)
        WG = np.linalg.solve(W, G)
        H_next = H + Ak.T @ H @ WA
        G = G + Ak @ WG @ Ak.T
        Ak = Ak @ WA
        if not np.all(np.isfinite(H_next)):
            break
        done = np.max(np.abs(H_next - H)) <= 1e-16 * np.max(np.abs(H_next))
        H = H_next
        if done:
            return _hewer((H + H.T) / 2, A, B, Q, R)
    from scipy.linalg import solve_discrete_are

    return solve_discrete_are(A, B, Q, R)


def _hewer(S, A, B, Q, R, steps: int = 2):
    """Newton's (Hewer's) steps on the Riccati equation from S (L4): the doubling's sums carry
    rounding of the largest terms (3e-11 of S where Q spans 1e6); each step solves the Stein
    equation S' = A_cᵀ·S'·A_c + Q + KᵀRK exactly for the gain of S, K = (R + BᵀSB)⁻¹BᵀSA,
    A_c = A − BK, and converges quadratically to the stabilising solution."""
    import numpy as np

    n = A.shape[0]
    for _ in range(steps):
        K = np.linalg.solve(R + B.T @ S @ B, B.T @ S @ A)
        Ac = A - B @ K
        rhs = Q + K.T @ R @ K
        # vec(S') = (I − A_cᵀ ⊗ A_cᵀ)⁻¹·vec(rhs), row-major vec
        S = np.linalg.solve(np.eye(n * n) - np.kron(Ac.T, Ac.T), rhs.reshape(-1)).reshape(n, n)
        S = (S + S.T) / 2
    return S


def matrix_power_2x2(M, t: float):
    """The principal power Mᵗ of a real 2×2 matrix (L3), its real part (as scipy's
    fractional_matrix_power, then np.real, gave); scipy's for eigenvalues that nearly coincide
    or vanish, where (L3) would lose digits."""
    import cmath

    import numpy as np

    tr, det = M[0, 0] + M[1, 1], M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
    root = cmath.sqrt(tr * tr / 4 - det)
    l1 = tr / 2 + root if tr >= 0 else tr / 2 - root  # the larger in size: no cancellation
    l2 = det / l1 if l1 != 0 else tr / 2 - root  # λ₁·λ₂ = det (the other by subtraction would cancel)
    scale = max(abs(l1), abs(l2))
    if scale == 0 or min(abs(l1), abs(l2)) <= 1e-8 * scale or abs(l1 - l2) <= 1e-3 * scale:
        from scipy.linalg import fractional_matrix_power

        return np.real(fractional_matrix_power(M, t))
    p1, p2 = cmath.exp(t * cmath.log(l1)), cmath.exp(t * cmath.log(l2))
    I = np.eye(2)
    out = (p1 * (M - l2 * I) - p2 * (M - l1 * I)) / (l1 - l2)  # (L3)
    return np.real(out)
