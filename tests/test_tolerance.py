"""Tolerances (core.tolerance): reading '± / +-', worst cases against brute-force corners, Monte
Carlo against an analytic variance, and seed 000's range-error table through a ball-mass tolerance."""

import itertools
import json
import math
from pathlib import Path

import pytest

from gearhead.core import tolerance, units
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.presets import from_dict, load
from gearhead.core.registry import get
from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]


def preset_inputs(calc: str, name: str) -> dict:
    return dict(load(ROOT / "presets" / calc / f"{name}.toml").inputs)


def si_text(calc_id, name, x):
    return f"{x!r} {units.SI_UNITS[get(calc_id).field(name).quantity]}".strip()


# --- reading ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text",
    [
        "3.5 in ± 0.01 in",
        "3.5 in +- 0.01 in",
        "3.5 in+/-0.01 in",
        "3.5 in ± 0.01",
        "88.9 mm ± 0.254 mm",
        "3.5 in ± 0.2857142857142857 %",
    ],
)
def test_spellings_of_a_length_tolerance(text):
    calc = get("beam")
    _, values, tols, _ = tolerance.parse(calc, {"outer_size": text, "section": "hex"})
    (t,) = tols
    assert t.nominal == pytest.approx(3.5 * 0.0254, rel=1e-12)
    assert t.high - t.nominal == pytest.approx(0.01 * 0.0254, rel=1e-9)
    assert t.nominal - t.low == pytest.approx(0.01 * 0.0254, rel=1e-9)
    assert values["outer_size"] == t.nominal


def test_percent_relative_unless_the_nominal_is_in_percent():
    calc = get("motor")
    (t,) = tolerance.parse(calc, {"voltage": "12 V ± 5 %"})[2]
    assert (t.low, t.high) == (pytest.approx(11.4), pytest.approx(12.6))
    calc = get("flywheel")
    (t,) = tolerance.parse(calc, {"loss_fraction": "10 % ± 2 %"})[2]
    assert (t.low, t.high) == (pytest.approx(0.08), pytest.approx(0.12))  # percentage points
    (t,) = tolerance.parse(calc, {"loss_fraction": "10 ± 2"})[2]  # the field's unit is %
    assert (t.low, t.high) == (pytest.approx(0.08), pytest.approx(0.12))


@pytest.mark.parametrize(
    "calc_id, entries, words",
    [
        ("motor", {"voltage": "12 V ± "}, "no tolerance after"),
        ("motor", {"voltage": "± 1 V"}, "no value before"),
        ("motor", {"voltage": "12 V ± 1 V ± 1 V"}, "more than one"),
        ("motor", {"voltage": "12 V ± 1 in"}, "voltage"),
        ("motor", {"voltage": "12 V ± -1 V"}, "positive"),
        ("motor", {"voltage": "12 V ± abc %"}, "cannot read"),
        ("motor", {"motor_count": "2 ± 1"}, "whole number"),
        ("motor", {"motor": "NEO ± 1"}, "cannot carry"),
        ("flywheel", {"ball_mass": "60 g ± 70 g"}, "low end"),
        ("flywheel", {"launch_angle": "80 deg ± 15 deg"}, "high end"),
    ],
)
def test_bad_tolerances_name_the_field(calc_id, entries, words):
    with pytest.raises(InputError) as exc:
        tolerance.parse(get(calc_id), entries)
    assert words in str(exc.value)
    assert exc.value.field == next(iter(entries))


@pytest.mark.parametrize(
    "entry",
    ["2 ft + 3 in ± 1", "3.5 in * 2 ± 0.1", "(3.5 in) ± 0.1", "3.5 in + 0 in ± 0.1", "7 in/1 ± 0.1"],
)
def test_a_bare_tolerance_after_an_expression_is_refused_with_a_hint(entry):
    """'2 ft + 3 in ± 1' read the expression's tail "ft + 3 in" as the unit (± 15 in), and
    '3.5 in * 2 ± 0.1' "in * 2" (± 0.2 in) (issue 34)."""
    with pytest.raises(InputError) as exc:
        tolerance.parse(get("beam"), {"outer_size": entry, "section": "hex"})
    assert exc.value.field == "outer_size"
    assert "give the tolerance its unit" in exc.value.message and "± " in exc.value.message


