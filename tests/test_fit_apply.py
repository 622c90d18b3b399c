"""`gearhead fit --apply` and the app's Apply on the flywheel and sprint cards (issue 44 item 6;
core/fit/entries.py (E5)-(E7)): synthetic SysId logs from known plants (tests/fit_plants.py) whose
gains are the card's own with a heavier wheel or robot and more friction; the entries written,
re-solved by the card itself (its kS/kV/kA outputs), give the plant's gains back:
- a log without noise: the fit is the plant's model exactly, so the gains come back to 1e-3
  (measured: within 1.1e-6) and to 1e-5 of the fit (the file's 6 significant digits);
- velocity noise of 0.2 % of the top speed (0.1 % on position, 1 ms of timestamp jitter): kV within
  1 %, kA and kS within 3 % (measured, the card re-solved against the plant: FRC shooter kA
  −0.08 %; MK4i L2 drive kS +0.45 %, kA −0.52 %).
kV is the card's n/Kv whatever is written (E3), here the plant's.
The flywheel card holds no friction torque: kS beyond the motors' own loss is noted, not written.
The written file keeps its comments and loads; a refused log writes nothing."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from gearhead.tui.cli import main

pytest.importorskip("wpiutil")
sys.path.insert(0, str(Path(__file__).parent))
from fit_plants import simulate  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DRIVE = {"period": 0.02, "step": 4.0, "dynamic_time": 1.5}  # a drivetrain's room: 4 V, 1.5 s


def run(capsys, *args):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


def copy(tmp_path, preset: str) -> Path:
    """A preset copied with comments of our own (the file is the user's: --apply may write it)."""
    path = tmp_path / Path(preset).name
    text = (ROOT / "presets" / preset).read_text(encoding="utf-8")
    path.write_text(
        "# my robot's card\n" + text.replace("[inputs]", "[inputs]  # as built"), encoding="utf-8"
    )
    return path


def solved_gains(kind: str, path: Path) -> dict[str, float]:
    """The card's own kS/kV/kA outputs from the file as written (a flywheel under its velocity loop,
    where the card reports them)."""
    from gearhead.core import presets
    from gearhead.core.model import solve

    raw = dict(presets.load(path).inputs)
    if kind == "flywheel":
        raw["control"] = "velocity_loop"
    sol = solve(kind, raw)
    return {k: sol.outputs[k].value for k in ("kS", "kV", "kA")}


def plant_of(kind: str, preset: Path, scale: dict[str, float], extra_ks: float = 0.0) -> dict[str, float]:
    from gearhead.core.fit import entries

    design = entries.load_card(kind, str(preset)).design
    g = {k: design[k] * scale.get(k, 1.0) for k in ("kS", "kV", "kA")}
    g["kS"] += extra_ks
    return g


CASES = [
    # (card, preset, the plant's gains over the card's, log options, noise as a fraction of top speed)
    ("flywheel", "flywheel/vex_hood_secondary.toml", {"kA": 1.3}, {"step": 6.0}, 0.0),
    ("flywheel", "flywheel/frc_velocity_loop_449.toml", {"kA": 1.3}, {}, 0.002),
    ("sprint", "sprint/swerve_mk4i_l2.toml", {"kS": 2.0, "kA": 1.2}, DRIVE, 0.002),
    ("sprint", "sprint/tank_6neo_kitbot.toml", {"kS": 3.0, "kA": 0.85}, DRIVE, 0.0),
]


@pytest.mark.parametrize("kind, preset, scale, options, noise", CASES, ids=[c[1] for c in CASES])
def test_apply_writes_entries_whose_card_gives_the_plant_back(
    capsys, tmp_path, kind, preset, scale, options, noise
):
    path = copy(tmp_path, preset)
    plant = plant_of(kind, path, scale)
    top = (options.get("step", 7.0) - plant["kS"]) / plant["kV"]
    log = simulate(
        tmp_path / "log.wpilog",
        kind,
        plant,
        noise=noise * top,
        jitter=0.001 if noise else 0.0,
        seed=3,
        **options,
    )
    before = path.read_text(encoding="utf-8")
    code, out, err = run(capsys, "fit", log, "--card", kind, "--preset", path, "--apply", "--json")
    assert code == 0, err
    data = json.loads(out)
    fitted = data["fits"][data["favoured"]]["gains"]
    after = path.read_text(encoding="utf-8")
    assert after != before and data["applied"]["diff"].startswith("---")
    # every comment is kept (tomlkit), and the file loads as a preset of its card
    assert [line for line in before.splitlines() if "#" in line] == [
        line for line in after.splitlines() if "#" in line
    ]
    got = solved_gains(kind, path)
    design = plant_of(kind, ROOT / "presets" / preset, {})  # the card's own gains, before
    # written: kA (the inertia or mass) and a sprint's kS (its rolling resistance); kV is the card's
    # n/Kv whatever the fit (E3), and a flywheel's kS its motors' own R·i_f (E5)
    written = ("kA", "kS") if kind == "sprint" else ("kA",)
    for k in ("kS", "kV", "kA"):
        want = fitted[k] if k in written else design[k]
        assert got[k] == pytest.approx(want, rel=1e-5), k  # the file's 6 significant digits
        bound = 1e-3 if noise == 0 else 0.01 if k == "kV" else 0.03
        assert got[k] == pytest.approx(plant[k], rel=bound), k
    changes = data["applied"]["changes"]
    if kind == "flywheel":
        assert set(changes) >= {"wheel_inertia"}
        if "vex" in preset:  # given by mass and radius of gyration: now entered, the secondary too
            assert changes["mode"] == "moment_of_inertia" and "secondary_inertia" in changes
            assert any("now entered as a moment of inertia" in n for n in data["applied"]["notes"])
        slower = "spin_up_time"
    else:
        assert set(changes) >= {"robot_mass", "rolling_coefficient"}
        assert "rolling_resistance" in changes["effects"]
        assert any(n.startswith("efficiency kept at") for n in data["applied"]["notes"])
        slower = "time_to_distance"
    # the card's move, re-solved with the fitted entries: the same as the file's (6 digits)
    from gearhead.core import presets
    from gearhead.core.model import solve

    moved = solve(kind, presets.load(path).inputs).outputs[slower].value
    assert data["moves"]["fitted"][slower] == pytest.approx(moved, rel=1e-4)
    if kind == "flywheel":  # a heavier wheel (nothing else written) spins up slower
        assert data["moves"]["fitted"][slower] > data["moves"]["design"][slower]


def test_flywheel_friction_is_noted_not_written_and_a_workbook_keeps_its_comments(capsys, tmp_path):
    """The robot_2027 workbook's shooter (a built-in preset with a linked battery resistance): a
    heavier wheel and 0.3 V more kS; the inertia is written into the card's inputs, the friction
    only noted (the card's kS stays R·i_f), the workbook's comments stay and it still checks."""
    from gearhead.core.fit import entries

    wb = tmp_path / "robot.toml"
    wb.write_text((ROOT / "examples/robot_2027.toml").read_text(encoding="utf-8"), encoding="utf-8")
    card = entries.load_card("flywheel", workbook=str(wb), name="shooter")
    plant = {"kS": card.design["kS"] + 0.3, "kV": card.design["kV"], "kA": card.design["kA"] * 1.25}
    log = simulate(tmp_path / "shooter.wpilog", "flywheel", plant)
    before = wb.read_text(encoding="utf-8")
    code, out, err = run(
        capsys, "fit", log, "--card", "flywheel", "--workbook", wb, "--name", "shooter", "--apply"
    )
    assert code == 0, err
    assert "note: the flywheel card holds no friction torque" in out and "wheel_inertia" in out
    after = wb.read_text(encoding="utf-8")
    assert [line for line in before.splitlines() if "#" in line] == [
        line for line in after.splitlines() if "#" in line
    ]
    assert 'battery_resistance = "= battery_resistance"' in after
    code, out, err = run(capsys, "check", wb, "--json")
    assert code in (0, 1), err and json.loads(out)["card_errors"] == {}
    again = entries.load_card("flywheel", workbook=str(wb), name="shooter")
    assert again.design["kA"] == pytest.approx(plant["kA"], rel=1e-3)
    assert again.design["kS"] == pytest.approx(card.design["kS"], rel=1e-12)  # not the plant's


@pytest.mark.parametrize(
    "kind, preset", [("flywheel", "flywheel/frc_hooded_449.toml"), ("sprint", "sprint/swerve_mk4i_l3.toml")]
)
@pytest.mark.parametrize(
    "data, words",
    [
        (b"WPILOG\x00\x01\x00\x00", "bad.wpilog"),  # cut off in its header
        (b"WPILOG\x00\x01\x00\x00\x00\x00", "no SysId test state"),
        (b"not a log", "is not a WPILog"),
    ],
)
def test_a_refused_log_writes_nothing(capsys, tmp_path, kind, preset, data, words):
    path = copy(tmp_path, preset)
    before = path.read_bytes()
    bad = tmp_path / "bad.wpilog"
    bad.write_bytes(data)
    code, out, err = run(capsys, "fit", bad, "--card", kind, "--preset", path, "--apply")
    assert code == 2 and out == "" and words in err and err.count("\n") == 1
    assert path.read_bytes() == before


# --- fitted_raw's choices, from gains (no log) -------------------------------------------------------


def test_sprint_below_the_motors_loss_turns_rolling_resistance_off():
    from gearhead.core.fit import entries

    card = entries.load_card("sprint", str(ROOT / "presets/sprint/swerve_mk4i_l2.toml"))
    loss_ks = card.loss / card.f  # R·i_f
    raw, notes = entries.fitted_raw(
        card, {"kS": 0.5 * loss_ks, "kV": card.design["kV"], "kA": card.design["kA"]}
    )
    assert "rolling_resistance" not in raw["effects"] and "stator_limit" in raw["effects"]
    assert any("rolling resistance turned off" in n for n in notes)
    again = entries.card_from_entries("sprint", raw, "x")
    assert again.design["kS"] == pytest.approx(loss_ks, rel=1e-12)  # the least the card holds


def test_a_fitted_value_the_card_refuses_is_not_written():
    """C_rr above the field's 1 (kS far beyond the mass's rolling resistance); a flywheel whose
    fitted inertia is below its rotors': a note each, the card's entry kept."""
    from gearhead.core.fit import entries

    card = entries.load_card("sprint", str(ROOT / "presets/sprint/swerve_mk4i_l2.toml"))
    raw, notes = entries.fitted_raw(card, {"kS": 12.0, "kV": card.design["kV"], "kA": card.design["kA"]})
    assert (
        raw["rolling_coefficient"] == card.raw["rolling_coefficient"]
        and raw["effects"] == card.raw["effects"]
    )
    assert any(n.startswith("rolling_coefficient: the fitted") for n in notes)
    assert raw["robot_mass"] != card.raw["robot_mass"]  # the rest is written

    fly = entries.card_from_entries(
        "flywheel", {"rotor_inertia": "1e-4 kg*m**2", "motor_count": 2, "ratio": 1}, "x"
    )
    raw, notes = entries.fitted_raw(fly, {"kS": fly.design["kS"], "kV": fly.design["kV"], "kA": 1e-6})
    assert "wheel_inertia" not in raw and "mode" not in raw
    assert any("is not above the rotors'" in n for n in notes)


def test_flywheel_with_rotors_and_a_secondary_wheel_reproduces_ka():
    """(E5): the rotors' N·J_r·G² and the secondary's G₂₁²·n₂·I₂ are taken off before dividing by
    the wheels; the card re-read from the written entries gives kA back."""
    from gearhead.core.fit import entries

    raw0 = {
        "shooter": "dual",
        "wheel_count": 2,
        "secondary_count": 3,
        "secondary_ratio": 0.5,
        "rotor_inertia": "2e-5 kg*m**2",
        "motor_count": 2,
        "ratio": 1.5,
    }
    card = entries.card_from_entries("flywheel", raw0, "x")
    gains = {"kS": card.design["kS"], "kV": card.design["kV"], "kA": card.design["kA"] * 1.7}
    raw, _ = entries.fitted_raw(card, gains)
    assert raw["mode"] == "moment_of_inertia"
    again = entries.card_from_entries("flywheel", raw, "x")
    assert again.design["kA"] == pytest.approx(gains["kA"], rel=1e-12)
    from gearhead.core.sim.shooter import secondary_reflected

    assert secondary_reflected(again.values) == pytest.approx(secondary_reflected(card.values), rel=1e-12)


# --- the app's Apply ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kind, scale, options, fields",
    [
        ("flywheel", {"kA": 1.3}, {}, {"mode", "wheel_inertia"}),
        ("sprint", {"kS": 3.0, "kA": 1.2}, DRIVE, {"robot_mass", "rolling_coefficient", "effects"}),
    ],
)
async def test_the_app_applies_the_flywheel_and_sprint_fits(tmp_path, kind, scale, options, fields):
    from gearhead.core.fit import entries
    from gearhead.tui.app import GearheadApp
    from tests.test_fit_app import SIZE, fit, open_fit
    from tests.tui_helpers import card, settle

    design = entries.load_card(kind).design
    plant = {k: design[k] * scale.get(k, 1.0) for k in ("kS", "kV", "kA")}
    path = simulate(tmp_path / f"{kind}.wpilog", kind, plant, **options)
    app = GearheadApp(blink=False, initial=kind, hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        titles = [c.title for c in app.get_system_commands(app.screen)]
        assert "Fit from log…" in titles
        screen = await open_fit(pilot)
        await fit(pilot, screen, str(path))
        r = screen.report
        assert r is not None, str(screen.query_one("#fit-status").render())
        assert set(screen.changes) == fields
        diff = str(screen.query_one("#fit-diff").render())
        assert "Apply writes into the card:" in diff and "not written back" not in diff
        assert not screen.query_one("#fit-apply").disabled
        await pilot.click("#fit-apply")
        await settle(pilot)
        tab = card(app, kind)
        assert tab.error is None and tab.solution is not None
        best = r.fits[r.favoured].gains
        from gearhead.core.tolerance import split_inputs

        raw, _ = split_inputs(tab.calculator, dict(tab.entries))  # a tolerance's nominal value
        on_screen = entries.card_from_entries(kind, raw, "on screen")
        for k in ("kS", "kV", "kA"):
            assert on_screen.design[k] == pytest.approx(best[k], rel=1e-9), k
            assert on_screen.design[k] == pytest.approx(plant[k], rel=1e-3), k


@pytest.mark.parametrize("kind", ["flywheel", "sprint"])
def test_any_fitted_gains_give_entries_the_card_reads(kind):
    """Gains from tiny to huge, kS below zero to far above the supply: the entries written are
    ones the card reads (a value it refuses kept as the card's, with a note), never nan or inf."""
    import itertools

    from gearhead.core import registry
    from gearhead.core.fit import entries
    from gearhead.core.model import parse_inputs

    card = entries.load_card(kind)
    for ks, ka in itertools.product((-5.0, 0.0, 1e-9, 0.3, 11.0, 1e300), (1e-300, 1e-9, 0.01, 3.0, 1e300)):
        raw, notes = entries.fitted_raw(card, {"kS": ks, "kV": card.design["kV"], "kA": ka})
        parse_inputs(registry.get(kind), raw)
        assert not any(w in str(v).lower() for v in raw.values() for w in ("nan", "inf")), raw
        assert all(isinstance(n, str) and n for n in notes)


def test_a_linked_robot_mass_is_held_and_rolling_resistance_taken_at_it(capsys, tmp_path):
    """The example workbook's drive links its mass (`= robot_mass`): --apply leaves it and writes
    C_rr = (kS·f − R·i_f·f)/(m·g) at the card's mass, so the card re-solved gives the fitted kS
    (at the fitted mass it would give kS·m_card/m_fitted: 13 % low here), its kA its own."""
    from gearhead.core import workbook
    from gearhead.core.fit import entries

    book = tmp_path / "robot.toml"
    book.write_text((ROOT / "examples/robot_2027.toml").read_text(encoding="utf-8"), encoding="utf-8")
    card = entries.load_card("sprint", workbook=str(book), name="drive")
    plant = {k: card.design[k] * s for k, s in (("kS", 1.5), ("kV", 1.0), ("kA", 1.15))}
    log = simulate(tmp_path / "drive.wpilog", "sprint", plant, **DRIVE)
    args = ("fit", log, "--card", "sprint", "--workbook", book, "--name", "drive", "--apply", "--json")
    code, out, err = run(capsys, *args)
    assert code == 0, err
    data = json.loads(out)
    fitted = data["fits"][data["favoured"]]["gains"]
    notes = data["applied"]["notes"]
    assert "robot_mass" not in data["applied"]["changes"]
    assert any(n.startswith("robot_mass is linked (= robot_mass): not written; the fit gives") for n in notes)
    assert any(n.startswith("the robot mass is held at the card's") for n in notes)
    outs = workbook.solve(workbook.load(book)).cards["drive"].solution.outputs
    assert outs["kS"].value == pytest.approx(fitted["kS"], rel=1e-5)
    assert outs["kA"].value == pytest.approx(card.design["kA"], rel=1e-9)
