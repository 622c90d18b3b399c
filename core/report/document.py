"""The report's content as plain data: title block, one section per card, requirements, the match.

Every value is the text the command line prints for it (Value.text of a solution, CheckResult.text(),
units.format_number and format_quantity), so a report and `gearhead solve --json` / `check` / `match`
never disagree. Nothing here draws or writes: core.report.html and core.report.markdown do, and the
charts are data (series in display units) until core.report.charts draws them.

No timestamp unless asked (`date`), and no wall time (it differs run to run) unless a date is asked
too: the same file gives the same report, byte for byte, to keep in a team's git and diff.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from typing import Any

from .. import units
from ..declarations import Calculator, HeatMap, Plot
from ..errors import InputError, printable
from ..sim.scene import VOLATILE

NOT_RECORDED = "not recorded (it differs run to run; `--date` records it)"
NOT_RECORDED_VALUE = "not recorded"  # in a results table (the simulation's table says why)


@dataclass(frozen=True)
class Entry:
    """One input as entered: its label, its text (with its unit), a workbook's reference to it."""

    name: str
    label: str
    text: str
    link: str = ""  # '= robot_mass' in a workbook
    used: bool = True  # False: the other choices leave it unused (kept, not read)


@dataclass(frozen=True)
class ResultLine:
    name: str
    label: str
    text: str  # in the display unit, as `gearhead solve` prints it
    equation: str  # the seed's equation label(s), e.g. "(12)" or "(GR1)"
    how: str  # the output's one-line "how" (the app's help line of the result)
    spread: str = ""  # with tolerances: worst case and σ


@dataclass(frozen=True)
class Series:
    label: str
    x: list[float]  # display units
    y: list[float]


@dataclass(frozen=True)
class HeatData:
    x: list[float]  # display units
    y: list[float]
    z: list[list[float | None]]
    pick: tuple[int, int] | None
    z_label: str


@dataclass(frozen=True)
class Chart:
    key: str  # unique in the report, file-name safe: the Markdown writer's SVG file name
    title: str
    x_label: str  # with its unit, "Time [s]"
    y_label: str
    series: list[Series] = field(default_factory=list)
    heat: HeatData | None = None
    level: tuple[float, str] | None = None  # a horizontal line (the brownout voltage) and its label
    stacked: bool = False  # the series are layers stacked on each other (one x for all), not lines


@dataclass(frozen=True)
class Table:
    title: str
    heads: list[str]
    rows: list[list[str]]


@dataclass(frozen=True)
class Simulation:
    """The effects and accuracy a simulated card used, its error estimate and its cost."""

    effects: str
    accuracy: str
    error_estimate: str
    work: str
    wall_time: str


@dataclass
class CardSection:
    key: str  # the card's name in a workbook, the calculator id for a preset
    heading: str
    calculator: str
    title: str
    summary: str
    share_code: str  # opens this card alone (gearhead --preset CODE, ctrl+o)
    inputs: list[Entry] = field(default_factory=list)
    results: list[ResultLine] = field(default_factory=list)
    equations: list[tuple[str, str]] = field(default_factory=list)  # (label, the line written out)
    method: str = ""  # the calculator's module docstring: its equations and corrections
    simulation: Simulation | None = None
    warnings: list[str] = field(default_factory=list)
    tables: list[Table] = field(default_factory=list)
    charts: list[Chart] = field(default_factory=list)
    error: str | None = None  # a workbook card that could not be solved


@dataclass(frozen=True)
class RequirementLine:
    name: str
    check: str
    note: str
    holds: bool | None  # None: not evaluated
    text: str  # values and margin, as `gearhead check` prints them
    worst: str = ""  # the worst case over the tolerances, when asked
    worst_holds: bool | None = None


@dataclass
class MatchSection:
    summary: list[tuple[str, str]]  # (label, value), as `gearhead match` prints them
    shares: Table
    moves: Table
    brownouts: Table
    charts: list[Chart]


