"""Cross-section properties and beam load cases for seed section 5 (eqs. 43-60), SI throughout.

Sections (seed 5.1) give the exact second moment of area I and torsion constant J:
- hex (43)/(44): I = 5√3/144·s⁴ exactly (s across flats; the seed's 0.0601 is it rounded).
  J has no closed form. J = 0.11505099441·s⁴, from a P1 finite-element solution of Prandtl's
  stress-function problem on the hexagon (structured equilateral mesh, n = 16…512 divisions per
  side, Richardson-extrapolated in h², h³ (the 120° corners' r^{3/2}), h⁴, h⁵, h⁶: every
  extrapolation over 5 or 6 of those grids gives 0.1150509944058-0.1150509944094, so the figure is
  good to ~4e-11 relative; re-computed in tests/test_hard_beam.py). The seed's 0.1154 is 0.30 %
  high; the six-digit 0.115051 was 4.9e-8 high.
- round tube (47)/(48): the seed's π/8·d³h and π/4·d³h are thin-wall forms; exact
  I = π/64·(D⁴ − d⁴), J = 2I, written as (D² + d²)(D + d)·2t so a thin wall does not cancel.
  With d the mean diameter d_m = D − t, (48) is low by the factor d_m²/(d_m² + t²) (shown as the
  thin-wall error); read with d = the outside diameter, it would be high by (D/d_m)³ instead.
- square (50): the seed's 9/64 = 0.140625 is Saint-Venant's series rounded; the series is
  summed here: J = 0.1405770·a⁴.
- rectangular tube (51): the seed's I = x²yh/3 is wrong (a thin square tube has 2/3·a³t, twice
  that); exact I = (x³y − (x−2h)³(y−2h))/12. (52) has a typo: Bredt's thin-wall formula for a
  uniform wall is J = 2h(x−h)²(y−h)²/(x + y − 2h) (the seed's denominator h(x+y−h) should be
  h(x+y−2h)). J has no closed form: it is bracketed between a lower and an upper finite-element
  bound (stress function and warping function, _tube_torsion_bounds) and shown as their midpoint
  with half the gap as its accuracy: 1e-9 to 1e-7 relative for FRC tubes (1×1 to 2×1 in, 1/16
  to 1/8 in wall). The old P1 grids with Richardson extrapolation were low by up to 1.6e-4,
  below the lower bound. Bredt is shown beside it. Common tubes read the two bounds from
  TUBE_TABLE, written by the same solve (J = t⁴·f(W/t, H/t): one row per pair of ratios).

Load cases (seed 5.2, Shigley table A-9), a measured from the left support (or the fixed end):
- (53) is the fixed-fixed beam (Shigley A-9-14), for 0 ≤ x ≤ a. Its maximum (56)/(57) lies in
  the LONGER segment, so a in (56)/(57) is the distance to the FARTHER support, not the closer
  one as the seed says (with a < l/2, (56) gives x > a, outside where (53) holds).
- simply supported (Shigley A-9-6): y_max = F·b·(l² − b²)^{3/2}/(9√3·E·I·l) at
  x = √((l² − b²)/3), b the shorter segment, x from the support at the end of the longer one.
- cantilever (58): tip deflection F·a²(3l − a)/(6EI) (the seed's sign is "down is negative").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

SECTIONS = ("hex", "round", "round_tube", "square", "rectangular_tube")
SECTION_LABELS = ("Hex", "Round", "Round tube", "Square", "Rectangular tube")
SUPPORTS = ("simple", "fixed", "cantilever")
SUPPORT_LABELS = ("Between simple supports", "Between fixed supports", "Cantilever")

HEX_TORSION = 0.11505099441  # J/s⁴, s across flats (FEM + Richardson, see module docstring)
HEX_AREA_MOMENT = 5 * math.sqrt(3) / 144  # I/s⁴, exact
THIN_WALL_LIMIT = 1e-4  # wall/size below which Bredt is used for J (its error is < 0.01 % there)


@dataclass(frozen=True)
class Section:
    area: float  # m²
    area_moment: float  # I about the bending axis (force across `height`), m⁴
    min_area_moment: float  # I about the weakest axis (column buckling), m⁴
    torsion_constant: float  # J, exact or numerically converged, m⁴
    extreme_fiber: float  # c: farthest fibre from the bending axis, m
    thin_wall_torsion_constant: float | None = None  # the seed's thin-wall J, for tubes
    torsion_constant_error: float | None = None  # relative bound on J's error where not exact


def hex_section(s: float) -> Section:
    """Regular hexagon, s across flats. I by triangles: see tests; c at a corner, s/√3."""
    I = HEX_AREA_MOMENT * s**4  # (43), exact
    return Section(math.sqrt(3) / 2 * s * s, I, I, HEX_TORSION * s**4, s / math.sqrt(3))  # (44)


def round_section(d: float) -> Section:
    I = math.pi / 64 * d**4  # (45)
    return Section(math.pi / 4 * d * d, I, I, 2 * I, d / 2)  # (46): J = π/32·d⁴


def round_tube_section(D: float, t: float) -> Section:
    """Outer diameter D, wall t < D/2. D⁴ − d⁴ = (D² + d²)(D + d)(D − d) with D − d = 2t."""
    d = D - 2 * t
    I = math.pi / 64 * (D * D + d * d) * (D + d) * (2 * t)  # exact form of (47)
    d_mean = D - t
    thin_J = math.pi / 4 * d_mean**3 * t  # (48), thin wall on the mean diameter
    return Section(math.pi / 4 * (D + d) * (2 * t), I, I, 2 * I, D / 2, thin_J)


def rectangle_torsion(b: float, h: float) -> float:
    """Saint-Venant's series for a solid b×h rectangle (b ≥ h); the tanh tail is exponentially small.

    J = b·h³/3·[1 − 192h/(π⁵b)·Σ_{n odd} tanh(nπb/2h)/n⁵]; Σ 1/n⁵ over odd n is (31/32)·ζ(5).
    """
    if b < h:
        b, h = h, b
    odd_zeta5 = 31 / 32 * 1.0369277551433699  # Σ_{n odd} n⁻⁵
    tail = 0.0
    for n in range(1, 40, 2):  # 1 − tanh(z) = 2/(e^{2z} + 1) ≤ 2e^{-2z}: negligible after a few terms
        z = n * math.pi * b / (2 * h)
        if z > 40:
            break
        tail += 2 / (math.exp(2 * z) + 1) / n**5
    return b * h**3 / 3 * (1 - 192 * h / (math.pi**5 * b) * (odd_zeta5 - tail))


def square_section(a: float) -> Section:
    I = a**4 / 12  # (49)
    return Section(a * a, I, I, rectangle_torsion(a, a), a / 2)  # (50), series instead of 9/64


def rectangular_tube_section(x: float, y: float, h: float) -> Section:
    """x outer size along the force (height), y across it (width), uniform wall h < min(x, y)/2."""
    # x³y − (x−2h)³(y−2h) = 2h·x³ + (y−2h)·2h·(x² + x(x−2h) + (x−2h)²): no cancellation
    xi, yi = x - 2 * h, y - 2 * h
    Ix = (2 * h * x**3 + yi * 2 * h * (x * x + x * xi + xi * xi)) / 12  # exact (51)
    Iy = (2 * h * y**3 + xi * 2 * h * (y * y + y * yi + yi * yi)) / 12
    area = 2 * h * (x + y) - 4 * h * h
    bredt = 2 * h * (x - h) ** 2 * (y - h) ** 2 / (x + y - 2 * h)  # (52), denominator corrected
    if h / min(x, y) < THIN_WALL_LIMIT:
        J, error = bredt, h / min(x, y)  # Bredt's error is O(t/a): ~1e-3 at t/a = 1e-3 (tests)
    else:
        J, error = tube_torsion_fem(x, y, h), tube_torsion_error(x, y, h)
    return Section(area, Ix, min(Ix, Iy), J, x / 2, bredt, error)


def tube_torsion_fem(W: float, H: float, t: float) -> float:
    """Torsion constant of a W×H rectangular tube (wall t): the midpoint of the two bounds of
    _tube_bounds, within tube_torsion_error(W, H, t) (relative) of the true J."""
    lower, upper = _tube_bounds(W / t, H / t)  # J ∝ length⁴: solve for t = 1, scale
    return (lower + upper) / 2 * t**4


def tube_torsion_error(W: float, H: float, t: float) -> float:
    """Half the gap between the bounds, relative, but not below the rounding of the two solves
    (TUBE_ROUNDING): the true J is within this of tube_torsion_fem."""
    lower, upper = _tube_bounds(W / t, H / t)
    return max(abs(upper - lower) / (upper + lower), TUBE_ROUNDING)


def _tube_bounds(W: float, H: float) -> tuple[float, float]:
    """_tube_torsion_bounds(W, H), read from TUBE_TABLE for the common tubes it lists (no numpy
    import and no solve: `gearhead solve beam` paid ~120 ms for them) when both ratios are within
    TUBE_TABLE_MATCH of a row's, else solved."""
    row = _TUBE_ROWS.get((round(W, 6), round(H, 6)))
    if row and abs(W - row[0]) <= TUBE_TABLE_MATCH * W and abs(H - row[1]) <= TUBE_TABLE_MATCH * H:
        return row[2], row[3]
    return _tube_torsion_bounds(W, H)


