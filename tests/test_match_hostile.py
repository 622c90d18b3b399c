"""Hostile matches: every wrong entry is an InputError naming its field, every run is bounded and
finite (no NaN, no hang, no traceback)."""

from __future__ import annotations

import math

import pytest

from gearhead.core.errors import InputError
from gearhead.core.match import timeline
from gearhead.core.match.battery import Battery
from gearhead.core.match.brownout import Controller
from gearhead.core.match.timeline import Load, Match, constant_current, constant_power

FLAT = Battery(ocv_table=((0.5, 12.5),))


def _err(**kwargs) -> InputError:
    with pytest.raises(InputError) as e:
        Match(**kwargs).run()
    return e.value


@pytest.mark.parametrize(
    "kwargs,field",
    [
        ({"length": -1.0}, "length"),
        ({"length": float("nan")}, "length"),
        ({"length": 1e9}, "length"),
        ({"length": True}, "length"),
        ({"base_load": float("inf")}, "base_load"),
        ({"loads": [Load("x", constant_current(1.0), -1.0, 2.0)]}, "loads[0].start"),
        ({"loads": [Load("x", constant_current(1.0), 3.0, 2.0)]}, "loads[0].stop"),
        ({"loads": [Load("x", constant_current(1.0), 200.0, 300.0)]}, "loads[0].start"),
        ({"loads": [Load("x", constant_current(1.0), float("nan"), 2.0)]}, "loads[0].start"),
        ({"loads": [Load("x", constant_current(1.0)), Load("x", constant_current(1.0))]}, "loads[1].name"),
        ({"loads": [Load("base", constant_current(1.0))]}, "loads[0].name"),
        ({"loads": [Load("x", "not a function")]}, "loads[0].terms"),
        ({"loads": ["drive"]}, "loads[0]"),
        ({"loads": [Load("x", constant_current(1.0), brownout_disables="no")]}, "loads[0].brownout_disables"),
        ({"loads": [Load("x", constant_current(1.0), breaker=40)]}, "loads[0].breaker"),
        ({"loads": "drive"}, "loads"),
        ({"loads": [Load(f"l{i}", constant_current(0.001)) for i in range(100_000)]}, "loads"),
        ({"battery": "fresh"}, "battery"),
        ({"controller": None}, "controller"),
    ],
)
def test_wrong_entries_are_named(kwargs, field):
    assert _err(**kwargs).field == field


def test_zero_capacity_is_named():
    with pytest.raises(InputError) as e:
        Battery(capacity_ah=0)
    assert e.value.field == "battery.capacity_ah"


@pytest.mark.parametrize(
    "terms,says",
    [
        (lambda t: (float("nan"), 0.0, 0.0), "a = 'nan'"),
        (lambda t: (1.0, 0.0, float("inf")), "p = 'inf'"),
        (lambda t: ("5", 0.0, 0.0), "a = '5'"),
        (lambda t: (True, 0.0, 0.0), "a = 'True'"),
        (lambda t: (1.0, -0.5, 0.0), "b = -0.5"),
        (lambda t: (1.0, 0.0), "ValueError"),
        (lambda t: 1 / 0, "ZeroDivisionError"),
        (lambda t: (1.0, 0.0, 0.0) if t < 1.5 else (math.nan, 0, 0), "at t = 1."),
    ],
)
def test_a_load_function_that_misbehaves_is_named_with_the_time(terms, says):
    e = _err(battery=FLAT, length=3.0, loads=[Load("arm", terms, 0.0, 3.0)])
    assert e.field == "loads[0] 'arm'"
    assert says in e.message
    when = float(e.message.split("t = ")[1].split(" s")[0])
    assert 0.0 <= when <= 3.0


def test_brownout_switches_are_bounded(monkeypatch):
    """A load that browns the bus out whenever it is on: the switching stops at MAX_SWITCHES with a
    message naming the dwell (bounded at 20 000 in use; 40 here to be quick)."""
    monkeypatch.setattr(timeline, "MAX_SWITCHES", 40)
    e = _err(
        battery=FLAT,
        controller=Controller(dwell=0.01),
        length=10.0,
        loads=[Load("x", constant_current(400.0))],
    )
    assert e.field == "controller.dwell"


def test_evaluations_are_bounded(monkeypatch):
    monkeypatch.setattr(timeline, "MAX_EVALS", 500)
    fast = lambda t: (10.0 + 5.0 * math.sin(2000.0 * t), 0.0, 0.0)  # noqa: E731
    e = _err(battery=FLAT, length=10.0, loads=[Load("buzz", fast)])
    assert e.field == "loads"


def test_a_collapsing_bus_stays_finite_and_balanced():
    """3 kW of constant-power load that brownout does not disable, on 12.5 V behind 0.02 Ω (at most
    1953 W): the bus collapses to V* = 6.25 V, the battery gives its most (312.5 A), the energy still
    balances and nothing is NaN."""
    load = Load("heater", constant_power(3000.0), 1.0, 2.0, brownout_disables=False)
    r = Match(battery=Battery(ocv_table=((0.5, 12.5),), resistance=0.02), length=3.0, loads=(load,)).run()
    assert r.collapsed_time == pytest.approx(1.0, abs=0.01)
    assert r.min_voltage == pytest.approx(6.25, rel=1e-12)
    assert r.peak_current == pytest.approx(312.5, rel=1e-12)
    assert r.energy_bus_wh + r.energy_loss_wh == pytest.approx(r.energy_cells_wh, rel=1e-9)
    values = [r.min_voltage, r.charge_ah, r.peukert_charge_ah, r.energy_cells_wh, r.rms_current, r.end_soc]
    assert all(math.isfinite(x) for x in values)
    assert all(math.isfinite(v) for v in r.volts) and all(math.isfinite(i) for i in r.amps)


def test_numpy_numbers_are_numbers():
    """A load function written with numpy returns numpy floats: accepted as the floats they are."""
    np = pytest.importorskip("numpy")
    load = Load("np", lambda t: (np.float64(10.0), np.float32(0.0), np.float64(0.0)), 0.0, 2.0)
    r = Match(battery=FLAT, length=2.0, loads=(load,)).run()
    assert r.charge_ah * 3600 == pytest.approx(20.0, rel=1e-9)


def test_a_load_starting_at_the_end_never_draws():
    """A load may start at the match's length (an event past the end is refused, one at it runs for
    no time): it shows nowhere, not even in the peak current."""
    r = Match(
        battery=FLAT, length=2.0, base_load=1.0, loads=(Load("late", constant_current(500.0), 2.0, 3.0),)
    ).run()
    assert r.peak_current == 1.0 and r.shares["late"] == 0.0
    assert r.min_voltage == pytest.approx(12.5 - 0.015, rel=1e-12)
