"""Ratio finder: the gears, pulleys, sprockets and planetary stages you can order that give a
reduction, fit the motor's shaft and your shafts, ranked as ReCalc's Ratio Finder ranks them.

The seed's section 9 (ratio & distance) is the one-pair special case. Parts and their sources:
core/parts/*.toml; the search and its guarantees: core/parts/finder.py. Every stage shows its
center distance: (N + n)/(2p) for gears (76), and for belts and chains the shortest stocked belt
(or even chain) whose center distance keeps the pitch circles apart and meets the stage's limits,
from the exact length equation (68, corrected) of chain_belt.py.

Equations (cited by the outputs):
    G = G_1·G_2·G_3,  G_k = driven teeth/driving teeth of stage k (a planetary stage: the
        product of its cartridges' ratios)                                                 (RF1)
    e = G/G* − 1; in range mode e = G/G_min − 1 below the range, G/G_max − 1 above, 0 inside (RF2)
"""

from __future__ import annotations

import math

from ..declarations import Calculator, Column, Output, Result, Table
from ..errors import InputError
from ..fields import Field
from ..parts import BORES, FAMILIES, SHAFT_BORES, VENDORS

STAGES = (1, 2, 3)

FIELDS = (
    Field(
        "mode",
        "Find",
        choices=("ratio", "range"),
        choice_labels=("Nearest to a ratio", "Any ratio in a range"),
        default="ratio",
        help="A single wanted reduction (ranked by how near), or a range (every ratio inside is "
        "as good; fewer stages and parts first).",
    ),
    Field(
        "target_ratio",
        "Wanted ratio",
        default=22.5,
        min=0,
        min_exclusive=True,
        max=1e5,
        modes=("ratio",),
        help="Reduction G*: motor turns per output turn (below 1 is a speed-up).",
    ),
    Field(
        "ratio_min",
        "Lowest ratio",
        default=20,
        min=0,
        min_exclusive=True,
        max=1e5,
        modes=("range",),
        help="Lower end of the acceptable reduction.",
    ),
    Field(
        "ratio_max",
        "Highest ratio",
        default=25,
        min=0,
        min_exclusive=True,
        max=1e5,
        modes=("range",),
        help="Upper end of the acceptable reduction.",
    ),
    Field(
        "input_bore",
        "Motor shaft",
        choices=tuple(BORES),
        choice_labels=tuple(b.choice_label for b in BORES.values()),
        default="keyed_8mm",
        help="The bore of the first part: the motor's shaft (or a shaft you already have, e.g. "
        "1/2 in hex out of a gearbox).",
    ),
    Field(
        "output_bore",
        "Output shaft",
        choices=("any",) + SHAFT_BORES,
        choice_labels=("any",) + tuple(BORES[b].choice_label for b in SHAFT_BORES),
        default="hex_half_in",
        help="The bore of the last driven part (or the planetary output).",
    ),
    Field(
        "max_stages",
        "Stages, at most",
        integer=True,
        default=3,
        min=1,
        max=3,
        help="1 to 3 stages in series; a stacked planetary gearbox counts as one stage.",
    ),
    Field(
        "vendors",
        "Vendors",
        flags=True,
        choices=tuple(VENDORS),
        default=", ".join(VENDORS),
        help="Buy only from these vendors.",
    ),
    Field(
        "families",
        "Families",
        flags=True,
        choices=tuple(FAMILIES),
        choice_labels=tuple(f.label for f in FAMILIES.values()),
        default=", ".join(FAMILIES),
        help="Kinds of stage allowed: spur gears by pitch, belts by profile, chains by size, "
        "planetary gearboxes.",
    ),
    Field(
        "shaft_bores",
        "Bores on your shafts",
        flags=True,
        choices=SHAFT_BORES,
        choice_labels=tuple(BORES[b].choice_label for b in SHAFT_BORES),
        default=", ".join(SHAFT_BORES),
        help="Shaft profiles you are willing to use between the stages and at the output.",
    ),
    Field(
        "same_shaft_bore",
        "Parts on a shaft share its bore",
        boolean=True,
        default=True,
        help="On: the driven part of one stage and the driving part of the next sit on one shaft, "
        "so they need the same bore. Off: any allowed bores (you adapt them).",
    ),
    Field(
        "min_teeth",
        "Fewest teeth",
        integer=True,
        default=10,
        min=1,
        max=1000,
        help="Smallest gear, pulley or sprocket allowed (small pinions are weak and undercut).",
    ),
    Field(
        "max_teeth",
        "Most teeth",
        integer=True,
        default=84,
        min=1,
        max=1000,
        help="Largest gear, pulley or sprocket allowed.",
    ),
    Field(
        "center_limits",
        "Center distance limits",
        choices=("none", "per_stage"),
        choice_labels=("none", "per stage"),
        default="none",
        help="Limit each stage's center distance (planetary stages are coaxial and have none).",
    ),
    *(
        Field(
            f"center_{end}_{i}",
            f"Stage {i} center distance, {'least' if end == 'min' else 'most'}",
            "length",
            "in",
            default=0 if end == "min" else 12,
            min=0,
            when=(("center_limits", ("per_stage",)),),
            help=f"Stage {i}: {'shortest' if end == 'min' else 'longest'} center distance between its "
            f"two shafts{' (0: no lower limit)' if end == 'min' else ''}.",
        )
        for i in STAGES
        for end in ("min", "max")
    ),
    Field(
        "results",
        "Combinations listed",
        integer=True,
        default=20,
        min=1,
        max=200,
        help="How many of the best combinations the table lists.",
    ),
)