@lru_cache(maxsize=64)
def _tube_torsion_bounds(W: float, H: float) -> tuple[float, float]:
    """Lower and upper bounds on J of a W×H tube of wall 1 from two finite-element solutions on one
    mesh of a quarter of the section (both problems are symmetric about the two mid-planes).

    Lower: Prandtl's stress function φ, ∇²φ = −2 in the wall, φ = 0 outside, φ = C over the hole
    (C one unknown, set by the energy: Bredt's circulation condition); J = max 4∫φ − ∫|∇φ|², so any
    conforming φ gives J from below. Upper: the warping function ψ (antisymmetric, 0 on the
    mid-planes, free on every edge); J = min ∫(ψ_x − y)² + (ψ_y + x)² over the wall, so any ψ
    gives J from above. Elements: tensor Lagrange polynomials of degree TUBE_DEGREE on
    Gauss-Lobatto points (spectral elements), graded geometrically (ratio TUBE_GRADING, TUBE_LAYERS
    layers) toward the inner corner, where both fields have an r^{2/3} singularity, and growing
    ×2 along the sides, where the field is one-dimensional but for terms like e^{−πs/t}. More
    layers would make the smallest cells so thin that rounding (≈ 1e-16/h²) spoils the bounds.
    Solved with numpy alone (_condensed_elements, then _frontal_energy): ~40 ms, where scipy's
    sparse LU took ~80 ms after a ~0.3 s import.
    """
    import numpy as np

    p, L = TUBE_DEGREE, TUBE_LAYERS
    x01, K1, M1, w1, m1 = _tube_reference()
    a, b = W / 2, H / 2  # the quarter, from the outer corner: u across the side of width W, v of H
    bu, bv = np.array(_tube_axis(a, L)), np.array(_tube_axis(b, L))
    Eu, Ev = len(bu) - 1, len(bv) - 1
    Nu, Nv = Eu * p + 1, Ev * p + 1
    iu, iv = np.arange(Nu)[:, None], np.arange(Nv)[None, :]
    corner = L * p  # node index of the inner wall face (u = 1, v = 1)
    EU, EV = np.meshgrid(np.arange(Eu), np.arange(Ev), indexing="ij")
    wall = ~((EU >= L) & (EV >= L))  # elements of the hole are not in the wall
    EU, EV = EU[wall], EV[wall]
    hu, hv = np.diff(bu)[EU], np.diff(bv)[EV]
    local = np.arange(p + 1)
    gu, gv = EU[:, None] * p + local, EV[:, None] * p + local

    # Prandtl: φ = 0 on the outer faces (u = 0, v = 0); one unknown C for the hole and its faces
    hole = (iu >= corner) & (iv >= corner)
    free = ~hole & (iu > 0) & (iv > 0)
    dof_lower = np.full((Nu, Nv), -1)
    n_lower = int(free.sum()) + 1
    dof_lower[free] = np.arange(n_lower - 1)
    dof_lower[hole] = n_lower - 1
    load = 2 * np.outer(hu * hv, np.kron(w1, w1))  # ∫2·N_i over each element
    extra = np.zeros(n_lower)
    extra[-1] = 2 * (a - 1) * (b - 1)  # ∫2·C over the hole

    # warping: ψ = s·x·y + χ, χ = 0 on the mid-planes (u = a, v = b), free elsewhere; x = a − u,
    # y = b − v. s = −1 when the W sides are the longer (s = +1 otherwise) takes out the shear of
    # the long walls, so J = ∫|∇χ + ((s−1)y, (s+1)x)|² is not a small difference of large terms
    # (with s = 0, i.e. the polar moment minus a correction, a 25000:1 tube kept 3 digits).
    free = ~((iu > corner) & (iv > corner)) & (iu < Nu - 1) & (iv < Nv - 1)
    dof_upper = np.full((Nu, Nv), -1)
    n_upper = int(free.sum())
    dof_upper[free] = np.arange(n_upper)
    jump = np.zeros(p + 1)
    jump[0], jump[-1] = -1.0, 1.0  # ∫ℓ_i' over an element
    u0, v0 = bu[EU], bv[EV]
    if W >= H:  # s = −1: ∇χ·(−2y, 0) = 2χ_u·y; the rest is ∫4y² = 4·I_xx
        y_int = np.outer(hv * (b - v0), w1) - np.outer(hv * hv, m1)  # ∫ℓ_j(v)·y dv
        cross = 2 * jump[None, :, None] * y_int[:, None, :]
        rest = 4 * (W * H**3 - (W - 2) * (H - 2) ** 3) / 12
    else:  # s = +1: ∇χ·(0, 2x) = −2χ_v·x; the rest is ∫4x² = 4·I_yy
        x_int = np.outer(hu * (a - u0), w1) - np.outer(hu * hu, m1)  # ∫ℓ_i(u)·x du
        cross = -2 * x_int[:, :, None] * jump[None, None, :]
        rest = 4 * (H * W**3 - (H - 2) * (W - 2) ** 3) / 12

    # one elimination of each element's interior for both problems (the stiffness is the same)
    stiffness, (load_lower, energy_lower), (load_upper, energy_upper), edge = _condensed_elements(
        hv / hu, K1, M1, p, (load, cross.reshape(len(EU), -1))
    )
    # elements in a chain along the wall (the W-side arm from its mid-plane, the corner, the other
    # arm to its mid-plane), grouped by element column or row: each group touches only its neighbours
    group = np.where(EV < L, Eu - 1 - EU, Eu + EV - L)

    def energy(dof, count, loads, extra):
        """f·K⁻¹f for K·x = f assembled over the wall elements (this node → unknown map, −1: held at 0)."""
        ld = dof[gu[:, :, None], gv[:, None, :]].reshape(len(EU), -1)[:, edge]
        return _frontal_energy(stiffness, loads, ld, extra, count, group)

    lower = 4 * (energy_lower + energy(dof_lower, n_lower, load_lower, extra))  # J = 2∫φ = f·φ
    upper = rest - 4 * (energy_upper + energy(dof_upper, n_upper, load_upper, 0.0))
    return lower, upper


