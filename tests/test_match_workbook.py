"""The workbook's [match] (core/workbook/match.py) and `gearhead match`: parsing and refusals named,
one elevator move alone equal to its card's solve, requirements on the match's outputs, the CLI's
text, --json and --csv, hostile timelines."""

from __future__ import annotations

import csv
import io
import json
import textwrap
from pathlib import Path

import pytest

from gearhead.core import workbook
from gearhead.core.errors import InputError
from gearhead.core.model import solve as solve_card
from gearhead.tui import cli

LIFT = """
format = 1
name = "match test"

[variables]
battery_resistance = "0.02 ohm"

[cards.lift]
calculator = "elevator"
[cards.lift.inputs]
motor_count = 2
ratio = 9
load_mass = "15 lb"
travel = "48 in"
effects = "gravity, stator_limit, battery_sag"
stator_current_limit = "80 A"
battery_resistance = "= battery_resistance"

[cards.arm]
preset = "builtin:arm/single_kraken"

[cards.shooter]
preset = "builtin:flywheel/frc_two_kraken_limits"

[cards.air]
preset = "builtin:pneumatics/frc_intake_climber"
"""

# one flat 12 V open-circuit voltage, the card's own battery, and no brownout: the card alone
ALONE = """
[match]
length = "5 s"
resistance = "= battery_resistance"
ocv = [[1.0, 12.0]]
brownout = "0.1 V"
recovery = "0.2 V"

[[match.events]]
at = "0 s"
card = "lift"
"""


def book(extra: str, base: str = LIFT):
    return workbook.from_text(textwrap.dedent(base) + textwrap.dedent(extra), "robot.toml")


def refused(extra: str, base: str = LIFT) -> InputError:
    with pytest.raises(InputError) as info:
        book(extra, base)
    assert info.value.source == "robot.toml"
    return info.value


def test_one_elevator_move_alone_is_its_card():
    wb = book(ALONE)
    out = workbook.solve(wb)
    assert out.match_error is None
    m = out.match
    card = out.cards["lift"].solution.outputs
    want = solve_card("elevator", out.cards["lift"].entries).outputs
    assert card["time_to_goal"].value == want["time_to_goal"].value
    res = m.moves[0][2]
    tol = 2e-5
    assert res.time_to_goal == pytest.approx(card["time_to_goal"].value, rel=tol)
    assert res.peak_stator_current == pytest.approx(card["peak_stator_current"].value, rel=tol)
    assert res.peak_supply_current == pytest.approx(card["peak_supply_current"].value, rel=tol)
    assert m.outputs["peak_current"] == pytest.approx(card["peak_battery_current"].value, rel=tol)
    assert m.outputs["min_bus_voltage"] == pytest.approx(card["min_bus_voltage"].value, rel=tol)
    assert m.outputs["moves"] == 1 and m.outputs["unfinished"] == 0
    assert m.shares["lift"] == pytest.approx(1.0)


def test_return_swaps_start_and_goal():
    wb = book(ALONE.replace('card = "lift"', 'card = "lift"\naction = "return"'))
    m = workbook.solve(wb).match
    res = m.moves[0][2]
    assert res.arrival is not None
    assert res.trace[0][1] == 0.0 and res.trace[-1][1] == pytest.approx(-48 * 0.0254)


def test_requirements_read_the_match_and_hold_or_fail_as_computed():
    checks = """
    [[requirements]]
    name = "bus"
    check = "match.min_bus_voltage > 10 V"
    [[requirements]]
    name = "no brownout"
    check = "match.brownouts == 0"
    [[requirements]]
    name = "charge"
    check = "match.charge_used < 1 mA*h"
    """
    wb = book(ALONE + checks)
    out = workbook.solve(wb)
    v = out.match.outputs["min_bus_voltage"]
    q = out.match.outputs["charge_used"]
    bus, brown, charge = out.checks
    assert bus.holds == (v > 10) and bus.margin == pytest.approx(v - 10)
    assert brown.holds is True
    assert charge.holds == (q < 1e-3) and charge.margin_si == pytest.approx((1e-3 - q) * 3600, rel=1e-9)
    assert q > 0
    # a worse battery through the variable: the match runs again, the verdict follows
    wb2 = workbook.from_text(
        textwrap.dedent(LIFT).replace("0.02 ohm", "0.2 ohm") + textwrap.dedent(ALONE + checks), "robot.toml"
    )
    out2 = workbook.solve(wb2)
    assert out2.match.outputs["min_bus_voltage"] < v
    assert out2.checks[0].holds is False


