"""Seed section 7 and Appendix E: chain/belt center-to-center distance (eqs. 65-68, 110-113).

Symbols as in the seed: p pitch, n_i teeth, r_i pitch radii, l links (belt teeth), L = l·p the
length (66), D the center distance, C = D − (r_1 + r_2) the clearance between pitch circles (67).
Sprocket 2 is whichever is larger below (Δ = r_2 − r_1 ≥ 0); the length is symmetric anyway.

Corrections to the seed (derived again; checked against mpmath in tests/test_chain_belt.py):
- (112) claims cos⁻¹((r_2 − r_1)/D) = cos⁻¹((r_1 − r_2)/D); false, cos⁻¹(−x) = π − cos⁻¹(x).
  The first form is right, so Appendix E's final (68) should read
      L = 2√(D² − Δ²) + 2(r_1 − r_2)·cos⁻¹((r_2 − r_1)/D) + 2π r_2,
  i.e. the exact open-drive length L = 2X + π(r_1 + r_2) + 2Δ·sin⁻¹(Δ/D), X = √(D² − Δ²), the
  same as L = 2D cos β + (π/2)(D_1 + D_2) + β(D_2 − D_1) with sin β = (D_2 − D_1)/(2D).
  The seed's form swaps the two wrap angles, giving a length short by 4Δ·sin⁻¹(Δ/D): for 20T
  and 30T on a 100-tooth 5 mm belt it gives D = 188.005 mm instead of 187.331 mm (ReCalc).
- Section 7's printed (68) also has 2(r_1 + r_2) for 2(r_1 − r_2) (a typo): 109.9 mm there.
- The seed solves (68) by Newton from D = L/2. Near the shortest length that wraps both
  (D → Δ) dL/dD = 2X/D → 0 and Newton fails. Here L is rewritten with u = X/Δ as
      L = 2π r_2 + 2Δ·(u − tan⁻¹ u),
  (u − tan⁻¹ u by its series for small u, no cancellation) and u is bracketed for brentq:
  max(s, (3s)^(1/3)) ≤ u ≤ s + π/2 where s = (L − 2π r_2)/(2Δ). Equal sprockets (Δ = 0)
  have the closed form D = (L − π d)/2.
- The seed takes the pitch diameter as n·p/π (65): exact for belts, while a chain sprocket's
  pitch circle through the roller centres is p / sin(180°/n) (slightly larger). That larger
  circle must NOT go into the length equation: the chain wraps the sprocket as a polygon of n
  links, n·p per turn, so the path length is (68) with n·p/π for chains too. For equal sprockets
  this is exact (D = (l − n)·p/2: the taut chain round two equal polygons is 2D + n·p), and for
  unequal ones the taut convex hull round the two roller polygons brackets l·p over the sprockets'
  phases (tests/test_chain_belt.py). p/sin(180°/n) in (68) would put D short by about
  (π²p/24)·(1/n_1 + 1/n_2) (16T-16T #25, 64 links: 5.987 in instead of exactly 6 in). So the
  pitch-diameter choice sets only the pitch diameters shown and the clearance (67).
- The seed's shortest length (D = |r_2 − r_1|) puts the small sprocket inside the large one. The
  fewest links reported here are the fewest at which the two wheels clear each other: for chain
  the sprockets' outside circles, OD = p·(0.6 + cot(180°/n)) (ANSI B29.1, the tooth tips reach
  past the roller circle), for belts the pitch circles n·p/π (a pulley's outside diameter lies
  inside its pitch circle by the pitch-line differential). Clear means D > (OD_1 + OD_2)/2.
- A standard pitch says whether it is a chain or a belt; the "Chain or belt" field is asked only
  for a custom pitch (picking #25 chain with the field left at belt used to be an error).

Equations beyond the seed (cited by the outputs), Δ = |r_2 − r_1|, X = √(D² − Δ²):
    r = p/(2·sin(180°/n))          chordal pitch radius of a chain sprocket (shown only)   (CB1)
    θ_small = π − 2·sin⁻¹(Δ/D) = 2·tan⁻¹(X/Δ)        wrap on the smaller wheel            (CB2)
    the wheels clear when D > (OD_1 + OD_2)/2, OD = p·(0.6 + cot(180°/n)) for a chain
        sprocket (ANSI B29.1), n·p/π for a belt pulley                                     (CB3)
    L(D) = 2X + π(r_1 + r_2) + 2Δ·sin⁻¹(Δ/D)         (68) corrected, as derived above      (CB4)
    l_below = s·⌊l_exact/s⌋, l_above = l_below + s (one count when l_exact is whole),
        s = 2 for chain without half links, else 1                                         (CB5)
    belt teeth in mesh on each pulley: z_i = ⌊θ_i/(2π)·n_i⌋, θ_small from (CB2),
        θ_large = 2π − θ_small; whole teeth, as the belt makers count teeth "in full contact"  (CB6)

(CB6) sources and conventions: Gates' drive design manuals (as quoted on Gates' own applications
blog, gatesbeltsandapplications.blogspot.com, 2012-05) ask for at least six teeth in mesh on a
loaded sprocket, subtract 20 % of the belt's rating for each tooth short of six "in full contact",
and ask for at least 60° of wrap on each loaded sprocket; Gates' printed formula is a linearised
form in (D − d)/C which could not be retrieved here, so the exact wrap (CB2) is used and the count
rounded down to whole teeth (a tooth partly in the arc is not in full contact). A pulley short of
6 teeth in mesh gets a warning. ReCalc's belts.ts teethInMesh (tervay/recalc, commit 03511cb4)
gives the larger pulley the smaller wrap and vice versa (20T and 30T HTD 5 mm at 100 mm: 10 and 14
there, 9 and 15 by (CB6)), and floors 9.99999... for a 180° wrap on 20T (9 there, 10 here: the
count is floored after adding 1e-9 for the rounding of an exact whole number).
"""