def _condensed_elements(ratio, K1, M1, p, loads):
    """Each element's stiffness k = r·K1⊗M1 + M1⊗K1/r (r = its height/width, nodes (i along u, j
    along v)) with its (p − 1)² interior nodes, which no other element shares, eliminated (static
    condensation): the edge nodes' Schur complement k_EE − k_EI·k_II⁻¹·k_IE, and for each load f
    its edge part f_E − k_EI·k_II⁻¹·f_I with the energy f_I·k_II⁻¹·f_I the interior takes. Returns
    them and the edge nodes' local indices."""
    import numpy as np

    inner = np.arange(1, p)
    interior = (inner[:, None] * (p + 1) + inner[None, :]).ravel()
    edge = np.flatnonzero(~np.isin(np.arange((p + 1) ** 2), interior))
    a, b = np.kron(K1, M1), np.kron(M1, K1)
    r = ratio[:, None, None]
    k_ie = r * a[np.ix_(interior, edge)] + b[np.ix_(interior, edge)] / r
    k_ee = r * a[np.ix_(edge, edge)] + b[np.ix_(edge, edge)] / r
    rhs = [k_ie] + [f[:, interior, None] for f in loads]
    x = np.linalg.solve(
        r * a[np.ix_(interior, interior)] + b[np.ix_(interior, interior)] / r, np.concatenate(rhs, axis=2)
    )
    condensed = [k_ee - k_ie.transpose(0, 2, 1) @ x[:, :, : len(edge)]]
    for n, f in enumerate(loads):
        z = x[:, :, len(edge) + n]
        condensed.append((f[:, edge] - np.einsum("eij,ei->ej", k_ie, z), float(np.sum(f[:, interior] * z))))
    return (*condensed, edge)


