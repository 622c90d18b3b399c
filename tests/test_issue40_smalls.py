"""Issue 40's smaller things, each pinned by a test that failed before its fix."""

import json
import math
from pathlib import Path

import pytest

from gearhead.core import motors, presets, recalc, sweep
from gearhead.core.calculators import flywheel as flywheel_calc
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.motors import motor_names
from gearhead.core.registry import get
from gearhead.tui.cli import main
from tests import test_velocity_loop as vl_tests

ROOT = Path(__file__).resolve().parents[1]


def test_sweep_status_is_ok_where_every_point_gives_the_same_note():
    # the elevator's default move is closed form: solve notes it; a sweep said it in every row's status
    result = sweep.run(get("elevator"), {}, ["voltage=10..12:3"])
    assert all(p.error is None and p.warnings == [] for p in result.points)
    shared = [n for n in result.notes if "closed form, no integration" in n]
    assert len(shared) == 1 and shared[0].startswith("at every point: ")
    assert "warning:" not in sweep.text_table(result)
    # a warning particular to a point stays in that point's row
    varied = sweep.run(get("flywheel"), {}, ["voltage=10..12:3"])
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


@pytest.fixture
def vl_no_free_current(monkeypatch):
    """The seed motor with no free current on both sides (tests/test_velocity_loop.py's fixture)."""
    real = flywheel_calc.lookup

    def lookup(name, source):
        m, note = real(name, source)
        return vl_tests.no_loss(m), note

    monkeypatch.setattr(flywheel_calc, "lookup", lookup)


def _flywheelsim_recovery(c, out):
    """tests/test_velocity_loop.py's FlywheelSim loop with the shot at an update instant, by the
    loop's stated rule: the sample taken at the shot's instant is the speed before the shot (what
    a reading then, or a whole number of periods later through the delay, gets); the shot follows."""
    from wpilib.simulation import FlywheelSim
    from wpimath.controller import PIDController, SimpleMotorFeedforwardRadians
    from wpimath.system.plant import DCMotor, LinearSystemId

    SUB, PERIOD = vl_tests.SUB, vl_tests.PERIOD
    base, _ = motors.lookup(c["name"], "wpilib")
    gearbox = DCMotor(
        base.v_spec, base.stall_torque, base.stall_current, 0.0, base.free_speed, out["motor_count"]
    )
    sim = FlywheelSim(LinearSystemId.flywheelSystem(gearbox, c["J"], out["ratio"]), gearbox)
    ff = SimpleMotorFeedforwardRadians(out["kS"], out["kV"], out["kA"], PERIOD)
    pid = PIDController(out["kP"], 0.0, 0.0, PERIOD)
    r, tol = out["target_speed"], out["speed_tolerance"]
    beta = out["ball_mass"] * 1.4 * (out["wheel_diameter"] / 4) ** 2 / c["J"]
    shot_sub, per = round(out["shot_time"] / SUB), round(PERIOD / SUB)
    delay_sub = round(out["sensor_delay"] / SUB)
    history = [0.0]
    for k in range(round((out["shot_time"] + max(1.0, out["shot_time"])) / PERIOD)):
        measured = history[max(k * per - delay_sub, 0)]
        sim.setInputVoltage(max(-12.0, min(12.0, ff.calculate(r) + pid.calculate(measured, r))))
        for _ in range(per):
            sim.update(SUB)
            history.append(sim.getAngularVelocity())
            if len(history) - 1 == shot_sub:
                sim.setState([sim.getAngularVelocity() / math.sqrt(1 + beta)])
    for i in range(len(history) - 1, shot_sub - 1, -1):
        if abs(history[i] - r) > tol:
            return (i + 1) * SUB - out["shot_time"]
    return 0.0


@pytest.mark.parametrize(
    "index, delay", [(0, "20 ms"), (2, "20 ms"), (4, "20 ms"), (0, "40 ms"), (2, "40 ms")]
)
def test_a_whole_period_delay_reads_the_speed_before_a_shot_at_an_update(vl_no_free_current, index, delay):
    """A shot at an update instant (1.5 s, a 20 ms loop) and a delay of one or two periods: the
    delayed reading got the speed after the shot (recovery 6-16 % off FlywheelSim); now within one
    0.1 ms substep of it, as off the grid."""
    c = vl_tests.cases()[index]
    sol = solve("flywheel", {**c["raw"], "shot_time": "1.5 s", "sensor_delay": delay})
    out = {k: v.value for k, v in sol.outputs.items()} | {k: v.value for k, v in sol.inputs.items()}
    mine, theirs = out["loop_recovery_time"], _flywheelsim_recovery(c, out)
    assert theirs > 0 and -1e-9 <= theirs - mine <= vl_tests.SUB + 1e-9, (mine, theirs)


def _linear_link(**params) -> str:
    from urllib.parse import urlencode

    return "https://www.reca.lc/linear?" + urlencode(
        {k: v if isinstance(v, str) else json.dumps(v) for k, v in params.items()}
    )


