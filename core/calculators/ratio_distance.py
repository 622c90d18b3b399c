"""Seed section 9: gear pair from ratio and center distance (eqs. 75-78, with 69-70).

G = N/n (75), d = (N + n)/(2p) (76), so n = 2dp/(G + 1) (77) and N = G·n (78). The seed's
equations are right; they give fractional teeth. Real gears need whole teeth, so the total
N + n is rounded to the nearest whole number T = round(2dp) (the center distance closest to the
one asked for) and split as close to the ratio as possible (compared on log G, so 2:1 missed by
one tooth counts the same either way). The whole-tooth pairs just below and just above the
ratio at that total are reported too. Diameters: pitch N/p (69), outside (N + 2)/p (70).

Whole-tooth pairs have at least MIN_TEETH = 10 teeth on the pinion: about the smallest spur
pinion sold for FRC and VEX motors (FRC pinions are mostly 10-14 T, VEX's smallest gear is 12 T);
a 20° full-depth involute undercuts below 17 T already. A ratio that would need a smaller pinion
at this center distance is refused: the nearest feasible pair (10 T pinion, the highest ratio the
distance allows) is offered instead, with a warning. Inputs are bounded to what a gear pair can
be: ratio 1-50 (50:1 needs a 500 T gear on a 10 T pinion), center distance up to 100 in, 1-200 DP.

Whole-tooth pairs (cited by the outputs):
    T = round(2dp)                         total teeth, (76) at the nearest whole total     (RD1)
    n_below = max(⌈T/(G + 1)⌉, 10), n_above = ⌊T/(G + 1)⌋ (if ≥ 10), N = T − n; the nearest
        pair is the one of the two with the smallest |ln(N/n) − ln G|                       (RD2)
"""

from __future__ import annotations

import math

from ..constants import INCH as IN
from ..declarations import Calculator, Output, Result
from ..errors import InputError
from ..fields import Field

MIN_TEETH = 10  # smallest pinion counted (module docstring)
MAX_RATIO = 50.0

FIELDS = (
    Field(
        "ratio",
        "Gear ratio",
        default=2.5,
        min=1,
        max=MAX_RATIO,
        help="G = N/n (75): large gear teeth over small gear teeth, 1 to 50. Pairs have a pinion "
        f"of at least {MIN_TEETH} teeth (about the smallest sold for FRC/VEX motors).",
    ),
    Field(
        "center_distance",
        "Center distance",
        "length",
        "in",
        default=2,
        min=0,
        min_exclusive=True,
        max=100,
        help="Distance d between the two gear centers (76), up to 100 in.",
    ),
    Field(
        "diametral_pitch",
        "Diametral pitch",
        "reciprocal_length",
        "1/in",
        default=20,
        min=1,
        max=200,
        help="p: teeth per inch of pitch diameter (e.g. 20 DP, 32 DP), 1 to 200.",
    ),
)

