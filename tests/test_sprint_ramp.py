"""The sprint's voltage ramp (core/calculators/sprint.py (S14)): the duty may rise from 0 to full over
T_r, so the robot waits at rest until the motors beat their own loss, then accelerates under a
ceiling that rises with time; the wheels may start slipping part-way up the ramp.

Oracles written here from the motor data, not from the code (per motor R = 12/I_s, Kv = ω_f/(12 − R·I_f),
Kt = τ_s/(I_s − I_f); F_m = η·N·Kt·n·(I − I_f), I = (u·V − n·v/Kv)/R, u = min(1, t/T_r, stator bound)):
mpmath's Taylor integrator where the motion is smooth in pieces with known ends, scipy's DOP853 at
1e-13 on the plain piecewise model elsewhere."""

import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from gearhead.core.model import solve

G0 = 9.80665
RPM = 2 * math.pi / 60
LB, INCH = 0.45359237, 0.0254
TS, IS, IF, WF = 7.09, 366.0, 2.0, 6000 * RPM  # Kraken X60, as tests/test_sprint.py
R = 12 / IS
KV, KT = WF / (12 - R * IF), TS / (IS - IF)
M, ETA, N = 135 * LB, 0.9, 4


def sprint(**raw):
    return solve("sprint", {"accuracy": "tight", **raw}).outputs


def test_ramp_without_slip_against_mpmath():
    """High grip, no limits: at rest until t₀ = T_r·R·I_f/V (the motors' force beats their loss),
    then m·v̇ = fpa·((t/T_r·V − n·v/Kv)/R − I_f) to T_r and the full-voltage line after; the
    energy ∫ V·N·u·I dt counts the stalled current while at rest."""
    mp.mp.dps = 30
    T_r, G_, d = 0.3, 3.0, 5.0  # stall force 1.5 kN < μ·m·g = 1.8 kN: never slips
    n = mp.mpf(G_) / (2 * INCH)
    fpa = ETA * N * KT * n
    Rm, Kv = mp.mpf(12) / IS, mp.mpf(WF) / (12 - mp.mpf(12) / IS * IF)

    def rhs(t, y):  # y = (x, v, energy)
        u = min(mp.mpf(1), t / T_r)
        current = (u * 12 - n * y[1] / Kv) / Rm
        return [y[1], fpa * (current - IF) / M, 12 * N * u * current]

    t0 = mp.mpf(T_r) * Rm * IF / 12
    rest_energy = 12 * N * 12 / Rm * t0**3 / (3 * T_r**2)  # ∫ V·N·u·(u·V/R) dt, u = t/T_r, v = 0
    up = mp.odefun(rhs, t0, [0, 0, rest_energy])
    y_r = up(T_r)
    full = mp.odefun(rhs, T_r, y_r)
    T = mp.findroot(lambda t: full(t)[0] - d, 1.5)
    out = sprint(ratio=G_, distance=f"{d} m", wheel_cof=3, effects="voltage_ramp", ramp_time=f"{T_r} s")
    assert out["time_to_distance"].value == pytest.approx(float(T), rel=1e-10)
    assert out["speed_at_distance"].value == pytest.approx(float(full(T)[1]), rel=1e-9)
    assert out["energy"].value == pytest.approx(float(full(T)[2]), rel=1e-9)
    assert out["traction_time"].value == 0
    # at most the stall current at full duty on the ramp's end, reached at T_r: the current
    # (u·V − E)/R rises while the ramp lifts u faster than the back-EMF grows
    I_T_r = (12 - n * y_r[1] / Kv) / Rm
    assert out["peak_stator_current"].value == pytest.approx(float(I_T_r), rel=1e-9)


def oracle(T_r, mu, I_st=None, G_=6.75, d=5.0, crr=0.0):
    """DOP853 at 1e-13 on the piecewise model (min, max and the rest clamp written out)."""
    n = G_ / (2 * INCH)
    fpa = ETA * N * KT * n
    F_t, F_rr = mu * M * G0, crr * M * G0
    I_slip = F_t / fpa + IF

    def electrical(t, v):
        u = min(1.0, t / T_r) if T_r > 0 else 1.0
        E = n * v / KV
        if I_st is not None:
            u = min(u, (E + R * I_st) / 12)
        return u, (u * 12 - E) / R

    def rhs(t, y):
        u, current = electrical(t, y[1])
        F_m = fpa * (current - IF)
        if F_m > F_t:  # at the edge of slip the motors draw I_slip at the ramp's duty
            return [y[1], (F_t - F_rr) / M, 12 * N * min(1.0, t / T_r) * I_slip]
        a = (F_m - F_rr) / M
        if y[1] <= 0 and a < 0:
            a = 0.0
        return [y[1], a, 12 * N * u * current]

    def goal(t, y):
        return y[0] - d

    goal.terminal, goal.direction = True, 1
    # the ramp's end is a known break point; elsewhere the kinks (grip changes, the limit letting go,
    # leaving rest) are in the acceleration's slope only, which DOP853's error control resolves
    t, y, pieces = 0.0, [0.0, 0.0, 0.0], []
    for t_end in [T_r, 60.0] if T_r > 0 else [60.0]:
        sol = solve_ivp(
            rhs, (t, t_end), y, method="DOP853", rtol=1e-13, atol=1e-13, events=[goal], dense_output=True
        )
        pieces.append(sol)
        if sol.t_events[0].size:
            return sol.t_events[0][0], sol.y_events[0][0], pieces
        t, y = sol.t[-1], sol.y[:, -1]
    raise AssertionError("the oracle did not arrive")


