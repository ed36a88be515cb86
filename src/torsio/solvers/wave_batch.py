"""Many operating points of the distributed model: what maps run for the ``wave`` strategy.

:func:`simulate_wave_batch` is what :func:`torsio.solvers.batch.simulate_batch` hands a
System with a :class:`torsio.model.wave.WaveModel` to. Every point starts from rest and
runs the compiled characteristic stepping (:mod:`torsio.solvers.characteristics`) on the
fixed grid (no tolerances: ``rtol`` and ``atol`` are kept for the record only); S_SS takes
the bit-speed extremes over every step of the window. A run ends early once it is on a
steady cycle within ``steady_tolerance`` (:mod:`torsio.solvers.characteristics`; not with
a torque-driven top). The engine is ``"wave"`` (the law's compiled kernel) or
``"wave-python"`` (a law without one); ``engine`` may be ``"auto"`` or ``"numba"`` (the
compiled kernel, required), the lumped engines' ``"numpy"`` and ``"scipy"`` are refused.

The runs are bounded up front (:func:`torsio.analysis.budget.check_wave_steps`, the
window's steps: :func:`torsio.analysis.simulation_options.check_window_samples`) and step
in chunks (:mod:`torsio.solvers.run_chunks`): on Ctrl-C the points running on other
threads stop at their next chunk.
"""

from __future__ import annotations

import math
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np

from torsio.analysis.budget import check_wave_steps
from torsio.analysis.severity import check_window, run_times, severity_of_extremes
from torsio.analysis.simulation_options import check_window_samples
from torsio.errors import ConfigError, SolverError
from torsio.model.wave import check_wave_damping
from torsio.solvers.batch_options import BatchOptions, batch_threads
from torsio.solvers.batch_results import (
    BatchResults,
    batch_points,
)
from torsio.solvers.wave_march import RunCancelled, law_functions, march
from torsio.solvers.wave_top import top_boundary
from torsio.units import RPM_TO_RAD_S

WAVE_ENGINES = ("auto", "numba", "compiled")
"""Engines a wave map accepts: its own stepping (compiled with numba when the law has a
kernel); ``numba`` and ``compiled`` require the kernel."""


def _check_engine(engine: Any, law: Any) -> tuple[Any, Any, np.ndarray] | None:
    """The law's compiled kernel functions for ``engine`` (None: the law's own choice)."""
    if engine not in WAVE_ENGINES:
        raise ConfigError(
            "engine",
            f"the wave model steps along characteristics with its own kernel; expected one "
            f"of {', '.join(WAVE_ENGINES)}, got {engine!r} (numpy and scipy are engines of "
            "the lumped strategies)",
        )
    if engine == "auto":
        return None
    torque, slope, parameters, name = law_functions(law)
    if name != "numba":
        raise ConfigError(
            "engine",
            f"engine {engine!r} needs the bit-rock law's compiled kernel, and "
            f"{getattr(law, 'name', type(law).__name__)!r} has none (or numba is not "
            "installed); use engine='auto' (plain Python steps, slowly)",
        )
    return torque, slope, parameters


def simulate_wave_batch(system: Any, wob: Any, rpm: Any, options: BatchOptions) -> Any:
    """S_SS of the wave model at each (wob[k], rpm[k]); returns a ``BatchResults``.

    Of the :class:`torsio.solvers.batch_options.BatchOptions`: ``threads``: points run side
    by side on so many threads (default: numba's thread count, as the lumped engine; one
    thread off the main thread, e.g. in a Dask worker); ``steady_tolerance``: as for the
    lumped engine (S_SS units; 0 runs to the end); ``rtol`` and ``atol`` are kept for the
    record (the grid has no tolerance), the step limits have no meaning on the grid.
    """
    duration, steady_window = options.duration, options.steady_window
    rtol, atol, threads, engine = options.rtol, options.atol, options.threads, options.engine
    steady_tolerance = options.steady_tolerance
    grid = system.model
    alpha = check_wave_damping(system.damping, system.model)
    kernel = _check_engine(engine, system.law)
    points = batch_points(system, wob, rpm)
    wob_arr, rpm_arr, torque_driven = points.wob, points.rpm, points.torque_driven
    omega_1 = grid.first_frequency()
    duration, default_window = run_times(system, duration, None)
    steady_window = default_window if steady_window is None else float(steady_window)
    window_given = steady_window != default_window
    check_window(duration, steady_window)
    dt = grid.time_step
    steps = check_wave_steps(grid, duration)
    check_window_samples(steady_window, None, dt, window_given, duration)
    window_steps = int(round(steady_window / dt))
    bit_max, bit_min, top_mean = (np.full(wob_arr.size, np.nan) for _ in range(3))
    status = np.zeros(wob_arr.size, dtype=np.int64)
    taken = np.zeros(wob_arr.size, dtype=np.int64)
    steady = 0.0 if torque_driven else float(steady_tolerance)
    engines = set()
    cancelled = threading.Event()

    def run_point(k: int) -> None:
        point = system.at(wob=float(wob_arr[k]), **({} if torque_driven else {"rpm": rpm_arr[k]}))
        point_grid = point.model  # its contacts at the point's weight on bit (StringContacts)
        top = top_boundary(point, point_grid)
        try:
            run = march(point_grid, top, point.law, point.wob, point.bit_radius, alpha, steps,
                        window_start=steps - window_steps + 1, track_energy=False,
                        steady_tolerance=steady, cycle_gap=0.5 * math.pi / omega_1,
                        kernel=kernel, should_stop=cancelled.is_set)  # fmt: skip
        except SolverError:
            status[k] = 1
            return
        except RunCancelled:
            return
        summary = run.summary
        engines.add(run.engine)
        taken[k] = int(summary["steps"])
        window = summary["window_steps"]
        bit_max[k] = summary["bit_speed_max"]
        bit_min[k] = summary["bit_speed_min"]
        top_mean[k] = summary["top_speed_sum"] / window if window else math.nan

    start = time.perf_counter()
    workers = batch_threads(threads, wob_arr.size)
    if workers == 1:
        for k in range(wob_arr.size):
            run_point(k)
    else:  # the compiled stepping releases the GIL: points run side by side
        with ThreadPoolExecutor(max_workers=workers) as pool:
            try:
                list(pool.map(run_point, range(wob_arr.size)))
            except BaseException:  # Ctrl-C: the other points stop at their next chunk
                cancelled.set()
                raise
    engine = "wave-python" if "python" in engines else "wave"
    elapsed = time.perf_counter() - start
    reference = top_mean if torque_driven else rpm_arr * RPM_TO_RAD_S
    with np.errstate(invalid="ignore", divide="ignore"):
        severity = np.where(status == 0, severity_of_extremes(bit_max, bit_min, reference), np.nan)
    ended = np.where((taken < steps) & (status == 0), taken * dt, float(duration))
    return BatchResults(
        wob_arr, rpm_arr, severity, bit_max, bit_min, top_mean, taken,
        np.zeros(wob_arr.size, dtype=np.int64), status, engine, float(duration),
        float(steady_window), float(rtol), float(atol), elapsed, ended, steady,
    )  # fmt: skip
