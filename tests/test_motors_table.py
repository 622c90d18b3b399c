"""The motor comparison (motors, issue 31): hand values from the data sheets' four figures, the motor
tab as an independent path to the same model, the sort, the curves, and the refusals."""

import json
import math
import subprocess
import sys

import pytest

from gearhead.core import motors
from gearhead.core.calculators import motors as table_calc
from gearhead.core.constants import LB, RPM
from gearhead.core.errors import InputError
from gearhead.core.model import solve


def rows(**inputs):
    sol = solve("motors", inputs)
    return sol, {r["motor"].value: {k: c.value for k, c in r.items()} for r in sol.tables["motors"]}


def test_every_motor_once():
    sol, by_name = rows()
    assert len(sol.tables["motors"]) == len(by_name) == len(motors.motor_names())
    assert sol.outputs["motors_listed"].value == len(motors.motor_names())


def test_kraken_x60_at_40_a_by_hand():
    # WPILib: 6000 rpm, 7.09 N·m, 366 A, 2 A. Kt = 7.09/364; at the 40 A stator limit, at rest:
    # τ = Kt·(40 − 2) = 0.74016... N·m; peak power 6000 rpm·7.09/4
    _, r = rows(source="wpilib", effects="stator_limit", stator_current_limit="40 A")
    k = r["Kraken X60"]
    assert k["limited_torque"] == pytest.approx(7.09 / 364 * 38, rel=1e-12)
    assert k["kt"] == pytest.approx(7.09 / 364, rel=1e-12)
    assert k["peak_power"] == pytest.approx(6000 * 2 * math.pi / 60 * 7.09 / 4, rel=1e-12)
    assert (k["free_speed"], k["stall_torque"], k["stall_current"]) == pytest.approx(
        (6000 * RPM, 7.09, 366), rel=1e-12
    )
    assert k["data"] == "WPILib" and "ratio" not in k


def test_half_voltage_scales_the_sheet_and_the_free_current():
    # 6 V: ω̃f 3000 rpm, τ̃s 3.545, ĩs 183, ĩf 1 (eqs. 1-4): τ at 40 A = 7.09/364·(40 − 1)
    _, r = rows(voltage="6 V", effects="stator_limit", stator_current_limit="40 A")
    k = r["Kraken X60"]
    assert k["limited_torque"] == pytest.approx(7.09 / 364 * 39, rel=1e-12)
    assert (k["free_speed"], k["stall_torque"], k["stall_current"]) == pytest.approx(
        (3000 * RPM, 3.545, 183), rel=1e-12
    )


def test_supply_limit_at_rest_by_hand():
    """At rest the supply current is u·I with I = u·V/R (R = 12/366): u·I = I²·R/V ≤ 30 A gives
    I = √(30·V/R) = √(30·366) A, and τ = Kt·(I − 2)."""
    _, r = rows(effects="supply_limit", supply_current_limit="30 A")
    I0 = math.sqrt(30 * 366)
    assert r["Kraken X60"]["limited_torque"] == pytest.approx(7.09 / 364 * (I0 - 2), rel=1e-12)
    # a motor whose stall current is below that draws its stall current: τ = τ̃s
    assert r["REV HD Hex"]["limited_torque"] == pytest.approx(0.105, rel=1e-12)


def test_no_limit_gives_the_stall_torque():
    _, r = rows(effects="")
    for name in ("Kraken X60", "CIM", "goBILDA Yellow Jacket 312 rpm", "Snowblower"):
        assert r[name]["limited_torque"] == pytest.approx(r[name]["stall_torque"], rel=1e-12)


def test_efficiency_within_the_limit_against_the_motor_tab():
    """(C6) below its peak: the motor tab's efficiency at the torque that draws exactly the limit
    (an independent path: eqs. 8-10 at τ = Kt·(I − ĩf)); above √(ĩf·ĩs), the tab's max efficiency."""
    _, r = rows(source="wpilib", effects="stator_limit", stator_current_limit="5 A")
    tau = 2.6 / (105 - 1.8) * (5 - 1.8)  # NEO, I = 5 A < √(1.8·105) = 13.7 A
    tab = solve("motor", {"motor": "NEO", "torque": f"{tau!r} N*m"})
    assert r["NEO"]["efficiency"] == pytest.approx(tab.outputs["efficiency_at_torque"].value, rel=1e-12)
    _, r = rows(source="wpilib", effects="stator_limit", stator_current_limit="40 A")
    tab = solve("motor", {"motor": "NEO", "torque": "1 N*m"})
    assert r["NEO"]["efficiency"] == pytest.approx(tab.outputs["max_efficiency"].value, rel=1e-12)


def test_efficiency_with_the_limit_below_the_free_current_is_zero():
    _, r = rows(effects="stator_limit", stator_current_limit="1 A")
    assert r["Kraken X60"]["efficiency"] == 0.0  # 1 A < 2 A free: the motor gives nothing


