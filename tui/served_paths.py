"""Where a served session may read and write files (`gearhead serve`, tui/serve.py).

A browser tab's app runs on the serving machine: its file dialogs (export, load a preset or
workbook) would reach any file the server's user can. A served session is confined to the Gearhead
folder (beside config.toml: presets/, and exports/, its working folder) and to any folder `gearhead
serve --allow-paths` adds; the terminal app is never confined. The dialogs call `check` on every
path they read or write.
"""

from __future__ import annotations

import os
from pathlib import Path

from gearhead.core.errors import InputError

_allowed: tuple[Path, ...] | None = None  # None: not confined (the terminal app)


def gearhead_folder() -> Path:
    import platformdirs

    return platformdirs.user_config_path("gearhead")


def _real(path: Path) -> Path:
    # symlinks and '..' resolved, as the OS will: a link inside the folder to a file outside is outside
    return Path(os.path.realpath(path))


def confine(extra: list[str] = ()) -> Path:
    """From now on, only the Gearhead folder and `extra` (folders; "/" allows every path). Returns
    the working folder a relative name is written in (exports/, created)."""
    global _allowed
    work = gearhead_folder() / "exports"
    work.mkdir(parents=True, exist_ok=True)
    _allowed = (_real(gearhead_folder()), *(_real(Path(p).expanduser()) for p in extra))
    return work


def confined() -> bool:
    return _allowed is not None


def check(raw: str) -> Path:
    """The path `raw` names (~ expanded); in a served session, an InputError naming the folders
    allowed when it lies outside them."""
    try:
        path = Path(raw).expanduser()
        if _allowed is None:
            return path
        real = _real(path)
    except (ValueError, RuntimeError, OSError) as exc:  # '~nosuchuser/x', a NUL, a loop of links
        raise InputError("file", f"not a usable file path ({exc})", raw[:80]) from None
    if any(real == root or root in real.parents for root in _allowed):
        return path
    raise InputError(
        "file",
        f"a served session reads and writes only in {gearhead_folder()}"
        + (f" and {', '.join(str(p) for p in _allowed[1:])}" if len(_allowed) > 1 else "")
        + " (gearhead serve --allow-paths DIR adds a folder)",
        raw[:80],
    )
