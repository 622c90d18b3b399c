"""Ratio finder: which purchasable stages (gear pairs, pulley pairs, sprocket pairs, planetary
gearboxes) give a wanted reduction, and fit the motor, the shafts and the output.

A *stage* is one pair of toothed parts (or one stacked planetary gearbox); its ratio is driven
teeth over driving teeth (or the product of the cartridges' ratios), exactly, as a Fraction.
A *combination* is 1-3 stages in series, from the motor shaft to the output shaft; its ratio is
the product of the stage ratios.

Shafts. The motor shaft holds the first driving part (or a planetary's input): its bore must be
the motor's. Every other shaft is one the team makes, so it carries one profile: the driven part
of stage k and the driving part of stage k+1 share that shaft's bore (unless `same_shaft_bore` is
off). Parts bored for a motor shaft never sit on the other shafts. The last driven part (or the
planetary output) must have the output bore. Bore feasibility is propagated as bit masks: after
a toothed stage the shaft may have any bore its driven parts come in, since the driving and driven
parts are bought separately.

Ranking (as ReCalc's finder): ratio error |G − G*| (the distance to the range in range mode),
then the number of stages, then the number of parts to buy (two per gear stage, two plus the belt
or chain per belt/chain stage, the gearbox plus each cartridge for a planetary). Stages alike in
family, ratio, part count and bores are one *class*; a class is shown by one member (the pair
sold by the most vendors, then the smaller) with the others listed as alternatives. Orders of
the same stages (a·b·c, b·a·c, ...), and stages of one family and ratio, are one combination:
the best-ranked feasible one is kept.

Search. One stage: every class is tried (exhaustive). k stages: the candidate ratio values of
each position are sorted once; for every choice of the first k−1 values the last is found by
bisection within a window |G − G*| ≤ ε (numpy searchsorted, a row of the first positions at a
time). ε starts as the N-th best error found with fewer stages (a k-stage combination must be
strictly better to rank above them) and as the N-th best of the nearest last values; the
windows' value tuples are expanded into classes and checked for bores; if fewer than N feasible
combinations result, ε grows and the search repeats. tests/test_ratio_finder.py checks it
against brute-force enumeration; bench/bench_ratio_finder.py times it.

Bounded mode (capped() in search). When a window would hold more than WINDOW_CAP value tuples (an
out-of-reach target, where bores make most tuples unbuildable, or a wide range), the k-stage
search restarts on bore-pruned tables (pruned_table: only classes on some feasible bore chain,
exact per class) and drops each tuple in which no class of one value chains to the next. What
stays exhaustive: every tuple inside the windows searched is still tried, in slices of at most
WINDOW_CAP tuples, each sorted by the rank's own order and cut once it passes the N-th best; the
same stop rule as above (the N-th best error within ε, or ε past the largest possible error)
keeps the result that of brute force. What bounds growth: ε grows at most fourfold per step
(plus 10⁻⁶·G*) and, by bisection (grown()), only as far as 4× the tuples of the last window +
64·N, so memory is set by WINDOW_CAP and time by how far the N best lie; a range is searched
outward from its geometric middle, stopping once the N-th best is in range and nothing farther
out could rank above it (no fewer stages or parts, no nearer the middle).
reach() gives the ratios these filters can reach at all, for the "Out of reach" warning.
"""

from __future__ import annotations

import bisect
import itertools
import math
from collections.abc import Iterable
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property, lru_cache

from . import BORES, FAMILIES, Catalogue, Part, PlanetarySystem, catalogue, pitch_si

PLANETARY_PARTS_BASE = 1  # the gearbox (housing, input and output) besides its cartridges


@dataclass(frozen=True)
class Query:
    target: float  # wanted ratio G* (motor turns per output turn); in range mode the geometric middle
    ratio_min: float  # the range (both equal to target when a single ratio is wanted)
    ratio_max: float
    input_bore: str
    output_bore: str  # a bore key, or "any"
    vendors: frozenset[str]
    families: frozenset[str]
    shaft_bores: frozenset[str]  # bores allowed on the shafts the team makes
    min_teeth: int = 1
    max_teeth: int = 1000
    max_stages: int = 3
    same_shaft_bore: bool = True
    # per stage position (0, 1, 2): (min, max) center distance in m, or None for no limit
    center_limits: tuple = (None, None, None)
    results: int = 20


