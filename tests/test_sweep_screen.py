"""The sweep view (ctrl+w, palette "Sweep…"): opens on the focused field, runs in a thread, shows a
table equal to core.sweep's, Esc cancels then closes, ctrl+e writes CSV; one snapshot."""

import pytest

from gearhead.core import sweep
from gearhead.core.registry import get
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.sweep_screen import SweepScreen, default_range
from tests.tui_helpers import card, settle, type_into

SIZE = (140, 45)


async def open_sweep(pilot, calc_id: str, field: str) -> SweepScreen:
    await settle(pilot)
    sheet = card(pilot.app, calc_id).sheet
    sheet.focus()
    await pilot.pause()
    assert sheet.move_to_field(field)  # the row under the sheet's cursor
    await pilot.press("ctrl+w")
    return await finished(pilot)


async def finished(pilot) -> SweepScreen:
    screen = pilot.app.screen
    assert isinstance(screen, SweepScreen)
    for _ in range(400):
        await pilot.pause(0.01)
        if screen.result is not None and not screen._sweeping:
            break
    await settle(pilot)
    return screen


@pytest.mark.asyncio
async def test_ctrl_w_sweeps_the_focused_field_and_table_is_core_sweep():
    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_sweep(pilot, "gear_ratio", "radius")
        assert screen.field_name == "radius"
        tab = app.query_one("#calc-gear_ratio")
        start, stop = default_range(tab.calculator.field("radius"), tab.entries["radius"])
        want = sweep.run(get("gear_ratio"), tab.entries, [f"radius={start}..{stop}:21"])
        got = screen.result
        assert [p.inputs for p in got.points] == [p.inputs for p in want.points]
        assert [p.outputs for p in got.points] == [p.outputs for p in want.points]
        table = screen.query_one("#sweep-table")
        assert table.row_count == 21
        # ctrl+w inside the sweep's own entries deletes a word, it does not open another sweep
        screen.query_one("#sweep-points").focus()
        await pilot.press("ctrl+w")
        await pilot.pause()
        assert app.screen is screen and screen.query_one("#sweep-points").value == ""
        await pilot.press("escape")
        await pilot.pause()
        assert not isinstance(app.screen, SweepScreen)


@pytest.mark.asyncio
async def test_bad_range_is_a_message_and_a_new_range_reruns():
    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_sweep(pilot, "gear_ratio", "load")
        screen.query_one("#sweep-start").value = "3 kg"
        screen.query_one("#sweep-start").focus()
        await pilot.press("enter")
        await pilot.pause()
        status = str(screen.query_one("#sweep-status").render())
        assert status.startswith("load:") and "force" in status
        screen.query_one("#sweep-start").value = "-10 lbf"
        screen.query_one("#sweep-points").value = "5"
        await pilot.press("enter")
        screen = await finished(pilot)
        assert len(screen.result.points) == 5
        assert screen.result.points[0].error is not None  # a negative load: a row with its reason
        assert "infeasible" in str(screen.query_one("#sweep-status").render())


@pytest.mark.asyncio
async def test_escape_cancels_a_running_sweep_and_the_card_stays_usable():
    app = GearheadApp(blink=False, initial="trebuchet", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_sweep(pilot, "trebuchet", "counterweight_mass")
        screen.query_one("#sweep-points").value = "5000"
        screen.query_one("#sweep-points").focus()
        await pilot.press("enter")
        await pilot.pause(0.4)
        assert screen._sweeping and screen.query_one("#sweep-progress").display
        await pilot.press("escape")
        await pilot.pause()
        assert not screen._sweeping and "cancelled" in str(screen.query_one("#sweep-status").render())
        await pilot.press("escape")
        await settle(pilot)
        assert not isinstance(app.screen, SweepScreen)
        tab = app.query_one("#calc-trebuchet")
        await type_into(pilot, "arm_mass", "60 kg")
        assert tab.solution is not None and tab.solution.inputs["arm_mass"].value == 60.0


@pytest.mark.asyncio
async def test_export_writes_csv(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_sweep(pilot, "gear_ratio", "radius")
        await pilot.press("ctrl+e")
        await pilot.press("ctrl+e")
        await pilot.pause()
        first = tmp_path / "gear_ratio_sweep_radius.csv"
        assert first.read_text() == screen.result.csv_text()
        assert (tmp_path / "gear_ratio_sweep_radius_2.csv").exists()  # never over the first


@pytest.mark.asyncio
async def test_palette_offers_sweep():
    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        titles = [c.title for c in app.get_system_commands(app.screen)]
        assert "Sweep…" in titles


def test_sweep_view_snapshot(snap_compare):
    async def sweep_radius(pilot):
        await open_sweep(pilot, "gear_ratio", "radius")

    assert snap_compare(
        GearheadApp(blink=False, initial="gear_ratio", hide_timings=True),
        terminal_size=SIZE,
        run_before=sweep_radius,
    )


@pytest.mark.asyncio
async def test_tolerance_in_a_field_shows_spreads_and_goes_away():
    from gearhead.core import tolerance

    app = GearheadApp(blink=False, initial="lead_screw", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-lead_screw")
        await type_into(pilot, "force", "50 N +- 10 %")
        table = tab.results
        assert tab.error is None and tab.spread is not None
        _, want, _ = tolerance.solve("lead_screw", tab.entries)
        s = want.outputs["raise_torque"]
        spreads = {row.name: row.spread for row in table.rows}
        assert spreads["raise_torque"] == tolerance.spread_text(tab.calculator, tab.solution, s)
        assert spreads["lead"] == "unaffected"
        drawn = "\n".join(table.render_line(y).text for y in range(table.size.height))
        assert "Worst case  σ" in drawn and "unaffected" in drawn  # the column is on screen
        assert "tolerances: worst case by corners" in str(tab.query_one(".status").render())
        table.focus()
        await pilot.pause()
        table.move_to([row.name for row in table.rows].index("raise_torque"))
        await settle(pilot)
        help_line = str(tab.query_one(".help-line").render())
        assert "Worst case" in help_line and "mostly force" in help_line, help_line
        await type_into(pilot, "force", "50 N")
        assert tab.spread is None and not any(row.spread for row in table.rows)
        assert table._widths[3] == 0  # no spread column
        tab._take_entry("friction", "0.2 ± 0.19")  # pasted (pilot cannot type "±")
        await settle(pilot)
        notes = tolerance.solve("lead_screw", tab.entries)[1].notes
        assert any("backdrivable changes" in n for n in notes)
        shown = str(tab.query_one(".warnings").render())
        assert all(f"± {n}" in shown for n in notes) and tab.query_one(".warnings-box").display
        tab._take_entry("force", "50 N ± 5 lbf*in")
        await settle(pilot)
        assert tab.error is not None and tab.error.field == "force"


@pytest.mark.asyncio
async def test_the_first_output_plotted_is_one_this_mode_produces():
    """The elevator's first output, 'Fastest ratio', exists only in optimise mode: a sweep of a move
    plotted it and showed an empty chart and a table with no result column (found in tmux)."""
    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        screen = await open_sweep(pilot, "elevator", "ratio")
        picked = screen.query_one("#sweep-outputs").selected
        assert picked == ["time_to_goal"]
        table = screen.query_one("#sweep-table")
        assert "time_to_goal" in [str(c.value) for c in table.columns]
