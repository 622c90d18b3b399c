"""A brownout-bound match integrated fast agrees with the integration before the speed-up, at its
finest tolerance (core.match.mechanisms: after a recovery a stiff piece tries DP54 first,
RECOVERY_STEPS, its integrals as the piece's increments; RECOVERY_STEPS = 0 is LSODA at once, the
integration before). The case: the example workbook's first 6 s (the drive's sprint, the lift up,
the shooter's burst, the lift down) on a tired battery (25 mΩ, 70 %) with a 60 A drive supply
limit, where the outputs come back and fall again every 21 ms: 284 brownouts, the lift's stiff
pieces each a fraction of a millisecond.

The tolerances are what the integration before gets at its own default tolerance (rtol 1e-6)
against itself at rtol 1e-9, with room: its charge, energy and ∫I²dt 3-6e-4 off (each piece's
integral is held against the match's totals), the brownouts' total length 4e-6, the lowest bus
voltage 1e-7. A speed-up that loses part of a piece's charge fails: DP54's pieces with the
integrals against the totals (one step a piece) were 2 % off."""

from __future__ import annotations

import dataclasses
import tomllib
from pathlib import Path

import pytest

from gearhead.core import workbook
from gearhead.core.match import mechanisms

ROOT = Path(__file__).resolve().parents[1]
SETS = {"battery_resistance": "0.025 ohm", "battery_charge": "70 %", "drive_supply_limit": "60 A"}
LENGTH = 6.0


def first_seconds() -> dict:
    data = tomllib.loads((ROOT / "examples" / "robot_2027.toml").read_text())
    data["match"]["length"] = f"{LENGTH:g} s"
    data["match"]["events"] = [
        e for e in data["match"]["events"] if "every" not in e and float(e["at"].split()[0]) < LENGTH
    ]
    return data


def outputs(monkeypatch, steps: int, rtol: float | None) -> dict:
    monkeypatch.setattr(mechanisms, "RECOVERY_STEPS", steps)
    run = mechanisms.MechanismMatch.run
    if rtol is not None:
        monkeypatch.setattr(
            mechanisms.MechanismMatch, "run", lambda self: run(dataclasses.replace(self, rtol=rtol))
        )
    wb = workbook.from_dict(first_seconds(), "first_seconds", ROOT / "examples", SETS)
    out = workbook.solve(wb).match
    monkeypatch.undo()
    return dict(out.outputs), out


@pytest.fixture(scope="module")
def reference():
    with pytest.MonkeyPatch.context() as mp:
        return outputs(mp, 0, 1e-9)


def test_brownout_bound_match_agrees_with_the_integration_before(monkeypatch, reference):
    ref, _ = reference
    fast, m = outputs(monkeypatch, mechanisms.RECOVERY_STEPS, None)
    assert ref["brownouts"] == fast["brownouts"] >= 200  # the case browns out all along
    assert any(ld.startswith("lift") for b in m.brownouts for ld in b.running)  # the stiff lift
    for key in ("charge_used", "peukert_charge_used", "energy", "rms_current"):
        assert fast[key] == pytest.approx(ref[key], rel=1.5e-3), key
    assert fast["end_charge"] == pytest.approx(ref["end_charge"], rel=1e-5)
    assert fast["brownout_time"] == pytest.approx(ref["brownout_time"], rel=5e-5)
    assert fast["min_bus_voltage"] == pytest.approx(ref["min_bus_voltage"], rel=1e-5)
    assert fast["time_below_brownout"] == pytest.approx(ref["time_below_brownout"], abs=1e-9)
    assert fast["unfinished"] == ref["unfinished"]


def test_the_integration_before_is_as_far_from_the_reference(monkeypatch, reference):
    """The bounds above are the integration before's own error, not looser: at its default tolerance
    it meets them too."""
    ref, _ = reference
    before, _ = outputs(monkeypatch, 0, None)
    for key in ("charge_used", "peukert_charge_used", "energy", "rms_current"):
        assert before[key] == pytest.approx(ref[key], rel=1.5e-3), key
    assert before["brownout_time"] == pytest.approx(ref["brownout_time"], rel=5e-5)


def test_a_quiet_dwell_in_closed_form_is_the_integration(monkeypatch):
    """(B14): at 0.05 ohm the drive's first sprint browns out at once every time the outputs come
    back; a dwell with every move at rest is stepped in closed form. Against the same dwells
    integrated (DP54, _quiet refused): the same to rounding (the solution is quadratic in t)."""
    quiet = mechanisms._Run._quiet
    used = []

    def counted(self, t, t1, y):
        out = quiet(self, t, t1, y)
        used.append(out is not None)
        return out

    def weak() -> dict:
        sets = {"battery_resistance": "0.05 ohm"}
        m = workbook.solve(
            workbook.from_dict(first_seconds(), "first_seconds", ROOT / "examples", sets)
        ).match
        bus = m.bus
        extra = {"energy_bus": bus.energy_bus, "energy_r": bus.energy_r, "i2": bus.current_squared}
        return {**m.outputs, **extra, "trace": len(bus.trace)}

    monkeypatch.setattr(mechanisms._Run, "_quiet", counted)
    closed = weak()
    assert sum(used) >= 100  # the case is mostly quiet dwells
    monkeypatch.setattr(mechanisms._Run, "_quiet", lambda self, t, t1, y: None)
    integrated = weak()
    assert closed["brownouts"] == integrated["brownouts"] >= 200
    for key, value in integrated.items():
        assert closed[key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
