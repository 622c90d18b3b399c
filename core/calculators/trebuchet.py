"""Seed 001 (kastmaskin): a counterweight trebuchet as a scene with effects.

The machine (seed's nominal values): counterweight M with radius of gyration k on the short arm
aL, arm of mass m and length L turning about a pivot at height h, projectile m_p on a sling of
length l at the long end C. Starts at rest with C on the ground (seed 1.3). Equations of motion:
core/sim/trebuchet.py (Lagrange, checked against sympy in the tests).

Scenes from the effects:
- none: the arm alone, one degree of freedom; the projectile rides in a cup at C and the
  counterweight is rigid (inertia M·k² about its centre, seed 1.2 "stel");
- `hinged_counterweight`: hanger length 0 is the seed's hinged counterweight (k drops out of
  I_tot, seed 1.2 "gångjärnsledd"); a hanger length d > 0 makes it a pendulum (one more degree of
  freedom, beyond the seed);
- `sling`: the seed's section 2 (two degrees of freedom, θ relative to the arm);
- `ground_contact`: the projectile starts on the ground and slides (frictionless) until the sling
  lifts it (the ground's push, a Lagrange multiplier, falls to zero);
- `air_drag`: the flight after release with quadratic drag (core/sim/flight.py); without it the
  flight is the vacuum parabola in closed form (C1).
The effects (their fields and outputs) are declared in core.sim.trebuchet.EFFECTS, which assembles
the swing's equations from those on, once per solve.

Modes (an action is a mode, not an effect):
- `throw`: one throw at the release angle and sling length entered;
- `optimise`: that throw, and the release angle and sling length of longest range: a grid of 1640
  candidate throws integrated together (numpy, fixed-step RK4, one swing per sling length serves
  every release angle), then the best polished by Nelder–Mead on accurate single throws (rtol 1e-8).
  `optimise` used to be an effect: an `effects` list that still names it is read as mode =
  optimise, with a notice (core.sim.effects.RetiredFlags; a preset file is rewritten on loading).

Flight and energy (beside the swing's (T1)-(T10) in core/sim/trebuchet.py):
    vacuum: t_land = (v·sin β + √(v²·sin²β + 2·g·z0))/g,  X = v·cos β·t_land,
            apex = z0 + (v·sin β)²/(2g)                                                   (C1)
    efficiency = (½·m_p·v² + m_p·g·Δz_p) / (g·(M·Δz_cw + m·Δz_arm)), drops from rest to release (C2)
(Δz of each centre of mass: the projectile's rise, the counterweight's and the arm's drops.)
`energy_drift` is max|E(t) − E(0)| / max T over the swing, E = T + V of (T4) plus the energy plastic
touchdowns (T8) took: the solver's error alone (a touchdown's loss is booked, not counted).
`arm_speed_at_vertical` and `time_to_vertical` read the swing (seed 1.5: φ and ω over time) at the
event where the long arm first points straight up; after release the arm swings on alone.

Frame: the seed's, φ from the horizontal, φ = 0 to the right. The counterweight starts up on the
left, so C swings up and over the top to the left: the throw goes toward −x (the side away from
where the projectile lay). Release happens when the projectile's velocity points up at the
release angle over the horizontal, toward the throw. `range` is measured from the pivot toward
the throw; the path plot shows x toward the throw (the projectile starts behind the pivot).

Departures from the seed:
- The seed's moment and energy lines, M_m = C·sin φ and V = C·cos φ with C = M·g·aL −
  m·g·(L/2 − aL), measure φ from the downward vertical (long arm hanging straight down, where
  both are consistent: −d(C·cos φ)/dφ = C·sin φ), not from the horizontal as it states. With φ from
  the horizontal (and the projectile in the cup) V = −(C − m_p·g·R)·sin φ and the moment is
  −dV/dφ = (C − m_p·g·R)·cos φ.
- The seed's pivot-force lines F_n = (mL/2)·ω² − ..., F_s = (mL/2)·ω̇ − ... put the arm's centre
  of mass at L/2 from the pivot; it is at L/2 − aL (they are not used here).
- The seed's section-1 model has no projectile; here the arm alone carries it in a cup at C
  (the seed's model is the limit m_p → 0).
- Efficiency: the projectile's energy at release over the potential energy released by the
  counterweight AND the arm (each by its centre of mass): T + V is conserved, so this is at most 1.
  Counting the counterweight's drop alone gave more than 100 % when the arm's centre of mass lies
  on the counterweight's side (a > 1/2) and falls with it.
"""

