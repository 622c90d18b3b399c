"""Equations of motion of a counterweight trebuchet (seed 001), derived by Lagrange, as a scene
assembled from effects (core.sim.effects).

Geometry (the seed's frame): pivot A at (0, h); the arm direction e = (cos φ, sin φ), φ from the
horizontal, φ = 0 pointing right. Long end C = A + R·e with R = (1 − a)·L; counterweight hinge
B = A − r·e with r = a·L; the arm's centre of mass at s·e with s = L/2 − a·L. The counterweight
starts up on the left and falls, so φ grows from φ0 < 0 through 90° (arm vertical) and C swings
over the top to the left: the throw goes toward −x.

Generalised coordinates (all angles absolute, from +x, counter-clockwise):
    φ  the arm;  γ = φ + θ  the sling (θ is the seed's sling angle relative to the arm);
    ψ  the counterweight hanger, from straight down (only with a pendulum counterweight).

    I_φ = m·L²·(1/12 + (1/2 − a)²) + M·(aL)² [+ M·k² when the counterweight is rigid]  (T1) seed 1.2
    sin φ0 = −h/((1 − a)·L): C on the ground at rest                                    (T2) seed 1.3
    P = A + R·e + l·(cos γ, sin γ) (seed 2.1, γ = φ + θ; the cup at C without sling),
    counterweight centre B + d·(sin ψ, −cos ψ)                                          (T3) seed 2.1
    T = ½·(I_φ + m_p·R²)·ω² + m_p·R·l·cos(γ−φ)·ω·γ̇ + ½·m_p·l²·γ̇²
        − M·r·d·sin(ψ−φ)·ω·ψ̇ + ½·M·(d² + k²)·ψ̇²
    V = g·[(m·s − M·r + m_p·R)·sin φ + m_p·l·sin γ − M·d·cos ψ]  (+ const)              (T4) seed 1.5
Lagrange's equations M(q)·q̈ = f(q, q̇) (seed 1.4 and 2.3-2.4, there by Newton and sympy):
    M11 = I_φ + m_p·R²,  M12 = m_p·R·l·cos(γ−φ),  M22 = m_p·l²,
    M13 = −M·r·d·sin(ψ−φ),  M33 = M·(d² + k²),  M23 = 0
    f1 = m_p·R·l·sin(γ−φ)·γ̇² + M·r·d·cos(ψ−φ)·ψ̇² − g·(m·s − M·r + m_p·R)·cos φ
    f2 = −m_p·R·l·sin(γ−φ)·ω² − g·m_p·l·cos γ
    f3 = −M·r·d·cos(ψ−φ)·ω² − g·M·d·sin ψ                                               (T5)
(checked against a sympy Lagrangian in tests/test_trebuchet.py). The arm alone (no sling) carries
the projectile in a cup at C: the same equations with l = 0 and no γ. The sling and a pendulum
counterweight each couple with φ only (M23 = 0), so M·q̈ = b is solved by block elimination:
    q̈1 = (b1 − Σ M1j·bj/Mjj) / (M11 − Σ M1j²/Mjj),   q̈j = (bj − M1j·q̈1)/Mjj             (T6)
Ground contact adds the constraint y_P = h + R·sin φ + l·sin γ = 0 with multiplier λ (the
ground's normal force):
    M·q̈ = f + Jᵀ·λ,  J·q̈ = R·sin φ·ω² + l·sin γ·γ̇²,  J = (R·cos φ, l·cos γ, 0)          (T7)
and lifts off where λ falls to zero. A fall back onto the ground is plastic:
    q̇⁺ = q̇⁻ − M⁻¹·Jᵀ·(J·q̇⁻)/(J·M⁻¹·Jᵀ)                                                  (T8)
The sling's pull on the projectile, T = −m_p·(a_P·u) − m_p·g·sin γ + λ·sin γ               (T9)
Release: when the projectile's velocity points up at the release angle β toward the throw (−x):
    u × v = 0 with u = (−cos β, sin β), rising, and u·v > 0                             (T10)

The scene is assembled once per solve from the effects on (EFFECTS): `sling` and
`hinged_counterweight` (with a hanger) each add two states and their blocks of (T5) through the
"coupling" slot, and their shares of (T3)-(T4); `ground_contact` adds the constraint (T7) and its
phase events (lift-off, touchdown); an effect that is off adds no state, no term and no branch.
The same terms serve one throw (math, plain floats, fast) and a batch of candidate throws (numpy
arrays): each part takes its `sin`, `cos` from the context's namespace.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

from ..declarations import Output
from ..fields import Field
from .effects import Assembly, Effect, Effects, Part, Slot, nothing

# The least effective inertia of the arm (Machine.least_inertia) the swing resolves, relative to the
# M11 it is computed from: rounding costs ~1e-16·M11, so at 1e-9 the elimination keeps 7 digits.
MIN_INERTIA_RATIO = 1e-9


@dataclass(frozen=True)
class Machine:
    """Parameters in SI; `sling`, `pendulum` say which degrees of freedom exist."""

    M: float  # counterweight mass
    k: float  # counterweight radius of gyration
    m: float  # arm mass
    L: float  # arm length
    a: float  # short-arm fraction
    h: float  # pivot height
    m_p: float  # projectile mass (0 after release)
    l: float  # sling length
    g: float
    rigid: bool = True  # counterweight fixed to the arm (adds M·k²); False: hinged
    d: float = 0.0  # hanger length of a pendulum counterweight (hinged, d > 0)
    sling: bool = True

    @property
    def pendulum(self) -> bool:
        return not self.rigid and self.d > 0

    @property
    def R(self) -> float:
        return (1 - self.a) * self.L

    @property
    def r(self) -> float:
        return self.a * self.L

    @property
    def s(self) -> float:
        return self.L / 2 - self.a * self.L

    @property
    def I_arm(self) -> float:
        return self.m * self.L**2 * (1 / 12 + (0.5 - self.a) ** 2)  # seed 1.2, Steiner

    @property
    def I_phi(self) -> float:
        """Inertia about A of arm and counterweight turning with φ (T1, seed 1.2: I_tot)."""
        I = self.I_arm + self.M * self.r**2
        if self.rigid:
            I += self.M * self.k**2  # rigid: the counterweight turns with the arm
        return I

    def least_inertia(self) -> tuple[float, float]:
        """(least, M11): the least the arm's effective inertia about the pivot (T6's Schur
        denominator M11 − Σ M1j²/Mjj) can be over the swing's configurations, in closed form, and
        M11, which the swing subtracts from. A sling along the arm takes the projectile's whole
        share (M12²/M22 = m_p·R²·cos²(γ−φ)); a pendulum counterweight in line with the arm all of its
        share but M·r²·k²/(d² + k²) (M13²/M33 = M·r²·d²·sin²(ψ−φ)/(d² + k²)). The swing computes
        the difference, so a least inertia below MIN_INERTIA_RATIO of M11 is lost to rounding
        (exactly 0 there: a division by zero; slightly negative: an arm that turns the wrong way)."""
        if self.pendulum:
            least = self.I_arm + self.M * self.r**2 * self.k**2 / (self.d**2 + self.k**2)
        else:
            least = self.I_phi
        if not self.sling:  # the projectile rides in the cup at C: its share never leaves the arm
            least += self.m_p * self.R**2
        return least, self.I_phi + self.m_p * self.R**2

    @property
    def phi0(self) -> float:
        return math.asin(-self.h / self.R)  # (T2), seed 1.3: sin φ0 = −h/((1−a)L), C on the ground

    def released(self) -> Machine:
        """The machine after the projectile has left: no projectile, no sling."""
        return replace(self, m_p=0.0, sling=False)

    def effects(self, ground_contact: bool = False) -> frozenset:
        """The effects of the swing this machine stands for (ground contact needs the sling)."""
        on = {"sling"} if self.sling else set()
        if not self.rigid:
            on.add("hinged_counterweight")
        if ground_contact and self.sling:
            on.add("ground_contact")
        return frozenset(on)


# ---- the parts ---------------------------------------------------------------------------------
# Each coupling term returns the blocks of (T5) for its degree of freedom j: (M1j, Mjj, its term of
# f1, fj); each energy term its (T, V) share of (T4); the sling's tip term the projectile's offset
# from C (T3). The arithmetic is written in the order of the equations above (the golden outputs
# are kept to the last bit).


@dataclass(frozen=True)
class Ctx:
    """What the parts are built from: the machine and the math namespace (math, or numpy)."""

    p: Machine
    xp: Any = math


SLOTS = (
    Slot(
        "coupling",
        "each",
        "(φ, ω, q, q̇) -> (M1j, Mjj, f1 term, fj): a degree of freedom coupled to the arm (T5)",
    ),
    Slot("energy", "each", "(φ, ω, q, q̇) -> (T, V): its share of the energy (T4)"),
    Slot("tip", "each", "(q, q̇) -> (Δx, Δz, Δvx, Δvy): the projectile's offset from C (T3)"),
    Slot("hanger", "each", "(q) -> Δz: the counterweight centre below its hinge (T3)"),
    Slot("constraint", "each", "(φ, ω, γ, γ̇) -> (J1, J2, J·q̈): the ground under the projectile (T7)"),
)


def _sling(values, ctx: Ctx) -> Part:
    p, sin, cos = ctx.p, ctx.xp.sin, ctx.xp.cos
    R, l = p.R, p.l
    A = p.m_p * R * l
    m22 = p.m_p * l * l
    gml = p.g * p.m_p * l
    half22 = 0.5 * p.m_p * l * l

    def coupling(phi, w, gam, gd):
        d = gam - phi
        sd = sin(d)
        return A * cos(d), m22, A * sd * gd * gd, -A * sd * w * w - gml * cos(gam)  # (T5)

    def energy(phi, w, gam, gd):
        return A * cos(gam - phi) * w * gd + half22 * gd * gd, gml * sin(gam)  # (T4)

    def tip(gam, gd):
        sg, cg = sin(gam), cos(gam)
        return l * cg, l * sg, -(l * gd * sg), l * gd * cg  # (T3)

    return Part(
        states=(("gamma", math.pi), ("gamma_dot", 0.0)),  # the sling lies flat toward the pivot
        terms={"coupling": coupling, "energy": energy, "tip": tip},
    )


def _hinged(values, ctx: Ctx) -> Part:
    """Hinged at its centre (d = 0): only I_φ changes (Machine.I_phi, no M·k²): no state, no term.
    On a hanger (d > 0): a pendulum, two states and its blocks of (T5)."""
    p, sin, cos = ctx.p, ctx.xp.sin, ctx.xp.cos
    if not p.pendulum:
        return Part()
    B = p.M * p.r * p.d
    m33 = p.M * (p.d * p.d + p.k * p.k)
    gMd = p.g * p.M * p.d
    half33 = 0.5 * p.M * (p.d**2 + p.k**2)
    d_ = p.d

    def coupling(phi, w, psi, pd):
        d = psi - phi
        ce = cos(d)
        return -B * sin(d), m33, B * ce * pd * pd, -B * ce * w * w - gMd * sin(psi)  # (T5)

    def energy(phi, w, psi, pd):
        return -B * sin(psi - phi) * w * pd + half33 * pd * pd, -gMd * cos(psi)  # (T4)

    def hanger(psi):
        return d_ * cos(psi)

    return Part(
        states=(("psi", 0.0), ("psi_dot", 0.0)),  # hanging straight down
        terms={"coupling": coupling, "energy": energy, "hanger": hanger},
    )


def _ground(values, ctx: Ctx) -> Part:
    """The constraint y_P = 0 on the sling's coordinates (T7); the swing adds its phase events."""
    p, sin, cos = ctx.p, ctx.xp.sin, ctx.xp.cos
    R, l = p.R, p.l

    def constraint(phi, w, gam, gd):
        return R * cos(phi), l * cos(gam), R * sin(phi) * w * w + l * sin(gam) * gd * gd

    def report(swing) -> dict:
        return {} if swing.liftoff is None else {"liftoff_time": swing.liftoff}

    return Part(terms={"constraint": constraint}, report=report)