@dataclass
class Report:
    title: str
    description: str
    kind: str  # "preset" or "workbook"
    source: str  # the file (or share code) as given
    version: str  # Gearhead's
    share_code: str  # "" for a workbook (a code holds one card: each card's is with it)
    date: str = ""
    # the variables the command line set (--set NAME=VALUE): (name, the value set, the file's entry);
    # the title block names them, so no reader takes the report for the file's own design
    sets: list[tuple[str, str, str]] = field(default_factory=list)
    variables: Table | None = None
    cards: list[CardSection] = field(default_factory=list)
    requirements: list[RequirementLine] = field(default_factory=list)
    requirements_note: str = ""
    worst_case_notes: list[str] = field(default_factory=list)
    match: MatchSection | None = None
    match_error: str | None = None

    def set_text(self) -> str:
        """The variables the command line set, each with what the file says."""
        return "; ".join(f"{name} = {value} (the file: {own})" for name, value, own in self.sets)

    def charts(self) -> list[Chart]:
        out = [c for card in self.cards for c in card.charts]
        return out + (self.match.charts if self.match else [])


def version() -> str:
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("gearhead")
    except PackageNotFoundError:  # run from a checkout that was never installed
        return "unknown"


# ---------------------------------------------------------------------------------------------
# One card


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-") or "chart"


def _axis(label: str, unit: str) -> str:
    return f"{label} [{unit}]" if unit else label


def charts_of(calc: Calculator, solution, prefix: str) -> list[Chart]:
    """The card's charts with data: the series its Plot declarations name (what the app's card
    plots, core.declarations.Plot), converted to the plot's display units as the card does."""
    out = []
    for spec in calc.plots:
        key = f"{prefix}-{_slug(spec.title)}"
        if isinstance(spec, HeatMap):
            data = solution.heat_maps.get(spec.name)
            if data is None:
                continue
            fx = units.factor(spec.x_unit, spec.x_quantity)
            fy = units.factor(spec.y_unit, spec.y_quantity)
            fz = units.factor(spec.z_unit, spec.z_quantity)
            heat = HeatData(
                [x / fx for x in data.x],
                [y / fy for y in data.y],
                [[None if z is None else z / fz for z in row] for row in data.z],
                data.pick,
                _axis(spec.z_label, spec.z_unit),
            )
            out.append(
                Chart(
                    key,
                    spec.title,
                    _axis(spec.x_label, spec.x_unit),
                    _axis(spec.y_label, spec.y_unit),
                    heat=heat,
                )
            )
            continue
        assert isinstance(spec, Plot)
        series = []
        fx = units.factor(spec.x_unit, spec.x_quantity)
        fy = units.factor(spec.y_unit, spec.y_quantity)
        for name in spec.series:
            xs, ys = solution.series.get(name, ([], []))
            if not xs:
                continue
            series.append(Series(solution.series_label(name), [x / fx for x in xs], [y / fy for y in ys]))
        if series:
            out.append(
                Chart(
                    key,
                    spec.title,
                    _axis(spec.x_label, spec.x_unit),
                    _axis(spec.y_label, spec.y_unit),
                    series,
                )
            )
    return out


def _module_doc(calc: Calculator) -> str:
    """The docstring of the calculator's own module (its equations, corrections and sources)."""
    for module in list(sys.modules.values()):
        if getattr(module, "CALCULATOR", None) is calc:
            return (module.__doc__ or "").strip()
    return ""


_LABEL = re.compile(r"\([A-Za-z]*\d+[a-z]?\)")


def written_out(calc: Calculator, doc: str) -> list[tuple[str, str]]:
    """(label, line) for each equation of the card's results that its module's docstring writes out
    (a line with '=' that ends with the label, as `P_out = F·v_load   (GR1)`)."""
    wanted = []
    for o in calc.outputs:
        for label in _LABEL.findall(o.equation):
            if label not in wanted:
                wanted.append(label)
    out = []
    lines = [" ".join(line.split()) for line in doc.splitlines()]
    for label in wanted:
        for line in lines:
            if line.endswith(label) and _EQUATION.match(line):
                out.append((label, line[: -len(label)].rstrip()))
    return out


