"""Writes examples/elevator_sysid.wpilog, the example SysId log of README "Fitting the model from
the robot's logs": the default elevator card's mechanism as built, heavier (a carriage 30 % heavier
than the card says), with more friction and 2 % more back-EMF loss than the model holds, logged
every 5 ms without noise or timestamp jitter (this mechanism's kA/kV is 3.6 ms: velocity noise of
0.0002 m/s, 0.03 % of its top speed, already takes its kA out of reach), by WPILib's own
DataLogWriter under SysIdRoutineLog's naming (tests/fit_plants.py, robotpy's wpiutil: the test
extra). The seed is fixed: the file comes out byte for byte the same (tests/test_fit_example.py).

    python examples/make_sysid_log.py [OUT]
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LOG = ROOT / "examples" / "elevator_sysid.wpilog"

# the plant, against the default card's own gains (kS 0.206 V, kV 10.4 V/(m/s), kA 0.0294 V/(m/s²),
# kG 0.288 V): these are what the fit should give back
FACTORS = {"kS": 2.5, "kV": 1.02, "kA": 1.3, "kG": 1.3}
SEED = 44
SETTINGS = dict(period=0.005, seed=SEED, mech="elevator", motor="lift")


def plant() -> dict[str, float]:
    """The log's plant: the default elevator card's gains times FACTORS."""
    from gearhead.core.fit import entries

    design = entries.load_card("elevator").design
    return {k: design[k] * FACTORS[k] for k in FACTORS}


def write(path: Path = LOG) -> Path:
    sys.path.insert(0, str(ROOT / "tests"))
    from fit_plants import simulate

    return simulate(path, "elevator", plant(), **SETTINGS)


if __name__ == "__main__":
    out = write(Path(sys.argv[1]) if len(sys.argv) > 1 else LOG)
    print(f"{out}: {out.stat().st_size} bytes, plant {plant()}")