from __future__ import annotations

import math

from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field
from ..sim import trebuchet as tb
from ..sim.scene import STATS_OUTPUTS, SimRun, accuracy_field, run_with_stats, solve_budget

EFFECTS = tb.EFFECTS
MODES = ("throw", "optimise")
RETIRED = (("optimise", "mode", "optimise"),)  # once an effect; a preset naming it means the mode
DEG = math.pi / 180
PLOT_POINTS = 240
ADVICE = (
    "accuracy",
    "the swing is too long or too stiff for this accuracy (a short hanger or a nearly "
    "balanced arm): try accuracy=coarse, a longer hanger_length or a heavier counterweight",
)
# optimise: the batch (1640 throws) and up to 200 accurate throws; the built-in preset takes ~400 000
OPTIMISE_NFEV = 3_000_000
REFINE_NFEV = 60_000  # the polish; the built-in preset takes ~23 000
OPTIMISE_ADVICE = (
    "mode",
    "optimise needs too much work for this machine (a short hanger or a nearly "
    "balanced arm makes every throw long or stiff): solve one throw instead, or "
    "lengthen hanger_length",
)

FIELDS = (
    Field(
        "mode",
        "Solve",
        choices=MODES,
        default="throw",
        choice_labels=(
            "One throw at the release angle and sling entered",
            "Optimise: the release angle and sling length of longest range",
        ),
        help="One throw, or also the release angle and sling length that throw furthest (a grid of "
        "1640 throws, then polished on accurate throws).",
    ),
    Field(
        "counterweight_mass",
        "Counterweight mass M",
        "mass",
        "kg",
        default=500,
        min=1e-3,
        max=1e7,
        help="Counterweight mass.",
    ),
    Field(
        "counterweight_gyration",
        "Counterweight gyration k",
        "length",
        "m",
        default=2,
        min=0,
        max=1e3,
        help="Radius of gyration of the counterweight about its centre (its inertia is M·k²); "
        "unused when it is hinged at its centre (hinged_counterweight, hanger 0), since it then does not turn.",
    ),
    Field(
        "arm_mass",
        "Arm mass m",
        "mass",
        "kg",
        default=50,
        min=0,
        max=1e7,
        help="Mass of the throwing arm (a uniform bar).",
    ),
    Field(
        "arm_length",
        "Arm length L",
        "length",
        "m",
        default=15,
        min=1e-2,
        max=1e3,
        help="Length of the throwing arm, counterweight hinge B to long end C.",
    ),
    Field(
        "short_arm_fraction",
        "Short-arm fraction a",
        default=0.25,
        min=0,
        max=1,
        min_exclusive=True,
        max_exclusive=True,
        help="Pivot to counterweight hinge as a fraction of L (short arm aL, long arm (1−a)L).",
    ),
    Field(
        "pivot_height",
        "Pivot height h",
        "length",
        "m",
        default=4,
        min=0,
        min_exclusive=True,
        max=1e3,
        help="Height of the pivot A above the ground; must be below the long arm (1−a)L so C rests on the ground.",
    ),
    Field(
        "projectile_mass",
        "Projectile mass m_p",
        "mass",
        "kg",
        default=5,
        min=1e-3,
        max=1e7,
        help="Projectile mass.",
    ),
    Field(
        "gravity",
        "Gravity g",
        "acceleration",
        "m/s**2",
        default=9.81,
        min=0.1,
        max=100,
        help="Gravitational acceleration.",
    ),
    Field(
        "release_angle",
        "Release angle",
        "angle",
        "deg",
        default=45,
        min=0,
        max=89,
        help="Release when the projectile's velocity points this far above the horizontal, toward the throw.",
    ),
    EFFECTS.field(
        "sling (2 DOF), ground_contact (projectile slides until lifted), hinged_counterweight "
        "(hinge or pendulum), air_drag (flight).",
        retired=RETIRED,
    ),
    *EFFECTS.fields(),
    Field(
        "sling_min",
        "Optimise: shortest sling",
        "length",
        "m",
        default=1,
        min=1e-2,
        max=1e3,
        help="optimise: the sling lengths searched start here.",
        modes=("optimise",),
    ),
    Field(
        "sling_max",
        "Optimise: longest sling",
        "length",
        "m",
        default=12,
        min=1e-2,
        max=1e3,
        help="optimise: the sling lengths searched end here.",
        modes=("optimise",),
    ),
    accuracy_field(),
)

