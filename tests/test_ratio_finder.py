"""The parts catalogue and the ratio finder, checked against brute-force enumeration written here
independently of core/parts/finder.py (from the raw parts, not the finder's stage classes)."""

import itertools
import json
import math
from dataclasses import replace
from fractions import Fraction

import pytest

from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.parts import (
    FAMILIES,
    SHAFT_BORES,
    VENDORS,
    catalogue,
    finder,
    problems,
    read,
)

ALL = dict(vendors=frozenset(VENDORS), families=frozenset(FAMILIES), shaft_bores=frozenset(SHAFT_BORES))


def query(target=22.5, **kw):
    base = dict(
        target=target,
        ratio_min=target,
        ratio_max=target,
        input_bore="keyed_8mm",
        output_bore="hex_half_in",
        min_teeth=10,
        max_teeth=84,
        max_stages=3,
        results=20,
        **ALL,
    )
    base.update(kw)
    return finder.Query(**base)


# --- the catalogue -------------------------------------------------------------------------------


def test_catalogue_is_consistent():
    cat = read()
    assert problems(cat) == []
    assert len(cat.parts) > 600 and len(cat.belts) > 300
    assert {p.vendor for p in cat.parts} >= {"REV", "WCP", "AndyMark", "Thrifty", "SDS"}
    assert {p.family for p in cat.parts} == set(FAMILIES) - {"planetary"}
    assert {p.bore for p in cat.parts} >= {
        "hex_half_in",
        "hex_3_8_in",
        "round_1125_in",
        "maxspline",
        "splinexl",
        "keyed_8mm",
        "falcon",
    }
    systems = {s.system: s for s in cat.planetaries}
    assert set(systems) == {"MAXPlanetary", "UltraPlanetary", "VersaPlanetary"}
    # ReCalc's versaplanetaries.json (the source planetaries.toml cites): six stages, two hex outputs
    versa = systems["VersaPlanetary"]
    assert [c.ratio for c in versa.cartridges] == [3, 4, 5, 7, 9, 10] and versa.max_cartridges == 3
    assert {"hex_half_in", "hex_3_8_in"} <= set(versa.output_bores)
    # REV's actual UltraPlanetary ratios, not the nominal 3, 4, 5
    assert [c.ratio for c in systems["UltraPlanetary"].cartridges] == [
        Fraction(84, 29),
        Fraction(76, 21),
        Fraction(68, 13),
    ]


@pytest.mark.parametrize(
    "spoil,expected",
    [
        (lambda c: c._replace(parts=c.parts + (c.parts[0]._replace(family="gear_48dp"),)), "unknown family"),
        (lambda c: c._replace(parts=c.parts + (c.parts[0]._replace(bore="hex_7_16_in"),)), "unknown bore"),
        (lambda c: c._replace(parts=c.parts + (c.parts[3],)), "listed twice"),
        (
            lambda c: c._replace(parts=c.parts + (c.parts[5]._replace(teeth=c.parts[5].teeth + 1),)),
            "one part number for two different parts",
        ),
        (lambda c: c._replace(parts=c.parts + (c.parts[0]._replace(vendor="Acme"),)), "unknown vendor"),
        (lambda c: c._replace(pitches={**c.pitches, ("gears", "REV", "gear_20dp"): "32 DP"}), "has pitch"),
        (
            lambda c: c._replace(belts=c.belts + (c.belts[0]._replace(family="chain_25"),)),
            "a belt in the chain family",
        ),
    ],
)
def test_catalogue_checks_catch_mistakes(spoil, expected):
    found = problems(spoil(read()))
    assert any(expected in p for p in found), found


# --- brute force, from the raw parts ---------------------------------------------------------------


