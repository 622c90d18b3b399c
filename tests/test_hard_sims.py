"""Hard cases of the simulations' robustness: inputs that once hung, crawled, divided by zero or
gave a result the physics forbids. Each states the input, what went wrong and what the answer is
checked against (a closed form, the geometry, or a bound of the physics)."""

import contextlib
import math
import signal

import mpmath as mp
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st

from gearhead.core.calculators import flywheel as fw
from gearhead.core.calculators import projectile as pj
from gearhead.core.errors import InputError
from gearhead.core.model import parse_inputs, solve
from gearhead.core.registry import get
from gearhead.core.sim import flight
from gearhead.core.sim import integrate as ig
from gearhead.core.sim import trebuchet as tb

mp.mp.dps = 30
DEG = math.pi / 180


@contextlib.contextmanager
def deadline(seconds: int):
    """A hang becomes a failure (SIGALRM; pytest and its xdist workers run tests on the main thread)."""

    def expire(*_):
        raise TimeoutError(f"still running after {seconds} s")

    previous = signal.signal(signal.SIGALRM, expire)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


# ---- hangs: the trebuchet's release event re-detected at its own restart -----------------------

HANG = dict(
    counterweight_gyration=0.6,
    arm_mass=40,
    arm_length=16.97,
    pivot_height=1.9,
    projectile_mass=3.1,
    gravity=50,
    effects="",
    accuracy="coarse",
)


@pytest.mark.parametrize("angle", ["88.9", "1.55334 rad"])
def test_trebuchet_release_near_89_degrees_neither_hangs_nor_misses_the_first_pass(angle):
    """Arm alone (cup), β ≈ 89°: coarse steps jumped over the release and over the old angle gauge's
    branch cut, the arm stopped past the top, and the reversal of the velocity (a jump across the cut)
    was detected as a release, rejected, and re-detected at the same instant forever (> 900 s).
    The cup's velocity is square to the arm, so it points β over the horizontal when φ = 90° − β:
    release height h + R·cos β, on the arm's first pass (geometry, not the code)."""
    with deadline(30):
        out = solve("trebuchet", dict(HANG, release_angle=angle)).outputs
    beta = out["release_angle"].value
    R = 0.75 * 16.97
    assert out["release_height"].value == pytest.approx(1.9 + R * math.cos(beta), rel=1e-3)
    assert out["release_time"].value < 0.5  # the first pass (the arm comes back over at ~2.8 s)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    M=st.floats(0, 3).map(lambda x: 10**x),
    m=st.floats(0, 200),
    k=st.floats(0, 3),
    L=st.floats(2, 20),
    h_frac=st.floats(0.05, 0.95),
    m_p=st.floats(0.5, 20),
    g=st.floats(1, 100),
    beta=st.floats(0, 89),
    effects=st.sets(st.sampled_from(["sling", "ground_contact"])),
)
def test_random_trebuchets_at_coarse_accuracy_always_end(M, m, k, L, h_frac, m_p, g, beta, effects):
    """The family of the hanging case (4 in 10 000 random machines hung): each ends, in a result or
    a message naming a field."""
    raw = dict(
        counterweight_mass=M,
        arm_mass=m,
        counterweight_gyration=k,
        arm_length=L,
        pivot_height=h_frac * 0.75 * L,
        projectile_mass=m_p,
        gravity=g,
        release_angle=beta,
        effects=",".join(sorted(effects)),
        accuracy="coarse",
    )
    with deadline(30):
        try:
            solve("trebuchet", raw)
        except InputError as exc:
            assert exc.field != "(result)", exc.message


def test_integrator_does_not_find_the_event_it_restarted_at_again():
    """g jumps from −1 to +1 at t = 1 (as an angle does at its branch cut). Restarted at t = 1 with
    that event named in `restart`, the run goes on; a later genuine crossing is still found."""
    jump = ig.Event("jump", lambda t, y: -1.0 if t <= 1.0 else 1.0, +1)
    first = ig.integrate(lambda t, y: [1.0], 0.0, 3.0, [0.0], events=[jump])
    assert first.event == "jump" and first.t[-1] == pytest.approx(1.0, abs=1e-12)
    again = ig.integrate(lambda t, y: [1.0], 1.0, 3.0, [1.0], events=[jump], restart=("jump",))
    assert again.event is None and again.t[-1] == 3.0 and again.y[-1][0] == pytest.approx(3.0)
    wave = ig.Event("wave", lambda t, y: math.sin(math.pi * t), +1)
    run = ig.integrate(lambda t, y: [1.0], 1.0, 3.0, [1.0], events=[wave], restart=("wave",), rtol=1e-10)
    assert run.event == "wave" and run.t[-1] == pytest.approx(2.0, abs=1e-9)


