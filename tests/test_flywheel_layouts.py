"""Flywheel layouts with a secondary wheel (issue 31): dual, compound, hood with a secondary wheel,
and a ball entering moving. Hand values solve the impulse and energy balances from their primitive
equations with mpmath (not the module's closed forms); ReCalc v2's shot model (tervay/recalc
app/lib/math/ballShot.ts, commit 03511cb4) is ported below as an independent oracle, on its own
defaults (app/routes/flywheel.tsx) and on the Team 449 spreadsheet case of its tests."""

import math
from pathlib import Path

import mpmath as mp
import pytest

from gearhead.core import presets
from gearhead.core.errors import InputError
from gearhead.core.model import solve

ROOT = Path(__file__).resolve().parents[1]
LB, IN = 0.45359237, 0.0254
RPM = 2 * math.pi / 60


def out(**raw):
    return solve("flywheel", raw).outputs


# --- ReCalc v2's ballShot.ts, ported line by line (rawSingleHooded, rawDualShooter, compound) ---
def recalc_single(w, rW, iW, mB, rB, iB, vBi=0.0, wBi=0.0):
    D = 4 * iW * rB * rB + iB * rW * rW + mB * rW * rW * rB * rB
    wf = (4 * iW * rB * rB * w + 2 * iB * rW * rB * wBi + 2 * mB * rW * rB * rB * vBi) / D
    v = rW / 2 * wf
    return wf, v, v / rB


def recalc_dual(w, rW1, iW, mB, rB, iB, rW2, G, vBi=0.0, wBi=0.0):
    A, B = rW1 + G * rW2, rW1 - G * rW2
    D = 4 * iW + B * B * iB / (rB * rB) + A * A * mB
    wf = (4 * iW * w + 2 * B * iB / rB * wBi + 2 * A * mB * vBi) / D
    return wf, A / 2 * wf, B / (2 * rB) * wf


def recalc_compound(w, rW1, iW, mB, rB, iB, rW2, G, vBi=0.0, wBi=0.0):
    one = recalc_single(w, rW1, iW, mB, rB, iB, vBi, wBi)
    return recalc_dual(one[0], rW1, iW, mB, rB, iB, rW2, G, one[1], one[2])


def recalc_energy(mB, iB, shot):
    return 0.5 * mB * shot[1] ** 2 + 0.5 * iB * shot[2] ** 2


# ReCalc v2's defaults (app/routes/flywheel.tsx DEFAULT_PARAMS): two Kraken X60 (FOC) at 1:1, shooter
# 4 in, 1 lb, I = m·r²/2; secondary 4 in, 1 lb, 1:1; ball 5 in, 0.5 lb, I_b = 2/5·m·r²; 3000 rpm.
RECALC_DEFAULTS = dict(
    mode="moment_of_inertia",
    wheel_diameter="4 in",
    wheel_inertia="2 lb*in**2",  # 1 lb·(2 in)²/2
    secondary_diameter="4 in",
    secondary_inertia="2 lb*in**2",
    ratio=1,
    secondary_ratio=1,
    ball_diameter="5 in",
    ball_mass="0.5 lb",
    ball_inertia_factor=0.4,
    target_speed="3000 rpm",
    motor="Kraken X60 FOC",
    motor_count=2,
    voltage="12 V",
    transfer="momentum",
    effects="",
)
R_W, I_W = 2 * IN, LB * (2 * IN) ** 2 / 2
M_B, R_B = 0.5 * LB, 2.5 * IN
I_B = 0.4 * M_B * R_B**2
W_0 = 3000 * RPM


