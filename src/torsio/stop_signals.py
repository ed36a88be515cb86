"""Ctrl-C and SIGTERM that stop a command even where Python loses their KeyboardInterrupt.

Python raises KeyboardInterrupt for SIGINT in whatever bytecode the main thread runs next.
When that is code whose exceptions Python discards (a weakref callback of the import
system, a finalizer, Python code called by C code that clears errors), the interrupt is
lost and the run goes on: 1 of 120 SIGINTs sent during the start of ``torsio simulate``
on a machine with both cores busy (the run went on to its end). :func:`stop_signals`,
which the command line installs, records each signal before it raises (and keeps
Python's "Exception ignored" traceback of a lost one off stderr);
:func:`raise_if_stopped`, called where a long loop returns to Python between its pieces
of work, raises it again. Outside :func:`stop_signals` (the Python API) nothing changes.

Examples
--------
>>> with stop_signals() as received:
...     raise_if_stopped()  # no signal yet: nothing happens
...     received
[]
"""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
from collections.abc import Iterator
from typing import Any

__all__ = ["raise_if_stopped", "stop_signals"]

_RECEIVED: list[int] = []
"""The stop signals received inside :func:`stop_signals` (signal numbers)."""


@contextlib.contextmanager
def stop_signals() -> Iterator[list[int]]:
    """SIGINT and SIGTERM raise KeyboardInterrupt inside the block and are recorded in the
    list it yields (signal numbers, emptied when the block ends); the previous handlers
    are restored after it.

    Nothing is installed outside the main thread; a SIGINT ignored by the parent process
    (a background job) stays ignored, as Python leaves it; SIGTERM is handled always.
    """
    if threading.current_thread() is not threading.main_thread():
        yield []
        return
    installed = [signal.SIGTERM]
    if signal.getsignal(signal.SIGINT) is not signal.SIG_IGN:
        installed.append(signal.SIGINT)
    _RECEIVED.clear()

    def record(signum: int, frame: Any) -> None:
        _RECEIVED.append(signum)
        raise KeyboardInterrupt

    unraisable = sys.unraisablehook

    def quiet_when_lost(info: Any) -> None:
        """No "Exception ignored" traceback for a lost interrupt: it is raised again."""
        if not (_RECEIVED and issubclass(info.exc_type, KeyboardInterrupt)):
            unraisable(info)

    previous = {s: signal.signal(s, record) for s in installed}
    sys.unraisablehook = quiet_when_lost
    try:
        yield _RECEIVED
    finally:
        if sys.unraisablehook is quiet_when_lost:
            sys.unraisablehook = unraisable
        for number, handler in previous.items():
            if handler is not None:  # None: a handler installed outside Python, kept
                signal.signal(number, handler)
        _RECEIVED.clear()


def raise_if_stopped() -> None:
    """Raise KeyboardInterrupt if a stop signal came (inside :func:`stop_signals`): the
    one its handler raised was lost, since the loop that calls this is still running."""
    if _RECEIVED:
        raise KeyboardInterrupt
