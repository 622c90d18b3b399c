"""Work the UI skips: the key bar recomposed only when its keys change (KeyFooter), entries styled
once mounted rather than while built (StyledWhenMounted)."""

from __future__ import annotations

from time import monotonic

from textual.widgets._footer import FooterKey

from gearhead.core.registry import ORDER
from gearhead.tui.app import GearheadApp
from gearhead.tui.components.field_input import FieldInput
from gearhead.tui.components.footer import KeyFooter
from tests.tui_helpers import settle

SIZE = (140, 45)


def keys_shown(app) -> list[str]:
    return [key.description for key in app.query(FooterKey)]


async def test_moving_between_fields_keeps_the_footer_and_a_card_switch_updates_it():
    composed = []
    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        footer = app.query_one(KeyFooter)
        original = footer.recompose

        async def counting():
            composed.append(1)
            await original()

        footer.recompose = counting
        app.query_one("#in-voltage").focus()
        await settle(pilot)
        before = keys_shown(app)
        composed.clear()
        for _ in range(2):  # Tab from entry to entry: Textual refreshes the bindings each time
            await pilot.press("tab")
            await settle(pilot)
            assert isinstance(app.focused, FieldInput)
        assert composed == [] and keys_shown(app) == before

        # projectile has no "Send to…" but an accuracy setting: the bar follows, recomposed once
        # (the switch refreshes the bindings three times before the first recompose runs)
        assert "Accuracy" not in before
        await app.card("projectile")  # built (as by the warm-up): no keys held back meanwhile
        await settle(pilot)
        assert composed == []
        await pilot.press("f5")  # Shooters: the projectile
        await settle(pilot)
        assert len(composed) == 1 and "Accuracy" in keys_shown(app)


async def test_entries_are_styled_once_mounted_not_while_built():
    """A card's entries change CSS classes as they are constructed (compact, and Input's -valid);
    Textual re-applied the whole stylesheet to each, mounted or not (3.6 ms an entry with every
    card built). Ours skip it until mounted, and mounting styles them with every class."""
    from textual.containers import Vertical
    from textual.widgets import Input

    from gearhead.tui.components.field_input import FieldCheckbox, FieldSelect

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        styled = []
        update = app.update_styles
        app.update_styles = lambda node=None, animate=True: (styled.append(node), update(node, animate))
        entries = [
            FieldInput(value="12", compact=True),
            FieldSelect([("a", 1), ("b", 2)], value=1, allow_blank=False, compact=True),
            FieldCheckbox("flag", compact=True),
        ]
        assert styled == []
        plain = Input(value="12", compact=True)  # Textual's own: styled while being built
        assert plain in styled
        box = Vertical(id="probe")
        await app.screen.mount(box)
        await box.mount_all(entries)
        await settle(pilot)
        for entry in entries:
            assert entry.has_class("-textual-compact")
            assert entry.styles.border_top[0] in ("", "none")  # the compact rule applied
        assert entries[0].styles.height.value == 1


async def test_a_focus_move_does_not_repaint_the_whole_screen():
    """Textual's Screen repaints itself whole when focus moves; HomeScreen leaves it to the two
    widgets concerned (tests/test_keystrokes.py checks in tmux that nothing is left stale)."""
    from gearhead.tui.app import HomeScreen

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        screen = app.screen
        assert isinstance(screen, HomeScreen)
        whole = []
        refresh = screen.refresh

        def counting(*regions, **kwargs):
            if not regions:
                whole.append(kwargs)
            return refresh(*regions, **kwargs)

        screen.refresh = counting
        for entry in ("#in-voltage", "#in-efficiency", "#in-torque"):
            app.query_one(entry).focus()
            await settle(pilot)
        assert app.focused.id == "in-torque"
        assert whole == []


def count_card_renders(monkeypatch, card_id: str) -> list[int]:
    """Counts content renders of the widgets inside one card (Textual's per-widget render)."""
    from textual.widget import Widget

    count = [0]
    render = Widget._render_content

    def counting(self, *args):
        if any(node.id == card_id for node in self.ancestors_with_self):
            count[0] += 1
        return render(self, *args)

    monkeypatch.setattr(Widget, "_render_content", counting)
    return count


def screen_cells(app) -> list[list[tuple[str, str]]]:
    """What the terminal shows: each cell's character and style. (A screenshot would differ where
    only the cuts between segments do: the compositor cuts lines at covered widgets' edges too.)"""
    return [
        [(char, str(segment.style)) for segment in strip for char in segment.text]
        for strip in app.screen._compositor.render_strips()
    ]


