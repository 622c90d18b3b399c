"""Seed section 6 (Appendix D): the projectile trajectory calculator, as a scene with flight effects.

Heights are above the floor, d is the horizontal distance from release to target, angles are from
the horizontal (negative: downward), g = 9.80665 m/s².
Forward (h_i, θ_i, v_i, d → h_f, θ_f):
    t   = d / (v_i·cos θ_i)                                         (103)
    h_f = h_i + (v_i·sin θ_i − g·t/2)·t = h_i + d·tan θ_i − g·d²/(2 v_i² cos² θ_i)    (104), (61)
    θ_f = atan2(v_i·sin θ_i − g·t, v_i·cos θ_i)                     (105), equal to (62)
Reverse (h_i, h_f, d, θ_f → θ_i, v_i), derived again (sympy) from (103)-(105) with Δh = h_f − h_i:
    m   = Δh − d·tan θ_f  (= d·tan θ_i − Δh = g·t²/2, how far gravity pulls the ball below the line
                            of the release direction; it must be positive)
    θ_i = atan2(Δh + m, d)                                          (63): tan θ_i = 2Δh/d − tan θ_f
    t   = sqrt(2m/g),  v_i = hypot(d, Δh + m) / t                   (64) corrected
Departures from / corrections to the seed:
- (64) takes |tan θ_i − tan θ_f|. The derivation (107) gives v_i² cos² θ_i = g·d / (tan θ_i − tan θ_f)
  with no absolute value: the arc bends down, so the target angle must lie below the straight line
  from release to target, θ_f < atan(Δh/d). The seed's |·| returns a finite speed for targets no
  thrown ball can meet; here that is an error naming `target_angle`. At equality (θ_i = θ_f, both
  on the line of sight) the speed is infinite: also an error.
- (64) is evaluated as hypot(d, Δh + m)/sqrt(2m/g): the seed's sec θ_i·sqrt(g·d/(tan θ_i − tan θ_f))
  loses digits when θ_i nears 90° (tan θ_i huge) and when m is small (tan θ_i − tan θ_f cancels
  after tan θ_i was rounded); here m is one subtraction of the inputs.
- Added, not in the seed: time of flight, apex (highest point between release and target), speed at
  the target, and the floor: a ball that reaches the floor before the target distance is an error
  naming `distance`.
Effects (core.sim.effects parts, their physics in core.sim.flight): `air_drag` (quadratic, C_d,
frontal area, air density; (F1)) and `magnus` (lift C_L·½ρA|v|² perpendicular to the path, upward
for backspin; (F2)). Each declares its fields here and adds its term to the flight's slot "accel";
`magnus` also reports the spin ratio S = |ω|·r/v_i (P1) that guides the choice of C_L. With no term
(no effect on, or only ones with a zero coefficient) the answer is the closed form above (core.sim.
flight (V1)-(V3), the one copy), with no integration. With terms, forward integrates to the target distance;
reverse finds θ_i and v_i by root finding (hybrid Powell) from the vacuum answer (or, when Magnus lift
from backspin bends the path upward so that no vacuum answer exists, from a throw above the line).
Where that misses (strong effects bend the path far from the parabola), continuation: the effects are
grown from 0 to full (or θ_f is moved up from below the line) in steps, each solve starting from the
last root; the path is followed with flights at rtol ≤ 1e-6 and the root polished at the chosen rtol.
"""

from __future__ import annotations

import dataclasses
import math

from ..constants import G0 as G
from ..declarations import Calculator, Output, Plot
from ..errors import InputError
from ..fields import Field
from ..sim import flight
from ..sim.effects import Effect, Effects
from ..sim.flight import Air, aim, aim_along, fly, vacuum_apex, vacuum_at, vacuum_path, vacuum_range
from ..sim.scene import STATS_OUTPUTS, SimRun, accuracy_field, compute_with_stats

HALF_PI = math.pi / 2
PATH_POINTS = 80
MAX_STEPS = 5_000  # per flight (a real throw takes < 100): a path curled up by extreme Magnus lift is
MAX_FLIGHTS = 150  # refused, not crawled along; the reverse root finder may try this many flights
MAX_NFEV = (
    50_000  # and this much work in all, continuation included (about 0.3 s; a found root takes < 10 000)
)
CONTINUATION_RTOL = 1e-6  # the reverse root is found with flights at most this tight, then polished at rtol
MIN_DISTANCE = 1e-3  # m, both modes: below it a reverse answer's θ_i rounds to 90° (forward then refuses it)
FLOOR_SLACK = 1e-9  # relative: a target on the floor (h_f = 0) is reached, not "hit the floor first"

