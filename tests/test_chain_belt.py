"""Chain/belt C-C calculator (seed section 7, Appendix E): hand values, the ReCalc cross-check,
the corrected length equation against an independent form, and links → center → links."""

import math

import mpmath as mp
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearhead.core import presets
from gearhead.core.calculators import chain_belt as cb
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.registry import get

IN = 0.0254
MM = 1e-3


def out(**raw):
    return {k: v.value for k, v in solve("chain_belt", raw).outputs.items()}


def belt_length_beta_form(C, D1, D2):
    """The open-drive length as the issue writes it (independent of the code's u-form):
    L = 2C cos β + (π/2)(D1 + D2) + β(D2 − D1), sin β = (D2 − D1)/(2C)."""
    beta = mp.asin((D2 - D1) / (2 * C))
    return 2 * C * mp.cos(beta) + mp.pi / 2 * (D1 + D2) + beta * (D2 - D1)


def mp_center(L, D1, D2):
    """mpmath reference: solve the β-form for C by bisection-safe findroot (anderson)."""
    lo = (max(D1, D2) - min(D1, D2)) / 2
    return mp.findroot(
        lambda C: belt_length_beta_form(C, D1, D2) - L, (lo + mp.mpf("1e-30"), L / 2), solver="anderson"
    )


def test_recalc_belt_cross_check():
    # ReCalc: 20T and 30T, 5 mm pitch, 100-tooth belt -> 187.331 mm
    o = out(kind="belt", pitch_standard="htd_5mm", teeth_1=20, teeth_2=30, links=100)
    assert o["center_distance"] / MM == pytest.approx(187.331, abs=5e-4)
    mp.mp.dps = 40
    ref = mp_center(mp.mpf(500), mp.mpf(100) / mp.pi, mp.mpf(150) / mp.pi)  # D_i = n p / π in mm
    assert o["center_distance"] / MM == pytest.approx(float(ref), rel=1e-13)
    assert o["length"] == pytest.approx(0.5, rel=1e-15)  # (66) L = l p = 100 * 5 mm


def test_seed_appendix_form_is_off_by_four_delta_asin():
    # The seed's final (68) uses acos((r1 - r2)/D); with r1 < r2 that is π/2 + asin(Δ/D), the
    # wrap angles swapped: L_seed = L_exact - 4Δ asin(Δ/D). At the ReCalc case it gives 188.005 mm.
    r1, r2 = 50 / math.pi, 75 / math.pi  # mm
    D = 187.3309535438752
    seed = 2 * math.sqrt(D**2 - (r1 - r2) ** 2) + 2 * (r1 - r2) * math.acos((r1 - r2) / D) + 2 * math.pi * r2
    exact = cb.length_from_center(D, r1, r2)
    delta = r2 - r1
    assert exact == pytest.approx(500, rel=1e-14)
    assert exact - seed == pytest.approx(4 * delta * math.asin(delta / D), rel=1e-12)


def test_equal_sprockets_closed_form():
    # 16T/16T #25 chain, 60 links: D = (L - π d)/2 = (60·0.25 - π·(16·0.25/π))/2 = (15 - 4)/2 = 5.5 in
    o = out(kind="chain", pitch_standard="chain_25", teeth_1=16, teeth_2=16, links=60)
    assert o["center_distance"] / IN == pytest.approx(5.5, rel=1e-14)
    assert o["clearance"] / IN == pytest.approx(5.5 - 4 / math.pi, rel=1e-14)  # (67): D - 2r, r = 2/π in
    assert o["wrap_angle_small"] == pytest.approx(math.pi, rel=1e-15)


def test_shortest_belt_that_wraps_both():
    # 20T/30T HTD 5 mm: L_min = 2π r2 = 30 teeth * 5 mm; there D = Δ = (30 - 20)·5 mm/(2π).
    o = out(teeth_1=20, teeth_2=30, links=30)
    assert o["center_distance"] == pytest.approx(10 * 5 * MM / (2 * math.pi), rel=1e-14)
    assert o["minimum_links"] == 42  # the fewest that clear: test_hard_transmission.py
    assert o["wrap_angle_small"] == pytest.approx(0, abs=1e-7)
    with pytest.raises(InputError) as e:
        solve("chain_belt", {"teeth_1": 20, "teeth_2": 30, "links": 29})
    assert e.value.field == "links" and "too short" in e.value.message and "30" in e.value.message


def test_overlapping_sprockets_warn():
    sol = solve("chain_belt", {"teeth_1": 20, "teeth_2": 30, "links": 40})
    assert sol.outputs["clearance"].value < 0
    assert any("overlap" in w for w in sol.warnings)


