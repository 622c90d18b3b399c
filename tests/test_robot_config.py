"""core.robot_config: PathPlanner settings.json and Choreo .chor exports of a drivetrain.

The key sets, types and units are written out here from the readers themselves (PathPlannerLib's
RobotConfig.fromGUISettings at mjansen4857/pathplanner e02bbf31, Choreo's ProjectFile at
SleipnirGroup/Choreo 9beecede), not taken from the module under test. Where robotpy-pathplannerlib
is installed (it is not in the locked [test] extra), its own reader loads the exported file.
"""

import json
import math
import re

import pytest

from gearhead.core import units
from gearhead.core.constants import INCH, RPM
from gearhead.core.motors import motor_names
from gearhead.core.robot_config import (
    RobotConfig,
    choreo_project,
    estimated_moi,
    motor_limits,
    pathplanner_motor_type,
    pathplanner_settings,
)

# PathPlannerLib fromGUISettings: read by every language's reader (KeyError/NPE/throw when missing)
PP_REQUIRED = {
    "holonomicMode": bool,
    "robotMass": float,
    "robotMOI": float,
    "driveWheelRadius": float,
    "driveGearing": float,
    "maxDriveSpeed": float,
    "wheelCOF": float,
    "driveMotorType": str,
    "driveCurrentLimit": float,
}
PP_MODULES = {f"{c}Module{a}" for c in ("fl", "fr", "bl", "br") for a in "XY"}
PP_GUI_SIZE = {"robotWidth", "robotLength", "bumperOffsetX", "bumperOffsetY"}

# The 8 strings PathPlannerLib accepts (case-sensitive), by the Gearhead motor name
PP_MOTORS = {
    "Kraken X60": "krakenX60",
    "Kraken X60 FOC": "krakenX60FOC",
    "Falcon 500": "falcon500",
    "Falcon 500 FOC": "falcon500FOC",
    "NEO Vortex": "vortex",
    "NEO": "NEO",
    "CIM": "CIM",
    "MiniCIM": "miniCIM",
}


def swerve(**changes) -> RobotConfig:
    """SDS MK4i L2, Kraken X60 at 60 A, 22.75 in × 20.75 in between module centres."""
    free, torque = motor_limits("Kraken X60", 60.0)
    values = dict(
        kind="swerve",
        mass=61.2,
        moi=5.8,
        wheel_radius=2 * INCH,
        gearing=(50 / 14) * (17 / 27) * (45 / 15),
        motor="Kraken X60",
        motor_count=4,
        current_limit=60.0,
        wheel_cof=1.2,
        max_speed=4.5,
        trackwidth=22.75 * INCH,
        wheelbase=20.75 * INCH,
        bumper_width=33 * INCH,
        bumper_length=35 * INCH,
        motor_free_speed=free,
        motor_max_torque=torque,
    )
    values.update(changes)
    return RobotConfig(**values)


def tank(**changes) -> RobotConfig:
    """Six NEOs (3 a side) at 40 A, 8.45:1, 6 in wheels."""
    free, torque = motor_limits("NEO", 40.0)
    values = dict(
        kind="tank",
        mass=55.0,
        moi=4.5,
        wheel_radius=3 * INCH,
        gearing=8.45,
        motor="NEO",
        motor_count=6,
        current_limit=40.0,
        wheel_cof=1.1,
        max_speed=4.6,
        trackwidth=0.6,
        wheelbase=0.5,
        bumper_width=0.8,
        bumper_length=0.9,
        motor_free_speed=free,
        motor_max_torque=torque,
    )
    values.update(changes)
    return RobotConfig(**values)


def _check_types(settings):
    for key, kind in PP_REQUIRED.items():
        if kind is float:  # a JSON number, not a bool (bool is an int in Python)
            assert type(settings[key]) in (int, float), key
        else:
            assert type(settings[key]) is kind, key


# ---- PathPlanner --------------------------------------------------------------------------------