@dataclass
class Stage:
    """One class of stages: a representative member and the alternatives."""

    family: str
    teeth_in: int  # driving teeth (planetary: 0)
    teeth_out: int  # driven teeth (planetary: 0)
    ratio: Fraction
    parts: int
    drive_mask: int  # bores a driving part (or planetary input) comes in
    out_mask: int  # bores the driven part (or planetary output) comes in, on a made shaft
    positions: int  # bit i: allowed as stage i (center distance limits)
    driving: tuple = ()  # Part objects of the representative (planetary: the system)
    driven: tuple = ()
    cartridges: tuple = ()  # planetary: Cartridge objects, largest reduction first
    system: PlanetarySystem | None = None
    alternatives: list = field(default_factory=list)  # (teeth_in, teeth_out) of the other members

    def __post_init__(self) -> None:
        self.ratio_f = self.ratio.numerator / self.ratio.denominator  # float(ratio), without the ABC's detour

    @cached_property
    def identity(self) -> tuple:
        """What makes two stages the same to a designer: a gearbox and its cartridges, or a
        family and ratio (16:36 and 20:45 are one 2.25:1 gear stage; "Also" lists the others)."""
        if self.system is not None:
            return ("planetary", self.system.system, tuple(c.name for c in self.cartridges))
        return (self.family, self.ratio)


@dataclass
class Combination:
    stages: tuple[Stage, ...]
    num: int  # the ratio as num/den (not reduced): products of the stages' teeth
    den: int
    error: float  # |G − G*| (0 inside the range), from exact integers: equal ratios, equal errors
    parts: int
    shaft_bores: tuple[int, ...]  # the bore mask left on each shaft after each stage

    @property
    def ratio(self) -> Fraction:
        return Fraction(self.num, self.den)


# --- building the stage classes --------------------------------------------------------------

BIT = {name: 1 << i for i, name in enumerate(BORES)}


def _union(masks: Iterable[int]) -> int:
    """The bitwise or of bore masks (0 for none)."""
    m = 0
    for x in masks:
        m |= x
    return m


def mask_of(bores: Iterable[str]) -> int:
    return _union(BIT[b] for b in bores)


def bores_in(mask: int) -> list[str]:
    return [b for b in BORES if mask & BIT[b]]


def gear_center(family: str, n: int, N: int) -> float:
    """Center distance of a gear pair: d = (N + n)/(2p), p the diametral pitch (ratio_distance (76))."""
    return (n + N) / (2 * pitch_si(FAMILIES[family].pitch))


@lru_cache(maxsize=65536)
def loop_links(
    family: str, n1: int, n2: int, lo: float | None, hi: float | None, belt_teeth: tuple[int, ...]
) -> int | None:
    """The shortest belt (stocked lengths) or chain (even links) whose center distance is at
    least lo and at least the touching-pitch-circles distance r_1 + r_2, and at most hi: its
    links or belt teeth, or None if there is none. Only the forward length equation is needed
    (the length grows with the center distance), so the search never loads scipy.

    Length from center: the exact open-drive length of chain_belt (68, corrected); pitch radii
    n·p/(2π) (65) for belt and chain alike (chain_belt.py).
    """
    from ..calculators.chain_belt import length_from_center, pitch_radius

    p = pitch_si(FAMILIES[family].pitch)
    r1, r2 = pitch_radius(n1, p, "circumference"), pitch_radius(n2, p, "circumference")
    d_low = max(lo or 0.0, r1 + r2)  # pitch circles must not overlap (clearance (67) ≥ 0)
    if hi is not None and hi < d_low:
        return None
    need = length_from_center(d_low, r1, r2) / p  # links or belt teeth at the lowest distance
    top = math.inf if hi is None else length_from_center(hi, r1, r2) / p
    if FAMILIES[family].kind == "chain":
        links = 2 * math.ceil(need / 2 - 1e-9)  # whole chain, no half (offset) link
    else:
        links = next((t for t in belt_teeth if t >= need - 1e-9), None)
    if links is None or links > top + 1e-9:
        return None
    return links


def loop_choice(
    family: str, n1: int, n2: int, lo: float | None, hi: float | None, belt_teeth: tuple[int, ...]
) -> tuple[int, float] | None:
    """loop_links and the center distance it gives (chain_belt's inverse of (68)), or None."""
    from ..calculators.chain_belt import center_from_length, pitch_radius

    links = loop_links(family, n1, n2, lo, hi, belt_teeth)
    if links is None:
        return None
    p = pitch_si(FAMILIES[family].pitch)
    r1, r2 = pitch_radius(n1, p, "circumference"), pitch_radius(n2, p, "circumference")
    excess = (links - max(n1, n2)) * p / 2  # exact (chain_belt.compute)
    return links, center_from_length(links * p, r1, r2, excess)


