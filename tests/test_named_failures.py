"""A failure names the input that causes it (issue 34 item 4): the fuzz found "(result): could not
be computed" naming no field for a flywheel's spin-up ("step size underflow") and a trebuchet
(a division by zero)."""

import pytest

from gearhead.core import presets
from gearhead.core.errors import InputError
from gearhead.core.model import solve

KRAKENS = presets.load(presets.builtin_dir() / "flywheel" / "frc_two_kraken_limits.toml").inputs


@pytest.mark.parametrize(
    "mode,field,entries",
    [
        ("moment_of_inertia", "wheel_inertia", {"wheel_inertia": "1e-9 lb*in**2"}),
        ("radius_of_gyration", "wheel_mass", {"wheel_mass": "1e-6 g", "gyration_fraction": 0.84}),
    ],
)
@pytest.mark.parametrize(
    "effects", ["stator_limit", "stator_limit, supply_limit, battery_sag, motor_during_shot"]
)
def test_a_flywheel_too_light_to_simulate_names_its_inertia(mode, field, entries, effects):
    """A wheel of 3e-13 kg·m² with a stator limit at accuracy=tight: the spin-up (1e-10 s) fell
    below the integrator's smallest step: "(result): ... RuntimeError: step size underflow"."""
    raw = dict(KRAKENS, mode=mode, ratio="1", accuracy="tight", effects=effects, rotor_inertia="0", **entries)
    with pytest.raises(InputError) as exc:
        solve("flywheel", raw)
    assert exc.value.field == field and "too small to simulate" in exc.value.message


def test_a_flywheel_with_its_rotors_inertia_still_solves():
    raw = dict(KRAKENS, mode="moment_of_inertia", wheel_inertia="1e-9 lb*in**2", ratio="1")
    raw.update(accuracy="tight", effects="stator_limit", rotor_inertia="1e-9 kg*m**2")
    assert solve("flywheel", raw).outputs["spin_up_time"].value > 0


# ---- warnings that were missing (issue 34 item 6) ---------------------------------------------

ARM = presets.load(presets.builtin_dir() / "arm" / "single_kraken.toml").inputs


@pytest.mark.parametrize("preset", ["single_kraken.toml", "two_kraken_limits_sag.toml"])
def test_an_arm_braking_above_its_stator_limit_says_so(preset):
    """A 90° → −90° swing with a 5 A stator limit peaked at 7.8 A (the load back-drives the motor
    past its free speed) with no warning."""
    inputs = presets.load(presets.builtin_dir() / "arm" / preset).inputs
    raw = dict(inputs, effects="gravity, stator_limit", stator_current_limit="5 A")
    raw.update(start_angle="90 deg", goal_angle="-90 deg")
    solution = solve("arm", raw)
    assert solution.outputs["peak_stator_current"].value > 5
    (warning,) = [w for w in solution.warnings if "above the stator current limit" in w]
    assert "back-drives" in warning and "5 A" in warning


def test_an_arm_within_its_stator_limit_has_no_such_warning():
    raw = dict(ARM, effects="gravity, stator_limit", stator_current_limit="40 A")
    solution = solve("arm", raw)
    assert solution.outputs["peak_stator_current"].value <= 40
    assert not any("above the stator current limit" in w for w in solution.warnings)


def test_an_elevator_lowered_by_its_load_past_the_stator_limit_says_so():
    elevator = presets.load(presets.builtin_dir() / "elevator" / "two_neo.toml").inputs
    raw = dict(elevator, effects="gravity, stator_limit", stator_current_limit="5 A", travel="-40 in")
    solution = solve("elevator", dict(raw, load_mass="60 lb"))
    assert solution.outputs["peak_stator_current"].value > 5
    assert any("above the stator current limit" in w for w in solution.warnings)


def test_a_trebuchet_efficiency_above_100_percent_is_flagged_as_the_solvers_error():
    """The fuzz found 100.69 % at accuracy=coarse with no warning: the energy balance (C2) cannot
    exceed 1, so above it the figure is the integration error. Here a release whose kinetic energy
    is 1 % more than the counterweight and arm gave, as a coarse solve can report it."""
    from types import SimpleNamespace

    from gearhead.core.calculators.trebuchet import release_and_flight

    p = SimpleNamespace(m_p=1.0, g=10.0, M=10.0, m=0.0)
    s = SimpleNamespace(release=(0.5, 0.0, 0.0, -20.1, 0.0), path=([0.0], [0.0]), cw_drop=2.0, arm_drop=0.0)
    values, warnings = {}, []
    release_and_flight({}, p, s, 1e-3, values, {}, warnings, ([], []))
    assert values["efficiency"] == pytest.approx(0.5 * 20.1**2 / 200)
    (warning,) = [w for w in warnings if "efficiency" in w]
    assert "101 %" in warning and "finer accuracy" in warning


def test_the_built_in_trebuchets_have_no_such_warning():
    for p in presets.listing("trebuchet"):
        solution = solve("trebuchet", dict(p.inputs, accuracy="coarse"))
        assert solution.outputs["efficiency"].value <= 1
        assert not any("above 100 %" in w for w in solution.warnings)