def test_chordal_pitch_diameter_option():
    # #25 chain 16T: true pitch circle p/sin(180°/16) = 0.25/0.19509032 = 1.281457 in; seed 16·0.25/π = 1.273240 in
    o = out(
        kind="chain", pitch_standard="chain_25", teeth_1=16, teeth_2=32, links=80, pitch_diameter="chordal"
    )
    assert o["pitch_diameter_1"] / IN == pytest.approx(1.281457, abs=2e-6)
    s = out(kind="chain", pitch_standard="chain_25", teeth_1=16, teeth_2=32, links=80)
    assert s["pitch_diameter_1"] / IN == pytest.approx(4 / math.pi, rel=1e-15)
    # the chain path is n·p per turn either way: the center distance does not change, the clearance
    # (67) does, by the difference of the pitch radii: 0.25/(2 sin 11.25°) + 0.25/(2 sin 5.625°) − 6/π
    # = 0.640729 + 1.275288 − 1.909859 = 0.006158 in
    assert o["center_distance"] == s["center_distance"]
    shift = 0.125 / math.sin(math.pi / 16) + 0.125 / math.sin(math.pi / 32) - 6 / math.pi
    assert (s["clearance"] - o["clearance"]) / IN == pytest.approx(shift, rel=1e-9)


@pytest.mark.parametrize("method", ["circumference", "chordal"])
def test_equal_chain_sprockets_exact_link_count(method):
    # 16T-16T #25, 6 in: the taut chain round two equal sprocket polygons is 2D + n·p (n links round
    # the two half-wraps), whatever the pitch circle: 2·6 + 16·0.25 = 16 in = 64 links exactly.
    # (p/sin(180°/n) in (68) would say 64.103 links and 64 links -> 5.987 in.)
    o = out(
        kind="chain",
        pitch_standard="chain_25",
        teeth_1=16,
        teeth_2=16,
        mode="links_from_center",
        target_center="6 in",
        pitch_diameter=method,
    )
    assert o["links_exact"] == pytest.approx(64, rel=1e-14)
    assert o["links_below"] == o["links_above"] == 64
    assert o["center_below"] / IN == pytest.approx(6, rel=1e-14)


def hull_links(D, n1, n2, p, phases=8):
    """Independent polygon model: rollers on the vertices of the sprockets' true pitch polygons
    (circumradius p/(2 sin(π/n))), sprocket 2 at (D, 0); the taut chain is the convex hull's
    perimeter. Returns (min, max) over the two sprockets' phases, in links."""
    import numpy as np
    from scipy.spatial import ConvexHull

    def ring(n, cx, f):
        a = f + 2 * np.pi * np.arange(n) / n
        R = p / (2 * math.sin(math.pi / n))
        return np.c_[cx + R * np.cos(a), R * np.sin(a)]

    per = [
        ConvexHull(
            np.vstack(
                [ring(n1, 0, 2 * math.pi * i / (phases * n1)), ring(n2, D, 2 * math.pi * j / (phases * n2))]
            )
        ).area
        / p
        for i in range(phases)
        for j in range(phases)
    ]  # 2-D hull: .area is the perimeter
    return min(per), max(per)


@pytest.mark.parametrize(
    "n1, n2, links, standard, p", [(12, 36, 74, "chain_25", 0.25 * IN), (12, 60, 92, "chain_35", 0.375 * IN)]
)
def test_chain_center_against_sprocket_polygons(n1, n2, links, standard, p):
    # At the calculator's D the taut hull round the roller polygons brackets the chain (74.0 ± 0.005
    # links); (68) with p/sin(180°/n) radii gives a D where every phase leaves ~0.08 link of slack.
    o = out(
        kind="chain", pitch_standard=standard, teeth_1=n1, teeth_2=n2, links=links, pitch_diameter="chordal"
    )
    lo, hi = hull_links(o["center_distance"], n1, n2, p)
    assert lo <= links <= hi and hi - lo < 0.01
    R1, R2 = cb.pitch_radius(n1, p, "chordal"), cb.pitch_radius(n2, p, "chordal")
    assert hull_links(cb.center_from_length(links * p, R1, R2), n1, n2, p)[1] < links - 0.05