OUTPUTS = (
    Output(
        "release_time",
        "Release time",
        "time",
        "s",
        equation="(T6), (T10)",
        help="When the projectile's velocity first points up at the release angle toward the throw (a swing event).",
    ),
    Output(
        "release_speed",
        "Release speed",
        "speed",
        "m/s",
        equation="§2.1, (T3)",
        help="The projectile's speed at release, from the arm's and the sling's rates.",
    ),
    Output(
        "release_angle",
        "Release angle",
        "angle",
        "deg",
        equation="(T10)",
        help="Of the velocity at release, above the horizontal toward the throw (the release condition).",
    ),
    Output(
        "release_height",
        "Release height",
        "length",
        "m",
        equation="§2.1, (T3)",
        help="The projectile's height above the ground at release, h + R·sin φ + l·sin γ.",
    ),
    Output(
        "range",
        "Range",
        "length",
        "m",
        equation="(T3), (C1)",
        help="Pivot to landing point toward the throw: release point plus flight (vacuum, or with air_drag).",
    ),
    Output(
        "max_height",
        "Max height",
        "length",
        "m",
        equation="(C1)",
        help="Highest point of the projectile's path: over the swing, or the flight's apex.",
    ),
    Output(
        "efficiency",
        "Efficiency",
        "dimensionless",
        "%",
        equation="(C2), (T4)",
        help="Projectile energy at release (kinetic + potential) over the potential energy the counterweight and arm lose.",
    ),
    *EFFECTS.outputs(),
    Output(
        "arm_speed_at_vertical",
        "Arm speed at vertical",
        "angular_speed",
        "rad/s",
        equation="§1.5, (T6)",
        help="The arm's angular speed when the long arm first points straight up (it swings on alone after release).",
    ),
    Output(
        "time_to_vertical",
        "Time to vertical",
        "time",
        "s",
        equation="§1.5, (T6)",
        help="From rest until the long arm points straight up (an event on the swing).",
    ),
    Output(
        "energy_drift",
        "Energy drift",
        equation="§1.5, (T4)",
        help="The solver's error: largest change of total energy T + V over the swing, over the largest kinetic energy.",
    ),
    *(
        Output(name, label, quantity, unit, equation="(T6), (T10), (C1)", help=f"optimise: {how}")
        for name, label, quantity, unit, how in (
            (
                "best_release_angle",
                "Best release angle",
                "angle",
                "deg",
                "the release angle of longest range (grid of batch throws, then Nelder–Mead on accurate throws).",
            ),
            (
                "best_sling_length",
                "Best sling length",
                "length",
                "m",
                "the sling length of longest range, within the lengths searched.",
            ),
            (
                "best_range",
                "Best range",
                "length",
                "m",
                "the range of the best throw, by the accurate scene.",
            ),
        )
    ),
    Output(
        "candidates",
        "Candidates evaluated",
        help="optimise: throws evaluated in the batch (40 sling lengths × 41 release angles).",
    ),
    *STATS_OUTPUTS,
)


