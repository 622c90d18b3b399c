"""The report as Markdown, its charts as SVG files beside it (`{stem}_charts/{chart key}.svg`).

Every text from a file or a solve goes through `esc`: control characters made visible, line breaks
made spaces, and each character Markdown (or the HTML a renderer passes through) would act on
escaped with a backslash, so a name like `[x](javascript:…)` or `<script>` is shown as written.
"""

from __future__ import annotations

import re

from ..errors import printable
from . import charts as chart_svgs
from .document import CardSection, Chart, Report, Table

# CommonMark: any ASCII punctuation may be backslash-escaped; these are the ones that start
# emphasis, code, links, images, HTML, entities, tables, headings or math in common renderers
_SPECIAL = re.compile(r"([\\`*_{}\[\]<>#+!|~&$])")  # ( ) need none: a link needs an unescaped ]
_LIST_START = re.compile(r"^(\s*)([-=]|\d+[.)])")  # a line starting so would be a list or a heading


def esc(text: object) -> str:
    one_line = " ".join(str(text).split("\n"))
    return _SPECIAL.sub(r"\\\1", printable(one_line))


def paragraph(text: object) -> str:
    """Text that starts a line: also a leading -, = or 1. escaped (a list or a heading otherwise)."""
    return _LIST_START.sub(lambda m: m.group(1) + m.group(2)[:-1] + "\\" + m.group(2)[-1], esc(text))


def code(text: object, table: bool = False) -> str:
    """Text in a code span: as written (a code span shows it literally), the fence longer than any
    run of backticks inside it; in a table, | escaped (GFM splits cells on it even in code)."""
    s = printable(" ".join(str(text).split("\n")))
    if table:
        s = s.replace("|", "\\|")
    longest = max((len(m) for m in re.findall(r"`+", s)), default=0)
    fence = "`" * (longest + 1)
    return f"{fence} {s} {fence}"


def _table(t: Table, title: bool = True) -> list[str]:
    out = [f"**{esc(t.title)}**", ""] if title else []
    out.append("| " + " | ".join(esc(h) for h in t.heads) + " |")
    out.append("|" + "---|" * len(t.heads))
    out += ["| " + " | ".join(esc(c) for c in row) + " |" for row in t.rows]
    out.append("")
    return out


def _mark(holds: bool | None) -> str:
    return "not evaluated" if holds is None else ("✔ holds" if holds else "✘ fails")


def chart_files(report: Report, stem: str) -> dict[str, str]:
    """{relative path: SVG text} of every chart the Markdown links to."""
    return {f"{stem}_charts/{c.key}.svg": chart_svgs.svg(c) for c in report.charts()}


def _figure(chart: Chart, stem: str) -> list[str]:
    return [f"![{esc(chart.title)}]({stem}_charts/{chart.key}.svg)", ""]