def _frontal_energy(stiffness, loads, ld, extra, count, group):
    """f·K⁻¹f, K and f assembled from element matrices and loads (on their edge nodes, interiors
    condensed) over the unknowns ld (−1: held at 0), f += extra, with numpy's dense solves (no
    sparse library: scipy.sparse takes ~0.3 s to import). The groups of elements form a chain along
    the wall. First each group's own unknowns (those no other group touches) are eliminated, all
    groups at once; then the groups are added in turn to a front (frontal elimination) and an unknown
    leaves it after the last group that touches it, so the front stays one or two wall-widths of
    nodes. Every dense solve and product stays small enough for OpenBLAS to run it on one thread
    (its threads, on a busy machine, cost more than they save). f·K⁻¹f needs no back-substitution:
    each elimination of unknowns e adds g_e·K_ee⁻¹·g_e, g the load condensed so far."""
    import numpy as np

    n_groups = int(group.max()) + 1
    held = ld < 0
    el, node = np.nonzero(~held)
    dof = ld[el, node]
    first, last = np.full(count, n_groups), np.full(count, -1)
    np.minimum.at(first, dof, group[el])
    np.maximum.at(last, dof, group[el])
    # each group's unknowns: its own first (sorted), then those it shares, numbered from 0 in each
    pairs = group[el] * count + dof
    by = np.argsort(pairs, kind="stable")  # (np.unique would import numpy.ma: 10 ms)
    step = np.concatenate([[True], pairs[by][1:] != pairs[by][:-1]])
    key, at = pairs[by][step], np.empty(len(pairs), dtype=int)
    at[by] = np.cumsum(step) - 1
    g_of, d_of = key // count, key % count
    shared = (first[d_of] != g_of) | (last[d_of] != g_of)
    order = np.lexsort((d_of, shared, g_of))
    start = np.searchsorted(g_of, np.arange(n_groups))
    local = np.empty(len(key), dtype=int)
    local[order] = np.arange(len(key)) - start[g_of[order]]
    n_all = np.bincount(g_of, minlength=n_groups)
    n_own = np.bincount(g_of[~shared], minlength=n_groups)
    size = int(n_all.max())
    where = np.full(ld.shape, size)  # held nodes go to a slot past the end, dropped
    where[el, node] = local[at]
    flat = (group[:, None, None] * (size + 1) + where[:, :, None]) * (size + 1) + where[:, None, :]
    K = np.bincount(flat.ravel(), stiffness.ravel(), n_groups * (size + 1) ** 2)
    K = K.reshape(n_groups, size + 1, size + 1)[:, :size, :size]
    f = np.bincount((group[:, None] * (size + 1) + where).ravel(), loads.ravel(), n_groups * (size + 1))
    f = f.reshape(n_groups, size + 1)[:, :size]
    first_here = first[d_of] == g_of
    f[g_of[first_here], local[first_here]] += np.broadcast_to(np.asarray(extra, dtype=float), (count,))[
        d_of[first_here]
    ]
    energy = 0.0
    condensed = [None] * n_groups
    n_shared = n_all - n_own
    for m, b in sorted(set(zip(n_own.tolist(), n_shared.tolist()))):  # groups of one shape at once
        gs = np.flatnonzero((n_own == m) & (n_shared == b))
        k_bb, f_b = K[gs, m : m + b, m : m + b], f[gs, m : m + b]
        if m:
            k_ob = K[gs, :m, m : m + b]
            x = np.linalg.solve(K[gs, :m, :m], np.concatenate([k_ob, f[gs, :m, None]], axis=2))
            energy += float(np.sum(f[gs, :m] * x[:, :, -1]))
            k_bb = k_bb - k_ob.transpose(0, 2, 1) @ x[:, :, :-1]
            f_b = f_b - np.einsum("gob,go->gb", k_ob, x[:, :, -1])
        for i, gi in enumerate(gs):
            condensed[gi] = (k_bb[i], f_b[i])
    shared_dofs = np.full((n_groups, size), -1)
    shared_dofs[g_of, local] = d_of

    slot = np.full(count, -1)  # an unknown's place in the front
    front = np.zeros(0, dtype=int)
    F, g = np.zeros((0, 0)), np.zeros(0)
    for gi in range(n_groups):
        mine = shared_dofs[gi, n_own[gi] : n_all[gi]]
        new = mine[slot[mine] < 0]
        n_old, n = len(front), len(front) + len(new)
        slot[new] = np.arange(n_old, n)
        front = np.concatenate([front, new])
        grown = np.zeros((n, n))
        grown[:n_old, :n_old] = F
        F, g = grown, np.concatenate([g, np.zeros(len(new))])
        s = slot[mine]
        F[np.ix_(s, s)] += condensed[gi][0]
        g[s] += condensed[gi][1]
        done = last[front] == gi
        keep = ~done
        if done.any():
            f_ek = F[np.ix_(done, keep)]
            z = np.linalg.solve(F[np.ix_(done, done)], np.column_stack([f_ek, g[done]]))
            energy += float(g[done] @ z[:, -1])
            F = F[np.ix_(keep, keep)] - f_ek.T @ z[:, :-1]
            g = g[keep] - f_ek.T @ z[:, -1]
        slot[front[done]] = -1
        front = front[keep]
        slot[front] = np.arange(len(front))
    return energy