from __future__ import annotations

import math

from ..constants import INCH as IN
from ..declarations import Calculator, Output, Result
from ..errors import InputError
from ..fields import Field

MM = 1e-3
MIN_TEETH_IN_MESH = 6  # Gates: fewer in full contact cost 20 % of the belt's rating per tooth

STANDARDS = ("chain_25", "chain_35", "chain_40", "htd_5mm", "gt2_3mm", "rt25", "custom")
STANDARD_LABELS = (
    "#25 chain (1/4 in)",
    "#35 chain (3/8 in)",
    "#40 chain (1/2 in)",
    "HTD 5 mm belt",
    "GT2 3 mm belt",
    "RT25 belt (1/4 in)",
    "Custom pitch",
)
STANDARD_PITCH = {
    "chain_25": 0.25 * IN,
    "chain_35": 0.375 * IN,
    "chain_40": 0.5 * IN,
    "htd_5mm": 5 * MM,
    "gt2_3mm": 3 * MM,
    "rt25": 0.25 * IN,
}
STANDARD_KIND = {
    "chain_25": "chain",
    "chain_35": "chain",
    "chain_40": "chain",
    "htd_5mm": "belt",
    "gt2_3mm": "belt",
    "rt25": "belt",
}

FIELDS = (
    Field(
        "mode",
        "Solve for",
        choices=("center_from_links", "links_from_center"),
        choice_labels=("Center distance from length", "Length from center distance"),
        default="center_from_links",
        help="Forward: a chain/belt length gives the center distance. Reverse: a wanted center "
        "distance gives the nearest usable lengths below and above it.",
    ),
    Field(
        "pitch_standard",
        "Pitch standard",
        choices=STANDARDS,
        choice_labels=STANDARD_LABELS,
        default="htd_5mm",
        help="A standard sets the pitch and whether it is a chain or a belt; "
        "choose Custom to type the pitch below.",
    ),
    Field(
        "kind",
        "Chain or belt",
        choices=("chain", "belt"),
        default="belt",
        help="Custom pitch only (a standard sets it): chains use an even number of links unless "
        "a half (offset) link is allowed; belts may have any number of teeth.",
        when=(("pitch_standard", ("custom",)),),
    ),
    Field(
        "pitch",
        "Custom pitch",
        "length",
        "mm",
        default=5,
        min=0,
        min_exclusive=True,
        help="Chain pitch or belt tooth pitch p, used when the standard is Custom.",
        when=(("pitch_standard", ("custom",)),),
    ),
    Field(
        "teeth_1",
        "Sprocket/pulley 1 teeth",
        integer=True,
        default=20,
        min=3,
        max=10000,
        help="Teeth n_1 on the first sprocket or pulley.",
    ),
    Field(
        "teeth_2",
        "Sprocket/pulley 2 teeth",
        integer=True,
        default=30,
        min=3,
        max=10000,
        help="Teeth n_2 on the second sprocket or pulley.",
    ),
    Field(
        "links",
        "Links / belt teeth",
        integer=True,
        default=100,
        min=1,
        max=100_000,  # a bound like every count's (was none: 1e308 links gave a 9.8e306 in C-C)
        modes=("center_from_links",),
        help="Chain links or belt teeth l; length L = l·p (66). At most 100 000.",
    ),
    Field(
        "target_center",
        "Wanted center distance",
        "length",
        "in",
        default=7.5,
        min=0,
        min_exclusive=True,
        modes=("links_from_center",),
        help="Center distance D you would like; the nearest usable lengths are found.",
    ),
    Field(
        "half_links",
        "Allow half links",
        boolean=True,
        default=False,
        help="Chain only (ignored for a belt): a half (offset) link allows an odd number of links.",
        when=(("pitch_standard", ("chain_25", "chain_35", "chain_40", "custom")),),
    ),
    Field(
        "pitch_diameter",
        "Pitch diameter shown",
        choices=("circumference", "chordal"),
        choice_labels=("n·p/π (spreadsheet; exact for belts)", "p/sin(180°/n) (true sprocket circle)"),
        default="circumference",
        help="Pitch diameters and clearance shown: n·p/π as the seed (65), or a chain sprocket's "
        "true pitch circle through the roller centres, p/sin(180°/n). The center distance "
        "does not depend on it: a chain wraps a sprocket as n links, n·p per turn.",
    ),
)

