"""Daily use of the results table: each row's equation number, the "how" of the row under the
cursor, values never cut, and a scene's error estimate shown after its results."""

from __future__ import annotations

import csv
import dataclasses
import io
import threading

import pytest
from rich.cells import cell_len
from textual.widgets import Static

import gearhead.tui.app as app_module
from gearhead.core import export
from gearhead.core.model import solve
from gearhead.core.registry import get
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.calculator_tab import CalculatorTab
from tests.tui_helpers import settle


def numbered(calc_id: str):
    """The calculator with an equation number of our own on every output (others fill in the
    real ones in core/calculators): "(1)", "(2)" … and one range; and a help where one is missing."""
    calc = get(calc_id)
    outputs = tuple(
        dataclasses.replace(
            o, equation=f"({i})" if i != 2 else "(61)-(64)", help=o.help or f"How {o.label} is found."
        )
        for i, o in enumerate(calc.outputs, 1)
    )
    return dataclasses.replace(calc, outputs=outputs)


@pytest.fixture
def gear_ratio_numbered(monkeypatch):
    calc = numbered("gear_ratio")
    real_get = app_module.get
    monkeypatch.setattr(app_module, "get", lambda cid: calc if cid == calc.id else real_get(cid))
    return calc


def cell(tab: CalculatorTab, row: str, column: str) -> str:
    """A cell of the results list: "value" as shown ("…" while pending), or "equation"."""
    if column == "value":
        return tab.shown_values()[row]
    return next(getattr(r, column) for r in tab.results.rows if r.name == row)


def drawn(tab: CalculatorTab) -> list[str]:
    """The results list's lines as drawn (the part on screen)."""
    results = tab.results
    return [results.render_line(y).text for y in range(results.size.height)]


async def test_each_result_row_shows_its_equation_number(gear_ratio_numbered):
    calc = gear_ratio_numbered
    app = GearheadApp(blink=False, initial=calc.id)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one(f"#calc-{calc.id}", CalculatorTab)
        assert tab.solution.outputs
        for name in tab.solution.outputs:
            assert cell(tab, name, "equation") == calc.output(name).equation
        lines = drawn(tab)
        assert "Eq." in lines[0]
        for i, name in enumerate(tab.solution.outputs):  # each row's line ends with its number
            line = next(
                lines[n - tab.results.scroll_offset.y]
                for n, (row, k) in enumerate(tab.results._lines)
                if row == i and k == 0
            )
            assert line.rstrip().endswith(calc.output(name).equation)
            if i > 5:
                break


async def test_the_row_under_the_cursor_says_how_with_its_equation(gear_ratio_numbered):
    calc = gear_ratio_numbered
    app = GearheadApp(blink=False, initial=calc.id)
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one(f"#calc-{calc.id}", CalculatorTab)
        table = tab.results
        table.focus()
        await pilot.pause()
        for name in list(tab.solution.outputs)[1:3]:
            table.move_to(list(tab.solution.outputs).index(name))
            await settle(pilot)
            out = calc.output(name)
            line = str(tab.query_one(".help-line", Static).render())
            assert line.startswith(f"{out.label} {out.equation}: ")
            assert out.help and out.help in line


def test_export_carries_the_equation_numbers():
    calc = numbered("gear_ratio")
    sol = solve("gear_ratio", {})
    rows = list(csv.DictReader(io.StringIO(export.results_csv(calc, sol))))
    assert [r["equation"] for r in rows] == [calc.output(r["output"]).equation for r in rows]
    lines = export.results_markdown(calc, sol).splitlines()
    assert lines[2] == "| Result | Value | Eq. |"
    first = calc.output(next(iter(sol.outputs)))
    assert lines[4] == f"| {first.label} | {sol.outputs[first.name].text} | {first.equation} |"


