"""Seed section 8: gear clearance (eqs. 69-74).

The geometry, read from the seed's equations (p_23 is one diametral pitch shared by gears 2
and 3, so those two mesh): shaft A carries gears 1 and 2, shaft B carries gears 3 and 4, and
gears 2 and 3 mesh, which fixes the center distance A-B at r_p2 + r_p3. Gear 1 (on A, in
another plane) must not reach shaft B, and if gears 1 and 4 share a plane they must not touch:
    C_a = r_p2 + r_p3 − r_o1 − d_axle/2,   C_g = r_p2 + r_p3 − r_o1 − r_o4.

Corrections to the seed:
- (71) and (72) add the *outside* radii r_o2 + r_o3 for the center distance; meshing gears sit
  at the sum of their *pitch* radii (69), r_p2 + r_p3 = (n_2 + n_3)/(2 p_23); (71)/(72) are
  2/p_23 too large (0.1 in at 20 DP). (73)/(74) do use pitch radii for gears 2 and 3, so
  (71)/(72) and (73)/(74) disagree with each other.
- (73)/(74) then also use pitch radii for gears 1 and 4 (n_1/(2p_1), n_4/(2p_4)); what collides
  is the tooth tips, the outside radius (70): (n + 2)/(2p). The seed's values are 1/p_1 (and
  1/p_4) too optimistic: 0.05 in each at 20 DP. Corrected:
      C_a = (n_2 + n_3)/(2 p_23) − (n_1 + 2)/(2 p_1) − d_axle/2
      C_g = (n_2 + n_3)/(2 p_23) − (n_1 + 2)/(2 p_1) − (n_4 + 2)/(2 p_4)
- The seed checks only gear 1 against shaft B; the mirror check (gear 4 against shaft A) is
  reported as well, since gear 4 passes shaft A in exactly the same way:
      C_a4 = (n_2 + n_3)/(2 p_23) − (n_4 + 2)/(2 p_4) − d_axle/2                        (GC1)
"""

from __future__ import annotations

from ..declarations import Calculator, Output, Result
from ..fields import Field

_WHERE = (
    "Gears 2 and 3 mesh. Gear 1 is on the shaft of gear 2 (shaft A); gear 4 is on the shaft "
    "of gear 3 (shaft B)."
)


def _dp(name, label, help):
    return Field(
        name,
        label,
        "reciprocal_length",
        "1/in",
        default=20,
        min=0,
        min_exclusive=True,
        help=help + " Diametral pitch: teeth per inch of pitch diameter (e.g. 20 DP, 32 DP).",
    )


FIELDS = (
    Field(
        "teeth_1",
        "Gear 1 teeth (shaft A)",
        integer=True,
        default=36,
        min=1,
        max=100000,
        help="Gear 1 shares shaft A with gear 2; checked against shaft B and gear 4. " + _WHERE,
    ),
    Field(
        "teeth_2",
        "Gear 2 teeth (shaft A)",
        integer=True,
        default=50,
        min=1,
        max=100000,
        help="Gear 2 on shaft A meshes gear 3 on shaft B. " + _WHERE,
    ),
    Field(
        "teeth_3",
        "Gear 3 teeth (shaft B)",
        integer=True,
        default=12,
        min=1,
        max=100000,
        help="Gear 3 on shaft B meshes gear 2 on shaft A. " + _WHERE,
    ),
    Field(
        "teeth_4",
        "Gear 4 teeth (shaft B)",
        integer=True,
        default=20,
        min=1,
        max=100000,
        help="Gear 4 shares shaft B with gear 3; checked against gear 1 (and shaft A). " + _WHERE,
    ),
    _dp("diametral_pitch_1", "Gear 1 diametral pitch", "p_1 of gear 1."),
    _dp("diametral_pitch_23", "Gears 2-3 diametral pitch", "p_23 of the meshing pair 2-3."),
    _dp("diametral_pitch_4", "Gear 4 diametral pitch", "p_4 of gear 4."),
    Field(
        "axle_diameter",
        "Axle diameter",
        "length",
        "in",
        default=0.5,
        min=0,
        help="Diameter of the shafts (for a hex shaft use the size across corners: 1/2 in hex is 0.577 in).",
    ),
)

