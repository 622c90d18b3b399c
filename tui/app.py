"""The Gearhead design card: one tab per registered calculator."""

from __future__ import annotations

from pathlib import Path
from typing import Iterable

from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.content import Content
from textual.screen import Screen
from textual.widgets import Footer, Header, TabbedContent, TabPane, Tabs

from core.registry import calculators

from .components.accuracy_screen import AccuracyScreen
from .components.calculator_tab import CalculatorTab
from .components.preset_screens import LoadPresetScreen, SavePresetScreen


def exact_text(value, output) -> str:
    """A result as an entry for another calculator: its display unit, every significant digit
    (the 5-figure display text would pass on a rounding error)."""
    from core import units

    if not isinstance(value.value, float):
        return value.text
    shown = units.to_unit(value.value, output.unit, output.quantity)
    return f"{shown!r} {output.unit}".rstrip()


class GearheadApp(App):
    CSS_PATH = Path(__file__).with_name("gearhead.tcss")  # absolute: subclasses live elsewhere
    TITLE = "Gearhead"
    SUB_TITLE = "mechanism design card"
    # below 120 columns inputs and results cannot sit side by side: gearhead.tcss stacks them
    HORIZONTAL_BREAKPOINTS = [(0, "-narrow"), (120, "-wide")]
    BINDINGS = [
        Binding("ctrl+s", "save_preset", "Save preset"),
        Binding("ctrl+o", "load_preset", "Load preset"),
        Binding("ctrl+g", "send", "Send to…", show=True),
        Binding("ctrl+r", "accuracy", "Accuracy"),
        Binding("ctrl+q", "quit", "Quit"),
    ]

    def __init__(self, blink: bool = True, initial: str | None = None, hide_timings: bool = False) -> None:
        super().__init__()
        self.blink = blink  # tests switch the cursor blink off for deterministic snapshots
        self.hide_timings = hide_timings  # and hide wall-clock figures
        self.initial = initial

    def compose(self) -> ComposeResult:
        yield Header()
        first = self.initial or next(iter(calculators()))
        with TabbedContent(initial=f"tab-{first}"):
            for calc in calculators().values():
                with TabPane(Content(calc.title), id=f"tab-{calc.id}"):
                    # only the first tab is built now; the others on first visit (fast first frame)
                    if calc.id == first:
                        yield self._card(calc.id)
        yield Footer()

    def _card(self, calc_id: str) -> CalculatorTab:
        return CalculatorTab(calculators()[calc_id], blink=self.blink, hide_timings=self.hide_timings,
                             id=f"calc-{calc_id}")

    async def card(self, calc_id: str) -> CalculatorTab:
        """The tab of a calculator, built if it has not been visited yet."""
        found = self.query(f"#calc-{calc_id}")
        if found:
            return found.first(CalculatorTab)
        tab = self._card(calc_id)
        await self.query_one(f"#tab-{calc_id}", TabPane).mount(tab)
        return tab

    async def on_tabbed_content_tab_activated(self, event: TabbedContent.TabActivated) -> None:
        await self.card(event.pane.id.removeprefix("tab-"))
        self.refresh_bindings()  # the footer shows ctrl+g / ctrl+r only where they do something

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if action in ("send", "accuracy"):
            pane = self.query(TabbedContent)
            calc_id = pane.first().active.removeprefix("tab-") if pane else ""
            calc = calculators().get(calc_id)
            if calc is not None:
                return bool(calc.exports) if action == "send" else calc.simulate is not None
        return True

    # ---- helpers ------------------------------------------------------------------------
    @property
    def current_tab(self) -> CalculatorTab:
        pane_id = self.query_one(TabbedContent).active
        return self.query_one(f"#calc-{pane_id.removeprefix('tab-')}", CalculatorTab)

    def show_calculator(self, calc_id: str) -> None:
        """Switch to a calculator's tab and put focus on the tab strip. Focus must leave the old
        pane: a checkbox or chart selector left focused there pulled the old tab back (Textual's
        TabbedContent activates the pane of a focused widget), so "Open …" did nothing."""
        tabbed = self.query_one(TabbedContent)
        self.screen.set_focus(None)
        tabbed.active = f"tab-{calc_id}"
        self.call_after_refresh(self._focus_tab_strip)

    def _focus_tab_strip(self) -> None:
        self.screen.set_focus(self.query_one(TabbedContent).query_one(Tabs))

    # ---- actions ------------------------------------------------------------------------
    def action_save_preset(self) -> None:
        tab = self.current_tab

        def saved(path) -> None:
            if path is not None:
                self.notify(f"Saved {path}", title="Preset saved", markup=False)  # a path may hold "["

        self.push_screen(SavePresetScreen(tab.calculator.id, tab.current_inputs(), self.blink), saved)

    def action_load_preset(self) -> None:
        tab = self.current_tab

        def loaded(preset) -> None:
            if preset is not None:
                # a preset is a whole design: fields it omits take their defaults (DESIGN.md),
                # not whatever was typed before, so the tab solves what the CLI solves
                defaults = {f.name: CalculatorTab.initial_entry(f) for f in tab.calculator.fields}
                tab.set_entries({**defaults, **preset.inputs})
                self.notify(f"Loaded {preset.name}", title="Preset loaded", markup=False)

        self.push_screen(LoadPresetScreen(tab.calculator.id, self.blink), loaded)

    async def action_send(self) -> None:
        """Send this tab's results into the calculator it feeds (e.g. lead screw → gear ratio)."""
        tab = self.current_tab
        exports = tab.calculator.exports
        if not exports:
            self.notify("This calculator has nothing to send.", severity="warning")
            return
        if tab.solution is None or tab.error is not None:
            self.notify("Fix the highlighted input first.", severity="error")
            return
        for target_id, mapping in exports.items():
            target = await self.card(target_id)
            values = {field: exact_text(tab.solution.outputs[out], tab.calculator.output(out))
                      for field, out in mapping.items() if out in tab.solution.outputs}
            target.set_entries(values)
            self.show_calculator(target_id)
            self.notify(", ".join(f"{k} = {v}" for k, v in values.items()), markup=False,
                        title=f"Sent to {target.calculator.title}")

    def action_accuracy(self) -> None:
        """Run the current simulation at every accuracy level (the accuracy-vs-time view)."""
        tab = self.current_tab
        if tab.calculator.simulate is None:
            self.notify("Only simulations have an accuracy setting.", severity="warning")
            return
        if tab.solution is None or tab.error is not None:
            self.notify("Fix the highlighted input first.", severity="error")
            return
        from core.model import parse_inputs

        values, _ = parse_inputs(tab.calculator, tab.entries)
        self.push_screen(AccuracyScreen(tab.calculator, values, self.hide_timings))

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        yield from super().get_system_commands(screen)
        yield SystemCommand("Save preset", "Save the current tab's inputs as a TOML preset",
                            self.action_save_preset)
        yield SystemCommand("Load preset", "Load a built-in or user preset into the current tab",
                            self.action_load_preset)
        yield SystemCommand("Accuracy vs time", "Run the current simulation at every accuracy level",
                            self.action_accuracy)
        for calc in calculators().values():
            yield SystemCommand(f"Open {calc.title}", calc.summary,
                                lambda cid=calc.id: self.show_calculator(cid))
            if calc.exports:
                targets = ", ".join(calculators()[t].title for t in calc.exports if t in calculators())
                yield SystemCommand(f"Send {calc.title} results to {targets}",
                                    "Copy the matching outputs into that calculator's inputs",
                                    lambda cid=calc.id: self._send_from(cid))


    async def _send_from(self, calc_id: str) -> None:
        self.show_calculator(calc_id)
        await self.card(calc_id)
        await self.action_send()

def run() -> None:
    GearheadApp().run()