def test_pathplanner_swerve_has_exactly_the_required_keys_plus_the_gui_sizes():
    s = pathplanner_settings(swerve())
    assert set(s) == set(PP_REQUIRED) | PP_MODULES | PP_GUI_SIZE | {"robotTrackwidth"}
    _check_types(s)
    assert all(type(s[k]) is float for k in PP_MODULES | PP_GUI_SIZE | {"robotTrackwidth"})
    assert s["holonomicMode"] is True
    assert s["driveMotorType"] == "krakenX60"
    # SI: kg, kg·m², m, reduction, m/s, A per motor
    assert s["robotMass"] == 61.2 and s["robotMOI"] == 5.8
    assert s["driveWheelRadius"] == pytest.approx(0.0508)
    assert s["driveGearing"] == pytest.approx(6.746031746)
    assert s["maxDriveSpeed"] == 4.5 and s["wheelCOF"] == 1.2
    assert s["driveCurrentLimit"] == 60.0
    assert s["robotWidth"] == pytest.approx(0.8382) and s["robotLength"] == pytest.approx(0.889)
    assert s["bumperOffsetX"] == 0.0 and s["bumperOffsetY"] == 0.0


def test_pathplanner_swerve_module_positions_by_hand():
    s = pathplanner_settings(swerve())
    # wheelbase 20.75 in = 0.52705 m, trackwidth 22.75 in = 0.57785 m; +x forward, +y left
    expected = {
        "flModuleX": 0.263525,
        "flModuleY": 0.288925,
        "frModuleX": 0.263525,
        "frModuleY": -0.288925,
        "blModuleX": -0.263525,
        "blModuleY": 0.288925,
        "brModuleX": -0.263525,
        "brModuleY": -0.288925,
    }
    for key, value in expected.items():
        assert s[key] == pytest.approx(value, rel=1e-12), key


def test_pathplanner_tank_has_trackwidth_and_no_modules():
    s = pathplanner_settings(tank(motor_count=4))
    assert set(s) == set(PP_REQUIRED) | {"robotTrackwidth"} | PP_GUI_SIZE
    _check_types(s)
    assert s["holonomicMode"] is False
    assert s["robotTrackwidth"] == 0.6
    assert s["driveMotorType"] == "NEO"
    assert s["driveCurrentLimit"] == 40.0  # 4 motors: PathPlannerLib's own 2 a side, per motor


def test_pathplanner_tank_other_motor_counts_keep_the_total_current():
    # PathPlannerLib multiplies the file's limit by its hard-coded 2 motors a side: 3 NEOs a side at
    # 40 A are 120 A a side, so the file says 60 A; 1 a side at 40 A, 20 A
    assert pathplanner_settings(tank(motor_count=6))["driveCurrentLimit"] == 60.0
    assert pathplanner_settings(tank(motor_count=2))["driveCurrentLimit"] == 20.0


def test_pathplanner_mecanum_goes_in_as_holonomic():
    free, torque = motor_limits("NEO", 40.0)
    cfg = swerve(
        kind="mecanum",
        motor="NEO",
        motor_free_speed=free,
        motor_max_torque=torque,
        current_limit=40.0,
        max_speed=3.5,
        gearing=10.71,
        wheel_radius=3 * INCH,
    )
    s = pathplanner_settings(cfg)
    assert set(s) == set(PP_REQUIRED) | PP_MODULES | PP_GUI_SIZE | {"robotTrackwidth"}
    assert s["holonomicMode"] is True and s["driveMotorType"] == "NEO"
    assert (s["blModuleX"], s["blModuleY"]) == pytest.approx((-0.263525, 0.288925))


def test_motor_type_mapping_for_every_motor_pathplanner_knows():
    for name, pp in PP_MOTORS.items():
        assert name in motor_names(), name  # a real Gearhead motor
        assert pathplanner_motor_type(name) == pp
        assert pathplanner_settings(swerve(motor=name, max_speed=1.0))["driveMotorType"] == pp
    others = [n for n in motor_names() if n not in PP_MOTORS]
    assert "Kraken X44" in others and "NEO 550" in others
    assert all(pathplanner_motor_type(n) is None for n in others)


