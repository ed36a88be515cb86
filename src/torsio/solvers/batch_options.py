"""The options of a batch of runs (severity maps, sweeps), validated once.

:class:`BatchOptions` travels from :func:`torsio.solvers.batch.simulate_batch` (or a map's
:class:`torsio.analysis.map_options.MapOptions`) to the model's batch engine unchanged;
each engine reads the fields that apply to it (the wave grid has no tolerances).

Examples
--------
>>> BatchOptions(rtol=1e-6).replace(steady_tolerance=0.0).steady_tolerance
0.0
>>> BatchOptions(rtol=-1.0)
Traceback (most recent call last):
...
torsio.errors.ConfigError: rtol: expected a positive tolerance, got -1.0
"""

from __future__ import annotations

import math
from typing import Any

import attrs

from torsio.errors import ConfigError
from torsio.solvers.batch_results import DEFAULT_STEADY_TOLERANCE, check_steady_tolerance

__all__ = [
    "DEFAULT_ATOL",
    "DEFAULT_MAX_STEPS",
    "DEFAULT_RTOL",
    "ENGINES",
    "BatchOptions",
    "batch_threads",
]

ENGINES = ("auto", "compiled", "numba", "numpy", "scipy")
"""Names accepted by ``simulate_batch(engine=...)`` (``"numba"`` is ``"compiled"``)."""

DEFAULT_RTOL = 1e-5
"""Default relative tolerance of the batch engine (see ``docs/performance.md`` for the
convergence study that chose it: |dS_SS| < 1e-3 against rtol = 1e-8 runs)."""

DEFAULT_ATOL = 1e-6
"""Default absolute tolerance [rad, rad/s]."""

DEFAULT_MAX_STEPS = 2_000_000
"""Accepted steps allowed per point before the point is reported as failed."""


def _tolerance(key: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ConfigError(key, f"expected a positive tolerance, got {value!r}")
    if not (math.isfinite(value) and value > 0):
        raise ConfigError(key, f"expected a positive tolerance, got {value!r}")
    return float(value)


def _optional_time(key: str, value: Any) -> float | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ConfigError(key, f"expected a positive time in s, got {value!r}")
    if not (math.isfinite(value) and value > 0):
        raise ConfigError(key, f"expected a positive time in s, got {value!r}")
    return float(value)


def _count(value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ConfigError("max_steps", f"expected a whole number of steps >= 1, got {value!r}")
    return int(value)


def _threads(value: Any) -> int | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ConfigError("threads", f"expected a number of threads >= 1, got {value!r}")
    return int(value)


@attrs.frozen
class BatchOptions:
    """How a batch of runs from rest is integrated and read.

    Attributes
    ----------
    duration, steady_window : float or None
        Run length and steady-state window [s]; None: the defaults of
        :func:`torsio.analysis.severity.run_times` (40 and 15 first-mode periods).
    rtol, atol : float
        Per-point local error tolerances (relative; absolute in rad, rad/s and the
        controller states' units).
    max_step : float or None
        Largest step [s]; None: a quarter of the first natural period.
    max_steps : int
        Accepted steps allowed per point before it is reported as failed.
    engine : str
        One of :data:`ENGINES` for the lumped models (each model's batch engine checks the
        names it takes).
    threads : int or None
        Threads of the compiled engine (None: numba's default).
    steady_tolerance : float
        End a run once on a cycle that cannot move S_SS by more than this (0: never).
    """

    duration: float | None = attrs.field(
        default=None, converter=lambda v: _optional_time("duration", v)
    )
    steady_window: float | None = attrs.field(
        default=None, converter=lambda v: _optional_time("steady_window", v)
    )
    rtol: float = attrs.field(default=DEFAULT_RTOL, converter=lambda v: _tolerance("rtol", v))
    atol: float = attrs.field(default=DEFAULT_ATOL, converter=lambda v: _tolerance("atol", v))
    max_step: float | None = attrs.field(
        default=None, converter=lambda v: _optional_time("max_step", v)
    )
    max_steps: int = attrs.field(default=DEFAULT_MAX_STEPS, converter=_count)
    engine: str = "auto"
    threads: int | None = attrs.field(default=None, converter=_threads)
    steady_tolerance: float = attrs.field(
        default=DEFAULT_STEADY_TOLERANCE, converter=check_steady_tolerance
    )

    def replace(self, **changes: Any) -> BatchOptions:
        """These options with ``changes`` (validated like the others)."""
        return attrs.evolve(self, **changes)


def batch_threads(threads: int | None, tasks: int) -> int:
    """Threads for ``tasks`` independent runs that release the GIL: ``threads``, else
    numba's thread count on the main thread and one off it (a thread of a pool, a Dask
    worker), at most one a task."""
    import threading

    if threads is None:
        if threading.current_thread() is not threading.main_thread():
            return 1
        try:
            import numba
        except ImportError:  # pragma: no cover - plain Python holds the GIL anyway
            return 1
        threads = numba.get_num_threads()
    return max(1, min(int(threads), tasks))
