"""Every motor of the database side by side (issue 31), as ReCalc's motors page: one motor each at a
voltage, with the controller's current limits, each on its own shaft or geared to one output speed.

The motor model is the one of every tab (core.motors, seed eqs. 1-10; README "One motor model on every
tab"); the limited torque is the motor tab's (core.calculators.motor (L1), core.sim.motor_limits
(E1)-(E3)). Per motor, data at V_spec, at voltage V, gearbox efficiency η (1 on its own shaft):
    ω̃f = ωf·V/V_spec, τ̃s = η·τs·V/V_spec, ĩs = Is·V/V_spec, ĩf = If·V/V_spec     (C1)  eqs. 1-4
    Kt = τs/(Is − If)                                  the motor's own, at its shaft   (C2)  eq. 7
    P_peak = ω̃f·τ̃s/4                                                                  (C3)  eq. 6
    P_peak/m                                   power density, where a source gives m (C4)
    τ_lim = η·Kt·(I(0) − ĩf)     at rest with the limits: I(0) from (E1)-(E3) at E = 0 (C5)  (L1)
           (the stator limit alone: I(0) = min(ĩs, I_st); the supply limit: u·I ≤ I_sup)
Efficiency along the line (8), (9) as a function of the stator current I (sympy: τ = τ̃s·(I − ĩf)/(ĩs − ĩf),
ω = ω̃f·(ĩs − I)/(ĩs − ĩf), η(I) = τ·ω/(V·I)):
    η(I) = ω̃f·τ̃s·(I − ĩf)·(ĩs − I) / (V·I·(ĩs − ĩf)²)                                (C6)
rising up to its peak at I* = √(ĩf·ĩs) (the seed's (91)) and falling after; the highest efficiency with
the stator current at or below the stator limit I_st is η(min(I_st, I*)) (0 when that is ≤ ĩf). This is
ReCalc's "efficiency at the current limit" (Motor.maxEfficiencyAtCurrentLimit) with the seed's Kt.
Geared to a common output speed ω_o, each motor through its own reduction:
    G = ω̃f/ω_o;  output free speed ω_o, torques ×G (η already in τ̃s and τ_lim)          (C7)
The curves (one per chosen motor, over the output speed): τ(ω)·G from (L1) at motor speed G·ω, stator
current I, output power τ·ω and efficiency τ·ω/(V·u·I).
"""

from __future__ import annotations

import dataclasses
import math

from ..declarations import Calculator, Column, Output, Plot, Result, Table
from ..errors import InputError
from ..fields import Field
from ..motors import MOTORS, lookup, motor_fields, motor_names, system
from ..sim import motor_limits
from ..sim.effects import Effects
from .motor import limited_curve

_stator, _supply, _ = motor_limits.electrical_effects()
EFFECTS = Effects(dataclasses.replace(_stator, default_on=True), _supply)

GEARINGS = ("none", "same_speed")
SORTS = (
    "peak_power",
    "limited_torque",
    "stall_torque",
    "free_speed",
    "stall_current",
    "power_density",
    "efficiency",
    "kt",
    "mass",
    "name",
)
SORT_LABELS = (
    "Peak power",
    "Torque at the limit",
    "Stall torque",
    "Free speed",
    "Stall current",
    "Power density",
    "Efficiency within the limit",
    "Kt",
    "Mass (lightest first)",
    "Name",
)
ASCENDING = {"name", "mass"}  # every other column sorts largest first
NONE = "(none)"
CURVES = 4
CURVE_DEFAULTS = ("Kraken X60", "NEO Vortex", "NEO", "Minion")
SOURCE_NAMES = {"wpilib": "WPILib", "recalc": "ReCalc", "vex": "VEX", "gobilda": "goBILDA"}

_source, _voltage, _efficiency = (f for f in motor_fields() if f.name in ("source", "voltage", "efficiency"))