def test_a_cascade_recalc_link_says_what_it_does_to_the_gains():
    """ReCalc's shown gains leave `cascade` out (computeElevatorFeedforwardGains has no cascade
    input); its simulation doubles the first stage's load (linear.ts CASCADE_LOAD_FACTOR = 2), as a
    2-stage cascade does. The import keeps the physics and says so, with the factors."""
    plain, cascade = (recalc.to_preset(_linear_link(cascade=c)) for c in ("false", "true"))
    gains = [
        {k: solve("elevator", p.inputs).outputs[k].value for k in ("kG", "kV", "kA")}
        for p in (plain, cascade)
    ]
    assert gains[1]["kG"] == pytest.approx(2 * gains[0]["kG"], rel=1e-12)
    assert gains[1]["kA"] == pytest.approx(2 * gains[0]["kA"], rel=1e-12)
    assert gains[1]["kV"] == pytest.approx(gains[0]["kV"] / 2, rel=1e-12)
    (note,) = [w for w in cascade.warnings if "cascade" in w]
    assert "kG and kA come out 2×" in note and "kV ½×" in note
    assert not any("cascade" in w for w in plain.warnings)


def test_recalc_has_data_for_every_motor_a_link_names():
    """'ReCalc (dyno) has no data for Falcon 500 FOC / AndyMark 9015' was false: Motor.ts lists
    'Falcon 500 (FOC)' (6080 rpm, 5.84 N·m, 304 A, 1.5 A) and 'AM-9015' (14270 rpm, 0.36 N·m, 71 A,
    3.7 A) at tervay/recalc 03511cb4."""
    for theirs, ours in recalc.MOTORS.items():
        assert motors.lookup(ours, "recalc")[1] is None, theirs
    for name, figures in (
        ("Falcon 500 FOC", (6080, 5.84, 304, 1.5)),
        ("AndyMark 9015", (14270, 0.36, 71, 3.7)),
    ):
        m, _ = motors.lookup(name, "recalc")
        assert m.source == "recalc"
        got = (m.free_speed * 60 / (2 * math.pi), m.stall_torque, m.stall_current, m.free_current)
        assert got == pytest.approx(figures, rel=1e-12)
    link = _linear_link(motor={"name": "Falcon 500 (FOC)", "quantity": 2})
    preset = recalc.to_preset(link)
    assert not any("no data" in w for w in solve("elevator", preset.inputs).warnings + preset.warnings)


@pytest.mark.parametrize(
    "argv",
    [
        ["solve", "elevator", "--preset", "builtin:elevator/two_neo"],
        ["solve", "elevator", "--preset", "builtin:two_neo"],
        ["sweep", "gear_ratio", "--preset", "builtin:elevator_neo", "--vary", "radius=0.5 in..1 in:2"],
        ["accuracy", "trebuchet", "--preset", "builtin:trebuchet/seed_kastmaskin.toml"],
        ["share", "builtin:elevator/two_neo"],
        ["import", "builtin:sprint/tank_6neo_kitbot"],
        ["check", "builtin:robot_2027"],
        ["solve", "builtin:robot_2027"],
        ["sweep", "builtin:robot_2027", "--vary", "robot_mass=110 lb..150 lb:2", "--output", "sprint_5_m"],
    ],
)
def test_builtin_names_work_wherever_a_preset_or_workbook_is_taken(argv, capsys, tmp_path, monkeypatch):
    """`--preset builtin:…` worked in a workbook's card only; `solve` read it as a file name."""
    monkeypatch.chdir(tmp_path)  # not the repository: nothing found by a relative path
    assert main(argv) == 0, capsys.readouterr().err


def test_builtin_names_load_as_the_files_and_a_wrong_one_is_named(capsys, tmp_path, monkeypatch):
    from gearhead.core import share

    want = presets.load(ROOT / "presets/elevator/two_neo.toml")
    for text in ("builtin:elevator/two_neo", "builtin:two_neo", " builtin:elevator/two_neo.toml "):
        got = share.load_any(text)  # also what ctrl+o's path entry reads
        assert (got.calculator, got.inputs, got.builtin) == (want.calculator, want.inputs, True)
    monkeypatch.chdir(tmp_path)
    assert main(["solve", "elevator", "--preset", "builtin:no_such"]) == 2
    err = capsys.readouterr().err
    assert "--preset: 'builtin:no_such' is no built-in preset" in err
    assert main(["check", "builtin:no_such"]) == 2
    assert "builtin:robot_2027" in capsys.readouterr().err


def test_a_workbook_card_takes_a_builtin_preset_by_its_bare_name(tmp_path):
    from gearhead.core import workbook

    path = tmp_path / "robot.toml"
    path.write_text('[cards.lift]\npreset = "builtin:two_neo"\n', encoding="utf-8")
    wb = workbook.load(path)
    assert wb.cards["lift"].calculator == "elevator"


def test_a_tiny_number_with_an_unknown_unit_says_both():
    with pytest.raises(InputError) as exc:
        solve("elevator", {"load_mass": "5e-400 foo"})
    assert "'foo' is not a unit I know" in exc.value.message and "too small" in exc.value.message


def test_every_builtin_recalc_preset_uses_recalcs_motor_data():
    """'ReCalc v2 defaults' presets defaulted to WPILib's motor figures (source = wpilib): ReCalc's
    defaults run on its own (dyno) data, as an imported ReCalc link does."""
    from gearhead.core.registry import get

    checked = 0
    for p in presets.listing():
        fields = {f.name for f in get(p.calculator).fields}
        if p.builtin and "source" in fields and "recalc" in f"{p.name} {p.description}".lower():
            assert p.inputs.get("source") == "recalc", p.name
            checked += 1
    assert checked == 3  # the dual and compound shooters, the motors table