@pytest.mark.parametrize(
    "T_r,mu,I_st",
    [(0.25, 1.1, None), (0.5, 0.8, None), (0.25, 1.1, 60.0), (1.0, 1.2, 80.0), (0.05, 1.1, None)],
)
def test_ramp_with_slip_and_stator_limit_against_dop853(T_r, mu, I_st):
    T, y, _ = oracle(T_r, mu, I_st)
    effects = "voltage_ramp" + (", stator_limit" if I_st else "")
    raw = {"wheel_cof": mu, "effects": effects, "ramp_time": f"{T_r} s"}
    if I_st:
        raw["stator_current_limit"] = I_st
    out = sprint(**raw)
    assert out["time_to_distance"].value == pytest.approx(T, rel=1e-9)  # measured ≤ 5.5e-11
    assert out["speed_at_distance"].value == pytest.approx(y[1], rel=1e-9)
    assert out["energy"].value == pytest.approx(y[2], rel=1e-9)  # measured ≤ 1.8e-10


def test_ramp_peaks_are_the_runs_maxima():
    """Peak stator and supply current against the oracle's dense solution sampled every 10 µs."""
    T_r, mu = 0.6, 1.3
    T, _, pieces = oracle(T_r, mu, None)
    n = 6.75 / (2 * INCH)
    fpa = ETA * N * KT * n
    I_slip = mu * M * G0 / fpa + IF
    stator, supply = 0.0, 0.0
    for sol in pieces:
        ts = np.arange(sol.t[0], min(sol.t[-1], T), 1e-5)
        for t in ts:
            v = sol.sol(t)[1]
            u = min(1.0, t / T_r)
            current = (u * 12 - n * v / KV) / R
            if fpa * (current - IF) > mu * M * G0:
                current = I_slip
            stator, supply = max(stator, current), max(supply, u * current)
    out = sprint(wheel_cof=mu, effects="voltage_ramp", ramp_time=f"{T_r} s")
    # sampled maxima are below the true ones by at most the curvature over 5 µs: ~1e-8 relative
    assert out["peak_stator_current"].value == pytest.approx(stator, rel=1e-6)
    assert out["peak_supply_current"].value == pytest.approx(supply, rel=1e-6)
    assert out["peak_stator_current"].value >= stator * (1 - 1e-9)


def test_a_vanishing_ramp_is_no_ramp():
    base = sprint(effects="stator_limit, battery_sag")
    ramped = sprint(effects="stator_limit, battery_sag, voltage_ramp", ramp_time="1e-7 s")
    for k in ("time_to_distance", "speed_at_distance", "peak_stator_current"):
        assert ramped[k].value == pytest.approx(base[k].value, rel=1e-6), k


def test_a_ramp_softens_the_start():
    """Slower to the distance, a lower peak current and a later, shorter slip than without it."""
    base = sprint(effects="")
    ramped = sprint(effects="voltage_ramp", ramp_time="0.4 s")
    assert ramped["time_to_distance"].value > base["time_to_distance"].value
    assert ramped["traction_time"].value < base["traction_time"].value
    slow = sprint(effects="voltage_ramp, stator_limit", ramp_time="1 s", stator_current_limit=120)
    assert (
        slow["peak_stator_current"].value
        < sprint(effects="stator_limit", stator_current_limit=120)["peak_stator_current"].value
    )


@pytest.mark.parametrize("effects", ["voltage_ramp", "voltage_ramp, stator_limit, supply_limit, battery_sag"])
def test_default_accuracy_holds_under_a_ramp(effects):
    """The runs stop where the ramp stops binding and integrate its smooth branch before that: the
    default accuracy (rtol 1e-6) stays within 1e-5 of the tight solve (straddled, the ramp's kink
    cost 1e-4 in energy)."""
    tight = sprint(effects=effects)
    loose = solve("sprint", {"effects": effects, "accuracy": "default"}).outputs
    for k in ("time_to_distance", "energy", "peak_supply_current"):
        assert loose[k].value == pytest.approx(tight[k].value, rel=1e-5), k


def test_optimise_under_a_ramp_finds_the_minimum():
    raw = {"mode": "optimise", "effects": "voltage_ramp, stator_limit, supply_limit, battery_sag"}
    out = solve("sprint", raw).outputs
    G_best, T_best = out["best_ratio"].value, out["time_to_distance"].value
    for k in (0.97, 1.03):
        other = solve("sprint", {**raw, "mode": "sprint", "ratio": G_best * k}).outputs
        assert other["time_to_distance"].value > T_best
