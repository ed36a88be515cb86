"""Many operating points of the distributed model: what maps run for the ``wave`` strategy.

:func:`simulate_wave_batch` is what :func:`torsio.solvers.batch.simulate_batch` hands a
System with a :class:`torsio.model.wave.WaveModel` to. Every point starts from rest and
runs the compiled characteristic stepping (:mod:`torsio.solvers.characteristics`) on the
fixed grid (no tolerances: ``rtol`` and ``atol`` are kept for the record only); S_SS takes
the bit-speed extremes over every step of the window. The engine is ``"wave"`` (the law's
compiled kernel) or ``"wave-python"`` (a law without one).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from torsio.analysis.severity import default_times
from torsio.errors import SolverError
from torsio.model.wave import check_wave_damping, first_frequency
from torsio.solvers.batch_results import BatchResults, batch_points
from torsio.solvers.wave_march import march
from torsio.solvers.wave_top import top_boundary


def wave_scales(grid: Any) -> tuple[float, float]:
    """(k_eq [N m/rad], omega_1 [rad/s]) of the continuum on the grid.

    k_eq = 1 / sum(L_i / (G_i J_i)): the static stiffness seen at the bit with the top
    held (Eq. 9 for the continuous string); omega_1 the grid string's first exact mode
    (the rigid-BHA continuum with ``rigid_bha``).
    """
    return grid.static_stiffness, first_frequency(grid)


def simulate_wave_batch(
    system: Any,
    wob: Any,
    rpm: Any = None,
    duration: float | None = None,
    steady_window: float | None = None,
    rtol: float = math.nan,
    atol: float = math.nan,
    **ignored: Any,
) -> Any:
    """S_SS of the wave model at each (wob[k], rpm[k]); returns a ``BatchResults``."""
    grid = system.model
    alpha = check_wave_damping(system.damping)
    wob_arr, rpm_arr, torque_driven = batch_points(system, wob, rpm)
    if duration is None or steady_window is None:
        default_duration, default_window = default_times(wave_scales(grid)[1])
        duration = default_duration if duration is None else duration
        steady_window = default_window if steady_window is None else steady_window
    dt = grid.time_step
    steps = max(1, int(round(float(duration) / dt)))
    window_steps = max(1, int(round(float(steady_window) / dt)))
    out = np.full((wob_arr.size, 3), np.nan)
    status = np.zeros(wob_arr.size, dtype=np.int64)
    engine = "wave"
    start = time.perf_counter()
    for k in range(wob_arr.size):
        point = system.at(wob=float(wob_arr[k]), **({} if torque_driven else {"rpm": rpm_arr[k]}))
        top = top_boundary(point, grid)
        try:
            run = march(grid, top, point.law, point.wob, point.bit_radius, alpha, steps,
                        window_start=steps - window_steps + 1, track_energy=False)  # fmt: skip
        except SolverError:
            status[k] = 1
            continue
        summary = run.summary
        engine = "wave" if run.engine == "numba" else "wave-python"
        out[k] = (
            summary["bit_speed_max"],
            summary["bit_speed_min"],
            summary["top_speed_sum"] / summary["window_steps"],
        )
    elapsed = time.perf_counter() - start
    reference = out[:, 2] if torque_driven else rpm_arr * (math.pi / 30.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        severity = np.where(status == 0, (out[:, 0] - out[:, 1]) / (2.0 * reference), np.nan)
    return BatchResults(
        wob_arr, rpm_arr, severity, out[:, 0], out[:, 1], out[:, 2],
        np.full(wob_arr.size, steps, dtype=np.int64), np.zeros(wob_arr.size, dtype=np.int64),
        status, engine, float(duration), float(steady_window), float(rtol), float(atol), elapsed,
    )  # fmt: skip
