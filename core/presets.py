"""Presets: TOML files that hold what a user typed into one calculator (DESIGN.md "Presets").

Read with tomllib, written with tomli_w, atomically (temporary file, then rename).
"""

from __future__ import annotations

import os
import re
import sys
import tomllib
from dataclasses import dataclass
from dataclasses import field as dc_field
from pathlib import Path
from typing import Any

from .errors import InputError, shown

FORMAT = 1


@dataclass
class Preset:
    calculator: str
    name: str
    description: str = ""
    inputs: dict[str, Any] = dc_field(default_factory=dict)
    path: Path | None = None
    builtin: bool = False
    # one line per problem that does not stop loading (a junk value in a field the mode ignores)
    warnings: list[str] = dc_field(default_factory=list, compare=False)

    def as_toml(self) -> dict[str, Any]:
        return {
            "calculator": self.calculator,
            "name": self.name,
            "description": self.description,
            "format": FORMAT,
            "inputs": dict(self.inputs),
        }


def builtin_dir() -> Path:
    import gearhead.presets as package  # the top-level data package shipped with Gearhead

    return Path(package.__file__).resolve().parent


def user_dir() -> Path:
    # beside config.toml, where platformdirs puts config (XDG_CONFIG_HOME on Linux, as before)
    import platformdirs

    return platformdirs.user_config_path("gearhead") / "presets"


MAX_PRESET_BYTES = 1_000_000  # a preset is a few hundred bytes; more is not a preset
MAX_NAME_BYTES = 120  # of a file name's stem in UTF-8: well under the 255 of every common file system


def load(path: str | Path, builtin: bool = False) -> Preset:
    """Read and validate one preset. Any problem is an InputError naming the file and field."""
    src = str(path)
    return from_dict(parse_text(read_text(path), src), src, path=Path(path), builtin=builtin)


def read_text(path: str | Path) -> str:
    """The text of a preset file. Only a regular file is read (a FIFO would block, /dev/zero never
    end), at most MAX_PRESET_BYTES, as UTF-8 with or without a byte-order mark."""
    import stat

    src = str(path)
    if "\0" in src:
        raise InputError("preset", "the file name contains a NUL character", repr(src))
    try:
        # O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    except FileNotFoundError:
        raise InputError("preset", "file not found", src) from None
    except IsADirectoryError:
        raise InputError("preset", "is a folder, not a preset file", src) from None
    except (OSError, ValueError) as exc:
        raise InputError("preset", f"cannot open the file ({_os_reason(exc)})", src) from None
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise InputError("preset", "is a folder, not a preset file", src)
        if not stat.S_ISREG(info.st_mode):
            raise InputError("preset", "is not a regular file (a device, pipe or socket)", src)
        if info.st_size > MAX_PRESET_BYTES:
            raise InputError(
                "preset", f"is too large for a preset ({info.st_size} bytes; at most {MAX_PRESET_BYTES})", src
            )
        chunks, size = [], 0
        while size <= MAX_PRESET_BYTES:  # the size may change while reading: never read past the cap
            chunk = os.read(fd, MAX_PRESET_BYTES + 1 - size)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > MAX_PRESET_BYTES:
            raise InputError("preset", f"is too large for a preset (over {MAX_PRESET_BYTES} bytes)", src)
    except OSError as exc:
        raise InputError("preset", f"cannot read the file ({_os_reason(exc)})", src) from None
    finally:
        os.close(fd)
    try:
        return b"".join(chunks).decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError("preset", f"is not UTF-8 text (byte {exc.start})", src) from None


# tomllib's time grows with the square of a dotted key's length (a 40 KB key 'a.a.a…' took 7.6 s,
# 1 MB would take hours); a preset's keys have two parts ('inputs.load'). Searched for before
# parsing, in one pass: a run of MAX_KEY_PARTS names joined by dots, bare or quoted, starting at
# a name's beginning (so a long word is not re-scanned from each of its letters).
MAX_KEY_PARTS = 32
_LONG_DOTTED_KEY = re.compile(
    r"(?<![\w-])(?:(?:[\w-]++|\"[^\"\n]*+\"|'[^'\n]*+')[ \t]*+\.[ \t]*+)" + f"{{{MAX_KEY_PARTS - 1}}}"
)


MAX_NESTING = 32  # arrays and inline tables inside each other; a preset needs two or three


