"""Seed section 5: the beam bend calculator (eqs. 43-60).

A straight beam of one cross section and material: bending deflection under a point force
(between simple supports, between fixed supports, or as a cantilever), the largest bending
stress and its safety factor against yield, Euler column buckling (59) with the seed's K table,
and twist under a torque (60). Section properties and load cases live in core/beams.py, whose
docstring lists where the seed is corrected: (44) hex J, (47)/(48) thin-wall round tube,
(50) rounded square J, (51) wrong rectangular-tube I, (52) typo in Bredt's denominator (the tube's J
itself is bracketed by two finite-element bounds and shown with its accuracy), and
(53)-(57) being the fixed-fixed case with a the distance to the FARTHER support.

Other choices:
- Dimension fields are generic (outer_size, height, width, wall) because `section` is not the
  mode field; each section checks the ones it uses and names the field when one cannot close.
- The hex's extreme fibre is taken at a corner (s/√3), the conservative orientation.
- Buckling uses the weakest axis of the section, slenderness KL/r with r = √(I_min/A). The load
  shown is the governing one: Euler's P = π²EI/(KL)² (59) above the transition slenderness
  (KL/r)_T = √(2π²E/S_y), Johnson's parabola P = A·(S_y − (S_y·KL/(2πr))²/E) below it (Shigley,
  'intermediate-length columns'); the two meet at (KL/r)_T, where both give σ = S_y/2, so the load is continuous.
  With the yield unknown (e.g. steel) only Euler's load can be given; a warning gives the yield
  it needs once σ_Euler passes half a mild steel's 250 MPa.
- The torque twists the whole length (one end held, the torque at the other): θ = TL/(GJ) (60).
- Polycarbonate's shear modulus is not in REFERENCE_DATA: G = E/(2(1+ν)) with ν = 0.37
  (typical datasheet value, e.g. the Wikipedia polycarbonate infobox).

Equations beyond the seed (cited by the outputs; beams.py has the derivations):
    A = √3/2·s² (hex), π/4·d² (round), π/4·(D² − d²) (round tube), a² (square),
        2h·(x + y) − 4h² (rectangular tube)                                                   (B1)
    J_lower ≤ J ≤ J_upper (stress-function and warping-function finite elements),
        J = (J_lower + J_upper)/2, accuracy ±(J_upper − J_lower)/(J_upper + J_lower)          (B2)
    e_thin = J_thin/J − 1, J_thin from (48) or (52)                                            (B3)
    simple supports (Shigley A-9-6), b the shorter segment, x from the far support:
        y_max = F·b·(l² − b²)^{3/2}/(9√3·E·I·l) at x = √((l² − b²)/3)                          (B4)
    M_max = F·a·b/l (simple), F·a·b·max(a, b)/l² (fixed, at the nearer support), F·a (cantilever) (B5)
    σ = M_max·c/I, c the distance to the extreme fibre                                        (B6)
    SF = S_y/σ                                                                                 (B7)
    KL/r with r = √(I_min/A);  (KL/r)_T = √(2π²E/S_y)                                          (B8)
    P_Johnson = A·(S_y − (S_y·(KL/r)/(2π))²/E)  for KL/r < (KL/r)_T                            (B9)
    m = ρ·A·l                                                                                  (B10)
"""

from __future__ import annotations

import math

from .. import beams
from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field
from ..units import format_number

MILD_STEEL_YIELD = 250e6  # Pa, ASTM A36 (the low end of common steels), for the short-column warning

# name: (label, E Pa, G Pa, yield Pa or None, density kg/m³ or None); REFERENCE_DATA.md
MATERIALS = {
    "6061_t6": ("6061-T6 aluminium", 68.9e9, 26.0e9, 276e6, 2700.0),
    "steel": ("Steel", 200e9, 79.3e9, None, 7850.0),  # density: typical carbon steel, 7.85 g/cm³
    "polycarbonate": ("Polycarbonate", 2.34e9, 2.34e9 / (2 * 1.37), 62e6, 1200.0),
    "custom": ("Custom", None, None, None, None),
}

# (theoretical K, recommended design K) for column buckling, seed table under (59)
END_CONDITIONS = {
    "fixed_fixed": ("Both ends fixed", 0.5, 0.65),
    "fixed_pinned": ("Fixed, other end pinned", 0.7, 0.80),
    "fixed_guided": ("Fixed, other end guided (cannot turn, slides sideways)", 1.0, 1.2),
    "pinned_pinned": ("Both ends pinned", 1.0, 1.0),
    "fixed_free": ("Fixed, other end free", 2.0, 2.10),
    "pinned_guided": ("Pinned, other end guided (cannot turn, slides sideways)", 2.0, 2.0),
}

