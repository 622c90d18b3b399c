"""The Gearhead design card: one tab per registered calculator."""

from __future__ import annotations

import gc
import os
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

from textual import events
from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.message import Message
from textual.screen import Screen
from textual.widget import Widget

from gearhead.core.registry import AREAS, ORDER, TITLES, area_of, calculators, get
from gearhead.core.unit_systems import SYSTEM_LABELS, SYSTEMS

from .components.card_screen import CardScreen
from .components.key_bar import KeyBar
from .components.tab_strip import TabStrip
from .guard import guard, guarded

if TYPE_CHECKING:
    from .components.calculator_tab import CalculatorTab

# The cards, dialogs and their widgets (Select, plots …) are imported when first built, after the
# first frame: the app starts with the tab strips and the footer. A card is built on its first
# visit: a sheet, a results list and a few lines (sheet.py, results.py), tens of milliseconds.


def exact_text(value, output) -> str:
    """A result as an entry for another calculator: its display unit, every significant digit
    (the 5-figure display text would pass on a rounding error; the sheet shows 6)."""
    from gearhead.core import units

    if not isinstance(value.value, float):
        return value.text
    shown = units.to_unit(value.value, output.unit, output.quantity)
    return f"{shown!r} {output.unit}".rstrip()


def sent_text(values: dict[str, str], target) -> str:
    """What ctrl+g sent, as the target's sheet shows it (6 significant digits: the entries keep
    every digit, the notice showed float noise such as 12.700000000000001)."""
    from .components.sheet import shown_entry

    return ", ".join(
        f"{target.field(k).label} = {shown_entry(target.field(k), v)}" for k, v in values.items()
    )


