"""ReCalc links as Gearhead presets: `gearhead import 'https://www.reca.lc/linear?...'`.

ReCalc (https://www.reca.lc, github.com/tervay/recalc, MIT) keeps a calculator's inputs in its
URL: "Copy Link" writes every input as a query parameter (nuqs `createSerializer` with
`clearOnDefault: false`, app/lib/hooks.ts `useSerializedState`), each serialised by its parser in
app/lib/types/queryParams.ts:

- a measurement as JSON `{"s": scalar, "u": units}`, the units as js-quantities writes them
  (`lbs`, `in`, `in2*lbs`, `m/s2`, `Ohm`);
- a motor as `{"name": "Kraken X60 (FOC)", "quantity": 2}` (names from app/lib/models/Motor.ts);
- a ratio as `{"magnitude": 2, "ratioType": "Reduction" | "Step-up"}` (app/lib/models/Ratio.ts);
- numbers as text (`100`), booleans as `true`/`false`, the ratio calculator's stages as
  `[[18,72],[24,48]]`.

A parameter missing from a link, or one ReCalc's parser would refuse, takes ReCalc's default, as
ReCalc itself does (`withDefault`): DEFAULTS below holds them, copied from each route's
`DEFAULT_PARAMS` (app/routes/linear.tsx, arm.tsx, flywheel.tsx, belts.tsx, chains.tsx, gears.tsx,
ratio.tsx, intake.tsx at tervay/recalc commit 03511cb4). Every parameter that has no Gearhead
field, or whose meaning differs, is named in the preset's warnings; nothing is dropped silently.
"""

from __future__ import annotations

import json
import math
import re
from typing import Any

from .errors import InputError, shown
from .presets import Preset, from_dict

SOURCE = "<ReCalc link>"
MAX_LINK_CHARS = 20_000

_LINK = re.compile(r"^(?:https?://)?(?:www\.)?reca\.lc/(?P<page>[\w-]*)/?(?:\?(?P<query>[^#]*))?(?:#.*)?$")


def _num(x: float) -> str:
    """The shortest text that reads back as exactly `x` (0.015, not 0.014999999999999999)."""
    text = repr(float(x))
    return text[:-2] if text.endswith(".0") else text


def _m(s: float, u: str) -> dict:
    return {"s": s, "u": u}


def _motor(quantity: int) -> dict:
    return {"name": "Kraken X60 (FOC)", "quantity": quantity}


def _ratio(magnitude: float) -> dict:
    return {"magnitude": magnitude, "ratioType": "Reduction"}