def nesting(text: str) -> tuple[int, int]:
    """(deepest nesting of arrays and inline tables in a TOML text, the line where it is first
    reached), strings and comments skipped. Written out because tomllib recurses once per level and
    has no limit of its own: 5000 levels ran deep into Python's stack before its RecursionError."""
    depth = deepest = 0
    line = where = 1
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
        elif c == "#":
            i = text.find("\n", i)
            if i < 0:
                break
            continue
        elif c in "\"'":
            quote = c * 3 if text.startswith(c * 3, i) else c
            j = i + len(quote)
            while j < n and not text.startswith(quote, j):
                j += 2 if c == '"' and text[j] == "\\" else 1
            line += text.count("\n", i, j)
            i = j + len(quote)
            continue
        elif c in "[{":
            depth += 1
            if depth > deepest:
                deepest, where = depth, line
        elif c in "]}":
            depth = max(0, depth - 1)
        i += 1
    return deepest, where


def parse_text(text: str, src: str = "<preset>") -> dict[str, Any]:
    """The TOML table of a preset's text, or an InputError naming `src`."""
    deepest, line = nesting(text)
    if deepest > MAX_NESTING:
        raise InputError(
            "preset",
            f"malformed TOML: arrays or tables nested too deeply ({deepest} levels on line {line}; "
            "a preset needs a few)",
            src,
        )
    deep = _LONG_DOTTED_KEY.search(text)
    if deep:
        line = text.count("\n", 0, deep.start()) + 1
        raise InputError(
            "preset",
            f"a dotted name of {MAX_KEY_PARTS} or more parts on line {line} ({shown(deep.group(), 20)}); "
            f"a preset's keys are plain names under [inputs]",
            src,
        )
    try:
        return tomllib.loads(text.lstrip("\ufeff"))
    except tomllib.TOMLDecodeError as exc:
        raise InputError("preset", f"malformed TOML: {_first_line(exc)}", src) from None
    except ValueError:  # int() of a literal past Python's int-to-str limit, inside tomllib
        line = _long_integer_line(text)
        raise InputError(
            "preset",
            f"an integer of more than {sys.get_int_max_str_digits()} digits{line}; no entry needs one",
            src,
        ) from None
    except RecursionError:  # tomllib recurses once per level of nested arrays and tables
        raise InputError("preset", "malformed TOML: arrays or tables nested too deeply", src) from None


def _long_integer_line(text: str) -> str:
    """' on line N' of the first run of more digits than int() reads, else ''."""
    found = re.search(f"[0-9_]{{{sys.get_int_max_str_digits() + 1},}}", text)
    return f" on line {text.count(chr(10), 0, found.start()) + 1}" if found else ""


def _first_line(exc: Exception) -> str:
    text = str(exc).strip()
    return text.splitlines()[0][:120] if text else type(exc).__name__


def _os_reason(exc: BaseException) -> str:
    return getattr(exc, "strerror", None) or _first_line(exc)  # "Permission denied", not "[Errno 13] …"


def from_dict(
    data: dict[str, Any], src: str = "<preset>", path: Path | None = None, builtin: bool = False
) -> Preset:
    from . import tolerance  # reads "60 g ± 6 g" (the nominal through parse_inputs, as before)
    from .registry import calculators

    fmt = data.get("format", FORMAT)
    if not isinstance(fmt, int) or isinstance(fmt, bool) or fmt < 1:
        raise InputError(
            "format", f"must be a whole number from 1 (this Gearhead writes {FORMAT}), got {shown(fmt)}", src
        )
    if fmt > FORMAT:
        raise InputError(
            "format", f"version {fmt} is newer than this Gearhead reads ({FORMAT}); upgrade Gearhead", src
        )
    calc_id = data.get("calculator")
    if not isinstance(calc_id, str):
        raise InputError("calculator", "missing or not a string", src)
    if calc_id not in calculators():
        raise InputError("calculator", f"unknown calculator {shown(calc_id)}", src)
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
            raise InputError(
                key, f"wrong type ({type(value).__name__}); use a string, number or boolean", src
            )
    calc = calculators()[calc_id]
    from .sim.effects import retire  # a flag retired since the preset was written: what replaced it

    try:
        inputs, notices = retire(calc.fields, inputs)  # stored in today's fields
        tolerance.parse(calc, inputs)  # unknown field, bad unit, out of bounds, bad ± tolerance
    except InputError as exc:
        raise exc.from_source(src) from None  # every wrong entry, each said of the file
    preset = Preset(calc_id, name, description, dict(inputs), path, builtin)
    preset.warnings = [f"{src}: {n}" for n in notices] + unused_entry_warnings(calc, inputs, src)
    return preset


