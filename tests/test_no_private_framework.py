"""No private Textual API in tui/ or bench/ (issue 42 item 2), except the key-order workaround
named where it is (tui/components/field_input.py: Textual #6605, fixed in PR #6631) and the served
app's process handle (tui/serve_session.py: textual-serve has no public one).

Two checks: no class of ours defines a private name its Textual base class uses (SweepScreen once
set `self._running`, MessagePump's own flag, and a Signal to it after a sweep was dropped); and no
module reads a Textual private attribute from the list of those we have used before."""

from __future__ import annotations

import importlib
import inspect
import pathlib
import pkgutil
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
FRAMEWORK = ("textual", "textual_plot", "textual_hires_canvas", "textual_serve")
ALLOWED = {("gearhead.tui.components.field_input", "FieldInput", "_on_key")}  # Textual #6605
# private names of Textual's that Gearhead used and gave up; the workaround's own stay in its file
KNOWN = r"\._(press_keys|compositor_refresh|compositor|update_margin_sizes|running|keymap|bindings|process)\b"
KNOWN_ALLOWED = {
    "tui/components/field_input.py": {"_keymap", "_bindings"},
    "tui/serve_session.py": {"_process"},
}


def _tui_modules():
    import gearhead.tui
    import gearhead.tui.components

    for package in (gearhead.tui, gearhead.tui.components):
        for info in pkgutil.iter_modules(package.__path__, package.__name__ + "."):
            if not info.name.endswith("__main__"):
                yield importlib.import_module(info.name)


def _private_names(source: str) -> set[str]:
    return (
        set(re.findall(r"self\.(_[a-z][a-z0-9_]*)\s*(?::[^=\n]*)?=(?!=)", source))
        | set(re.findall(r"def (_[a-z][a-z0-9_]*)\(", source))
        | set(re.findall(r"^    (_[a-z][a-z0-9_]*)\s*[:=]", source, re.M))
    )


def shadowed() -> set[tuple[str, str, str]]:
    found = set()
    for module in _tui_modules():
        for name, cls in inspect.getmembers(module, inspect.isclass):
            if cls.__module__ != module.__name__:
                continue
            bases = [b for b in cls.__mro__[1:] if b.__module__.split(".")[0] in FRAMEWORK]
            if not bases:
                continue
            base_names: set[str] = set()
            for b in bases:
                try:
                    base_names |= _private_names(inspect.getsource(b))
                except (OSError, TypeError):
                    continue
            for k in _private_names(inspect.getsource(cls)) & base_names:
                found.add((module.__name__, name, k))
    return found


def test_no_class_of_ours_takes_a_private_name_of_textuals():
    assert shadowed() - ALLOWED == set()


def test_the_check_sees_a_shadowed_name():
    """The old SweepScreen's flag is found (the check can fail)."""
    from textual.message_pump import MessagePump

    assert "_running" in _private_names(inspect.getsource(MessagePump))
    assert "_running" in _private_names("class S:\n    def f(self):\n        self._running = False\n")


def test_no_module_reads_a_private_textual_attribute_we_gave_up():
    hits = []
    for path in [*ROOT.joinpath("tui").rglob("*.py"), *ROOT.joinpath("bench").rglob("*.py")]:
        rel = path.relative_to(ROOT).as_posix()
        for line in path.read_text(encoding="utf-8").splitlines():
            code = line.split("#", 1)[0]
            for match in re.finditer(KNOWN, code):
                name = "_" + match.group(1)
                if name not in KNOWN_ALLOWED.get(rel, set()) and not code.lstrip().startswith(
                    ("self._", "'", '"')
                ):
                    if f"self.{name}" in code and rel.startswith("tui/"):
                        continue  # our own attribute of that name is the first check's business
                    hits.append(f"{rel}: {line.strip()}")
    assert hits == [], hits