FIELDS = (
    _source,
    _voltage,
    Field(
        "gearing",
        "Gearing",
        choices=GEARINGS,
        choice_labels=("Each on its own shaft", "Each geared to one output speed"),
        default="none",
        help="Own shaft: the motors as they come. Geared: each through the reduction G = ω̃f/ω_o (C7) "
        "that gives its free speed at the output speed, so torques compare at one speed.",
    ),
    Field(
        "output_speed",
        "Output free speed",
        "angular_speed",
        "rpm",
        default=500,
        min=0,
        min_exclusive=True,
        max=100_000,
        when=(("gearing", ("same_speed",)),),
        help="ω_o: the free speed every motor is geared to (C7).",
    ),
    dataclasses.replace(
        _efficiency,
        when=(("gearing", ("same_speed",)),),
        help="Gearbox efficiency η of each motor's reduction, 0 to 1 (C1).",
    ),
    EFFECTS.field(
        "stator_limit (per motor, on by default: the torque and efficiency at the limit), supply_limit "
        "(per motor: stator current × duty)."
    ),
    *EFFECTS.fields(),
    Field(
        "sort_by",
        "Sort the table by",
        choices=SORTS,
        choice_labels=SORT_LABELS,
        default="peak_power",
        help="Largest first, except name (A to Z) and mass (lightest first); a motor with no figure last.",
    ),
    *(
        Field(
            f"curve_motor_{k + 1}",
            f"Curve {k + 1}",
            choices=motor_names() if k == 0 else (NONE, *motor_names()),
            default=CURVE_DEFAULTS[k],
            help="A motor whose curves the charts show (limited as the table: (L1)).",
        )
        for k in range(CURVES)
    ),
)

OUTPUTS = (
    Output(
        "first_motor",
        "First by the sort",
        help="The motor at the top of the table in the chosen order.",
        equation="(C1)-(C7)",
    ),
    Output("motors_listed", "Motors listed", help="Every motor of the database.", equation=""),
)

TABLES = (
    Table(
        "motors",
        "Every motor (sorted as chosen)",
        (
            Column("motor", "Motor", width=30),
            Column("data", "Data", width=7),
            Column("ratio", "G", width=7),
            Column("free_speed", "Free speed", "angular_speed", "rpm", width=8),
            Column("stall_torque", "Stall τ", "torque", "N*m", width=8),
            Column("stall_current", "Stall I", "current", "A", width=7),
            Column("peak_power", "Peak P", "power", "W", width=7),
            Column("limited_torque", "τ at limit", "torque", "N*m", width=8),
            Column("power_density", "P/mass", "power_density", "W/kg", width=7),
            Column("efficiency", "η ≤ limit", "dimensionless", "%", width=7),
            Column("kt", "Kt", "torque_constant", "N*m/A", width=7),
            Column("mass", "Mass", "mass", "lb", width=6),
        ),
    ),
)

CURVE_KINDS = ("torque", "power", "current", "efficiency")  # one series per chosen motor in each plot


def _keys(what: str) -> tuple[str, ...]:
    return tuple(f"{what} {k + 1}" for k in range(CURVES))


PLOTS = (
    Plot(
        "Torque vs speed", _keys("torque"), "output speed", "angular_speed", "rpm", "torque", "torque", "N*m"
    ),
    Plot(
        "Power vs speed", _keys("power"), "output speed", "angular_speed", "rpm", "output power", "power", "W"
    ),
    Plot(
        "Stator current vs speed",
        _keys("current"),
        "output speed",
        "angular_speed",
        "rpm",
        "stator current",
        "current",
        "A",
    ),
    Plot(
        "Efficiency vs speed",
        _keys("efficiency"),
        "output speed",
        "angular_speed",
        "rpm",
        "efficiency",
        "dimensionless",
        "%",
    ),
)


def line_efficiency(I: float, s) -> float:
    """(C6): the efficiency on the unlimited line at stator current I (per motor system `s`)."""
    i_f, i_s = s.free_current, s.stall_current
    if I <= i_f or I >= i_s:
        return 0.0
    return s.free_speed * s.stall_torque * (I - i_f) * (i_s - I) / (s.voltage * I * (i_s - i_f) ** 2)


def efficiency_within_limit(s, stator_limit: float | None) -> float:
    """(C6) at min(I_st, √(ĩf·ĩs)): the best efficiency with the stator current at most the limit."""
    best = math.sqrt(s.free_current * s.stall_current)  # (91)
    return line_efficiency(best if stator_limit is None else min(stator_limit, best), s)


def mass_of(name: str) -> float | None:
    """The motor's mass from whichever source gives one (a mass is the motor's, not its data's)."""
    return next((m.mass for m in MOTORS if m.name == name and m.mass is not None), None)


def limited_system(v, name: str, count: int = 1, efficiency: float = 1.0):
    """`count` motors `name` at v's voltage and limits: the system (C1), the motor tab's limited curve
    ω -> (τ, u, I) (L1) at the gearbox output (η included), its zero-torque speed and τ at rest (C5)."""
    motor, _ = lookup(name, v["source"])
    s = system(motor, count, v["voltage"], efficiency)
    point, _, _, w_zero = limited_curve({**v, "motor": name, "motor_count": count}, s)
    return s, point, w_zero, point(0.0)[0]


