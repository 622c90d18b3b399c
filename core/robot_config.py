"""A drivetrain's robot configuration, exported for PathPlanner (settings.json) and Choreo (.chor).

Pure text/dict builders (standard library and gearhead core only); the calculator and the CLI decide
where the result goes. All values are SI, as Gearhead works inside.

Sources (read with `git show <commit>:<path>` from snapshots of the public repositories):

PathPlanner, mjansen4857/pathplanner at e02bbf3176588166e8fe5192ab8dea85f6d62f7a (tag v2026.1.2):
- `pathplannerlib-python/pathplannerlib/config.py` (last changed 5d514694, 2024-11-10):
  `RobotConfig.fromGUISettings()` reads `holonomicMode`, `robotMass`, `robotMOI`, `driveWheelRadius`,
  `driveGearing`, `maxDriveSpeed`, `wheelCOF`, `driveMotorType`, `driveCurrentLimit` and then either
  the eight `{fl,fr,bl,br}Module{X,Y}` (holonomic) or `robotTrackwidth` (differential); a missing key
  raises KeyError (Java: NullPointerException, C++: json.at throws). `numMotors = 1 if holonomic
  else 2` is hard-coded, and `ModuleConfig` multiplies `driveCurrentLimit` by it, so the file holds a
  limit per motor. The same file ships in PyPI's robotpy-pathplannerlib 2026.1.2 (checked equal).
- The same reader in Java and C++: `pathplannerlib/src/main/java/com/pathplanner/lib/config/
  RobotConfig.java` (148181f2) and `pathplannerlib/src/main/native/cpp/pathplanner/lib/config/
  RobotConfig.cpp` (52b46b11); motor strings, case-sensitive: krakenX60, krakenX60FOC, falcon500,
  falcon500FOC, vortex, NEO, CIM, miniCIM (also the GUI's `lib/trajectory/dc_motor.dart`).
- GUI keys `robotWidth`, `robotLength` (bumper size, m), `bumperOffsetX/Y`: `lib/util/prefs.dart`
  and `lib/pages/home_page.dart` (e1c6c53c, 2026-01-11); the GUI draws with them, the library ignores
  them.
- `Writerside/topics/Robot-Config.md` (207d36a6, 2024-11-15): "Calculating a Rough MOI Estimate",
  I = 1/12·mass·(length² + width²), "likely ... inaccurate ... as it assumes a uniform distribution
  of mass"; the current limit is called a supply limit there, but the library's maths uses it as a
  torque-producing (stator) clamp, which is what Gearhead's `current_limit` is.

Choreo, SleipnirGroup/Choreo at 9beecedeadde4341ead9d31f409b9231abc944b9 (v2026.0.3-29):
- `src-core/src/spec/project.rs` (4353a4a2, 2026-02-16): `ProjectFile` {name, version, type
  (default Swerve), variables {expressions, poses}, config, generationFeatures (default []), codegen
  {root: Option<String>, genVars, genTrajData, useChoreoLib}}; `RobotConfig<Expr>` camelCase with
  frontLeft, backLeft {x, y}, mass, inertia, gearing, radius, vmax (motor rad/s), tmax (motor N·m),
  cof, bumper {front, side, back}, differentialTrackWidth, none optional.
- `src-core/src/spec/mod.rs` (a9b06e58): `Expr {exp: String, val: f64}`;
  `src-core/src/spec/project_schema_version.rs` (f3bc4f6f): version 2;
  `src-core/src/spec/trajectory.rs` (4353a4a2): `DriveType` is Swerve or Differential only (no
  mecanum).
- `src/document/ExpressionStore.tsx` (47e6099f): mathjs with the units "RPM" and "rpm" added;
  `src/document/RobotConfigStore.ts` (1bc4288c) writes its default vmax in "rpm".
- `test-jsons/project/2/swerve.chor`, `differential.chor` (7b59ff80): the reference files.
- `src-core/src/generation/transformers/drivetrain_and_bumpers.rs` (3884e196): bumpers are distances
  from the robot centre to the front, side and back edges; `wheel_max_torque = tmax·gearing`.
- `trajoptlib/src/differential_trajectory_generator.cpp` (1e8c1cfa): `num_wheels = 2`, each side's
  force ≤ tmax·G/r, so for a differential drive tmax is the torque of one side's motors together.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from .constants import RPM
from .gains_numbers import export_number
from .motors import lookup, motor_names, system

KINDS = ("swerve", "tank", "mecanum")

# Gearhead motor name (core.motors) -> PathPlanner's driveMotorType (all eight PathPlanner knows)
PATHPLANNER_MOTOR_TYPES: dict[str, str] = {
    "Kraken X60": "krakenX60",
    "Kraken X60 FOC": "krakenX60FOC",
    "Falcon 500": "falcon500",
    "Falcon 500 FOC": "falcon500FOC",
    "NEO Vortex": "vortex",
    "NEO": "NEO",
    "CIM": "CIM",
    "MiniCIM": "miniCIM",
}

CHOREO_PROJECT_VERSION = 2  # PROJECT_SCHEMA_VERSION in Choreo 2026

# PathPlannerLib's model holds 4 drive motors in all: 1 per swerve module, 2 per differential side
_PATHPLANNER_MOTORS = 4


@dataclass(frozen=True)
class RobotConfig:
    """A drivetrain as the path planners see it; SI units. Checked on construction (ValueError)."""

    kind: str  # "swerve", "tank" or "mecanum"
    mass: float  # kg, robot with battery and bumpers
    moi: float  # kg·m² about the vertical axis through the centre
    wheel_radius: float  # m
    gearing: float  # drive reduction (motor turns per wheel turn)
    motor: str  # Gearhead motor name (core.motors)
    motor_count: int  # all drive motors (swerve: one per module; tank: both sides)
    current_limit: float  # A, stator limit per motor
    wheel_cof: float
    max_speed: float  # m/s, attainable top speed
    trackwidth: float  # m, left-right distance between wheel (module) centres
    wheelbase: float  # m, front-back distance between wheel (module) centres
    bumper_width: float  # m, overall left-right with bumpers
    bumper_length: float  # m, overall front-back with bumpers
    motor_free_speed: float  # rad/s, one motor at the battery voltage
    motor_max_torque: float  # N·m, one motor at its current limit (after losses), what Choreo's tmax wants

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"drivetrain kind {self.kind!r} is not one of {', '.join(KINDS)}")
        if self.motor not in motor_names():
            raise ValueError(f"motor {self.motor!r} is not a Gearhead motor (core.motors)")
        if isinstance(self.motor_count, bool) or not isinstance(self.motor_count, int):
            raise ValueError(f"motor_count must be a whole number, got {self.motor_count!r}")
        for f in fields(self):
            if f.name in ("kind", "motor", "motor_count"):
                continue
            v = getattr(self, f.name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ValueError(f"{f.name} must be a positive finite number, got {v!r}")
        if self.kind in ("swerve", "mecanum") and self.motor_count != 4:
            wheels = "modules" if self.kind == "swerve" else "wheels"
            raise ValueError(
                f"a {self.kind} drive here has one drive motor on each of its 4 {wheels}: "
                f"motor_count must be 4, got {self.motor_count}"
            )
        if self.kind == "tank" and (self.motor_count < 2 or self.motor_count % 2):
            raise ValueError(
                f"a tank drive has the same number of motors on each side: motor_count must be even "
                f"and at least 2, got {self.motor_count}"
            )
        if self.trackwidth >= self.bumper_width or self.wheelbase >= self.bumper_length:
            raise ValueError(
                f"the wheels ({self.trackwidth:.4g} m × {self.wheelbase:.4g} m between centres) must lie "
                f"inside the bumpers ({self.bumper_width:.4g} m wide × {self.bumper_length:.4g} m long)"
            )
        floor_free_speed = self.motor_free_speed * self.wheel_radius / self.gearing
        if self.max_speed > floor_free_speed * (1 + 1e-9):
            raise ValueError(
                f"max_speed {self.max_speed:.4g} m/s is above the free speed at the wheels, "
                f"{floor_free_speed:.4g} m/s (motor free speed × wheel radius / gearing)"
            )

    @property
    def motors_per_unit(self) -> int:
        """Motors driving one unit the planners model: a tank side, a swerve module, a mecanum wheel."""
        return self.motor_count // 2 if self.kind == "tank" else self.motor_count // 4

    def module_positions(self) -> dict[str, tuple[float, float]]:
        """Wheel (module) centres from the robot centre, m, WPILib axes (+x forward, +y left)."""
        x, y = self.wheelbase / 2, self.trackwidth / 2
        return {"fl": (x, y), "fr": (x, -y), "bl": (-x, y), "br": (-x, -y)}


def motor_limits(
    motor: str,
    current_limit: float,
    *,
    voltage: float = 12.0,
    efficiency: float = 1.0,
    source: str = "wpilib",
) -> tuple[float, float]:
    """(free speed rad/s, torque N·m) of one motor at `voltage`: the torque at the stator
    `current_limit` (or at stall, when that is lower), after the gearbox efficiency, from eqs. (1)-(9)
    of core.motors: τ = kT·(min(i_lim, ĩs) − ĩf). These are RobotConfig's motor_free_speed and
    motor_max_torque for a calculator that has no sharper figures."""
    m, _ = lookup(motor, source)
    s = system(m, 1, voltage, efficiency)
    torque = s.kt * (min(current_limit, s.stall_current) - s.free_current)
    return s.free_speed, max(torque, 0.0)


def estimated_moi(mass: float, length: float, width: float) -> float:
    """An ESTIMATE of the yaw moment of inertia, kg·m²: the robot as a uniform rectangular plate
    about its centre, I = m·(L² + W²)/12 (mass kg, length and width m, e.g. the bumper outline).

    This is PathPlanner's "Rough MOI Estimate" (Writerside/topics/Robot-Config.md, 207d36a6), which
    warns it "will likely lead to an inaccurate estimate as it assumes a uniform distribution of
    mass"; a real robot, its battery and superstructure nearer the centre, is usually below it. CAD
    or a sysId measurement (PathPlanner: I = m·(trackwidth/2)·kA_angular/kA_linear) is better.
    """
    for name, v in (("mass", mass), ("length", length), ("width", width)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
            raise ValueError(f"{name} must be a positive finite number, got {v!r}")
    return mass * (length**2 + width**2) / 12


def pathplanner_motor_type(motor: str) -> str | None:
    """PathPlanner's driveMotorType for a Gearhead motor name, None when PathPlanner has none (e.g.
    Kraken X44, Minion, NEO 550: PathPlannerLib would refuse the file)."""
    return PATHPLANNER_MOTOR_TYPES.get(motor)


def pathplanner_settings(cfg: RobotConfig) -> dict:
    """The robot block of PathPlanner's deploy/pathplanner/settings.json, in the GUI's key order.

    Holds every key PathPlannerLib's `RobotConfig.fromGUISettings()` reads, plus the GUI's drawing
    keys robotWidth, robotLength (bumper size) and bumperOffsetX/Y (0: the bumpers are centred). It
    leaves out the path keys (pathFolders, defaultMaxVel, ...): merge this into an existing file, or
    write it alone and the GUI fills those with its defaults.

    - swerve and mecanum: holonomicMode true, the eight module keys from trackwidth and wheelbase
      (FL (+L/2, +W/2), FR (+L/2, −W/2), BL (−L/2, +W/2), BR (−L/2, −W/2), +x forward, +y left),
      robotTrackwidth also written (the GUI keeps it; the library ignores it). A mecanum robot goes
      in as holonomic, as teams run it: PathPlannerLib then models its wheels as swerve modules,
      which can push their full traction any way, so it overrates a mecanum drive sideways.
    - tank: holonomicMode false and robotTrackwidth; no module keys.
    - driveCurrentLimit is per motor (the library multiplies it by its motors per module) and is
      the stator limit. PathPlannerLib hard-codes 4 drive motors in all (1 per swerve module, 2 per
      differential side). A tank drive with another count (2, 6, 8 motors) gets the limit scaled by
      motor_count/4, so the total torque-producing current, and with it the current-limited force,
      is the robot's: 6 motors at 40 A are written as 60 A. The back-EMF side of the curve (near top
      speed) is still that of 2 motors per side.
    - maxDriveSpeed is the attainable top speed (PathPlanner's "True Max Drive Speed"), from which
      the library infers a constant friction torque.

    Raises ValueError for a motor PathPlanner has no type for.
    """
    motor_type = pathplanner_motor_type(cfg.motor)
    if motor_type is None:
        raise ValueError(
            f"PathPlanner has no drive motor type for {cfg.motor}; it accepts "
            + ", ".join(f"{name} ({t})" for name, t in PATHPLANNER_MOTOR_TYPES.items())
        )
    holonomic = cfg.kind in ("swerve", "mecanum")
    current_limit = float(cfg.current_limit) * cfg.motor_count / _PATHPLANNER_MOTORS
    r = export_number  # 12 significant digits: no float noise (0.8635999999999999 is 0.8636)
    out: dict = {
        "robotWidth": r(cfg.bumper_width),
        "robotLength": r(cfg.bumper_length),
        "holonomicMode": holonomic,
        "robotMass": r(cfg.mass),
        "robotMOI": r(cfg.moi),
        "robotTrackwidth": r(cfg.trackwidth),
        "driveWheelRadius": r(cfg.wheel_radius),
        "driveGearing": r(cfg.gearing),
        "maxDriveSpeed": r(cfg.max_speed),
        "driveMotorType": motor_type,
        "driveCurrentLimit": r(current_limit),
        "wheelCOF": r(cfg.wheel_cof),
    }
    if holonomic:
        for corner, (x, y) in cfg.module_positions().items():
            out[f"{corner}ModuleX"] = r(x)
            out[f"{corner}ModuleY"] = r(y)
    out["bumperOffsetX"] = 0.0
    out["bumperOffsetY"] = 0.0
    return out


def _expr(si: float, unit: str = "", per_unit: float = 1.0) -> dict:
    """Choreo's {"exp", "val"}: `exp` a mathjs expression in `unit` (worth `per_unit` SI each),
    `val` its SI value, the two consistent (val is what exp evaluates to, to 12 digits); the number
    to 12 significant digits (core.gains_numbers.export_number: "61.23496995 kg", not the float
    noise of 61.23496995000001)."""
    text = format(export_number(float(si) / per_unit), ".12g")
    val = float(text) if per_unit == 1.0 else export_number(float(text) * per_unit)
    return {"exp": f"{text} {unit}" if unit else text, "val": val}


def choreo_project(cfg: RobotConfig, name: str) -> dict:
    """A complete, minimal Choreo project (.chor, schema version 2, Choreo 2026) for the robot.

    - type "Swerve" (swerve) or "Differential" (tank); mecanum is refused: Choreo plans neither.
    - variables empty, generationFeatures [], codegen {root: null, genVars, genTrajData,
      useChoreoLib: true} as Choreo's own default project.
    - config, every value {"exp", "val"} with val in SI and exp in m, kg, kg m ^ 2, rpm, N * m:
      frontLeft/backLeft the wheel centres (+wheelbase/2, +trackwidth/2), (−wheelbase/2,
      +trackwidth/2) (kept for a differential project too, as Choreo's reference file does);
      mass, inertia (moi), gearing, radius, cof; bumper front = back = bumper_length/2, side =
      bumper_width/2; differentialTrackWidth = trackwidth.
    - vmax: the attainable top speed as a motor speed, max_speed·gearing/wheel_radius (not the free
      speed: Choreo's docs suggest about 80 % of free speed for headroom; lower it there for more).
    - tmax: swerve, one module's motor, motor_max_torque. Differential: TrajoptLib has one wheel
      per side, each limited to tmax·G/r, so tmax is the torque of one side's motors together,
      motor_max_torque·motor_count/2 (Choreo's docs say "each drive motor", which holds for one
      motor per side). Choreo's "Theoretical" panel uses 4·tmax for its motor acceleration even for
      a differential drive, so its readout doubles there; the generated paths do not.

    Choreo has no motor type, current limit or efficiency: the motor is only vmax and tmax.
    """
    if not isinstance(name, str) or not name.strip():
        raise ValueError("a Choreo project needs a name")
    if any(c in name for c in "/\\") or any(ord(c) < 32 for c in name):
        raise ValueError(f"Choreo project name {name!r} must not hold a path separator or control character")
    if cfg.kind == "mecanum":
        raise ValueError(
            "Choreo plans swerve and differential (tank) drives only (its DriveType is Swerve or "
            "Differential): a mecanum robot cannot be exported to Choreo"
        )
    x, y = cfg.wheelbase / 2, cfg.trackwidth / 2
    m = "m"
    return {
        "name": name,
        "version": CHOREO_PROJECT_VERSION,
        "type": "Swerve" if cfg.kind == "swerve" else "Differential",
        "variables": {"expressions": {}, "poses": {}},
        "config": {
            "frontLeft": {"x": _expr(x, m), "y": _expr(y, m)},
            "backLeft": {"x": _expr(-x, m), "y": _expr(y, m)},
            "mass": _expr(cfg.mass, "kg"),
            "inertia": _expr(cfg.moi, "kg m ^ 2"),
            "cof": _expr(cfg.wheel_cof),
            "gearing": _expr(cfg.gearing),
            "radius": _expr(cfg.wheel_radius, m),
            "vmax": _expr(cfg.max_speed * cfg.gearing / cfg.wheel_radius, "rpm", RPM),
            "tmax": _expr(cfg.motor_max_torque * cfg.motors_per_unit, "N * m"),
            "bumper": {
                "front": _expr(cfg.bumper_length / 2, m),
                "side": _expr(cfg.bumper_width / 2, m),
                "back": _expr(cfg.bumper_length / 2, m),
            },
            "differentialTrackWidth": _expr(cfg.trackwidth, m),
        },
        "generationFeatures": [],
        "codegen": {"root": None, "genVars": True, "genTrajData": True, "useChoreoLib": True},
    }