# a line that starts an equation: its left side (a symbol, maybe a function of something), then '=';
# not the end of one begun on the line above ('(d = v·τ), then ...', '⇔ X = ...')
_EQUATION = re.compile(r"^[^\s=(⇔,;.][^=]{0,40}=")


def _active(calc: Calculator, raw: dict) -> dict[str, bool]:
    from ..model import choice_values

    choices = choice_values(calc, raw)
    mode = None
    if "mode" in {f.name for f in calc.fields}:
        try:
            mode = calc.field("mode").parse(raw.get("mode", calc.field("mode").default))
        except InputError:
            mode = None
    return {f.name: f.active(mode, choices) for f in calc.fields}


def _simulation(calc: Calculator, solution, timings: bool) -> Simulation | None:
    names = {f.name for f in calc.fields}
    if "accuracy" not in names or "error_estimate" not in solution.outputs:
        return None
    acc = calc.field("accuracy")
    level = solution.inputs["accuracy"].value
    accuracy = acc.choice_labels[acc.choices.index(level)] if level in acc.choices else str(level)
    effects = solution.inputs["effects"].text if "effects" in names else ""
    wall = solution.outputs.get("wall_time")
    return Simulation(
        effects or "none",
        accuracy,
        solution.outputs["error_estimate"].text,
        solution.outputs["rhs_evaluations"].text if "rhs_evaluations" in solution.outputs else "",
        (wall.text if timings else NOT_RECORDED) if wall is not None else "",
    )


def card_section(
    key: str,
    heading: str,
    calc: Calculator,
    solution,
    raw: dict,
    share_code: str,
    links: dict[str, str] | None = None,
    spread=None,
    warnings: list[str] | None = None,
    timings: bool = False,
) -> CardSection:
    """A solved card: its inputs (as entered), results, equations, simulation, warnings, charts."""
    doc = _module_doc(calc)
    section = CardSection(
        key, heading, calc.id, calc.title, calc.summary, share_code, method=doc, warnings=list(warnings or [])
    )
    from ..solving import has_tolerance

    links = links or {}
    used = _active(calc, raw)
    for f in calc.fields:
        if f.name in solution.inputs:
            text = solution.inputs[f.name].text
            if has_tolerance({f.name: raw.get(f.name)}):  # the solution holds the nominal value
                text = printable(str(raw[f.name]).strip())
            section.inputs.append(Entry(f.name, f.label, text, links.get(f.name, ""), used[f.name]))
    if spread is not None:
        from ..tolerance import spread_text
    for name, value in solution.outputs.items():
        out = calc.output(name)
        text = value.text if (timings or name not in VOLATILE) else NOT_RECORDED_VALUE
        extra = ""
        if spread is not None and name in spread.outputs:
            extra = spread_text(calc, solution, spread.outputs[name])
        section.results.append(ResultLine(name, out.label, text, out.equation, out.help, extra))
    section.equations = written_out(calc, doc)
    section.simulation = _simulation(calc, solution, timings)
    section.warnings += [w for w in solution.warnings if w not in section.warnings]
    if spread is not None:
        section.warnings += [f"± {n}" for n in spread.notes]
    entries = solution.entries()
    for t in calc.tables:
        if not t.shown_in(entries):
            continue
        columns = [c for c in t.columns if not c.hidden]
        rows = [
            [row[c.name].text if c.name in row else "" for c in columns]
            for row in solution.tables.get(t.name, [])
        ]
        section.tables.append(Table(t.title, [_axis(c.label, c.unit) for c in columns], rows))
    section.charts = charts_of(calc, solution, _slug(key))
    return section


# ---------------------------------------------------------------------------------------------
# A preset


def from_preset(preset, source: str = "", *, date: str = "", method: str = "auto") -> Report:
    """The report of one preset (a file, a share code or a ReCalc link, core.share.load_any)."""
    from .. import share, solving
    from ..registry import get

    calc = get(preset.calculator)
    solved = solving.solve(calc, preset.inputs, method=method)
    code = share.encode(preset)
    report = Report(
        preset.name,
        preset.description,
        "preset",
        source or str(preset.path or ""),
        version(),
        code,
        date,
    )
    report.cards.append(
        card_section(
            calc.id,
            f"{calc.title} ({calc.id})",
            calc,
            solved.solution,
            dict(preset.inputs),
            code,
            spread=solved.spread,
            warnings=list(preset.warnings),
            timings=bool(date),
        )
    )
    return report