@pytest.mark.parametrize(
    "shooter,recalc",
    [
        ("hood", lambda: recalc_single(W_0, R_W, I_W, M_B, R_B, I_B)),
        ("dual", lambda: recalc_dual(W_0, R_W, 2 * I_W, M_B, R_B, I_B, R_W, 1.0)),
        ("compound", lambda: recalc_compound(W_0, R_W, 2 * I_W, M_B, R_B, I_B, R_W, 1.0)),
    ],
)
def test_recalc_v2_defaults_agree(shooter, recalc):
    o = out(**RECALC_DEFAULTS, shooter=shooter)
    want = recalc()
    assert o["wheel_speed_after"].value == pytest.approx(want[0], rel=1e-12)
    assert o["ball_speed"].value == pytest.approx(want[1], rel=1e-12)
    assert o["ball_spin"].value == pytest.approx(want[2], rel=1e-12, abs=1e-12)
    assert o["ball_energy"].value == pytest.approx(recalc_energy(M_B, I_B, want), rel=1e-12)


def test_recalc_v2_defaults_by_hand():
    """Dual, 1:1 equal wheels: A = 2·r_w, B = 0 ⇒ ω₁ = 4I·ω₀/(4I + 4·r_w²·m) with I = 2·I_w, no spin;
    by hand: I_w = 0.45359·0.0508²/2 = 5.8528e-4 kg·m², m·r_w² = 0.22680·0.0508² = 5.8528e-4, so
    ω₁ = ω₀·2/3 (the wheels' inertia is twice m·r_w²): 2000 rpm, V = r_w·ω₁ = 10.6395 m/s."""
    o = out(**RECALC_DEFAULTS, shooter="dual")
    assert o["wheel_speed_after"].value == pytest.approx(2000 * RPM, rel=1e-12)
    assert o["ball_speed"].value == pytest.approx(0.0508 * 2000 * RPM, rel=1e-12)
    assert o["ball_speed"].value == pytest.approx(10.6395, abs=5e-5)
    assert o["ball_spin"].value == 0


def test_team_449_compound_spreadsheet_case():
    """ReCalc's ballShot.test.ts 'compound' case, from the Team 449 whitepaper's spreadsheet:
    r_w1 = 0.0508, r_w2 = 0.0127 m, I = 0.006643 kg·m², G₂₁ = 3, ω₀ = 150 rad/s, m_b = 0.226796 kg,
    r_b = 0.075057 m, I_b = 5.111e-4 kg·m² ⇒ ω₁ ≈ 141.80 rad/s, V ≈ 6.303 m/s, ω_b ≈ 11.997 rad/s."""
    k_b = 5.111e-4 / (0.226796 * 0.075057**2)
    o = out(
        mode="moment_of_inertia",
        wheel_diameter="0.1016 m",
        wheel_inertia=f"{0.006643 - 9 * 1e-4!r} kg*m**2",  # + 3²·1e-4 of the secondary = 0.006643
        secondary_diameter="0.0254 m",
        secondary_inertia="1e-4 kg*m**2",
        ratio=0.04,
        secondary_ratio=0.04 / 3,
        ball_diameter="0.150114 m",
        ball_mass="0.226796 kg",
        ball_inertia_factor=k_b,
        target_speed="150 rad/s",
        transfer="momentum",
        shooter="compound",
    )
    assert o["wheel_speed_after"].value == pytest.approx(141.80, abs=0.005)
    assert o["ball_speed"].value == pytest.approx(6.303, abs=5e-4)
    assert o["ball_spin"].value == pytest.approx(11.997, abs=5e-4)
    want = recalc_compound(150, 0.0508, 0.006643, 0.226796, 0.075057, 5.111e-4, 0.0127, 3)
    assert o["wheel_speed_after"].value == pytest.approx(want[0], rel=1e-12)
    assert o["ball_speed"].value == pytest.approx(want[1], rel=1e-12)