def raw_stages(q):
    """Every (identity, ratio, parts, drive bores, driven bores, kind) the filters allow, from the
    catalogue's parts directly."""
    cat = catalogue()
    allowed = set(q.shaft_bores)
    out = []
    reducing = q.target >= 1
    usable = [
        p
        for p in cat.parts
        if p.vendor in q.vendors and p.family in q.families and q.min_teeth <= p.teeth <= q.max_teeth
    ]
    by = {}
    for p in usable:
        by.setdefault((p.family, p.teeth), []).append(p)
    for (fam, n_in), drivers in by.items():
        for (fam2, n_out), driven in by.items():
            if fam2 != fam or n_in == n_out or (n_out > n_in) != reducing:
                continue
            drive = {p.bore for p in drivers if p.bore in allowed or p.bore == q.input_bore}
            take = {p.bore for p in driven if p.bore in allowed}
            if drive and take:
                parts = 2 if FAMILIES[fam].kind == "gear" else 3
                out.append(((fam, Fraction(n_out, n_in)), Fraction(n_out, n_in), parts, drive, take, fam))
    if "planetary" in q.families and reducing:
        for s in cat.planetaries:
            if s.vendor not in q.vendors:
                continue
            ins = {b for b in s.input_bores if b in allowed or b == q.input_bore}
            outs = {b for b in s.output_bores if b in allowed}
            if not ins or not outs:
                continue
            for count in range(1, s.max_cartridges + 1):
                for stack in itertools.combinations_with_replacement(s.cartridges, count):
                    ratio = math.prod((c.ratio for c in stack), start=Fraction(1))
                    names = tuple(sorted(c.name for c in stack))
                    out.append((("planetary", s.system, names), ratio, 1 + count, ins, outs, "planetary"))
    return out


def brute_force(q, stages_allowed):
    """(error, stages, parts) of every distinct feasible combination, best first."""
    raw = raw_stages(q)
    target_lo, target_hi = Fraction(repr(q.ratio_min)), Fraction(repr(q.ratio_max))
    out_bores = set(q.shaft_bores) if q.output_bore == "any" else {q.output_bore}
    best = {}
    for k in stages_allowed:
        for combo in itertools.product(raw, repeat=k):
            shaft = {q.input_bore}
            ok = True
            for i, st in enumerate(combo):
                fits = shaft if (i == 0 or q.same_shaft_bore) else set(q.shaft_bores)
                if not st[3] & fits:
                    ok = False
                    break
                shaft = st[4]
            if not ok or not shaft & out_bores:
                continue
            ratio = math.prod((st[1] for st in combo), start=Fraction(1))
            err = max(target_lo - ratio, ratio - target_hi, Fraction(0))
            ident = tuple(sorted(repr(st[0]) for st in combo))
            key = (float(err), k, sum(st[2] for st in combo))
            if ident not in best or key < best[ident]:
                best[ident] = key
    return sorted(best.values())


def finder_keys(q):
    combos, _ = finder.search(q)
    return [(c.error, len(c.stages), c.parts) for c in combos]


@pytest.mark.parametrize(
    "target,bore",
    [(3.0, "keyed_8mm"), (4.2, "falcon"), (2.57, "hex_half_in"), (0.6, "falcon"), (7.77, "splinexs")],
)
def test_single_stage_agrees_with_exhaustive_enumeration(target, bore):
    q = query(target, input_bore=bore, max_stages=1, results=60, output_bore="any")
    want = brute_force(q, [1])[:60]
    assert want, "the brute force found nothing: the case tests nothing"
    assert finder_keys(q) == want