# ---------------------------------------------------------------------------------------------
# A workbook


def _variable_text(v, value: Any) -> str:
    if value is None:
        return "not solved"
    from ..workbook.expressions import is_quantity, kind_of

    if is_quantity(value):
        if v.unit and kind_of(value):
            try:
                return f"{units.format_number(float(value.to(v.unit).magnitude))} {v.unit}"
            except Exception:  # a unit pint reads differently: the value in SI below
                pass
        return f"{units.format_number(float(value.to_base_units().magnitude))} {value.to_base_units().units:~}".strip()
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, (int, float)):
        return units.format_number(value) if isinstance(value, float) else str(value)
    return str(value)


def _entry(v) -> str:
    """A variable as written in its file: its entry, or '= ' and its expression."""
    return str(v.entry) if v.expr is None else "= " + v.expr.text


def from_workbook(
    wb, *, date: str = "", worst_case: bool = False, file_entries: dict[str, str] | None = None
) -> Report:
    """The report of a workbook: its variables, every card, the requirements and the match.
    `file_entries`: the file's own entry of each variable the command line set (--set), which `wb`
    holds replaced; the title block and the variables' table say so."""
    from .. import share, workbook
    from ..presets import Preset
    from ..registry import get

    outcome = workbook.solve(wb)
    report = Report(wb.name, wb.description, "workbook", wb.source, version(), "", date)
    file_entries = file_entries or {}
    report.sets = [(k, _entry(wb.variables[k]), e) for k, e in file_entries.items() if k in wb.variables]
    rows = []
    for name, v in wb.variables.items():
        entry = _entry(v) + (" (--set)" if name in file_entries else "")
        rows.append([name, entry, _variable_text(v, outcome.variables.get(name))])
    if rows:
        report.variables = Table("Variables", ["Variable", "As written", "Value"], rows)
    for name, card in outcome.cards.items():
        calc = get(card.calculator)
        heading = f"{name}: {calc.title} ({calc.id})"
        book_card = wb.cards[name]
        if card.solution is None:  # its entries as written (links resolved), and why it failed
            entries = [
                Entry(f.name, f.label, printable(str(card.entries[f.name])), card.links.get(f.name, ""))
                for f in calc.fields
                if f.name in card.entries
            ]
            report.cards.append(
                CardSection(
                    name,
                    heading,
                    calc.id,
                    calc.title,
                    calc.summary,
                    "",
                    inputs=entries,
                    warnings=list(book_card.warnings),
                    error=card.error,
                )
            )
            continue
        preset = Preset(
            calc.id, f"{wb.name}: {name}", f"card {name} of {wb.source}", _stored(calc, card.entries)
        )
        report.cards.append(
            card_section(
                name,
                heading,
                calc,
                card.solution,
                dict(card.entries),
                share.encode(preset),
                card.links,
                warnings=list(book_card.warnings),
                timings=bool(date),
            )
        )
    worst = None
    if worst_case:
        from ..workbook import study

        worst = study.worst_case(wb)
        report.worst_case_notes = list(worst.notes)
        if worst.spread is not None:
            tolerances = ", ".join(t.entry for t in worst.spread.tolerances)
            cost = worst.spread.cost.text() if date else f"{worst.spread.cost.solves} solves"
            report.worst_case_notes.insert(0, f"tolerances: {tolerances}; {cost}")
    elif any(v.tolerance for v in wb.variables.values()):
        report.requirements_note = (
            "tolerances on variables are not analysed here: `gearhead report FILE --worst-case` adds each "
            "requirement's worst case"
        )
    for c in outcome.checks:
        r = c.requirement
        line = RequirementLine(r.name or r.check, r.check, r.note, c.holds, c.text())
        if worst is not None and c.holds is not None:
            line = _with_worst(line, worst, r.key)
        report.requirements.append(line)
    report.match_error = outcome.match_error
    if outcome.match is not None:
        report.match = match_section(outcome.match)
    return report