@pytest.mark.parametrize(
    "entry,nominal_in,half_in",
    [
        ("2 ft + 3 in ± 1 in", 27, 1),
        ("3.5 in * 2 ± 0.1 in", 7, 0.1),
        ("3.5 in * 2 ± 1 %", 7, 0.07),
        ("3 * 2 ± 0.1", 6, 0.1),  # plain numbers: the field's unit (in), as a bare nominal
        ("6 in ± 0.1", 6, 0.1),
        ("0.5 ft ± 0.1", 6, 1.2),
        ("6 in**2/in ± 0.1", 6, 0.1),
    ],
)
def test_tolerances_with_their_unit_or_after_a_plain_nominal_still_read(entry, nominal_in, half_in):
    _, _, (t,), _ = tolerance.parse(get("beam"), {"outer_size": entry, "section": "hex"})
    assert t.nominal == pytest.approx(nominal_in * 0.0254, rel=1e-12)
    assert t.high - t.nominal == pytest.approx(half_in * 0.0254, rel=1e-9)


def test_a_tolerance_below_the_nominals_last_digit_is_a_note_not_a_crash(capsys):
    """'25 lbf ± 1e-20 lbf' divided by the box's zero width: ZeroDivisionError, exit 70."""
    from gearhead.tui.cli import main

    _, _, tols, notes = tolerance.parse(get("lead_screw"), {"force": "25 lbf ± 1e-20 lbf"})
    assert tols == [] and any("force" in n and "too small" in n for n in notes)
    assert main(["solve", "lead_screw", "--set", "force=25 lbf ± 1e-20 lbf"]) == 0
    assert "too small to change the value" in capsys.readouterr().out


def test_preset_with_a_tolerance_loads():
    p = from_dict({"calculator": "flywheel", "inputs": {"ball_mass": "60 g ± 10 %"}})
    assert p.inputs["ball_mass"] == "60 g ± 10 %"
    with pytest.raises(InputError):
        from_dict({"calculator": "flywheel", "inputs": {"ball_mass": "60 g ± 200 %"}})


# --- worst case = brute-force corners -----------------------------------------------------------

CASES = [
    (
        "gear_ratio",
        "elevator_neo",
        {"load": "40 lbf ± 10 %", "radius": "0.75 in ± 0.02 in", "voltage": "12 V ± 0.5 V"},
    ),
    # (the section's dimensions stay fixed: its exact torsion constant is a numerical solve, ~27 ms each)
    (
        "beam",
        "frame_rail_1x2",
        {"length": "27 in ± 0.25 in", "force": "150 lbf ± 30 lbf", "load_position": "13.5 in ± 2 in"},
    ),
    ("lead_screw", "t8_lift", {"friction": "0.2 ± 0.05", "force": "50 N ± 5 N", "diameter": "8 mm ± 0.1 mm"}),
]


@pytest.mark.parametrize("calc_id, preset, tols", CASES)
def test_worst_case_equals_brute_force_corners(calc_id, preset, tols):
    raw = {**preset_inputs(calc_id, preset), **tols}
    solution, result, _ = tolerance.solve(calc_id, raw)
    ts = result.tolerances
    assert len(ts) == len(tols)
    nominal = {**preset_inputs(calc_id, preset), **{k: v.split("±")[0] for k, v in tols.items()}}
    corner_solutions = [
        solve(calc_id, {**nominal, **{t.name: si_text(calc_id, t.name, x) for t, x in zip(ts, c)}})
        for c in itertools.product(*[(t.low, t.high) for t in ts])
    ]
    checked = 0
    for name, s in result.outputs.items():
        ys = [c.outputs[name].value for c in corner_solutions if name in c.outputs]
        ys.append(solution.outputs[name].value)  # the nominal is inside the box
        if "optimiser" not in s.worst_case_method:
            assert s.low == min(ys) and s.high == max(ys), name
            checked += 1
        else:  # an optimiser searched the inside too: never narrower than the corners
            assert s.low <= min(ys) and s.high >= max(ys)
        assert s.low <= solution.outputs[name].value <= s.high
    assert checked >= 5


