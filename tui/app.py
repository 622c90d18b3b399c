"""The Gearhead design card: one tab per registered calculator."""

from __future__ import annotations

import gc
from asyncio import sleep
from collections.abc import Iterable
from functools import wraps
from pathlib import Path
from time import monotonic
from typing import TYPE_CHECKING

from textual import events, work
from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.content import Content
from textual.reactive import Reactive
from textual.screen import Screen
from textual.widget import Widget
from textual.widgets import Tab, TabbedContent, TabPane, Tabs

from gearhead.core.registry import AREAS, ORDER, TITLES, area_of, calculators, get
from gearhead.core.unit_systems import SYSTEM_LABELS, SYSTEMS

from .components.footer import KeyFooter

if TYPE_CHECKING:
    from .components.calculator_tab import CalculatorTab

# The cards, dialogs and their widgets (DataTable, Select, plots …) are imported when first built,
# after the first frame: the app starts with only the tab strips and the footer.


class HomeScreen(Screen):
    """The screen with the strips and cards. Textual's Screen repaints itself whole when focus
    moves (its `focused` reactive repaints): every Tab between fields redrew all ~100 visible
    widgets (about 30 ms), and a card switch did it twice. The widgets gaining and losing focus
    restyle and repaint themselves; nothing else on the screen changes."""

    focused: Reactive[Widget | None] = Reactive(None, repaint=False)


def exact_text(value, output) -> str:
    """A result as an entry for another calculator: its display unit, every significant digit
    (the 5-figure display text would pass on a rounding error)."""
    from gearhead.core import units

    if not isinstance(value.value, float):
        return value.text
    shown = units.to_unit(value.value, output.unit, output.quantity)
    return f"{shown!r} {output.unit}".rstrip()


class Closing(Exception):
    """The app is closing: a strip or card awaited (built on a key, by the warm-up) is gone or
    going (F2 then ctrl+q in one burst printed a traceback from the strip's pruned panes)."""


