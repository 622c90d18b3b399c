"""Our DP54 (core.sim.integrate) against scipy's solve_ivp on the scenes' own right-hand sides
(printed, never asserted): the lead the hand-written integrator must keep.

Run:  .venv/bin/python bench/bench_integrators.py
- projectile with drag (and drag + Magnus): one flight from release to the target distance, event
  located, the scene's assembled right-hand side (core.sim.flight.rhs_for);
- pneumatics: the compressor filling the storage from 0 psi to the switch-off pressure (event),
  dP/dt = P_atm·V̇(P)/V on the vendor curve.
Both at rtol 1e-6 (the default accuracy) and 1e-9; solve_ivp with RK45 (the same Dormand-Prince
pair) and DOP853, events terminal. Median of 30 calls each.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)


def _scipy(rhs, t1, y0, rtol, atol, event, method):
    import numpy as np
    from scipy.integrate import solve_ivp

    ev = lambda t, y: event(t, list(y))  # noqa: E731
    ev.terminal, ev.direction = True, 1
    return solve_ivp(
        lambda t, y: rhs(t, list(y)),
        (0.0, t1),
        np.asarray(y0, float),
        method=method,
        rtol=rtol,
        atol=atol,
        events=ev,
    )


def cases():
    from gearhead.core.calculators import pneumatics as pn
    from gearhead.core.calculators import projectile as pj
    from gearhead.core.model import parse_inputs
    from gearhead.core.registry import get
    from gearhead.core.sim import flight

    out = []
    for name, raw in (
        ("projectile, drag", {"effects": "air_drag"}),
        ("projectile, drag + magnus", {"effects": "air_drag, magnus", "spin": "2000 rpm"}),
    ):
        v, _ = parse_inputs(get("projectile"), raw)
        a = pj.scene_air(v)
        h_i, th, sp, d = v["release_height"], v["release_angle"], v["release_speed"], v["distance"]
        y0 = [0.0, h_i, sp * math.cos(th), sp * math.sin(th)]
        scale = max(abs(h_i), d, sp, 1.0)
        out.append((name, flight.rhs_for(a), flight.T_MAX, y0, scale * 1e-3, lambda t, s, d=d: s[0] - d))
    v, _ = parse_inputs(get("pneumatics"), {})
    curve = pn.flow_curve(v["compressor_model"])
    k = pn.P_ATM / v["tank_volume"]
    top = v["switch_off"]
    out.append(
        (
            "pneumatics, compressor fill",
            lambda t, y: [k * pn.flow_through(curve, y[0])],
            1e4,
            [0.0],
            pn.PSI,
            lambda t, y: y[0] - top,
        )
    )
    return out


def main() -> None:
    from gearhead.core.sim.integrate import Event, integrate

    print("  median of 30, ms (nfev)")
    for name, rhs, t1, y0, atol_scale, g in cases():
        for rtol in (1e-6, 1e-9):
            ev = [Event("end", g, +1)]
            ours = integrate(rhs, 0.0, t1, y0, rtol=rtol, atol=rtol * atol_scale, events=ev)
            row = [
                f"DP54 {median_seconds(lambda: integrate(rhs, 0.0, t1, y0, rtol=rtol, atol=rtol * atol_scale, events=ev), 30) * 1e3:7.3f} ({ours.nfev})"
            ]
            base = None
            for method in ("RK45", "DOP853"):
                sol = _scipy(rhs, t1, y0, rtol, rtol * atol_scale, g, method)
                t = median_seconds(lambda: _scipy(rhs, t1, y0, rtol, rtol * atol_scale, g, method), 30)
                base = base or t
                row.append(f"{method} {t * 1e3:7.3f} ({sol.nfev})")
            dp = median_seconds(
                lambda: integrate(rhs, 0.0, t1, y0, rtol=rtol, atol=rtol * atol_scale, events=ev), 30
            )
            print(f"  {name:<28} rtol {rtol:.0e}:  " + "   ".join(row) + f"   RK45/DP54 {base / dp:.1f}x")


if __name__ == "__main__":
    main()
