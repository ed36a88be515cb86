"""Maps over (weight on bit, rpm) of axial-torsional runs with the RGD bit.

:func:`axial_map` runs :mod:`torsio.solvers.axial_kernel` at every point of the grid with the
options of :func:`torsio.analysis.axial_transient.simulate_axial` (no signals kept), and returns
:class:`~torsio.analysis.map_results.SeverityMap`, the map of every model: S_SS, its
classification and critical weight on bit, and the layers axial severity, stuck and
off-bottom fractions, mean ROP [m/s] and mean MSE [Pa] (``severity[i][j]`` at ``rpm[i]``,
``wob[j]``), and optionally the linear growth rate of steady drilling, whose change of sign
along each row is the map's ``stability_wob``. It saves, loads, plots and writes CSV as
every map; Ctrl-C or a failed executor raise with the points done as a partial map
(:class:`~torsio.analysis.map_results.MapInterrupted`,
:class:`~torsio.analysis.map_runs.MapFailed`).

**Where the points run**: on the driver of every map
(:func:`torsio.analysis.map_runs.drive_map`, :mod:`torsio.analysis.sweep`):
``executor=None`` in this process, side by side on ``threads`` threads (default numba's
thread count, the machine's cores; the compiled loop releases the GIL), or on an
executor: N local processes, a Dask scheduler's address (the ``dask`` extra) or any
:class:`concurrent.futures.Executor`, in chunks of points each run on one thread. Every
point is the same deterministic run wherever it runs: the map is identical to the bit.

Examples
--------
>>> from torsio.model.axial_assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> grid = axial_map(rgd_two_dof_example(), rgd_example(), [90e3, 110e3], [60.0, 120.0],
...                  duration=20.0, window=10.0, threads=2)
>>> grid.severity.shape
(2, 2)
>>> [key in grid.to_dict() for key in ("critical_wob", "rop", "mse", "growth_rate")]
[True, True, True, True]
"""

from __future__ import annotations

import math
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING, Any, cast

import attrs
import numpy as np
from numpy.typing import ArrayLike, NDArray

from torsio.analysis.axial_results import SCHEME, channels_of
from torsio.analysis.axial_transient import run_top_boundary, simulate_axial
from torsio.analysis.map_checks import LAYERS
from torsio.analysis.map_options import MapOptions
from torsio.analysis.map_results import STICK_SLIP_THRESHOLD, SeverityMap
from torsio.analysis.map_runs import MapWork, drive_map
from torsio.analysis.severity import SEVERE_THRESHOLD, run_times
from torsio.errors import ConfigError
from torsio.model.axial_assembly import assembly_description, assembly_summary, lumped_twin
from torsio.model.lumped import LumpedModel
from torsio.model.wave import WaveModel
from torsio.physics.torque_law_bit import AxialBit
from torsio.solvers.batch_options import batch_threads
from torsio.solvers.batch_results import refuse_speed_table

if TYPE_CHECKING:
    from torsio.analysis.sweep import ExecutorSpec
    from torsio.solvers.batch_results import BatchPoints

__all__ = ["axial_map"]


@attrs.frozen(eq=False)
class PointRun:
    """What every point of an axial map runs: ``simulate_axial`` of one assembly and bit
    with one set of run ``options`` (no signals kept), and the growth rate if asked.

    Module-level and frozen, so it pickles to the workers with the points.
    """

    assembly: LumpedModel | WaveModel
    bit: AxialBit
    options: dict[str, Any]
    growth_rate: bool


