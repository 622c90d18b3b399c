"""The app as `gearhead serve` starts it for each browser session (tui/serve.py): Textual's web
driver in place of a terminal, so the command line's terminal check does not apply."""

from __future__ import annotations

import sys

from .app import run

if __name__ == "__main__":
    failure = run()
    if failure is not None:
        sys.stderr.write(failure)
        sys.exit(70)
