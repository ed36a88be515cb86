"""Long compiled loops run in chunks of bounded wall time, with progress on stderr.

A compiled loop (numba, no GIL) does not return to the interpreter until it is done, so
Python's signal handlers (Ctrl-C, SIGTERM turned into KeyboardInterrupt by the command
line) wait for it. :func:`run_in_chunks` calls a function that advances a loop by ``k``
steps again and again, ``k`` chosen so that each call lasts about
:data:`CHUNK_SECONDS`; between calls the interpreter runs (signals are handled there, and
a signal whose KeyboardInterrupt Python lost is raised again: :mod:`torsio.stop_signals`) and
progress is reported (:func:`count_progress` reports work of no known total, a fit's or a
search's runs). The function keeps the loop's state between calls, so the result
is the one a single call of every step would give.

:func:`stderr_progress` is the progress reporter of a single run: nothing for a run that
ends within :data:`QUIET_SECONDS`; then a transient rich progress bar on stderr when
stderr is a terminal, else one line every :data:`LINE_SECONDS` (never on stdout, which
``--json`` keeps for one JSON object).

Examples
--------
>>> done = []
>>> run_in_chunks(10, lambda k: done.append(k), first=4)
10
>>> done
[4, 6]
>>> run_in_chunks(10, lambda k: True, first=3)  # the loop stopped by itself
3
"""

from __future__ import annotations

import contextlib
import math
import sys
import time
from collections.abc import Callable, Iterator
from typing import Any, TextIO

from torsio.stop_signals import raise_if_stopped

__all__ = [
    "CHUNK_SECONDS",
    "LINE_SECONDS",
    "QUIET_SECONDS",
    "count_progress",
    "progress_bar",
    "run_in_chunks",
    "run_progress",
    "stderr_progress",
]

CHUNK_SECONDS = 0.2
"""Wall time aimed at for one chunk [s]: a signal is handled within about that."""

FIRST_CHUNK = 1000
"""Steps of the first chunk (its time, compilation included, sets the next ones)."""

QUIET_SECONDS = 2.0
"""A run that ends within this wall time [s] shows no progress."""

LINE_SECONDS = 4.0
"""Seconds between progress lines when stderr is not a terminal (with :data:`QUIET_SECONDS`,
no command is silent for more than 5 s while its work reports)."""

Progress = Callable[[int, int], None]


def run_in_chunks(
    total: int,
    advance: Callable[[int], bool | None],
    progress: Progress | None = None,
    *,
    first: int = FIRST_CHUNK,
    seconds: float = CHUNK_SECONDS,
) -> int:
    """Advance a loop of ``total`` steps by chunks; return the steps handed to ``advance``.

    Parameters
    ----------
    total : int
        Steps of the whole loop.
    advance : callable
        ``advance(k)`` runs the next ``k`` steps; a true return value means the loop
        ended by itself (e.g. on a steady cycle, or a failed step) and no chunk follows.
    progress : callable, optional
        ``progress(done, total)`` after every chunk.
    first : int
        Steps of the first chunk.
    seconds : float
        Wall time aimed at per chunk [s]; the chunk grows or shrinks (at most four times
        per chunk) by the time the last one took.
    """
    done = 0
    chunk = max(1, int(first))
    while done < total:
        k = min(chunk, total - done)
        started = time.perf_counter()
        stopped = advance(k)
        elapsed = time.perf_counter() - started
        done += k
        raise_if_stopped()  # a stop signal whose KeyboardInterrupt Python lost
        if progress is not None:
            progress(done, total)
        if stopped:
            break
        rate = k / elapsed if elapsed > 0 else math.inf
        chunk = int(min(4 * k, max(k / 4, rate * seconds, 1)))
    return done


