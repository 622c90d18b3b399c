"""Numerically delicate beam cases, each against a closed form evaluated in mpmath or an
independent high-resolution computation."""

import math

import mpmath as mp
import numpy as np
import pytest

from core import beams

mp.mp.dps = 50


def test_simple_support_load_right_next_to_a_support():
    """a = 1e-9·l: l² − b² (b = l − a) cancels to 9 digits if formed directly; the code uses a(l + b)."""
    l, a, F, EI = 1.0, 1e-9, 1000.0, 50.0
    y, x = beams.max_deflection("simple", F, a, l, EI)
    A, L = mp.mpf(a), mp.mpf(l)
    B = L - A
    y_ref = F * A * (L**2 - A**2) ** mp.mpf(1.5) / (9 * mp.sqrt(3) * EI * L)  # mirror: a is the short side
    x_ref = L - mp.sqrt((L**2 - A**2) / 3)
    assert y == pytest.approx(float(y_ref), rel=1e-14)
    assert x == pytest.approx(float(x_ref), rel=1e-14)
    # the load near the right support: b tiny, l² − b² with b = l − a rounded
    y2, x2 = beams.max_deflection("simple", F, float(B), l, EI)
    b_float = l - float(B)  # the short side the code sees
    y2_ref = F * mp.mpf(b_float) * (L**2 - mp.mpf(b_float) ** 2) ** mp.mpf(1.5) / (9 * mp.sqrt(3) * EI * L)
    assert y2 == pytest.approx(float(y2_ref), rel=1e-12)


def test_round_tube_with_a_wall_of_1e_minus_10_of_the_diameter():
    """D⁴ − d⁴ with d = D − 2t, t/D = 1e-10: direct subtraction keeps ~6 digits; the factored form all."""
    D, t = 0.05, 5e-12
    sec = beams.round_tube_section(D, t)
    d = mp.mpf(D) - 2 * mp.mpf(t)
    I_ref = mp.pi / 64 * (mp.mpf(D) ** 4 - d**4)
    assert sec.area_moment == pytest.approx(float(I_ref), rel=1e-14)
    naive = math.pi / 64 * (D**4 - (D - 2 * t) ** 4)
    assert abs(naive / float(I_ref) - 1) > 1e-8  # what the factoring avoids
    assert sec.area == pytest.approx(float(mp.pi / 4 * (mp.mpf(D) ** 2 - d**2)), rel=1e-14)


def test_rectangular_tube_area_moment_with_a_very_thin_wall():
    """x³y − (x−2h)³(y−2h) with h/x = 1e-11 cancels in direct form; compared with mpmath."""
    x, y, h = 0.0508, 0.0254, 5e-13
    sec = beams.rectangular_tube_section(x, y, h)
    X, Y, H = mp.mpf(x), mp.mpf(y), mp.mpf(h)
    ref = (X**3 * Y - (X - 2 * H) ** 3 * (Y - 2 * H)) / 12
    assert sec.area_moment == pytest.approx(float(ref), rel=1e-13)
    ref_weak = (Y**3 * X - (Y - 2 * H) ** 3 * (X - 2 * H)) / 12
    assert sec.min_area_moment == pytest.approx(float(ref_weak), rel=1e-13)
    # so thin that J is Bredt's: 4A_m²t/p_m, again in mpmath
    bredt = 4 * ((X - H) * (Y - H)) ** 2 * H / (2 * (X + Y - 2 * H))
    assert sec.torsion_constant == pytest.approx(float(bredt), rel=1e-13)


def test_fixed_fixed_load_at_midspan_switches_branches_continuously():
    """At a = l/2 the longer segment swaps sides; y and x must be continuous across the switch.

    Centre: y = F·l³/(192EI) at x = l/2; one ulp either side must agree to rounding."""
    l, F, EI = 1.0, 1.0, 1.0
    for a in (0.5, np.nextafter(0.5, 0), np.nextafter(0.5, 1)):
        y, x = beams.max_deflection("fixed", F, float(a), l, EI)
        A = mp.mpf(float(a))
        p, q = max(A, 1 - A), min(A, 1 - A)
        y_ref = 2 * p**3 * q**2 / (3 * (3 * p + q) ** 2)
        assert y == pytest.approx(float(y_ref), rel=1e-14)
        assert y == pytest.approx(1 / 192, rel=1e-14)
        assert x == pytest.approx(0.5, rel=1e-14)


