"""Modal screens to save the current tab as a preset and to load one."""

from __future__ import annotations

from pathlib import Path

from rich.text import Text
from textual import events, on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.message import Message
from textual.widgets import Button, Checkbox, Input, Label, OptionList, Static
from textual.widgets.option_list import Option

from gearhead.core import presets
from gearhead.core.errors import InputError, printable

from .. import served_paths
from ..guard import guarded
from .choice_screen import TypeAhead
from .dialog import Dialog
from .field_input import FieldInput
from .tick_box import TickBox


class SavePresetScreen(Dialog[Path | None]):
    """Ask for a name and description; write to the user preset folder (never silently overwrite)."""

    BINDINGS = [Binding("escape", "dismiss(None)", "Cancel")]

    def __init__(
        self, calc_id: str, inputs: dict, blink: bool = True, name: str = "", description: str = ""
    ) -> None:
        super().__init__()
        self.calc_id = calc_id
        self.inputs = inputs
        self.blink = blink
        self.name_, self.description = name, description  # of the preset loaded, if any

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog"):
            yield Label(Text(f"Save {self.calc_id} preset"), classes="dialog-title")
            name = FieldInput(self.name_, placeholder="Name, e.g. Elevator 2 NEO", id="preset-name")
            desc = FieldInput(self.description, placeholder="Description (optional)", id="preset-description")
            name.cursor_blink = desc.cursor_blink = self.blink
            yield name
            yield desc
            yield Static("", id="save-target")  # the file the name gives, and whether it exists
            yield TickBox("Overwrite an existing preset of that name", id="overwrite")
            yield Static("", id="save-error", classes="field-error")
            with Horizontal(classes="dialog-buttons"):
                yield Button("Save", variant="primary", id="save")
                yield Button("Cancel", id="cancel")

    @on(Button.Pressed, "#cancel")
    def _cancel(self) -> None:
        self.dismiss(None)

    def on_mount(self) -> None:
        self._show_target()

    @on(Input.Changed, "#preset-name")
    def _show_target(self) -> None:
        """The file name proposed from the preset name, and a warning when it exists."""
        name = self.query_one("#preset-name", Input).value.strip()
        target = self.query_one("#save-target", Static)
        if not name:
            target.update(Text("Type a name: the file name is made from it", style="dim"))
            return
        path = presets.user_dir() / self.calc_id / f"{presets.slug(name)}.toml"
        line = Text("Saves as ", style="dim")
        line.append(str(path))
        if path.exists():
            line.append("  exists: tick Overwrite to replace it, or change the name", style="yellow")
        target.update(line)

    @on(Input.Submitted)
    @on(Button.Pressed, "#save")
    @guarded
    def _save(self) -> None:
        name = self.query_one("#preset-name", Input).value.strip()
        error = self.query_one("#save-error", Static)
        if not name:
            error.update(Text("name: enter a name for the preset", style="bold red"))
            return
        preset = presets.Preset(
            self.calc_id, name, self.query_one("#preset-description", Input).value.strip(), dict(self.inputs)
        )
        try:
            path = presets.save(preset, overwrite=self.query_one("#overwrite", Checkbox).value)
        except InputError as exc:
            error.update(Text(str(exc), style="bold red"))
            return
        except OSError as exc:
            error.update(Text(f"cannot write preset: {exc}", style="bold red"))
            return
        self.dismiss(path)


def preview(preset: presets.Preset) -> Text:
    """A preset's description and the inputs it sets, a few lines, to read before loading."""
    from gearhead.core.registry import get

    fields = {f.name: f for f in get(preset.calculator).fields}

    def shown_value(f, v) -> str:
        return f.kind.preview_text(f, v) if f is not None else str(v)

    out = Text(preset.description or "(no description)", style="italic")
    shown = [
        f"{fields[k].label if k in fields else k} {shown_value(fields.get(k), v)}"
        for k, v in preset.inputs.items()
    ]
    line = "  ·  ".join(shown)
    out.append("\n" + (line if len(line) <= 300 else line[:299] + "…"), style="dim")
    return out


MAX_PASTE = 100_000  # characters: a preset is a few hundred; more is a paste gone wrong


def _carries_preset(text: str) -> bool:
    """Whether a one-line paste is a share code or a link carrying one (loaded at once)."""
    from gearhead.core import share

    return len(text) <= MAX_PASTE and share.from_text_kind(text) is not None


