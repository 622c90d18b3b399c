"""Issue 34 item 2, the motor scenes' last gaps (core/sim/motion.py): each test failed before the
fix in motion.py (LQR gains that destabilise the loop refused; the optimise pre-search charged to
the solve's budget).

- `batch_times`, optimise's pre-search over 240 ratios (up to 6 000 numpy steps), charged nothing
  to the solve's budget: the CPU backstop and the app's cancel were not polled during it.
- `lqr`: with the position and voltage tolerances many decades apart the Riccati solve loses its
  digits and returns gains that destabilise the loop; they were reported as results (kP -0.43 V/m,
  or -9.4e51 V/m with a 20 ms sensor delay), and with a long delay the latency compensation
  (A − BK)^(delay/dt) overflowed with numpy RuntimeWarnings on stderr before the message.
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
def test_lqr_gains_that_do_not_stabilise_the_loop_are_refused(delay):
    with pytest.raises(InputError) as exc:
        solve("elevator", dict(UNSTABLE, sensor_delay=delay))
    assert exc.value.field == "q_position"


def test_a_long_delay_at_the_shortest_period_leaks_no_numpy_warning():
    motion.lqr.cache_clear()  # a cached result would say nothing
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(InputError) as exc:
            solve("elevator", dict(UNSTABLE, sensor_delay="1000"))
    assert exc.value.field == "q_position"
    assert [str(w.message) for w in caught] == []


def test_ordinary_gains_stay_gains():
    """The default elevator and a long delay at the shortest period (a loop that is stable) still
    give their gains: positive, finite, the delayed ones smaller."""
    plain = solve("elevator", {}).outputs
    slow = solve("elevator", {"control_period": "0.1", "sensor_delay": "1000"}).outputs
    for out in (plain, slow):
        assert 0 < out["kP"].value < math.inf and 0 < out["kD"].value < math.inf
    assert slow["kP"].value < plain["kP"].value
