"""The workbook's Match card: its [match] run (core/workbook/match.py) as `gearhead match` shows it,
the outputs (the same names, values and units), the brownouts (time, length, the moves running),
and plots over the match (core/match/series.py): the bus voltage with the brownout and recovery
levels, the battery current stacked by card (plus the base load), the state of charge.

The match is run by the workbook screen's solve (workbook_screen.py: a thread worker, exclusive, a
newer request cancelling the running one through its budget, the result posted as `Solved` with the
request it answers): the match is part of the workbook's outcome and is cached there by what it
reads, so running it a second time here would only double the work. This card shows what the
latest outcome holds, says when a newer one is on its way, and names what went wrong when the match
could not be run. The charts' data (the series, thinned to what a chart can show: series.envelope)
is made in a thread worker of this card's own (exclusive: a newer outcome cancels it between its
steps), posted as `Prepared` with the request it answers, and drawn while the card is on screen.

Above them, the timeline (timeline.py): the events as rows of the app's sheet, edited as any card's
entries; this card holds the events' tables, each edit asks the screen for a solve (`on_change`), and
the screen's solve builds the match from these tables. A refusal of the match (`match.events[2].card:
'lfit' is not a card`) is shown under its row and in the status line, the last good match's outputs
kept below, dimmed, and its charts, until the entries solve again.

The current is stacked with textual-plot's bars (filled from 0): the layers' running sums are drawn
from the top one down, each over the last, so each card's band is its share of the current. A bar
is one time bin of the match, showing the sample with the highest battery current in it
(series.peak_bins: a move's peak is never averaged away).
"""

from __future__ import annotations

import sys
from typing import Any

from rich.markup import escape
from rich.text import Text
from textual import work
from textual.binding import Binding
from textual.containers import Container, VerticalScroll
from textual.message import Message
from textual.widgets import Static
from textual.worker import get_current_worker

from gearhead.core.errors import InputError

from ..guard import guarded
from . import timeline

PLOT_HEIGHT = 15
CHARTS = {
    "voltage": "Bus voltage over the match",
    "current": "Battery current over the match",
    "charge": "State of charge over the match",
}
MAX_BROWNOUTS_LISTED = 200  # a hostile match may have thousands: the count says how many more
LAYER_COLOURS = ("cyan", "magenta", "yellow", "green", "red", "blue")
BASE_COLOUR = "grey50"


def output_rows(m) -> list[tuple[str, str, str]]:
    """(label, value with its unit, requirement name) per output, as `gearhead match` prints them."""
    from gearhead.core import units
    from gearhead.core.workbook.match import OUTPUTS, output_info

    rows = []
    for key, (label, unit) in OUTPUTS.items():
        if key not in m.outputs:  # the breaker's margin without a trip table, its trip without a trip
            continue
        value = m.outputs[key]
        text = f"{value:d}" if isinstance(value, int) else f"{units.format_number(value)} {unit}".rstrip()
        if key == "min_bus_time" and m.running_at_min:
            text += f"  ({', '.join(m.running_at_min)} running)"
        rows.append((label, text, f"match.{key}"))
    cards = set(m.bus.channels)
    for key, value in m.outputs.items():  # each card's channel breaker (`lift_breaker_load`, ...)
        if key not in OUTPUTS and (info := output_info(key, cards)) is not None:
            label, unit = info
            rows.append((label, f"{units.format_number(value)} {unit}".rstrip(), f"match.{key}"))
    return rows


