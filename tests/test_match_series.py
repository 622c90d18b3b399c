"""The match's series for the app's plots (core/match/series.py): each move's supply current recorded
on the bus trace's samples (mechanisms.MechanismResult.supply_trace), the per-card currents plus the
base load summing to the battery current at every sample, the state of charge ending at the
match's own output, and the bins a stacked chart shows."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import pytest

from gearhead.core import workbook
from gearhead.core.match.series import MatchSeries, peak_bins, series

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "robot_2027.toml"


@pytest.fixture(scope="module")
def example():
    m = workbook.solve(workbook.load(str(EXAMPLE))).match
    assert m is not None
    return m, series(m)


def test_each_move_records_its_supply_current_on_the_bus_samples(example):
    m, _ = example
    trace = m.bus.trace
    for _, _, r in m.moves:
        assert r.supply_trace, r.name
        for i, t, amps in r.supply_trace:
            assert trace[i][0] == t
            assert math.isfinite(amps)
        # from its start to its goal, every sample in between
        idx = [i for i, _, _ in r.supply_trace]
        assert idx == list(range(idx[0], idx[0] + len(idx)))


def test_cards_and_base_sum_to_the_battery_current_at_every_sample(example):
    m, s = example
    assert set(s.by_card) == {ev.card for _, ev, _ in m.moves}  # every card the match moves
    n = len(s.t)
    assert n == len(m.bus.trace) and all(len(v) == n for v in s.by_card.values())
    worst = 0.0
    for i in range(n):
        total = s.base[i] + sum(v[i] for v in s.by_card.values())
        worst = max(worst, abs(total - s.battery_current[i]))
    print(f"largest |base + Σ cards − battery current| over {n} samples: {worst:.3g} A")
    assert worst <= 1e-9 * max(abs(x) for x in s.battery_current)
    assert max(max(v) for v in s.by_card.values()) > 50  # the moves draw, not only the base


def test_state_of_charge_ends_at_the_outputs(example):
    m, s = example
    assert 100 * s.soc[-1] == pytest.approx(m.outputs["end_charge"], rel=1e-12)
    assert 100 * s.available[-1] == pytest.approx(m.outputs["end_available"], rel=1e-12)
    assert s.soc[0] == m.battery.start_soc
    assert all(math.isfinite(x) for x in s.soc + s.available + s.bus_voltage)


def test_state_of_charge_falls_wherever_the_battery_gives_current(example):
    _, s = example
    # a move driven past its motors' free speed (gravity helping) pushes current back: over such a
    # step the charge rises, as the model counts it; wherever the battery gives current it falls
    back = 0
    for j in range(1, len(s.t)):
        if s.battery_current[j - 1] >= 0 and s.battery_current[j] >= 0:
            assert s.soc[j] <= s.soc[j - 1]
            assert s.available[j] <= s.available[j - 1]
        elif s.battery_current[j - 1] <= 0 and s.battery_current[j] <= 0:
            back += 1
            assert s.soc[j] >= s.soc[j - 1]
    print(f"{back} of {len(s.t)} steps with current pushed back; lowest {min(s.battery_current):.3g} A")
    assert min(s.battery_current) > -20


MONOTONE = """
format = 1
name = "one lift up"

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
length = "20 s"
base_load = "3 A"

[[match.events]]
at = "1 s"
card = "lift"
every = "5 s"
count = 3
"""


def test_lifts_only_the_state_of_charge_never_rises(tmp_path):
    p = tmp_path / "lift.toml"
    p.write_text(textwrap.dedent(MONOTONE))
    m = workbook.solve(workbook.load(str(p))).match
    s = series(m)
    assert min(s.battery_current) >= 0
    assert all(b <= a for a, b in zip(s.soc, s.soc[1:]))
    assert all(b <= a for a, b in zip(s.available, s.available[1:]))
    assert 100 * s.soc[-1] == pytest.approx(m.outputs["end_charge"], rel=1e-12)
    for i in range(len(s.t)):
        assert s.base[i] + s.by_card["lift"][i] == pytest.approx(s.battery_current[i], abs=1e-9)


def test_peak_bins_show_each_bins_highest_current_and_carry_on_through_empty_ones():
    s = MatchSeries(
        t=[0.0, 1.0, 1.5, 6.0, 9.0],
        bus_voltage=[12.0] * 5,
        battery_current=[3.0, 50.0, 20.0, 3.0, 4.0],
        base=[3.0] * 5,
        length=10.0,
    )
    bins = peak_bins(s, 5)  # 2 s each
    assert [round(x, 9) for x, _ in bins] == [1.0, 3.0, 5.0, 7.0, 9.0]
    assert [i for _, i in bins] == [1, 2, 2, 3, 4]
    assert peak_bins(s, 0) == [] and peak_bins(MatchSeries([], [], [], []), 4) == []


def test_the_envelope_keeps_every_bins_first_last_and_extremes_in_time_order(example):
    from gearhead.core.match.series import envelope

    m, s = example
    xs, ys = envelope(s.t, s.bus_voltage, s.length, 600)
    assert len(xs) <= 4 * 600 and len(xs) < len(s.t)
    assert xs == sorted(xs) and xs[0] == s.t[0] and xs[-1] == s.t[-1]
    assert min(ys) == m.outputs["min_bus_voltage"] == m.bus.min_bus_voltage
    assert xs[ys.index(min(ys))] == m.outputs["min_bus_time"]
    assert max(ys) == max(s.bus_voltage)
    # every sample kept is a sample of the trace, and each bin's own lowest and highest are there
    pairs = set(zip(s.t, s.bus_voltage))
    assert all((x, y) in pairs for x, y in zip(xs, ys))
    width = s.length / 600
    for b in (0, 150, 599):
        inside = [v for t, v in zip(s.t, s.bus_voltage) if min(599, int(t / width)) == b]
        kept = [v for t, v in zip(xs, ys) if min(599, int(t / width)) == b]
        if inside:
            assert min(kept) == min(inside) and max(kept) == max(inside)
            assert kept[0] == inside[0] and kept[-1] == inside[-1]  # exact at the bin's edges
    assert envelope([], [], 1.0, 10) == ([], []) and envelope([0.0], [1.0], 1.0, 0) == ([], [])
