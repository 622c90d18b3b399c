"""Equations of motion of a counterweight trebuchet (seed 001), derived by Lagrange.

Geometry (the seed's frame): pivot A at (0, h); the arm direction e = (cos φ, sin φ), φ from the
horizontal, φ = 0 pointing right. Long end C = A + R·e with R = (1 − a)·L; counterweight hinge
B = A − r·e with r = a·L; the arm's centre of mass at s·e with s = L/2 − a·L. The counterweight
starts up on the left and falls, so φ grows from φ0 < 0 through 90° (arm vertical) and C swings
over the top to the left: the throw goes toward −x.

Generalised coordinates (all angles absolute, from +x, counter-clockwise):
    φ  the arm;  γ = φ + θ  the sling (θ is the seed's sling angle relative to the arm);
    ψ  the counterweight hanger, from straight down (only with a pendulum counterweight).
Projectile P = A + R·e + l·(cos γ, sin γ);  counterweight centre B + d·(sin ψ, −cos ψ).

    T = ½·(I_φ + m_p·R²)·ω² + m_p·R·l·cos(γ−φ)·ω·γ̇ + ½·m_p·l²·γ̇²
        − M·r·d·sin(ψ−φ)·ω·ψ̇ + ½·M·(d² + k²)·ψ̇²
    V = g·[(m·s − M·r + m_p·R)·sin φ + m_p·l·sin γ − M·d·cos ψ]        (+ const)

with I_φ = m·L²·(1/12 + (1/2 − a)²) + M·(aL)² [+ M·k² when the counterweight is rigid] (seed 1.2).
Lagrange's equations M(q)·q̈ = f(q, q̇):
    M11 = I_φ + m_p·R²,  M12 = m_p·R·l·cos(γ−φ),  M22 = m_p·l²,
    M13 = −M·r·d·sin(ψ−φ),  M33 = M·(d² + k²),  M23 = 0
    f1 = m_p·R·l·sin(γ−φ)·γ̇² + M·r·d·cos(ψ−φ)·ψ̇² − g·(m·s − M·r + m_p·R)·cos φ
    f2 = −m_p·R·l·sin(γ−φ)·ω² − g·m_p·l·cos γ
    f3 = −M·r·d·cos(ψ−φ)·ω² − g·M·d·sin ψ
(checked against a sympy Lagrangian in tests/test_trebuchet.py). The arm alone (no sling) carries
the projectile in a cup at C: the same equations with l = 0 and no γ. Ground contact adds the
constraint y_P = h + R·sin φ + l·sin γ = 0 with multiplier λ (the ground's normal force):
    M·q̈ = f + Jᵀ·λ,  J·q̈ = R·sin φ·ω² + l·sin γ·γ̇²,  J = (R·cos φ, l·cos γ, 0).

Every function here takes `sin`, `cos` so the same lines serve one throw (math, plain floats,
fast) and a batch of candidate throws (numpy arrays).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace


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
        """Inertia about A of arm and counterweight turning with φ (seed 1.2: I_tot)."""
        I = self.I_arm + self.M * self.r**2
        if self.rigid:
            I += self.M * self.k**2  # rigid: the counterweight turns with the arm
        return I

    @property
    def phi0(self) -> float:
        return math.asin(-self.h / self.R)  # seed 1.3: sin φ0 = −h/((1−a)L), C on the ground

    def released(self) -> "Machine":
        """The machine after the projectile has left: no projectile, no sling."""
        return replace(self, m_p=0.0, sling=False)


def accelerations(p: Machine, phi, w, gam, gd, psi, pd, contact, sin, cos):
    """(ω̇, γ̈, ψ̈, λ) from Lagrange's equations; λ is the ground's push on the projectile.

    `contact` (bool, or an array of 0/1) switches the ground constraint on; coordinates the
    machine lacks (no sling / no pendulum) may be passed as 0 and come back as 0.
    """
    R, l, g = p.R, p.l, p.g
    m11 = p.I_phi + p.m_p * R * R
    f1 = -g * (p.m * p.s - p.M * p.r + p.m_p * R) * cos(phi)
    # Block elimination of M·x = b (M23 = 0):
    #   x1 = (b1 − M12·b2/M22 − M13·b3/M33) / (M11 − M12²/M22 − M13²/M33), x2 = (b2 − M12·x1)/M22, ...
    den = m11
    if p.sling:
        A = p.m_p * R * l
        cd, sd = cos(gam - phi), sin(gam - phi)
        m12, m22 = A * cd, p.m_p * l * l
        f1 = f1 + A * sd * gd * gd
        f2 = -A * sd * w * w - g * p.m_p * l * cos(gam)
        den = den - m12 * m12 / m22
    if p.pendulum:
        B = p.M * p.r * p.d
        ce, se = cos(psi - phi), sin(psi - phi)
        m13, m33 = -B * se, p.M * (p.d * p.d + p.k * p.k)
        f1 = f1 + B * ce * pd * pd
        f3 = -B * ce * w * w - g * p.M * p.d * sin(psi)
        den = den - m13 * m13 / m33
    b1 = f1
    if p.sling:
        b1 = b1 - m12 * f2 / m22
    if p.pendulum:
        b1 = b1 - m13 * f3 / m33
    x1 = b1 / den
    x2 = (f2 - m12 * x1) / m22 if p.sling else 0.0
    x3 = (f3 - m13 * x1) / m33 if p.pendulum else 0.0
    lam = 0.0
    if p.sling:
        # M·y = Jᵀ with J = (R·cos φ, l·cos γ, 0); then λ from J·(x + λ·y) = R·sin φ·ω² + l·sin γ·γ̇²
        J1, J2 = R * cos(phi), l * cos(gam)
        y1 = (J1 - m12 * J2 / m22) / den
        y2 = (J2 - m12 * y1) / m22
        y3 = -m13 * y1 / m33 if p.pendulum else 0.0
        Jy = J1 * y1 + J2 * y2  # J·M⁻¹·Jᵀ > 0 unless J = 0 (arm and sling both vertical)
        if contact is not False:
            rhs_c = R * sin(phi) * w * w + l * sin(gam) * gd * gd
            lam = contact * (rhs_c - J1 * x1 - J2 * x2) / Jy
            x1 = x1 + lam * y1
            x2 = x2 + lam * y2
            x3 = x3 + lam * y3
    return x1, x2, x3, lam


# ---- one throw (plain floats) -------------------------------------------------------------------
# State vector: [φ, ω] + [γ, γ̇] with a sling + [ψ, ψ̇] with a pendulum counterweight.

def unpack(p: Machine, y):
    phi, w = y[0], y[1]
    i = 2
    gam = gd = psi = pd = 0.0
    if p.sling:
        gam, gd = y[2], y[3]
        i = 4
    if p.pendulum:
        psi, pd = y[i], y[i + 1]
    return phi, w, gam, gd, psi, pd


def rhs_for(p: Machine, contact: bool):
    sin, cos = math.sin, math.cos
    sling, pendulum = p.sling, p.pendulum

    def rhs(t, y):
        phi, w, gam, gd, psi, pd = unpack(p, y)
        wd, gdd, pdd, _ = accelerations(p, phi, w, gam, gd, psi, pd, contact, sin, cos)
        out = [w, wd]
        if sling:
            out += [gd, gdd]
        if pendulum:
            out += [pd, pdd]
        return out

    return rhs


def energy(p: Machine, y) -> tuple[float, float]:
    """(T, V) of the machine and projectile; V from the pivot height (a constant apart)."""
    phi, w, gam, gd, psi, pd = unpack(p, y)
    R, l = p.R, p.l
    T = 0.5 * (p.I_phi + p.m_p * R * R) * w * w
    V = p.g * (p.m * p.s - p.M * p.r + p.m_p * R) * math.sin(phi)
    if p.sling:
        T += p.m_p * R * l * math.cos(gam - phi) * w * gd + 0.5 * p.m_p * l * l * gd * gd
        V += p.g * p.m_p * l * math.sin(gam)
    if p.pendulum:
        T += -p.M * p.r * p.d * math.sin(psi - phi) * w * pd + 0.5 * p.M * (p.d**2 + p.k**2) * pd * pd
        V += -p.g * p.M * p.d * math.cos(psi)
    return T, V


def projectile(p: Machine, y) -> tuple[float, float, float, float]:
    """Projectile (x, height above ground, vx, vy) in the seed's frame (cup at C without sling)."""
    phi, w, gam, gd, psi, pd = unpack(p, y)
    R = p.R
    x, z = R * math.cos(phi), p.h + R * math.sin(phi)
    vx, vy = -R * w * math.sin(phi), R * w * math.cos(phi)
    if p.sling:
        x += p.l * math.cos(gam)
        z += p.l * math.sin(gam)
        vx -= p.l * gd * math.sin(gam)
        vy += p.l * gd * math.cos(gam)
    return x, z, vx, vy


