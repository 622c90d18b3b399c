"""Each mechanism's channel breaker on the match's bus (core/match/mechanisms.py (B9)): the
thermal state (breaker.py (M12)) along the per-motor supply current, its trip located by hand on a
constant current, a card's moves on one channel, and the workbook's outputs
`match.<card>_breaker_load`, `_margin`, `_trip`."""

import math

import pytest

from gearhead.core.errors import InputError
from gearhead.core.match.breaker import Breaker
from gearhead.core.match.brownout import Controller
from gearhead.core.match.mechanisms import IdealSource, MechanismMatch, MechanismMove, _Sprint, from_card

LOW = Controller(brownout=0.1, recovery=0.2)
SLIPPING = {"effects": "rolling_resistance", "wheel_cof": 0.3, "distance": 10}  # slips for 1.63 s


def test_a_trip_on_a_constant_current_by_hand():
    """A sprint slipping on an ideal 12 V source draws I_slip per motor, constant (B7), for 1.63 s:
    a 10 A breaker with the table (1.5×, 3 s), (3×, 0.2 s) trips at (M13)'s time from cold, located
    at the first record after it (the trace's step)."""
    mv = from_card("sprint", SLIPPING)
    brk = Breaker(10.0, ((1.5, 3.0), (3.0, 0.2)), name="channel_breaker")
    res = MechanismMatch((mv,), IdealSource(12.0), LOW, length=5.0, channel_breaker=brk).run()
    I_slip = _Sprint("m", mv, 5.0).I_slip
    t_trip = brk.trip_time(I_slip)
    t_grip = res.switches[0][0]
    assert 0 < t_trip < t_grip  # inside the slip: a constant current
    ch = res.channels["sprint"]
    steps = sorted({t for t, _, _ in res.trace})
    after = min(t for t in steps if t >= t_trip)
    assert t_trip <= ch.trip_time <= after
    assert ch.peak == pytest.approx(I_slip, rel=1e-12)
    assert ch.rating == 10.0 and ch.theta_max >= 1.0 and ch.margin <= 0.0


def test_the_thermal_state_by_hand_while_slipping():
    """No trip: θ after the slip is advance(0, I_slip, t_grip) exactly (a constant current), and the
    state only falls after it if the gripping current's heating is below it: θ_max ≥ that value,
    and equal to it when the breaker's rating is so high the heating is x² everywhere and falling."""
    mv = from_card("sprint", SLIPPING)
    brk = Breaker(40.0, ((1.5, 3.0), (3.0, 0.2)), name="channel_breaker")
    res = MechanismMatch((mv,), IdealSource(12.0), LOW, length=5.0, channel_breaker=brk).run()
    I_slip = _Sprint("m", mv, 5.0).I_slip
    t_grip = res.switches[0][0]
    theta_grip = brk.advance(0.0, I_slip, t_grip)
    ch = res.channels["sprint"]
    assert ch.trip_time is None
    # after the grip the current falls from I_slip: its heating x² < θ(t_grip)? then θ falls at once
    x = I_slip / 40.0
    assert x * x > theta_grip  # here it still heats a little after the grip
    assert ch.theta_max >= theta_grip * (1 - 1e-12)
    assert ch.theta_max < x * x  # never past the slip current's own equilibrium


def test_moves_of_one_channel_share_its_breaker_and_no_table_gives_peaks_only():
    el = from_card("elevator", {"effects": "gravity, stator_limit", "stator_current_limit": 60})
    a = MechanismMove("lift#0", el.setup, 0.0, channel="lift")
    b = MechanismMove("lift#1", el.setup, 2.0, after=0, channel="lift")
    res = MechanismMatch((a, b), IdealSource(12.0), LOW, length=4.0).run()
    assert list(res.channels) == ["lift"]
    ch = res.channels["lift"]
    assert ch.theta_max is None and ch.trip_time is None and ch.margin is None and ch.rating == 40.0
    assert ch.peak == pytest.approx(max(m.peak_supply_current for m in res.mechanisms), rel=1e-12)


