"""Gains as code (core.gains_code, issue 30): each unit conversion against numbers worked by hand, the
generated WPILib Python run against robotpy's wpimath classes, the Java files' values read back, and
the elevator's documents through the CLI (`solve elevator --document NAME`)."""

import math
import re

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
        assert _number(ph, rf"cfg\.Slot0\.{name}") == v[name]
    assert _number(ph, r"MotionMagicCruiseVelocity") == v["MotionMagicCruiseVelocity"]
    assert _number(ph, r"SensorToMechanismRatio") == 12.0
    assert _number(ph, r"StatorCurrentLimit") == 40.0 and _number(ph, r"SupplyCurrentLimit") == 30.0
    assert "GravityTypeValue.Elevator_Static" in ph
    rev = gains_code.revlib_java(HAND)
    r = gains_code.revlib_values(HAND)
    assert _number(rev, r"\.p") == r["p"] and _number(rev, r"\.d") == r["d"]
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
    assert (ff.getKs(), ff.getKg(), ff.getKv(), ff.getKa()) == (out["kS"], out["kG"], out["kV"], out["kA"])
    assert (pid.getP(), pid.getD(), pid.getPeriod()) == (out["kP"], out["kD"], 0.02)
    c = pid.getConstraints()
    assert (c.maxVelocity, c.maxAcceleration) == (
        out["profile_max_velocity"],
        out["profile_max_acceleration"],
    )


def document(capsys, *args):
    code = main(["solve", "elevator", *args])
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.parametrize("name", ["wpilib-java", "wpilib-python", "phoenix6", "revlib"])
def test_documents_through_the_cli(capsys, name):
    code, text, _ = document(capsys, "--set", "mode=profiled", "--document", name)
    assert code == 0 and ("kP" in text or ".p(" in text)
    code, text, err = document(capsys, "--document", name)  # the full-voltage move has no profile
    assert code == 2 and text == "" and "mode = profiled" in err and "Traceback" not in err


def test_export_is_the_designs_name_for_it(capsys):
    code, text, _ = document(capsys, "--set", "mode=profiled", "--export", "phoenix6")
    assert code == 0 and "cfg.Slot0.kP" in text


def test_arm_documents():
    """The arm's: ArmFeedforward in radians, run against robotpy; Phoenix 6 in arm rotations (2π rad)
    with Arm_Cosine; REVLib's arm term refused with the reason, not guessed."""
    from dataclasses import replace

    from gearhead.core.calculators import arm as arm_calc

    sol = solve("arm", {"mode": "profiled", "effects": "gravity, stator_limit"})
    out = {k: v.value for k, v in sol.outputs.items()}
    g = arm_calc.gains_of(sol)
    namespace: dict = {}
    exec(gains_code.wpilib_python(g), namespace)  # noqa: S102 - our own text
    ff, pid = namespace["feedforward"], namespace["controller"]
    assert type(ff).__name__ == "ArmFeedforward"
    assert (ff.getKs(), ff.getKg(), ff.getKv(), ff.getKa()) == (out["kS"], out["kG"], out["kV"], out["kA"])
    assert (pid.getP(), pid.getD()) == (out["kP"], out["kD"])
    ph = gains_code.phoenix6_java(g)
    assert "GravityTypeValue.Arm_Cosine" in ph and "horizontal" in ph
    # a gain per radian times 2π rad a rotation; 90°/s = 0.25 rps
    assert _number(ph, r"cfg\.Slot0\.kP") == pytest.approx(out["kP"] * 2 * math.pi, rel=1e-15)
    quarter = replace(g, max_velocity=math.pi / 2)
    assert gains_code.phoenix6_values(quarter)["MotionMagicCruiseVelocity"] == pytest.approx(0.25, rel=1e-15)
    with pytest.raises(ValueError, match="kCosRatio"):
        gains_code.revlib_java(g)
    assert [d.name for d in arm_calc.CALCULATOR.documents] == ["wpilib-java", "wpilib-python", "phoenix6"]
    java = gains_code.wpilib_java(g)
    assert "new ArmFeedforward(kS, kG, kV, kA, kPeriod)" in java and "V*s/rad" in java
