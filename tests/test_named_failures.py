"""A failure names the input that causes it (issue 34 item 4): the fuzz found "(result): could not
be computed" naming no field for a flywheel's spin-up ("step size underflow") and a trebuchet
(a division by zero)."""

import math

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


# The trebuchet's "(result): ... ZeroDivisionError": the swing eliminates the sling and a pendulum
# counterweight from the arm's equation (T6), dividing by M11 − Σ M1j²/Mjj, the arm's effective
# inertia. In closed form that is I + m_p·R²·sin²(γ−φ) (+ the pendulum's share): with the arm and
# counterweight's own inertia I below rounding of m_p·R² it came out 0 (C nearly on the level of
# the pivot at rest, the sling along the arm), or noise (an efficiency of 63 985 285 %).
ZERO_DIVISIONS = [
    # by hand: counterweight 1 g, 1 mm from the pivot, massless arm, 10 000 t projectile, 1 µm pivot
    dict(
        arm_length="1000",
        short_arm_fraction="1e-6",
        arm_mass="0",
        counterweight_mass="1e-3",
        counterweight_gyration="0",
        projectile_mass="1e7",
        pivot_height="1e-6",
    ),
    # the same, the projectile lifted at once (no ground contact)
    dict(
        arm_length="1000",
        short_arm_fraction="1e-6",
        arm_mass="0",
        counterweight_mass="1e-3",
        counterweight_gyration="0",
        projectile_mass="1e7",
        pivot_height="1e-6",
        effects="sling",
    ),
    # found by a fuzz drawing each field at its bounds (4 of 600 draws; the default projectile)
    dict(
        counterweight_mass="10000000.0",
        counterweight_gyration="0",
        arm_mass="0",
        arm_length="0.01",
        short_arm_fraction="1e-12",
        pivot_height="1e-12",
        gravity="0.49293260416809576",
        release_angle="2.4546825297136654",
        sling_length="0.01",
        effects="sling",
        accuracy="coarse",
    ),
    dict(
        counterweight_gyration="1.1328598500617867e-11",
        arm_mass="0",
        arm_length="7.212708229831064",
        short_arm_fraction="1e-12",
        pivot_height="1e-12",
        projectile_mass="10000000.0",
        release_angle="0",
        effects="sling, ground_contact",
        accuracy="fine",
    ),
    dict(
        counterweight_mass="0.001",
        counterweight_gyration="0",
        arm_mass="0",
        arm_length="0.06290207415388478",
        short_arm_fraction="1e-12",
        pivot_height="1e-12",
        sling_length="0.8842456375947066",
        hanger_length="0",
        drag_coefficient="1.3360199697037831",
        air_density="20",
        effects="sling, ground_contact, hinged_counterweight, air_drag",
        accuracy="coarse",
    ),
    # solved, with an efficiency of 2 253 % (the same noise, not zero): now refused too
    dict(
        counterweight_mass="0.001",
        arm_mass="0",
        arm_length="0.01",
        pivot_height="1e-12",
        projectile_mass="5522037.118939778",
        gravity="100",
        release_angle="0",
        sling_length="0.01",
        hanger_length="0",
        effects="sling, ground_contact, hinged_counterweight",
        accuracy="fine",
    ),
]


@pytest.mark.parametrize("entries", ZERO_DIVISIONS)
@pytest.mark.parametrize("mode", ["throw", "optimise"])
def test_a_trebuchet_whose_arm_loses_its_inertia_names_the_projectile_mass(entries, mode):
    with pytest.raises(InputError) as exc:
        solve("trebuchet", dict(entries, mode=mode))
    assert exc.value.field == "projectile_mass"
    assert "too heavy for this arm" in exc.value.message and "kg·m²" in exc.value.message


@pytest.mark.parametrize("effects", ["hinged_counterweight", "sling, hinged_counterweight"])
@pytest.mark.parametrize("arm_mass,gyration", [("0", "0"), ("1e-15", "0"), ("0", "1e-9")])
def test_a_near_massless_arm_with_a_point_counterweight_on_a_hanger_names_the_arm_mass(
    effects, arm_mass, gyration
):
    """After release such an arm has no inertia of its own when the hanger lies in line with it
    (upright arm, counterweight hanging under the pivot). Only an arm of exactly 0 kg with a
    gyration of exactly 0 was refused; 1e-15 kg gave "projectile_mass (or sling_length): the swing
    could not be integrated (step size underflow)" at a 45° release on a 2 m hanger."""
    raw = dict(effects=effects, hanger_length="2", release_angle="45", arm_mass=arm_mass)
    raw["counterweight_gyration"] = gyration
    with pytest.raises(InputError) as exc:
        solve("trebuchet", raw)
    assert exc.value.field == "arm_mass" and "in line with the arm" in exc.value.message


def test_the_least_inertia_is_the_swings_own_elimination_at_its_worst():
    """Machine.least_inertia in closed form equals the Schur denominator the swing computes (T6) with
    the sling along the arm and the hanger in line with it, for a machine where both are well
    resolved."""
    from gearhead.core.sim import trebuchet as tb

    p = tb.Machine(M=500, k=0.3, m=50, L=15, a=0.25, h=4, m_p=5, l=5, g=9.81, rigid=False, d=1.5)
    sc = tb.build(p, False)
    phi = 0.4
    _, _, den = sc.solve(phi, 0.0, [phi, 0.0, phi, 0.0, phi + math.pi / 2, 0.0])
    least, m11 = p.least_inertia()
    assert den == pytest.approx(least, rel=1e-12)
    assert m11 == pytest.approx(p.I_phi + p.m_p * p.R**2)
    assert p.released().least_inertia()[0] == pytest.approx(least)  # the sling took all of m_p·R²
    cup = tb.Machine(M=500, k=0.3, m=50, L=15, a=0.25, h=4, m_p=5, l=5, g=9.81, sling=False)
    assert cup.least_inertia() == (cup.I_phi + 5 * cup.R**2, cup.I_phi + 5 * cup.R**2)


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
