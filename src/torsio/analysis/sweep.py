"""Run independent chunks of work (grid points of a map, cases of a study) on any executor.

A sweep is a list of tasks, each a call ``function(*arguments)`` whose result does
not depend on where it runs. :func:`run_tasks` submits them to a
:class:`concurrent.futures.Executor` and collects the results in task order, so
the outcome is identical whichever executor ran it:

``None`` or ``"serial"``
    In this process, one task after the other (:class:`SerialExecutor`).
an ``int`` N
    N local worker processes (a :class:`~concurrent.futures.ProcessPoolExecutor`
    owned by the sweep and shut down at its end).
a ``str`` address (``"tcp://host:8786"``)
    A running Dask scheduler, through ``distributed.Client(address).get_executor()``
    (the ``dask`` extra). The connection times out after :data:`CONNECT_TIMEOUT`
    seconds with a :class:`~torsio.errors.ConfigError` naming the address.
any :class:`concurrent.futures.Executor`
    Used as given and left open (for instance ``client.get_executor()`` of a
    ``distributed.Client`` the caller manages).

Failures of the infrastructure (a worker process that died: ``BrokenProcessPool``,
Dask's ``KilledWorker``, a lost connection) are retried up to ``retries`` times
per task; a pool the sweep owns is rebuilt first. Exceptions raised by the task
itself (bad input, a solver error) are not retried: they propagate.

Ctrl-C (``KeyboardInterrupt``) cancels what has not started and raises
:class:`SweepInterrupted`, which carries the results finished so far (``None``
for the others) and is itself a ``KeyboardInterrupt``.

Examples
--------
>>> import operator
>>> run_tasks(operator.mul, [(2, 3), (4, 5)]).results
[6, 20]
"""

from __future__ import annotations

import concurrent.futures as cf
import os
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any

import attrs

from torsio.analysis.dask_client import (
    CONNECT_TIMEOUT,
    check_timeout,
    close_dask,
    connect_dask,
)
from torsio.errors import ConfigError, TorsioError
from torsio.stop_signals import raise_if_stopped

__all__ = [
    "CONNECT_TIMEOUT",
    "ExecutorSpec",
    "SerialExecutor",
    "SweepError",
    "SweepInterrupted",
    "SweepOutcome",
    "open_executor",
    "run_tasks",
]

NO_PROGRESS_TIMEOUT = 900.0
"""Seconds without any task finishing after which a sweep on workers gives up (a
scheduler whose workers are gone or hang); far longer than one task of a map."""

PARENT_POLL = 0.5
EXECUTOR_POLL = 1.0
"""Seconds between two checks, while tasks run, that the executor is still there."""
"""Seconds between two checks, in a local worker process, that its parent is alive."""

ExecutorSpec = None | int | str | cf.Executor
"""What ``executor=`` accepts: None/"serial", a number of processes, a Dask address, an
Executor."""


class SerialExecutor(cf.Executor):
    """An Executor that runs each task at submission, in the calling thread.

    Exceptions are stored in the future like any executor's, except
    ``KeyboardInterrupt``, which propagates at once.
    """

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> cf.Future[Any]:
        """Run ``fn(*args, **kwargs)`` now, in this thread; return its finished future."""
        future: cf.Future[Any] = cf.Future()
        if not future.set_running_or_notify_cancel():  # pragma: no cover - never cancelled
            return future
        try:
            result = fn(*args, **kwargs)
        except Exception as exc:
            future.set_exception(exc)
        else:
            future.set_result(result)
        return future


