"""Beam calculator (seed section 5): sections, load cases, buckling, twist, errors, presets.

References are independent of the code: polygon (shoelace) second moments, mpmath, and the beam
equation EI·y'''' = F·δ(x − a) solved again with sympy for each support.
"""

import math
from functools import cache

import mpmath as mp
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from gearhead.core import beams, presets
from gearhead.core.calculators import beam as calc
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve

IN = 0.0254
LBF = 4.4482216152605


def polygon_ix(points):
    """Second moment about the x axis through the origin of a simple polygon (shoelace form)."""
    total = 0.0
    for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]):
        total += (x0 * y1 - x1 * y0) * (y0 * y0 + y0 * y1 + y1 * y1)
    return abs(total) / 12


def rectangle(w, h):
    return [(-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)]


# --- sections ---------------------------------------------------------------------------------


@pytest.mark.parametrize("corner_angle", [0, 30])
def test_hex_area_moment_is_5_root3_over_144_either_way_up(corner_angle):
    """Regular hexagon across flats s = 1: circumradius 1/√3; I is the same about every axis."""
    R = 1 / math.sqrt(3)
    pts = [
        (R * math.cos(math.radians(corner_angle + 60 * k)), R * math.sin(math.radians(corner_angle + 60 * k)))
        for k in range(6)
    ]
    assert polygon_ix(pts) == pytest.approx(5 * math.sqrt(3) / 144, rel=1e-14)
    sec = beams.hex_section(1.0)
    assert sec.area_moment == pytest.approx(polygon_ix(pts), rel=1e-14)
    assert sec.area == pytest.approx(3 * math.sqrt(3) / 2 * R * R, rel=1e-14)  # 6 equilateral triangles
    assert sec.area_moment == pytest.approx(0.0601, abs=5e-5)  # the seed's (43), rounded


def test_round_and_round_tube_against_mpmath():
    D, t = mp.mpf("0.0254"), mp.mpf("0.0015875")  # 1 in tube, 1/16 in wall
    d = D - 2 * t
    I_ref = mp.pi / 64 * (D**4 - d**4)
    sec = beams.round_tube_section(float(D), float(t))
    assert sec.area_moment == pytest.approx(float(I_ref), rel=1e-14)
    assert sec.torsion_constant == pytest.approx(float(2 * I_ref), rel=1e-14)
    assert sec.area == pytest.approx(float(mp.pi / 4 * (D**2 - d**2)), rel=1e-14)
    solid = beams.round_section(0.0127)
    assert solid.area_moment == pytest.approx(math.pi * 0.0127**4 / 64, rel=1e-15)
    assert solid.torsion_constant == pytest.approx(math.pi * 0.0127**4 / 32, rel=1e-15)


def test_round_tube_thin_wall_error_is_minus_t2_over_dm2_plus_t2():
    """Exact J = π/4·d_m·t·(d_m² + t²) (expand D⁴ − d⁴ with D, d = d_m ± t); thin wall drops t²."""
    for D, t in [(1.0, 0.05), (1.0, 0.25), (1.0, 0.45)]:
        sec = beams.round_tube_section(D, t)
        dm = D - t
        assert sec.thin_wall_torsion_constant / sec.torsion_constant - 1 == pytest.approx(
            -t * t / (dm * dm + t * t), rel=1e-12
        )


def test_square_torsion_constant_is_saint_venant_series():
    """J/a⁴ = 1/3·(1 − 192/π⁵·Σ_{n odd} tanh(nπ/2)/n⁵) = 0.140577 (the seed's 9/64 is 0.140625)."""
    s = mp.nsum(lambda k: mp.tanh((2 * k + 1) * mp.pi / 2) / (2 * k + 1) ** 5, [0, mp.inf])
    ref = (1 - 192 / mp.pi**5 * s) / 3
    assert beams.square_section(1.0).torsion_constant == pytest.approx(float(ref), rel=1e-14)
    assert float(ref) == pytest.approx(0.1406, abs=5e-5)
    assert beams.square_section(2.0).area_moment == pytest.approx(16 / 12, rel=1e-15)


