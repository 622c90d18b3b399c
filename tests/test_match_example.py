"""The example workbook's match (issue 43 item 7): auto (a sprint, a lift, shots), teleop cycles of
sprint, lift and shots, an endgame climb (the lift's gearbox lifting the robot's weight), whose
requirements hold on a fresh battery and fail, by name, on a tired one (0.025 ohm, 70 % charged).
The lowest bus voltage is checked by hand: V = V_oc − R·ΣI with ΣI the drive's four motors at their
supply limit, the base load and the shooter holding its speed."""

from __future__ import annotations

from pathlib import Path

import pytest

from gearhead.core import workbook

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = str(ROOT / "examples" / "robot_2027.toml")
TIRED = {"battery_resistance": "0.025 ohm", "battery_charge": "70 %"}


@pytest.fixture(scope="module")
def fresh():
    return workbook.solve(workbook.load(EXAMPLE))


@pytest.fixture(scope="module")
def tired():
    return workbook.solve(workbook.load(EXAMPLE, TIRED))


def holds(outcome) -> dict[str, bool]:
    return {c.requirement.key: c.holds for c in outcome.checks}


def test_auto_teleop_and_an_endgame_climb(fresh):
    m = fresh.match
    asked = [(t, ev.card, ev.action) for t, ev, _ in m.moves]
    auto = {(card, action) for t, card, action in asked if t < 15}
    assert {("drive", "move"), ("lift", "move"), ("shooter", "burst")} <= auto
    teleop = [(card, action) for t, card, action in asked if 15 <= t < 130]
    for move in (("drive", "move"), ("drive", "return"), ("lift", "move"), ("shooter", "burst")):
        assert teleop.count(move) >= 6, move  # cycles, not one of each
    climbs = [t for t, card, _ in asked if card == "climb"]
    assert len(climbs) == 1 and climbs[0] >= 130  # the endgame
    # the climb is the lift's gearbox on the robot's weight
    links = fresh.cards["climb"].links
    assert links["load_mass"] == "= robot_mass" and links["motor"] == "= mechanism_motor"
    for name in ("motor_count", "ratio", "spool_diameter", "stator_current_limit"):
        assert links[name] == f"= lift.{name}", name
    assert fresh.cards["climb"].entries["load_mass"] == "125 lb"
    assert m.outputs["unfinished"] == 0 and m.outputs["moves"] == len(asked)


def test_fresh_battery_holds_every_match_requirement(fresh):
    m = fresh.match
    assert fresh.all_hold and m.outputs["brownouts"] == 0
    assert m.outputs["min_bus_voltage"] > 7.5  # clear of the 7 V asked


def test_tired_battery_fails_the_bus_requirement_by_hand(tired):
    h = holds(tired)
    assert not h["match_bus_above_7_v"]
    assert h["match_no_brownout"]  # the drive's 55 A supply limit keeps it out of brownout
    m = tired.match
    v_min = m.outputs["min_bus_voltage"]
    t_min = m.outputs["min_bus_time"]
    assert "drive" in " ".join(m.running_at_min)
    _, v, i = min(m.bus.trace, key=lambda s: abs(s[0] - t_min))
    # four drive motors at their 55 A supply limit, the 3 A base load and the shooter holding its
    # speed (a few amps): V = V_oc − R·ΣI, V_oc between the start's 12.612 V and the end's
    assert 4 * 55 + 3 < i < 4 * 55 + 3 + 10
    v_oc = v + 0.025 * i
    assert m.outputs["end_voltage"] - 1e-9 <= v_oc <= 12.54 + 0.2 * 0.18 * 2 + 1e-9
    assert v == pytest.approx(v_min, abs=1e-9)
    assert 6.75 < v_min < 7.0
