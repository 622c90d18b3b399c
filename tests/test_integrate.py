"""The DP54 integrator: convergence with tolerance, event location, agreement with scipy, bounded work."""

import math

import pytest

from core.sim.integrate import Event, integrate

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
    ref = integrate(f, 0.0, 15.0, [2.5, 0.0], rtol=1e-13, atol=1e-15, method="DOP853").y[-1]
    assert ours == pytest.approx(ref, abs=1e-9)


def test_blow_up_ends_with_an_error_not_an_endless_loop():
    with pytest.raises(RuntimeError):
        integrate(lambda t, y: [y[0] ** 2], 0.0, 2.0, [1.0], rtol=1e-8, atol=1e-10, max_steps=20000)


def test_dense_output_is_fourth_order_accurate():
    run = integrate(oscillator, 0.0, 10.0, [1.0, 0.0], rtol=1e-10, atol=1e-12, dense=True)
    for t in [0.123, 3.3, 7.77, 9.99]:
        assert run.at(t)[0] == pytest.approx(math.cos(t), abs=1e-8)
