"""Motor database and the motor-system equations of seed section 1 (eqs. 1-10, Appendix A).

Figures from ../shared/REFERENCE_DATA.md:
- WPILib `DCMotor` (wpimath, 2026), specification voltage 12 V.
- ReCalc `app/lib/models/Motor.ts` (tervay/recalc, dyno-based), 12 V; also the motors WPILib lacks
  (NEO 2.0, 775 RedLine, NeveRest, REV HD Hex, REV Core Hex): choosing WPILib data for them says
  so and uses ReCalc's.
- VEX: V5 Smart Motor cartridges and VEX 393 (7.2 V), from VEX's published specifications.
- Added for issue 31 (docs/motors.md lists each with its source): Minion (Adv Hall), Thrifty Pulsar,
  BaneBots 550, Snowblower and Modern Robotics from ReCalc's Motor.ts; the Romi's built-in motor
  from WPILib's DCMotor (4.5 V); the goBILDA Yellow Jacket family (5203 series) from goBILDA's
  specifications. They follow every motor above in MOTORS, so the choice lists only grow at the end.
SI inside: speeds in rad/s, torques in N*m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .constants import G0, LB, RPM
from .fields import Field


@dataclass(frozen=True)
class Motor:
    name: str
    source: str  # "wpilib", "recalc", "vex" or "gobilda"
    v_spec: float  # V
    free_speed: float  # ω_f, rad/s
    stall_torque: float  # τ_s, N*m
    stall_current: float  # i_s, A
    free_current: float  # i_f, A
    mass: float | None = None  # kg


def _m(name, source, v, rpm, ts, is_, if_, lb=None) -> Motor:
    return Motor(name, source, v, rpm * RPM, ts, is_, if_, None if lb is None else lb * LB)


# WPILib DCMotor: τs N*m, is A, if A, ωf rpm
_WPILIB = [
    ("CIM", 2.42, 133, 2.7, 5310),
    ("MiniCIM", 1.41, 89, 3, 5840),
    ("BAG", 0.43, 53, 1.8, 13180),
    ("775pro", 0.71, 134, 0.7, 18730),
    ("AndyMark RS775-125", 0.28, 18, 1.6, 5800),
    ("BaneBots RS775", 0.72, 97, 2.7, 13050),
    ("AndyMark 9015", 0.36, 71, 3.7, 14270),
    ("BaneBots RS550", 0.38, 84, 0.4, 19000),
    ("NEO", 2.6, 105, 1.8, 5676),
    ("NEO 550", 0.97, 100, 1.4, 11000),
    ("Falcon 500", 4.69, 257, 1.5, 6380),
    ("Falcon 500 FOC", 5.84, 304, 1.5, 6080),
    ("Kraken X60", 7.09, 366, 2, 6000),
    ("Kraken X60 FOC", 9.37, 483, 2, 5800),
    ("Kraken X44", 4.11, 279, 2, 7758),
    ("Kraken X44 FOC", 5.01, 329, 2, 7368),
    ("Minion", 3.17, 211, 2, 7704),
    # free current 3.615 A as WPILib's DCMotor (robotpy-wpimath 2026.2.2: DCMotor.neoVortex(1).freeCurrent;
    # REFERENCE_DATA.md's table rounds it to 3.6), so every Vortex result matches WPILib's
    ("NEO Vortex", 3.60, 211, 3.615, 6784),
]

# ReCalc: ωf rpm, τs N*m, is A, if A, mass lb (electrical figures checked against Motor.ts at tervay/recalc
# commit 03511cb4; there "Kraken X60 (FOC)" and "Kraken X44 (FOC)" are named with brackets, and CIM, MiniCIM,
# BAG and 775pro weigh a placeholder 1.0 lb: the weights here are REFERENCE_DATA.md's)
_RECALC = [
    ("Kraken X60", 6065, 7.157, 374.383, 2.83, 1.2),
    ("Kraken X60 FOC", 5784, 9.362, 476.098, 3.496, 1.2),
    ("NEO Vortex", 6825, 5.957, 391.091, 5.434, 0.98),
    ("NEO", 5906, 4.201, 216.269, 1.782, 0.938),
    ("Kraken X44", 7757, 4.113, 279.099, 3.156, 0.75),
    ("Kraken X44 FOC", 7367, 5.011, 329.188, 3.231, 0.75),
    ("Falcon 500", 6380, 4.69, 257, 1.5, 1.25),
    ("Minion", 7703, 3.173, 211.607, 2.206, 0.65),
    ("NEO 550", 11710, 1.08, 111, 1.1, 0.313),
    ("775pro", 18730, 0.71, 134, 0.7, 0.8),
    ("CIM", 5330, 2.41, 131, 2.7, 2.82),
    ("MiniCIM", 5840, 1.41, 89, 3, 2.16),
    ("BAG", 13180, 0.43, 53, 1.8, 0.71),
    # Motors teams use today that WPILib's DCMotor lacks (ReCalc app/lib/models/Motor.ts, tervay/recalc
    # commit 03511cb4): NEO 2.0 (ReCalc lists the NEO's dyno figures for it), AndyMark 775 RedLine,
    # AndyMark NeveRest (bare motor), REV HD Hex (bare motor, before its UltraPlanetary or gearbox)
    # and REV Core Hex (at its output shaft: the 72:1 gearbox is built in).
    ("NEO 2.0", 5906, 4.201, 216.269, 1.782, 0.8),
    ("775 RedLine", 19500, 0.64, 122, 2.6, 1.0),
    ("NeveRest", 5480, 0.173, 9.8, 0.355, 1.0),
    ("REV HD Hex", 6000, 0.105, 8.5, 0.4, 1.0),
    ("REV Core Hex", 125, 3.2, 4.4, 0.5, 1.0),
]
# Motor.ts weighs every brushed motor it has no weight for at a placeholder 1.0 lb: no mass here, so
# the motors table shows no power density it cannot back (the 1.0 above is not read by any calculator).
_PLACEHOLDER_MASS = {"775 RedLine", "NeveRest", "REV HD Hex", "REV Core Hex"}

# Added for issue 31, ReCalc app/lib/models/Motor.ts at tervay/recalc commit 03511cb4 (MIT): ωf rpm, τs N*m,
# is A, if A, mass lb (None: Motor.ts's placeholder 1.0 lb). Motor.ts's dataSource: CTRE for the Minion (Adv
# Hall), Thrifty for the Pulsar, VEX (motors.vex.com dyno) for the BaneBots 550, Snowblower and Modern Robotics.
_RECALC_ADDED = [
    ("Minion (Adv Hall)", 7644, 3.201, 207.18, 2.384, 0.65),
    ("Thrifty Pulsar", 7500, 3.1, 189, 1, 0.65),
    ("BaneBots 550", 19300, 0.488, 85, 1.4, None),
    ("Snowblower", 100, 7.90893775, 24, 5, None),
    ("Modern Robotics", 5900, 0.19, 11, 0.3, None),
    # issue 40: ReCalc lists these two as well (Motor.ts 'Falcon 500 (FOC)', 'AM-9015'); without them a
    # ReCalc import of either said "ReCalc (dyno) has no data" and used WPILib's (the same figures)
    ("Falcon 500 FOC", 6080, 5.84, 304, 1.5, 1.25),
    ("AndyMark 9015", 14270, 0.36, 71, 3.7, None),
]

# goBILDA 5203-series Yellow Jacket planetary gear motors at 12 V, at the gearbox output (goBILDA's product
# pages: stall torque in kg*cm, 9.2 A stall and 0.25 A no-load for every ratio): name, ratio, ωf rpm, τs kg*cm.
# The stall torques include the gearbox's losses (24.3 kg*cm at 19.2:1 is 86 % of 19.2 bare motors' worth).
_GOBILDA = [
    ("goBILDA Yellow Jacket 1150 rpm", 5.2, 1150, 7.9),
    ("goBILDA Yellow Jacket 435 rpm", 13.7, 435, 18.7),
    ("goBILDA Yellow Jacket 312 rpm", 19.2, 312, 24.3),
    ("goBILDA Yellow Jacket 223 rpm", 26.9, 223, 38.0),
]
KGF_CM = G0 / 100  # N*m per kg*cm

MOTORS: list[Motor] = (
    [_m(n, "wpilib", 12.0, rpm, ts, i_s, i_f) for n, ts, i_s, i_f, rpm in _WPILIB]
    + [
        _m(n, "recalc", 12.0, rpm, ts, i_s, i_f, None if n in _PLACEHOLDER_MASS else lb)
        for n, rpm, ts, i_s, i_f, lb in _RECALC
    ]
    + [
        # VEX V5 Smart Motor (11 W): one motor, three gear cartridges; same currents.
        _m("V5 100 rpm (red)", "vex", 12.0, 100, 2.1, 2.5, 0.9),
        _m("V5 200 rpm (green)", "vex", 12.0, 200, 1.05, 2.5, 0.9),
        _m("V5 600 rpm (blue)", "vex", 12.0, 600, 0.35, 2.5, 0.9),
        # VEX 393 at 7.2 V; the high-speed gearing trades torque for speed at the same power.
        _m("VEX 393", "vex", 7.2, 100, 1.67, 4.8, 0.37),
        _m("VEX 393 high speed", "vex", 7.2, 160, 1.67 * 100 / 160, 4.8, 0.37),
    ]
    + [_m(n, "recalc", 12.0, rpm, ts, i_s, i_f, lb) for n, rpm, ts, i_s, i_f, lb in _RECALC_ADDED]
    # Romi's built-in motor, WPILib DCMotor.getRomiBuiltIn (wpimath, 2026): 4.5 V, 0.1765 N*m, 1.25 A, 0.13 A,
    # 150 rpm (at the wheel: the gearbox is part of it)
    + [_m("Romi", "wpilib", 4.5, 150, 0.1765, 1.25, 0.13)]
    + [_m(n, "gobilda", 12.0, rpm, kgcm * KGF_CM, 9.2, 0.25) for n, _, rpm, kgcm in _GOBILDA]
)

SOURCES = ("wpilib", "recalc")
SOURCE_LABELS = ("WPILib DCMotor", "ReCalc (dyno)")


def motor_names() -> tuple[str, ...]:
    seen: dict[str, None] = {}
    for m in MOTORS:
        seen.setdefault(m.name, None)
    return tuple(seen)


def lookup(name: str, source: str = "wpilib") -> tuple[Motor, str | None]:
    """The motor's data from `source`, or from the source that has it (with a note saying so)."""
    matches = [m for m in MOTORS if m.name == name]
    if not matches:
        raise KeyError(name)
    for m in matches:
        if m.source == source:
            return m, None
    m = matches[0]
    if m.source not in SOURCES:  # a vendor's only figures (VEX, goBILDA): nothing to choose between
        return m, None
    label = dict(zip(SOURCES, SOURCE_LABELS))
    return m, f"{label.get(source, source)} has no data for {name}; using {label.get(m.source, m.source)}"


