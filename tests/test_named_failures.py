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