@pytest.mark.parametrize(
    "target,k,kw",
    [
        # small enough for the brute force (all k-tuples of raw stages) to run in a second or two
        (22.5, 2, dict(vendors=frozenset({"REV"}), min_teeth=12, max_teeth=60)),
        (
            13.7,
            2,
            dict(
                families=frozenset({"htd_5mm", "gear_20dp", "planetary"}),
                vendors=frozenset({"REV", "WCP"}),
                min_teeth=12,
                max_teeth=48,
            ),
        ),
        (
            47.3,
            3,
            dict(
                vendors=frozenset({"REV"}),
                families=frozenset({"chain_25", "planetary"}),
                min_teeth=16,
                max_teeth=36,
            ),
        ),
        (
            0.45,
            2,
            dict(
                input_bore="falcon", families=frozenset({"gear_20dp", "htd_5mm"}), min_teeth=12, max_teeth=48
            ),
        ),
        (
            9.0,
            2,
            dict(
                vendors=frozenset({"WCP"}),
                same_shaft_bore=False,
                output_bore="any",
                min_teeth=12,
                max_teeth=48,
            ),
        ),
    ],
)
def test_pruned_multi_stage_search_agrees_with_brute_force(target, k, kw):
    q = query(target, max_stages=k, results=25, **kw)
    want = brute_force(q, range(1, k + 1))[:25]
    assert len(want) == 25
    got = finder_keys(q)
    assert [g[0] for g in got] == pytest.approx([w[0] for w in want], rel=1e-12, abs=1e-15)
    assert [g[1:] for g in got] == [w[1:] for w in want]


def test_planetary_plus_belt_found_for_five_times_three():
    # the catalogue's 3:1 HTD pairs on a 1/2 in hex shaft (14T) end on a 42T 1.125 in bearing-bore
    # pulley, so the output may be any bore
    q = query(15, max_stages=2, families=frozenset({"planetary", "htd_5mm"}), results=60, output_bore="any")
    combos, _ = finder.search(q)
    pairs = [
        c
        for c in combos
        if len(c.stages) == 2
        and c.error == 0
        and c.stages[0].system is not None
        and c.stages[0].ratio == 5
        and c.stages[1].family == "htd_5mm"
        and c.stages[1].ratio == 3
    ]
    assert pairs, [(c.ratio, [s.identity for s in c.stages]) for c in combos]
    # the one-stage 5:1 x 3:1 stack ranks first (fewer stages), and every exact two-stage with
    # fewer parts (two gearboxes, 2 + 2) ahead of the planetary and belt (2 + 3)
    assert len(combos[0].stages) == 1 and combos[0].ratio == 15
    first = combos.index(pairs[0])
    assert all((c.error, len(c.stages), c.parts) <= (0, 2, 5) for c in combos[:first])


def assembled(combo, q):
    """Whether real parts (from each stage's lists) chain from the motor to the output."""
    out = set(q.shaft_bores) if q.output_bore == "any" else {q.output_bore}
    shafts = {q.input_bore}
    for i, s in enumerate(combo.stages):
        if s.system is not None:
            ins, outs = set(s.system.input_bores), set(s.system.output_bores)
        else:
            ins, outs = {p.bore for p in s.driving}, {p.bore for p in s.driven}
            assert all(p.vendor in q.vendors and p.family in q.families for p in (*s.driving, *s.driven))
            assert all(q.min_teeth <= p.teeth <= q.max_teeth for p in (*s.driving, *s.driven))
        if i and not q.same_shaft_bore:
            shafts = set(q.shaft_bores)
        if not ins & shafts:
            return False
        shafts = outs & set(q.shaft_bores)
    return bool(shafts & out)


@pytest.mark.parametrize(
    "kw",
    [
        dict(input_bore="falcon", output_bore="maxspline", vendors=frozenset({"REV", "WCP", "SDS"})),
        dict(input_bore="keyed_8mm", output_bore="hex_3_8_in", shaft_bores=frozenset({"hex_3_8_in"})),
        dict(input_bore="splinexs", output_bore="splinexl", vendors=frozenset({"WCP"})),
    ],
)
def test_bores_and_vendors_are_respected(kw):
    q = query(12.0, max_stages=2, **kw)
    combos, _ = finder.search(q)
    assert combos
    for c in combos:
        assert assembled(c, q)
        for s in c.stages:
            if s.system is not None:
                assert s.system.vendor in q.vendors
    # and the calculator lists only those vendors' part numbers in the table
    v = {
        "target_ratio": 12,
        "max_stages": 2,
        "input_bore": q.input_bore,
        "output_bore": q.output_bore,
        "vendors": ", ".join(sorted(q.vendors)),
        "shaft_bores": ", ".join(sorted(q.shaft_bores)),
    }
    sol = solve("ratio_finder", v)
    for row in sol.tables["combinations"]:
        for vendor in VENDORS:
            if vendor not in q.vendors:
                assert f"({vendor})" not in row["parts"].text