def unused_entry_warnings(calc, inputs: dict[str, Any], src: str) -> list[str]:
    """One line per field the chosen mode or choices do not use whose value is not valid either:
    it is ignored (the field's default is used), which must not pass silently."""
    from .model import choice_values

    mode = inputs.get("mode")
    choices = choice_values(calc, inputs)
    out = []
    for f in calc.fields:
        if f.name not in inputs or f.active(mode, choices):
            continue
        try:
            f.parse(inputs[f.name])
        except InputError as exc:
            out.append(f"{src}: {f.name}: ignored (not used in this mode), and not valid: {exc.message}")
    return out


_WINDOWS_RESERVED = {
    "con",
    "prn",
    "aux",
    "nul",
    *(f"com{i}" for i in range(10)),
    *(f"lpt{i}" for i in range(10)),
}


def slug(name: str) -> str:
    """A file-name stem for a preset name: letters of any script (NFC, lower case), digits and
    "_"; safe on Linux, macOS and Windows (no reserved names, at most MAX_NAME_BYTES in UTF-8; a
    shortened name ends in a hash of the whole so two long names stay two files)."""
    import hashlib
    import unicodedata

    text = unicodedata.normalize("NFC", name.strip())
    s = re.sub(r"[\W_]+", "_", text).strip("_").lower()
    s = unicodedata.normalize("NFC", s) or "preset"
    if len(s.encode("utf-8")) > MAX_NAME_BYTES:
        digest = hashlib.sha256(text.encode("utf-8")).hexdigest()[:10]
        cut = s.encode("utf-8")[: MAX_NAME_BYTES - 11].decode("utf-8", "ignore").rstrip("_")
        s = f"{cut}_{digest}"
    if s.split(".")[0] in _WINDOWS_RESERVED:
        s += "_preset"
    return s


def save(
    preset: Preset, path: str | Path | None = None, overwrite: bool = False, field: str = "preset"
) -> Path:
    """Write atomically (core.atomic_file: whole or not at all, a replaced file keeps its mode, a
    symlink is written through). Refuses to replace an existing file unless overwrite=True; of
    two saves of the same new name at once exactly one succeeds. A new file gets the mode the umask
    gives. A file that cannot be written raises atomic_file.WriteError (an InputError) naming
    `field` and the path."""
    import tomli_w

    from . import atomic_file

    from_dict(preset.as_toml(), "<unsaved preset>")  # never write a preset we could not load
    if path is None:
        path = user_dir() / preset.calculator / f"{slug(preset.name)}.toml"
    path = atomic_file.expand(path, field)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except (OSError, ValueError) as exc:  # /proc, /dev/null/x, a read-only folder, a long name
        raise atomic_file.WriteError(field, getattr(exc, "strerror", None) or str(exc), path) from None
    try:
        atomic_file.write_text(path, tomli_w.dumps(preset.as_toml()), overwrite=overwrite, field=field)
    except atomic_file.FileExists:
        raise atomic_file.FileExists(field, path, _EXISTS) from None
    preset.path = path
    return path


_EXISTS = "file exists; choose another name or overwrite explicitly"


def listing(calc_id: str | None = None) -> list[Preset]:
    """Built-in then user presets (for one calculator or all). Broken files are skipped here;
    `problems()` reports them."""
    found, _ = _scan(calc_id)
    return found


def problems(calc_id: str | None = None) -> list[InputError]:
    return _scan(calc_id)[1]


def scan(calc_id: str | None = None) -> tuple[list[Preset], list[InputError]]:
    """`listing` and `problems` from one pass over the folders (the load dialog shows both)."""
    return _scan(calc_id)


def _scan(calc_id: str | None) -> tuple[list[Preset], list[InputError]]:
    found: list[Preset] = []
    bad: list[InputError] = []
    for root, builtin in ((builtin_dir(), True), (user_dir(), False)):
        if not root.is_dir():
            continue
        try:
            dirs = [root / calc_id] if calc_id else sorted(p for p in root.iterdir() if p.is_dir())
            files = [path for d in dirs for path in sorted(d.glob("*.toml"))]
        except OSError as exc:  # an unreadable folder: named, and the built-in presets still listed
            bad.append(InputError("presets", f"cannot list the folder ({_os_reason(exc)})", str(root)))
            continue
        for path in files:
            try:
                p = load(path, builtin=builtin)
            except InputError as exc:
                bad.append(exc)
                continue
            except Exception as exc:  # noqa: BLE001 - a reader's bug: one bad file never hides the others
                bad.append(
                    InputError("preset", f"could not be read ({type(exc).__name__}: {exc})", str(path))
                )
                continue
            if calc_id is None or p.calculator == calc_id:
                found.append(p)
    return found, bad