def test_a_motor_pathplanner_lacks_is_refused_naming_it_and_the_accepted_types():
    cfg = swerve(motor="Kraken X44", max_speed=1.0)
    with pytest.raises(ValueError) as err:
        pathplanner_settings(cfg)
    text = str(err.value)
    assert "Kraken X44" in text
    assert all(pp in text for pp in PP_MOTORS.values())


@pytest.mark.parametrize("make", [swerve, tank], ids=["swerve", "tank"])
def test_json_round_trip(make):
    s = pathplanner_settings(make())
    assert json.loads(json.dumps(s)) == s
    c = choreo_project(make(), "Robot")
    assert json.loads(json.dumps(c)) == c


def _pathplannerlib(tmp_path, monkeypatch, settings):
    from pathplannerlib import config  # a test extra (pyproject.toml): PathPlannerLib's own reader

    (tmp_path / "pathplanner").mkdir()
    (tmp_path / "pathplanner" / "settings.json").write_text(json.dumps(settings, indent=2))
    monkeypatch.setattr(config, "getDeployDirectory", lambda: str(tmp_path))
    return config.RobotConfig.fromGUISettings()


def test_pathplannerlib_reads_the_swerve_export(tmp_path, monkeypatch):
    cfg = swerve()
    rc = _pathplannerlib(tmp_path, monkeypatch, pathplanner_settings(cfg))
    from wpimath.system.plant import DCMotor

    assert rc.isHolonomic and rc.massKG == cfg.mass and rc.MOI == cfg.moi
    assert [(t.X(), t.Y()) for t in rc.moduleLocations] == pytest.approx(
        [(0.263525, 0.288925), (0.263525, -0.288925), (-0.263525, 0.288925), (-0.263525, -0.288925)]
    )
    mc = rc.moduleConfig
    assert mc.wheelRadiusMeters == cfg.wheel_radius and mc.maxDriveVelocityMPS == cfg.max_speed
    assert mc.wheelCOF == cfg.wheel_cof and mc.driveCurrentLimit == 60.0  # 1 motor a module
    gearbox = DCMotor.krakenX60(1).withReduction(cfg.gearing)
    assert mc.driveMotor.stallTorque == pytest.approx(gearbox.stallTorque)
    # Gearhead's WPILib Kraken X60 is PathPlannerLib's
    assert DCMotor.krakenX60(1).freeSpeed == pytest.approx(cfg.motor_free_speed, rel=1e-9)


def test_pathplannerlib_reads_the_tank_export(tmp_path, monkeypatch):
    cfg = tank()
    rc = _pathplannerlib(tmp_path, monkeypatch, pathplanner_settings(cfg))
    assert not rc.isHolonomic
    assert [(t.X(), t.Y()) for t in rc.moduleLocations] == [(0.0, 0.3), (0.0, -0.3)]
    # 3 NEOs a side at 40 A: the side's current limit is the robot's
    assert rc.moduleConfig.driveCurrentLimit == pytest.approx(3 * 40.0)


# ---- Choreo -------------------------------------------------------------------------------------

# Choreo's RobotConfig<Expr>: key -> the SI unit and Gearhead quantity kind of its val
CHOREO_SCALARS = {
    "mass": ("kg", "mass"),
    "inertia": ("kg*m**2", "inertia"),
    "cof": ("", "dimensionless"),
    "gearing": ("", "dimensionless"),
    "radius": ("m", "length"),
    "vmax": ("rad/s", "angular_speed"),
    "tmax": ("N*m", "torque"),
    "differentialTrackWidth": ("m", "length"),
}


def _exprs(config):
    """(path, {"exp", "val"}, SI unit, kind) for every Expr in a Choreo config."""
    for key, (unit, kind) in CHOREO_SCALARS.items():
        yield key, config[key], unit, kind
    for module in ("frontLeft", "backLeft"):
        for axis in ("x", "y"):
            yield f"{module}.{axis}", config[module][axis], "m", "length"
    for edge in ("front", "side", "back"):
        yield f"bumper.{edge}", config["bumper"][edge], "m", "length"