OUTPUTS = (
    Output(
        "center_distance",
        "Center distance",
        "length",
        "in",
        help="Center distance D at which the length equation (68, corrected) gives this length L = l·p.",
        equation="(66), (68)",
    ),
    Output(
        "clearance",
        "Clearance between pitch circles",
        "length",
        "in",
        help="Gap between the pitch circles, C = D − (r_1 + r_2); negative: the sprockets overlap (67).",
        equation="(67)",
    ),
    Output(
        "length",
        "Chain/belt length",
        "length",
        "in",
        help="Links (belt teeth) × pitch, L = l·p (66).",
        equation="(66)",
    ),
    Output(
        "links_exact",
        "Exact links for that distance",
        help="Length at the wanted center distance (68, corrected) ÷ pitch: a fractional link count.",
        equation="(66), (68)",
    ),
    Output(
        "links_below",
        "Shorter usable length (links)",
        help="The exact count rounded down to a usable one (even for chain without half links) (CB5).",
        equation="(CB5)",
    ),
    Output(
        "center_below",
        "Center distance, shorter",
        "length",
        "in",
        help="Center distance the shorter usable length gives (68, corrected).",
        equation="(66), (68)",
    ),
    Output(
        "links_above",
        "Longer usable length (links)",
        help="The exact count rounded up to a usable one (even for chain without half links) (CB5).",
        equation="(CB5)",
    ),
    Output(
        "center_above",
        "Center distance, longer",
        "length",
        "in",
        help="Center distance the longer usable length gives (68, corrected).",
        equation="(66), (68)",
    ),
    Output(
        "pitch_diameter_1",
        "Pitch diameter 1",
        "length",
        "in",
        help="Wheel 1: n·p/π (65), or a sprocket's chordal p/sin(180°/n) (CB1), as chosen below.",
        equation="(65), (CB1)",
    ),
    Output(
        "pitch_diameter_2",
        "Pitch diameter 2",
        "length",
        "in",
        help="Wheel 2: n·p/π (65), or a sprocket's chordal p/sin(180°/n) (CB1), as chosen below.",
        equation="(65), (CB1)",
    ),
    Output(
        "wrap_angle_small",
        "Wrap on the smaller sprocket",
        "angle",
        "deg",
        help="Angle of contact on the smaller wheel, π − 2·sin⁻¹(|r_2 − r_1|/D) (CB2).",
        equation="(CB2)",
    ),
    Output(
        "teeth_in_mesh_1",
        "Belt teeth in mesh, pulley 1",
        help="Whole belt teeth in the wrap of pulley 1, ⌊θ_1/(2π)·n_1⌋ (belts; reverse mode: at the wanted D).",
        equation="(CB6)",
    ),
    Output(
        "teeth_in_mesh_2",
        "Belt teeth in mesh, pulley 2",
        help="Whole belt teeth in the wrap of pulley 2, ⌊θ_2/(2π)·n_2⌋ (belts; reverse mode: at the wanted D).",
        equation="(CB6)",
    ),
    Output(
        "minimum_links",
        "Fewest links with both clear",
        help="Fewest links (belt teeth) at which the wheels clear each other, D > (OD_1 + OD_2)/2 (CB3).",
        equation="(CB3)",
    ),
)