def test_worst_case_of_a_match_requirement():
    from gearhead.core.workbook import study

    base = LIFT.replace('"0.02 ohm"', '"0.02 ohm ± 0.005 ohm"')
    wb = book(ALONE + '\n[[requirements]]\nname = "bus"\ncheck = "match.min_bus_voltage > 5 V"\n', base)
    worst = study.worst_case(wb)
    at_high = workbook.solve(wb, {"battery_resistance": 0.025}).checks[0].margin_si
    assert worst.low("bus") == pytest.approx(at_high, rel=1e-6)


@pytest.mark.parametrize(
    "extra, field, words",
    [
        ("[match]\nlenght = 3\n", "match.lenght", "unknown key"),
        ("[match]\ncontroller = 'roborio9'\n", "match.controller", "roborio2"),
        ("[match]\nresistance = '2 V'\n", "match.resistance", "ohm"),
        ("[match]\nresistance = '= nothing_here'\n", "match.resistance", "not a variable"),
        ("[match]\nresistance = '= lift.peak_current'\n", "match.resistance", "reads the card"),
        ("[match]\nocv = [[0.5, 12], [0.2, 12]]\n", "match.ocv", "increase"),
        (
            "[match]\nlength = 10\n[[match.events]]\nat = 1\ncard = 'lfit'\n",
            "match.events[1].card",
            "not a card",
        ),
        ("[match]\n[[match.events]]\nat = 1\ncard = 'air'\n", "match.events[1].card", "pneumatic cycles"),
        (
            "[match]\n[[match.events]]\nat = 1\ncard = 'shooter'\naction = 'move'\n",
            "match.events[1].action",
            "spin_up",
        ),
        (
            "[match]\n[[match.events]]\nat = 1\ncard = 'lift'\naction = 'up'\n",
            "match.events[1].action",
            "move",
        ),
        ("[match]\n[[match.events]]\nat = -1\ncard = 'lift'\n", "match.events[1].at", "≥ 0"),
        ("[match]\nlength = 10\n[[match.events]]\nat = 10\ncard = 'lift'\n", "match.events[1].at", "past"),
        ("[match]\n[[match.events]]\nat = 1\ncard = 'lift'\ncolor = 1\n", "match.events[1].color", "unknown"),
        ("[match]\n[[match.events]]\ncard = 'lift'\n", "match.events[1].at", "missing"),
        ("[match]\n[[match.events]]\nat = 1\ncard = 'lift'\ncount = 3\n", "match.events[1].every", "count"),
        ("[match]\n[[match.events]]\nat = 1\ncard = 'lift'\nevery = 0\n", "match.events[1].every", "> 0"),
        (
            "[match]\n[[match.events]]\nat = 1\ncard = 'lift'\nevery = 1\ncount = 0\n",
            "match.events[1].count",
            "≥ 1",
        ),
        ("[match]\n[[match.events]]\nat = 'nan'\ncard = 'lift'\n", "match.events[1].at", ""),
        ("[match]\nbase_load = 1e999\n", "match.base_load", "finite"),
        ("[match]\nlength = '2 h'\n", "match.length", "at most 3600 s"),
        ("[match]\nlength = 0\n", "match.length", "above 0 s"),
        (
            "[match]\n[[match.events]]\nat = 1\ncard = 'lift'\nevery = 0.1\ncount = 100000\n",
            "match.events[1].count",
            "at most",
        ),
        (
            "[match]\n[[match.events]]\nat = 1\ncard = 'lift'\nevery = 0.1\n",
            "match.events[1].every",
            "1491 times",
        ),
        (
            "[match]\n[[match.events]]\nat = 1\ncard = 'lift'\nevery = 1\ncount = 150\n"
            "[[match.events]]\nat = 1\ncard = 'arm'\nevery = 1\ncount = 150\n",
            "match.events",
            "at most 200",
        ),
        ('[[requirements]]\ncheck = "match.min_bus_voltage > 7 V"\n[match]\n', None, None),
        (
            '[[requirements]]\ncheck = "match.lowest > 7 V"\n[match]\n',
            "requirements[1].check",
            "not an output of the match",
        ),
        ("[cards.match]\ncalculator = 'elevator'\n[match]\n", "cards.match", "rename"),
    ],
)
def test_names_refused_with_file_and_field(extra, field, words):
    if field is None:
        book(extra)  # loads
        return
    err = refused(extra)
    assert err.field == field, str(err)
    assert words in err.message