def counterweight_height(p: Machine, y) -> float:
    phi, w, gam, gd, psi, pd = unpack(p, y)
    z = p.h - p.r * math.sin(phi)
    if p.pendulum:
        z -= p.d * math.cos(psi)
    return z


def sling_tension(p: Machine, y, contact: bool) -> float:
    """Pull of the sling on the projectile (negative: the sling would have to push).

    m_p·a_P = −T·u − m_p·g·ŷ + λ·ŷ, u = (cos γ, sin γ) from C to P, so
    T = −m_p·(a_P·u) − m_p·g·sin γ + λ·sin γ with a_P·u = R·ω̇·sin(γ−φ) − R·ω²·cos(γ−φ) − l·γ̇².
    """
    phi, w, gam, gd, psi, pd = unpack(p, y)
    wd, gdd, pdd, lam = accelerations(p, phi, w, gam, gd, psi, pd, contact, math.sin, math.cos)
    d = gam - phi
    a_u = p.R * wd * math.sin(d) - p.R * w * w * math.cos(d) - p.l * gd * gd
    return -p.m_p * a_u - p.m_p * p.g * math.sin(gam) + lam * math.sin(gam)


def release_gauge(beta: float):
    """g(v) for the batch's release event: the signed angle from the release direction to the velocity.

    The release direction points up at β over the horizontal toward the throw (−x): angle π − β
    from +x. The velocity turns counter-clockwise as the sling whips, so the event is a rising zero.
    The branch cut sits in the direction the projectile never moves before release (backwards
    and down, between π − β and straight down). The accurate run uses `release_cross` instead.
    """
    target = math.pi - beta
    cut = math.pi / 4 + beta / 2
    two_pi = 2 * math.pi

    def gauge(vx: float, vy: float) -> float:
        alpha = math.atan2(vy, vx) - target
        while alpha > cut:
            alpha -= two_pi
        while alpha <= cut - two_pi:
            alpha += two_pi
        return alpha

    return gauge