class GearheadApp(App):
    CSS_PATH = Path(__file__).with_name("gearhead.tcss")  # absolute: subclasses live elsewhere
    TITLE = "Gearhead"
    SUB_TITLE = "mechanism design card"
    # below 120 columns inputs and results cannot sit side by side: gearhead.tcss stacks them
    HORIZONTAL_BREAKPOINTS = [(0, "-narrow"), (120, "-wide")]
    BINDINGS = [
        Binding("ctrl+s", "save_preset", "Save", tooltip="Save this tab as a TOML preset"),
        Binding("ctrl+o", "load_preset", "Load", tooltip="Load a preset into this tab"),
        Binding("ctrl+g", "send", "Send to…", tooltip="Send results to the calculator they feed"),
        Binding("ctrl+r", "accuracy", "Accuracy", tooltip="Accuracy vs time of this simulation"),
        Binding(
            "ctrl+y", "copy_share_code", "Copy", tooltip="Copy this tab as a share code (gh1:…, to share)"
        ),
        Binding("ctrl+e", "export", "Export", tooltip="Results or plot data as CSV or Markdown"),
        # priority: from inside a dialog's entry too (where Input binds ctrl+w to delete a word)
        Binding("ctrl+w", "sweep", "Sweep row", priority=True),
        Binding("ctrl+q", "quit", "Quit", priority=True),
        *(
            Binding(f"f{n}", f"area('{area}')", title, show=False, priority=True)
            for n, (area, (title, _)) in enumerate(AREAS.items(), 1)
        ),
        # the digit right after an F-key picks a calculator of that area (check_action lets it
        # through only then); priority, so the app takes it in the order typed, before any key
        # behind it reaches a widget
        *(Binding(str(n), f"pick({n})", show=False, priority=True) for n in range(1, 10)),
    ]

    def __init__(
        self,
        blink: bool = True,
        initial: str | None = None,
        hide_timings: bool = False,
        settings_file: dict | None = None,
        workbook=None,
        open_text: str | None = None,
    ) -> None:
        # NO_COLOR: Textual's Monochrome filter fails on a segment without a style (the chart's
        # canvas draws one before it has a size); its NoColor filter, used with ANSI colours,
        # takes them. Colours are off either way.
        super().__init__(ansi_color=True if "NO_COLOR" in os.environ else None)
        self.blink = blink  # tests switch the cursor blink off for deterministic snapshots
        self.hide_timings = hide_timings  # and hide wall-clock figures
        self.open_text = open_text  # a share code (or a link with one) to open once started
        self.initial = initial
        self.workbook = workbook  # a core.workbook.Workbook to open at start (`gearhead robot.toml`)
        self._cards: dict[str, CalculatorTab] = {}
        self._mounting: dict[str, object] = {}  # calc_id -> its AwaitMount, while mounting
        self._area_active: dict[str, str] = {}  # area -> the calculator shown there
        self._area = ""  # the area shown
        self._strips: dict[str, TabStrip] = {}  # area -> its calculator strip, built on its first visit
        self._strip_mounts: dict[str, object] = {}  # area -> the AwaitMount of a strip being built
        self._started = False  # the first frame is on screen
        self._pick_armed = False  # the last key was an F-key: a digit now picks a calculator
        self._picking = False  # ... and the key being handled is the one after it
        self._early_keys: list[events.Key] | None = []  # keys read before the first card is built
        self.unit_system = "calculator" if settings_file is None else settings_file.get("units", "calculator")

    def compose(self) -> ComposeResult:
        # Two strips: areas (F1-F5), then the calculators of the active area (digits 1-9 on the
        # focused strip). They come from the registry's tables, without importing any calculator.
        # One calculator strip per area (built on the area's first visit, hidden while
        # another area shows), and the cards below them, each shown or hidden by the app: no
        # TabbedContent, whose panes and switchers nested six containers above a card, each drawn
        # again under it on every frame.
        first = self.initial or ORDER[0]
        self._area_active = {area: first if first in ids else ids[0] for area, (_, ids) in AREAS.items()}
        self._area = area_of(first)
        yield TabStrip(
            [(f"area-{area}", f"F{n} {title}") for n, (area, (title, _)) in enumerate(AREAS.items(), 1)],
            active=f"area-{self._area}",
            id="areas",
        )
        yield self._new_strip(self._area)
        yield KeyBar()
        # the cards are mounted into this box, never painted itself (they cover it): a mount
        # repaints the parent, and into the screen that was the whole screen drawn once more in a
        # card's first visit, after the layout's paint
        self._card_box = Widget(id="cards")
        yield self._card_box

    def _new_strip(self, area: str) -> TabStrip:
        strip = self._strips[area] = TabStrip(
            [(f"tab-{cid}", f"{i} {TITLES[cid]}") for i, cid in enumerate(AREAS[area][1], 1)],
            active=f"tab-{self._area_active[area]}",
            id=f"calcs-{area}",
            classes="calculators",
        )
        return strip

    def _strip(self, area: str) -> TabStrip:
        """An area's calculator strip, built (mounted below the others) on its first visit."""
        strip = self._strips.get(area)
        if strip is None:
            last = list(self._strips.values())[-1]
            strip = self._new_strip(area)
            self._strip_mounts[area] = self.home.mount(strip, after=last)
        return strip

    def get_default_screen(self) -> Screen:
        return CardScreen(id="_default")  # a focus move does not repaint the whole screen

    @property
    def home(self) -> Screen:
        """The screen with the strips and cards (a dialog or the palette may be on top of it)."""
        return self.screen_stack[0]

    @guarded
    async def on_ready(self) -> None:
        self._started = True
        try:
            tab = await self.card(self.current_calculator)
            if self.workbook is not None:
                await self.open_workbook(self.workbook)
        finally:
            self._release_early_keys()
        if self.open_text:  # e.g. a served page's ?p=gh1:… (tui/serve.py)
            from gearhead.core import share
            from gearhead.core.errors import InputError

            try:
                preset = share.from_text(self.open_text)
            except InputError as exc:
                self.notify(
                    str(exc), title="Could not open the link's design", severity="error", markup=False
                )
                return
            if preset is not None:
                await self.open_preset(preset, tab)

    def open_workbook(self, book):
        """Show a workbook's cards over the calculator cards (Esc returns to them); awaitable."""
        from .components.workbook_screen import WorkbookScreen

        return self.push_screen(WorkbookScreen(book, self.blink, self.hide_timings))

    class EarlyKeysReleased(Message):
        """Posted once the first card has the keys: what was typed before it is taken now."""

    def _release_early_keys(self) -> None:
        # a message, not a loop here: keys read while the card was being built wait in the queue
        # ahead of it, and are kept too (re-posting the early ones put them behind those)
        self.post_message(self.EarlyKeysReleased())

    @guarded
    async def on_gearhead_app_early_keys_released(self, message: EarlyKeysReleased) -> None:
        """Keys typed before the first card could take them (they went to no widget and were
        lost: issue 40), taken in the order typed, before any key read after this."""
        early, self._early_keys = self._early_keys, None
        for key in early or ():
            await self.on_event(events.Key(key.key, key.character))

    async def on_event(self, event: events.Event) -> None:
        """Every key the app reads (before its bindings): an F-key arms the pick of a calculator by
        the next key, and any key ends it, so only F-key-then-digit picks (the digit's priority
        binding asks check_action, which reads this)."""
        if isinstance(event, events.Key) and not event.is_forwarded:
            if self._early_keys is not None:  # the first card is not built yet: kept for it
                self._early_keys.append(event)
                event.stop()
                return
            self._picking, self._pick_armed = self._pick_armed, False
        await super().on_event(event)

    async def card(self, calc_id: str) -> CalculatorTab:
        """The card of a calculator, built on its first visit."""
        tab = self._cards.get(calc_id)
        if tab is None:
            from .components.calculator_tab import CalculatorTab

            # recorded before the await: a second caller meanwhile waits for this mount
            tab = self._cards[calc_id] = CalculatorTab(
                get(calc_id), blink=self.blink, hide_timings=self.hide_timings, id=f"calc-{calc_id}"
            )
            tab.unit_system = self.unit_system
            tab.display = calc_id == self.current_calculator
            self._mounting[calc_id] = self._card_box.mount(tab)
        mounting = self._mounting.get(calc_id)
        strip = self._strip_mounts.get(area_of(calc_id))
        if mounting is not None or strip is not None:
            # no layout or frame while the card (or its area's strip) is composed: a frame of the
            # strip without the card, or half-built, was a whole layout and repaint more on a
            # first visit, drawn for nothing
            with self.batch_update():
                if strip is not None:
                    await strip
                    self._strip_mounts.pop(area_of(calc_id), None)
                if mounting is not None:
                    await mounting
            if mounting is not None:
                self._mounting.pop(calc_id, None)
                # what is built lives as long as the app: out of the collector's reach (an O(1)
                # move), a full collection walks only what came since, not every card, numpy and
                # Textual. Still pays (bench/bench_startup.py --gc, 3 fresh apps visiting all 18
                # cards, 2-core machine under load): without it a full collection of 62-329 ms
                # (median per card) fell inside the first visit of 9 of 18 cards, and of 3 repeat
                # visits (259-362 ms); with it, 22 ms in one first visit, 16 and 25 ms in two repeats
                gc.freeze()
                if calc_id == self.current_calculator:
                    self.home.set_focus(tab.sheet)  # the card shown takes the keys (show_calculator)
                    self.refresh_bindings()  # the footer shows ctrl+g / ctrl+r where they apply
        return tab

    _quitting = False  # ctrl+q taken: no card is mounted meanwhile, no other key acts

    @guarded
    def action_command_palette(self) -> None:
        """Textual's palette, with PageUp/PageDown safe as it opens (command_palette.py)."""
        from textual.command import CommandPalette

        from .components.command_palette import GearheadCommandPalette

        if self.use_command_palette and not CommandPalette.is_open(self):
            self.push_screen(GearheadCommandPalette(id="--command-palette"))

    @guarded
    async def action_quit(self) -> None:
        """Quit once the cards being mounted are: a quit pruned the screen a card was mounting
        into (F2 then ctrl+q in one burst: a MountError on the way out). An open workbook with
        unsaved changes asks first (save, discard, stay), once however often ctrl+q is pressed."""
        from .components.leave_screen import LeaveScreen
        from .components.workbook_screen import WorkbookScreen

        if isinstance(self.screen, LeaveScreen):
            return  # already asked
        book = next((s for s in self.screen_stack if isinstance(s, WorkbookScreen)), None)
        if book is not None and not self._quitting and book.unsaved_changes():
            book.leave(lambda: self.call_later(self._quit_now))
            return
        await self._quit_now()

    @guarded
    async def _quit_now(self) -> None:
        self._quitting = True
        try:
            for mount in [*self._strip_mounts.values(), *self._mounting.values()]:
                await mount
        finally:  # a failed mount is logged (guarded), and the app quits all the same
            self.exit()

    def card_ready(self, calc_id: str) -> bool:
        """The calculator's card is mounted, its sheet and results composed."""
        return calc_id in self._cards and calc_id not in self._mounting

    @guarded
    async def on_tab_strip_tab_activated(self, event: TabStrip.TabActivated) -> None:
        """A tab of a strip picked (a click, ← →, or show_calculator): show its card. (A strip
        posts this when its active tab changes, not when it is built with one.)"""
        strip_id = event.strip.id or ""
        if strip_id == "areas":
            self._show_area(event.tab_id.removeprefix("area-"))
        elif strip_id.startswith("calcs-"):
            area = strip_id.removeprefix("calcs-")
            self._area_active[area] = event.tab_id.removeprefix("tab-")
            if area == self._area:
                self._show_card(self._area_active[area])
        if not self._started or self._quitting:  # start-up: on_ready builds the first card
            return
        await self.card(self.current_calculator)
        self.refresh_bindings()

    def _show_area(self, area: str) -> None:
        """Show an area's strip and the card of the calculator last used there."""
        if area != self._area:
            self._area = area
            shown = self._strip(area)
            for strip in self._strips.values():
                if strip.display != (strip is shown):
                    strip.display = strip is shown
        self._show_card(self._area_active[area])

    def _show_card(self, calc_id: str) -> None:
        for cid, tab in self._cards.items():
            if tab.display != (cid == calc_id):
                tab.display = cid == calc_id

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if self._quitting:  # the F-keys are priority bindings: one after ctrl+q would mount a card
            return action == "quit"
        on_home = self.screen is self.home
        if action in ("area", "sweep"):  # not under a dialog: the card would change behind it
            return on_home
        if action == "pick":  # only right after an F-key (on_event), else the digit is typed
            return self._picking and on_home and parameters[0] <= len(AREAS[self._area][1])
        if action in ("send", "accuracy"):
            tab = self._cards.get(self._area_active.get(self.current_area, ""))
            if tab is None:  # not built yet (start-up): shown once the card is there
                return False
            calc = tab.calculator
            if action == "send":
                return tab.can_send()
            return calc.simulate is not None
        return True

    # ---- navigation ---------------------------------------------------------------------
    @property
    def current_area(self) -> str:
        return self._area

    @property
    def current_calculator(self) -> str:
        """Id of the calculator on screen: the active tab of the active area."""
        return self._area_active[self.current_area]

    @property
    def current_tab(self) -> CalculatorTab:
        return self._cards[self.current_calculator]

    def show_calculator(self, calc_id: str) -> None:
        """Switch to a calculator's card and give its sheet the keys, in one focus change (a card
        not built yet takes focus once mounted: `card`). The strips only show where one is: the
        keys typed after a switch go to the card, in the order typed."""
        area = area_of(calc_id)
        self._area_active[area] = calc_id
        if area in self._strips:  # else built now, with this tab active
            self._strips[area].active = f"tab-{calc_id}"
        self._strip(area)
        self.home.query_one("#areas", TabStrip).active = f"area-{area}"
        self._show_area(area)
        if self.card_ready(calc_id):
            self.home.set_focus(self._cards[calc_id].sheet)

    @guarded
    async def action_focus_next(self) -> None:
        """Tab on a calculator strip goes into the card it shows (its sheet). Textual's focus
        chain, taken while a card switches (F5 2 Tab in a burst), reached the card being left and
        TabbedContent then showed that one again."""
        strip = self.focused
        on_strip = isinstance(strip, TabStrip) and (strip.id or "").startswith("calcs-")
        if self.screen is self.home and (on_strip or strip is None):  # None: a card to come
            tab = await self.card(self.current_calculator)
            self.home.set_focus(tab.sheet)
            return
        super().action_focus_next()

    @guarded
    async def action_area(self, area: str) -> None:
        """F1-F5: show an area at the calculator last used there, its sheet focused; a digit
        typed next picks a calculator of the area (two keys to any calculator: action_pick). A
        card not built yet is built here, before the next frame: the pane and its card are drawn
        in one frame."""
        self.show_calculator(self._area_active[area])
        await self.card(self.current_calculator)  # and its strip, if built now
        self._pick_armed = True

    @guarded
    async def action_pick(self, n: int) -> None:
        """The digit after an F-key: the area's n-th calculator (check_action lets only that
        digit through, and only for a calculator the area has)."""
        calc_id = AREAS[self._area][1][n - 1]
        self.show_calculator(calc_id)
        await self.card(calc_id)

    DIGITS = "123456789"  # ASCII only: '²' or '①' pass str.isdigit() and int() refuses them

    @guarded
    async def on_key(self, event: events.Key) -> None:
        """A digit on a focused tab strip picks its n-th tab (the sheet never sees it: a strip is
        focused, not the sheet); ↓ there goes into the card. The pick is made here, at once (show_calculator), not by the
        strip's TabActivated message: a Tab typed right after the digit would find the card left
        still recorded as shown."""
        character = event.character or ""
        strip = self.focused
        owner = (strip.id or "") if isinstance(strip, TabStrip) else ""
        if event.key == "down" and owner.startswith("calcs-") and not self._quitting:
            event.stop()  # ↓ from the strip goes into the card, as Tab does (a strip has no ↓ of its own)
            await self.action_focus_next()
            return
        if len(character) != 1 or character not in self.DIGITS or self._quitting:
            return
        n = int(character)
        if owner.startswith("calcs-"):
            ids = AREAS[owner.removeprefix("calcs-")][1]
            if n <= len(ids):
                event.stop()
                self.show_calculator(ids[n - 1])
                await self.card(ids[n - 1])  # in the frame that shows its pane (action_area)
        elif owner == "areas":
            if n <= len(AREAS):
                event.stop()
                await self.action_area(list(AREAS)[n - 1])

    def set_unit_system(self, system: str, remember: bool = True) -> None:
        """The units preference for every card (each built card solves and redraws), kept in the
        user's config.toml."""
        self.unit_system = system
        for tab in self._cards.values():
            tab.set_unit_system(system)
        if remember:
            from . import settings

            try:
                where = settings.save({**settings.load(), "units": system})
                self.notify(f"Results in {SYSTEM_LABELS[system]} (saved in {where})", markup=False)
            except OSError as exc:
                self.notify(
                    f"Results in {SYSTEM_LABELS[system]}; could not save the setting "
                    f"({exc.strerror or type(exc).__name__})",
                    severity="warning",
                    markup=False,
                )

    # ---- actions ------------------------------------------------------------------------
    @guarded
    async def action_save_preset(self) -> None:
        tab = await self.card(self.current_calculator)  # a key on a card still being built waits for it

        def saved(path) -> None:
            if path is not None:
                self.notify(f"Saved {path}", title="Preset saved", markup=False)  # a path may hold "["

        name, description = tab.preset_meta
        from .components.preset_screens import SavePresetScreen

        self.push_screen(
            SavePresetScreen(
                tab.calculator.id, tab.current_inputs(), self.blink, name=name, description=description
            ),
            guard(self, saved),
        )

    async def open_preset(self, preset, tab: CalculatorTab) -> None:
        """A preset's inputs into its calculator's card (`tab`'s, or the card of the calculator the
        preset is for, opened), with a notice and its warnings."""
        target = tab
        if preset.calculator != tab.calculator.id:  # another calculator's: open that one
            self.show_calculator(preset.calculator)
            target = await self.card(preset.calculator)
        # a preset is a whole design: fields it omits take their defaults (DESIGN.md),
        # not whatever was typed before, so the card solves what the CLI solves
        defaults = {f.name: type(target).initial_entry(f) for f in target.calculator.fields}
        target.set_entries({**defaults, **preset.inputs})
        target.preset_meta = (preset.name, preset.description)  # the save dialog offers them
        where = "" if target is tab else f" (a {target.calculator.title} preset: opened that card)"
        self.notify(f"Loaded {preset.name}{where}", title="Preset loaded", markup=False)
        for warning in preset.warnings:  # e.g. a junk value in a field this mode ignores
            self.notify(warning, title="Preset warning", severity="warning", markup=False)

    @guarded
    async def action_load_preset(self) -> None:
        tab = await self.card(self.current_calculator)  # a key on a card still being built waits for it

        async def loaded(preset) -> None:
            from gearhead.core.workbook import Workbook

            if isinstance(preset, Workbook):  # a workbook file typed or browsed to
                self.open_workbook(preset)
                return
            if preset is not None:
                await self.open_preset(preset, tab)

        from .components.preset_screens import LoadPresetScreen

        self.push_screen(LoadPresetScreen(tab.calculator.id, self.blink), guard(self, loaded))

    @guarded
    async def action_copy_preset(self) -> None:
        """ctrl+y: the tab as preset TOML on the clipboard (OSC 52), to paste in a chat or file."""
        from gearhead.core.export import preset_toml

        tab = await self.card(self.current_calculator)  # a key on a card still being built waits for it
        name, description = tab.preset_meta
        self.copy_to_clipboard(preset_toml(tab.calculator.id, tab.current_inputs(), name, description))
        self.notify(
            f"{tab.calculator.title} copied as preset TOML; paste it into ctrl+o of any "
            f"Gearhead or save it as a .toml file",
            title="Copied",
            markup=False,
        )

    @guarded
    async def action_copy_share_code(self) -> None:
        """ctrl+y: the tab as a share code (core/share.py): one line that survives a chat or a
        terminal's paste, where the TOML's line breaks did not; ctrl+o anywhere reads it."""
        from gearhead.core import share
        from gearhead.core.presets import Preset

        tab = await self.card(self.current_calculator)  # a key on a card still being built waits for it
        name, description = tab.preset_meta
        preset = Preset(
            tab.calculator.id, name or f"{tab.calculator.id} design", description, tab.current_inputs()
        )
        self.copy_to_clipboard(share.encode(preset))
        self.notify(
            f"{tab.calculator.title} copied as a share code; paste it into ctrl+o of any Gearhead, or "
            f"`gearhead solve {tab.calculator.id} --preset CODE` (the palette's 'Copy as preset TOML' copies the file)",
            title="Copied",
            markup=False,
        )

    @guarded
    async def action_export(self) -> None:
        tab = await self.card(self.current_calculator)  # a key on a card still being built waits for it
        if tab.solution is None:
            self.notify("Fix the highlighted input first.", severity="error")
            return
        from .components.export_screen import ExportScreen

        plot = tab.plot.current if tab.plot is not None else None

        def done(message) -> None:
            if message:
                self.notify(message, title="Exported", markup=False)

        self.push_screen(ExportScreen(tab.calculator, tab.solution, plot, self.blink), guard(self, done))

    @guarded
    async def action_send(self) -> None:
        """Send this tab's results into the calculator it feeds (e.g. lead screw → gear ratio)."""
        tab = await self.card(self.current_calculator)  # a key on a card still being built waits for it
        if tab.calculator.tables and tab.error is None and tab.selected_row() is not None:
            await self._send_row(tab)
            return
        exports = tab.calculator.exports
        if not exports:
            self.notify("This calculator has nothing to send.", severity="warning")
            return
        if tab.solution is None or tab.error is not None:
            self.notify("Fix the highlighted input first.", severity="error")
            return
        for target_id, mapping in exports.items():
            target = await self.card(target_id)
            values = {
                field: exact_text(tab.solution.outputs[out], tab.calculator.output(out))
                for field, out in mapping.items()
                if out in tab.solution.outputs
            }
            if not values:  # e.g. drivetrain's forward mode has no ratio to send
                self.notify("Nothing to send in this mode.", severity="warning")
                continue
            target.set_entries(values)
            self.show_calculator(target_id)
            self.notify(
                sent_text(values, target.calculator),
                markup=False,
                title=f"Sent to {target.calculator.title}",
            )

    async def _send_row(self, tab: CalculatorTab) -> None:
        """Send the table row under the cursor (e.g. one ratio-finder stage) to the calculator
        whose fields it fills: the first target all of whose columns the row has."""
        table, row = tab.selected_row()
        for target_id, mapping in table.exports.items():
            if all(column in row for column in mapping.values()):
                target = await self.card(target_id)
                values = {
                    field: exact_text(row[column], table.column(column)) for field, column in mapping.items()
                }
                target.set_entries(values)
                self.show_calculator(target_id)
                self.notify(
                    sent_text(values, target.calculator),
                    markup=False,
                    title=f"Sent to {target.calculator.title}",
                )
                return
        self.notify(
            "This row has nothing another calculator takes (a planetary stage, or no belt long enough).",
            severity="warning",
            markup=False,
        )

    @guarded
    async def action_accuracy(self) -> None:
        """Run the current simulation at every accuracy level (the accuracy-vs-time view)."""
        tab = await self.card(self.current_calculator)  # a key on a card still being built waits for it
        if tab.calculator.simulate is None:
            self.notify("Only simulations have an accuracy setting.", severity="warning")
            return
        if tab.solution is None or tab.error is not None:
            self.notify("Fix the highlighted input first.", severity="error")
            return
        from gearhead.core.errors import InputError
        from gearhead.core.model import parse_inputs
        from gearhead.core.tolerance import split_inputs

        try:  # the nominal values: a tolerance (`15 lb ± 1 lb`) is not what the ladder varies
            nominal, tolerances = split_inputs(tab.calculator, tab.entries)
            values, _ = parse_inputs(tab.calculator, nominal)
        except InputError as exc:
            self.notify(str(exc), severity="error", markup=False)
            return
        if tolerances:
            self.notify(
                f"The accuracy view runs the nominal values (tolerances on {', '.join(tolerances)} aside).",
                markup=False,
            )
        from .components.accuracy_screen import AccuracyScreen

        self.push_screen(AccuracyScreen(tab.calculator, values, self.hide_timings))

    @guarded
    async def action_sweep(self) -> None:
        """The sweep view over the focused input (or the first numeric one): core.sweep in a thread."""
        from .components.sweep_screen import SweepScreen

        tab = await self.card(self.current_calculator)
        field = tab.sheet.current_field  # the row under the sheet's cursor
        name = field.name if field is not None else None
        shown = tuple(tab.solution.outputs) if tab.solution is not None else ()
        self.push_screen(
            SweepScreen(tab.calculator, dict(tab.entries), name, self.blink, self.hide_timings, shown)
        )

    @guarded
    async def action_fit_from_log(self) -> None:
        """The card's model fitted from a SysId log (fit_screen.py); Apply sets the fitted entries."""
        from gearhead.core.fit import KINDS

        tab = await self.card(self.current_calculator)
        if tab.calculator.id not in KINDS:
            self.notify(
                "Only the elevator, arm, flywheel and sprint cards fit from a log.", severity="warning"
            )
            return
        from .components.fit_screen import FitScreen

        def applied(values) -> None:
            if values:
                tab.set_entries(values)
                self.notify(sent_text(values, tab.calculator), title="Fitted entries applied", markup=False)

        self.push_screen(
            FitScreen(tab.calculator, dict(tab.entries), self.blink, self.hide_timings), guard(self, applied)
        )

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        # each command's callback is guarded (the actions by their decorator, the lambdas here)
        yield from super().get_system_commands(screen)
        from .components.workbook_screen import WorkbookScreen

        if isinstance(screen, WorkbookScreen):  # its own commands, not the calculator card's behind it
            yield from self._workbook_commands(screen)
            return
        yield SystemCommand(
            "Save preset", "Save the current tab's inputs as a TOML preset", self.action_save_preset
        )
        yield SystemCommand(
            "Load preset", "Load a built-in or user preset into the current tab", self.action_load_preset
        )
        yield SystemCommand(
            "Copy share code",
            "Copy the current tab as a gh1: share code (ctrl+y)",
            self.action_copy_share_code,
        )
        yield SystemCommand(
            "Copy as preset TOML", "Copy the current tab as preset text, to share", self.action_copy_preset
        )
        yield SystemCommand(
            "Export results", "The results table or the plot's data as CSV or Markdown", self.action_export
        )
        for system in SYSTEMS:
            yield SystemCommand(
                f"Units: {SYSTEM_LABELS[system]}",
                "Show every result in these units (remembered)",
                guard(self, lambda s=system: self.set_unit_system(s)),
            )
        yield SystemCommand(
            "Accuracy vs time", "Run the current simulation at every accuracy level", self.action_accuracy
        )
        yield SystemCommand(
            "Sweep…", "Vary the focused input over a range: plot, table, CSV", self.action_sweep
        )
        from gearhead.core.fit import KINDS

        if self.current_calculator in KINDS:
            yield SystemCommand(
                "Fit from log…",
                "Fit this card's model from a SysId log (.wpilog, .csv); Apply sets the fitted entries",
                self.action_fit_from_log,
            )
        for calc in calculators().values():
            yield SystemCommand(
                f"Open {calc.title}", calc.summary, guard(self, lambda cid=calc.id: self.show_calculator(cid))
            )
            if calc.exports:
                targets = ", ".join(calculators()[t].title for t in calc.exports if t in calculators())
                yield SystemCommand(
                    f"Send {calc.title} results to {targets}",
                    "Copy the matching outputs into that calculator's inputs",
                    lambda cid=calc.id: self._send_from(cid),
                )

    def _workbook_commands(self, book) -> Iterable[SystemCommand]:
        """A workbook screen's palette: what its keys do, and the fit of its card. The calculator
        cards' commands (presets, share codes, export, sweep, accuracy, units, open, send) act on the
        cards hidden behind it (a workbook shows its units as its file gives them), so they are not
        offered here (their keys say so: action_not_here)."""
        yield SystemCommand(
            "Save workbook", "Write the workbook's entries to its file (ctrl+s)", book.action_save
        )
        yield SystemCommand("Next card", "The workbook's next card (ctrl+right)", lambda: book.action_step(1))
        yield SystemCommand(
            "Previous card", "The workbook's previous card (ctrl+left)", lambda: book.action_step(-1)
        )
        if book.match_view is not None:
            yield SystemCommand(
                "Match", "The match card: one battery, every mechanism (ctrl+t)", book.action_match
            )
        yield SystemCommand("Close workbook", "Back to the calculator cards (Esc)", book.action_close)
        fitted = book.fit_card()
        if fitted is not None:
            yield SystemCommand(
                f"Fit {fitted.card_name} from log…",
                f"Fit the workbook's {fitted.card_name} card from a SysId log (.wpilog, .csv); "
                "Apply sets its fitted entries (linked fields are left as they are)",
                book.action_fit_from_log,
            )

    @guarded
    async def _send_from(self, calc_id: str) -> None:
        self.show_calculator(calc_id)
        await self.card(calc_id)
        await self.action_send()


def run(open_text: str | None = None, workbook=None) -> str | None:
    """Run the app until it quits: None, or Textual's report of an exception that stopped it.

    Our handlers catch their own exceptions (guard.py); one that still reaches Textual ends the
    app, and Textual prints its traceback on sys.stderr once the terminal is given back. Textual
    has no public hook to print something else (its `_handle_exception` and `error_console` are
    private), so sys.stderr is a buffer while the app runs (the screen itself is drawn on
    sys.__stderr__): cli.main logs the report and says one line. A clean exit passes on what the
    buffer holds."""
    import contextlib
    import io

    from . import settings

    app = GearheadApp(settings_file=settings.load(), open_text=open_text, workbook=workbook)
    report = io.StringIO()
    with contextlib.redirect_stderr(report):
        app.run()
    if not app.return_code:  # 0, or None: never started (no failure either)
        sys.stderr.write(report.getvalue())
        return None
    return report.getvalue() or f"the app stopped with code {app.return_code} and no report"