def test_ten_thousand_event_rows_refused_at_once():
    rows = "".join("[[match.events]]\nat = 1\ncard = 'lift'\n" for _ in range(100_001))
    err = refused("[match]\n" + rows)
    assert err.field == "match.events" and "at most" in err.message


def test_overlapping_moves_on_one_card_are_queued():
    extra = (
        ALONE.replace('length = "5 s"', 'length = "5 s"')
        + '\n[[match.events]]\nat = "0.1 s"\ncard = "lift"\n'
    )
    m = workbook.solve(book(extra)).match
    (t0, _, first), (t1, _, second) = m.moves
    assert t1 == 0.1 and first.arrival > 0.1
    assert second.start == pytest.approx(first.arrival)  # waited for the first to arrive
    assert second.time_to_goal == pytest.approx(first.time_to_goal, rel=1e-5)


def test_a_card_that_cannot_be_solved_is_named_not_a_traceback():
    extra = ALONE + '\n[[requirements]]\ncheck = "match.min_bus_voltage > 7 V"\n'
    wb = book(
        extra, LIFT.replace('load_mass = "15 lb"', 'load_mass = "= battery_resistance * 100000 lb/ohm"')
    )
    out = workbook.solve(wb)
    assert out.match is None
    assert "match.events[1] (lift at 0 s)" in out.match_error and "could not be solved" in out.match_error
    assert out.checks[0].holds is None and "the match could not be run" in out.checks[0].error


def test_check_says_why_the_match_did_not_run(tmp_path, capsys):
    p = tmp_path / "robot.toml"
    base = LIFT.replace('load_mass = "15 lb"', 'load_mass = "= battery_resistance * 100000 lb/ohm"')
    p.write_text(
        textwrap.dedent(base) + textwrap.dedent(ALONE) + '[[requirements]]\ncheck = "match.brownouts == 0"\n'
    )
    code, out, _ = run_cli(["check", str(p)], capsys)
    assert code == 1 and "match not run: match.events[1] (lift at 0 s)" in out


def test_a_battery_entry_out_of_range_at_run_time_is_named():
    wb = book(
        ALONE.replace('resistance = "= battery_resistance"', 'resistance = "= battery_resistance * -1"')
    )
    out = workbook.solve(wb)
    assert out.match is None and out.match_error.startswith("match.resistance:")


def test_a_brownout_run_is_bounded_and_listed():
    weak = ALONE.replace('brownout = "0.1 V"\nrecovery = "0.2 V"', "resistance_unused = 0").replace(
        "resistance_unused = 0\n", ""
    )
    wb = book(weak, LIFT.replace('"0.02 ohm"', '"0.08 ohm"'))
    m = workbook.solve(wb).match
    assert m.outputs["brownouts"] == len(m.brownouts) >= 1
    assert all(b.running == ("lift move",) for b in m.brownouts)
    assert m.outputs["time_below_brownout"] >= 0


# ---- the command line ----------------------------------------------------------------------------


def run_cli(args, capsys):
    code = cli.main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture
def robot(tmp_path: Path) -> Path:
    p = tmp_path / "robot.toml"
    p.write_text(textwrap.dedent(LIFT) + textwrap.dedent(ALONE), encoding="utf-8")
    return p


def test_cli_text(robot, capsys):
    code, out, _ = run_cli(["match", str(robot)], capsys)
    assert code == 0
    assert "Lowest bus voltage" in out and "Brownouts: none" in out
    plot = [line for line in out.splitlines() if "|" in line]
    assert len(plot) == 12 and all(len(line) <= 80 for line in out.splitlines())
    m = workbook.solve(workbook.load(robot)).match
    assert f"{m.outputs['min_bus_voltage']:.5g} V" in out