def shown_cut(tab: CalculatorTab) -> list[str]:
    """Values or units that do not fit their column, or columns that do not fit the list, or a
    value on screen not drawn whole."""
    table = tab.results
    label, value, equation, spread = table._widths
    values = tab.shown_values()
    cut = [text for text in (values[name] for name in tab.solution.outputs) if cell_len(text) > value]
    used = 1 + label + 1 + value + (1 + equation if equation else 0) + (1 + spread if spread else 0)
    if used > table.size.width:
        cut.append(f"columns need {used} of {table.size.width}")
    lines = drawn(tab)
    for n, (row, k) in enumerate(table._lines):
        y = n - table.scroll_offset.y
        if row >= 0 and k == 0 and 0 <= y < len(lines) and table.rows[row].value not in lines[y]:
            cut.append(f"{table.rows[row].value!r} drawn as {lines[y]!r}")
    return cut


@pytest.mark.parametrize("size", [(80, 24), (140, 45)])
@pytest.mark.parametrize("calc_id", ["flywheel", "trebuchet", "motor"])
async def test_values_and_units_are_never_cut(calc_id, size):
    calc = numbered(calc_id)  # with an equation column too
    real_get = app_module.get
    app_module.get, restore = (lambda cid: calc if cid == calc_id else real_get(cid)), real_get
    try:
        app = GearheadApp(blink=False, initial=calc_id)
        async with app.run_test(size=size) as pilot:
            await settle(pilot)
            tab = app.query_one(f"#calc-{calc_id}", CalculatorTab)
            for system in ("calculator", "imperial", "metric"):
                app.set_unit_system(system, remember=False)
                await settle(pilot)
                assert not shown_cut(tab), (system, shown_cut(tab))
            # a unit wider than any the calculator foresees (typed, shown "as entered") widens the
            # value column rather than being cut
            speed = next(o for o in calc.outputs if o.quantity in ("speed", "angular_speed"))
            tab.display_units = {
                speed.name: "furlong/fortnight" if speed.quantity == "speed" else "revolution/fortnight"
            }
            tab.solve()
            await settle(pilot)
            assert "fortnight" in tab.solution.outputs[speed.name].text
            assert not shown_cut(tab), shown_cut(tab)
    finally:
        app_module.get = restore


async def test_scene_results_come_before_their_error_estimate(monkeypatch):
    """The pneumatics tab shows its results while the 100x tighter estimate run is still going
    ("…" in its row), then the estimate, the same number the CLI prints."""
    from gearhead.core.sim import scene

    release = threading.Event()
    real = scene._estimate

    def held(*args, **kwargs):
        release.wait(20)
        return real(*args, **kwargs)

    app = GearheadApp(blink=False, initial="pneumatics")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-pneumatics", CalculatorTab)
        monkeypatch.setattr(scene, "_estimate", held)
        entries = {**tab.entries, "tank_volume": "1.5 L"}
        tab.set_entries({"tank_volume": "1.5 L"})
        for _ in range(200):
            await pilot.pause()
            if tab.solution is not None and tab.solution.inputs["tank_volume"].value == pytest.approx(1.5e-3):
                break
        else:
            raise AssertionError("the new entries were never solved")
        assert tab.busy  # the estimate is still running
        assert cell(tab, "error_estimate", "value") == "…"
        assert tab.results.state == "fresh"  # the results of these entries, only the estimate to come
        assert cell(tab, "final_pressure", "value") == tab.solution.outputs["final_pressure"].text
        release.set()
        await settle(pilot)
        expected = solve("pneumatics", entries).outputs["error_estimate"].text  # as the CLI computes it
        assert cell(tab, "error_estimate", "value") == expected


