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

from bench_projectile import scene_rows  # noqa: E402  (bench/ is on sys.path when run)


def main() -> None:
    from gearhead.core import presets

    cases = {"defaults": {}, "defaults, no switch": {"effects": "compressor, regulator"}}
    cases.update({p.path.stem: p.inputs for p in presets.listing("pneumatics") if p.builtin})
    scene_rows("pneumatics", cases)


if __name__ == "__main__":
    main()