def _stored(calc: Calculator, entries: dict) -> dict:
    """A card's entries as a preset stores them (whole numbers as integers, as the app saves)."""
    out = {}
    for f in calc.fields:
        if f.name in entries:
            try:
                out[f.name] = f.kind.stored(f, entries[f.name])
            except (InputError, ValueError, TypeError):
                out[f.name] = entries[f.name]
    return out


def _with_worst(line: RequirementLine, worst, key: str) -> RequirementLine:
    from dataclasses import replace

    low = worst.low(key)
    if worst.spread is None or key not in worst.spread.outputs or low is None:
        return line
    o = worst.calculator.output(key)
    spread = worst.spread.outputs[key]
    text = f"margin {units.format_quantity(low, o.unit, o.quantity)} ({spread.worst_case_method})"
    if spread.infeasible:
        text += "; not solved in the tolerance box: " + "; ".join(spread.infeasible)
    return replace(line, worst=text, worst_holds=worst.holds(key))


def match_section(m) -> MatchSection:
    """The match as `gearhead match` shows it: its outputs, the charge's shares, the moves and the
    brownouts, and the bus voltage and battery current over the match as charts."""
    from ..workbook.match import OUTPUTS, output_info

    summary = []
    length = m.spec.values["length"]
    summary.append(("Match", f"{units.format_number(length)} s, {len(m.moves)} moves"))
    summary.append(
        (
            "Battery",
            f"{units.format_number(m.battery.R * 1000)} mΩ, {units.format_number(m.battery.start_soc * 100)} % charged",
        )
    )
    summary.append(("Brownout level", f"{units.format_number(m.controller.brownout)} V"))
    for key, (label, unit) in OUTPUTS.items():
        if key not in m.outputs:
            continue
        value = m.outputs[key]
        text = f"{value:d}" if isinstance(value, int) else f"{units.format_number(value)} {unit}".rstrip()
        if key == "min_bus_time" and m.running_at_min:
            text += f" ({', '.join(m.running_at_min)} running)"
        summary.append((label.strip() if label.strip() != "at" else "Lowest bus voltage at", text))
    cards = set(m.bus.channels)
    for key, value in m.outputs.items():  # each card's channel breaker: `<card>_breaker_load` ...
        if key not in OUTPUTS and (info := output_info(key, cards)) is not None:
            label, unit = info
            summary.append((label.strip(), f"{units.format_number(value)} {unit}".rstrip()))
    shares = Table(
        "Share of the charge; peak supply current per motor (of a 40 A breaker)",
        ["Card", "Share of the charge", "Peak supply current per motor"],
        [
            [
                k,
                f"{units.format_number(v * 100)} %",
                (f"{units.format_number(m.channel_peaks[k])} A" if k in m.channel_peaks else ""),
            ]
            for k, v in m.shares.items()
        ],
    )
    moves = Table(
        "Moves",
        ["Card", "Action", "Asked at", "Started", "Arrived", "Peak supply current"],
        [
            [
                ev.card,
                ev.action,
                f"{units.format_number(t)} s",
                f"{units.format_number(r.start)} s" if r.trace else "",
                f"{units.format_number(r.arrival)} s" if r.arrival is not None else "not finished",
                f"{units.format_number(r.peak_supply_current)} A",
            ]
            for t, ev, r in m.moves
        ],
    )
    brownouts = Table(
        "Brownouts",
        ["Start", "Length", "Running"],
        [
            [
                f"{units.format_number(b.start)} s",
                f"{units.format_number(b.length * 1000)} ms",
                ", ".join(b.running) or "-",
            ]
            for b in m.brownouts
        ],
    )
    ts = [t for t, _, _ in m.bus.trace]
    charts = _match_charts(m, ts)
    return MatchSection(summary, shares, moves, brownouts, charts)


# the charts are ~430 pt wide: the state of charge keeps each of LINE_BINS time bins' first, lowest,
# highest and last sample (series.envelope, exact at the bins' edges); the stacked current shows in
# each of STACK_BINS columns the sample of its highest battery current (series.peak_bins), as the
# app's Match card does (a move's peak is never averaged away)
LINE_BINS = 600
STACK_BINS = 400