def effects_on(v) -> frozenset:
    """The physics switched on (a retired name, e.g. 'optimise', is not physics)."""
    return v["effects"] - {name for name, _, _ in RETIRED}


def optimising(v) -> bool:
    return v["mode"] == "optimise"  # an old 'optimise' among the effects is read as the mode (retire)


def machine(v, sling: bool | None = None, l: float | None = None) -> tb.Machine:
    effects = effects_on(v)
    a, L, h = v["short_arm_fraction"], v["arm_length"], v["pivot_height"]
    if h >= (1 - a) * L:
        raise InputError(
            "pivot_height",
            f"must be below the long arm (1−a)·L = {(1 - a) * L:.4g} m, "
            "so that the long end C can rest on the ground",
        )
    hinged = "hinged_counterweight" in effects
    p = tb.Machine(
        M=v["counterweight_mass"],
        k=v["counterweight_gyration"],
        m=v["arm_mass"],
        L=L,
        a=a,
        h=h,
        m_p=v["projectile_mass"],
        l=v["sling_length"] if l is None else l,
        g=v["gravity"],
        rigid=not hinged,
        d=v["hanger_length"] if hinged else 0.0,
        sling=("sling" in effects) if sling is None else sling,
    )
    check_inertia(p)
    return p


def check_inertia(p: tb.Machine) -> None:
    """Refuse a machine whose arm can lose (nearly) all its inertia about the pivot in some
    configuration (Machine.least_inertia): the equations of motion are singular there, and the
    swing's elimination divided by zero (or by rounding noise) instead."""
    least, m11 = p.released().least_inertia()
    if least < tb.MIN_INERTIA_RATIO * m11:
        # After release the arm's own inertia about the pivot is I_arm + M·r²·k²/(d² + k²) (the
        # pendulum's block eliminated) whenever the hanger lies in line with the arm (ψ − φ = ±90°,
        # e.g. hanging straight down under an upright arm): 0 for a massless arm and a point
        # counterweight (no unique motion), rounding noise for a near-massless one.
        raise InputError(
            "arm_mass",
            f"is too small for a counterweight of gyration {p.k:.3g} m on a {p.d:.3g} m hanger: once "
            f"the projectile has left, the arm's inertia about the pivot falls to {least:.3g} kg·m² "
            f"when the hanger lies in line with the arm ({least / m11:.1e} of its {m11:.3g} kg·m², below "
            f"the {tb.MIN_INERTIA_RATIO:.0e} the swing resolves): a heavier arm, a larger "
            "counterweight_gyration or a shorter hanger_length",
        )
    least, m11 = p.least_inertia()
    if least < tb.MIN_INERTIA_RATIO * m11:
        # Before release the sling along the arm takes the projectile's whole m_p·R² off it: what
        # is left is the arm and counterweight's own inertia.
        raise InputError(
            "projectile_mass",
            f"is too heavy for this arm: when the sling lies along the arm, the arm's inertia about "
            f"the pivot is {least:.3g} kg·m², {least / m11:.1e} of the projectile's m_p·R² "
            f"({m11 - least:.3g} kg·m²), below the {tb.MIN_INERTIA_RATIO:.0e} the swing resolves: "
            "a lighter projectile, a heavier counterweight or arm, or a longer short arm",
        )


def sample(ts: list, ys: list, n: int = PLOT_POINTS) -> tuple[list, list]:
    """At most n points of a series, for plotting."""
    if len(ts) <= n:
        return list(ts), list(ys)
    step = (len(ts) - 1) / (n - 1)
    idx = sorted({round(i * step) for i in range(n)})
    return [ts[i] for i in idx], [ys[i] for i in idx]