OUTPUTS = (
    Output(
        "ratio",
        "Best ratio",
        help="The best combination's reduction: the product of its stages' ratios (RF1).",
        equation="(RF1)",
    ),
    Output(
        "ratio_error",
        "Its error",
        "dimensionless",
        "%",
        help="G/G* − 1; in range mode the distance outside the range (0 inside), relative (RF2).",
        equation="(RF2)",
    ),
    Output(
        "stage_count", "Stages", help="Stages in series in the best combination (a planetary stack is one)."
    ),
    Output(
        "part_count",
        "Parts to buy",
        help="2 per gear stage; 2 + the belt or chain per loop stage; gearbox + cartridges for a planetary.",
    ),
    *(
        Output(
            f"stage_{i}",
            f"Stage {i}",
            help=f"Stage {i}, motor side first, driving:driven teeth (its ratio G_{i} "
            "in (RF1)); parts in the table.",
            equation="(RF1)",
        )
        for i in STAGES
    ),
    Output(
        "combinations",
        "Combinations found",
        help="Distinct feasible combinations the search assembled (not all of them listed).",
    ),
)

COLUMNS = (
    Column("rank", "#", width=3),
    Column("total_ratio", "Ratio", width=8),
    Column("error", "Error", "dimensionless", "%", width=9),
    Column("stage", "St", width=2),
    Column("kind", "Kind", width=21),
    Column("teeth", "Teeth", width=11),
    Column("center_distance", "C-C", "length", "in", width=9),
    Column("loop", "Belt/chain", width=10),
    Column("parts", "Parts", width=44),
    Column("bores", "Bores", width=30),
    Column("alternatives", "Also", width=22),
    # carried for ctrl+g (send the row under the cursor)
    Column("loop_kind", "chain or belt", hidden=True),
    Column("pitch_standard", "pitch standard", hidden=True),
    Column("teeth_1", "driving teeth", hidden=True),
    Column("teeth_2", "driven teeth", hidden=True),
    Column("links", "links", hidden=True),
    Column("links_mode", "chain/belt mode", hidden=True),
    Column("pair_ratio", "pair ratio (large/small)", hidden=True),
    Column("diametral_pitch", "diametral pitch", "reciprocal_length", "1/in", hidden=True),
)

TABLES = (
    Table(
        "combinations",
        "Combinations, best first",
        COLUMNS,
        exports={
            "chain_belt": {
                "mode": "links_mode",
                "kind": "loop_kind",
                "pitch_standard": "pitch_standard",
                "teeth_1": "teeth_1",
                "teeth_2": "teeth_2",
                "links": "links",
            },
            "ratio_distance": {
                "ratio": "pair_ratio",
                "center_distance": "center_distance",
                "diametral_pitch": "diametral_pitch",
            },
        },
    ),
)


