"""ReCalc links as presets (core/recalc.py).

The links are built here as ReCalc's "Copy Link" builds them: every parameter of the route's
DEFAULT_PARAMS (tervay/recalc at commit 03511cb4: app/routes/linear.tsx, arm.tsx, flywheel.tsx,
belts.tsx, chains.tsx, gears.tsx, ratio.tsx, intake.tsx), serialised by the parsers of
app/lib/types/queryParams.ts (JSON.stringify of Measurement.toDict / Motor.toDict / Ratio.toDict;
numbers and booleans as text) into a query string (nuqs createSerializer, app/lib/hooks.ts). Units
are spelled as js-quantities' `units()` writes them (`lbs`, `Ohm`, `m/s2`, `in2*lbs`).

The expected values are worked out here by hand from those defaults, not read from the module.
"""

import json
import math
from urllib.parse import urlencode

import pytest

from gearhead.core import recalc, share
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.registry import get
from gearhead.tui.cli import main

LB, IN = 0.45359237, 0.0254


def m(s, u):
    return {"s": s, "u": u}


MOTOR_1 = {"name": "Kraken X60 (FOC)", "quantity": 1}

# DEFAULT_PARAMS of each route, every parameter (those Gearhead has no field for included)
RECALC_DEFAULTS = {
    "linear": {
        "motor": MOTOR_1,
        "travelDistance": m(60, "in"),
        "spoolDiameter": m(1, "in"),
        "load": m(5, "lbs"),
        "ratio": {"magnitude": 2, "ratioType": "Reduction"},
        "efficiency": 100,
        "statorLimit": m(80, "A"),
        "supplyLimit": m(60, "A"),
        "supplyVoltage": m(12, "V"),
        "angle": m(90, "deg"),
        "batteryResistance": m(0.015, "Ohm"),
        "cascade": False,
        "maximumComfortableStatorLimit": m(80, "A"),
        "maximumComfortableSupplyLimit": m(60, "A"),
        "enableCustomMaxVelocity": False,
        "maxVelocity": m(2, "m/s"),
        "enableCustomMaxAcceleration": False,
        "maxAcceleration": m(10, "m/s2"),
        "qPosition": m(0.02, "m"),
        "qVelocity": m(0.4, "m/s"),
        "rVolts": m(12, "V"),
        "sensorDelay": m(1, "ms"),
        "feedbackDt": m(20, "ms"),
        "kalmanFilterPositionStdDev": m(2, "in"),
        "kalmanFilterVelocityStdDev": m(40, "in/s"),
        "kalmanFilterEncoderPositionStdDev": m(0.001, "in"),
    },
    "arm": {
        "motor": MOTOR_1,
        "ratio": {"magnitude": 100, "ratioType": "Reduction"},
        "statorLimit": m(80, "A"),
        "supplyLimit": m(60, "A"),
        "supplyVoltage": m(12, "V"),
        "statorVoltage": m(12, "V"),
        "batteryResistance": m(0.015, "Ohm"),
        "armLength": m(24, "in"),
        "minAngle": m(0, "deg"),
        "maxAngle": m(90, "deg"),
        "efficiency": 100,
        "load": m(5, "lbs"),
        "maximumComfortableStatorLimit": m(80, "A"),
        "maximumComfortableSupplyLimit": m(60, "A"),
        "qPosition": m(2, "deg"),
        "qVelocity": m(40, "deg/s"),
        "rVolts": m(12, "V"),
        "sensorDelay": m(1, "ms"),
        "feedbackDt": m(20, "ms"),
    },
    "flywheel": {
        "motor": {"name": "Kraken X60 (FOC)", "quantity": 2},
        "ratio": {"magnitude": 1, "ratioType": "Reduction"},
        "statorLimit": m(80, "A"),
        "supplyLimit": m(60, "A"),
        "supplyVoltage": m(12.6, "V"),
        "batteryResistance": m(0.015, "Ohm"),
        "shooterDiameter": m(4, "in"),
        "shooterWeight": m(1, "lbs"),
        "shooterTargetSpeed": m(3000, "rpm"),
        "customShooterMoi": m(4.5, "in2*lbs"),
        "useCustomShooterMoi": False,
        "flywheelDiameter": m(4, "in"),
        "flywheelWeight": m(1.5, "lbs"),
        "customFlywheelMoi": m(3, "in2*lbs"),
        "useCustomFlywheelMoi": False,
        "flywheelEnabled": False,
        "flywheelToShooterRatio": {"magnitude": 1, "ratioType": "Reduction"},
        "projectileDiameter": m(5, "in"),
        "projectileWeight": m(0.5, "lbs"),
        "ballInitialVelocity": m(0, "ft/s"),
        "ballInitialSpin": m(0, "rpm"),
        "shooterMode": "single-hooded",
        "useCustomBallMoi": False,
        "customBallMoi": m(2.5, "in2*lbs"),
        "secondaryShooterDiameter": m(4, "in"),
        "secondaryShooterWeight": m(1, "lbs"),
        "secondaryShooterToShooterRatio": {"magnitude": 1, "ratioType": "Reduction"},
        "useCustomSecondaryShooterMoi": False,
        "customSecondaryShooterMoi": m(4.5, "in2*lbs"),
        "efficiency": 100,
        "maximumComfortableStatorLimit": m(80, "A"),
        "maximumComfortableSupplyLimit": m(60, "A"),
        "qVelocity": m(50, "rpm"),
        "rVolts": m(12, "V"),
        "sensorDelay": m(1, "ms"),
        "feedbackDt": m(20, "ms"),
    },
    "belts": {
        "customBeltTeeth": 125,
        "desiredCenter": m(5, "in"),
        "extraCenter": m(0, "mm"),
        "p1Teeth": 16,
        "p2Teeth": 24,
        "pitch": m(5, "mm"),
        "toothIncrement": 5,
        "useCustomBelt": False,
    },
    "chains": {
        "pitch": m(0.25, "in"),
        "p1Teeth": 16,
        "p2Teeth": 36,
        "desiredCenter": m(5, "in"),
        "extraCenter": m(0, "in"),
        "allowHalfLinks": False,
    },
    "gears": {"gear1Teeth": 16, "gear2Teeth": 36, "gearDP": 20},
    "ratio": {"ratioPairs": [[18, 72], [24, 48]]},
    "intake": {
        "motor": MOTOR_1,
        "ratio": {"magnitude": 2, "ratioType": "Reduction"},
        "rollerDiameter": m(2, "in"),
        "travelDistance": m(15, "in"),
        "drivetrainSpeed": m(14, "ft/s"),
        "statorCurrentLimit": m(30, "A"),
    },
}