# --- pitch radii (65) -----------------------------------------------------------------------


def pitch_radius(n: int, p: float, method: str) -> float:
    if method == "chordal":
        return p / (2 * math.sin(math.pi / n))  # true sprocket pitch circle
    return n * p / (2 * math.pi)  # (65): 2π r = n p


# --- length equation (68), exact form --------------------------------------------------------


def u_minus_atan(u: float) -> float:
    """u − tan⁻¹(u) for u ≥ 0 without cancellation: series u³/3 − u⁵/5 + ... for small u."""
    if u > 0.25:
        return u - math.atan(u)
    u2, term, total, k = u * u, u * u * u, 0.0, 3
    while True:
        piece = term / k
        total += piece
        if abs(piece) <= 1e-18 * abs(total) or term == 0:
            return total
        term *= -u2
        k += 2


def length_from_center(D: float, r1: float, r2: float) -> float:
    """Exact open-drive length L(D) (Appendix E corrected), D ≥ |r_2 − r_1|."""
    r_small, r_large = min(r1, r2), max(r1, r2)
    delta = r_large - r_small
    if delta == 0:
        return 2 * D + 2 * math.pi * r_large
    X = math.sqrt(max(0.0, (D - delta) * (D + delta)))  # (111), factored: no cancellation
    # (110)-(113) with (112) corrected: L = 2X + π(r_1 + r_2) + 2Δ·sin⁻¹(Δ/D), rewritten
    # with sin⁻¹(Δ/D) = π/2 − tan⁻¹(X/Δ) so that it stays accurate as X → 0
    return 2 * math.pi * r_large + 2 * delta * u_minus_atan(X / delta)


def clear_radius_sum(n1: int, n2: int, p: float, kind: str) -> float:
    """(OD_1 + OD_2)/2: the center distance at which the two wheels touch."""
    if kind == "chain":  # ANSI B29.1 sprocket outside diameter p·(0.6 + cot(180°/n))
        return sum(p * (0.6 + 1 / math.tan(math.pi / n)) for n in (n1, n2)) / 2
    return (n1 + n2) * p / (2 * math.pi)  # belt: pitch circles (65)


def minimum_length(r1: float, r2: float) -> float:
    """Shortest length that wraps both: D = |r_2 − r_1|, the small one inside the large one."""
    return 2 * math.pi * max(r1, r2)