def query_from(v):
    from ..parts.finder import Query

    if v["mode"] == "range":
        lo, hi = v["ratio_min"], v["ratio_max"]
        if lo > hi:
            raise InputError("ratio_max", f"must be at least the lowest ratio ({lo:g})")
        if (lo < 1) != (hi < 1) and hi != 1:
            raise InputError("ratio_max", "a range must be all reductions (≥ 1) or all speed-ups (< 1)")
        target = math.sqrt(lo * hi)  # the middle on a log scale
    else:
        lo = hi = target = v["target_ratio"]
    if v["min_teeth"] > v["max_teeth"]:
        raise InputError("max_teeth", f"must be at least the fewest teeth ({v['min_teeth']})")
    for name in ("vendors", "families", "shaft_bores"):
        if not v[name]:
            raise InputError(name, "choose at least one")
    limits = []
    for i in STAGES:
        if v["center_limits"] == "per_stage":
            c_min, c_max = v[f"center_min_{i}"], v[f"center_max_{i}"]
            if c_max <= c_min:
                raise InputError(f"center_max_{i}", "must be more than the least center distance")
            limits.append((c_min, c_max))
        else:
            limits.append(None)
    return Query(
        target,
        lo,
        hi,
        v["input_bore"],
        v["output_bore"],
        frozenset(v["vendors"]),
        frozenset(v["families"]),
        frozenset(v["shaft_bores"]),
        v["min_teeth"],
        v["max_teeth"],
        v["max_stages"],
        v["same_shaft_bore"],
        tuple(limits),
        v["results"],
    )


# --- describing a combination ------------------------------------------------------------------


def shaft_choice(combo, q) -> list[str]:
    """A bore for every shaft: the motor's, then for each made shaft the first (in BORES order)
    that its driven part comes in and that the next stage's driving part (or the output) takes."""
    from ..parts.finder import BIT, bores_in, mask_of

    n = len(combo.stages)
    out_mask = BIT[q.output_bore] if q.output_bore != "any" else mask_of(q.shaft_bores)
    chosen = [q.input_bore]
    for i in range(n):
        mask = combo.shaft_bores[i]
        if i == n - 1:
            mask &= out_mask
        elif q.same_shaft_bore:
            mask &= combo.stages[i + 1].drive_mask
        chosen.append(bores_in(mask)[0])  # not empty: the search checked the chain
    return chosen


def pick(parts, bore: str):
    """The part of that bore to list first: vendor order of the catalogue, then part number."""
    from ..parts import VENDORS as order

    vendors = list(order)
    fitting = [p for p in parts if p.bore == bore] or list(parts)
    return min(fitting, key=lambda p: (vendors.index(p.vendor), p.part_number, p.url))


def stage_rows(combo, q, rank: int) -> list[dict]:
    from ..parts import FAMILIES as fams
    from ..parts import catalogue, pitch_si
    from ..parts.finder import belt_lengths, gear_center, loop_choice

    bores = shaft_choice(combo, q)
    rows = []
    for i, s in enumerate(combo.stages):
        row = {"stage": i + 1}
        if i == 0:
            row.update(rank=rank, total_ratio=float(combo.ratio), error=relative_error(combo, q))
        b_in, b_out = bores[i], bores[i + 1]
        if s.system is not None:
            row["kind"] = f"{s.system.system} ({s.system.vendor})"
            row["teeth"] = " × ".join(c.name for c in s.cartridges)
            numbers = [s.system.part_number] + [c.part_number for c in s.cartridges]
            row["parts"] = ", ".join(x for x in numbers if x) or s.system.url
            row["bores"] = f"{BORES[b_in].label} → {BORES[b_out].label}"
        else:
            fam = fams[s.family]
            row["kind"] = fam.label
            row["teeth"] = f"{s.teeth_in}:{s.teeth_out}"
            a, b = pick(s.driving, b_in), pick(s.driven, b_out)
            row["parts"] = f"{a.name} ({a.vendor}) → {b.name} ({b.vendor})"
            row["bores"] = f"{BORES[a.bore].label} → {BORES[b.bore].label}"
            row["teeth_1"], row["teeth_2"] = s.teeth_in, s.teeth_out
            limits = q.center_limits[i]
            if fam.kind == "gear":
                row["center_distance"] = gear_center(s.family, s.teeth_in, s.teeth_out)  # (76)
                row["pair_ratio"] = max(s.teeth_in, s.teeth_out) / min(s.teeth_in, s.teeth_out)
                row["diametral_pitch"] = pitch_si(fam.pitch)
            else:
                small, large = sorted((s.teeth_in, s.teeth_out))
                found = loop_choice(
                    s.family,
                    small,
                    large,
                    *(limits or (None, None)),
                    belt_lengths(q, catalogue()).get(s.family, ()),
                )
                if found is not None:
                    links, center = found
                    row["center_distance"] = center
                    row["links"] = links
                    row["loop"] = f"{links} links" if fam.kind == "chain" else f"{links}T belt"
                    row.update(
                        loop_kind=fam.kind, pitch_standard=fam.standard, links_mode="center_from_links"
                    )
        if s.alternatives:
            shown = ", ".join(f"{a}:{b}" for a, b in s.alternatives[:4])
            row["alternatives"] = shown + (f" +{len(s.alternatives) - 4}" if len(s.alternatives) > 4 else "")
        rows.append(row)
    return rows


