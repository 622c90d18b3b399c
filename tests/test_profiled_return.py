"""The arm's return move (core.sim.profiled (P16), arm (AR13), issue 30 "Arms: the up and the down
move"): one profiled solve runs start → goal, then goal → start from rest at the goal with the same
gains and profile. Its figures must be those of a separate solve with start and goal swapped (the
same computation, so to 1e-12), a current limit that binds one way only must show in that way's
figures, and no entry may give NaN, inf or a traceback."""

import json
import math
import random

import pytest

from gearhead.core.calculators import arm as arm_calc
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import motion, profiled

RTOL = 1e-6
LIMITS = {
    "effects": "gravity, stator_limit, supply_limit, battery_sag, friction, counterbalance",
    "stator_current_limit": "60 A",
    "supply_current_limit": "40 A",
    "sensor_delay": "10 ms",
}
SWAPPABLE = {  # the profile does not depend on the direction: a swapped solve runs the same one
    "entered trapezoid, gravity": {"profile_limits": "entered"},
    "entered trapezoid, limits, sag, friction, spring": {**LIMITS, "profile_limits": "entered"},
    "exponential, entered gains": {
        "profile_type": "exponential",
        "max_input": "8 V",
        "feedback": "entered",
        "feedback_kp": "0.3 V/deg",
        "feedback_kd": "0.004 V*s/deg",
    },
    "down first, exponential, limits": {
        **LIMITS,
        "profile_type": "exponential",
        "start_angle": "100 deg",
        "goal_angle": "-45 deg",
    },
}


def _values(raw: dict) -> dict:
    v, _ = parse_inputs(get("arm"), {"mode": "profiled", **raw})
    return v


def _swapped(v: dict) -> dict:
    return {**v, "start_angle": v["goal_angle"], "goal_angle": v["start_angle"]}


def _assert_same(a: float, b: float, name: str) -> None:
    assert math.isfinite(a) and a == pytest.approx(b, rel=1e-12, abs=1e-12), name


@pytest.mark.parametrize("case", list(SWAPPABLE))
def test_return_is_the_swapped_solve(case):
    v = _values(SWAPPABLE[case])
    both = arm_calc.simulate(v, RTOL)
    swapped = arm_calc.simulate(_swapped(v), RTOL)
    present = [n for n in profiled.RETURN_FIGURES if n in swapped.values]
    assert {"overshoot", "final_error", "peak_stator_current", "energy"} <= set(present)
    for name in present:
        _assert_same(both.values[profiled.RETURN_PREFIX + name], swapped.values[name], name)
        # and the other way round: the swapped solve's return is this solve's first move
        _assert_same(swapped.values[profiled.RETURN_PREFIX + name], both.values[name], name)
    assert ("settle_time" in swapped.values) == (profiled.RETURN_PREFIX + "settle_time" in both.values)
    for series in ("position", "profile"):
        ts, ys = both.series[profiled.RETURN_PREFIX + series]
        ts2, ys2 = swapped.series[series]
        assert ts == ts2 and ys == ys2, series
    # the profile runs from the goal back to the start
    ys = both.series[profiled.RETURN_PREFIX + "profile"][1]
    assert ys[0] == pytest.approx(v["goal_angle"]) and ys[-1] == pytest.approx(v["start_angle"])
    # the first move's outputs are those of a one-way solve (run_profiled without the return), and
    # the work is the two one-way solves'
    one_way = _one_way(v)
    for name, value in one_way.values.items():
        assert both.values[name] == value, name
    assert both.nfev == one_way.nfev + _one_way(_swapped(v)).nfev


def _one_way(v: dict):
    s = arm_calc.setup(v)
    ff = motion.feedforward(s, 0.0)
    return profiled.run_profiled(s, v, RTOL, ff, lambda q: ff["kG"] * math.cos(q), arm=True)


def test_derived_limits_are_the_first_moves():
    """A derived trapezoid's acceleration is a fraction of the stall acceleration against the load at
    the start (M4), which differs the other way; the return keeps the first move's profile (one set
    of constraints in the robot code), so it equals a swapped solve with those limits entered, and
    not the swapped solve that derives its own."""
    v = _values({"arm_mass": "20 lb", "ratio": 60})
    both = arm_calc.simulate(v, RTOL)
    entered = {
        **_swapped(v),
        "profile_limits": "entered",
        "max_velocity": both.values["profile_max_velocity"],
        "max_acceleration": both.values["profile_max_acceleration"],
    }
    same = arm_calc.simulate(entered, RTOL)
    derived = arm_calc.simulate(_swapped(v), RTOL)
    assert derived.values["profile_max_acceleration"] > 1.05 * both.values["profile_max_acceleration"]
    for name in profiled.RETURN_FIGURES:
        if name in same.values:
            _assert_same(both.values[profiled.RETURN_PREFIX + name], same.values[name], name)
    assert derived.values["peak_tracking_error"] != pytest.approx(
        both.values[profiled.RETURN_PREFIX + "peak_tracking_error"], rel=1e-6
    )