EFFECTS = Effects(
    Effect(
        "sling",
        "2 DOF: the projectile on a sling of length l (seed section 2)",
        _sling,
        fields=(
            Field(
                "sling_length",
                "Sling length l",
                "length",
                "m",
                default=5,
                min=1e-2,
                max=1e3,
                help="Sling length, C to the projectile.",
            ),
        ),
        default_on=True,
    ),
    Effect(
        "ground_contact",
        "the projectile starts on the ground and slides until the sling lifts it",
        _ground,
        outputs=(
            Output(
                "liftoff_time",
                "Lift-off time",
                "time",
                "s",
                equation="(T7)",
                help="When the ground's push λ on the projectile falls to zero (an event "
                "on the constrained swing).",
            ),
        ),
        default_on=True,
    ),
    Effect(
        "hinged_counterweight",
        "hinged counterweight: at its centre (hanger 0) or a pendulum",
        _hinged,
        fields=(
            Field(
                "hanger_length",
                "Hanger length d",
                "length",
                "m",
                default=0,
                min=0,
                max=1e3,
                help="Hinge to counterweight centre. 0: hinged at its centre of mass (the seed's "
                "hinged case); > 0: a pendulum.",
            ),
        ),
    ),
    Effect(
        "air_drag",
        "quadratic drag on the flight after release",
        nothing,
        fields=(
            Field(
                "projectile_diameter",
                "Projectile diameter",
                "length",
                "m",
                default=0.2,
                min=1e-3,
                max=5,
                help="For the drag area.",
            ),
            Field(
                "drag_coefficient", "Drag coefficient", default=0.47, min=0, max=2, help="C_d (sphere 0.47)."
            ),
            Field(
                "air_density",
                "Air density",
                "density",
                "kg/m**3",
                default=1.225,
                min=0,
                max=20,
                help="Density of air.",
            ),
        ),
    ),
)
BASE_STATES = ("phi", "omega")


