"""Chain/belt length solver: time per solve in three regimes, accuracy against mpmath, and how
far the seed's forms (and p/sin(180°/n) radii in (68), which the code does not use) move D."""

from __future__ import annotations

import math
import random
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def mp_center(L, r1, r2, dps=50, same_excess=False):
    """mpmath D for length L; with same_excess, for the spare length S = (L − 2π r_large)/2 as
    double precision computes it (what the solver is given), isolating the solver's own error
    from the rounding of the input."""
    import mpmath as mp

    with mp.workdps(dps):
        if same_excess:
            S = (L - 2 * math.pi * max(r1, r2)) / 2
            L = 2 * mp.pi * mp.mpf(max(r1, r2)) + 2 * mp.mpf(S)
        L, r1, r2 = mp.mpf(L), mp.mpf(r1), mp.mpf(r2)
        delta = abs(r2 - r1)

        def length(X):
            C = mp.sqrt(X**2 + delta**2)
            return 2 * X + mp.pi * (r1 + r2) + 2 * delta * mp.asin(delta / C)

        lo, hi = mp.mpf(0), L
        for _ in range(4 * dps + 60):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if length(mid) < L else (lo, mid)
        return float(mp.sqrt(((lo + hi) / 2) ** 2 + delta**2))


def main() -> None:
    from gearhead.core.calculators import chain_belt as cb

    r1, r2 = 50e-3 / math.pi, 75e-3 / math.pi  # 20T and 30T, 5 mm
    cases = {
        "typical (100T belt)": 0.5,
        "1e-10 above minimum": cb.minimum_length(r1, r2) * (1 + 1e-10),
        "s ~ 1e12 (very long)": 1e12 * 0.025,
    }
    cb.center_from_length(0.5, r1, r2)  # warm: scipy import
    for name, L in cases.items():
        reps = 2000
        t0 = time.perf_counter()
        for _ in range(reps):
            D = cb.center_from_length(L, r1, r2)
        dt = (time.perf_counter() - t0) / reps
        ref, ref_s = mp_center(L, r1, r2), mp_center(L, r1, r2, same_excess=True)
        print(
            f"  {name:24s} {dt * 1e6:7.1f} us/solve   rel. error vs mpmath {abs(D - ref) / ref:.1e} "
            f"(solver alone {abs(D - ref_s) / ref_s:.1e})"
        )

    rng = random.Random(1)
    worst = worst_solver = 0.0
    for _ in range(200):
        a, b = rng.uniform(1e-3, 0.1), rng.uniform(1e-3, 0.1)
        L = cb.minimum_length(a, b) * (1 + 10 ** rng.uniform(-12, 3))
        D = cb.center_from_length(L, a, b)
        ref, ref_s = mp_center(L, a, b), mp_center(L, a, b, same_excess=True)
        worst = max(worst, abs(D - ref) / ref)
        worst_solver = max(worst_solver, abs(D - ref_s) / ref_s)
    print(
        f"  200 random cases (L/L_min - 1 in 1e-12..1e3): worst rel. error {worst:.1e} end to end "
        f"(input rounding of L - 2 pi r amplified near the minimum), solver alone {worst_solver:.1e}"
    )

    D = cb.center_from_length(0.5, r1, r2)

    def seed_center(length_of):
        from scipy.optimize import brentq

        return brentq(lambda x: length_of(x) - 0.5, abs(r2 - r1) * (1 + 1e-15), 0.5)

    seed_e = seed_center(
        lambda x: (
            2 * math.sqrt(x * x - (r1 - r2) ** 2)
            + 2 * (r1 - r2) * math.acos((r1 - r2) / x)
            + 2 * math.pi * r2
        )
    )
    seed_7 = seed_center(
        lambda x: (
            2 * math.sqrt(x * x - (r1 - r2) ** 2)
            + 2 * (r1 + r2) * math.acos((r1 - r2) / x)
            + 2 * math.pi * r2
        )
    )
    print(
        f"  ReCalc case 20T/30T 5 mm 100T: exact {D * 1e3:.4f} mm, seed App. E (68) "
        f"{seed_e * 1e3:.4f} mm ({(seed_e - D) * 1e3:+.3f}), seed sec. 7 (68) {seed_7 * 1e3:.2f} mm"
    )

    IN = 0.0254
    for label, p, n1, n2, links in (
        ("#25 16T-16T 60 links", 0.25 * IN, 16, 16, 60),
        ("#25 12T-36T 74 links", 0.25 * IN, 12, 36, 74),
        ("#35 12T-60T 92 links", 0.375 * IN, 12, 60, 92),
    ):
        D_seed = cb.center_from_length(
            links * p, cb.pitch_radius(n1, p, "circumference"), cb.pitch_radius(n2, p, "circumference")
        )
        D_chord = cb.center_from_length(
            links * p, cb.pitch_radius(n1, p, "chordal"), cb.pitch_radius(n2, p, "chordal")
        )
        print(
            f"  {label:22s} n·p/π (used) {D_seed / IN:.4f} in; p/sin(180°/n) in (68) would give "
            f"{D_chord / IN:.4f} in ({(D_chord - D_seed) / IN:+.4f} in, chain slack)"
        )


if __name__ == "__main__":
    main()