@pytest.mark.parametrize("make", [swerve, tank], ids=["swerve", "tank"])
def test_choreo_project_is_a_complete_v2_file(make):
    c = choreo_project(make(), "Robot")
    assert set(c) == {"name", "version", "type", "variables", "config", "generationFeatures", "codegen"}
    assert c["name"] == "Robot" and c["version"] == 2 and type(c["version"]) is int
    assert c["type"] == ("Swerve" if make is swerve else "Differential")
    assert c["variables"] == {"expressions": {}, "poses": {}}
    assert c["generationFeatures"] == []
    assert c["codegen"] == {"root": None, "genVars": True, "genTrajData": True, "useChoreoLib": True}
    config = c["config"]
    assert set(config) == set(CHOREO_SCALARS) | {"frontLeft", "backLeft", "bumper"}
    assert set(config["frontLeft"]) == set(config["backLeft"]) == {"x", "y"}
    assert set(config["bumper"]) == {"front", "side", "back"}


@pytest.mark.parametrize("make", [swerve, tank], ids=["swerve", "tank"])
def test_choreo_every_exp_parses_to_its_val(make):
    for path, e, unit, kind in _exprs(choreo_project(make(), "Robot")["config"]):
        assert set(e) == {"exp", "val"}, path
        assert type(e["exp"]) is str and type(e["val"]) is float, path
        assert re.fullmatch(r"-?[0-9.]+(e[-+][0-9]+)?( [a-zA-Z *^0-9]+)?", e["exp"]), (path, e["exp"])
        assert units.parse(e["exp"], unit, kind, path) == pytest.approx(e["val"], rel=1e-12), path


def test_choreo_swerve_values_in_si_by_hand():
    cfg = swerve()
    config = choreo_project(cfg, "Robot")["config"]
    assert config["mass"] == {"exp": "61.2 kg", "val": 61.2}
    assert config["inertia"] == {"exp": "5.8 kg m ^ 2", "val": 5.8}
    assert config["cof"] == {"exp": "1.2", "val": 1.2}
    assert config["radius"]["val"] == pytest.approx(0.0508)
    assert config["gearing"]["val"] == pytest.approx(6.746031746)
    assert (config["frontLeft"]["x"]["val"], config["frontLeft"]["y"]["val"]) == pytest.approx(
        (0.263525, 0.288925)
    )
    assert (config["backLeft"]["x"]["val"], config["backLeft"]["y"]["val"]) == pytest.approx(
        (-0.263525, 0.288925)
    )
    # bumper: centre to edge; 35 in long, 33 in wide
    assert config["bumper"]["front"]["val"] == pytest.approx(0.4445)
    assert config["bumper"]["back"]["val"] == pytest.approx(0.4445)
    assert config["bumper"]["side"]["val"] == pytest.approx(0.4191)
    # vmax: the attainable 4.5 m/s at the motor, 4.5 m/s / 0.0508 m × 6.746 = 597.6 rad/s (5707 rpm)
    assert config["vmax"]["val"] == pytest.approx(4.5 / 0.0508 * 6.746031746, rel=1e-9)
    assert config["vmax"]["exp"].endswith(" rpm")
    assert float(config["vmax"]["exp"].split()[0]) == pytest.approx(597.6 / RPM, rel=1e-3)
    # tmax: one Kraken X60 at 60 A, kT·(60 A − 2 A) = 7.09/(366 − 2)·58 N·m
    assert config["tmax"]["val"] == pytest.approx(7.09 / 364 * 58, rel=1e-11)
    assert config["differentialTrackWidth"]["val"] == pytest.approx(0.57785)