def assemble(p: Machine, ground_contact: bool, xp: Any = math) -> Assembly:
    """The parts of the swing this machine stands for (once per solve)."""
    return EFFECTS.assemble(p.effects(ground_contact), {}, Ctx(p, xp), SLOTS, BASE_STATES)


# ---- the assembled scene -----------------------------------------------------------------------
# State vector: [φ, ω] + the states of the effects on, in catalogue order ([γ, γ̇] with the sling,
# [ψ, ψ̇] with a pendulum counterweight).


@dataclass
class Scene:
    """One solve's equations, specialised once to the effects on: `free` and `contact` give the
    accelerations (T6) without and with the ground constraint (T7); the rest read the state."""

    p: Machine
    asm: Assembly
    free: Callable  # (φ, ω, y) -> [φ̈, q̈j ...]
    contact: Callable | None  # (φ, ω, y, gate) -> ([φ̈, q̈j ...], λ); None without ground_contact
    solve: Callable  # (φ, ω, y) -> (accelerations, blocks of each coupling, Schur denominator)
    mobility: Callable | None  # (φ, y, blocks, den) -> (M⁻¹Jᵀ, J·M⁻¹·Jᵀ, J1, J2, J·q̈ rhs)
    energies: tuple = ()  # ((offset, term), ...) of the slots, read once here
    tips: tuple = ()
    hangers: tuple = ()

    @property
    def n(self) -> int:
        return len(self.asm.states)

    @property
    def sling(self) -> bool:
        return bool(self.tips)

    def rhs(self, contact: bool):
        """The right-hand side of the free or the constrained phase (built once per phase)."""
        n_dof = self.n // 2
        if contact:
            acc = self.contact
            return _interleave(lambda y: acc(y[0], y[1], y, True)[0], n_dof)
        free = self.free
        return _interleave(lambda y: free(y[0], y[1], y), n_dof)

    def accelerations(self, y, contact: bool):
        """([φ̈, q̈j ...], λ) at state y (λ = 0 off the ground)."""
        if contact:
            return self.contact(y[0], y[1], y, True)
        return self.free(y[0], y[1], y), 0.0

    def energy(self, y) -> tuple[float, float]:
        """(T, V) of the machine and projectile (T4); V from the pivot height (a constant apart)."""
        p = self.p
        phi, w = y[0], y[1]
        R = p.R
        T = 0.5 * (p.I_phi + p.m_p * R * R) * w * w
        V = p.g * (p.m * p.s - p.M * p.r + p.m_p * R) * math.sin(phi)
        for i, e in self.energies:
            dT, dV = e(phi, w, y[i], y[i + 1])
            T += dT
            V += dV
        return T, V

    def projectile(self, y) -> tuple[float, float, float, float]:
        """Projectile (x, height above ground, vx, vy) in the seed's frame (T3; cup at C without sling)."""
        p = self.p
        phi, w = y[0], y[1]
        R = p.R
        x, z = R * math.cos(phi), p.h + R * math.sin(phi)
        vx, vy = -R * w * math.sin(phi), R * w * math.cos(phi)
        for i, tip in self.tips:
            dx, dz, dvx, dvy = tip(y[i], y[i + 1])
            x += dx
            z += dz
            vx += dvx
            vy += dvy
        return x, z, vx, vy

    def counterweight_height(self, y) -> float:
        z = self.p.h - self.p.r * math.sin(y[0])
        for i, hanger in self.hangers:
            z -= hanger(y[i])
        return z

    def sling_tension(self, y, contact: bool) -> float:
        """Pull of the sling on the projectile (T9; negative: the sling would have to push).

        m_p·a_P = −T·u − m_p·g·ŷ + λ·ŷ, u = (cos γ, sin γ) from C to P, so
        T = −m_p·(a_P·u) − m_p·g·sin γ + λ·sin γ with a_P·u = R·ω̇·sin(γ−φ) − R·ω²·cos(γ−φ) − l·γ̇².
        """
        p = self.p
        phi, w, gam, gd = y[0], y[1], y[2], y[3]
        xs, lam = self.accelerations(y, contact)
        d = gam - phi
        a_u = p.R * xs[0] * math.sin(d) - p.R * w * w * math.cos(d) - p.l * gd * gd
        return -p.m_p * a_u - p.m_p * p.g * math.sin(gam) + lam * math.sin(gam)

    def touchdown(self, y: list) -> list:
        """State after the projectile lands on the ground (T8, plastic: its vertical speed goes to 0).

        The ground's impulse Λ acts along Jᵀ: q̇⁺ = q̇⁻ − M⁻¹·Jᵀ·(J·q̇⁻)/(J·M⁻¹·Jᵀ), so that J·q̇⁺ = 0
        (the impulsive form of the contact constraint; it only removes energy).
        """
        phi, w = y[0], y[1]
        _, blocks, den = self.solve(phi, w, y)
        ys, Jy, J1, J2, _ = self.mobility(phi, y, blocks, den)
        lam = (J1 * w + J2 * y[3]) / Jy if Jy > 0 else 0.0
        out = list(y)
        for k, yk in enumerate(ys):
            out[2 * k + 1] = y[2 * k + 1] - lam * yk
        return out


