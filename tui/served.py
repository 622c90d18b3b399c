"""The app as `gearhead serve` starts it for each browser session (tui/serve.py): Textual's web
driver in place of a terminal, so the command line's terminal check does not apply.

    python -m gearhead.tui.served [--memory MB] [--allow-paths DIR]... [--open CODE]

Before the app (and its libraries) load: the session's memory is bounded (Linux: the address space,
RLIMIT_AS, so a runaway allocation fails with MemoryError instead of taking the machine; elsewhere
no bound is set), the process ends with the server (Linux: PR_SET_PDEATHSIG), and file dialogs are
confined to the Gearhead folder (tui/served_paths.py), the working folder being its exports/.
"""

from __future__ import annotations

import argparse
import os
import sys


def limit_memory(megabytes: int) -> bool:
    """Bound this process's address space (Linux); False where the OS offers no such bound."""
    if not sys.platform.startswith("linux") or megabytes <= 0:
        return False
    import resource

    limit = megabytes * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    return True


def end_with_parent() -> None:
    """Linux: SIGTERM when the server's process ends, however it ends (kill -9 too), so no session
    outlives it (an orphaned session with a huge terminal grew to 12.8 GB)."""
    if not sys.platform.startswith("linux"):
        return
    import ctypes
    import signal

    parent = os.getppid()
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGTERM)  # 1: PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:  # the server ended before the line above
        sys.exit(0)


def main(argv: list[str]) -> None:
    parser = argparse.ArgumentParser(prog="gearhead.tui.served")
    parser.add_argument("--memory", type=int, default=0, metavar="MB")
    parser.add_argument("--allow-paths", action="append", default=[], metavar="DIR")
    parser.add_argument("--open", metavar="CODE")  # the share code of the page's ?p= (tui/serve.py)
    args = parser.parse_args(argv)
    end_with_parent()
    # one BLAS thread: each thread reserves address space, and a session needs no parallel algebra
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    limit_memory(args.memory)
    from . import served_paths

    os.chdir(served_paths.confine(args.allow_paths))

    from .app import run

    failure = run(args.open)
    if failure is not None:
        sys.stderr.write(failure)
        sys.exit(70)


if __name__ == "__main__":
    main(sys.argv[1:])
