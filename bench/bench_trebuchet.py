"""Trebuchet figures: one seed-scene throw, each scene's cost, the optimiser's batch, the accuracy view.

Run:  .venv/bin/python bench/bench_trebuchet.py   (benchmark.py also calls main())
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)


def main() -> None:
    from gearhead.core.calculators import trebuchet as calc
    from gearhead.core.model import parse_inputs, solve
    from gearhead.core.registry import get
    from gearhead.core.sim import trebuchet as tb
    from gearhead.core.sim.scene import LEVELS, ladder

    c = get("trebuchet")
    print("  right-hand side of the assembled scene, one evaluation (min of 5 × 20 000):")
    import timeit

    for effects, contact, kw in (
        ("(arm alone)", False, dict(sling=False)),
        ("sling", False, {}),
        ("sling, on the ground", True, {}),
        ("sling, on the ground, pendulum", True, dict(rigid=False, d=0.2)),
    ):
        p = tb.Machine(M=500, k=2, m=50, L=15, a=0.25, h=4, m_p=5, l=5, g=9.81, **kw)
        rhs = tb.rhs_for(p, contact)
        y = [x + 0.1 for x in tb.initial_state(p)]
        t = min(timeit.repeat(lambda: rhs(0.0, y), number=20_000, repeat=5)) / 20_000
        print(f"    {effects:<46} {t * 1e6:7.2f} µs")
    print("  one throw at default accuracy (rtol 1e-6), swing + flight, median of 50:")
    for effects in (
        "",
        "sling",
        "sling, ground_contact",
        "sling, ground_contact, hinged_counterweight",
        "sling, ground_contact, air_drag",
    ):
        v = parse_inputs(c, {"effects": effects, "hanger_length": "0.2 m"})[0]
        run = calc.simulate(v, LEVELS["default"])
        t = median_seconds(lambda: calc.simulate(v, LEVELS["default"]))
        label = effects or "(arm alone)"
        print(f"    {label:<46} {t * 1e3:7.3f} ms  {run.nfev:5d} RHS evaluations")
    seed = parse_inputs(c, {"effects": "sling"})[0]
    print(
        f"  seed scene (sling, release 45°), full solve with error estimate: "
        f"{median_seconds(lambda: solve('trebuchet', {'effects': 'sling'})) * 1e3:.3f} ms"
    )
    v = parse_inputs(c, {"mode": "optimise", "effects": "sling, ground_contact"})[0]
    p = calc.machine(v)
    t = median_seconds(lambda: tb.optimise(p, v, v["sling_min"], v["sling_max"]), 5)
    n = tb.optimise(p, v, v["sling_min"], v["sling_max"])[2]
    print(f"  optimiser batch: {n} candidate throws in {t * 1e3:.1f} ms (median of 5)")
    vd = parse_inputs(c, {"mode": "optimise", "effects": "sling, ground_contact, air_drag"})[0]
    t = median_seconds(lambda: tb.optimise(p, vd, vd["sling_min"], vd["sling_max"]), 5)
    print(f"  optimiser batch with air drag: {n} candidate throws in {t * 1e3:.1f} ms (median of 5)")
    t = median_seconds(
        lambda: solve("trebuchet", {"mode": "optimise", "effects": "sling, ground_contact"}), 5
    )
    print(
        f"  optimise mode, whole solve (batch + Nelder–Mead polish on accurate throws): {t * 1e3:.1f} ms (median of 5)"
    )
    print("  accuracy view of the seed scene (error vs the rtol 1e-13 reference):")
    rungs, _ = ladder(calc.simulate, seed)
    for r in rungs:
        print(
            f"    {r.level:<8} rtol {r.rtol:.0e}  error {r.error:.2e}  {r.wall_time * 1e3:7.3f} ms  {r.nfev:5d} RHS"
        )


if __name__ == "__main__":
    main()
