"""Gains as code: a profiled move's feedforward and feedback gains, profile limits and current limits,
and a flywheel velocity loop's, written as the code a team pastes into its robot project, for WPILib
(Java, Python), CTRE Phoenix 6 (TalonFXConfiguration) and REVLib (SparkMaxConfig). Pure text
builders (standard library only); the numbers they write, in each target's units, are
core.gains_numbers' ((GC1)-(GC12) there). The calculators declare the documents (mechanism_documents,
flywheel_documents: core.declarations.Document), so ctrl+e and `solve --document NAME` offer them.
"""

from __future__ import annotations

from .gains_numbers import (  # noqa: F401 (gains_code.X for every caller: the numbers re-exported)
    EXPO_KA_RANGE,
    EXPORT_DIGITS,
    PHOENIX6_MOTORS,
    PHOENIX6_RANGES,
    PHOENIX_MAX_ACCELERATION,
    REV_LOOP_PERIOD,
    REVLIB_MOTORS,
    RPM_PER_RAD_S,
    FlywheelGains,
    Gains,
    check_controller,
    check_wpilib,
    export_number,
    flywheel_phoenix6_values,
    flywheel_revlib_values,
    phoenix6_out_of_range,
    phoenix6_values,
    profiled_gains,
    revlib_values,
    velocity_loop_gains,
)


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


def _u(g: Gains) -> str:
    return "rad" if g.arm else "m"


def _ff(g: Gains) -> str:
    return "ArmFeedforward" if g.arm else "ElevatorFeedforward"


def _num(x: float) -> str:
    """A float as a literal Java and Python both read back to the same double, rounded (GC11)."""
    return repr(export_number(x))


def _header(g: Gains | FlywheelGains, comment: str) -> str:
    """What the document holds and for which loop period, a mechanism's or a flywheel's."""
    ms = f"{g.period * 1000:g}"
    if isinstance(g, FlywheelGains):
        lines = (
            "Flywheel velocity-loop gains from Gearhead (per rad/s of the wheel unless said).",
            f"kP is LQR's for a {ms} ms loop unless entered; a loop on the motor",
            "controller (1 kHz) may take it higher: re-solve with its period.",
        )
    else:
        lines = (
            f"{g.title} gains from Gearhead's profiled move (SI: "
            f"{'radians of arm angle from horizontal' if g.arm else 'metres of carriage travel'}).",
            f"kP and kD are LQR gains for a {ms} ms loop unless entered; a loop on the",
            "motor controller (1 kHz) may take them higher: re-solve with its period.",
        )
    return "".join(f"{comment} {line}\n" for line in lines)


def _gain_rows(g: Gains | FlywheelGains) -> list[tuple]:
    """The feedforward and feedback gains as constants (_constants' rows), per unit of the
    mechanism's coordinate or per rad/s of the flywheel."""
    if isinstance(g, FlywheelGains):
        return [
            ("kS", "kS", g.kS, "V"),
            ("kV", "kV", g.kV, "V*s/rad"),
            ("kA", "kA", g.kA, "V*s^2/rad"),
            ("kP", "kP", g.kP, "V*s/rad"),
        ]
    u = _u(g)
    return [
        ("kS", "kS", g.kS, "V"),
        ("kG", "kG", g.kG, "V"),
        ("kV", "kV", g.kV, f"V*s/{u}"),
        ("kA", "kA", g.kA, f"V*s^2/{u}"),
        ("kP", "kP", g.kP, f"V/{u}"),
        ("kD", "kD", g.kD, f"V*s/{u}"),
    ]


def _constants(rows: list[tuple], java: bool) -> str:
    """Rows (Python name, Java name, value, comment[, Java's comment]) as Python assignments or Java
    constants, every number by _num (GC11)."""
    if java:
        return "".join(f"  public static final double {r[1]} = {_num(r[2])}; // {r[-1]}\n" for r in rows)
    return "".join(f"{r[0]} = {_num(r[2])}  # {r[3]}\n" for r in rows)


SLOT0_VELOCITY = {"kV": "V per rps", "kA": "V per rps/s"}  # the feedforward's, in both documents