def test_a_bore_no_part_has_gives_no_result_and_says_why():
    sol = solve("ratio_finder", {"input_bore": "shaft_bag", "families": "gear_32dp", "target_ratio": 5})
    assert sol.tables["combinations"] == []
    assert any("fits the motor shaft" in w for w in sol.warnings)


def test_impossible_target_gives_the_nearest_and_says_why():
    sol = solve(
        "ratio_finder",
        {"target_ratio": 50000, "max_stages": 2, "families": "gear_20dp, htd_5mm", "vendors": "REV, Thrifty"},
    )
    rows = sol.tables["combinations"]
    assert rows, "the nearest combinations are listed"
    q = query(
        50000,
        max_stages=2,
        families=frozenset({"gear_20dp", "htd_5mm"}),
        vendors=frozenset({"REV", "Thrifty"}),
    )
    reach = brute_force(replace(q, target=1.0, ratio_min=1e9, ratio_max=1e9), [1, 2])
    assert sol.outputs["ratio"].value == pytest.approx(1e9 - reach[0][0], rel=1e-9)  # the largest
    assert any("Out of reach" in w and "at most" in w for w in sol.warnings), sol.warnings
    assert sol.outputs["ratio_error"].value < -0.9


def test_near_miss_says_how_far():
    sol = solve("ratio_finder", {"target_ratio": 5.123, "max_stages": 1, "families": "gear_20dp"})
    assert sol.outputs["ratio_error"].value != 0
    assert any("off by" in w for w in sol.warnings)


# --- center distances: the chain_belt and ratio_distance equations, checked by sending ----------


def test_every_belt_and_gear_row_is_what_the_other_calculators_compute():
    from gearhead.core.registry import get

    calc_table = get("ratio_finder").tables[0]
    seen = set()
    rows = [
        row
        for families in ("htd_5mm, gt2_3mm, rt25", "chain_25, chain_35", "gear_20dp, gear_32dp")
        for row in solve(
            "ratio_finder",
            {"target_ratio": 9, "max_stages": 2, "results": 30, "output_bore": "any", "families": families},
        ).tables["combinations"]
    ]
    for row in rows:
        for target, mapping in calc_table.exports.items():
            if not all(c in row for c in mapping.values()):
                continue
            seen.add(target)
            sent = {field: row[col].value for field, col in mapping.items()}
            if target == "chain_belt":
                other = solve(
                    "chain_belt",
                    {k: (v if not isinstance(v, float) else f"{v!r} m") for k, v in sent.items()},
                )
                assert other.outputs["center_distance"].value == pytest.approx(
                    row["center_distance"].value, rel=1e-12
                )
                assert other.outputs["clearance"].value >= -1e-12  # pitch circles apart
            else:
                other = solve(
                    "ratio_distance",
                    {
                        "ratio": sent["ratio"],
                        "center_distance": f"{sent['center_distance']!r} m",
                        "diametral_pitch": f"{sent['diametral_pitch']!r} 1/m",
                    },
                )
                pair = sorted((row["teeth_1"].value, row["teeth_2"].value))
                assert [
                    other.outputs["nearest_small_teeth"].value,
                    other.outputs["nearest_large_teeth"].value,
                ] == pair
    assert seen == {"chain_belt", "ratio_distance"}


def test_center_distance_limits_are_met():
    v = {
        "target_ratio": 6,
        "max_stages": 2,
        "center_limits": "per_stage",
        "families": "chain_25, htd_5mm",
        "center_min_1": "3 in",
        "center_max_1": "5 in",
        "center_min_2": "6 in",
        "center_max_2": "9 in",
        "results": 30,
    }
    sol = solve("ratio_finder", v)
    rows = sol.tables["combinations"]
    assert rows
    for row in rows:
        c = row["center_distance"].value / 0.0254
        lo, hi = (3, 5) if row["stage"].value == 1 else (6, 9)
        assert lo - 1e-9 <= c <= hi + 1e-9


