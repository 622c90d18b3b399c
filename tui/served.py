"""The app as `gearhead serve` starts it for each browser session (tui/serve.py): Textual's web
driver in place of a terminal, so the command line's terminal check does not apply."""

from __future__ import annotations

import sys

from .app import run

if __name__ == "__main__":
    # `--open CODE`: the share code of the page's ?p= (tui/serve.py), opened once the app starts
    args = sys.argv[1:]
    failure = run(args[1] if len(args) == 2 and args[0] == "--open" else None)
    if failure is not None:
        sys.stderr.write(failure)
        sys.exit(70)
