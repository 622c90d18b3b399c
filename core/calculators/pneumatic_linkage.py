"""Seed section 11: a pneumatic cylinder swinging an arm (eqs. 84-89).

Geometry, read off (84)-(87) (the seed's figure is lost): x right, y up, origin at the arm pivot.
The rod end is fixed to the arm at (X, Y) in arm coordinates, so when the arm has turned by θ
(counter-clockwise positive) it is at P(θ) = (X cos θ − Y sin θ, X sin θ + Y cos θ). The
cylinder's fixed pivot is at C = (−A, B): A is how far the arm pivot lies to the right of the
cylinder pivot, B how far the cylinder pivot lies above the arm pivot. α is the cylinder's angle
below the horizontal, L its retracted pin-to-pin length and L + ΔL its extended length.

With r = |(X, Y)|, d = |C|, φ = atan2(Y, X) and ψ = atan2(B, −A), (88)/(89) are the law of cosines
    ℓ² = r² + d² − 2rd·cos(θ + φ − ψ)                                   (88), (89)
so in the triangle (arm pivot, cylinder pivot, rod end) the angle at the arm pivot is
    γ(ℓ) = atan2(2·area, (r² + d² − ℓ²)/2),   2·area = ½·sqrt(Heron product of r, d, ℓ)     (PL1)
and
    θ = ψ − φ ± γ(ℓ)                                                                          (PL2)
The two signs are the two assemblies (mirror images about the line from the arm pivot to the
cylinder pivot). "Primary" is +: extending the cylinder turns the arm counter-clockwise; the other
assembly turns it clockwise. The pushing cylinder's torque on the arm is F·dℓ/dθ, and
    h = |dℓ/dθ| = rd·sin γ/ℓ = 2·area/ℓ,   τ = ±F·h                                           (PL3)
is the lever arm (the distance from the arm pivot to the cylinder's line), so no cylinder can turn
an arm through 180° or more (dead centre). The cylinder's own angle below the horizontal follows
from (84)/(86) (retracted) and (85)/(87) (extended): ℓ·cos α = A + P_x(θ), ℓ·sin α = B − P_y(θ).
The pin-to-pin length can only lie between the two dead centres:
    |d − r| ≤ ℓ ≤ d + r                                                                       (PL5)

Reverse: the cylinder pivot is at distance L from P(θ1) and L + ΔL from P(θ2): a circle-circle
intersection with two mirror solutions about the chord P(θ1)P(θ2), of length c = 2r·|sin(Δθ/2)|
(closed form; subtracting the two points loses every digit when Δθ is tiny):
    C = P(θ1) + a·e ± b·e⊥,  a = (c² − ΔL·(2L + ΔL))/(2c),  b = 2·area(L, L + ΔL, c)/c       (PL4)
with e the unit vector from P(θ1) to P(θ2). A solution is kept
only if the arm does not pass dead centre between θ1 and θ2 (then, and only then, the cylinder
length grows monotonically from L to L + ΔL along the swing); rejected ones are named in a warning.

Departures from / corrections to the seed:
- The text says (88) combines (84) with (87); it is (84) with (86) (both retracted).
- The seed gives no solution of (88)/(89); the closed forms above are derived here (sympy check of
  (88) and of the lever arm = dℓ/dθ in tests/test_pneumatic_linkage.py) and written with atan2 and
  Kahan's ordering of Heron's formula so that they keep full accuracy at dead centre (tangent
  circles), where acos(...) loses half the digits.
"""

from __future__ import annotations

import math

from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field
from ..units import format_quantity

MODES = ("forward", "reverse")
MODE_LABELS = ("Arm angles from pivot", "Pivot from arm angles")
TOUCH = 1e-10  # relative slack: inputs meant to be exactly at dead centre still solve (as touching)
# Dead centre is where the cylinder's line passes through the arm pivot: the lever arm h = dℓ/dθ
# is 0 and the cylinder gives no torque. Warn while h < 10 % of the arm length r (the rod end's
# distance from the arm pivot), i.e. while the cylinder pushes within asin(0.1) = 5.7° of along
# the arm, so the torque is under a tenth of F·r.
NEAR_DEAD_CENTRE = 0.10
SIDE_SLACK = 1e-9  # sin of the angle by which a rod end may sit past the line through both pivots (rounding)
CURVE_POINTS = 61