def test_reverse_even_links_for_chain_and_half_links():
    # #25, 12T/36T, wanted 6 in: exact count from the β-form in mpmath
    mp.mp.dps = 30
    D1, D2 = 12 * mp.mpf("0.25") / mp.pi, 36 * mp.mpf("0.25") / mp.pi
    exact_links = belt_length_beta_form(mp.mpf(6), D1, D2) / mp.mpf("0.25")  # 72.609...
    o = out(
        kind="chain",
        pitch_standard="chain_25",
        teeth_1=12,
        teeth_2=36,
        mode="links_from_center",
        target_center="6 in",
    )
    assert o["links_exact"] == pytest.approx(float(exact_links), rel=1e-13)
    assert (o["links_below"], o["links_above"]) == (72, 74)
    assert o["center_below"] / IN < 6 < o["center_above"] / IN
    h = out(
        kind="chain",
        pitch_standard="chain_25",
        teeth_1=12,
        teeth_2=36,
        mode="links_from_center",
        target_center="6 in",
        half_links=True,
    )
    assert (h["links_below"], h["links_above"]) == (72, 73)
    b = out(
        kind="belt",
        pitch_standard="rt25",
        teeth_1=12,
        teeth_2=36,
        mode="links_from_center",
        target_center="6 in",
    )
    assert (b["links_below"], b["links_above"]) == (72, 73)


def test_odd_chain_links_warn():
    sol = solve("chain_belt", {"kind": "chain", "pitch_standard": "chain_35", "links": 71})
    assert any("half" in w for w in sol.warnings)


def test_a_standard_sets_the_kind():
    """Switching to #25 chain with 'Chain or belt' left at belt used to be an error; the field is
    asked only for a custom pitch now, so a chain standard is a chain (even links)."""
    o = out(
        kind="belt",
        pitch_standard="chain_25",
        teeth_1=16,
        teeth_2=16,
        mode="links_from_center",
        target_center="6.1 in",
    )
    assert o["links_above"] % 2 == 0 and o["links_below"] % 2 == 0
    f = next(f for f in get("chain_belt").fields if f.name == "kind")
    assert not f.active("center_from_links", {"pitch_standard": "chain_25"})
    assert f.active("center_from_links", {"pitch_standard": "custom"})


def test_custom_pitch_is_used_only_for_custom():
    a = out(pitch_standard="custom", pitch="8 mm", teeth_1=20, teeth_2=20, links=50)
    # equal pulleys: D = (L - π d)/2 = (400 mm - 160 mm)/2 = 120 mm
    assert a["center_distance"] / MM == pytest.approx(120, rel=1e-14)
    b = out(pitch_standard="gt2_3mm", pitch="8 mm", teeth_1=20, teeth_2=20, links=50)
    assert b["center_distance"] / MM == pytest.approx((150 - 60) / 2, rel=1e-14)


def test_target_inside_radius_difference_is_an_input_error():
    with pytest.raises(InputError) as e:
        solve(
            "chain_belt", {"mode": "links_from_center", "teeth_1": 10, "teeth_2": 60, "target_center": "1 mm"}
        )
    assert e.value.field == "target_center"