def serialise(value) -> str:
    """One parameter as nuqs writes it: JSON.stringify for objects and arrays, else the text."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (dict, list)):
        return json.dumps(value, separators=(",", ":"))
    return str(value)


def link(page: str, **changes) -> str:
    params = {**RECALC_DEFAULTS[page], **changes}
    return f"https://www.reca.lc/{page}?" + urlencode({k: serialise(v) for k, v in params.items()})


def si(preset, name):
    calc = get(preset.calculator)
    field = next(f for f in calc.fields if f.name == name)
    return field.parse(preset.inputs[name])


@pytest.mark.parametrize("page", sorted(RECALC_DEFAULTS))
def test_each_calculators_default_link_imports_and_solves(page):
    preset = recalc.to_preset(link(page))
    assert preset.calculator == recalc.TARGETS[page]
    result = solve(preset.calculator, preset.inputs)
    assert result.outputs
    # every parameter is either read or named in the notes
    named = " ".join(preset.warnings)
    for param in RECALC_DEFAULTS[page]:
        assert param in recalc.DEFAULTS[page] or param in named, param


def test_linear_maps_every_quantity_it_shares():
    preset = recalc.to_preset(link("linear"))
    assert preset.inputs["motor"] == "Kraken X60 FOC" and preset.inputs["source"] == "recalc"
    assert preset.inputs["motor_count"] == 1 and preset.inputs["ratio"] == 2
    assert si(preset, "travel") == pytest.approx(60 * IN, rel=1e-15)
    assert si(preset, "spool_diameter") == pytest.approx(IN, rel=1e-15)
    assert si(preset, "load_mass") == pytest.approx(5 * LB, rel=1e-15)
    assert si(preset, "incline") == 0  # ReCalc's 90 deg from horizontal is vertical
    assert si(preset, "battery_resistance") == pytest.approx(0.015, rel=1e-15)
    assert si(preset, "control_period") == pytest.approx(0.020, rel=1e-15)
    assert si(preset, "q_velocity") == pytest.approx(0.4, rel=1e-15)
    assert set(preset.inputs["effects"]) == {"gravity", "stator_limit", "supply_limit", "battery_sag"}
    notes = " ".join(preset.warnings)
    assert "kalmanFilterPositionStdDev" in notes and "maxAcceleration" in notes


def test_linear_angle_cascade_and_step_up():
    preset = recalc.to_preset(
        link("linear", angle=m(30, "deg"), cascade=True, ratio={"magnitude": 4, "ratioType": "Step-up"})
    )
    assert si(preset, "incline") == pytest.approx(math.radians(60), rel=1e-14)
    assert preset.inputs["rigging"] == "cascade" and preset.inputs["stages"] == 2
    assert preset.inputs["ratio"] == 0.25
    flat = recalc.to_preset(link("linear", angle=m(0, "deg")))
    assert "gravity" not in flat.inputs["effects"]


def test_arm_is_a_point_mass_at_the_arms_length():
    preset = recalc.to_preset(link("arm"))
    assert preset.inputs["inertia_model"] == "entered"
    assert si(preset, "moment_of_inertia") == pytest.approx(
        5 * LB * (24 * IN) ** 2, rel=1e-14
    )  # 0.84280 kg m^2
    assert si(preset, "goal_angle") == pytest.approx(math.pi / 2, rel=1e-15)
    assert preset.inputs["ratio"] == 100


def test_flywheel_wheel_is_a_solid_disc_unless_its_moi_is_given():
    preset = recalc.to_preset(link("flywheel"))
    assert si(preset, "wheel_inertia") == pytest.approx(0.5 * LB * (2 * IN) ** 2, rel=1e-14)
    assert si(preset, "target_speed") == pytest.approx(3000 * 2 * math.pi / 60, rel=1e-15)
    assert preset.inputs["shooter"] == "hood" and preset.inputs["motor_count"] == 2
    custom = recalc.to_preset(link("flywheel", useCustomShooterMoi=True))
    assert si(custom, "wheel_inertia") == pytest.approx(4.5 * LB * IN**2, rel=1e-14)
    also = recalc.to_preset(link("flywheel", useCustomShooterMoi=True, customShooterMoi=m(4.5, "lbs*in2")))
    assert si(also, "wheel_inertia") == pytest.approx(4.5 * LB * IN**2, rel=1e-14)
    compound = recalc.to_preset(link("flywheel", shooterMode="compound", flywheelEnabled=True))
    assert compound.inputs["shooter"] == "compound"  # the extra flywheel as well is not modelled: said
    assert "flywheelEnabled" in " ".join(compound.warnings)


def test_belts_and_chains_pick_the_standard_pitch():
    belt = recalc.to_preset(link("belts"))
    assert (belt.inputs["kind"], belt.inputs["pitch_standard"]) == ("belt", "htd_5mm")
    assert (belt.inputs["teeth_1"], belt.inputs["teeth_2"]) == (16, 24)
    assert si(belt, "target_center") == pytest.approx(5 * IN, rel=1e-15)
    custom = recalc.to_preset(link("belts", useCustomBelt=True, customBeltTeeth=110))
    assert (custom.inputs["mode"], custom.inputs["links"]) == ("center_from_links", 110)
    odd = recalc.to_preset(link("belts", pitch=m(8, "mm")))
    assert odd.inputs["pitch_standard"] == "custom" and si(odd, "pitch") == pytest.approx(0.008, rel=1e-15)
    chain = recalc.to_preset(link("chains", pitch=m(0.375, "in"), allowHalfLinks=True))
    assert (chain.inputs["pitch_standard"], chain.inputs["half_links"]) == ("chain_35", True)
    extra = recalc.to_preset(link("chains", extraCenter=m(0.1, "in")))
    assert any("extraCenter" in w for w in extra.warnings)


def test_gears_come_back_as_the_same_pair():
    preset = recalc.to_preset(link("gears", gear1Teeth=14, gear2Teeth=60, gearDP=32))
    out = solve(preset.calculator, preset.inputs).outputs
    assert (out["small_teeth"].value, out["large_teeth"].value) == (14, 60)
    assert si(preset, "center_distance") == pytest.approx(74 / 64 * IN, rel=1e-15)


def test_ratio_pairs_give_the_overall_ratio():
    preset = recalc.to_preset(link("ratio", ratioPairs=[[12, 60], [18, 54], [20, 40]]))
    assert preset.inputs["target_ratio"] == pytest.approx(5 * 3 * 2, rel=1e-15)
    assert preset.inputs["max_stages"] == 3


def test_intake_opens_the_intake_calculator_with_every_input():
    """ReCalc's intake defaults (2 in rollers, 15 in travel, 14 ft/s, a 30 A stator limit): each
    has its field, and the surface speed is the roller's free speed through the ratio by hand."""
    preset = recalc.to_preset(link("intake"))
    assert preset.calculator == "intake" and not preset.warnings
    assert si(preset, "roller_diameter") == pytest.approx(2 * IN, rel=1e-15)
    assert si(preset, "pull_distance") == pytest.approx(15 * IN, rel=1e-15)
    assert si(preset, "drivetrain_speed") == pytest.approx(14 * 12 * IN, rel=1e-15)
    assert si(preset, "stator_current_limit") == pytest.approx(30, rel=1e-15)
    from gearhead.core.motors import lookup

    motor, _ = lookup(preset.inputs["motor"], preset.inputs["source"])  # ReCalc's Kraken X60 (FOC)
    out = solve("intake", preset.inputs).outputs
    free = motor.free_speed * 12 / motor.v_spec  # rad/s at 12 V (eq. 1)
    assert out["surface_speed"].value == pytest.approx(free / 2 * IN, rel=1e-12)  # ω/G · d/2
    assert out["speed_ratio"].value == pytest.approx(free / 2 * IN / (14 * 12 * IN), rel=1e-12)


