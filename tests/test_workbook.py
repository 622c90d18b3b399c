"""Workbooks (core/workbook/, tui/workbook_cli.py): references, arithmetic, order, cycles, unknown
names, unit mismatches, requirements and margins, the CLI's exit codes, sweeps and worst cases."""

import json
import math
from pathlib import Path

import pytest

from gearhead.core import workbook
from gearhead.core.errors import InputError
from gearhead.core.model import solve as solve_card
from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "robot_2027.toml"
LBF = 4.4482216152605  # N, exact by definition (0.45359237 kg × 9.80665 m/s²)
INCH = 0.0254

# Two gear-ratio cards: a lift from a mass variable, a second stage at twice the lift's ratio.
BASE = """
format = 1
name = "test robot"

[variables]
mass = "10 lb"
spool = "0.75 in"
motor_name = "NEO"

[cards.lift]
calculator = "gear_ratio"
[cards.lift.inputs]
motor = "= motor_name"
load = "= mass * 9.80665 m/s**2"
radius = "= spool"
mode = "max_power"

[cards.stage]
calculator = "gear_ratio"
[cards.stage.inputs]
mode = "ratio"
ratio = "= lift.ratio * 2"
load = "= lift.stall_load / 4"
radius = "1 in"
"""


def book(text: str, tmp_path: Path | None = None) -> workbook.Workbook:
    if tmp_path is None:
        return workbook.from_text(text, "robot.toml")
    path = tmp_path / "robot.toml"
    path.write_text(text, encoding="utf-8")
    return workbook.load(path)


def with_requirements(*checks: str) -> str:
    return BASE + "".join(f'\n[[requirements]]\ncheck = "{c}"\n' for c in checks)


def run(capsys, *args):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


# ---- references and arithmetic ----------------------------------------------------------------


def test_a_variable_with_arithmetic_reaches_the_card_in_si():
    outcome = workbook.solve(book(BASE))
    lift = outcome.cards["lift"].solution
    # 10 lb × g is 10 lbf by the definition of the pound-force
    assert lift.inputs["load"].value == pytest.approx(10 * LBF, rel=1e-12)
    assert lift.inputs["radius"].value == pytest.approx(0.75 * INCH, rel=1e-15)
    assert lift.inputs["motor"].value == "NEO"
    # the same card solved by hand with those entries gives the same outputs
    direct = solve_card(
        "gear_ratio", {"motor": "NEO", "load": "10 lbf", "radius": "0.75 in", "mode": "max_power"}
    )
    assert lift.outputs["ratio"].value == pytest.approx(direct.outputs["ratio"].value, rel=1e-12)


def test_an_output_feeds_another_card():
    outcome = workbook.solve(book(BASE))
    lift, stage = outcome.cards["lift"].solution, outcome.cards["stage"].solution
    assert stage.inputs["ratio"].value == pytest.approx(2 * lift.outputs["ratio"].value, rel=1e-12)
    assert stage.inputs["load"].value == pytest.approx(lift.outputs["stall_load"].value / 4, rel=1e-12)
    assert outcome.cards["stage"].links == {"ratio": "= lift.ratio * 2", "load": "= lift.stall_load / 4"}


def test_cards_are_solved_after_what_they_read():
    wb = book(BASE.replace("[cards.lift]", "[cards.zlift]").replace("lift.", "zlift."))
    assert wb.order.index("zlift") < wb.order.index("stage")
    assert wb.order.index("mass") < wb.order.index("zlift")


