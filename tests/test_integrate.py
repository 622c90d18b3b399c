"""The integrator: DP54's convergence with tolerance, event location, agreement with scipy, bounded
work; every method behind the one interface, charged to the budget."""

import math

import pytest

from gearhead.core.sim.integrate import Event, integrate

oscillator = lambda t, y: [y[1], -y[0]]  # noqa: E731


@pytest.mark.parametrize("rtol", [1e-4, 1e-6, 1e-8, 1e-10])
def test_error_tracks_tolerance(rtol):
    run = integrate(oscillator, 0.0, 10.0, [1.0, 0.0], rtol=rtol, atol=rtol * 1e-2)
    err = math.hypot(run.y[-1][0] - math.cos(10), run.y[-1][1] + math.sin(10))
    assert err < 50 * rtol


def test_work_grows_at_fifth_order_rate():
    # a 5th-order method needs (tol ratio)^(1/5) more steps: 1e5 tighter -> about 10x the steps
    coarse = integrate(oscillator, 0.0, 20.0, [1.0, 0.0], rtol=1e-5, atol=1e-7)
    fine = integrate(oscillator, 0.0, 20.0, [1.0, 0.0], rtol=1e-10, atol=1e-12)
    ratio = fine.steps / coarse.steps
    assert 6 < ratio < 16, ratio


def test_results_at_tol_and_tol_over_100_agree():
    a = integrate(oscillator, 0.0, 10.0, [1.0, 0.0], rtol=1e-8, atol=1e-10).y[-1]
    b = integrate(oscillator, 0.0, 10.0, [1.0, 0.0], rtol=1e-10, atol=1e-12).y[-1]
    assert abs(a[0] - b[0]) < 1e-7


def test_event_located_to_tolerance_not_to_a_step():
    ev = Event("down", lambda t, y: y[0], direction=-1)
    run = integrate(oscillator, 0.0, 10.0, [1.0, 0.0], rtol=1e-11, atol=1e-13, events=[ev])
    assert run.event == "down"
    assert run.t[-1] == pytest.approx(math.pi / 2, abs=1e-10)
    assert run.t[-2] < run.t[-1]  # the event sits inside a step, not on a step boundary


def test_dp54_agrees_with_scipy_dop853():
    f = lambda t, y: [y[1], -math.sin(y[0]) - 0.1 * y[1]]  # noqa: E731 damped pendulum
    ours = integrate(f, 0.0, 15.0, [2.5, 0.0], rtol=1e-11, atol=1e-13).y[-1]
    from scipy.integrate import solve_ivp

    ref = solve_ivp(f, (0.0, 15.0), [2.5, 0.0], method="DOP853", rtol=1e-13, atol=1e-15).y[:, -1]
    assert ours == pytest.approx(ref, abs=1e-9)


def test_blow_up_ends_with_an_error_not_an_endless_loop():
    with pytest.raises(RuntimeError):
        integrate(lambda t, y: [y[0] ** 2], 0.0, 2.0, [1.0], rtol=1e-8, atol=1e-10, max_steps=20000)


def test_dense_output_is_fourth_order_accurate():
    run = integrate(oscillator, 0.0, 10.0, [1.0, 0.0], rtol=1e-10, atol=1e-12, dense=True)
    for t in [0.123, 3.3, 7.77, 9.99]:
        assert run.at(t)[0] == pytest.approx(math.cos(t), abs=1e-8)


def test_tiny_first_step_far_from_zero_is_not_an_underflow():
    """A segment that starts with the tiny last step of the previous one (1e-16 s at t = 100 s) must
    grow its step, not stop with "step size underflow": 1e-16 < 1e-14·100 is accepted, not rejected."""
    run = integrate(
        oscillator, 100.0, 110.0, [math.cos(100), -math.sin(100)], rtol=1e-8, atol=1e-10, first_step=1e-16
    )
    assert abs(run.y[-1][0] - math.cos(110)) < 1e-6


def test_locate_when_interpolant_rounds_to_the_other_side_at_the_step_end():
    """g_new is a tiny positive number but the dense output at θ = 1 gives g < 0 (rounding): the
    root bracket [0, 1] has no sign change and brentq would raise; the crossing is at the step end."""
    from gearhead.core.sim.integrate import _locate

    rc = ([0.0], [1.0], [0.0], [0.0], [0.0])  # y(θ) = θ, so g(θ = 1) = 0 while g_new > 0
    ev = Event("x", lambda t, y: y[0] - 1.0 - 1e-300, +1)  # -1e-300 rounds away: g(θ = 1) = 0, not > 0
    assert _locate(ev, rc, 0.0, 0.5, -1.0, 1e-300) == 0.5


def test_huge_trial_step_error_is_a_rejection_not_an_overflow():
    """A wild trial step (seen in a projectile flight from 1000 m with drag and Magnus) gives an
    error ratio ~1e200: `r ** 2` raised OverflowError; the norm must be inf (and the step rejected)."""
    from gearhead.core.sim.integrate import _norm

    assert _norm([1e200, 0.0], [1.0, 1.0], [1.0, 1.0], 1e-6, 1e-9) == math.inf