def _interleave(accel, n_dof: int):
    """rhs(t, y) = [ω, φ̈, q̇1, q̈1, ...] from accel(y) = [φ̈, q̈1, ...]."""
    if n_dof == 1:
        return lambda t, y: [y[1], accel(y)[0]]
    if n_dof == 2:

        def rhs2(t, y):
            a = accel(y)
            return [y[1], a[0], y[3], a[1]]

        return rhs2
    vel = tuple(range(1, 2 * n_dof, 2))

    def rhs(t, y):
        out = []
        for i, a in zip(vel, accel(y)):
            out += (y[i], a)
        return out

    return rhs


def build(p: Machine, ground_contact: bool, xp: Any = math) -> Scene:
    """Assemble the scene (T5)-(T7) from the effects this machine and ground_contact stand for."""
    asm = assemble(p, ground_contact, xp)
    R = p.R
    m11 = p.I_phi + p.m_p * R * R
    K1 = -p.g * (p.m * p.s - p.M * p.r + p.m_p * R)
    cos = xp.cos
    dofs = asm.with_state("coupling")

    solve = _elimination(m11, K1, cos, dofs)
    if not dofs:

        def free(phi, w, y):
            return [K1 * cos(phi) / m11]
    else:

        def free(phi, w, y):
            return solve(phi, w, y)[0]

    contact = mobility = None
    if asm.slots["constraint"] is not None:
        (constraint,) = asm.slots["constraint"]
        i_s = asm.offset("sling")
        n_rest = len(dofs) - 1  # couplings besides the sling's: the ground does not push on them

        def mobility(phi, y, blocks, den):
            """M⁻¹·Jᵀ by the same elimination (the ground pushes on φ and γ only), J·M⁻¹·Jᵀ."""
            m12, m22 = blocks[0][0], blocks[0][1]
            J1, J2, c = constraint(phi, y[1], y[i_s], y[i_s + 1])
            y1 = (J1 - m12 * J2 / m22) / den
            y2 = (J2 - m12 * y1) / m22
            ys = [y1, y2]
            if n_rest:
                ys += [-b[0] * y1 / b[1] for b in blocks[1:]]
            return ys, J1 * y1 + J2 * y2, J1, J2, c

        def contact(phi, w, y, gate):  # (T7): λ from J·q̈ = J·(x + λ·M⁻¹Jᵀ)
            xs, blocks, den = solve(phi, w, y)
            ys, Jy, J1, J2, c = mobility(phi, y, blocks, den)
            lam = gate * (c - J1 * xs[0] - J2 * xs[1]) / Jy
            return [x + lam * yj for x, yj in zip(xs, ys)], lam

    return Scene(
        p,
        asm,
        free,
        contact,
        solve,
        mobility,
        asm.with_state("energy"),
        asm.with_state("tip"),
        asm.with_state("hanger"),
    )


def _elimination(m11, K1, cos, dofs):
    """(φ, ω, y) -> ([φ̈, q̈j ...], blocks, Schur denominator): (T6) for the couplings on. The loop
    is the definition; one and two couplings (the sling, a pendulum) run it unrolled, with the same
    operations in the same order (so the same bits), for speed."""
    if len(dofs) == 1:
        ((i1, c1),) = dofs

        def solve1(phi, w, y):
            b = c1(phi, w, y[i1], y[i1 + 1])
            m12, m22, f12, f2 = b
            den = m11 - m12 * m12 / m22
            x1 = (K1 * cos(phi) + f12 - m12 * f2 / m22) / den
            return [x1, (f2 - m12 * x1) / m22], (b,), den

        return solve1
    if len(dofs) == 2:
        (i1, c1), (i2, c2) = dofs

        def solve2(phi, w, y):
            b, e = c1(phi, w, y[i1], y[i1 + 1]), c2(phi, w, y[i2], y[i2 + 1])
            m12, m22, f12, f2 = b
            m13, m33, f13, f3 = e
            den = m11 - m12 * m12 / m22 - m13 * m13 / m33
            x1 = (K1 * cos(phi) + f12 + f13 - m12 * f2 / m22 - m13 * f3 / m33) / den
            return [x1, (f2 - m12 * x1) / m22, (f3 - m13 * x1) / m33], (b, e), den

        return solve2

    def solve(phi, w, y):
        f1 = K1 * cos(phi)
        den = m11
        blocks = [c(phi, w, y[i], y[i + 1]) for i, c in dofs]
        for m1j, mjj, f1j, _ in blocks:
            f1 = f1 + f1j
            den = den - m1j * m1j / mjj
        b1 = f1
        for m1j, mjj, _, fj in blocks:
            b1 = b1 - m1j * fj / mjj
        x1 = b1 / den
        return [x1] + [(fj - m1j * x1) / mjj for m1j, mjj, _, fj in blocks], blocks, den

    return solve