@pytest.mark.parametrize(
    "text, si",
    [
        ("2 ft + 3 in", (24 + 3) * INCH),  # 'in' is a Python keyword: still the inch
        ("2ft", 24 * INCH),
        ("(1 m + 1 m) * 3", 6.0),
        ("-(2 m) ** 2 / 4 m", -1.0),  # unary minus of the square: -(4 m²) / (4 m)
        ("1e3 mm", 1.0),
        ("50 %", 0.5),
        ("6 m − 1 m", 5.0),  # a typeset minus
        ("3 × 2 m", 6.0),
    ],
)
def test_expressions_with_units(text, si):
    expr = workbook.parse_expression(text, "x", "t.toml")
    value = workbook.evaluate(expr, workbook.Scope({}, {}, {}), "x", "t.toml")
    value = float(value.to_base_units().magnitude) if hasattr(value, "magnitude") else value
    assert value == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize(
    "text",
    [
        "__import__('os').system('true')",
        "lift.ratio.real.imag",
        "lift.ratio[0]",
        "(lambda: 1)()",
        "'text' * 3",
        "1 if 2 else 3",
        "[1, 2]",
        "x == 1",
        "not 1",
        "1 // 2",
        "a; b",
        "x = 1",
        "1 +",
        "",
        "(" * 60 + "1" + ")" * 60,
        "1" * 400,
        "1\n2",
        "2 $ 3",
    ],
)
def test_only_arithmetic_is_read(text):
    with pytest.raises(InputError) as err:
        workbook.parse_expression(text, "cards.lift.load", "robot.toml")
    assert str(err.value).startswith("robot.toml: cards.lift.load: ")


def test_a_huge_power_is_refused_not_computed():
    expr = workbook.parse_expression("9 ** 9 ** 9", "v", "t.toml")
    with pytest.raises(InputError, match="exponent"):
        workbook.evaluate(expr, workbook.Scope({}, {}, {}), "v", "t.toml")


def test_a_table_column_takes_the_first_row_that_has_it():
    text = """
[variables]
wanted = 3

[cards.finder]
calculator = "ratio_finder"
inputs = { target_ratio = "= wanted", input_bore = "hex_half_in", output_bore = "hex_half_in", max_stages = 1, families = "chain_25" }

[cards.loop]
calculator = "chain_belt"
[cards.loop.inputs]
mode = "= finder.combinations.links_mode"
kind = "= finder.combinations.loop_kind"
pitch_standard = "= finder.combinations.pitch_standard"
teeth_1 = "= finder.combinations.teeth_1"
teeth_2 = "= finder.combinations.teeth_2"
links = "= finder.combinations.links"
"""
    outcome = workbook.solve(book(text))
    row = outcome.cards["finder"].solution.tables["combinations"][0]
    loop = outcome.cards["loop"].solution
    for name in ("teeth_1", "teeth_2", "links"):
        assert loop.inputs[name].value == row[name].value
    assert loop.inputs["pitch_standard"].value == row["pitch_standard"].value == "chain_25"
    # the chain card's centre distance is the finder's, which solved the same loop
    assert loop.outputs["center_distance"].value == pytest.approx(row["center_distance"].value, rel=1e-9)


# ---- what is refused when the file loads ---------------------------------------------------------


def refused(text: str) -> InputError:
    with pytest.raises(InputError) as err:
        book(text)
    return err.value


def test_a_cycle_is_refused_naming_file_card_and_field():
    text = BASE.replace('radius = "= spool"', 'radius = "= stage.free_speed * 1 s * 1 m"')
    err = refused(text)
    assert err.source == "robot.toml"
    assert err.field in ("cards.lift.radius", "cards.stage.ratio", "cards.stage.load")
    assert "cycle" in err.message and "lift" in err.message and "stage" in err.message


def test_a_variable_reading_itself_is_a_cycle():
    err = refused('[variables]\nx = "= x + 1"\n')
    assert err.field == "variables.x" and "cycle" in err.message


