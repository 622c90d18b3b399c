"""A bug in a handler of the app or of a card is a notification and a logged traceback, never a
Textual crash (issue 34).

Textual gives an exception that reaches it (from any message handler, action, timer or screen
callback) to its private `App._handle_exception`: the app exits and prints a full traceback, and it
has no public hook to do otherwise. So our own handlers catch what they raise, before Textual sees
it: the traceback goes to the log (bug_log.py), the user gets one line in a notification, and the
app keeps running with everything typed. What still escapes (a widget's rendering, a dialog) ends
the app as Textual decides; app.run() then turns Textual's report into the same line, the log and
exit code 70 (cli.main)."""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from typing import Any


def internal_error(exc: BaseException, path) -> str:
    """The line the user sees, as the command line writes it after `gearhead: `."""
    text = " ".join(f"{type(exc).__name__}: {exc}".split())
    return f"internal error ({text})" + (f" (traceback in {path})" if path else "")


def report(node: Any, exc: Exception, where: str) -> None:
    """Log `exc` and notify its one line on `node`'s app (a notification cannot crash it)."""
    from .bug_log import record

    path = record(exc, f"gearhead (the app) {where}")
    try:
        node.app.notify(
            internal_error(exc, path), title="Gearhead", severity="error", markup=False, timeout=30
        )
    except Exception:  # no app to tell (it is closing): the log has it
        pass


def guard(node: Any, handler: Callable) -> Callable:
    """`handler` (a function or a coroutine function, e.g. a dialog's result callback) with its
    exceptions reported on `node`'s app."""
    return _wrapped(handler, lambda args: node)


def guarded(method: Callable) -> Callable:
    """Decorator: a method of the app or of a widget (its `self` has `.app`), guarded likewise."""
    return _wrapped(method, lambda args: args[0])


def _wrapped(handler: Callable, node_of: Callable, /) -> Callable:
    where = getattr(handler, "__qualname__", repr(handler))
    if inspect.iscoroutinefunction(handler):

        @functools.wraps(handler)
        async def guarded_async(*args, **kwargs):
            try:
                return await handler(*args, **kwargs)
            except Exception as exc:
                report(node_of(args), exc, where)
                return None

        return guarded_async

    @functools.wraps(handler)
    def guarded_sync(*args, **kwargs):
        try:
            return handler(*args, **kwargs)
        except Exception as exc:
            report(node_of(args), exc, where)
            return None

    return guarded_sync
