"""core/match/bus.py: the bus voltage from every supply current together (M6-M9), against sympy's
derivation, scipy's brentq (1e-12) and robotpy's BatterySim.calculate at constant open-circuit
voltage; the two-root case of constant-power loads and the branch followed in time."""

from __future__ import annotations

import ast
import pathlib
import random

import pytest
from scipy.optimize import brentq

from gearhead.core.match.bus import current, motor_terms, solve_bus

# Kraken X60-like motor: k_e = 12 V / 628 rad/s, R_m = 12 V / 366 A (WPILib's DCMotor figures)
K_E, R_M = 12.0 / 628.3, 12.0 / 366.0


def test_supply_current_is_affine_in_the_bus_voltage_sympy():
    """(M6): I_s = u·I_m with I_m = (u·V − k_e·ω)/R_m, from the bridge's power balance, is
    (u²/R_m)·V − u·k_e·ω/R_m; and (M7) solves V = V_oc − R·(a + b·V)."""
    sp = pytest.importorskip("sympy")
    u, V, w, ke, Rm, n, Voc, R, a, b = sp.symbols("u V omega k_e R_m n V_oc R a b", real=True)
    i_motor = (u * V - ke * w) / Rm
    i_supply = sp.solve(sp.Eq(V * sp.Symbol("I_s"), u * V * i_motor), sp.Symbol("I_s"))[0]
    A, B = (-n * u * ke * w / Rm, n * u**2 / Rm)
    assert sp.simplify(n * i_supply - (A + B * V)) == 0
    assert sp.diff(n * i_supply, V, 2) == 0  # affine
    got = motor_terms(0.7, 300.0, K_E, R_M, 4)
    assert got == pytest.approx(
        (float(A.subs({u: 0.7, w: 300.0, ke: K_E, Rm: R_M, n: 4})), 4 * 0.49 / R_M), rel=1e-15
    )
    v = sp.solve(sp.Eq(V, Voc - R * (a + b * V)), V)[0]
    assert sp.simplify(v - (Voc - R * a) / (1 + R * b)) == 0


def _residual(voc, r, a, b, p):
    return lambda v: v - (voc - r * (a + b * v + p / v))


@pytest.mark.parametrize("seed", range(20))
def test_closed_form_matches_brentq_to_1e_12(seed):
    rng = random.Random(seed)
    voc, r = rng.uniform(11.5, 13.0), rng.uniform(0.01, 0.04)
    loads = [
        motor_terms(rng.uniform(-1, 1), rng.uniform(0, 600), K_E, R_M, rng.randint(1, 4)) for _ in range(5)
    ]
    a = sum(x for x, _ in loads) + rng.uniform(0, 5)
    b = sum(y for _, y in loads)
    got = solve_bus(voc, r, a, b)
    f = _residual(voc, r, a, b, 0.0)
    hi = 1e6
    root = brentq(lambda v: v - (voc - r * (a + b * v)), -hi, hi, xtol=1e-15, rtol=1e-15)
    if root > 0:
        assert got.voltage == pytest.approx(root, rel=1e-12, abs=1e-12)
        assert abs(f(got.voltage)) < 1e-11
    else:
        assert got.collapsed and got.voltage == 0.0


@pytest.mark.parametrize("seed", range(10))
def test_closed_form_matches_robotpy_batterysim_at_constant_ocv(seed):
    """WPILib's BatterySim.calculate(V_nominal, R, currents) = V_nominal − R·ΣI: fed the currents
    our loads draw at our bus voltage, it gives that voltage back (the closed form is its fixed point)."""
    sim = pytest.importorskip("wpilib.simulation")
    rng = random.Random(100 + seed)
    voc, r = 12.5, rng.uniform(0.01, 0.03)
    loads = [motor_terms(rng.uniform(0, 1), rng.uniform(0, 300), K_E, R_M, 2) for _ in range(4)]
    base = rng.uniform(1, 5)
    v = solve_bus(voc, r, base + sum(x for x, _ in loads), sum(y for _, y in loads)).voltage
    currents = [base] + [x + y * v for x, y in loads]
    assert sim.BatterySim.calculate(voc, r, currents) == pytest.approx(v, rel=1e-12, abs=1e-12)
    # a constant current alone: the same formula as theirs
    assert solve_bus(voc, r, 123.0).voltage == pytest.approx(
        sim.BatterySim.calculate(voc, r, [123.0]), abs=1e-12
    )


def test_two_roots_match_brentq_in_their_brackets():
    """(M8): P > 0 with D > 0: the upper root in [V*, W/α], the lower in (0, V*], each to 1e-12."""
    voc, r, a, b, p = 12.6, 0.02, 20.0, 5.0, 1500.0
    w, alpha = voc - r * a, 1 + r * b
    vstar = w / (2 * alpha)
    got = solve_bus(voc, r, a, b, p)
    assert got.lower is not None and not got.collapsed
    f = _residual(voc, r, a, b, p)
    up = brentq(f, vstar, w / alpha, xtol=1e-15, rtol=1e-15)
    lo = brentq(f, 1e-9, vstar, xtol=1e-15, rtol=1e-15)
    assert got.upper == pytest.approx(up, rel=1e-12)
    assert got.lower == pytest.approx(lo, rel=1e-12)
    assert got.voltage == got.upper  # no previous voltage: the upper branch
    # both are operating points: the current they make gives them back
    for v in (got.upper, got.lower):
        assert voc - r * current(v, a, b, p) == pytest.approx(v, rel=1e-12)


