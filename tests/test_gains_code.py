"""Gains as code (core.gains_code, issue 30): each unit conversion against numbers worked by hand, the
generated WPILib Python run against robotpy's wpimath classes, the Java files' values read back, and
the elevator's documents through the CLI (`solve elevator --document NAME`)."""

import math
import re
from dataclasses import replace

import pytest

from gearhead.core import gains_code
from gearhead.core.calculators import elevator as elevator_calc
from gearhead.core.model import solve
from gearhead.tui.cli import main

# A hand case: drum radius 1 in, continuous rigging, G = 12, battery 12 V.
# L = 2π·0.0254 m = 0.159592906802... m per drum turn
L = 2 * math.pi * 0.0254
HAND = gains_code.Gains(
    kS=0.2,
    kG=0.4,
    kV=10.0,
    kA=0.5,
    kP=100.0,
    kD=3.0,
    max_velocity=1.5,
    max_acceleration=6.0,
    period=0.02,
    ratio=12.0,
    metres_per_rotation=L,
    battery_voltage=12.0,
    tolerance=0.005,
    stator_limit=40.0,
    supply_limit=30.0,
)


def test_phoenix6_by_hand():
    v = gains_code.phoenix6_values(HAND)
    # per drum rotation: a gain per metre times the metres a rotation moves (GC2)
    assert v["kV"] == pytest.approx(1.5959290680236, rel=1e-12)  # 10 V·s/m × 0.15959 m
    assert v["kA"] == pytest.approx(0.0797964534012, rel=1e-12)  # 0.5 × 0.15959
    assert v["kP"] == pytest.approx(15.959290680236, rel=1e-12)  # 100 V/m × 0.15959 m
    assert v["kD"] == pytest.approx(0.47877872040708, rel=1e-12)  # 3 × 0.15959
    assert v["MotionMagicCruiseVelocity"] == pytest.approx(
        9.398913962119803, rel=1e-12
    )  # 1.5 m/s ÷ 0.15959 m
    assert v["MotionMagicAcceleration"] == pytest.approx(37.59565584847921, rel=1e-12)  # 6 ÷ 0.15959
    assert (v["kS"], v["kG"], v["SensorToMechanismRatio"]) == (0.2, 0.4, 12.0)


def test_revlib_by_hand():
    v = gains_code.revlib_values(HAND)
    assert v["positionConversionFactor"] == pytest.approx(0.013299408900196791, rel=1e-12)  # 0.15959/12
    assert v["velocityConversionFactor"] == pytest.approx(2.2165681500327986e-4, rel=1e-12)  # ÷ 60 s/min
    assert v["p"] == pytest.approx(100 / 12, rel=1e-15)  # duty per metre at 12 V (GC3)
    assert v["d"] == pytest.approx(250.0, rel=1e-15)  # 3 V·s/m ÷ 12 V ÷ 0.001 s
    # native units are SI through the factors: the feedforward and MAXMotion limits pass unchanged
    assert (v["kV"], v["kA"], v["cruiseVelocity"], v["maxAcceleration"]) == (10.0, 0.5, 1.5, 6.0)


def test_phoenix_kv_is_the_motors_through_the_ratio():
    """An independent path to kV per drum rps: a motor's back-EMF constant is 1/Kv V per rad/s, i.e.
    2π/Kv per motor rps, G motor turns per drum turn; Gearhead's kV per metre times L must agree."""
    sol = solve(
        "elevator", {"mode": "profiled", "motor": "Kraken X60", "ratio": 9, "spool_diameter": "1.75 in"}
    )
    g = elevator_calc.gains_of(sol)
    setup = elevator_calc.setup({k: v.value for k, v in sol.inputs.items()})
    assert gains_code.phoenix6_values(g)["kV"] == pytest.approx(2 * math.pi / setup.mech.Kv * 9, rel=1e-12)
    assert g.metres_per_rotation == pytest.approx(math.pi * 1.75 * 0.0254, rel=1e-15)


def _number(text: str, pattern: str) -> float:
    m = re.search(pattern + r"\s*[=(]\s*([-+0-9.eE]+)", text)
    assert m, pattern
    return float(m.group(1))