class PresetPathInput(FieldInput):
    """The load dialog's path entry; a multi-line paste is a preset's text (ctrl+y elsewhere)."""

    class PresetPasted(Message):
        def __init__(self, text: str) -> None:
            super().__init__()
            self.text = text

    def on_paste(self, event: events.Paste) -> None:
        """A paste with a line break (LF, CRLF or a lone CR, as some terminals send it) is a
        preset's text; one line is a path, inserted by Input as usual (once: this handler runs
        before Input's own and leaves it alone)."""
        if self._is_preset(event.text):
            event.stop()
            event.prevent_default()
            self.post_message(self.PresetPasted(event.text.replace("\r\n", "\n").replace("\r", "\n")))

    @staticmethod
    def _is_preset(text: str) -> bool:
        return "\n" in text.strip() or "\r" in text.strip() or _carries_preset(text)

    def take_paste(self, text: str) -> None:
        """A paste made while another part of the dialog had the keys, taken as if made here."""
        self.focus()
        if self._is_preset(text):
            self.post_message(self.PresetPasted(text.replace("\r\n", "\n").replace("\r", "\n")))
        elif text:
            self.insert_text_at_cursor(text.splitlines()[0])


class LoadPresetScreen(Dialog[presets.Preset | None]):
    """Pick a built-in or user preset for this calculator, or type a file path.

    The path box has the keys when it opens: what is typed goes there, and Enter loads only that
    path (the list had them: letters vanished into its type-ahead and Enter loaded the highlighted
    preset over the entries). ↓ or Tab reaches the list; Enter there loads the preset highlighted."""

    BINDINGS = [Binding("escape", "dismiss(None)", "Cancel")]
    AUTO_FOCUS = "#preset-path"

    def __init__(self, calc_id: str, blink: bool = True) -> None:
        super().__init__()
        self.calc_id = calc_id
        self.blink = blink
        # a user preset that cannot be read is listed (greyed, not loadable) with why: it was
        # skipped without a word, and before that it kept the dialog from opening
        self.found, self.bad = presets.scan(calc_id)
        self.type_ahead = TypeAhead()  # letters on the list jump to the preset they name

    def on_paste(self, event: events.Paste) -> None:
        """A paste on the list (which has the keys when the dialog opens) goes to the path entry:
        the dialog invites pasting a preset's text, and the list dropped it."""
        event.stop()
        self.query_one("#preset-path", PresetPathInput).take_paste(event.text)

    def on_key(self, event: events.Key) -> None:
        listing = self.query_one("#preset-list", OptionList)
        path = self.query_one("#preset-path", PresetPathInput)
        if self.focused is path and event.key == "down" and listing.option_count:
            event.stop()
            listing.focus()
            if listing.highlighted is None:
                listing.highlighted = 0
            return
        if self.focused is listing and self.type_ahead.key(
            event, listing, [(str(i), p.name) for i, p in enumerate(self.found)]
        ):
            event.stop()

    def compose(self) -> ComposeResult:
        with Vertical(classes="dialog load-dialog"):
            yield Label(Text(f"Load {self.calc_id} preset"), classes="dialog-title")
            options = [
                Option(Text(f"{p.name}  ({'built-in' if p.builtin else 'yours'})"), id=str(i))
                for i, p in enumerate(self.found)
            ] + [
                Option(Text(f"✗ {printable(str(exc))}", style="red"), id=f"bad-{i}", disabled=True)
                for i, exc in enumerate(self.bad)
            ]
            # the path box first (it has the keys) and its error right under it: on a small
            # terminal the dialog is cut at the bottom, and an error below the list went unseen
            path = PresetPathInput(
                placeholder="A preset file path, then Enter (or paste a preset's text); ↓ the list",
                id="preset-path",
            )
            path.cursor_blink = self.blink
            yield path
            yield Static("", id="load-error", classes="field-error")
            yield OptionList(*options, id="preset-list")
            # what the highlighted preset holds, before loading it
            yield Static("", id="preset-preview")
            with Horizontal(classes="dialog-buttons"):
                # a served session may not look around the serving machine's folders
                yield Button("Browse files…", id="browse", disabled=served_paths.confined())
                yield Button("Cancel", id="cancel")

    @on(OptionList.OptionHighlighted, "#preset-list")
    @guarded
    def _preview(self, event: OptionList.OptionHighlighted) -> None:
        if not (event.option.id or "").isdigit():
            return
        self.query_one("#preset-preview", Static).update(preview(self.found[int(event.option.id)]))

    @on(OptionList.OptionSelected)
    @guarded
    def _picked(self, event: OptionList.OptionSelected) -> None:
        if not (event.option.id or "").isdigit():
            return
        self.dismiss(self.found[int(event.option.id)])

    @on(Button.Pressed, "#cancel")
    def _cancel(self) -> None:
        self.dismiss(None)

    @on(Button.Pressed, "#browse")
    @guarded
    def _browse(self) -> None:
        """Browse the file system for a .toml preset (textual-fspicker's open dialog)."""
        from textual_fspicker import FileOpen, Filters

        start = presets.user_dir() / self.calc_id
        if not start.is_dir():
            start = Path.cwd()
        dialog = FileOpen(
            start,
            title=f"Open a {self.calc_id} preset",
            filters=Filters(("*.toml", lambda p: p.suffix.lower() == ".toml"), ("Any file", lambda _: True)),
            # its completer globs what is typed: `**a` raised ValueError in a worker and ended the
            # app (textual-fspicker 1.0.1, issue 41); the list beside it still browses
            suggest_completions=False,
        )

        def chosen(path: Path | None) -> None:
            if path is not None:
                self.query_one("#preset-path", Input).value = str(path)
                self._load_path(str(path))

        self.app.push_screen(dialog, chosen)

    @on(PresetPathInput.PresetPasted)
    @guarded
    def _from_text(self, event: PresetPathInput.PresetPasted) -> None:
        import tomllib

        from gearhead.core import share

        try:
            if len(event.text) > MAX_PASTE:
                raise InputError("preset", f"pasted text is too long ({len(event.text)} characters)")
            carried = share.from_text(event.text)  # a share code or a ReCalc link, else TOML
            if carried is not None:
                self.dismiss(carried)
                return
            try:
                data = tomllib.loads(event.text.lstrip("\ufeff"))
            except (tomllib.TOMLDecodeError, RecursionError) as exc:
                raise InputError(
                    "preset",
                    f"pasted text is not a preset (malformed TOML: "
                    f"{str(exc).splitlines()[0][:80] if str(exc) else 'too deeply nested'})",
                ) from None
            preset = presets.from_dict(data, "<pasted preset>")  # another calculator's: the app opens it
        except InputError as exc:
            self.query_one("#load-error", Static).update(Text(str(exc), style="bold red"))
            return
        self.dismiss(preset)

    @on(Input.Submitted, "#preset-path")
    def _from_path(self, event: Input.Submitted) -> None:
        if not event.value.strip():
            self.query_one("#load-error", Static).update(
                Text("path: type a preset file path, or ↓ to pick one from the list", style="bold red")
            )
            return
        self._load_path(event.value)

    @guarded
    def _load_path(self, text: str) -> None:
        try:
            if "\0" in text:  # the OS refuses such a name (Path raises ValueError deep inside)
                raise InputError("preset", "a file path cannot contain a NUL character", repr(text)[:80])
            from gearhead.core import builtin, share, workbook

            # a share code, a link or builtin:NAME (shipped with Gearhead) is no path; a file, in
            # a served session, only in the Gearhead folder (its InputError, as it is)
            carried = share.from_text_kind(text) or builtin.is_builtin(text.strip())
            path = None if carried else served_paths.check(text)
            try:
                if path is None and builtin.is_builtin(text.strip()):
                    try:  # an example workbook, else a built-in preset
                        book = builtin.workbook_path(text.strip())
                    except InputError:
                        preset = share.load_any(text)
                    else:
                        preset = workbook.load(book)
                elif path is None:
                    preset = share.load_any(text)
                elif workbook.is_workbook_file(path):  # opens as one: its cards
                    preset = workbook.load(path)
                else:
                    preset = presets.load(path)
            except InputError:  # (an InputError is a ValueError: said as it is)
                raise
            except (ValueError, RuntimeError) as exc:  # an unusable path ('~nosuchuser/x')
                raise InputError("preset", f"not a usable file path ({exc})", text[:80]) from None
        except InputError as exc:
            self.query_one("#load-error", Static).update(Text(str(exc), style="bold red"))
            return
        self.dismiss(preset)
