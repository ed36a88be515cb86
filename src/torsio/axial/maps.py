"""Maps over (weight on bit, rpm) of axial-torsional runs with the RGD bit.

:func:`axial_map` runs :mod:`torsio.axial.kernel` at every point of the grid with the
options of :func:`torsio.axial.transient.simulate_axial` (no signals kept), and returns
:class:`AxialMap`: S_SS, axial severity, stuck and off-bottom fractions, mean ROP [m/s] and
mean MSE [Pa], each of shape (rpm, wob) like torsio's severity maps (``severity[i][j]`` at
``rpm[i]``, ``wob[j]``), and optionally the linear growth rate of steady drilling.

**Where the points run**, as torsio's severity maps (:mod:`torsio.analysis.sweep`):
``executor=None`` in this process, side by side on ``threads`` threads (default numba's
thread count, the machine's cores; the compiled loop releases the GIL), or on an
executor: N local processes, a Dask scheduler's address (the ``dask`` extra) or any
:class:`concurrent.futures.Executor`, in chunks of points each run on one thread. Every
point is the same deterministic run wherever it runs: the map is identical to the bit.

Examples
--------
>>> from torsio.axial.assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> grid = axial_map(rgd_two_dof_example(), rgd_example(), [90e3, 110e3], [60.0, 120.0],
...                  duration=20.0, window=10.0, threads=2)
>>> grid.severity.shape
(2, 2)
>>> sorted(grid.to_dict())[:4]
['axial_severity', 'duration', 'growth_rate', 'mse']
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.analysis.severity import run_times
from torsio.axial.assembly import DrillingAssembly
from torsio.axial.rgd import RGDBit
from torsio.axial.transient import simulate_axial
from torsio.axial.wave_assembly import WaveDrillingAssembly
from torsio.errors import ConfigError

if TYPE_CHECKING:
    from torsio.analysis.sweep import ExecutorSpec

__all__ = ["AxialMap", "axial_map"]

_FIELDS = (
    "severity",
    "axial_severity",
    "stick_fraction",
    "off_bottom_fraction",
    "rop_mean",
    "mse_mean",
)


@attrs.frozen(eq=False)
class AxialMap:
    """Window outputs over a (rpm, wob) grid; every array has shape (len(rpm), len(wob)).

    Attributes
    ----------
    wob, rpm : ndarray
        The grid [N], [rev/min].
    severity, axial_severity, stick_fraction, off_bottom_fraction : ndarray
        As in :class:`torsio.axial.window_summary.WindowSummary`.
    rop, mse : ndarray
        Mean ROP [m/s] and mean MSE [Pa] over the window (MSE inf where the bit did not
        advance).
    growth_rate : ndarray or None
        The linear growth rate [1/s] of steady drilling (when asked).
    duration, window : float
        Run length and window [s].
    executor : str
        What ran the points: ``"threads(N)"``, ``"processes(N)"``, ``"dask(address)"``.
    string_friction_work : ndarray or None
        The work of the friction along the string over each run [J] (0 without contacts).
    """

    wob: NDArray[np.float64]
    rpm: NDArray[np.float64]
    severity: NDArray[np.float64]
    axial_severity: NDArray[np.float64]
    stick_fraction: NDArray[np.float64]
    off_bottom_fraction: NDArray[np.float64]
    rop: NDArray[np.float64]
    mse: NDArray[np.float64]
    growth_rate: NDArray[np.float64] | None
    duration: float
    window: float
    executor: str = "threads(1)"
    string_friction_work: NDArray[np.float64] | None = None

    def to_dict(self) -> dict[str, Any]:
        """DESIGN.md's keys for ``torsio map --json`` with axial dynamics: ``wob``, ``rpm``,
        ``severity``, ``rop``, ``mse`` (null where not finite) and the other fractions."""

        def plain(array: NDArray[np.float64] | None) -> Any:
            if array is None:
                return None
            return [[float(x) if np.isfinite(x) else None for x in row] for row in array]

        return {
            "wob": self.wob.tolist(),
            "rpm": self.rpm.tolist(),
            "severity": plain(self.severity),
            "axial_severity": plain(self.axial_severity),
            "stick_fraction": plain(self.stick_fraction),
            "off_bottom_fraction": plain(self.off_bottom_fraction),
            "rop": plain(self.rop),
            "mse": plain(self.mse),
            "growth_rate": plain(self.growth_rate),
            "string_friction_work": plain(self.string_friction_work),
            "duration": self.duration,
            "steady_window": self.window,
        }


_OUTPUTS = len(_FIELDS) + 2
"""Values of one point: the window's fields, the work of the friction along the string
[J], then the growth rate (NaN when not asked)."""


@attrs.frozen(eq=False)
class PointRun:
    """What every point of an axial map runs: ``simulate_axial`` of one assembly and bit
    with one set of run ``options`` (no signals kept), and the growth rate if asked.

    Module-level and frozen, so it pickles to the workers with the points.
    """

    assembly: DrillingAssembly | WaveDrillingAssembly
    bit: RGDBit
    options: dict[str, Any]
    growth_rate: bool

    def __call__(self, wob: float, rpm: float) -> list[float]:
        """The point's values at ``wob`` [N] and ``rpm`` [rev/min] (:data:`_OUTPUTS`)."""
        run = simulate_axial(
            self.assembly,
            self.bit,
            wob,
            rpm,
            samples=0,
            growth_rate=self.growth_rate,
            **self.options,
        )
        rate = math.nan if run.growth_rate is None else run.growth_rate
        return [float(getattr(run.summary, name)) for name in _FIELDS] + [
            run.string_friction_work,
            rate,
        ]