def run_points(run: PointRun, points: BatchPoints, settings: Any = None) -> NDArray:
    """The rows of the map driver (:class:`torsio.analysis.map_runs.MapWork`) at the
    ``points``: S_SS, status 0, the steps, 0 rejected, the run's end [s], stuck (the bit
    stuck throughout the window), then the layers :data:`~torsio.analysis.map_checks.LAYERS`
    (the growth rate NaN when not asked)."""
    rows = []
    for wob, rpm in zip(points.wob, points.rpm, strict=True):
        results = simulate_axial(run.assembly, run.bit, float(wob), float(rpm), samples=0,
                                 growth_rate=run.growth_rate, **run.options)  # fmt: skip
        one = channels_of(results)
        s = one.summary
        layers = {"rop": s.rop_mean, "mse": s.mse_mean, "stick_fraction": s.stick_fraction,
                  "off_bottom_fraction": s.off_bottom_fraction,
                  "axial_severity": s.axial_severity,
                  "growth_rate": math.nan if one.growth_rate is None else one.growth_rate,
                  "string_friction_work": one.string_friction_work}  # fmt: skip
        steps = round(one.duration / one.step)
        head = [s.severity, 0.0, steps, 0.0, one.duration, float(s.stick_fraction >= 1.0)]
        rows.append(head + [layers[name] for name in LAYERS])
    return np.array(rows, dtype=float).reshape(-1, 6 + len(LAYERS))


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
    assembly: LumpedModel | WaveModel,
    bit: AxialBit,
    wobs: ArrayLike,
    rpms: ArrayLike,
    *,
    growth_rate: bool = False,
    threshold: float = SEVERE_THRESHOLD,
    refine: int = 0,
    threads: int | None = None,
    executor: ExecutorSpec = None,
    progress: bool | Callable[[int, int], None] | None = None,
    timeout: float | None = None,
    chunk_size: int | None = None,
    **options: Any,
) -> SeverityMap:
    """Run :func:`~torsio.analysis.axial_transient.simulate_axial` at every (rpm, wob) of the grid,
    no signals kept.

    Parameters
    ----------
    wobs, rpms : sequence of float
        The grid: weights on bit [N] and rotary speeds [rev/min].
    growth_rate : bool
        Add the linear growth rate [1/s] of steady drilling at each point (any assembly;
        not with a prescribed ``bit_rotation``).
    threshold : float
        S_SS above which a point is severe (the critical weight on bit's).
    refine : int
        Bisection steps of the critical weight on bit in its grid cell: one more run per
        row and step (0: the middle of the cell, as ``"grid"``).
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
    top = options.get("top_drive")
    if top is not None and rpm_grid.size:
        refuse_speed_table(top, run_top_boundary(top, assembly, float(rpm_grid[0])))
    choices = MapOptions(threshold=threshold, refine=refine, timeout=timeout, chunk_size=chunk_size)
    run = PointRun(assembly, bit, {"duration": duration, "window": window, **options}, growth_rate)
    points = wob_grid.size * rpm_grid.size
    info = {"engine": "axial", "scheme": SCHEME, "start": options.get("start", "rest")}
    info.update(model=assembly_description(assembly), duration=duration, steady_window=window)
    info["label"] = f"{assembly_summary(info['model'])}, {bit.name} bit"
    pool = None
    if executor is None or executor == "serial":  # this process: a point per task, on threads
        workers = batch_threads(threads, points)
        info["executor"] = f"threads({workers})"
        if workers > 1:  # the compiled loop releases the GIL: points run side by side
            pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="torsio-axial")
        size = 1
    else:
        from torsio.analysis.sweep import worker_count

        size = chunk_size or max(1, math.ceil(points / (4 * worker_count(executor))))
    chain = assembly if assembly.has_matrices else lumped_twin(cast(WaveModel, assembly))
    scales = {"wob": wob_grid, "rpm": rpm_grid, "threshold": choices.threshold,
              "stick_slip_threshold": STICK_SLIP_THRESHOLD,
              "k_eq": chain.equivalent_stiffness,
              "omega1": assembly.first_frequency(), "bit_radius": bit.radius,
              "engine": "axial"}  # fmt: skip
    work = MapWork(run_points, run, None, size, "the axial engine", LAYERS)
    try:
        grid = drive_map(work, scales, info, choices, executor=pool or executor,
                         progress=progress, label="axial map")  # fmt: skip
    finally:
        if pool is not None:  # Ctrl-C: the points not started are cancelled
            pool.shutdown(wait=False, cancel_futures=True)
    rates = grid.layers["growth_rate"] if growth_rate else None
    return attrs.evolve(
        grid,
        layers={**grid.layers, "growth_rate": rates},
        stability_wob=_sign_change(wob_grid, rates, rpm_grid.size),
    )


def _sign_change(wob: NDArray[np.float64], rates: NDArray | None, rows: int) -> NDArray:
    """Per row, the weight on bit [N] where the growth rate first turns positive, linear
    between the grid points that bracket it (NaN: no growth rate, or no change of sign)."""
    found = np.full(rows, np.nan)
    for i, row in enumerate(() if rates is None else rates):
        cross = np.flatnonzero((row[:-1] <= 0) & (row[1:] > 0))
        if cross.size:
            j = int(cross[0])
            found[i] = wob[j] - row[j] * (wob[j + 1] - wob[j]) / (row[j + 1] - row[j])
    return found
