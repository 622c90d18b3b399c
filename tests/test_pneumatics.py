"""Pneumatics scene (seed section 10): closed forms, exact compressor time, effects and their cost."""

import math

import mpmath as mp
import pytest

from gearhead.core.calculators import pneumatics as pn
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get

PSI = 6894.757293168361
IN = 0.0254
NO_CYL = {"c1_count": 0}


def values(**raw):
    return parse_inputs(get("pneumatics"), raw)[0]


def test_forces_eqs_82_83():
    out = solve("pneumatics", {"c1_period": 0}).outputs  # one firing: never short of air (N4)
    assert out["push_force_1"].value == pytest.approx(math.pi * (1.5 * IN) ** 2 / 4 * 60 * PSI, rel=1e-12)
    assert out["pull_force_1"].value == pytest.approx(
        math.pi * ((1.5 * IN) ** 2 - (0.4375 * IN) ** 2) / 4 * 60 * PSI, rel=1e-12
    )
    assert out["push_force_1"].text == "106.03 lbf"


def test_no_compressor_is_closed_form_with_no_integration():
    raw = {"effects": "regulator", "c1_period": 20, "c1_start": 0}
    run = pn.simulate(values(**raw), 1e-6)
    assert run.nfev == 0
    V = 1148e-6
    A_push, A_pull = math.pi * (1.5 * IN) ** 2 / 4, math.pi * ((1.5 * IN) ** 2 - (0.4375 * IN) ** 2) / 4
    # push stroke: 2 cylinders x 347.5 cc at 60 psi out of 1148 cc is 18.16 psi (by hand)
    assert A_push * 6 * IN * 2 * 60 * PSI / V == pytest.approx(18.16 * PSI, rel=1e-3)
    P = 120 * PSI
    for _ in range(8):  # firings at 0, 20, ..., 140 s; (81) into (79) per stroke
        for A in (A_push, A_pull):
            P_cyl = 60 * PSI if 60 * PSI < P else P  # the regulator passes tank pressure below its setting
            P = max(P - P_cyl * A * 6 * IN * 2 / V, 0.0)
    assert run.values["final_pressure"] == pytest.approx(P, rel=1e-12)
    sol = solve("pneumatics", raw)
    assert sol.outputs["rhs_evaluations"].value == 0
    assert sol.outputs["error_estimate"].value == 0


def exact_fill_time(name, p0, p1, V):
    """∫ dP / (P_atm·V̇(P)/V) from p0 to p1, with mpmath (the inverse of the scene's ODE); V̇ is
    scipy's PchipInterpolator through the vendor table, split at its knots."""
    from scipy.interpolate import PchipInterpolator

    knots = [k * PSI for k in pn.CURVE_PSI]
    q = PchipInterpolator(knots, [c * pn.CFM for c in pn.COMPRESSORS[name]])
    pts = [p0] + [k for k in knots if p0 < k < p1] + [p1]
    return float(mp.quad(lambda p: V / (pn.P_ATM * float(q(float(p)))), pts))


@pytest.mark.parametrize("compressor", list(pn.COMPRESSORS))
def test_switch_off_time_matches_the_quadrature(compressor):
    raw = {**NO_CYL, "compressor_model": compressor, "start_pressure": "60 psi", "accuracy": "tight"}
    run = pn.simulate(values(**raw), 1e-11)
    t_on = run.values["compressor_duty"] * 150
    assert t_on == pytest.approx(exact_fill_time(compressor, 60 * PSI, 120 * PSI, 1148e-6), rel=1e-8)
    assert run.values["final_pressure"] == pytest.approx(120 * PSI, rel=1e-12)


def test_absolute_bookkeeping_uses_more_air_than_the_seeds_gauge():
    gauge = solve("pneumatics", {}).outputs["final_pressure"].value
    absolute = solve("pneumatics", {"pressure_model": "absolute"})
    assert absolute.outputs["final_pressure"].value < gauge


def test_unregulated_stroke_shares_air_exactly_in_absolute_mode():
    v = values(effects="", pressure_model="absolute", c1_period=0, c1_start=0)
    V = 1148e-6
    g = pn.groups(v)[0]
    P_abs = (120 * PSI + pn.P_ATM) * V / (V + g["A_push"] * 6 * IN * 2)
    P_abs = P_abs * V / (V + g["A_pull"] * 6 * IN * 2)
    assert pn.simulate(v, 1e-6).values["final_pressure"] == pytest.approx(P_abs - pn.P_ATM, rel=1e-13)


