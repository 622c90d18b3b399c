"""A workbook in the app (core/workbook/): a Robot card and one card per workbook card.

The Robot card lists the variables (a Sheet over core.workbook.as_calculator's fields: every plain
number or quantity, editable) and the requirements, each ✔ or ✘ with its values. Each workbook card
is the generic card (CalculatorTab) of its calculator; a linked field shows its reference after its
label and is read-only. Any change (a variable, a card's own entry) re-solves the workbook in a
thread (latest wins) and the linked fields of every dependent card take their new values, which
each card then solves as it does for any entry.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from rich.text import Text
from textual import work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical, VerticalScroll
from textual.message import Message
from textual.widgets import ContentSwitcher, Static, Tab, Tabs
from textual.worker import get_current_worker

from gearhead.core.errors import InputError

from ..guard import guarded
from .calculator_tab import CalculatorTab
from .card_screen import CardScreen
from .sheet import Sheet

LINK_MARK = "⇐"  # after a linked field's label: 'Robot mass ⇐ = robot_mass'


class LinkedSheet(Sheet):
    """A card's form whose linked rows cannot be edited: Enter or a key there says why."""

    linked: dict[str, str] = {}  # field -> its reference, set by the card

    def begin_edit(self, replace_with: str | None = None) -> None:
        stop = self.current_stop
        if stop is not None and stop.field.name in self.linked:
            self.app.notify(
                f"{stop.field.name} is linked ({self.linked[stop.field.name]}): change what it reads instead",
                title="Linked field",
                severity="warning",
                markup=False,
            )
            return
        super().begin_edit(replace_with)


class WorkbookCard(CalculatorTab):
    """The generic card of one workbook card: linked fields read-only, each change reported."""

    sheet_class = LinkedSheet

    def __init__(self, name: str, calculator, links: dict[str, str], on_change, **kwargs) -> None:
        fields = tuple(
            dataclasses.replace(f, label=f"{f.label} {LINK_MARK} {links[f.name]}") if f.name in links else f
            for f in calculator.fields
        )
        super().__init__(dataclasses.replace(calculator, fields=fields), **kwargs)
        self.card_name = name
        self.links = dict(links)
        self.on_change = on_change
        self.edited: set[str] = set()  # inputs changed on screen since the workbook was opened

    @guarded
    def on_mount(self) -> None:
        self.sheet.linked = dict(self.links)
        super().on_mount()

    @guarded
    def _take_entry(self, name: str, value: Any) -> None:
        if name in self.links:  # a choice or a toggle on a linked row
            self.sheet.editing = False
            self.sheet.refresh()
            self.app.notify(
                f"{name} is linked ({self.links[name]}): change what it reads instead",
                title="Linked field",
                severity="warning",
                markup=False,
            )
            return
        before = self.entries.get(name)
        super()._take_entry(name, value)
        if self.entries.get(name) != before:
            self.edited.add(name)  # what ctrl+s writes back
            self.on_change()

    def own_inputs(self) -> dict[str, Any]:
        """What was typed on this card (not its linked fields), as a preset stores it."""
        return {k: v for k, v in self.current_inputs().items() if k not in self.links}

    def take_entries(self, values: dict[str, Any]) -> dict[str, Any]:
        """Entries put in as if typed (a fit's Apply): a linked field is left as it is; those that
        changed are the card's own edits (ctrl+s writes them) and the workbook re-solves once.
        Returns what was set."""
        own = {k: v for k, v in values.items() if k not in self.links}
        if not own:
            return {}
        before = dict(self.entries)
        self.set_entries(own)
        changed = {k for k in own if self.entries.get(k) != before.get(k)}
        if changed:
            self.edited |= changed
            self.on_change()
        return own


