"""Take results away: the results table (Markdown or CSV) or the plot's data (CSV), copied to the
clipboard or written to a new file (never over an existing one)."""

from __future__ import annotations

from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.widgets import Button, Input, Label, OptionList, Static
from textual.widgets.option_list import Option

from gearhead.core import atomic_file, export
from gearhead.core.errors import InputError
from gearhead.core.model import Calculator, HeatMap, Plot, Solution

from .. import served_paths
from .dialog import Dialog
from .field_input import FieldInput


class ExportScreen(Dialog[str | None]):
    """Dismisses with a message for the notice ("Copied …", "Saved …"), or None if cancelled."""

    BINDINGS = [Binding("escape", "dismiss(None)", "Cancel")]

    def __init__(
        self, calculator: Calculator, solution: Solution, plot: Plot | HeatMap | None, blink: bool = True
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

    def compose(self) -> ComposeResult:
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
        text = self._built(build)
        if text is None:
            return
        self.app.copy_to_clipboard(text)
        self.dismiss(f"Copied to the clipboard: {label.lower()}")

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
        text = self._built(build)
        if text is None:
            return
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