def release_cross(beta: float):
    """g(v) = u × v = |v|·sin α for the accurate run's release event, u = (−cos β, sin β) the release
    direction and α the angle from u to the velocity. It is smooth in the state (no branch cut, so
    no false crossing where an angle wraps, and no window a long step can jump over short of a half
    turn past u). It rises through zero when the velocity turns counter-clockwise through u (α = 0:
    the release) and also where it turns through −u or passes through zero speed (a reversal):
    those have u·v ≤ 0 and are not releases (the caller checks, and goes on).
    """
    ux, uy = -math.cos(beta), math.sin(beta)

    def cross(vx: float, vy: float) -> float:
        return ux * vy - uy * vx

    return cross


SUBSTEPS = (0.25, 0.5, 0.75)  # dense-output points drawn inside each step (plots, lowest heights)
T_SWING = 1000.0  # s: bounds the work of a stalled scene (a near-balanced arm may take minutes)


@dataclass
class Swing:
    """The machine from rest to release (and on to the arm's vertical, if it is not there yet)."""

    released: bool
    ending: str  # "release", "stopped" (the arm swung back), "arm_ground", "time", "stuck"
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


def initial_state(p: Machine) -> list:
    """At rest, C on the ground (seed 1.3); the sling lies along the ground toward the pivot
    (γ = π, θ0 = π − φ0); a pendulum counterweight hangs straight down (ψ = 0)."""
    y = [p.phi0, 0.0]
    if p.sling:
        y += [math.pi, 0.0]
    if p.pendulum:
        y += [0.0, 0.0]
    return y


