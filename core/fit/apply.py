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
    import tomlkit

    from .. import atomic_file

    if workbook is not None:
        path = Path(workbook)
        field = "workbook"
    elif preset is not None:
        from .. import presets

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
    try:
        before = path.read_text(encoding="utf-8")
        doc = tomlkit.parse(before)
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(
            field, f"cannot be read ({getattr(exc, 'strerror', None) or exc})", str(path)
        ) from None
    except Exception as exc:  # tomlkit's parse errors share no base class but Exception
        raise InputError(field, f"is not TOML ({exc})", str(path)) from None
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
    if workbook is not None:
        from ..workbook.file import from_text

        from_text(after, str(path), path.parent)  # never write a workbook that would not load
    else:
        from .. import presets

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


def _linked(entry) -> bool:
    """A workbook's link ("= EXPR"): not overwritten."""
    return isinstance(entry, str) and entry.lstrip().startswith("=")


def card_name(card: Card, name: str | None) -> str:
    """The workbook card's name as entries.load_card resolved it (its label ends ': NAME')."""
    return name if name else card.label.rsplit(": ", 1)[-1]