def fly(v, g: float, z0: float, speed: float, angle: float, rtol: float):
    """(distance from the release point toward the throw, apex, path xs, path zs, nfev)."""
    from ..sim import flight  # the solve's (its dataclasses, ~3 ms): not the card's description

    t_land = flight.vacuum_landing_time(z0, angle, speed, g)  # (V3), from z0 > 0
    X = flight.vacuum_range(z0, angle, speed, g)
    if "air_drag" not in v["effects"]:
        xs, zs = flight.vacuum_path(z0, angle, speed, t_land, PLOT_POINTS - 1, g)
        zs[-1] = 0.0
        return X, flight.vacuum_apex(z0, angle, speed, t_land, 0.0, g), xs, zs, 0  # (V2)
    air = flight.air(
        v["effects"],
        v["projectile_mass"],
        v["projectile_diameter"],
        v["drag_coefficient"],
        0.0,
        v["air_density"],
        0.0,
        g,
    )
    try:
        f = flight.fly(air, z0, angle, speed, 2 * X + 1.0, rtol)
    except RuntimeError as exc:
        raise InputError(
            "projectile_diameter",
            f"the flight could not be integrated ({exc}): drag far too large for the projectile's mass",
        ) from None
    xs, zs = sample(*f.path)
    if f.t >= flight.T_MAX * (1 - 1e-9):
        raise InputError(
            "projectile_diameter",
            f"the projectile is still in the air after {flight.T_MAX:.0f} s "
            "(drag far too large for its mass)",
        )
    return f.x_end, f.apex, xs, zs, f.nfev


def simulate(v, rtol: float) -> SimRun:
    """One throw: the swing (the scene assembled once from the effects on), then the flight."""
    effects = effects_on(v)
    p = machine(v)
    sc = tb.build(p, "ground_contact" in effects)
    s = _swing(p, sc, v["release_angle"], rtol)
    # the results whose error is estimated; all present in every run (0 when absent), so a run at
    # a tighter tolerance that ends differently (e.g. no release) shows as a large error estimate
    key = dict.fromkeys(
        ("release_time", "release_speed", "range", "time_to_vertical", "arm_speed_at_vertical"), 0.0
    )
    values: dict = {"energy_drift": s.drift}
    if s.vertical is not None:
        values["time_to_vertical"], values["arm_speed_at_vertical"] = s.vertical
        key["time_to_vertical"], key["arm_speed_at_vertical"] = s.vertical
    values.update(sc.asm.report(s))  # the effects' own outputs (liftoff_time)
    warnings = swing_warnings(s, p, effects)
    series = {"φ arm": sample(s.t, s.phi), "ω arm": sample(s.t, s.omega)}
    if p.sling:
        series["θ sling"] = sample(s.t[: len(s.theta)], s.theta)
    # the projectile path, x toward the throw (−x of the seed's frame)
    path = ([-x for x in s.path[0]], list(s.path[1]))
    if not s.released:
        why = {
            "stuck": "the counterweight cannot lift the arm off the ground",
            "stopped": "the arm swings back first",
            "arm_ground": "the arm hits the ground first",
            "time": f"not within {tb.T_SWING:.0f} s",
            "bouncing": f"the projectile falls back onto the ground {tb.MAX_TOUCHDOWNS} times",
        }[s.ending]
        warnings.append(f"The throw never releases at {v['release_angle'] / DEG:.4g}°: {why}.")
        series["projectile"] = sample(*path)
        return SimRun(values, key, s.nfev, warnings, series)
    nfev = s.nfev + release_and_flight(v, p, s, rtol, values, key, warnings, path)
    series["projectile"] = sample(*path, 2 * PLOT_POINTS)
    return SimRun(values, key, nfev, warnings, series)


def _swing(p: tb.Machine, sc: tb.Scene, beta: float, rtol: float) -> tb.Swing:
    try:
        return tb.swing(p, beta, sc.contact is not None, rtol, scene=sc)
    except RuntimeError as exc:  # step-size underflow: a machine too stiff to resolve
        raise InputError(
            "sling_length" if p.sling else "projectile_mass",
            f"the swing could not be integrated ({exc}); the machine's proportions are too extreme",
        ) from None


