"""Hard cases for the trebuchet scene: each numerically delicate, each against an mpmath
quadrature or a closed form worked out independently of the scene's code."""

import math

import mpmath as mp
import pytest

from gearhead.core.model import solve
from gearhead.core.sim import trebuchet as tb

mp.mp.dps = 40
DEG = math.pi / 180
SEED = dict(M=500, k=2, m=50, L=15, a=0.25, h=4, m_p=5, l=5, g=9.81)


def arm_time(I, C, phi_a, phi_b, w_a2=0):
    """∫ dφ/ω from φ_a to φ_b for the arm alone: ω² = ω_a² + 2·C·(sin φ − sin φ_a)/I (mpmath)."""
    I, C, phi_a, phi_b = map(mp.mpf, (I, C, phi_a, phi_b))
    # φ = φ_a + u² removes the 1/sqrt(φ − φ_a) singularity of starting from rest: dφ/ω = 2u·du/ω;
    # sin φ − sin φ_a = 2·cos(φ_a + u²/2)·sin(u²/2), free of cancellation for tiny u
    w = lambda u: mp.sqrt(w_a2 + 4 * C * mp.cos(phi_a + u * u / 2) * mp.sin(u * u / 2) / I)  # noqa: E731
    U = mp.sqrt(phi_b - phi_a)
    return mp.quad(lambda u: 2 * u / w(u), [0, U / 100, U / 10, U])


def cup_machine_constants(M, m, L, a, m_p, k, g):
    """(I with the projectile in the cup, its moment C, I′ and C′ after release), by hand from
    seed 1.2: I = m·L²·(1/12 + (1/2 − a)²) + M·(aL)² + M·k² + m_p·((1 − a)L)²."""
    mpf = mp.mpf
    M, m, L, a, m_p, k, g = map(mpf, (M, m, L, a, m_p, k, g))
    I2 = m * L**2 * (mpf(1) / 12 + (mpf(1) / 2 - a) ** 2) + M * (a * L) ** 2 + M * k**2
    C2 = g * (M * a * L - m * (L / 2 - a * L))
    R = (1 - a) * L
    return I2 + m_p * R**2, C2 - g * m_p * R, I2, C2


def test_arm_starting_next_to_its_unstable_equilibrium():
    """h = 0.9999·(1 − a)·L: the arm starts 0.81° from hanging straight down, where the moment
    (∝ cos φ0 ≈ 0.014) almost vanishes. The solver's first step sees a near-zero derivative and the
    swing creeps away for a long time before it accelerates; time to vertical is a log-singular
    integral. Reference: mpmath quadrature of ∫ dφ/ω, before and after release (β = 45°)."""
    R = 0.75 * 15
    h = 0.9999 * R
    p = tb.Machine(**{**SEED, "h": h}, sling=False)
    s = tb.swing(p, 45 * DEG, False, 1e-10)
    I, C, I2, C2 = cup_machine_constants(500, 50, 15, 0.25, 5, 2, 9.81)
    phi0 = mp.asin(-mp.mpf(h) / R)
    phi_r = mp.pi / 4  # the cup's velocity is ⟂ the arm: 45° forward-up at φ = 45°
    t_r = arm_time(I, C, phi0, phi_r)
    w_r2 = 2 * C * (mp.sin(phi_r) - mp.sin(phi0)) / I
    t_v = t_r + arm_time(I2, C2, phi_r, mp.pi / 2, w_r2)
    w_v = mp.sqrt(w_r2 + 2 * C2 * (1 - mp.sin(phi_r)) / I2)
    assert s.release[0] == pytest.approx(float(t_r), rel=1e-7)
    assert s.vertical[0] == pytest.approx(float(t_v), rel=1e-7)
    assert s.vertical[1] == pytest.approx(float(w_v), rel=1e-8)


def test_nearly_balanced_arm_swings_for_minutes():
    """M·r exceeds m·s + m_p·R by 1.5e-4 of either: the driving moment is a difference of nearly
    equal moments (0.37 N·m out of 2391 N·m), the swing lasts minutes and the step-size control
    must stretch over a very slow motion without drifting. Reference: mpmath quadrature."""
    M = 65.01  # M·r = 243.7875 vs m·s + m_p·R = 187.5 + 56.25 = 243.75
    p = tb.Machine(**{**SEED, "M": M}, sling=False)
    s = tb.swing(p, 45 * DEG, False, 1e-10)
    I, C, I2, C2 = cup_machine_constants(M, 50, 15, 0.25, 5, 2, 9.81)
    assert float(C) == pytest.approx(
        9.81 * 0.0375, rel=1e-9
    )  # by hand: 9.81·(243.7875 − 243.75) = 0.367875 N·m
    phi0 = mp.asin(-mp.mpf(4) / 11.25)
    t_r = arm_time(I, C, phi0, mp.pi / 4)
    assert float(t_r) > 60
    assert s.release[0] == pytest.approx(float(t_r), rel=1e-7)
    w_r = mp.sqrt(2 * C * (mp.sin(mp.pi / 4) - mp.sin(phi0)) / I)
    assert math.hypot(s.release[3], s.release[4]) == pytest.approx(float(w_r * 11.25), rel=1e-7)


def test_release_exactly_at_the_vertical():
    """β = 0 with the projectile in the cup: release (velocity horizontal, forward) and the arm
    reaching the vertical are the same instant, two events at one root; the release gauge starts
    exactly on its negative branch (−π + β). Closed form: ω_v² = 2·C·(1 − sin φ0)/I,
    v = R·ω_v from height h + R, range = v·sqrt(2·(h + R)/g) (x_release = 0)."""
    out = solve("trebuchet", {"effects": "", "release_angle": 0, "accuracy": "tight"}).outputs
    I, C, _, _ = cup_machine_constants(500, 50, 15, 0.25, 5, 2, 9.81)
    w_v = mp.sqrt(2 * C * (1 + mp.mpf(4) / 11.25) / I)
    v = 11.25 * w_v
    assert out["arm_speed_at_vertical"].value == pytest.approx(float(w_v), rel=1e-9)
    assert out["release_speed"].value == pytest.approx(float(v), rel=1e-9)
    assert out["release_height"].value == pytest.approx(15.25, rel=1e-9)
    assert out["range"].value == pytest.approx(float(v * mp.sqrt(2 * 15.25 / mp.mpf(9.81))), rel=1e-8)
    assert out["time_to_vertical"].value == pytest.approx(out["release_time"].value, rel=1e-9)
