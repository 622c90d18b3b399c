"""Pneumatics scene timings (printed, never asserted).

Run:  .venv/bin/python bench/bench_pneumatics.py
The built-in presets and the defaults: the scene alone at the default accuracy (median of 50) and
the full solve (adds the error estimate's run and the seed's 1 s scheme); evaluations of the scene.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from timing import median_seconds  # noqa: E402  (bench/ is on sys.path when run)


def main() -> None:
    from gearhead.core import presets
    from gearhead.core.model import parse_inputs, solve
    from gearhead.core.registry import get
    from gearhead.core.sim.scene import LEVELS

    calc = get("pneumatics")
    cases = {"defaults": {}, "defaults, no switch": {"effects": "compressor, regulator"}}
    cases.update({p.path.stem: p.inputs for p in presets.listing("pneumatics") if p.builtin})
    print("  default accuracy (rtol 1e-6), median of 50:")
    for name, raw in cases.items():
        values, _ = parse_inputs(calc, raw)
        scene = median_seconds(lambda: calc.simulate(values, LEVELS["default"]), 50) * 1e3
        full = median_seconds(lambda: solve("pneumatics", raw), 50) * 1e3
        nfev = calc.simulate(values, LEVELS["default"]).nfev
        print(f"    {name:<24} scene {scene:7.3f} ms   solve {full:7.3f} ms   nfev {nfev:6d}")


if __name__ == "__main__":
    main()