def initial_state(p: Machine) -> list:
    """At rest, C on the ground (T2, seed 1.3); the sling lies along the ground toward the pivot
    (γ = π, θ0 = π − φ0); a pendulum counterweight hangs straight down (ψ = 0)."""
    return [p.phi0, 0.0] + list(assemble(p, False).y0_extra)


def rhs_for(p: Machine, contact: bool):
    """The right-hand side of one phase of the swing (the scene assembled for it)."""
    return build(p, contact).rhs(contact)


def accelerations(p: Machine, phi, w, gam, gd, psi, pd, contact, sin=None, cos=None):
    """(ω̇, γ̈, ψ̈, λ) at one state, coordinates the machine lacks passed as 0 and returned as 0
    (the old one-function interface, for the tests; the swing uses the assembled Scene)."""
    xp = math if not hasattr(phi, "shape") else _numpy()
    sc = build(p, contact is not False, xp)
    y = [phi, w] + ([gam, gd] if p.sling else []) + ([psi, pd] if p.pendulum else [])
    if contact is not False:
        xs, lam = sc.contact(phi, w, y, contact)
    else:
        xs, lam = sc.free(phi, w, y), 0.0
    xs = list(xs)
    wd = xs.pop(0)
    gdd = xs.pop(0) if p.sling else 0.0
    pdd = xs.pop(0) if p.pendulum else 0.0
    return wd, gdd, pdd, lam


def _numpy():
    import numpy as np

    return np


# the scene's readings as functions of a machine and a state (tests, one-off calls)


def energy(p: Machine, y) -> tuple[float, float]:
    return build(p, False).energy(y)


def projectile(p: Machine, y) -> tuple[float, float, float, float]:
    return build(p, False).projectile(y)


def counterweight_height(p: Machine, y) -> float:
    return build(p, False).counterweight_height(y)


def sling_tension(p: Machine, y, contact: bool) -> float:
    return build(p, contact).sling_tension(y, contact)


def touchdown(p: Machine, y: list) -> list:
    return build(p, True).touchdown(y)


def onto_ground(p: Machine, y: list) -> list:
    """The state moved onto the ground constraint: y_P = 0 (by γ) and no vertical speed (by γ̇).

    The contact phase integrates the constraint's second derivative, so y_P and ẏ_P drift by the
    solver's tolerance; at lift-off they are set back exactly (a change of the order of that drift).
    """
    phi, w, gam = y[0], y[1], y[2]
    c = -(p.h + p.R * math.sin(phi)) / p.l
    if abs(c) > 1 or abs(math.cos(gam)) < 1e-9:
        return y
    gam_new = math.pi - math.asin(c) if math.cos(gam) < 0 else math.asin(c)  # keep the branch...
    gam_new += 2 * math.pi * round((gam - gam_new) / (2 * math.pi))  # ...and the turn
    gd_new = -p.R * w * math.cos(phi) / (p.l * math.cos(gam_new))  # ẏ_P = R·ω·cos φ + l·γ̇·cos γ = 0
    return [phi, w, gam_new, gd_new] + list(y[4:])


def release_cross(beta: float):
    """g(v) = u × v = |v|·sin α for the accurate run's release event (T10), u = (−cos β, sin β) the
    release direction and α the angle from u to the velocity. It is smooth in the state (no branch
    cut, so no false crossing where an angle wraps, and no window a long step can jump over short
    of a half turn past u). It rises through zero when the velocity turns counter-clockwise through
    u (α = 0: the release) and also where it turns through −u or passes through zero speed (a
    reversal): those have u·v ≤ 0 and are not releases (the caller checks, and goes on).
    """
    ux, uy = -math.cos(beta), math.sin(beta)

    def cross(vx: float, vy: float) -> float:
        return ux * vy - uy * vx

    return cross


SUBSTEPS = (0.25, 0.5, 0.75)  # dense-output points drawn inside each step (plots, lowest heights)
T_SWING = 1000.0  # s: bounds the work of a stalled scene (a near-balanced arm may take minutes)
MAX_TOUCHDOWNS = 20
MAX_RESTARTS = 200  # guard: lift-offs, touchdowns and rejected releases together (a real swing has < 25)
MAX_STEPS = 20_000  # a real swing takes < 1000 steps even at rtol 1e-11; more means a degenerate machine


@dataclass
class Swing:
    """The machine from rest to release (and on to the arm's vertical, if it is not there yet)."""

    released: bool
    ending: str  # "release", "stopped" (the arm swung back), "arm_ground", "time", "stuck", "bouncing"
    t: list  # step times
    phi: list
    omega: list
    theta: list  # sling angle relative to the arm (until release)
    path: tuple  # projectile (x, height) until release, seed frame
    release: tuple | None  # (t, x, z, vx, vy) of the projectile
    cw_drop: float  # counterweight centre's fall from rest to release
    arm_drop: float  # the arm's centre of mass's fall from rest to release (negative: it rose)
    drift: float  # max |ΔE| / max kinetic energy over the conservative phases
    vertical: tuple | None  # (t, ω) when the long arm first points straight up
    min_tension: float  # most negative sling pull before release (inf without sling)
    min_projectile_height: float
    min_counterweight_height: float
    nfev: int
    liftoff: float | None = None  # time the sling lifts the projectile off the ground
    touchdowns: int = 0  # times it fell back onto the ground afterwards (ground_contact)