def _p1_torsion(n, inside, on_edge, lo):
    """Prandtl's problem ∇²φ = −2, φ = 0 on the edge, P1 elements on the equilateral lattice of
    spacing 1/n (axial coordinates i, j from lo to n); J = 2∫φ dA. Independent of core's code."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    points = [(i, j) for i in range(lo, n + 1) for j in range(lo, n + 1) if inside(i, j)]
    index = {p: k for k, p in enumerate(points)}
    triangles = []
    for i in range(lo - 1, n + 1):
        for j in range(lo - 1, n + 1):
            for tri in (((i, j), (i + 1, j), (i, j + 1)), ((i + 1, j), (i + 1, j + 1), (i, j + 1))):
                if all(inside(*v) for v in tri):
                    triangles.append([index[v] for v in tri])
    tris = np.array(triangles)
    area = math.sqrt(3) / 4 / n**2
    k = np.where(np.eye(3, dtype=bool), 1 / math.sqrt(3), -1 / (2 * math.sqrt(3)))  # cot 60° rule
    rows = np.repeat(tris, 3, axis=1).ravel()
    cols = np.tile(tris, (1, 3)).ravel()
    K = coo_matrix((np.tile(k.ravel(), len(tris)), (rows, cols)), shape=(len(points),) * 2).tocsr()
    load = np.zeros(len(points))
    np.add.at(load, tris.ravel(), 2 * area / 3)
    free = np.array([not on_edge(i, j) for i, j in points])
    phi = spsolve(K[free][:, free].tocsc(), load[free])
    return float(load[free] @ phi)


def _hex_torsion_p1(n):
    """Regular hexagon of side 1: |i|, |j|, |i + j| ≤ n."""
    return _p1_torsion(n, lambda i, j: abs(i) <= n and abs(j) <= n and abs(i + j) <= n,
                       lambda i, j: abs(i) == n or abs(j) == n or abs(i + j) == n, -n)


def _triangle_torsion_p1(n):
    """Equilateral triangle of side 1: i, j ≥ 0, i + j ≤ n."""
    return _p1_torsion(n, lambda i, j: i >= 0 and j >= 0 and i + j <= n,
                       lambda i, j: i == 0 or j == 0 or i + j == n, 0)


def test_hex_torsion_constant_from_an_independent_fem():
    """No closed form: J on the hexagon from P1 FEM at n = 16, 32, 64, 128, Richardson in h², h³
    (the 120° corners' r^{3/2} singularity), h⁴. The extrapolation is good to ~5e-11 here (over
    n up to 512 it settles at 0.11505099441); the six-digit 0.115051 (4.9e-8 high) fails.

    Checked on the equilateral triangle, whose J = √3·a⁴/80 is exact (same element, same rule)."""
    t32, t64 = _triangle_torsion_p1(32), _triangle_torsion_p1(64)
    assert t64 + (t64 - t32) / 3 == pytest.approx(math.sqrt(3) / 80, rel=2e-4)
    ns = (16, 32, 64, 128)
    A = np.array([[1.0] + [n ** -p for p in (2, 3, 4)] for n in ns])
    j_side = np.linalg.solve(A, np.array([_hex_torsion_p1(n) for n in ns]))[0]
    assert _hex_torsion_p1(128) < 9 * beams.HEX_TORSION  # P1 on Prandtl's problem is a lower bound
    assert beams.HEX_TORSION == pytest.approx(j_side / 9, rel=1e-9)  # side 1 → across flats √3: /9
    assert beams.hex_section(0.0127).torsion_constant == pytest.approx(j_side / 9 * 0.0127**4, rel=1e-9)
    assert 0.1154 / beams.HEX_TORSION - 1 == pytest.approx(0.0030, abs=2e-4)  # the seed's (44) is 0.3 % high


@pytest.mark.parametrize("W,H", [(16.0, 16.0), (32.0, 16.0), (4.0, 4.0), (2.5, 2.2), (2.0001, 2.0001)])
def test_rectangular_tube_fem_against_grids_four_times_finer(W, H):
    """Re-entrant inner corners (r^{2/3} singularity) slow convergence to order 4/3, but a small hole
    shows order 2 first; the observed order is used. Reference: 16/32/64 cells across the wall."""
    reference = beams.extrapolated_torsion(W, H, (16, 32, 64))
    assert beams.tube_torsion_fem(W, H, 1.0) == pytest.approx(reference, rel=2e-4)


def test_rectangular_tube_fem_long_tube_extrapolation():
    """A 25000:4 tube (wall 1) is not meshed: J is linear in the long side L up to an O(1/L) term
    (Bredt-like 2tA²/p, not exponentially small), so the extrapolation from 2048:1 and 4096:1 is
    low by ~2/4096² ≈ 1e-7; check against a direct (graded, so still small) mesh."""
    reference = beams.extrapolated_torsion(1e5, 4.0, (8, 16, 32))
    assert beams.tube_torsion_fem(1e5, 4.0, 1.0) == pytest.approx(reference, rel=1e-6)


def test_long_thin_walled_tube_is_meshed_and_stays_above_bredt():
    """50 × 10001 (wall 1, ratio 200:1): delicate because J exceeds Bredt's by only ~2e-4, less
    than the 2.5e-4 a linear extrapolation in the long side from 32:1 and 64:1 loses (the O(1/L)
    term); the exact J must stay above Bredt's and agree with a finer direct mesh to 1e-6."""
    W, H = 50.0, 10001.0
    reference = beams.extrapolated_torsion(W, H, (8, 16, 32))
    J = beams.tube_torsion_fem(W, H, 1.0)
    assert J == pytest.approx(reference, rel=1e-6)
    bredt = 2 * (W - 1) ** 2 * (H - 1) ** 2 / (W + H - 2)
    assert J > bredt