def test_loop_choice_is_the_shortest_stocked_belt():
    from gearhead.core.calculators.chain_belt import length_from_center, pitch_radius

    belts = finder.belt_lengths(query(), catalogue())["htd_5mm"]
    links, center = finder.loop_choice("htd_5mm", 18, 30, None, None, belts)
    p = 0.005
    r1, r2 = pitch_radius(18, p, "circumference"), pitch_radius(30, p, "circumference")
    assert links in belts and center >= r1 + r2
    shorter = [b for b in belts if b < links]
    if shorter:  # the next shorter stocked belt would put the pitch circles over each other
        assert shorter[-1] * p < length_from_center(r1 + r2, r1, r2)
    assert length_from_center(center, r1, r2) == pytest.approx(links * p, rel=1e-12)


# --- inputs and the command line -----------------------------------------------------------------


@pytest.mark.parametrize(
    "raw,field",
    [
        ({"mode": "range", "ratio_min": 5, "ratio_max": 3}, "ratio_max"),
        ({"mode": "range", "ratio_min": 0.5, "ratio_max": 3}, "ratio_max"),
        ({"min_teeth": 50, "max_teeth": 20}, "max_teeth"),
        ({"vendors": ""}, "vendors"),
        ({"target_ratio": "nan"}, "target_ratio"),
        ({"target_ratio": 0}, "target_ratio"),
        ({"max_stages": 4}, "max_stages"),
        ({"center_limits": "per_stage", "center_min_1": "5 in", "center_max_1": "2 in"}, "center_max_1"),
    ],
)
def test_bad_entries_name_their_field(raw, field):
    with pytest.raises(InputError) as err:
        solve("ratio_finder", raw)
    assert err.value.field == field


def test_cli_json(capsys):
    from gearhead.tui.cli import main

    assert (
        main(["solve", "ratio_finder", "--set", "target_ratio=22.5", "--set", "max_stages=2", "--json"]) == 0
    )
    out = json.loads(capsys.readouterr().out)
    assert out["outputs"]["ratio"]["value"] == 22.5
    rows = out["tables"]["combinations"]
    assert rows[0]["rank"]["value"] == 1 and rows[0]["stage"]["value"] == 1
    assert main(["solve", "ratio_finder", "--set", "min_teeth=90", "--set", "max_teeth=20"]) == 2
    assert "max_teeth" in capsys.readouterr().err


def test_other_calculators_json_has_no_tables_key():
    assert "tables" not in solve("gear_ratio", {}).as_json()


# --- the tab ------------------------------------------------------------------------------------


async def test_ctrl_g_sends_the_belt_row_under_the_cursor_to_chain_belt():
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.result_table import ResultTable
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="ratio_finder", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.current_tab
        tab.set_entries(
            {"families": "htd_5mm", "max_stages": "1", "target_ratio": "2.5", "output_bore": "any"}
        )
        await settle(pilot)
        rows = tab.solution.tables["combinations"]
        n = next(i for i, r in enumerate(rows) if "links" in r)
        grid = tab.query_one("#table-combinations", ResultTable)
        assert grid.row_count == len(rows)
        grid.focus()
        grid.move_cursor(row=n)
        await pilot.press("ctrl+g")
        await settle(pilot)
        assert app.current_calculator == "chain_belt"
        belt = app.current_tab
        assert belt.solution.outputs["center_distance"].value == pytest.approx(
            rows[n]["center_distance"].value, rel=1e-12
        )
        assert belt.entries["teeth_1"] == str(rows[n]["teeth_1"].value)