MAX_TOUCHDOWNS = 20
MAX_RESTARTS = 200  # guard: lift-offs, touchdowns and rejected releases together (a real swing has < 25)
MAX_STEPS = 20_000  # a real swing takes < 1000 steps even at rtol 1e-11; more means a degenerate machine


def touchdown(p: Machine, y: list) -> list:
    """State after the projectile lands on the ground (plastic: its vertical speed goes to zero).

    The ground's impulse Λ acts along Jᵀ: q̇⁺ = q̇⁻ − M⁻¹·Jᵀ·(J·q̇⁻)/(J·M⁻¹·Jᵀ), so that J·q̇⁺ = 0
    (the impulsive form of the contact constraint; it only removes energy).
    """
    phi, w, gam, gd, psi, pd = unpack(p, y)
    R, l = p.R, p.l
    A = p.m_p * R * l
    m12, m22 = A * math.cos(gam - phi), p.m_p * l * l
    den = p.I_phi + p.m_p * R * R - m12 * m12 / m22
    J1, J2 = R * math.cos(phi), l * math.cos(gam)
    m13 = m33 = 1.0
    if p.pendulum:
        m13, m33 = -p.M * p.r * p.d * math.sin(psi - phi), p.M * (p.d**2 + p.k**2)
        den -= m13 * m13 / m33
    y1 = (J1 - m12 * J2 / m22) / den
    y2 = (J2 - m12 * y1) / m22
    y3 = -m13 * y1 / m33 if p.pendulum else 0.0
    Jy = J1 * y1 + J2 * y2
    lam = (J1 * w + J2 * gd) / Jy if Jy > 0 else 0.0
    out = [phi, w - lam * y1, gam, gd - lam * y2]
    if p.pendulum:
        out += [psi, pd - lam * y3]
    return out


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