def summary_text(m, source: str) -> Text:
    """The match's head line, outputs, shares and brownouts (Text: no markup is read)."""
    from gearhead.core.workbook import match

    length = m.spec.values["length"]
    out = Text()
    out.append(
        f"Match of {length:g} s, {len(m.moves)} moves; battery {m.battery.R * 1000:.4g} mΩ, "
        f"{m.battery.start_soc * 100:.4g} % charged; brownout {m.controller.brownout:g} V, "
        f"recovery {m.controller.recovery:g} V\n",
        style="bold",
    )
    rows = output_rows(m)
    width = max(len(label) for label, _, _ in rows)
    value_width = max(len(value.partition("  (")[0]) for _, value, _ in rows)
    for label, value, name in rows:
        value, _, running = value.partition("  (")
        out.append(f"  {label:<{width}}  ")
        out.append(f"{value:<{value_width}}", style="bold")
        out.append(f"  {name}\n", style="dim")
        if running:  # a line of its own: beside the name it wrapped mid-words at 80 columns
            out.append(f"  {'':<{width}}  ({running}\n", style="italic")
    # the shares and the channel breakers as `gearhead match` prints them (one text for both)
    lines = match.summary(m)
    start = next(i for i, line in enumerate(lines) if line.startswith("  Charge share"))
    out.append(lines[start].strip() + "\n", style="bold")
    for line in lines[start + 1 :]:
        out.append(line + "\n", style="dim" if line.lstrip().startswith("(") else "")
    if m.brownouts:
        out.append(f"Brownouts ({len(m.brownouts)}): start, length, moves running\n", style="bold red")
        for b in m.brownouts[:MAX_BROWNOUTS_LISTED]:
            out.append(f"  {b.start:8.3f} s  {b.length * 1000:7.1f} ms  {', '.join(b.running) or '-'}\n")
        if len(m.brownouts) > MAX_BROWNOUTS_LISTED:
            out.append(
                f"  ... {len(m.brownouts) - MAX_BROWNOUTS_LISTED} more (gearhead match --json lists all)\n"
            )
    else:
        out.append("Brownouts: none\n", style="bold green")
    return out


