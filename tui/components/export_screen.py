"""Take results away: the results table (Markdown or CSV) or the plot's data (CSV), copied to the
clipboard or written to a new file (never over an existing one); the design report of the card (and
of the workbook the app opened, as its file holds it) as one HTML file (core/report/).

A report draws its charts with matplotlib (a card's: about half a second, the first time; a
workbook's: its whole solve too), so it is built in a worker thread, the dialog saying so, and
the dialog closes when it is written."""

from __future__ import annotations

from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.widgets import Button, Input, Label, OptionList, Static
from textual.widgets.option_list import Option

from gearhead.core import atomic_file, export
from gearhead.core.errors import InputError, printable
from gearhead.core.model import Calculator, HeatMap, Plot, Solution

from .. import served_paths
from .dialog import Dialog
from .field_input import FieldInput


class ExportScreen(Dialog[str | None]):
    """Dismisses with a message for the notice ("Copied …", "Saved …"), or None if cancelled."""

    BINDINGS = [Binding("escape", "dismiss(None)", "Cancel")]

    def __init__(
        self,
        calculator: Calculator,
        solution: Solution,
        plot: Plot | HeatMap | None,
        blink: bool = True,
        workbook=None,
    ) -> None:
        super().__init__()
        self.calculator = calculator
        self.solution = solution
        self.blink = blink
        # (label, file suffix, text builder)
        self.formats = [
            ("Results table as Markdown", "md", lambda: export.results_markdown(calculator, solution)),
            (
                "Results table as CSV (shown and full-precision SI values)",
                "csv",
                lambda: export.results_csv(calculator, solution),
            ),
        ]
        self.names = [f"{calculator.id}_results.md", f"{calculator.id}_results.csv"]
        if plot is not None and any(solution.series.get(s, ([], []))[0] for s in plot.series):
            self.formats.append(
                (f"Plot data as CSV: {plot.title}", "csv", lambda: export.plot_csv(plot, solution))
            )
            self.names.append(f"{calculator.id}_plot.csv")
        if isinstance(plot, HeatMap) and plot.name in solution.heat_maps:
            self.formats.append(
                (f"Heat map data as CSV: {plot.title}", "csv", lambda: export.heat_map_csv(plot, solution))
            )
            self.names.append(f"{calculator.id}_heat_map.csv")
        for doc in calculator.documents:  # files for other tools (PathPlanner, Choreo)
            self.formats.append(
                (doc.label, doc.filename.rpartition(".")[2], lambda doc=doc: doc.build(solution))
            )
            self.names.append(doc.filename)
        # last, so the options above keep their places: the design reports (HTML, one file)
        self.formats.append(
            (
                f"Report: {calculator.title} as a design report (HTML)",
                "html",
                lambda: card_report(calculator, solution),
            )
        )
        self.names.append(f"{calculator.id}_report.html")
        self.slow = {len(self.formats) - 1}
        self.workbook = workbook  # else the one the app opened (`gearhead robot.toml`), in compose

    def _add_workbook_report(self) -> None:
        book = self.workbook if self.workbook is not None else getattr(self.app, "workbook", None)
        if book is not None and getattr(book, "source", ""):
            self.formats.append(
                (
                    f"Report: the workbook {printable(book.name)} as a design report (HTML)",
                    "html",
                    lambda: workbook_report(book),
                )
            )
            self.names.append(f"{_stem(book.source)}_report.html")
            self.slow.add(len(self.formats) - 1)

    def compose(self) -> ComposeResult:
        self._add_workbook_report()
        with Vertical(classes="dialog"):
            yield Label(Text(f"Export {self.calculator.title}"), classes="dialog-title")
            yield OptionList(
                *(Option(Text(label), id=str(i)) for i, (label, _, _) in enumerate(self.formats)),
                id="export-format",
            )
            path = FieldInput(value=self._default_name(0), id="export-path")
            path.cursor_blink = self.blink
            yield path
            yield Static("", id="export-error", classes="field-error")
            with Horizontal(classes="dialog-buttons"):
                yield Button("Copy to clipboard", variant="primary", id="copy")
                yield Button("Save to file", id="save")
                yield Button("Cancel", id="cancel")

    def _default_name(self, index: int) -> str:
        return self.names[index]

    @property
    def _index(self) -> int:
        highlighted = self.query_one("#export-format", OptionList).highlighted
        return highlighted if highlighted is not None else 0

    @on(OptionList.OptionHighlighted, "#export-format")
    def _format_changed(self, event: OptionList.OptionHighlighted) -> None:
        path = self.query_one("#export-path", Input)
        old = {self._default_name(i) for i in range(len(self.formats))}
        if path.value in old:  # keep a name the user typed
            path.value = self._default_name(event.option_index)

    @on(OptionList.OptionSelected, "#export-format")
    @on(Button.Pressed, "#copy")
    def _copy(self) -> None:
        label, _, build = self.formats[self._index]
        if self._index in self.slow:
            self._in_worker(build, lambda text: self._copied(label, text))
            return
        text = self._built(build)
        if text is None:
            return
        self._copied(label, text)

    def _copied(self, label: str, text: str) -> None:
        self.app.copy_to_clipboard(text)
        self.dismiss(f"Copied to the clipboard: {label.lower()}")

    building = False  # a report is being built in a worker: a second press waits for it

    def _in_worker(self, build, then) -> None:
        """Build a report in a thread (matplotlib and a workbook's solve take a while), then
        `then(text)` on the app's thread; a wrong entry or a failure is shown, the dialog stays."""
        if self.building:
            return
        self.building = True
        error = self.query_one("#export-error", Static)
        error.update(Text("building the report…", style="dim"))

        def work() -> None:
            try:
                text = build()
            except (InputError, ValueError) as exc:
                self.app.call_from_thread(self._failed, f"cannot export: {exc}")
                return
            except Exception as exc:  # a bug: said here, the app goes on (and the dialog with it)
                self.app.call_from_thread(
                    self._failed, f"cannot export: internal error ({type(exc).__name__}: {exc})"
                )
                return
            self.app.call_from_thread(self._built_in_worker, then, text)

        self.run_worker(work, thread=True, exclusive=True, group="report", exit_on_error=False)

    def _failed(self, message: str) -> None:
        self.building = False
        if not self.is_attached:  # closed (Esc) while the report was being built
            return
        self.query_one("#export-error", Static).update(Text(message, style="bold red"))

    def _built_in_worker(self, then, text: str) -> None:
        self.building = False
        if not self.is_attached:
            return
        self.query_one("#export-error", Static).update(Text(""))
        then(text)

    def _built(self, build) -> str | None:
        """The export's text, or None with the reason shown (a robot another tool cannot take)."""
        try:
            return build()
        except ValueError as exc:
            self.query_one("#export-error", Static).update(Text(f"cannot export: {exc}", style="bold red"))
            return None

    @on(Input.Submitted, "#export-path")
    @on(Button.Pressed, "#save")
    def _save(self) -> None:
        label, _, build = self.formats[self._index]
        raw = self.query_one("#export-path", Input).value.strip()
        error = self.query_one("#export-error", Static)
        if not raw or "\0" in raw:
            error.update(Text("file: enter a file name", style="bold red"))
            return
        if self._index in self.slow:
            self._in_worker(build, lambda text: self._write(label, raw, text))
            return
        text = self._built(build)
        if text is None:
            return
        self._write(label, raw, text)

    def _write(self, label: str, raw: str, text: str) -> None:
        """The export to a new file, whole or not at all (the same for every format)."""
        error = self.query_one("#export-error", Static)
        try:
            path = served_paths.check(raw)  # a served session: only in the Gearhead folder
        except InputError as exc:
            error.update(Text(str(exc), style="bold red"))
            return
        try:  # whole or not at all, never over an existing file; ~nosuchuser is refused by name
            path = atomic_file.write_text(path, text, field="file")
        except atomic_file.FileExists:
            error.update(Text(f"file: {raw[:60]} exists; choose another name", style="bold red"))
            return
        except atomic_file.WriteError as exc:
            error.update(Text(f"file: cannot write ({exc.reason})", style="bold red"))
            return
        self.dismiss(f"Saved {label.lower()} to {path}")

    @on(Button.Pressed, "#cancel")
    def _cancel(self) -> None:
        self.dismiss(None)


def card_report(calculator: Calculator, solution: Solution) -> str:
    """The card's design report (HTML): its inputs as the card solved them (a preset of their
    texts, so the share code in it reopens this card), results, equations and charts."""
    from gearhead.core import share
    from gearhead.core.presets import Preset
    from gearhead.core.report import document, html

    entries = {name: value.text for name, value in solution.inputs.items()}
    preset = Preset(calculator.id, f"{calculator.title} (from the app)", "", entries)
    code = share.encode(preset)
    report = document.Report(
        preset.name, calculator.summary, "card", "the app (ctrl+e)", document.version(), code
    )
    report.cards.append(
        document.card_section(
            calculator.id, f"{calculator.title} ({calculator.id})", calculator, solution, entries, code
        )
    )
    return html.write(report)


def workbook_report(book) -> str:
    """The workbook's design report (HTML), as its file holds it now (saved edits included)."""
    from gearhead.core import workbook
    from gearhead.core.report import document, html

    try:
        current = workbook.load(book.source)
    except InputError:  # moved or broken since it was opened: the workbook as the app read it
        current = book
    return html.write(document.from_workbook(current))


def _stem(source: str) -> str:
    from pathlib import Path

    return Path(source.removeprefix("builtin:")).stem or "workbook"
