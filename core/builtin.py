"""`builtin:NAME`: a preset or example workbook shipped with Gearhead, named without its path.

Installed by pip, the built-in presets and the example workbook live inside site-packages, where a
README's `presets/...` or `examples/...` path does not reach from the user's folder. Anywhere a
preset is taken (`solve`/`sweep`/`accuracy --preset`, `share`, `import`, ctrl+o, a workbook card's
`preset`) `builtin:CALC/NAME` names presets/CALC/NAME.toml, and `builtin:NAME` the one built-in
preset of that name (an error lists the choices when two calculators have one). Where a workbook
is taken (`check`, `solve`/`sweep` of a workbook, `gearhead ROBOT.toml`) `builtin:NAME` names
examples/NAME.toml.
"""

from __future__ import annotations

from pathlib import Path

from .errors import InputError, shown

PREFIX = "builtin:"


def is_builtin(text: object) -> bool:
    return isinstance(text, str) and text.strip().startswith(PREFIX)


def _name(text: str) -> str:
    return text.strip()[len(PREFIX) :].strip().removesuffix(".toml")


def preset_path(text: str, where: str = "--preset") -> Path:
    """The file `builtin:CALC/NAME` or `builtin:NAME` names; an InputError naming `where` if none."""
    from .presets import builtin_dir

    name = _name(text)
    root = builtin_dir()
    everything = sorted(p.relative_to(root).with_suffix("").as_posix() for p in root.glob("*/*.toml"))
    if name in everything:
        return root / f"{name}.toml"
    matches = [n for n in everything if n.split("/")[-1] == name]
    if len(matches) == 1:
        return root / f"{matches[0]}.toml"
    if matches:
        raise InputError(
            where, f"{shown(text)} names several built-in presets: {', '.join(PREFIX + m for m in matches)}"
        )
    raise InputError(
        where,
        f"{shown(text)} is no built-in preset (`gearhead presets` lists them; e.g. {PREFIX}{everything[0]})",
    )


def examples_dir() -> Path:
    import gearhead.examples as package  # the example workbooks shipped with Gearhead

    return Path(package.__file__).resolve().parent


def workbook_path(text: str) -> Path:
    """The example workbook `builtin:NAME` names; an InputError naming the workbook if none."""
    name = _name(text)
    found = sorted(p.stem for p in examples_dir().glob("*.toml"))
    if name in found:
        return examples_dir() / f"{name}.toml"
    raise InputError(
        "workbook", f"{shown(text)} is no example workbook (built-in: {', '.join(PREFIX + n for n in found)})"
    )