def span_from_length(L: float, r1: float, r2: float, excess: float | None = None) -> tuple[float, float]:
    """(D, X): center distance and straight span X = √(D² − Δ²) from L (inverse of (68)).

    L must be at least minimum_length. Relative error ~1e-15 in D, and in X too (X is solved
    for directly, so it stays accurate near the minimum where D − Δ would cancel). `excess`,
    if known exactly, is S = (L − 2π r_large)/2 (for n·p/π diameters it is (l − n_large)·p/2).
    """
    r_large = max(r1, r2)
    delta = r_large - min(r1, r2)
    S = (L - 2 * math.pi * r_large) / 2 if excess is None else excess  # = Δ·(u − tan⁻¹ u), u = X/Δ
    if -1e-13 * L <= S < 0:  # at the minimum, lost to rounding
        S = 0.0
    if S < 0:
        raise ValueError("length shorter than the wrap minimum")
    if delta == 0:
        return S, S  # equal sprockets: D = X = (L − π d)/2
    s = S / delta
    if s == 0:
        return delta, 0.0
    from scipy.optimize import brentq

    lo = max(s, (3 * s) ** (1 / 3)) if s < 1e100 else s  # u − tan⁻¹u ≤ min(u, u³/3)
    hi = s + math.pi / 2  # u − tan⁻¹u ≥ u − π/2
    lo = min(lo, hi)
    f = lambda u: u_minus_atan(u) - s  # noqa: E731
    if f(lo) >= 0:
        u = lo
    elif f(hi) <= 0:
        u = hi
    else:
        u = brentq(f, lo, hi, xtol=1e-300, rtol=1e-15, maxiter=500)
    return delta * math.hypot(1.0, u), delta * u  # D = √(X² + Δ²)


def center_from_length(L: float, r1: float, r2: float, excess: float | None = None) -> float:
    return span_from_length(L, r1, r2, excess)[0]


def wrap_angle(X: float, r1: float, r2: float) -> float:
    """Angle of contact on the smaller sprocket, π − 2·sin⁻¹(Δ/D) = 2·tan⁻¹(X/Δ) (accurate at X → 0)."""
    return 2 * math.atan2(X, abs(r2 - r1))


def teeth_in_mesh(X: float, n1: int, n2: int) -> tuple[int, int]:
    """(CB6): whole teeth in the wrap of each pulley (r ∝ n for a belt, so Δ ∝ |n_2 − n_1|)."""
    small = 2 * math.atan2(X, abs(n2 - n1) / (2 * math.pi))  # (CB2), θ on the smaller, per unit p
    theta_1, theta_2 = (small, 2 * math.pi - small) if n1 <= n2 else (2 * math.pi - small, small)
    if n1 == n2:
        theta_1 = theta_2 = math.pi
    return tuple(math.floor(th / (2 * math.pi) * n + 1e-9) for th, n in ((theta_1, n1), (theta_2, n2)))


def mesh_check(values: dict, warnings: list[str], X: float, p: float, n1: int, n2: int) -> None:
    """(CB6) outputs and the makers' six-teeth warning, belts only (X the straight span, m)."""
    z1, z2 = teeth_in_mesh(X / p, n1, n2)
    values.update(teeth_in_mesh_1=z1, teeth_in_mesh_2=z2)
    short = [f"pulley {i} ({z} teeth)" for i, z in ((1, z1), (2, z2)) if z < MIN_TEETH_IN_MESH]
    if short:
        warnings.append(
            f"Fewer than {MIN_TEETH_IN_MESH} belt teeth in mesh on {' and '.join(short)}: the belt "
            f"makers (Gates) ask for at least {MIN_TEETH_IN_MESH} on a loaded pulley and derate the "
            f"belt 20 % per tooth short; it may skip. Use a larger pulley or a longer center distance."
        )


# --- the calculator --------------------------------------------------------------------------


def step_of(kind: str, half_links: bool) -> int:
    return 2 if kind == "chain" and not half_links else 1