def _java_class(cls: str, rows: list[tuple], methods: str) -> str:
    """A WPILib document's Java class: the constants, a blank line, the factory methods, no instances."""
    return (
        f"public final class {cls} {{\n"
        + _constants(rows, java=True)
        + "\n"
        + methods
        + f"  private {cls}() {{}}\n}}\n"
    )


def _slot0(v: dict[str, float], comments: dict[str, str | None]) -> list[str]:
    """Phoenix 6's Slot0 lines in the order of `comments`; a gain not in `v` is written 0.0."""
    return [
        f"    cfg.Slot0.{k} = {_num(v[k])}; // {c}" if k in v else f"    cfg.Slot0.{k} = 0.0;"
        for k, c in comments.items()
    ]


def _revlib_current_limits(g: Gains | FlywheelGains) -> list[str]:
    """REVLib's stator limit (whole amps), and a note that it has no supply limit."""
    lines = []
    if g.stator_limit is not None:
        lines.append(f"    config.smartCurrentLimit({int(round(g.stator_limit))}); // A, stator")
    if g.supply_limit is not None:
        lines.append(
            f"    // supply limit {g.supply_limit:g} A per motor: REVLib has none (a stator limit only)"
        )
    return lines


def _trapezoid_rows(g: Gains) -> list[tuple]:
    u = _u(g)
    return _gain_rows(g) + [
        ("MAX_VELOCITY", "kMaxVelocity", g.max_velocity, f"{u}/s"),
        ("MAX_ACCELERATION", "kMaxAcceleration", g.max_acceleration, f"{u}/s^2"),
        ("PERIOD", "kPeriod", g.period, "s"),
    ]


def _exponential_rows(g: Gains) -> list[tuple]:
    return _gain_rows(g) + [
        (
            "MAX_INPUT",
            "kMaxInput",
            g.max_input,
            "V: the profile's, on top of kS and kG",
            "V, on top of kS and kG",
        ),
        ("PERIOD", "kPeriod", g.period, "s"),
    ]


def _flywheel_rows(g: FlywheelGains) -> list[tuple]:
    return _gain_rows(g) + [
        ("TARGET_SPEED", "kTargetSpeed", g.target_speed, "rad/s at the wheel"),
        ("PERIOD", "kPeriod", g.period, "s"),
        *(
            [("ACCELERATION", "kAcceleration", g.acceleration, "rad/s^2, the setpoint's ramp")]
            if g.acceleration
            else []
        ),
    ]


