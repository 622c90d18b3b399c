"""`gearhead report FILE [--format html|md|pdf] [--out PATH] [--set VAR=VALUE ...]`: a preset or
workbook as a design report (core/report/). A bad file exits 2 (tui/cli.py's handler of InputError)
with the message `check` and `solve --preset` give (a bad --set as `check --set` refuses it); PDF
without a Chromium exits 69 (EX_UNAVAILABLE) saying so.

HTML is one self-contained file; Markdown is written with its charts beside it
(`STEM_charts/*.svg`); an existing file is replaced only with --overwrite."""

from __future__ import annotations

import re
import sys
from pathlib import Path

from gearhead.core.errors import InputError, printable

EXIT_NO_BROWSER = 69  # EX_UNAVAILABLE: PDF asked and no Chromium to print it
SUFFIXES = {"html": ".html", "md": ".md", "pdf": ".pdf"}


def add_parser(sub) -> None:
    r = sub.add_parser("report", help="a design report of a preset or workbook: HTML, Markdown or PDF")
    r.add_argument("file", help="a preset or workbook file, builtin:NAME, or a share code")
    r.add_argument(
        "--format",
        choices=tuple(SUFFIXES),
        help="html (one self-contained file; the default), md (Markdown, charts as SVG files beside it) "
        "or pdf (printed by a headless Chromium); default: from --out's suffix",
    )
    r.add_argument(
        "--out",
        metavar="PATH",
        help="where to write it (default: the file's name with .html/.md/.pdf, in this folder; "
        "'-' prints HTML or Markdown without charts files)",
    )
    r.add_argument(
        "--date",
        nargs="?",
        const="today",
        metavar="TEXT",
        help="put a date in the report (today's, or TEXT) and the simulations' wall times; without it the "
        "same file gives the same report, byte for byte",
    )
    r.add_argument(
        "--set",
        dest="sets",
        action="append",
        default=[],
        metavar="VAR=VALUE",
        help="a workbook: replace a variable's value (as check --set); the report's title block names it",
    )
    r.add_argument(
        "--worst-case",
        action="store_true",
        help="a workbook: each requirement's worst case over the variables' tolerances (as check --worst-case)",
    )
    r.add_argument(
        "--overwrite", action="store_true", help="replace PATH if it exists (a report kept in git)"
    )


def _format(args) -> str:
    if args.format:
        return args.format
    if args.out and args.out != "-":
        suffix = Path(args.out).suffix.lower().lstrip(".")
        if suffix in SUFFIXES:
            return suffix
        if suffix in ("htm", "markdown"):
            return {"htm": "html", "markdown": "md"}[suffix]
    return "html"


def _stem(file: str, title: str) -> str:
    """The default output's name: the file's own (builtin:CALC/NAME: NAME; a share code: the title)."""
    from gearhead.core import builtin, share

    text = file.strip()
    if builtin.is_builtin(text):
        name = text[len(builtin.PREFIX) :].strip().split("/")[-1].removesuffix(".toml")
    elif share.is_code(text) or "://" in text:
        name = title
    else:
        name = Path(text).stem
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("._") or "report"


def _date(text: str | None) -> str:
    if text is None:
        return ""
    if text == "today":
        from datetime import UTC, datetime

        return datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    return text


def run(args) -> int:
    from gearhead.core import atomic_file
    from gearhead.core.report import document, html, markdown

    kind = _format(args)
    if args.out is not None and not args.out.strip():
        raise InputError("--out", "is empty; give a file name, or - to print the report")
    if args.out == "-" and kind == "pdf":
        raise InputError("--out", "a PDF is written to a file, not printed; give a file name")
    from .workbook_cli import _sets

    report = document.build(args.file, date=_date(args.date), worst_case=args.worst_case, sets=_sets(args))
    out = args.out or _stem(args.file, report.title) + SUFFIXES[kind]
    stem = Path(out).stem if out != "-" else _stem(args.file, report.title)
    if kind == "md":
        text = markdown.write(report, stem)
        files = markdown.chart_files(report, stem)
    else:
        text = html.write(report)
        files = {}
    if out == "-":
        if files:
            print(
                f"gearhead: note: {len(files)} charts are not printed (write to a file: --out NAME.md)",
                file=sys.stderr,
            )
        sys.stdout.write(text)
        return 0
    if kind == "pdf":
        from gearhead.core.report import pdf

        try:
            data = pdf.from_html(text)
        except pdf.NoBrowser as exc:
            print(f"gearhead: --format pdf: {printable(exc)}", file=sys.stderr)
            return EXIT_NO_BROWSER
        path = atomic_file.write_bytes(out, data, overwrite=args.overwrite, field="--out")
    else:
        path = atomic_file.write_text(out, text, overwrite=args.overwrite, field="--out")
        folder = Path(path).parent
        for name, svg in files.items():
            target = folder / name
            target.parent.mkdir(exist_ok=True)
            atomic_file.write_text(target, svg, overwrite=args.overwrite, field="--out")
    size = Path(path).stat().st_size
    more = f" and {len(files)} charts in {stem}_charts/" if files else ""
    print(f"{printable(report.title)}: report written to {printable(path)} ({size} bytes){more}")
    return 0
