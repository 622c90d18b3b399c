"""The report as one self-contained HTML file: its style inline, each chart an inline SVG, no script,
no font, image or link that would reach the network (a Content-Security-Policy says so too).

Every text from a file or a solve goes through `esc`: control characters made visible
(core.errors.printable), then HTML-escaped, so a name like `<script>` is shown, never run.
"""

from __future__ import annotations

import html
import re

from ..errors import printable
from . import charts as chart_svgs
from .document import CardSection, Chart, Report, Table

STYLE = """
:root { color-scheme: light; }
body { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; font-size: 10.5pt; color: #111;
  max-width: 190mm; margin: 0 auto; padding: 10mm 6mm; line-height: 1.35; }
h1 { font-size: 20pt; margin: 0 0 2mm; }
h2 { font-size: 14pt; margin: 8mm 0 2mm; border-bottom: 1.5px solid #333; padding-bottom: 1mm; }
h3 { font-size: 11pt; margin: 4mm 0 1.5mm; }
p.description { font-size: 11.5pt; margin: 0 0 3mm; }
table { border-collapse: collapse; width: 100%; margin: 1mm 0 3mm; font-size: 9.5pt; }
th, td { border: 1px solid #bbb; padding: 1mm 1.6mm; text-align: left; vertical-align: top; }
th { background: #eee; }
td.value { white-space: nowrap; font-variant-numeric: tabular-nums; }
td.mark { white-space: nowrap; }
table.results td:first-child, table.inputs td:first-child { width: 30%; }
table.results td.value { width: 1%; }
table.meta th { width: 28%; }
tr.unused td { color: #777; }
.code { font-family: "DejaVu Sans Mono", monospace; font-size: 8pt; word-break: break-all; }
.holds { color: #176b2c; font-weight: bold; }
.fails { color: #b00020; font-weight: bold; }
.unknown { color: #8a6d00; font-weight: bold; }
.how { color: #444; font-size: 8.5pt; }
ul.warnings li { color: #8a4b00; }
figure { margin: 2mm 0 4mm; break-inside: avoid; }
figure svg { width: 100%; height: auto; }
figcaption { font-size: 8.5pt; color: #444; }
details pre { white-space: pre-wrap; font-size: 8pt; background: #f6f6f6; padding: 2mm; }
section.card { break-before: page; }
footer { margin-top: 8mm; font-size: 8pt; color: #555; }
@media print { body { padding: 0; } details { display: block; } }
@page { margin: 14mm 12mm; }
"""

# no network: nothing may load from anywhere (the charts are inline, the style is inline)
CSP = "default-src 'none'; style-src 'unsafe-inline'; img-src data:"


def esc(text: object) -> str:
    """Text from a file or a solve, safe in HTML text and attributes (control characters shown)."""
    return html.escape(printable(text, keep_newlines=True), quote=True)


def _mark(holds: bool | None) -> str:
    if holds is None:
        return '<span class="unknown">not evaluated</span>'
    return '<span class="holds">✔ holds</span>' if holds else '<span class="fails">✘ fails</span>'


def _table(t: Table, caption: bool = True) -> list[str]:
    out = [f"<h3>{esc(t.title)}</h3>"] if caption else []
    out.append("<table><thead><tr>" + "".join(f"<th>{esc(h)}</th>" for h in t.heads) + "</tr></thead><tbody>")
    for row in t.rows:
        out.append("<tr>" + "".join(f"<td>{esc(c)}</td>" for c in row) + "</tr>")
    out.append("</tbody></table>")
    return out


_SVG_START = re.compile(r"<svg\b")


def inline_svg(chart: Chart) -> str:
    text = chart_svgs.svg(chart)
    start = _SVG_START.search(text)
    return text[start.start() :] if start else text  # the XML declaration and DOCTYPE go


def _figure(chart: Chart) -> list[str]:
    return [
        f'<figure id="{esc(chart.key)}">',
        inline_svg(chart),
        f"<figcaption>{esc(chart.title)}: {esc(chart.y_label)} against {esc(chart.x_label)}</figcaption>",
        "</figure>",
    ]


