"""Issue 34 item 2, the motor scenes' last gaps (core/sim/motion.py): each test failed before the
fix in motion.py (LQR gains that destabilise the loop refused; the optimise pre-search charged to
the solve's budget).

- `batch_times`, optimise's pre-search over 240 ratios (up to 6 000 numpy steps), charged nothing
  to the solve's budget: the CPU backstop and the app's cancel were not polled during it.
- `lqr`: with the position and voltage tolerances many decades apart scipy's Riccati solve lost its
  digits and returned gains that destabilise the loop; they were reported as results (kP -0.43 V/m,
  or -9.4e51 V/m with a 20 ms sensor delay), and with a long delay the latency compensation
  (A − BK)^(delay/dt) overflowed with numpy RuntimeWarnings on stderr before the message. Issue 33
  replaced scipy there (core/sim/small_math.py: doubling and Newton's steps), which keeps the
  digits: those gains are now right, and the refusal stays for a solution that would not be.
"""

import math
import warnings

import numpy as np
import pytest

from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import motion
from gearhead.core.sim.integrate import Cancelled, budget

# an elevator that moves (ratio 1e-4 on a 0.22 g load) with LQR tolerances 12 decades apart
# (r 1e-7 V against q 12.7 mm), at the shortest control period
UNSTABLE = {"control_period": "0.1", "r_volts": "1e-7", "ratio": "0.0001", "load_mass": "0.00022"}


def _batch():
    v, _ = parse_inputs(get("elevator"), {"mode": "optimise"})
    from gearhead.core.calculators import elevator

    return elevator.setup(v, np.geomspace(0.5, 500, motion.CANDIDATES), motion._Array())


def test_the_batch_presearch_polls_the_apps_cancel():
    with budget(cancel=lambda: True), pytest.raises(Cancelled):
        motion.batch_times(_batch())


def test_the_batch_presearch_is_charged_to_the_solves_budget():
    with budget() as b:
        times = motion.batch_times(_batch())
    assert np.isfinite(times).any()
    assert 0 < b.nfev <= 3 * 40 * motion.BATCH_STEPS


@pytest.mark.parametrize("delay", ["0", "20"])
def test_lqr_gains_with_tolerances_12_decades_apart_now_stabilise_the_loop(delay):
    """scipy's Riccati solve lost its digits here and its gains destabilised the loop (refused:
    kP -0.43 V/m); the doubling with Newton's steps (core/sim/small_math.py) keeps them. With
    control this costly the gain is the cheap-state limit of a double integrator, kP = √(q₁/ρ)
    = √((1/12.7 mm)²/(1/1e-7 V)²) = 7.874e-6 V/m (ratio 1e-4: hardly any damping)."""
    out = solve("elevator", dict(UNSTABLE, sensor_delay=delay)).outputs
    assert 0 < out["kD"].value < math.inf
    expected = math.sqrt((1 / 0.0127) ** 2 / (1 / 1e-7) ** 2)
    assert out["kP"].value == pytest.approx(expected, rel=1e-3)


def test_gains_that_would_destabilise_the_loop_are_still_refused(monkeypatch):
    """The check stays for a Riccati solution that loses its digits (forced here: S = 0, K = 0
    leaves the integrator's eigenvalue at 1 + 1e-6 once A is nudged)."""
    from gearhead.core.sim import small_math

    motion.lqr.cache_clear()
    monkeypatch.setattr(small_math, "dare", lambda A, B, Q, R: np.zeros_like(Q))
    real_hold = small_math.zero_order_hold
    monkeypatch.setattr(
        small_math, "zero_order_hold", lambda *a: (real_hold(*a)[0] * (1 + 1e-6), real_hold(*a)[1])
    )
    with pytest.raises(InputError) as exc:
        solve("elevator", {"q_position": "0.51 in"})
    assert exc.value.field == "q_position"
    motion.lqr.cache_clear()


def test_a_long_delay_at_the_shortest_period_leaks_no_numpy_warning():
    motion.lqr.cache_clear()  # a cached result would say nothing
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = solve("elevator", dict(UNSTABLE, sensor_delay="1000")).outputs
    assert 0 < out["kP"].value < math.inf
    assert [str(w.message) for w in caught] == []


def test_ordinary_gains_stay_gains():
    """The default elevator and a long delay at the shortest period (a loop that is stable) still
    give their gains: positive, finite, the delayed ones smaller."""
    plain = solve("elevator", {}).outputs
    slow = solve("elevator", {"control_period": "0.1", "sensor_delay": "1000"}).outputs
    for out in (plain, slow):
        assert 0 < out["kP"].value < math.inf and 0 < out["kD"].value < math.inf
    assert slow["kP"].value < plain["kP"].value