def robot_calculator(book):
    """The Robot card's form: core.workbook.as_calculator's fields (numbers and quantities), then
    each text variable that a card's choice field reads as it is ('motor = "= drive_motor"') as a
    choice of that field's choices, and each yes/no variable as a yes/no."""
    import ast

    from gearhead.core import workbook
    from gearhead.core.fields import Field
    from gearhead.core.registry import get

    calc = workbook.as_calculator(book)
    extra = []
    for v in book.variables.values():
        if not v.text:
            continue
        if isinstance(v.nominal, bool):
            extra.append(Field(v.name, v.name, boolean=True, default=v.nominal))
            continue
        for card in book.cards.values():
            reading = [
                get(card.calculator).field(name)
                for name, expr in card.links.items()
                if isinstance(expr.tree, ast.Name) and expr.tree.id == v.name
            ]
            choice = next((f for f in reading if f.choices and not f.flags and v.nominal in f.choices), None)
            if choice is not None:
                extra.append(
                    Field(
                        v.name,
                        v.name,
                        choices=choice.choices,
                        choice_labels=choice.choice_labels,
                        default=v.nominal,
                    )
                )
                break
    return dataclasses.replace(calc, fields=calc.fields + tuple(extra))


class RobotCard(Vertical):
    """The workbook's variables (editable) and requirements (live ✔/✘)."""

    DEFAULT_CSS = """
    RobotCard { height: 1fr; }
    RobotCard > #requirements-box { height: 1fr; }
    """

    def __init__(self, calculator, entries: dict[str, Any], on_change, **kwargs) -> None:
        super().__init__(**kwargs)
        self.calculator = calculator
        self.entries = dict(entries)
        self.on_change = on_change
        self.edited: set[str] = set()  # variables changed on screen since the workbook was opened

    def compose(self) -> ComposeResult:
        yield Static(Text(self.calculator.title, style="bold"), classes="summary")
        self.sheet = Sheet(
            self.calculator,
            entries=lambda: self.entries,
            on_entry=self._take_entry,
            on_cursor=lambda f: None,
            on_choose=self._choose,
            classes="form",
        )
        self.sheet.styles.height = min(len(self.calculator.fields), 12) + 1
        yield self.sheet
        self.status = Static("", id="workbook-status")
        yield self.status
        with VerticalScroll(id="requirements-box"):
            self.requirements = Static("", id="requirements")
            yield self.requirements

    @guarded
    def _take_entry(self, name: str, value: Any) -> None:
        if self.entries.get(name) == value:
            return
        self.entries = {**self.entries, name: value}
        self.edited.add(name)
        self.sheet.refresh_field(name)
        self.on_change()

    @guarded
    def _choose(self, field) -> None:
        """A choice row's list (Enter or a click on it), as on any card."""
        from ..guard import guard
        from .choice_screen import ChoiceScreen

        def chosen(value) -> None:
            if value is not None:
                self._take_entry(field.name, value)

        options = field.kind.widget(field).options
        self.app.push_screen(
            ChoiceScreen(field.label, options, self.entries.get(field.name)), guard(self, chosen)
        )


