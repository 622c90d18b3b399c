"""core/sim/small_math.py against scipy, the functions it replaces on a move's first solve:
lambertw, expm (zero-order hold), solve_discrete_are, fractional_matrix_power, and the whole LQR
as motion.lqr computed it with them."""

import math
import subprocess
import sys

import numpy as np
import pytest
from scipy.linalg import expm, fractional_matrix_power, solve_discrete_are
from scipy.special import lambertw

from gearhead.core.sim import motion
from gearhead.core.sim.small_math import dare, lambert_w0, matrix_power_2x2, zero_order_hold

RNG = np.random.default_rng(20261127)


def test_lambert_w0_is_scipys_principal_branch():
    xs = np.concatenate(
        [
            -np.exp(-(np.linspace(0.01, 60, 400) + 1)),  # the arguments (C2) passes: D from 0.01 up
            -np.logspace(-300, math.log10(0.36), 200),
            [-1 / math.e + 1e-6, -0.3, -0.25, -0.2500001, -1e-320, -0.0],
        ]
    )
    for x in xs:
        want = float(lambertw(x).real)
        got = lambert_w0(float(x))
        # W's own conditioning: x known to half an ulp moves W by that over (e^W·(1 + W)), which
        # grows without bound at the branch point (x = -1/e + 1e-6: 3e-14)
        conditioning = 2.3e-16 * abs(x) / (math.exp(want) * (1 + want))
        assert abs(got - want) <= 3e-15 * abs(want) + 2 * conditioning, (x, got, want)
    assert lambert_w0(-1 / math.e) == pytest.approx(-1, abs=1e-7)  # the branch point: √ε-conditioned
    with pytest.raises(ValueError):
        lambert_w0(-0.5)
    with pytest.raises(ValueError):
        lambert_w0(0.1)


@pytest.mark.parametrize("a", [0.0, 1e-9, 1e-5, 2e-4, 0.01, 1.0, 30.0, 400.0])
@pytest.mark.parametrize("dt", [0.001, 0.02, 0.1])
def test_zero_order_hold_is_the_matrix_exponential(a, dt):
    b = 3.7
    M = np.zeros((3, 3))
    M[0, 1], M[1, 1], M[1, 2] = 1.0, -a, b
    phi = expm(M * dt)
    Ad, Bd = zero_order_hold(a, b, dt)
    np.testing.assert_allclose(Ad, phi[:2, :2], rtol=1e-12, atol=0)
    np.testing.assert_allclose(Bd, phi[:2, 2:], rtol=1e-12, atol=0)


def _cases(n: int):
    for _ in range(n):
        kV = 10 ** RNG.uniform(-2, 1.5)
        kA = 10 ** RNG.uniform(-3.5, 0)
        yield (
            kV,
            kA,
            10 ** RNG.uniform(-3, -0.5),  # q_position
            10 ** RNG.uniform(-2, 0.5),  # q_velocity
            RNG.uniform(1, 12),  # r_volts
            RNG.choice([0.005, 0.01, 0.02, 0.05]),  # dt
        )


def test_dare_matches_scipys_riccati_solution():
    for kV, kA, qp, qv, r, dt in _cases(150):
        Ad, Bd = zero_order_hold(kV / kA, 1 / kA, dt)
        Q, R = np.diag([1 / qp**2, 1 / qv**2]), np.array([[1 / r**2]])
        want = solve_discrete_are(Ad, Bd, Q, R)
        got = dare(Ad, Bd, Q, R)

        def residual(S):
            gain = np.linalg.solve(R + Bd.T @ S @ Bd, Bd.T @ S @ Ad)
            return np.max(np.abs(Ad.T @ S @ Ad - Ad.T @ S @ Bd @ gain + Q - S))

        assert residual(got) <= 4 * residual(want) + 1e-15 * np.max(np.abs(want))  # as exact as scipy's
        np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-12 * np.max(np.abs(want)))


def test_matrix_power_matches_scipys_fractional_power():
    for _ in range(150):
        M = RNG.normal(size=(2, 2)) * 10 ** RNG.uniform(-1, 1)
        t = RNG.uniform(0, 1.5)
        want = np.real(fractional_matrix_power(M, t))
        got = matrix_power_2x2(M, t)
        np.testing.assert_allclose(got, want, rtol=1e-11, atol=1e-12 * np.max(np.abs(want)))
    for M in (np.eye(2) * 0.5, np.array([[0.5, 1.0], [0.0, 0.5]]), np.zeros((2, 2))):  # scipy's own path
        np.testing.assert_allclose(matrix_power_2x2(M, 0.3), np.real(fractional_matrix_power(M, 0.3)))