FIELDS = (
    Field(
        "mode",
        "Solve for",
        choices=MODES,
        choice_labels=MODE_LABELS,
        default="forward",
        help="Forward: where the arm ends up. Reverse: where to put the cylinder's fixed pivot.",
    ),
    Field(
        "pivot_x",
        "Cylinder pivot A (horizontal)",
        "length",
        "in",
        default=6,
        modes=("forward",),
        help="A: how far the arm pivot lies to the right of the cylinder's fixed pivot "
        "(the cylinder pivot is at (−A, B) from the arm pivot).",
    ),
    Field(
        "pivot_y",
        "Cylinder pivot B (vertical)",
        "length",
        "in",
        default=-14,
        modes=("forward",),
        help="B: how far the cylinder's fixed pivot lies above the arm pivot (negative: below).",
    ),
    Field(
        "retracted_angle",
        "Arm angle retracted θ1",
        "angle",
        "deg",
        default=-45,
        modes=("reverse",),
        min=-360,
        max=360,
        help="Arm rotation θ1 with the cylinder retracted, counter-clockwise from the pose in "
        "which the rod end is at (X, Y); −360° to 360°.",
    ),
    Field(
        "extended_angle",
        "Arm angle extended θ2",
        "angle",
        "deg",
        default=45,
        modes=("reverse",),
        min=-360,
        max=360,
        help="Arm rotation θ2 with the cylinder extended, −360° to 360°; |θ2 − θ1| must be under 180°.",
    ),
    Field(
        "arm_x",
        "Rod end on arm X",
        "length",
        "in",
        default=5,
        help="X: rod-end attachment along the arm, from the arm pivot, at θ = 0.",
    ),
    Field(
        "arm_y",
        "Rod end on arm Y",
        "length",
        "in",
        default=0,
        help="Y: rod-end attachment across the arm (up at θ = 0), from the arm pivot.",
    ),
    Field(
        "retracted_length",
        "Retracted length L",
        "length",
        "in",
        default=11,
        min=0,
        min_exclusive=True,
        help="L: cylinder pin-to-pin length when retracted.",
    ),
    Field(
        "stroke",
        "Stroke ΔL",
        "length",
        "in",
        default=6,
        min=0,
        min_exclusive=True,
        help="ΔL: extended length is L + ΔL.",
    ),
    Field(
        "cylinder_force",
        "Cylinder push force",
        "force",
        "lbf",
        default=100,
        min=0,
        help="Push force F for the torque outputs (e.g. eq. 82: πD²/4 · P from the pneumatics tab).",
    ),
)