def swing(p: Machine, beta: float, ground_contact: bool, rtol: float) -> Swing:
    from .integrate import Event, Run, _interp, integrate

    atol = rtol
    sin, cos = math.sin, math.cos
    y = initial_state(p)
    contact = p.sling and ground_contact
    wd0, _, _, lam0 = accelerations(p, *unpack(p, y), contact, sin, cos)
    if contact and lam0 <= 0:
        contact = False  # the sling pulls the projectile up at once
        wd0 = accelerations(p, *unpack(p, y), False, sin, cos)[0]
    t_, phi_, w_, th_, xs, zs, E_ = [], [], [], [], [], [], []
    min_T = math.inf
    min_z = math.inf
    nfev = 0

    def record(machine, run, skip_first, in_flight_phase, contact_now):
        """Plot points (steps and 3 dense-output points inside each), energy and tension at steps."""
        nonlocal min_T, min_z
        end = run.t[-1]
        pts = []
        for i, (t0, hs, rc) in enumerate(run.dense):
            if not (i == 0 and skip_first):
                pts.append((t0, run.y[i], True))
            for frac in SUBSTEPS:
                if (t0 + frac * hs - end) * hs < 0:
                    pts.append((t0 + frac * hs, _interp(rc, frac), False))
        pts.append((end, run.y[-1], True))
        for t, s, at_step in pts:
            ph, w, gam, *_ = unpack(machine, s)
            t_.append(t)
            phi_.append(ph)
            w_.append(w)
            if in_flight_phase:
                th_.append(gam - ph if machine.sling else 0.0)
                x, z, _, _ = projectile(machine, s)
                xs.append(x)
                zs.append(z)
                if not contact_now:  # on the ground the constraint holds it (to the solver's drift)
                    min_z = min(min_z, z)
                if at_step:
                    T, V = energy(machine, s)
                    E_.append((T, T + V))
                    if machine.sling:
                        min_T = min(min_T, sling_tension(machine, s, contact_now))

    cw0 = counterweight_height(p, y)
    if wd0 <= 0:  # the counterweight cannot lift the arm off the ground
        record(p, Run([0.0], [y], 0, 0, 0), False, True, contact)
        return Swing(False, "stuck", t_, phi_, w_, th_, (xs, zs), None, 0.0, 0.0, 0.0, None,
                     min_T, 0.0, cw0, 0)
    gauge = release_cross(beta)

    def release_g(t, s):
        _, _, vx, vy = projectile(p, s)
        return gauge(vx, vy)

    events = [Event("release", release_g, +1),
              Event("stopped", lambda t, s: s[1], -1),
              Event("arm_ground", lambda t, s: p.h + p.R * sin(s[0]), -1),
              Event("vertical", lambda t, s: s[0] - math.pi / 2, +1, terminal=False)]
    lift = Event("liftoff", lambda t, s: accelerations(p, *unpack(p, s), True, sin, cos)[3], -1)
    touch = Event("touchdown", lambda t, s: p.h + p.R * sin(s[0]) + p.l * sin(s[2]), -1)
    touchdowns = 0
    lost = 0.0  # energy taken by plastic touchdowns (the ground stops the projectile's fall)
    t = 0.0
    vertical = None
    liftoff = None
    ending = "time"
    cw_min = cw0
    first = True
    restart: tuple = ()  # the event the last run ended at, when the swing goes on from it
    restarts = 0
    while True:
        evs = events + ([lift] if contact else [touch] if ground_contact and p.sling else [])
        run = integrate(rhs_for(p, contact), t, T_SWING, y, rtol=rtol, atol=atol, events=evs, dense=True,
                        max_steps=MAX_STEPS, restart=restart)
        nfev += run.nfev
        n_E = len(E_)
        record(p, run, not first, True, contact)
        E_[n_E:] = [(T, E + lost) for T, E in E_[n_E:]]
        first = False
        cw_min = min(cw_min, min(counterweight_height(p, s) for s in run.y))
        for name, tc, yc in run.crossings:
            if name == "vertical" and vertical is None:
                vertical = (tc, yc[1])
        t, y = run.t[-1], run.y[-1]
        restart = (run.event,) if run.event else ()
        if run.event in ("liftoff", "touchdown", "release"):
            restarts += 1
            if restarts > MAX_RESTARTS:
                raise RuntimeError(f"the swing restarted {MAX_RESTARTS} times at t = {t:.6g} s")
        if run.event == "liftoff":
            contact = False
            liftoff = t
            y = onto_ground(p, y)  # remove the constraint's drift, so the touchdown gauge starts at 0
            continue
        if run.event == "touchdown":
            if touchdowns == MAX_TOUCHDOWNS:
                ending = "bouncing"
                break
            touchdowns += 1
            T_before = energy(p, y)[0]
            y = touchdown(p, y)
            lost += T_before - energy(p, y)[0]
            contact = accelerations(p, *unpack(p, y), True, sin, cos)[3] > 0
            continue
        if run.event == "release":
            _, _, vx, vy = projectile(p, y)
            if vx * -math.cos(beta) + vy * math.sin(beta) <= 0:  # through −u or zero speed: not a release
                if y[1] <= 0:  # the velocity reversed because the arm stopped (ω = 0) here
                    ending = "stopped"
                    break
                continue
        ending = run.event or "time"
        break
    released = ending == "release"
    release = (t, *projectile(p, y)) if released else None
    cw_drop = cw0 - counterweight_height(p, y)
    arm_drop = p.s * (math.sin(p.phi0) - math.sin(y[0]))  # its centre at height h + s·sin φ
    KE_max = max((e[0] for e in E_), default=0.0)
    drift = max(abs(e[1] - E_[0][1]) for e in E_) / KE_max if KE_max > 0 else 0.0
    if released and vertical is None and y[1] > 0:
        # the arm goes on without the projectile until it points straight up
        q = p.released()
        yq = [y[0], y[1]] + ([y[-2], y[-1]] if p.pendulum else [])
        E0 = sum(energy(q, yq))
        T0 = energy(q, yq)[0]
        ev = [Event("vertical", lambda t, s: s[0] - math.pi / 2, +1),
              Event("stopped", lambda t, s: s[1], -1)]
        run = integrate(rhs_for(q, False), t, T_SWING, yq, rtol=rtol, atol=atol, events=ev, dense=True,
                        max_steps=MAX_STEPS)
        nfev += run.nfev
        record(q, run, True, False, False)
        cw_min = min(cw_min, min(counterweight_height(q, s) for s in run.y))
        if run.event == "vertical":
            vertical = (run.t[-1], run.y[-1][1])
        if T0 > 0:
            drift = max(drift, max(abs(sum(energy(q, s)) - E0) for s in run.y) / max(T0, KE_max))
    return Swing(released, ending, t_, phi_, w_, th_, (xs, zs), release, cw_drop, arm_drop, drift, vertical,
                 min_T, min(min_z, 0.0), cw_min, nfev, liftoff, touchdowns)