def _card(card: CardSection, workbook: bool, stem: str) -> list[str]:
    out = [f"## {esc(card.heading)}", ""]
    if card.summary:
        out += [paragraph(card.summary), ""]
    if card.share_code:
        out += [f"Share code (opens this card{' alone' if workbook else ''}): {code(card.share_code)}", ""]
    if card.error:
        out += [f"**Not solved:** {esc(card.error)}", ""]
    if card.inputs:
        heads = ["Input", "As entered"] + (["Linked from"] if workbook else [])
        out += ["### Inputs", "", "| " + " | ".join(heads) + " |", "|" + "---|" * len(heads)]
        for e in [e for e in card.inputs if e.used] + [e for e in card.inputs if not e.used]:
            label = esc(e.label) + ("" if e.used else " *(not used with these choices)*")
            cells = [label, esc(e.text)] + ([esc(e.link)] if workbook else [])
            out.append("| " + " | ".join(cells) + " |")
        out.append("")
    if card.results:
        spread = any(r.spread for r in card.results)
        heads = ["Result", "Value"] + (["Spread"] if spread else []) + ["Eq.", "How"]
        out += ["### Results", "", "| " + " | ".join(heads) + " |", "|" + "---|" * len(heads)]
        for r in card.results:
            cells = (
                [esc(r.label), esc(r.text)]
                + ([esc(r.spread)] if spread else [])
                + [esc(r.equation), esc(r.how)]
            )
            out.append("| " + " | ".join(cells) + " |")
        out.append("")
    if card.equations:
        out += ["### Equations written out", ""]
        out += [f"- {esc(label)} {code(line)}" for label, line in card.equations]
        out.append("")
    if card.simulation is not None:
        s = card.simulation
        out += ["### Simulation", ""]
        out += [
            f"- Effects: {esc(s.effects)}",
            f"- Accuracy: {esc(s.accuracy)}",
            f"- Error estimate: {esc(s.error_estimate)}",
            f"- Solver work (evaluations): {esc(s.work)}",
            f"- Time of one run: {esc(s.wall_time)}",
            "",
        ]
    if card.warnings:
        out += ["### Warnings", ""] + [f"- {esc(w)}" for w in card.warnings] + [""]
    for t in card.tables:
        out += _table(t)
    for chart in card.charts:
        out += _figure(chart, stem)
    return out


def write(report: Report, stem: str) -> str:
    """The report as Markdown text; its charts are `chart_files(report, stem)`, beside it."""
    workbook = report.kind == "workbook"
    out = [f"# {esc(report.title)}", ""]
    if report.description:
        out += [paragraph(report.description), ""]
    out.append(f"- Design report of a {report.kind}: {esc(report.source)}")
    if report.sets:
        out.append(f"- Set for this report (--set): {esc(report.set_text())}")
    out.append(f"- Gearhead version: {esc(report.version)}")
    if report.date:
        out.append(f"- Date: {esc(report.date)}")
    if report.share_code:
        out.append(f"- Share code: {code(report.share_code)}")
    if workbook:
        holds = sum(1 for r in report.requirements if r.holds)
        out.append(f"- Cards: {esc(', '.join(c.key for c in report.cards))}")
        out.append(
            f"- Requirements: {len(report.requirements)}: {holds} hold, {len(report.requirements) - holds} fail"
        )
    out.append("")
    if workbook:
        out += ["## Requirements", ""]
        worst = any(r.worst for r in report.requirements)
        heads = ["", "Requirement", "Check", "Values and margin"] + (["Worst case"] if worst else [])
        if report.requirements:
            out += ["| " + " | ".join(heads) + " |", "|" + "---|" * len(heads)]
            for r in report.requirements:
                name = esc(r.name) + (f" ({esc(r.note)})" if r.note else "")
                cells = [_mark(r.holds), name, code(r.check, table=True), esc(r.text)]
                if worst:
                    cells.append((_mark(r.worst_holds) + " " if r.worst else "") + esc(r.worst))
                out.append("| " + " | ".join(cells) + " |")
            out.append("")
        if report.requirements_note:
            out += [f"Note: {esc(report.requirements_note)}", ""]
        out += [f"Worst case: {esc(n)}" for n in report.worst_case_notes] + (
            [""] if report.worst_case_notes else []
        )
        if report.variables is not None:
            out += ["## Variables", ""] + _table(report.variables, title=False)
    for card in report.cards:
        out += _card(card, workbook, stem)
    if report.match is not None:
        m = report.match
        out += ["## The match", ""]
        out += [f"- {esc(label)}: {esc(text)}" for label, text in m.summary] + [""]
        for chart in m.charts:
            out += _figure(chart, stem)
        out += _table(m.shares)
        out += _table(m.brownouts) if m.brownouts.rows else ["**Brownouts**: none", ""]
        out += _table(m.moves)
    elif report.match_error:
        out += ["## The match", "", f"**Not run:** {esc(report.match_error)}", ""]
    out += [f"*Made by Gearhead {esc(report.version)} (gearhead report).*", ""]
    return "\n".join(out)