def test_cli_json_and_csv(robot, capsys):
    code, out, _ = run_cli(["match", str(robot), "--json"], capsys)
    assert code == 0
    data = json.loads(out)
    m = workbook.solve(workbook.load(robot)).match
    assert data["outputs"]["min_bus_voltage"] == {"value": m.outputs["min_bus_voltage"], "unit": "V"}
    assert data["moves"][0]["card"] == "lift" and data["brownouts"] == []
    code, out, _ = run_cli(["match", str(robot), "--csv"], capsys)
    rows = list(csv.reader(io.StringIO(out)))
    assert code == 0 and rows[0] == ["t_s", "bus_voltage_V", "battery_current_A"]
    assert len(rows) - 1 == len(m.bus.trace)
    assert min(float(r[1]) for r in rows[1:]) == pytest.approx(m.outputs["min_bus_voltage"], rel=1e-5)


def test_cli_set_and_bad_file(robot, tmp_path, capsys):
    code, out, _ = run_cli(["match", str(robot), "--set", "battery_resistance=0.05 ohm", "--json"], capsys)
    worse = json.loads(out)["outputs"]["min_bus_voltage"]["value"]
    code0, out0, _ = run_cli(["match", str(robot), "--json"], capsys)
    assert code == code0 == 0 and worse < json.loads(out0)["outputs"]["min_bus_voltage"]["value"]
    bad = tmp_path / "bad.toml"
    bad.write_text(textwrap.dedent(LIFT) + "[match]\n[[match.events]]\nat = 1\ncard = 'air'\n")
    code, out, err = run_cli(["match", str(bad)], capsys)
    assert code == 2 and "bad.toml" in err and "match.events[1].card" in err and "not on the match bus" in err
    plain = tmp_path / "plain.toml"
    plain.write_text(textwrap.dedent(LIFT))
    code, _, err = run_cli(["match", str(plain)], capsys)
    assert code == 2 and "no [match] table" in err


def test_example_holds_fresh_and_fails_tired(capsys):
    code, out, _ = run_cli(["check", "builtin:robot_2027"], capsys)
    assert code == 0 and "Match: bus above 7 V" in out
    code, out, _ = run_cli(
        [
            "check",
            "builtin:robot_2027",
            "--set",
            "battery_resistance=0.025 ohm",
            "--set",
            "battery_charge=70 %",
        ],
        capsys,
    )
    assert code == 1 and "✘ Match: battery left" in out
    assert "✘ Match: bus above 7 V" in out and "✔ Match: no brownout" in out


def test_main_breaker_table_margin_and_trip_by_hand():
    """A base load alone (no moves): a constant current, so θ(t) = g·(1 − e^{−t/τ}) (breaker.py M13)."""
    from gearhead.core.match.breaker import Breaker

    table = [[2.0, 10.0], [5.0, 1.0]]
    extra = f"""
    [match]
    length = "10 s"
    base_load = "300 A"
    main_breaker = {table}
    [[requirements]]
    name = "breaker"
    check = "match.main_breaker_margin > 0 %"
    """
    out = workbook.solve(book(extra))
    m = out.match
    brk = Breaker(120.0, tuple(map(tuple, table)))
    i = m.outputs["peak_current"]  # the base load at the sagged bus: 300 A whatever the voltage
    assert i == pytest.approx(300.0)
    theta = brk.advance(0.0, 300.0, 10.0)
    assert m.outputs["main_breaker_margin"] == pytest.approx(100 * (1 - theta), rel=1e-9)
    trip = brk.trip_time(300.0)
    # the trip is read at the end of the trace's step where θ reached 1
    times = [t for t, _, _ in m.bus.trace]
    after = min(t for t in times if t >= trip)
    assert trip < 10.0 and m.outputs["main_breaker_trip"] == pytest.approx(after, rel=1e-9)
    assert out.checks[0].holds is False
    # without a table: no margin, and a requirement reading it says why
    out = workbook.solve(book(extra.replace(f"main_breaker = {table}", "")))
    assert "main_breaker_margin" not in out.match.outputs
    assert "no trip table" in out.checks[0].error