OUTPUTS = (
    Output(
        "retracted_angle",
        "Arm angle retracted θ1",
        "angle",
        "deg",
        help="θ1 at which the pin-to-pin length is L: ψ − φ + γ(L); extending turns the arm CCW (PL2).",
        equation="(88), (PL2)",
    ),
    Output(
        "extended_angle",
        "Arm angle extended θ2",
        "angle",
        "deg",
        help="θ2 at which the length is L + ΔL, same assembly: θ1 + γ(L + ΔL) − γ(L) (PL2).",
        equation="(89), (PL2)",
    ),
    Output(
        "pivot_x",
        "Cylinder pivot A",
        "length",
        "in",
        help="Reverse: A of the pivot at L from the rod end at θ1 and L + ΔL from it at θ2 (PL4).",
        equation="(88), (89), (PL4)",
    ),
    Output(
        "pivot_y",
        "Cylinder pivot B",
        "length",
        "in",
        help="Reverse: B of the pivot at L from the rod end at θ1 and L + ΔL from it at θ2 (PL4).",
        equation="(88), (89), (PL4)",
    ),
    Output(
        "sweep",
        "Arm swing θ2 − θ1",
        "angle",
        "deg",
        help="θ2 − θ1: how far the arm turns over the stroke (PL2).",
        equation="(PL2)",
    ),
    Output(
        "retracted_angle_alt",
        "Other assembly: θ1",
        "angle",
        "deg",
        help="Mirror assembly, ψ − φ − γ(L): extending turns the arm clockwise (PL2).",
        equation="(88), (PL2)",
    ),
    Output(
        "extended_angle_alt",
        "Other assembly: θ2",
        "angle",
        "deg",
        help="Mirror assembly's θ2 = θ1 − (γ(L + ΔL) − γ(L)), continuing from θ1 (may pass ±180°) (PL2).",
        equation="(89), (PL2)",
    ),
    Output(
        "pivot_x_alt",
        "Second pivot A",
        "length",
        "in",
        help="Reverse: A of the other circle intersection, when it also works (PL4).",
        equation="(88), (89), (PL4)",
    ),
    Output(
        "pivot_y_alt",
        "Second pivot B",
        "length",
        "in",
        help="Reverse: B of the other circle intersection, when it also works (PL4).",
        equation="(88), (89), (PL4)",
    ),
    Output(
        "retracted_cylinder_angle",
        "Cylinder angle α1 (below horiz.)",
        "angle",
        "deg",
        help="α1 from L·cos α = A + P_x(θ1) and L·sin α = B − P_y(θ1) (84), (86).",
        equation="(84), (86)",
    ),
    Output(
        "extended_cylinder_angle",
        "Cylinder angle α2 (below horiz.)",
        "angle",
        "deg",
        help="α2 from (L + ΔL)·cos α = A + P_x(θ2) and (L + ΔL)·sin α = B − P_y(θ2) (85), (87).",
        equation="(85), (87)",
    ),
    Output(
        "retracted_lever_arm",
        "Lever arm retracted",
        "length",
        "in",
        help="Distance h from the arm pivot to the cylinder's line, = dℓ/dθ; warned below 10 % of r (PL3).",
        equation="(PL3)",
    ),
    Output(
        "extended_lever_arm",
        "Lever arm extended",
        "length",
        "in",
        help="Distance h from the arm pivot to the cylinder's line when extended, = dℓ/dθ (PL3).",
        equation="(PL3)",
    ),
    Output(
        "retracted_torque",
        "Arm torque retracted",
        "torque",
        "N*m",
        help="Push force × lever arm, F·h, on the arm when retracted; counter-clockwise positive (PL3).",
        equation="(PL3)",
    ),
    Output(
        "extended_torque",
        "Arm torque extended",
        "torque",
        "N*m",
        help="Push force × lever arm, F·h, on the arm when extended; counter-clockwise positive (PL3).",
        equation="(PL3)",
    ),
    Output(
        "min_length",
        "Shortest pin-to-pin reachable",
        "length",
        "in",
        help="|d − r|: the shortest cylinder length these pivots allow, arm at dead centre (PL5).",
        equation="(PL5)",
    ),
    Output(
        "max_length",
        "Longest pin-to-pin reachable",
        "length",
        "in",
        help="d + r: the longest cylinder length these pivots allow, arm at dead centre (PL5).",
        equation="(PL5)",
    ),
)


def heron16(a: float, b: float, c: float) -> float:
    """16·area² of the triangle with sides a, b, c (Kahan's ordering; negative: no triangle)."""
    a, b, c = sorted((a, b, c), reverse=True)
    return (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c))


def pivot_angle(r: float, d: float, ell: float) -> float:
    """γ: angle at the arm pivot between cylinder pivot and rod end, from (88) (law of cosines)."""
    small, big = sorted((r, d))
    k = (small * small + (big - ell) * (big + ell)) / 2  # r·d·cos γ, without cancelling big² − ℓ²
    return math.atan2(math.sqrt(max(heron16(r, d, ell), 0.0)) / 2, k)  # r·d·sin γ = 2·area


def lever_arm(r: float, d: float, ell: float) -> float:
    """dℓ/dθ = r·d·sin γ / ℓ = 2·area/ℓ: distance from the arm pivot to the cylinder's line."""
    return math.sqrt(max(heron16(r, d, ell), 0.0)) / (2 * ell)


def rod_end(X: float, Y: float, theta: float) -> tuple[float, float]:
    """P(θ), the left sides of (84)/(86) without A."""
    c, s = math.cos(theta), math.sin(theta)
    return X * c - Y * s, X * s + Y * c


def cylinder_angle(A: float, B: float, X: float, Y: float, theta: float) -> float:
    """α from (84)/(86): L cos α = A + Px, L sin α = B − Py."""
    px, py = rod_end(X, Y, theta)
    return math.atan2(B - py, A + px)


def wrap(angle: float) -> float:
    return math.remainder(angle, 2 * math.pi)


def check_length(ell: float, lo: float, hi: float, field: str, what: str) -> float:
    """ℓ must lie in [|d − r|, d + r] for (88)/(89) to have a root; touching within TOUCH is dead centre."""
    slack = TOUCH * hi
    if ell < lo - slack or ell > hi + slack:
        short = ell < lo
        raise InputError(
            field,
            f"{what} {format_quantity(ell, 'in', 'length')} is too {'short' if short else 'long'}: "
            f"with these pivots the pin-to-pin length can only be "
            f"{format_quantity(lo, 'in', 'length')} to {format_quantity(hi, 'in', 'length')} "
            f"(the arm at dead centre); the geometry cannot close",
        )
    return min(max(ell, lo), hi)