@dataclass
class Trace:
    """What the swing records as it goes: plot points (steps and SUBSTEPS inside each), the energy
    (T, T + V + energy lost to touchdowns) and the sling's tension at steps, the lowest points."""

    t: list = field(default_factory=list)
    phi: list = field(default_factory=list)
    omega: list = field(default_factory=list)
    theta: list = field(default_factory=list)  # and x, z: only before release
    x: list = field(default_factory=list)
    z: list = field(default_factory=list)
    energy: list = field(default_factory=list)
    min_tension: float = math.inf
    min_height: float = math.inf  # of the projectile off the ground

    def record(
        self, sc: Scene, run, skip_first: bool, flying: bool, contact: bool, lost: float = 0.0
    ) -> None:
        from .integrate import _interp

        end = run.t[-1]
        pts = []
        for i, (t0, hs, rc) in enumerate(run.dense):
            if not (i == 0 and skip_first):
                pts.append((t0, run.y[i], True))
            for frac in SUBSTEPS:
                if (t0 + frac * hs - end) * hs < 0:
                    pts.append((t0 + frac * hs, _interp(rc, frac), False))
        pts.append((end, run.y[-1], True))
        sling = sc.sling
        for t, s, at_step in pts:
            ph = s[0]
            self.t.append(t)
            self.phi.append(ph)
            self.omega.append(s[1])
            if not flying:
                continue
            self.theta.append(s[2] - ph if sling else 0.0)
            x, z, _, _ = sc.projectile(s)
            self.x.append(x)
            self.z.append(z)
            if not contact:  # on the ground the constraint holds it (to the solver's drift)
                self.min_height = min(self.min_height, z)
            if at_step:
                T, V = sc.energy(s)
                self.energy.append((T, T + V + lost))
                if sling:
                    self.min_tension = min(self.min_tension, sc.sling_tension(s, contact))

    def drift(self) -> tuple[float, float]:
        """(max |ΔE| / max T, max T) over what was recorded."""
        KE_max = max((e[0] for e in self.energy), default=0.0)
        if KE_max <= 0:
            return 0.0, KE_max
        E0 = self.energy[0][1]
        return max(abs(e[1] - E0) for e in self.energy) / KE_max, KE_max


@dataclass
class Progress:
    """Where the swing is between two runs of the integrator."""

    t: float
    y: list
    contact: bool
    nfev: int = 0
    touchdowns: int = 0
    lost: float = 0.0  # energy taken by plastic touchdowns (the ground stops the projectile's fall)
    vertical: tuple | None = None
    liftoff: float | None = None
    cw_min: float = math.inf
    restarts: int = 0
    restart: tuple = ()  # the event the last run ended at, when the swing goes on from it
    ending: str = "time"


def _start(sc: Scene, ground_contact: bool) -> tuple[Progress, float]:
    """At rest: on the ground unless the sling pulls the projectile up at once; (progress, ω̇(0))."""
    y = [sc.p.phi0, 0.0] + list(sc.asm.y0_extra)  # (T2), as initial_state
    contact = sc.contact is not None and ground_contact
    xs, lam0 = sc.accelerations(y, contact)
    if contact and lam0 <= 0:
        contact = False  # the sling pulls the projectile up at once
        xs, _ = sc.accelerations(y, False)
    return Progress(0.0, y, contact, cw_min=sc.counterweight_height(y)), xs[0]


def _events(sc: Scene, beta: float):
    """The terminal events of the swing, and those of the ground phases (lift-off, touchdown)."""
    from .integrate import Event

    p, sin = sc.p, math.sin
    gauge = release_cross(beta)
    projectile = sc.projectile

    def release_g(t, s):
        _, _, vx, vy = projectile(s)
        return gauge(vx, vy)

    events = [
        Event("release", release_g, +1),
        Event("stopped", lambda t, s: s[1], -1),
        Event("arm_ground", lambda t, s: p.h + p.R * sin(s[0]), -1),
        Event("vertical", lambda t, s: s[0] - math.pi / 2, +1, terminal=False),
    ]
    if sc.contact is None:
        return events, None, None
    contact = sc.contact
    lift = Event("liftoff", lambda t, s: contact(s[0], s[1], s, True)[1], -1)
    touch = Event("touchdown", lambda t, s: p.h + p.R * sin(s[0]) + p.l * sin(s[2]), -1)
    return events, lift, touch


def _to_release(sc: Scene, pr: Progress, trace: Trace, beta: float, rtol: float) -> None:
    """Integrate phase after phase (on the ground, off it, back on it) until the swing ends."""
    from .integrate import integrate

    events, lift, touch = _events(sc, beta)
    rhs = {False: sc.rhs(False)}
    if sc.contact is not None:
        rhs[True] = sc.rhs(True)
    first = True
    while True:
        evs = events + ([lift] if pr.contact else [touch] if touch is not None else [])
        run = integrate(
            rhs[pr.contact],
            pr.t,
            T_SWING,
            pr.y,
            rtol=rtol,
            atol=rtol,
            events=evs,
            dense=True,
            max_steps=MAX_STEPS,
            restart=pr.restart,
        )
        pr.nfev += run.nfev
        trace.record(sc, run, not first, True, pr.contact, pr.lost)
        first = False
        pr.cw_min = min(pr.cw_min, min(sc.counterweight_height(s) for s in run.y))
        for name, tc, yc in run.crossings:
            if name == "vertical" and pr.vertical is None:
                pr.vertical = (tc, yc[1])
        pr.t, pr.y = run.t[-1], run.y[-1]
        pr.restart = (run.event,) if run.event else ()
        if run.event in ("liftoff", "touchdown", "release"):
            pr.restarts += 1
            if pr.restarts > MAX_RESTARTS:
                raise RuntimeError(f"the swing restarted {MAX_RESTARTS} times at t = {pr.t:.6g} s")
        if run.event == "liftoff":
            pr.contact = False
            pr.liftoff = pr.t
            pr.y = onto_ground(
                sc.p, pr.y
            )  # remove the constraint's drift, so the touchdown gauge starts at 0
            continue
        if run.event == "touchdown":
            if pr.touchdowns == MAX_TOUCHDOWNS:
                pr.ending = "bouncing"
                return
            pr.touchdowns += 1
            T_before = sc.energy(pr.y)[0]
            pr.y = sc.touchdown(pr.y)
            pr.lost += T_before - sc.energy(pr.y)[0]
            pr.contact = sc.accelerations(pr.y, True)[1] > 0
            continue
        if run.event == "release":
            _, _, vx, vy = sc.projectile(pr.y)
            if vx * -math.cos(beta) + vy * math.sin(beta) <= 0:  # through −u or zero speed: not a release
                if pr.y[1] <= 0:  # the velocity reversed because the arm stopped (ω = 0) here
                    pr.ending = "stopped"
                    return
                continue
        pr.ending = run.event or "time"
        return