def stage_classes(q: Query, cat: Catalogue | None = None) -> list[Stage]:
    """Every stage the filters allow, grouped into classes."""
    cat = cat or catalogue()
    allowed_shaft = mask_of(q.shaft_bores)
    motor_bit = BIT[q.input_bore]
    reducing = q.target >= 1  # every stage turns the same way as the whole: no up-then-down trains
    belt_teeth = belt_lengths(q, cat)

    # teeth -> {bore mask, parts} per family, for driving (any allowed bore, and the motor's) and
    # driven (made shafts only)
    by_family: dict[str, dict[int, list[Part]]] = {}
    for part in cat.parts:
        if part.vendor not in q.vendors or part.family not in q.families:
            continue
        if not q.min_teeth <= part.teeth <= q.max_teeth:
            continue
        bit = BIT[part.bore]
        if not (bit & allowed_shaft or part.bore == q.input_bore):
            continue
        by_family.setdefault(part.family, {}).setdefault(part.teeth, []).append(part)

    # members of a class as (family, driving teeth, driven teeth): a Stage is made for the one that
    # shows the class; each teeth count's parts are filtered once, not once per pair (the classes
    # are most of the ratio finder's first solve after the catalogue's read)
    members: dict[tuple, list[tuple[str, int, int]]] = {}
    drivers: dict[str, dict[int, tuple[Part, ...]]] = {}  # family -> teeth -> driving parts
    takers: dict[str, dict[int, tuple[Part, ...]]] = {}  # family -> teeth -> driven parts
    for family, table in by_family.items():
        kind = FAMILIES[family].kind
        drive = {t: mask_of(p.bore for p in ps) & (allowed_shaft | motor_bit) for t, ps in table.items()}
        driven = {t: mask_of(p.bore for p in ps) & allowed_shaft for t, ps in table.items()}
        drivers[family] = {
            t: tuple(p for p in ps if BIT[p.bore] & (allowed_shaft | motor_bit)) for t, ps in table.items()
        }
        takers[family] = {t: tuple(p for p in ps if BIT[p.bore] & allowed_shaft) for t, ps in table.items()}
        # the positions (bits) sharing each center-distance limit: one stage_fits per pair and limit
        bits: dict = {}
        for i in range(q.max_stages):
            limit = q.center_limits[i] if i < len(q.center_limits) else None
            bits[limit] = bits.get(limit, 0) | 1 << i
        outs = [t for t in table if driven[t]]
        # the pairs of itertools.permutations(table, 2), in its order, that drive and are driven
        for n_in in (t for t in table if drive[t]):
            for n_out in outs:
                if n_out == n_in or (n_out > n_in) != reducing:
                    continue
                positions = 0
                for limit, bit in bits.items():
                    if stage_fits(family, kind, n_in, n_out, limit, belt_teeth):
                        positions |= bit
                if not positions:
                    continue
                parts = 2 if kind == "gear" else 3  # two gears; or two pulleys/sprockets and the loop
                g = math.gcd(n_in, n_out)  # the reduced ratio as ints: hashing Fractions was slow
                key = (family, n_out // g, n_in // g, parts, drive[n_in], driven[n_out], positions)
                members.setdefault(key, []).append((family, n_in, n_out))

    classes = []
    ratios: dict[tuple[int, int], Fraction] = {}  # one Fraction per ratio: classes share them
    for (family, num, den, parts, drive_mask, out_mask, positions), group in members.items():
        # the member sold by the most vendors' parts, then the smaller pair
        group.sort(key=lambda m: (-(len(drivers[m[0]][m[1]]) + len(takers[m[0]][m[2]])), m[1] + m[2], m[1]))
        _, n_in, n_out = group[0]
        ratio = ratios.get((num, den))
        if ratio is None:
            ratio = ratios[(num, den)] = Fraction(num, den)
        best = Stage(
            family,
            n_in,
            n_out,
            ratio,
            parts,
            drive_mask,
            out_mask,
            positions,
            drivers[family][n_in],
            takers[family][n_out],
        )
        best.alternatives = [(a, b) for _, a, b in group[1:]]
        classes.append(best)

    if "planetary" in q.families and reducing:  # each stack its own class (systems are unique)
        for system in cat.planetaries:
            if system.vendor not in q.vendors:
                continue
            inputs = mask_of(system.input_bores) & (allowed_shaft | motor_bit)
            outputs = mask_of(system.output_bores) & allowed_shaft
            if not inputs or not outputs:
                continue
            ordered = sorted(system.cartridges, key=lambda c: c.ratio, reverse=True)
            for count in range(1, system.max_cartridges + 1):
                # largest reduction nearest the motor, as REV advises for its stacks
                for stack in itertools.combinations_with_replacement(ordered, count):
                    ratio = math.prod((c.ratio for c in stack), start=Fraction(1))
                    classes.append(
                        Stage(
                            "planetary",
                            0,
                            0,
                            ratio,
                            PLANETARY_PARTS_BASE + count,
                            inputs,
                            outputs,
                            (1 << q.max_stages) - 1,
                            cartridges=stack,
                            system=system,
                        )
                    )
    return classes


def belt_lengths(q: Query, cat: Catalogue) -> dict[str, tuple[int, ...]]:
    """Stocked belt lengths (teeth) per belt family, from the allowed vendors (all vendors if
    those sell none of that family)."""
    out = {}
    for family, fam in FAMILIES.items():
        if fam.kind != "belt":
            continue
        mine = sorted({b.teeth for b in cat.belts if b.family == family and b.vendor in q.vendors})
        out[family] = tuple(mine or sorted({b.teeth for b in cat.belts if b.family == family}))
    return out


def stage_fits(family: str, kind: str, n_in: int, n_out: int, limits, belt_teeth) -> bool:
    lo, hi = limits if limits else (None, None)
    if kind == "gear":
        if limits is None:
            return True
        c = gear_center(family, n_in, n_out)
        return (lo is None or c >= lo * (1 - 1e-12)) and (hi is None or c <= hi * (1 + 1e-12))
    small, large = sorted((n_in, n_out))
    return loop_links(family, small, large, lo, hi, belt_teeth.get(family, ())) is not None


# --- searching ---------------------------------------------------------------------------------


def exact(x: float) -> Fraction:
    """A typed number as the decimal it was written as (0.37 is 37/100, not the binary float)."""
    return Fraction(repr(x))


def ratio_error(num: int, den: int, lo: Fraction, hi: Fraction) -> float:
    """Distance of num/den from [lo, hi], in exact integers, rounded once (plain ints: Fraction
    arithmetic made the search five times slower)."""
    a, b = lo.numerator, lo.denominator
    if num * b < a * den:
        return (a * den - num * b) / (den * b)
    a, b = hi.numerator, hi.denominator
    if num * b > a * den:
        return (num * b - a * den) / (den * b)
    return 0.0


def rank_key(c: Combination, q: Query) -> tuple:
    # within equal error, stages and parts: nearer the middle of a range, then a fixed order
    middle = abs(math.log(c.num / c.den / q.target))
    return (
        c.error,
        len(c.stages),
        c.parts,
        middle,
        tuple((-s.ratio, s.family, s.teeth_in) for s in c.stages),
    )


@dataclass
class Table:
    """Stage classes usable at one position, by ratio value: sorted distinct values, the classes
    of each, and the fewest parts among them (a lower bound used to stop expanding early)."""

    values: object  # numpy array
    members: list[list[Stage]]
    fewest_parts: object  # numpy array
    drive_union: object = None  # numpy arrays: bores any class of the value drives from / drives onto
    out_union: object = None


WINDOW_CAP = 250_000  # value tuples held at once (about 25 MB of index arrays)


@dataclass
class Prepared:
    classes: list[Stage]
    tables: dict  # (position, fits the motor, fits the output) -> Table


_PREPARED: dict = {}


def prepare(q: Query, cat: Catalogue | None = None) -> Prepared:
    """Stage classes and value tables; they do not depend on the wanted ratio (only on whether
    it is a reduction), so typing a new ratio reuses them."""
    key = (
        q.target >= 1,
        q.input_bore,
        q.output_bore,
        q.vendors,
        q.families,
        q.shaft_bores,
        q.min_teeth,
        q.max_teeth,
        q.max_stages,
        q.center_limits,
        id(cat),
    )
    if key not in _PREPARED:
        if len(_PREPARED) > 16:
            _PREPARED.clear()
        _PREPARED[key] = Prepared(stage_classes(q, cat), {})
    return _PREPARED[key]


def table(prep: Prepared, q: Query, position: int, first: bool, last: bool) -> Table:
    """The classes allowed at a position; on the motor shaft only those that fit the motor, and
    as the last stage only those that fit the output."""
    import numpy as np

    key = (position, first, last)
    if key not in prep.tables:
        motor = BIT[q.input_bore]
        output = BIT[q.output_bore] if q.output_bore != "any" else mask_of(q.shaft_bores)
        by_value: dict[float, list[Stage]] = {}
        for s in prep.classes:
            if not s.positions >> position & 1:
                continue
            if (first and not s.drive_mask & motor) or (last and not s.out_mask & output):
                continue
            by_value.setdefault(s.ratio_f, []).append(s)
        ordered = sorted(by_value)
        prep.tables[key] = Table(
            np.array(ordered, dtype=float),
            [by_value[v] for v in ordered],
            np.array([min(s.parts for s in by_value[v]) for v in ordered], dtype=np.int64),
        )
    return prep.tables[key]


def pruned_table(prep: Prepared, q: Query, position: int, k: int) -> Table:
    """table() for position of k stages, keeping only the classes that some feasible chain of
    bores passes through: a driving bore reachable from the motor through the stages before,
    and a driven bore from which the stages after reach the output. Exact per class: with one
    bore per shaft chosen freely, a class lies on a feasible chain iff both hold."""
    import numpy as np

    key = ("pruned", position, k)
    if key not in prep.tables:
        base = [[s for m in table(prep, q, i, i == 0, i == k - 1).members for s in m] for i in range(k)]
        all_shafts = mask_of(q.shaft_bores)
        ahead = [BIT[q.input_bore]]  # bores reachable on the shaft before each position
        for i in range(k - 1):
            fits = ahead[i] if (i == 0 or q.same_shaft_bore) else all_shafts
            ahead.append(_union(s.out_mask for s in base[i] if s.drive_mask & fits))
        behind = [0] * k + [BIT[q.output_bore] if q.output_bore != "any" else all_shafts]
        for i in range(k - 1, -1, -1):  # bores after each position from which the output is reached
            behind[i] = _union(s.drive_mask for s in base[i] if s.out_mask & behind[i + 1])
            if i > 0 and not q.same_shaft_bore and behind[i]:
                behind[i] = all_shafts
        for i in range(k):
            fits = ahead[i] if (i == 0 or q.same_shaft_bore) else all_shafts
            by_value: dict[float, list[Stage]] = {}
            for s in base[i]:
                if s.drive_mask & fits and s.out_mask & behind[i + 1]:
                    by_value.setdefault(s.ratio_f, []).append(s)
            ordered = sorted(by_value)
            groups = [by_value[v] for v in ordered]
            prep.tables[("pruned", i, k)] = Table(
                np.array(ordered, dtype=float),
                groups,
                np.array([min(s.parts for s in g) for g in groups], dtype=np.int64),
                np.array([_union(s.drive_mask for s in g) for g in groups], dtype=np.int64),
                np.array([_union(s.out_mask for s in g) for g in groups], dtype=np.int64),
            )
    return prep.tables[key]


def reach(prep: Prepared, q: Query) -> tuple[Fraction, Fraction] | None:
    """The smallest and the largest ratio of any combination of 1 to q.max_stages stages that can
    be assembled (bores, stage positions and the output included), exactly; None if there is none.

    Dynamic programming over the bore of each shaft: with one bore chosen per shaft, the extreme
    ratio that reaches a shaft in bore b after stage i is the extreme over the classes whose driven
    part comes in b of (their ratio) × (the extreme reaching a bore their driving part comes in);
    every ratio is positive, so extremes multiply. Classes alike in bores and position are taken
    together (their least and greatest ratio), which keeps this to a few dozen groups per stage.
    (Tables of the largest value per position ignore how bores chain: 20 DP gears alone reach
    592.7:1 that way, 302.4:1 in fact, since only motor pinions go down to 10 teeth.)"""
    key = ("reach",)
    if key not in prep.tables:
        all_shafts = mask_of(q.shaft_bores)
        out_mask = BIT[q.output_bore] if q.output_bore != "any" else all_shafts
        # (drive mask, out mask, positions) -> [least, greatest ratio] of the classes alike in them
        extremes: dict[tuple[int, int, int], list[Fraction]] = {}
        for s in prep.classes:
            g = extremes.get((s.drive_mask, s.out_mask, s.positions))
            if g is None:
                extremes[(s.drive_mask, s.out_mask, s.positions)] = [s.ratio, s.ratio]
            elif s.ratio_f <= float(g[0]) or s.ratio_f >= float(g[1]):  # exact only when it may matter
                g[0], g[1] = min(g[0], s.ratio), max(g[1], s.ratio)
        state = {BIT[q.input_bore]: (Fraction(1), Fraction(1))}  # bore bit -> (least, greatest)
        least = most = None
        for i in range(q.max_stages):
            after: dict[int, tuple[Fraction, Fraction]] = {}
            for (drive, out, positions), (low, high) in extremes.items():
                if not positions >> i & 1:
                    continue
                if i == 0 or q.same_shaft_bore:
                    came = [v for bit, v in state.items() if bit & drive]
                else:  # any made shaft is adapted to the next part
                    came = list(state.values()) if drive & all_shafts else []
                if not came:
                    continue
                a = min(v[0] for v in came) * low
                b = max(v[1] for v in came) * high
                for bit in (BIT[x] for x in bores_in(out)):
                    old = after.get(bit)
                    after[bit] = (a, b) if old is None else (min(old[0], a), max(old[1], b))
            state = after
            for bit, (a, b) in state.items():
                if bit & out_mask:
                    least = a if least is None else min(least, a)
                    most = b if most is None else max(most, b)
            if not state:
                break
        prep.tables[key] = None if least is None else (least, most)
    return prep.tables[key]


def search(q: Query, cat: Catalogue | None = None) -> tuple[list[Combination], dict]:
    """The best q.results combinations, ranked; and counts for the user (how much was searched)."""
    import numpy as np

    prep = prepare(q, cat)
    stats = {"stage_classes": len(prep.classes), "checked": 0}
    keys: dict[tuple, tuple] = {}  # identity -> (float error, stages, parts) of what found holds
    n_best = q.results
    found: dict[tuple, Combination] = {}  # order-free identity -> its best order
    top: list[tuple] = []  # (key, serial, identity) of the N best keys, sorted
    in_top: dict[tuple, tuple] = {}
    serial = itertools.count()
    all_shafts = mask_of(q.shaft_bores)
    out_mask = BIT[q.output_bore] if q.output_bore != "any" else all_shafts

    lo_x, hi_x = exact(q.ratio_min), exact(q.ratio_max)

    def consider(stages: tuple[Stage, ...], masks: tuple[int, ...]) -> None:
        stats["checked"] += 1
        num = den = 1
        for s in stages:
            num *= s.ratio.numerator
            den *= s.ratio.denominator
        combo = Combination(
            stages, num, den, ratio_error(num, den, lo_x, hi_x), sum(s.parts for s in stages), masks
        )
        ident = tuple(sorted(s.identity for s in stages))
        old = found.get(ident)
        if old is None or rank_key(combo, q) < rank_key(old, q):
            found[ident] = combo
            key = (combo.error, len(stages), combo.parts, abs(math.log(num / den / q.target)))
            keys[ident] = key
            # the N best keys, kept sorted (an identity's key only ever decreases)
            if ident in in_top:
                top.remove(in_top[ident])
            elif len(top) == n_best and not key < top[-1][0]:
                return
            entry = in_top[ident] = (key, next(serial), ident)
            bisect.insort(top, entry)
            if len(top) > n_best:
                del in_top[top.pop()[2]]

    def expand(lists: list[list[Stage]]) -> None:
        """Every assembly of one class per position whose bores chain (depth first, pruned)."""
        k = len(lists)

        def down(i: int, shaft: int, acc: tuple, masks: tuple) -> None:
            if i == k:
                if shaft & out_mask:
                    consider(acc, masks)
                return
            fits = shaft if (i == 0 or q.same_shaft_bore) else all_shafts
            for s in lists[i]:
                if s.drive_mask & fits:
                    down(i + 1, s.out_mask, acc + (s,), masks + (s.out_mask,))

        down(0, BIT[q.input_bore], (), ())

    def nth_key() -> tuple | None:
        if len(found) < n_best:
            return None
        e, stages, parts, middle = top[n_best - 1][0]  # as sorted(keys.values())[n_best - 1]
        return (e, stages, parts, round(e / tie), middle)

    # one stage: exhaustive
    for members in table(prep, q, 0, True, True).members:
        expand([members])

    lo_t, hi_t = q.ratio_min, q.ratio_max
    tie = 1e-12 * max(1.0, hi_t)
    log_t = math.log(q.target)

    def scan(chosen: list[Table], tail, intervals: list[tuple[float, float]], k: int) -> None:
        """Expand the value tuples whose product lies in the intervals, best first within each
        slice of at most WINDOW_CAP tuples; a slice stops at the current N-th best (it is sorted
        by error, fewest parts and distance to the middle, the rank's own order)."""
        first = chosen[0].values
        for rows, at in _slices(first, tail[0], intervals, np):
            index = [rows] + [f[at] for f in tail[1]]
            ok = np.ones(rows.size, dtype=bool)  # some class of each value chains to the next
            for i in range(k - 1):
                ok &= (chosen[i].out_union[index[i]] & chosen[i + 1].drive_union[index[i + 1]]) != 0
            index = [ix[ok] for ix in index]
            r = first[index[0]] * tail[0][at[ok]]
            errors = np.maximum(np.maximum(lo_t - r, r - hi_t), 0.0)
            parts = sum(chosen[i].fewest_parts[index[i]] for i in range(k))
            grid = np.round(errors / tie)
            middle = np.abs(np.log(r) - log_t)
            order = np.lexsort((middle, parts, grid))
            for n, j in enumerate(order):
                if n % 32 == 0 and n:
                    limit = nth_key()
                    if limit is not None and (int(grid[j]), k, int(parts[j]), middle[j] - 1e-9) > (
                        limit[3],
                        limit[1],
                        limit[2],
                        limit[4],
                    ):
                        break
                expand([chosen[i].members[index[i][j]] for i in range(k)])

    def capped(k: int) -> None:
        """k stages on tables pruned to classes that some feasible bore chain passes through,
        windows grown so that no slice holds more than WINDOW_CAP value tuples (bounded memory),
        and a wide range searched outward from its middle first (bounded time)."""
        chosen = [pruned_table(prep, q, i, k) for i in range(k)]
        if any(len(t.values) == 0 for t in chosen):
            return
        tail = tail_table(prep, q, k, np, chosen)
        first = chosen[0].values
        lowest = math.prod(float(t.values[0]) for t in chosen)
        highest = math.prod(float(t.values[-1]) for t in chosen)
        worst = max(lo_t - lowest, hi_t - lowest, highest - lo_t, highest - hi_t, 0.0)
        least_parts = sum(int(t.fewest_parts.min()) for t in chosen)
        # 1. inside a range: outward from its (geometric) middle, while the N best all have no
        # error, k stages or fewer and the fewest parts possible (nothing farther can beat them)
        if hi_t > lo_t:
            rho = 1.0 + 1e-3
            while True:
                a, b = max(lo_t, q.target / rho), min(hi_t, q.target * rho)
                covered = a <= lo_t and b >= hi_t
                if not covered and _count_within(first, tail[0], a, b, np) < 8 * n_best:
                    rho *= rho
                    continue
                scan(chosen, tail, [(a, b)], k)
                now = nth_key()
                if (
                    now is not None
                    and now[0] == 0
                    and (
                        now[1] < k
                        or now[2] < least_parts
                        or (now[2] == least_parts and now[4] <= math.log(rho))
                    )
                ):
                    return
                if covered:
                    if now is not None and now[0] == 0:
                        return  # every tuple inside the range was seen; outside ones have an error
                    break
                rho *= rho
            done = (lo_t, hi_t)
        else:
            done = None
        # 2. error windows |G − G*| ≤ eps, grown until the N-th best is inside (as search())
        nearest = _nearest_errors(first, tail, lo_t, hi_t, np)
        m = min(4 * n_best, nearest.size) - 1
        eps = float(np.partition(nearest, m)[m])
        bound = nth_key()
        if bound is not None:
            eps = min(eps, bound[0])
        while True:
            window = eps + tie
            lo_w, hi_w = lo_t - window, hi_t + window
            if done is None:
                intervals = [(lo_w, hi_w)]
            else:  # the range itself was scanned whole above: its two sides only
                intervals = [(lo_w, math.nextafter(lo_t, -math.inf)), (math.nextafter(hi_t, math.inf), hi_w)]
            scan(chosen, tail, intervals, k)
            now = nth_key()
            if (now is not None and now[0] <= eps) or eps > worst:
                return
            eps = grown(eps, first, tail[0], 4 * _count_within(first, tail[0], lo_w, hi_w, np) + 64 * n_best)

    def grown(eps: float, first, products, most: int) -> float:
        """The next window: four times wider, or less if that would hold more than `most` tuples
        (an out-of-reach target would jump to the whole catalogue at once)."""
        wide = eps * 4 + 1e-6 * max(1.0, hi_t)

        def count(e):
            return _count_within(first, products, lo_t - e - tie, hi_t + e + tie, np)

        if count(wide) <= most:
            return wide
        narrow = eps
        for _ in range(60):  # bisection: the count grows with the window
            mid = (narrow + wide) / 2
            if count(mid) <= most:
                narrow = mid
            else:
                wide = mid
        return wide if narrow <= eps else narrow

    # float products of equal exact ratios differ by rounding only
    for k in range(2, q.max_stages + 1):
        chosen = [table(prep, q, i, i == 0, i == k - 1) for i in range(k)]
        tables = [t.values for t in chosen]
        if any(len(v) == 0 for v in tables):
            break
        bound = nth_key()
        if bound is not None and bound[0] == 0:
            break  # k stages cannot beat N exact (or in-range) combinations with fewer stages
        # start from the (4N)-th best nearest error: orders of the same stages and infeasible bores
        # make fewer combinations than value tuples, and every regrowth repeats the pass
        spare = 4 * n_best
        tail = tail_table(prep, q, k, np)
        nearest = _nearest_errors(tables[0], tail, lo_t, hi_t, np)
        if nearest.size == 0:
            continue
        # the largest error any k-stage tuple can have: past it, every tuple has been enumerated
        lowest = math.prod(float(v[0]) for v in tables)
        highest = math.prod(float(v[-1]) for v in tables)
        worst = max(lo_t - lowest, highest - hi_t, 0.0)
        m = min(spare, nearest.size) - 1
        eps = float(np.partition(nearest, m)[m])
        if bound is not None:
            eps = min(eps, bound[0])
        for _ in range(60):
            window = eps + tie
            if _count_within(tables[0], tail[0], lo_t - window, hi_t + window, np) > WINDOW_CAP:
                # bores make most value tuples here infeasible (or a wide range holds millions):
                # search again on bore-pruned tables, a bounded slice at a time
                capped(k)
                break
            index, errors = _tuples_within(tables[0], tail, lo_t - window, hi_t + window, lo_t, hi_t, np)
            parts = sum(chosen[i].fewest_parts[index[i]] for i in range(k))
            grid = np.round(errors / tie)  # ties in exact error compare equal
            order = np.lexsort((parts, grid))
            for n, j in enumerate(order):
                if n % 32 == 0 and n:
                    limit = nth_key()
                    # sorted by (error, fewest parts): once past the N-th best, nothing better follows
                    if limit is not None and (int(grid[j]), k, int(parts[j])) > (
                        limit[3],
                        limit[1],
                        limit[2],
                    ):
                        break
                lists = [chosen[i].members[index[i][j]] for i in range(k)]
                expand(lists)
            now = nth_key()
            # every k-stage combination within eps is found; the N best are final once the N-th
            # best error is within eps (anything not yet found is worse)
            if (now is not None and now[0] <= eps) or eps > worst:
                break
            eps = eps * 4 + 1e-6 * max(1.0, hi_t)
    ranked = sorted(found.values(), key=lambda c: rank_key(c, q))
    stats["feasible"] = len(found)
    return ranked[:n_best], stats


def tail_table(prep: Prepared, q: Query, k: int, np, chosen: list[Table] | None = None):
    """The positions after the first, as one sorted array of products and the index of each
    factor: for two stages the last table itself; for three, every product of the middle and
    last tables, sorted once per filter setting (meet in the middle: a new ratio then costs a
    bisection per first-stage value). chosen: other tables than table()'s (the pruned ones)."""
    key = ("tail", k) if chosen is None else ("pruned tail", k)
    if key not in prep.tables:
        last = (chosen[k - 1] if chosen else table(prep, q, k - 1, False, True)).values
        if k == 2:
            prep.tables[key] = (last, [np.arange(last.size)])
        else:
            middle = (chosen[1] if chosen else table(prep, q, 1, False, False)).values
            products = np.multiply.outer(middle, last).ravel()
            order = np.argsort(products)  # introsort: 4x faster than the stable sorts here
            prep.tables[key] = (products[order], [order // last.size, order % last.size])
    return prep.tables[key]


def _nearest_errors(first, tail, lo: float, hi: float, np):
    """For each first-stage value, the error of the nearest tail product."""
    products = tail[0]
    idx = np.searchsorted(products, (lo + hi) / 2 / first)
    best = None
    for j in (np.clip(idx - 1, 0, products.size - 1), np.clip(idx, 0, products.size - 1)):
        r = first * products[j]
        err = np.maximum(np.maximum(lo - r, r - hi), 0.0)
        best = err if best is None else np.minimum(best, err)
    return best


def _tuples_within(first, tail, lo: float, hi: float, r_lo: float, r_hi: float, np):
    """Every tuple of values (one per position) whose product lies in [lo, hi]: index arrays (one
    per position) and each tuple's error."""
    products, factors = tail
    start = np.searchsorted(products, lo / first, side="left")
    stop = np.searchsorted(products, hi / first, side="right")
    counts = np.maximum(stop - start, 0)
    rows = np.repeat(np.arange(first.size), counts)
    at = start[rows] + np.arange(rows.size) - np.repeat(np.cumsum(counts) - counts, counts)
    r = first[rows] * products[at]
    errors = np.maximum(np.maximum(r_lo - r, r - r_hi), 0.0)
    return [rows] + [f[at] for f in factors], errors


def _count_within(first, products, lo: float, hi: float, np) -> int:
    """How many value tuples have their product in [lo, hi] (no tuple is built)."""
    start = np.searchsorted(products, lo / first, side="left")
    stop = np.searchsorted(products, hi / first, side="right")
    return int(np.maximum(stop - start, 0).sum())


def _slices(first, products, intervals, np):
    """The value tuples whose product lies in one of the intervals, as (first-stage index, tail
    index) arrays of at most WINDOW_CAP tuples each (a first-stage row split where it must)."""
    rows, starts, counts = [], [], []
    for lo, hi in intervals:
        if hi < lo:
            continue
        start = np.searchsorted(products, lo / first, side="left")
        stop = np.searchsorted(products, hi / first, side="right")
        count = np.maximum(stop - start, 0)
        pieces = -(-count // WINDOW_CAP)  # ceil: a row with more than the cap is cut in pieces
        row = np.repeat(np.arange(first.size), pieces)
        piece = np.arange(row.size) - np.repeat(np.cumsum(pieces) - pieces, pieces)
        begin = start[row] + piece * WINDOW_CAP
        rows.append(row)
        starts.append(begin)
        counts.append(np.minimum(stop[row] - begin, WINDOW_CAP))
    if not rows:
        return
    row, begin, count = np.concatenate(rows), np.concatenate(starts), np.concatenate(counts)
    total = np.cumsum(count)
    cut = 0
    while cut < row.size:
        end = int(np.searchsorted(total, (total[cut - 1] if cut else 0) + WINDOW_CAP, side="right"))
        end = max(end, cut + 1)
        r, b, c = row[cut:end], begin[cut:end], count[cut:end]
        offsets = np.arange(int(c.sum())) - np.repeat(np.cumsum(c) - c, c)
        yield np.repeat(r, c), np.repeat(b, c) + offsets
        cut = end