def test_java_files_carry_the_values():
    ph = gains_code.phoenix6_java(HAND)
    v = gains_code.phoenix6_values(HAND)
    for name in ("kS", "kG", "kV", "kA", "kP", "kD"):
        assert _number(ph, rf"cfg\.Slot0\.{name}") == gains_code.export_number(v[name])  # 12 digits (GC11)
    assert _number(ph, r"MotionMagicCruiseVelocity") == gains_code.export_number(
        v["MotionMagicCruiseVelocity"]
    )
    assert _number(ph, r"SensorToMechanismRatio") == 12.0
    assert _number(ph, r"StatorCurrentLimit") == 40.0 and _number(ph, r"SupplyCurrentLimit") == 30.0
    assert "GravityTypeValue.Elevator_Static" in ph
    rev = gains_code.revlib_java(HAND)
    r = gains_code.revlib_values(HAND)
    assert _number(rev, r"\.p") == gains_code.export_number(r["p"]) and _number(
        rev, r"\.d"
    ) == gains_code.export_number(r["d"])
    assert _number(rev, r"\.cruiseVelocity") == 1.5 and _number(rev, r"smartCurrentLimit") == 40
    assert "REVLib has none" in rev  # the supply limit is said, not dropped silently
    java = gains_code.wpilib_java(HAND)
    assert _number(java, r"double kP") == 100.0 and _number(java, r"double kMaxAcceleration") == 6.0
    assert java.count("{") == java.count("}")


def test_wpilib_python_runs_against_robotpy():
    sol = solve("elevator", {"mode": "profiled", "travel": "-20 in", "sensor_delay": "5 ms"})
    out = {k: v.value for k, v in sol.outputs.items()}
    namespace: dict = {}
    exec(gains_code.wpilib_python(elevator_calc.gains_of(sol)), namespace)  # noqa: S102 - our own text
    ff, pid = namespace["feedforward"], namespace["controller"]
    assert (ff.getKs(), ff.getKg(), ff.getKv(), ff.getKa()) == tuple(
        map(gains_code.export_number, (out["kS"], out["kG"], out["kV"], out["kA"]))
    )
    assert (pid.getP(), pid.getD(), pid.getPeriod()) == (
        gains_code.export_number(out["kP"]),
        gains_code.export_number(out["kD"]),
        0.02,
    )
    c = pid.getConstraints()
    assert (c.maxVelocity, c.maxAcceleration) == (
        gains_code.export_number(out["profile_max_velocity"]),
        gains_code.export_number(out["profile_max_acceleration"]),
    )


def document(capsys, *args):
    code = main(["solve", "elevator", *args])
    out = capsys.readouterr()
    return code, out.out, out.err


MOTOR_OF = {"phoenix6": "Kraken X60", "revlib": "NEO"}  # a motor each controller drives (GC10)


@pytest.mark.parametrize("name", ["wpilib-java", "wpilib-python", "phoenix6", "revlib"])
def test_documents_through_the_cli(capsys, name):
    motor = MOTOR_OF.get(name, "Falcon 500")
    code, text, _ = document(capsys, "--set", "mode=profiled", "--set", f"motor={motor}", "--document", name)
    assert code == 0 and ("kP" in text or ".p(" in text)
    code, text, err = document(capsys, "--document", name)  # the full-voltage move has no profile
    assert code == 2 and text == "" and "mode = profiled" in err and "Traceback" not in err


def test_export_is_the_designs_name_for_it(capsys):
    code, text, _ = document(
        capsys, "--set", "mode=profiled", "--set", "motor=Kraken X60", "--export", "phoenix6"
    )
    assert code == 0 and "cfg.Slot0.kP" in text


def test_arm_documents():
    """The arm's: ArmFeedforward in radians, run against robotpy; Phoenix 6 in arm rotations (2π rad)
    with Arm_Cosine; REVLib in radians with kCos and kCosRatio (GC3a)."""
    from gearhead.core.calculators import arm as arm_calc

    sol = solve("arm", {"mode": "profiled", "effects": "gravity, stator_limit"})
    out = {k: v.value for k, v in sol.outputs.items()}
    g = arm_calc.gains_of(sol)
    namespace: dict = {}
    exec(gains_code.wpilib_python(g), namespace)  # noqa: S102 - our own text
    ff, pid = namespace["feedforward"], namespace["controller"]
    assert type(ff).__name__ == "ArmFeedforward"
    assert (ff.getKs(), ff.getKg(), ff.getKv(), ff.getKa()) == tuple(
        map(gains_code.export_number, (out["kS"], out["kG"], out["kV"], out["kA"]))
    )
    assert (pid.getP(), pid.getD()) == (
        gains_code.export_number(out["kP"]),
        gains_code.export_number(out["kD"]),
    )
    ph = gains_code.phoenix6_java(g)
    assert "GravityTypeValue.Arm_Cosine" in ph and "horizontal" in ph
    # a gain per radian times 2π rad a rotation; 90°/s = 0.25 rps
    assert _number(ph, r"cfg\.Slot0\.kP") == pytest.approx(out["kP"] * 2 * math.pi, rel=1e-11)
    quarter = replace(g, max_velocity=math.pi / 2)
    assert gains_code.phoenix6_values(quarter)["MotionMagicCruiseVelocity"] == pytest.approx(0.25, rel=1e-15)
    rev = gains_code.revlib_java(replace(g, motor="NEO"))  # the default arm's Kraken: a Talon FX's
    r = gains_code.revlib_values(g)
    assert (
        _number(rev, r"\.kCos") == gains_code.export_number(out["kG"]) and ".kG(" not in rev
    )  # REVLib keeps one of the two
    assert _number(rev, r"\.kCosRatio") == gains_code.export_number(r["kCosRatio"]) and "horizontal" in rev
    assert [d.name for d in arm_calc.CALCULATOR.documents] == [
        "wpilib-java",
        "wpilib-python",
        "phoenix6",
        "revlib",
    ]
    java = gains_code.wpilib_java(g)
    assert "new ArmFeedforward(kS, kG, kV, kA, kPeriod)" in java and "V*s/rad" in java


