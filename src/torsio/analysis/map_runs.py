"""The grid of a severity map and how its points run.

Axis checks and the memory bound of a grid (:func:`check_grid_size`), the chunks of
points sent to an executor
(:class:`PointRunner`), the error of a map whose executor failed (:class:`MapFailed`),
and the progress bar.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from torsio.analysis.severity import DEFAULT_STICK_THRESHOLD
from torsio.analysis.sweep import SweepError, SweepInterrupted, run_tasks_on
from torsio.errors import ConfigError, SolverError
from torsio.physics.system import System
from torsio.solvers.batch import simulate_batch
from torsio.solvers.batch_options import BatchOptions
from torsio.solvers.batch_results import STATUS_MESSAGES, BatchPoints

__all__ = [
    "BYTES_PER_POINT",
    "MapFailed",
    "MapWork",
    "PointRunner",
    "check_grid_size",
    "drive_map",
]

BYTES_PER_POINT = 256
"""Memory a grid point costs, results and their JSON text included (an upper estimate)."""


class MapFailed(SweepError):
    """The executor of a map failed (workers that keep dying, a lost scheduler, no progress).

    A :class:`~torsio.analysis.sweep.SweepError` whose ``partial`` is the map of the
    points finished before the failure, with ``complete = False`` (``torsio map --out``
    writes it to ``FILE.partial.*``).
    """

    def __init__(self, error: SweepError, partial: Any) -> None:
        done = int(partial.done.sum())
        super().__init__(
            f"{error} (map: {done} of {partial.done.size} points computed)", error.results
        )
        self.partial = partial


def _axis(key: str, values: Any, positive: bool) -> np.ndarray:
    array = _axis_values(key, values)
    if array.ndim != 1 or array.size == 0:
        raise ConfigError(
            key, f"expected a non-empty 1-D sequence of values, got shape {array.shape}"
        )
    bad = ~np.isfinite(array) | ((array <= 0) if positive else (array < 0))
    if bad.any():
        what = "positive" if positive else "non-negative"
        raise ConfigError(key, f"expected {what} finite values, got {array[bad][0]!r}")
    if array.size > 1 and not (np.diff(array) > 0).all():
        k = int(np.argmin(np.diff(array) > 0))
        raise ConfigError(
            key, f"expected strictly increasing values, got {array[k]!r} then {array[k + 1]!r}"
        )
    return array


def _axis_values(key: str, values: Any) -> np.ndarray:
    """The values of an axis as floats: numbers, or strings with units for ``wob`` (a
    force, "100 kN") and ``rpm`` (a speed, "10 rad/s"); a ConfigError naming ``key``."""
    from torsio.units import as_rpm, to_si

    def one(value: Any) -> float:
        if isinstance(value, str) and key == "wob":
            return to_si(value, "force", key=key)
        if isinstance(value, str) and key == "rpm":
            return as_rpm(value, key)
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise ConfigError(key, f"expected a number or a sequence of numbers, got {value!r}")
        return float(value)

    try:
        return np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        items = [values] if isinstance(values, str) or not np.iterable(values) else list(values)
        return np.asarray([one(item) for item in items], dtype=float)


def _available_memory() -> float | None:
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):  # pragma: no cover - not POSIX
        return None


def check_grid_size(rows: int, columns: int, memory: float | None = None) -> None:
    """ConfigError if a rows x columns grid's results would not fit in memory.

    Parameters
    ----------
    rows, columns : int
        Number of rotary speeds and of weights on bit.
    memory : float, optional
        Bytes available (default: free physical memory); the results may use half.
    """
    points = int(rows) * int(columns)
    needed = points * BYTES_PER_POINT
    memory = _available_memory() if memory is None else memory
    if memory is not None and needed > 0.5 * memory:
        raise ConfigError(
            "grid",
            f"a grid of {rows:,} rpm x {columns:,} wob = {points:,} "
            f"points needs about {_bytes(needed)} for its results; "
            f"{_bytes(memory)} of memory is available (split the map "
            f"or use fewer points)",
        )


def _bytes(value: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if value < 1000 or unit == "PB":
            return f"{value:.3g} {unit}"
        value /= 1000.0
    return f"{value:.3g} PB"  # pragma: no cover


def _chunk_task(system: System, points: BatchPoints, options: BatchOptions) -> np.ndarray:
    """Worker side: S_SS, status, steps, rejected steps, the time each run ended [s] and
    whether the bit stuck throughout the window (1.0 or 0.0), shape (k, 6)."""
    result = simulate_batch(system, points, None, options)
    stuck = result.stuck(DEFAULT_STICK_THRESHOLD)
    return np.column_stack(
        [result.severity, result.status, result.steps, result.rejected, result.ended, stuck]
    )


@attrs.frozen
class MapWork:
    """What the points of a map run, on any engine: ``task(model, points, settings)`` gives
    rows (S_SS, solver status, steps, rejected steps, the time the run ended [s], stuck 1/0,
    then the map's layers) of the :class:`~torsio.solvers.batch_results.BatchPoints`, in
    tasks of ``chunk_size`` points; ``solver`` names the engine in errors. ``task`` is
    module-level and ``model`` and ``settings`` pickle, for process and Dask workers."""

    task: Callable[[Any, BatchPoints, Any], np.ndarray]
    model: Any
    settings: Any
    chunk_size: int
    solver: str = "the solver"
    layers: tuple[str, ...] = ()


class PointRunner:
    """Runs lists of points of a :class:`MapWork` through a sweep, in chunks, with one
    shared progress count.

    Parameters
    ----------
    work : MapWork
        What every point runs, and in chunks of how many points.
    handle : object
        An open executor (:func:`torsio.analysis.sweep.open_executor`).
    retries : int
        Resubmissions of a chunk whose worker died.
    progress : callable, optional
        ``progress(done_points, total_points)``.
    total : int, optional
        Points the whole job may run, known up front (a map: its grid plus every
        possible bisection run), so that a progress bar's total never changes;
        runs found unnecessary are counted as done with :meth:`skip`. Default: the
        total grows with each :meth:`run`.
    """

    def __init__(
        self,
        work: MapWork,
        handle: Any,
        retries: int,
        progress: Callable[[int, int], None] | None,
        total: int | None = None,
    ) -> None:
        self.work = work
        self.handle = handle
        self.retries = retries
        self.progress = progress
        self.done_points = 0
        self.total_points = 0 if total is None else int(total)
        self.fixed_total = total is not None
        self.runs = 0
        self.retried = 0

    def skip(self, count: int) -> None:
        """Count ``count`` planned points as done without running them (progress only)."""
        if count <= 0:
            return
        self.done_points = min(self.done_points + int(count), self.total_points)
        if self.progress is not None:
            self.progress(self.done_points, self.total_points)

    def run(
        self,
        points: BatchPoints,
        on_partial: Callable[[list[tuple[tuple[int, int], np.ndarray]]], None] | None = None,
    ) -> np.ndarray:
        """Rows (severity, status, steps, rejected, ended, stuck, layers...) of the checked
        points (``points.wob[k]``, ``points.rpm[k]``)."""
        count = points.size
        size = self.work.chunk_size
        bounds = [(k, min(k + size, count)) for k in range(0, count, size)]
        tasks = [(self.work.model, points[a:b], self.work.settings) for a, b in bounds]
        base = self.done_points
        if not self.fixed_total or base + count > self.total_points:
            self.total_points = max(self.total_points, base) + count
        progress = self.progress

        def report(done: int, total: int) -> None:
            if progress is not None:
                progress(
                    base + (count if done == total else min(done * size, count)), self.total_points
                )

        try:
            outcome = run_tasks_on(
                self.handle, self.work.task, tasks, retries=self.retries, progress=report
            )
        except (SweepInterrupted, SweepError) as exc:  # keep what finished, then re-raise
            if on_partial is not None:
                on_partial([(bounds[k], r) for k, r in enumerate(exc.results) if r is not None])
            raise
        self.retried += outcome.retries
        self.done_points += count
        self.runs += count
        return np.concatenate(outcome.results) if outcome.results else np.empty((0, 6))


def _default_chunk_size(points: int, workers: int, serial: bool, dofs: int) -> int:
    largest = max(8, 4096 // max(1, dofs))  # about a second of work per chunk at most
    if serial:
        return max(1, min(points, 2 * largest))
    return max(1, min(largest, math.ceil(points / (4 * workers))))


def _failure_lines(wob: np.ndarray, rpm: np.ndarray, status: np.ndarray) -> list[str]:
    return [
        f"wob={wob[j]:g} N, rpm={rpm[i]:g}: "
        f"{STATUS_MESSAGES.get(int(status[i, j]), f'status {status[i, j]}')}"
        for i, j in zip(*np.nonzero(status), strict=True)
    ]


def drive_map(
    work: MapWork,
    scales: dict[str, Any],
    info: dict[str, Any],
    options: Any,
    *,
    executor: Any = None,
    progress: bool | Callable[[int, int], None] | None = None,
    label: str = "severity map",
) -> Any:
    """The map of every engine: ``work`` at every point of the grid ``scales["wob"]`` x
    ``scales["rpm"]`` on ``executor`` (:func:`torsio.analysis.sweep.open_executor`), then
    its critical weight on bit bisected with more runs of ``work``
    (:func:`torsio.analysis.critical_wob.locate_critical_wob`), as a
    :class:`~torsio.analysis.map_results.SeverityMap` with ``work.layers`` (its
    ``stability_wob`` NaN: the engine's to add).

    ``scales`` are the map's fields every map of the call shares (axes, thresholds,
    k_eq, ω₁, bit radius, ...); ``options`` a :class:`~torsio.analysis.map_options.MapOptions`
    (``threshold``, ``refine``, ``on_failure``, ``retries``, ``timeout``); ``progress`` as
    :func:`torsio.analysis.maps.severity_map`'s. Ctrl-C raises
    :class:`~torsio.analysis.map_results.MapInterrupted`, a failed executor
    :class:`MapFailed`, each with the points done as a partial map.
    """
    import time
    import warnings

    from torsio.analysis.critical_wob import locate_critical_wob
    from torsio.analysis.map_results import MapInterrupted, SeverityMap
    from torsio.analysis.sweep import CONNECT_TIMEOUT, open_executor

    wob, rpm = scales["wob"], scales["rpm"]
    shape, points = (rpm.size, wob.size), rpm.size * wob.size
    stop: Callable[[], None] | None = None
    callback = progress if callable(progress) else None
    if progress is True:  # the command line's reporter, shown at once
        from torsio.solvers.run_chunks import stderr_progress

        reporter = stderr_progress(label, quiet=0.0, unit="points")
        callback, stop = reporter, reporter.close
    severity = np.full(shape, np.nan)
    status = np.zeros(shape, dtype=np.int64)
    steps = np.zeros(shape, dtype=np.int64)
    done = np.zeros(shape, dtype=bool)
    stuck = np.zeros(shape, dtype=bool)
    ended_early = np.zeros(shape, dtype=bool)
    layers = {name: np.full(shape, np.nan) for name in work.layers}
    grid_rpm, grid_wob = np.meshgrid(rpm, wob, indexing="ij")
    start = time.perf_counter()

    def store(rows: np.ndarray, at: np.ndarray) -> None:
        i, j = np.unravel_index(at, shape)
        severity[i, j] = rows[:, 0]
        status[i, j] = rows[:, 1].astype(np.int64)
        steps[i, j] = rows[:, 2].astype(np.int64)
        ended_early[i, j] = rows[:, 4] < info["duration"]
        stuck[i, j] = rows[:, 5] > 0.5
        done[i, j] = True
        for k, layer in enumerate(layers.values()):
            layer[i, j] = rows[:, 6 + k]

    def partial_map() -> SeverityMap:
        nan_rows = np.full(rpm.size, np.nan)
        return SeverityMap(
            **scales,
            severity=severity.copy(),
            critical_wob=nan_rows,
            critical_status=("unresolved",) * rpm.size,
            critical_bracket=np.full((rpm.size, 2), np.nan),
            stability_wob=nan_rows.copy(),
            status=status.copy(),
            steps=steps.copy(),
            done=done.copy(),
            stuck=stuck.copy(),
            complete=False,
            info={**info, "elapsed_s": time.perf_counter() - start},
            layers={name: layer.copy() for name, layer in layers.items()},
        )

    try:
        timeout = CONNECT_TIMEOUT if options.timeout is None else options.timeout
        with open_executor(executor, timeout) as handle:
            info.setdefault("executor", handle.name)
            # a fixed progress total: the grid and every possible bisection run
            total = points + options.refine * rpm.size
            runner = PointRunner(work, handle, options.retries, callback, total=total)
            indices = np.arange(points)

            def keep_partial(chunks: list[Any]) -> None:
                for (a, b), rows in chunks:
                    store(rows, indices[a:b])

            try:
                flat = BatchPoints(grid_wob.ravel(), grid_rpm.ravel())  # axes checked
                store(runner.run(flat, keep_partial), indices)
                failed = done & (status != 0)
                if failed.any() and options.on_failure == "raise":
                    lines = _failure_lines(wob, rpm, status)
                    raise SolverError(
                        f"{work.solver} failed at {len(lines)} of {points} points: "
                        + "; ".join(lines[:5])
                        + (" ..." if len(lines) > 5 else "")
                        + " (on_failure='mark' keeps the others)"
                    )
                critical, crit_status, bracket = locate_critical_wob(
                    runner, wob, rpm, severity, options.threshold, options.refine,
                    options.on_failure,
                )  # fmt: skip
            except SweepInterrupted:
                raise MapInterrupted(partial_map()) from None
            except SweepError as exc:
                raise MapFailed(exc, partial_map()) from exc
            info["retried_chunks"] = runner.retried
    finally:
        if stop is not None:
            stop()
    if failed.any():
        warnings.warn(
            f"{work.solver} failed at {int(failed.sum())} points; they are NaN in the map",
            RuntimeWarning,
            stacklevel=4,
        )
    info["elapsed_s"] = time.perf_counter() - start
    info["extra_runs"] = runner.runs - points
    info["ended_on_steady_cycle"] = int(ended_early.sum())  # grid points that ended early
    return SeverityMap(
        **scales,
        severity=severity,
        critical_wob=critical,
        critical_status=crit_status,
        critical_bracket=bracket,
        stability_wob=np.full(rpm.size, np.nan),
        status=status,
        steps=steps,
        done=done,
        stuck=stuck,
        complete=True,
        info=info,
        layers=layers,
    )
