"""The app's "Fit from log" (issue 44 item 7, tui/components/fit_screen.py): offered by the palette
on the elevator, arm, flywheel and sprint cards only; on the elevator card the shipped example log gives
the table `gearhead fit --json` gives, Apply puts the fitted entries into the card's fields; a
hostile log is one line naming the file; Esc closes."""

from __future__ import annotations

import json
import math
import time

import pytest

from gearhead.core import units
from gearhead.tui.app import GearheadApp
from gearhead.tui.cli import main
from gearhead.tui.components.fit_screen import FitScreen
from tests.test_fit_example import LOG
from tests.tui_helpers import card, settle

SIZE = (140, 45)


async def open_fit(pilot) -> FitScreen:
    await settle(pilot)
    await pilot.press("ctrl+p")
    await pilot.press(*"Fit from log")
    await pilot.pause(0.3)
    await pilot.press("enter")
    for _ in range(100):
        await pilot.pause(0.01)
        if isinstance(pilot.app.screen, FitScreen):
            return pilot.app.screen
    raise AssertionError(f"the palette's 'Fit from log…' opened {pilot.app.screen!r}")


async def fit(pilot, screen: FitScreen, path: str) -> float:
    """Type the path, Enter, wait for the result; the seconds until the table is drawn."""
    entry = screen.query_one("#fit-path")
    entry.focus()
    entry.value = path
    started = time.perf_counter()
    await pilot.press("enter")
    for _ in range(1000):
        await pilot.pause(0.01)
        if not screen._fitting:
            break
    await pilot.pause()
    return time.perf_counter() - started