@dataclass(frozen=True)
class MotorSystem:
    """n equal motors 1:1 in a gearbox of efficiency η at applied voltage V (the x̃ quantities)."""

    free_speed: float  # ω̃f, rad/s
    stall_torque: float  # τ̃s, N*m (at the gearbox input, all motors, after η)
    free_current: float  # ĩf, A (all motors)
    stall_current: float  # ĩs, A (all motors)
    voltage: float
    count: int
    efficiency: float
    motor: Motor

    @property
    def kt(self) -> float:
        return self.stall_torque / (self.stall_current - self.free_current)  # (7)

    @property
    def peak_power(self) -> float:
        return self.free_speed * self.stall_torque / 4  # (6); SI: ω in rad/s, so no 2π

    def speed(self, tau):
        return self.free_speed * (1 - tau / self.stall_torque)  # (8)

    def current(self, tau):
        return (self.stall_current - self.free_current) * tau / self.stall_torque + self.free_current  # (9)

    def efficiency_at(self, tau):
        """(10): output power over electrical power, τ·ω(τ) / (V·i(τ))."""
        return tau * self.speed(tau) / (self.voltage * self.current(tau))

    @property
    def max_efficiency_torque(self) -> float:
        rf, rs = math.sqrt(self.free_current), math.sqrt(self.stall_current)
        return self.stall_torque * rf / (rf + rs)  # (91)

    @property
    def max_efficiency(self) -> float:
        """η at (91), simplified (sympy): ω̃f·τ̃s / (V·(√ĩf + √ĩs)²).

        This form stays finite when ĩf = 0, where (10) at τ = 0 would be 0/0.
        """
        rf, rs = math.sqrt(self.free_current), math.sqrt(self.stall_current)
        return self.free_speed * self.stall_torque / (self.voltage * (rf + rs) ** 2)