# An arm hand case: G = 50, so one arm turn (2π rad) is 50 motor turns.
ARM = replace(HAND, ratio=50.0, metres_per_rotation=2 * math.pi, kG=0.6, max_velocity=math.pi, arm=True)


def test_arm_revlib_by_hand():
    v = gains_code.revlib_values(ARM)
    assert v["positionConversionFactor"] == pytest.approx(0.12566370614359174, rel=1e-15)  # 2π/50 rad
    assert v["velocityConversionFactor"] == pytest.approx(0.0020943951023931952, rel=1e-15)  # 2π/3000
    assert v["kCosRatio"] == pytest.approx(0.15915494309189535, rel=1e-15)  # 1/(2π) turns per rad
    assert v["kCos"] == 0.6 and "kG" not in v
    # 12.5 motor turns are a quarter arm turn: π/2 rad native, 0.25 rotations after kCosRatio
    quarter = 12.5 * v["positionConversionFactor"]
    assert quarter == pytest.approx(math.pi / 2, rel=1e-15)
    assert quarter * v["kCosRatio"] == pytest.approx(0.25, rel=1e-15)
    # 3000 motor rpm = 50 motor rps = 1 arm rps = 2π rad/s native
    assert 3000 * v["velocityConversionFactor"] == pytest.approx(2 * math.pi, rel=1e-15)


@pytest.mark.parametrize("motor_turns", [-20.0, -6.25, 0.0, 3.0, 6.25, 12.5, 17.0])
def test_arm_revlib_gravity_is_wpilibs(motor_turns):
    """The SPARK's gravity term kCos·cos(2π·kCosRatio·position) (REV's javadoc) at an encoder
    reading, against robotpy's ArmFeedforward(kS=0, kG).calculate(angle, 0) at the arm's angle."""
    from wpimath.controller import ArmFeedforward

    v = gains_code.revlib_values(ARM)
    native = motor_turns * v["positionConversionFactor"]
    spark = v["kCos"] * math.cos(2 * math.pi * v["kCosRatio"] * native)
    angle = motor_turns / ARM.ratio * 2 * math.pi  # the arm's angle from horizontal, rad
    assert spark == pytest.approx(ArmFeedforward(0.0, ARM.kG, 0.0, 0.0).calculate(angle, 0.0), abs=1e-12)


@pytest.mark.parametrize("max_input", [None, 8.0])
def test_arm_documents_say_what_armfeedforward_computes(max_input):
    """WPILib 2026.2.2's ArmFeedforward.calculate(angle, v, next) inverts no gravity while kA < 0.1
    (core.sim.profiled (P5a)): no document says it does; Java's calculate(a, b) is (angle, velocity)
    for an arm, not (velocity, acceleration); the Java trapezoid documents show the discrete call."""
    arm = replace(ARM, max_input=max_input)
    docs = [
        gains_code.wpilib_python(arm),
        gains_code.wpilib_java(arm),
        gains_code.phoenix6_java(arm),
        gains_code.revlib_java(arm),
    ]
    for text in docs:
        assert "inverts" not in text and "reads b as an acceleration" not in text, text
    for text in docs[:2]:
        assert "kA*(next - v)/period + kG*cos(angle)" in text and "kA < 0.1" in text
    java = gains_code.wpilib_java(replace(ARM, max_input=None))
    assert "feedforward.calculateWithVelocities(sp.position, sp.velocity, next.velocity)" in java
    elevator = gains_code.wpilib_java(HAND)
    assert "feedforward.calculateWithVelocities(sp.velocity, next.velocity)" in elevator
    for text in (gains_code.phoenix6_java(arm), gains_code.revlib_java(HAND)):
        assert "not the roboRIO loop" in text and "its own profile" in text
    expo_rev = gains_code.revlib_java(replace(HAND, max_input=8.0))  # the profile stays on the roboRIO
    assert "its own profile" not in expo_rev and "setpoints the roboRIO sends" in expo_rev


