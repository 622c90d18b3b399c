"""Share codes: a preset as one line of URL-safe text, to paste in a chat, a URL or a terminal.

    gh1:eNpVjsEKgjAQRO9-xeA5A5U6eBO9C36BrNsoaKO7NerfF9RF9jbMe7w1...  (a few hundred characters)

The code is the version prefix `gh1:`, then the preset's TOML (DESIGN.md "Presets", exactly what
ctrl+y copied before codes existed) compressed with zlib and written in URL-safe base64 without
padding. zlib's Adler-32 checksum refuses a code with a character changed; a prefix other than
`gh1:` is refused by name (a newer Gearhead's code, or not a code at all), so version 1 codes read
the same for as long as Gearhead reads them. The preset inside is validated as a file is
(core.presets.from_dict): a code can never load what a file could not.

A code is also accepted inside a link, as its `p` query parameter: `gearhead://open?p=gh1:…` or,
from `gearhead serve`, `http://host:port/?p=gh1:…`. Spaces and line breaks inside a code (a chat
that wrapped it) are ignored.
"""

from __future__ import annotations

import base64
import binascii
import re
import zlib
from pathlib import Path

from .errors import InputError, shown
from .presets import MAX_PRESET_BYTES, Preset, from_dict, load, parse_text

VERSION = 1
PREFIX = f"gh{VERSION}:"
SOURCE = "<share code>"
MAX_CODE_CHARS = 200_000  # a preset compresses to a few hundred characters; more is not a code

_ANY_PREFIX = re.compile(r"gh(\d+):", re.IGNORECASE)  # any version: an unknown one is named, not guessed
_ALPHABET = re.compile(r"[A-Za-z0-9_-]*")


def encode(preset: Preset) -> str:
    """The share code of `preset` (its name, description and inputs, as its TOML holds them)."""
    import tomli_w

    text = tomli_w.dumps(preset.as_toml())
    return encode_text(text)


def encode_text(toml_text: str) -> str:
    """The share code of a preset's TOML text (not validated here: `decode` validates)."""
    packed = zlib.compress(toml_text.encode("utf-8"), 9)
    return PREFIX + base64.urlsafe_b64encode(packed).decode("ascii").rstrip("=")


def link(code: str, base: str = "gearhead://open") -> str:
    """A link that carries `code`: gearhead://open?p=gh1:…, or `base` (e.g. a served app's URL)."""
    return f"{base.rstrip('?')}{'&' if '?' in base else '?'}p={code}"


def find_code(text: str) -> str | None:
    """The share code `text` is or carries (a bare code, or a link's `p` parameter), else None."""
    s = "".join(text.split())  # a chat may wrap a long code over lines
    if _ANY_PREFIX.match(s):
        return s
    if "?" in s or "&" in s:
        from urllib.parse import parse_qs, urlsplit

        try:
            query = urlsplit(s).query
        except ValueError:  # e.g. an unbalanced '[' in the host part
            return None
        for value in parse_qs(query).get("p", []):
            if _ANY_PREFIX.match(value):
                return value
    return None


def is_code(text: str) -> bool:
    return find_code(text) is not None


def decode_text(text: str) -> str:
    """The preset TOML inside a share code (or a link carrying one); InputError if it is not one."""
    code = find_code(text)
    if code is None:
        raise InputError("share code", f"{shown(text.strip())} is not a share code (they begin {PREFIX})")
    if len(code) > MAX_CODE_CHARS:
        raise InputError("share code", f"is too long ({len(code)} characters)")
    version = _ANY_PREFIX.match(code)
    if version.group(0) != PREFIX:
        digits = version.group(1).lstrip("0") or "0"
        # compared by length first: int() of a 5 000-digit version raised (Python's int-to-str limit)
        newer = len(digits) > 9 or int(digits) > VERSION
        said = digits if len(digits) <= 9 else shown(digits, 12)
        why = (
            f"version {said} is newer than this Gearhead reads ({VERSION}); upgrade Gearhead"
            if newer
            else f"version {digits} is not a Gearhead share code version (this Gearhead reads {PREFIX})"
        )
        raise InputError("share code", why)
    body = code[version.end() :].rstrip("=")  # base64's padding, left off, is harmless if kept
    if not body:
        raise InputError("share code", f"is empty after {PREFIX}")
    if not _ALPHABET.fullmatch(body):
        bad = next(ch for ch in body if not _ALPHABET.fullmatch(ch))
        raise InputError(
            "share code", f"contains {bad!r}, which no share code holds (was it cut or changed?)"
        )
    try:
        packed = base64.urlsafe_b64decode(body + "=" * (-len(body) % 4))
    except (binascii.Error, ValueError):
        raise InputError("share code", "is damaged (cut short or changed); copy it again") from None
    unpacker = zlib.decompressobj()
    try:
        raw = unpacker.decompress(packed, MAX_PRESET_BYTES + 1)
    except zlib.error:
        raise InputError("share code", "is damaged (cut short or changed); copy it again") from None
    if len(raw) > MAX_PRESET_BYTES or unpacker.unconsumed_tail:
        raise InputError("share code", f"holds more than a preset's {MAX_PRESET_BYTES} bytes")
    if not unpacker.eof:  # the stream stopped before zlib's end and checksum
        raise InputError("share code", "is damaged (cut short); copy it again")
    if unpacker.unused_data:
        raise InputError("share code", "has extra characters after its end; copy it again")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        raise InputError("share code", "does not hold text (damaged?)") from None


def decode(text: str) -> Preset:
    """The preset a share code (or a link carrying one) holds, validated as a preset file is."""
    return from_dict(parse_text(decode_text(text), SOURCE), SOURCE)


def from_text_kind(text: str) -> str | None:
    """ "code" if a one-line text is a share code or a link carrying one, "recalc" if it is a
    ReCalc link, else None (a file path, or TOML): nothing is decoded here."""
    if is_code(text):
        return "code"
    from . import recalc

    if recalc.is_link(text):
        return "recalc"
    return None


def from_text(text: str) -> Preset | None:
    """The preset a one-line text carries: a share code, a link with one, or a ReCalc link
    (core.recalc; what it could not map in the preset's warnings); None if it is none of these."""
    if is_code(text):
        return decode(text)
    from . import recalc

    if recalc.is_link(text):
        return recalc.to_preset(text)
    return None


def load_any(text: str | Path) -> Preset:
    """A preset from a file path, a share code or a ReCalc link: what `--preset` and ctrl+o's path
    entry take. A file of that name wins over reading the text as a code."""
    import os

    from . import builtin

    if builtin.is_builtin(text) and not os.path.isfile(text):  # builtin:CALC/NAME, wherever installed
        return load(builtin.preset_path(text), builtin=True)
    if isinstance(text, str) and not os.path.isfile(text):
        found = from_text(text)
        if found is not None:
            return found
    return load(text)
