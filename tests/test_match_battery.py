"""core/match/battery.py and the timeline's charge and energy: a constant current gives
Ah = I·t/3600 and the Peukert runtime; the energy balances, ∫V_oc·I dt = ∫V·I dt + ∫I²R dt."""

from __future__ import annotations

import pytest

from gearhead.core.errors import InputError
from gearhead.core.match.battery import OCV_TABLE, Battery
from gearhead.core.match.breaker import Breaker
from gearhead.core.match.brownout import Controller
from gearhead.core.match.bus import motor_terms
from gearhead.core.match.timeline import Load, Match, affine, constant_current, constant_power


def test_open_circuit_voltage_table_by_hand():
    """(M1): the default table (6·(SG + 0.84) at SG 1.150, 1.250, 1.280), linear between rows,
    held outside them."""
    assert OCV_TABLE == ((0.0, 11.94), (0.5, 12.54), (1.0, 12.72))
    b = Battery()
    assert b.ocv(1.0) == 12.72 and b.ocv(0.0) == 11.94
    assert b.ocv(0.75) == pytest.approx(12.63, rel=1e-15)
    assert b.ocv(0.25) == pytest.approx(12.24, rel=1e-15)
    assert b.ocv(-0.3) == 11.94 and b.ocv(1.2) == 12.72
    assert b.R == 0.015 and Battery(wiring_resistance=0.004).R == pytest.approx(0.019)


def test_peukert_runtime_by_hand():
    """(M4): t = H·(C/(I·H))^k h; 54 A (3C, the frc-docs figure) with k = 1.25: 0.11977 h."""
    b = Battery()
    assert b.runtime(54.0) == pytest.approx(20 * (18 / (54 * 20)) ** 1.25 * 3600, rel=1e-14)
    assert b.runtime(54.0) == pytest.approx(431.165, abs=0.001)
    assert b.runtime(0.9) == pytest.approx(20 * 3600, rel=1e-14)  # the rated current: 20 h
    assert Battery(peukert=1.0).runtime(54.0) == pytest.approx(1200.0, rel=1e-14)  # C/I
    assert b.peukert_rate(-5.0) == -5.0  # charging counts plain


def test_constant_current_charge_is_i_t_and_the_peukert_runtime_empties_the_battery():
    """A constant 54 A for the Peukert runtime: plain charge I·t/3600 Ah, the Peukert-weighted
    charge the whole 18 Ah, the end state of charge 0."""
    b = Battery()
    t = b.runtime(54.0)
    r = Match(
        battery=b, length=t, loads=(Load("load", constant_current(54.0), 0.0, t),), trace_step=1.0
    ).run()
    assert r.charge_ah == pytest.approx(54.0 * t / 3600, rel=1e-9)
    assert r.peukert_charge_ah == pytest.approx(18.0, rel=1e-9)
    assert r.end_available == pytest.approx(0.0, abs=1e-9)  # empty at 54 A
    # the open-circuit voltage follows the plain charge (M3): 6.4675 Ah of 18 drawn
    s = 1 - 54.0 * t / 3600 / 18
    assert r.end_soc == pytest.approx(s, rel=1e-9)
    assert s == pytest.approx(0.64070, abs=1e-5)  # on the upper row pair: 12.54 V + 0.36 V·(s − 0.5)
    assert r.end_ocv == pytest.approx(12.54 + (12.72 - 12.54) * (s - 0.5) / 0.5, rel=1e-9)
    assert r.brownouts == ()
    assert r.peak_current == 54.0 and r.rms_current == pytest.approx(54.0, rel=1e-9)
    assert r.shares == {"base": 0.0, "load": pytest.approx(1.0, rel=1e-12)}


def test_cell_energy_by_hand_and_the_balance():
    """A linear table 11 V → 13 V, k = 1, 10 A for 100 s: s = 1 − 10·t/64800, V_oc = 11 + 2s,
    E_oc = 10·(13·100 − 20·100²/(2·64800)) J; the bus gets V_oc − R·I, R burns I²R."""
    b = Battery(ocv_table=((0.0, 11.0), (1.0, 13.0)), peukert=1.0, resistance=0.02)
    r = Match(
        battery=b, length=100.0, loads=(Load("load", constant_current(10.0), 0.0, 100.0),), trace_step=1.0
    ).run()
    e_oc = 10 * (13 * 100 - 20 * 100**2 / (2 * 64800))
    assert r.energy_cells_wh * 3600 == pytest.approx(e_oc, rel=1e-10)
    assert r.energy_loss_wh * 3600 == pytest.approx(100 * 0.02 * 100, rel=1e-10)
    assert r.energy_bus_wh * 3600 == pytest.approx(e_oc - 200.0, rel=1e-10)
    assert r.end_soc == pytest.approx(1 - 1000 / 64800, rel=1e-12)


def test_energy_balance_with_motors_constant_power_and_brownouts():
    """∫V_oc·I dt = ∫V·I dt + ∫I²R dt to the solver's tolerance, over a match with affine (motor)
    loads, a constant-power load, a time-varying load and brownouts."""
    k_e, r_m = 12.0 / 628.3, 12.0 / 366.0
    loads = (
        Load(
            "drive",
            affine(*motor_terms(1.0, 150.0, k_e, r_m, 4)),
            1.0,
            4.0,
            breaker=Breaker(40.0, name="drive"),
        ),
        Load("shooter", constant_power(900.0), 2.0, 9.0),
        Load("arm", lambda t: (30.0 + 20.0 * (t - 5.0), 0.0, 0.0), 5.0, 7.0),
    )
    r = Match(
        battery=Battery(resistance=0.02),
        controller=Controller(dwell=0.05),
        length=12.0,
        base_load=3.0,
        loads=loads,
    ).run()
    assert r.brownouts  # the drive's 4 stalled-ish motors pull the bus under 6.75 V
    total = r.energy_cells_wh
    assert r.energy_bus_wh + r.energy_loss_wh == pytest.approx(total, rel=1e-8)
    assert r.energy_loss_wh > 0.01 * total
    assert sum(r.shares.values()) == pytest.approx(1.0, rel=1e-8)


@pytest.mark.parametrize(
    "field,kwargs",
    [
        ("battery.capacity_ah", {"capacity_ah": 0.0}),
        ("battery.capacity_ah", {"capacity_ah": float("nan")}),
        ("battery.peukert", {"peukert": 0.9}),
        ("battery.start_soc", {"start_soc": 1.5}),
        ("battery.resistance", {"resistance": -0.01}),
        ("battery.resistance", {"resistance": "0.015"}),
        ("battery.resistance", {"resistance": 0.0}),
        ("battery.ocv_table", {"ocv_table": ()}),
        ("battery.ocv_table", {"ocv_table": ((1.0, 12.0), (0.5, 12.5))}),
        ("battery.ocv_table[1].volts", {"ocv_table": ((0.0, 12.0), (0.5, float("inf")))}),
        ("battery.ocv_table[0]", {"ocv_table": ((0.0,),)}),
        ("battery.ocv_table", {"ocv_table": tuple((i / 2000, 12.0) for i in range(2000))}),
    ],
)
def test_a_wrong_battery_entry_is_named(field, kwargs):
    with pytest.raises(InputError) as e:
        Battery(**kwargs)
    assert e.value.field == field
