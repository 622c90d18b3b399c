"""Tracebacks of unexpected failures, kept for the developer in the user's log directory
(platformdirs: ~/.local/state/gearhead/log on Linux, ~/Library/Logs/gearhead on macOS, the
matching AppData folder on Windows), while the user sees a one-line message. Imported only when
something went wrong, so a normal start pays nothing for logging or platformdirs."""

from __future__ import annotations

import logging
import logging.handlers
from functools import lru_cache
from pathlib import Path


def log_file() -> Path:
    import platformdirs

    return platformdirs.user_log_path("gearhead") / "gearhead.log"


@lru_cache(maxsize=1)
def _logger() -> logging.Logger | None:
    path = log_file()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        # rotated at 1 MB, two old files kept: a loop of failures never fills the disk
        handler = logging.handlers.RotatingFileHandler(
            path, maxBytes=1_000_000, backupCount=2, encoding="utf-8"
        )
    except OSError:
        return None
    handler.setFormatter(logging.Formatter("%(asctime)s %(message)s"))
    log = logging.getLogger("gearhead.bugs")
    log.propagate = False  # never echoed to the terminal by logging's last-resort handler
    log.setLevel(logging.ERROR)
    log.addHandler(handler)
    return log


def is_bug(exc: BaseException) -> bool:
    """An exception the user cannot fix by changing an entry: anything but an InputError, or an
    InputError the last-resort guard raised from another exception (its `__cause__`)."""
    from gearhead.core.errors import InputError

    return not isinstance(exc, InputError) or exc.__cause__ is not None


def record(exc: BaseException, context: str) -> Path | None:
    """Append `exc`'s traceback (with its cause) to the log; the file, or None if it cannot be written."""
    log = _logger()
    if log is None:
        return None
    log.error("%s", context, exc_info=(type(exc), exc, exc.__traceback__))
    for handler in log.handlers:
        handler.flush()
    return log_file()


def record_text(text: str, context: str) -> Path | None:
    """Append a traceback already written out (Textual's, of an exception that stopped the app)."""
    log = _logger()
    if log is None:
        return None
    log.error("%s\n%s", context, text.rstrip())
    for handler in log.handlers:
        handler.flush()
    return log_file()
