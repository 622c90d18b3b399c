import os

import pytest

# Snapshot determinism: no colour overrides or theme from the caller's environment.
for var in ("NO_COLOR", "TEXTUAL_THEME", "FORCE_COLOR"):
    os.environ.pop(var, None)


@pytest.fixture(autouse=True)
def _isolated_config(tmp_path, monkeypatch):
    """User presets go to a fresh directory, never the developer's ~/.config."""
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))


@pytest.fixture
def terminal(tmp_path):
    """The app in a tmux pane of its own (tests/test_keystrokes.py's Terminal); skipped without tmux."""
    from tests.test_keystrokes import TMUX, Terminal

    if TMUX is None:
        pytest.skip("tmux is not installed (.ci/run installs it)")
    term = Terminal(tmp_path)
    try:
        yield term
    finally:
        term.close()