def test_bad_channels_are_named():
    mv = from_card("elevator", {})
    with pytest.raises(InputError) as e:
        MechanismMatch((MechanismMove("x", mv.setup, channel=""),)).run()
    assert e.value.field == "moves[0].channel"
    with pytest.raises(InputError) as e:
        MechanismMatch((mv,), channel_breaker=40).run()
    assert e.value.field == "channel_breaker"
    assert math.isinf(Breaker(40.0, ((2.0, 1.0),)).trip_time(40.0))  # at the rating: never


WB = """
format = 1
name = "channels"

[cards.lift]
calculator = "elevator"
[cards.lift.inputs]
motor_count = 2
ratio = 9
load_mass = "15 lb"
travel = "48 in"
effects = "gravity, stator_limit, battery_sag"
stator_current_limit = "80 A"

[match]
length = "6 s"
{table}
[[match.events]]
at = "0 s"
card = "lift"

[[match.events]]
at = "3 s"
card = "lift"
action = "return"

[[requirements]]
name = "lift breaker"
check = "{check}"
"""


def book(table: str, check: str = "match.lift_breaker_load < 1000 %"):
    from gearhead.core import workbook

    return workbook.from_text(WB.format(table=table, check=check), "robot.toml")


def test_workbook_channel_outputs_and_requirements():
    from gearhead.core import workbook

    table = "channel_rating = '30 A'\nchannel_breaker = [[1.5, 10.0], [3.0, 1.0]]\n"
    o = workbook.solve(book(table, "match.lift_breaker_margin > 50 %"))
    ch = o.match.bus.channels["lift"]
    assert ch.rating == 30.0 and list(o.match.bus.channels) == ["lift"]
    out = o.match.outputs
    assert out["lift_breaker_load"] == pytest.approx(100 * ch.peak / 30.0, rel=1e-12)
    assert out["lift_breaker_margin"] == pytest.approx(100 * (1 - ch.theta_max), rel=1e-12)
    assert "lift_breaker_trip" not in out
    assert o.checks[0].holds
    assert o.match.as_json()["outputs"]["lift_breaker_margin"]["unit"] == "%"
    # a breaker rated 1 A trips: its time is an output a requirement reads
    o = workbook.solve(
        book(
            "channel_rating = '1 A'\nchannel_breaker = [[1.5, 1.0], [3.0, 0.1]]\n",
            "match.lift_breaker_trip > 5 s",
        )
    )
    assert 0 < o.match.outputs["lift_breaker_trip"] < 1.0 and not o.checks[0].holds
    # without a table: the load only; the margin is not given (named)
    o = workbook.solve(book("", "match.lift_breaker_margin > 50 %"))
    assert "lift_breaker_load" in o.match.outputs and "lift_breaker_margin" not in o.match.outputs
    assert "match.channel_breaker" in (o.checks[0].error or "")


@pytest.mark.parametrize(
    "table, check, field, words",
    [
        ("channel_breaker = [[0.5, 1.0]]\n", None, "match.channel_breaker.trip_table[0].multiple", ""),
        ("channel_breaker = []\n", None, "match.channel_breaker", "at least one row"),
        ("channel_breaker = 'fast'\n", None, "match.channel_breaker", ""),
        ("channel_rating = '0 A'\n", None, "match.channel_rating", "above 0 A"),
        ("channel_rating = '3 V'\n", None, "match.channel_rating", "A"),
        ("", "match.arm_breaker_load < 100 %", "requirements[1].check", "not an output of the match"),
    ],
)
def test_workbook_channel_entries_refused_by_name(table, check, field, words):
    with pytest.raises(InputError) as e:
        book(table, check or "match.lift_breaker_load < 1000 %")
    assert e.value.field.startswith(field) and words in e.value.message
    assert e.value.source == "robot.toml"