async def first_visit_renders(monkeypatch, rehearse: bool) -> tuple[int, bool]:
    """Content renders inside the beam card during its first visit (built out of sight before),
    and whether the screen stayed as it was while the card was rehearsed beneath it."""
    import asyncio

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await app.card("beam")
        await settle(pilot)
        before = screen_cells(app)
        unchanged = True
        if rehearse:
            app.REHEARSAL_SETTLED_S = app.REHEARSAL_MAX_S = 3.0  # long enough to look at the screen meanwhile
            rehearsal = asyncio.create_task(app._rehearse("beam"))
            await pilot.pause(0.5)  # the rehearsal's layout and first frames are done
            assert app._rehearsal  # under way
            unchanged = screen_cells(app) == before
            # laid out at its size but below the screen: none of it is composited (beneath the
            # card on screen it doubled the compositing of every frame: 110-465 ms)
            card = app._cards["beam"]
            assert card.region.height > 10 and card.region.width > 100
            visible = app.screen._compositor.visible_widgets
            assert not any(widget in visible for widget in card.walk_children(with_self=True))
            await rehearsal
            await settle(pilot)
            assert "beam" in app._drawn
            area = app._areas().get_pane("area-structure")
            assert not area.display and not area.styles.has_rule("layer")  # hidden as before
            assert not area.styles.has_rule("offset")
            unchanged = unchanged and screen_cells(app) == before
        count = count_card_renders(monkeypatch, "calc-beam")
        app.show_calculator("beam")
        await settle(pilot)
        assert app.current_calculator == "beam" and app._cards["beam"].region.height
        monkeypatch.undo()
        return count[0], unchanged


async def test_a_rehearsed_card_is_drawn_beneath_the_screen_and_its_first_visit_draws_little(monkeypatch):
    """A card laid out once below the screen and drawn into its widgets' caches (the warm-up's
    rehearsal) leaves the screen as it was, and its first visit finds its widgets sized and
    drawn: a handful of content renders instead of every widget's (two layouts, the table and
    chart redrawn)."""
    cold, _ = await first_visit_renders(monkeypatch, rehearse=False)
    warm, unchanged = await first_visit_renders(monkeypatch, rehearse=True)
    assert unchanged
    assert cold > 40  # every label, entry, selector, the table and chart (67 when written)
    assert warm < cold / 4  # 7 when written


async def test_a_key_ends_a_rehearsal_at_once_and_goes_where_it_asked(monkeypatch):
    """A rehearsal yields the screen to the user: F3 during the warm-up's rehearsal of the beam
    is handled at once (the step does not hold the app's message loop) and shows the beam card
    (the pane the key asked for stays shown, no longer beneath)."""
    import asyncio

    import gearhead.tui.app as app_module

    monkeypatch.setattr(app_module, "ORDER", ["motor", "beam"])  # built: motor, then beam
    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await app.card("beam")
        await settle(pilot)
        app.REHEARSAL_SETTLED_S = app.REHEARSAL_MAX_S = 30.0  # only the key can end it
        app.IDLE_BEFORE_BUILD_S = 0.0
        app.warm_up = True
        app._build_next()  # as its timer calls it: everything built, the beam not yet drawn
        for _ in range(100):
            await asyncio.sleep(0.02)
            if app._rehearsal:
                break
        assert app._rehearsal
        await asyncio.wait_for(pilot.press("f3"), 5.0)  # held until the rehearsal's end before
        app.warm_up = False
        await settle(pilot)
        assert app._rehearsal == []
        assert app.current_calculator == "beam" and app._cards["beam"].region.height
        assert not app._areas().get_pane("area-structure").styles.has_rule("layer")
        assert not app._areas().get_pane("area-structure").styles.has_rule("offset")
        assert app._cards["beam"] in app.screen._compositor.visible_widgets  # on screen, not below
        await pilot.press("f1")  # and back: the area it left is hidden as usual
        await settle(pilot)
        assert app.current_calculator == "motor" and not app._cards["beam"].region.height


