"""What sweeps and tolerance runs cost (best of a few runs, warm: imports and caches paid first).

- a 200-point sweep of a closed-form calculator (gear ratio, elevator preset)   goal <= 50 ms
- 200 trebuchet throws (a sweep of the release angle, seed preset)               goal <= 1 s
- a 1000-sample Monte Carlo of a closed-form calculator (gear ratio, 3 inputs)   goal <= 100 ms

Run alone:  .venv/bin/python bench/bench_sweep.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from gearhead.core import sweep, tolerance  # noqa: E402
from gearhead.core.presets import load  # noqa: E402
from gearhead.core.registry import get  # noqa: E402


def best(fn, repeats: int) -> tuple[float, object]:
    fn()  # warm: lazy imports (numpy, scipy), unit caches
    times, result = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return min(times), result


def inputs(calc: str, name: str) -> dict:
    return dict(load(ROOT / "presets" / calc / f"{name}.toml").inputs)


def main() -> None:
    rows = []
    gear = inputs("gear_ratio", "elevator_neo")
    t, s = best(lambda: sweep.run(get("gear_ratio"), gear, ["radius=0.5 in..1.5 in:200"]), 7)
    rows.append(("200-point sweep, gear_ratio (closed form)", t, 0.050, s.cost.text()))

    treb = inputs("trebuchet", "seed_kastmaskin")
    t, s = best(lambda: sweep.run(get("trebuchet"), treb, ["release_angle=30 deg..60 deg:200"]), 2)
    rows.append(("200 trebuchet throws (release-angle sweep)", t, 1.0, s.cost.text()))

    toleranced = {**gear, "load": "40 lbf ± 10 %", "radius": "0.75 in ± 0.02 in", "voltage": "12 V ± 0.5 V"}
    calc = get("gear_ratio")
    _, values, tols, _ = tolerance.parse(calc, toleranced)
    t, r = best(lambda: tolerance.spread(calc, values, tols, method="monte-carlo", samples=1000), 7)
    rows.append(("1000-sample Monte Carlo, gear_ratio (3 inputs)", t, 0.100, r.cost.text()))

    # for information: the lead screw also builds its 60-point plot series on every solve
    screw = {
        **inputs("lead_screw", "t8_lift"),
        "friction": "0.2 ± 0.05",
        "force": "50 N ± 10 %",
        "diameter": "8 mm ± 0.05 mm",
    }
    calc = get("lead_screw")
    _, values, tols, _ = tolerance.parse(calc, screw)
    t, r = best(lambda: tolerance.spread(calc, values, tols, method="monte-carlo", samples=1000), 3)
    rows.append(("(info) same, lead_screw (plot series per solve)", t, None, r.cost.text()))

    print(f"{'run':<48}{'wall time':>12}{'goal':>10}  cost (last run)")
    for name, t, goal, cost in rows:
        if goal is None:
            print(f"{name:<48}{t * 1e3:>9.1f} ms{'':>10}        {cost}")
            continue
        flag = "ok" if t <= goal else "OVER"
        print(f"{name:<48}{t * 1e3:>9.1f} ms{goal * 1e3:>7.0f} ms  {flag:<4}  {cost}")


if __name__ == "__main__":
    main()
