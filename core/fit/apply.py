"""Writing the fitted entries into the card's file (issue 44 item 6): a workbook's card or a preset,
through tomlkit so that the file's comments and layout stay, checked by loading the new text before
it replaces the old one (core.atomic_file: whole or not at all). A field the workbook links
("= EXPR") is not overwritten: the note names the link and the value it would take. A built-in
preset is not changed (copy it first). The unified diff of the file is returned."""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from .entries import Card, fitted_raw

# the entries the fit writes (fitted_raw's), numbers with 6 significant digits
WRITTEN = {
    "elevator": ("load_mass", "friction_force", "effects"),
    "arm": ("arm_mass", "inertia_model", "moment_of_inertia", "friction_torque", "effects"),
    "flywheel": ("mode", "wheel_inertia", "secondary_inertia"),
    "sprint": ("robot_mass", "rolling_coefficient", "effects"),
}
NUMBERS = {
    "load_mass",
    "arm_mass",
    "friction_force",
    "friction_torque",
    "moment_of_inertia",
    "wheel_inertia",
    "secondary_inertia",
    "robot_mass",
    "rolling_coefficient",
}


@dataclass
class Applied:
    path: str
    changes: dict[str, str]
    diff: str
    notes: list[str]


def _entries(card: Card, gains: dict[str, float], held=()) -> tuple[dict[str, str], list[str]]:
    raw, notes = fitted_raw(card, gains, held)
    out = {}
    for k in WRITTEN[card.kind]:
        if k in raw and raw[k] != card.raw.get(k):
            v = raw[k]
            if k in NUMBERS:
                number, _, unit = v.partition(" ")
                v = f"{float(number):.6g} {unit}".rstrip()
            out[k] = v
    return out, notes


def apply(
    card: Card,
    gains: dict[str, float],
    *,
    preset: str | None = None,
    workbook: str | None = None,
    name: str | None = None,
) -> Applied:
    import os

    import tomlkit

    from .. import atomic_file, builtin, presets

    given = workbook if workbook is not None else preset
    if given is not None and builtin.is_builtin(given) and not os.path.isfile(given):
        what = "an example workbook" if workbook is not None else "a built-in preset"
        raise InputError("--apply", f"does not change {what}: copy it and fit the copy", given)
    if workbook is not None:
        path = Path(workbook)
        field = "workbook"
    elif preset is not None:
        path = Path(preset)
        field = "preset"
        try:
            if path.resolve().is_relative_to(presets.builtin_dir()):
                raise InputError(
                    "--apply", "does not change a built-in preset: copy it and fit the copy", preset
                )
        except OSError:
            pass
    else:
        raise InputError("--apply", "needs the card's file: --preset FILE or --workbook FILE --name CARD")
    if preset is not None and not os.path.isfile(path):  # a share code or ReCalc link: no file to write
        raise InputError("--apply", "writes into a preset file; this preset is not one", preset[:80])
    try:
        # as the card was read (a regular file, UTF-8 with or without a byte-order mark: a BOM was
        # "not TOML" here though the card loaded; the line ends as they are, not made \n)
        before = presets.read_text(path)
    except InputError as exc:
        raise InputError(field, exc.message, str(path)) from None
    try:
        doc = tomlkit.parse(before)
    except Exception as exc:  # tomlkit's parse errors share no base class but Exception
        raise InputError(field, f"is not TOML ({exc})", str(path)) from None
    _unchanged(card, before, path, field, workbook is not None and card_name(card, name))
    if workbook is not None:
        table = doc["cards"][card_name(card, name)]
        if "inputs" not in table:
            table["inputs"] = tomlkit.table()
        target = table["inputs"]
    else:
        if "inputs" not in doc:
            doc["inputs"] = tomlkit.table()
        target = doc["inputs"]
    linked = {k for k in WRITTEN[card.kind] if _linked(target.get(k))}
    free, _ = _entries(card, gains)  # what the fit gives each entry
    changes, notes = _entries(card, gains, held=linked)  # the rest computed with the links held
    for k in sorted(linked & set(free)):
        notes.append(f"{k} is linked ({target[k].strip()}): not written; the fit gives {free[k]}")
        changes.pop(k, None)
    for k, v in list(changes.items()):
        # a number without a unit (C_rr) stays a TOML number, as the presets write it
        target[k] = float(v) if k in NUMBERS and " " not in v else v
    after = tomlkit.dumps(doc)
    if "\r\n" in before and "\n" not in before.replace("\r\n", ""):  # a CRLF file stays CRLF
        after = after.replace("\r\n", "\n").replace("\n", "\r\n")
    if workbook is not None:
        from ..workbook.file import from_text

        from_text(after, str(path), path.parent)  # never write a workbook that would not load
    else:
        presets.from_dict(presets.parse_text(after, str(path)), str(path))
    diff = "".join(
        difflib.unified_diff(
            before.splitlines(keepends=True),
            after.splitlines(keepends=True),
            str(path),
            str(path) + " (fitted)",
        )
    )
    if after != before:
        atomic_file.write_text(path, after, overwrite=True, field=field)
    return Applied(str(path), changes, diff, notes)


def _unchanged(card: Card, text: str, path: Path, field: str, name) -> None:
    """Refuse when the card's entries in the file's `text` are not those it was fitted with: the
    file changed on disk since `gearhead fit` read it (the fitted entries were derived from the
    old card's motor, ratio and geometry, and would be written beside the new ones)."""
    from .. import presets

    try:
        if name:
            from ..workbook import solve
            from ..workbook.file import from_text

            result = solve(from_text(text, str(path), path.parent)).cards.get(name)
            now = None if result is None else result.entries
        else:
            now = presets.from_dict(presets.parse_text(text, str(path)), str(path)).inputs
    except InputError as exc:
        raise InputError(
            field, f"changed on disk since it was read and no longer loads ({exc.message})", str(path)
        ) from None
    if now is None or dict(now) != card.raw:
        raise InputError(
            field,
            "changed on disk since it was read (the card's entries are not those fitted): fit again; nothing written",
            str(path),
        )


def _linked(entry) -> bool:
    """A workbook's link ("= EXPR"): not overwritten."""
    return isinstance(entry, str) and entry.lstrip().startswith("=")


def card_name(card: Card, name: str | None) -> str:
    """The workbook card's name as entries.load_card resolved it (its label ends ': NAME')."""
    return name if name else card.label.rsplit(": ", 1)[-1]