async def test_a_card_built_out_of_sight_sizes_its_table_for_the_width_it_will_have():
    """Its results table is as wide as the one on screen, so its first visit keeps the rows it
    has instead of re-filling the table and measuring it again (an extra layout and frame)."""
    from textual.widgets._data_table import ColumnKey

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await app.card("beam")
        await settle(pilot)
        table = app._cards["beam"]._parts.table
        width = table.columns[ColumnKey("label")].width
        on_screen = app._cards["motor"].results_width
        cleared = []
        original = table.clear
        table.clear = lambda *a, **k: (cleared.append(1), original(*a, **k))[1]
        app.show_calculator("beam")
        await settle(pilot)
        assert table.size.width == on_screen > 0
        assert table.columns[ColumnKey("label")].width == width and cleared == []


async def test_a_rehearsal_in_another_area_sets_that_strips_card_aside_and_back():
    """Rehearsing the chain/belt card (Structure, whose strip shows the beam) shows only it
    beneath the screen: the beam's pane is set aside meanwhile (or it would be drawn as well)
    and is the Structure card again after, as F3 then shows."""
    import asyncio

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await app.card("beam")
        await app.card("chain_belt")
        await settle(pilot)
        beam_pane = app._strips["structure"].get_pane("tab-beam")
        assert beam_pane.display
        app.REHEARSAL_SETTLED_S = app.REHEARSAL_MAX_S = 3.0
        rehearsal = asyncio.create_task(app._rehearse("chain_belt"))
        await pilot.pause(0.5)
        assert app._rehearsal and not beam_pane.display
        assert app._cards["chain_belt"].region.height and not app._cards["beam"].region.height
        await rehearsal
        await settle(pilot)
        assert beam_pane.display and "chain_belt" in app._drawn
        await pilot.press("f3")
        await settle(pilot)
        assert app.current_calculator == "beam" and app._cards["beam"].region.height


