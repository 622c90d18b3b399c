"""Units preference: every mapping keeps the dimension; each system shows what it says."""

import pytest

from gearhead.core import unit_systems, units
from gearhead.core.model import solve
from gearhead.core.registry import calculators, get


@pytest.mark.parametrize("table", [unit_systems.TO_METRIC, unit_systems.TO_IMPERIAL])
def test_every_mapping_keeps_the_dimension(table):
    ureg = units.registry()
    for a, b in table.items():
        assert ureg.Quantity(1, a).dimensionality == ureg.Quantity(1, b).dimensionality, (a, b)


def test_imperial_and_metric_leave_no_unit_of_the_other_system():
    metric_only = set(unit_systems.TO_IMPERIAL) - {"W", "J", "kJ"}  # W (and N*m … mapped) stay
    imperial_only = set(unit_systems.TO_METRIC)
    for calc in calculators().values():
        for system, foreign in (("imperial", metric_only), ("metric", imperial_only)):
            shown = unit_systems.display_units(calc, system, {})
            for o in calc.outputs:
                assert shown.get(o.name, o.unit) not in foreign, (calc.id, o.name, system)


def test_same_si_values_whatever_the_preference():
    calc = get("gear_ratio")
    base = solve("gear_ratio", {})
    for system in unit_systems.SYSTEMS:
        sol = solve("gear_ratio", {}, unit_systems.display_units(calc, system, {}))
        assert {k: v.value for k, v in sol.outputs.items()} == {k: v.value for k, v in base.outputs.items()}


def test_as_entered_uses_the_unit_typed_for_that_kind():
    calc = get("gear_ratio")
    entries = {"load": "180 N", "radius": "19 mm"}
    shown = unit_systems.display_units(calc, "as_entered", entries)
    lengths = [o.name for o in calc.outputs if o.quantity == "length" and o.unit]
    forces = [o.name for o in calc.outputs if o.quantity == "force" and o.unit]
    assert all(shown.get(n, "mm") == "mm" for n in lengths)
    assert all(shown.get(n, "N") == "N" for n in forces)
    assert unit_systems.typed_units(calc.fields, {"load": "180", "radius": "2*3 in"}) == {}


async def test_units_preference_in_the_app_is_remembered(tmp_path):
    from gearhead.tui import settings
    from gearhead.tui.app import GearheadApp
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="beam", settings_file={})
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.current_tab
        before = {k: v.value for k, v in tab.solution.outputs.items()}
        app.set_unit_system("metric")
        await settle(pilot)
        after = tab.solution.outputs
        assert {k: v.value for k, v in after.items()} == before
        assert all(not v.text.endswith((" in", " lbf", " psi", " in**4")) for v in after.values())
        shown = tab.shown_values()  # and the list on screen says so
        assert tab.results.state == "fresh" and shown
        assert all(not text.endswith((" in", " lbf", " psi", " in⁴")) for text in shown.values()), shown
    assert settings.load() == {"units": "metric"}
    again = GearheadApp(blink=False, initial="beam", settings_file=settings.load())
    async with again.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        assert again.current_tab.unit_system == "metric"
        deflection = again.current_tab.solution.outputs.get("deflection")
        assert deflection is None or deflection.text.split()[-1] in ("mm", "m")