MODES = ("forward", "reverse")
MODE_LABELS = ("Forward: where the ball goes", "Reverse: how to throw it")

_MASS = Field(
    "ball_mass",
    "Ball mass",
    "mass",
    "kg",
    default=0.27,
    min=1e-3,
    max=100,
    help="Mass of the game piece (2022 FRC cargo: 0.27 kg).",
)
_DIAMETER = Field(
    "ball_diameter",
    "Ball diameter",
    "length",
    "m",
    default=0.24,
    min=1e-3,
    max=2,
    help="Diameter; the frontal area is π·D²/4 (2022 FRC cargo: 0.24 m).",
)
_DENSITY = Field(
    "air_density",
    "Air density",
    "density",
    "kg/m^3",
    default=1.204,
    min=0,
    max=2,
    help="ρ (1.204 kg/m³ at 20 °C and sea level; ≈ 1.0 at 1600 m).",
)


def _magnus(values, body):
    """(F2), and the spin ratio (P1) at release: |ω|·r/v_i, r = D/2."""
    spin, D = values["spin"], values["ball_diameter"]
    return dataclasses.replace(
        flight.magnus_build(values, body),
        report=lambda run: {"spin_ratio": abs(spin) * D / 2 / run["release_speed"]},
    )


EFFECTS = Effects(
    Effect(
        "air_drag",
        "quadratic drag",
        flight.drag_build,
        fields=(
            _MASS,
            _DIAMETER,
            Field(
                "drag_coefficient",
                "Drag coefficient",
                default=0.47,
                min=0,
                max=2,
                help="C_d for `air_drag` (smooth sphere ≈ 0.47, foam ball ≈ 0.5).",
            ),
            _DENSITY,
        ),
    ),
    Effect(
        "magnus",
        "spin lift",
        _magnus,
        fields=(
            _MASS,
            _DIAMETER,
            Field(
                "lift_coefficient",
                "Lift coefficient",
                default=0.2,
                min=0,
                max=1,
                help="C_L for `magnus`, constant over the flight. It grows with the spin ratio "
                "ω·r/v (shown as an output): about 0.1-0.3 for spin ratios 0.1-0.4.",
            ),
            Field(
                "spin",
                "Spin",
                "angular_speed",
                "rpm",
                default=0,
                min=-9.5e5,
                max=9.5e5,
                help="Spin of the ball; positive is backspin (lifts), negative topspin (drops). Its "
                "sign sets the direction of the Magnus force, C_L sets its size; 0: no Magnus "
                "force.",
            ),
            _DENSITY,
        ),
        outputs=(
            Output(
                "spin_ratio",
                "Spin ratio ω·r/v",
                equation="(P1)",
                help="|ω|·r/v_i at release (r = D/2); guides the choice of C_L (magnus).",
            ),
        ),
    ),
)
_EFFECT_FIELDS = {f.name: f for f in EFFECTS.fields()}

FIELDS = (
    Field(
        "mode",
        "Solve",
        choices=MODES,
        choice_labels=MODE_LABELS,
        default="forward",
        help="Forward: from the release to the target height and angle (6.1). "
        "Reverse: from the target to the release angle and speed (6.2).",
    ),
    Field(
        "release_height",
        "Release height",
        "length",
        "m",
        default=0.6,
        min=0,
        max=1000,
        help="Height h_i of the ball above the floor when it leaves the mechanism.",
    ),
    Field(
        "release_angle",
        "Release angle",
        "angle",
        "deg",
        default=60,
        min=-90,
        max=90,
        min_exclusive=True,
        max_exclusive=True,
        modes=("forward",),
        help="Angle θ_i of the release velocity above the horizontal.",
    ),
    Field(
        "release_speed",
        "Release speed",
        "speed",
        "m/s",
        default=7.5,
        min=0,
        min_exclusive=True,
        max=10_000,
        modes=("forward",),
        help="Speed v_i of the ball as it leaves the mechanism.",
    ),
    Field(
        "distance",
        "Distance to target",
        "length",
        "m",
        default=3,
        min=MIN_DISTANCE,
        max=10_000,
        help="Horizontal distance d from the release point to the target (at least 1 mm: "
        "closer, the release angle of a reverse solve rounds to 90°, which no throw has).",
    ),
    Field(
        "target_height",
        "Target height",
        "length",
        "m",
        default=2.64,
        min=0,
        max=1000,
        modes=("reverse",),
        help="Height h_f above the floor where the ball must pass.",
    ),
    Field(
        "target_angle",
        "Target angle",
        "angle",
        "deg",
        default=-45,
        min=-90,
        max=90,
        min_exclusive=True,
        max_exclusive=True,
        modes=("reverse",),
        help="Angle θ_f of the ball's path at the target (negative: coming down). It must be "
        "below the line from release to target: a thrown ball curves downward (only strong "
        "backspin with `magnus` can bend it up).",
    ),
    EFFECTS.field(
        "air_drag (quadratic drag), magnus (spin lift). None: the seed's closed form, no integration."
    ),
    accuracy_field(),
    *(
        _EFFECT_FIELDS[n]
        for n in ("ball_mass", "ball_diameter", "drag_coefficient", "lift_coefficient", "spin", "air_density")
    ),
)

