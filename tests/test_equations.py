"""Every result row can say how it is obtained: each Output has a one-line `help`, and each output
that comes from an equation names it in `equation` (issue 15).

An equation is either the seed's number, "(12)", from seeds/003 (the AMB Design Spreadsheet
Equations, numbered (1)-(117)), or a label the calculator's own module docstring defines, "(EL3)",
for what the seed does not cover. Several are written "(61)-(64)" or "(14), (GR1)". The flywheel
(seeds/000, which numbers nothing) numbers the seed's equations (1)-(9) in its module docstring; the
trebuchet's seed (seeds/001) numbers its sections, not its equations, and is cited "§2.1, (T3)".
"""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

from gearhead.core.model import Calculator, Output
from gearhead.core.registry import calculators

HELP_MAX = 110  # characters: the help shows in one status line beside the equation

# seeds/003 numbers its equations (1)-(117). Which a calculator may cite: its section's, the
# appendix that derives them, and section 1's motor-system equations (1)-(10) and Appendix A
# (90)-(92), which every motor calculator builds on; section 9 reuses section 8's (69), (70).
SEED_TAGS = range(1, 118)
MOTOR = (*range(1, 11), *range(90, 93))
SECTION_EQUATIONS = {
    "1": MOTOR,
    "2": (*range(11, 29), *MOTOR),
    "3": (*range(29, 37), *range(93, 96)),
    "4": (*range(37, 43), *range(96, 103), *MOTOR),
    "5": range(43, 61),
    "6": (*range(61, 65), *range(103, 110)),
    "7": (*range(65, 69), *range(110, 114)),
    "8": range(69, 75),
    "9": (*range(69, 71), *range(75, 79)),
    "10": (*range(79, 84), *range(114, 118)),
    "11": range(84, 90),
}
# the seeds' text, copied into the repository from the project's shared/seeds (an absolute path
# outside it existed on no CI machine: these checks skipped there and could not fail)
SEEDS = Path(__file__).with_name("seeds")
SEED_FILE = SEEDS / "003_38524b71ccf9c8b1.txt"

# Calculators of the other seeds. Their numbers "(3)" are the module docstring's own (seeds/000 numbers
# no equations); a section of the seed is cited "§2.1" (seeds/001 numbers its sections 1.1-2.5).
OWN_NUMBERS = {"seed 000"}
SEED_SECTIONS = {"001": ("1", "1.1", "1.2", "1.3", "1.4", "1.5", "2", "2.1", "2.2", "2.3", "2.4", "2.5")}
SECTION_FILES = {"001": SEEDS / "001_0826cae8dd8b66ab.txt"}

# Outputs that report on the computation, not on the mechanism: they may have no equation.
BOOKKEEPING = {"error_estimate", "rhs_evaluations", "wall_time"}
BOOKKEEPING_OF = {
    "ratio_finder": {"stage_count", "part_count", "combinations"},  # counts
    "trebuchet": {"candidates"},  # throws evaluated by the optimiser
    "motors": {"motors_listed"},  # a count of the database
}

ITEM = r"(?:\(\w+\)|§\d+(?:\.\d+)?)"  # an equation "(12)", "(GR1)" or a seed section "§2.1"
EQUATION_FORM = re.compile(rf"{ITEM}(\s*[-–,/]\s*{ITEM})*")
LABEL = re.compile(r"\((\w+)\)")
SECTION_REF = re.compile(r"§(\d+(?:\.\d+)?)")


def module_doc(calc: Calculator) -> str:
    """The docstrings of the module that declares the calculator (core/calculators/<id>.py) and of
    the core.sim modules it imports (a scene's equations are numbered where they are coded)."""
    module = importlib.import_module(f"gearhead.core.calculators.{calc.id}")
    assert getattr(module, "CALCULATOR", None) is calc
    sims = {
        getattr(v, "__module__", None) if not isinstance(v, type(module)) else v.__name__
        for v in vars(module).values()
    }
    # and those its docstring names (core.sim.velocity_loop): a module the solve imports lazily
    sims |= {f"gearhead.{name}" for name in re.findall(r"\bcore\.sim\.\w+", module.__doc__ or "")}
    docs = [module.__doc__ or ""]
    docs += [
        importlib.import_module(name).__doc__ or ""
        for name in sorted(n for n in sims if n and n.startswith("gearhead.core.sim."))
    ]
    return "\n".join(docs)


def unknown_labels(calc: Calculator, out: Output) -> list[str]:
    """The labels in `out.equation` that name no equation the calculator may cite."""
    doc = module_doc(calc)
    allowed = set(SECTION_EQUATIONS.get(calc.section, ()))
    bad = []
    for label in LABEL.findall(out.equation):
        if label.isdigit() and calc.section not in OWN_NUMBERS:
            if int(label) not in allowed:
                bad.append(f"({label}) is not an equation of seed section {calc.section or '-'}")
        elif f"({label})" not in doc:
            bad.append(f"({label}) is not defined in the module docstring")
    for ref in SECTION_REF.findall(out.equation):
        if ref not in SEED_SECTIONS.get(calc.section, ()):
            bad.append(f"§{ref} is not a section of seed {calc.section or '-'}")
    return bad