@pytest.mark.parametrize(
    "old, new, field, words",
    [
        (
            '"= mass * 9.80665 m/s**2"',
            '"= masss * 9.80665 m/s**2"',
            "cards.lift.load",
            "'masss' is not a variable",
        ),
        # a typo that is one of pint's units (milliarcseconds) is caught by its kind, and named
        ('"= mass * 9.80665 m/s**2"', '"= mas * 9.80665 m/s**2"', "cards.lift.load", "(read as units: mas)"),
        ('"= lift.ratio * 2"', '"= lift.ratoi * 2"', "cards.stage.ratio", "not an output or input of lift"),
        ('"= lift.ratio * 2"', '"= lifts.ratio * 2"', "cards.stage.ratio", "is not a card"),
        ('"= lift.ratio * 2"', '"= lift * 2"', "cards.stage.ratio", "is a card"),
        ('mode = "ratio"', 'mood = "ratio"', "cards.stage.mood", "is not an input of gear_ratio"),
        (
            'calculator = "gear_ratio"\n[cards.stage',
            'calculator = "gear_ration"\n[cards.stage',
            "cards.stage.calculator",
            "unknown calculator",
        ),
        # a mass into a force field: the unit mismatch named with the field's kind
        ('"= mass * 9.80665 m/s**2"', '"= mass"', "cards.lift.load", "takes a force"),
        ('"= spool"', '"= spool + 1 s"', "cards.lift.radius", "length and time"),
        ('"= lift.ratio * 2"', '"= spool"', "cards.stage.ratio", "takes a plain number"),
        ('"= motor_name"', '"= mass"', "cards.lift.motor", "not a number"),
        ('"= lift.stall_load / 4"', '"= motor_name * 2"', "cards.stage.load", "arithmetic needs numbers"),
        ('radius = "1 in"', 'radius = "banana"', "cards.stage.radius", "not a unit"),
        ('"= lift.stall_load / 4"', '"= lift.stall_load ** lift.ratio"', "cards.stage.load", "power"),
    ],
)
def test_unknown_names_and_unit_mismatches_are_refused(old, new, field, words):
    assert old in BASE
    err = refused(BASE.replace(old, new, 1))
    assert err.source == "robot.toml"
    assert err.field == field
    assert words in err.message


def test_a_requirement_comparing_two_kinds_is_refused():
    err = refused(with_requirements("lift.loaded_speed < 300 A"))
    assert err.field == "requirements[1].check"
    assert "angular speed" in err.message and "current" in err.message


@pytest.mark.parametrize(
    "text, field",
    [
        ('calculator = "motor"\n', "calculator"),  # a preset is not a workbook
        ("format = 2\n", "format"),
        ('[variables]\nin = "1 m"\n', "variables.in"),
        ('[variables]\ns = "1 m"\n', "variables.s"),  # a unit's name would hide the unit
        ("[variables]\nx = [1, 2]\n", "variables.x"),
        ('[cards.arm]\ncalculator = "motor"\nnope = 1\n', "cards.arm.nope"),
        ('[cards.arm]\npreset = "missing.toml"\n', "cards.arm.preset"),
        ('[cards.arm]\ncalculator = "motor"\ninputs = { voltage = "12 kg" }\n', "cards.arm.voltage"),
        (
            '[cards.arm]\ncalculator = "motor"\n[[requirements]]\ncheck = "arm.kt > 1 s"\n',
            "requirements[1].check",
        ),
        ('[[requirements]]\nname = "x"\n', "requirements[1].check"),
        ('[[requirements]]\ncheck = "1 m + 2 m"\n', "requirements[1].check"),
        ('[variables]\nx = "1 m"\n[cards.x]\ncalculator = "motor"\n', "cards.x"),
    ],
)
def test_bad_files_name_the_field(text, field):
    err = refused(text)
    assert err.field == field


# ---- requirements --------------------------------------------------------------------------------


def test_requirements_hold_or_fail_with_their_margins():
    text = with_requirements(
        "stage.ratio > 1", "lift.ratio > 1e6", "0.5 * lift.ratio < lift.ratio < lift.ratio * 2"
    )
    checks = workbook.solve(book(text)).checks
    ratio = workbook.solve(book(text)).cards["lift"].solution.outputs["ratio"].value
    assert checks[0].holds is True and checks[0].margin == pytest.approx(2 * ratio - 1, rel=1e-12)
    assert checks[1].holds is False and checks[1].margin == pytest.approx(ratio - 1e6, rel=1e-12)
    # a chain holds when every link does; its margin is the smallest
    assert checks[2].holds is True and checks[2].margin == pytest.approx(0.5 * ratio, rel=1e-12)