OUTPUTS = (
    Output(
        "target_height",
        "Target height",
        "length",
        "m",
        equation="(61)",
        help="h_f: height at the target distance; (61) in vacuum, else the integrated flight.",
    ),
    Output(
        "target_angle",
        "Target angle",
        "angle",
        "deg",
        equation="(62)",
        help="θ_f: path angle at the target, atan2(v_y, v_x) there; (62) = (105) in vacuum.",
    ),
    Output(
        "release_angle",
        "Release angle",
        "angle",
        "deg",
        equation="(63)",
        help="θ_i; (63) in vacuum, else root finding on the integrated flight.",
    ),
    Output(
        "release_speed",
        "Release speed",
        "speed",
        "m/s",
        equation="(64)",
        help="v_i; (64) corrected (no |·|) in vacuum, else root finding on the integrated flight.",
    ),
    Output(
        "time_of_flight",
        "Time of flight",
        "time",
        "s",
        equation="(103)",
        help="From release to the target distance: d/(v_i·cos θ_i) in vacuum, else the integrated flight.",
    ),
    Output(
        "apex_height",
        "Apex height",
        "length",
        "m",
        equation="(V2)",
        help="Highest point between release and target (the target height if still rising).",
    ),
    Output(
        "target_speed",
        "Speed at target",
        "speed",
        "m/s",
        equation="(105)",
        help="|v| at the target: hypot(v_i·cos θ_i, v_i·sin θ_i − g·t) in vacuum, else integrated.",
    ),
    *EFFECTS.outputs(),
    *STATS_OUTPUTS,
)


# --- closed form (no effects): core.sim.flight (V1)-(V3) ------------------------------------


def line_angle(h_i: float, h_f: float, d: float) -> float:
    """Angle of the straight line from release to target: θ_f must lie below it."""
    return math.atan2(h_f - h_i, d)


def reverse_vacuum(h_i: float, h_f: float, d: float, theta_f: float) -> tuple[float, float, float]:
    """(θ_i, v_i, t) from (63) and the corrected (64); InputError if no thrown ball arrives so."""
    dh = h_f - h_i
    m = dh - d * math.tan(theta_f)  # = d·tan θ_i − Δh = g·t²/2 > 0
    if not m > 0:
        raise InputError("target_angle", _too_high(h_i, h_f, d, theta_f))
    theta_i = math.atan2(dh + m, d)  # (63)
    t = math.sqrt(2 * m / G)  # (104) with (103)
    v_i = math.hypot(d, dh + m) / t  # (64), corrected (no |·|)
    if not v_i <= 10_000:
        raise InputError(
            "target_angle",
            f"is so close to the line from release to target "
            f"({math.degrees(line_angle(h_i, h_f, d)):.6g}°) that it needs a release speed of "
            f"{v_i:.3g} m/s: choose a steeper downward target angle",
        )
    return theta_i, v_i, t


def _too_high(h_i, h_f, d, theta_f) -> str:
    line = math.degrees(line_angle(h_i, h_f, d))
    return (
        f"{math.degrees(theta_f):.6g}° cannot be reached: a thrown ball curves downward, so it must "
        f"arrive below the straight line from release to target ({line:.6g}°); even on that line it "
        f"would need infinite speed"
    )