TUBE_DEGREE = 8
# Rounding in the two solves, relative: where the bounds close below it they may cross (a 25000:1
# tube: upper 7e-10 below lower) and a 4×1e5 tube differs from 1e5×4 by 1.3e-9; the 32×32 tube's J
# is 2.7e-9 from the same solve in extended precision on an AMD EPYC (OpenBLAS, AVX2), under 2e-9
# on CI's machine (tests/test_beam_solver.py).
TUBE_ROUNDING = 4e-9
# Longest side over shortest of a rectangular tube whose J is solved: the frontal elimination met
# exact zero pivots at 1e8:1 (16 walls wide) and 1e9:1, none up to 3e7:1 in the tubes tried.
MAX_TUBE_ASPECT = 1e6
TUBE_LAYERS = 6
TUBE_GRADING = 0.15

# (W/t, H/t, lower, upper): _tube_torsion_bounds of common FRC/VEX and metric tubes, written by
# `python -m tests.tube_table` (height × width × wall after each row); tests/test_beam_table.py
# recomputes every row. A ratio within TUBE_TABLE_MATCH of a row's (1.5/(1/16) in SI is
# 23.999999999999996) reads the row: J/t⁴ grows at most as the 4th power of either ratio, so the
# row is within ~4·TUBE_TABLE_MATCH of the exact bounds at that ratio; a solve there differs from
# the row by its own rounding, which moves with every bit of its input (up to 9e-11 of J seen).
TUBE_TABLE_MATCH = 1e-12
TUBE_TABLE = (
    (7.936507936507937, 15.873015873015873, 1023.7440845699359, 1023.7440875601005),  # 1 x 1/2 x 0.063 in
    (8.0, 8.0, 369.44177846978266, 369.4417800416488),  # 1 x 1 x 1/8 in; 1/2 x 1/2 x 1/16 in
    (8.0, 16.0, 1050.7666809472812, 1050.7666840252446),  # 2 x 1 x 1/8 in; 1 x 1/2 x 1/16 in
    (8.0, 24.0, 1791.442056707425, 1791.4420610147668),  # 3 x 1 x 1/8 in
    (10.0, 10.0, 770.9340872593921, 770.9340900640482),  # 20 x 20 x 2 mm
    (10.0, 20.0, 2164.977110853203, 2164.977117348926),  # 40 x 20 x 2 mm
    (10.869565217391305, 21.73913043478261, 2827.948268993608, 2827.948277846379),  # 1 x 1/2 x 0.046 in
    (12.0, 12.0, 1391.9572544672985, 1391.9572600324082),  # 3/4 x 3/4 x 1/16 in; 1.5 x 1.5 x 1/8 in
    (12.5, 12.5, 1587.1396990629355, 1587.1397056042097),  # 25 x 25 x 2 mm
    (13.333333333333332, 13.333333333333332, 1951.6378193728965, 1951.6378278040456),  # 20 x 20 x 1.5 mm
    (15.0, 15.0, 2840.111698063377, 2840.111711900653),  # 30 x 30 x 2 mm
    (15.873015873015873, 7.936507936507937, 1023.7440845549302, 1023.7440876117495),  # 1 x 1/2 x 0.063 in
    (16.0, 8.0, 1050.7666809134014, 1050.766684099001),  # 2 x 1 x 1/8 in; 1 x 1/2 x 1/16 in
    (16.0, 16.0, 3484.595028474803, 3484.595047413085),  # 1 x 1 x 1/16 in; 2 x 2 x 1/8 in
    (16.0, 32.0, 9598.60385085732, 9598.603898853758),  # 2 x 1 x 1/16 in
    (16.666666666666668, 16.666666666666668, 3964.3705320337, 3964.3705543869364),  # 25 x 25 x 1.5 mm
    (20.0, 10.0, 2164.977110832215, 2164.97711743747),  # 40 x 20 x 2 mm
    (20.0, 20.0, 7031.354052755594, 7031.354107328083),  # 40 x 40 x 2 mm
    (21.73913043478261, 10.869565217391305, 2827.948269013067, 2827.94827806789),  # 1 x 1/2 x 0.046 in
    (24.0, 8.0, 1791.4420567331813, 1791.4420611328987),  # 3 x 1 x 1/8 in
    (24.0, 24.0, 12416.234022944182, 12416.234156373295),  # 1.5 x 1.5 x 1/16 in
    (25.0, 25.0, 14094.660396874096, 14094.660562423396),  # 1 x 1 x 0.040 in
    (25.0, 50.0, 38374.95478828595, 38374.9552128498),  # 2 x 1 x 0.040 in
    (32.0, 16.0, 9598.60385065883, 9598.603901232093),  # 2 x 1 x 1/16 in
    (32.0, 32.0, 30236.356378482484, 30236.356950555855),  # 2 x 2 x 1/16 in
    (50.0, 25.0, 38374.95478741969, 38374.95522138347),  # 2 x 1 x 0.040 in
)
_TUBE_ROWS = {(round(row[0], 6), round(row[1], 6)): row for row in TUBE_TABLE}