# ReCalc's own defaults (each route's DEFAULT_PARAMS; see the module docstring), in its serialised
# form. Only the parameters an import reads or names are listed.
DEFAULTS: dict[str, dict[str, Any]] = {
    "linear": {
        "motor": _motor(1),
        "travelDistance": _m(60, "in"),
        "spoolDiameter": _m(1, "in"),
        "load": _m(5, "lb"),
        "ratio": _ratio(2),
        "efficiency": 100,
        "statorLimit": _m(80, "A"),
        "supplyLimit": _m(60, "A"),
        "supplyVoltage": _m(12, "V"),
        "angle": _m(90, "deg"),
        "batteryResistance": _m(0.015, "Ohm"),
        "cascade": False,
        "qPosition": _m(0.02, "m"),
        "qVelocity": _m(0.4, "m/s"),
        "rVolts": _m(12, "V"),
        "sensorDelay": _m(1, "ms"),
        "feedbackDt": _m(20, "ms"),
    },
    "arm": {
        "motor": _motor(1),
        "ratio": _ratio(100),
        "statorLimit": _m(80, "A"),
        "supplyLimit": _m(60, "A"),
        "supplyVoltage": _m(12, "V"),
        "batteryResistance": _m(0.015, "Ohm"),
        "armLength": _m(24, "in"),
        "minAngle": _m(0, "deg"),
        "maxAngle": _m(90, "deg"),
        "efficiency": 100,
        "load": _m(5, "lb"),
        "qPosition": _m(2, "deg"),
        "qVelocity": _m(40, "deg/s"),
        "rVolts": _m(12, "V"),
        "sensorDelay": _m(1, "ms"),
        "feedbackDt": _m(20, "ms"),
    },
    "flywheel": {
        "motor": _motor(2),
        "ratio": _ratio(1),
        "statorLimit": _m(80, "A"),
        "supplyLimit": _m(60, "A"),
        "supplyVoltage": _m(12.6, "V"),
        "batteryResistance": _m(0.015, "Ohm"),
        "shooterDiameter": _m(4, "in"),
        "shooterWeight": _m(1, "lb"),
        "shooterTargetSpeed": _m(3000, "rpm"),
        "customShooterMoi": _m(4.5, "in2*lbs"),
        "useCustomShooterMoi": False,
        "flywheelEnabled": False,
        "flywheelDiameter": _m(4, "in"),
        "flywheelWeight": _m(1.5, "lb"),
        "customFlywheelMoi": _m(3, "in2*lbs"),
        "useCustomFlywheelMoi": False,
        "flywheelToShooterRatio": _ratio(1),
        "projectileDiameter": _m(5, "in"),
        "projectileWeight": _m(0.5, "lb"),
        "ballInitialVelocity": _m(0, "ft/s"),
        "ballInitialSpin": _m(0, "rpm"),
        "shooterMode": "single-hooded",
        "useCustomBallMoi": False,
        "customBallMoi": _m(2.5, "in2*lbs"),
        "secondaryShooterDiameter": _m(4, "in"),
        "secondaryShooterWeight": _m(1, "lb"),
        "secondaryShooterToShooterRatio": _ratio(1),
        "useCustomSecondaryShooterMoi": False,
        "customSecondaryShooterMoi": _m(4.5, "in2*lbs"),
        "efficiency": 100,
    },
    "belts": {
        "customBeltTeeth": 125,
        "desiredCenter": _m(5, "in"),
        "extraCenter": _m(0, "mm"),
        "p1Teeth": 16,
        "p2Teeth": 24,
        "pitch": _m(5, "mm"),
        "toothIncrement": 5,
        "useCustomBelt": False,
    },
    "chains": {
        "pitch": _m(0.25, "in"),
        "p1Teeth": 16,
        "p2Teeth": 36,
        "desiredCenter": _m(5, "in"),
        "extraCenter": _m(0, "in"),
        "allowHalfLinks": False,
    },
    "gears": {"gear1Teeth": 16, "gear2Teeth": 36, "gearDP": 20},
    "ratio": {"ratioPairs": [[18, 72], [24, 48]]},
    "intake": {
        "motor": _motor(1),
        "ratio": _ratio(2),
        "rollerDiameter": _m(2, "in"),
        "travelDistance": _m(15, "in"),
        "drivetrainSpeed": _m(14, "ft/s"),
        "statorCurrentLimit": _m(30, "A"),
    },
}

TARGETS = {
    "linear": "elevator",
    "arm": "arm",
    "flywheel": "flywheel",
    "belts": "chain_belt",
    "chains": "chain_belt",
    "gears": "ratio_distance",
    "ratio": "ratio_finder",
    "intake": "intake",
}

# ReCalc's motor names (Motor.ts) -> Gearhead's; the others have no Gearhead motor
MOTORS = {
    "Kraken X60": "Kraken X60",
    "Kraken X60 (FOC)": "Kraken X60 FOC",
    "NEO Vortex": "NEO Vortex",
    "NEO 2.0": "NEO 2.0",
    "NEO": "NEO",
    "Kraken X44": "Kraken X44",
    "Kraken X44 (FOC)": "Kraken X44 FOC",
    "Falcon 500": "Falcon 500",
    "Falcon 500 (FOC)": "Falcon 500 FOC",
    "Minion": "Minion",
    "NEO 550": "NEO 550",
    "775pro": "775pro",
    "775 RedLine": "775 RedLine",
    "CIM": "CIM",
    "MiniCIM": "MiniCIM",
    "BAG": "BAG",
    "AM-9015": "AndyMark 9015",
    "BaneBots 550": "BaneBots 550",  # ReCalc's own figures (WPILib's RS550 differs: 0.38 vs 0.488 N*m)
    "NeveRest": "NeveRest",
    "HD Hex": "REV HD Hex",
    "Core Hex": "REV Core Hex",
    "V5 Smart Motor (Red)": "V5 100 rpm (red)",
}