def _match_charts(m, ts: list[float]) -> list[Chart]:
    """The bus voltage and battery current (every sample), the state of charge and the current
    stacked by card (core.match.series: S1, S2)."""
    from ..match.series import envelope, peak_bins, series

    s = series(m)
    bins = peak_bins(s, STACK_BINS)
    xs = [x for x, _ in bins]
    layers = [Series("base load", xs, [s.base[i] for _, i in bins])]
    layers += [Series(card, xs, [amps[i] for _, i in bins]) for card, amps in s.by_card.items()]
    return [
        Chart(
            "match-bus-voltage",
            "Bus voltage over the match",
            "Time [s]",
            "Bus voltage [V]",
            [Series("bus voltage", ts, [v for _, v, _ in m.bus.trace])],
            level=(m.controller.brownout, "brownout"),
        ),
        Chart(
            "match-battery-current",
            "Battery current over the match",
            "Time [s]",
            "Battery current [A]",
            [Series("battery current", ts, [i for _, _, i in m.bus.trace])],
        ),
        Chart(
            "match-state-of-charge",
            "State of charge over the match",
            "Time [s]",
            "Charge [%]",
            [
                Series("state of charge", *envelope(s.t, [100 * x for x in s.soc], s.length, LINE_BINS)),
                Series(
                    "charge available at the rates drawn",
                    *envelope(s.t, [100 * x for x in s.available], s.length, LINE_BINS),
                ),
            ],
        ),
        Chart(
            "match-current-by-card",
            "Battery current by card (each column: its highest)",
            "Time [s]",
            "Battery current [A]",
            layers,
            stacked=True,
        ),
    ]


# ---------------------------------------------------------------------------------------------
# A file


def is_workbook(path: str) -> bool:
    """Whether `path` names a workbook (an example `builtin:NAME`, or a file with no `calculator`)."""
    import os

    from .. import builtin
    from ..workbook import is_workbook_file

    if builtin.is_builtin(path) and not os.path.isfile(path):
        try:
            builtin.workbook_path(path)
            return True
        except InputError:
            return False
    return os.path.isfile(path) and is_workbook_file(path)


def load(path: str, *, worst_case: bool = False, sets: dict[str, str] | None = None):
    """What `path` holds, read and checked but not solved: a Workbook, or a (Preset, source) pair.
    A bad file raises InputError with the message `gearhead check` / `solve --preset` give;
    `sets` replaces workbook variables' entries as `gearhead check --set` does."""
    from .. import share, workbook

    if not str(path).strip():
        raise InputError("file", "is empty; give a preset or workbook file")
    if is_workbook(path):
        return workbook.load(path, sets or None)
    if worst_case:
        raise InputError("--worst-case", "is for a workbook; a preset's tolerances are in its entries (±)")
    if sets:
        raise InputError(
            "--set", "is for a workbook's variables; a preset has none (its entries are in the file)"
        )
    return share.load_any(path), path


def build(
    path: str, *, date: str = "", worst_case: bool = False, sets: dict[str, str] | None = None
) -> Report:
    """The report of a preset or workbook file, a `builtin:NAME`, a share code or a ReCalc link;
    `sets`: workbook variables replaced (NAME: VALUE, the command line's --set)."""
    loaded = load(path, worst_case=worst_case, sets=sets)
    file_entries = None
    if sets and not isinstance(loaded, tuple):  # what the file itself says, for the title block
        from .. import workbook

        own = workbook.load(path).variables
        file_entries = {k: _entry(own[k]) for k in sets}
    return of(loaded, date=date, worst_case=worst_case, file_entries=file_entries)


def of(
    loaded, *, date: str = "", worst_case: bool = False, file_entries: dict[str, str] | None = None
) -> Report:
    """The report of what `load` read (solved now); `file_entries` as from_workbook's."""
    if isinstance(loaded, tuple):
        preset, source = loaded
        return from_preset(preset, source, date=date)
    return from_workbook(loaded, date=date, worst_case=worst_case, file_entries=file_entries)