def test_rectangle_series_for_a_long_strip_tends_to_bh3_over_3():
    """b/h = 10: J = bh³/3·(1 − 0.630·h/b) to 1e-6 (the tanh terms are e^{-31}-close to 1)."""
    ref = 10 / 3 * (1 - 192 / (math.pi**5 * 10) * 31 / 32 * 1.0369277551433699)
    assert beams.rectangle_torsion(10.0, 1.0) == pytest.approx(ref, rel=1e-12)


def test_rectangular_tube_area_moment_outer_minus_inner_polygon():
    x, y, h = 2 * IN, 1 * IN, 0.0625 * IN  # 1x2 tube, force along the 2 in side
    sec = beams.rectangular_tube_section(x, y, h)
    ref = polygon_ix(rectangle(y, x)) - polygon_ix(rectangle(y - 2 * h, x - 2 * h))
    assert sec.area_moment == pytest.approx(ref, rel=1e-12)
    ref_weak = polygon_ix(rectangle(x, y)) - polygon_ix(rectangle(x - 2 * h, y - 2 * h))
    assert sec.min_area_moment == pytest.approx(ref_weak, rel=1e-12)
    assert sec.extreme_fiber == x / 2


def test_seed_rectangular_tube_area_moment_is_half_the_thin_wall_value():
    """Thin square tube: two webs 2·(t·a³/12) + two flanges 2·(a·t)(a/2)² = 2/3·a³t; (51) gives 1/3."""
    a, t = 1.0, 1e-5
    exact = beams.rectangular_tube_section(a, a, t).area_moment
    assert exact == pytest.approx(2 / 3 * a**3 * t, rel=1e-4)
    seed_51 = a * a * a * t / 3
    assert seed_51 / exact == pytest.approx(0.5, rel=1e-4)


def test_bredt_denominator_typo_in_seed_52():
    """Bredt: J = 4A_m²t/p_m, A_m = (x−h)(y−h), p_m = 2(x + y − 2h) → 2h(x−h)²(y−h)²/(x+y−2h)."""
    x, y, h = 2.0, 1.0, 0.1
    bredt = 4 * ((x - h) * (y - h)) ** 2 * h / (2 * (x + y - 2 * h))
    assert beams.rectangular_tube_section(x, y, h).thin_wall_torsion_constant == pytest.approx(
        bredt, rel=1e-14
    )
    seed_52 = 2 * h**2 * (x - h) ** 2 * (y - h) ** 2 / (h * (x + y - h))
    assert seed_52 != pytest.approx(bredt, rel=1e-2)


def test_rectangular_tube_torsion_close_to_bredt_for_thin_walls_and_error_shown():
    """Bredt's error shrinks with the wall (≈ −0.44·t/a for a square tube, from a fine-grid run)."""
    errors = []
    for t in (0.1, 0.01, 0.001):
        sec = beams.rectangular_tube_section(1.0, 1.0, t)
        errors.append(sec.thin_wall_torsion_constant / sec.torsion_constant - 1)
    assert all(e < 0 for e in errors)
    assert abs(errors[1]) < abs(errors[0]) / 5 and abs(errors[2]) < abs(errors[1]) / 5
    assert abs(errors[2]) < 1e-3
    sol = solve("beam", {"section": "rectangular_tube", "height": "1 in", "width": "1 in", "wall": "0.25 in"})
    assert sol.outputs["thin_wall_error"].value < -0.15  # thick wall: Bredt ~18 % low
    assert any("thin-wall" in w for w in sol.warnings)


# --- load cases: the beam equation solved again with sympy --------------------------------------