def test_branch_followed_is_continuous_in_time():
    """(M9): on the lower branch, a slowly varying P keeps the bus on the lower root (a jump to the
    upper one would be ~9 V); taking the upper root regardless would not be continuous."""
    voc, r = 12.6, 0.02
    ps = [1500.0 + 300.0 * k / 200 for k in range(201)] + [1800.0 - 300.0 * k / 200 for k in range(201)]
    v = solve_bus(voc, r, 0.0, 0.0, ps[0]).lower
    trace = [v]
    for p in ps[1:]:
        pt = solve_bus(voc, r, 0.0, 0.0, p, previous=v)
        v = pt.voltage
        assert v == pt.lower
        trace.append(v)
    jumps = max(abs(x - y) for x, y in zip(trace, trace[1:]))
    assert jumps < 0.02
    assert trace[-1] == pytest.approx(trace[0], rel=1e-12)  # back where it began, same branch
    # starting from the upper root, the same sweep stays upper
    v = solve_bus(voc, r, 0.0, 0.0, ps[0]).voltage
    for p in ps[1:]:
        pt = solve_bus(voc, r, 0.0, 0.0, p, previous=v)
        assert pt.voltage == pt.upper
        v = pt.voltage


def test_collapse_when_the_loads_ask_more_than_the_battery_gives():
    """D < 0: more than W²/(4αR) asked: collapsed, at the vertex V* = W/(2α)."""
    voc, r = 12.0, 0.02
    pmax = voc * voc / (4 * r)  # 1800 W
    ok = solve_bus(voc, r, 0.0, 0.0, pmax * 0.999)
    assert not ok.collapsed
    bad = solve_bus(voc, r, 0.0, 0.0, pmax * 1.001)
    assert bad.collapsed and bad.voltage == pytest.approx(6.0, rel=1e-15)
    assert solve_bus(voc, r, 700.0).collapsed  # a current past V_oc/R: no positive bus voltage
    regen = solve_bus(voc, r, 0.0, 0.0, -500.0)  # a regenerating P < 0: the positive root
    assert not regen.collapsed and regen.voltage > voc


def test_core_match_imports_only_errors_units_numpy_scipy():
    """The package's layer: core.errors, core.units, its own modules, numpy, scipy, the standard
    library's math and typing helpers; never the UI."""
    allowed = ("gearhead.core.errors", "gearhead.core.units", "gearhead.core.match", "numpy", "scipy")
    # mechanisms.py puts the cards' scenes on the bus: their equations (core.sim), their inputs and
    # their motors' data (core.motors)
    scenes = (
        "gearhead.core.sim",
        "gearhead.core.calculators",
        "gearhead.core.motors",
        "gearhead.core.model",
        "gearhead.core.registry",
    )
    stdlib = {"__future__", "math", "dataclasses", "collections", "numbers", "typing"}
    root = pathlib.Path(__file__).resolve().parents[1] / "core" / "match"
    for path in root.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""]
            for name in names:
                ok = name.split(".")[0] in stdlib or any(
                    name == x or name.startswith(x + ".")
                    for x in allowed + (scenes if path.name == "mechanisms.py" else ())
                )
                assert ok, f"{path.name} imports {name}"


def test_timeline_follows_the_branch_nearest_the_last_bus_voltage():
    """Flat 12.5 V, 0.02 Ω. 1900 W of constant power (at most 1953 W): roots (12.5 ± √4.25)/2 =
    7.2808 V and 5.2192 V. After a 400 A piece (bus 4.5 V) the 1900 W piece starts on the lower root
    (nearest 4.5 V) and stays there; alone from the start it sits on the upper root."""
    from gearhead.core.match.battery import Battery
    from gearhead.core.match.brownout import Controller
    from gearhead.core.match.timeline import Load, Match, constant_current, constant_power

    flat = Battery(ocv_table=((0.5, 12.5),), resistance=0.02)
    low = Controller(brownout=1.0, recovery=2.0)  # keep the outputs on: only the branch matters here
    upper, lower = (12.5 + 4.25**0.5) / 2, (12.5 - 4.25**0.5) / 2
    power = Load("p", constant_power(1900.0), 1.0, 2.0, brownout_disables=False)
    amps = Load("i", constant_current(400.0), 0.0, 1.0, brownout_disables=False)
    r = Match(battery=flat, controller=low, length=2.0, loads=(amps, power), trace_step=0.1).run()
    during = [v for t, v in zip(r.times, r.volts) if 1.0 < t < 2.0]
    assert during and all(v == pytest.approx(lower, rel=1e-12) for v in during)
    assert r.min_voltage == pytest.approx(4.5, rel=1e-12)
    alone = Match(battery=flat, controller=low, length=2.0, loads=(power,), trace_step=0.1).run()
    during = [v for t, v in zip(alone.times, alone.volts) if 1.0 < t < 2.0]
    assert during and all(v == pytest.approx(upper, rel=1e-12) for v in during)
