"""One way to solve (core/solving.py): the card and `gearhead solve` go through the same function;
a scene's error estimate can come as an explicit second step (model.finish_estimate) with the same
number; cancellation is the caller's; no module-wide state changes how a solve runs."""

from __future__ import annotations

import ast
import json
import pathlib

import pytest

from gearhead.core import model, solving
from gearhead.core.registry import calculators
from gearhead.core.sim.integrate import Cancelled

CORE = pathlib.Path(__file__).resolve().parents[1] / "core"
SCENES = [c.id for c in calculators().values() if any(o.name == model.ESTIMATE for o in c.outputs)]


def _without_clock(solution):
    data = solution.as_json()
    data["outputs"].pop("wall_time", None)
    return data


def test_the_scenes_are_found():
    assert {"pneumatics", "elevator", "arm", "flywheel", "sprint", "projectile", "trebuchet"} <= set(SCENES)


@pytest.mark.parametrize("calc_id", SCENES)
def test_the_estimate_later_is_the_estimate_now(calc_id):
    now = model.solve(calc_id, {})
    later = model.solve(calc_id, {}, estimate="later")
    if later.pending_estimate is None:  # a closed form (nothing integrated): 0 at once
        assert later.outputs[model.ESTIMATE] == now.outputs[model.ESTIMATE]
        return
    assert later.outputs[model.ESTIMATE].text == model.ESTIMATE_PENDING_TEXT
    assert list(later.outputs) == list(now.outputs)  # the row keeps its place
    done = model.finish_estimate(later)
    assert done.pending_estimate is None and later.pending_estimate is not None  # a new solution
    assert _without_clock(done) == _without_clock(now)


def test_estimate_now_is_never_pending():
    assert all(model.solve(c, {}).pending_estimate is None for c in ("pneumatics", "gear_ratio"))
    assert model.solve("gear_ratio", {}, estimate="later").pending_estimate is None  # no estimate
    with pytest.raises(ValueError):
        model.solve("gear_ratio", {}, estimate="soon")


def test_a_card_solve_is_the_cli_solve(monkeypatch, capsys):
    from gearhead.tui import cli

    calls = []
    real = solving.solve
    monkeypatch.setattr(solving, "solve", lambda *a, **k: calls.append(a) or real(*a, **k))
    assert cli.main(["solve", "gear_ratio", "--set", "load=120", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert len(calls) == 1
    assert printed == real("gear_ratio", {"load": "120"}).solution.as_json()


def test_units_preference_and_chosen_units():
    solved = solving.solve("gear_ratio", {}, {"free_speed": "rad/s"}, "imperial")
    assert solved.units["free_speed"] == "rad/s"  # chosen beats the preference
    assert solved.solution.outputs["free_speed"].text.endswith("rad/s")
    assert solving.solve("gear_ratio", {}).units == {}


def test_dropped_tolerances_are_said_as_warnings():
    solved = solving.solve("gear_ratio", {"load": "150 ± 0"})
    assert solved.spread is None and solved.notes
    assert all(n in solved.solution.warnings for n in solved.notes)


def test_cancelled_is_raised_for_a_scene_and_for_tolerances():
    with pytest.raises(Cancelled):
        solving.solve("pneumatics", {}, cancelled=lambda: True)
    with pytest.raises(Cancelled):
        solving.solve("gear_ratio", {"load": "150 ± 10"}, cancelled=lambda: True)
    assert solving.solve("pneumatics", {}, cancelled=lambda: False).solution is not None


def test_no_context_variable_or_warm_up_changes_a_solve():
    """The estimate's deferral was a ContextVar and a process-wide set of scenes run once: both
    changed a solve out of sight. Only the integration budget remains a context (a `with` block)."""
    holders = []
    for path in CORE.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "ContextVar":
                holders.append(path.relative_to(CORE).as_posix())
    assert holders == ["sim/integrate.py"], holders
    from gearhead.core.sim import scene

    assert not hasattr(scene, "_WARMED") and not hasattr(scene, "deferred_estimate")