def test_optimiser_finds_an_interior_maximum():
    # Vacuum arc: the height at a distance d peaks at tan θ* = V²/(g·d), h* = h + V²/2g − g·d²/(2V²)
    g, V, d, h = 9.80665, 7.5, 3.0, 0.6
    raw = {**preset_inputs("projectile", "vacuum_closed_form"), "release_angle": "60 deg ± 8 deg"}
    _, result, _ = tolerance.solve("projectile", raw)
    s = result.outputs["target_height"]
    assert "optimiser" in s.worst_case_method and "release_angle" in s.worst_case_method
    assert s.high == pytest.approx(h + V * V / (2 * g) - g * d * d / (2 * V * V), rel=1e-9)
    assert math.degrees(math.atan(V * V / (g * d))) < 68  # the peak is inside the box


# --- statistics ---------------------------------------------------------------------------------


def test_monte_carlo_agrees_with_analytic_variance_of_a_linear_case():
    # Stall current is proportional to the voltage (the motor data scale with V / V_spec): with V
    # uniform on [V₀−a, V₀+a], σ = |I(V₀+a) − I(V₀−a)| / √12 exactly.
    raw = {"motor": "NEO", "motor_count": 2, "voltage": "12 V ± 1.5 V"}
    low = solve("motor", {**raw, "voltage": "10.5 V"}).outputs["stall_current"].value
    high = solve("motor", {**raw, "voltage": "13.5 V"}).outputs["stall_current"].value
    sigma = abs(high - low) / math.sqrt(12)
    _, mc, _ = tolerance.solve("motor", raw, method="monte-carlo", samples=4000, seed=7)
    s = mc.outputs["stall_current"]
    assert s.statistical_method.startswith("Monte Carlo (4000 samples, seed 7")
    lo, hi = s.std_interval
    assert lo <= sigma <= hi
    assert hi - lo < 0.1 * sigma  # the interval is informative, not a blanket
    _, fo, _ = tolerance.solve("motor", raw, method="first-order")
    assert fo.outputs["stall_current"].std == pytest.approx(sigma, rel=1e-12)
    _, auto, _ = tolerance.solve("motor", raw)  # exact enough: first-order, no sampling
    assert auto.outputs["stall_current"].statistical_method.startswith("first-order")
    # peak power goes as V²: not linear enough, so auto sampled it
    assert auto.outputs["peak_power"].statistical_method.startswith("Monte Carlo")


def test_monte_carlo_is_seeded():
    raw = {"motor": "NEO", "voltage": "12 V ± 1.5 V", "torque": "1 N*m ± 0.2 N*m"}
    a = tolerance.solve("motor", raw, method="monte-carlo", samples=200, seed=3)[1]
    b = tolerance.solve("motor", raw, method="monte-carlo", samples=200, seed=3)[1]
    assert a.outputs["speed"].std == b.outputs["speed"].std


def test_main_contributor_two_inputs():
    # Lead screw raise torque ∝ force: a 10 % force tolerance outweighs a tiny diameter one
    raw = {**preset_inputs("lead_screw", "t8_lift"), "force": "50 N ± 10 %", "diameter": "8 mm ± 0.001 mm"}
    _, result, _ = tolerance.solve("lead_screw", raw)
    s = result.outputs["raise_torque"]
    assert s.main_input == "force" and s.shares["force"] > 0.99
    assert sum(s.shares.values()) == pytest.approx(1.0)


# --- seed 000: ball-mass tolerance -> range error -----------------------------------------------

SEED_TABLE = {1: -1.42, 2: -0.76, 3: -0.52, 4: -0.40, 5: -0.32}  # seed 000, %e_m_ball = 10 %


