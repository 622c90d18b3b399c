"""core/match/breaker.py: the thermal state (M12) calibrated to a trip table (M14, M15): a constant
current from cold trips at the table's time exactly; under a varying load the state by hand."""

from __future__ import annotations

import math

import pytest

from gearhead.core.errors import InputError
from gearhead.core.match.battery import Battery
from gearhead.core.match.breaker import Breaker
from gearhead.core.match.timeline import Load, Match, constant_current

# A table as a user would enter it from a data sheet (multiple of the rating → seconds from cold)
TABLE = ((1.5, 60.0), (2.0, 20.0), (3.0, 5.0), (5.0, 1.0))


def test_empty_table_by_default_checks_nothing():
    b = Breaker()
    assert b.rating == 40.0 and not b.calibrated


def test_calibration_reproduces_every_row_exactly():
    """(M13) with g from (M14): t_trip(x_i) = T_i for every row, whatever the row."""
    b = Breaker(40.0, TABLE)
    for x, t in TABLE:
        assert b.trip_time(x * 40.0) == pytest.approx(t, rel=1e-12)
    # τ (M15) by hand: the first row is pure Joule heating, x₀² = 2.25 = 1/(1 − e^{−60/τ})
    tau = 60.0 / math.log(2.25 / 1.25)
    assert b.tau == pytest.approx(tau, rel=1e-14)
    assert b.heating(1.5 * 40) == pytest.approx(2.25, rel=1e-12)
    # between rows: log-log; 2.5× lies between 20 s and 5 s at log(2.5/2)/log(3/2) of the way
    f = math.log(1.25) / math.log(1.5)
    assert b.trip_time(100.0) == pytest.approx(20.0 * (5.0 / 20.0) ** f, rel=1e-12)
    # beyond the last row: I²t constant
    assert b.trip_time(10 * 40.0) == pytest.approx(1.0 * (5 / 10) ** 2, rel=1e-12)
    # at or under the rating it never trips (θ → x² ≤ 1); just above, it does, later than the first row
    assert b.trip_time(40.0) == math.inf and b.trip_time(20.0) == math.inf
    assert 60.0 < b.trip_time(1.2 * 40) < math.inf
    # monotone: a larger current trips sooner
    times = [b.trip_time(40.0 * (1.01 + 0.05 * k)) for k in range(200)]
    assert all(t1 < t0 for t0, t1 in zip(times, times[1:]))


@pytest.mark.parametrize("row", range(len(TABLE)))
def test_a_step_current_trips_at_the_tables_time_in_a_match(row):
    """A channel breaker under a step to x·40 A at t = 2 s: the match's trip event at 2 s + T."""
    x, t_trip = TABLE[row]
    br = Breaker(40.0, TABLE, name="arm")
    load = Load("arm", constant_current(x * 40.0), 2.0, 100.0, breaker=br)
    r = Match(battery=Battery(ocv_table=((0.5, 12.5),)), length=80.0, loads=(load,), trace_step=0.5).run()
    arm = r.breakers[1]
    assert arm.name == "arm" and arm.calibrated
    assert arm.trip_time == pytest.approx(2.0 + t_trip, abs=1e-6)
    assert arm.peak_multiple == pytest.approx(x, rel=1e-12)
    assert r.breakers[0].name == "main_breaker" and not r.breakers[0].calibrated


