"""Wheel surface speed: the toy calculator docs/adding-a-calculator.md walks through.

It is registered only inside tests/test_adding_a_calculator.py (never in the app). The page quotes
this file; that test checks every quoted block is still here, word for word.

Equations, in the order of the (imaginary) seed section "Wheel speed":
    ω_w = ω_m / G            (T1)  wheel speed from the motor speed and the reduction
    d_e = d + 2·t            (T2)  effective diameter: the wheel plus a tread of thickness t
    v   = ω_w · d_e / 2      (T3)  surface speed
    G   = ω_m · d_e / (2·v)  (T4)  (T3) and (T1) solved for the reduction (mode "ratio")
Everything is SI inside: ω in rad/s, lengths in m, v in m/s.
"""

from __future__ import annotations

from gearhead.core.errors import InputError
from gearhead.core.model import Calculator, Column, Field, Output, Plot, Result, Table

MODES = ("speed", "ratio")

FIELDS = (
    Field(
        "mode",
        "Mode",
        choices=MODES,
        choice_labels=("Speed from a ratio", "Ratio for a speed"),
        default="speed",
        help="Speed: the surface speed a reduction gives. Ratio: the reduction for a speed.",
    ),
    Field(
        "motor_speed",
        "Motor speed",
        "angular_speed",
        "rpm",
        default=5676,
        min=0,
        min_exclusive=True,
        max=100_000,
        help="ω_m: free speed of the motor (NEO: 5676 rpm).",
    ),
    Field(
        "ratio",
        "Reduction G",
        default=8.45,
        min=1,
        max=1000,
        modes=("speed",),
        help="Motor turns per wheel turn (T1).",
    ),
    Field(
        "target_speed",
        "Target speed",
        "speed",
        "ft/s",
        default=15,
        min=0,
        min_exclusive=True,
        max=100,
        modes=("ratio",),
        help="v: the surface speed wanted (T4).",
    ),
    Field(
        "wheel_diameter",
        "Wheel diameter",
        "length",
        "in",
        default=4,
        min=0.5,
        max=12,
        help="d: diameter of the bare wheel, 0.5 to 12 in.",
    ),
    Field(
        "tread",
        "Tread",
        choices=("none", "tread"),
        choice_labels=("None", "Tread strip"),
        default="none",
        help="A tread strip adds its thickness on each side (T2).",
    ),
    Field(
        "tread_thickness",
        "Tread thickness",
        "length",
        "in",
        default=0.125,
        min=0,
        max=1,
        when=(("tread", ("tread",)),),
        help="t: thickness of the tread strip (T2).",
    ),
)

OUTPUTS = (
    Output(
        "ratio_needed",
        "Reduction needed",
        equation="(T4)",
        help="G = ω_m·d_e/(2·v): the reduction that gives the target speed.",
    ),
    Output(
        "surface_speed",
        "Surface speed",
        "speed",
        "ft/s",
        equation="(T3)",
        help="v = ω_w·d_e/2: how fast the tread moves (the robot's free speed on the floor).",
    ),
    Output("wheel_speed", "Wheel speed", "angular_speed", "rpm", equation="(T1)", help="ω_w = ω_m/G."),
    Output(
        "effective_diameter",
        "Effective diameter",
        "length",
        "in",
        equation="(T2)",
        help="d_e = d + 2·t: the diameter that touches the floor.",
    ),
)

PLOTS = (
    Plot(
        "Surface speed against reduction",
        ("speed_vs_ratio",),
        "Reduction G",
        "dimensionless",
        "",
        "Surface speed",
        "speed",
        "ft/s",
    ),
)

WHEELS_IN = (2, 3, 4, 6)  # the table's other wheel sizes
TABLES = (
    Table(
        "wheels",
        "Other wheel sizes at this reduction",
        (
            Column("diameter", "Wheel", "length", "in", width=8),
            Column("surface_speed", "Speed", "speed", "ft/s", width=10),
        ),
    ),
)

INCH = 0.0254  # m (exact); a real calculator imports it from gearhead.core.constants


def effective_diameter(v) -> float:
    tread = v["tread_thickness"] if v["tread"] == "tread" else 0.0  # a field `when` hides is not used
    return v["wheel_diameter"] + 2 * tread  # (T2)


def surface_speed(motor_speed: float, ratio: float, diameter: float) -> float:
    return motor_speed / ratio * diameter / 2  # (T1), (T3)


def compute(v) -> Result:
    d_e = effective_diameter(v)
    warnings = []
    if v["mode"] == "ratio":
        G = v["motor_speed"] * d_e / (2 * v["target_speed"])  # (T4)
        if G < 1:
            raise InputError(
                "target_speed",
                f"needs a reduction below 1 ({G:.3g}): the wheel would turn faster than the motor",
            )
        values = {"ratio_needed": G}
    else:
        G = v["ratio"]
        values = {"surface_speed": surface_speed(v["motor_speed"], G, d_e)}
    w = v["motor_speed"] / G  # (T1)
    values.update(wheel_speed=w, effective_diameter=d_e)
    if w * d_e / 2 > 30 * 0.3048:  # 30 ft/s
        warnings.append("Over 30 ft/s: few FRC drivetrains can accelerate to this speed on a field.")
    ratios = [G * (0.5 + k / 20) for k in range(21)]  # 0.5 G to 1.5 G
    series = {"speed_vs_ratio": (ratios, [surface_speed(v["motor_speed"], r, d_e) for r in ratios])}
    rows = [
        {"diameter": d * INCH, "surface_speed": surface_speed(v["motor_speed"], G, d * INCH)}
        for d in WHEELS_IN
    ]
    return Result(values, warnings, series, {"wheels": rows})


CALCULATOR = Calculator(
    id="toy_wheel",
    title="Wheel speed",
    summary="Surface speed of a wheel from the motor speed and the reduction, or the reduction for a speed.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="Wheel speed (T1)-(T4)",
    plots=PLOTS,
    tables=TABLES,
)