# js-quantities unit names (as ReCalc writes them) that pint spells otherwise
_UNIT_NAMES = {"lbs": "lb", "Ohm": "ohm", "hr": "hour", "\u00b0": "deg", "degrees": "deg"}
_UNIT_TOKEN = re.compile(r"^([A-Za-z\u00b0\u00b5]+)(?:\^?(-?[0-9]+))?$")


def is_link(text: str) -> bool:
    return bool(_LINK.match(text.strip()))


def pint_units(units: str) -> str:
    """A js-quantities unit string as Gearhead reads it: 'in2*lbs' -> 'in**2*lb', 'm/s2' -> 'm/s**2'."""
    out, sep = [], ""
    for part in re.split(r"([*/])", units.replace(" ", "*")):
        if part in ("*", "/"):
            sep = part
            continue
        token = _UNIT_TOKEN.match(part)
        if not token:
            raise ValueError(units)
        name = _UNIT_NAMES.get(token[1], token[1])
        out.append(sep + name + (f"**{token[2]}" if token[2] and token[2] != "1" else ""))
    return "".join(out)


def _same_shape(value: Any, default: Any) -> bool:
    """Whether a parsed JSON value has the shape of ReCalc's default: an object with the same keys,
    each member of its default's type (a number for a number), or a list (its items are checked
    where it is read)."""
    if isinstance(default, dict):
        return (
            isinstance(value, dict)
            and set(value) == set(default)
            and all(_same_shape(value[k], default[k]) for k in default)
        )
    if isinstance(default, bool) or isinstance(value, bool):
        return isinstance(value, bool) and isinstance(default, bool)
    if isinstance(default, (int, float)):
        return isinstance(value, (int, float))
    return type(value) is type(default)


def _finite(value: Any) -> bool:
    """Whether every number in a parsed JSON value is a finite float (json reads Infinity, NaN,
    1e400 as inf, and integers of any size)."""
    if isinstance(value, dict):
        return all(_finite(v) for v in value.values())
    if isinstance(value, list):
        return all(_finite(v) for v in value)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        try:
            return math.isfinite(float(value))
        except OverflowError:
            return False
    return True