@pytest.mark.parametrize(
    "table, field",
    [
        ("[[0.5, 10]]", "match.main_breaker.trip_table[0].multiple"),
        ("[]", "match.main_breaker"),
        ("'x'", "match.main_breaker.trip_table"),
    ],
)
def test_main_breaker_table_refused_named(table, field):
    err = refused(f"[match]\nmain_breaker = {table}\n")
    assert err.field == field, str(err)


def test_a_spin_up_and_a_sprint_in_a_workbook_are_their_cards():
    """The flywheel's spin_up and a sprint as [[match.events]], each alone on a flat battery of the
    card's voltage and resistance (no brownout): the card's spin-up time and sprint time."""
    drive = '\n[cards.drive]\npreset = "builtin:sprint/swerve_mk4i_l3"\n'
    for card, ocv, action, out, key in (
        ("shooter", 12.5, "spin_up", "spin_up_time", "shooter"),
        ("drive", 12.0, "move", "time_to_distance", "drive"),
    ):
        extra = ALONE.replace("[[1.0, 12.0]]", f"[[1.0, {ocv}]]").replace('card = "lift"', f'card = "{card}"')
        extra = extra.replace('resistance = "= battery_resistance"', 'resistance = "0.02 ohm"')
        extra += f'action = "{action}"\n'
        wb = book(extra, LIFT + drive)
        o = workbook.solve(wb)
        assert o.match is not None, o.match_error
        (_, ev, r), *_ = o.match.moves
        assert ev.card == key
        assert r.time_to_goal == pytest.approx(o.cards[card].solution.outputs[out].value, rel=2e-5)


def test_a_lift_holds_until_its_stop():
    """Elevator, arm and flywheel moves hold their goal (mechanisms.py (B10)) until the card's next
    move or a `stop`; a stop before any move of the card has nothing to stop."""
    early = '[[match.events]]\nat = "0 s"\ncard = "arm"\naction = "stop"\n'
    stop = '[[match.events]]\nat = "3 s"\ncard = "lift"\naction = "stop"\n'
    held = workbook.solve(book(ALONE + early))
    stopped = workbook.solve(book(ALONE + stop))
    ((_, _, h),) = held.match.moves
    ((_, _, s),) = stopped.match.moves
    assert h.arrival == pytest.approx(s.arrival, rel=1e-9) and s.arrival < 3.0
    assert max(t for t, _, _ in h.trace) == pytest.approx(5.0)  # held to the end of the match
    assert max(t for t, _, _ in s.trace) == pytest.approx(3.0)
    assert held.match.outputs["charge_used"] > stopped.match.outputs["charge_used"]
    e = refused('[match]\n[[match.events]]\nat = 1\ncard = "shooter"\naction = "return"\n')
    assert e.field == "match.events[1].action" and "spin_up, burst, stop" in e.message


def test_solve_prints_the_match(robot, tmp_path, capsys):
    """`gearhead solve ROBOT.toml` shows the match's outputs after the cards (and in --json), or why
    it did not run."""
    code, out, _ = run_cli(["solve", str(robot)], capsys)
    assert code == 0 and "[match]" in out and "Lowest bus voltage" in out
    assert out.index("[match]") < out.index("Lowest bus voltage")
    code, out, _ = run_cli(["solve", str(robot), "--json"], capsys)
    data = json.loads(out)
    code2, out2, _ = run_cli(["match", str(robot), "--json"], capsys)
    assert code == code2 == 0 and data["match"] == json.loads(out2)["outputs"]
    p = tmp_path / "bad.toml"
    base = LIFT.replace('load_mass = "15 lb"', 'load_mass = "= battery_resistance * 100000 lb/ohm"')
    p.write_text(textwrap.dedent(base) + textwrap.dedent(ALONE))
    code, out, _ = run_cli(["solve", str(p)], capsys)
    assert code == 0 and "[match]" in out and "not run: match.events[1] (lift at 0 s)" in out