def test_margins_are_in_the_unit_written():
    outcome = workbook.solve(
        book(with_requirements("lift.current_per_motor < 1000 mA", "1 lbf < lift.stall_load"))
    )
    current = outcome.cards["lift"].solution.outputs["current_per_motor"].value
    stall = outcome.cards["lift"].solution.outputs["stall_load"].value
    first, second = outcome.checks
    assert first.unit == "mA" and first.margin == pytest.approx(1000 - current * 1000)
    assert first.margin_si == pytest.approx(1 - current)
    assert second.unit == "lbf" and second.margin == pytest.approx(stall / LBF - 1)
    assert second.holds is True


def test_text_compares_with_equals():
    outcome = workbook.solve(book(with_requirements("motor_name == motor_name")))
    assert outcome.checks[0].holds is True


def test_a_card_that_cannot_solve_fails_what_reads_it():
    # a negative ratio from the first card is out of the second's range: the design fails, not the file
    text = with_requirements("stage.ratio > 1", "lift.ratio > 0").replace(
        '"= lift.ratio * 2"', '"= lift.ratio * -2"'
    )
    outcome = workbook.solve(book(text))
    assert outcome.cards["stage"].error and "ratio" in outcome.cards["stage"].error
    assert outcome.checks[0].holds is None and "stage could not be solved" in outcome.checks[0].error
    assert outcome.checks[1].holds is True
    assert not outcome.all_hold


# ---- the command line ----------------------------------------------------------------------------


def test_check_exit_codes(tmp_path, capsys):
    good = tmp_path / "good.toml"
    good.write_text(with_requirements("stage.ratio > 1"), encoding="utf-8")
    bad = tmp_path / "bad.toml"
    bad.write_text(with_requirements("stage.ratio > 1", "lift.ratio > 1e6"), encoding="utf-8")
    broken = tmp_path / "broken.toml"
    broken.write_text(with_requirements("stage.ratio > 1 s"), encoding="utf-8")
    code, out, _ = run(capsys, "check", good)
    assert code == 0 and "✔" in out and "✘" not in out
    code, out, _ = run(capsys, "check", bad)
    assert code == 1 and "✘ lift.ratio > 1e6" in out
    code, out, err = run(capsys, "check", broken)
    assert code == 2 and out == ""
    assert err.startswith(f"gearhead: {broken}: requirements[1].check: ")
    code, _, err = run(capsys, "check", tmp_path / "missing.toml")
    assert code == 2 and "file not found" in err
    (tmp_path / "toml.toml").write_text("[variables\n", encoding="utf-8")
    code, _, err = run(capsys, "check", tmp_path / "toml.toml")
    assert code == 2 and "malformed TOML" in err