def _tube_axis(half: float, layers: int):
    """Element edges on [0, half] (wall 1): geometric toward 1 from both sides, then doubling."""
    sigma = TUBE_GRADING
    edges = [0.0] + [1 - sigma**k for k in range(1, layers)] + [1.0]
    above = [1 + sigma**k for k in range(layers - 1, 0, -1) if 1 + sigma**k < half]
    step = (above[-1] - (above[-2] if len(above) > 1 else 1.0)) * 2 if above else half - 1
    edge = above[-1] if above else 1.0
    while edge + step < half - step / 2:
        edge += step
        above.append(edge)
        step *= 2
    return edges + above + ([half] if half > 1 else [])


# _spectral_reference(TUBE_DEGREE) as numpy computes it on x86-64 with OpenBLAS's Haswell or Zen
# kernels, written by `python -m tests.tube_table`; the solve reads it (_tube_reference). The bounds
# follow the last bits of these matrices: computed on OpenBLAS's Sandybridge, Nehalem, Prescott or
# Atom kernels the stiffness differed by up to 7.6e-13 (entries up to 42), which moved the warping
# bound by up to 5e-8 and J by 2.5e-8 on TUBE_TABLE's tubes, 10x TUBE_ROUNDING; from this text
# they agree across those kernels to 7e-10 (upper) and 3.4e-10 (J). They are ~30 ulps from the
# exact integrals, which move J by at most 0.43x its stated error (tests/test_beam_table.py).
TUBE_REFERENCE = """
nodes:
0.0 0.05012100229426969 0.1614068602446309 0.31844126808691126
0.5 0.6815587319130891 0.838593139755369 0.94987899770573
1.0
stiffness:
24.33333333333347 -26.98995548216949 3.352019735320902 -0.9673794864489792
0.406349206349275 -0.21117815475773155 0.12417893629649594 -0.07514586570164991
0.02777777777777194 -26.98995548216949 41.713731326522016 -17.211342726651406
3.3257743206111123 -1.225158140853308 0.6005354788779602 -0.3428640944462719
0.20442518381092534 -0.07514586570163234 3.352019735320901 -17.211342726651406
24.339493920777507 -12.506015641007409 2.7857116601265886 -1.1398515097192696
0.5986697193029581 -0.3428640944464061 0.12417893629662397 -0.9673794864489792
3.325774320611112 -12.50601564100741 19.154121691475574 -10.88336531065656
2.627358611625211 -1.139851509719247 0.6005354788778928 -0.21117815475765964
0.4063492063492748 -1.2251581408533079 2.785711660126589 -10.883365310656561
17.83292517006807 -10.883365310656558 2.78571166012661 -1.225158140853384
0.4063492063493013 -0.2111781547577318 0.6005354788779601 -1.13985150971927
2.6273586116252106 -10.88336531065656 19.154121691475655 -12.506015641007487
3.3257743206112953 -0.967379486449088 0.12417893629649597 -0.3428640944462714
0.5986697193029581 -1.139851509719247 2.78571166012661 -12.506015641007485
24.33949392077764 -17.21134272665168 3.3520197353209378 -0.07514586570164992
0.20442518381092517 -0.3428640944464062 0.6005354788778934 -1.2251581408533843
3.3257743206112953 -17.21134272665168 41.71373132652249 -26.989955482169528
0.027777777777771906 -0.07514586570163229 0.12417893629662402 -0.21117815475765978
0.4063492063493013 -0.9673794864490883 3.3520197353209378 -26.98995548216953
24.333333333333357
mass:
0.013071895424836671 0.00199417260393837 -0.0025684530348850515 0.0028852048006946583
-0.0029878618113911353 0.0028852048006946076 -0.002568453034885149 0.0019941726039384403
-0.0008169934640523002 0.0019941726039383705 0.07788017014626099 0.0062692529402443185
-0.007042401957243349 0.007292974094403444 -0.007042401957243335 0.006269252940244816
-0.004867510634141383 0.001994172603938423 -0.0025684530348850515 0.006269252940244318
0.12919468823537017 0.009070467944570466 -0.009393199670437127 0.009070467944569893
-0.008074668014710424 0.006269252940244813 -0.0025684530348850797 0.002885204800694657
-0.007042401957243349 0.00907046794457046 0.16302518163437474 0.010551606128254329
-0.010189073852148253 0.009070467944569728 -0.007042401957243005 0.002885204800694599
-0.002987861811391136 0.007292974094403444 -0.009393199670437129 0.010551606128254329
0.17483259970654924 0.010551606128254653 -0.009393199670437091 0.007292974094403536
-0.0029878618113911223 0.0028852048006946076 -0.007042401957243335 0.009070467944569893
-0.010189073852148251 0.010551606128254653 0.163025181634375 0.00907046794456977
-0.007042401957243774 0.0028852048006945533 -0.002568453034885149 0.006269252940244816
-0.008074668014710424 0.009070467944569727 -0.009393199670437093 0.009070467944569777
0.12919468823537017 0.0062692529402442135 -0.002568453034885166 0.0019941726039384403
-0.004867510634141383 0.006269252940244813 -0.007042401957243005 0.007292974094403534
-0.007042401957243776 0.006269252940244215 0.07788017014626164 0.0019941726039383856
-0.0008169934640523001 0.0019941726039384234 -0.0025684530348850797 0.002885204800694598
-0.0029878618113911228 0.002885204800694553 -0.0025684530348851664 0.001994172603938386
0.013071895424836586
weights:
0.01388888888888885 0.08274768078040272 0.1372693562500809 0.1732142554865232
0.18575963718820862 0.17321425548652325 0.13726935625008094 0.08274768078040272
0.01388888888888885
moments:
0.0 0.004147396698240061 0.022156215800127263 0.05515856716785867
0.09287981859410431 0.11805568831866463 0.11511314044995366 0.07860028408216263
0.01388888888888885
"""


