"""Presets: TOML files that hold what a user typed into one calculator (DESIGN.md "Presets").

Read with tomllib, written with tomli_w, atomically (temporary file, then rename).
"""

from __future__ import annotations

import os
import re
import tempfile
import tomllib
from dataclasses import dataclass, field as dc_field
from pathlib import Path
from typing import Any

from .errors import InputError

FORMAT = 1


@dataclass
class Preset:
    calculator: str
    name: str
    description: str = ""
    inputs: dict[str, Any] = dc_field(default_factory=dict)
    path: Path | None = None
    builtin: bool = False

    def as_toml(self) -> dict[str, Any]:
        return {"calculator": self.calculator, "name": self.name,
                "description": self.description, "format": FORMAT, "inputs": dict(self.inputs)}


def builtin_dir() -> Path:
    import presets as package  # the top-level data package shipped with Gearhead

    return Path(package.__file__).resolve().parent


def user_dir() -> Path:
    # beside config.toml, where platformdirs puts config (XDG_CONFIG_HOME on Linux, as before)
    import platformdirs

    return platformdirs.user_config_path("gearhead") / "presets"


def load(path: str | Path, builtin: bool = False) -> Preset:
    """Read and validate one preset. Any problem is an InputError naming the file and field."""
    path = Path(path)
    src = str(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError("preset", "file not found", src) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("preset", f"cannot read file ({exc.__class__.__name__})", src) from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError("preset", f"malformed TOML: {exc}", src) from None
    return from_dict(data, src, path=path, builtin=builtin)


def from_dict(data: dict[str, Any], src: str = "<preset>", path: Path | None = None,
              builtin: bool = False) -> Preset:
    from .model import parse_inputs
    from .registry import calculators

    fmt = data.get("format", FORMAT)
    if not isinstance(fmt, int) or isinstance(fmt, bool):
        raise InputError("format", f"must be a whole number, got {fmt!r}", src)
    if fmt > FORMAT:
        raise InputError("format", f"version {fmt} is newer than this Gearhead reads ({FORMAT}); upgrade Gearhead", src)
    calc_id = data.get("calculator")
    if not isinstance(calc_id, str):
        raise InputError("calculator", "missing or not a string", src)
    if calc_id not in calculators():
        raise InputError("calculator", f"unknown calculator {calc_id!r}", src)
    for key in data:
        if key not in ("calculator", "name", "description", "format", "inputs"):
            raise InputError(key, "unknown top-level key", src)
    name = data.get("name", path.stem if path else "preset")
    description = data.get("description", "")
    if not isinstance(name, str) or not isinstance(description, str):
        raise InputError("name" if not isinstance(name, str) else "description", "must be a string", src)
    inputs = data.get("inputs", {})
    if not isinstance(inputs, dict):
        raise InputError("inputs", "must be a table", src)
    for key, value in inputs.items():
        if isinstance(value, list) and all(isinstance(x, str) for x in value):
            continue  # a set of flags, e.g. effects = ["compressor", "regulator"]
        if not isinstance(value, (str, int, float, bool)):
            raise InputError(key, f"wrong type ({type(value).__name__}); use a string, number or boolean", src)
    try:
        parse_inputs(calculators()[calc_id], inputs)  # unknown field, bad unit, out of bounds
    except InputError as exc:
        raise InputError(exc.field, exc.message, src) from None
    return Preset(calc_id, name, description, dict(inputs), path, builtin)


def slug(name: str) -> str:
    s = re.sub(r"[^A-Za-z0-9]+", "_", name.strip()).strip("_").lower()
    return s or "preset"


def save(preset: Preset, path: str | Path | None = None, overwrite: bool = False) -> Path:
    """Write atomically. Refuses to replace an existing file unless overwrite=True."""
    import tomli_w

    from_dict(preset.as_toml(), "<unsaved preset>")  # never write a preset we could not load
    if path is None:
        path = user_dir() / preset.calculator / f"{slug(preset.name)}.toml"
    path = Path(path)
    if path.exists() and not overwrite:
        raise InputError("preset", "file exists; choose another name or overwrite explicitly", str(path))
    path.parent.mkdir(parents=True, exist_ok=True)
    text = tomli_w.dumps(preset.as_toml())
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    preset.path = path
    return path


def listing(calc_id: str | None = None) -> list[Preset]:
    """Built-in then user presets (for one calculator or all). Broken files are skipped here;
    `problems()` reports them."""
    found, _ = _scan(calc_id)
    return found


def problems(calc_id: str | None = None) -> list[InputError]:
    return _scan(calc_id)[1]


def _scan(calc_id: str | None) -> tuple[list[Preset], list[InputError]]:
    found: list[Preset] = []
    bad: list[InputError] = []
    for root, builtin in ((builtin_dir(), True), (user_dir(), False)):
        if not root.is_dir():
            continue
        dirs = [root / calc_id] if calc_id else sorted(p for p in root.iterdir() if p.is_dir())
        for d in dirs:
            for path in sorted(d.glob("*.toml")):
                try:
                    p = load(path, builtin=builtin)
                except InputError as exc:
                    bad.append(exc)
                    continue
                if calc_id is None or p.calculator == calc_id:
                    found.append(p)
    return found, bad