@cache
def sympy_beam(support, a, l):
    """Piecewise cubic y(x) (EI = F = 1, y along F) from EI·y'''' = F·δ(x − a) and the end conditions.

    Returns (max |y|, x of the max) from the stationary points of each segment and the ends.
    """
    x = sp.symbols("x")
    c = sp.symbols("c0:8")
    y1 = c[0] + c[1] * x + c[2] * x**2 + c[3] * x**3
    y2 = c[4] + c[5] * x + c[6] * x**2 + c[7] * x**3
    d = lambda f, n=1: sp.diff(f, x, n)  # noqa: E731
    eqs = [
        (y1 - y2).subs(x, a),
        d(y1 - y2).subs(x, a),
        d(y1 - y2, 2).subs(x, a),
        (d(y2, 3) - d(y1, 3)).subs(x, a) - 1,
    ]  # shear jumps by F at the load
    if support == "simple":
        eqs += [y1.subs(x, 0), d(y1, 2).subs(x, 0), y2.subs(x, l), d(y2, 2).subs(x, l)]
    elif support == "fixed":
        eqs += [y1.subs(x, 0), d(y1).subs(x, 0), y2.subs(x, l), d(y2).subs(x, l)]
    else:
        eqs += [y1.subs(x, 0), d(y1).subs(x, 0), d(y2, 2).subs(x, l), d(y2, 3).subs(x, l)]
    sol = sp.solve(eqs, c, dict=True)[0]
    y1, y2 = y1.subs(sol), y2.subs(sol)
    candidates = [(0, y1), (a, y1), (l, y2)]
    for seg, lo, hi in ((y1, 0, a), (y2, a, l)):
        for r in sp.solve(sp.diff(seg, x), x):
            if r.is_real and lo <= r <= hi:
                candidates.append((r, seg))
    best = max(candidates, key=lambda p: abs(p[1].subs(x, p[0])))
    return float(abs(best[1].subs(x, best[0]))), float(best[0])


@pytest.mark.parametrize("support", beams.SUPPORTS)
@pytest.mark.parametrize(
    "a", [sp.Rational(1, 10), sp.Rational(1, 3), sp.Rational(1, 2), sp.Rational(7, 10), sp.Rational(19, 20)]
)
def test_max_deflection_matches_the_beam_equation(support, a):
    l = 1
    y_ref, x_ref = sympy_beam(support, a, l)
    y, xm = beams.max_deflection(support, 1.0, float(a), 1.0, 1.0)
    assert y == pytest.approx(y_ref, rel=1e-12)
    assert xm == pytest.approx(x_ref, rel=1e-9)


@pytest.mark.parametrize("support", beams.SUPPORTS)
def test_deflection_curve_matches_max_and_ends(support):
    a, l = 0.3, 1.0
    xs, ys = beams.deflection_curve(support, 1.0, a, l, 1.0, points=2001)
    y, _ = beams.max_deflection(support, 1.0, a, l, 1.0)
    assert max(ys) <= y * (1 + 1e-12)
    assert max(ys) == pytest.approx(y, rel=1e-5)
    assert ys[0] == 0.0 and (support == "cantilever" or abs(ys[-1]) < 1e-15)


