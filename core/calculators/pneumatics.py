"""Seed section 10 (Appendix F): air over a match, as a scene with effects.

State: storage pressure P (gauge, Pa). Between firings the slot "inflow" (core.sim.effects) gives
dP/dt; the compressor (if on) adds free air:
    d(P·V)/dt = P_atm · V̇_comp(P)  ⇒  dP/dt = P_atm · V̇_comp(P) / V        (N1) = (80) into (79), dt → 0
Each firing of a cylinder group removes the air of one extend and one retract stroke (81), at
t_k = start + k·period < T (N3):
    ΔP = −(A_push·P_push + A_pull·P_pull)·L·count / V                     (79), (81), gauge (seed)
The model choice `pressure_model` = absolute makes the bookkeeping isothermal in absolute pressure:
a stroke fills the chamber from empty to its absolute pressure, so it takes (P_cyl + P_atm)·A·L of
P·V; and an unregulated stroke shares the tank's air, P_abs ← P_abs·V/(V + A·L) (exact, not
linearised) (N2).
Effects (parts, core.sim.effects), each with its own fields:
- `compressor` (compressor_model): the term of "inflow"; off, the slot is None and the match is
  answered in closed form (firings only) with no integration.
- `pressure_switch` (switch_on, switch_off): a discrete state (motor on/off) through its event at
  the switch-off pressure and its check after each firing (on at or below switch_on). Without it the
  compressor runs all match and the 125 psi relief valve (the scene's own event) holds the top.
- `regulator`: cylinders get min(setting, storage pressure); without it they get storage pressure
  (a parameter of the firing map (81), no term).
Departures from the seed: the seed integrates with a 1 s explicit step (its own result is shown
beside ours with the difference); events (switch flips) are located to the solver's tolerance.
Compressor curves: the accurate run follows the vendor table (REFERENCE_DATA.md) through every
point with a shape-preserving monotone cubic (PCHIP, Fritsch-Carlson, as scipy's
PchipInterpolator), extended past 120 psi by its last piece to the 125 psi relief. The seed's
4th-degree least-squares fit strays from the table (up to 7.5 % at the table points themselves for
the AndyMark 1.1, 15 % between them, and bends up past 100 psi): it is kept for the seed's own
1 s comparison only. Both are clamped at zero flow.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from functools import cache

from ..constants import LBF, PSI
from ..declarations import Calculator, Output, Plot, Result
from ..errors import InputError
from ..fields import Field
from ..sim.effects import Effect, Effects, Part, Slot
from ..sim.integrate import Event, integrate
from ..sim.scene import SOLVE_NFEV, STATS_OUTPUTS, SimRun, accuracy_field, run_with_stats

P_ATM = 101325.0  # Pa
CFM = 0.028316846592 / 60  # m^3/s per ft^3/min
RELIEF = 125 * PSI  # FRC relief valve
SLACK = 1 + 1e-12  # field bounds: a value typed exactly at a bound parses a bit off it (unit factors)
GROUPS = 3
MIN_PERIOD = 0.1  # s; a valve cannot cycle faster, and it bounds the work of a match
# A stroke whose chamber gets under this fraction of its working pressure has under 1 % of its force:
# the tank is as good as empty. Without it "emptied" meant a storage at exactly 0 psi, which
# unregulated strokes (each shares the tank's air: P·V/(V + A·L)) approach but never reach: a tank
# at 0.0069 psi after 15 firings read "Tank emptied: no".
EMPTY_FRACTION = 0.01
MAX_FIRINGS = SOLVE_NFEV // 30  # with the compressor on: 2 runs × ≥ 15 evaluations per firing
ADVICE = (
    "match_length",
    "the match is too long for this accuracy and firing rate (every firing restarts "
    "the integration): try a shorter match, longer firing periods, or a coarser accuracy",
)

# Free-air flow (CFM) at 0, 20, ..., 120 psi (ReCalc compressor data, REFERENCE_DATA.md).
COMPRESSORS: dict[str, tuple[float, ...]] = {
    "VIAIR 90C 12 V": (0.880, 0.425, 0.302, 0.251, 0.237, 0.224, 0.210),
    "VIAIR 90C 13.8 V": (1.030, 0.670, 0.599, 0.530, 0.450, 0.390, 0.340),
    "VIAIR 250C-IG 13.8 V": (0.879, 0.771, 0.684, 0.597, 0.519, 0.451, 0.386),
    "Thomas 215 12 V": (0.972, 0.764, 0.594, 0.469, 0.379, 0.297, 0.219),
    "AndyMark 1.1 12 V": (1.100, 0.602, 0.502, 0.406, 0.331, 0.312, 0.300),
}
CURVE_PSI = (0, 20, 40, 60, 80, 100, 120)
PRESSURE_MODELS = ("gauge", "absolute")
SLOTS = (Slot("inflow", "sum", "dP/dt of the storage (Pa/s), of its gauge pressure P"),)


@cache
def flow_fit(name: str) -> tuple[float, ...]:
    """4th-degree fit of V̇(P): coefficients (highest first) in SI, m^3/s of free air vs Pa gauge."""
    import numpy as np

    coeffs = np.polyfit(np.array(CURVE_PSI) * PSI, np.array(COMPRESSORS[name]) * CFM, 4)
    return tuple(float(c) for c in coeffs)


@cache
def flow_curve(name: str) -> tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]:
    """PCHIP through the vendor points: (P_k in Pa, V̇_k in m^3/s, slopes dV̇/dP at P_k).

    Written out (Fritsch-Carlson with scipy's end rule; equal to PchipInterpolator to rounding,
    tests/test_hard_cases.py) because importing scipy.interpolate costs 0.3-0.75 s on a first solve.
    """
    x = [psi * PSI for psi in CURVE_PSI]
    y = [cfm * CFM for cfm in COMPRESSORS[name]]
    h = [b - a for a, b in zip(x, x[1:])]
    m = [(y[k + 1] - y[k]) / h[k] for k in range(len(h))]
    d = [0.0] * len(x)
    for k in range(1, len(x) - 1):
        if m[k - 1] * m[k] > 0:  # same sign: weighted harmonic mean of the two slopes
            w1, w2 = 2 * h[k] + h[k - 1], h[k] + 2 * h[k - 1]
            d[k] = (w1 + w2) / (w1 / m[k - 1] + w2 / m[k])

    def edge(h0, h1, m0, m1):  # three-point end slope, kept monotone
        e = ((2 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
        if math.copysign(1, e) != math.copysign(1, m0) or m0 == 0:
            return 0.0
        if math.copysign(1, m0) != math.copysign(1, m1) and abs(e) > 3 * abs(m0):
            return 3 * m0
        return e

    d[0] = edge(h[0], h[1], m[0], m[1])
    d[-1] = edge(h[-1], h[-2], m[-1], m[-2])
    return tuple(x), tuple(y), tuple(d)


def flow_through(curve, P: float) -> float:
    """V̇(P) on the PCHIP curve (cubic Hermite on P's interval; the end pieces extend), ≥ 0."""
    x, y, d = curve
    k = min(max(bisect_right(x, P) - 1, 0), len(x) - 2)
    h = x[k + 1] - x[k]
    t = (P - x[k]) / h
    q = (
        ((2 * t - 3) * t * t + 1) * y[k]
        + ((t - 2) * t + 1) * t * h * d[k]
        + (3 - 2 * t) * t * t * y[k + 1]
        + (t - 1) * t * t * h * d[k + 1]
    )
    return q if q > 0 else 0.0


def flow(coeffs, P: float) -> float:
    """The seed's 4th-degree fit at P (its 1 s comparison)."""
    q = 0.0
    for c in coeffs:
        q = q * P + c
    return q if q > 0 else 0.0


# --- the effects ---------------------------------------------------------------------------------


def _compressor(values, V: float) -> Part:
    """(N1): dP/dt = P_atm·V̇(P)/V on the vendor curve."""
    curve = flow_curve(values["compressor_model"])
    k = P_ATM / V
    return Part(terms={"inflow": lambda P: k * flow_through(curve, P)})


def _switch(values, V: float) -> Part:
    """On at or below switch_on, off at switch_off: its event stops the compressor's run."""
    on_at, off_at = values["switch_on"], values["switch_off"]
    if on_at >= off_at:
        raise InputError("switch_on", "must be below the switch-off pressure")
    return Part(
        events=(Event("switch_off", lambda t, y: y[0] - off_at, +1),),
        params={"switch_on": on_at, "top": off_at},
    )


EFFECTS = Effects(
    Effect(
        "compressor",
        "the compressor fills the storage (N1)",
        _compressor,
        default_on=True,
        fields=(
            Field(
                "compressor_model",
                "Compressor",
                choices=tuple(COMPRESSORS),
                default="VIAIR 90C 13.8 V",
                help="Compressor flow curve: vendor data, followed through every point (shape-"
                "preserving PCHIP); the seed's 1 s comparison uses its 4th-degree fit.",
            ),
        ),
    ),
    Effect(
        "pressure_switch",
        "stops the compressor at switch_off, restarts it at or below switch_on",
        _switch,
        default_on=True,
        fields=(
            Field(
                "switch_on",
                "Switch on at",
                "pressure",
                "psi",
                default=95,
                min=0,
                max=125 * SLACK,
                help="Pressure switch closes (compressor on) at or below this.",
            ),
            Field(
                "switch_off",
                "Switch off at",
                "pressure",
                "psi",
                default=120,
                min=0,
                max=125 * SLACK,
                help="Pressure switch opens (compressor off) at this.",
            ),
        ),
    ),
    Effect(
        "regulator",
        "cylinders get min(setting, storage pressure)",
        lambda values, V: Part(params={"regulated": True}),
        default_on=True,
    ),
)
_EFFECT_FIELDS = {f.name: f for f in EFFECTS.fields()}
# once an effect, now a model choice: a preset or --set naming it still means the choice (with a notice)
RETIRED = (("absolute_pressure", "pressure_model", "absolute"),)


def _group_fields(i: int):
    on = i == 1
    g = f"Cylinder group {i}: "
    return (
        Field(
            f"c{i}_count",
            f"Cyl {i}: count",
            integer=True,
            default=2 if on else 0,
            min=0,
            max=50,
            help=g + "number of identical cylinders firing together (0: group unused).",
        ),
        Field(
            f"c{i}_bore",
            f"Cyl {i}: bore",
            "length",
            "in",
            default=1.5,
            min=0,
            min_exclusive=True,
            max=19,
            help=g + "bore D.",
        ),
        Field(
            f"c{i}_rod",
            f"Cyl {i}: rod",
            "length",
            "in",
            default=0.4375,
            min=0,
            max=19,
            help=g + "rod diameter d (smaller than the bore).",
        ),
        Field(
            f"c{i}_stroke",
            f"Cyl {i}: stroke",
            "length",
            "in",
            default=6 if on else 4,
            min=0,
            min_exclusive=True,
            max=190,
            help=g + "stroke L.",
        ),
        Field(
            f"c{i}_push_pressure",
            f"Cyl {i}: push pressure",
            "pressure",
            "psi",
            default=60,
            min=0,
            max=200 * SLACK,
            help=g + "pressure on the extend stroke (its regulator setting).",
        ),
        Field(
            f"c{i}_pull_pressure",
            f"Cyl {i}: pull pressure",
            "pressure",
            "psi",
            default=60,
            min=0,
            max=200 * SLACK,
            help=g + "pressure on the retract stroke.",
        ),
        Field(
            f"c{i}_period",
            f"Cyl {i}: firing period",
            "time",
            "s",
            default=10 if on else 5,
            min=0,
            max=1000,
            help=g + "time between actuations (extend + retract); 0 fires once.",
        ),
        Field(
            f"c{i}_start",
            f"Cyl {i}: first firing",
            "time",
            "s",
            default=5 if on else 0,
            min=0,
            max=1000,
            help=g + "time of the first actuation.",
        ),
    )


FIELDS = (
    _EFFECT_FIELDS["compressor_model"],
    Field(
        "tank_volume",
        "Storage volume",
        "volume",
        "cc",
        default=1148,
        min=1 / SLACK,
        max=1e6 * SLACK,
        help="Total storage: tanks plus tubing (two Clippard tanks: 1148 cc).",
    ),
    Field(
        "start_pressure",
        "Start pressure",
        "pressure",
        "psi",
        default=120,
        min=0,
        max=125 * SLACK,
        help="Storage pressure (gauge) when the match starts.",
    ),
    _EFFECT_FIELDS["switch_on"],
    _EFFECT_FIELDS["switch_off"],
    Field(
        "match_length",
        "Match length",
        "time",
        "s",
        default=150,
        min=0,
        min_exclusive=True,
        max=3600,
        help="Simulated time.",
    ),
    EFFECTS.field(
        "compressor, pressure_switch, regulator. (Absolute P·V bookkeeping, once the effect "
        "absolute_pressure, is the choice pressure_model = absolute.)",
        retired=RETIRED,
    ),
    Field(
        "pressure_model",
        "Air bookkeeping",
        choices=PRESSURE_MODELS,
        default="gauge",
        choice_labels=("Gauge P·V (the seed's)", "Absolute P·V, isothermal"),
        help="How a stroke's air leaves the storage: gauge, as the seed's (79), (81); or absolute, "
        "isothermal (a stroke fills its chamber from empty to its absolute pressure; an "
        "unregulated one shares the tank's air) (N2).",
    ),
    accuracy_field(),
) + tuple(f for i in range(1, GROUPS + 1) for f in _group_fields(i))

_MATCH = "(79)-(81)"
OUTPUTS = (
    Output(
        "min_pressure",
        "Minimum pressure",
        "pressure",
        "psi",
        equation=_MATCH,
        help="Lowest storage pressure (gauge): (N1) integrated between firings, (81) at each firing.",
    ),
    Output(
        "min_pressure_time",
        "…at time",
        "time",
        "s",
        equation=_MATCH,
        help="When the storage pressure is lowest (the first time, if it is reached twice).",
    ),
    Output(
        "final_pressure",
        "Final pressure",
        "pressure",
        "psi",
        equation=_MATCH,
        help="Storage pressure (gauge) at the end of the match, as the minimum.",
    ),
    Output(
        "compressor_duty",
        "Compressor duty",
        "dimensionless",
        "%",
        equation="(80)",
        help="Fraction of the match the compressor runs (switch closed, or all match without a switch).",
    ),
    Output(
        "firings",
        "Actuations",
        equation="(N3)",
        help="Firings of all groups in the match: start + k·period before its end.",
    ),
    Output(
        "tank_empty",
        "Tank emptied",
        equation="(81)",
        help="Whether a stroke got under 1 % of its working pressure (1 % of its force): storage near 0 psig.",
    ),
    *[
        o
        for i in range(1, GROUPS + 1)
        for o in (
            Output(
                f"push_force_{i}",
                f"Cyl {i}: push force",
                "force",
                "lbf",
                equation="(82)",
                help="π·D²/4 × the lowest pressure an extend stroke got: its push pressure or less (N4).",
            ),
            Output(
                f"pull_force_{i}",
                f"Cyl {i}: pull force",
                "force",
                "lbf",
                equation="(83)",
                help="π·(D² − d²)/4 × the lowest pressure a retract stroke got: its pull pressure or less (N4).",
            ),
        )
    ],
    Output(
        "seed_min_pressure",
        "Spreadsheet (1 s steps): minimum",
        "pressure",
        "psi",
        equation=_MATCH,
        help="The seed's own scheme: explicit 1 s steps of (79)-(81) on its 4th-degree fit of the curve.",
    ),
    Output(
        "seed_final_pressure",
        "Spreadsheet (1 s steps): final",
        "pressure",
        "psi",
        equation=_MATCH,
        help="The seed's own scheme at the end of the match.",
    ),
    Output(
        "seed_difference",
        "Spreadsheet minus accurate (final)",
        "pressure",
        "psi",
        equation=_MATCH,
        help="Spreadsheet's final pressure minus the accurate one.",
    ),
    *STATS_OUTPUTS,
)


def groups(v) -> list[dict]:
    out = []
    for i in range(1, GROUPS + 1):
        if v[f"c{i}_count"] == 0:
            continue
        D, d = v[f"c{i}_bore"], v[f"c{i}_rod"]
        if d >= D:
            raise InputError(f"c{i}_rod", "must be smaller than the bore")
        out.append(
            {
                "index": i,
                "count": v[f"c{i}_count"],
                "stroke": v[f"c{i}_stroke"],
                "A_push": math.pi * D**2 / 4,
                "A_pull": math.pi * (D**2 - d**2) / 4,
                "P_push": v[f"c{i}_push_pressure"],
                "P_pull": v[f"c{i}_pull_pressure"],
                "period": v[f"c{i}_period"],
                "start": v[f"c{i}_start"],
            }
        )
        if 0 < v[f"c{i}_period"] < MIN_PERIOD:
            raise InputError(f"c{i}_period", f"must be 0 (fire once) or at least {MIN_PERIOD} s")
    return out


def firing_times(gs: list[dict], T: float) -> list[tuple[float, dict]]:
    times = []
    for g in gs:
        k = 0
        t = g["start"]
        while t < T * (1 - 1e-12):  # start + k·period, not a running sum: no drift over many firings
            times.append((t, g))
            if g["period"] <= 0:
                break
            k += 1
            t = g["start"] + k * g["period"]
    times.sort(key=lambda x: x[0])
    return times


def fire(P: float, g: dict, V: float, regulator: bool, absolute: bool, chambers: list | None = None) -> float:
    """Storage pressure (gauge) after one actuation of group g: extend, then retract; (81), or (N2)
    when `absolute`. `chambers`, if given, gets (storage pressure before the stroke, the gauge pressure
    the stroke's chamber ends at) for the push then the pull stroke: the force of a stroke is its
    area times the latter, (82)/(83); it is the regulator's setting, or the storage pressure when
    that is lower or there is no regulator ((N2) in the absolute model)                        (N4)"""
    for A, setting in ((g["A_push"], g["P_push"]), (g["A_pull"], g["P_pull"])):
        Vc = A * g["stroke"] * g["count"]
        regulated = regulator and setting < P
        P_before = P
        if not absolute:
            P_cyl = setting if regulated else P
            P = P - P_cyl * Vc / V  # (81) into (79), gauge as in the seed
        else:
            P_abs = P + P_ATM
            if regulated and P_abs - (setting + P_ATM) * Vc / V >= setting + P_ATM:
                P_abs -= (setting + P_ATM) * Vc / V
                P_cyl = setting
            else:  # no regulator, or it opens fully: the chamber shares the tank's air
                P_abs = P_abs * V / (V + Vc)
                P_cyl = P_abs - P_ATM  # (N2): the chamber ends at the shared pressure
            P = P_abs - P_ATM
        P = max(P, 0.0)  # a tank cannot go below atmospheric: the stroke is incomplete
        if chambers is not None:
            chambers.append((P_before, max(P_cyl, 0.0)))
    return P


def short_of_pressure(gs: list[dict], lows: dict[int, list]) -> list[str]:
    """A warning per group that fired with a chamber below the push or pull pressure entered (N4):
    the first such stroke, its time and the storage pressure then, and the lowest push and pull
    forces over the match, at the chamber pressures actually reached ((82), (83) at them)."""
    out = []
    for g in gs:
        low = lows.get(g["index"])
        if low is None or low[2] is None:
            continue
        t, stroke, P_storage, P_cyl, setting = low[2]
        push, pull = g["A_push"] * low[0] / LBF, g["A_pull"] * low[1] / LBF
        out.append(
            f"Cylinder group {g['index']} is short of air from t = {t:.4g} s: its {stroke} stroke there "
            f"ends at {P_cyl / PSI:.4g} psi, below its {setting / PSI:.4g} psi working pressure (storage "
            f"{P_storage / PSI:.4g} psi before the stroke). At the pressures available its lowest "
            f"forces in the match are {push:.4g} lbf push and {pull:.4g} lbf pull (the forces shown); at "
            f"the pressures entered they would be {g['A_push'] * g['P_push'] / LBF:.4g} and "
            f"{g['A_pull'] * g['P_pull'] / LBF:.4g} lbf."
        )
    return out


def assemble(v):
    """The effects that are on, composed once for this solve (ctx: the storage volume)."""
    return EFFECTS.assemble(v["effects"], v, v["tank_volume"], SLOTS, ("pressure",))


def simulate(v, rtol: float) -> SimRun:
    V, T = v["tank_volume"], v["match_length"]
    gs = groups(v)
    asm = assemble(v)
    inflow = asm.slots["inflow"]
    has_comp = inflow is not None
    switch = "pressure_switch" in asm.on
    regulator, absolute = "regulator" in asm.on, v["pressure_model"] == "absolute"
    if has_comp:
        rhs = lambda t, y: [inflow(y[0])]  # noqa: E731  (N1)
    top = asm.params.get("top", RELIEF)
    # the switch's event stops the motor below the relief valve; without it the valve holds the top
    stop = list(asm.events) or [Event("relief", lambda t, y: y[0] - RELIEF, +1)]
    P = v["start_pressure"]
    on = has_comp and (P < top or not switch)  # with no switch the motor runs from the start
    t = 0.0
    ts, Ps = [0.0], [P]
    run_time = 0.0
    nfev = 0
    h = None
    empty = False
    warnings = []
    lows: dict[int, list] = {}  # group -> [lowest push chamber, lowest pull chamber, first short firing]
    schedule = firing_times(gs, T) + [(T, None)]
    if has_comp and len(schedule) > MAX_FIRINGS:
        # each firing restarts the integration (at least one step, ~15 evaluations charged to the
        # solve's budget, twice with the error estimate): past this the budget cannot hold; say so now
        raise InputError(
            "match_length",
            f"{len(schedule) - 1} firings in the match, more than the {MAX_FIRINGS} "
            f"one solve integrates (each restarts the integration): try a shorter "
            f"match or longer firing periods",
        )
    for tf, g in schedule:
        if on and tf > t and P >= top:  # no switch, at the relief pressure: the valve vents the flow
            run_time += tf - t
            ts.append(tf)
            Ps.append(P)
        elif on and tf > t:
            run = integrate(rhs, t, tf, [P], rtol=rtol, atol=rtol * PSI, events=stop, first_step=h)
            nfev += run.nfev
            h = (run.t[-1] - run.t[-2]) if len(run.t) > 1 else None
            ts.extend(run.t[1:])
            Ps.extend(y[0] for y in run.y[1:])
            P = run.y[-1][0]
            if run.event is not None:  # the switch opened, or the relief valve
                run_time += run.t[-1] - t
                P = top
                on = not switch  # without a switch the relief valve holds the top, motor still runs
                if not switch:
                    run_time += tf - run.t[-1]
                ts.append(tf)
                Ps.append(P)
            else:
                run_time += tf - t
        elif tf > t:
            if on:
                run_time += tf - t
            ts.append(tf)
            Ps.append(P)
        t = tf
        if g is None:
            break
        P_before = P
        chambers: list[tuple[float, float]] = []
        P = fire(P, g, V, regulator, absolute, chambers)
        working = (g["P_push"], g["P_pull"])
        low = lows.setdefault(g["index"], [math.inf, math.inf, None])
        for k, ((P_storage, P_cyl), setting) in enumerate(zip(chambers, (g["P_push"], g["P_pull"]))):
            low[k] = min(low[k], P_cyl)
            if low[2] is None and P_cyl < setting:  # (N4): the first stroke short of its pressure
                low[2] = (tf, ("push", "pull")[k], P_storage, P_cyl, setting)
        if not empty and (P == 0.0 or any(c < EMPTY_FRACTION * w for (_, c), w in zip(chambers, working))):
            empty = True
            warnings.append(
                f"The tank empties at t = {tf:.3g} s: from then a stroke gets under "
                f"{EMPTY_FRACTION * 100:g} % of its working pressure (storage {P / PSI:.3g} psi), too little "
                f"to move a load."
            )
        ts.append(tf)
        Ps.append(P)
        if has_comp and (not switch or P <= asm.params["switch_on"]) and P < top:
            on = True
        elif has_comp and not switch and P_before >= top > P:
            on = True
    i_min = min(range(len(Ps)), key=Ps.__getitem__)
    values = {
        "min_pressure": Ps[i_min],
        "min_pressure_time": ts[i_min],
        "final_pressure": P,
        "compressor_duty": run_time / T,
        "firings": len(schedule) - 1,
        "tank_empty": empty,
    }
    for g in gs:  # (82), (83) at the lowest chamber pressure of the match (N4); unfired: as entered
        low = lows.get(g["index"], [g["P_push"], g["P_pull"]])
        values[f"push_force_{g['index']}"] = g["A_push"] * low[0]
        values[f"pull_force_{g['index']}"] = g["A_pull"] * low[1]
    warnings += short_of_pressure(gs, lows)
    if not has_comp:
        warnings.append("No compressor: pressure only falls; answered in closed form (no integration).")
    if gs and not regulator:
        warnings.append(
            "No regulator: cylinders get storage pressure, so the air used follows the tank; "
            "the forces shown are at the lowest pressure a stroke got."
        )
    return SimRun(
        values,
        {"min_pressure": Ps[i_min] + P_ATM, "final_pressure": P + P_ATM},
        nfev,
        warnings,
        {"pressure": (ts, Ps)},
    )


def seed_step(v) -> tuple[float, float, tuple[list[float], list[float]]]:
    """The seed's own scheme: explicit 1 s steps of (79)-(81), the same effects, gauge pressure."""
    effects = v["effects"]
    V, T = v["tank_volume"], v["match_length"]
    gs = groups(v)
    coeffs = flow_fit(v["compressor_model"])
    regulator = "regulator" in effects
    switch = "pressure_switch" in effects
    top = v["switch_off"] if switch else RELIEF
    P = v["start_pressure"]
    on = "compressor" in effects and P < top
    schedule = firing_times(gs, T)
    low = P
    ts, Ps = [0.0], [P]
    k = 0  # next firing in the (sorted) schedule: one pass, not a scan of it per step
    for n in range(int(math.ceil(T))):
        W_comp = flow(coeffs, P) * 1.0 * P_ATM if on else 0.0  # (80), dt = 1 s
        P = min(P + W_comp / V, top) if on else P  # (79)
        while k < len(schedule) and schedule[k][0] < n + 1:  # firings in [n, n + 1)
            P = fire(P, schedule[k][1], V, regulator, False)  # (81): the seed is gauge only
            k += 1
        low = min(low, P)
        ts.append(float(n + 1))
        Ps.append(P)
        if "compressor" in effects:
            on = (P < top) if not switch else ((on and P < top) or P <= v["switch_on"])
    return low, P, (ts, Ps)


def compute(v, estimate: str = "now") -> Result:
    run = run_with_stats(simulate, v, ADVICE, estimate)  # a retired effect is read before (effects.retire)
    seed_min, seed_final, seed_trace = seed_step(v)
    run.series["spreadsheet, 1 s"] = seed_trace
    run.values["seed_min_pressure"] = seed_min
    run.values["seed_final_pressure"] = seed_final
    run.values["seed_difference"] = seed_final - run.values["final_pressure"]
    return Result(run.values, run.warnings, run.series)


CALCULATOR = Calculator(
    id="pneumatics",
    title="Pneumatics",
    summary="Storage pressure over a match: compressor, pressure switch, regulator, cylinders.",
    fields=FIELDS,
    outputs=OUTPUTS,
    compute=compute,
    section="10",
    simulate=simulate,
    plots=(
        Plot(
            "Storage pressure",
            ("pressure", "spreadsheet, 1 s"),
            "time",
            "time",
            "s",
            "pressure",
            "pressure",
            "psi",
        ),
    ),
)