def test_varying_load_state_by_hand():
    """80 A (2×) for 5 s, 20 A (0.5×) for 10 s, 120 A (3×) for 1 s, from cold. With τ = 60/ln 1.8:
    θ₁ = g(2)·(1 − e^{−5/τ}), g(2) = 1/(1 − e^{−20/τ});
    θ₂ = 0.25 + (θ₁ − 0.25)·e^{−10/τ};
    θ₃ = g(3) + (θ₂ − g(3))·e^{−1/τ}, g(3) = 1/(1 − e^{−5/τ})."""
    b = Breaker(40.0, TABLE, name="intake")
    tau = 60.0 / math.log(1.8)
    g2 = 1 / (1 - math.exp(-20 / tau))
    g3 = 1 / (1 - math.exp(-5 / tau))
    th1 = g2 * (1 - math.exp(-5 / tau))
    th2 = 0.25 + (th1 - 0.25) * math.exp(-10 / tau)
    th3 = g3 + (th2 - g3) * math.exp(-1 / tau)
    # by hand: τ = 102.078 s, g(2) = 1/0.177930 = 5.62019, g(3) = 1/0.0478018 = 20.9197
    assert (th1, th2, th3) == pytest.approx((0.26866, 0.26692, 0.46825), abs=1e-5)
    got = b.advance(b.advance(b.advance(0.0, 80.0, 5.0), 20.0, 10.0), 120.0, 1.0)
    assert got == pytest.approx(th3, rel=1e-12)
    # the match integrates the same: the worst state is θ₃ at the end of the 120 A piece
    loads = (
        Load("a", constant_current(80.0), 0.0, 5.0, breaker=b),
        Load("b", constant_current(20.0), 5.0, 15.0, breaker=Breaker(40.0, TABLE, name="b")),
        Load("c", constant_current(120.0), 15.0, 16.0, breaker=Breaker(40.0, TABLE, name="c")),
    )
    # one breaker sees all three pieces: one load whose current steps
    steps = lambda t: (80.0 if t < 5 else 20.0 if t < 15 else 120.0, 0.0, 0.0)  # noqa: E731
    one = Load("intake", steps, 0.0, 16.0, breaker=b)
    flat = Battery(ocv_table=((0.5, 12.5),))
    r = Match(battery=flat, length=16.0, loads=(one,), trace_step=0.01).run()
    intake = r.breakers[1]
    assert intake.theta_max == pytest.approx(th3, rel=1e-6)
    assert intake.margin == pytest.approx(1 - th3, rel=1e-6)
    assert intake.trip_time is None
    # the three-load version: each breaker sees only its own piece
    r3 = Match(battery=flat, length=16.0, loads=loads, trace_step=0.01).run()
    assert r3.breakers[1].theta_max == pytest.approx(th1, rel=1e-6)
    assert r3.breakers[3].theta_max == pytest.approx(g3 * (1 - math.exp(-1 / tau)), rel=1e-6)


def test_main_breaker_sees_the_battery_current():
    """Two 80 A loads on their own channels and a 2 A base: the main breaker carries 162 A = 1.35×."""
    main = Breaker(120.0, ((1.35, 30.0), (2.0, 5.0)), name="main_breaker")
    loads = (Load("l", constant_current(80.0), 0.0, 40.0), Load("r", constant_current(80.0), 0.0, 40.0))
    flat = Battery(ocv_table=((0.5, 12.5),))
    r = Match(battery=flat, length=40.0, base_load=2.0, loads=loads, main_breaker=main, trace_step=0.5).run()
    assert r.breakers[0].peak_multiple == pytest.approx(1.35, rel=1e-12)
    assert r.breakers[0].trip_time == pytest.approx(30.0, abs=1e-6)


@pytest.mark.parametrize(
    "table,field",
    [
        (((1.0, 10.0),), "b.trip_table[0].multiple"),  # a breaker trips only above its rating
        (((2.0, 10.0), (1.5, 5.0)), "b.trip_table"),
        (((1.5, 10.0), (2.0, 10.0)), "b.trip_table"),
        (((1.5, -1.0),), "b.trip_table[0].seconds"),
        (((1.5, float("nan")),), "b.trip_table[0].seconds"),
        ("1.5 10", "b.trip_table"),
        (((1.5, 10.0, 3.0),), "b.trip_table[0]"),
    ],
)
def test_a_wrong_table_is_named(table, field):
    with pytest.raises(InputError) as e:
        Breaker(40.0, table, name="b")
    assert e.value.field == field


def test_a_wrong_rating_is_named():
    with pytest.raises(InputError) as e:
        Breaker(0.0, name="main_breaker")
    assert e.value.field == "main_breaker.rating"
