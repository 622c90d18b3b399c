"""The user's settings (config.toml where platformdirs puts config: ~/.config/gearhead on Linux,
~/Library/Application Support/gearhead on macOS, %APPDATA%\\gearhead on Windows)."""

from __future__ import annotations

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
    """Write atomically (core.atomic_file); a failure raises its WriteError, an OSError."""
    import tomli_w

    from gearhead.core import atomic_file

    path = config_file()
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_file.write_text(path, tomli_w.dumps(settings), overwrite=True, field="settings")
    return path