def _floor_error(x: float) -> InputError:
    return InputError(
        "distance",
        f"is beyond where the ball comes down to the floor "
        f"(x = {max(x, 0.0):.4g} m): it never reaches the target distance",
    )


def _parabola(h_i, theta_i, v_i, t_end):
    return vacuum_path(h_i, theta_i, v_i, t_end, PATH_POINTS, G)


# --- the scene ----------------------------------------------------------------------------------


def scene_air(v) -> Air:
    """The flight effects that are on, assembled once for this solve."""
    return flight.assemble(
        EFFECTS, v["effects"], v, flight.Body.of(G, v["ball_mass"], v["ball_diameter"], v["air_density"])
    )


def _check_release(h_i: float, theta_i: float) -> None:
    if h_i == 0 and theta_i <= 0:
        raise InputError("release_angle", "must point upward when the ball is released at floor level")


def _fly(a: Air, h_i, theta_i, v_i, d, rtol, samples=0):
    try:
        f = fly(
            a,
            h_i,
            theta_i,
            v_i,
            d,
            rtol,
            ground=-FLOOR_SLACK * max(1.0, d),
            samples=samples,
            max_steps=MAX_STEPS,
        )
    except RuntimeError:  # step limit: a flight no solver budget covers
        raise InputError(
            "spin",
            "the flight curls up too tightly to integrate (Magnus force far "
            "above gravity): lower the lift coefficient or the spin",
        ) from None
    if not f.reached:
        raise _floor_error(f.x_end)
    return f


def _reverse_with_effects(a: Air, h_i, h_f, d, theta_f, rtol, series) -> tuple[float, float, int]:
    """_search within MAX_NFEV evaluations, every flight counted (those that fail too): past it,
    ValueError (no release found)."""
    from ..sim.integrate import BudgetExceeded, budget

    try:
        with budget(MAX_NFEV) as spent:
            return _search(a, h_i, h_f, d, theta_f, rtol, series)
    except BudgetExceeded as exc:
        if exc.budget is not spent:
            raise
        raise ValueError(f"no release found within {MAX_NFEV} right-hand-side evaluations") from None


def _search(a: Air, h_i, h_f, d, theta_f, rtol, series) -> tuple[float, float, int]:
    """(θ_i, v_i, nfev) with flight effects. First hybrid Powell straight from the vacuum answer; if
    that misses (the effects bend the path far from the parabola), continuation: the effects grown
    from 0 to full in steps, each solve starting from the last root. A target above the line of sight
    (backspin only) has no vacuum answer: solve for an angle below the line, then move θ_f up to it."""
    spent = [0]
    limits = dict(max_flights=MAX_FLIGHTS, max_steps=MAX_STEPS, max_nfev=MAX_NFEV)
    rtol_path = max(rtol, CONTINUATION_RTOL)  # the path is followed cheaply, the end polished at rtol

    def polish(guess):
        if rtol >= rtol_path:
            return guess
        return aim(a, h_i, h_f, d, theta_f, rtol, guess, spent=spent, **limits)[:2]

    def from_vacuum(theta_target):
        vac = reverse_vacuum(h_i, h_f, d, theta_target)
        try:
            return aim(a, h_i, h_f, d, theta_target, rtol_path, vac[:2], spent=spent, **limits)[:2]
        except (ValueError, RuntimeError):
            grow = lambda s: (a.scaled(s), theta_target)  # noqa: E731
            return aim_along(grow, h_i, h_f, d, rtol_path, vac[:2], spent, **limits)

    try:
        vac = reverse_vacuum(h_i, h_f, d, theta_f)
    except InputError:
        if a.k_magnus <= 0:  # drag and topspin only bend the path further down
            raise
        line = line_angle(h_i, h_f, d)  # backspin may lift it: start just above the line
        guess = (min(line + 0.2, 1.4), math.sqrt(G / a.k_magnus) * 2)
        try:
            theta_i, v_i = polish(aim(a, h_i, h_f, d, theta_f, rtol_path, guess, spent=spent, **limits)[:2])
        except (ValueError, RuntimeError):
            below = max(line - 0.1, -HALF_PI + 0.05)  # reachable in vacuum: start there
            start = from_vacuum(below)
            move = lambda s: (a, below + s * (theta_f - below))  # noqa: E731
            theta_i, v_i = polish(aim_along(move, h_i, h_f, d, rtol_path, start, spent, **limits))
        return theta_i, v_i, spent[0]
    series["vacuum"] = _parabola(h_i, vac[0], vac[1], vac[2])
    theta_i, v_i = polish(from_vacuum(theta_f))
    return theta_i, v_i, spent[0]


