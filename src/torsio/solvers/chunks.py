"""Long compiled loops in chunks of bounded wall time, and their progress on the terminal.

Compiled code does not see signals: Ctrl-C (and SIGTERM, which the CLI turns into
KeyboardInterrupt) takes effect only once it returns to Python. :func:`run_in_chunks`
calls a resumable kernel over chunks of its work (e.g. of an output grid) sized so that
each takes about :data:`CHUNK_SECONDS`, so an interruption lands within about that time,
and reports the work done after each chunk. The kernel carries its own state from one
chunk to the next, so the chunking does not change its result.

:class:`TerminalProgress` is such a report for a person: one line on stderr, updated in
place on a terminal (from :data:`QUIET_SECONDS` on), or a plain line every
:data:`LOG_SECONDS` when stderr is not a terminal and the run is long. Never on stdout.

Examples
--------
>>> done = []
>>> def advance(stop):  # a kernel that does the work up to index ``stop``
...     done.append(stop)
...     return stop
>>> run_in_chunks(advance, 10, first=4)
10
>>> done[0], done[-1]
(4, 10)
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from typing import Any, TextIO

__all__ = ["CHUNK_SECONDS", "LOG_SECONDS", "QUIET_SECONDS", "TerminalProgress", "run_in_chunks"]

CHUNK_SECONDS = 0.1
"""Wall time each chunk aims at [s]: an interruption takes effect within about this."""

QUIET_SECONDS = 1.0
"""A run shorter than this shows no progress on a terminal [s]."""

LOG_SECONDS = 10.0
"""Interval of the progress lines when stderr is not a terminal [s] (none before it)."""


def run_in_chunks(
    advance: Callable[[int], int],
    total: int,
    progress: Callable[[int, int], None] | None = None,
    first: int = 1,
    seconds: float = CHUNK_SECONDS,
) -> int:
    """Call ``advance(stop)`` for growing ``stop`` up to ``total``; return the work reached.

    ``advance(stop)`` does the work up to index ``stop`` (it may go past it) and returns
    the index it reached; reaching less than ``stop`` means it ended early (a failure or
    nothing more to do), and the loop stops there. Each chunk is sized from the wall
    time of the last one to take about ``seconds``; ``progress(reached, total)`` is
    called after each.
    """
    reached = 0
    size = max(1, int(first))
    while reached < total:
        stop = min(total, reached + size)
        start = time.perf_counter()
        now = advance(stop)
        elapsed = time.perf_counter() - start
        if progress is not None:
            progress(min(now, total), total)
        if now < stop:
            return now
        done = now - reached
        reached = now
        if elapsed > 0:  # aim at ``seconds`` per chunk, changing the size at most 4x at once
            size = max(1, int(min(4.0 * size, max(size / 4.0, done * seconds / elapsed))))
        else:
            size *= 4
    return reached


class TerminalProgress:
    """``progress(done, total)`` as one line on stderr: '<label>:  41 % (125 s of 306 s, 9 s)'.

    Parameters
    ----------
    label : str
        Start of the line (e.g. ``"torsio simulate"``).
    unit : callable, optional
        Text of an amount of work (default: ``f"{amount:g}"``), e.g. of a time.
    stream : file, optional
        Default ``sys.stderr``.
    """

    def __init__(
        self, label: str, unit: Callable[[float], str] | None = None, stream: TextIO | None = None
    ) -> None:
        self.label = label
        self.unit = unit or (lambda amount: f"{amount:g}")
        self.stream = stream if stream is not None else sys.stderr
        isatty = getattr(self.stream, "isatty", None)
        self.terminal = bool(isatty and isatty())
        self.start = time.monotonic()
        self.last = -float("inf")  # when a line was last shown
        self.shown = False

    def __call__(self, done: float, total: float) -> None:
        now = time.monotonic()
        elapsed = now - self.start
        if self.terminal:
            if elapsed < QUIET_SECONDS or (now - self.last < 0.25 and done < total):
                return
        elif elapsed < LOG_SECONDS or (now - self.last < LOG_SECONDS and done < total):
            return
        self.last = now
        percent = 100.0 * done / total if total else 100.0
        text = (
            f"{self.label}: {percent:3.0f} % ({self.unit(done)} of {self.unit(total)}, "
            f"{elapsed:.0f} s)"
        )
        self.stream.write(("\r" + text + "\x1b[K") if self.terminal else text + "\n")
        self.stream.flush()
        self.shown = True

    def close(self) -> None:
        """End the line on a terminal (if one was shown)."""
        if self.terminal and self.shown:
            self.stream.write("\n")
            self.stream.flush()

    def __enter__(self) -> TerminalProgress:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()