def _card(card: CardSection, workbook: bool) -> list[str]:
    out = [f'<section class="card" id="card-{esc(card.key)}">', f"<h2>{esc(card.heading)}</h2>"]
    if card.summary:
        out.append(f"<p>{esc(card.summary)}</p>")
    if card.share_code:
        out.append(
            f"<p>Share code (opens this card{' alone' if workbook else ''}): "
            f'<span class="code">{esc(card.share_code)}</span></p>'
        )
    if card.error:
        out.append(f'<p class="fails">Not solved: {esc(card.error)}</p>')
    used = [e for e in card.inputs if e.used]
    unused = [e for e in card.inputs if not e.used]
    if card.inputs:
        out.append("<h3>Inputs</h3>")
        heads = ["Input", "As entered"] + (["Linked from"] if workbook else [])
        out.append(
            '<table class="inputs"><thead><tr>'
            + "".join(f"<th>{h}</th>" for h in heads)
            + "</tr></thead><tbody>"
        )
        for e in used + unused:
            cls = ' class="unused"' if not e.used else ""
            link = f"<td>{esc(e.link)}</td>" if workbook else ""
            label = esc(e.label) + (" <i>(not used with these choices)</i>" if not e.used else "")
            out.append(f'<tr{cls}><td>{label}</td><td class="value">{esc(e.text)}</td>{link}</tr>')
        out.append("</tbody></table>")
    if card.results:
        spread = any(r.spread for r in card.results)
        out.append("<h3>Results</h3>")
        heads = ["Result", "Value"] + (["Spread"] if spread else []) + ["Eq.", "How"]
        out.append(
            '<table class="results"><thead><tr>'
            + "".join(f"<th>{h}</th>" for h in heads)
            + "</tr></thead><tbody>"
        )
        for r in card.results:
            cells = [f"<td>{esc(r.label)}</td>", f'<td class="value">{esc(r.text)}</td>']
            if spread:
                cells.append(f"<td>{esc(r.spread)}</td>")
            cells += [f"<td>{esc(r.equation)}</td>", f'<td class="how">{esc(r.how)}</td>']
            out.append("<tr>" + "".join(cells) + "</tr>")
        out.append("</tbody></table>")
    if card.equations:
        out.append("<h3>Equations written out</h3><ul>")
        out += [f"<li>{esc(label)} {esc(line)}</li>" for label, line in card.equations]
        out.append("</ul>")
    if card.simulation is not None:
        s = card.simulation
        out.append('<h3>Simulation</h3><table class="meta"><tbody>')
        for label, text in (
            ("Effects", s.effects),
            ("Accuracy", s.accuracy),
            ("Error estimate", s.error_estimate),
            ("Solver work (evaluations)", s.work),
            ("Time of one run", s.wall_time),
        ):
            out.append(f"<tr><th>{label}</th><td>{esc(text)}</td></tr>")
        out.append("</tbody></table>")
    if card.warnings:
        out.append('<h3>Warnings</h3><ul class="warnings">')
        out += [f"<li>{esc(w)}</li>" for w in card.warnings]
        out.append("</ul>")
    for t in card.tables:
        out += _table(t)
    for chart in card.charts:
        out += _figure(chart)
    if card.method:
        out.append(
            "<details><summary>Method: the calculator's own notes (equations, corrections, sources)"
            f"</summary><pre>{esc(card.method)}</pre></details>"
        )
    out.append("</section>")
    return out