def _thread_count(threads: int | None, points: int) -> int:
    """``threads``, else numba's thread count on the main thread and one elsewhere (a Dask
    worker's thread, a thread pool's), at most one per point."""
    if threads is None:
        if threading.current_thread() is not threading.main_thread():
            return 1
        from torsio.solvers.compiled import numba

        if numba is None:  # pragma: no cover - plain Python holds the GIL anyway
            return 1
        threads = numba.get_num_threads()
    return max(1, min(int(threads), points))


def run_points(
    run: PointRun,
    points: Sequence[tuple[float, float]],
    threads: int | None = 1,
    progress: Callable[[int, int], None] | None = None,
) -> NDArray[np.float64]:
    """``run`` at the (wob [N], rpm) ``points`` on ``threads`` threads: rows of the window's
    fields and the growth rate (a task of :func:`axial_map`; module-level, so it pickles)."""
    total = len(points)
    rows = np.empty((total, _OUTPUTS))
    done = [0]
    lock = threading.Lock()

    def one(k: int) -> None:
        wob, rpm = points[k]
        rows[k] = run(wob, rpm)
        if progress is not None:
            with lock:
                done[0] += 1
                progress(done[0], total)

    workers = _thread_count(threads, total)
    if workers == 1:
        for k in range(total):
            one(k)
    else:  # the compiled loop releases the GIL: points run side by side
        with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="torsio-axial") as pool:
            list(pool.map(one, range(total)))
    return rows


def _check_threads(threads: Any, executor: Any) -> int | None:
    if threads is None:
        return None
    if isinstance(threads, bool) or not isinstance(threads, int) or threads < 1:
        raise ConfigError("threads", f"expected a number of threads >= 1, got {threads!r}")
    if executor is not None and executor != "serial":
        raise ConfigError(
            "threads",
            f"{threads!r} applies to this process; on the executor {executor!r} every chunk "
            "of points runs on one thread",
        )
    return int(threads)