def test_tank_that_empties_warns_and_stays_finite():
    sol = solve(
        "pneumatics",
        {
            "effects": "compressor",
            "c1_count": 20,
            "c1_bore": "2 in",
            "c1_stroke": "12 in",
            "c1_period": 1,
            "c1_start": 0,
        },
    )
    assert sol.outputs["tank_empty"].value is True
    assert sol.outputs["min_pressure"].value == 0.0
    assert any("empties" in w for w in sol.warnings)


def test_effect_off_removes_its_cost():
    with_switch = pn.simulate(values(), 1e-6)
    no_comp = pn.simulate(values(effects="pressure_switch, regulator"), 1e-6)
    assert no_comp.nfev == 0 < with_switch.nfev


def test_seed_one_second_step_is_reported_beside_the_accurate_result():
    out = solve("pneumatics", {}).outputs
    assert out["seed_difference"].value == pytest.approx(
        out["seed_final_pressure"].value - out["final_pressure"].value, rel=1e-12
    )
    # the 1 s explicit step is close but not equal
    assert 0 < abs(out["seed_difference"].value) < 10 * PSI


def test_error_estimate_brackets_the_true_error():
    v = values(accuracy="coarse")
    rough = pn.simulate(v, 1e-3).key
    tight = pn.simulate(v, 1e-13).key
    true = max(abs(rough[k] - tight[k]) / abs(tight[k]) for k in rough)
    est = solve("pneumatics", {"accuracy": "coarse"}).outputs["error_estimate"].value
    assert true / 10 <= est <= true * 10


def test_bad_switch_settings_and_rods_name_fields():
    with pytest.raises(InputError) as e:
        solve("pneumatics", {"switch_on": "125 psi"})
    assert e.value.field == "switch_on"
    with pytest.raises(InputError) as e:
        solve("pneumatics", {"c1_rod": "2 in"})
    assert e.value.field == "c1_rod"


def test_values_typed_at_the_bounds_are_accepted():
    """'125 psi' parses to 125·PSI·(1 + 1 ulp), '1000000 cc' to 1.0000000000000002 m³: a value typed
    exactly at a bound the error message names must be accepted."""
    for name, typed in (
        ("start_pressure", "125 psi"),
        ("switch_off", "125 psi"),
        ("c1_push_pressure", "200 psi"),
        ("tank_volume", "1000000 cc"),
        ("tank_volume", "1 cc"),
    ):
        sol = solve("pneumatics", {name: typed})  # the bounds shown in the field's own error message
        assert math.isfinite(sol.outputs["final_pressure"].value)


def test_seed_step_matches_an_independent_loop():
    """The seed's scheme written out again: 1 s explicit steps of (79)-(80) from the numpy fit, firing (81)
    at 5, 15, ... s (2 cylinders, regulator: each stroke at min(60 psi, tank)), switch 95/120 psi."""
    import numpy as np

    c = np.polyfit(
        np.array(pn.CURVE_PSI) * PSI, np.array(pn.COMPRESSORS["VIAIR 90C 13.8 V"]) * 0.028316846592 / 60, 4
    )
    V, L = 1148e-6, 6 * IN
    A_push, A_pull = math.pi * (1.5 * IN) ** 2 / 4, math.pi * ((1.5 * IN) ** 2 - (0.4375 * IN) ** 2) / 4
    P, on, low = 120 * PSI, False, 120 * PSI
    for n in range(150):
        if on:
            P = min(P + max(np.polyval(c, P), 0.0) * 101325.0 / V, 120 * PSI)
        if n >= 5 and (n - 5) % 10 == 0:
            for A in (A_push, A_pull):
                P -= min(60 * PSI, P) * A * L * 2 / V
        low = min(low, P)
        on = (on and P < 120 * PSI) or P <= 95 * PSI
    out = solve("pneumatics", {}).outputs
    assert out["seed_min_pressure"].value == pytest.approx(low, rel=1e-12)  # 38.8496 psi
    assert out["seed_final_pressure"].value == pytest.approx(P, rel=1e-12)  # 52.5829 psi