def test_trebuchet_swing_restarts_are_capped(monkeypatch):
    """The guard behind the fix: a swing that keeps restarting stops with a message naming a field."""
    monkeypatch.setattr(tb, "MAX_RESTARTS", 0)
    with pytest.raises(InputError) as err:
        solve("trebuchet", {})  # sling + ground contact: lift-off is a restart
    assert err.value.field != "(result)" and "restarted" in err.value.message


# ---- the per-solve budget and cancellation -----------------------------------------------------


def test_long_pneumatics_match_with_fast_firings_is_refused_with_advice():
    """3 600 s, three groups firing every 0.1 s: 108 000 firings, each a restart of the integration
    (5.2 s before the budget). Refused within the budget, naming the match length and what to do."""
    raw = dict(
        match_length=3600,
        c1_count=1,
        c1_period=0.1,
        c1_start=0,
        c2_count=1,
        c2_period=0.1,
        c2_start=0,
        c3_count=1,
        c3_period=0.1,
        c3_start=0,
    )
    with pytest.raises(InputError) as err:
        solve("pneumatics", raw)
    assert err.value.field == "match_length" and "shorter match" in err.value.message


def test_projectile_reverse_with_extreme_magnus_counts_every_flight():
    """Spin 1e5 rpm, C_L 1, a 1 g ball: flights curl up and fail at their step limit. The failed ones
    were not counted against MAX_NFEV, so the search ran ~4x over it (2.4 s). Every right-hand-side
    evaluation is counted here, independently of the integrator, by wrapping the flight's."""
    calls = [0]
    original = flight.rhs_for

    def counting(a):
        f = original(a)

        def rhs(t, s):
            calls[0] += 1
            return f(t, s)

        return rhs

    raw = dict(mode="reverse", effects="magnus", spin=1e5, lift_coefficient=1, ball_mass=0.001)
    with pytest.MonkeyPatch.context() as mpatch:
        mpatch.setattr(flight, "rhs_for", counting)
        with pytest.raises(InputError) as err:
            solve("projectile", raw)
    assert err.value.field == "target_angle" and "no release found" in err.value.message
    assert calls[0] <= pj.MAX_NFEV + 10_000  # the last step in flight when the budget ran out


def test_near_point_hinged_counterweight_optimise_polish_is_bounded():
    """Hanger 1 cm, gyration 0: a stiff pendulum, each accurate throw ~0.4 s; the Nelder–Mead polish
    took 27 s. It now stops at REFINE_NFEV with the best throw so far, and says so."""
    from gearhead.core.calculators import trebuchet as tc

    raw = dict(
        effects="sling,ground_contact,hinged_counterweight,optimise",
        hanger_length=0.01,
        counterweight_gyration=0,
    )
    with ig.budget() as spent:
        sol = solve("trebuchet", raw)
    assert any("polish" in w for w in sol.warnings)
    assert sol.outputs["best_range"].value > sol.outputs["range"].value
    # the whole solve: its run with the estimate, the batch, the polish, the best throw's check
    assert spent.nfev < 400_000 + tc.REFINE_NFEV + 250_000


def test_cancel_stops_a_solve_between_steps():
    polls = [0]

    def cancel():
        polls[0] += 1
        return polls[0] > 50

    with pytest.raises(ig.Cancelled):
        with ig.budget(cancel=cancel):
            solve("trebuchet", {"effects": "sling, ground_contact, optimise"})
    assert polls[0] == 51


def test_budget_exceeded_is_not_swallowed_by_the_solver_failure_fallbacks():
    """flywheel's slip phase falls back to its closed form on RuntimeError; a budget is no failure."""
    assert not issubclass(ig.BudgetExceeded, (RuntimeError, ValueError, ArithmeticError))
    with pytest.raises(ig.BudgetExceeded):
        with ig.budget(max_nfev=100):
            ig.integrate(lambda t, y: [math.cos(50 * t)], 0.0, 100.0, [0.0], rtol=1e-10)


# ---- wrong results -----------------------------------------------------------------------------


