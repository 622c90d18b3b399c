"""The catalogue of purchasable power-transmission parts, read from the TOML files beside this one.

gears.toml, pulleys.toml, sprockets.toml and belts.toml list toothed parts by vendor and family;
planetaries.toml lists cartridge gearbox systems. Each file says where its figures come from.
`catalogue()` reads them once (tomllib, ~30 ms, at the ratio finder's first solve) and checks them;
`problems()` lists what is wrong with a catalogue (unknown family, bore, pitch or vendor,
duplicates), for the tests.

The records are named tuples, not dataclasses: the ratio finder's card imports this module for its
choices (FAMILIES, BORES, VENDORS) on the UI thread, where each dataclass took ~1 ms to create
(seven of them, with tomllib, 13 ms of the card's first visit), and ~1100 parts read as tuples of
strings and numbers are left alone by the garbage collector. (No `from __future__ import
annotations` here: NamedTuple compiles each field's annotation when it is a string, 8 ms for these.)
"""

from fractions import Fraction
from functools import lru_cache
from pathlib import Path
from typing import NamedTuple

from ..constants import INCH as IN

HERE = Path(__file__).parent

MM = 1e-3


class Family(NamedTuple):
    label: str
    kind: str  # gear, belt, chain or planetary
    pitch: str  # as written in the catalogue: "20 DP" (diametral) or a circular pitch "5 mm"
    standard: str = ""  # the chain_belt calculator's pitch_standard for belts and chains


FAMILIES: dict[str, Family] = {
    "gear_20dp": Family("20 DP gear", "gear", "20 DP"),
    "gear_32dp": Family("32 DP gear", "gear", "32 DP"),
    "htd_5mm": Family("HTD 5 mm belt", "belt", "5 mm", "htd_5mm"),
    "gt2_3mm": Family("GT2 3 mm belt", "belt", "3 mm", "gt2_3mm"),
    "rt25": Family("RT25 belt", "belt", "0.25 in", "rt25"),
    "chain_25": Family("#25 chain", "chain", "0.25 in", "chain_25"),
    "chain_35": Family("#35 chain", "chain", "0.375 in", "chain_35"),
    "planetary": Family("planetary", "planetary", ""),
}


class Bore(NamedTuple):
    label: str
    motor: bool  # a motor's own shaft: such a part can only sit on the motor
    fits: str = ""  # the motors with that shaft, for the motor-shaft choice

    @property
    def choice_label(self) -> str:
        return f"{self.label} ({self.fits})" if self.fits else self.label


BORES: dict[str, Bore] = {
    "hex_half_in": Bore("1/2 in hex", False),
    "hex_3_8_in": Bore("3/8 in hex", False),
    "round_1125_in": Bore("1.125 in round", False, "bearing bore"),
    "maxspline": Bore("MAXSpline", False),
    "splinexl": Bore("SplineXL", False),
    "hex_5mm": Bore("5 mm hex", False),
    "round_quarter_in": Bore("1/4 in round", False),
    "keyed_8mm": Bore("8 mm keyed", True, "NEO, CIM"),
    "falcon": Bore("Falcon spline", True, "Falcon 500, Kraken X60"),
    "splinexs": Bore("SplineXS", True, "Kraken X44, Minion"),
    "vortex": Bore("Vortex shaft", True, "NEO Vortex"),
    "shaft_775": Bore("775 motor shaft", True),
    "shaft_550": Bore("550 motor shaft", True),
    "shaft_bag": Bore("BAG motor shaft", True),
}
SHAFT_BORES = tuple(k for k, b in BORES.items() if not b.motor)

VENDORS: dict[str, str] = {
    "REV": "REV Robotics",
    "WCP": "WestCoast Products",
    "AndyMark": "AndyMark",
    "Thrifty": "The Thrifty Bot (TTB)",
    "SDS": "Swerve Drive Specialties",
    "LastAnvil": "Last Anvil",
    "VEX": "VEX Robotics (VEXpro)",
}


def pitch_si(text: str) -> float:
    """'20 DP' -> diametral pitch in 1/m; '5 mm' or '0.25 in' -> circular pitch in m."""
    number, _, unit = text.partition(" ")
    scale = {"DP": 1 / IN, "mm": MM, "in": IN}[unit]
    return float(number) * scale


class Part(NamedTuple):
    """A gear, pulley or sprocket."""

    vendor: str
    part_number: str
    family: str
    teeth: int
    bore: str
    url: str
    width_mm: float | None = None

    @property
    def name(self) -> str:
        return self.part_number or f"{self.vendor} {self.teeth}T {BORES[self.bore].label}"


class Belt(NamedTuple):
    vendor: str
    part_number: str
    family: str
    teeth: int
    url: str
    width_mm: float | None = None


class Cartridge(NamedTuple):
    name: str
    part_number: str
    ratio: Fraction


class PlanetarySystem(NamedTuple):
    system: str
    vendor: str
    part_number: str
    url: str
    max_cartridges: int
    input_bores: tuple[str, ...]
    output_bores: tuple[str, ...]
    cartridges: tuple[Cartridge, ...]


class Catalogue(NamedTuple):
    parts: tuple[Part, ...]
    belts: tuple[Belt, ...]
    planetaries: tuple[PlanetarySystem, ...]
    pitches: dict  # (file, vendor, family) -> pitch text as written, for the checks