def test_seed_56_57_need_a_as_the_longer_segment():
    """(56) x = 2al/(2a + l) lies inside 0 ≤ x ≤ a (where (53) holds) only when a ≥ l/2."""
    l, a_closer = 1.0, 0.25
    x56 = 2 * a_closer * l / (2 * a_closer + l)
    assert x56 > a_closer  # outside the segment: the seed's "distance to closer support" is wrong
    y57_closer = 2 * a_closer**3 * (l - a_closer) ** 2 / (3 * (2 * a_closer + l) ** 2)
    y_ref, _ = sympy_beam("fixed", sp.Rational(1, 4), 1)
    assert y57_closer != pytest.approx(y_ref, rel=1e-2)
    a_farther = 0.75
    y57_farther = 2 * a_farther**3 * (l - a_farther) ** 2 / (3 * (2 * a_farther + l) ** 2)
    assert y57_farther == pytest.approx(y_ref, rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(st.sampled_from(("simple", "fixed")), st.floats(0.0, 1.0), st.floats(1e-3, 1e3))
def test_mirrored_load_gives_the_same_max_deflection(support, fraction, l):
    a = fraction * l
    assume(l - (l - a) == a)  # an exact mirror in floating point
    y1, x1 = beams.max_deflection(support, 50.0, a, l, 3.0)
    y2, x2 = beams.max_deflection(support, 50.0, l - a, l, 3.0)
    assert y1 == pytest.approx(y2, rel=1e-9, abs=1e-300)
    assert x1 == pytest.approx(l - x2, rel=1e-9, abs=1e-12 * l)


def test_handworked_simply_supported_round_bar():
    """0.5 in 6061 rod, 24 in span, 100 lbf in the middle: y = Fl³/(48EI).

    0.0127⁴ = 2.60145e-8, I = π/64·2.60145e-8 = 1.27698e-9 m⁴; F = 444.822 N; l³ = 0.6096³ = 0.226535 m³;
    y = 444.822·0.226535/(48·68.9e9·1.27698e-9) = 100.768/4223.23 = 0.023860 m (0.939 in).
    M = Fl/4 = 444.822·0.6096/4 = 67.791 N·m; σ = Mc/I = 67.791·0.00635/1.27698e-9 = 337.10 MPa.
    """
    sol = solve(
        "beam",
        {
            "section": "round",
            "outer_size": "0.5 in",
            "length": "24 in",
            "load_position": "12 in",
            "force": "100 lbf",
            "support": "simple",
        },
    )
    out = {k: v.value for k, v in sol.outputs.items()}
    assert out["max_deflection"] == pytest.approx(0.023860, rel=1e-4)
    assert out["max_deflection_position"] == pytest.approx(0.3048, rel=1e-12)
    assert out["max_bending_stress"] == pytest.approx(337.10e6, rel=1e-4)
    assert out["safety_factor"] == pytest.approx(276 / 337.10, rel=1e-4)
    assert any("exceeds the yield" in w for w in sol.warnings)


def test_fixed_centre_load_is_a_quarter_of_simple_and_cantilever_tip():
    """Fixed-fixed centre load: Fl³/(192EI), a quarter of Fl³/(48EI). Cantilever tip load: Fl³/(3EI)."""
    base = {"section": "square", "outer_size": "1 in", "length": "30 in", "force": "20 lbf"}
    simple = solve("beam", {**base, "support": "simple", "load_position": "15 in"}).outputs
    fixed = solve("beam", {**base, "support": "fixed", "load_position": "15 in"}).outputs
    cant = solve("beam", {**base, "support": "cantilever", "load_position": "30 in"}).outputs
    assert fixed["max_deflection"].value == pytest.approx(simple["max_deflection"].value / 4, rel=1e-12)
    EI = 68.9e9 * IN**4 / 12
    assert cant["max_deflection"].value == pytest.approx(20 * LBF * (30 * IN) ** 3 / (3 * EI), rel=1e-12)
    assert cant["max_deflection_position"].value == pytest.approx(30 * IN)
    assert fixed["max_bending_moment"].value == pytest.approx(20 * LBF * 30 * IN / 8, rel=1e-12)


# --- buckling, twist, materials ---------------------------------------------------------------


@pytest.mark.parametrize(
    "end,k_values,K",
    [
        ("fixed_fixed", "theoretical", 0.5),
        ("fixed_fixed", "recommended", 0.65),
        ("fixed_free", "recommended", 2.1),
        ("pinned_pinned", "theoretical", 1.0),
        ("fixed_guided", "recommended", 1.2),
    ],
)
def test_buckling_uses_weak_axis_and_k_table(end, k_values, K):
    raw = {
        "section": "rectangular_tube",
        "height": "2 in",
        "width": "1 in",
        "wall": "0.0625 in",
        "length": "60 in",
        "end_condition": end,
        "k_values": k_values,
    }
    sec = beams.rectangular_tube_section(2 * IN, 1 * IN, 0.0625 * IN)
    expected = math.pi**2 * 68.9e9 * sec.min_area_moment / (K * 60 * IN) ** 2  # (59)
    assert solve("beam", raw).outputs["buckling_load"].value == pytest.approx(expected, rel=1e-12)
    assert sec.min_area_moment < sec.area_moment


def test_twist_angle_of_steel_round_shaft():
    """θ = TL/(GJ): 10 N·m over 0.5 m, 12 mm steel: J = π·0.012⁴/32 = 2.03575e-9 m⁴,
    θ = 5/(79.3e9·2.03575e-9) = 5/161.435 = 0.030973 rad."""
    sol = solve(
        "beam",
        {
            "section": "round",
            "outer_size": "12 mm",
            "material": "steel",
            "torque": "10 N*m",
            "length": "0.5 m",
            "load_position": "0 m",
        },
    )
    assert sol.outputs["twist_angle"].value == pytest.approx(0.030973, rel=1e-4)
    assert "safety_factor" not in sol.outputs  # steel grade unknown
    assert sol.outputs["mass"].value == pytest.approx(7850 * math.pi * 0.006**2 * 0.5, rel=1e-12)


def test_custom_material_and_unknown_yield():
    raw = {
        "material": "custom",
        "youngs_modulus": "200 GPa",
        "shear_modulus": "80 GPa",
        "yield_strength": 0,
        "density": 0,
    }
    sol = solve("beam", raw)
    assert "safety_factor" not in sol.outputs and "mass" not in sol.outputs
    values, _ = parse_inputs(calc.CALCULATOR, raw)
    assert calc.material_from(values)[:2] == (200e9, 80e9)


# --- input errors -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "raw,field",
    [
        ({"section": "round_tube", "outer_size": "1 in", "wall": "0.5 in"}, "wall"),
        ({"section": "rectangular_tube", "height": "2 in", "width": "1 in", "wall": "0.6 in"}, "wall"),
        ({"length": "10 in", "load_position": "11 in"}, "load_position"),
        ({"force": "-5 lbf"}, "force"),
        ({"section": "round", "outer_size": "3 kg"}, "outer_size"),
    ],
)
def test_bad_inputs_name_the_field(raw, field):
    with pytest.raises(InputError) as e:
        solve("beam", raw)
    assert e.value.field == field