class _Link:
    """One ReCalc link's parameters, read as ReCalc reads them, with the notes of the import."""

    def __init__(self, page: str, query: str):
        from urllib.parse import parse_qs

        self.page = page
        self.raw = {k: v[-1] for k, v in parse_qs(query, keep_blank_values=True).items()}
        self.notes: list[str] = []
        self.used: set[str] = set()

    def value(self, name: str) -> Any:
        """The parameter's value as ReCalc's parser reads it; its default if absent or refused."""
        self.used.add(name)
        default = DEFAULTS[self.page][name]
        if name not in self.raw:
            return default
        text = self.raw[name]
        try:
            if isinstance(default, bool):
                if text not in ("true", "false"):
                    raise ValueError(text)
                return text == "true"
            if isinstance(default, (int, float)):
                number = float(text)
                if not math.isfinite(number):
                    raise ValueError(text)
                return number
            if isinstance(default, str):
                return text
            value = json.loads(text)
            if not _same_shape(value, default):  # {"name": ["x"]}: a list where a name goes
                raise ValueError(text)
        except (ValueError, TypeError, RecursionError):
            self.notes.append(f"{name}: {shown(text)} is not what ReCalc writes there; ReCalc's default used")
            return default
        if not _finite(value):  # 1e400, a 400-digit integer, Infinity, NaN: past any robot
            raise InputError(name, f"{shown(text)} holds a number past the finite range", SOURCE)
        return value

    def quantity(self, name: str) -> str:
        """A measurement as text Gearhead's fields read ('60 in', '4.5 in**2*lb')."""
        m = self.value(name)
        s, u = m.get("s"), m.get("u")
        if not isinstance(s, (int, float)) or isinstance(s, bool) or not isinstance(u, str):
            raise InputError(name, f"{shown(self.raw.get(name))} is not a ReCalc measurement", SOURCE)
        try:
            return f"{_num(s)} {pint_units(u)}"
        except ValueError:
            raise InputError(name, f"the unit {shown(u)} is not one Gearhead reads", SOURCE) from None

    def si(self, name: str, kind: str) -> float:
        from .units import parse

        return parse(self.quantity(name), "", kind, name)

    def motor(self, inputs: dict) -> None:
        m = self.value("motor")
        name, count = m.get("name"), m.get("quantity")
        if name in MOTORS:
            inputs["motor"] = MOTORS[name]
            inputs["source"] = "recalc"  # ReCalc's motor data, as its sims use
        else:
            self.notes.append(f"motor: Gearhead has no {shown(name)}; the calculator's default motor used")
        if isinstance(count, (int, float)) and not isinstance(count, bool):
            if not math.isfinite(count):  # json reads Infinity and NaN
                raise InputError("motor", f"{shown(count)} motors is not a count", SOURCE)
            inputs["motor_count"] = int(count) if count == int(count) else count

    def ratio(self, name: str = "ratio") -> float:
        r = self.value(name)
        magnitude, kind = r.get("magnitude"), r.get("ratioType")
        if not isinstance(magnitude, (int, float)) or isinstance(magnitude, bool) or magnitude <= 0:
            raise InputError(name, f"{shown(self.raw.get(name))}: a ratio must be a positive number", SOURCE)
        if kind not in ("Reduction", "Step-up"):
            raise InputError(name, f"ratio type {shown(kind)} is neither Reduction nor Step-up", SOURCE)
        return magnitude if kind == "Reduction" else 1 / magnitude  # Gearhead: motor turns per output turn

    def efficiency(self, inputs: dict) -> None:
        inputs["efficiency"] = f"{_num(self.value('efficiency'))} %"

    def limits(
        self, inputs: dict, stator: str = "statorLimit", supply: str | None = "supplyLimit"
    ) -> list[str]:
        """ReCalc's sims always limit the current and sag the battery: the matching effects on."""
        inputs["stator_current_limit"] = self.quantity(stator)
        effects = ["stator_limit"]
        if supply:
            inputs["supply_current_limit"] = self.quantity(supply)
            effects.append("supply_limit")
        if "batteryResistance" in DEFAULTS[self.page]:
            inputs["battery_resistance"] = self.quantity("batteryResistance")
            effects.append("battery_sag")
        return effects

    def control(self, inputs: dict) -> None:
        for theirs, ours in (
            ("qPosition", "q_position"),
            ("qVelocity", "q_velocity"),
            ("rVolts", "r_volts"),
            ("sensorDelay", "sensor_delay"),
            ("feedbackDt", "control_period"),
        ):
            inputs[ours] = self.quantity(theirs)


def _linear(link: _Link) -> dict:
    inputs: dict[str, Any] = {}
    link.motor(inputs)
    inputs["ratio"] = link.ratio()
    link.efficiency(inputs)
    inputs["voltage"] = link.quantity("supplyVoltage")
    inputs["load_mass"] = link.quantity("load")
    inputs["spool_diameter"] = link.quantity("spoolDiameter")
    inputs["travel"] = link.quantity("travelDistance")
    # ReCalc's angle is the rail's from horizontal (90 deg: vertical); Gearhead's incline from vertical
    angle = link.si("angle", "angle")
    inputs["incline"] = f"{_num(90 - math.degrees(angle))} deg"
    if link.value("cascade"):
        inputs["rigging"] = "cascade"
        inputs["stages"] = 2  # ReCalc's cascade: the carriage moves twice the rope (CASCADE_TRAVEL_FACTOR)
        # ReCalc's simulation doubles the load on the first stage (linear.ts CASCADE_LOAD_FACTOR), as
        # Gearhead's cascade does; its shown gains (computeElevatorFeedforwardGains) leave it out
        link.notes.append(
            "cascade: a 2-stage cascade (rigging = cascade, stages = 2): the spool holds twice the load "
            "and the carriage moves twice the rope, as in ReCalc's simulation, so kG and kA come out 2× "
            "and kV ½× the gains ReCalc shows (its gains leave the cascade out); gains here are per "
            "metre of carriage travel"
        )
    else:
        inputs["rigging"] = "continuous"
    effects = link.limits(inputs)
    inputs["effects"] = (["gravity"] if abs(math.cos(math.pi / 2 - angle)) > 1e-12 else []) + effects
    link.control(inputs)
    return inputs