@settings(max_examples=200, deadline=None)
@given(
    n1=st.integers(3, 120),
    n2=st.integers(3, 120),
    extra=st.integers(1, 400),
    p=st.floats(1e-3, 0.03),
    chordal=st.booleans(),
)
def test_links_to_center_to_links(n1, n2, extra, p, chordal):
    method = "chordal" if chordal else "circumference"  # only what is shown; the path is n·p/π
    r1, r2 = cb.pitch_radius(n1, p, "circumference"), cb.pitch_radius(n2, p, "circumference")
    links = math.ceil(cb.minimum_length(r1, r2) / p) + extra
    raw = dict(pitch_standard="custom", pitch=f"{p} m", teeth_1=n1, teeth_2=n2, pitch_diameter=method)
    D = out(**raw, links=links)["center_distance"]
    assert cb.length_from_center(D, r1, r2) == pytest.approx(links * p, rel=1e-12)
    back = out(**raw, mode="links_from_center", target_center=f"{D!r} m")
    assert back["links_exact"] == pytest.approx(links, rel=1e-12)
    assert back["links_below"] == back["links_above"] == links
    assert back["center_below"] == pytest.approx(D, rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(r1=st.floats(1e-4, 1.0), r2=st.floats(1e-4, 1.0), s=st.floats(0, 1e6))
def test_center_from_length_inverts_length(r1, r2, s):
    L = cb.minimum_length(r1, r2) * (1 + s)
    D = cb.center_from_length(L, r1, r2)
    assert cb.length_from_center(D, r1, r2) == pytest.approx(L, rel=1e-12)


def test_presets_load_and_solve():
    found = [p for p in presets.listing("chain_belt") if p.builtin]
    assert len(found) >= 2
    for p in found:
        sol = solve("chain_belt", p.inputs)
        assert sol.outputs


@pytest.mark.parametrize("method", ["circumference", "chordal"])
def test_minimum_links_chain(method):
    # #25 chain 13T/37T: the sprockets' outside diameters p(0.6 + cot(180°/n)) = 1.16430 and
    # 3.08660 in touch at D = 2.12545 in; Δ = 24·0.25/(2π) = 0.954930 in, X = 1.89888 in,
    # L = 2X + π(r_1 + r_2) + 2Δ·sin⁻¹(Δ/D) = 3.79776 + 6.25 + 0.88977 = 10.9375 in = 43.75 links:
    # 44 with or without half links. (Wrapping alone needs 37 p: 38 even, 37 with a half link.)
    o = out(kind="chain", pitch_standard="chain_25", teeth_1=13, teeth_2=37, links=38, pitch_diameter=method)
    assert o["minimum_links"] == 44
    h = out(
        kind="chain",
        pitch_standard="chain_25",
        teeth_1=13,
        teeth_2=37,
        links=38,
        pitch_diameter=method,
        half_links=True,
    )
    assert h["minimum_links"] == 44
    with pytest.raises(InputError):
        solve(
            "chain_belt",
            {
                "kind": "chain",
                "pitch_standard": "chain_25",
                "teeth_1": 13,
                "teeth_2": 37,
                "links": 36,
                "pitch_diameter": method,
            },
        )


@pytest.mark.parametrize("method", ["circumference", "chordal"])
@pytest.mark.parametrize("factor", [1.0, 1 + 1e-15, 1 + 1e-9])
def test_reverse_at_the_wrap_minimum(method, factor):
    # D = Δ (the small sprocket inside the large one): the length is the minimum, 2π r_2
    p = 0.375 * IN
    r1, r2 = cb.pitch_radius(15, p, "circumference"), cb.pitch_radius(40, p, "circumference")
    sol = solve(
        "chain_belt",
        {
            "kind": "chain",
            "pitch_standard": "chain_35",
            "teeth_1": 15,
            "teeth_2": 40,
            "pitch_diameter": method,
            "mode": "links_from_center",
            "target_center": f"{(r2 - r1) * factor!r} m",
        },
    )
    o = {k: v.value for k, v in sol.outputs.items()}
    assert o["links_exact"] == pytest.approx(cb.minimum_length(r1, r2) / p, rel=1e-6)
    assert o["links_above"] == 40 and o["links_above"] < o["minimum_links"]  # wraps, but overlaps
    assert any("overlap" in w for w in sol.warnings)
    assert o["center_above"] >= r2 - r1


async def test_switching_to_a_chain_standard_in_the_app_solves_as_a_chain():
    """Picking #25 chain used to leave 'Chain or belt' at belt and show an error until changed by
    hand; the kind now follows the standard and half links appear for a chain."""
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab
    from tests.tui_helpers import settle, shown_rows

    app = GearheadApp(blink=False, initial="chain_belt")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-chain_belt", CalculatorTab)
        assert "kind" not in shown_rows(tab) and "half_links" not in shown_rows(tab)
        tab._take_entry("pitch_standard", "chain_25")
        await settle(pilot)
        assert tab.solution is not None and tab.solution.inputs["pitch_standard"].value == "chain_25"
        assert "half_links" in shown_rows(tab) and "kind" not in shown_rows(tab)
        assert tab.solution.outputs["minimum_links"].value % 2 == 0


# --- belt teeth in mesh (CB6), issue 31 ---


def mp_teeth_in_mesh(C, n1, n2, p):
    """θ_small = π − 2·asin((D − d)/(2C)) (textbook form, not the code's atan2), θ_large = 2π − θ_small;
    fractional teeth θ/(2π)·n on each pulley."""
    D1, D2 = n1 * p / mp.pi, n2 * p / mp.pi
    small = mp.pi - 2 * mp.asin(abs(D2 - D1) / (2 * C))
    th1, th2 = (small, 2 * mp.pi - small) if n1 <= n2 else (2 * mp.pi - small, small)
    return th1 / (2 * mp.pi) * n1, th2 / (2 * mp.pi) * n2


def test_teeth_in_mesh_intake_belt_by_hand():
    """20T and 30T HTD 5 mm on a 100-tooth belt: C = 187.331 mm (mpmath from the β-form), Δ = 7.9577 mm,
    θ_small = π − 2·asin(7.9577/187.331) = 3.05661 rad: 20·0.48647 = 9.729 → 9; 30·0.51353 = 15.41 → 15."""
    mp.mp.dps = 30
    p = mp.mpf(5) / 1000
    C = mp_center(100 * p, 20 * p / mp.pi, 30 * p / mp.pi)
    x1, x2 = mp_teeth_in_mesh(C, 20, 30, p)
    assert float(x1) == pytest.approx(9.729, abs=5e-4) and float(x2) == pytest.approx(15.406, abs=5e-4)
    o = out(mode="center_from_links", pitch_standard="htd_5mm", teeth_1=20, teeth_2=30, links=100)
    assert (o["teeth_in_mesh_1"], o["teeth_in_mesh_2"]) == (int(mp.floor(x1)), int(mp.floor(x2))) == (9, 15)


def test_teeth_in_mesh_recalc_case_with_the_wraps_the_right_way_round():
    """ReCalc's belts.test.ts case: 30T and 20T, 5 mm, C = 100 mm. ReCalc answers 14 (30T) and 10 (20T),
    its wrap angles swapped; Δ = 7.9577 mm, θ_small = π − 2·asin(0.079577) = 2.98227 rad, so the
    exact wraps give 30·0.52536 = 15.761 → 15 and 20·0.47464 = 9.493 → 9."""
    mp.mp.dps = 30
    x30, x20 = mp_teeth_in_mesh(mp.mpf("0.1"), 30, 20, mp.mpf(5) / 1000)
    assert float(x30) == pytest.approx(15.7607, abs=5e-5) and float(x20) == pytest.approx(9.4929, abs=5e-5)
    o = out(
        mode="links_from_center", pitch_standard="htd_5mm", teeth_1=30, teeth_2=20, target_center="100 mm"
    )
    assert (o["teeth_in_mesh_1"], o["teeth_in_mesh_2"]) == (15, 9)


def test_teeth_in_mesh_equal_pulleys_half_each():
    """180° on each of two 20T pulleys is exactly 10 teeth (ReCalc floors 9.99999... to 9)."""
    o = out(
        mode="links_from_center", pitch_standard="htd_5mm", teeth_1=20, teeth_2=20, target_center="100 mm"
    )
    assert (o["teeth_in_mesh_1"], o["teeth_in_mesh_2"]) == (10, 10)


def test_fewer_than_six_teeth_in_mesh_warns():
    """GT2 3 mm, 12T to 36T at 30 mm: Δ = 24·3/(2π) = 11.459 mm, θ_small = π − 2·asin(11.459/30)
    = 2.3579 rad: 12·0.37527 = 4.50 → 4 teeth on the 12T (36·0.62473 = 22.49 → 22)."""
    mp.mp.dps = 30
    x1, x2 = mp_teeth_in_mesh(mp.mpf("0.03"), 12, 36, mp.mpf(3) / 1000)
    assert float(x1) == pytest.approx(4.503, abs=5e-4)
    sol = solve(
        "chain_belt",
        dict(
            mode="links_from_center", pitch_standard="gt2_3mm", teeth_1=12, teeth_2=36, target_center="30 mm"
        ),
    )
    assert (sol.outputs["teeth_in_mesh_1"].value, sol.outputs["teeth_in_mesh_2"].value) == (4, 22)
    assert any("Fewer than 6 belt teeth in mesh on pulley 1 (4 teeth)" in w for w in sol.warnings)
    far = solve(
        "chain_belt",
        dict(
            mode="links_from_center", pitch_standard="gt2_3mm", teeth_1=18, teeth_2=36, target_center="300 mm"
        ),
    )
    assert not any("teeth in mesh" in w for w in far.warnings)


def test_chains_have_no_belt_teeth_in_mesh():
    o = out(mode="center_from_links", pitch_standard="chain_25", teeth_1=16, teeth_2=32, links=80)
    assert "teeth_in_mesh_1" not in o and "teeth_in_mesh_2" not in o


@settings(max_examples=200, deadline=None)
@given(st.integers(3, 200), st.integers(3, 200), st.integers(0, 400))
def test_teeth_in_mesh_against_mpmath(n1, n2, extra):
    """Random belts: the whole counts equal ⌊mpmath⌋ wherever the fraction is not within 1e-6 of a whole."""
    mp.mp.dps = 30
    links = max(n1, n2) + 1 + extra
    o = out(mode="center_from_links", pitch_standard="htd_5mm", teeth_1=n1, teeth_2=n2, links=links)
    p = mp.mpf(5) / 1000
    C = mp.mpf(o["center_distance"])
    for x, got in zip(mp_teeth_in_mesh(C, n1, n2, p), (o["teeth_in_mesh_1"], o["teeth_in_mesh_2"])):
        if abs(x - mp.nint(x)) > 1e-6:
            assert got == int(mp.floor(x))
