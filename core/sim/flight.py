"""Flight of a ball with the effects a scene switches on: quadratic air drag and Magnus lift,
assembled from parts (core.sim.effects); and the vacuum flight in closed form (the one copy).

State (x, y, vx, vy) in the vertical plane of the throw, x toward the target, y up.
    a = accel((0, −g), vx, vy, |v|)                  gravity (always), then each term of the slot
                                                     "accel" adds its own to the running a:
        −k_d·|v|·v,        k_d = ρ·C_d·A/(2m)        (F1) `air_drag`
        k_m·|v|·(−vy, vx), k_m = ρ·C_L·A/(2m)        (F2) `magnus`: ½ρC_L·A·|v|² along ω̂ × v̂;
                                                     backspin (spin > 0) lifts a ball moving forward
The slot "accel" (combine "fold", in catalogue order: the additions round as they always did) holds the terms of the effects that are on and exert a force,
composed once per solve (`assemble`); an effect that is off, or on with a zero coefficient, adds no
term. With no term the slot is None: the flight is the vacuum parabola and callers use the closed
form below instead (no integration).

Vacuum (the closed form every caller uses; seed (103)-(105), (61)-(62)):
    t = d/(v·cos θ),  h = h_i + (v·sin θ − g·t/2)·t,  θ_f = atan2(v·sin θ − g·t, v·cos θ)     (V1)
    apex h_i + (v·sin θ)²/(2g) when the vertex comes before t, else the higher end            (V2)
    landing from h ≥ 0: t = (q + √(q² + 2gh))/g, q = v·sin θ (= 2h/(√(q² + 2gh) − q) for q < 0)  (V3)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from ..constants import G0
from .effects import Assembly, Effect, Effects, Part, Slot
from .integrate import Event, integrate

T_MAX = 120.0  # s: no robot throw flies longer; bounds the work of a stalled solve
STATES = ("x", "y", "vx", "vy")
SLOTS = (
    Slot(
        "accel",
        "fold",
        "acceleration (ax, ay): each term adds its own to the running one, "
        "of (a, vx, vy, |v|); the scene starts from gravity's (0, −g)",
        arity=3,
    ),
)


# --- the vacuum flight, in closed form ------------------------------------------------------------


def _xp(*args):
    """math for scalars, numpy for arrays: the forward formulas run over sweeps in one call."""
    if all(isinstance(a, (int, float)) for a in args):
        return math, math.atan2
    import numpy as np

    return np, np.arctan2


def vacuum_at(h_i, theta_i, v_i, d, g: float = G0):
    """(h, θ, t) of the vacuum arc at horizontal distance d, (V1); accepts numpy arrays; cos θ_i > 0."""
    xp, atan2 = _xp(h_i, theta_i, v_i, d)
    vx = v_i * xp.cos(theta_i)
    vy_i = v_i * xp.sin(theta_i)
    t = d / vx  # (103)
    h_f = h_i + (vy_i - g * t / 2) * t  # (104) = (61)
    theta_f = atan2(vy_i - g * t, vx)  # (105) = (62)
    return h_f, theta_f, t


def vacuum_apex(h_i: float, theta_i: float, v_i: float, t: float, h_f: float, g: float = G0) -> float:
    """Highest point flown in [0, t], (V2): the vertex if it comes before t, else an end."""
    vy_i = v_i * math.sin(theta_i)
    if vy_i > 0 and vy_i / g < t:
        return h_i + vy_i * vy_i / (2 * g)
    return max(h_i, h_f)


def vacuum_landing_time(h_i: float, theta_i: float, v_i: float, g: float = G0) -> float:
    """When the vacuum arc from height h_i ≥ 0 comes down to 0, (V3), without cancellation."""
    return landing_time(v_i * math.sin(theta_i), h_i, g)


def landing_time(q, h_i, g: float = G0):
    """(V3) from the vertical release speed q (up positive) and height h_i ≥ 0; accepts numpy arrays
    (a batch of throws: each element takes the branch a scalar would)."""
    xp, _ = _xp(q, h_i)
    if xp is math:
        root = math.sqrt(q * q + 2 * g * h_i)
        return (q + root) / g if q >= 0 else (2 * h_i / (root - q) if root - q > 0 else 0.0)
    with xp.errstate(divide="ignore", invalid="ignore"):  # each branch is kept only where it is sound
        root = xp.sqrt(q * q + 2 * g * h_i)
        falling = xp.where(root - q > 0, 2 * h_i / (root - q), 0.0)
        return xp.where(q >= 0, (q + root) / g, falling)


def vacuum_range(h_i: float, theta_i: float, v_i: float, g: float = G0) -> float:
    """Horizontal distance where the vacuum arc from height h_i ≥ 0 comes down to 0, (V3)."""
    return v_i * math.cos(theta_i) * vacuum_landing_time(h_i, theta_i, v_i, g)


def vacuum_path(h_i: float, theta_i: float, v_i: float, t_end: float, n: int, g: float = G0):
    """n + 1 points (x, y) of the vacuum arc, evenly spaced in time over [0, t_end]."""
    vx, vy = v_i * math.cos(theta_i), v_i * math.sin(theta_i)
    ts = [t_end * k / n for k in range(n + 1)]
    return [vx * t for t in ts], [h_i + (vy - g * t / 2) * t for t in ts]


# --- the effects ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Body:
    """What the flight effects read besides their own fields (the assembly's context)."""

    g: float = G0
    mass: float = 1.0  # kg
    area: float = 0.0  # m², frontal
    density: float = 0.0  # kg/m³ of the air
    scale: float = 1.0  # continuation: every effect's coefficient times this (grown from 0 to 1)

    @staticmethod
    def of(g: float, mass: float, diameter: float, density: float) -> Body:
        return Body(g, mass, math.pi * diameter**2 / 4, density)


def drag_build(values: Mapping[str, Any], body: Body) -> Part:
    """`air_drag` (F1) from the field drag_coefficient; no term when k_d = 0 (no force)."""
    k = body.density * values["drag_coefficient"] * body.area / (2 * body.mass)
    if body.scale != 1.0:
        k = k * body.scale
    if k == 0.0:
        return Part(params={"k_drag": 0.0})
    return Part(
        terms={"accel": lambda a, vx, vy, v: (a[0] - k * v * vx, a[1] - k * v * vy)}, params={"k_drag": k}
    )


def magnus_build(values: Mapping[str, Any], body: Body) -> Part:
    """`magnus` (F2) from the fields lift_coefficient and spin (its sign: backspin > 0 lifts);
    no term when k_m = 0 (no spin or no lift)."""
    k = 0.0
    if values["spin"] != 0:
        k = math.copysign(
            body.density * values["lift_coefficient"] * body.area / (2 * body.mass), values["spin"]
        )
        if body.scale != 1.0:
            k = k * body.scale
    if k == 0.0:
        return Part(params={"k_magnus": 0.0})
    return Part(
        terms={"accel": lambda a, vx, vy, v: (a[0] - k * v * vy, a[1] + k * v * vx)}, params={"k_magnus": k}
    )


# The bare catalogue (no fields: each calculator declares its own, with its own field names, and
# uses these builds); `air` below assembles from it.
BARE = Effects(
    Effect("air_drag", "quadratic air drag (F1)", drag_build),
    Effect("magnus", "Magnus lift from spin (F2)", magnus_build),
)


@dataclass(frozen=True)
class Air:
    """The air of one solve: gravity and the assembled slot "accel" (None: vacuum)."""

    g: float = G0
    accel: Callable | None = None
    k_drag: float = 0.0  # the parts' coefficients (1/m), for start guesses and messages
    k_magnus: float = 0.0
    rebuild: Callable[[float], Air] | None = field(default=None, repr=False, compare=False)
    assembly: Assembly | None = field(default=None, repr=False, compare=False)

    @property
    def vacuum(self) -> bool:
        return self.accel is None

    def scaled(self, s: float) -> Air:
        """The same effects with every coefficient times s (continuation from vacuum)."""
        return self.rebuild(s) if self.rebuild is not None else self


def assemble(effects: Effects, on, values: Mapping[str, Any], body: Body) -> Air:
    """The effects that are on, composed once for this solve (core.sim.effects)."""
    asm = effects.assemble(on, values, body, SLOTS, STATES)
    return Air(
        body.g,
        asm.slots["accel"],
        asm.params.get("k_drag", 0.0),
        asm.params.get("k_magnus", 0.0),
        lambda s: assemble(effects, on, values, replace(body, scale=body.scale * s)),
        asm,
    )


def air(
    effects,
    mass: float,
    diameter: float,
    drag_coefficient: float,
    lift_coefficient: float,
    density: float,
    spin: float,
    g: float,
) -> Air:
    """The Air of the bare effects named in `effects` (for a caller without an Effects catalogue)."""
    values = {"drag_coefficient": drag_coefficient, "lift_coefficient": lift_coefficient, "spin": spin}
    return assemble(BARE, frozenset(effects) & set(BARE.names), values, Body.of(g, mass, diameter, density))


def air_with(g: float, k_drag: float = 0.0, k_magnus: float = 0.0) -> Air:
    """The Air with these coefficients (1/m; k_magnus signed), through the same builds (tests)."""
    values = {"drag_coefficient": k_drag, "lift_coefficient": abs(k_magnus), "spin": k_magnus}
    return assemble(BARE, frozenset(BARE.names), values, Body(g, 0.5, 1.0, 1.0))  # k = C·1·1/(2·0.5) = C


def rhs_for(a: Air):
    """The right-hand side: the assembled slot from gravity, or gravity alone (vacuum)."""
    g, accel = a.g, a.accel
    gravity = (0.0, -g)
    if accel is None:

        def rhs(t, s):
            return [s[2], s[3], 0.0, -g]
    else:

        def rhs(t, s):
            vx, vy = s[2], s[3]
            ax, ay = accel(gravity, vx, vy, math.hypot(vx, vy))
            return [vx, vy, ax, ay]

    return rhs


@dataclass
class Flight:
    reached: bool  # the ball got to the target distance
    t: float
    height: float  # at the target distance (or where it stopped)
    angle: float  # of the velocity there, rad (negative: descending)
    speed: float
    apex: float
    x_end: float
    nfev: int
    path: tuple[list[float], list[float]] = field(default_factory=lambda: ([], []))


def fly(
    a: Air,
    h_i: float,
    theta_i: float,
    v_i: float,
    d: float,
    rtol: float,
    ground: float = 0.0,
    samples: int = 0,
    max_steps: int = 100_000,
) -> Flight:
    """Integrate from release to the target distance d (terminal event), the ground, or T_MAX.

    The path is the step points, or `samples` points evenly spaced in time on the dense output.
    The apex is the highest point flown: a ball still rising at the target peaks there."""
    s0 = [0.0, h_i, v_i * math.cos(theta_i), v_i * math.sin(theta_i)]
    scale = max(abs(h_i), d, v_i, 1.0)
    events = [
        Event("target", lambda t, s: s[0] - d, +1),
        Event("ground", lambda t, s: s[1] - ground, -1),
        Event("apex", lambda t, s: s[3], -1, terminal=False),
    ]
    run = integrate(
        rhs_for(a),
        0.0,
        T_MAX,
        s0,
        rtol=rtol,
        atol=rtol * scale * 1e-3,
        events=events,
        dense=samples > 0,
        max_steps=max_steps,
    )
    end = run.y[-1]
    apex = max([h_i, end[1]] + [c[2][1] for c in run.crossings if c[0] == "apex"])
    points = run.y
    if samples > 0 and run.dense:
        t_end = run.t[-1]
        points = [run.at(min(t_end * i / samples, t_end)) for i in range(samples)] + [end]
    return Flight(
        run.event == "target",
        run.t[-1],
        end[1],
        math.atan2(end[3], end[2]),
        math.hypot(end[2], end[3]),
        apex,
        end[0],
        run.nfev,
        ([s[0] for s in points], [s[1] for s in points]),
    )


def aim(
    a: Air,
    h_i: float,
    h_f: float,
    d: float,
    theta_f: float,
    rtol: float,
    guess: tuple[float, float],
    max_flights: int = 400,
    max_steps: int = 100_000,
    max_nfev: int | None = None,
    spent: list[int] | None = None,
) -> tuple[float, float, int]:
    """Release angle and speed that reach (d, h_f) arriving at angle theta_f, by root finding
    (scipy.optimize.root, hybrid Powell) from the vacuum solution. Returns (θ_i, v_i, nfev).
    ValueError when there is none, or when the flights tried exceed max_nfev evaluations.
    `spent` ([n]) shares the evaluation count (and so the max_nfev budget) between several calls."""
    from scipy.optimize import root

    count = spent if spent is not None else [0]

    def residual(p):
        theta, log_v = p
        if not (-math.pi / 2 < theta < math.pi / 2) or not (-50.0 < log_v < 50.0):
            return [1e3, 1e3]  # outside any throw: push the solver back
        f = fly(a, h_i, theta, math.exp(log_v), d, rtol, ground=-1e9, max_steps=max_steps)
        count[0] += f.nfev
        if max_nfev is not None and count[0] > max_nfev:
            raise ValueError(f"no release found within {max_nfev} right-hand-side evaluations")
        if not f.reached:  # short: push the solver toward faster throws
            return [f.height - h_f - 1e3 * (d - f.x_end), f.angle - theta_f]
        return [(f.height - h_f) / max(d, 1.0), f.angle - theta_f]

    sol = root(
        residual,
        [guess[0], math.log(guess[1])],
        method="hybr",
        options={"xtol": 1e-11, "maxfev": max_flights, "eps": rtol},
    )  # FD step above the flight noise
    miss = max(abs(r) for r in residual(sol.x))
    # hybr may report "not making good progress" once the residual is down at the flights' own noise
    # (a polish at rtol 1e-13 stalls at 1e-14): a root that close is a root
    if miss > 1e-6 or (not sol.success and miss > max(1e-12, 100 * rtol)):  # incl. outside any throw
        raise ValueError("no release reaches that target with these flight effects")
    return float(sol.x[0]), float(math.exp(sol.x[1])), count[0]


def aim_along(
    path,
    h_i: float,
    h_f: float,
    d: float,
    rtol: float,
    guess: tuple[float, float],
    spent: list[int],
    max_halvings: int = 6,
    **limits,
) -> tuple[float, float]:
    """Continuation: follow the root of `aim` from path(0), where `guess` is (nearly) the answer, to
    path(1). path(s) -> (Air, θ_f). Hybrid Powell from the vacuum answer can miss when the effects
    bend the path far from the parabola; small steps in s keep each start close to its root.
    ValueError when a step cannot be made after max_halvings halvings (or the budget is spent)."""
    s, ds, g = 0.0, 0.25, guess
    while s < 1.0:
        s1 = min(1.0, s + ds)
        a, theta_f = path(s1)
        try:
            theta, v, _ = aim(a, h_i, h_f, d, theta_f, rtol, g, spent=spent, **limits)
        except (ValueError, RuntimeError):
            ds /= 2
            if ds < 0.25 / 2**max_halvings:
                raise ValueError("the continuation lost the root") from None
            continue
        g, s, ds = (theta, v), s1, min(2 * ds, 0.5)
    return g