def test_trebuchet_efficiency_counts_the_arms_fall_exactly():
    """M = 10 kg, m = 200 kg, a = 0.6 (the arm's centre of mass on the counterweight's side, s < 0):
    the arm's own fall drives the throw; 112.95 % when only the counterweight's drop was counted.
    Arm alone with the projectile in its cup, in closed form (energy conservation, seed 1.2):
        ½(I + m_p·R²)·ω² = (C − W)·Δ,  C = g·(M·r − m·s),  W = g·m_p·R,  Δ = sin φ_r − sin φ0
        E_p = ½·m_p·R²·ω² + W·Δ,  supplied = g·(M·r·Δ − m·s·Δ) = C·Δ
        η = (m_p·R²·(C − W)/(I + m_p·R²) + W)/C     (independent of β once released)"""
    M, m, a, L, k, m_p, g = (mp.mpf(x) for x in (10, 200, "0.6", 15, 2, 5, "9.81"))
    r, s, R = a * L, L / 2 - a * L, (1 - a) * L
    I = m * L**2 * (mp.mpf(1) / 12 + (mp.mpf(1) / 2 - a) ** 2) + M * r**2 + M * k**2
    C, W = g * (M * r - m * s), g * m_p * R
    eta = (m_p * R**2 * (C - W) / (I + m_p * R**2) + W) / C
    out = solve(
        "trebuchet",
        dict(counterweight_mass=10, arm_mass=200, short_arm_fraction=0.6, effects="", accuracy="fine"),
    ).outputs
    assert out["efficiency"].value == pytest.approx(float(eta), rel=1e-7)
    sling = solve("trebuchet", dict(counterweight_mass=10, arm_mass=200, short_arm_fraction=0.6)).outputs
    assert 0 < sling["efficiency"].value <= 1


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@example(
    M=10, m=200, a=0.6, L=15, h_frac=4 / 6, m_p=5, l=5, beta=45, k=2, d=0, effects={"sling", "ground_contact"}
)
@given(
    M=st.floats(0, 3).map(lambda x: 10**x),
    m=st.floats(-1, 2.7).map(lambda x: 10**x),
    a=st.floats(0.1, 0.7),
    L=st.floats(2, 20),
    h_frac=st.floats(0.1, 0.9),
    m_p=st.floats(0.1, 50),
    l=st.floats(0.5, 10),
    beta=st.floats(10, 80),
    k=st.floats(0, 3),
    d=st.floats(0, 2),
    effects=st.sets(st.sampled_from(["sling", "ground_contact", "hinged_counterweight"])),
)
def test_trebuchet_efficiency_never_exceeds_one(M, m, a, L, h_frac, m_p, l, beta, k, d, effects):
    """Energy conservation: what the projectile holds at release comes out of the potential energy
    the counterweight and the arm gave up (the ground's push does no work, touchdowns only take)."""
    raw = dict(
        counterweight_mass=M,
        arm_mass=m,
        short_arm_fraction=a,
        arm_length=L,
        pivot_height=h_frac * (1 - a) * L,
        projectile_mass=m_p,
        sling_length=l,
        release_angle=beta,
        counterweight_gyration=k,
        hanger_length=d,
        effects=",".join(sorted(effects)),
        accuracy="fine",
    )
    try:
        out = solve("trebuchet", raw).outputs
    except InputError as exc:
        assert exc.field != "(result)", exc.message
        assume(False)
    if "efficiency" in out:
        assert 0 <= out["efficiency"].value <= 1 + 1e-6


def test_trebuchet_massless_arm_with_point_counterweight_on_a_hanger_is_refused():
    """m = 0, k = 0 and a hanger: after release the arm's inertia I_arm + M·r²·k²/(d² + k²) is 0
    (a ZeroDivisionError reported as '(result)'). Refused naming the arm mass."""
    raw = dict(
        arm_mass=0,
        counterweight_gyration=0,
        effects="hinged_counterweight",
        hanger_length=0.5,
        counterweight_mass=100,
        short_arm_fraction=0.1,
        pivot_height=0.5,
        release_angle=5,
    )
    with pytest.raises(InputError) as err:
        solve("trebuchet", raw)
    assert err.value.field == "arm_mass"


def test_flywheel_wheel_stopped_by_the_previous_shots_throws_nothing():
    """Ratio 1e-12 (the motor can hardly turn the wheel), β = 1e5 per shot: each shot divides the wheel
    speed by 1 + β and the motor adds nothing between shots, so it reaches 0 (underflow) within the
    burst. The next shot's slip phase scales by t₀ ∝ ω₀ and divided by zero ("(result)"). A wheel at
    rest meets the ball with no impulse: the ball is not thrown, and a warning says so."""
    raw = dict(
        effects="momentum,motor_during_shot",
        shooter="two_wheel",
        wheel_diameter="2 m",
        mode="moment_of_inertia",
        wheel_inertia="1e-6 kg*m^2",
        ratio=1e-12,
        voltage=0.1,
        target_speed="1e-3 rad/s",
        shots=50,
        shot_interval=0.01,
        ball_mass=100,
    )
    sol = solve("flywheel", raw)
    assert sol.outputs["slowest_ball_speed"].value == 0.0
    assert any("not thrown" in w for w in sol.warnings)
    values = parse_inputs(get("flywheel"), raw)[0]
    sc, _ = fw.scene_from(values)
    out = fw.shot(sc, 0.0, 0.1, values["target_speed"], 1e-6)
    assert (out.omega_after, out.V, out.energy) == (0.0, 0.0, 0.0)


