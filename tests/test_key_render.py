"""What a keystroke makes the app redraw (issue 12): the chart once typing pauses, no layout for
warnings of the same height, nothing left to fail when the app closes with a chart pending."""

from __future__ import annotations

import asyncio

from textual.app import App


async def test_chart_waits_for_a_pause_and_draws_once_for_a_burst():
    """A chart costs more than a frame: it follows the results once typing pauses, drawn once
    for a burst of keys, and the tab counts as busy until it is drawn (tests wait for that)."""
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab
    from gearhead.tui.components.plot_panel import PlotPanel
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-motor", CalculatorTab)
        panel = tab.query_one(PlotPanel)
        drawn = []
        show = panel.show

        async def counting(solution):
            drawn.append(solution.inputs["voltage"].value)
            await show(solution)

        panel.show = counting
        panel.QUIET_S = 1.0  # a pause that a loaded machine cannot pass between two keys
        tab.sheet.focus()
        await pilot.pause()
        tab.sheet.move_to_field("voltage")
        from textual import events

        for key, char in (("backspace", "\x7f"), ("1", "1"), ("1", "1")):
            app.post_message(events.Key(key, char))  # as the driver delivers a fast typist's keys
            await asyncio.sleep(0.02)
        for _ in range(100):  # the keys are handled (the entry holds them all)
            if tab.entries["voltage"] == "11":
                break
            await asyncio.sleep(0.01)
        assert tab.entries["voltage"] == "11"
        assert tab.busy  # the chart is pending
        await settle(pilot)
        assert not tab.busy
        assert drawn == [11.0]  # once, with the last entry


async def test_warnings_of_the_same_height_do_not_lay_the_screen_out():
    """A layout repaints every field of the card (25 ms on the drivetrain card); warnings whose
    numbers change with each key keep their height and only need a repaint."""
    from gearhead.tui.app import GearheadApp
    from gearhead.tui.components.calculator_tab import CalculatorTab
    from tests.tui_helpers import settle

    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        warnings = tab.warnings
        calls = []
        update = warnings.update

        def spying(content="", *, layout=True):
            calls.append(layout)
            return update(content, layout=layout)

        warnings.update = spying
        tab._show_warnings(["speed 1 is high"])  # the box appears: its width is known after
        await pilot.pause()
        tab._show_warnings(["speed 2 is high"])  # the first at a known width: laid out once more
        await pilot.pause()
        tab._show_warnings(["speed 3 is high"])  # same height
        tab._show_warnings(["speed 3 is high"])  # same text: nothing to do
        tab._show_warnings(["speed 2 is high", "and a second line"])
        await pilot.pause()
        tab._show_warnings([])
        await asyncio.sleep(0)
    assert calls == [True, True, False, True, True]


async def test_closing_while_a_chart_is_pending_or_mounting_is_quiet():
    """A chart is drawn 80 ms after the results, so the app may close meanwhile (ctrl+q right
    after a key, or a card warmed up in idle time): the pending chart is dropped, and one whose
    widget was still mounting draws nothing, instead of a traceback on the way out."""
    from gearhead.core.model import Plot, Solution
    from gearhead.tui.components.plot_panel import PlotPanel

    plots = (Plot("Force", ("a",), "x", "length", "m", "F", "force", "N"),)
    solution = Solution("x", {}, {}, [], {"a": ([0.0, 1.0], [0.0, 1.0])})

    class Harness(App):
        def compose(self):
            yield PlotPanel(plots)

    for wait in (0.0, 0.002, 0.005, 0.01, 0.02):
        app = Harness()
        async with app.run_test(size=(80, 24)):
            panel = app.query_one(PlotPanel)
            panel.QUIET_S = 0.005
            panel.show_soon(solution)
            await asyncio.sleep(wait)
        # leaving run_test raised if a task of the app failed
        assert app.return_code in (None, 0)