class MatchView(VerticalScroll, can_focus=True):
    """The Match card: ↑↓, PageUp/PageDown, Home/End scroll it (a small terminal shows it in parts)."""

    DEFAULT_CSS = f"""
    MatchView {{ height: 1fr; }}
    MatchView > #match-timeline-title {{ margin-bottom: 1; }}
    MatchView > .match-plot {{ height: {PLOT_HEIGHT}; }}
    MatchView > .match-heading {{ margin-top: 1; }}
    """

    BINDINGS = [
        Binding("enter", "edit_timeline", "Edit timeline"),
        Binding(timeline.ADD_KEY, "add_event", "Add event"),
        Binding(timeline.DELETE_KEY, "delete_event", "Delete event"),
    ]

    def __init__(
        self,
        source: str,
        tables: list | None = None,
        on_change=lambda: None,
        calculators: dict[str, str] | None = None,
        **kwargs,
    ) -> None:
        super().__init__(**kwargs)
        self.source = source  # the workbook's file, named in a failure
        self.calculators = dict(calculators or {})  # card -> calculator: a left-out action's default
        # the events' tables as the file has them, then as edited: the one copy (timeline.py)
        self.tables: list[dict[str, Any]] = [dict(t) for t in (tables or []) if isinstance(t, dict)]
        self.origins: list[int | None] = list(range(len(self.tables)))  # the file's table of each
        self.saved: list = self.saved_events()  # what the file holds (as opened or last saved)
        self.on_change = on_change  # an edit: the screen solves the workbook again
        self.good: Any = None  # the last match that ran (shown dimmed while the entries are wrong)
        self.good_request: int | None = None  # the request it answered
        self.result: Any = None  # the last outcome given (core.workbook.Outcome or InputError)
        self.request: int | None = None  # the solve request it answers
        self.running = True  # a newer solve is on its way
        self.drawn: int | None = None  # the request whose charts are drawn
        self._preparing: int | None = None  # the request whose charts' data a worker is making

    def compose(self):
        yield Static(self._timeline_title(), id="match-timeline-title")
        self.sheet = timeline.TimelineSheet(
            timeline.calculator(self.tables),
            entries=self.entries,
            on_entry=self._take_entry,
            on_cursor=lambda f: None,
            on_choose=lambda f: None,
            on_add=self.action_add_event,
            on_delete=self.action_delete_event,
            calculators=self.calculators,
            id="match-timeline",
        )
        self._fit_sheet()
        yield self.sheet
        self.status = Static(Text("… running the match", style="yellow"), id="match-status")
        yield self.status
        self.summary = Static("", id="match-summary")
        yield self.summary
        for name, title in CHARTS.items():
            yield Static(Text(title, style="bold"), classes="match-heading", id=f"match-{name}-title")
            yield Container(classes="match-plot", id=f"match-{name}")

    # ---- the timeline -----------------------------------------------------------------------
    def _timeline_title(self) -> Text:
        text = Text(f"Timeline: {len(self.tables)} events ([[match.events]])", style="bold")
        text.append(
            f"  Enter edits a cell; {timeline.ADD_KEY} adds an event, {timeline.DELETE_KEY} deletes the "
            "one under the cursor",
            style="dim",
        )
        return text

    def _fit_sheet(self) -> None:
        self.sheet.styles.height = min(len(self.sheet.calculator.fields), 10) + 1

    def entries(self) -> timeline.Cells:
        """The sheet's entries: each event's values, as the file has them or as typed (read per
        drawn row: a view of the tables, never a copy built per row of a 1000-event timeline)."""
        return timeline.Cells(self.tables)

    def event_tables(self) -> list[dict[str, Any]]:
        """The `[[match.events]]` tables the screen's solve runs (core.workbook.match.event_table)."""
        from gearhead.core.workbook.match import event_table

        return [event_table(t) for t in self.tables]

    def saved_events(self) -> list:
        """What a save writes: each table with the file's table it came from (None: added)."""
        return list(zip(self.origins, self.event_tables()))

    @property
    def unsaved(self) -> bool:
        return self.saved_events() != self.saved

    @guarded
    def _take_entry(self, name: str, value: Any) -> None:
        cell = timeline.cell_of(name)
        if cell is None or not 1 <= cell[0] <= len(self.tables):
            return
        table = self.tables[cell[0] - 1]
        if table.get(cell[1], "") == value:
            return
        table[cell[1]] = value
        self.sheet.refresh_field(name)
        for key in ("action", "count"):  # their shown defaults follow the card and `every`
            self.sheet.refresh_field(timeline.field_name(cell[0], key))
        self.on_change()

    def _rows_changed(self) -> None:
        self.sheet.set_calculator(timeline.calculator(self.tables))
        self.sheet.set_errors({})  # their rows moved: the next solve names what is still wrong
        self._fit_sheet()
        self.query_one("#match-timeline-title", Static).update(self._timeline_title())
        self.on_change()

    @guarded
    def action_edit_timeline(self) -> None:
        self.sheet.focus()

    @guarded
    def action_add_event(self) -> None:
        """A new event at the end, a copy of the time and card of the one under the cursor (or of
        the last), its cursor on its time: an event to edit, never an empty row the match refuses."""
        from gearhead.core.workbook.match import EVENT_KEYS

        at = self.sheet.current_event
        like = self.tables[at - 1] if at else (self.tables[-1] if self.tables else {})
        new = {key: like[key] for key in EVENT_KEYS[:2] if key in like} or {"at": "0 s", "card": ""}
        self.tables.append(new)
        self.origins.append(None)
        self._rows_changed()
        self.sheet.move_to_field(timeline.field_name(len(self.tables), "at"))
        self.sheet.focus()

    @guarded
    def action_delete_event(self) -> None:
        at = self.sheet.current_event
        if at is None:
            self.app.notify("No event to delete.", severity="warning", markup=False)
            return
        del self.tables[at - 1]
        del self.origins[at - 1]
        self._rows_changed()
        self.sheet.move_to_field(timeline.field_name(min(at, len(self.tables)), "at"))

    # ---- what the workbook screen tells it ------------------------------------------------
    @guarded
    def mark_running(self) -> None:
        """A solve of newer entries is running (the screen says so after 0.1 s)."""
        self.running = True
        if self.is_mounted:
            self._status()

    @guarded
    def show_result(self, request: int, result: Any) -> None:
        """The outcome of solve request `request` (the latest: the screen drops older ones)."""
        self.request, self.result, self.running = request, result, False
        m = self.match
        if m is not None:
            self.good, self.good_request = m, request
        if not self.is_mounted:
            return
        errors = {}
        if isinstance(result, InputError):  # a refusal of an event's field: said under its row too
            for e in result.errors:
                name = timeline.error_cell(e.field)
                if name is not None and name not in errors:
                    errors[name] = f"{e.field}: {e.message}"
        elif (
            result is not None
            and result.match_error
            and (name := timeline.run_error_cell(result.match_error))
        ):
            errors[name] = result.match_error  # a move that could not run: under its event too
        self.sheet.set_errors(errors)
        self._status()
        if m is not None:
            self.summary.update(summary_text(m, self.source))
        elif self.good is not None:  # the last good match, dimmed, as a card keeps its last results
            last = summary_text(self.good, self.source)
            last.stylize("dim")
            self.summary.update(last)
        else:
            self.summary.update("")
        for node in self.query(".match-heading, .match-plot"):  # no charts of a match never run
            node.display = self.good is not None
        if self.display:  # the card on screen (the switcher shows one pane): else when it is opened
            self.draw()

    @property
    def match(self):
        r = self.result
        return None if r is None or isinstance(r, InputError) else r.match

    def _status(self) -> None:
        r = self.result
        if r is None:
            self.status.update(Text("… running the match", style="yellow"))
            return
        if isinstance(r, InputError):
            text = Text(f"✗ the workbook could not be solved: {r}", style="red")
        elif r.match is None:
            why = r.match_error or "the workbook has no [match] table"
            text = Text(f"✗ {self.source}: match: {why}", style="red")
        else:
            text = Text("✓ the match of the entries on screen", style="green")  # no path: snapshots
        if self.match is None and self.good is not None:
            text.append(
                "\n  (below, dimmed: the last match that ran, until the entries are fixed)", style="dim"
            )
        if self.running:  # the charts and outputs below stay those of the last entries until then
            text = Text(
                "… running the match for the entries on screen (below: the last entries')", style="yellow"
            )
        self.status.update(text)

    @guarded
    def opened(self) -> None:
        """The card was brought on screen (the workbook screen's tab strip: Textual's Show event
        did not always come when the pane switched, in a real terminal): its charts drawn now."""
        if self.good is not None and self.drawn != self.good_request:
            self.draw()
        else:
            self.call_after_refresh(self._fit_plots)

    @guarded
    def on_resize(self) -> None:
        self.call_after_refresh(self._fit_plots)

    @guarded
    def _fit_plots(self) -> None:
        """Each chart fitted again to its size after the card was hidden or resized: textual-plot
        resizes its canvases on a layout refresh (its public refresh(layout=True))."""
        if "textual_plot" not in sys.modules:
            return
        from textual_plot import PlotWidget

        for plot in self.query(PlotWidget):
            plot.refresh(layout=True)

    # ---- the charts ------------------------------------------------------------------------
    class Prepared(Message):
        """The charts' data (chart_data) of solve request `request`, or why it could not be made."""

        def __init__(self, request: int | None, charts: dict | None, error: str | None = None) -> None:
            super().__init__()
            self.request, self.charts, self.error = request, charts, error

    def draw(self) -> None:
        """The charts of the match shown: their data made in a worker (a brownout-ridden match has
        ~10⁵ samples: 0.17 s for the series alone), then drawn here. Nothing if they are drawn or
        being made for this request already."""
        wanted = self.good_request  # the latest match that ran (the one shown, dimmed if it is not)
        if self.good is None or self.drawn == wanted or self._preparing == wanted:
            return
        self._preparing = wanted
        # about a bar per column of the chart (the card's width less the axis margin and the scrollbar)
        columns = self.size.width - 14 if self.size.width > 34 else 120
        self._prepare(wanted, self.good, columns)

    # a description of our own: Textual's default is the arguments' repr, and the outcome's (10⁵ trace
    # samples in a brownout-ridden match) took 1.6 s on the UI thread at each start
    @work(
        thread=True,
        exclusive=True,
        group="match-charts",
        exit_on_error=False,
        description="Match card charts",
    )
    def _prepare(self, request: int | None, match, columns: int) -> None:
        worker = get_current_worker()
        try:
            charts = chart_data(match, columns, cancelled=lambda: worker.is_cancelled)
        except Exception as exc:  # a bug: said on the card and logged, the screen keeps working
            from ..bug_log import record
            from ..guard import internal_error

            self.post_message(self.Prepared(request, None, internal_error(exc, record(exc, "match charts"))))
            return
        if charts is not None:  # None: cancelled by a newer request, which posts its own
            self.post_message(self.Prepared(request, charts))

    @guarded
    async def on_match_view_prepared(self, message: Prepared) -> None:
        message.stop()
        if message.request != self.good_request:
            return  # a newer outcome came meanwhile: its charts are on their way
        self._preparing = None
        if message.charts is None:
            self.status.update(Text(f"✗ the charts could not be drawn: {message.error}", style="red"))
            return
        if self.display and self.app.is_running:
            await self._draw(message.charts)
            self.drawn = message.request

    async def _draw(self, c: dict) -> None:
        """The charts from chart_data's lists (textual-plot's public API only)."""
        from textual_plot import HiResMode

        from .plot_panel import quiet_plot_widget

        widget = quiet_plot_widget()
        plots = {}
        for name in CHARTS:
            holder = self.query_one(f"#match-{name}", Container)
            found = holder.query(widget)
            if found:
                plots[name] = found.first()
            else:
                plot = widget(allow_pan_and_zoom=False)
                await holder.mount(plot)
                if not plot.children:  # the app closed while it mounted
                    return
                plots[name] = plot
        length = c["length"]
        # bus voltage, and the controller's levels as flat lines across the match
        p = plots["voltage"]
        p.clear()
        p.plot(*c["voltage"], line_style="cyan", hires_mode=HiResMode.BRAILLE)
        for level, colour in ((c["brownout"], "red"), (c["recovery"], "yellow")):
            p.plot([0.0, length], [level] * 2, line_style=colour, hires_mode=HiResMode.BRAILLE)
        p.set_xlimits(0.0, length)
        p.set_ylimits(c["voltage_floor"], None)
        self._title(
            "voltage",
            ("bus", "cyan"),
            (f"brownout {c['brownout']:g} V", "red"),
            (f"recovery {c['recovery']:g} V (the outputs back on above it)", "yellow"),
        )
        p.set_xlabel(escape("Time [s]"))
        p.set_ylabel(escape("Bus [V]"))  # the left margin's width: a longer label is cut
        # the current, stacked: each layer's running sum, painted from the top one down
        p = plots["current"]
        p.clear()
        xs, bar = c["bars"], c["bar_width"]
        for _, ys, colour in reversed(c["layers"]):
            p.bar(xs, ys, width=bar, bar_style=colour)
        p.set_xlimits(0.0, length)
        self._title(
            "current",
            *((name, colour) for name, _, colour in c["layers"]),
            note=f"stacked from the bottom; a bar per {bar:.3g} s, at the instant of its highest current",
        )
        p.set_xlabel(escape("Time [s]"))
        p.set_ylabel(escape("Current [A]"))
        # the state of charge, plain and Peukert-weighted (the charge still available at these rates)
        p = plots["charge"]
        p.clear()
        p.plot(*c["charge"], line_style="green", hires_mode=HiResMode.BRAILLE)
        p.plot(*c["available"], line_style="magenta", hires_mode=HiResMode.BRAILLE)
        p.set_xlimits(0.0, length)
        self._title(
            "charge",
            ("state of charge", "green"),
            ("available at the rates drawn (Peukert; the lower line)", "magenta"),
        )
        p.set_xlabel(escape("Time [s]"))
        p.set_ylabel(escape("Charge [%]"))

    def _title(self, chart: str, *keys: tuple[str, str], note: str = "") -> None:
        """A chart's heading with its key, in place of a legend box (which hid the data under it:
        the example's lowest voltage, at 138.5 s): each series' colour swatch and name, in words
        too, so the key reads without colour (NO_COLOR)."""
        text = Text(CHARTS[chart], style="bold")
        text.append(": ")
        for i, (name, colour) in enumerate(keys):
            text.append("██", style=colour)
            text.append(f" {name}" + (", " if i < len(keys) - 1 else ""))
        if note:
            text.append(f" ({note})", style="dim")
        self.query_one(f"#match-{chart}-title", Static).update(text)