async def test_a_key_drops_the_pending_error_estimate(monkeypatch):
    """Nothing stale: an estimate still running when the next key arrives is never shown, even
    when it ends after the next entries' own estimate is drawn."""
    from gearhead.core.sim import scene

    started, release, ended = threading.Event(), threading.Event(), threading.Event()
    real = scene._estimate

    def held(*args, **kwargs):
        started.set()
        release.wait(20)
        try:
            return real(*args, **kwargs)
        finally:
            ended.set()

    app = GearheadApp(blink=False, initial="pneumatics")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-pneumatics", CalculatorTab)
        monkeypatch.setattr(scene, "_estimate", held)
        tab.set_entries({"tank_volume": "1.5 L"})
        for _ in range(200):
            await pilot.pause()
            if started.is_set():
                break
        assert started.is_set()
        first = tab.solution
        assert first.outputs["error_estimate"].text == "…"
        monkeypatch.setattr(scene, "_estimate", real)
        tab.set_entries({"tank_volume": "2 L"})  # the next key, while the first estimate runs
        await settle(pilot)
        expected = solve("pneumatics", {**tab.entries}).outputs["error_estimate"].text
        assert cell(tab, "error_estimate", "value") == expected
        release.set()  # now the first estimate ends, after the second is drawn
        assert ended.wait(20)
        for _ in range(10):
            await pilot.pause()
        assert tab.solution.inputs["tank_volume"].value == pytest.approx(2e-3)
        assert cell(tab, "error_estimate", "value") == expected
        assert (
            tab.sheet.value_text(
                tab.sheet.stops[[s.field.name for s in tab.sheet.stops].index("tank_volume")]
            )
            == "2000"
        )
        first_estimate = solve("pneumatics", {**tab.entries, "tank_volume": "1.5 L"}).outputs[
            "error_estimate"
        ]
        assert first_estimate.text != expected  # so the check above can tell them apart


async def test_results_of_other_entries_are_drawn_dimmed_until_the_new_ones_land(monkeypatch):
    """No frame shows a result as current for entries no longer on screen: while the new entries'
    solve runs, every line the list draws is dimmed (read when drawn: a frame after the result has
    landed draws it once, bold)."""
    import gearhead.core.model

    release = threading.Event()
    real = gearhead.core.model.solve

    def held(*args, **kwargs):
        release.wait(20)
        return real(*args, **kwargs)

    def value_styles(tab) -> list:
        results = tab.results
        lines = [results.render_line(y) for y in range(1, 4)]  # value rows under the header
        return [seg.style for strip in lines for seg in strip if seg.text.strip() and seg.style]

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        assert any(s.bold for s in value_styles(tab))  # fresh: the values are bold
        monkeypatch.setattr(gearhead.core.model, "solve", held)
        tab.set_entries({"load": "120"})
        await pilot.pause()
        assert tab.solution_key != tab.key and not tab.results.is_current()
        styles = value_styles(tab)
        assert styles and not any(s.bold for s in styles)  # waiting: nothing drawn as current
        release.set()
        await settle(pilot)
        assert tab.results.is_current() and any(s.bold for s in value_styles(tab))


async def test_rows_drawn_dimmed_are_drawn_again_when_the_result_lands(monkeypatch):
    """A frame drawn while the solve ran showed every row dimmed; the result then repainted only
    the rows whose text changed, and the others stayed dimmed on screen (a real terminal showed
    'Stall load 300 lbf' not bold after typing 2 motors). Every row is drawn again."""
    import gearhead.core.model

    release = threading.Event()
    real = gearhead.core.model.solve

    def held(*args, **kwargs):
        release.wait(20)
        return real(*args, **kwargs)

    app = GearheadApp(blink=False, initial="gear_ratio")
    async with app.run_test(size=(140, 45)) as pilot:
        await settle(pilot)
        tab = app.query_one("#calc-gear_ratio", CalculatorTab)
        before = {r.name: r.value for r in tab.results.rows}
        monkeypatch.setattr(gearhead.core.model, "solve", held)
        tab.set_entries({"motor_count": "2"})
        await app.screen.wait_for_refresh()  # a frame draws the rows dimmed
        repainted = []
        refresh = tab.results.refresh

        def spying(*regions, **kwargs):
            repainted.append(regions)
            return refresh(*regions, **kwargs)

        tab.results.refresh = spying
        release.set()
        await settle(pilot)
        after = {r.name: r.value for r in tab.results.rows}
        assert any(before[n] == after[n] for n in after) and before != after  # some rows kept their text
        assert () in repainted  # the whole list, not only the rows that changed