def test_wall_is_not_checked_for_solid_sections():
    assert solve("beam", {"section": "round", "outer_size": "1 in", "wall": "2 in"}).outputs


# --- presets and CLI shape --------------------------------------------------------------------


def test_builtin_beam_presets_load_and_solve():
    found = presets.listing("beam")
    assert len(found) >= 2
    for p in found:
        sol = solve("beam", p.inputs)
        assert sol.outputs["max_deflection"].value > 0


def test_required_outputs_present():
    sol = solve("beam", {"section": "round_tube"}).as_json()
    for name in (
        "area_moment",
        "torsion_constant",
        "max_deflection",
        "max_deflection_position",
        "buckling_load",
        "twist_angle",
    ):
        assert sol["outputs"][name]["unit"] in ("m**4", "m", "N", "rad")


def test_short_column_gives_johnsons_load():
    """Solid 1 in square 6061, 10 in pinned: r = a/√12 = 0.0073323 m, KL/r = 0.254/0.0073323 = 34.641;
    Euler σ = π²E/(KL/r)² = 9.8696·68.9e9/1200 = 566.7 MPa > Sy/2 → Johnson:
    σ = Sy − (Sy·34.641/2π)²/E = 276e6 − (1.52167e9)²/68.9e9 = 276e6 − 33.607e6 = 242.39 MPa;
    P = 242.39e6·0.0254² = 156,380 N."""
    sol = solve(
        "beam",
        {
            "section": "square",
            "outer_size": "1 in",
            "length": "10 in",
            "load_position": "5 in",
            "end_condition": "pinned_pinned",
            "k_values": "theoretical",
        },
    )
    assert sol.outputs["buckling_formula"].value == "Johnson"
    assert sol.outputs["buckling_load"].value == pytest.approx(156380, rel=1e-3)
    long_column = solve(
        "beam", {"section": "square", "outer_size": "1 in", "length": "100 in", "load_position": "5 in"}
    )
    assert long_column.outputs["buckling_formula"].value == "Euler"


# --- review additions: lines no earlier test pinned down ------------------------------------


def test_k_table_is_the_seeds():
    """Seed table under (59), columns in order: theoretical 0.5 0.7 1.0 1.0 2.0 2.0,
    recommended 0.65 0.80 1.2 1.0 2.10 2.0."""
    table = {
        "fixed_fixed": (0.5, 0.65),
        "fixed_pinned": (0.7, 0.80),
        "fixed_guided": (1.0, 1.2),
        "pinned_pinned": (1.0, 1.0),
        "fixed_free": (2.0, 2.10),
        "pinned_guided": (2.0, 2.0),
    }
    assert {k: v[1:] for k, v in calc.END_CONDITIONS.items()} == table


def test_fixed_fixed_off_centre_moment_is_at_the_nearer_support():
    """a = l/4, b = 3l/4 (Shigley A-9-14): M_left = F·a·b²/l² = F·l·0.25·0.5625 = 0.140625·F·l,
    M_right = F·a²·b/l² = 0.046875·F·l, under the load 2F·a²b²/l³ = 0.0703125·F·l."""
    for a in (0.25, 0.75):
        assert beams.max_moment("fixed", 10.0, a, 1.0) == pytest.approx(1.40625, rel=1e-14)
    assert beams.max_moment("simple", 10.0, 0.25, 1.0) == pytest.approx(10 * 0.25 * 0.75, rel=1e-14)
    assert beams.max_moment("cantilever", 10.0, 0.25, 1.0) == pytest.approx(2.5, rel=1e-14)