async def test_gear_ratio_sends_its_ratio_to_the_finder():
    from gearhead.tui.app import GearheadApp
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        ratio = app.current_tab.solution.outputs["ratio"].value
        await pilot.press("ctrl+g")
        await settle(pilot)
        assert app.current_calculator == "ratio_finder"
        assert float(app.current_tab.entries["target_ratio"]) == pytest.approx(ratio, rel=1e-15)
        assert app.current_tab.solution is not None
        # what the list shows is the result of the entries sent, not of the finder's defaults
        assert app.current_tab.results.state == "fresh"
        assert app.current_tab.solution.inputs["target_ratio"].value == pytest.approx(ratio, rel=1e-15)


def test_markdown_export_lists_the_combinations_and_part_numbers():
    from gearhead.core.export import results_markdown
    from gearhead.core.registry import get

    sol = solve("ratio_finder", {"target_ratio": 9, "max_stages": 1, "families": "gear_20dp", "results": 5})
    text = results_markdown(get("ratio_finder"), sol)
    rows = sol.tables["combinations"]
    assert "**Combinations, best first**" in text
    assert all(row["parts"].text in text for row in rows)
    assert text.count("\n| ") >= len(rows) + 1 + len(sol.outputs)


@pytest.mark.parametrize("calc_id", ["elevator", "arm"])
def test_elevator_and_arm_send_their_fastest_ratio_to_the_finder(calc_id):
    from gearhead.core.registry import calculators

    calc = calculators()[calc_id]
    assert calc.exports == {"ratio_finder": {"target_ratio": "best_ratio"}}
    best = solve(calc_id, {"mode": "optimise"}).outputs["best_ratio"].value
    found = solve("ratio_finder", {"target_ratio": best})
    assert found.outputs  # the sent ratio is one the finder accepts


def largest_reachable(q):
    """The largest ratio any feasible combination of at most q.max_stages stages gives, by
    dynamic programming over the bore on each shaft (from raw_stages, not the finder's tables)."""
    raw = raw_stages(q)
    out_bores = set(q.shaft_bores) if q.output_bore == "any" else {q.output_bore}
    reach = {q.input_bore: Fraction(1)}  # shaft bore -> largest ratio that reaches it
    best = None
    for _ in range(q.max_stages):
        after = {}
        for _ident, ratio, _parts, drive, take, _fam in raw:
            came = [reach[b] for b in drive if b in reach]
            if came:
                for b in take:
                    after[b] = max(after.get(b, 0), max(came) * ratio)
        reach = after
        for b in out_bores & reach.keys():
            best = reach[b] if best is None else max(best, reach[b])
    return best


@pytest.mark.parametrize(
    "kw",
    [
        dict(target=5000, families=frozenset({"gear_20dp"})),  # bores cap 3 stages at 302.4:1
        dict(target=5000),
        dict(target=1e5),  # the field's largest
        dict(target=1e5, families=frozenset(FAMILIES) - {"planetary"}, min_teeth=1, max_teeth=1000),
        dict(target=1234.5, families=frozenset({"chain_25", "htd_5mm", "gear_20dp"})),
        dict(target=math.sqrt(100 * 1e5), ratio_min=100, ratio_max=1e5, families=frozenset({"gear_20dp"})),
    ],
)
def test_out_of_reach_and_wide_targets_search_in_bounded_memory(kw):
    """Once ~12 GB and 40 s: the windows grew past every bore-infeasible value tuple at once."""
    import tracemalloc

    q = query(**{"ratio_min": kw["target"], "ratio_max": kw["target"], **kw})
    finder._PREPARED.clear()
    tracemalloc.start()
    try:
        combos, stats = finder.search(q)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 300e6, f"peak traced memory {peak / 1e6:.0f} MB"
    assert stats["checked"] < 50_000
    assert len(combos) == q.results
    top = largest_reachable(q)
    if top < Fraction(repr(q.ratio_min)):  # out of reach: the best is the largest reachable ratio
        assert combos[0].ratio == top
        assert all(c.ratio <= top for c in combos)
    keys = [finder.rank_key(c, q) for c in combos]
    assert keys == sorted(keys)