def test_a_short_link_takes_recalcs_defaults():
    assert recalc.to_preset("https://www.reca.lc/linear").inputs == recalc.to_preset(link("linear")).inputs
    assert recalc.to_preset("reca.lc/arm").inputs == recalc.to_preset(link("arm")).inputs


def test_a_value_recalc_would_refuse_takes_its_default_with_a_note():
    preset = recalc.to_preset(link("linear", load="{not json", cascade="maybe"))
    assert si(preset, "load_mass") == pytest.approx(5 * LB, rel=1e-15)
    assert preset.inputs["rigging"] == "continuous"
    notes = " ".join(preset.warnings)
    assert "load" in notes and "cascade" in notes
    unknown = recalc.to_preset(link("linear", motor={"name": "Snowblower", "quantity": 1}))
    assert "motor" not in unknown.inputs and any("Snowblower" in w for w in unknown.warnings)


@pytest.mark.parametrize(
    "text,why",
    [
        ("https://www.reca.lc/motors", "no Gearhead counterpart"),
        ("https://example.com/linear?x=1", "not a ReCalc link"),
        (link("linear", travelDistance=m(60, "furlongz")), None),  # a unit no one reads: named, default used
        (link("linear", efficiency=150), None),  # out of range: named, default used
        (link("arm", ratio={"magnitude": -1, "ratioType": "Reduction"}), "positive"),
        ("https://www.reca.lc/linear?" + "a=1&" * 5000, "too long"),
    ],
)
def test_links_gearhead_cannot_take_are_named(text, why):
    if why is None:
        preset = recalc.to_preset(text)
        name = "travel" if "furlongz" in text else "efficiency"
        assert name not in preset.inputs and any(
            w.startswith(f"ReCalc linear: {name}:") for w in preset.warnings
        )
        return
    with pytest.raises(InputError) as caught:
        recalc.to_preset(text)
    assert why in str(caught.value) and "\n" not in str(caught.value)