def swing_warnings(s: tb.Swing, p: tb.Machine, effects) -> list[str]:
    """What the swing says about its own validity (a sling that pushes, a projectile or a
    counterweight through the ground, ...), in the order they are shown."""
    warnings = []
    if s.vertical is None:
        warnings.append("The long arm never points straight up: the counterweight cannot raise it that far.")
    if "ground_contact" in effects and not p.sling:
        warnings.append("ground_contact needs the sling (without it the projectile rides in a cup at C).")
    scale = p.L * 1e-5  # deeper than the solver's drift
    if s.min_tension < 0:
        warnings.append(
            f"The sling would push (compression {-s.min_tension:.3g} N) before release: a real sling "
            "goes slack there, so the rigid-sling result is not valid."
        )
    if s.min_projectile_height < -scale:
        warnings.append(
            f"The projectile goes {-s.min_projectile_height:.3g} m below the ground before release "
            "(switch on ground_contact)."
        )
    if s.touchdowns:
        warnings.append(
            f"The projectile falls back onto the ground {s.touchdowns} time(s) after lift-off "
            "(plastic landing: energy is lost, see energy drift)."
        )
    if s.min_counterweight_height < -scale:
        warnings.append(
            f"The counterweight's centre goes {-s.min_counterweight_height:.3g} m below the ground: "
            "raise the pivot or shorten the short arm or hanger."
        )
    return warnings


def release_and_flight(
    v,
    p: tb.Machine,
    s: tb.Swing,
    rtol: float,
    values: dict,
    key: dict,
    warnings: list,
    path: tuple[list, list],
) -> int:
    """The release, the efficiency (C2) and the flight (C1, or integrated with drag) into values,
    key, warnings and the path; returns the flight's right-hand-side evaluations."""
    t_r, x_r, z_r, vx, vy = s.release
    speed = math.hypot(vx, vy)
    angle = math.atan2(vy, -vx)  # toward the throw
    values.update(release_time=t_r, release_speed=speed, release_angle=angle, release_height=z_r)
    key.update(release_time=t_r, release_speed=speed)
    # Energy balance from rest to release (T + V conserved; the ground's push does no work, a plastic
    # touchdown only takes energy): E_p + T_machine = M·g·Δz_cw + m·g·Δz_arm, so the potential energy
    # released by the counterweight AND the arm (each by its centre of mass) is what the throw is
    # paid from, and E_p over it is at most 1 (the rest is the machine's own motion at release).
    E_p = 0.5 * p.m_p * speed**2 + p.m_p * p.g * (z_r - s.path[1][0])
    supplied = p.g * (p.M * s.cw_drop + p.m * s.arm_drop)
    if supplied > 0:
        values["efficiency"] = max(E_p, 0.0) / supplied  # (C2)
        if values["efficiency"] > 1:  # the energy balance cannot give more: it is the solver's error
            warnings.append(
                f"The efficiency ({values['efficiency'] * 100:.4g} %) is above 100 %: that is the "
                f"simulation's error at this accuracy (rtol {rtol:.0e}); choose a finer accuracy."
            )
    n_fly = 0
    if z_r > 0:
        X, apex, fx, fz, n_fly = fly(v, p.g, z_r, speed, angle, rtol)
        path[0].extend(-x_r + x for x in fx[1:])
        path[1].extend(fz[1:])
    else:
        X, apex = 0.0, z_r
        warnings.append("The projectile is released below ground level: it lands where it is released.")
    values["range"] = -x_r + X
    values["max_height"] = max(apex, max(s.path[1]))
    key["range"] = values["range"]
    return n_fly