# A dual shooter from the seed's parts: VEX 5 in bottom wheel (180 g, k = 0.84), a 3 in top wheel
# (100 g, k = 0.7) geared 2x faster (its surface 1.2x the bottom's: backspin), the seed's ball.
DUAL = dict(
    wheel_diameter="5 in",
    wheel_mass="180 g",
    secondary_diameter="3 in",
    secondary_mass="100 g",
    secondary_gyration_fraction=0.7,
    ratio=0.04,
    secondary_ratio=0.02,
    ball_diameter="4 in",
    ball_mass="60 g",
    target_speed="2000 rpm",
    shooter="dual",
)
mp.mp.dps = 40
R1, R2, G21 = mp.mpf(2.5) * mp.mpf(IN), mp.mpf(1.5) * mp.mpf(IN), mp.mpf(2)
I_DUAL = mp.mpf("0.18") * (mp.mpf("0.84") * R1) ** 2 + G21**2 * mp.mpf("0.1") * (mp.mpf("0.7") * R2) ** 2
M, RB = mp.mpf("0.06"), 2 * mp.mpf(IN)
IB = mp.mpf("0.4") * M * RB**2
W0 = 2000 * 2 * mp.pi / 60


def no_slip(w1):
    """V + r_b·ω_b = r₁·ω₁ (bottom), V − r_b·ω_b = G₂₁·r₂·ω₁ (top)."""
    return (R1 + G21 * R2) * w1 / 2, (R1 - G21 * R2) * w1 / (2 * RB)


def test_dual_momentum_from_the_impulse_equations():
    """Unknowns ω₁, V, ω_b, J₁, J₂: wheels I·(ω₀ − ω₁) = r₁·J₁ + G₂₁·r₂·J₂, ball m·V = J₁ + J₂,
    I_b·ω_b = r_b·(J₁ − J₂), and the two no-slip conditions, solved as one linear system."""
    A = mp.matrix(
        [
            [I_DUAL, 0, 0, R1, G21 * R2],
            [0, M, 0, -1, -1],
            [0, 0, IB, -RB, RB],
            [-R1, 1, RB, 0, 0],
            [-G21 * R2, 1, -RB, 0, 0],
        ]
    )
    w1, V, wb, J1, J2 = mp.lu_solve(A, mp.matrix([I_DUAL * W0, 0, 0, 0, 0]))
    assert 0 < J1 < J2 and wb < 0  # the faster top surface pushes harder: backspin
    o = out(**DUAL, transfer="momentum")
    assert o["wheel_speed_after"].value == pytest.approx(float(w1), rel=1e-12)
    assert o["ball_speed"].value == pytest.approx(float(V), rel=1e-12)
    assert o["ball_spin"].value == pytest.approx(float(wb), rel=1e-12)
    assert o["ball_spin"].value < 0
    assert o["secondary_speed"].value == pytest.approx(2 * float(W0), rel=1e-12)


def test_dual_energy_from_the_energy_balance():
    """½·I·ω₀² = ½·I·ω₁² + ½·m·V² + ½·I_b·ω_b², V and ω_b from the no-slip conditions (root-found)."""

    def balance(w1):
        V, wb = no_slip(w1)
        return I_DUAL * (W0**2 - w1**2) - M * V**2 - IB * wb**2

    w1 = mp.findroot(balance, W0 * 0.9)
    V, wb = no_slip(w1)
    o = out(**DUAL, transfer="energy")
    assert o["wheel_speed_after"].value == pytest.approx(float(w1), rel=1e-12)
    assert o["ball_speed"].value == pytest.approx(float(V), rel=1e-12)
    assert o["ball_energy"].value == pytest.approx(float((M * V**2 + IB * wb**2) / 2), rel=1e-12)
    # (6) with σ = c²: E_b/E_w,final
    assert o["energy_ratio"].value == pytest.approx(
        float((M * V**2 + IB * wb**2) / (I_DUAL * w1**2)), rel=1e-12
    )


@pytest.mark.parametrize("transfer", ["energy", "momentum"])
def test_dual_with_the_secondary_still_is_the_hood(transfer):
    """G₂₁ → 0 (secondary ratio 1e4, G₂₁ = 4e-6): the ball between a wheel and a still one is the hood."""
    dual = out(**{**DUAL, "secondary_ratio": 1e4}, transfer=transfer)
    hood = out(**{**DUAL, "shooter": "hood"}, transfer=transfer)
    for name in ("wheel_speed_after", "ball_speed", "ball_spin", "range_error"):
        assert dual[name].value == pytest.approx(hood[name].value, rel=2e-5)