def _on_to_vertical(sc: Scene, pr: Progress, trace: Trace, rtol: float, KE_max: float) -> float:
    """After the release the arm goes on without the projectile until it points straight up (or
    swings back); records it and returns the energy drift of this phase (relative)."""
    from .integrate import Event, integrate

    p = sc.p
    q = build(p.released(), False)
    y = pr.y
    yq = [y[0], y[1]] + ([y[-2], y[-1]] if p.pendulum else [])
    E0 = sum(q.energy(yq))
    T0 = q.energy(yq)[0]
    ev = [Event("vertical", lambda t, s: s[0] - math.pi / 2, +1), Event("stopped", lambda t, s: s[1], -1)]
    run = integrate(
        q.rhs(False), pr.t, T_SWING, yq, rtol=rtol, atol=rtol, events=ev, dense=True, max_steps=MAX_STEPS
    )
    pr.nfev += run.nfev
    trace.record(q, run, True, False, False)
    pr.cw_min = min(pr.cw_min, min(q.counterweight_height(s) for s in run.y))
    if run.event == "vertical":
        pr.vertical = (run.t[-1], run.y[-1][1])
    if T0 > 0:
        return max(abs(sum(q.energy(s)) - E0) for s in run.y) / max(T0, KE_max)
    return 0.0


def swing(p: Machine, beta: float, ground_contact: bool, rtol: float, scene: Scene | None = None) -> Swing:
    """The swing from rest (T2) to release (T10) and on to the arm's vertical: the scene assembled
    once (or `scene`, assembled by the caller for this machine and ground_contact)."""
    sc = scene or build(p, ground_contact)
    trace = Trace()
    pr, wd0 = _start(sc, ground_contact)
    cw0 = pr.cw_min
    if wd0 <= 0:  # the counterweight cannot lift the arm off the ground
        from .integrate import Run

        trace.record(sc, Run([0.0], [pr.y], 0, 0, 0), False, True, pr.contact)
        return Swing(
            False,
            "stuck",
            trace.t,
            trace.phi,
            trace.omega,
            trace.theta,
            (trace.x, trace.z),
            None,
            0.0,
            0.0,
            0.0,
            None,
            trace.min_tension,
            0.0,
            cw0,
            0,
        )
    _to_release(sc, pr, trace, beta, rtol)
    released = pr.ending == "release"
    release = (pr.t, *sc.projectile(pr.y)) if released else None
    cw_drop = cw0 - sc.counterweight_height(pr.y)
    arm_drop = p.s * (math.sin(p.phi0) - math.sin(pr.y[0]))  # its centre at height h + s·sin φ
    drift, KE_max = trace.drift()
    if released and pr.vertical is None and pr.y[1] > 0:
        drift = max(drift, _on_to_vertical(sc, pr, trace, rtol, KE_max))
    return Swing(
        released,
        pr.ending,
        trace.t,
        trace.phi,
        trace.omega,
        trace.theta,
        (trace.x, trace.z),
        release,
        cw_drop,
        arm_drop,
        drift,
        pr.vertical,
        trace.min_tension,
        min(trace.min_height, 0.0),
        pr.cw_min,
        pr.nfev,
        pr.liftoff,
        pr.touchdowns,
    )


# ---- many throws at once (numpy): the optimiser's batch ------------------------------------------

BATCH_SLINGS = 40
BATCH_ANGLES = 41  # 40 × 41 = 1640 candidate throws
STEPS_PER_TAU = 400  # fixed RK4 steps per characteristic time sqrt(I/torque)


def rk4_step(f, state: tuple, dt):
    """One classical Runge–Kutta step of ṡ = f(s) on a tuple of arrays (every candidate at once)."""
    k1 = f(state)
    k2 = f(tuple(s + 0.5 * dt * k for s, k in zip(state, k1)))
    k3 = f(tuple(s + 0.5 * dt * k for s, k in zip(state, k2)))
    k4 = f(tuple(s + dt * k for s, k in zip(state, k3)))
    return tuple(s + dt / 6 * (a + 2 * b + 2 * c + d) for s, a, b, c, d in zip(state, k1, k2, k3, k4))