def test_absolute_regulated_stroke_by_hand():
    """Absolute bookkeeping, regulated at 60 psi, one actuation from 120 psi: each stroke takes
    (60 psi + 1 atm)·A·L·2 of P·V. By hand: push 347.50 cc, pull 317.94 cc of 1148 cc, 74.696 psi abs:
    120 − 74.696·(347.50 + 317.94)/1148 = 76.70 psi."""
    v = values(effects="regulator", pressure_model="absolute", c1_period=0, c1_start=0)
    V, L = 1148e-6, 6 * IN
    A_push, A_pull = math.pi * (1.5 * IN) ** 2 / 4, math.pi * ((1.5 * IN) ** 2 - (0.4375 * IN) ** 2) / 4
    expected = 120 * PSI - (60 * PSI + 101325.0) * (A_push + A_pull) * L * 2 / V
    assert expected == pytest.approx(76.70 * PSI, rel=1e-4)
    assert pn.simulate(v, 1e-6).values["final_pressure"] == pytest.approx(expected, rel=1e-13)


@pytest.mark.parametrize("switch_on, runs", [(95, False), (105, True)])
def test_switch_closes_only_at_or_below_its_setting(switch_on, runs):
    """One regulated actuation of one 1.5 in x 6 in cylinder from 120 psi leaves
    120 − 60·(173.75 + 158.97)/1148 = 102.6 psi (by hand): above 95 psi the switch stays open (the
    pressure stays at 102.6 psi all match), below 105 psi it closes and the compressor refills to 120."""
    raw = {"c1_count": 1, "c1_period": 0, "c1_start": 10, "switch_on": f"{switch_on} psi"}
    A_push, A_pull = math.pi * (1.5 * IN) ** 2 / 4, math.pi * ((1.5 * IN) ** 2 - (0.4375 * IN) ** 2) / 4
    after = 120 * PSI - 60 * PSI * (A_push + A_pull) * 6 * IN / 1148e-6
    assert after == pytest.approx(102.6 * PSI, rel=1e-3)
    out = solve("pneumatics", raw).outputs
    if runs:
        assert out["final_pressure"].value == pytest.approx(120 * PSI, rel=1e-12)
        assert 0 < out["compressor_duty"].value < 1
    else:
        assert out["final_pressure"].value == pytest.approx(after, rel=1e-12)
        assert out["compressor_duty"].value == 0


def test_without_switch_the_compressor_runs_all_match_against_the_relief_valve():
    """No pressure switch: the motor never stops; the 125 psi relief valve holds the top. The seed's
    1 s scheme clamps at the same 125 psi."""
    out = solve("pneumatics", {**NO_CYL, "effects": "compressor", "start_pressure": "60 psi"}).outputs
    assert out["compressor_duty"].value == 1.0
    assert out["final_pressure"].value == pytest.approx(125 * PSI, rel=1e-12)
    assert out["seed_final_pressure"].value == pytest.approx(125 * PSI, rel=1e-12)


def test_no_switch_at_the_relief_pressure_holds_it_and_stays_finite():
    """No switch, cylinders that use no air (0 psi): after the tank reaches 125 psi each segment starts
    exactly at the relief pressure, where the rising 'full' event cannot fire. The pressure once climbed
    past the relief valve into the polynomial's rising tail and stopped with 'step size underflow'."""
    raw = {
        "effects": "compressor, regulator",
        "c1_push_pressure": 0,
        "c1_pull_pressure": 0,
        "start_pressure": "60 psi",
    }
    out = solve("pneumatics", raw).outputs
    assert out["final_pressure"].value == pytest.approx(125 * PSI, rel=1e-12)
    assert out["compressor_duty"].value == 1.0
    # and starting at the relief pressure the motor still runs (no switch to stop it)
    out = solve("pneumatics", {**NO_CYL, "effects": "compressor", "start_pressure": "125 psi"}).outputs
    assert out["compressor_duty"].value == 1.0


def test_error_estimate_is_not_zero_when_the_check_run_agrees_to_the_last_bit():
    """Here the runs at rtol 1e-3 and 1e-5 give bit-identical minimum and final pressures (the tank
    refills to the switch-off pressure, which resets the state, and the later segments take the same
    steps), so the 100x check reported an error of exactly 0 while the true error is ~1e-7."""
    raw = {
        "compressor_model": "AndyMark 1.1 12 V",
        "c1_count": 4,
        "c1_period": 7,
        "c2_count": 1,
        "c2_period": 2.5,
        "c2_start": 1,
        "accuracy": "coarse",
    }
    v = values(**raw)
    rough, tight = pn.simulate(v, 1e-3).key, pn.simulate(v, 1e-13).key
    true = max(abs(rough[k] - tight[k]) / abs(tight[k]) for k in rough)
    assert true > 1e-8
    est = solve("pneumatics", raw).outputs["error_estimate"].value
    assert true / 10 <= est <= true * 10