# --- what the filters can reach: the "Out of reach" warning against brute force ------------------


def brute_reach(q):
    """The least and greatest ratio of every assemblable combination of 1 to q.max_stages stages,
    by enumerating each one (depth first over raw_stages, a branch dropped once its bores fail)."""
    raw = raw_stages(q)
    out_bores = set(q.shaft_bores) if q.output_bore == "any" else {q.output_bore}
    ratios = []

    def down(depth, shaft, ratio):
        if depth and shaft & out_bores:
            ratios.append(ratio)
        if depth == q.max_stages:
            return
        fits = shaft if (depth == 0 or q.same_shaft_bore) else set(q.shaft_bores)
        for st in raw:
            if st[3] & fits:
                down(depth + 1, st[4], ratio * st[1])

    down(0, {q.input_bore}, Fraction(1))
    return (min(ratios), max(ratios)) if ratios else None


REACH_CASES = [
    # only the motor pinions (8 mm keyed) go down to 10 teeth: bores aside 3 stages give (30/10)^3
    dict(vendors="REV", families="gear_20dp", min_teeth=10, max_teeth=30, max_stages=3),
    dict(vendors="REV", families="gear_20dp, planetary", min_teeth=10, max_teeth=24, max_stages=1),
    dict(
        vendors="WCP", families="gear_20dp", min_teeth=12, max_teeth=30, max_stages=2, same_shaft_bore=False
    ),
    dict(
        vendors="WCP, Thrifty",
        families="gear_20dp, htd_5mm",
        input_bore="falcon",
        output_bore="any",
        min_teeth=10,
        max_teeth=36,
        max_stages=2,
    ),
]


def reach_query(target, inputs):
    kw = {k: v for k, v in inputs.items() if k not in ("vendors", "families")}
    return query(
        target,
        vendors=frozenset(s.strip() for s in inputs["vendors"].split(",")),
        families=frozenset(s.strip() for s in inputs["families"].split(",")),
        **kw,
    )


@pytest.mark.parametrize(
    "inputs,target",
    [(c, 5.0) for c in REACH_CASES]
    + [(REACH_CASES[2], 0.5)]
    + [
        (
            dict(
                vendors=", ".join(VENDORS), families="gear_20dp, htd_5mm", input_bore="falcon", max_stages=2
            ),
            0.5,
        )
    ],
)
def test_reach_is_what_brute_force_can_assemble(inputs, target):
    q = reach_query(target, inputs)
    want = brute_reach(q)
    assert want is not None, "the brute force found nothing: the case tests nothing"
    assert finder.reach(finder.prepare(q), q) == want


@pytest.mark.parametrize("inputs", REACH_CASES)
def test_out_of_reach_quotes_what_the_parts_and_bores_can_reach(inputs):
    lo, hi = brute_reach(reach_query(5.0, inputs))
    for target, side in (
        (float(hi) * 3, f"at most {float(hi):.4g}:1"),
        (1 + (float(lo) - 1) / 3, "at least"),
    ):
        sol = solve("ratio_finder", {**inputs, "target_ratio": target})
        notes = [w for w in sol.warnings if "Out of reach" in w]
        assert len(notes) == 1, sol.warnings
        assert side in notes[0] and f"{float(lo):.4g}:1 to {float(hi):.4g}:1" in notes[0], notes[0]
        # the nearest combination listed is the reachable end itself
        assert sol.outputs["ratio"].value == pytest.approx(float(hi if target > hi else lo), rel=1e-12)


def test_reach_first_case_differs_from_the_bore_blind_bound():
    """The first case above is one the old warning got wrong (largest value per position, bores
    aside), so the test above can tell the two apart."""
    q = reach_query(5.0, REACH_CASES[0])
    prep = finder.prepare(q)
    blind = math.prod(float(finder.table(prep, q, i, i == 0, i == 2).values[-1]) for i in range(3))
    assert blind > float(brute_reach(q)[1]) * 1.5