def relative_error(combo, q) -> float:
    """G/G* − 1 in ratio mode; in range mode the distance outside the range, relative to it."""
    ratio = combo.num / combo.den
    if q.ratio_min == q.ratio_max:
        return ratio / q.target - 1
    if ratio < q.ratio_min:
        return ratio / q.ratio_min - 1
    if ratio > q.ratio_max:
        return ratio / q.ratio_max - 1
    return 0.0


def describe(row) -> str:
    """A stage of the best combination in a few words (its parts are in the table)."""
    kind = row["kind"].split(" (")[0]  # "MAXPlanetary (REV)" -> "MAXPlanetary"
    return f"{kind} {row['teeth']}"


def why_not(q, combos, stats) -> list[str]:
    """Why the best is not on target (or why nothing was found)."""
    from ..parts.finder import exact, prepare, reach, table

    prep = prepare(q)
    if not combos:
        first = table(prep, q, 0, True, False)
        if not len(first.values):
            return [
                f"No allowed part fits the motor shaft ({BORES[q.input_bore].label}) with these "
                "vendors, families and tooth limits."
            ]
        return [
            "No combination ends on the output shaft "
            f"({'any allowed bore' if q.output_bore == 'any' else BORES[q.output_bore].label}) with "
            "these filters: allow more bores, families or stages."
        ]
    best = combos[0]
    if best.error == 0:
        return []
    notes = []
    lo, hi = reach(prep, q)  # not None: a combination was found
    stages = f"up to {q.max_stages} stages" if q.max_stages > 1 else "1 stage"
    span = f"{float(lo):.4g}:1 to {float(hi):.4g}:1"
    if exact(q.ratio_min) > hi:  # as the search measures errors: the decimals typed
        notes.append(
            f"Out of reach: with {stages} these parts give at most {float(hi):.4g}:1 (all they give: "
            f"{span}, bores included); allow more stages, larger tooth counts, more bores or "
            "planetary stacks."
        )
    elif exact(q.ratio_max) < lo:
        notes.append(
            f"Out of reach: with {stages} these parts give at least {float(lo):.4g}:1 (all they give: "
            f"{span}, bores included); allow more stages, other tooth counts or more bores."
        )
    else:
        notes.append(f"No exact combination: the nearest is off by {relative_error(best, q):+.3%}.")
    return notes


def compute(v) -> Result:
    from ..parts.finder import search

    q = query_from(v)
    combos, stats = search(q)
    warnings = why_not(q, combos, stats)
    if not combos:
        return Result({"combinations": 0}, warnings, tables={"combinations": []})
    rows = []
    for rank, combo in enumerate(combos, 1):
        rows.extend(stage_rows(combo, q, rank))
    best = combos[0]
    values = {
        "ratio": float(best.ratio),
        "ratio_error": relative_error(best, q),
        "stage_count": len(best.stages),
        "part_count": best.parts,
        "combinations": stats["feasible"],
    }
    for i, row in enumerate(rows[: len(best.stages)], 1):
        values[f"stage_{i}"] = describe(row)
    return Result(values, warnings, tables={"combinations": rows})


CALCULATOR = Calculator(
    id="ratio_finder",
    title="Ratio finder",
    summary="Gears, pulleys, sprockets and planetary stages you can order for a reduction: 1-3 "
    "stages that fit your motor, shafts and output, ranked by error, stages, then parts.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="9",
    tables=TABLES,
)