@pytest.mark.parametrize("n", sorted(SEED_TABLE))
def test_seed_000_range_error_through_a_ball_mass_tolerance(n):
    raw = {**preset_inputs("flywheel", "nbn_seed_single_wheel"), "wheel_count": n, "ball_mass": "60 g ± 10 %"}
    solution, result, _ = tolerance.solve("flywheel", raw)
    s = result.outputs["range"]
    R0 = solution.outputs["range"].value
    # worst case (the heavy ball) against the seed's exact (8): e_r = −e_m/(m_w/(c·m₀) + 1 + e_m),
    # m_w = n·180 g, c = (1 + 2/5)·(1/2)²/0.84² (the seed's ".4954", computed exactly)
    c = 1.4 * 0.25 / 0.84**2
    exact = -0.1 / (n * 0.180 / (c * 0.060) + 1 + 0.1)
    assert (s.low - R0) / R0 == pytest.approx(exact, rel=1e-9)
    # first order (the sensitivity times the tolerance): the seed's linearised table, its two decimals
    first_order = s.sensitivities["ball_mass"] * 0.006 / R0 * 100
    assert round(first_order, 2) == SEED_TABLE[n]
    assert s.main_input == "ball_mass"
    assert s.worst_case_method == "corners (all 2)"


# --- CLI ----------------------------------------------------------------------------------------


def test_cli_solve_json_carries_spreads(capsys):
    preset = str(ROOT / "presets/flywheel/nbn_seed_single_wheel.toml")
    assert main(["solve", "flywheel", "--preset", preset, "--set", "ball_mass=60 g +- 10 %", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["inputs"]["ball_mass"]["tolerance"]["low"] == pytest.approx(0.054)
    spread = data["outputs"]["range"]["spread"]
    assert spread["worst_case"]["low"] < data["outputs"]["range"]["value"] < spread["worst_case"]["high"]
    assert spread["main_input"] == "ball_mass"
    assert data["tolerance_cost"]["solves"] >= 7
    # no tolerance: the JSON shape is unchanged (tables: the flywheel declares its limit grid's)
    assert main(["solve", "flywheel", "--preset", preset, "--json"]) == 0
    assert set(json.loads(capsys.readouterr().out)) == {
        "calculator",
        "inputs",
        "outputs",
        "warnings",
        "tables",
    }


def test_cli_solve_text_and_bad_tolerance(capsys):
    assert main(["solve", "motor", "--set", "voltage=12 V ± 5 %"]) == 0
    out = capsys.readouterr().out
    assert "worst" in out and "cost:" in out and "first-order" in out
    assert main(["solve", "motor", "--set", "voltage=12 V ± 5 in"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("gearhead: voltage:") and err.count("\n") == 1


def test_time_budget_cuts_monte_carlo_reproducibly():
    raw = {"motor": "NEO", "voltage": "12 V ± 1.5 V", "torque": "1 N*m ± 0.2 N*m"}
    full = tolerance.solve("motor", raw, method="monte-carlo", samples=400, seed=1)[1]
    cut = tolerance.solve("motor", raw, method="monte-carlo", samples=400, seed=1, budget_s=0.0)[1]
    assert cut.samples == tolerance.MIN_SAMPLES and full.samples == 400
    assert any("stopped at 100 of 400" in n for n in cut.notes)
    assert cut.outputs["speed"].statistical_method.startswith("Monte Carlo (100 samples, seed 1")


def test_a_yes_no_result_that_flips_inside_the_box_is_noted():
    # T8 lead screw (2 mm pitch, 4 starts: lead 8 mm on 8 mm): backdrivable while μ < tan λ·cos α_n
    # (tan λ = 8/(π·7), α_n ≈ 14.5°: about 0.352); μ = 0.2 ± 0.19 holds both answers, ± 0.05 only yes
    raw = preset_inputs("lead_screw", "t8_lift")
    _, wide, _ = tolerance.solve("lead_screw", {**raw, "friction": "0.2 ± 0.19"})
    _, narrow, _ = tolerance.solve("lead_screw", {**raw, "friction": "0.2 ± 0.05"})
    assert any(n.startswith("backdrivable changes within the tolerances: no / yes") for n in wide.notes)
    assert not any("backdrivable" in n for n in narrow.notes)