CALCS = list(calculators().values())
IDS = [c.id for c in CALCS]


@pytest.mark.parametrize("calc", CALCS, ids=IDS)
def test_every_output_has_a_one_line_help(calc):
    bad = [f"{o.name}: {problem}" for o in calc.outputs for problem in help_problems(o)]
    assert not bad, f"{calc.id}: " + "; ".join(bad)


def help_problems(o: Output) -> list[str]:
    problems = []
    if not o.help.strip():
        problems.append("no help")
    if "\n" in o.help:
        problems.append("help spans lines")
    if len(o.help) > HELP_MAX:
        problems.append(f"help is {len(o.help)} characters (at most {HELP_MAX})")
    return problems


@pytest.mark.parametrize("calc", CALCS, ids=IDS)
def test_every_output_names_its_equation(calc):
    skip = BOOKKEEPING | BOOKKEEPING_OF.get(calc.id, set())
    missing = [o.name for o in calc.outputs if o.name not in skip and not o.equation]
    assert not missing, f"{calc.id}: no equation for {', '.join(missing)}"
    malformed = [
        f"{o.name}: {o.equation!r}"
        for o in calc.outputs
        if o.equation and not EQUATION_FORM.fullmatch(o.equation)
    ]
    assert not malformed, (
        f"{calc.id}: equations written neither (12) nor (12)-(14) nor (12), (GR1) nor §2.1, (T3): {malformed}"
    )
    unknown = [f"{o.name}: {why}" for o in calc.outputs for why in unknown_labels(calc, o)]
    assert not unknown, f"{calc.id}: " + "; ".join(unknown)


@pytest.mark.parametrize("calc", CALCS, ids=IDS)
def test_bookkeeping_outputs_are_real_outputs(calc):
    """The exemptions above name outputs that exist (a renamed output must not slip out of the check)."""
    names = {o.name for o in calc.outputs}
    assert BOOKKEEPING_OF.get(calc.id, set()) <= names


def test_section_table_matches_the_seed():
    """SECTION_EQUATIONS cites only numbers the seed has, and the seed numbers (1)-(117)."""
    for numbers in SECTION_EQUATIONS.values():
        assert set(numbers) <= set(SEED_TAGS)
    tags = {int(n) for n in re.findall(r"\\quad \((\d+)\)", SEED_FILE.read_text())}
    assert tags == set(SEED_TAGS)


def test_section_references_match_the_seeds():
    """SEED_SECTIONS lists the sections the seed text numbers, no more and no fewer."""
    for section, path in SECTION_FILES.items():
        numbered = set(re.findall(r"^(\d+(?:\.\d+)?) \S", path.read_text(), re.M))
        assert numbered == set(SEED_SECTIONS[section]), section


def test_labels_are_checked():
    """The checks can fail: a wrong section number, an undefined label, a bad form, a long help."""
    calc = calculators()["gear_ratio"]
    assert unknown_labels(calc, Output("x", "X", equation="(45)"))  # a beam equation
    assert unknown_labels(calc, Output("x", "X", equation="(ZZ9)"))
    assert not unknown_labels(calc, Output("x", "X", equation="(12), (10)"))
    assert not EQUATION_FORM.fullmatch("eq. 12")
    assert not EQUATION_FORM.fullmatch("§, (T3)")
    assert EQUATION_FORM.fullmatch("§2.1, (T3)")
    assert unknown_labels(calc, Output("x", "X", equation="§2.1"))  # gear_ratio's seed numbers no sections
    trebuchet, flywheel = calculators()["trebuchet"], calculators()["flywheel"]
    assert unknown_labels(trebuchet, Output("x", "X", equation="§3.1, (T3)"))  # seeds/001 has no 3.1
    assert not unknown_labels(trebuchet, Output("x", "X", equation="§2.1, (T3)"))
    assert unknown_labels(flywheel, Output("x", "X", equation="(12)"))  # its docstring numbers (1)-(9)
    assert not unknown_labels(flywheel, Output("x", "X", equation="(9), (FW1)"))
    assert help_problems(Output("x", "X", help="a\nb"))
    assert help_problems(Output("x", "X", help="x" * (HELP_MAX + 1)))
    assert help_problems(Output("x", "X"))


def test_the_seeds_in_the_repository_are_the_projects():
    """The copies under tests/seeds are byte for byte the project's seeds, where those are at hand
    (beside the repository, as on a developer's machine)."""
    shared = Path(__file__).resolve().parents[2] / "shared" / "seeds"
    copies = sorted(SEEDS.glob("*.txt"))
    assert len(copies) == 3
    if not shared.is_dir():
        pytest.skip("the project's shared/seeds is not beside this checkout")
    for copy in copies:
        assert copy.read_bytes() == (shared / copy.name).read_bytes(), copy.name
