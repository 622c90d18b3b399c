"""No input a user can type makes any calculator produce NaN, inf or a traceback.

Generated entries: zeros, negatives, huge and tiny magnitudes, junk text, foreign units.
The only acceptable failure is an InputError naming a real field (never the "(result)" guard).
"""

import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearhead.core.errors import InputError
from gearhead.core.model import solve
from gearhead.core.registry import calculators

CALC_IDS = list(calculators())

numbers = st.one_of(
    st.sampled_from([0, -0.0, 1, -1, 1e-300, -1e-300, 1e-12, 1e12, 1e300, -1e300, 0.5, 2, 3]),
    st.floats(allow_nan=False, allow_infinity=False),
    st.integers(min_value=-(10**6), max_value=10**6),
)
junk = st.sampled_from(
    [
        "",
        " ",
        "abc",
        "nan",
        "inf",
        "-inf",
        "1e999",
        "5 parsecs/",
        "3 kg",
        "2 psi",
        "(",
        "1/0",
        "0 m",
        "7 in",
        "12 ft/s",
        "45 deg",
        "100 rpm",
        "10 %",
        "1e-320",
    ]
)


def field_value(f):
    if f.kind.numeric:  # quantities and whole numbers
        return st.one_of(numbers, numbers.map(str), junk, st.sampled_from(["2.5", "x", "1e400"]))
    words = f.kind.vocabulary(f)  # choice and flag names, yes/no words...
    return st.one_of(
        st.sampled_from(words),
        st.lists(st.sampled_from(words), unique=True).map(", ".join),
        st.booleans(),
        st.sampled_from(["not-a-choice", "warp_drive", "maybe"]),
    )


def inputs_for(calc):
    return st.fixed_dictionaries({}, optional={f.name: field_value(f) for f in calc.fields})


def check(calc_id, raw):
    calc = calculators()[calc_id]
    try:
        sol = solve(calc_id, raw)
    except InputError as exc:
        assert exc.field in {f.name for f in calc.fields} | {"mode"}, str(exc)
        return
    for name, out in sol.outputs.items():
        if isinstance(out.value, float):
            assert math.isfinite(out.value), (name, raw)
            assert "nan" not in out.text.lower() and "inf" not in out.text.lower(), (name, out.text)


@pytest.mark.parametrize("calc_id", CALC_IDS)
def test_defaults_solve_cleanly(calc_id):
    sol = solve(calc_id, {})
    assert sol.outputs, "a calculator with defaults must produce outputs"
    for out in sol.outputs.values():
        if isinstance(out.value, float):
            assert math.isfinite(out.value)


@pytest.mark.parametrize("calc_id", CALC_IDS)
def test_generated_inputs_never_give_nan_or_traceback(calc_id):
    calc = calculators()[calc_id]

    @settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck))
    @given(inputs_for(calc))
    def run(raw):
        check(calc_id, raw)

    run()


@pytest.mark.parametrize("calc_id", CALC_IDS)
def test_every_mode_with_extreme_single_entries(calc_id):
    """Each field alone at each extreme, in every mode."""
    calc = calculators()[calc_id]
    modes = calc.modes or (None,)
    extremes = [0, -1, 1e-300, 1e300, "1e-9", "1e9"]
    for mode in modes:
        base = {"mode": mode} if mode else {}
        for f in calc.fields:
            if f.kind.numeric:
                for x in extremes:
                    check(calc_id, {**base, f.name: x})