# A 20 lb arm at 75:1 on the exponential profile at 6 V, -30° → 90°: with no limit the way down
# peaks at 294.7 A (braking into the bottom, gravity loading the brake) and the way up at 280.8 A.
DOWN_BITES = {
    "arm_mass": "20 lb",
    "ratio": 75,
    "start_angle": "-30 deg",
    "goal_angle": "90 deg",
    "profile_type": "exponential",
    "max_input": "6 V",
}


def test_stator_limit_bites_on_the_way_down_only():
    free = solve("arm", {"mode": "profiled", **DOWN_BITES, "effects": "gravity"})
    up, down = free.outputs["peak_stator_current"].value, free.outputs["return_peak_stator_current"].value
    assert up < down
    limit = (up + down) / 2
    sol = solve(
        "arm",
        {
            "mode": "profiled",
            **DOWN_BITES,
            "effects": "gravity, stator_limit",
            "stator_current_limit": f"{limit!r} A",
        },
    )
    out = {k: x.value for k, x in sol.outputs.items()}
    # the way up never reaches the limit: its figures are the unlimited move's, bit for bit
    for name in ("peak_stator_current", "settle_time", "overshoot", "energy"):
        assert out[name] == free.outputs[name].value, name
    # the way down is held at it (the loop's braking current too: the driver's mirrored bound)
    assert out["return_peak_stator_current"] == pytest.approx(limit, rel=1e-9)
    assert out["return_peak_stator_current"] < down * (1 - 1e-3)
    assert out["return_settle_time"] != free.outputs["return_settle_time"].value


def test_stator_limit_bites_on_the_way_up_only():
    """Vice versa: the default arm with a 30 A stator limit and a trapezoid derived from the limited
    stall acceleration: the way up (against gravity, friction) reaches 30 A, the way down not.
    (At 40 A both do: WPILib's ArmFeedforward (P5a) does not invert the plant, the feedback makes
    up the lag, and its kicks reach 40 A on the way down too.)"""
    raw = {
        "mode": "profiled",
        "effects": "gravity, stator_limit, friction",
        "stator_current_limit": "30 A",
        "acceleration_fraction": 0.3,
    }
    out = {k: x.value for k, x in solve("arm", raw).outputs.items()}
    assert out["peak_stator_current"] == pytest.approx(30.0, rel=1e-9)
    assert out["return_peak_stator_current"] < 30.0 * (1 - 1e-3)


def test_return_warnings_are_prefixed():
    """Tolerance too tight for both ways with no feedback: two 'does not settle' warnings, the second
    one said of the return move; and a return the motors cannot make is said, not a traceback."""
    raw = {"feedback": "entered", "feedback_kp": 0, "feedback_kd": 0, "settle_tolerance": "0.001 deg"}
    sol = solve("arm", {"mode": "profiled", **raw})
    unsettled = [w for w in sol.warnings if "does not settle" in w]
    assert len(unsettled) == 2
    assert not unsettled[0].startswith(profiled.RETURN_WARNING)
    assert unsettled[1].startswith(profiled.RETURN_WARNING)
    assert "settle_time" not in sol.outputs and "return_settle_time" not in sol.outputs

    # a spring lifting 140 N·m more than gravity at 10:1: up is easy, down is beyond stall
    cannot = solve(
        "arm",
        {
            "mode": "profiled",
            "effects": "gravity, counterbalance",
            "counterbalance_torque": "150 N*m",
            "ratio": 10,
        },
    )
    assert math.isfinite(cannot.outputs["settle_time"].value)
    assert not any(k.startswith(profiled.RETURN_PREFIX) for k in cannot.outputs)
    said = [w for w in cannot.warnings if w.startswith(profiled.RETURN_WARNING)]
    assert len(said) == 1 and "not simulated" in said[0] and "ratio" in said[0]


def test_return_outputs_and_plot_only_in_profiled_mode():
    move = solve("arm", {})
    assert not any(k.startswith(profiled.RETURN_PREFIX) for k in move.outputs)
    assert not any(k.startswith(profiled.RETURN_PREFIX) for k in move.series)
    prof = solve("arm", {"mode": "profiled"})
    for o in arm_calc.CALCULATOR.outputs:
        if o.name.startswith(profiled.RETURN_PREFIX):
            assert o.label.startswith("Return move: ")
            assert math.isfinite(prof.outputs[o.name].value), o.name
    plot = next(p for p in arm_calc.CALCULATOR.plots if p.title.startswith("Return move"))
    for name in plot.series:
        assert len(prof.series[name][0]) == prof.outputs["control_updates"].value + 1
    assert prof.series_label("return_position") == "position"


