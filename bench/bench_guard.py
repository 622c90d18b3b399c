"""Wall time of the slow and hanging simulation cases (the per-solve guard), and of the built-in
presets (the guard's polling must not slow the integrator). Prints; asserts nothing.

    python bench/bench_guard.py [seconds]      # each slow case in a subprocess, killed after `seconds`

CPU time is printed beside wall time: on a shared machine it is the steadier figure.
"""

from __future__ import annotations

import subprocess
import sys
import time

CASES = {
    "trebuchet release at 88.9° (hang)": (
        "trebuchet",
        dict(
            counterweight_gyration=0.6,
            arm_mass=40,
            arm_length=16.97,
            pivot_height=1.9,
            projectile_mass=3.1,
            gravity=50,
            release_angle=88.9,
            effects="",
            accuracy="coarse",
        ),
    ),
    "pneumatics 3600 s, 3 groups every 0.1 s": (
        "pneumatics",
        dict(
            match_length=3600,
            c1_count=1,
            c1_period=0.1,
            c1_start=0,
            c2_count=1,
            c2_period=0.1,
            c2_start=0,
            c3_count=1,
            c3_period=0.1,
            c3_start=0,
        ),
    ),
    "projectile reverse, extreme Magnus": (
        "projectile",
        dict(mode="reverse", effects="magnus", spin=1e5, lift_coefficient=1, ball_mass=0.001),
    ),
    "trebuchet optimise, hanger 1 cm, k = 0": (
        "trebuchet",
        dict(
            effects="sling,ground_contact,hinged_counterweight,optimise",
            hanger_length=0.01,
            counterweight_gyration=0,
        ),
    ),
}

CHILD = """
import sys, time
from gearhead.core.model import solve
from gearhead.core.errors import InputError
calc, raw = {calc!r}, {raw!r}
try:
    solve(calc, dict(raw, accuracy="coarse") if calc == "projectile" else {{}})  # imports, caches
except InputError:
    pass
t, c = time.perf_counter(), time.process_time()
try:
    sol = solve(calc, raw)
    what = "solved"
except InputError as exc:
    what = "refused: " + exc.field
print(f"{{time.perf_counter() - t:6.2f}} s wall {{time.process_time() - c:6.2f}} s CPU  {{what}}")
"""


def main() -> None:
    limit = float(sys.argv[1]) if len(sys.argv) > 1 else 60.0
    for name, (calc, raw) in CASES.items():
        try:
            out = subprocess.run(
                [sys.executable, "-c", CHILD.format(calc=calc, raw=raw)],
                capture_output=True,
                text=True,
                timeout=limit,
            ).stdout.strip()
        except subprocess.TimeoutExpired:
            out = f"> {limit:.0f} s (killed)"
        print(f"{name:<44} {out}")
    from gearhead.core import presets
    from gearhead.core.model import solve

    for p in presets.listing():
        if p.builtin and p.calculator in ("trebuchet", "pneumatics", "projectile", "flywheel"):
            solve(p.calculator, p.inputs)
            best = min(_timed(solve, p.calculator, p.inputs) for _ in range(5))
            print(f"preset {p.calculator}/{p.path.name:<32} {best * 1e3:8.1f} ms")


def _timed(f, *args) -> float:
    t = time.perf_counter()
    f(*args)
    return time.perf_counter() - t


if __name__ == "__main__":
    main()