# ---- many throws at once (numpy): the optimiser's batch ------------------------------------------

BATCH_SLINGS = 40
BATCH_ANGLES = 41  # 40 × 41 = 1640 candidate throws
STEPS_PER_TAU = 400  # fixed RK4 steps per characteristic time sqrt(I/torque)


def batch_swing(p: Machine, lengths, betas, ground_contact: bool):
    """Release states of every (sling length, release angle) pair, from one RK4 run per length.

    The swing does not depend on the release angle, so each length is integrated once (all
    lengths together, as numpy arrays) and every angle's release is caught on the way: the same
    gauge as the accurate run, its zero located by linear interpolation within the step. Lift-off
    is caught at step ends and a fall back onto the ground is not modelled here: the batch only
    ranks candidates, and the winner is re-run with the accurate scene.
    Returns arrays (N_l, N_b): released, x, z, vx, vy at release.
    """
    import numpy as np

    q = replace(p, l=np.asarray(lengths, float), sling=True)
    nl, nb = len(lengths), len(betas)
    torque = abs(p.g * (p.m * p.s - p.M * p.r))  # at rest the sling lies flat: m_p's weight is not on the arm
    tau = math.sqrt((p.I_phi + p.m_p * p.R**2) / torque)
    dt = tau / STEPS_PER_TAU
    sin, cos = np.sin, np.cos
    phi = np.full(nl, p.phi0)
    w = np.zeros(nl)
    gam = np.full(nl, math.pi)
    gd = np.zeros(nl)
    psi = np.zeros(nl)
    pd = np.zeros(nl)
    contact = np.full(nl, 1.0 if ground_contact else 0.0)
    _, _, _, lam = accelerations(q, phi, w, gam, gd, psi, pd, contact, sin, cos)
    contact = np.where(lam > 0, contact, 0.0)
    beta = np.asarray(betas, float)[None, :]
    target = math.pi - beta
    cut = math.pi / 4 + beta / 2
    direction = (-np.cos(beta), np.sin(beta))

    def f(s):
        ph, om, ga, gad, ps, psd = s
        a1, a2, a3, _ = accelerations(q, ph, om, ga, gad, ps, psd, contact, sin, cos)
        return (om, a1, gad, a2, psd, a3)

    def kinematics(ph, om, ga, gad):
        x = q.R * cos(ph) + q.l * cos(ga)
        z = q.h + q.R * sin(ph) + q.l * sin(ga)
        vx = -q.R * om * sin(ph) - q.l * gad * sin(ga)
        vy = q.R * om * cos(ph) + q.l * gad * cos(ga)
        return x, z, vx, vy

    def gauge(vx, vy):
        alpha = np.arctan2(vy, vx)[:, None] - target
        return alpha - 2 * math.pi * np.ceil((alpha - cut) / (2 * math.pi))  # into (cut − 2π, cut]

    state = (phi, w, gam, gd, psi, pd)
    kin = kinematics(phi, w, gam, gd)
    g_old = gauge(kin[2], kin[3])
    released = np.zeros((nl, nb), bool)
    out = [np.zeros((nl, nb)) for _ in range(4)]
    alive = np.ones(nl, bool)
    from .integrate import charge

    for _ in range(int(40 * STEPS_PER_TAU)):
        charge(4 * nl)  # RK4: four evaluations per sling length (the per-solve budget, and cancel)
        k1 = f(state)
        k2 = f(tuple(s + 0.5 * dt * k for s, k in zip(state, k1)))
        k3 = f(tuple(s + 0.5 * dt * k for s, k in zip(state, k2)))
        k4 = f(tuple(s + dt * k for s, k in zip(state, k3)))
        state = tuple(s + dt / 6 * (a + 2 * b + 2 * c + d) for s, a, b, c, d in zip(state, k1, k2, k3, k4))
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
        if contact.any():
            lam = accelerations(q, *state, contact, sin, cos)[3]
            contact = np.where(lam > 0, contact, 0.0)
        alive &= (state[1] > 0) & (q.h + q.R * sin(state[0]) > 0)
        if not (alive[:, None] & ~released).any():
            break
    return released, out