def test_a_burst_then_the_cards_next_move_waits_for_its_shots():
    extra = ALONE.replace('card = "lift"', 'card = "shooter"\naction = "burst"').replace(
        "[[1.0, 12.0]]", "[[1.0, 12.5]]"
    )
    extra += '\n[[match.events]]\nat = "0.1 s"\ncard = "shooter"\naction = "spin_up"\n'
    o = workbook.solve(book(extra))
    assert o.match is not None, o.match_error
    (_, _, b), (_, _, s) = o.match.moves
    card = o.cards["shooter"].solution.outputs
    assert len(b.shots) == 3 and min(V for _, V, _, _ in b.shots) == pytest.approx(
        card["slowest_ball_speed"].value, rel=1e-4
    )
    assert s.start >= b.shots[-1][0]  # queued behind the last shot (and its recovery)
    moves = o.match.as_json()["moves"]
    assert moves[0]["ball_speeds"] == [V for _, V, _, _ in b.shots] and "ball_speeds" not in moves[1]


DRIVE = '\n[cards.drive]\npreset = "builtin:sprint/swerve_mk4i_l3"\n'


@pytest.mark.parametrize(
    "inputs, event, field, words",
    [
        ("mode = 'optimise'", "", "match.events[1].card", "mode = sprint"),
        ("", "action = 'stop'\n", "match.events[1].action", "move, return"),
        ("", "action = 'burst'\n", "match.events[1].action", "move, return"),
    ],
)
def test_sprint_events_refused_by_name(inputs, event, field, words):
    base = LIFT + DRIVE + (f"inputs = {{ {inputs} }}\n" if inputs else "")
    e = refused(f"[match]\n[[match.events]]\nat = 1\ncard = 'drive'\n{event}", base)
    assert e.field == field and words in e.message


@pytest.mark.parametrize(
    "card, inputs, action, says",
    [
        (
            "drive",
            "effects = 'voltage_ramp, rolling_resistance'",
            "move",
            "(drive at 0 s).effects: voltage_ramp",
        ),
        ("shooter", "control = 'velocity_loop'", "spin_up", "(shooter at 0 s): control: "),
        ("shooter", "effects = 'motor_during_shot'", "burst", "(shooter at 0 s): effects: motor_during_shot"),
    ],
)
def test_sprint_and_flywheel_scenes_refused_at_the_run_by_name(card, inputs, action, says):
    base = (
        LIFT.replace(
            '[cards.shooter]\npreset = "builtin:flywheel/frc_two_kraken_limits"\n',
            '[cards.shooter]\npreset = "builtin:flywheel/frc_two_kraken_limits"\n'
            + (f"inputs = {{ {inputs} }}\n" if card == "shooter" else ""),
        )
        + DRIVE
        + (f"inputs = {{ {inputs} }}\n" if card == "drive" else "")
    )
    out = workbook.solve(
        book(f"[match]\n[[match.events]]\nat = 0\ncard = '{card}'\naction = '{action}'\n", base)
    )
    assert out.match is None and says in out.match_error, out.match_error


def test_pneumatics_refused_saying_why():
    e = refused("[match]\n[[match.events]]\nat = 1\ncard = 'air'\n")
    assert e.field == "match.events[1].card" and "no compressor current" in e.message


def test_a_flywheel_move_starts_at_the_speed_its_last_move_held():
    """(B13): a spin-up held at its target, then a burst: the burst fires at once, at the target; after
    a stop the wheel is not followed, so the next spin-up starts from rest (the card's)."""
    ev = ALONE.replace('card = "lift"', 'card = "shooter"\naction = "spin_up"').replace(
        "[[1.0, 12.0]]", "[[1.0, 12.5]]"
    )
    burst = ev + '\n[[match.events]]\nat = "2 s"\ncard = "shooter"\naction = "burst"\n'
    o = workbook.solve(book(burst))
    (_, _, up), (_, _, b) = o.match.moves
    card = o.cards["shooter"].solution.outputs
    assert up.time_to_goal == pytest.approx(card["spin_up_time"].value, rel=1e-4)
    assert b.start == b.arrival == 2.0 and b.shots[0][0] == 2.0
    assert b.shots[0][1] == pytest.approx(card["ball_speed"].value, rel=1e-12)
    again = ev + (
        '\n[[match.events]]\nat = "1.5 s"\ncard = "shooter"\naction = "stop"\n'
        '\n[[match.events]]\nat = "2 s"\ncard = "shooter"\naction = "spin_up"\n'
    )
    (_, _, first), (_, _, second) = workbook.solve(book(again)).match.moves
    assert second.start == 2.0
    assert second.time_to_goal == pytest.approx(first.time_to_goal, rel=1e-5)