OUTPUTS = (
    Output(
        "center_distance",
        "Center distance A-B (gears 2-3)",
        "length",
        "in",
        help="Meshing gears 2 and 3 sit at the sum of their pitch radii, (n_2 + n_3)/(2·p_23) (69).",
        equation="(69)",
    ),
    Output(
        "outside_diameter_1",
        "Gear 1 outside diameter",
        "length",
        "in",
        help="Gear 1's tip diameter, (n_1 + 2)/p_1 (70).",
        equation="(70)",
    ),
    Output(
        "outside_diameter_4",
        "Gear 4 outside diameter",
        "length",
        "in",
        help="Gear 4's tip diameter, (n_4 + 2)/p_4 (70).",
        equation="(70)",
    ),
    Output(
        "axle_clearance",
        "Gear 1 to shaft B clearance",
        "length",
        "in",
        help="C_a: center distance − gear 1's outside radius − axle radius ((71)/(73), corrected).",
        equation="(71), (73)",
    ),
    Output(
        "gear_clearance",
        "Gear 1 to gear 4 clearance",
        "length",
        "in",
        help="C_g: center distance − outside radii of gears 1 and 4, if in one plane ((72)/(74), corrected).",
        equation="(72), (74)",
    ),
    Output(
        "axle_clears", "Gear 1 clears shaft B", help="Yes when C_a > 0 ((71)/(73)).", equation="(71), (73)"
    ),
    Output(
        "gear_clears", "Gear 1 clears gear 4", help="Yes when C_g > 0 ((72)/(74)).", equation="(72), (74)"
    ),
    Output(
        "axle_clearance_4",
        "Gear 4 to shaft A clearance",
        "length",
        "in",
        help="The mirror check: center distance − gear 4's outside radius − axle radius (GC1).",
        equation="(GC1)",
    ),
    Output(
        "axle_clears_4",
        "Gear 4 clears shaft A",
        help="Yes when the gear 4 to shaft A clearance is > 0 (GC1).",
        equation="(GC1)",
    ),
)


def pitch_radius(n, p):
    return n / (2 * p)  # (69)


def outside_radius(n, p):
    return (n + 2) / (2 * p)  # (70)


def half_teeth_over_pitch(terms) -> float:
    """Σ k/(2p) over (k, p) pairs, whole tooth counts summed first for equal pitches, so that
    gears that exactly touch give exactly 0 rather than ±1e-17 of rounding (which would flip
    the clears/does-not-clear verdict)."""
    by_pitch: dict[float, int] = {}
    for k, p in terms:
        by_pitch[p] = by_pitch.get(p, 0) + k
    return sum(k / (2 * p) for p, k in by_pitch.items())


def compute(v) -> Result:
    n1, n2, n3, n4 = v["teeth_1"], v["teeth_2"], v["teeth_3"], v["teeth_4"]
    p1, p23, p4 = v["diametral_pitch_1"], v["diametral_pitch_23"], v["diametral_pitch_4"]
    d_axle = v["axle_diameter"]
    D = pitch_radius(n2, p23) + pitch_radius(n3, p23)  # (n_2 + n_3)/(2 p_23), (69)
    r_o1, r_o4 = outside_radius(n1, p1), outside_radius(n4, p4)  # (70)
    C_a = half_teeth_over_pitch([(n2 + n3, p23), (-(n1 + 2), p1)]) - d_axle / 2  # (71)/(73), corrected
    C_g = half_teeth_over_pitch([(n2 + n3, p23), (-(n1 + 2), p1), (-(n4 + 2), p4)])  # (72)/(74), corrected
    C_a4 = half_teeth_over_pitch([(n2 + n3, p23), (-(n4 + 2), p4)]) - d_axle / 2  # gear 4 vs shaft A
    scale = D + r_o1 + r_o4 + d_axle  # rounding of the unit conversions is ~1e-16 of this
    C_a, C_g, C_a4 = (0.0 if abs(C) <= 1e-12 * scale else C for C in (C_a, C_g, C_a4))  # touching
    warnings = []
    if C_a <= 0:
        warnings.append("Gear 1 touches or cuts into shaft B (the shaft of gears 3 and 4).")
    if C_g <= 0:
        warnings.append("Gears 1 and 4 touch or overlap: they must sit in different planes.")
    if C_a4 <= 0:
        warnings.append("Gear 4 touches or cuts into shaft A (the shaft of gears 1 and 2).")
    values = {
        "center_distance": D,
        "outside_diameter_1": 2 * r_o1,
        "outside_diameter_4": 2 * r_o4,
        "axle_clearance": C_a,
        "gear_clearance": C_g,
        "axle_clears": bool(C_a > 0),
        "gear_clears": bool(C_g > 0),
        "axle_clearance_4": C_a4,
        "axle_clears_4": bool(C_a4 > 0),
    }
    return Result(values, warnings)


CALCULATOR = Calculator(
    id="gear_clearance",
    title="Gear clearance",
    summary="Does a gear on one shaft clear the neighbouring shaft and its gear? Gears 2 and 3 "
    "mesh; gear 1 rides with gear 2, gear 4 with gear 3 (seed section 8).",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="8",
)
