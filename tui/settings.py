"""The user's settings (config.toml where platformdirs puts config: ~/.config/gearhead on Linux,
~/Library/Application Support/gearhead on macOS, %APPDATA%\\gearhead on Windows)."""

from __future__ import annotations

import os
import tempfile
import tomllib
from pathlib import Path

from gearhead.core.unit_systems import SYSTEMS


def config_file() -> Path:
    import platformdirs

    return platformdirs.user_config_path("gearhead") / "config.toml"


def load() -> dict:
    """The settings, or {} when there are none or the file cannot be read (never an error at
    start-up: a broken settings file must not keep the app from opening)."""
    try:
        data = tomllib.loads(config_file().read_text(encoding="utf-8-sig"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError, RecursionError):
        return {}
    units = data.get("units")
    return {"units": units} if units in SYSTEMS else {}


def save(settings: dict) -> Path:
    """Write atomically (temporary file, then rename)."""
    import tomli_w

    path = config_file()
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".config.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(tomli_w.dumps(settings))
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path