@lru_cache(maxsize=1)
def _tube_reference():
    """TUBE_REFERENCE as arrays: nodes, stiffness, mass, ∫ℓ_i, ∫ℓ_i·s (see _spectral_reference)."""
    import numpy as np

    parts: dict[str, list[float]] = {}
    for token in TUBE_REFERENCE.split():
        if token.endswith(":"):
            numbers = parts.setdefault(token[:-1], [])
        else:
            numbers.append(float(token))
    n = TUBE_DEGREE + 1
    x, K, M, w, m = (parts[k] for k in ("nodes", "stiffness", "mass", "weights", "moments"))
    return np.array(x), np.array(K).reshape(n, n), np.array(M).reshape(n, n), np.array(w), np.array(m)


@lru_cache(maxsize=4)
def _spectral_reference(p: int):
    """Lagrange basis of degree p on the Gauss-Lobatto points of [0, 1]: nodes, stiffness ∫ℓ_i'ℓ_j',
    mass ∫ℓ_iℓ_j (Gauss-Legendre, exact), ∫ℓ_i and ∫ℓ_i·s (Lobatto, exact to degree 2p − 1)."""
    import numpy as np
    from numpy.polynomial import legendre

    c = np.zeros(p + 1)
    c[-1] = 1
    x = np.concatenate([[-1.0], legendre.legroots(legendre.legder(c)), [1.0]])
    w = 2 / (p * (p + 1) * legendre.legval(x, c) ** 2)
    q, qw = legendre.leggauss(p + 2)
    value, slope = np.zeros((len(q), p + 1)), np.zeros((len(q), p + 1))
    for i in range(p + 1):
        basis = np.polynomial.Polynomial.fromroots(np.delete(x, i))
        basis = basis / basis(x[i])
        value[:, i], slope[:, i] = basis(q), basis.deriv()(q)
    mass = (value * qw[:, None]).T @ value / 2  # [−1, 1] → [0, 1]
    stiffness = (slope * qw[:, None]).T @ slope * 2
    nodes = (x + 1) / 2
    return nodes, stiffness, mass, w / 2, w / 2 * nodes