def _arm(link: _Link) -> dict:
    inputs: dict[str, Any] = {}
    link.motor(inputs)
    inputs["ratio"] = link.ratio()
    link.efficiency(inputs)
    inputs["voltage"] = link.quantity("supplyVoltage")
    inputs["arm_mass"] = link.quantity("load")
    inputs["com_distance"] = link.quantity("armLength")
    # ReCalc's arm is its load at the arm's length: I = m·L² (arm.tsx momentOfInertia)
    mass, length = link.si("load", "mass"), link.si("armLength", "length")
    inputs["inertia_model"] = "entered"
    try:
        inertia = mass * length * length
    except OverflowError:
        inertia = math.inf
    if not (math.isfinite(inertia) and inertia > 0):
        raise InputError("load", "and armLength give no finite, positive moment of inertia (m·L²)", SOURCE)
    inputs["moment_of_inertia"] = f"{_num(inertia)} kg*m**2"
    inputs["start_angle"] = link.quantity("minAngle")
    inputs["goal_angle"] = link.quantity("maxAngle")
    inputs["effects"] = ["gravity", *link.limits(inputs)]
    link.control(inputs)
    return inputs


def _disc_or_custom(link: _Link, diameter: str, weight: str, custom: str, use_custom: str) -> str:
    """A wheel's moment of inertia as ReCalc takes it: the entered one, else a solid disc m·r²/2
    (flywheel.tsx derivedShooterMOI and its siblings)."""
    if link.value(use_custom):
        link.used.update((diameter, weight))
        return link.quantity(custom)
    link.used.add(custom)
    radius = link.si(diameter, "length") / 2
    try:
        inertia = link.si(weight, "mass") * radius * radius / 2
    except OverflowError:
        inertia = math.inf
    if not math.isfinite(inertia) or inertia <= 0:
        raise InputError(weight, "and the diameter give no finite, positive moment of inertia", SOURCE)
    return f"{_num(inertia)} kg*m**2"


# ReCalc's shooter modes (flywheel.tsx, ballShot.ts) -> Gearhead's layouts (core/calculators/flywheel.py)
SHOOTER_MODES = {"single-hooded": "hood", "dual-shooter": "dual", "compound": "compound"}


