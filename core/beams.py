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
  h(x+y−2h)). The exact J comes from a finite-element solution (below); Bredt is shown beside it.

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
ELONGATION = 4096  # side ratio beyond which a tube's J is extrapolated linearly in its long side
THIN_WALL_LIMIT = 1e-4  # wall/size below which Bredt is used for J (its error is < 0.01 % there)


@dataclass(frozen=True)
class Section:
    area: float  # m²
    area_moment: float  # I about the bending axis (force across `height`), m⁴
    min_area_moment: float  # I about the weakest axis (column buckling), m⁴
    torsion_constant: float  # J, exact or numerically converged, m⁴
    extreme_fiber: float  # c: farthest fibre from the bending axis, m
    thin_wall_torsion_constant: float | None = None  # the seed's thin-wall J, for tubes


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
        J = bredt
    else:
        J = tube_torsion_fem(x, y, h)
    return Section(area, Ix, min(Ix, Iy), J, x / 2, bredt)


def tube_torsion_fem(W: float, H: float, t: float) -> float:
    """Torsion constant of a W×H rectangular tube (wall t) from Prandtl's stress function φ.

    ∇²φ = −2 in the wall, φ = 0 on the outside, φ = const on the hole boundary (the constant set
    by minimising the energy, which is Bredt's circulation condition), J = 2∫φ dA with φ = const
    over the hole. Bilinear elements on a tensor grid, graded towards the walls; the hole's nodes
    share one unknown. Three grids (4, 8, 16 elements across the wall) are Richardson-extrapolated
    (see extrapolated_torsion). Agrees with grids four times finer to ~1e-4 (tests/test_hard_beam.py).
    """
    return _tube_torsion_unit_wall(W / t, H / t) * t**4  # J ∝ length⁴: solve for t = 1, scale


@lru_cache(maxsize=64)
def _tube_torsion_unit_wall(W: float, H: float) -> float:
    """J of a W×H tube with wall 1 (depends on the two ratios only, so it caches well).

    The graded grid meshes a long tube cheaply (its cells grow geometrically along the sides), but
    beyond ~1e15:1 its cells round to zero width, so beyond ELONGATION × the short side J is
    extrapolated linearly from two grids. J is then linear in the long side L only up to an
    O(1/L) term (the hole's stress-function constant is set by the whole perimeter, as in Bredt's
    2t·A²/p), so the extrapolation is low by about 2/ELONGATION² relative: ~1e-7 at 4096 (a
    threshold of 64 gave 2.5e-4, enough to put a thin wall's J below Bredt's).
    """
    short, long_ = min(W, H), max(W, H)
    if long_ > ELONGATION * short:
        near = _tube_torsion_unit_wall(short, ELONGATION / 2 * short)
        far = _tube_torsion_unit_wall(short, ELONGATION * short)
        return far + (long_ - ELONGATION * short) * (far - near) / (ELONGATION / 2 * short)
    return extrapolated_torsion(W, H, (4, 8, 16))


def extrapolated_torsion(W: float, H: float, cells: tuple[int, int, int]) -> float:
    """Richardson extrapolation over three grids, halving the cell size each time, at the observed
    order p, kept between 4/3 (the inner corners' r^{2/3} singularity, the asymptotic rate) and 2
    (a small hole, where the singularity is weak and the smooth rate shows first)."""
    coarse, middle, fine = (_tube_torsion_grid(W, H, m) for m in cells)
    step1, step2 = middle - coarse, fine - middle
    p = math.log2(step1 / step2) if step1 * step2 > 0 else 4 / 3
    p = min(max(p, 4 / 3), 2.0)
    return fine + step2 / (2**p - 1)


def _graded(length: float, h0: float, ratio: float = 1.3):
    """Points on [0, length], spacing h0 at both ends growing geometrically to the middle."""
    half = length / 2
    points = [0.0]
    h = h0
    while points[-1] + h < half - 0.5 * h:
        points.append(points[-1] + h)
        h *= ratio
    points.append(half)
    return points + [length - p for p in reversed(points[:-1])]


def _axis(size: float, m: int):
    """Grid along one side of a tube of wall 1: m cells across each wall, graded in the hole."""
    wall = [i / m for i in range(m + 1)]
    middle = [1 + p for p in _graded(size - 2, 1 / m)]
    return wall + middle[1:] + [size - p for p in reversed(wall[:-1])]


def _tube_torsion_grid(W: float, H: float, m: int) -> float:
    import numpy as np
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    xu, xv = np.array(_axis(W, m)), np.array(_axis(H, m))
    nu, nv = len(xu), len(xv)
    iu, iv = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    outside = (iu == 0) | (iu == nu - 1) | (iv == 0) | (iv == nv - 1)
    hole = (iu >= m) & (iu <= nu - 1 - m) & (iv >= m) & (iv <= nv - 1 - m)
    dof = -np.ones((nu, nv), dtype=int)
    free = ~outside & ~hole
    count = int(free.sum())
    dof[free] = np.arange(count)
    dof[hole] = count  # one shared unknown: φ is constant over the hole
    count += 1
    a = np.repeat(np.diff(xu), nv - 1)  # element widths (u), row-major over (iu, iv)
    b = np.tile(np.diff(xv), nu - 1)  # element heights (v)
    eu, ev = np.meshgrid(np.arange(nu - 1), np.arange(nv - 1), indexing="ij")
    eu, ev = eu.ravel(), ev.ravel()
    nodes = np.stack([dof[eu, ev], dof[eu + 1, ev], dof[eu + 1, ev + 1], dof[eu, ev + 1]], axis=1)
    kx = np.array([[2, -2, -1, 1], [-2, 2, 1, -1], [-1, 1, 2, -2], [1, -1, -2, 2]]) / 6
    ky = np.array([[2, 1, -1, -2], [1, 2, -2, -1], [-1, -2, 2, 1], [-2, -1, 1, 2]]) / 6
    k_el = (b / a)[:, None, None] * kx + (a / b)[:, None, None] * ky  # bilinear element stiffness
    rows = np.repeat(nodes, 4, axis=1).ravel()
    cols = np.tile(nodes, (1, 4)).ravel()
    keep = (rows >= 0) & (cols >= 0)
    K = coo_matrix((k_el.reshape(-1)[keep], (rows[keep], cols[keep])), shape=(count, count)).tocsc()
    load = np.zeros(count)
    flat = nodes.ravel()
    per_node = np.repeat(2 * a * b / 4, 4)  # ∫2·N_i over the element
    np.add.at(load, flat[flat >= 0], per_node[flat >= 0])
    phi = spsolve(K, load)
    return float(load @ phi)  # J = 2∫φ dA = load·φ


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