def test_hex_bending_stress_uses_the_corner_fibre():
    """1/2 in hex, 10 in cantilever, 10 lbf at the tip: M = 44.4822·0.254 = 11.29848 N·m;
    I = 5√3/144·0.0127⁴ = 0.0601407·2.60145e-8 = 1.564530e-9 m⁴; c = 0.0127/√3 = 7.33235e-3 m;
    σ = 11.29848·7.33235e-3/1.564530e-9 = 52.952 MPa."""
    sol = solve(
        "beam",
        {
            "section": "hex",
            "outer_size": "0.5 in",
            "support": "cantilever",
            "length": "10 in",
            "load_position": "10 in",
            "force": "10 lbf",
        },
    )
    assert sol.outputs["max_bending_stress"].value == pytest.approx(52.952e6, rel=1e-4)


def test_johnson_branch_starts_where_euler_stress_is_half_the_yield():
    """Solid 1 in square 6061, pinned, K = 1: r = 0.0254/√12 = 7.33235e-3 m. Euler σ = Sy/2 at
    KL/r = √(2π²E/Sy) = √(2·9.8696·68.9e9/276e6) = 70.197 → L = 0.51471 m = 20.264 in.
    At 18 in (KL/r = 62.35, σ_E = 174.9 MPa, between Sy/2 and Sy) Johnson applies; at 22 in not."""
    base = {
        "section": "square",
        "outer_size": "1 in",
        "load_position": "0 in",
        "end_condition": "pinned_pinned",
        "k_values": "theoretical",
    }
    assert solve("beam", {**base, "length": "18 in"}).outputs["buckling_formula"].value == "Johnson"
    assert solve("beam", {**base, "length": "22 in"}).outputs["buckling_formula"].value == "Euler"


@pytest.mark.parametrize(
    "material,E,G,rho",
    [
        ("6061_t6", 68.9e9, 26.0e9, 2700.0),
        ("steel", 200e9, 79.3e9, 7850.0),
        ("polycarbonate", 2.34e9, 2.34e9 / (2 * (1 + 0.37)), 1200.0),
    ],
)
def test_material_figures_reach_the_outputs(material, E, G, rho):
    """REFERENCE_DATA.md; polycarbonate G = E/(2(1 + ν)) = 2.34/2.74 = 0.85401 GPa with ν = 0.37.
    1 in round bar, 10 in, 1 N·m of torque: θ = T·L/(G·J), J = π·0.0254⁴/32 = 4.08620e-8 m⁴."""
    sol = solve(
        "beam",
        {
            "section": "round",
            "outer_size": "1 in",
            "length": "10 in",
            "load_position": "0 in",
            "torque": "1 N*m",
            "material": material,
        },
    )
    J = math.pi * IN**4 / 32
    assert sol.outputs["twist_angle"].value == pytest.approx(0.254 / (G * J), rel=1e-12)
    assert sol.outputs["mass"].value == pytest.approx(rho * math.pi / 4 * IN**2 * 0.254, rel=1e-12)
    assert sol.outputs["euler_load"].value == pytest.approx(
        math.pi**2 * E * J / 2 / 0.254**2, rel=1e-12
    )  # K = 1 (pinned, recommended 1.0), I = J/2


def test_short_steel_column_without_a_yield_says_which_yield_euler_needs():
    """Steel 1 in square, 10 in pinned: KL/r = 34.641 (see the Johnson test), σ_E = π²·200e9/1200
    = 1644.9 MPa, so Euler needs a yield ≥ 3290 MPa: no steel in FRC has that. At 100 in,
    σ_E = 16.45 MPa < 125 MPa: no warning."""
    base = {
        "section": "square",
        "outer_size": "1 in",
        "material": "steel",
        "load_position": "0 in",
        "end_condition": "pinned_pinned",
        "k_values": "theoretical",
    }
    (warning,) = [w for w in solve("beam", {**base, "length": "10 in"}).warnings if "Short column" in w]
    needed = float(warning.split("at least ")[1].split(" MPa")[0])
    assert needed == pytest.approx(2 * math.pi**2 * 200e3 / 1200, rel=1e-4)  # 3289.9 MPa
    assert not any("Short column" in w for w in solve("beam", {**base, "length": "100 in"}).warnings)