def _read(name: str) -> dict:
    import tomllib  # here: the card's description needs none of it

    with open(HERE / f"{name}.toml", "rb") as fh:
        return tomllib.load(fh)


def read() -> Catalogue:
    """The catalogue as the files hold it (unchecked)."""
    parts, belts, pitches = [], [], {}
    for name in ("gears", "pulleys", "sprockets", "belts"):
        for group in _read(name).get(name, []):
            vendor, family = group["vendor"], group["family"]
            pitches[(name, vendor, family)] = group["pitch"]
            for p in group["parts"]:
                if name == "belts":
                    belts.append(
                        Belt(vendor, p["part_number"], family, p["teeth"], p["url"], p.get("width_mm"))
                    )
                else:
                    parts.append(
                        Part(
                            vendor,
                            p["part_number"],
                            family,
                            p["teeth"],
                            p["bore"],
                            p["url"],
                            p.get("width_mm"),
                        )
                    )
    planetaries = []
    for s in _read("planetaries").get("planetaries", []):
        planetaries.append(
            PlanetarySystem(
                s["system"],
                s["vendor"],
                s["part_number"],
                s["url"],
                s["max_cartridges"],
                tuple(s["input_bores"]),
                tuple(s["output_bores"]),
                tuple(
                    Cartridge(c["name"], c["part_number"], Fraction(c["num"], c["den"]))
                    for c in s["cartridges"]
                ),
            )
        )
    return Catalogue(tuple(parts), tuple(belts), tuple(planetaries), pitches)


def problems(cat: Catalogue) -> list[str]:
    """Everything inconsistent in a catalogue; empty when it is sound."""
    found = []
    for (file, vendor, family), pitch in cat.pitches.items():
        if family not in FAMILIES or FAMILIES[family].kind == "planetary":
            found.append(f"{file}: {vendor}: unknown family {family!r}")
            continue
        kind = FAMILIES[family].kind
        expected_kind = {"gears": "gear", "pulleys": "belt", "belts": "belt", "sprockets": "chain"}[file]
        if kind != expected_kind:
            found.append(f"{file}: {vendor}: {family} is a {kind} family, not a {expected_kind}")
        try:
            if abs(pitch_si(pitch) - pitch_si(FAMILIES[family].pitch)) > 1e-12 * pitch_si(
                FAMILIES[family].pitch
            ):
                found.append(
                    f"{file}: {vendor}: {family} has pitch {pitch!r}, not {FAMILIES[family].pitch!r}"
                )
        except (KeyError, ValueError):
            found.append(f"{file}: {vendor}: unreadable pitch {pitch!r}")
    seen_numbers: dict[tuple[str, str], object] = {}
    seen_parts: set = set()
    for item in (*cat.parts, *cat.belts):
        where = f"{item.vendor} {item.part_number or '(no part number)'}"
        if item.vendor not in VENDORS:
            found.append(f"{where}: unknown vendor")
        if item.family not in FAMILIES:
            found.append(f"{where}: unknown family {item.family!r}")
        elif isinstance(item, Belt) and FAMILIES[item.family].kind != "belt":
            found.append(f"{where}: a belt in the {FAMILIES[item.family].kind} family {item.family}")
        elif isinstance(item, Part) and FAMILIES[item.family].kind == "planetary":
            found.append(f"{where}: a toothed part in the planetary family")
        if not (isinstance(item.teeth, int) and 6 <= item.teeth <= 400):
            found.append(f"{where}: implausible tooth count {item.teeth!r}")
        if isinstance(item, Part) and item.bore not in BORES:
            found.append(f"{where}: unknown bore {item.bore!r}")
        if not item.url.startswith("https://"):
            found.append(f"{where}: url {item.url!r} is not an https address")
        whole = (
            type(item).__name__,
            item.vendor,
            item.part_number,
            item.family,
            item.teeth,
            getattr(item, "bore", ""),
            item.width_mm,
            item.url,
        )
        if whole in seen_parts:
            found.append(f"{where}: listed twice")
        seen_parts.add(whole)
        if item.part_number:
            key = (item.vendor, item.part_number)
            if key in seen_numbers and seen_numbers[key] != whole:
                found.append(f"{where}: one part number for two different parts")
            seen_numbers[key] = whole
    names = set()
    for s in cat.planetaries:
        if s.system in names:
            found.append(f"planetary {s.system}: listed twice")
        names.add(s.system)
        if s.vendor not in VENDORS:
            found.append(f"planetary {s.system}: unknown vendor {s.vendor!r}")
        for b in (*s.input_bores, *s.output_bores):
            if b not in BORES:
                found.append(f"planetary {s.system}: unknown bore {b!r}")
        if not 1 <= s.max_cartridges <= 4:
            found.append(f"planetary {s.system}: max_cartridges {s.max_cartridges} outside 1-4")
        ratios = [c.ratio for c in s.cartridges]
        if len(set(ratios)) != len(ratios):
            found.append(f"planetary {s.system}: two cartridges with one ratio")
        if any(r <= 1 for r in ratios):
            found.append(f"planetary {s.system}: a cartridge ratio is not a reduction")
    return found


@lru_cache(maxsize=1)
def catalogue() -> Catalogue:
    cat = read()
    wrong = problems(cat)
    if wrong:  # a broken data file is a bug in Gearhead, not a user error
        raise RuntimeError("parts catalogue: " + "; ".join(wrong[:5]))
    return cat