def test_choreo_differential_tmax_is_one_sides_motors():
    cfg = tank()  # 3 NEOs a side
    config = choreo_project(cfg, "Tank")["config"]
    assert config["tmax"]["val"] == pytest.approx(3 * cfg.motor_max_torque, rel=1e-11)
    assert config["differentialTrackWidth"] == {"exp": "0.6 m", "val": 0.6}


def test_choreo_refuses_mecanum_and_bad_names():
    free, torque = motor_limits("NEO", 40.0)
    cfg = swerve(kind="mecanum", motor="NEO", motor_free_speed=free, motor_max_torque=torque, max_speed=1.0)
    with pytest.raises(ValueError, match="mecanum"):
        choreo_project(cfg, "Robot")
    for bad in ("", "  ", "a/b", "a\\b"):
        with pytest.raises(ValueError):
            choreo_project(swerve(), bad)


# ---- the config and its helpers -----------------------------------------------------------------


def test_estimated_moi_by_hand():
    # uniform plate 60 kg, 0.9 m × 0.8 m: 60·(0.81 + 0.64)/12 = 7.25 kg·m²
    assert estimated_moi(60.0, 0.9, 0.8) == pytest.approx(7.25, rel=1e-15)
    with pytest.raises(ValueError):
        estimated_moi(0.0, 0.9, 0.8)


def test_motor_limits_by_hand():
    free, torque = motor_limits("Kraken X60", 60.0)
    assert free == pytest.approx(6000 * 2 * math.pi / 60)
    assert torque == pytest.approx(7.09 / (366 - 2) * (60 - 2))
    # at 10 V and 90 % gearbox: ω scales with V, the torque per amp by η
    free, torque = motor_limits("Kraken X60", 60.0, voltage=10.0, efficiency=0.9)
    assert free == pytest.approx(6000 * RPM * 10 / 12)
    assert torque == pytest.approx(0.9 * 7.09 / (366 - 2) * (60 - 2 * 10 / 12))
    # a limit above stall current: the stall torque
    assert motor_limits("Kraken X60", 1000.0)[1] == pytest.approx(7.09)


@pytest.mark.parametrize(
    "changes, words",
    [
        ({"kind": "hovercraft"}, "kind"),
        ({"motor": "Warp Drive"}, "Warp Drive"),
        ({"motor_count": 8}, "motor_count must be 4"),
        ({"mass": float("nan")}, "mass"),
        ({"moi": -1.0}, "moi"),
        ({"max_speed": 9.0}, "free speed"),
        ({"bumper_width": 0.5}, "inside the bumpers"),
    ],
)
def test_config_refuses_what_cannot_be_a_robot(changes, words):
    with pytest.raises(ValueError, match=words):
        swerve(**changes)


def test_tank_needs_an_even_motor_count():
    with pytest.raises(ValueError, match="even"):
        tank(motor_count=3)


def test_exports_carry_no_float_noise(capsys):
    """(GC11): the default sprint's 34 in bumpers and 135 lb robot are 0.8636 m and 61.23496995 kg
    in PathPlanner's settings.json and Choreo's .chor (they were 0.8635999999999999 and
    61.23496995000001, and Choreo's exp "61.23496995000001 kg"); every number has at most 12
    significant digits; the card keeps full precision."""
    from gearhead.core.model import solve
    from gearhead.tui.cli import main

    assert main(["solve", "sprint", "--document", "pathplanner"]) == 0
    settings = json.loads(capsys.readouterr().out)
    assert settings["robotWidth"] == 0.8636 and settings["robotMass"] == 61.23496995
    assert main(["solve", "sprint", "--document", "choreo"]) == 0
    text = capsys.readouterr().out
    chor = json.loads(text)
    assert chor["config"]["mass"] == {"exp": "61.23496995 kg", "val": 61.23496995}
    for number in re.findall(r"-?\d+\.\d+(?:e[-+]\d+)?", text):
        assert len(number.lstrip("-").replace(".", "").split("e")[0].lstrip("0")) <= 12, number
    sol = solve("sprint", {})
    assert sol.inputs["robot_mass"].value == 61.23496995000001  # the card keeps its value (pint's)
