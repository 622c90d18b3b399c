"""Issue 40's smaller things, each pinned by a test that failed before its fix."""

import json
from pathlib import Path

import pytest

from gearhead.core import presets, sweep
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.motors import motor_names
from gearhead.tui.cli import main

ROOT = Path(__file__).resolve().parents[1]


def test_sweep_status_is_ok_where_every_point_gives_the_same_note():
    # the elevator's default move is closed form: solve notes it; a sweep said it in every row's status
    result = sweep.run("elevator", {}, ["voltage=10..12:3"])
    assert all(p.error is None and p.warnings == [] for p in result.points)
    shared = [n for n in result.notes if "closed form, no integration" in n]
    assert len(shared) == 1 and shared[0].startswith("at every point: ")
    assert "warning:" not in sweep.text_table(result)
    # a warning particular to a point stays in that point's row
    varied = sweep.run("flywheel", {}, ["voltage=10..12:3"])
    assert all(len(p.warnings) == 1 and "VEX 393" in p.warnings[0] for p in varied.points)


@pytest.mark.parametrize(
    "typed, quoted",
    [("²", "'²'"), ("5 kg²", "'5 kg²'"), ("5 m²", "'5 m²'"), ("2 kg·m²", "'2 kg·m²'")],
)
def test_a_superscript_in_a_mass_is_quoted_as_typed(typed, quoted):
    with pytest.raises(InputError) as exc:
        solve("elevator", {"load_mass": typed})
    assert exc.value.field == "load_mass"
    assert exc.value.message.startswith(quoted) and "**" not in exc.value.message


def test_superscripts_read_where_the_unit_makes_sense():
    assert solve("arm", {"moment_of_inertia": "2 kg·m²"}).inputs["moment_of_inertia"].value == 2.0
    si = solve("flywheel", {"wheel_inertia": "2 lb·in²"}).inputs["wheel_inertia"].value
    assert si == pytest.approx(2 * 0.45359237 * 0.0254**2, rel=1e-12)


@pytest.mark.parametrize("typed", ["5e-400 m", "5e-400 m*s"])
def test_a_tiny_number_with_the_wrong_unit_says_the_unit_is_wrong(typed):
    with pytest.raises(InputError) as exc:
        solve("elevator", {"load_mass": typed})
    assert "is not a mass" in exc.value.message and "too small" in exc.value.message


def test_a_tiny_number_with_a_right_unit_says_only_too_small():
    with pytest.raises(InputError) as exc:
        solve("elevator", {"load_mass": "5e-400 lb*2"})
    assert "too small" in exc.value.message and "not a mass" not in exc.value.message


def test_pneumatics_with_the_compressor_off_says_the_tank_is_empty_and_shows_the_forces_it_gets():
    """The default match with the compressor off: 15 unregulated-by-then strokes take the storage to
    0.0069 psi (each shares the tank's air), never exactly 0: it read "Tank emptied: no", and a push
    force of 106 lbf (at the 60 psi entered) beside a warning that the lowest was 0.024 lbf."""
    sol = solve("pneumatics", {"effects": "regulator"})
    out = sol.outputs
    assert out["final_pressure"].value < 0.01 * 6894.757
    assert out["tank_empty"].value is True
    assert any(w.startswith("The tank empties at t = ") for w in sol.warnings)
    (short,) = [w for w in sol.warnings if "short of air" in w]
    shown = f"{out['push_force_1'].value / 4.4482216152605:.4g} lbf push"
    assert shown in short and out["push_force_1"].value < 0.03 * 4.4482216152605


def test_the_tank_sprint_preset_is_a_tank_and_pathplanner_takes_it(capsys):
    code = main(
        [
            "solve",
            "sprint",
            "--preset",
            str(ROOT / "presets/sprint/tank_6neo_kitbot.toml"),
            "--document",
            "pathplanner",
        ]
    )
    out = capsys.readouterr()
    assert code == 0, out.err
    pp = json.loads(out.out)
    assert pp["holonomicMode"] is False and pp["driveGearing"] == 10.71


def test_every_builtin_drive_preset_names_the_drive_it_solves():
    """A preset whose name or description says tank or swerve gives the sprint's `drive` for it
    (the field's default is swerve: a tank preset without it solved as a swerve)."""
    for p in presets.listing():
        if not p.builtin or p.calculator != "sprint":
            continue
        words = f"{p.name} {p.description}".lower()
        drive = p.inputs.get("drive")
        if "tank" in words:
            assert drive == "tank", p.name
        if "swerve" in words:
            assert drive is not None and drive != "tank" and drive != "mecanum", p.name


def test_the_motor_tabs_default_torque_solves_for_every_motor(capsys):
    """`solve motor --set motor=NeveRest` (and REV HD Hex) exited 2: the default torque (0.2 N·m)
    was above their stall torque (0.173 and 0.105 N·m)."""
    for name in ("NeveRest", "REV HD Hex"):
        assert main(["solve", "motor", "--set", f"motor={name}"]) == 0, capsys.readouterr().err
    for name in motor_names():
        for source in ("wpilib", "recalc"):
            for effects in ("", "stator_limit, supply_limit, battery_sag"):
                solve("motor", {"motor": name, "source": source, "effects": effects})