def test_rectangular_tube_fem_and_bredt_agree_for_a_thin_wall():
    """Bredt's thin-wall J is exact as t → 0 with error O(t/a): at t/a = 1e-3 within 0.1 %."""
    exact = beams.tube_torsion_fem(1.0, 2.0, 1e-3)
    bredt = 2 * 1e-3 * (1 - 1e-3) ** 2 * (2 - 1e-3) ** 2 / (3 - 2e-3)
    assert bredt / exact - 1 == pytest.approx(0, abs=1e-3)
    assert bredt < exact


def _beam(**raw):
    from core.model import solve
    s = solve("beam", raw)
    return {k: v.value for k, v in s.outputs.items()}, s.warnings


def test_short_column_shows_johnsons_load_not_eulers():
    """1 in round 6061-T6 bar, 6 in long, pinned-pinned (K = 1). By hand, in mpmath:
    I = π/64·d⁴, A = π/4·d², r = d/4 = 0.00635 m, KL/r = 0.1524/0.00635 = 24;
    transition √(2π²·68.9e9/276e6) = 70.197 > 24, so Johnson governs:
    P = A·(Sy − (Sy·24/2π)²/E) = 131 679 N = 29 602 lbf; Euler's π²EI/L² = 598 206 N = 134 483 lbf.
    The old code showed Euler's 134 483 lbf as the buckling load."""
    d, L, E, Sy = mp.mpf("0.0254"), mp.mpf("0.1524"), mp.mpf("68.9e9"), mp.mpf("276e6")
    A, I = mp.pi / 4 * d**2, mp.pi / 64 * d**4
    lam = L / mp.sqrt(I / A)
    johnson = A * (Sy - (Sy * lam / (2 * mp.pi)) ** 2 / E)
    euler = mp.pi**2 * E * I / L**2
    assert float(lam) == pytest.approx(24, rel=1e-14)
    assert float(johnson) / 4.4482216152605 == pytest.approx(29602.5, abs=1)
    o, _ = _beam(section="round", outer_size=1, length=6, load_position=3, end_condition="pinned_pinned")
    assert o["buckling_formula"] == "Johnson"
    assert o["buckling_load"] == pytest.approx(float(johnson), rel=1e-12)
    assert o["euler_load"] == pytest.approx(float(euler), rel=1e-12)
    assert o["transition_slenderness"] == pytest.approx(float(mp.sqrt(2 * mp.pi**2 * E / Sy)), rel=1e-14)


def test_buckling_load_is_continuous_at_the_transition_slenderness():
    """Either side of (KL/r)_T = √(2π²E/Sy) the formula switches; both give σ = Sy/2 there."""
    r = 0.0254 / 4  # 1 in round bar
    L_T = math.sqrt(2 * math.pi**2 * 68.9e9 / 276e6) * r
    loads = {}
    for k in (1 - 1e-9, 1 + 1e-9):
        o, _ = _beam(section="round", outer_size=1, length=f"{L_T * k!r} m", load_position=0,
                     end_condition="pinned_pinned")
        loads[o["buckling_formula"]] = o["buckling_load"]
    assert set(loads) == {"Johnson", "Euler"}
    area = math.pi / 4 * 0.0254**2
    assert loads["Johnson"] == pytest.approx(area * 276e6 / 2, rel=1e-8)
    assert loads["Euler"] == pytest.approx(area * 276e6 / 2, rel=1e-8)


def test_long_column_is_eulers():
    o, _ = _beam(section="round", outer_size=1, length=120, load_position=0, end_condition="pinned_pinned")
    # KL/r = 3.048/0.00635 = 480 > 70.2: Euler, π²·68.9e9·π/64·0.0254⁴/3.048²
    assert o["buckling_formula"] == "Euler"
    ref = math.pi**2 * 68.9e9 * math.pi / 64 * 0.0254**4 / 3.048**2
    assert o["buckling_load"] == pytest.approx(ref, rel=1e-12)