class WorkbookScreen(CardScreen):
    """One workbook: a strip of its cards (Robot first), the card chosen below it."""

    # the panes fill what the strip and the key bar leave (a ContentSwitcher is as tall as its
    # content: the Robot card's last requirements fell under the key bar, out of every key's reach)
    DEFAULT_CSS = """
    WorkbookScreen #workbook-panes { height: 1fr; }
    """

    BINDINGS = [
        Binding("escape", "close", "Close workbook"),
        Binding("ctrl+s", "save", "Save workbook"),
        # priority: the card switches (and takes the focus) as the key arrives, so a key typed right
        # after it goes to the card switched to (as a non-priority binding, the key bubbled up from
        # the sheet after the sheet had read the next key: Home after ctrl+← moved the old card)
        Binding("ctrl+right", "step(1)", "Next card", priority=True),
        Binding("ctrl+left", "step(-1)", "Previous card", priority=True),
        Binding("ctrl+t", "match", "Match", priority=True),  # the Match card; shown with a [match]
        # the app's card commands act on the calculator cards behind this screen: not here
        *(Binding(key, "not_here", show=False) for key in ("ctrl+o", "ctrl+g", "ctrl+r", "ctrl+y", "ctrl+e")),
    ]

    def __init__(self, book, blink: bool = True, hide_timings: bool = False) -> None:
        super().__init__()

        self.book = book
        self.blink = blink
        self.hide_timings = hide_timings
        self.robot_calc = robot_calculator(book)
        self.outcome = None  # the last core.workbook.Outcome shown
        self._wb_generation = 0  # solves asked for; a worker's result older than the last is dropped
        self._wb_shown = 0  # the request whose result is shown
        self._wb_pushed: dict[tuple[str, str], Any] = {}  # (card, field) -> the linked value last set
        self._saved: dict[str, dict[str, Any]] = {}  # per card ("" the Robot card): entries last saved
        self.match_view = None  # the Match card (match_view.py), when the workbook has a [match]
        self._before_match = "wbtab-robot"  # the tab ctrl+t on the Match card returns to

    def compose(self) -> ComposeResult:
        from gearhead.core.registry import get

        book = self.book
        yield Tabs(
            Tab("Robot", id="wbtab-robot"),
            *(Tab(name, id=f"wbtab-{name}") for name in book.cards),
            *((Tab("Match", id="wbtab-match"),) if book.match is not None else ()),
            id="workbook-tabs",
        )
        entries = {
            f.name: f.kind.entry(f, book.variables[f.name].entry)
            if f.kind.with_unit
            else f.kind.initial_entry(f)
            for f in self.robot_calc.fields
        }
        self.robot = RobotCard(self.robot_calc, entries, self.request_solve, id="wbpane-robot")
        self.cards: dict[str, WorkbookCard] = {}
        with ContentSwitcher(initial="wbpane-robot", id="workbook-panes"):
            yield self.robot
            for name, card in book.cards.items():
                links = {k: "= " + e.text for k, e in card.links.items()}
                tab = WorkbookCard(
                    name,
                    get(card.calculator),
                    links,
                    self.request_solve,
                    blink=self.blink,
                    hide_timings=self.hide_timings,
                    id=f"wbpane-{name}",
                )
                calc = tab.calculator
                literal = {k: v for k, v in card.inputs.items() if k not in links}
                tab.entries = {
                    **{f.name: tab.initial_entry(f) for f in calc.fields},
                    **{k: calc.field(k).kind.entry(calc.field(k), v) for k, v in literal.items()},
                }
                self.cards[name] = tab
                yield tab
            if book.match is not None:  # no card may be named "match" (core/workbook/match.py)
                from .match_view import MatchView

                events = book.data.get("match", {}).get("events", [])  # the timeline's rows
                self.match_view = MatchView(
                    book.source,
                    events if isinstance(events, list) else [],
                    self.request_solve,
                    calculators={name: card.calculator for name, card in book.cards.items()},
                    id="wbpane-match",
                )
                yield self.match_view
        from .key_bar import KeyBar

        yield KeyBar()

    @guarded
    def on_mount(self) -> None:
        self.sub_title = self.book.name
        self._saved = self._own_entries()
        self.request_solve()
        self.robot.sheet.focus()

    @guarded
    def on_tabs_tab_activated(self, event: Tabs.TabActivated) -> None:
        if event.tabs.id != "workbook-tabs" or event.tab is None:
            return
        event.stop()
        self._show_tab(event.tab.id or "")

    def _show_tab(self, tab_id: str) -> None:
        """The card of tab `tab_id` on screen with the focus, now (Screen.set_focus, not the
        deferred Widget.focus): a key already read after the switching one goes to it."""
        pane = "wbpane-" + tab_id.removeprefix("wbtab-")
        switcher = self.query_one("#workbook-panes", ContentSwitcher)
        if switcher.current == pane and self.focused is not None:
            return  # the strip's message after a switch made by a key: already done
        switcher.current = pane
        if pane == "wbpane-match":
            self.set_focus(self.match_view)  # its arrows and PageUp/PageDown scroll it
            self.match_view.opened()  # its charts are drawn while it is on screen
            return
        shown = self.robot if pane == "wbpane-robot" else self.cards[pane.removeprefix("wbpane-")]
        if shown.is_mounted:
            self.set_focus(shown.sheet)  # typing goes to the card on screen

    def _activate(self, tab_id: str) -> None:
        self.query_one("#workbook-tabs", Tabs).active = tab_id
        self._show_tab(tab_id)

    def action_step(self, step: int) -> None:
        tabs = self.query_one("#workbook-tabs", Tabs)
        ids = ["wbtab-robot", *(f"wbtab-{n}" for n in self.book.cards)]
        ids += ["wbtab-match"] if self.match_view is not None else []
        current = ids.index(tabs.active) if tabs.active in ids else 0
        self._activate(ids[(current + step) % len(ids)])

    def action_match(self) -> None:
        """ctrl+t: the Match card; from it, back to the card it was opened from."""
        tabs = self.query_one("#workbook-tabs", Tabs)
        if tabs.active == "wbtab-match":
            self._activate(self._before_match)
        else:
            self._before_match = tabs.active or "wbtab-robot"
            self._activate("wbtab-match")

    def check_action(self, action: str, parameters: tuple) -> bool | None:
        if action == "match":  # in the key bar only when the workbook has a [match]
            return self.match_view is not None
        return super().check_action(action, parameters)

    @property
    def current_card(self) -> WorkbookCard | None:
        """The workbook card on screen (None on the Robot and Match cards)."""
        active = self.query_one("#workbook-tabs", Tabs).active or ""
        return self.cards.get(active.removeprefix("wbtab-")) if active.startswith("wbtab-") else None

    def fit_card(self) -> WorkbookCard | None:
        """The card on screen when "Fit from log" fits its kind (core.fit.KINDS), else None."""
        from gearhead.core.fit import KINDS

        tab = self.current_card
        return tab if tab is not None and tab.calculator.id in KINDS else None

    @guarded
    def action_fit_from_log(self) -> None:
        """The card on screen fitted from a SysId log (fit_screen.py), with its entries as shown
        (each linked field its resolved value); Apply puts the fitted entries into its own fields
        as if typed, and says what the fit gives for each linked one instead of writing it."""
        from gearhead.core.registry import get

        from ..guard import guard
        from .fit_screen import FitScreen
        from .sheet import shown_entry
        from .unit_text import pretty_unit

        tab = self.fit_card()
        if tab is None:
            self.app.notify(
                "Fit from log works on a workbook's elevator, arm, flywheel or sprint card: choose one first.",
                severity="warning",
                markup=False,
            )
            return
        name = tab.card_name
        result = self.outcome.cards.get(name) if self.outcome is not None else None
        if self.busy or result is None:
            self.app.notify(
                f"The workbook is still solving: fit {name} once its linked fields show their values.",
                severity="warning",
                markup=False,
            )
            return
        unresolved = [k for k in tab.links if k not in result.entries]
        if unresolved:
            self.app.notify(
                f"{name}: the linked field {unresolved[0]} has no value ({result.error}): "
                "the fit needs every entry.",
                severity="error",
                markup=False,
            )
            return
        calc = get(tab.calculator.id)  # its own labels (the card's carry their link)

        def shown(f, entry) -> str:
            """An entry as the sheet now shows it: in its field's unit, 6 digits."""
            unit = pretty_unit(f.unit) if f.kind.with_unit and f.unit else ""
            return f"{f.label} = {shown_entry(f, str(entry))} {unit}".rstrip()

        def applied(values) -> None:
            if not values or not tab.is_attached:
                return
            done = tab.take_entries(values)
            if done:
                text = ", ".join(shown(calc.field(k), tab.entries[k]) for k in done)
                self.app.notify(text, title=f"Fitted entries applied to {name}", markup=False)

        self.app.push_screen(
            FitScreen(
                calc,
                dict(tab.entries),
                self.blink,
                self.hide_timings,
                label=f"{name} ({calc.title})",
                linked=tab.links,
            ),
            guard(self, applied),
        )

    def _own_entries(self) -> dict[str, dict[str, Any]]:
        """What was typed on the screen, per card ("" the Robot card): what a save writes."""
        return {
            "": {n: self.robot.entries[n] for n in self.robot.edited},
            **{name: {k: tab.entries[k] for k in tab.edited} for name, tab in self.cards.items()},
        }

    def unsaved_changes(self) -> int:
        """Entries that differ from the file (as opened or last saved)."""
        now, saved = self._own_entries(), self._saved
        timeline = 1 if self.match_view is not None and self.match_view.unsaved else 0
        return timeline + sum(
            1 for card, entries in now.items() for k, v in entries.items() if saved.get(card, {}).get(k) != v
        )

    @guarded
    def action_close(self) -> None:
        """Esc: leave the workbook; with unsaved changes, ask first (they were dropped silently)."""
        self.leave(self._close)

    def _close(self) -> None:
        """This screen off the stack, whatever a key typed meanwhile pushed over it (the palette):
        the answer's callback runs later, and popping the top then closed the palette instead."""
        if self not in self.app.screen_stack:
            return
        if self.app.screen is not self:
            self.pop_until_active()
        self.app.pop_screen()

    def leave(self, then) -> None:
        """Run `then` (close the screen, quit the app) once the unsaved changes are saved or
        discarded; nothing if the user stays."""
        changes = self.unsaved_changes()
        if not changes:
            then()
            return
        from ..guard import guard
        from .leave_screen import DISCARD, SAVE, LeaveScreen

        def answered(choice: str | None) -> None:
            if choice == DISCARD or (choice == SAVE and self.action_save()):
                then()

        self.app.push_screen(LeaveScreen(f"Workbook {self.book.name!r}", changes), guard(self, answered))

    def action_not_here(self) -> None:
        self.app.notify(
            "On a workbook, ctrl+s saves it; the other card commands work on the calculator cards "
            "(Esc closes the workbook).",
            severity="warning",
            markup=False,
        )

    @guarded
    def action_save(self) -> bool:
        """ctrl+s: the variables and card inputs changed here, written into the workbook's file
        (core.workbook.save: its comments and layout kept); links stay as the file has them."""
        from pathlib import Path

        from gearhead.core import builtin, workbook
        from gearhead.core.errors import InputError

        from .. import served_paths

        path = Path(self.book.source)
        if not path.is_file():
            self.app.notify("This workbook has no file to save to.", severity="warning", markup=False)
            return False
        if path.resolve().parent == builtin.examples_dir():  # shipped with Gearhead: never rewritten
            self.app.notify(
                f"{path.name} is the example shipped with Gearhead, not saved over: copy it "
                f"(cp {path} my_robot.toml) and open the copy to keep changes.",
                severity="warning",
                markup=False,
                timeout=15,
            )
            return False
        try:
            served_paths.check(str(path))  # a served session: only in the Gearhead folder
        except InputError as exc:
            self.app.notify(str(exc), severity="error", markup=False)
            return False
        variables = {n: self._with_unit(n, self.robot.entries[n]) for n in sorted(self.robot.edited)}
        inputs = {}
        for name, tab in self.cards.items():
            own = tab.own_inputs()
            inputs[name] = {k: own[k] for k in sorted(tab.edited) if k in own}
        view = self.match_view
        events = view.saved_events() if view is not None and view.unsaved else None  # the timeline
        try:
            workbook.save(path, variables, inputs, events)
        except OSError as exc:
            self.app.notify(f"Could not save {path}: {exc.strerror or exc}", severity="error", markup=False)
            return False
        self._saved = self._own_entries()
        if events is not None:  # the file's tables are now these, in this order
            view.origins = list(range(len(view.tables)))
            view.saved = view.saved_events()
        changed = len(variables) + sum(len(v) for v in inputs.values()) + (events is not None)
        self.app.notify(f"Saved {changed} change(s) to {path}", title="Workbook saved", markup=False)
        return True

    # ---- solving ------------------------------------------------------------------------
    class Solved(Message):
        """The workbook solved (core.workbook.Outcome, or the InputError) for request `generation`."""

        def __init__(self, generation: int, result) -> None:
            super().__init__()
            self.generation, self.result = generation, result

    def request_solve(self) -> None:
        """Solve the workbook with what is on screen in a worker, as a card solves: a newer request
        cancels the running one (it stops at its next integration step) and only the latest is shown."""
        self._wb_generation += 1
        variables = {name: self._with_unit(name, entry) for name, entry in self.robot.entries.items()}
        inputs = {name: tab.own_inputs() for name, tab in self.cards.items()}
        events = self.match_view.event_tables() if self.match_view is not None else None
        self._solve_worker(self._wb_generation, variables, inputs, events)
        self.set_timer(0.1, self._mark_busy)

    @guarded
    def _mark_busy(self) -> None:
        """A solve taking a moment (a match runs 40 moves): say the checks shown are not yet these
        entries'."""
        if self.busy and self.is_attached:
            self.robot.status.update(
                Text("… solving (the requirements below are those of the last entries)", style="yellow")
            )
            if self.match_view is not None:
                self.match_view.mark_running()

    def _with_unit(self, name: str, entry: Any) -> Any:
        """A bare number typed on a Robot card row is in the unit the row shows (as on any card):
        '140' on 'robot_mass … lb' is 140 lb (the workbook read it as a plain number and refused it)."""
        field = next((f for f in self.robot_calc.fields if f.name == name), None)
        if field is None or not (field.kind.with_unit and field.unit) or not isinstance(entry, str):
            return entry
        try:
            float(entry.strip().replace("−", "-"))
        except ValueError:
            return entry  # a unit of its own, a tolerance, or something the workbook will name
        return f"{entry.strip()} {field.unit}"

    @property
    def busy(self) -> bool:
        return self._wb_shown != self._wb_generation

    @work(thread=True, exclusive=True, group="workbook", exit_on_error=False)
    def _solve_worker(self, generation: int, variables: dict, inputs: dict, events: list | None) -> None:
        from gearhead.core import workbook
        from gearhead.core.sim.integrate import Cancelled, budget

        worker = get_current_worker()
        try:
            with budget(cancel=lambda: worker.is_cancelled):
                result: Any = workbook.solve(workbook.edited(self.book, variables, inputs, events))
        except Cancelled:  # a newer request runs: it posts
            return
        except InputError as exc:
            result = exc
        except Exception as exc:  # a bug: said on the Robot card, logged; the screen keeps working
            from ..bug_log import record

            path = record(exc, "gearhead (the app) workbook solve")
            result = InputError(
                "(workbook)", f"internal error: {type(exc).__name__}: {exc} (traceback in {path})"
            )
        self.post_message(self.Solved(generation, result))

    @guarded
    def on_workbook_screen_solved(self, message: Solved) -> None:
        message.stop()
        if message.generation == self._wb_generation:
            self._wb_shown = message.generation
        self._show(message.generation, message.result)

    @guarded
    def _show(self, generation: int, result) -> None:
        if generation != self._wb_generation or not self.is_attached:
            return  # a newer request is on its way
        if self.match_view is not None:
            self.match_view.show_result(generation, result)
        if isinstance(result, InputError):
            self.robot.status.update(Text(f"✗ {result}", style="red"))
            return
        self.outcome = result
        for name, card in result.cards.items():
            tab = self.cards[name]
            pushed = {
                field_name: card.entries[field_name]
                for field_name in card.links
                if field_name in card.entries
                and self._wb_pushed.get((name, field_name)) != card.entries[field_name]
            }
            if pushed:
                tab.set_entries(pushed)
                self._wb_pushed.update({(name, k): v for k, v in pushed.items()})
            if card.error:
                tab.status.update(Text(f"✗ workbook: {card.error}", style="red"))
        self.robot.requirements.update(requirements_text(result))
        holding = sum(1 for c in result.checks if c.holds)
        style = "green" if result.all_hold else "red"
        self.robot.status.update(Text(f"{holding} of {len(result.checks)} requirements hold", style=style))


def requirements_text(outcome) -> Text:
    """One line per requirement: ✔/✘ (? when it could not be evaluated), its name, its values."""
    text = Text()
    for c in outcome.checks:
        r = c.requirement
        mark, style = ("✔", "green") if c.holds else (("?", "yellow") if c.holds is None else ("✘", "red"))
        text.append(f"{mark} ", style=style)
        text.append(r.name or r.check, style="bold")
        text.append(f"  {c.text()}\n")
        if r.name:
            text.append(f"    {r.check}\n", style="dim")
    for name, card in outcome.cards.items():
        if card.error:
            text.append(f"card {name} not solved: {card.error}\n", style="red")
    return text
