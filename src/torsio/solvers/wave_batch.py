"""Many operating points of the distributed model: what maps run for the ``wave`` strategy.

:func:`simulate_wave_batch` is what :func:`torsio.solvers.batch.simulate_batch` hands a
System with a :class:`torsio.model.wave.WaveModel` to. Every point starts from rest and
runs the compiled characteristic stepping (:mod:`torsio.solvers.characteristics`) on the
fixed grid (no tolerances: ``rtol`` and ``atol`` are kept for the record only); S_SS takes
the bit-speed extremes over every step of the window. A run ends early once it is on a
steady cycle within ``steady_tolerance`` (:mod:`torsio.solvers.characteristics`; not with
a torque-driven top). The engine is ``"wave"`` (the law's compiled kernel) or
``"wave-python"`` (a law without one).
"""

from __future__ import annotations

import math
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np

from torsio.analysis.severity import default_times
from torsio.errors import SolverError
from torsio.model.wave import check_wave_damping, first_frequency
from torsio.solvers.batch_results import (
    DEFAULT_STEADY_TOLERANCE,
    BatchResults,
    batch_points,
    check_steady_tolerance,
)
from torsio.solvers.wave_march import march
from torsio.solvers.wave_top import top_boundary


def wave_scales(grid: Any) -> tuple[float, float]:
    """(k_eq [N m/rad], omega_1 [rad/s]) of the continuum on the grid.

    k_eq = 1 / sum(L_i / (G_i J_i)): the static stiffness seen at the bit with the top
    held (Eq. 9 for the continuous string); omega_1 the grid string's first exact mode
    (the rigid-BHA continuum with ``rigid_bha``).
    """
    return grid.static_stiffness, first_frequency(grid)


def _worker_count(threads: int | None, points: int) -> int:
    """Threads for ``points`` points: ``threads``, else numba's count on the main thread."""
    if threads is None:
        if threading.current_thread() is not threading.main_thread():
            return 1
        try:
            import numba
        except ImportError:  # pragma: no cover - plain Python holds the GIL anyway
            return 1
        threads = numba.get_num_threads()
    return max(1, min(int(threads), points))


def simulate_wave_batch(
    system: Any,
    wob: Any,
    rpm: Any = None,
    duration: float | None = None,
    steady_window: float | None = None,
    rtol: float = math.nan,
    atol: float = math.nan,
    threads: int | None = None,
    steady_tolerance: float = DEFAULT_STEADY_TOLERANCE,
    **ignored: Any,
) -> Any:
    """S_SS of the wave model at each (wob[k], rpm[k]); returns a ``BatchResults``.

    ``threads``: points run side by side on so many threads (default: numba's thread
    count, as the lumped engine; one thread off the main thread, e.g. in a Dask worker).
    ``steady_tolerance``: as for the lumped engine (S_SS units; 0 runs to the end).
    """
    check_steady_tolerance(steady_tolerance)
    grid = system.model
    alpha = check_wave_damping(system.damping, system.model)
    wob_arr, rpm_arr, torque_driven = batch_points(system, wob, rpm)
    omega_1 = first_frequency(grid)
    if duration is None or steady_window is None:
        default_duration, default_window = default_times(omega_1)
        duration = default_duration if duration is None else duration
        steady_window = default_window if steady_window is None else steady_window
    dt = grid.time_step
    steps = max(1, int(round(float(duration) / dt)))
    window_steps = max(1, int(round(float(steady_window) / dt)))
    out = np.full((wob_arr.size, 3), np.nan)
    status = np.zeros(wob_arr.size, dtype=np.int64)
    taken = np.zeros(wob_arr.size, dtype=np.int64)
    steady = 0.0 if torque_driven else float(steady_tolerance)
    engines = set()

    def run_point(k: int) -> None:
        point = system.at(wob=float(wob_arr[k]), **({} if torque_driven else {"rpm": rpm_arr[k]}))
        top = top_boundary(point, grid)
        try:
            run = march(grid, top, point.law, point.wob, point.bit_radius, alpha, steps,
                        window_start=steps - window_steps + 1, track_energy=False,
                        steady_tolerance=steady, cycle_gap=0.5 * math.pi / omega_1)  # fmt: skip
        except SolverError:
            status[k] = 1
            return
        summary = run.summary
        engines.add(run.engine)
        taken[k] = int(summary["steps"])
        window = summary["window_steps"]
        out[k] = (
            summary["bit_speed_max"],
            summary["bit_speed_min"],
            summary["top_speed_sum"] / window if window else math.nan,
        )

    start = time.perf_counter()
    workers = _worker_count(threads, wob_arr.size)
    if workers == 1:
        for k in range(wob_arr.size):
            run_point(k)
    else:  # the compiled stepping releases the GIL: points run side by side
        with ThreadPoolExecutor(max_workers=workers) as pool:
            list(pool.map(run_point, range(wob_arr.size)))
    engine = "wave-python" if "python" in engines else "wave"
    elapsed = time.perf_counter() - start
    reference = out[:, 2] if torque_driven else rpm_arr * (math.pi / 30.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        severity = np.where(status == 0, (out[:, 0] - out[:, 1]) / (2.0 * reference), np.nan)
    ended = np.where((taken < steps) & (status == 0), taken * dt, float(duration))
    return BatchResults(
        wob_arr, rpm_arr, severity, out[:, 0], out[:, 1], out[:, 2], taken,
        np.zeros(wob_arr.size, dtype=np.int64), status, engine, float(duration),
        float(steady_window), float(rtol), float(atol), elapsed, ended, steady,
    )  # fmt: skip