def _random_entry(rng: random.Random) -> dict:
    effects = ["gravity"] + [
        e
        for e in ("stator_limit", "supply_limit", "battery_sag", "friction", "counterbalance")
        if rng.random() < 0.5
    ]
    raw = {
        "mode": "profiled",
        "motor": rng.choice(["Kraken X60", "NEO", "Falcon 500", "NEO 550"]),
        "motor_count": rng.choice([1, 2]),
        "ratio": round(10 ** rng.uniform(0.7, 2.7), 3),
        "arm_mass": f"{rng.uniform(0.5, 40):.4g} lb",
        "com_distance": f"{rng.uniform(2, 40):.4g} in",
        "start_angle": f"{rng.uniform(-120, 120):.4g} deg",
        "goal_angle": f"{rng.uniform(-120, 120):.4g} deg",
        "effects": ", ".join(effects),
        "stator_current_limit": f"{rng.uniform(5, 120):.4g} A",
        "supply_current_limit": f"{rng.uniform(5, 80):.4g} A",
        "battery_resistance": f"{rng.uniform(0, 0.05):.4g} ohm",
        "friction_torque": f"{rng.uniform(0, 5):.4g} N*m",
        "counterbalance_torque": f"{rng.uniform(0, 100):.4g} N*m",
        "sensor_delay": f"{rng.uniform(0, 40):.4g} ms",
        "profile_type": rng.choice(["trapezoid", "exponential"]),
        "max_input": f"{rng.uniform(1, 12):.4g} V",
        "velocity_fraction": rng.uniform(0.05, 1),
        "acceleration_fraction": rng.uniform(0.05, 1),
        "settle_tolerance": f"{10 ** rng.uniform(-2, 1):.4g} deg",
    }
    if rng.random() < 0.3:
        raw.update(
            feedback="entered",
            feedback_kp=f"{10 ** rng.uniform(-3, 1):.4g} V/deg",
            feedback_kd="0.002 V*s/deg",
        )
    return raw


@pytest.mark.parametrize("seed", range(12))
def test_no_entry_gives_nan_or_a_traceback(seed):
    """Random arms both ways: either a refusal naming a field, or every output finite, JSON without
    NaN, and for each return figure missing a warning saying why."""
    rng = random.Random(1000 + seed)
    for _ in range(3):
        raw = _random_entry(rng)
        try:
            sol = solve("arm", raw)
        except InputError as exc:
            assert exc.field and exc.message
            continue
        for name, value in sol.outputs.items():
            assert math.isfinite(value.value), (name, raw)
        json.dumps(sol.as_json(), allow_nan=False)
        for xs, ys in sol.series.values():
            assert all(math.isfinite(x) for x in xs) and all(math.isfinite(y) for y in ys)
        if "return_energy" not in sol.outputs:
            assert any(w.startswith(profiled.RETURN_WARNING + "not simulated") for w in sol.warnings), raw
        if "return_settle_time" not in sol.outputs and "return_energy" in sol.outputs:
            assert any(w.startswith(profiled.RETURN_WARNING) and "settle" in w for w in sol.warnings), raw


@pytest.mark.parametrize(
    "raw",
    [
        {"profile_limits": "entered"},
        {
            **LIMITS,
            "effects": "gravity, stator_limit, supply_limit, battery_sag, friction",
            "profile_limits": "entered",  # derived limits are the first move's, a new solve derives its own
        },
        {"profile_type": "exponential", "max_input": "8 V", "travel": "-30 in"},
    ],
    ids=["entered trapezoid", "limits, sag, friction", "exponential, down first"],
)
def test_elevator_return_is_the_reversed_travel(raw):
    """The elevator's way back (EL15): nothing on a carriage depends on where it is, so the return
    from the goal is the solve of the opposite travel from 0, figure for figure, its profile shifted
    by the travel (to 1e-9: positions offset by the travel round differently, 7e-12 measured)."""
    from gearhead.core.calculators import elevator as elevator_calc

    v, _ = parse_inputs(get("elevator"), {"mode": "profiled", **raw})
    both = elevator_calc.simulate(v, RTOL)
    reverse = elevator_calc.simulate({**v, "travel": -v["travel"]}, RTOL)
    present = [n for n in profiled.RETURN_FIGURES if n in reverse.values]
    assert {"overshoot", "final_error", "peak_stator_current", "energy"} <= set(present)
    for name in present:
        a, b = both.values[profiled.RETURN_PREFIX + name], reverse.values[name]
        assert math.isfinite(a) and a == pytest.approx(b, rel=1e-9, abs=1e-12), name
    ts, ys = both.series[profiled.RETURN_PREFIX + "profile"]
    ts2, ys2 = reverse.series["profile"]
    assert ts == ts2
    assert [y - v["travel"] for y in ys] == pytest.approx(ys2, abs=1e-9)
    # gravity loads the carriage one way and helps it the other: the two ways differ
    assert both.values["return_energy"] != pytest.approx(both.values["energy"], rel=1e-3)