OUTPUTS = (
    Output(
        "small_teeth",
        "Small gear teeth (exact)",
        help="Small gear teeth for exactly this ratio and distance, n = 2dp/(G + 1), fractional (77).",
        equation="(77)",
    ),
    Output(
        "large_teeth",
        "Large gear teeth (exact)",
        help="Large gear teeth, N = G·n, fractional (78).",
        equation="(78)",
    ),
    Output(
        "nearest_small_teeth",
        "Nearest pair: small teeth",
        help="Whole teeth: total nearest 2dp, split nearest the ratio on a log scale (RD1), (RD2).",
        equation="(RD1), (RD2)",
    ),
    Output(
        "nearest_large_teeth",
        "Nearest pair: large teeth",
        help="The whole-tooth total round(2dp) minus the small gear's teeth (RD1), (RD2).",
        equation="(RD1), (RD2)",
    ),
    Output(
        "nearest_ratio",
        "Nearest pair: ratio",
        help="N/n of the nearest whole-tooth pair (75).",
        equation="(75)",
    ),
    Output(
        "nearest_center_distance",
        "Nearest pair: center distance",
        "length",
        "in",
        help="(N + n)/(2p) for the nearest whole-tooth pair (76).",
        equation="(76)",
    ),
    Output(
        "below_small_teeth",
        "Just below the ratio: small teeth",
        help="Same total T, small gear ⌈T/(G + 1)⌉ teeth: the largest ratio not above the target (RD2).",
        equation="(RD2)",
    ),
    Output(
        "below_large_teeth",
        "Just below the ratio: large teeth",
        help="The total T minus the small gear's teeth, for the pair just below the ratio (RD2).",
        equation="(RD2)",
    ),
    Output(
        "below_ratio",
        "Just below the ratio: ratio",
        help="N/n of the pair just below the ratio (75).",
        equation="(75)",
    ),
    Output(
        "above_small_teeth",
        "Just above the ratio: small teeth",
        help="Same total T, small gear ⌊T/(G + 1)⌋ teeth: the smallest ratio not below the target (RD2).",
        equation="(RD2)",
    ),
    Output(
        "above_large_teeth",
        "Just above the ratio: large teeth",
        help="The total T minus the small gear's teeth, for the pair just above the ratio (RD2).",
        equation="(RD2)",
    ),
    Output(
        "above_ratio",
        "Just above the ratio: ratio",
        help="N/n of the pair just above the ratio (75).",
        equation="(75)",
    ),
    Output(
        "small_pitch_diameter",
        "Small gear pitch diameter",
        "length",
        "in",
        help="Nearest pair's small gear, n/p (69).",
        equation="(69)",
    ),
    Output(
        "small_outside_diameter",
        "Small gear outside diameter",
        "length",
        "in",
        help="Nearest pair's small gear tip diameter, (n + 2)/p (70).",
        equation="(70)",
    ),
    Output(
        "large_pitch_diameter",
        "Large gear pitch diameter",
        "length",
        "in",
        help="Nearest pair's large gear, N/p (69).",
        equation="(69)",
    ),
    Output(
        "large_outside_diameter",
        "Large gear outside diameter",
        "length",
        "in",
        help="Nearest pair's large gear tip diameter, (N + 2)/p (70).",
        equation="(70)",
    ),
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
    """Whole-tooth splits of `total` with ratio just below (or equal) and just above G, pinion at
    least MIN_TEETH and ratio at least 1; None where no such split exists."""
    n_exact = total / (G + 1)
    below = above = None
    n_hi = max(snapped_ceil(n_exact), MIN_TEETH)  # more small teeth: ratio at or below G
    if n_hi <= total - n_hi:
        below = (n_hi, total - n_hi)
    n_lo = snapped_floor(n_exact)  # fewer small teeth: ratio at or above G
    if MIN_TEETH <= n_lo <= total - n_lo:
        above = (n_lo, total - n_lo)
    return below, above


def compute(v) -> Result:
    G, d, p = v["ratio"], v["center_distance"], v["diametral_pitch"]
    n, N = teeth_exact(G, d, p)
    total_exact = 2 * d * p  # N + n from (76)
    total = round(total_exact)
    if total < 2 * MIN_TEETH:
        raise InputError(
            "center_distance",
            f"too small for this pitch: it holds {total_exact:.3g} "
            f"teeth in total, a pair needs at least {2 * MIN_TEETH} "
            f"({MIN_TEETH} on each gear)",
        )
    warnings = []
    below, above = split(total, G)
    candidates = [pair for pair in (below, above) if pair]
    best = min(candidates, key=lambda pair: abs(math.log(pair[1] / pair[0]) - math.log(G)))
    values = {"small_teeth": n, "large_teeth": N}
    n_best, N_best = best
    values.update(
        nearest_small_teeth=n_best,
        nearest_large_teeth=N_best,
        nearest_ratio=N_best / n_best,
        nearest_center_distance=(n_best + N_best) / (2 * p),
    )
    for word, pair in (("below", below), ("above", above)):
        if pair:
            values.update(
                {
                    f"{word}_small_teeth": pair[0],
                    f"{word}_large_teeth": pair[1],
                    f"{word}_ratio": pair[1] / pair[0],
                }
            )
    values.update(
        small_pitch_diameter=n_best / p,
        small_outside_diameter=(n_best + 2) / p,  # (69), (70)
        large_pitch_diameter=N_best / p,
        large_outside_diameter=(N_best + 2) / p,
    )
    if abs(total - total_exact) > SNAP * total_exact:
        warnings.append(
            f"Whole teeth need the center distance {total / (2 * p) / IN:.4g} in "
            f"instead of {d / IN:.4g} in (N + n = {total})."
        )
    if above is None and total / (G + 1) < MIN_TEETH * (1 - SNAP):
        warnings.append(
            f"The ratio needs a {n:.3g}-tooth pinion at this center distance, below the "
            f"{MIN_TEETH}-tooth minimum: the nearest feasible pair is {n_best}:{N_best} "
            f"(ratio {N_best / n_best:.4g}); a larger center distance or finer pitch "
            f"reaches the ratio."
        )
    elif below is None:
        warnings.append("No whole-tooth pair reaches down to this ratio at this center distance.")
    elif n_best < 12:
        warnings.append(
            f"A {n_best}-tooth pinion is small (undercut unless profile-shifted; check "
            f"it is sold in this pitch)."
        )
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