async def test_a_card_built_in_steps_lets_a_key_through_and_ends_as_one_built_at_once(monkeypatch):
    """The warm-up builds a card's field rows a few at a time (a key waited for a whole card's
    mount, 90-230 ms): a key pressed meanwhile is handled before the build ends, and the card
    then has the same rows, shown or hidden alike, wired to its solve, as one built at once."""
    import asyncio

    from gearhead.tui.components.calculator_tab import CalculatorTab, FieldRow

    def rows(tab):
        return [(row.id, row.display) for row in tab.query(FieldRow)]

    app = GearheadApp(blink=False, initial="elevator", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        at_once = app._cards["elevator"]
        monkeypatch.setattr(CalculatorTab, "STEP_PAUSE_S", 0.3)  # slow steps: time for a key
        build = asyncio.create_task(app.card("arm", in_steps=True))
        await asyncio.sleep(0.2)
        assert not build.done()
        # (pilot.press waits for every widget's queue, the card's too: the key as a terminal's)
        await app._press_keys(["f3"])
        for _ in range(50):
            if app.current_area == "structure":
                break
            await asyncio.sleep(0.01)
        assert app.current_area == "structure" and not build.done()  # taken in the build
        stepped = await asyncio.wait_for(build, 10.0)
        await settle(pilot)
        assert stepped.in_steps and not at_once.in_steps
        assert len(rows(stepped)) == len(stepped.calculator.fields) > 2 * CalculatorTab.ROWS_PER_STEP
        assert stepped.solution is not None and stepped.solution.outputs
        assert all(entry.edited is not None for entry in stepped.query(FieldInput))
        # the same calculator built at once, out of sight too: the same rows, shown alike
        monkeypatch.setattr("gearhead.tui.app.get", lambda cid: stepped.calculator)
        twin = app._card("arm")
        app._strips["mechanisms"].get_pane("tab-elevator").mount(twin)
        await settle(pilot)
        assert rows(twin) == rows(stepped)
        assert twin.solution.outputs.keys() == stepped.solution.outputs.keys()


async def test_a_card_half_built_takes_no_card_action_until_it_is_built(monkeypatch):
    """A preset loaded into a card whose rows were still being mounted raised NoMatches: the
    card's keys (save, load, export…) wait for it to be built."""
    import asyncio

    from gearhead.tui.components.calculator_tab import CalculatorTab

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        monkeypatch.setattr(CalculatorTab, "STEP_PAUSE_S", 0.3)
        build = asyncio.create_task(app.card("arm", in_steps=True))
        await asyncio.sleep(0.2)
        app.show_calculator("arm")  # (its visit then hurries the build: looked at before that)
        assert app.current_calculator == "arm" and not build.done()
        for action in ("load_preset", "save_preset", "export"):
            assert app.check_action(action, ()) is False
        await asyncio.wait_for(build, 10.0)
        await settle(pilot)
        assert all(app.check_action(action, ()) for action in ("load_preset", "save_preset", "export"))


async def test_a_visit_to_a_card_built_in_steps_mounts_its_remaining_rows_at_once(monkeypatch):
    """The warm-up pauses between a card's row steps so a key gets through; once the user comes
    to that card, the pauses only keep them waiting: the rows left are mounted in one step."""
    import asyncio

    from gearhead.tui.components.calculator_tab import CalculatorTab, Form

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        monkeypatch.setattr(CalculatorTab, "STEP_PAUSE_S", 0.3)
        steps = []
        mount_all = Form.mount_all
        monkeypatch.setattr(
            Form,
            "mount_all",
            lambda self, rows, **kw: (steps.append(len(rows)), mount_all(self, rows, **kw))[1],
        )
        build = asyncio.create_task(app.card("arm", in_steps=True))
        for _ in range(500):  # the first step mounted (then a 0.3 s pause)
            if steps:
                break
            await asyncio.sleep(0.01)
        assert steps == [CalculatorTab.ROWS_PER_STEP]
        app.show_calculator("arm")
        await asyncio.wait_for(build, 10.0)
        await settle(pilot)
        fields = len(app._cards["arm"].calculator.fields)
        assert fields > 2 * CalculatorTab.ROWS_PER_STEP  # more than two steps' worth were left
        assert steps == [CalculatorTab.ROWS_PER_STEP, fields - CalculatorTab.ROWS_PER_STEP]
        assert app.current_calculator == "arm" and app._cards["arm"].region.height


async def test_the_warm_up_builds_every_card_then_rehearses_the_likeliest_visits_first():
    """Every card is built before any is rehearsed (a visit to a card not built is the longest),
    each in order of the likeliest first visits: the cards of the area on screen (a digit away),
    then what F2-F5 would show (a calculator picked in an area moves up with it), then the rest."""
    app = GearheadApp(blink=False, initial="gear_ratio", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        app._area_active["mechanisms"] = "elevator"  # as if picked there earlier
        cards, drawn = dict(app._cards), set(app._drawn)
        steps = []
        try:
            while (step := app._warm_up_next()) is not None and len(steps) < 40:
                steps.append(step)
                what, calc_id = step
                if what == "build":
                    app._cards[calc_id] = None  # the choice reads only which are there
                else:
                    app._drawn.add(calc_id)
        finally:
            app._cards, app._drawn = cards, drawn
    # gear_ratio is on screen (built and drawn at start)
    likely = ["motor", "ratio_distance", "ratio_finder", "elevator", "beam", "pneumatics", "projectile"]
    likely += [c for c in ORDER if c not in likely and c != "gear_ratio"]
    assert steps == [("build", c) for c in likely] + [("rehearse", c) for c in likely]


async def test_a_rehearsal_ends_once_its_layouts_settle():
    """A rehearsal waits for the layouts that follow the card's first (the sizes, the table,
    the chart) and ends once none came for REHEARSAL_SETTLED_S, not after a fixed wait."""
    import asyncio

    app = GearheadApp(blink=False, initial="motor", hide_timings=True)
    async with app.run_test(size=SIZE) as pilot:
        await settle(pilot)
        await app.card("beam")
        await settle(pilot)
        app.REHEARSAL_MAX_S = 60.0  # the old fixed wait: would outlast the 20 s below
        layouts, drawing = [], []  # when the screen was laid out; when the drawing began
        app.home.screen_layout_refresh_signal.subscribe(
            app._cards["beam"], lambda screen: layouts.append(monotonic()), immediate=True
        )
        draw = app._draw_into_caches
        app._draw_into_caches = lambda pane: (drawing.append(monotonic()), draw(pane))[1]
        began = monotonic()
        await asyncio.wait_for(app._rehearse("beam"), 20.0)
        assert "beam" in app._drawn and app._rehearsal == []
        before = [t for t in layouts if began <= t <= drawing[0]]
        # the card's first layout and the ones its sizes brought (the table, the chart), then
        # quiet: drawn right after the first layout, the card would be drawn half laid out
        assert len(drawing) == 1 and len(before) >= 2
        assert drawing[0] - before[-1] >= app.REHEARSAL_SETTLED_S