def write(report: Report) -> str:
    """The whole report as one HTML document (text)."""
    workbook = report.kind == "workbook"
    out = [
        "<!DOCTYPE html>",
        '<html lang="en">',
        "<head>",
        '<meta charset="utf-8">',
        f'<meta http-equiv="Content-Security-Policy" content="{CSP}">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{esc(report.title)} · Gearhead design report</title>",
        f"<style>{STYLE}</style>",
        "</head>",
        "<body>",
        "<header>",
        f"<h1>{esc(report.title)}</h1>",
    ]
    if report.description:
        out.append(f'<p class="description">{esc(report.description)}</p>')
    out.append('<table class="meta"><tbody>')
    meta = [
        ("Design report of", f"a {report.kind}: {report.source}"),
        ("Gearhead version", report.version),
    ]
    if report.sets:
        meta.insert(1, ("Set for this report (--set)", report.set_text()))
    if report.date:
        meta.append(("Date", report.date))
    for label, text in meta:
        out.append(f"<tr><th>{esc(label)}</th><td>{esc(text)}</td></tr>")
    if report.share_code:
        out.append(f'<tr><th>Share code</th><td class="code">{esc(report.share_code)}</td></tr>')
    if workbook:
        holds = sum(1 for r in report.requirements if r.holds)
        fails = len(report.requirements) - holds
        out.append(
            f"<tr><th>Cards</th><td>{esc(', '.join(c.key for c in report.cards))}</td></tr>"
            f"<tr><th>Requirements</th><td>{len(report.requirements)}: "
            f'<span class="holds">{holds} hold</span>, '
            f'<span class="{"fails" if fails else "holds"}">{fails} fail</span></td></tr>'
        )
    out.append("</tbody></table>")
    out.append("</header>")
    if workbook:
        out += _requirements(report)
        if report.variables is not None:
            out += ["<h2>Variables</h2>"] + _table(report.variables, caption=False)
    for card in report.cards:
        out += _card(card, workbook)
    if report.match is not None or report.match_error:
        out += _match(report)
    out.append(
        "<footer>Made by Gearhead "
        f"{esc(report.version)} (`gearhead report`). Values are shown as `gearhead solve` prints them; "
        "each card's share code reopens it in Gearhead.</footer>"
    )
    out += ["</body>", "</html>", ""]
    return "\n".join(out)


def _requirements(report: Report) -> list[str]:
    out = ['<section id="requirements"><h2>Requirements</h2>']
    if not report.requirements:
        out.append("<p>The workbook states no requirement.</p>")
    else:
        worst = any(r.worst for r in report.requirements)
        heads = ["", "Requirement", "Check", "Values and margin"] + (["Worst case"] if worst else [])
        out.append("<table><thead><tr>" + "".join(f"<th>{h}</th>" for h in heads) + "</tr></thead><tbody>")
        for r in report.requirements:
            note = f'<div class="how">{esc(r.note)}</div>' if r.note else ""
            cells = [
                f'<td class="mark">{_mark(r.holds)}</td>',
                f"<td>{esc(r.name)}{note}</td>",
                f'<td class="code">{esc(r.check)}</td>',
                f"<td>{esc(r.text)}</td>",
            ]
            if worst:
                cells.append(f"<td>{_mark(r.worst_holds) if r.worst else ''} {esc(r.worst)}</td>")
            out.append("<tr>" + "".join(cells) + "</tr>")
        out.append("</tbody></table>")
    if report.requirements_note:
        out.append(f'<p class="how">Note: {esc(report.requirements_note)}</p>')
    for note in report.worst_case_notes:
        out.append(f'<p class="how">Worst case: {esc(note)}</p>')
    out.append("</section>")
    return out


def _match(report: Report) -> list[str]:
    out = ['<section class="card" id="match"><h2>The match</h2>']
    if report.match is None:
        out.append(f'<p class="fails">Not run: {esc(report.match_error)}</p></section>')
        return out
    m = report.match
    out.append('<table class="meta"><tbody>')
    out += [f'<tr><th>{esc(label)}</th><td class="value">{esc(text)}</td></tr>' for label, text in m.summary]
    out.append("</tbody></table>")
    for chart in m.charts:
        out += _figure(chart)
    out += _table(m.shares)
    if m.brownouts.rows:
        out += _table(m.brownouts)
    else:
        out.append("<h3>Brownouts</h3><p>None.</p>")
    out += _table(m.moves)
    out.append("</section>")
    return out