def _cli(capsys, calc, *args):
    code = main(["solve", calc, *args])
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.parametrize(
    "calc, args, line",
    [
        # the reproducers: Expo_kV 107.4 V per rps (> 100), SensorToMechanismRatio 1500
        # (> 1000), MotionMagicAcceleration > 9999 rps/s (a Kraken X60: a NEO is refused; the derived
        # acceleration at a 120 A stator limit: at the default 40 A it is 9053 rps/s, in range)
        (
            "arm",
            ["--set", "ratio=300", "--set", "profile_type=exponential", "--set", "max_input=4 V"],
            "MotionMagicExpo_kV = 107.4",
        ),
        ("arm", ["--set", "ratio=1500"], "SensorToMechanismRatio = 1500"),
        (
            "elevator",
            [
                *("--set", "ratio=4", "--set", "spool_diameter=0.5 in", "--set", "load_mass=5 lb"),
                *("--set", "acceleration_fraction=0.9", "--set", "motor=Kraken X60"),
                *("--set", "effects=gravity, stator_limit", "--set", "stator_current_limit=120 A"),
            ],
            "MotionMagicAcceleration = 28579",
        ),
    ],
)
def test_phoenix6_values_outside_ctres_ranges_are_flagged(capsys, calc, args, line):
    """(GC9): each value outside Phoenix 6's documented bounds is listed with its range at the top and
    marked on its line."""
    code, text, _ = _cli(capsys, calc, "--set", "mode=profiled", *args, "--document", "phoenix6")
    assert code == 0
    top = text.split("import ")[0]
    assert "OUT OF RANGE for Phoenix 6" in top and line in top and "documented range" in top
    name = line.split(" = ")[0]
    (marked,) = [x for x in text.splitlines() if f".{name} = " in x]
    assert "// OUT OF RANGE:" in marked
    # in range: no flag
    code, text, _ = _cli(
        capsys, calc, "--set", "mode=profiled", "--set", "motor=Kraken X60", "--document", "phoenix6"
    )
    assert code == 0 and "OUT OF RANGE" not in text


@pytest.mark.parametrize(
    "calc, motor, name",
    [
        ("elevator", "NEO", "phoenix6"),
        ("arm", "Kraken X60", "revlib"),
        ("elevator", "CIM", "revlib"),
        ("arm", "NEO Vortex", "phoenix6"),
    ],
)
def test_a_controller_that_cannot_drive_the_motor_is_refused(capsys, calc, motor, name):
    """(GC10): phoenix6 (a Talon FX) for a NEO, revlib (a SPARK MAX on its primary encoder) for a
    Kraken X60: refused with the pairs that work, not written."""
    code, text, err = _cli(
        capsys, calc, "--set", "mode=profiled", "--set", f"motor={motor}", "--document", name
    )
    assert code == 2 and text == "" and "Traceback" not in err
    assert f"cannot drive a {motor}" in err and "Pairs that work" in err
    assert "phoenix6 with Falcon 500" in err and "revlib with NEO" in err
    for other in ("wpilib-java", "wpilib-python"):
        code, text, _ = _cli(
            capsys, calc, "--set", "mode=profiled", "--set", f"motor={motor}", "--document", other
        )
        assert code == 0 and text


def test_flywheel_documents_refuse_the_wrong_controller():
    from gearhead.core.calculators import flywheel as flywheel_calc

    sol = solve(
        "flywheel", {"control": "velocity_loop", "motor": "NEO", "ratio": 1, "target_speed": "3000 rpm"}
    )
    docs = {d.name: d for d in flywheel_calc.CALCULATOR.documents}
    with pytest.raises(ValueError, match="cannot drive a NEO"):
        docs["phoenix6"].build(sol)
    assert "SparkMaxConfig" in docs["revlib"].build(sol)


def test_wpilib_documents_refuse_gains_wpilib_throws_on(capsys):
    """(GC12): LQR gives kP = -55.5 V/m, kD = -0.27 V·s/m here (a 20 ms delay on a light
    elevator); WPILib's PIDController takes none (Java throws, C++ and robotpy zero the gains), so
    the WPILib documents are refused naming the value and the range (Phoenix 6 flags its
    own range, kP ≥ 0)."""
    from wpimath.controller import PIDController

    raw = ["--set", "mode=profiled", "--set", "sensor_delay=20 ms", "--set", "q_position=0.305 in"]
    raw += ["--set", "q_velocity=66.7 in/s", "--set", "ratio=6.806212814446597"]
    assert PIDController(-55.5, 0.0, -0.27).getP() == 0.0  # robotpy zeroes them (Java throws)
    for name in ("wpilib-java", "wpilib-python"):
        code, text, err = _cli(capsys, "elevator", *raw, "--document", name)
        assert code == 2 and text == "" and "kP = -55.49" in err and "≥ 0" in err, err
    code, text, _ = _cli(capsys, "elevator", *raw, "--set", "motor=Kraken X60", "--document", "phoenix6")
    assert code == 0 and "OUT OF RANGE" in text.split("import ")[0]