def axial_map(
    assembly: DrillingAssembly | WaveDrillingAssembly,
    bit: RGDBit,
    wobs: Sequence[float],
    rpms: Sequence[float],
    *,
    growth_rate: bool = False,
    threads: int | None = None,
    executor: ExecutorSpec = None,
    progress: bool | Callable[[int, int], None] | None = None,
    timeout: float | None = None,
    chunk_size: int | None = None,
    **options: Any,
) -> AxialMap:
    """Run :func:`~torsio.axial.transient.simulate_axial` at every (rpm, wob) of the grid,
    no signals kept.

    Parameters
    ----------
    wobs, rpms : sequence of float
        The grid: weights on bit [N] and rotary speeds [rev/min].
    growth_rate : bool
        Add the linear growth rate [1/s] of steady drilling at each point (any assembly;
        not with a prescribed ``bit_rotation``).
    threads : int, optional
        Points side by side in this process (default numba's thread count: the cores).
    executor : None, int, str or concurrent.futures.Executor
        None: this process, on ``threads``; N local processes, a Dask scheduler address
        (``"tcp://host:8786"``, the ``dask`` extra) or an executor
        (:mod:`torsio.analysis.sweep`), chunks of ``chunk_size`` points (default about
        four per worker) on one thread each. The result does not depend on it.
    progress : bool or callable, optional
        ``progress(done_points, total_points)``; True shows a progress bar on stderr.
    timeout : float, optional
        Seconds to wait for a Dask scheduler (default
        :data:`torsio.analysis.sweep.CONNECT_TIMEOUT`).
    **options
        The run options of ``simulate_axial`` (``duration``, ``window``, ``start``,
        ``perturbation``, ``step``, ``steps_per_period``, ``bit_rotation``, ``contacts``).
    """
    wob_grid = np.asarray(wobs, dtype=float).reshape(-1)
    rpm_grid = np.asarray(rpms, dtype=float).reshape(-1)
    threads = _check_threads(threads, executor)
    duration, window = run_times(
        assembly, options.pop("duration", None), options.pop("window", None)
    )
    if growth_rate and options.get("bit_rotation") is not None:
        raise ConfigError(
            "growth_rate",
            "the linear growth rate is of the assembly's turning chain; a prescribed "
            "bit_rotation does not integrate it",
        )
    run = PointRun(assembly, bit, {"duration": duration, "window": window, **options}, growth_rate)
    shape = (rpm_grid.size, wob_grid.size)
    points = [(float(w), float(r)) for r in rpm_grid for w in wob_grid]  # row-major: (rpm, wob)
    stop: Callable[[], None] | None = None
    callback = progress if callable(progress) else None
    if progress is True:
        from torsio.solvers.run_chunks import map_progress

        callback, stop = map_progress("axial map")
    try:
        rows, ran_on = _run_grid(run, points, threads, executor, callback, timeout, chunk_size)
    finally:
        if stop is not None:
            stop()
    out = {name: rows[:, k].reshape(shape) for k, name in enumerate(_FIELDS)}
    return AxialMap(
        wob=wob_grid,
        rpm=rpm_grid,
        severity=out["severity"],
        axial_severity=out["axial_severity"],
        stick_fraction=out["stick_fraction"],
        off_bottom_fraction=out["off_bottom_fraction"],
        rop=out["rop_mean"],
        mse=out["mse_mean"],
        growth_rate=rows[:, -1].reshape(shape) if growth_rate else None,
        duration=duration,
        window=window,
        executor=ran_on,
        string_friction_work=rows[:, -2].reshape(shape),
    )


def _run_grid(
    run: PointRun,
    points: list[tuple[float, float]],
    threads: int | None,
    executor: ExecutorSpec,
    progress: Callable[[int, int], None] | None,
    timeout: float | None,
    chunk_size: int | None,
) -> tuple[NDArray[np.float64], str]:
    """The rows of every point, in order, and what ran them."""
    if executor is None or executor == "serial":
        workers = _thread_count(threads, len(points))
        rows = run_points(run, points, workers, progress)
        return rows, f"threads({workers})"
    from torsio.analysis.sweep import CONNECT_TIMEOUT, run_tasks, worker_count

    if chunk_size is not None and (
        isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 1
    ):
        raise ConfigError("chunk_size", f"expected a whole number >= 1, got {chunk_size!r}")
    size = chunk_size or max(1, math.ceil(len(points) / (4 * worker_count(executor))))
    bounds = [(k, min(k + size, len(points))) for k in range(0, len(points), size)]
    tasks = [(run, points[a:b]) for a, b in bounds]

    def report(done: int, total: int) -> None:
        if progress is not None:
            progress(len(points) if done == total else min(done * size, len(points)), len(points))

    outcome = run_tasks(
        run_points,
        tasks,
        executor,
        progress=report,
        timeout=CONNECT_TIMEOUT if timeout is None else timeout,
    )
    return np.concatenate(outcome.results), outcome.executor