# a line chart's points: each bin's lowest and highest (series.envelope), 2 or more per braille
# pixel of a 300-column chart, and fine enough that a dip keeps its shape to the pixel
LINE_BINS = 2000


def chart_data(match, columns: int, cancelled=lambda: False) -> dict | None:
    """What the three charts draw, from a MatchOutcome (core/match/series.py), in plain lists: the
    lines thinned to their envelope, the current as each layer's running sum at the bins' peak
    instants. None when `cancelled()` says a newer request came (checked between the steps)."""
    from gearhead.core.match.series import envelope, peak_bins, series

    s = series(match)
    if cancelled():
        return None
    length = s.length
    bins = peak_bins(s, max(20, min(300, columns)))
    layers = [("base", s.base, BASE_COLOUR)] + [
        (card, amps, LAYER_COLOURS[k % len(LAYER_COLOURS)])
        for k, (card, amps) in enumerate(s.by_card.items())
    ]
    sums, running = [], [0.0] * len(bins)
    for name, amps, colour in layers:
        running = [r + amps[i] for r, (_, i) in zip(running, bins)]
        sums.append((name, list(running), colour))
    if cancelled():
        return None
    return {
        "length": length,
        "voltage": envelope(s.t, s.bus_voltage, length, LINE_BINS),
        "voltage_floor": min(min(s.bus_voltage, default=s.brownout), s.brownout) - 0.5,
        "brownout": s.brownout,
        "recovery": s.recovery,
        "bars": [x for x, _ in bins],
        "bar_width": length / max(len(bins), 1),
        "layers": sums,
        "charge": envelope(s.t, [100 * x for x in s.soc], length, LINE_BINS),
        "available": envelope(s.t, [100 * x for x in s.available], length, LINE_BINS),
    }
