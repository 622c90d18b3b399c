"""Flight of a ball with the effects a scene switches on: quadratic air drag and Magnus lift.

State (x, y, vx, vy) in the vertical plane of the throw, x toward the target, y up.
    a = (0, −g)                                   gravity (always)
      − k_d·|v|·v,       k_d = ρ·C_d·A / (2m)     `air_drag`
      + k_m·|v|·(−vy, vx), k_m = ρ·C_L·A / (2m)   `magnus`: ½ρC_L·A·|v|² along ω̂ × v̂;
                                                  backspin (spin > 0) lifts a ball moving forward
Only the terms of the effects that are on are built into the right-hand side. With no effect the
flight is the vacuum parabola and callers use the closed form instead (no integration).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..constants import G0
from .integrate import Event, integrate

T_MAX = 120.0  # s: no robot throw flies longer; bounds the work of a stalled solve


@dataclass(frozen=True)
class Air:
    g: float = G0
    k_drag: float = 0.0  # 1/m
    k_magnus: float = 0.0  # 1/m, signed by the spin direction

    @property
    def vacuum(self) -> bool:
        return self.k_drag == 0.0 and self.k_magnus == 0.0


def air(effects, mass: float, diameter: float, drag_coefficient: float, lift_coefficient: float,
        density: float, spin: float, g: float) -> Air:
    area = math.pi * diameter**2 / 4
    k_d = density * drag_coefficient * area / (2 * mass) if "air_drag" in effects else 0.0
    k_m = 0.0
    if "magnus" in effects and spin != 0:
        k_m = math.copysign(density * lift_coefficient * area / (2 * mass), spin)
    return Air(g, k_d, k_m)


def rhs_for(a: Air):
    """The right-hand side with only the active terms (an effect that is off costs nothing)."""
    g, kd, km = a.g, a.k_drag, a.k_magnus
    if kd and km:
        def rhs(t, s):
            vx, vy = s[2], s[3]
            v = math.hypot(vx, vy)
            return [vx, vy, -kd * v * vx - km * v * vy, -g - kd * v * vy + km * v * vx]
    elif kd:
        def rhs(t, s):
            vx, vy = s[2], s[3]
            v = math.hypot(vx, vy)
            return [vx, vy, -kd * v * vx, -g - kd * v * vy]
    elif km:
        def rhs(t, s):
            vx, vy = s[2], s[3]
            v = math.hypot(vx, vy)
            return [vx, vy, -km * v * vy, -g + km * v * vx]
    else:
        def rhs(t, s):
            return [s[2], s[3], 0.0, -g]
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


def fly(a: Air, h_i: float, theta_i: float, v_i: float, d: float, rtol: float,
        ground: float = 0.0, samples: int = 0, max_steps: int = 100_000) -> Flight:
    """Integrate from release to the target distance d (terminal event), the ground, or T_MAX.

    The path is the step points, or `samples` points evenly spaced in time on the dense output.
    The apex is the highest point flown: a ball still rising at the target peaks there."""
    s0 = [0.0, h_i, v_i * math.cos(theta_i), v_i * math.sin(theta_i)]
    scale = max(abs(h_i), d, v_i, 1.0)
    events = [Event("target", lambda t, s: s[0] - d, +1),
              Event("ground", lambda t, s: s[1] - ground, -1),
              Event("apex", lambda t, s: s[3], -1, terminal=False)]
    run = integrate(rhs_for(a), 0.0, T_MAX, s0, rtol=rtol, atol=rtol * scale * 1e-3, events=events,
                    dense=samples > 0, max_steps=max_steps)
    end = run.y[-1]
    apex = max([h_i, end[1]] + [c[2][1] for c in run.crossings if c[0] == "apex"])
    points = run.y
    if samples > 0 and run.dense:
        t_end = run.t[-1]
        points = [run.at(min(t_end * i / samples, t_end)) for i in range(samples)] + [end]
    return Flight(run.event == "target", run.t[-1], end[1], math.atan2(end[3], end[2]),
                  math.hypot(end[2], end[3]), apex, end[0], run.nfev,
                  ([s[0] for s in points], [s[1] for s in points]))


def aim(a: Air, h_i: float, h_f: float, d: float, theta_f: float, rtol: float,
        guess: tuple[float, float], max_flights: int = 400, max_steps: int = 100_000,
        max_nfev: int | None = None, spent: list[int] | None = None) -> tuple[float, float, int]:
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

    sol = root(residual, [guess[0], math.log(guess[1])], method="hybr",
               options={"xtol": 1e-11, "maxfev": max_flights, "eps": rtol})  # FD step above the flight noise
    res = residual(sol.x)
    if not sol.success or max(abs(r) for r in res) > 1e-6:  # includes a root outside any throw
        raise ValueError("no release reaches that target with these flight effects")
    return float(sol.x[0]), float(math.exp(sol.x[1])), count[0]


def aim_along(path, h_i: float, h_f: float, d: float, rtol: float, guess: tuple[float, float],
              spent: list[int], max_halvings: int = 6, **limits) -> tuple[float, float]:
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
