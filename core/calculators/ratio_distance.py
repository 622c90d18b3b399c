"""Seed section 9: gear pair from ratio and center distance (eqs. 75-78, with 69-70).

G = N/n (75), d = (N + n)/(2p) (76), so n = 2dp/(G + 1) (77) and N = G·n (78). The seed's
equations are right; they give fractional teeth. Real gears need whole teeth, so the total
N + n is rounded to the nearest whole number T = round(2dp) (the center distance closest to the
one asked for) and split as close to the ratio as possible (compared on log G, so 2:1 missed by
one tooth counts the same either way). The whole-tooth pairs just below and just above the
ratio at that total are reported too. Diameters: pitch N/p (69), outside (N + 2)/p (70).
"""

from __future__ import annotations

import math

from ..errors import InputError
from ..model import Calculator, Field, Output, Result

IN = 0.0254

FIELDS = (
    Field("ratio", "Gear ratio", default=2.5, min=1,
          help="G = N/n (75): large gear teeth over small gear teeth (at least 1)."),
    Field("center_distance", "Center distance", "length", "in", default=2, min=0, min_exclusive=True,
          help="Distance d between the two gear centers (76)."),
    Field("diametral_pitch", "Diametral pitch", "reciprocal_length", "1/in", default=20, min=0,
          min_exclusive=True, help="p: teeth per inch of pitch diameter (e.g. 20 DP, 32 DP)."),
)

OUTPUTS = (
    Output("small_teeth", "Small gear teeth (exact)", help="n = 2dp/(G + 1) (77), fractional."),
    Output("large_teeth", "Large gear teeth (exact)", help="N = G·n (78), fractional."),
    Output("nearest_small_teeth", "Nearest pair: small teeth",
           help="Whole-tooth pair with the total closest to 2dp, split closest to the ratio."),
    Output("nearest_large_teeth", "Nearest pair: large teeth"),
    Output("nearest_ratio", "Nearest pair: ratio"),
    Output("nearest_center_distance", "Nearest pair: center distance", "length", "in",
           help="(N + n)/(2p) for the whole-tooth pair."),
    Output("below_small_teeth", "Just below the ratio: small teeth",
           help="Same total teeth, the split whose ratio is the largest not above the target."),
    Output("below_large_teeth", "Just below the ratio: large teeth"),
    Output("below_ratio", "Just below the ratio: ratio"),
    Output("above_small_teeth", "Just above the ratio: small teeth",
           help="Same total teeth, the split whose ratio is the smallest not below the target."),
    Output("above_large_teeth", "Just above the ratio: large teeth"),
    Output("above_ratio", "Just above the ratio: ratio"),
    Output("small_pitch_diameter", "Small gear pitch diameter", "length", "in", help="n/p (69)."),
    Output("small_outside_diameter", "Small gear outside diameter", "length", "in", help="(n + 2)/p (70)."),
    Output("large_pitch_diameter", "Large gear pitch diameter", "length", "in", help="N/p (69)."),
    Output("large_outside_diameter", "Large gear outside diameter", "length", "in", help="(N + 2)/p (70)."),
)

SNAP = 1e-9  # a count this close (relatively) to a whole number is that number


def teeth_exact(G, d, p):
    n = 2 * d * p / (G + 1)  # (77)
    return n, n * G  # (78)


def snapped_floor(x: float) -> int:
    near = round(x)
    return int(near) if abs(x - near) <= SNAP * max(1.0, abs(x)) else math.floor(x)


def snapped_ceil(x: float) -> int:
    near = round(x)
    return int(near) if abs(x - near) <= SNAP * max(1.0, abs(x)) else math.ceil(x)


def split(total: int, G: float):
    """Whole-tooth splits of `total` with ratio just below (or equal) and just above G."""
    n_exact = total / (G + 1)
    below = above = None
    n_hi = snapped_ceil(n_exact)  # more small teeth: ratio at or below G
    if 1 <= n_hi <= total - n_hi:
        below = (n_hi, total - n_hi)
    n_lo = snapped_floor(n_exact)  # fewer small teeth: ratio at or above G
    if 1 <= n_lo <= total - n_lo:
        above = (n_lo, total - n_lo)
    if below is None and above is None:  # only possible when n_exact < 1: the 1-tooth pinion
        above = (1, total - 1)
    return below, above


def compute(v) -> Result:
    G, d, p = v["ratio"], v["center_distance"], v["diametral_pitch"]
    n, N = teeth_exact(G, d, p)
    total_exact = 2 * d * p  # N + n from (76)
    total = round(total_exact)
    if total < 2:
        raise InputError("center_distance", f"too small for this pitch: it holds {total_exact:.3g} "
                                            "teeth in total, a pair needs at least 2")
    warnings = []
    below, above = split(total, G)
    candidates = [pair for pair in (below, above) if pair]
    best = min(candidates, key=lambda pair: abs(math.log(pair[1] / pair[0]) - math.log(G)))
    values = {"small_teeth": n, "large_teeth": N}
    n_best, N_best = best
    values.update(nearest_small_teeth=n_best, nearest_large_teeth=N_best,
                  nearest_ratio=N_best / n_best, nearest_center_distance=(n_best + N_best) / (2 * p))
    for word, pair in (("below", below), ("above", above)):
        if pair:
            values.update({f"{word}_small_teeth": pair[0], f"{word}_large_teeth": pair[1],
                           f"{word}_ratio": pair[1] / pair[0]})
    values.update(small_pitch_diameter=n_best / p, small_outside_diameter=(n_best + 2) / p,  # (69), (70)
                  large_pitch_diameter=N_best / p, large_outside_diameter=(N_best + 2) / p)
    if abs(total - total_exact) > SNAP * total_exact:
        warnings.append(f"Whole teeth need the center distance {total / (2 * p) / IN:.4g} in "
                        f"instead of {d / IN:.4g} in (N + n = {total}).")
    if below is None:
        warnings.append("No whole-tooth pair reaches down to this ratio at this center distance.")
    if n < 1:
        warnings.append("The ratio is too high for this center distance: the pinion would have "
                        "fewer than one tooth.")
    elif n_best < 8:
        warnings.append(f"A {n_best}-tooth pinion is very small (heavily undercut, rarely sold).")
    return Result(values, warnings)


CALCULATOR = Calculator(
    id="ratio_distance",
    title="Ratio & distance",
    summary="Tooth counts for a gear pair from its ratio and center distance, and the nearest "
            "whole-tooth pairs (seed section 9).",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="9",
)