def until_closing(handler):
    """An async handler that awaits a strip or card ends quietly if the app closes meanwhile."""

    @wraps(handler)
    async def run(*args, **kwargs):
        try:
            return await handler(*args, **kwargs)
        except Closing:
            return None

    return run


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
        Binding("ctrl+y", "copy_preset", "Copy", tooltip="Copy this tab as preset TOML (to share)"),
        Binding("ctrl+e", "export", "Export", tooltip="Results or plot data as CSV or Markdown"),
        # priority: from inside a field too (where Input binds ctrl+w to delete a word); not on the footer
        Binding("ctrl+w", "sweep", "Sweep", show=False, priority=True),
        Binding("ctrl+q", "quit", "Quit"),
        *(
            Binding(f"f{n}", f"area('{area}')", title, show=False, priority=True)
            for n, (area, (title, _)) in enumerate(AREAS.items(), 1)
        ),
    ]

    def __init__(
        self,
        blink: bool = True,
        initial: str | None = None,
        hide_timings: bool = False,
        settings_file: dict | None = None,
        warm_up: bool = False,
    ) -> None:
        super().__init__()
        # build the other cards in idle moments after the first: on in the real app (run());
        # off by default so a pilot test that ends early never closes the app mid-mount
        self.warm_up = warm_up
        self.blink = blink  # tests switch the cursor blink off for deterministic snapshots
        self.hide_timings = hide_timings  # and hide wall-clock figures
        self.initial = initial
        self._cards: dict[str, CalculatorTab] = {}
        self._mounting: dict[str, object] = {}  # calc_id or area -> its AwaitMount
        self._built: set[str] = set()  # calculators whose card is mounted and composed
        self._area_pressed = ("", 0.0)  # the last F-key's area and when: a digit may follow it
        self._last_key = 0.0  # monotonic time of the last key or click (warm-up waits for a pause)
        self._started = False  # the first frame is on screen
        self._area_active: dict[str, str] = {}  # area -> the calculator shown there
        # area -> its calculator strip, once created: found without a query (a query walks every
        # widget of every card built: 60-80 ms per switch once the cards are up)
        self._strips: dict[str, TabbedContent] = {}
        self._strips_built: set[str] = set()  # strips whose tabs are composed (a pick can be shown)
        self._picked: dict[str, str] = {}  # area -> calculator picked while its strip was mounting
        self._drawn: set[str] = set()  # calculators whose card has been on screen or rehearsed
        self._rehearsal: list[TabPane] = []  # panes shown beneath the screen's card right now
        self._set_aside: list[TabPane] = []  # a strip's own card, hidden while another rehearses
        self._laid_out_at = 0.0  # monotonic time of the home screen's last layout
        self._quitting = False  # ctrl+q taken: nothing new is built or shown meanwhile
        self.unit_system = "calculator" if settings_file is None else settings_file.get("units", "calculator")

    def get_default_screen(self) -> Screen:
        return HomeScreen(id="_default")

    def compose(self) -> ComposeResult:
        # Two strips: areas (F1-F5), then the calculators of the active area (digits 1-9 on the
        # focused strip). A calculator added to one area never moves another area's strip.
        # Only the first area's strip is built before the first frame, and no card: they come
        # from the registry's tables, without importing any calculator. The rest is built on
        # first visit.
        first = self.initial or ORDER[0]
        self._area_active = {area: first if first in ids else ids[0] for area, (_, ids) in AREAS.items()}
        with TabbedContent(initial=f"area-{area_of(first)}", id="areas"):
            for n, (area, (title, _)) in enumerate(AREAS.items(), 1):
                with TabPane(Content(f"F{n} {title}"), id=f"area-{area}"):
                    if area == area_of(first):
                        yield self._strip(area)
        yield KeyFooter()

    def _strip(self, area: str) -> TabbedContent:
        strip = TabbedContent(
            initial=f"tab-{self._area_active[area]}", id=f"calcs-{area}", classes="calculators"
        )
        for i, cid in enumerate(AREAS[area][1], 1):
            strip.compose_add_child(TabPane(Content(f"{i} {TITLES[cid]}"), id=f"tab-{cid}"))
        self._strips[area] = strip
        return strip

    @property
    def home(self) -> Screen:
        """The screen with the strips and cards (a dialog or the palette may be on top of it)."""
        return self.screen_stack[0]

    _areas_found: TabbedContent | None = None

    def _areas(self) -> TabbedContent | None:
        """The area strip on the home screen; None while the app is closing. Found once: a query
        walks every widget of every card built (0.6 s of a 1.8 s first visit went to
        check_action asking it for the footer's bindings)."""
        areas = self._areas_found
        if areas is None or not areas.is_attached:
            found = self.home.query("#areas") if self._screen_stack else ()
            areas = self._areas_found = found.first(TabbedContent) if found else None
        return areas if areas is not None and areas.is_attached else None

    async def strip(self, area: str) -> TabbedContent:
        """An area's calculator strip, built on the area's first visit."""
        if area not in self._mounting:
            composed = self._strips.get(area)
            if composed is not None:  # composed with the app (the first area)
                self._strips_built.add(area)
                return composed
            self._mounting[area] = self._area_pane(area).mount(self._strip(area))
        # a strip being mounted by another caller (the warm-up, a tab switch) is in the DOM before
        # its panes are: wait for the whole mount
        await self._mounting[area]
        self._check_open()
        strip = self._strips[area]
        self._strips_built.add(area)
        picked = self._picked.pop(area, None)
        if picked is not None:  # a key chose a calculator there while the strip was mounting
            self._area_active[area] = picked
            strip.active = f"tab-{picked}"
        return strip

    def _check_open(self) -> None:
        """Raises Closing once the app is closing (exit() called: its widgets are being pruned)."""
        if self._quitting or self._exit or not self.is_running or self._areas() is None:
            raise Closing

    def _area_pane(self, area: str) -> TabPane:
        self._check_open()
        return self._areas().get_pane(f"area-{area}")

    @until_closing
    async def on_ready(self) -> None:
        self._started = True
        self.home.screen_layout_refresh_signal.subscribe(self, self._laid_out, immediate=True)
        await self.card(self.current_calculator)
        self._drawn_now()
        if self.warm_up:
            self._freeze_heap()
            self._import_the_rest()

    # ---- the garbage collector ------------------------------------------------------------
    # Python's full collection walks every object alive: 90 ms with the first card up, 455 ms
    # with every card built (gc.collect, 428 000 objects), a stall wherever it falls (a key,
    # a first visit: two of them in a 1.5 s first visit of the beam). The cards and modules live
    # as long as the app, so once each is built the heap is frozen (gc.freeze): collections
    # then walk only what came after. Showing a card leaves its drawing caches behind (60 000
    # objects on a first visit: a 67 ms full collection 0.4 s after the key), so pauses are
    # used to collect and freeze again, and full collections are made 10x rarer meanwhile
    # (they then come in pauses, not in a burst of keys). The first freeze collects the young
    # generations only (a full pass over the start-up heap is the 90 ms above); a cycle that
    # dies among frozen objects stays until exit. Only with the warm-up (the real app): test
    # apps come and go in one process.
    _frozen = False
    _thresholds: tuple[int, int, int] | None = None  # the collector's own, restored at exit
    FULL_COLLECTION_EVERY = 100  # young collections per full one (Python's default: 10)

    def _freeze_heap(self, full: bool = False) -> None:
        if not self.is_running:  # closing: on_unmount may already have released the heap
            return
        if self._thresholds is None:
            self._thresholds = gc.get_threshold()
            young, middle, _ = self._thresholds
            gc.set_threshold(young, middle, self.FULL_COLLECTION_EVERY)
        gc.collect(2 if full else 1)
        gc.freeze()
        self._frozen = True

    def _tidy_heap(self) -> None:
        """In a pause: collect what was promoted since the last freeze, and freeze the rest. Not
        while a notification shows: it dies in seconds, and frozen its cycles would stay."""
        if gc.get_count()[2] and not len(self._notifications):  # objects were promoted since
            self._freeze_heap(full=True)

    def on_unmount(self) -> None:
        if self._frozen:  # the app's objects can be collected again once it is gone
            gc.unfreeze()
            self._frozen = False
        if self._thresholds is not None:
            gc.set_threshold(*self._thresholds)
            self._thresholds = None

    # ---- warming up after the first card ------------------------------------------------
    # A card is built on the UI thread (Textual widgets must be); importing its calculator
    # module (and the widget modules) is the larger part of a first visit. So once the first
    # card is up, a thread imports every calculator, then the other strips and cards are built
    # one after another while no key arrives (a card mounts in many small steps, the longest
    # about 35 ms once the heap is frozen: a key arriving meanwhile waits at most that). A first
    # visit later finds its card ready, built while the user was reading, not while they switched.
    AREA_DIGIT_S = 2.0  # a digit this soon after an F-key picks in that area, focused or not
    IDLE_BEFORE_BUILD_S = 0.75  # no key for this long: the user is reading, build the next card
    BUSY_RETRY_S = 0.1  # a card is solving or drawing its chart: build the next after it
    TIDY_EVERY_S = 1.0  # once every card is built: look for a pause to tidy the heap this often
    # a tidy after a first visit walks ~75 000 objects (73 ms): wait for a pause a key is
    # unlikely to end soon, not the first lull after the card is drawn
    IDLE_BEFORE_TIDY_S = 2.0

    @work(thread=True, group="warm-up", exit_on_error=False)
    def _import_the_rest(self) -> None:
        calculators()  # imports every calculator module (numpy, never pint or scipy)
        from .components import accuracy_screen, export_screen, preset_screens  # noqa: F401

        try:
            self.call_from_thread(self.set_timer, self.IDLE_BEFORE_BUILD_S, self._build_next)
        except RuntimeError:  # the app closed meanwhile
            pass

    def _build_next(self) -> None:
        """The warm-up's next step, run as a task of its own: a timer's callback runs inside the
        app's message loop, so awaiting a mount or a rehearsal there held every key back until
        it ended (a key waited for a whole card's mount)."""
        if self.is_running:
            self.run_worker(self._warm_up_step(), group="warm-up", exit_on_error=False)

    @until_closing
    async def _warm_up_step(self) -> None:
        if not self.warm_up or not self.is_running or not self._screen_stack:  # off, or closed
            return
        areas = self._areas()
        if areas is None or areas.screen is not self.screen:  # closing, or a dialog is up: later
            if self.is_running:
                self.set_timer(self.IDLE_BEFORE_BUILD_S, self._build_next)
            return
        idle = monotonic() - self._last_key
        if idle < self.IDLE_BEFORE_BUILD_S:  # typing: look again once a pause could have begun
            self.set_timer(self.IDLE_BEFORE_BUILD_S - idle, self._build_next)
            return
        if any(c.busy for c in self._cards.values()):  # a solve or chart first (a new card's own)
            self.set_timer(self.BUSY_RETRY_S, self._build_next)
            return
        step = self._warm_up_next()
        if step is None:  # every card built and drawn: keep the heap tidy in longer pauses
            if idle >= self.IDLE_BEFORE_TIDY_S:
                self._tidy_heap()
            self.set_timer(self.TIDY_EVERY_S, self._build_next)
            return
        what, calc_id = step
        try:
            if what == "build":
                await self.card(calc_id, in_steps=True)
            else:
                await self._rehearse(calc_id)
        finally:  # the warm-up goes on (the worker swallows an error, and its timer with it)
            self._freeze_heap()
            if self.is_running:
                self.set_timer(0.05, self._build_next)

    def _warm_up_next(self) -> tuple[str, str] | None:
        """The warm-up's next step: ("build" or "rehearse", calculator), None once all are done.
        Every card is built before any is rehearsed: a first visit to a card not built is the
        longest (F3 then 2 at 8 s: 425 ms when the F-key cards were readied first, 193 ms built
        but not rehearsed). Each in order of the likeliest first visits: the cards of the area on
        screen (a digit away), the cards the F-keys show, then the rest."""
        area = self.current_area if self._areas() is not None else None
        shown_by_keys = set(self._area_active.values())
        likely = sorted(ORDER, key=lambda c: (area_of(c) != area, c not in shown_by_keys))
        for calc_id in likely:
            if calc_id not in self._cards:
                return "build", calc_id
        for calc_id in likely:
            if calc_id not in self._drawn:
                return "rehearse", calc_id
        return None

    # ---- rehearsals: each card laid out and drawn once before its first visit ---------------
    # A card shown for the first time has no size and nothing drawn: Textual lays it out, draws
    # every widget, then lays it out again as the new sizes come in, and the results table and
    # chart redraw at their size (beam: frames of 250, 120 and 30 ms). A card laid out and drawn
    # before is one frame of about 60 ms. So once every card is built (_warm_up_next), each is
    # shown once while the user reads: in a lower layer of its switcher (gearhead.tcss), so it
    # gets the size it will have, and below the screen (an offset), so it is laid out but never
    # composited (drawn beneath the card on screen it doubled every frame's compositing: stalls
    # of 110-465 ms). Once its layouts settle, its widgets draw their lines into their caches, a
    # few at a time, and it is hidden again. A key ends a rehearsal at once (it waits at most for
    # a frame or a step in flight).
    REHEARSAL_SETTLED_S = 0.15  # no layout of the screen for this long: the card is laid out
    REHEARSAL_MAX_S = 1.0  # after the first layout, at most (a chart that keeps redrawing)
    DRAW_STEP_S = 0.008  # widgets drawn per step: about this long, then the app takes a turn

    def _laid_out(self, screen: Screen) -> None:
        self._laid_out_at = monotonic()

    def _drawn_now(self) -> None:
        """The calculator on screen has been drawn: no rehearsal needed."""
        if self._areas() is not None:
            self._drawn.add(self.current_calculator)

    async def _rehearse(self, calc_id: str) -> None:
        area = area_of(calc_id)
        strip = self._strips[area]
        panes = [self._area_pane(area), strip.get_pane(f"tab-{calc_id}")]
        self._rehearsal = [p for p in panes if not p.display]
        if not self._rehearsal:  # on screen now
            self._drawn.add(calc_id)
            return
        if len(self._rehearsal) == 2 and strip.active:  # another area, another of its cards:
            own = strip.get_pane(strip.active)  # set that one aside, or it is drawn as well
            if own is not None and own.display:
                own.display = False
                self._set_aside = [own]
        for pane in self._rehearsal:  # inline: a class would restyle the card (tables clear caches)
            pane.styles.layer = "rehearsal"  # its own layer: the switchers' layers (gearhead.tcss)
            pane.display = True
        self._rehearsal[0].styles.offset = (0, self.screen.size.height)  # below the screen
        card = panes[1]
        until = monotonic() + 3.0  # the first layout (0.1 s; more if loaded)
        while self._rehearsal and not card.region.height and monotonic() < until:
            await sleep(0.02)
        # then the layouts that follow it, as the sizes come in (the table, the chart): 2-3 in
        # 60-230 ms. Settled once none came for a while (a fixed 0.5 s wait idled 0.3-0.45 s)
        until = monotonic() + self.REHEARSAL_MAX_S
        tab = self._cards[calc_id]
        while self._rehearsal and monotonic() < until:
            if monotonic() - self._laid_out_at >= self.REHEARSAL_SETTLED_S and not tab.busy:
                break
            await sleep(0.03)
        try:
            if self._rehearsal:
                await self._draw_into_caches(self._rehearsal[0])
        finally:  # a widget that fails to draw must not leave the card shown below the screen
            if self._rehearsal:  # not cut short by a key (laid out or not: a tiny terminal may
                self._drawn.add(calc_id)  # leave it no room; it is not tried again)
                self._end_rehearsal()

    async def _draw_into_caches(self, pane: Widget) -> None:
        """Each widget of a pane laid out off the screen draws its lines as the compositor would
        ask for them (Widget.render_lines, whole), kept in its line cache for the first visit."""
        from textual.geometry import Region

        step_began = monotonic()
        for widget in list(pane.walk_children(with_self=True)):
            if not self._rehearsal:  # a key: the screen is the user's
                return
            if not widget.display or not widget.is_attached:
                continue
            region = widget.region
            if region.width and region.height:
                widget.render_lines(Region(0, 0, region.width, region.height))
            if monotonic() - step_began > self.DRAW_STEP_S:
                await sleep(0.005)
                step_began = monotonic()

    def _end_rehearsal(self) -> None:
        for pane in self._rehearsal:
            pane.styles.clear_rule("layer")
            pane.styles.clear_rule("offset")
            if pane.parent is not None and pane.parent.current != pane.id:  # not shown meanwhile
                pane.display = False
        for pane in self._set_aside:
            if pane.parent is not None and pane.parent.current == pane.id:  # still its strip's card
                pane.display = True
        self._rehearsal = []
        self._set_aside = []

    # what counts as the user acting (the warm-up waits for a pause in these; a rehearsal ends)
    USER_ACTS = (
        events.Key,
        events.Paste,
        events.MouseDown,
        events.MouseScrollDown,
        events.MouseScrollUp,
        events.MouseScrollLeft,
        events.MouseScrollRight,
    )

    async def on_event(self, event: events.Event) -> None:
        if isinstance(event, self.USER_ACTS):
            self._last_key = monotonic()
            if self._rehearsal:  # the user is back: the screen is theirs
                self._end_rehearsal()
        await super().on_event(event)

    def _card(self, calc_id: str, in_steps: bool = False) -> CalculatorTab:
        from .components.calculator_tab import CalculatorTab

        tab = CalculatorTab(
            get(calc_id),
            blink=self.blink,
            hide_timings=self.hide_timings,
            in_steps=in_steps,
            id=f"calc-{calc_id}",
        )
        tab.unit_system = self.unit_system
        shown = self._cards.get(self.current_calculator) if self._areas() is not None else None
        if shown is not None:  # built out of sight: its table will be as wide as the one on screen
            tab.table_width_hint = shown.results_width
        return tab

    def set_unit_system(self, system: str, remember: bool = True) -> None:
        """The units preference for every tab, kept in the user's config.toml."""
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

    async def card(self, calc_id: str, in_steps: bool = False) -> CalculatorTab:
        """The tab of a calculator, built if it has not been visited yet (`in_steps`: out of
        sight, its field rows a few at a time, CalculatorTab.ROWS_PER_STEP)."""
        tab = self._cards.get(calc_id)
        if tab is None:
            await self.strip(area_of(calc_id))
            tab = self._cards.get(calc_id)
        self._check_open()
        if tab is None:
            # recorded before the await: a second caller meanwhile (tab activation and on_ready
            # at start-up, the warm-up) waits for this mount instead of mounting a duplicate
            tab = self._cards[calc_id] = self._card(calc_id, in_steps)
            pane = self._strips[area_of(calc_id)].get_pane(f"tab-{calc_id}")
            self._mounting[calc_id] = pane.mount(tab)
        elif not in_steps and calc_id not in self._built:  # wanted now: the warm-up is building it
            tab.hurry()
        await self._mounting[calc_id]
        self._check_open()
        self._built.add(calc_id)
        if self._areas() is not None and calc_id == self.current_calculator:  # the footer shows ctrl+g /
            self.refresh_bindings()  # ctrl+r where they apply; a card built out of sight changes none
        return tab

    def card_ready(self, calc_id: str) -> bool:
        """The calculator's card is on its pane, its fields and results composed."""
        return calc_id in self._built

    @until_closing
    async def on_tabbed_content_tab_activated(self, event: TabbedContent.TabActivated) -> None:
        strip_id = event.tabbed_content.id or ""
        area = strip_id.removeprefix("calcs-") if strip_id.startswith("calcs-") else None
        if area is not None:
            self._area_active[area] = event.pane.id.removeprefix("tab-")
        if not self._started:  # start-up: on_ready builds the first card, after the first frame
            return
        if self._areas() is None:  # the app is closing
            return
        if area is not None and area != self.current_area:  # a strip built out of sight (warm-up)
            return
        await self.strip(self.current_area)
        await self.card(self.current_calculator)
        self._drawn_now()
        self.refresh_bindings()  # the footer shows ctrl+g / ctrl+r only where they do something

    # what acts on the card on screen: only once it is built (a preset loaded into a card whose
    # rows the warm-up was still mounting raised NoMatches)
    CARD_ACTIONS = ("save_preset", "load_preset", "copy_preset", "export", "send", "accuracy", "sweep")

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if self._quitting:  # the F-keys are priority bindings: one after ctrl+q found no strips
            return action == "quit"
        if action in self.CARD_ACTIONS:
            shown = self.current_calculator if self._areas() is not None else None
            if shown not in self._built:  # shown once the card is there (card() refreshes the keys)
                return False
        if action == "sweep":  # on the card only: in a dialog's entry ctrl+w deletes a word as usual
            return self.screen is self.screen_stack[0]
        if action in ("send", "accuracy"):
            tab = self._cards.get(self.current_calculator) if self._areas() is not None else None
            if tab is None:  # not built yet (start-up): shown once the card is there
                return False
            calc = tab.calculator
            if action == "send":
                return bool(calc.exports) or any(t.exports for t in calc.tables)
            return calc.simulate is not None
        return True

    # ---- navigation ---------------------------------------------------------------------
    @property
    def current_area(self) -> str:
        return self._areas().active.removeprefix("area-")

    @property
    def current_calculator(self) -> str:
        """Id of the calculator on screen: the active tab of the active area."""
        return self._area_active[self.current_area]

    @property
    def current_tab(self) -> CalculatorTab:
        return self._cards[self.current_calculator]

    def show_calculator(self, calc_id: str) -> None:
        """Switch to a calculator's tab and put focus on its area's tab strip. Focus must leave
        the old pane: a checkbox or chart selector left focused there pulled the old tab back
        (Textual's TabbedContent activates the pane of a focused widget), so "Open …" did nothing."""
        area = area_of(calc_id)
        if self._quitting or self._areas() is None:  # closing: the strips are going
            return
        self.screen.set_focus(None)
        self._area_active[area] = calc_id
        strip = self._strips.get(area)
        if area in self._strips_built or (strip is not None and area not in self._mounting):
            strip.active = f"tab-{calc_id}"
        elif strip is not None:  # mounting (the warm-up): its tabs are not there yet (a traceback)
            self._picked[area] = calc_id
        # else not built yet: it is built with this tab active
        self._areas().active = f"area-{area}"
        self.call_after_refresh(self._focus_strip, area)

    async def action_quit(self) -> None:
        """Quit once the strips and cards being mounted are (a strip still mounting when the app
        closes trips Textual: its tab bar looks for tabs already pruned, a traceback). A card the
        warm-up builds in steps is hurried: a quit waits tens of milliseconds, not its pauses."""
        self._quitting = True
        for calc_id, tab in list(self._cards.items()):
            if calc_id not in self._built:
                tab.hurry()
        for mount in list(self._mounting.values()):  # none starts now (_check_open)
            await mount
        self.call_after_refresh(self.exit)  # after the mounted widgets' own mount handlers

    def action_area(self, area: str) -> None:
        """F1-F5: show an area at the calculator last used there; its strip takes focus, so a
        digit then picks a calculator (two keys to any calculator)."""
        self._area_pressed = (area, monotonic())
        self.show_calculator(self._area_active[area])

    @until_closing
    async def _focus_strip(self, area: str) -> None:
        strip = await self.strip(area)
        await self.card(self._area_active[area])
        self._drawn_now()
        self.screen.set_focus(strip.query_one(Tabs))

    def on_key(self, event: events.Key) -> None:
        """A digit on a focused tab strip picks its n-th tab (fields never see it: a strip is
        focused, not an entry)."""
        strip = self.focused
        if not (event.character or "").isdigit() or event.character == "0":
            return
        n = int(event.character)
        if isinstance(strip, Tabs):
            tabs = list(strip.query(Tab))
            if n <= len(tabs) and tabs[n - 1].id:
                event.stop()
                strip.active = tabs[n - 1].id
            return
        # F-key then a digit typed at once: the strip may not have focus yet (it is focused after
        # the next refresh, and built first on the area's first visit); the digit still counts
        area, pressed = self._area_pressed
        if strip is None and area and monotonic() - pressed < self.AREA_DIGIT_S:
            ids = AREAS[area][1]
            if n <= len(ids):
                event.stop()
                self._area_pressed = ("", 0.0)
                self.show_calculator(ids[n - 1])

    # ---- actions ------------------------------------------------------------------------
    def action_save_preset(self) -> None:
        tab = self.current_tab

        def saved(path) -> None:
            if path is not None:
                self.notify(f"Saved {path}", title="Preset saved", markup=False)  # a path may hold "["

        name, description = tab.preset_meta
        from .components.preset_screens import SavePresetScreen

        self.push_screen(
            SavePresetScreen(
                tab.calculator.id, tab.current_inputs(), self.blink, name=name, description=description
            ),
            saved,
        )

    def action_load_preset(self) -> None:
        tab = self.current_tab

        def loaded(preset) -> None:
            if preset is not None:
                # a preset is a whole design: fields it omits take their defaults (DESIGN.md),
                # not whatever was typed before, so the tab solves what the CLI solves
                defaults = {f.name: type(tab).initial_entry(f) for f in tab.calculator.fields}
                tab.set_entries({**defaults, **preset.inputs})
                tab.preset_meta = (preset.name, preset.description)  # the save dialog offers them
                self.notify(f"Loaded {preset.name}", title="Preset loaded", markup=False)
                for warning in preset.warnings:  # e.g. a junk value in a field this mode ignores
                    self.notify(warning, title="Preset warning", severity="warning", markup=False)

        from .components.preset_screens import LoadPresetScreen

        self.push_screen(LoadPresetScreen(tab.calculator.id, self.blink), loaded)

    def action_copy_preset(self) -> None:
        """ctrl+y: the tab as preset TOML on the clipboard (OSC 52), to paste in a chat or file."""
        from gearhead.core.export import preset_toml

        tab = self.current_tab
        name, description = tab.preset_meta
        self.copy_to_clipboard(preset_toml(tab.calculator.id, tab.current_inputs(), name, description))
        self.notify(
            f"{tab.calculator.title} copied as preset TOML; paste it into ctrl+o of any "
            f"Gearhead or save it as a .toml file",
            title="Copied",
            markup=False,
        )

    def action_export(self) -> None:
        tab = self.current_tab
        if tab.solution is None:
            self.notify("Fix the highlighted input first.", severity="error")
            return
        from .components.export_screen import ExportScreen
        from .components.plot_panel import PlotPanel

        plot = tab.query_one(PlotPanel).current if tab.calculator.plots else None

        def done(message) -> None:
            if message:
                self.notify(message, title="Exported", markup=False)

        self.push_screen(ExportScreen(tab.calculator, tab.solution, plot, self.blink), done)

    @until_closing
    async def action_send(self) -> None:
        """Send this tab's results into the calculator it feeds (e.g. lead screw → gear ratio)."""
        tab = self.current_tab
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
                ", ".join(f"{k} = {v}" for k, v in values.items()),
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
                    ", ".join(f"{k} = {v}" for k, v in values.items()),
                    markup=False,
                    title=f"Sent to {target.calculator.title}",
                )
                return
        self.notify(
            "This row has nothing another calculator takes (a planetary stage, or no belt long enough).",
            severity="warning",
            markup=False,
        )

    def action_accuracy(self) -> None:
        """Run the current simulation at every accuracy level (the accuracy-vs-time view)."""
        tab = self.current_tab
        if tab.calculator.simulate is None:
            self.notify("Only simulations have an accuracy setting.", severity="warning")
            return
        if tab.solution is None or tab.error is not None:
            self.notify("Fix the highlighted input first.", severity="error")
            return
        from gearhead.core.model import parse_inputs

        values, _ = parse_inputs(tab.calculator, tab.entries)
        from .components.accuracy_screen import AccuracyScreen

        self.push_screen(AccuracyScreen(tab.calculator, values, self.hide_timings))

    def action_sweep(self) -> None:
        """The sweep view over the focused input (or the first numeric one): core.sweep in a thread."""
        from .components.sweep_screen import SweepScreen

        tab, focused = self.current_tab, self.focused
        name = focused.id[3:] if focused is not None and (focused.id or "").startswith("in-") else None
        shown = tuple(tab.solution.outputs) if tab.solution is not None else ()
        self.push_screen(
            SweepScreen(tab.calculator, dict(tab.entries), name, self.blink, self.hide_timings, shown)
        )

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        yield from super().get_system_commands(screen)
        yield SystemCommand(
            "Save preset", "Save the current tab's inputs as a TOML preset", self.action_save_preset
        )
        yield SystemCommand(
            "Load preset", "Load a built-in or user preset into the current tab", self.action_load_preset
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
                lambda s=system: self.set_unit_system(s),
            )
        yield SystemCommand(
            "Accuracy vs time", "Run the current simulation at every accuracy level", self.action_accuracy
        )
        yield SystemCommand(
            "Sweep…", "Vary the focused input over a range: plot, table, CSV", self.action_sweep
        )
        for calc in calculators().values():
            yield SystemCommand(
                f"Open {calc.title}", calc.summary, lambda cid=calc.id: self.show_calculator(cid)
            )
            if calc.exports:
                targets = ", ".join(calculators()[t].title for t in calc.exports if t in calculators())
                yield SystemCommand(
                    f"Send {calc.title} results to {targets}",
                    "Copy the matching outputs into that calculator's inputs",
                    lambda cid=calc.id: self._send_from(cid),
                )

    @until_closing
    async def _send_from(self, calc_id: str) -> None:
        self.show_calculator(calc_id)
        await self.card(calc_id)
        await self.action_send()


def run() -> None:
    from . import settings

    GearheadApp(settings_file=settings.load(), warm_up=True).run()
