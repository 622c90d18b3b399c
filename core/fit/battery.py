"""The battery plus wiring resistance from the log's bus voltage and motor current (issue 44 item 4),
when the log has both (SysIdRoutineLog writes current-<motor>-<mech>; the bus voltage comes from
AdvantageKit's SystemStats/BatteryVoltage or --bus-voltage):
    I_batt = N·I·u/V_b   each of the card's N motors draws the logged motor's supply current, its
                         stator current I times the duty u/V_b (u the applied voltage)
    V_b = E − R·I_batt   ordinary least squares (numpy lstsq) over the four tests' current samples,
                         R's standard deviation from the fit's covariance                         (B1)
Gearhead's battery_sag effect uses the same law (bus = battery − R × total supply current)."""

from __future__ import annotations

import math

import numpy as np

from .signals import Picked
from .sysid_fit import _lerp, ols

MIN_SPREAD = 1.0  # A: a current that never varies more than this cannot separate R from E


def fit_battery(picked: Picked, count: int) -> tuple[float, float, float, int] | str:
    """(R, σ_R, E, samples) of (B1), or why it cannot be fitted."""
    if picked.current is None or picked.bus is None:
        return "the log has no motor current and bus voltage together"
    tc, ic = picked.current
    tb, vb = picked.bus
    if len(tb) < 2:
        return "the bus voltage has fewer than 2 samples"
    rows_i, rows_v = [], []
    for run in picked.runs.values():
        t0, t1 = run.t_voltage[0], run.t_voltage[-1]
        sel = (tc >= t0) & (tc <= t1)
        if not np.any(sel):
            continue
        t = tc[sel]
        k = np.clip(np.searchsorted(run.t_voltage, t, "right") - 1, 0, len(run.voltage) - 1)
        u = run.voltage[k]  # the voltage held since its last sample
        v_bus = _lerp(t, tb, vb)
        ok = v_bus > 0
        rows_i.append(count * ic[sel][ok] * u[ok] / v_bus[ok])
        rows_v.append(v_bus[ok])
    if not rows_i:
        return "no current sample falls inside the tests"
    i_batt, v_bus = np.concatenate(rows_i), np.concatenate(rows_v)
    if len(i_batt) < 3 or float(np.ptp(i_batt)) < MIN_SPREAD:
        return f"the battery current varies less than {MIN_SPREAD:g} A over the tests"
    with np.errstate(all="ignore"):
        c, cov, _, _ = ols(np.column_stack([np.ones(len(i_batt)), -i_batt]), v_bus)
    R, E, s = float(c[1]), float(c[0]), float(math.sqrt(cov[1, 1])) if cov[1, 1] >= 0 else math.nan
    if not (math.isfinite(R) and math.isfinite(E)):
        return "the regression of bus voltage on current gives no finite resistance"
    if R <= 0:  # a battery's voltage falls as it is drawn on: the signals are not what they were named
        return (
            f"the regression of bus voltage on current gives R = {R:.3g} Ω (≤ 0: the bus voltage does "
            "not fall as the current rises; are these the motor current and the bus voltage?)"
        )
    return R, s, E, len(i_batt)