def forward(A: float, B: float, X: float, Y: float, L: float, dL: float) -> dict:
    """θ1, θ2 of both assemblies from (88), (89)."""
    r, d = math.hypot(X, Y), math.hypot(A, B)
    if r == 0:
        raise InputError(
            "arm_x", "the rod end is at the arm pivot (X = Y = 0): the cylinder cannot turn the arm"
        )
    if d == 0:
        raise InputError(
            "pivot_x",
            "the cylinder pivot is on the arm pivot (A = B = 0): "
            "the cylinder length never changes as the arm turns",
        )
    phi, psi = math.atan2(Y, X), math.atan2(B, -A)
    lo, hi = abs(d - r), d + r
    ell1 = check_length(L, lo, hi, "retracted_length", "retracted length")
    ell2 = check_length(L + dL, lo, hi, "stroke", "extended length L + ΔL =")
    g1, g2 = pivot_angle(r, d, ell1), pivot_angle(r, d, ell2)
    theta1 = wrap(psi - phi + g1)  # (88), primary assembly
    theta1_alt = wrap(psi - phi - g1)  # (88), other assembly
    return {
        "r": r,
        "d": d,
        "lo": lo,
        "hi": hi,
        "g1": g1,
        "g2": g2,
        "theta1": theta1,
        "theta2": theta1 + (g2 - g1),  # (89), continuous with θ1
        "theta1_alt": theta1_alt,
        "theta2_alt": theta1_alt - (g2 - g1),
    }


def reverse(theta1: float, theta2: float, X: float, Y: float, L: float, dL: float) -> dict:
    """Cylinder pivots (A, B) meeting (88) and (89): both circle-circle intersections, each checked."""
    r = math.hypot(X, Y)
    if r == 0:
        raise InputError(
            "arm_x", "the rod end is at the arm pivot (X = Y = 0): the cylinder cannot turn the arm"
        )
    dtheta = theta2 - theta1
    if dtheta == 0:
        raise InputError(
            "extended_angle", "equals the retracted angle: the arm must turn as the cylinder extends"
        )
    if abs(dtheta) >= math.pi:
        raise InputError(
            "extended_angle",
            f"the arm would swing {math.degrees(abs(dtheta)):.4g}°: a cylinder can "
            f"swing an arm less than 180° (it would pass dead centre)",
        )
    turn = math.copysign(1.0, dtheta)
    phi = math.atan2(Y, X)
    c = 2 * r * abs(math.sin(dtheta / 2))  # chord travelled by the rod end
    L2 = L + dL
    if c < dL * (1 - TOUCH):
        raise InputError(
            "stroke",
            f"{format_quantity(dL, 'in', 'length')} is longer than the rod end travels "
            f"between the two angles ({format_quantity(c, 'in', 'length')} in a straight line); "
            f"the geometry cannot close",
        )
    if c > (L + L2) * (1 + TOUCH):
        raise InputError(
            "retracted_length",
            f"too short: the two rod-end positions are "
            f"{format_quantity(c, 'in', 'length')} apart, more than L + (L + ΔL); "
            f"the geometry cannot close",
        )
    c = min(max(c, dL), L + L2)  # touching within rounding
    mu = phi + (theta1 + theta2) / 2 + math.pi / 2
    ex, ey = turn * math.cos(mu), turn * math.sin(mu)  # unit vector from P(θ1) to P(θ2)
    px, py = rod_end(X, Y, theta1)
    along = (c * c - dL * (L + L2)) / (2 * c)  # distance along the chord: L² − (L+ΔL)² = −ΔL(2L+ΔL)
    across = math.sqrt(max(heron16(L, L2, c), 0.0)) / (2 * c)  # 2·area / c
    found, rejected = [], []
    for side in (1.0, -1.0) if across > 0 else (1.0,):  # left, then right of the chord (one if touching)
        cx = px + along * ex - side * across * ey
        cy = py + along * ey + side * across * ex
        psi = math.atan2(cy, cx)
        # the arm stays on one side of the line through both pivots iff it never passes dead centre
        ok = all(turn * math.sin(t + phi - psi) >= -SIDE_SLACK for t in (theta1, theta2))
        (found if ok else rejected).append((-cx, cy))
    # Both valid: the one on the arm pivot's side of the chord first (the compact linkage).
    if len(found) == 2 and turn < 0:
        found.reverse()
    return {"r": r, "found": found, "rejected": rejected, "chord": c}