def compute(v) -> Result:
    warnings: list[str] = []
    standard = v["pitch_standard"]
    if standard == "custom":
        p, kind = v["pitch"], v["kind"]
    else:  # the custom pitch and kind fields are not used
        p, kind = STANDARD_PITCH[standard], STANDARD_KIND[standard]
    n1, n2 = v["teeth_1"], v["teeth_2"]
    method = v["pitch_diameter"]
    if kind == "belt" and method == "chordal":
        warnings.append(
            "Belts: n·p/π is the exact pulley pitch diameter; p/sin(180°/n) is for chain sprockets."
        )
    # the chain/belt path: n·p per turn of either, so r = n·p/(2π) (65) for chain as for belt
    r1, r2 = pitch_radius(n1, p, "circumference"), pitch_radius(n2, p, "circumference")
    shown_1, shown_2 = pitch_radius(n1, p, method), pitch_radius(n2, p, method)  # diameters, (67)
    step = step_of(kind, v["half_links"])
    unit = "links" if kind == "chain" else "belt teeth"

    def spare(l: int) -> float:
        """S = (l·p − 2π r_large)/2 = (l − n_large)·p/2, the length beyond the wrap minimum,
        halved; exact in whole teeth since 2π r = n p (65)."""
        return (l - max(n1, n2)) * p / 2

    l_min = step * math.ceil(max(n1, n2) / step)  # L ≥ 2π r_large = n_large·p
    touch = clear_radius_sum(n1, n2, p, kind)  # D at which the wheels touch
    l_clear = max(l_min, step * math.ceil(length_from_center(touch, r1, r2) / p / step))
    while center_from_length(l_clear * p, r1, r2, spare(l_clear)) <= touch:  # rounding at the edge
        l_clear += step
    values = {"pitch_diameter_1": 2 * shown_1, "pitch_diameter_2": 2 * shown_2, "minimum_links": l_clear}
    wheels = "sprockets' outside circles" if kind == "chain" else "pulleys' pitch circles"

    if v["mode"] == "center_from_links":
        l = v["links"]
        L = l * p  # (66)
        if spare(l) < 0:
            raise InputError(
                "links", f"{l} {unit} are too short to wrap both sprockets: at least {l_min} are needed"
            )
        if kind == "chain" and l % 2 and not v["half_links"]:
            warnings.append(
                "An odd number of links needs a half (offset) link: allow half links or use an even count."
            )
        D, X = span_from_length(L, r1, r2, spare(l))
        values.update(center_distance=D, length=L, clearance=D - (shown_1 + shown_2))  # (67)
        values["wrap_angle_small"] = wrap_angle(X, r1, r2)
        if kind == "belt":
            mesh_check(values, warnings, X, p, n1, n2)
        if D <= touch:
            warnings.append(
                f"The {wheels} overlap at this length: the wheels would collide; "
                f"{l_clear} {unit} is the fewest at which they clear."
            )
        return Result(values, warnings)

    # links_from_center: the reverse calculation
    D = v["target_center"]
    delta = abs(r2 - r1)
    if D < delta:
        raise InputError(
            "target_center",
            f"shorter than the difference of the pitch radii ({delta / IN:.4g} in): no chain path wraps both",
        )
    L = length_from_center(D, r1, r2)
    l_exact = L / p
    values["links_exact"] = l_exact
    if kind == "belt":  # at the wanted center distance
        mesh_check(values, warnings, math.sqrt((D - delta) * (D + delta)), p, n1, n2)
    if D <= touch:
        warnings.append(
            f"The {wheels} overlap at this center distance: the wheels would collide; "
            f"{l_clear} {unit} is the fewest at which they clear."
        )
    nearest = step * round(l_exact / step)
    if abs(nearest - l_exact) <= 1e-9 * l_exact:
        below = above = nearest
    else:
        below = step * math.floor(l_exact / step)
        above = below + step
    if below >= 1 and spare(below) >= 0:
        values["links_below"] = below
        values["center_below"] = center_from_length(below * p, r1, r2, spare(below))
    else:
        warnings.append(f"No shorter usable length: fewer than {l_min} {unit} cannot wrap both.")
    while spare(above) < 0:  # only when rounding put the exact count a hair under the minimum
        above += step
    values["links_above"] = above
    values["center_above"] = center_from_length(above * p, r1, r2, spare(above))
    return Result(values, warnings)


CALCULATOR = Calculator(
    id="chain_belt",
    title="Chain/belt C-C",
    summary="Center distance from a chain or belt length, or the nearest lengths for a wanted "
    "center distance (seed section 7, Appendix E).",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="7",
)