def batch_ranges(released, x, z, vx, vy, g: float, k_drag: float):
    """Range toward the throw of every released candidate (−inf for the rest); vacuum in closed
    form, with drag a fixed-step RK4 over all candidates together."""
    import numpy as np

    ux, uy = -vx, vy  # toward the throw
    ok = released & (z > 0)
    z0 = np.where(ok, z, 1.0)
    t_vac = (uy + np.sqrt(np.maximum(uy * uy + 2 * g * z0, 0.0))) / g
    X = ux * t_vac
    if k_drag > 0 and ok.any():
        T = float(np.max(np.where(ok, t_vac, 0.0)))
        n = 400
        dt = T / n
        px, pz, qx, qz = np.zeros_like(z0), z0.copy(), np.where(ok, ux, 0.0), np.where(ok, uy, 0.0)
        landed = ~ok
        Xd = np.zeros_like(z0)

        def acc(qx, qz):
            speed = np.sqrt(qx * qx + qz * qz)
            return -k_drag * speed * qx, -g - k_drag * speed * qz

        from .integrate import charge

        for _ in range(2 * n):  # drag only shortens the flight: 2·T is ample
            charge(4)  # (one vectorised evaluation over the candidates counts as one: cancel is polled)
            s = (px, pz, qx, qz)
            d1 = (qx, qz, *acc(qx, qz))
            s2 = tuple(a + 0.5 * dt * b for a, b in zip(s, d1))
            d2 = (s2[2], s2[3], *acc(s2[2], s2[3]))
            s3 = tuple(a + 0.5 * dt * b for a, b in zip(s, d2))
            d3 = (s3[2], s3[3], *acc(s3[2], s3[3]))
            s4 = tuple(a + dt * b for a, b in zip(s, d3))
            d4 = (s4[2], s4[3], *acc(s4[2], s4[3]))
            nx, nz, nqx, nqz = (a + dt / 6 * (b + 2 * c + 2 * d + e) for a, b, c, d, e in zip(s, d1, d2, d3, d4))
            down = ~landed & (nz <= 0)
            if down.any():
                frac = pz / np.where(down, pz - nz, 1.0)
                Xd = np.where(down, px + frac * (nx - px), Xd)
                landed |= down
            px, pz, qx, qz = nx, nz, nqx, nqz
            if landed.all():
                break
        X = np.where(landed, Xd, px)
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

        k_drag = air(effects, p.m_p, v["projectile_diameter"], v["drag_coefficient"], 0.0, v["air_density"],
                     0.0, p.g).k_drag
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
