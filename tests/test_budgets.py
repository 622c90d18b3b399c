"""Every solve is bounded in work and memory, and its backstop counts the solve's own CPU time
(issue 34): a busy machine must not refuse a correct entry, and no input (extreme but accepted)
may run a solve, a tolerance spread, Monte Carlo or a preset parse past its budget."""

import itertools
import time

import pytest

from gearhead.core import presets
from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.sim import integrate

DRAG = presets.load(presets.builtin_dir() / "projectile" / "frc_2022_cargo_drag.toml")


# ---- the backstop counts CPU time of the solving thread -----------------------------------------


def test_a_busy_wall_clock_does_not_count_against_a_solve(monkeypatch):
    """200 solves at once on two cores: 40 of 40 projectile-with-drag solves were refused, "needs
    more than 30 s", though each needs 44 evaluations and 0.64 s of CPU alone. Here the wall clock
    jumps a minute at every look, as it would for a solve that waits its turn for the CPU."""
    real, looks = time.perf_counter, itertools.count()
    monkeypatch.setattr(time, "perf_counter", lambda: real() + 60.0 * next(looks))
    solution = solve("projectile", DRAG.inputs)
    assert solution.outputs["rhs_evaluations"].value > 0


def test_the_backstop_still_stops_a_solve_that_computes_too_long(monkeypatch):
    """The same backstop, now on the thread's CPU clock: a solve whose own computing passes it
    stops with a message naming what to change."""
    real, looks = integrate.cpu_clock, itertools.count()
    monkeypatch.setattr(integrate, "cpu_clock", lambda: real() + 60.0 * next(looks))
    with pytest.raises(InputError) as exc:
        solve("projectile", DRAG.inputs)
    assert "computing" in exc.value.message and exc.value.field != "(result)"


# ---- preset parsing --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text",
    [
        "a" + ".a" * 20_000 + " = 1\n",  # 40 KB: 7.6 s of tomllib, quadratic in the key's length
        "[" + "a" + ".a" * 40_000 + "]\n",  # 80 KB (1 MB, the cap, would take hours)
        'calculator = "beam"\n[inputs]\nx = {' + "a" + '."a"' * 20_000 + " = 1}\n",
    ],
    ids=["key-40KB", "header-80KB", "inline-quoted-100KB"],
)
def test_a_long_dotted_key_is_refused_before_tomllib_reads_it(text):
    with pytest.raises(InputError) as exc:
        presets.parse_text(text, "deep.toml")
    assert exc.value.field == "preset" and "dotted name" in exc.value.message
    assert "line 1" in exc.value.message or "line 3" in exc.value.message


def test_dotted_keys_a_preset_may_use_still_read():
    text = 'calculator = "beam"\nname = "x"\ninputs.wall = "0.1 in"\n"inputs"."force" = "5 lbf"\n'
    assert presets.parse_text(text)["inputs"] == {"wall": "0.1 in", "force": "5 lbf"}