def where_text(pivot: tuple[float, float]) -> str:
    A, B = pivot
    return f"A = {format_quantity(A, 'in', 'length')}, B = {format_quantity(B, 'in', 'length')}"


def stroke_curve(r: float, d: float, theta1: float, turn: float, L: float, dL: float, F: float):
    """Arm angle and torque over the stroke, ℓ from L to L + ΔL (for the plot)."""
    g1 = pivot_angle(r, d, L)
    thetas, torques = [], []
    for i in range(CURVE_POINTS):
        ell = L + dL * i / (CURVE_POINTS - 1)
        thetas.append(theta1 + turn * (pivot_angle(r, d, ell) - g1))
        torques.append(turn * F * lever_arm(r, d, ell))
    return thetas, torques


def compute(v) -> Result:
    X, Y, L, dL, F = v["arm_x"], v["arm_y"], v["retracted_length"], v["stroke"], v["cylinder_force"]
    warnings: list[str] = []
    values: dict = {}
    if v["mode"] == "forward":
        A, B = v["pivot_x"], v["pivot_y"]
        f = forward(A, B, X, Y, L, dL)
        r, d, theta1, theta2, turn = f["r"], f["d"], f["theta1"], f["theta2"], 1.0
        values.update(
            retracted_angle=theta1,
            extended_angle=theta2,
            retracted_angle_alt=f["theta1_alt"],
            extended_angle_alt=f["theta2_alt"],
        )
    else:
        theta1, theta2 = v["retracted_angle"], v["extended_angle"]
        rv = reverse(theta1, theta2, X, Y, L, dL)
        if not rv["found"]:
            raise InputError(
                "stroke",
                "no cylinder pivot works: both positions giving L at θ1 and L + ΔL at θ2 "
                f"({'; '.join(map(where_text, rv['rejected']))}) put the arm through dead centre "
                f"in between. Use a stroke nearer the rod end's straight-line travel "
                f"({format_quantity(rv['chord'], 'in', 'length')}) or change L",
            )
        (A, B), *alt = rv["found"]
        r, d, turn = rv["r"], math.hypot(A, B), math.copysign(1.0, theta2 - theta1)
        values.update(pivot_x=A, pivot_y=B)
        if alt:
            values.update(pivot_x_alt=alt[0][0], pivot_y_alt=alt[0][1])
            warnings.append("Two pivot positions work; the second is listed as Second pivot A, B.")
        for p in rv["rejected"]:
            warnings.append(
                f"The other intersection, {where_text(p)}, is not a working linkage: the arm would "
                f"pass dead centre between θ1 and θ2."
            )
        f = {"lo": abs(d - r), "hi": d + r}
    values["sweep"] = theta2 - theta1
    values["retracted_cylinder_angle"] = cylinder_angle(A, B, X, Y, theta1)
    values["extended_cylinder_angle"] = cylinder_angle(A, B, X, Y, theta2)
    h1, h2 = lever_arm(r, d, L), lever_arm(r, d, L + dL)
    for name, h in (("retracted", h1), ("extended", h2)):
        if h < NEAR_DEAD_CENTRE * r:
            where = (
                "at dead centre (the cylinder's line passes through the arm pivot)"
                if h < 1e-9 * r
                else f"near dead centre: the lever arm is {format_quantity(h, 'in', 'length')}, "
                f"{h / r:.2%} of the arm length {format_quantity(r, 'in', 'length')}"
            )
            warnings.append(
                f"When {name} the arm is {where}; the cylinder gives little torque "
                f"there and the arm may lock (warned below 10 % of the arm length)."
            )
    values.update(
        retracted_lever_arm=h1,
        extended_lever_arm=h2,
        retracted_torque=turn * F * h1,
        extended_torque=turn * F * h2,
        min_length=f["lo"],
        max_length=f["hi"],
    )
    thetas, torques = stroke_curve(r, d, theta1, turn, L, dL, F)
    return Result(values, warnings, {"torque": (thetas, torques)})


CALCULATOR = Calculator(
    id="pneumatic_linkage",
    title="Pneumatic linkage",
    summary="A cylinder swinging an arm: arm angles from the pivot position, or the pivot from the angles.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="11",
    plots=(
        Plot(
            "Arm torque over the stroke", ("torque",), "arm angle", "angle", "deg", "torque", "torque", "N*m"
        ),
    ),
)