FIELDS = (
    Field(
        "section",
        "Cross section",
        choices=beams.SECTIONS,
        choice_labels=beams.SECTION_LABELS,
        default="rectangular_tube",
        help="Shape of the beam's cross section (seed 5.1).",
    ),
    Field(
        "outer_size",
        "Outer size (flats/diameter)",
        "length",
        "in",
        default=0.5,
        min=0,
        min_exclusive=True,
        help="Hex: across flats. Round and round tube: outside diameter. Square: side. "
        "Not used by the rectangular tube.",
        when=(("section", ("hex", "round", "round_tube", "square")),),
    ),
    Field(
        "height",
        "Tube height (along the force)",
        "length",
        "in",
        default=2,
        min=0,
        min_exclusive=True,
        help="Rectangular tube only: outside size in the direction of the force (x).",
        when=(("section", ("rectangular_tube",)),),
    ),
    Field(
        "width",
        "Tube width (across the force)",
        "length",
        "in",
        default=1,
        min=0,
        min_exclusive=True,
        help="Rectangular tube only: outside size across the force (y).",
        when=(("section", ("rectangular_tube",)),),
    ),
    Field(
        "wall",
        "Wall thickness",
        "length",
        "in",
        default=0.0625,
        min=0,
        min_exclusive=True,
        help="Tubes only: wall thickness h, less than half the smallest outside size.",
        when=(("section", ("round_tube", "rectangular_tube")),),
    ),
    Field(
        "material",
        "Material",
        choices=tuple(MATERIALS),
        choice_labels=tuple(m[0] for m in MATERIALS.values()),
        default="6061_t6",
        help="6061-T6, steel or polycarbonate (REFERENCE_DATA), or your own figures.",
    ),
    Field(
        "youngs_modulus",
        "Custom Young's modulus E",
        "modulus",
        "GPa",
        default=68.9,
        min=0,
        min_exclusive=True,
        help="Used only when the material is Custom.",
        when=(("material", ("custom",)),),
    ),
    Field(
        "shear_modulus",
        "Custom shear modulus G",
        "modulus",
        "GPa",
        default=26,
        min=0,
        min_exclusive=True,
        help="Used only when the material is Custom.",
        when=(("material", ("custom",)),),
    ),
    Field(
        "yield_strength",
        "Custom yield strength",
        "pressure",
        "MPa",
        default=276,
        min=0,
        help="Used only when the material is Custom; 0 if unknown (no safety factor).",
        when=(("material", ("custom",)),),
    ),
    Field(
        "density",
        "Custom density",
        "density",
        "g/cm**3",
        default=2.7,
        min=0,
        help="Used only when the material is Custom; 0 if unknown (no mass).",
        when=(("material", ("custom",)),),
    ),
    Field(
        "support",
        "Load case",
        choices=beams.SUPPORTS,
        choice_labels=beams.SUPPORT_LABELS,
        default="simple",
        help="Force between two simple supports, two fixed supports, or on a cantilever (seed 5.2).",
    ),
    Field(
        "length",
        "Length",
        "length",
        "in",
        default=24,
        min=0,
        min_exclusive=True,
        help="Distance between supports l, or the cantilever's length; also the column and twisted length.",
    ),
    Field(
        "load_position",
        "Load position",
        "length",
        "in",
        default=12,
        min=0,
        help="Distance a of the force from the left support (cantilever: from the fixed end).",
    ),
    Field("force", "Force", "force", "lbf", default=100, min=0, help="Point force F across the beam."),
    Field(
        "torque",
        "Torque",
        "torque",
        "in*lbf",
        default=100,
        min=0,
        help="Torque T twisting the beam over its length (60).",
    ),
    Field(
        "end_condition",
        "Column end condition",
        choices=tuple(END_CONDITIONS),
        choice_labels=tuple(e[0] for e in END_CONDITIONS.values()),
        default="pinned_pinned",
        help="End fixity for column buckling: sets K in (59).",
    ),
    Field(
        "k_values",
        "K values",
        choices=("recommended", "theoretical"),
        choice_labels=("Recommended design", "Theoretical"),
        default="recommended",
        help="The seed's recommended design K (allows for imperfect fixity) or the theoretical K.",
    ),
)