def wpilib_python(g: Gains) -> str:
    check_wpilib(g)
    if g.max_input is not None:
        return _wpilib_python_exponential(g)
    return (
        _header(g, "#") + f"from wpimath.controller import {_ff(g)}, ProfiledPIDController\n"
        "from wpimath.trajectory import TrapezoidProfile\n\n"
        + _constants(_trapezoid_rows(g), java=False)
        + "\n"
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
        + _java_class(
            cls,
            _trapezoid_rows(g),
            f"  public static {_ff(g)} feedforward() {{\n"
            f"    return new {_ff(g)}(kS, kG, kV, kA, kPeriod);\n"
            "  }\n\n"
            "  public static ProfiledPIDController controller() {\n"
            "    return new ProfiledPIDController(\n"
            "        kP, 0.0, kD, new TrapezoidProfile.Constraints(kMaxVelocity, kMaxAcceleration), kPeriod);\n"
            "  }\n\n",
        )
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
    where = (
        [
            "// Positions in arm rotations (SensorToMechanismRatio = motor turns per arm turn), 0 with the",
            "// arm horizontal (set the sensor's offset so): Arm_Cosine needs it. ",
        ]
        if g.arm
        else [
            "// Positions in drum rotations (SensorToMechanismRatio = motor turns per drum turn);",
            f"// one drum rotation = {_num(g.metres_per_rotation)} m of carriage travel. ",
        ]
    )
    where[-1] += f"Request {_phoenix6_request(g)}."
    return _phoenix6_document(
        g,
        v,
        f"{g.title.replace(' ', '')}TalonFXConfig",
        [DEVICE_LOOP_NOTE, *where],
        "import com.ctre.phoenix6.signals.GravityTypeValue;",
        f"  public static final double k{'Radians' if g.arm else 'Metres'}PerRotation = "
        f"{_num(g.metres_per_rotation)};",
        [
            f"    cfg.Feedback.SensorToMechanismRatio = {_num(v['SensorToMechanismRatio'])};",
            f"    cfg.Slot0.GravityType = GravityTypeValue.{'Arm_Cosine' if g.arm else 'Elevator_Static'};",
            *_slot0(
                v,
                {
                    "kS": "V",
                    "kG": "V",
                    **SLOT0_VELOCITY,
                    "kP": "V per rotation",
                    "kI": None,
                    "kD": "V per rps",
                },
            ),
            *_phoenix6_motion_magic(g, v),
        ],
        [],
        "Lower the ratio, the max input or the profile's limits, or re-solve for a mechanism whose "
        "values fit: Phoenix 6 keeps the value in range, not the one Gearhead simulated.",
    )


def _phoenix6_document(g, v: dict, cls: str, notes, import_, constant: str, body, methods, hint: str) -> str:
    """A TalonFXConfiguration class, a mechanism's (GC2) or a flywheel's (GC5): the header and
    notes, a constant, config() with `body` and the current limits that are on, `methods`; a value
    outside Phoenix 6's ranges marked (GC9)."""
    lines = [
        _header(g, "//").rstrip("\n"),
        *notes,
        "import com.ctre.phoenix6.configs.TalonFXConfiguration;",
        import_,
        "",
        f"public final class {cls} {{",
        constant,
        "",
        "  public static TalonFXConfiguration config() {",
        "    var cfg = new TalonFXConfiguration();",
        *body,
        *_phoenix6_current_limits(g),
        "    return cfg;",
        "  }",
        "",
        *methods,
        f"  private {cls}() {{}}",
        "}",
        "",
    ]
    limits = {"StatorCurrentLimit": g.stator_limit, "SupplyCurrentLimit": g.supply_limit}
    return "\n".join(_flag_phoenix6(lines, v | {k: x for k, x in limits.items() if x is not None}, hint))


def _revlib_document(g, v: dict, cls: str, notes, constants, body, methods) -> str:
    """A SparkMaxConfig class, a mechanism's (GC3) or a flywheel's (GC8): the header and notes,
    `constants`, config() with the compensated voltage, the stator limit and `body`, `methods`."""
    return "\n".join(
        [
            _header(g, "//").rstrip("\n"),
            *notes,
            "import com.revrobotics.spark.FeedbackSensor;",
            "import com.revrobotics.spark.config.SparkMaxConfig;",
            "",
            f"public final class {cls} {{",
            *constants,
            "  public static SparkMaxConfig config() {",
            "    SparkMaxConfig config = new SparkMaxConfig();",
            f"    config.voltageCompensation({_num(v['voltageCompensation'])});",
            *_revlib_current_limits(g),
            *body,
            "    return config;",
            "  }",
            "",
            *methods,
            f"  private {cls}() {{}}",
            "}",
            "",
        ]
    )


def revlib_java(g: Gains) -> str:
    check_controller("revlib", g.motor)
    v = revlib_values(g)
    u = _u(g)
    notes = [
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
    ]
    gravity = (
        [
            f"        .kCos({_num(v['kCos'])}) // V at horizontal",
            f"        .kCosRatio({_num(v['kCosRatio'])}); // arm rotations per rad",
        ]
        if g.arm
        else [f"        .kG({_num(v['kG'])});"]
    )
    body = [
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
        body += [
            "    config.closedLoop.feedForward",
            f"        .kS({_num(v['kS'])})",
            f"        .kV({_num(v['kV'])})",
            f"        .kA({_num(v['kA'])})",
            *gravity,
        ]
    body += _revlib_max_motion(g, v, u)
    return _revlib_document(g, v, f"{g.title.replace(' ', '')}SparkMaxConfig", notes, [], body, [])


# --- the exponential profile's documents (GC6) ------------------------------------------------------


def _wpilib_python_exponential(g: Gains) -> str:
    ff_args = (
        "setpoint.position, setpoint.velocity, nxt.velocity" if g.arm else "setpoint.velocity, nxt.velocity"
    )
    return (
        _header(g, "#") + f"from wpimath.controller import {_ff(g)}, PIDController\n"
        "from wpimath.trajectory import ExponentialProfileMeterVolts\n\n"
        + _constants(_exponential_rows(g), java=False)
        + "\n"
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
        + _java_class(
            cls,
            _exponential_rows(g),
            f"  public static {_ff(g)} feedforward() {{\n"
            f"    return new {_ff(g)}(kS, kG, kV, kA, kPeriod);\n"
            "  }\n\n"
            "  public static PIDController controller() {\n"
            "    return new PIDController(kP, 0.0, kD, kPeriod);\n"
            "  }\n\n"
            "  public static ExponentialProfile profile() {\n"
            "    return new ExponentialProfile(ExponentialProfile.Constraints.fromCharacteristics(kMaxInput, kV, kA));\n"
            "  }\n\n",
        )
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


# --- a flywheel's velocity loop (issue 30): the numbers (GC4)-(GC8) in core.gains_numbers ---------


def flywheel_wpilib_python(g: FlywheelGains) -> str:
    check_wpilib(g)
    return (
        _header(g, "#")
        + "from wpimath.controller import PIDController, SimpleMotorFeedforwardRadians\n\n"
        + _constants(_flywheel_rows(g), java=False)
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
        _header(g, "//") + "import edu.wpi.first.math.controller.PIDController;\n"
        "import edu.wpi.first.math.controller.SimpleMotorFeedforward;\n\n"
        + _fw_usage(g, java=True)
        + _java_class(
            "FlywheelGains",
            _flywheel_rows(g),
            "  public static SimpleMotorFeedforward feedforward() {\n"
            "    return new SimpleMotorFeedforward(kS, kV, kA, kPeriod);\n"
            "  }\n\n"
            "  public static PIDController controller() {\n"
            "    return new PIDController(kP, 0.0, 0.0, kPeriod);\n"
            "  }\n\n",
        )
    )


def flywheel_phoenix6_java(g: FlywheelGains, rotor: bool = False) -> str:
    check_controller("phoenix6", g.motor)
    v = flywheel_phoenix6_values(g, rotor)
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
    body = [
        *(
            []
            if rotor
            else [f"    cfg.Feedback.SensorToMechanismRatio = {_num(v['SensorToMechanismRatio'])};"]
        ),
        *_slot0(v, {"kS": "V", **SLOT0_VELOCITY, "kP": "V per rps of error", "kI": None, "kD": None}),
    ]
    request = "VelocityVoltage"
    if g.acceleration is not None:
        request = "MotionMagicVelocityVoltage"
        a = v["MotionMagicAcceleration"]
        body += [
            f"    cfg.MotionMagic.MotionMagicAcceleration = {_num(a)}; // rps/s, the setpoint's ramp",
            "    cfg.MotionMagic.MotionMagicJerk = 0.0; // no jerk limit",
        ]
        if a > PHOENIX_MAX_ACCELERATION:  # (GC9), said where the ramp is set as before
            body.append(
                f"    // beyond the config's maximum {PHOENIX_MAX_ACCELERATION:g} rps/s: lower the ramp's acceleration"
            )
    return _phoenix6_document(
        g,
        v,
        f"Flywheel{'Rotor' if rotor else ''}TalonFXConfig",
        units,
        f"import com.ctre.phoenix6.controls.{request};",
        f"  public static final double kTargetRps = {_num(v['target_rps'])}; // {'rotor' if rotor else 'wheel'} rotations/s",
        body,
        [
            f"  public static {request} request() {{",
            f"    return new {request}(kTargetRps).withSlot(0);",
            "  }",
            "",
        ],
        "Lower the ratio or the ramp's acceleration: Phoenix 6 keeps the value in range, not this one.",
    )


def flywheel_revlib_java(g: FlywheelGains) -> str:
    check_controller("revlib", g.motor)
    v = flywheel_revlib_values(g)
    notes = [
        "// Native units are the wheel's through the encoder's conversion factors (rotations, rpm); the PID",
        "// output is a duty cycle of the compensated voltage. Request ControlType."
        + ("kVelocity." if g.acceleration is None else "kMAXMotionVelocityControl (the ramp)."),
    ]
    body = [
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
        body += [
            "    config.closedLoop.maxMotion",
            "        .cruiseVelocity(kTargetRpm) // wheel rpm",
            f"        .maxAcceleration({_num(v['maxAcceleration'])}); // wheel rpm/s, the setpoint's ramp",
        ]
    control = "kVelocity" if g.acceleration is None else "kMAXMotionVelocityControl"
    return _revlib_document(
        g,
        v,
        "FlywheelSparkMaxConfig",
        notes,
        [f"  public static final double kTargetRpm = {_num(v['target_rpm'])}; // wheel rpm", ""],
        body,
        [f"  // closedLoopController.setSetpoint(kTargetRpm, ControlType.{control})"],
    )


def documents(gains_of, specs) -> tuple:
    """Documents (core.declarations.Document) from specs (name, label, filename, template, options):
    each builds template(gains_of(solution), **options)."""
    from .declarations import Document

    def build(template, options):
        return lambda sol: template(gains_of(sol), **options)

    return tuple(
        Document(name, label, filename, build(template, options))
        for name, label, filename, template, options in specs
    )


def mechanism_documents(title: str, gains_of, phoenix_note: str = "", revlib: bool = True) -> tuple:
    """The documents of an elevator's or an arm's profiled move: WPILib Java and Python, Phoenix 6,
    and REVLib where its gravity term is defined."""
    ff = f"{title}Feedforward"
    return documents(
        gains_of,
        (
            (
                "wpilib-java",
                f"WPILib Java: {ff} + PID and motion profile",
                f"{title}Gains.java",
                wpilib_java,
                {},
            ),
            (
                "wpilib-python",
                f"WPILib Python (robotpy): {ff} + PID and motion profile",
                f"{title.lower()}_gains.py",
                wpilib_python,
                {},
            ),
            (
                "phoenix6",
                f"CTRE Phoenix 6 TalonFXConfiguration{phoenix_note} (Java)",
                f"{title}TalonFXConfig.java",
                phoenix6_java,
                {},
            ),
            *(
                [
                    (
                        "revlib",
                        "REVLib SparkMaxConfig with MAXMotion (Java)",
                        f"{title}SparkMaxConfig.java",
                        revlib_java,
                        {},
                    )
                ]
                if revlib
                else []
            ),
        ),
    )


def flywheel_documents(gains_of) -> tuple:
    """The documents of a flywheel's velocity loop: WPILib Java and Python, Phoenix 6 in wheel and in
    rotor units, REVLib."""
    return documents(
        gains_of,
        (
            (
                "wpilib-java",
                "WPILib Java: SimpleMotorFeedforward + PIDController",
                "FlywheelGains.java",
                flywheel_wpilib_java,
                {},
            ),
            (
                "wpilib-python",
                "WPILib Python (robotpy): SimpleMotorFeedforward + PIDController",
                "flywheel_gains.py",
                flywheel_wpilib_python,
                {},
            ),
            (
                "phoenix6",
                "CTRE Phoenix 6 TalonFXConfiguration + VelocityVoltage (Java)",
                "FlywheelTalonFXConfig.java",
                flywheel_phoenix6_java,
                {},
            ),
            (
                "phoenix6-rotor",
                "CTRE Phoenix 6 TalonFXConfiguration in rotor units, no SensorToMechanismRatio (Java)",
                "FlywheelRotorTalonFXConfig.java",
                flywheel_phoenix6_java,
                {"rotor": True},
            ),
            (
                "revlib",
                "REVLib SparkMaxConfig, velocity control in wheel rpm (Java)",
                "FlywheelSparkMaxConfig.java",
                flywheel_revlib_java,
                {},
            ),
        ),
    )