def _flywheel(link: _Link) -> dict:
    """ReCalc's shot (ballShot.ts) is the momentum transfer with no loss, the ball a solid sphere
    (2/5·m·r²) unless entered: the same model chosen here, so the numbers are ReCalc's."""
    inputs: dict[str, Any] = {}
    link.motor(inputs)
    G = inputs["ratio"] = link.ratio()
    link.efficiency(inputs)
    inputs["voltage"] = link.quantity("supplyVoltage")
    inputs["wheel_diameter"] = link.quantity("shooterDiameter")
    inputs["mode"] = "moment_of_inertia"
    inputs["wheel_inertia"] = _disc_or_custom(
        link, "shooterDiameter", "shooterWeight", "customShooterMoi", "useCustomShooterMoi"
    )
    inputs["wheel_count"] = 1
    inputs["target_speed"] = link.quantity("shooterTargetSpeed")
    inputs["ball_diameter"] = link.quantity("projectileDiameter")
    inputs["ball_mass"] = link.quantity("projectileWeight")
    if link.value("useCustomBallMoi"):
        r_b = link.si("projectileDiameter", "length") / 2
        try:
            factor = link.si("customBallMoi", "inertia") / (link.si("projectileWeight", "mass") * r_b * r_b)
        except (OverflowError, ZeroDivisionError):
            factor = math.nan
        if not (math.isfinite(factor) and factor > 0):
            raise InputError("customBallMoi", "gives no finite, positive I/(m·r²) for the ball", SOURCE)
        inputs["ball_inertia_factor"] = factor
    else:
        link.used.add("customBallMoi")
        inputs["ball_inertia_factor"] = 0.4
    inputs["ball_initial_speed"] = link.quantity("ballInitialVelocity")
    inputs["ball_initial_spin"] = link.quantity("ballInitialSpin")
    inputs["transfer"] = "momentum"
    inputs["loss_fraction"] = "0 %"
    mode = link.value("shooterMode")
    shooter = SHOOTER_MODES.get(mode)
    if shooter is None:
        link.notes.append(f"shooterMode: Gearhead has no {shown(mode)} shooter; a hooded single wheel used")
        shooter = "hood"
    secondary = ("secondaryShooterDiameter", "secondaryShooterWeight", "customSecondaryShooterMoi")
    extra = ("flywheelDiameter", "flywheelWeight", "customFlywheelMoi")
    if shooter in ("dual", "compound"):  # the top wheel turns at 1/r of the shooter: G₂ = G·r
        inputs["secondary_diameter"] = link.quantity("secondaryShooterDiameter")
        inputs["secondary_inertia"] = _disc_or_custom(link, *secondary, "useCustomSecondaryShooterMoi")
        inputs["secondary_count"] = 1
        inputs["secondary_ratio"] = G * link.ratio("secondaryShooterToShooterRatio")
        if link.value("flywheelEnabled"):
            link.notes.append(
                "flywheelEnabled: Gearhead models a secondary shooter wheel or an extra geared flywheel, "
                "not both; the extra flywheel left out"
            )
        link.used.update((*extra, "useCustomFlywheelMoi", "flywheelToShooterRatio"))
    elif link.value("flywheelEnabled"):  # a hood with ReCalc's extra geared flywheel: its inertia only
        shooter = "hood_secondary"
        inputs["secondary_diameter"] = link.quantity("flywheelDiameter")
        inputs["secondary_inertia"] = _disc_or_custom(link, *extra, "useCustomFlywheelMoi")
        inputs["secondary_count"] = 1
        inputs["secondary_ratio"] = G * link.ratio("flywheelToShooterRatio")
        link.used.update((*secondary, "useCustomSecondaryShooterMoi", "secondaryShooterToShooterRatio"))
    else:  # neither: their parameters have nothing to act on
        link.used.update(
            (*secondary, "useCustomSecondaryShooterMoi", "secondaryShooterToShooterRatio", *extra)
        )
        link.used.update(("useCustomFlywheelMoi", "flywheelToShooterRatio"))
    inputs["shooter"] = shooter
    inputs["effects"] = link.limits(inputs)
    return inputs


def _pitch(link: _Link, kind: str, standards: dict[float, str]) -> dict:
    pitch = link.si("pitch", "length")
    inputs: dict[str, Any] = {"kind": kind}
    for size, name in standards.items():
        if math.isclose(pitch, size, rel_tol=1e-9):
            inputs["pitch_standard"] = name
            break
    else:
        inputs["pitch_standard"] = "custom"
        inputs["pitch"] = link.quantity("pitch")
    inputs["teeth_1"] = link.value("p1Teeth")
    inputs["teeth_2"] = link.value("p2Teeth")
    inputs["mode"] = "links_from_center"
    inputs["target_center"] = link.quantity("desiredCenter")
    if link.si("extraCenter", "length") != 0:
        link.notes.append(
            f"extraCenter: Gearhead adds no extra center distance ({link.quantity('extraCenter')} left out)"
        )
    return inputs


def _belts(link: _Link) -> dict:
    inputs = _pitch(link, "belt", {0.005: "htd_5mm", 0.003: "gt2_3mm"})
    if link.value("useCustomBelt"):
        inputs["mode"] = "center_from_links"
        inputs["links"] = link.value("customBeltTeeth")
    link.used.add("toothIncrement")
    link.notes.append(
        "toothIncrement: Gearhead lists the nearest lengths of every tooth count, not steps of it"
    )
    return inputs


def _chains(link: _Link) -> dict:
    inputs = _pitch(link, "chain", {0.00635: "chain_25", 0.009525: "chain_35", 0.0127: "chain_40"})
    inputs["half_links"] = link.value("allowHalfLinks")
    return inputs