def batch_swing(p: Machine, lengths, betas, ground_contact: bool):
    """Release states of every (sling length, release angle) pair, from one RK4 run per length.

    The swing does not depend on the release angle, so each length is integrated once (all
    lengths together, as numpy arrays, the scene assembled with numpy's sin and cos) and every
    angle's release is caught on the way: the signed angle from the release direction (π − β
    from +x) to the velocity, its zero located by linear interpolation within the step. Its branch
    cut sits where the projectile never moves before release (backwards and down, between π − β
    and straight down). Lift-off is caught at step ends and a fall back onto the ground is not
    modelled here: the batch only ranks candidates, and the winner is re-run with the accurate scene.
    Returns arrays (N_l, N_b): released, x, z, vx, vy at release.
    """
    import numpy as np

    from .integrate import charge

    q = replace(p, l=np.asarray(lengths, float), sling=True)
    sc = build(q, ground_contact, np)
    nl, nb = len(lengths), len(betas)
    torque = abs(p.g * (p.m * p.s - p.M * p.r))  # at rest the sling lies flat: m_p's weight is not on the arm
    tau = math.sqrt((p.I_phi + p.m_p * p.R**2) / torque)
    dt = tau / STEPS_PER_TAU
    sin, cos = np.sin, np.cos
    state = tuple(np.full(nl, v) for v in initial_state(q))
    gate = np.full(nl, 1.0)  # 1 while a candidate's projectile is on the ground (read when f runs)
    if sc.contact is not None:
        contact = sc.contact
        gate = np.where(contact(state[0], state[1], state, gate)[1] > 0, gate, 0.0)
        rhs = _interleave(lambda y: contact(y[0], y[1], y, gate)[0], len(state) // 2)
    else:
        free = sc.free
        rhs = _interleave(lambda y: free(y[0], y[1], y), len(state) // 2)

    def f(s):
        return rhs(0.0, s)

    beta = np.asarray(betas, float)[None, :]
    target = math.pi - beta
    cut = math.pi / 4 + beta / 2
    direction = (-np.cos(beta), np.sin(beta))

    def kinematics(ph, om, ga, gad):
        x = q.R * cos(ph) + q.l * cos(ga)
        z = q.h + q.R * sin(ph) + q.l * sin(ga)
        vx = -q.R * om * sin(ph) - q.l * gad * sin(ga)
        vy = q.R * om * cos(ph) + q.l * gad * cos(ga)
        return x, z, vx, vy

    def gauge(vx, vy):
        alpha = np.arctan2(vy, vx)[:, None] - target
        return alpha - 2 * math.pi * np.ceil((alpha - cut) / (2 * math.pi))  # into (cut − 2π, cut]

    kin = kinematics(*state[:4])
    g_old = gauge(kin[2], kin[3])
    released = np.zeros((nl, nb), bool)
    out = [np.zeros((nl, nb)) for _ in range(4)]
    alive = np.ones(nl, bool)
    for _ in range(int(40 * STEPS_PER_TAU)):
        charge(4 * nl)  # RK4: four evaluations per sling length (the per-solve budget, and cancel)
        state = rk4_step(f, state, dt)
        new = kinematics(*state[:4])
        g_new = gauge(new[2], new[3])
        hit = (g_old < 0) & (g_new >= 0) & ~released & alive[:, None]
        hit &= (new[2][:, None] * direction[0] + new[3][:, None] * direction[1]) > 0
        if hit.any():
            frac = np.where(hit, -g_old / np.where(hit, g_new - g_old, 1.0), 0.0)
            for o, a, b in zip(out, kin, new):
                o[hit] = (a[:, None] + frac * (b - a)[:, None])[hit]
            released |= hit
        g_old, kin = g_new, new
        if sc.contact is not None and gate.any():
            gate = np.where(sc.contact(state[0], state[1], state, gate)[1] > 0, gate, 0.0)
        alive &= (state[1] > 0) & (q.h + q.R * sin(state[0]) > 0)
        if not (alive[:, None] & ~released).any():
            break
    return released, out


def batch_ranges(released, x, z, vx, vy, g: float, k_drag: float):
    """Range toward the throw of every released candidate (−inf for the rest); vacuum in closed
    form, with drag a fixed-step RK4 (rk4_step) over all candidates together."""
    import numpy as np

    from .flight import landing_time
    from .integrate import charge

    ux, uy = -vx, vy  # toward the throw
    ok = released & (z > 0)
    z0 = np.where(ok, z, 1.0)
    t_vac = landing_time(uy, z0, g)  # (V3), every candidate at once
    X = ux * t_vac
    if k_drag > 0 and ok.any():
        T = float(np.max(np.where(ok, t_vac, 0.0)))
        n = 400
        dt = T / n
        s = (np.zeros_like(z0), z0.copy(), np.where(ok, ux, 0.0), np.where(ok, uy, 0.0))
        landed = ~ok
        Xd = np.zeros_like(z0)

        def f(s):
            qx, qz = s[2], s[3]
            speed = np.sqrt(qx * qx + qz * qz)
            return qx, qz, -k_drag * speed * qx, -g - k_drag * speed * qz

        for _ in range(2 * n):  # drag only shortens the flight: 2·T is ample
            charge(4)  # (one vectorised evaluation over the candidates counts as one: cancel is polled)
            new = rk4_step(f, s, dt)
            px, pz, nx, nz = s[0], s[1], new[0], new[1]
            down = ~landed & (nz <= 0)
            if down.any():
                frac = pz / np.where(down, pz - nz, 1.0)
                Xd = np.where(down, px + frac * (nx - px), Xd)
                landed |= down
            s = new
            if landed.all():
                break
        X = np.where(landed, Xd, s[0])
    return np.where(ok, -x + X, np.where(released, -x, -np.inf))


def optimise(p: Machine, v, lo: float, hi: float):
    """(best release angle, best sling length, candidates) over the grid, or None."""
    import numpy as np

    # At rest the sling lies flat (γ = π): the sling takes none of the projectile's weight and the
    # ground's push does not reach the arm, so ω̇(0) ∝ M·r − m·s whatever m_p (not M·r − m·s − m_p·R)
    torque = p.g * (p.m * p.s - p.M * p.r)
    if torque >= 0:  # the arm cannot lift (see swing's "stuck"): nothing to optimise
        return None
    lengths = np.linspace(lo, hi, BATCH_SLINGS) if hi > lo else np.array([lo])
    betas = np.linspace(5 * math.pi / 180, 85 * math.pi / 180, BATCH_ANGLES)
    effects = v["effects"]
    k_drag = 0.0
    if "air_drag" in effects:
        from .flight import air

        k_drag = air(
            effects, p.m_p, v["projectile_diameter"], v["drag_coefficient"], 0.0, v["air_density"], 0.0, p.g
        ).k_drag
    # A fixed step can be unstable for an extreme machine: such candidates turn non-finite and drop out
    # (the winner is re-run with the adaptive solver anyway).
    with np.errstate(all="ignore"):
        released, (x, z, vx, vy) = batch_swing(p, lengths, betas, "ground_contact" in effects)
        ranges = batch_ranges(released, x, z, vx, vy, p.g, k_drag)
    ranges = np.where(np.isfinite(ranges), ranges, -np.inf)
    if not np.isfinite(ranges).any():
        return None
    i, j = np.unravel_index(int(np.argmax(ranges)), ranges.shape)
    return float(betas[j]), float(lengths[i]), int(ranges.size)