def test_check_json(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    path.write_text(with_requirements("stage.ratio > 1", "lift.ratio > 1e6"), encoding="utf-8")
    code, out, _ = run(capsys, "check", path, "--json")
    data = json.loads(out)
    assert code == 1 and data["holds"] is False
    assert [r["holds"] for r in data["requirements"]] == [True, False]
    assert data["requirements"][0]["check"] == "stage.ratio > 1"
    assert math.isfinite(data["requirements"][1]["margin"])


def test_set_replaces_a_variable(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    path.write_text(with_requirements("lift.stall_load > 1 lbf"), encoding="utf-8")
    _, out, _ = run(capsys, "solve", path, "--json")
    light = json.loads(out)["cards"]["lift"]["solution"]["inputs"]["load"]["value"]
    _, out, _ = run(capsys, "solve", path, "--json", "--set", "mass=20 lb")
    heavy = json.loads(out)["cards"]["lift"]["solution"]["inputs"]["load"]["value"]
    assert light == pytest.approx(10 * LBF) and heavy == pytest.approx(20 * LBF)
    code, _, err = run(capsys, "check", path, "--set", "weight=1 kg")
    assert code == 2 and "weight" in err


def test_solve_prints_every_card_and_its_links(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    path.write_text(BASE, encoding="utf-8")
    code, out, _ = run(capsys, "solve", path)
    assert code == 0
    assert "[lift] Gear ratio (gear_ratio)" in out and "[stage] Gear ratio (gear_ratio)" in out
    assert "= lift.ratio * 2  →" in out


def test_the_example_holds(capsys):
    code, out, err = run(capsys, "check", EXAMPLE)
    assert code == 0, out + err
    assert "11 requirements, 11 hold, 0 fail" in out  # 8, and 3 on the [match] (issue 43)
    # every card solved, and the finder's pick reached the chain card
    outcome = workbook.solve(workbook.load(EXAMPLE))
    assert not [c.error for c in outcome.cards.values() if c.error]
    row = outcome.cards["finder"].solution.tables["combinations"][0]
    assert outcome.cards["intake_chain"].solution.inputs["teeth_2"].value == row["teeth_2"].value


def test_the_example_ships_in_the_package():
    import gearhead.examples

    assert (Path(gearhead.examples.__file__).parent / "robot_2027.toml").is_file()


# ---- sweeps and worst cases ----------------------------------------------------------------------


def test_a_sweep_gives_each_requirement_s_margin(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    path.write_text(with_requirements("lift.current_per_motor < 100 A"), encoding="utf-8")
    code, out, _ = run(capsys, "sweep", path, "--vary", "mass=10 lb..30 lb:3", "--json")
    assert code == 0
    points = json.loads(out)["points"]
    assert [p["inputs"]["mass"] for p in points] == pytest.approx([x * 0.45359237 for x in (10, 20, 30)])
    # each point's margin is the check solved with that mass
    for p, lb in zip(points, (10, 20, 30)):
        outcome = workbook.solve(workbook.load(path, {"mass": f"{lb} lb"}))
        assert p["outputs"]["check_1"] == pytest.approx(outcome.checks[0].margin_si, rel=1e-12)
    code, out, _ = run(capsys, "sweep", path, "--vary", "mass=10 lb..30 lb:3")
    assert code == 0 and "check_1 [A]" in out
    code, _, err = run(capsys, "sweep", path, "--vary", "motor_name=1..2")
    assert code == 2 and "motor_name" in err


def test_the_worst_case_is_at_the_heavy_corner(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    text = with_requirements("lift.stall_load > 1 lbf").replace('mass = "10 lb"', 'mass = "10 lb ± 2 lb"')
    path.write_text(text, encoding="utf-8")
    code, out, _ = run(capsys, "check", path, "--worst-case", "--json")
    data = json.loads(out)
    assert code == 0
    worst = data["worst_case"]["requirements"]["check_1"]["worst_margin"]
    corners = [
        workbook.solve(workbook.load(path, {"mass": f"{lb} lb"})).checks[0].margin_si for lb in (8, 12)
    ]
    assert worst == pytest.approx(min(corners), rel=1e-9)
    assert data["worst_case"]["tolerances"] == ["10 lb ± 2 lb"]


def test_a_division_by_zero_at_these_values_fails_the_card_not_the_file():
    text = with_requirements("stage.ratio > 1", "lift.ratio / (lift.ratio - lift.ratio) > 1").replace(
        '"= lift.ratio * 2"', '"= lift.ratio / (lift.ratio - lift.ratio)"'
    )
    outcome = workbook.solve(book(text))
    assert "divides by zero" in outcome.cards["stage"].error
    assert outcome.checks[0].holds is None
    assert outcome.checks[1].holds is None and "divides by zero" in outcome.checks[1].error


def test_yes_no_outputs_compare_with_true_and_false():
    text = """
[cards.gears]
calculator = "gear_clearance"
inputs = { axle_diameter = "0.5 in" }

[[requirements]]
check = "gears.axle_clears == true"

[[requirements]]
check = "gears.axle_clears == false"
"""
    outcome = workbook.solve(book(text))
    clears = outcome.cards["gears"].solution.outputs["axle_clears"].value
    assert isinstance(clears, bool)
    assert [c.holds for c in outcome.checks] == [clears, not clears]


def test_cards_print_in_file_order_where_links_allow():
    # 'stage' reads 'lift', so it waits; otherwise the file's order stands
    text = BASE.replace("[cards.lift]", '[cards.stage2]\ncalculator = "motor"\n\n[cards.lift]')
    text = text.replace("[cards.stage2]", "[cards.first]")
    assert book(text).order == ["mass", "spool", "motor_name", "first", "lift", "stage"]


def test_a_card_waits_for_a_later_card_it_reads():
    lift = BASE[BASE.index("[cards.lift]") : BASE.index("[cards.stage]")]
    stage = BASE[BASE.index("[cards.stage]") :]
    text = BASE[: BASE.index("[cards.lift]")] + stage + "\n" + lift
    assert text.index("[cards.stage]") < text.index("[cards.lift]")
    assert book(text).order[-2:] == ["lift", "stage"]


@pytest.mark.parametrize(
    "reference",
    [
        "= 99 ** 99 * 99 ** 99 * 99 ** 99 * 99 ** 99",
        "= " + "9" * 320,
        "= 1e300 * 1e300",
        "= 2 ** 2 ** 2 ** 2 ** 2",
        "= lift.ratio / 0",
        "= " + "(" * 41 + "1" + ")" * 41,
        "= -" * 60 + "1",
        "= 1 degC + 1 degC",  # pint's OffsetUnitCalculusError was a traceback (exit 70)
        "= 2 degF * lift.ratio",
    ],
)
def test_hostile_references_give_a_message_never_a_traceback(tmp_path, capsys, reference):
    path = tmp_path / "robot.toml"
    path.write_text(with_requirements("stage.ratio > 1").replace('"= lift.ratio * 2"', json.dumps(reference)))
    code, out, err = run(capsys, "check", path, "--json")
    assert code in (1, 2), err
    if code == 2:
        assert out == "" and err.startswith(f"gearhead: {path}: cards.stage.ratio: ") and "\n" == err[-1]
        assert err.count("\n") == 1
    else:  # solved as far as it goes: the card failed, named
        data = json.loads(out)
        assert data["card_errors"]["stage"].startswith("ratio: ")
        assert data["requirements"][0]["holds"] is None


def test_a_kind_without_a_name_compares_in_si():
    outcome = workbook.solve(book(with_requirements("mass / 1 s < 10 kg/s")))
    check = outcome.checks[0]
    assert check.holds is True
    assert check.margin_si == pytest.approx(10 - 10 * 0.45359237, rel=1e-12)  # kg/s


def test_a_variable_reading_a_failed_card_fails_what_reads_it():
    text = (
        with_requirements("double > 1")
        .replace('[variables]\nmass = "10 lb"', '[variables]\nmass = "10 lb"\ndouble = "= stage.ratio * 2"')
        .replace('"= lift.ratio * 2"', '"= lift.ratio * -2"')
    )
    outcome = workbook.solve(book(text))
    assert outcome.checks[0].holds is None and "stage could not be solved" in outcome.checks[0].error


def test_words_are_text_variables():
    text = BASE.replace('motor_name = "NEO"', 'motor_name = "775pro"')
    outcome = workbook.solve(book(text))
    assert outcome.cards["lift"].solution.inputs["motor"].value == "775pro"


@pytest.mark.parametrize(
    "text, si",
    [
        ("10 kg / 2 s", 5.0),  # a number and its unit are one quantity
        ("2 m**2", 2.0),
        ("1 / 4 s**-1", 0.25),  # 1 / (4 per second)
        ("3 lbf ft", 3 * LBF * 12 * INCH),
        ("6 m / 2", 3.0),
        ("(2 + 1) m", 3.0),
    ],
)
def test_a_number_and_its_unit_bind_as_written(text, si):
    expr = workbook.parse_expression(text, "x", "t.toml")
    value = workbook.evaluate(expr, workbook.Scope({}, {}, {}), "x", "t.toml")
    assert float(value.to_base_units().magnitude) == pytest.approx(si, rel=1e-12)


def test_a_tolerance_corner_where_a_card_cannot_be_solved_fails_the_worst_case(tmp_path, capsys):
    """200 lb ± 150 lb on an 80 A elevator: at 350 lb the motors cannot lift it, so the requirement
    does not hold in the worst case (it said '✔ worst case' from the corners that did solve, exit 0,
    while `check --set carriage_mass='350 lb'` failed)."""
    from gearhead.tui.cli import main

    path = tmp_path / "wc.toml"
    path.write_text(
        """format = 1
name = "wc"
[variables]
carriage_mass = "200 lb ± 150 lb"
[cards.lift]
calculator = "elevator"
[cards.lift.inputs]
motor = "Kraken X60"
motor_count = 2
ratio = 9
load_mass = "= carriage_mass"
spool_diameter = "1.75 in"
travel = "48 in"
effects = "gravity, stator_limit"
stator_current_limit = "80 A"
[[requirements]]
name = "lift"
check = "lift.time_to_goal < 10 s"
""",
        encoding="utf-8",
    )
    assert main(["check", str(path)]) == 0  # at the nominal 200 lb it holds
    assert main(["check", str(path), "--worst-case"]) == 1
    out = capsys.readouterr().out
    assert (
        "✘ worst case" in out and "not solved in the tolerance box" in out and "stator_current_limit" in out
    )


@pytest.mark.parametrize(
    "a,op,b,holds",
    [(5.0, "!=", 5.0, False), (5.5, "!=", 5.0, True), (5.0, "==", 5.0, True), (5.0, "==", 5.5, False),
     (5.0, "==", 5.0 * (1 + 1e-12), True)],
)  # fmt: skip
def test_an_equality_margin_has_the_sign_of_its_verdict(a, op, b, holds):
    """== and != margins are negative exactly when the check fails, as the inequalities' are (a
    worst case takes the least margin: '!=' at 5 m ± 1 m read ✔ with margin 0 where x = 5 m fails)."""
    from gearhead.core.workbook.solving import _holds

    verdict, margin = _holds(a, b, op)
    assert verdict is holds
    assert (margin >= 0) is holds


def test_a_workbook_sweep_is_core_sweep_s_loop(monkeypatch):
    """The workbook's sweep runs through core.sweep.run (issue 42 item 3: it had a copy of the
    loop): past the CPU budget it stops with sweep's note, which says what to change; progress is
    reported as for a calculator's sweep."""
    import itertools

    from gearhead.core.sim import integrate
    from gearhead.core.workbook import study as workbook_study

    wb = book(with_requirements("lift.current_per_motor < 100 A"))
    calls = []
    done = workbook_study.run_sweep(wb, ["mass=10 lb..30 lb:3"], progress=lambda i, n: calls.append(i))
    assert calls == [1, 2, 3] and len(done.points) == 3
    real, looks = integrate.cpu_clock, itertools.count()
    monkeypatch.setattr(integrate, "cpu_clock", lambda: real() + 100.0 * next(looks))
    result = workbook_study.run_sweep(wb, ["mass=10 lb..30 lb:50"])
    assert 1 <= len(result.points) < 50
    assert any("sweep's budget" in n and "fewer points" in n for n in result.notes), result.notes


def test_a_sweep_of_a_whole_number_over_a_huge_range_picks_its_points(capsys):
    """intake_ratio = 1..1e19 in 3 points: len(range(...)) overflowed (a traceback, exit 70). A
    whole number is now at most 10^15 (core.fields.MAX_WHOLE): 1e19 is refused by name, and the
    largest range allowed picks its points."""
    code, out, err = run(capsys, "sweep", EXAMPLE, "--vary", "intake_ratio=1..1e19:3")
    assert code == 2 and "intake_ratio" in err and "at most 1000000000000000" in err
    code, out, err = run(capsys, "sweep", EXAMPLE, "--vary", "intake_ratio=1..1e15:3")
    assert code in (0, 1), err
    assert "Traceback" not in err and "internal error" not in err
    assert "1000000000000000" in out