def _gears(link: _Link) -> dict:
    t1, t2, dp = link.value("gear1Teeth"), link.value("gear2Teeth"), link.value("gearDP")
    if not (t1 > 0 and t2 > 0 and dp > 0):
        raise InputError("gear1Teeth", "teeth and diametral pitch must be positive", SOURCE)
    link.notes.append(
        f"gears: opened as Ratio & distance at ratio {t2:g}/{t1:g} and the pair's center "
        f"(T1 + T2)/(2·DP) = {(t1 + t2) / (2 * dp):.6g} in, which gives back {t1:g}T and {t2:g}T"
    )
    return {"ratio": t2 / t1, "center_distance": f"{_num((t1 + t2) / (2 * dp))} in", "diametral_pitch": dp}


def _ratio_pairs(link: _Link) -> dict:
    pairs = link.value("ratioPairs")
    if not pairs or not all(
        isinstance(p, list) and len(p) == 2 and all(isinstance(x, (int, float)) and x > 0 for x in p)
        for p in pairs
    ):
        raise InputError(
            "ratioPairs", f"{shown(link.raw.get('ratioPairs'))}: stages of two tooth counts", SOURCE
        )
    overall = math.prod(driven / driving for driving, driven in pairs)
    link.notes.append(
        f"ratioPairs: {len(pairs)} stage(s) giving {overall:.6g}:1 overall; the ratio finder searches "
        f"parts for that ratio (the stages' tooth counts are not kept)"
    )
    return {"mode": "ratio", "target_ratio": overall, "max_stages": min(max(len(pairs), 1), 3)}


def _intake(link: _Link) -> dict:
    inputs: dict[str, Any] = {}
    link.motor(inputs)
    inputs["ratio"] = link.ratio()
    inputs["roller_diameter"] = link.quantity("rollerDiameter")
    inputs["pull_distance"] = link.quantity("travelDistance")
    inputs["drivetrain_speed"] = link.quantity("drivetrainSpeed")
    inputs["effects"] = "stator_limit"
    inputs["stator_current_limit"] = link.quantity("statorCurrentLimit")
    return inputs


_BUILDERS = {
    "linear": _linear,
    "arm": _arm,
    "flywheel": _flywheel,
    "belts": _belts,
    "chains": _chains,
    "gears": _gears,
    "ratio": _ratio_pairs,
    "intake": _intake,
}

TITLES = {
    "linear": "linear mechanism",
    "arm": "arm",
    "flywheel": "flywheel",
    "belts": "belt",
    "chains": "chain",
    "gears": "gears",
    "ratio": "ratio",
    "intake": "intake",
}


def to_preset(url: str) -> Preset:
    """The Gearhead preset a ReCalc link describes; its warnings say what could not be mapped."""
    text = url.strip()
    if len(text) > MAX_LINK_CHARS:
        raise InputError("link", f"is too long for a ReCalc link ({len(text)} characters)", SOURCE)
    found = _LINK.match(text)
    if not found:
        raise InputError("link", f"{shown(text)} is not a ReCalc link (https://www.reca.lc/...)", SOURCE)
    page = found["page"]
    if page not in _BUILDERS:
        known = ", ".join(sorted(_BUILDERS))
        raise InputError(
            "link",
            f"ReCalc's {shown(page or '/')} page has no Gearhead counterpart (importable: {known})",
            SOURCE,
        )
    link = _Link(page, found["query"] or "")
    inputs = _BUILDERS[page](link)
    unmapped = sorted(set(link.raw) - link.used)
    if unmapped:
        link.notes.append(f"not mapped (no Gearhead field): {', '.join(unmapped)}")
    calc = TARGETS[page]
    name = f"ReCalc {TITLES[page]}"
    description = f"imported from {text[:300]}"
    try:
        preset = from_dict(
            {"calculator": calc, "name": name, "description": description, "inputs": inputs}, SOURCE
        )
    except InputError as exc:  # a value Gearhead's field refuses (out of its range): named, and left out
        bad = {e.field for e in exc.errors}
        if not bad <= set(inputs):
            raise
        for e in exc.errors:
            link.notes.append(f"{e.field}: {e.message}; the field's default used")
        kept = {k: v for k, v in inputs.items() if k not in bad}
        preset = from_dict(
            {"calculator": calc, "name": name, "description": description, "inputs": kept}, SOURCE
        )
    preset.warnings = [f"ReCalc {page}: {note}" for note in link.notes] + preset.warnings
    return preset
