"""The texts a card draws are plain functions of what core solved (tui/components/card_text.py),
checked here without an app."""

from __future__ import annotations

from gearhead.core import model, solving
from gearhead.core.errors import InputError, InputErrors
from gearhead.core.registry import get
from gearhead.tui.components import card_text
from gearhead.tui.components.unit_text import pretty_quantity


def test_result_rows_are_the_solution_outputs_in_order():
    calc = get("gear_ratio")
    solution = model.solve("gear_ratio", {"load": "120"})
    rows = card_text.result_rows(calc, solution)
    assert [r.name for r in rows] == list(solution.outputs)
    for r in rows:
        assert r.label == calc.output(r.name).label
        assert r.value == pretty_quantity(solution.outputs[r.name].text)
        assert r.spread == ""


def test_timings_are_hidden_only_when_asked():
    calc = get("pneumatics")
    solution = model.solve("pneumatics", {})
    shown = {r.name: r.value for r in card_text.result_rows(calc, solution)}
    hidden = {r.name: r.value for r in card_text.result_rows(calc, solution, hide_timings=True)}
    assert hidden["wall_time"] == "(hidden)" and shown["wall_time"] != "(hidden)"
    assert {k: v for k, v in hidden.items() if k != "wall_time"} == {
        k: v for k, v in shown.items() if k != "wall_time"
    }


def test_glance_names_the_first_three_results():
    calc = get("gear_ratio")
    solution = model.solve("gear_ratio", {})
    text = card_text.glance(calc, solution).plain
    first = list(solution.outputs)[: card_text.GLANCE_RESULTS]
    assert text.startswith("✓ ")
    for name in first:
        assert calc.output(name).label in text
        assert pretty_quantity(solution.outputs[name].text) in text
    fourth = list(solution.outputs)[card_text.GLANCE_RESULTS]
    assert calc.output(fourth).label not in text


def test_errors_are_marked_on_every_row_and_counted_on_the_status_line():
    calc = get("gear_ratio")
    error = InputErrors([InputError("radius", "is not a length"), InputError("load", "is not a force")])
    assert card_text.error_marks(calc, error) == {"radius": "is not a length", "load": "is not a force"}
    status = card_text.error_status(calc, error).plain
    assert status.startswith(f"✗ {calc.field('radius').label} (and 1 more): is not a length")
    assert "(results show the last valid inputs)" in status
    assert (
        card_text.error_glance(calc, error).plain
        == f"✗ {calc.field('radius').label} (and 1 more): is not a length"
    )
    one = InputError("(result)", "internal error")
    assert card_text.error_marks(calc, one) == {}  # not a field: on the status line only
    assert card_text.error_status(calc, one).plain.startswith("✗ (result): internal error")


def test_solved_status_says_how_long_unless_hidden():
    assert card_text.solved_status(0.0123).plain == "✓ solved in 12.3 ms"
    assert card_text.solved_status(1.5).plain == "✓ solved in 1.50 s"
    assert card_text.solved_status(1.5, hide_timings=True).plain == "✓ solved"


def test_tolerances_show_their_spread_in_rows_status_and_help():
    calc = get("gear_ratio")
    solved = solving.solve(calc, {"load": "150 ± 10"})
    assert solved.spread is not None
    rows = card_text.result_rows(calc, solved.solution, solved.spread)
    assert any(".." in r.spread for r in rows)  # 'low .. high  σ …'
    status = card_text.solved_status(0.01, solved.spread, hide_timings=True).plain
    assert status.startswith("✓ solved; tolerances: worst case by ") and "(hidden)" in status
    name = next(r.name for r in rows if ".." in r.spread)
    assert "\nWorst case " in card_text.output_help(calc, name, solved.solution, solved.spread).plain
    assert "Worst case" not in card_text.output_help(calc, name, solved.solution).plain


def test_warnings_and_tolerance_notes():
    class Spread:
        notes = ["backdrivable changes within the tolerances"]

    assert card_text.warnings_text([]) == ""
    assert card_text.warnings_text(["a", "b"]) == "! a\n! b"
    assert card_text.warnings_text(["a"], Spread()) == "! a\n± backdrivable changes within the tolerances"
    assert card_text.warnings_text([], Spread()) == "± backdrivable changes within the tolerances"


def test_field_help_puts_the_rows_error_first():
    f = get("gear_ratio").field("radius")
    plain = card_text.field_help(f).plain
    assert plain.startswith(f"{f.label}: ")
    with_error = card_text.field_help(f, "'3 kg' is not a length").plain
    assert with_error.startswith("⚠ '3 kg' is not a length\n") and with_error.endswith(plain)