def _lqr_with_scipy(kV, kA, q_position, q_velocity, r_volts, dt, delay, closed_loop=False):
    """motion.lqr as it was written on scipy (before core/sim/small_math.py); with closed_loop,
    also A_d − B_d·K (whose fractional power the latency compensation takes)."""
    A = np.array([[0.0, 1.0], [0.0, -kV / kA]])
    B = np.array([[0.0], [1.0 / kA]])
    M = np.zeros((3, 3))
    M[:2, :2], M[:2, 2:] = A, B
    phi = expm(M * dt)
    Ad, Bd = phi[:2, :2], phi[:2, 2:]
    Q = np.diag([1.0 / q_position**2, 1.0 / q_velocity**2])
    R = np.array([[1.0 / r_volts**2]])
    S = solve_discrete_are(Ad, Bd, Q, R)
    K = np.linalg.solve(Bd.T @ S @ Bd + R, Bd.T @ S @ Ad)
    closed = Ad - Bd @ K
    if delay > 0:
        K = K @ np.real(fractional_matrix_power(closed, delay / dt))
    gains = (float(K[0, 0]), float(K[0, 1]))
    return (gains, closed) if closed_loop else gains


def _lqr_mpmath(kV, kA, q_position, q_velocity, r_volts, dt, delay):
    """The same gains at 50 digits (mpmath): Newton's steps on the Riccati equation from scipy's
    solution, each Stein equation by doubling, and the latency power by the eigenvalues."""
    import mpmath as mp

    with mp.workdps(50):
        a, b, dt_, t = mp.mpf(kV) / mp.mpf(kA), 1 / mp.mpf(kA), mp.mpf(dt), mp.mpf(delay) / mp.mpf(dt)
        decay = (1 - mp.exp(-a * dt_)) / a
        A = mp.matrix([[1, decay], [0, mp.exp(-a * dt_)]])
        B = mp.matrix([[b * (dt_ - decay) / a], [b * decay]])
        Q = mp.diag([1 / mp.mpf(q_position) ** 2, 1 / mp.mpf(q_velocity) ** 2])
        R = mp.matrix([[1 / mp.mpf(r_volts) ** 2]])
        Ad, Bd = np.array(A.tolist(), dtype=float), np.array(B.tolist(), dtype=float)
        S = mp.matrix(
            solve_discrete_are(Ad, Bd, np.diag([1 / q_position**2, 1 / q_velocity**2]), [[1 / r_volts**2]])
        )
        for _ in range(5):
            K = mp.inverse(R + B.T * S * B) * (B.T * S * A)
            closed, S = A - B * K, Q + K.T * R * K
            power = closed
            for _ in range(80):
                S, power = S + power.T * S * power, power * power
        K = mp.inverse(R + B.T * S * B) * (B.T * S * A)
        if delay > 0:
            closed = A - B * K
            values, vectors = mp.eig(closed)
            K = K * vectors * mp.diag([v**t for v in values]) * mp.inverse(vectors)
        return float(mp.re(K[0, 0])), float(mp.re(K[0, 1]))


def _gain_errors(reference, cases, delays=(0.0, 0.001, 0.005, 0.02)):
    """Each gain's error against `reference`, relative to the gain (or to 1e-3 of the undelayed
    gains where the closed loop is nearly deadbeat: its fractional power is then noise, kP ~ 1e-14
    against ~600 undelayed), and the latency power's own conditioning t·ε·|M|/|λ_min| (a closed-loop
    eigenvalue of 1e-8 and t = 0.1: 2.4e-8)."""
    for case in cases:
        (undelayed, closed) = _lqr_with_scipy(*case, 0.0, closed_loop=True)
        scale = max(abs(k) for k in undelayed)
        smallest = min(abs(np.linalg.eigvals(closed)))
        for delay in delays:
            t = delay / case[-1]
            conditioning = t * 2.2e-16 * np.max(np.abs(closed)) / max(smallest, 1e-300)
            want, got = reference(*case, delay), motion.lqr.__wrapped__(*case, delay)
            for g, w in zip(got, want):
                yield abs(g - w) / max(abs(w), 1e-3 * scale), conditioning, (case, delay, got, want)


def test_lqr_gains_match_50_digit_gains_to_1e_12():
    for error, conditioning, case in _gain_errors(_lqr_mpmath, list(_cases(30))):
        assert error <= 1e-12 + 10 * conditioning, case


def test_lqr_gains_match_the_former_scipy_computation():
    """scipy's own gains carry up to ~2e-12 of rounding (against 50 digits, where ours are within
    1e-14 on the same case): agreement to 1e-10, and to 1e-12 on most (93 % of 2400 gains)."""
    errors = list(_gain_errors(_lqr_with_scipy, list(_cases(120))))
    for error, conditioning, case in errors:
        assert error <= 1e-10 + 10 * conditioning, case
    assert sum(error <= 1e-12 for error, _, _ in errors) >= 0.9 * len(errors)


def test_an_elevator_solve_in_closed_form_imports_no_scipy():
    """(The arm's move is integrated: its event location still loads scipy.optimize.brentq.)"""
    code = (
        "import sys; from gearhead.core.model import solve; "
        "solve('elevator', {}); solve('elevator', {'sensor_delay': '5 ms'}); "
        "print(sorted(m for m in sys.modules if m.split('.')[0] == 'scipy')[:3])"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