def test_accuracy_command_reports_a_computation_failure_without_a_traceback(monkeypatch, capsys):
    from gearhead.core.sim import scene
    from gearhead.tui.cli import main

    def broken(simulate, values, *a, **k):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(scene, "ladder", broken)
    assert main(["accuracy", "flywheel"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "ZeroDivisionError" in err and "Traceback" not in err


def test_ctrl_c_gives_one_line_and_exit_130(monkeypatch, capsys):
    import gearhead.tui.cli as cli

    def interrupted(args):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "_solve", interrupted)
    try:
        code = cli.main(["solve", "pneumatics"])
    except KeyboardInterrupt:
        pytest.fail("Ctrl+C escaped main() (a traceback on screen)")
    assert code == 130
    assert capsys.readouterr().err == "gearhead: interrupted\n"


def test_projectile_distance_below_a_millimetre_is_refused_in_both_modes():
    """d = 1e-8 m: reverse gave θ_i = 90.000° (atan2 of a huge ratio), which forward refuses."""
    for mode in ("forward", "reverse"):
        with pytest.raises(InputError) as err:
            solve("projectile", {"mode": mode, "distance": "1e-8 m"})
        assert err.value.field == "distance"


def test_projectile_reverse_at_the_minimum_distance_round_trips_through_forward():
    rev = solve("projectile", {"mode": "reverse", "distance": "1 mm", "target_angle": "-89.9 deg"}).outputs
    theta, v = rev["release_angle"].value, rev["release_speed"].value
    assert theta < math.pi / 2
    fwd = solve(
        "projectile",
        {
            "mode": "forward",
            "distance": "1 mm",
            "release_angle": f"{theta!r} rad",
            "release_speed": f"{v!r} m/s",
        },
    ).outputs
    assert fwd["target_height"].value == pytest.approx(2.64, rel=1e-6)


async def test_typing_cancels_a_running_simulation_in_the_app(monkeypatch):
    """The app's worker polls `cancel` (the entries changed) between integration steps: a running
    simulation is dropped at once, not run to its end, and the latest entries are solved."""
    import asyncio
    import threading

    from textual import events

    import gearhead.core.model
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab
    from tests.tui_helpers import settle

    real_solve = gearhead.core.model.solve
    outcomes: list[str] = []
    running = threading.Event()

    calls = []

    def slow_then_real(calc_id, raw=None, *args):
        calls.append(1)  # counted on entry: the next solve may start before this one has ended
        if len(calls) == 1:  # the first solve after the key: an integration of minutes unless cancelled
            running.set()
            try:
                with ig.budget(max_seconds=20):  # (a bound for this test, should the cancel not come)
                    ig.integrate(lambda t, y: [math.cos(t)], 0.0, 1e9, [0.0], rtol=1e-12, max_steps=10**9)
                outcomes.append("finished")
            except ig.Cancelled:
                outcomes.append("cancelled")
                raise
        else:
            outcomes.append("solved")
        return real_solve(calc_id, raw, *args)

    app = GearheadApp(blink=False, initial="pneumatics")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        monkeypatch.setattr(gearhead.core.model, "solve", slow_then_real)
        tab = app.query_one("#calc-pneumatics", CalculatorTab)
        tab.sheet.focus()
        await pilot.pause()
        tab.sheet.move_to_field("match_length")
        assert tab.entries["match_length"] in ("150", 150)
        app.post_message(events.Key("enter", "\r"))  # edit it, the cursor at the end
        app.post_message(events.Key("backspace", "\x7f"))  # 150 -> 15: starts the slow solve
        for _ in range(200):  # until it runs (a solve cancelled before it begins never runs)
            if running.is_set():
                break
            await asyncio.sleep(0.02)
        await asyncio.sleep(0.1)
        app.post_message(events.Key("0", "0"))  # 15 -> 150 while it runs
        for _ in range(100):
            await asyncio.sleep(0.05)
            if not tab.busy:
                break
        await settle(pilot)
        # the slow solve was cancelled, never finished; the new entries were solved. Their order in
        # the list is the threads': the new solve may enter before the old one notices its cancel
        assert "finished" not in outcomes and outcomes.count("cancelled") == 1, outcomes
        assert "solved" in outcomes, outcomes
        assert tab.solution is not None and tab.solution.inputs["match_length"].value == 150