def test_cli_import_and_preset_take_a_recalc_link(capsys):
    url = link("gears")
    assert main(["import", url]) == 0
    out = capsys.readouterr()
    assert 'calculator = "ratio_distance"' in out.out and "ReCalc gears" in out.err
    assert main(["solve", "ratio_distance", "--preset", url, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["outputs"]["small_teeth"]["value"] == 16 and data["outputs"]["large_teeth"]["value"] == 36
    assert main(["import", url, "--code"]) == 0
    code = capsys.readouterr().out.strip()
    assert share.decode(code).inputs == recalc.to_preset(url).inputs
    assert main(["import", "https://www.reca.lc/motors"]) == 2
    assert "no Gearhead counterpart" in capsys.readouterr().err


@pytest.mark.parametrize("how", ["paste", "enter"])
async def test_a_recalc_link_pasted_or_typed_into_ctrl_o_opens_its_card(how):
    from textual import events
    from textual.widgets import Input

    from gearhead.tui.app import GearheadApp
    from tests.tui_helpers import card, settle

    url = link("gears", gear1Teeth=14, gear2Teeth=60)
    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        await pilot.press("ctrl+o")
        await settle(pilot)
        entry = app.screen.query_one("#preset-path", Input)
        if how == "paste":
            entry.post_message(events.Paste(url))
        else:
            entry.focus()
            entry.value = url
            await pilot.press("enter")
        await settle(pilot)
        assert app.current_calculator == "ratio_distance"
        tab = card(app, "ratio_distance")
        assert tab.preset_meta[0] == "ReCalc gears"
        assert (tab.solution.outputs["small_teeth"].value, tab.solution.outputs["large_teeth"].value) == (
            14,
            60,
        )


def _shot_cases():
    from tests.test_flywheel_layouts import (
        I_B,
        I_W,
        M_B,
        R_B,
        R_W,
        W_0,
        recalc_compound,
        recalc_dual,
        recalc_single,
    )

    i_fw = 1.5 * LB * (2 * IN) ** 2 / 2  # ReCalc's extra flywheel: 4 in, 1.5 lb, a solid disc
    return [
        ({"shooterMode": "single-hooded"}, "hood", recalc_single(W_0, R_W, I_W, M_B, R_B, I_B)),
        ({"shooterMode": "dual-shooter"}, "dual", recalc_dual(W_0, R_W, 2 * I_W, M_B, R_B, I_B, R_W, 1.0)),
        (
            {"shooterMode": "compound"},
            "compound",
            recalc_compound(W_0, R_W, 2 * I_W, M_B, R_B, I_B, R_W, 1.0),
        ),
        ({"flywheelEnabled": True}, "hood_secondary", recalc_single(W_0, R_W, I_W + i_fw, M_B, R_B, I_B)),
    ]


@pytest.mark.parametrize("changes,shooter,want", _shot_cases())
def test_a_flywheel_link_gives_recalcs_own_shot(changes, shooter, want):
    """ReCalc's shot (ballShot.ts: momentum, no loss, the ball 2/5·m·r², the top wheel's and the
    extra flywheel's inertia through their ratios) on its defaults, against the port of its
    formulas in tests/test_flywheel_layouts.py. The import used the energy model and mapped a
    dual shooter to the same-speed pair: the hooded ball 16 % fast (6.868 m/s for 5.911)."""
    preset = recalc.to_preset(link("flywheel", **changes))
    assert preset.inputs["shooter"] == shooter
    out = solve("flywheel", preset.inputs).outputs
    assert out["wheel_speed_after"].value == pytest.approx(want[0], rel=1e-12)
    assert out["ball_speed"].value == pytest.approx(want[1], rel=1e-12)
    assert out["ball_spin"].value == pytest.approx(want[2], rel=1e-12, abs=1e-12)


@pytest.mark.parametrize(
    "page,changes,field",
    [
        ("linear", {"motor": {"name": "NEO", "quantity": math.inf}}, "motor"),
        ("linear", {"motor": {"name": "NEO", "quantity": math.nan}}, "motor"),
        ("arm", {"load": m(1e200, "lbs"), "armLength": m(1e200, "in")}, "load"),
        ("flywheel", {"shooterDiameter": m(1e200, "in"), "shooterWeight": m(1e200, "lbs")}, "shooterWeight"),
        ("flywheel", {"useCustomBallMoi": True, "projectileWeight": m(0, "lbs")}, "customBallMoi"),
    ],
)
def test_a_link_with_numbers_past_any_robot_is_refused_naming_the_parameter(page, changes, field):
    """json reads Infinity and NaN, and 1e200² overflows: each was a traceback (exit 70)."""
    with pytest.raises(InputError) as refused:
        recalc.to_preset(link(page, **changes))
    assert refused.value.field == field
