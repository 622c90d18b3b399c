"""The numbers of the gains-as-code documents (core.gains_code writes them as text): a profiled
move's and a flywheel's gains, profile limits and current limits in each target's units, for WPILib
(Java, Python), CTRE Phoenix 6 (TalonFXConfiguration) and REVLib (SparkMaxConfig), their ranges and
the controllers each can drive. Standard library only.

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


EXPORT_DIGITS = 12  # significant digits of an exported number (GC11)


def export_number(x: float) -> float:
    """(GC11): x to EXPORT_DIGITS significant digits. An entry is typed with a handful of digits and
    a unit conversion (135 lb = 61.23496995 kg, 34 in = 0.8636 m) is exact within 12, so 12 keep
    every digit the entries give and drop a double's arithmetic noise (61.23496995000001): the
    exported loop differs from the card's by under 1e-12 of each value. The card keeps full precision."""
    if not math.isfinite(x):
        raise ValueError(f"{x} cannot be exported")
    return float(f"{float(x):.{EXPORT_DIGITS}g}")


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


def velocity_loop_gains(solution) -> FlywheelGains:
    """A flywheel's velocity-loop gains for the exports (GC4)-(GC8), from a solved flywheel; a
    ValueError when the solution is not of that mode."""
    v = {name: value.value for name, value in solution.inputs.items()}
    out = {name: value.value for name, value in solution.outputs.items()}
    if v.get("control") != "velocity_loop" or "kP" not in out:
        raise ValueError("the gains are exported from the velocity loop: set control = velocity_loop")
    on = v["effects"]
    return FlywheelGains(
        acceleration=out.get("loop_ramp_acceleration"),
        kS=out["kS"],
        kV=out["kV"],
        kA=out["kA"],
        kP=out["kP"],
        period=v["control_period"],
        ratio=v["ratio"],
        target_speed=v["target_speed"],
        battery_voltage=v["voltage"],
        stator_limit=v["stator_current_limit"] if "stator_limit" in on else None,
        supply_limit=v["supply_current_limit"] if "supply_limit" in on else None,
        motor=v["motor"],  # which controllers can drive it (gains_code (GC10))
    )