# Load cases ------------------------------------------------------------------------------------


def max_deflection(support: str, F: float, a: float, l: float, EI: float) -> tuple[float, float]:
    """(largest deflection, its distance from the left support / fixed end), load F at a."""
    if support == "cantilever":
        return F * a * a * (3 * l - a) / (6 * EI), l  # (58), at the free end
    b = l - a
    if support == "simple":
        # Shigley A-9-6 for the load in the right half (a ≥ b): y = Fbx(l² − x² − b²)/(6EIl), x ≤ a;
        # dy/dx = 0 at x = √((l² − b²)/3). Mirror for a < b. l² − b² = a(l + b) avoids cancellation.
        near, far = min(a, b), max(a, b)
        l2_minus = far * (l + near)  # l² − near²
        y = F * near * l2_minus * math.sqrt(l2_minus) / (9 * math.sqrt(3) * EI * l)
        x = math.sqrt(l2_minus / 3)
        return y, (x if a >= b else l - x)
    # fixed-fixed, (53)-(57) with a the LONGER segment: y_max = 2F·a³b²/(3EI(3a + b)²), 3a + b = 2a + l
    long_, short = max(a, b), min(a, b)
    y = 2 * F * long_**3 * short**2 / (3 * EI * (3 * long_ + short) ** 2)  # (57)
    x = 2 * long_ * l / (3 * long_ + short)  # (56)
    return y, (x if a >= b else l - x)


def max_moment(support: str, F: float, a: float, l: float) -> float:
    """Largest bending moment magnitude along the beam."""
    if support == "cantilever":
        return F * a  # at the fixed end
    b = l - a
    if support == "simple":
        return F * a * (b / l)  # under the load
    # fixed-fixed: support moments F·a·b²/l², F·a²·b/l²; under the load 2F·a²b²/l³ (never larger)
    return F * max(a, b) * (max(a, b) / l) * (min(a, b) / l)


def deflection_curve(support: str, F: float, a: float, l: float, EI: float, points: int = 81):
    """(x, y) along the beam, y positive in the direction of F (Shigley A-9-2, A-9-6, A-9-14)."""
    xs = [l * i / (points - 1) for i in range(points)]
    b = l - a
    ys = []
    for x in xs:
        if support == "cantilever":
            y = F * x * x * (3 * a - x) / (6 * EI) if x <= a else F * a * a * (3 * x - a) / (6 * EI)
        elif support == "simple":
            if x <= a:
                y = F * b * x * (l * l - x * x - b * b) / (6 * EI * l)
            else:
                u = l - x
                y = F * a * u * (l * l - u * u - a * a) / (6 * EI * l)
        else:
            if x <= a:
                y = F * x * x * b * b * (3 * a * l - x * (3 * a + b)) / (6 * EI * l**3)  # (53)
            else:
                u = l - x
                y = F * u * u * a * a * (3 * b * l - u * (3 * b + a)) / (6 * EI * l**3)
        ys.append(y)
    return xs, ys