OUTPUTS = (
    Output(
        "area_moment",
        "Area moment of inertia I",
        "area_moment",
        "in**4",
        help="Second moment of area about the bending axis, exact for the section ((47), (51) corrected).",
        equation="(43), (45), (47), (49), (51)",
    ),
    Output(
        "torsion_constant",
        "Torsion constant J",
        "area_moment",
        "in**4",
        help="Exact for round and round tube, series for square, finite elements for hex and rectangular tube.",
        equation="(44), (46), (48), (50), (52), (B2)",
    ),
    Output(
        "torsion_constant_error",
        "J accuracy (±)",
        "dimensionless",
        "%",
        help="Rectangular tube: half the gap between proven lower and upper finite-element bounds on J (B2).",
        equation="(B2)",
    ),
    Output(
        "thin_wall_torsion_constant",
        "Thin-wall J (estimate)",
        "area_moment",
        "in**4",
        help="Tubes: the seed's thin-wall J, π/4·d³h (48) or Bredt's (52, corrected), for comparison.",
        equation="(48), (52)",
    ),
    Output(
        "thin_wall_error",
        "Thin-wall J error",
        "dimensionless",
        "%",
        help="Thin-wall J ÷ J − 1: how far the seed's thin-wall formula is off for this wall (B3).",
        equation="(B3)",
    ),
    Output(
        "max_deflection",
        "Max deflection",
        "length",
        "in",
        help="Largest deflection under the force: (57) fixed ends, (58) cantilever, (B4) simple supports.",
        equation="(57), (58), (B4)",
    ),
    Output(
        "max_deflection_position",
        "Max deflection at",
        "length",
        "in",
        help="Where it bends most, from the left support (cantilever: fixed end): (56), (B4); tip (58).",
        equation="(56), (58), (B4)",
    ),
    Output(
        "max_bending_moment",
        "Max bending moment",
        "torque",
        "in*lbf",
        help="F·a·b/l between simple supports, F·a·b·max(a, b)/l² fixed, F·a at a cantilever's root (B5).",
        equation="(B5)",
    ),
    Output(
        "max_bending_stress",
        "Max bending stress",
        "pressure",
        "MPa",
        help="Largest moment × distance to the extreme fibre ÷ I, σ = M·c/I (B6).",
        equation="(B6)",
    ),
    Output(
        "safety_factor",
        "Safety factor (bending yield)",
        help="Yield strength ÷ largest bending stress (B7).",
        equation="(B7)",
    ),
    Output(
        "buckling_load",
        "Buckling load",
        "force",
        "lbf",
        help="Critical column load, weakest axis: Euler's (59) if slender, Johnson's parabola (B9) if short.",
        equation="(59), (B9)",
    ),
    Output(
        "buckling_formula",
        "Buckling governed by",
        help="Euler above the transition slenderness √(2π²E/Sy), Johnson below it (B8).",
        equation="(B8)",
    ),
    Output(
        "euler_load",
        "Euler load",
        "force",
        "lbf",
        help="Euler's critical load π²EI/(KL)², weakest axis; an overestimate for short columns (59).",
        equation="(59)",
    ),
    Output(
        "slenderness_ratio",
        "Slenderness KL/r",
        help="K·L over the radius of gyration √(I/A) of the weakest axis (B8).",
        equation="(B8)",
    ),
    Output(
        "transition_slenderness",
        "Transition slenderness",
        help="√(2π²E/Sy), where Euler's stress is half the yield: Euler above, Johnson below (B8).",
        equation="(B8)",
    ),
    Output(
        "twist_angle",
        "Twist angle",
        "angle",
        "deg",
        help="Twist of the whole length under the torque, θ = T·L/(G·J) (60).",
        equation="(60)",
    ),
    Output(
        "cross_section_area",
        "Cross-section area",
        "area",
        "in**2",
        help="Area of the section, exact (B1).",
        equation="(B1)",
    ),
    Output("mass", "Beam mass", "mass", "lb", help="Density × area × length (B10).", equation="(B10)"),
)

PLOTS = (
    Plot(
        "Deflection along the beam", ("deflection",), "position", "length", "in", "deflection", "length", "in"
    ),
)


def section_from(v) -> beams.Section:
    """The chosen section, each dimension checked where the section needs it."""
    name = v["section"]
    if name == "hex":
        return beams.hex_section(v["outer_size"])
    if name == "round":
        return beams.round_section(v["outer_size"])
    if name == "square":
        return beams.square_section(v["outer_size"])
    h = v["wall"]
    if name == "round_tube":
        D = v["outer_size"]
        if h >= D / 2:
            raise InputError(
                "wall",
                f"must be less than half the outer diameter ({D / 2 * 1e3:.4g} mm): "
                "the tube would have no bore (use Round for a solid bar)",
            )
        return beams.round_tube_section(D, h)
    x, y = v["height"], v["width"]
    if h >= min(x, y) / 2:
        raise InputError(
            "wall",
            f"must be less than half the smaller outside size "
            f"({min(x, y) / 2 * 1e3:.4g} mm): the tube would have no hole",
        )
    if max(x, y) > beams.MAX_TUBE_ASPECT * min(x, y):
        # the torsion solve's elimination meets exact zero pivots past ~1e7:1 (a 16e9:16 tube)
        longer, shorter = ("height", "width") if x > y else ("width", "height")
        raise InputError(
            longer,
            f"must be at most {beams.MAX_TUBE_ASPECT:.0e} times the {shorter} for a rectangular tube "
            "(the torsion constant is not solved past that)",
        )
    return beams.rectangular_tube_section(x, y, h)