def test_geared_to_one_speed_by_hand():
    # G = 6000/500 = 12; 90 %: stall torque 0.9·12·7.09, at the 40 A limit 0.9·12·7.09/364·38
    _, r = rows(
        source="wpilib",
        gearing="same_speed",
        output_speed="500 rpm",
        efficiency=0.9,
        effects="stator_limit",
        stator_current_limit="40 A",
    )
    k = r["Kraken X60"]
    assert k["ratio"] == pytest.approx(12, rel=1e-12)
    assert k["free_speed"] == pytest.approx(500 * RPM, rel=1e-12)
    assert k["stall_torque"] == pytest.approx(0.9 * 12 * 7.09, rel=1e-12)
    assert k["limited_torque"] == pytest.approx(0.9 * 12 * 7.09 / 364 * 38, rel=1e-12)
    assert k["peak_power"] == pytest.approx(0.9 * 6000 * RPM * 7.09 / 4, rel=1e-12)
    assert k["efficiency"] == pytest.approx(0.9 * rows(effects="stator_limit")[1]["Kraken X60"]["efficiency"])


def test_power_density_and_mass_from_the_source_that_weighs_it():
    # Kraken X60, ReCalc: 6065 rpm, 7.157 N·m, 1.2 lb
    _, r = rows(source="recalc")
    k = r["Kraken X60"]
    assert k["mass"] == pytest.approx(1.2 * LB, rel=1e-12)
    assert k["power_density"] == pytest.approx(6065 * RPM * 7.157 / 4 / (1.2 * LB), rel=1e-12)
    # WPILib's data has no weights: the motor's mass is still the motor's
    _, r = rows(source="wpilib")
    assert r["Kraken X60"]["mass"] == pytest.approx(1.2 * LB, rel=1e-12)
    assert "power_density" not in r["REV HD Hex"] and "mass" not in r["Snowblower"]


@pytest.mark.parametrize("key", table_calc.SORTS)
def test_sorted_by_every_column(key):
    sol = solve("motors", {"sort_by": key, "effects": "stator_limit"})
    table = sol.tables["motors"]
    if key == "name":
        names = [r["motor"].value for r in table]
        assert names == sorted(names, key=str.casefold)
        return
    have = [r[key].value for r in table if key in r]
    assert have, key
    # the rows with the figure come first, then those without
    assert all(key in r for r in table[: len(have)]) and not any(key in r for r in table[len(have) :])
    assert have == sorted(have, reverse=key not in table_calc.ASCENDING)
    assert sol.outputs["first_motor"].value == table[0]["motor"].value


def test_curves_are_the_chosen_motors_limited():
    sol = solve(
        "motors",
        {
            "effects": "stator_limit",
            "stator_current_limit": "40 A",
            "curve_motor_1": "NEO",
            "curve_motor_2": "(none)",
            "curve_motor_3": "Thrifty Pulsar",
            "curve_motor_4": "(none)",
        },
    )
    assert sol.series_labels == {
        **{f"{w} 1": "NEO" for w in table_calc.CURVE_KINDS},
        **{f"{w} 3": "Thrifty Pulsar" for w in table_calc.CURVE_KINDS},
    }
    assert "torque 2" not in sol.series and "torque 4" not in sol.series
    by_name = {r["motor"].value: r for r in sol.tables["motors"]}
    ws, taus = sol.series["torque 1"]
    assert ws[0] == 0 and taus[0] == pytest.approx(by_name["NEO"]["limited_torque"].value, rel=1e-12)
    assert taus[-1] == pytest.approx(0, abs=1e-9)  # the last point is the zero-torque speed
    assert all(a >= b - 1e-12 for a, b in zip(taus, taus[1:]))  # never rises with speed
    # flat at the limit, then the unlimited line: at 90 % of free speed τ = τ̃s·(1 − 0.9)
    w90 = 0.9 * 5676 * RPM
    k = min(range(len(ws)), key=lambda i: abs(ws[i] - w90))
    assert taus[k] == pytest.approx(2.6 * (1 - ws[k] / (5676 * RPM)), rel=1e-9)


def test_a_limit_that_leaves_every_motor_nothing_names_the_field():
    with pytest.raises(InputError) as e:
        solve("motors", {"effects": "stator_limit", "stator_current_limit": "0 A"})
    assert e.value.field == "stator_current_limit"


def test_a_limit_some_motors_cannot_work_with_is_a_warning():
    sol = solve("motors", {"effects": "stator_limit", "stator_current_limit": "1 A"})
    assert any("No torque at rest" in w and "Kraken X60" in w for w in sol.warnings)
    by_name = {r["motor"].value: r for r in sol.tables["motors"]}
    assert by_name["Kraken X60"]["limited_torque"].value == 0.0
    assert by_name["V5 100 rpm (red)"]["limited_torque"].value > 0


def test_cli_json_gives_the_table():
    out = subprocess.run(
        [sys.executable, "-m", "gearhead.tui", "solve", "motors", "--json"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    data = json.loads(out)
    table = data["tables"]["motors"]
    assert len(table) == len(motors.motor_names())
    assert table[0]["peak_power"]["unit"] == "W" and table[0]["free_speed"]["unit"] == "rad/s"


def test_chart_csv_names_the_motors_not_the_slots():
    """Result.series_labels reaches the exported chart data (the legend uses the same label)."""
    from gearhead.core.export import plot_csv
    from gearhead.core.registry import get

    sol = solve("motors", {"curve_motor_1": "Kraken X60", "curve_motor_2": "(none)", "curve_motor_3": "NEO"})
    text = plot_csv(get("motors").plots[0], sol)
    first_column = {line.split(",")[0] for line in text.splitlines()[1:]}
    assert first_column == {"Kraken X60", "NEO", "Minion"}
    assert sol.series_label("torque 1") == "Kraken X60" and sol.series_label("other") == "other"