def system(motor: Motor, count: int, voltage: float, efficiency: float) -> MotorSystem:
    scale = voltage / motor.v_spec
    return MotorSystem(
        free_speed=motor.free_speed * scale,  # (1)
        stall_torque=motor.stall_torque * efficiency * count * scale,  # (2)
        free_current=motor.free_current * count * scale,  # (3)
        stall_current=motor.stall_current * count * scale,  # (4)
        voltage=voltage,
        count=count,
        efficiency=efficiency,
        motor=motor,
    )


# ---- fields shared by every calculator that drives something with motors ------------------


def motor_fields(default_motor: str = "Kraken X60", default_count: int = 1):
    """The motor picker and system fields (motor, source, count, voltage, gearbox efficiency)."""
    return (
        Field(
            "motor",
            "Motor",
            choices=motor_names(),
            default=default_motor,
            help="Motor model; FRC motors from WPILib or ReCalc data, VEX V5 and 393 from VEX.",
        ),
        Field(
            "source",
            "Motor data",
            choices=SOURCES,
            choice_labels=SOURCE_LABELS,
            default="wpilib",
            help="Which published figures to use where WPILib and ReCalc disagree.",
        ),
        Field(
            "motor_count",
            "Motors",
            integer=True,
            default=default_count,
            min=1,
            max=16,
            help="Number of identical motors geared 1:1 together (n).",
        ),
        Field(
            "voltage",
            "Voltage",
            "voltage",
            "V",
            default=12,
            min=0.1,
            max=48,
            help="Applied voltage V; motor data is scaled by V/V_spec (eqs. 1-4).",
        ),
        Field(
            "efficiency",
            "Gearbox efficiency",
            "dimensionless",
            "",
            default=1,
            min=0,
            min_exclusive=True,
            max=1,
            help="Gearbox efficiency η, 0 to 1 (e.g. 0.9 or 90 %).",
        ),
    )


def system_from(values) -> tuple[MotorSystem, list[str]]:
    """The motor system described by the motor fields of a parsed input dict."""
    motor, note = lookup(values["motor"], values["source"])
    warnings = [note] if note else []
    if values["voltage"] > 1.25 * motor.v_spec:  # e.g. a VEX 393 left at the 12 V default
        warnings.append(
            f"{motor.name} is specified at {motor.v_spec:.3g} V: at {values['voltage']:.3g} V "
            f"its data are scaled up {values['voltage'] / motor.v_spec:.3g}× (eqs. 1-4), "
            f"beyond its rating; enter {motor.v_spec:.3g} V for its published figures."
        )
    return system(motor, values["motor_count"], values["voltage"], values["efficiency"]), warnings