@pytest.mark.parametrize(
    "calc_id, offered",
    [("elevator", True), ("arm", True), ("flywheel", True), ("sprint", True), ("motor", False)],
)
async def test_the_palette_offers_it_on_the_fitted_cards_only(calc_id, offered):
    app = GearheadApp(blink=False, initial=calc_id, hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        titles = [c.title for c in app.get_system_commands(app.screen)]
        assert ("Fit from log…" in titles) == offered


async def test_elevator_fits_the_example_log_as_the_cli_and_applies(capsys):
    assert main(["fit", str(LOG), "--card", "elevator", "--json"]) == 0
    want = json.loads(capsys.readouterr().out)
    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_fit(pilot)
        seconds = await fit(pilot, screen, str(LOG))
        print(f"fit from log: {seconds * 1000:.0f} ms from Enter to the table drawn")
        assert screen.report is not None, str(screen.query_one("#fit-status").render())
        assert screen.report.favoured == want["favoured"] == "discrete"
        table = screen.query_one("#fit-table")
        assert table.display
        for form, column in (("continuous", 2), ("discrete", 3)):
            for row, k in enumerate(("kS", "kV", "kA", "kG")):
                got = screen.report.fits[form].gains[k]
                assert got == pytest.approx(want["fits"][form]["gains"][k], rel=1e-12)
                value, sigma = str(table.get_cell_at((row, column))).split(" ± ")
                assert float(value) == pytest.approx(got, rel=5e-4)  # 4 digits, as the CLI prints
        assert screen.query_one("#fit-plot").display
        diff = str(screen.query_one("#fit-diff").render())
        assert "Apply writes into the card:" in diff and "Load mass" in diff
        best = screen.report.fits["discrete"].gains
        mass = best["kA"] * screen.report.card.f
        friction = best["kS"] * screen.report.card.f - screen.report.card.loss
        await pilot.click("#fit-apply")
        await settle(pilot)
        assert not isinstance(app.screen, FitScreen)
        tab = card(app, "elevator")
        assert units.parse(tab.entries["load_mass"], "lb", "mass", "load_mass") == pytest.approx(
            mass, rel=1e-12
        )
        assert units.parse(tab.entries["friction_force"], "lbf", "force", "friction_force") == pytest.approx(
            friction, rel=1e-12
        )
        assert "friction" in tab.entries["effects"]
        entry = {e["entry"]: e for e in want["entries"]}
        assert mass == pytest.approx(entry["moving mass"]["fitted"], rel=1e-12)
        assert tab.solution is not None and tab.error is None


@pytest.mark.parametrize(
    "data, words",
    [
        (b"not a log at all", "is not a WPILog"),
        (b"WPILOG\x00\x01\x00\x00\x00\x00", "sysid"),
        (b"", "is not a WPILog"),
    ],
)
async def test_a_hostile_log_is_one_line_naming_the_file(tmp_path, data, words):
    path = tmp_path / "bad.wpilog"
    path.write_bytes(data)
    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_fit(pilot)
        await fit(pilot, screen, str(path))
        status = str(screen.query_one("#fit-status").render())
        assert str(path) in status and words.lower() in status.lower(), status
        assert "Traceback" not in status and "nan" not in status.lower().split()
        assert screen.report is None and not screen.query_one("#fit-table").display
        assert screen.query_one("#fit-apply").disabled
        for text in ("", str(tmp_path), str(tmp_path / "none.wpilog")):
            await fit(pilot, screen, text)
            status = str(screen.query_one("#fit-status").render())
            assert status.startswith(text or "log:") and screen.report is None, status
        await pilot.press("escape")
        await pilot.pause()
        assert not isinstance(app.screen, FitScreen)


async def test_flywheel_fits_and_offers_its_wheel_inertia(tmp_path):
    pytest.importorskip("wpiutil")
    from gearhead.core.fit import entries
    from tests.fit_plants import simulate

    design = entries.load_card("flywheel").design
    path = simulate(tmp_path / "fly.wpilog", "flywheel", {k: design[k] * 1.2 for k in ("kS", "kV", "kA")})
    app = GearheadApp(blink=False, initial="flywheel", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_fit(pilot)
        await fit(pilot, screen, str(path))
        assert screen.report is not None, str(screen.query_one("#fit-status").render())
        kv = screen.report.fits[screen.report.favoured].gains["kV"]
        assert kv == pytest.approx(design["kV"] * 1.2, rel=0.01) and math.isfinite(kv)
        diff = str(screen.query_one("#fit-diff").render())
        assert "Wheel inertia (each)" in diff and "→ Moment of inertia" in diff, diff
        assert not screen.query_one("#fit-apply").disabled  # Apply: tests/test_fit_apply.py


async def test_a_name_not_utf8_is_shown_escaped_in_the_dialog(tmp_path):
    # the dialog's signals line showed the replacement character (as the CLI did)
    pytest.importorskip("wpiutil")
    from tests.test_fit_cli import named_log

    path = named_log(tmp_path)
    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_fit(pilot)
        await fit(pilot, screen, str(path))
        assert screen.report is not None, str(screen.query_one("#fit-status").render())
        signals = str(screen.query_one("#fit-signals").render())
        assert "voltage voltage-m\\xff-lift" in signals and "\ufffd" not in signals, signals


@pytest.mark.parametrize("size", [(140, 45), (80, 24)])
def test_in_a_real_terminal_it_opens_fits_and_closes(tmp_path, size):
    from tests.test_keystrokes import TMUX, Terminal

    if TMUX is None:
        pytest.skip("tmux is not installed (.ci/run installs it)")
    term = Terminal(tmp_path)
    try:
        term.tmux("resize-window", "-t", "app", "-x", str(size[0]), "-y", str(size[1]))
        for command, shown in (("Open Elevator", "Load mass"), ("Fit from log", "fit from a SysId log")):
            term.keys("C-p")
            time.sleep(0.5)
            term.keys(command)
            time.sleep(0.5)
            term.keys("Enter")
            term.wait_for(lambda s, shown=shown: shown in s, command)
        term.keys("examples/elevator_sysid.wpilog", "Enter")
        screen = term.wait_for(lambda s: "fitted in" in s, "the fit")
        assert "discrete ★" in screen and "Traceback" not in screen
        term.keys("Escape")
        screen = term.wait_for(lambda s: "fit from a SysId log" not in s, "Esc to close the dialog")
        assert "Load mass" in screen and "Traceback" not in screen
    finally:
        term.close()


async def test_arm_applies_its_mass_inertia_and_friction(tmp_path):
    pytest.importorskip("wpiutil")
    from gearhead.core.fit import entries
    from tests.fit_plants import simulate

    design = entries.load_card("arm").design
    plant = {"kS": design["kS"] * 2, "kV": design["kV"], "kA": design["kA"] * 1.3, "kG": design["kG"] * 1.25}
    path = simulate(tmp_path / "arm.wpilog", "arm", {**plant, "offset": 0.0}, period=0.005)
    app = GearheadApp(blink=False, initial="arm", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_fit(pilot)
        await fit(pilot, screen, str(path))
        r = screen.report
        assert r is not None, str(screen.query_one("#fit-status").render())
        changes = dict(screen.changes)
        assert {"arm_mass", "inertia_model", "moment_of_inertia", "friction_torque"} <= set(changes)
        await pilot.click("#fit-apply")
        await settle(pilot)
        tab = card(app, "arm")
        assert tab.error is None and tab.solution is not None
        best = r.fits[r.favoured].gains
        got = tab.solution.inputs
        assert got["moment_of_inertia"].value == pytest.approx(best["kA"] * r.card.f, rel=1e-9)
        assert got["inertia_model"].value == "entered"


async def test_a_bad_entry_on_the_card_or_a_bad_csv_is_named(tmp_path):
    bad_csv = tmp_path / "bad.csv"
    bad_csv.write_text("Timestamp,voltage-m-mech\n0.0,nan\n", encoding="utf-8")
    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await fit_with(pilot, app, str(bad_csv), str(bad_csv))
        card(app).set_entries({"load_mass": "-3 kg"})
        await settle(pilot)
        await fit_with(pilot, app, str(LOG), "load_mass")


async def fit_with(pilot, app, path: str, named: str) -> None:
    screen = await open_fit(pilot)
    await fit(pilot, screen, path)
    status = str(screen.query_one("#fit-status").render())
    assert named in status and screen.report is None and "Traceback" not in status, status
    await pilot.press("escape")
    await pilot.pause()
    assert not isinstance(app.screen, FitScreen)


def test_the_dialog_as_it_opens_snapshot(snap_compare):
    """Before a log is chosen (a fitted table's standard deviations of 1e-16 are rounding, which
    differs between machines: no snapshot of it)."""
    assert snap_compare(
        GearheadApp(blink=False, initial="elevator", hide_timings=True),
        terminal_size=SIZE,
        run_before=open_fit,
    )


async def test_tab_goes_from_the_log_to_apply_in_three_keys():
    """The fit's tables are read, not browsed: Tab goes log → Browse → the fit (it scrolls) → Apply
    → Close, so a keyboard reaches Apply in three keys."""
    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        dialog = await open_fit(pilot)
        await fit(pilot, dialog, str(LOG))
        seen = []
        for _ in range(5):
            seen.append(app.focused.id)
            await pilot.press("tab")
        assert seen == ["fit-path", "fit-browse", "fit-body", "fit-apply", "fit-close"]
        assert not dialog.query_one("#fit-apply").disabled