class SweepError(TorsioError, RuntimeError):
    """The executor failed in a way retries could not cure.

    Attributes
    ----------
    results : list
        Results of the tasks that finished (``None`` for the others).
    """

    def __init__(self, message: str, results: list[Any]) -> None:
        super().__init__(message)
        self.results = results


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during a sweep; ``results`` holds what finished (``None`` elsewhere)."""

    def __init__(self, results: list[Any], done: int, total: int) -> None:
        super().__init__(f"sweep interrupted after {done} of {total} tasks")
        self.results = results
        self.done = done
        self.total = total


@attrs.frozen
class SweepOutcome:
    """Results of a sweep, in task order.

    Attributes
    ----------
    results : list
        One result per task.
    retries : int
        Tasks resubmitted after an infrastructure failure.
    executor : str
        What ran the tasks ("serial", "processes(N)", "dask(address)", or the
        executor's class name).
    """

    results: list[Any]
    retries: int = 0
    executor: str = "serial"


def _retryable_types() -> tuple[type[BaseException], ...]:
    """Errors after which a task is resubmitted (Dask's only if Dask is already in use)."""
    kinds: list[type[BaseException]] = [
        cf.BrokenExecutor,
        cf.CancelledError,
        ConnectionError,
        EOFError,
    ]
    if _dask_in_use():
        from distributed import KilledWorker
        from distributed.comm.core import CommClosedError

        kinds += [KilledWorker, CommClosedError]
    return tuple(kinds)


def _fatal_types() -> tuple[type[BaseException], ...]:
    """Errors that mean the executor itself is gone (a closed Dask client)."""
    if _dask_in_use():
        from distributed.client import ClosedClientError

        return (ClosedClientError,)
    return ()


def _dask_in_use() -> bool:
    """Whether ``distributed`` is imported: a Dask executor can only come from it, and
    importing it (0.8 s) for a serial or process map would be waste."""
    return "distributed" in sys.modules


def describe_executor(spec: ExecutorSpec) -> str:
    """A short name for an executor specification, for reports."""
    if spec is None or spec == "serial":
        return "serial"
    if isinstance(spec, bool):
        raise ConfigError(
            "executor",
            f"expected None, a number of processes, a Dask "
            f"scheduler address or an Executor, got {spec!r}",
        )
    if isinstance(spec, int):
        return f"processes({spec})"
    if isinstance(spec, str):
        return f"dask({spec})"
    return type(spec).__name__


@attrs.define
class _Handle:
    """An executor and how to rebuild it if the sweep owns it."""

    executor: cf.Executor
    name: str
    rebuild: Callable[[], cf.Executor] | None = None
    close: Callable[[], None] | None = None
    serial: bool = False
    alive: Callable[[], bool] = lambda: True


@contextmanager
def open_executor(spec: ExecutorSpec, timeout: float = CONNECT_TIMEOUT) -> Iterator[_Handle]:
    """The executor ``spec`` names (see the module documentation), closed at exit if owned."""
    name = describe_executor(spec)
    check_timeout(timeout)
    if spec is None or spec == "serial":
        yield _Handle(SerialExecutor(), name, serial=True)
        return
    if isinstance(spec, int):
        if spec < 1:
            raise ConfigError("workers", f"expected a number of worker processes >= 1, got {spec}")
        holder: dict[str, cf.Executor] = {}

        def build() -> cf.Executor:
            import multiprocessing

            holder["pool"] = cf.ProcessPoolExecutor(
                spec,
                mp_context=multiprocessing.get_context("spawn"),
                initializer=watch_parent,
                initargs=(os.getpid(),),
            )
            return holder["pool"]

        def close() -> None:
            terminate_workers(holder["pool"])

        handle = _Handle(build(), name, rebuild=build, close=close)
        try:
            yield handle
        finally:
            holder["pool"].shutdown(wait=True, cancel_futures=True)
        return
    if isinstance(spec, str):
        client = connect_dask(spec, timeout)
        try:
            yield _Handle(
                client.get_executor(pure=False),
                name,
                alive=lambda: client.status not in ("closing", "closed"),
            )
        finally:
            close_dask(client)
        return
    if isinstance(spec, cf.Executor):
        yield _Handle(spec, name)
        return
    raise ConfigError(
        "executor",
        f"expected None, a number of processes, a Dask scheduler "
        f"address or a concurrent.futures.Executor, got {spec!r}",
    )


def watch_parent(parent: int) -> None:
    """In a worker process: end it as soon as process ``parent`` is no longer its parent.

    Runs as the initializer of the local process pools, so that no worker outlives
    the sweep's process (killed, or ended by a signal it could not handle).
    """
    import threading

    def watch() -> None:
        import time

        while os.getppid() == parent:
            time.sleep(PARENT_POLL)
        os._exit(1)

    threading.Thread(target=watch, name="torsio-watch-parent", daemon=True).start()


def terminate_workers(pool: cf.Executor) -> None:
    """Stop a process pool now: cancel what waits, terminate the running workers."""
    processes = list(getattr(pool, "_processes", {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        if process.is_alive():
            process.terminate()
    for process in processes:
        process.join(5.0)
        if process.is_alive():  # pragma: no cover - ignores SIGTERM
            process.kill()


def run_tasks(
    function: Callable[..., Any],
    tasks: Sequence[tuple[Any, ...]],
    executor: ExecutorSpec = None,
    retries: int = 2,
    progress: Callable[[int, int], None] | None = None,
    timeout: float = CONNECT_TIMEOUT,
    no_progress_timeout: float = NO_PROGRESS_TIMEOUT,
) -> SweepOutcome:
    """Run ``function(*task)`` for every task; results in task order.

    Parameters
    ----------
    function : callable
        A module-level function (it is pickled for process and Dask workers).
    tasks : sequence of tuple
        Positional arguments of each call.
    executor : None, int, str or Executor
        Where to run (see the module documentation).
    retries : int
        Resubmissions allowed per task after an infrastructure failure.
    progress : callable, optional
        ``progress(done, total)`` after each finished task.
    timeout : float
        Seconds to wait for a Dask scheduler and its first worker.
    no_progress_timeout : float
        Seconds without any task finishing after which the sweep fails.

    Raises
    ------
    SweepInterrupted
        On Ctrl-C, with the finished results.
    SweepError
        When a task's worker keeps dying, an executor the sweep does not own
        breaks, the executor itself fails (a lost scheduler) or no task finishes
        within ``no_progress_timeout``; it carries the finished results.
    """
    if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
        raise ConfigError("retries", f"expected a whole number >= 0, got {retries!r}")
    check_timeout(no_progress_timeout, "no_progress_timeout")
    with open_executor(executor, timeout) as handle:
        return _run(function, list(tasks), handle, retries, progress, no_progress_timeout)


def run_tasks_on(
    handle: _Handle,
    function: Callable[..., Any],
    tasks: Sequence[tuple[Any, ...]],
    retries: int = 2,
    progress: Callable[[int, int], None] | None = None,
    no_progress_timeout: float = NO_PROGRESS_TIMEOUT,
) -> SweepOutcome:
    """:func:`run_tasks` on an executor already opened with :func:`open_executor`."""
    return _run(function, list(tasks), handle, retries, progress, no_progress_timeout)


def _run(
    function: Callable[..., Any],
    tasks: list[tuple[Any, ...]],
    handle: _Handle,
    retries: int,
    progress: Callable[[int, int], None] | None,
    no_progress_timeout: float = NO_PROGRESS_TIMEOUT,
) -> SweepOutcome:
    total = len(tasks)
    results: list[Any] = [None] * total
    finished = [False] * total
    attempts = [0] * total
    retried = 0
    rebuilds = 0
    done = 0
    retryable = _retryable_types()
    fatal = _fatal_types()
    pending: dict[cf.Future[Any], int] = {}

    def submit(index: int) -> None:
        attempts[index] += 1
        try:
            future = handle.executor.submit(function, *tasks[index])
        except Exception as exc:  # e.g. a closed Dask client, a shut-down pool
            raise failure(f"refused task {index}", exc) from exc
        pending[future] = index

    def lost() -> SweepError:
        return SweepError(
            f"the executor {handle.name} was lost (its scheduler is gone or closed the "
            f"connection); {done} of {total} tasks finished",
            results,
        )

    def failure(what: str, exc: BaseException) -> SweepError:
        """The executor's own error ``exc`` (it ``what``), or :func:`lost` if it is gone."""
        if not handle.alive():
            return lost()
        return SweepError(
            f"the executor {handle.name} {what} ({type(exc).__name__}: {exc}); "
            f"{done} of {total} tasks finished",
            results,
        )

    def finish(index: int, value: Any) -> None:
        nonlocal done
        results[index] = value
        finished[index] = True
        done += 1
        if progress is not None:
            progress(done, total)

    def cancel_pending() -> None:
        if handle.alive():  # a closed Dask client cannot cancel (its callbacks would raise)
            for future in pending:
                future.cancel()

    try:
        if handle.serial:  # in order, in this thread
            for index in range(total):
                finish(index, handle.executor.submit(function, *tasks[index]).result())
            return SweepOutcome(results, 0, handle.name)
        for index in range(total):
            submit(index)
        last_progress = time.monotonic()
        while pending:
            raise_if_stopped()  # a stop signal whose KeyboardInterrupt Python lost
            completed, _ = cf.wait(
                list(pending),
                timeout=min(EXECUTOR_POLL, no_progress_timeout),
                return_when=cf.FIRST_COMPLETED,
            )
            if not completed and not handle.alive():
                raise lost()
            if completed:
                last_progress = time.monotonic()
            elif time.monotonic() - last_progress < no_progress_timeout:
                continue
            else:
                raise SweepError(
                    f"no task finished within {no_progress_timeout:g} s on {handle.name} "
                    f"({done} of {total} tasks finished): its workers are gone or hang",
                    results,
                )
            broken: BaseException | None = None
            for future in completed:
                index = pending.pop(future)
                try:
                    value = future.result()
                except cf.BrokenExecutor as exc:  # the pool lost a worker: all pending fail
                    broken = exc
                    continue
                except fatal as exc:  # the executor itself is gone (a lost Dask scheduler)
                    raise failure("failed", exc) from exc
                except retryable as exc:  # e.g. Dask's KilledWorker: resubmit this task
                    if attempts[index] > retries:
                        raise SweepError(
                            f"task {index} failed {attempts[index]} times on {handle.name} "
                            f"(last: {type(exc).__name__}: {exc}); {done} of {total} tasks "
                            f"finished",
                            results,
                        ) from exc
                    retried += 1
                    submit(index)
                    continue
                finish(index, value)
            if broken is not None:
                rebuilds += 1
                if handle.rebuild is None or rebuilds > retries:
                    why = (
                        "cannot be rebuilt" if handle.rebuild is None else f"broke {rebuilds} times"
                    )
                    raise SweepError(
                        f"the executor {handle.name} lost a worker process and "
                        f"{why} ({type(broken).__name__}: {broken}); {done} of "
                        f"{total} tasks finished",
                        results,
                    ) from broken
                for future in pending:
                    future.cancel()
                pending.clear()
                if handle.close is not None:
                    handle.close()
                handle.executor = handle.rebuild()
                for index in range(total):
                    if not finished[index]:
                        retried += 1
                        submit(index)
        return SweepOutcome(results, retried, handle.name)
    except KeyboardInterrupt:
        cancel_pending()
        if handle.close is not None:
            handle.close()
        raise SweepInterrupted(results, done, total) from None
    except BaseException:  # a task's own error or a SweepError: stop what still runs
        cancel_pending()
        if handle.close is not None:
            handle.close()
        raise


def worker_count(spec: ExecutorSpec) -> int:
    """How many tasks the executor runs at once (1 for serial; a guess for foreign ones)."""
    if spec is None or spec == "serial":
        return 1
    if isinstance(spec, int) and not isinstance(spec, bool):
        return max(1, spec)
    return max(1, os.cpu_count() or 1)