def material_from(v):
    label, E, G, Sy, rho = MATERIALS[v["material"]]
    if v["material"] == "custom":
        E, G = v["youngs_modulus"], v["shear_modulus"]
        Sy = v["yield_strength"] or None
        rho = v["density"] or None
    return E, G, Sy, rho


def compute(v) -> Result:
    sec = section_from(v)
    E, G, Sy, rho = material_from(v)
    support, l, a, F, T = v["support"], v["length"], v["load_position"], v["force"], v["torque"]
    if a > l:
        raise InputError("load_position", f"must be within the length ({l * 1e3:.4g} mm)")
    warnings: list[str] = []

    EI = E * sec.area_moment
    y_max, x_max = beams.max_deflection(support, F, a, l, EI)  # (53)-(58)
    M = beams.max_moment(support, F, a, l)
    sigma = M * sec.extreme_fiber / sec.area_moment
    label, K_theory, K_design = END_CONDITIONS[v["end_condition"]]
    K = K_design if v["k_values"] == "recommended" else K_theory
    P_euler = math.pi**2 * E * sec.min_area_moment / (K * l) ** 2  # (59)
    slenderness = K * l / math.sqrt(sec.min_area_moment / sec.area)  # KL/r
    if Sy is None:
        P_cr, formula, transition = P_euler, "Euler (yield unknown)", None
    else:
        transition = math.sqrt(2 * math.pi**2 * E / Sy)  # where σ_Euler = π²E/(KL/r)² = Sy/2
        if slenderness >= transition:
            P_cr, formula = P_euler, "Euler"
        else:
            P_cr = sec.area * (Sy - (Sy * slenderness / (2 * math.pi)) ** 2 / E)  # Johnson's parabola
            formula = "Johnson"
    theta = T * l / (G * sec.torsion_constant)  # (60)

    values = {
        "area_moment": sec.area_moment,
        "torsion_constant": sec.torsion_constant,
        "max_deflection": y_max,
        "max_deflection_position": x_max,
        "max_bending_moment": M,
        "max_bending_stress": sigma,
        "buckling_load": P_cr,
        "buckling_formula": formula,
        "euler_load": P_euler,
        "slenderness_ratio": slenderness,
        "twist_angle": theta,
        "cross_section_area": sec.area,
    }
    if sec.thin_wall_torsion_constant is not None:
        error = sec.thin_wall_torsion_constant / sec.torsion_constant - 1
        values["thin_wall_torsion_constant"] = sec.thin_wall_torsion_constant
        values["thin_wall_error"] = error
    if sec.torsion_constant_error is not None:
        values["torsion_constant_error"] = sec.torsion_constant_error
        if abs(error) > 0.05:
            warnings.append(
                f"The seed's thin-wall torsion constant is {abs(error):.0%} "
                f"{'low' if error < 0 else 'high'} for this wall; the finite-element J is used."
            )
    if transition is not None:
        values["transition_slenderness"] = transition
    if rho is not None:
        values["mass"] = rho * sec.area * l
    if Sy is not None and sigma > 0:
        values["safety_factor"] = Sy / sigma
        if sigma > Sy:
            warnings.append("The bending stress exceeds the yield strength: the beam bends permanently.")
    elif Sy is None and v["material"] == "steel":
        warnings.append("Steel's yield strength depends on the grade: choose Custom to get a safety factor.")
    if Sy is None and P_cr / sec.area > MILD_STEEL_YIELD / 2:
        # Johnson's parabola takes over below σ_Euler = Sy/2: without Sy, say which yield Euler needs
        needed = 2 * P_cr / sec.area
        warnings.append(
            f"Short column: Euler's load holds only if the yield strength is at least "
            f"{format_number(needed / 1e6)} MPa (twice the Euler stress); below that Johnson's "
            "parabola gives less. Choose Custom with the yield strength to check."
        )
    if y_max > 0.1 * l:
        warnings.append(
            f"The deflection is {y_max / l:.0%} of the length: beyond small-deflection "
            "beam theory, treat the numbers as rough."
        )
    xs, ys = beams.deflection_curve(support, F, a, l, EI)
    return Result(values, warnings, {"deflection": (xs, ys)})


CALCULATOR = Calculator(
    id="beam",
    title="Beam",
    summary="Deflection, stress, buckling and twist of a beam.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="5",
    plots=PLOTS,
)