@pytest.mark.parametrize("transfer", ["energy", "momentum"])
def test_dual_of_equal_wheels_at_one_speed_is_the_two_wheel_shooter(transfer):
    same = {
        **DUAL,
        "secondary_diameter": "5 in",
        "secondary_mass": "180 g",
        "secondary_gyration_fraction": 0.84,
    }
    dual = out(**{**same, "secondary_ratio": 0.04}, transfer=transfer)
    pair = out(**{**same, "shooter": "two_wheel", "wheel_count": 2}, transfer=transfer)
    for name in ("wheel_speed_after", "ball_speed", "ball_energy", "range_error", "spin_up_time"):
        assert dual[name].value == pytest.approx(pair[name].value, rel=1e-12)
    assert dual["ball_spin"].value == 0


def test_compound_lossless_energy_is_the_dual_energy():
    """(D6): energy is path independent, so two sections end where one does, with the energy
    model's proportional loss f too (E_b = (1 − f)·(E_w0 − E_w1) summed over the sections)."""
    c = out(**{**DUAL, "shooter": "compound"}, transfer="energy")
    d = out(**DUAL, transfer="energy")
    for name in ("wheel_speed_after", "ball_speed", "ball_spin", "range_error_linear"):
        assert c[name].value == pytest.approx(d[name].value, rel=1e-12)
    lossy = {"loss_fraction": "10 %", "transfer": "energy"}
    c, d = out(**{**DUAL, "shooter": "compound"}, **lossy), out(**DUAL, **lossy)
    assert c["ball_speed"].value == pytest.approx(d["ball_speed"].value, rel=1e-12)
    # the momentum model is not path independent: the hood section's slip loses energy first
    c, d = out(**{**DUAL, "shooter": "compound"}, transfer="momentum"), out(**DUAL, transfer="momentum")
    assert c["ball_energy"].value != pytest.approx(d["ball_energy"].value, rel=1e-6)


def test_compound_momentum_by_hand_sections():
    """Hood section then the pair, each from its impulse equations (mpmath linear solves)."""
    A = mp.matrix(
        [[I_DUAL, 0, 0, R1, 0], [0, M, 0, -1, -1], [0, 0, IB, -RB, RB], [-R1, 1, RB, 0, 0], [0, 1, -RB, 0, 0]]
    )
    wm, Vm, wbm, _, _ = mp.lu_solve(A, mp.matrix([I_DUAL * W0, 0, 0, 0, 0]))  # hood: V − r_b·ω_b = 0
    A[4, 0] = -G21 * R2
    A[0, 4] = G21 * R2
    w1, V, wb, _, _ = mp.lu_solve(A, mp.matrix([I_DUAL * wm, M * Vm, IB * wbm, 0, 0]))
    o = out(**{**DUAL, "shooter": "compound"}, transfer="momentum")
    assert o["wheel_speed_after"].value == pytest.approx(float(w1), rel=1e-12)
    assert o["ball_speed"].value == pytest.approx(float(V), rel=1e-12)
    assert o["ball_spin"].value == pytest.approx(float(wb), rel=1e-12)


@pytest.mark.parametrize("transfer", ["energy", "momentum"])
def test_hood_with_secondary_wheel_is_a_hood_with_its_inertia(transfer):
    """(D7): the secondary adds G₂₁²·I₂ and nothing else."""
    base = dict(mode="moment_of_inertia", wheel_inertia="2 lb*in**2", ratio=0.04, transfer=transfer)
    sec = out(**base, shooter="hood_secondary", secondary_inertia="3 lb*in**2", secondary_ratio=0.02)
    hood = out(**{**base, "wheel_inertia": f"{2 + 4 * 3} lb*in**2"}, shooter="hood")
    for name in (
        "wheel_speed_after",
        "ball_speed",
        "ball_spin",
        "range_error",
        "spin_up_time",
        "wheel_inertia_total",
    ):
        assert sec[name].value == pytest.approx(hood[name].value, rel=1e-12)
    assert sec["secondary_speed"].value == pytest.approx(2 * 2000 * RPM, rel=1e-12)