def test_zero_first_step_falls_back_to_the_heuristic():
    """pneumatics hands on the last step of a segment as first_step; an event located at a step's
    start makes it 0, which used to spin 100 000 zero-length steps and raise."""
    run = integrate(oscillator, 0.0, 10.0, [1.0, 0.0], rtol=1e-8, atol=1e-10, first_step=0.0)
    assert abs(run.y[-1][0] - math.cos(10)) < 1e-6 and run.steps < 1000


# ---- one interface: every method behind integrate(..., method=...) (issue 42 item 3) -------------


def plant(t, y):
    """ṗ = w, ẇ = 1 − 5w, ė = w²: the 3-state form EXP takes (c = 1), exact for its (X1)."""
    return [y[1], 1.0 - 5.0 * y[1], y[1] * y[1]]


def plant_p(t):
    return t / 5 - (1 - math.exp(-5 * t)) / 25


OPTIONS = {"DP54": {}, "EXP": {"scale": 1.0}, "RK4": {"step": 1e-3}, "LSODA": {}, "Radau": {}, "BDF": {}}


@pytest.mark.parametrize("method", list(OPTIONS))
def test_every_method_is_one_call_returning_one_run_type(method):
    """The same problem, events and dense output through integrate's `method`: a Run each time."""
    from gearhead.core.sim.integrate import METHODS, Run

    assert set(METHODS) == set(OPTIONS)
    reach = Event("reach", lambda t, y: y[0] - plant_p(1.0), +1)
    half = Event("half", lambda t, y: y[1] - 0.1, +1, terminal=False)
    run = integrate(
        plant,
        0.0,
        2.0,
        [0.0, 0.0, 0.0],
        1e-9,
        1e-12,
        [reach, half],
        dense=True,
        method=method,
        **OPTIONS[method],
    )
    assert type(run) is Run and run.nfev > 0
    assert run.event == "reach" and run.t[-1] == pytest.approx(1.0, abs=1e-5)
    [(name, t_half, _)] = run.crossings
    assert name == "half" and t_half == pytest.approx(math.log(2) / 5, abs=1e-5)
    assert run.at(0.5)[0] == pytest.approx(plant_p(0.5), abs=1e-7)


@pytest.mark.parametrize("method", list(OPTIONS))
def test_every_method_is_charged_to_the_budget(method):
    """Every method's evaluations count against `with budget(...)`, and a cancel stops each one."""
    from gearhead.core.sim.integrate import BudgetExceeded, Cancelled, budget

    wave = lambda t, y: [math.cos(50 * t), -y[1] + math.sin(50 * t), 0.0]  # noqa: E731
    opts = {**OPTIONS[method], "step": 1e-4} if method == "RK4" else OPTIONS[method]
    with pytest.raises(BudgetExceeded), budget(max_nfev=200):
        integrate(wave, 0.0, 100.0, [0.0, 0.0, 0.0], 1e-10, 1e-12, method=method, **opts)
    with pytest.raises(Cancelled), budget(cancel=lambda: True):
        integrate(wave, 0.0, 100.0, [0.0, 0.0, 0.0], 1e-10, 1e-12, method=method, **opts)
    with budget() as spent:
        run = integrate(plant, 0.0, 0.5, [0.0, 0.0, 0.0], 1e-8, 1e-10, method=method, **OPTIONS[method])
    assert spent.nfev >= run.nfev - 8  # scipy's are charged 8 at a time


def test_a_method_refuses_an_option_it_does_not_take():
    with pytest.raises(TypeError, match="step"):
        integrate(plant, 0.0, 1.0, [0.0, 0.0, 0.0], method="DP54", step=0.1)
    with pytest.raises(TypeError, match="step"):
        integrate(plant, 0.0, 1.0, [0.0, 0.0, 0.0], method="RK4")
    with pytest.raises(TypeError, match="RK45"):
        integrate(plant, 0.0, 1.0, [0.0, 0.0, 0.0], method="RK45")
    with pytest.raises(TypeError, match="restart"):
        integrate(plant, 0.0, 1.0, [0.0, 0.0, 0.0], method="Radau", restart=("x",))


def test_integrate_stiff_is_the_interface_s_scipy_method():
    """integrate_stiff (kept for its callers) returns the same Run as integrate(method=...)."""
    from gearhead.core.sim.integrate import integrate_stiff

    a = integrate_stiff(plant, 0.0, 1.0, [0.0, 0.0, 0.0], 1e-8, 1e-10, method="Radau")
    b = integrate(plant, 0.0, 1.0, [0.0, 0.0, 0.0], 1e-8, 1e-10, method="Radau")
    assert type(a) is type(b) and (a.t, a.y, a.nfev) == (b.t, b.y, b.nfev)