class _StderrProgress:
    """:func:`stderr_progress`'s reporter (a callable with ``close``); ``total`` None: the
    total is not known (:func:`count_progress`)."""

    def __init__(
        self, label: str, stream: TextIO | None, quiet: float, every: float, unit: str = "steps"
    ) -> None:
        self.label = label
        self.unit = unit
        self.stream = stream
        self.quiet = quiet
        self.every = every
        self.started = time.perf_counter()
        self.last_line = -math.inf
        self.first: tuple[float, int] | None = None  # (elapsed, done) at the first call
        self.bar: Any = None
        self.task: Any = None

    def _output(self) -> TextIO:
        return self.stream if self.stream is not None else sys.stderr

    def __call__(self, done: int, total: int | None) -> None:
        elapsed = time.perf_counter() - self.started
        if self.first is None:
            self.first = (elapsed, done)
        ended = total is not None and done >= total
        if elapsed < self.quiet or ended:
            if self.bar is not None and ended:
                self.bar.update(self.task, completed=done, total=total)
            return
        output = self._output()
        if output.isatty():
            if self.bar is None:
                self._start_bar(output, total)
            self.bar.update(self.task, completed=done, total=total)
        elif elapsed - self.last_line >= self.every:
            self.last_line = elapsed
            line = self._line(elapsed, done, total)
            print(f"torsio: {self.label}: {line}", file=output, flush=True)

    def _line(self, elapsed: float, done: int, total: int | None) -> str:
        if total is None:
            return f"{done:,} {self.unit}, {elapsed:.0f} s"
        return (
            f"{done / total:.0%} ({done:,} of {total:,} {self.unit}), {elapsed:.0f} s, "
            f"{self._time_left(elapsed, done, total)}"
        )

    def _time_left(self, elapsed: float, done: int, total: int) -> str:
        """The rate since the first call (the first steps may hold numba's compile)."""
        assert self.first is not None
        since, done_then = self.first
        if done <= done_then or elapsed <= since:
            return "time left not known yet"
        return f"about {(elapsed - since) * (total - done) / (done - done_then):.0f} s left"

    def _start_bar(self, output: TextIO, total: int | None) -> None:
        self.bar = progress_bar(self.label, self.unit, output)
        self.task = self.bar.add_task(self.label, total=total)
        self.bar.start()

    def close(self) -> None:
        """Remove the bar (if one was shown)."""
        if self.bar is not None:
            self.bar.stop()
            self.bar = None


def progress_bar(label: str, unit: str, output: TextIO | None = None) -> Any:
    """A transient rich progress bar on ``output`` (default stderr): ``label``, the bar,
    done of total ``unit``, elapsed and remaining time. Not started; add a task to it."""
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    return Progress(
        TextColumn(label),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn(unit),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        transient=True,
        console=Console(stderr=True) if output is None else Console(file=output),
    )


def stderr_progress(
    label: str,
    stream: TextIO | None = None,
    quiet: float = QUIET_SECONDS,
    every: float = LINE_SECONDS,
    unit: str = "steps",
) -> _StderrProgress:
    """A ``progress(done, total)`` reporter for one long run (or a map's points, ``unit``);
    call ``close()`` at the end.

    Silent for the first ``quiet`` seconds; then a rich bar when ``stream`` (default:
    stderr at the time of the call) is a terminal, else a line every ``every`` seconds.

    Examples
    --------
    >>> import io
    >>> stream = io.StringIO()
    >>> report = stderr_progress("wave run", stream, quiet=0.0, every=0.0)
    >>> report(50, 200)
    >>> report.close()
    >>> stream.getvalue().startswith("torsio: wave run: 25% (50 of 200 steps)")
    True
    """
    return _StderrProgress(label, stream, quiet, every, unit)


def count_progress(
    label: str,
    unit: str = "runs",
    stream: TextIO | None = None,
    quiet: float = QUIET_SECONDS,
    every: float = LINE_SECONDS,
) -> _Count:
    """A ``progress(n)`` reporter of work whose total is not known (``n`` more ``unit``
    done: the runs of a search or a fit), shown as :func:`stderr_progress` shows a run;
    ``close`` it at the end.

    Examples
    --------
    >>> import io
    >>> stream = io.StringIO()
    >>> report = count_progress("fit", stream=stream, quiet=0.0, every=0.0)
    >>> report(2)
    >>> report(2)
    >>> report.close()
    >>> stream.getvalue().splitlines()[-1].startswith("torsio: fit: 4 runs, ")
    True
    """
    return _Count(_StderrProgress(label, stream, quiet, every, unit))


class _Count:
    """:func:`count_progress`'s reporter: the count so far, shown with no total."""

    def __init__(self, shown: _StderrProgress) -> None:
        self.shown, self.done = shown, 0

    def __call__(self, count: int) -> None:
        self.done += count
        self.shown(self.done, None)

    def close(self) -> None:
        """Remove the bar (if one was shown)."""
        self.shown.close()


@contextlib.contextmanager
def run_progress(progress: Any, label: str = "simulate") -> Iterator[Progress | None]:
    """The ``progress(done, total)`` of one run: ``None``, :func:`stderr_progress` after
    :data:`QUIET_SECONDS`; ``True``, at once; ``False``, none; a callable, itself. The
    reporter is closed at the end."""
    reporter = None
    if progress is None or progress is True:
        reporter = stderr_progress(label, quiet=0.0 if progress else QUIET_SECONDS)
    try:
        yield reporter if reporter is not None else (progress or None)
    finally:
        if reporter is not None:
            reporter.close()