def test_incoming_ball_momentum_agrees_with_recalc():
    """ReCalc's V_bi, ω_bi terms (D4), hood and dual, on ReCalc's defaults with 5 m/s and 600 rpm in."""
    inc = dict(ball_initial_speed="5 m/s", ball_initial_spin="600 rpm")
    h = out(**RECALC_DEFAULTS, **inc, shooter="hood")
    want = recalc_single(W_0, R_W, I_W, M_B, R_B, I_B, 5.0, 600 * RPM)
    assert h["wheel_speed_after"].value == pytest.approx(want[0], rel=1e-12)
    assert h["ball_speed"].value == pytest.approx(want[1], rel=1e-12)
    d = out(**{**RECALC_DEFAULTS, "secondary_ratio": 2}, **inc, shooter="compound")  # top at half speed
    want = recalc_compound(W_0, R_W, I_W + I_W / 4, M_B, R_B, I_B, R_W, 0.5, 5.0, 600 * RPM)
    assert d["wheel_speed_after"].value == pytest.approx(want[0], rel=1e-12)
    assert d["ball_spin"].value == pytest.approx(want[2], rel=1e-12)
    assert h["ball_speed"].value > out(**RECALC_DEFAULTS, shooter="hood")["ball_speed"].value


def test_incoming_ball_energy_balance():
    """(D5) lossless: ½·I·ω₀² + ½·m·V_i² + ½·I_b·ω_bi² = ½·I·ω₁² + ½·m·V² + ½·I_b·ω_b² (mpmath)."""
    Vi, wbi = mp.mpf(3), 50 * 2 * mp.pi / 60
    o = out(**DUAL, transfer="energy", ball_initial_speed="3 m/s", ball_initial_spin="50 rpm")

    def balance(w1):
        V, wb = no_slip(w1)
        return I_DUAL * (W0**2 - w1**2) + M * Vi**2 + IB * wbi**2 - M * V**2 - IB * wb**2

    assert o["wheel_speed_after"].value == pytest.approx(float(mp.findroot(balance, W0)), rel=1e-12)
    assert any(
        "energy model counts the incoming" in w
        for w in solve("flywheel", {**DUAL, "ball_initial_speed": "3 m/s"}).warnings
    )


@pytest.mark.parametrize(
    "raw,field",
    [
        ({"shooter": "compound"}, "shooter"),
        ({"ball_initial_speed": "2 m/s"}, "ball_initial_speed"),
        ({"ball_initial_spin": "100 rpm"}, "ball_initial_spin"),
    ],
)
def test_motor_during_shot_needs_one_section_and_a_ball_at_rest(raw, field):
    with pytest.raises(InputError) as e:
        solve("flywheel", {**DUAL, "transfer": "momentum", "effects": "motor_during_shot", **raw})
    assert e.value.field == field


def test_motor_during_shot_runs_for_the_dual_layout():
    """One section, ball at rest: the slip phase applies with s and σ = c² of (D2)-(D3); infinite-grip
    limit is the impulse model."""
    strong = out(**DUAL, transfer="momentum", effects="motor_during_shot", grip_force="1e5 N")
    impulse = out(**DUAL, transfer="momentum")
    assert strong["ball_speed"].value == pytest.approx(impulse["ball_speed"].value, rel=1e-2)


def test_spin_against_the_wheels_is_named():
    with pytest.raises(InputError) as e:
        solve(
            "flywheel", {**DUAL, "shooter": "hood", "transfer": "momentum", "ball_initial_spin": "-1e6 rpm"}
        )
    assert e.value.field == "ball_initial_spin"


@pytest.mark.parametrize(
    "name", ["frc_dual_recalc.toml", "frc_compound_recalc.toml", "vex_hood_secondary.toml"]
)
def test_new_presets_solve(name):
    p = presets.load(ROOT / "presets" / "flywheel" / name)
    o = solve(p.calculator, p.inputs).outputs
    assert o["ball_speed"].value > 0 and math.isfinite(o["range"].value)