def test_no_regulator_warns_that_forces_are_at_the_entered_pressures():
    sol = solve("pneumatics", {"effects": "compressor, pressure_switch"})
    assert any("No regulator" in w for w in sol.warnings)
    assert not any("No regulator" in w for w in solve("pneumatics", {}).warnings)


SHORT_OF_AIR = {  # a 2 in bore, rod 2·√0.2 in (pull area 0.8 of push), 10 in stroke, 40π in³ tank
    "effects": "regulator",
    "tank_volume": f"{40 * math.pi!r} in**3",
    "start_pressure": "100 psi",
    "match_length": "25 s",
    "c1_count": 1,
    "c1_bore": "2 in",
    "c1_rod": f"{2 * math.sqrt(0.2)!r} in",
    "c1_stroke": "10 in",
    "c1_push_pressure": "60 psi",
    "c1_pull_pressure": "60 psi",
    "c1_period": "10 s",
    "c1_start": "0 s",
}


def test_a_group_short_of_its_working_pressure_is_named_with_the_time_and_its_forces():
    """Issue 28 item 5: storage below a group's working pressure, shown at the entered forces with no
    warning. By hand, (81) with the regulator at 60 psi: a push stroke takes 10π/40π = 0.25 of the
    tank's volume at its chamber pressure, a pull 0.2. Firings at 0, 10, 20 s:
      t = 0:  push 100 − 0.25·60 = 85, pull 85 − 0.2·60 = 73 psi
      t = 10: push 73 − 0.25·60 = 58, pull: the storage (58) is below 60, the chamber gets 58 psi:
              58 − 0.2·58 = 46.4 psi                                 ← first short stroke: t = 10 s
      t = 20: push chamber 46.4 psi, 46.4·0.75 = 34.8; pull chamber 34.8, 34.8·0.8 = 27.84 psi
    Lowest forces: push π·(1 in)²·46.4 psi = 145.77 lbf, pull 0.8·π·34.8 = 87.46 lbf (the entered
    60 psi gives 188.5 and 150.8 lbf)."""
    sol = solve("pneumatics", SHORT_OF_AIR)
    assert sol.outputs["final_pressure"].value == pytest.approx(27.84 * PSI, rel=1e-9)
    # issue 40: the forces shown are the lowest of the match (the warning gives the entered ones)
    assert sol.outputs["push_force_1"].value == pytest.approx(math.pi * IN**2 * 46.4 * PSI, rel=1e-9)
    assert sol.outputs["pull_force_1"].value == pytest.approx(0.8 * math.pi * IN**2 * 34.8 * PSI, rel=1e-9)
    (short,) = [w for w in sol.warnings if "short of air" in w]
    assert short.startswith(
        "Cylinder group 1 is short of air from t = 10 s: its pull stroke there ends at 58 psi"
    )
    push, pull = math.pi * 1**2 * 46.4, 0.8 * math.pi * 1**2 * 34.8  # in²·psi = lbf
    assert f"{push:.4g} lbf push and {pull:.4g} lbf pull" in short  # 145.8 and 87.46
    # storage never below 60 psi before a stroke: no warning (one firing, 100 → 85 → 73 psi)
    assert not any(
        "short of air" in w for w in solve("pneumatics", {**SHORT_OF_AIR, "match_length": "5 s"}).warnings
    )


def test_every_group_short_of_air_is_named():
    """Two groups at 60 psi whose storage falls to about 20 psi: each gets its own warning."""
    raw = {**SHORT_OF_AIR, "c2_count": 1, "c2_bore": "2 in", "c2_rod": "0.5 in", "c2_stroke": "5 in"}
    raw |= {
        "c2_push_pressure": "60 psi",
        "c2_pull_pressure": "60 psi",
        "c2_period": "10 s",
        "c2_start": "5 s",
    }
    sol = solve("pneumatics", raw)
    assert sol.outputs["min_pressure"].value < 25 * PSI
    groups = sorted(w.split(" is short")[0] for w in sol.warnings if "short of air" in w)
    assert groups == ["Cylinder group 1", "Cylinder group 2"]