def refine(v, beta: float, l: float, lo: float, hi: float) -> tuple[float, float, float, bool]:
    """Polish the grid's best throw with accurate single throws (Nelder–Mead inside the search box).
    Within REFINE_NFEV evaluations: past them the polish stops at the best throw found so far
    (the last value is False then; a stiff machine makes every accurate throw costly)."""
    from scipy.optimize import minimize

    from ..sim.integrate import BudgetExceeded, budget

    effects = effects_on(v) | {"sling"}
    scale = max(abs(l), 1.0)
    best = [math.inf, None]

    def miss(x):
        b, length = x[0], x[1] * scale
        if not (5 * DEG <= b <= 85 * DEG and lo <= length <= hi):
            return 1e30
        try:
            run = simulate(dict(v, release_angle=b, sling_length=length, effects=effects), 1e-8)
        except InputError:
            return 1e30
        f = -run.values.get("range", -1e30)
        if f < best[0]:
            best[:] = [f, (float(b), float(length))]
        return f

    try:
        with budget(REFINE_NFEV) as spent:
            start = -miss([beta, l / scale])
            res = minimize(
                miss,
                [beta, l / scale],
                method="Nelder-Mead",
                options={
                    "xatol": 1e-5,
                    "fatol": 1e-9 * scale,
                    "maxfev": 200,
                    "initial_simplex": [
                        [beta, l / scale],
                        [beta + 2 * DEG, l / scale],
                        [beta, l / scale * 1.05],
                    ],
                },
            )
    except BudgetExceeded as exc:
        if exc.budget is not spent:
            raise
        if best[1] is None:
            return beta, l, -1e30, False
        return best[1][0], best[1][1], -best[0], False
    if -res.fun >= start:
        return float(res.x[0]), float(res.x[1] * scale), float(-res.fun), True
    return beta, l, start, True


def compute(v, estimate: str = "now") -> Result:
    run = run_with_stats(simulate, v, ADVICE, estimate)
    if optimising(v):
        with solve_budget(OPTIMISE_ADVICE, max_nfev=OPTIMISE_NFEV):
            _optimise(v, run)
    return Result(run.values, run.warnings, run.series)


def _optimise(v, run: SimRun) -> None:
    """The best release angle and sling length, into run (values and warnings)."""
    from ..sim.trebuchet import optimise

    lo, hi = v["sling_min"], v["sling_max"]
    if lo > hi:
        raise InputError("sling_min", "must not exceed the longest sling searched")
    best = optimise(machine(v, sling=True), v, lo, hi)
    if best is None:
        run.warnings.append("optimise: no candidate throw released.")
    else:
        beta, l, n = best
        beta, l, reach, polished = refine(v, beta, l, lo, hi)
        if not polished:
            run.warnings.append(
                f"optimise: the polish of the best throw stopped after {REFINE_NFEV} evaluations "
                "(every accurate throw of this machine is costly): the best shown is the best "
                "found so far, not the optimum to the last digit."
            )
        if reach > -1e29:
            run.values.update(best_release_angle=beta, best_sling_length=l, best_range=reach, candidates=n)
            # the best throw's own validity (sling pushing, projectile through the ground, ...):
            # the warnings above are about the throw at the entered angle and sling length
            effects = effects_on(v) | {"sling"}
            best_run = simulate(dict(v, release_angle=beta, sling_length=l, effects=effects), 1e-8)
            run.warnings += [f"optimise, best throw: {w}" for w in best_run.warnings if w not in run.warnings]


CALCULATOR = Calculator(
    id="trebuchet",
    title="Trebuchet",
    summary="Counterweight trebuchet from rest to landing: arm, sling, ground contact, hinged counterweight, drag.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="001",
    simulate=simulate,
    plots=(
        Plot(
            "Projectile path", ("projectile",), "x toward the throw", "length", "m", "height", "length", "m"
        ),
        Plot("Arm and sling angles", ("φ arm", "θ sling"), "time", "time", "s", "angle", "angle", "deg"),
        Plot("Arm speed", ("ω arm",), "time", "time", "s", "ω", "angular_speed", "rad/s"),
    ),
)
