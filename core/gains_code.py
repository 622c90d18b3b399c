"""Gains as code: a profiled move's feedforward and feedback gains, profile limits and current limits
written as the code a team pastes into its robot project, for WPILib (Java, Python), CTRE Phoenix 6
(TalonFXConfiguration) and REVLib (SparkMaxConfig). Pure text builders (standard library only); the
calculators declare them as Documents (core.declarations), so ctrl+e and `solve --document NAME`
offer them.

Gearhead's gains are SI per unit of the mechanism's coordinate q (an elevator: metres of carriage
travel; kS, kG in V, kV in V·s/m, kA in V·s²/m, kP in V/m, kD in V·s/m). Each target's units:
- WPILib (ElevatorFeedforward or ArmFeedforward, ProfiledPIDController, TrapezoidProfile.Constraints):
  SI as they are (WPILib is unit-agnostic; the profile and the gains share the metre, or for an
  arm the radian from horizontal, ArmFeedforward's kG·cos θ).                                   (GC1)
- Phoenix 6 (CTRE docs, Slot0Configs: kP "output per unit of error" with position in rotations,
  kV per rps, kA per rps/s, kD per rps; MotionMagicConfigs in rps and rps/s; voltage output with
  MotionMagicVoltage): positions in mechanism rotations, the drum's, with
  Feedback.SensorToMechanismRatio = G (rotor turns per drum turn). One drum turn moves the carriage
  L = 2π·r·k metres (r the drum radius, k the rigging factor), so a gain per metre becomes
      kP_rot = kP·L,  kD_rot = kD·L,  kV_rot = kV·L,  kA_rot = kA·L  (V per rotation, rps, rps/s);
      cruise = v_max/L (rps),  acceleration = a_max/L (rps/s);  kS, kG unchanged (V)         (GC2)
  GravityType Elevator_Static (a constant kG); MotionMagicJerk = 0 (no jerk limit: a trapezoid).
  An arm: positions in arm rotations (L = 2π rad a rotation, SensorToMechanismRatio = G), GravityType
  Arm_Cosine, which needs the sensor at 0 with the arm horizontal (CTRE's GravityTypeValue docs).
  (Sources: CrossTheRoadElec/Phoenix6-Examples at b6dd147 "Bump to 26.2.0",
  java/MotionMagic/src/main/java/frc/robot/Robot.java: cfg.Feedback.SensorToMechanismRatio,
  cfg.MotionMagic.MotionMagicCruiseVelocity/Acceleration/Jerk, cfg.Slot0.kS/kV/kA/kP/kI/kD;
  java/CurrentLimits: CurrentLimits.StatorCurrentLimit(Enable), SupplyCurrentLimit(Enable);
  GravityTypeValue.Elevator_Static in com.ctre.phoenix6.signals.)
- REVLib 2026 (REVrobotics/REVLib-Examples at 6b03aa4 "Update examples to use 2026 WPILib and
  REVLib", Java/SPARK/MAXMotion: closedLoop.p/i/d/outputRange, closedLoop.feedForward.kV "now in
  Volts", closedLoop.maxMotion.cruiseVelocity/maxAcceleration/allowedProfileError; REV's
  FeedForwardConfig docs: kS, kV, kA, kG in volts per native unit): the encoder's conversion
  factors make the native units SI, positionConversionFactor = L/G (m per motor rotation) and
  velocityConversionFactor = L/(60·G) (m/s per rpm), so kS, kG, kV, kA, the cruise velocity and the
  acceleration are Gearhead's as they are. The SPARK's PID output is normalised (duty cycle, ±1)
  and runs at 1 kHz with kD on the error's change per 1 ms step (REV's "SPARK MAX Closed Loop
  Control" page: kP normalized/native, kD normalized/(native/ms)); with voltageCompensation(V_b) a
  duty of 1 is V_b volts:
      kP_rev = kP/V_b,  kD_rev = kD/(V_b · 1 ms)                                               (GC3)
  smartCurrentLimit is the stator limit (whole amps); REVLib has no supply current limit, said in
  a comment.
The exponential profile (WPILib ExponentialProfile, max input U volts on the plant kV, kA; the
profiled move's choice, core.sim.profiled (P12)-(P15)):
- WPILib: ExponentialProfile.Constraints.fromCharacteristics(U, kV, kA) with a PIDController, the
  profile advanced each period by the robot code (no ProfiledPIDController takes it); robotpy binds
  it as ExponentialProfileMeterVolts only, its units labels (an arm's radians go through unchanged).
- Phoenix 6 Motion Magic Expo (MotionMagicExpoVoltage; CTRE's Motion Magic page: "Dividing the supply
  voltage by kV results in the maximum velocity of the profile", by kA the maximum acceleration from
  0; MotionMagicExpo_kV in V/rps, MotionMagicExpo_kA in V/(rps/s), always volts): its profile drives
  the whole supply voltage V_b, ours U, so the same profile (v_m = U/kV, a_0 = U/kA) takes
      Expo_kV = kV·L·V_b/U,  Expo_kA = kA·L·V_b/U;  MotionMagicCruiseVelocity = 0 (no cap)    (GC6)
  (V_b the entered battery voltage: the device reads its own supply, which sags).
- REVLib: MAXMotion has no exponential profile (MAXMotionConfig.MAXMotionPositionMode offers
  kMAXMotionTrapezoidal only): the document says so, keeps the closed loop and feedforward, and
  leaves the profile to the roboRIO (WPILib's, sending each setpoint as a position request).
  An arm (q the angle from horizontal in rad, L = 2π rad an arm turn): the factors make the native
  units radians, positionConversionFactor = 2π/G, velocityConversionFactor = 2π/(60·G), and the
  gravity term is REVLib's kCos with kCosRatio, not kG (REVLib keeps one of the two). REVLib 2026's
  FeedForwardConfig (javadoc of kCos and kCosRatio; the "Feed Forward Control" page's table: kCos
  "Arm/rotary mechanism gravity feedforward. Feedback sensor must be configured to 0 =
  horizontal", kCosRatio "Converts feedback sensor readings to mechanism rotations"): kCos, in
  volts, "is multiplied by the cosine of the absolute position of the mechanism", that position
  being the native position times kCosRatio, which "is applied after the conversion factor and
  should convert from those units to absolute rotations of your mechanism". So the SPARK adds
  kCos·cos(2π·kCosRatio·q_native), and with q_native in rad
      kCos = kG,  kCosRatio = 1/L = 1/(2π)  (arm rotations per rad)                           (GC3a)
  which is ArmFeedforward's kG·cos θ when the encoder reads 0 with the arm horizontal, positive up.
Ranges: a Phoenix 6 value outside CTRE's documented bounds (PHOENIX6_RANGES, e.g. MotionMagicAcceleration
0 to 9999 rps/s, MotionMagicExpo_kV 0.001 to 100 V per rps, SensorToMechanismRatio ±1000) is marked
OUT OF RANGE on its line and listed, with its range, at the top of the document               (GC9)
Controllers: phoenix6 (TalonFXConfiguration) is written only for the Talon FX motors (Falcon 500,
Kraken X60, X44), revlib (SparkMaxConfig on the primary encoder) only for REV's brushless NEOs; any
other motor is refused with the pairs that work (the WPILib documents take any)            (GC10)
WPILib: a negative kP, kD, kV or kA (or a period ≤ 0), which its constructors throw on, is refused (GC12)
Numbers: every exported number to 12 significant digits (export_number), the card's unrounded (GC11)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

REV_LOOP_PERIOD = 1e-3  # s: the SPARK's closed loop runs at 1 kHz (GC3)

# Phoenix 6's documented bounds of each value a document writes (phoenix6 26.3.0, configs/
# config_groups.py: "Minimum Value", "Maximum Value" of FeedbackConfigs, Slot0Configs,
# MotionMagicConfigs, CurrentLimitsConfigs; the same in CTRE's Java and C++ API pages). A value
# outside is marked on its line and listed at the top of the document (GC9).
PHOENIX6_RANGES = {
    "SensorToMechanismRatio": (-1000.0, 1000.0, ""),
    "kS": (-128.0, 127.0, "V"),
    "kG": (-128.0, 127.0, "V"),
    "kV": (0.0, 3.4e38, ""),
    "kA": (0.0, 3.4e38, ""),
    "kP": (0.0, 3.4e38, ""),
    "kD": (0.0, 3.4e38, ""),
    "MotionMagicCruiseVelocity": (0.0, 9999.0, "rps"),
    "MotionMagicAcceleration": (0.0, 9999.0, "rps/s"),
    "MotionMagicExpo_kV": (0.001, 100.0, "V per rps"),
    "MotionMagicExpo_kA": (1e-5, 100.0, "V per rps/s"),
    "StatorCurrentLimit": (0.0, 800.0, "A"),
    "SupplyCurrentLimit": (0.0, 800.0, "A"),
}
EXPO_KA_RANGE = PHOENIX6_RANGES["MotionMagicExpo_kA"][:2]
# What each document's controller can drive (GC10): TalonFXConfiguration is the Talon FX's, built
# into these motors; SparkMaxConfig's closed loop on the primary encoder is a REV brushless motor's
# (its hall sensor). The WPILib documents run on the roboRIO with any motor controller.
PHOENIX6_MOTORS = (
    "Falcon 500",
    "Falcon 500 FOC",
    "Kraken X60",
    "Kraken X60 FOC",
    "Kraken X44",
    "Kraken X44 FOC",
)
REVLIB_MOTORS = ("NEO", "NEO 550", "NEO 2.0", "NEO Vortex")


def check_controller(document: str, motor: str) -> None:
    """(GC10): a ValueError naming the pairs that work when `document` cannot drive `motor`."""
    allowed = {"phoenix6": PHOENIX6_MOTORS, "revlib": REVLIB_MOTORS}[document]
    if not motor or motor in allowed:
        return
    raise ValueError(
        f"the {document} document configures a "
        f"{'Talon FX' if document == 'phoenix6' else 'SPARK MAX'}, which cannot drive a {motor}. "
        f"Pairs that work: phoenix6 with {', '.join(PHOENIX6_MOTORS)}; revlib with "
        f"{', '.join(REVLIB_MOTORS)}; wpilib-java and wpilib-python with any motor (the loop on the roboRIO)"
    )


def check_wpilib(g) -> None:
    """(GC12): WPILib 2026.2.2 takes no negative gain (PIDController: "Kp must be a non-negative
    number", Kd likewise; ArmFeedforward, ElevatorFeedforward, SimpleMotorFeedforward: kv, ka) nor a
    period ≤ 0: Java's constructors throw IllegalArgumentException, C++'s and robotpy's report the
    error and zero the gains (no feedback, measured in robotpy). Such a document is refused, naming
    the value and the range (LQR gives a negative kP or kD for some tolerances and delays)."""
    for name in ("kP", "kD", "kV", "kA", "period"):
        x = getattr(g, name, 0.0)
        if x < 0 or (name == "period" and x <= 0):
            raise ValueError(
                f"{name} = {x:.6g}: WPILib takes {name} {'> 0' if name == 'period' else '≥ 0'} (Java "
                "throws IllegalArgumentException, C++ and robotpy zero the gains); enter the feedback gains "
                "(feedback = entered) or change the LQR tolerances or the sensor delay"
            )


def phoenix6_out_of_range(values: dict[str, float]) -> list[str]:
    """(GC9): each value outside Phoenix 6's documented bounds, said with its range."""
    out = []
    for name, x in values.items():
        if name not in PHOENIX6_RANGES:
            continue
        lo, hi, unit = PHOENIX6_RANGES[name]
        if not lo <= x <= hi:
            out.append(
                f"{name} = {x:.6g} is outside CTRE's documented range {lo:g} to {hi:g}{' ' + unit if unit else ''}"
            )
    return out


def _flag_phoenix6(lines: list[str], values: dict[str, float], hint: str) -> list[str]:
    """(GC9): mark each out-of-range value's line and list them at the top (after the header)."""
    problems = phoenix6_out_of_range(values)
    if not problems:
        return lines
    marked = []
    for line in lines:
        for name in values:
            if f".{name} = " in line and any(p.startswith(f"{name} = ") for p in problems):
                lo, hi, unit = PHOENIX6_RANGES[name]
                line += f" // OUT OF RANGE: {lo:g} to {hi:g}{' ' + unit if unit else ''}"
        marked.append(line)
    at = next(i for i, line in enumerate(marked) if line.startswith("import "))
    note = [
        "// OUT OF RANGE for Phoenix 6 (the device refuses these values; the lines are marked):",
        *(f"//   {p}" for p in problems),
        f"// {hint}",
    ]
    return marked[:at] + note + marked[at:]


@dataclass(frozen=True)
class Gains:
    """What a profiled move exports, SI per unit of the coordinate (metres for an elevator)."""

    kS: float
    kG: float
    kV: float
    kA: float
    kP: float
    kD: float
    max_velocity: float
    max_acceleration: float
    period: float  # s, the loop the LQR gains were discretised for
    ratio: float  # G, motor turns per drum turn
    metres_per_rotation: float  # L: q per drum turn, 2π·r·k m (elevator) or 2π rad per arm turn
    battery_voltage: float
    tolerance: float  # settle tolerance, m
    stator_limit: float | None = None  # A per motor, None when off
    supply_limit: float | None = None
    title: str = "Elevator"
    arm: bool = False  # q is the arm's angle from horizontal (rad): ArmFeedforward, Arm_Cosine
    max_input: float | None = None  # V: the exponential profile's U (GC6); None for a trapezoid
    motor: str = ""  # Gearhead's motor name: which controllers can drive it (GC10); "" unchecked


def _u(g: Gains) -> str:
    return "rad" if g.arm else "m"


def _ff(g: Gains) -> str:
    return "ArmFeedforward" if g.arm else "ElevatorFeedforward"


EXPORT_DIGITS = 12  # significant digits of an exported number (GC11)


def export_number(x: float) -> float:
    """(GC11): x to EXPORT_DIGITS significant digits. An entry is typed with a handful of digits and
    a unit conversion (135 lb = 61.23496995 kg, 34 in = 0.8636 m) is exact within 12, so 12 keep
    every digit the entries give and drop a double's arithmetic noise (61.23496995000001): the
    exported loop differs from the card's by under 1e-12 of each value. The card keeps full precision."""
    if not math.isfinite(x):
        raise ValueError(f"{x} cannot be exported")
    return float(f"{float(x):.{EXPORT_DIGITS}g}")


def _num(x: float) -> str:
    """A float as a literal Java and Python both read back to the same double, rounded (GC11)."""
    return repr(export_number(x))


def phoenix6_values(g: Gains) -> dict[str, float]:
    """(GC2): the Slot0 and MotionMagic values, in drum rotations ((GC6) for Motion Magic Expo)."""
    L = g.metres_per_rotation
    if g.max_input is not None:
        expo = {
            "MotionMagicCruiseVelocity": 0.0,
            "MotionMagicExpo_kV": g.kV * L * g.battery_voltage / g.max_input,
            "MotionMagicExpo_kA": g.kA * L * g.battery_voltage / g.max_input,
        }
    else:
        expo = {
            "MotionMagicCruiseVelocity": g.max_velocity / L,
            "MotionMagicAcceleration": g.max_acceleration / L,
        }
    return {
        "SensorToMechanismRatio": g.ratio,
        "kS": g.kS,
        "kG": g.kG,
        "kV": g.kV * L,
        "kA": g.kA * L,
        "kP": g.kP * L,
        "kD": g.kD * L,
        **expo,
    }


def revlib_values(g: Gains) -> dict[str, float]:
    """(GC3): the encoder's conversion factors and the closed loop's gains; an arm's gravity term as
    kCos and kCosRatio (GC3a) in place of kG."""
    L, G, Vb = g.metres_per_rotation, g.ratio, g.battery_voltage
    gravity = {"kCos": g.kG, "kCosRatio": 1.0 / L} if g.arm else {"kG": g.kG}
    return {
        "positionConversionFactor": L / G,
        "velocityConversionFactor": L / G / 60.0,
        "voltageCompensation": Vb,
        "p": g.kP / Vb,
        "d": g.kD / (Vb * REV_LOOP_PERIOD),
        "kS": g.kS,
        "kV": g.kV,
        "kA": g.kA,
        **gravity,
        "cruiseVelocity": g.max_velocity,
        "maxAcceleration": g.max_acceleration,
        "allowedProfileError": g.tolerance,
    }


def _header(g: Gains, comment: str) -> str:
    return (
        f"{comment} {g.title} gains from Gearhead's profiled move (SI: "
        f"{'radians of arm angle from horizontal' if g.arm else 'metres of carriage travel'}).\n"
        f"{comment} kP and kD are LQR gains for a {g.period * 1000:g} ms loop unless entered; a loop on the\n"
        f"{comment} motor controller (1 kHz) may take them higher: re-solve with its period.\n"
    )


def wpilib_python(g: Gains) -> str:
    check_wpilib(g)
    if g.max_input is not None:
        return _wpilib_python_exponential(g)
    return (
        _header(g, "#") + f"from wpimath.controller import {_ff(g)}, ProfiledPIDController\n"
        "from wpimath.trajectory import TrapezoidProfile\n\n"
        f"kS = {_num(g.kS)}  # V\n"
        f"kG = {_num(g.kG)}  # V\n"
        f"kV = {_num(g.kV)}  # V*s/{_u(g)}\n"
        f"kA = {_num(g.kA)}  # V*s^2/{_u(g)}\n"
        f"kP = {_num(g.kP)}  # V/{_u(g)}\n"
        f"kD = {_num(g.kD)}  # V*s/{_u(g)}\n"
        f"MAX_VELOCITY = {_num(g.max_velocity)}  # {_u(g)}/s\n"
        f"MAX_ACCELERATION = {_num(g.max_acceleration)}  # {_u(g)}/s^2\n"
        f"PERIOD = {_num(g.period)}  # s\n\n"
        f"feedforward = {_ff(g)}(kS, kG, kV, kA, PERIOD)\n"
        "controller = ProfiledPIDController(\n"
        "    kP, 0.0, kD, TrapezoidProfile.Constraints(MAX_VELOCITY, MAX_ACCELERATION), PERIOD\n"
        ")\n" + _usage(g)
    )


def _usage(g: Gains) -> str:
    """How the loop calls the feedforward: an arm's takes the angle first (its two-argument call
    reads (angle, velocity): passing two velocities there made the velocity an angle)."""
    if g.arm:
        return (
            "# each period: sp = controller.getSetpoint(); u = controller.calculate(angle)\n"
            "#             nxt = controller.getSetpoint()  # after calculate: the next setpoint\n"
            "#             volts = u + feedforward.calculate(sp.position, sp.velocity, nxt.velocity)\n"
            + _arm_ff_note("#")
        )
    return (
        "# each period: v = controller.getSetpoint().velocity; u = controller.calculate(position)\n"
        "#             volts = u + feedforward.calculate(v, controller.getSetpoint().velocity)\n"
    )


def _arm_ff_note(c: str) -> str:
    """What ArmFeedforward's discrete calculate computes (WPILib 2026.2.2, core.sim.profiled (P5a)):
    the card simulates that, not an inversion of the plant."""
    return (
        f"{c} (WPILib 2026.2.2's ArmFeedforward: kS*sgn(v) + kV*v + kA*(next - v)/period + kG*cos(angle)\n"
        f"{c}  while kA < 0.1 V*s^2/rad, else an RK4 inversion of the arm; Gearhead's card simulates it)\n"
    )


def _java_usage(g: Gains) -> str:
    """How the Java loop calls the feedforward: calculateWithVelocities is the discrete one, as the
    card simulates ((P5), (P5a)); ArmFeedforward's calculate(a, b) reads (angle, velocity),
    ElevatorFeedforward's (velocity, acceleration): neither is the next velocity."""
    args = "sp.position, sp.velocity, next.velocity" if g.arm else "sp.velocity, next.velocity"
    return (
        "// Each period: var sp = controller.getSetpoint(); double u = controller.calculate(position);\n"
        "//   var next = controller.getSetpoint(); // after calculate: the next setpoint\n"
        f"//   volts = u + feedforward.calculateWithVelocities({args});\n"
        + (
            _arm_ff_note("//")
            if g.arm
            else "// (calculateWithVelocities is the discrete feedforward; calculate(a, b) reads b as an acceleration)\n"
        )
    )


def wpilib_java(g: Gains) -> str:
    check_wpilib(g)
    if g.max_input is not None:
        return _wpilib_java_exponential(g)
    cls = f"{g.title.replace(' ', '')}Gains"
    return (
        _header(g, "//") + f"import edu.wpi.first.math.controller.{_ff(g)};\n"
        "import edu.wpi.first.math.controller.ProfiledPIDController;\n"
        "import edu.wpi.first.math.trajectory.TrapezoidProfile;\n\n"
        + _java_usage(g)
        + f"public final class {cls} {{\n"
        f"  public static final double kS = {_num(g.kS)}; // V\n"
        f"  public static final double kG = {_num(g.kG)}; // V\n"
        f"  public static final double kV = {_num(g.kV)}; // V*s/{_u(g)}\n"
        f"  public static final double kA = {_num(g.kA)}; // V*s^2/{_u(g)}\n"
        f"  public static final double kP = {_num(g.kP)}; // V/{_u(g)}\n"
        f"  public static final double kD = {_num(g.kD)}; // V*s/{_u(g)}\n"
        f"  public static final double kMaxVelocity = {_num(g.max_velocity)}; // {_u(g)}/s\n"
        f"  public static final double kMaxAcceleration = {_num(g.max_acceleration)}; // {_u(g)}/s^2\n"
        f"  public static final double kPeriod = {_num(g.period)}; // s\n\n"
        f"  public static {_ff(g)} feedforward() {{\n"
        f"    return new {_ff(g)}(kS, kG, kV, kA, kPeriod);\n"
        "  }\n\n"
        "  public static ProfiledPIDController controller() {\n"
        "    return new ProfiledPIDController(\n"
        "        kP, 0.0, kD, new TrapezoidProfile.Constraints(kMaxVelocity, kMaxAcceleration), kPeriod);\n"
        "  }\n\n"
        f"  private {cls}() {{}}\n"
        "}\n"
    )


def _phoenix6_current_limits(g) -> list[str]:
    """CurrentLimitsConfigs lines for the limits that are on (a mechanism's or a flywheel's gains)."""
    lines = []
    if g.stator_limit is not None:
        lines += [
            f"    cfg.CurrentLimits.StatorCurrentLimit = {_num(g.stator_limit)}; // A",
            "    cfg.CurrentLimits.StatorCurrentLimitEnable = true;",
        ]
    if g.supply_limit is not None:
        lines += [
            f"    cfg.CurrentLimits.SupplyCurrentLimit = {_num(g.supply_limit)}; // A",
            "    cfg.CurrentLimits.SupplyCurrentLimitEnable = true;",
        ]
    return lines


DEVICE_LOOP_NOTE = (
    "// This loop runs on the motor controller with its own profile and continuous feedforward (kV*v +\n"
    "// kA*a at the profile's targets), not the roboRIO loop of the WPILib documents that the card simulates."
)
# REVLib with the exponential profile: the profile and feedforward stay on the roboRIO, the PID moves
REV_EXPO_LOOP_NOTE = (
    "// The PID runs on the SPARK (1 kHz) on setpoints the roboRIO sends: not quite the roboRIO loop of\n"
    "// the WPILib documents that the card simulates."
)


def phoenix6_java(g: Gains) -> str:
    check_controller("phoenix6", g.motor)
    v = phoenix6_values(g)
    cls = f"{g.title.replace(' ', '')}TalonFXConfig"
    lines = [
        _header(g, "//").rstrip("\n"),
        DEVICE_LOOP_NOTE,
        *(
            [
                "// Positions in arm rotations (SensorToMechanismRatio = motor turns per arm turn), 0 with the",
                "// arm horizontal (set the sensor's offset so): Arm_Cosine needs it. "
                f"Request {_phoenix6_request(g)}.",
            ]
            if g.arm
            else [
                "// Positions in drum rotations (SensorToMechanismRatio = motor turns per drum turn);",
                f"// one drum rotation = {_num(g.metres_per_rotation)} m of carriage travel. "
                f"Request {_phoenix6_request(g)}.",
            ]
        ),
        "import com.ctre.phoenix6.configs.TalonFXConfiguration;",
        "import com.ctre.phoenix6.signals.GravityTypeValue;",
        "",
        f"public final class {cls} {{",
        f"  public static final double k{'Radians' if g.arm else 'Metres'}PerRotation = "
        f"{_num(g.metres_per_rotation)};",
        "",
        "  public static TalonFXConfiguration config() {",
        "    var cfg = new TalonFXConfiguration();",
        f"    cfg.Feedback.SensorToMechanismRatio = {_num(v['SensorToMechanismRatio'])};",
        f"    cfg.Slot0.GravityType = GravityTypeValue.{'Arm_Cosine' if g.arm else 'Elevator_Static'};",
        f"    cfg.Slot0.kS = {_num(v['kS'])}; // V",
        f"    cfg.Slot0.kG = {_num(v['kG'])}; // V",
        f"    cfg.Slot0.kV = {_num(v['kV'])}; // V per rps",
        f"    cfg.Slot0.kA = {_num(v['kA'])}; // V per rps/s",
        f"    cfg.Slot0.kP = {_num(v['kP'])}; // V per rotation",
        "    cfg.Slot0.kI = 0.0;",
        f"    cfg.Slot0.kD = {_num(v['kD'])}; // V per rps",
    ]
    lines += _phoenix6_motion_magic(g, v)
    lines += _phoenix6_current_limits(g)
    lines += ["    return cfg;", "  }", "", f"  private {cls}() {{}}", "}", ""]
    limits = {"StatorCurrentLimit": g.stator_limit, "SupplyCurrentLimit": g.supply_limit}
    hint = (
        "Lower the ratio, the max input or the profile's limits, or re-solve for a mechanism whose "
        "values fit: Phoenix 6 keeps the value in range, not the one Gearhead simulated."
    )
    return "\n".join(_flag_phoenix6(lines, v | {k: x for k, x in limits.items() if x is not None}, hint))


def revlib_java(g: Gains) -> str:
    check_controller("revlib", g.motor)
    v = revlib_values(g)
    u = _u(g)
    cls = f"{g.title.replace(' ', '')}SparkMaxConfig"
    lines = [
        _header(g, "//").rstrip("\n"),
        DEVICE_LOOP_NOTE if g.max_input is None else REV_EXPO_LOOP_NOTE,
        f"// Native units are SI through the encoder's conversion factors ({u}, {u}/s); the PID output is a",
        "// duty cycle of the compensated voltage, kD per 1 ms step (the SPARK's loop runs at 1 kHz).",
        *(
            [
                "// Gravity: kCos·cos(2π·kCosRatio·position), kCosRatio turning radians into arm rotations;",
                "// zero the encoder with the arm horizontal (encoder.setPosition at a known angle, in rad)",
                "// and make positive the arm going up (config.inverted as needed). Request kMAXMotionPositionControl.",
            ]
            if g.arm and g.max_input is None
            else []
        ),
        "import com.revrobotics.spark.FeedbackSensor;",
        "import com.revrobotics.spark.config.SparkMaxConfig;",
        "",
        f"public final class {cls} {{",
        "  public static SparkMaxConfig config() {",
        "    SparkMaxConfig config = new SparkMaxConfig();",
        f"    config.voltageCompensation({_num(v['voltageCompensation'])});",
    ]
    if g.stator_limit is not None:
        lines.append(f"    config.smartCurrentLimit({int(round(g.stator_limit))}); // A, stator")
    if g.supply_limit is not None:
        lines.append(
            f"    // supply limit {g.supply_limit:g} A per motor: REVLib has none (a stator limit only)"
        )
    gravity = (
        [
            f"        .kCos({_num(v['kCos'])}) // V at horizontal",
            f"        .kCosRatio({_num(v['kCosRatio'])}); // arm rotations per rad",
        ]
        if g.arm
        else [f"        .kG({_num(v['kG'])});"]
    )
    lines += [
        "    config.encoder",
        f"        .positionConversionFactor({_num(v['positionConversionFactor'])}) // {u} per motor turn",
        f"        .velocityConversionFactor({_num(v['velocityConversionFactor'])}); // {u}/s per rpm",
        "    config.closedLoop",
        "        .feedbackSensor(FeedbackSensor.kPrimaryEncoder)",
        f"        .p({_num(v['p'])})",
        "        .i(0.0)",
        f"        .d({_num(v['d'])})",
        "        .outputRange(-1, 1);",
    ]
    if g.max_input is None:
        lines += [
            "    config.closedLoop.feedForward",
            f"        .kS({_num(v['kS'])})",
            f"        .kV({_num(v['kV'])})",
            f"        .kA({_num(v['kA'])})",
            *gravity,
        ]
    lines += _revlib_max_motion(g, v, u)
    lines += [
        "    return config;",
        "  }",
        "",
        f"  private {cls}() {{}}",
        "}",
        "",
    ]
    return "\n".join(lines)


# --- the exponential profile's documents (GC6) ------------------------------------------------------


def _wpilib_python_exponential(g: Gains) -> str:
    ff_args = (
        "setpoint.position, setpoint.velocity, nxt.velocity" if g.arm else "setpoint.velocity, nxt.velocity"
    )
    return (
        _header(g, "#") + f"from wpimath.controller import {_ff(g)}, PIDController\n"
        "from wpimath.trajectory import ExponentialProfileMeterVolts\n\n"
        f"kS = {_num(g.kS)}  # V\n"
        f"kG = {_num(g.kG)}  # V\n"
        f"kV = {_num(g.kV)}  # V*s/{_u(g)}\n"
        f"kA = {_num(g.kA)}  # V*s^2/{_u(g)}\n"
        f"kP = {_num(g.kP)}  # V/{_u(g)}\n"
        f"kD = {_num(g.kD)}  # V*s/{_u(g)}\n"
        f"MAX_INPUT = {_num(g.max_input)}  # V: the profile's, on top of kS and kG\n"
        f"PERIOD = {_num(g.period)}  # s\n\n"
        f"feedforward = {_ff(g)}(kS, kG, kV, kA, PERIOD)\n"
        "controller = PIDController(kP, 0.0, kD, PERIOD)\n"
        "# robotpy binds ExponentialProfile for metres and volts only; the units are labels"
        + (" (radians go through unchanged)\n" if g.arm else "\n")
        + "constraints = ExponentialProfileMeterVolts.Constraints.fromCharacteristics(MAX_INPUT, kV, kA)\n"
        "profile = ExponentialProfileMeterVolts(constraints)\n"
        "# start: setpoint = ExponentialProfileMeterVolts.State(position, 0.0); goal = ...State(target, 0.0)\n"
        "# each period: nxt = profile.calculate(PERIOD, setpoint, goal)\n"
        "#              volts = controller.calculate(position, nxt.position)\n"
        f"#                      + feedforward.calculate({ff_args})\n"
        "#              setpoint = nxt\n" + (_arm_ff_note("#") if g.arm else "")
    )


def _wpilib_java_exponential(g: Gains) -> str:
    cls = f"{g.title.replace(' ', '')}Gains"
    ff_args = (
        "setpoint.position, setpoint.velocity, next.velocity" if g.arm else "setpoint.velocity, next.velocity"
    )
    return (
        _header(g, "//") + f"import edu.wpi.first.math.controller.{_ff(g)};\n"
        "import edu.wpi.first.math.controller.PIDController;\n"
        "import edu.wpi.first.math.trajectory.ExponentialProfile;\n\n"
        "// Each period: var next = profile.calculate(kPeriod, setpoint, goal);\n"
        "//   volts = controller.calculate(position, next.position)\n"
        f"//           + feedforward.calculateWithVelocities({ff_args}); setpoint = next;\n"
        + (
            _arm_ff_note("//")
            if g.arm
            else "// (calculateWithVelocities is the discrete feedforward; calculate(a, b) reads b as an acceleration)\n"
        )
        + f"public final class {cls} {{\n"
        f"  public static final double kS = {_num(g.kS)}; // V\n"
        f"  public static final double kG = {_num(g.kG)}; // V\n"
        f"  public static final double kV = {_num(g.kV)}; // V*s/{_u(g)}\n"
        f"  public static final double kA = {_num(g.kA)}; // V*s^2/{_u(g)}\n"
        f"  public static final double kP = {_num(g.kP)}; // V/{_u(g)}\n"
        f"  public static final double kD = {_num(g.kD)}; // V*s/{_u(g)}\n"
        f"  public static final double kMaxInput = {_num(g.max_input)}; // V, on top of kS and kG\n"
        f"  public static final double kPeriod = {_num(g.period)}; // s\n\n"
        f"  public static {_ff(g)} feedforward() {{\n"
        f"    return new {_ff(g)}(kS, kG, kV, kA, kPeriod);\n"
        "  }\n\n"
        "  public static PIDController controller() {\n"
        "    return new PIDController(kP, 0.0, kD, kPeriod);\n"
        "  }\n\n"
        "  public static ExponentialProfile profile() {\n"
        "    return new ExponentialProfile(ExponentialProfile.Constraints.fromCharacteristics(kMaxInput, kV, kA));\n"
        "  }\n\n"
        f"  private {cls}() {{}}\n"
        "}\n"
    )


def _phoenix6_request(g: Gains) -> str:
    return "MotionMagicVoltage" if g.max_input is None else "MotionMagicExpoVoltage"


def _phoenix6_motion_magic(g: Gains, v: dict) -> list[str]:
    if g.max_input is None:
        return [
            f"    cfg.MotionMagic.MotionMagicCruiseVelocity = {_num(v['MotionMagicCruiseVelocity'])}; // rps",
            f"    cfg.MotionMagic.MotionMagicAcceleration = {_num(v['MotionMagicAcceleration'])}; // rps/s",
            "    cfg.MotionMagic.MotionMagicJerk = 0.0; // no jerk limit: a trapezoid",
        ]
    return [
        f"    // Motion Magic Expo: the profile of {g.max_input:g} V on kV, kA. CTRE's divides the supply voltage",
        f"    // by Expo_kV and Expo_kA: they are kV, kA x {g.battery_voltage:g} V / {g.max_input:g} V (GC6)",
        "    cfg.MotionMagic.MotionMagicCruiseVelocity = 0.0; // no cap: the profile's own limit",
        f"    cfg.MotionMagic.MotionMagicExpo_kV = {_num(v['MotionMagicExpo_kV'])}; // V per rps",
        f"    cfg.MotionMagic.MotionMagicExpo_kA = {_num(v['MotionMagicExpo_kA'])}; // V per rps/s",
    ]


def _revlib_max_motion(g: Gains, v: dict, u: str) -> list[str]:
    if g.max_input is None:
        return [
            "    config.closedLoop.maxMotion",
            f"        .cruiseVelocity({_num(v['cruiseVelocity'])}) // {u}/s",
            f"        .maxAcceleration({_num(v['maxAcceleration'])}) // {u}/s^2",
            f"        .allowedProfileError({_num(v['allowedProfileError'])}); // {u}",
        ]
    return [
        "    // MAXMotion has no exponential profile (MAXMotionConfig.MAXMotionPositionMode offers",
        "    // kMAXMotionTrapezoidal only): no maxMotion limits here. Run WPILib's ExponentialProfile on the",
        "    // roboRIO (the wpilib-java document) and send each setpoint as a kPosition request with the",
        "    // whole WPILib feedforward's volts (kS, kG, kV, kA: calculateWithVelocities) as its arbitrary",
        "    // feedforward; so no closedLoop.feedForward is set here (it would add kS and gravity again).",
    ]


# --- a flywheel's velocity loop (issue 30) ---------------------------------------------------------
#
# Gearhead's flywheel gains are per rad/s of the wheel (kS in V, kV and kP in V·s/rad, kA in
# V·s²/rad; core.sim.velocity_loop (VL2), (VL9)).
# - WPILib (SimpleMotorFeedforward + PIDController; robotpy's SimpleMotorFeedforwardRadians): as they
#   are, velocities in rad/s.                                                                    (GC4)
# - Phoenix 6 (Slot0 for a VelocityVoltage request: kV "output per unit of requested velocity"
#   in rps, kA per rps/s, kP per rps of error; SensorToMechanismRatio = G, motor turns per wheel
#   turn, makes the velocity the wheel's): one wheel rotation is 2π rad, so
#       kV_rps = 2π·kV,  kA_rps = 2π·kA,  kP_rps = 2π·kP,  kS unchanged;  target rps = ω/(2π)     (GC5)
#   (CrossTheRoadElec/Phoenix6-Examples, java/VelocityClosedLoop: Slot0.kS/kV/kP, VelocityVoltage.)
#   Or in rotor units (no SensorToMechanismRatio: the TalonFX's own rotor rotations), a wheel rps
#   being G rotor rps:
#       kV_rot = 2π·kV/G,  kA_rot = 2π·kA/G,  kP_rot = 2π·kP/G,  target rps = G·ω/(2π)            (GC5a)
#   (kV_rot = 2π/Kv of the motor whatever G: a check.)
# - REVLib (SparkMaxConfig, ControlType.kVelocity; REVLib-Examples at 6b03aa4, Java/SPARK/Closed Loop
#   Control: closedLoop.feedForward.kV "in Volts" per velocity unit, setSetpoint(v, kVelocity); kV
#   is applied in velocity mode, kA in MAXMotion modes only (FeedForwardConfig javadoc)): the
#   encoder's factors 1/G make the native units wheel rotations and wheel rpm, one rpm = 2π/60
#   rad/s, and the PID output is a duty of the compensated voltage V_b (GC3):
#       kV_rpm = kV·2π/60,  kA_rpm = kA·2π/60 (per rpm/s),  p = kP·2π/(60·V_b),  kS unchanged;
#       target rpm = 60·ω/(2π)                                                                   (GC8)
# A ramped setpoint (VL4a) at a rad/s²: Phoenix 6 MotionMagicVelocityVoltage with
# MotionMagicAcceleration = a/(2π) wheel rps/s (a·G/(2π) rotor rps/s; it ignores the cruise
# velocity; CTRE's MotionMagicVelocityVoltage docs), REVLib kMAXMotionVelocityControl with
# maxMotion.maxAcceleration = 60·a/(2π) wheel rpm/s (MAXMotionConfig javadoc: rpm/s through the
# velocity factor), WPILib's feedforward.calculate(setpoint, next) with the PID against next.   (GC7)


@dataclass(frozen=True)
class FlywheelGains:
    kS: float  # V
    kV: float  # V·s/rad at the wheel
    kA: float  # V·s²/rad
    kP: float  # V·s/rad
    period: float  # s
    ratio: float  # G, motor turns per wheel turn
    target_speed: float  # rad/s at the wheel
    battery_voltage: float
    stator_limit: float | None = None
    supply_limit: float | None = None
    acceleration: float | None = None  # rad/s² at the wheel: a ramped setpoint (VL4a); None: a step
    motor: str = ""  # Gearhead's motor name (GC10); "" unchecked


def flywheel_phoenix6_values(g: FlywheelGains, rotor: bool = False) -> dict[str, float]:
    """(GC5): Slot0 in wheel rotations per second; rotor=True: in rotor rotations per second with no
    SensorToMechanismRatio (GC5a)."""
    per_turn = 2 * math.pi / g.ratio if rotor else 2 * math.pi  # rad/s of the wheel per rps
    return {
        **({} if rotor else {"SensorToMechanismRatio": g.ratio}),
        "kS": g.kS,
        "kV": g.kV * per_turn,
        "kA": g.kA * per_turn,
        "kP": g.kP * per_turn,
        "target_rps": g.target_speed / per_turn,
        **({} if g.acceleration is None else {"MotionMagicAcceleration": g.acceleration / per_turn}),
    }


RPM_PER_RAD_S = 60.0 / (2 * math.pi)
PHOENIX_MAX_ACCELERATION = 9999.0  # rps/s: MotionMagicConfigs.MotionMagicAcceleration's maximum


def flywheel_revlib_values(g: FlywheelGains) -> dict[str, float]:
    """(GC8): the encoder's factors (wheel rotations, wheel rpm) and the velocity loop's gains."""
    per_rpm = 1.0 / RPM_PER_RAD_S  # rad/s in one rpm
    return {
        "positionConversionFactor": 1.0 / g.ratio,
        "velocityConversionFactor": 1.0 / g.ratio,
        "voltageCompensation": g.battery_voltage,
        "p": g.kP * per_rpm / g.battery_voltage,
        "kS": g.kS,
        "kV": g.kV * per_rpm,
        "kA": g.kA * per_rpm,
        "target_rpm": g.target_speed * RPM_PER_RAD_S,
        **({} if g.acceleration is None else {"maxAcceleration": g.acceleration * RPM_PER_RAD_S}),
    }


def _fw_header(g: FlywheelGains, comment: str) -> str:
    return (
        f"{comment} Flywheel velocity-loop gains from Gearhead (per rad/s of the wheel unless said).\n"
        f"{comment} kP is LQR's for a {g.period * 1000:g} ms loop unless entered; a loop on the motor\n"
        f"{comment} controller (1 kHz) may take it higher: re-solve with its period.\n"
    )


def flywheel_wpilib_python(g: FlywheelGains) -> str:
    check_wpilib(g)
    return (
        _fw_header(g, "#") + "from wpimath.controller import PIDController, SimpleMotorFeedforwardRadians\n\n"
        f"kS = {_num(g.kS)}  # V\n"
        f"kV = {_num(g.kV)}  # V*s/rad\n"
        f"kA = {_num(g.kA)}  # V*s^2/rad\n"
        f"kP = {_num(g.kP)}  # V*s/rad\n"
        f"TARGET_SPEED = {_num(g.target_speed)}  # rad/s at the wheel\n"
        f"PERIOD = {_num(g.period)}  # s\n"
        + (
            f"ACCELERATION = {_num(g.acceleration)}  # rad/s^2, the setpoint's ramp\n"
            if g.acceleration
            else ""
        )
        + "\nfeedforward = SimpleMotorFeedforwardRadians(kS, kV, kA, PERIOD)\n"
        "controller = PIDController(kP, 0.0, 0.0, PERIOD)\n" + _fw_usage(g)
    )


def _fw_usage(g: FlywheelGains, java: bool = False) -> str:
    """How the loop calls them: at the target, or along the ramp (VL4a: the feedforward from the
    setpoint to the next one, the feedback against the next one). Java's discrete feedforward is
    calculateWithVelocities: its two-argument calculate is the continuous (velocity, acceleration)."""
    c, target, accel, period = (
        ("//", "kTargetSpeed", "kAcceleration", "kPeriod")
        if java
        else (
            "#",
            "TARGET_SPEED",
            "ACCELERATION",
            "PERIOD",
        )
    )
    if g.acceleration is None:
        return (
            f"{c} each period: volts = feedforward.calculate({target})\n"
            f"{c}                      + controller.calculate(wheel_speed_rad_per_s, {target})\n"
        )
    discrete = "calculateWithVelocities" if java else "calculate"
    return (
        f"{c} setpoint = 0.0 at the start; each period:\n"
        f"{c}   nxt = min({target}, setpoint + {accel} * {period})\n"
        f"{c}   volts = feedforward.{discrete}(setpoint, nxt) + controller.calculate(wheel_speed_rad_per_s, nxt)\n"
        f"{c}   setpoint = nxt\n"
    )


def flywheel_wpilib_java(g: FlywheelGains) -> str:
    check_wpilib(g)
    return (
        _fw_header(g, "//") + "import edu.wpi.first.math.controller.PIDController;\n"
        "import edu.wpi.first.math.controller.SimpleMotorFeedforward;\n\n"
        + _fw_usage(g, java=True)
        + "public final class FlywheelGains {\n"
        f"  public static final double kS = {_num(g.kS)}; // V\n"
        f"  public static final double kV = {_num(g.kV)}; // V*s/rad\n"
        f"  public static final double kA = {_num(g.kA)}; // V*s^2/rad\n"
        f"  public static final double kP = {_num(g.kP)}; // V*s/rad\n"
        f"  public static final double kTargetSpeed = {_num(g.target_speed)}; // rad/s at the wheel\n"
        f"  public static final double kPeriod = {_num(g.period)}; // s\n"
        + (
            f"  public static final double kAcceleration = {_num(g.acceleration)}; // rad/s^2, the setpoint's ramp\n"
            if g.acceleration
            else ""
        )
        + "\n"
        "  public static SimpleMotorFeedforward feedforward() {\n"
        "    return new SimpleMotorFeedforward(kS, kV, kA, kPeriod);\n"
        "  }\n\n"
        "  public static PIDController controller() {\n"
        "    return new PIDController(kP, 0.0, 0.0, kPeriod);\n"
        "  }\n\n"
        "  private FlywheelGains() {}\n"
        "}\n"
    )


def flywheel_phoenix6_java(g: FlywheelGains, rotor: bool = False) -> str:
    check_controller("phoenix6", g.motor)
    v = flywheel_phoenix6_values(g, rotor)
    cls = f"Flywheel{'Rotor' if rotor else ''}TalonFXConfig"
    units = (
        [
            "// Velocities in rotor rotations per second (no SensorToMechanismRatio: the motor's own);",
            f"// the wheel turns once every {_num(g.ratio)} rotor turns.",
        ]
        if rotor
        else [
            "// Velocities in wheel rotations per second (SensorToMechanismRatio = motor turns per wheel turn)."
        ]
    )
    lines = [
        _fw_header(g, "//").rstrip("\n"),
        *units,
        "import com.ctre.phoenix6.configs.TalonFXConfiguration;",
        f"import com.ctre.phoenix6.controls.{'VelocityVoltage' if g.acceleration is None else 'MotionMagicVelocityVoltage'};",
        "",
        f"public final class {cls} {{",
        f"  public static final double kTargetRps = {_num(v['target_rps'])}; // {'rotor' if rotor else 'wheel'} rotations/s",
        "",
        "  public static TalonFXConfiguration config() {",
        "    var cfg = new TalonFXConfiguration();",
        *(
            []
            if rotor
            else [f"    cfg.Feedback.SensorToMechanismRatio = {_num(v['SensorToMechanismRatio'])};"]
        ),
        f"    cfg.Slot0.kS = {_num(v['kS'])}; // V",
        f"    cfg.Slot0.kV = {_num(v['kV'])}; // V per rps",
        f"    cfg.Slot0.kA = {_num(v['kA'])}; // V per rps/s",
        f"    cfg.Slot0.kP = {_num(v['kP'])}; // V per rps of error",
        "    cfg.Slot0.kI = 0.0;",
        "    cfg.Slot0.kD = 0.0;",
    ]
    request = "VelocityVoltage"
    if g.acceleration is not None:
        request = "MotionMagicVelocityVoltage"
        a = v["MotionMagicAcceleration"]
        lines += [
            f"    cfg.MotionMagic.MotionMagicAcceleration = {_num(a)}; // rps/s, the setpoint's ramp",
            "    cfg.MotionMagic.MotionMagicJerk = 0.0; // no jerk limit",
        ]
        if a > PHOENIX_MAX_ACCELERATION:  # (GC9), said where the ramp is set as before
            lines.append(
                f"    // beyond the config's maximum {PHOENIX_MAX_ACCELERATION:g} rps/s: lower the ramp's acceleration"
            )
    lines += _phoenix6_current_limits(g)
    lines += [
        "    return cfg;",
        "  }",
        "",
        f"  public static {request} request() {{",
        f"    return new {request}(kTargetRps).withSlot(0);",
        "  }",
        "",
        f"  private {cls}() {{}}",
        "}",
        "",
    ]
    limits = {"StatorCurrentLimit": g.stator_limit, "SupplyCurrentLimit": g.supply_limit}
    values = {k: x for k, x in v.items() if k != "target_rps"} | {
        k: x for k, x in limits.items() if x is not None
    }
    hint = "Lower the ratio or the ramp's acceleration: Phoenix 6 keeps the value in range, not this one."
    return "\n".join(_flag_phoenix6(lines, values, hint))


def flywheel_revlib_java(g: FlywheelGains) -> str:
    check_controller("revlib", g.motor)
    v = flywheel_revlib_values(g)
    lines = [
        _fw_header(g, "//").rstrip("\n"),
        "// Native units are the wheel's through the encoder's conversion factors (rotations, rpm); the PID",
        "// output is a duty cycle of the compensated voltage. Request ControlType."
        + ("kVelocity." if g.acceleration is None else "kMAXMotionVelocityControl (the ramp)."),
        "import com.revrobotics.spark.FeedbackSensor;",
        "import com.revrobotics.spark.config.SparkMaxConfig;",
        "",
        "public final class FlywheelSparkMaxConfig {",
        f"  public static final double kTargetRpm = {_num(v['target_rpm'])}; // wheel rpm",
        "",
        "  public static SparkMaxConfig config() {",
        "    SparkMaxConfig config = new SparkMaxConfig();",
        f"    config.voltageCompensation({_num(v['voltageCompensation'])});",
    ]
    if g.stator_limit is not None:
        lines.append(f"    config.smartCurrentLimit({int(round(g.stator_limit))}); // A, stator")
    if g.supply_limit is not None:
        lines.append(
            f"    // supply limit {g.supply_limit:g} A per motor: REVLib has none (a stator limit only)"
        )
    lines += [
        "    config.encoder",
        f"        .positionConversionFactor({_num(v['positionConversionFactor'])}) // wheel turns per motor turn",
        f"        .velocityConversionFactor({_num(v['velocityConversionFactor'])}); // wheel rpm per motor rpm",
        "    config.closedLoop",
        "        .feedbackSensor(FeedbackSensor.kPrimaryEncoder)",
        f"        .p({_num(v['p'])}) // duty per wheel rpm of error",
        "        .i(0.0)",
        "        .d(0.0)",
        "        .outputRange(-1, 1);",
        "    config.closedLoop.feedForward",
        f"        .kS({_num(v['kS'])}) // V",
        f"        .kV({_num(v['kV'])}) // V per wheel rpm",
        f"        .kA({_num(v['kA'])}); // V per wheel rpm/s (MAXMotion modes only)",
    ]
    if g.acceleration is not None:
        lines += [
            "    config.closedLoop.maxMotion",
            "        .cruiseVelocity(kTargetRpm) // wheel rpm",
            f"        .maxAcceleration({_num(v['maxAcceleration'])}); // wheel rpm/s, the setpoint's ramp",
        ]
    control = "kVelocity" if g.acceleration is None else "kMAXMotionVelocityControl"
    lines += [
        "    return config;",
        "  }",
        "",
        f"  // closedLoopController.setSetpoint(kTargetRpm, ControlType.{control})",
        "  private FlywheelSparkMaxConfig() {}",
        "}",
        "",
    ]
    return "\n".join(lines)


def mechanism_documents(title: str, gains_of, phoenix_note: str = "", revlib: bool = True) -> tuple:
    """The documents of an elevator's or an arm's profiled move (core.declarations.Document):
    WPILib Java and Python, Phoenix 6, and REVLib where its gravity term is defined."""
    from .declarations import Document

    ff, snake = f"{title}Feedforward", title.lower()
    docs = [
        Document(
            "wpilib-java",
            f"WPILib Java: {ff} + PID and motion profile",
            f"{title}Gains.java",
            lambda sol: wpilib_java(gains_of(sol)),
        ),
        Document(
            "wpilib-python",
            f"WPILib Python (robotpy): {ff} + PID and motion profile",
            f"{snake}_gains.py",
            lambda sol: wpilib_python(gains_of(sol)),
        ),
        Document(
            "phoenix6",
            f"CTRE Phoenix 6 TalonFXConfiguration{phoenix_note} (Java)",
            f"{title}TalonFXConfig.java",
            lambda sol: phoenix6_java(gains_of(sol)),
        ),
    ]
    if revlib:
        docs.append(
            Document(
                "revlib",
                "REVLib SparkMaxConfig with MAXMotion (Java)",
                f"{title}SparkMaxConfig.java",
                lambda sol: revlib_java(gains_of(sol)),
            )
        )
    return tuple(docs)


def profiled_gains(solution, metres_per_rotation, **kind) -> Gains:
    """A profiled move's gains and limits for the exports (GC1)-(GC3), from a solved elevator or arm
    (`metres_per_rotation(inputs)`: L; `kind`: the arm's title and arm=True); a ValueError when the solution is not of that mode (the
    profile's limits come from it)."""
    v = {name: value.value for name, value in solution.inputs.items()}
    out = {name: value.value for name, value in solution.outputs.items()}
    if v.get("mode") != "profiled" or "profile_max_velocity" not in out:
        raise ValueError("the gains and the profile are exported from the profiled move: set mode = profiled")
    on = v["effects"]
    return Gains(
        kS=out["kS"],
        kG=out["kG"],
        kV=out["kV"],
        kA=out["kA"],
        kP=out["kP"],
        kD=out["kD"],
        max_velocity=out["profile_max_velocity"],
        max_acceleration=out["profile_max_acceleration"],
        period=v["control_period"],
        ratio=v["ratio"],
        metres_per_rotation=metres_per_rotation(v),
        battery_voltage=v["voltage"],
        tolerance=v["settle_tolerance"],
        max_input=v["max_input"] if v.get("profile_type") == "exponential" else None,
        motor=v["motor"],
        stator_limit=v["stator_current_limit"] if "stator_limit" in on else None,
        supply_limit=v["supply_current_limit"] if "supply_limit" in on else None,
        **kind,
    )
