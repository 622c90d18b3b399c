"""The flywheel on the parts every calculator shares (issue 42 item 3): its current-limit grid
through core.sim.limit_grid, its stiff slip phase through core.sim.integrate.integrate_stiff, its
tables and heat maps given to SimRun as declared (not set on the run afterwards)."""

import dataclasses

import pytest

from gearhead.core.calculators import flywheel as fw
from gearhead.core.model import parse_inputs
from gearhead.core.registry import get
from gearhead.core.sim import limit_grid, scene, shooter

GRID = {
    "motor": "Kraken X60",
    "voltage": "12 V",
    "motor_count": 2,
    "ratio": 1.0,
    "mode": "moment_of_inertia",
    "wheel_inertia": "0.003 kg*m**2",
    "target_speed": "4000 rpm",
    "control": "limit_grid",
    "stator_min": "40 A",
    "stator_max": "70 A",
    "stator_step": "30 A",
    "supply_min": "30 A",
    "supply_max": "60 A",
    "supply_step": "30 A",
    "supply_budget": "45 A",
}


@dataclasses.dataclass
class SealedRun(scene.SimRun):
    """A SimRun that refuses any attribute set after construction (tables, heat maps included)."""

    def __post_init__(self):
        object.__setattr__(self, "_sealed", True)

    def __setattr__(self, name, value):
        if getattr(self, "_sealed", False):
            raise AttributeError(f"SimRun.{name} set after construction")
        object.__setattr__(self, name, value)


def values(raw):
    return parse_inputs(get("flywheel"), raw)[0]


def test_the_flywheel_grid_runs_through_limit_grid(monkeypatch):
    """The grid's axes, pick, table and heat map are limit_grid's: the flywheel gives its cells."""
    calls = []
    real = limit_grid.grid

    def spy(*args, **kwargs):
        calls.append(args[5] if len(args) > 5 else kwargs["cells"])
        return real(*args, **kwargs)

    monkeypatch.setattr(limit_grid, "grid", spy)
    run = fw.simulate(values(GRID), 1e-6)
    assert calls == [fw.grid_cells]
    assert run.values["grid_cells"] == 4 and "grid_spin_up_time" in run.values
    assert len(run.tables["limit_grid"]) == 4 and "limit_grid_time" in run.heat_maps


def test_tables_and_heat_maps_are_given_to_simrun_not_attached(monkeypatch):
    monkeypatch.setattr(fw, "SimRun", SealedRun)
    monkeypatch.setattr(limit_grid, "SimRun", SealedRun)
    run = fw.simulate(values(GRID), 1e-6)
    assert isinstance(run, SealedRun) and run.tables["limit_grid"] and run.heat_maps["limit_grid_time"]
    from gearhead.core.calculators import elevator

    ev = parse_inputs(get("elevator"), {"mode": "limit_grid"})[0]
    grid = elevator.simulate(ev, 1e-6)
    assert isinstance(grid, SealedRun) and grid.tables["limit_grid"]


def test_the_stiff_slip_phase_integrates_through_integrate_stiff(monkeypatch):
    """A wheel of 1e-9 lb·in² under a stator limit with the motor on during the shot: the slip
    phase is stiff, integrated by integrate_stiff's Radau (with the solve's budget), not scipy
    called directly."""
    methods = []
    real = shooter.integrate_stiff

    def spy(*args, **kwargs):
        methods.append(args[7])
        return real(*args, **kwargs)

    monkeypatch.setattr(shooter, "integrate_stiff", spy)
    from tests.test_limits_flywheel import raw

    v = values(
        raw(
            wheel_inertia="1e-9 lb*in**2",
            grip_force="100 N",
            effects="stator_limit, motor_during_shot",
            stator_current_limit="250 A",
        )
    )
    sc = fw.scene_from(v, 1e-10)[0]
    one = fw.shot(sc, 622.0, 0.2268, 622.0, 1e-10)
    assert methods == ["Radau"] and one.nfev > 0
    assert one.omega_after == pytest.approx(436.0158161592423, rel=1e-6)  # the closed form's ω*


def test_the_flywheel_documents_are_gains_codes():
    """The flywheel's documents come from gains_code's builder (as the elevator's and the arm's), its
    gains from gains_code's reading of a solution; the numbers live apart from the templates."""
    from gearhead.core import gains_code, gains_numbers

    want = gains_code.flywheel_documents(fw.gains_of)
    assert [(d.name, d.label, d.filename) for d in fw.DOCUMENTS] == [
        (d.name, d.label, d.filename) for d in want
    ]
    assert fw.gains_of is gains_numbers.velocity_loop_gains
    for name in ("phoenix6_values", "revlib_values", "flywheel_phoenix6_values", "export_number", "Gains"):
        assert getattr(gains_code, name) is getattr(gains_numbers, name), name  # re-exported, one copy
    assert not [n for n in vars(gains_numbers) if n.endswith("_java") or n.endswith("_python")]