def simulate(v, rtol: float) -> SimRun:
    a = scene_air(v)
    h_i, d = v["release_height"], v["distance"]
    forward = v["mode"] == "forward"
    values: dict = {}
    series: dict = {}
    warnings: list[str] = []
    nfev = 0
    if forward:
        theta_i, v_i = v["release_angle"], v["release_speed"]
        _check_release(h_i, theta_i)
    else:
        h_f, theta_f = v["target_height"], v["target_angle"]
    if a.vacuum:
        if forward:
            h_f, theta_f, t = vacuum_at(h_i, theta_i, v_i, d, G)
            if h_f < -FLOOR_SLACK * max(1.0, d):
                raise _floor_error(vacuum_range(h_i, theta_i, v_i, G))
            h_f = max(h_f, 0.0)
        else:
            theta_i, v_i, t = reverse_vacuum(h_i, h_f, d, theta_f)
        vx, vy_f = v_i * math.cos(theta_i), v_i * math.sin(theta_i) - G * t
        apex = vacuum_apex(h_i, theta_i, v_i, t, h_f, G)
        speed_f = math.hypot(vx, vy_f)
        series["flight"] = _parabola(h_i, theta_i, v_i, t)
    else:
        if forward:
            f = _fly(a, h_i, theta_i, v_i, d, rtol, samples=PATH_POINTS)
            nfev = f.nfev
            h_f, theta_f = max(f.height, 0.0), f.angle
            vac = vacuum_at(h_i, theta_i, v_i, d, G)
            if vac[0] >= 0:
                series["vacuum"] = _parabola(h_i, theta_i, v_i, vac[2])
        else:
            try:
                theta_i, v_i, used = _reverse_with_effects(a, h_i, h_f, d, theta_f, rtol, series)
            except (ValueError, RuntimeError):
                line = math.degrees(line_angle(h_i, h_f, d))
                raise InputError(
                    "target_angle",
                    f"no release found that reaches the target arriving at "
                    f"{math.degrees(theta_f):.6g}° with these flight effects (drag and topspin "
                    f"steepen the descent, backspin flattens it; the line from release to target "
                    f"is at {line:.4g}°): try another target angle, less drag or a shorter "
                    f"distance",
                ) from None
            if not v_i <= 10_000:
                raise InputError("target_angle", f"needs a release speed of {v_i:.3g} m/s")
            f = _fly(a, h_i, theta_i, v_i, d, rtol, samples=PATH_POINTS)
            nfev = used + f.nfev
        t, apex, speed_f = f.t, max(f.apex, h_f), f.speed
        series["flight"] = f.path
    if forward:
        values.update(target_height=h_f, target_angle=theta_f)
        key = {"target_height": d + h_f}  # offset by d: a relative error that stays meaningful at h_f = 0
    else:
        values.update(release_angle=theta_i, release_speed=v_i)
        key = {"release_speed": v_i, "release_angle": theta_i + math.pi}  # θ + π ∈ (π/2, 3π/2)
    values.update(time_of_flight=t, apex_height=apex, target_speed=speed_f)
    key.update(time_of_flight=t, target_speed=speed_f)
    values.update(a.assembly.report({"release_speed": v_i}))
    if "magnus" in v["effects"]:
        if v["spin"] == 0:
            warnings.append("magnus is on but the spin is 0: no Magnus force.")
    if a.vacuum:
        warnings.append(
            "No flight effects: the seed's closed form (section 6), no integration."
            if not v["effects"]
            else "The effects on exert no force here (zero drag coefficient, density or spin): "
            "closed form, no integration."
        )
    return SimRun(values, key, nfev, warnings, series)


compute = compute_with_stats(simulate)


CALCULATOR = Calculator(
    id="projectile",
    title="Projectile",
    summary="Ball trajectory from release to target, forward and reverse, with air drag and Magnus lift.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="6",
    simulate=simulate,
    plots=(Plot("Trajectory", ("flight", "vacuum"), "distance", "length", "m", "height", "length", "m"),),
)