def row_of(v, name: str):
    """One motor's row (C1)-(C7), its system, its limited curve and its reduction G."""
    geared = v["gearing"] == "same_speed"
    eta = v["efficiency"] if geared else 1.0
    s, point, w_zero, tau_lim = limited_system(v, name, 1, eta)  # (C1), (C5)
    motor = s.motor
    G = s.free_speed / v["output_speed"] if geared else 1.0  # (C7)
    stator = v["stator_current_limit"] if "stator_limit" in v["effects"] else None
    row = {
        "motor": name,
        "data": SOURCE_NAMES.get(motor.source, motor.source),
        "free_speed": s.free_speed / G,
        "stall_torque": s.stall_torque * G,
        "stall_current": s.stall_current,
        "peak_power": s.peak_power,  # (C3)
        "limited_torque": max(tau_lim, 0.0) * G,
        "efficiency": eta * efficiency_within_limit(system(motor, 1, v["voltage"], 1.0), stator),  # (C6)
        "kt": motor.stall_torque / (motor.stall_current - motor.free_current),  # (C2)
    }
    if geared:
        row["ratio"] = G
    mass = mass_of(name)
    if mass is not None:
        row["mass"] = mass
        row["power_density"] = s.peak_power / mass  # (C4)
    return row, s, point, w_zero, G, tau_lim


def sort_rows(rows: list[dict], key: str) -> list[dict]:
    """Rows in the chosen order; a row without the figure goes last (in name order)."""
    have = [r for r in rows if key in r]
    missing = sorted((r for r in rows if key not in r), key=lambda r: r["motor"])
    if key == "name":
        return sorted(rows, key=lambda r: r["motor"].casefold())
    have.sort(key=lambda r: r[key], reverse=key not in ASCENDING)  # stable: ties keep the database order
    return have + missing


def curves(v, name: str) -> dict[str, tuple[list[float], list[float]]] | None:
    """(L1) over the output speed for one motor: torque, output power, stator current, efficiency."""
    _, s, point, w_zero, G, tau0 = row_of(v, name)
    if tau0 <= 0:
        return None
    Vb = v["voltage"]
    ws = [w_zero * k / 100 for k in range(101)]  # motor speeds, rest to zero torque
    pts = [point(w) for w in ws]
    out_w = [w / G for w in ws]
    torque = [p[0] * G for p in pts]
    eff_x, eff_y = [], []
    for w, t, (_, u, I) in zip(out_w, torque, pts):
        p_in = Vb * u * I
        if w > 0 and p_in > 0 and t >= 0:
            eff_x.append(w)
            eff_y.append(t * w / p_in)
    return {
        "torque": (out_w, torque),
        "power": (out_w, [t * w for t, w in zip(torque, out_w)]),
        "current": (out_w, [p[2] for p in pts]),
        "efficiency": (eff_x, eff_y),
    }


def compute(v) -> Result:
    names = motor_names()
    rows, warnings, no_torque, over_rated = [], [], [], []
    for name in names:
        row, s, *_ = row_of(v, name)
        rows.append(row)
        if row["limited_torque"] <= 0:
            no_torque.append(name)
        if v["voltage"] > 1.25 * s.motor.v_spec:
            over_rated.append(f"{name} ({s.motor.v_spec:.3g} V)")
    if no_torque:
        what = "stator_current_limit" if "stator_limit" in v["effects"] else "supply_current_limit"
        if len(no_torque) == len(names):
            raise InputError(what, "leaves every motor at or below its free current at rest: no torque")
        warnings.append(
            f"No torque at rest with these limits (at or below the free current): {', '.join(no_torque)}."
        )
    if over_rated:
        warnings.append(
            f"Specified below {v['voltage']:.3g} V, scaled beyond their rating (eqs. 1-4): "
            f"{', '.join(over_rated)}."
        )
    rows = sort_rows(rows, v["sort_by"])
    series, labels = {}, {}
    for k in range(CURVES):
        name = v[f"curve_motor_{k + 1}"]
        c = None if name == NONE else curves(v, name)
        if c is None:  # no motor in this slot, or one that gives no torque at these limits
            continue
        for what in CURVE_KINDS:
            key = f"{what} {k + 1}"
            series[key] = c[what]
            labels[key] = name  # the legend names the motor, not the slot
    return Result(
        {"first_motor": rows[0]["motor"], "motors_listed": len(rows)},
        warnings,
        series,
        {"motors": rows},
        labels,
    )


CALCULATOR = Calculator(
    id="motors",
    title="Motor comparison",
    summary="Every motor side by side at a voltage and current limits, on its own shaft or geared to one "
    "output speed: a sortable table and the curves of chosen motors.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="1 (eqs. 1-10, Appendix A), issue 31",
    plots=PLOTS,
    tables=TABLES,
)
