"""Bounds on the work an analysis may start: tolerances, output size, integrator effort.

Every analysis that integrates (one transient run, a severity map) checks its inputs
here before it starts, so that a careless value ends in a clear
:class:`~torsio.errors.ConfigError` or :class:`~torsio.errors.SolverError` instead of a
silently wrong answer, an exhausted memory or a run that never ends:

* :func:`check_rtol`: a relative tolerance in :data:`RTOL_RANGE`. Above 1e-2 an
  error-controlled integrator no longer resolves a stick-slip cycle (``rtol = 10``
  reports S_SS = 8.5e-16 at a point whose S_SS is 1.16); below 1e-13 scipy raises
  it to 100 machine epsilons by itself.
* :func:`check_output_size`: the sampled time series must fit in half the free memory.
* :class:`EvaluationBudget`: caps the right-hand-side evaluations of one run.
* :func:`check_law_time_scale`: the bit-rock law's own time scale at sticking, the
  bit inertia over the law's slope at zero speed, must not be more than
  :data:`MAX_STIFFNESS_RATIO` times shorter than the run (a law that no integrator
  resolves in double precision, e.g. Tucker-Wang with a0 = 1e20).
* :func:`check_wave_steps`: a run of the distributed model (fixed steps of its grid)
  takes at least one step, at most :data:`MAX_WAVE_STEPS` of them and at most
  :data:`MAX_WAVE_WORK` node-steps; the error names the key that decides it (the
  duration, or the grid's time step).
* :func:`check_batch_work`: the same checks for the runs of a map, and a run length the
  batch engine's step limit can cover (a map and one run refuse the same inputs).

Examples
--------
>>> check_rtol(1e-6, "rtol")
1e-06
>>> check_rtol(10.0, "rtol")
Traceback (most recent call last):
...
torsio.errors.ConfigError: rtol: expected a relative tolerance in 1e-13..0.01, got 10.0 ...
"""

from __future__ import annotations

import math
import os
from typing import Any

import numpy as np

from torsio.errors import ConfigError, SolverError
from torsio.model.wave import DEFAULT_TRAVEL_TIME_TOLERANCE

__all__ = [
    "EVALUATIONS_PER_SAMPLE",
    "MAX_STIFFNESS_RATIO",
    "MAX_WAVE_STEPS",
    "MAX_WAVE_WORK",
    "MIN_EVALUATIONS",
    "RTOL_RANGE",
    "BudgetExceeded",
    "EvaluationBudget",
    "check_batch_work",
    "check_law_time_scale",
    "check_output_size",
    "check_rtol",
    "check_wave_steps",
    "most_fixed_steps",
]

RTOL_RANGE = (1e-13, 1e-2)
"""Relative tolerances accepted by the integrators (see the module documentation)."""

MIN_EVALUATIONS = 200_000
"""Right-hand-side evaluations every run may use, however few samples it asks for."""

EVALUATIONS_PER_SAMPLE = 50
"""Further evaluations allowed per output sample (the default run of the Ritto et al.
2017 string uses about 0.4 per sample at rtol = 1e-6 and 5 at rtol = 1e-10)."""

MAX_WAVE_STEPS = 2_000_000
"""Time steps one run of the distributed model may take: the step limit of a map point
(``torsio.solvers.batch_options.DEFAULT_MAX_STEPS``), for single runs and maps alike (2877 s of
run on the default grid of the Ritto et al. 2017 string, Delta t = 1.4386 ms)."""

MAX_WAVE_WORK = 5e10
"""Node-steps (grid nodes x time steps) one run of the distributed model may take: about
20 s of stepping at 0.4 ns a node-step (measured on 2 busy cores, grids of 1 094 to
157 241 nodes: 0.35-0.8 ns); the default run of the Ritto et al. 2017 string takes 2.3e8."""

MAX_STIFFNESS_RATIO = 1e10
"""Largest ratio of run length to the bit-rock law's time scale at sticking (about 1e4
for the Ritto et al. 2017 string)."""


def check_rtol(value: Any, key: str) -> float:
    """The relative tolerance ``value`` as a float, or a ConfigError naming ``key``."""
    low, high = RTOL_RANGE
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ConfigError(key, f"expected a relative tolerance in {low:g}..{high:g}, got {value!r}")
    number = float(value)
    if not (math.isfinite(number) and low <= number <= high):
        raise ConfigError(
            key,
            f"expected a relative tolerance in {low:g}..{high:g}, got {value!r} (a looser "
            "tolerance does not resolve stick-slip; a tighter one is below what double "
            "precision can honour)",
        )
    return number


def _available_memory() -> float | None:
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):  # pragma: no cover - not POSIX
        return None


def check_output_size(
    duration: float, step: float, columns: int, memory: float | None = None
) -> int:
    """Number of output samples of a run; ConfigError if its series would not fit.

    Parameters
    ----------
    duration, step : float
        Run length and output step [s].
    columns : int
        Floats stored per sample (all series of the results).
    memory : float, optional
        Bytes available (default: free physical memory); the series may use half.

    Examples
    --------
    >>> check_output_size(300.0, 0.01, 10, memory=1e9)
    30000
    >>> check_output_size(1e12, 0.04, 10, memory=1e9)
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: simulation.duration: a run of 1e+12 s sampled every 0.04 s ...
    """
    samples = duration / step
    needed = (samples + 1.0) * columns * 8.0
    memory = _available_memory() if memory is None else memory
    if not math.isfinite(needed) or (memory is not None and needed > 0.5 * memory):
        have = "" if memory is None else f"; {memory / 1e9:.3g} GB of memory is free"
        raise ConfigError(
            "simulation.output_step" if step < 1e-3 else "simulation.duration",
            f"a run of {duration:g} s sampled every {step:g} s has {samples:.3g} samples "
            f"whose series need {needed / 1e9:.3g} GB{have}; shorten the run or give a "
            "longer output step",
        )
    return max(1, math.ceil(samples * (1.0 - 1e-12)))


class BudgetExceeded(Exception):
    """Raised inside an integration when its :class:`EvaluationBudget` is spent."""


class EvaluationBudget:
    """Counts calls of a right-hand side and stops the run past ``limit`` of them.

    Wrap the right-hand side with :meth:`wrap`; the integrator then raises
    :class:`BudgetExceeded`, which :meth:`error` turns into a SolverError.

    Examples
    --------
    >>> budget = EvaluationBudget(2)
    >>> rhs = budget.wrap(lambda t, y: -y)
    >>> rhs(0.0, 1.0), rhs(0.0, 2.0)
    (-1.0, -2.0)
    >>> rhs(0.0, 3.0)
    Traceback (most recent call last):
    ...
    torsio.analysis.budget.BudgetExceeded: 2
    """

    def __init__(self, limit: int) -> None:
        self.limit = int(limit)
        self.used = 0
        self.time = 0.0

    @classmethod
    def for_samples(cls, samples: int) -> EvaluationBudget:
        """The budget of a run with ``samples`` output samples."""
        return cls(MIN_EVALUATIONS + EVALUATIONS_PER_SAMPLE * int(samples))

    def wrap(self, rhs: Any) -> Any:
        """``rhs`` counting its calls; raises BudgetExceeded past the limit."""

        def counted(t: float, y: Any) -> Any:
            self.used += 1
            self.time = t
            if self.used > self.limit:
                raise BudgetExceeded(self.limit)
            return rhs(t, y)

        return counted

    def error(self, method: str, duration: float, where: str) -> SolverError:
        """The SolverError to raise when the budget is spent."""
        return SolverError(
            f"the {method} integrator used its budget of {self.limit:,} right-hand-side "
            f"evaluations and reached only t = {self.time:.6g} s of {duration:.6g} s "
            f"({where}); the equations are too stiff or the run too long for it: check the "
            "bit-rock law's parameters, or try method='Radau' or a shorter run"
        )


def law_slope_at_rest(law: Any, wob: float, radius: float) -> float:
    """|d torque / d speed| of a bit-rock law at zero bit speed [N m s/rad]."""
    with np.errstate(all="ignore"):
        if hasattr(law, "slope"):
            slope = float(np.asarray(law.slope(0.0, wob, radius), dtype=float))
        else:
            step = 1e-6
            slope = float(
                (
                    np.asarray(law.torque(step, wob, radius))
                    - np.asarray(law.torque(-step, wob, radius))
                )
                / (2 * step)
            )
    return abs(slope) if not math.isnan(slope) else math.inf


def check_law_time_scale(system: Any, wob: float, duration: float) -> None:
    """ConfigError if the bit-rock law at ``wob`` [N] is too stiff for a run of ``duration`` [s].

    The time scale is the bit's inertia over the law's slope at zero speed; a run
    may last at most :data:`MAX_STIFFNESS_RATIO` of them.
    """
    slope = law_slope_at_rest(system.law, wob, system.bit_radius)
    if slope == 0.0:
        return
    bit_inertia = float(system.model.bit_inertia)
    scale = bit_inertia / slope
    if math.isfinite(scale) and scale > 0 and duration / scale <= MAX_STIFFNESS_RATIO:
        return
    name = getattr(system.law, "name", "") or type(system.law).__name__
    raise ConfigError(
        "bit_rock",
        f"the bit-rock law {name!r} {system.law!r} at wob = {wob:g} N and radius "
        f"{system.bit_radius:g} m has a slope of {slope:.3g} N m s/rad at zero speed: the bit "
        f"(inertia {bit_inertia:.3g} kg m^2) reacts within {scale:.3g} s, more than "
        f"{MAX_STIFFNESS_RATIO:.0e} times faster than the run of {duration:.4g} s can be "
        "integrated; check the law's parameters (e.g. a0, a1) and the bit radius",
    )


def most_fixed_steps(nodes: int, max_steps: int = MAX_WAVE_STEPS) -> float:
    """The most steps a fixed-step run on ``nodes`` nodes may take: at most ``max_steps``
    and at most :data:`MAX_WAVE_WORK` node-steps (the wave model's and the axial engine's
    runs alike).

    >>> most_fixed_steps(1), most_fixed_steps(100_000)
    (2000000.0, 500000.0)
    """
    return min(float(max_steps), MAX_WAVE_WORK / max(1, int(nodes)))


def check_wave_steps(
    grid: Any, duration: float, key: str = "simulation.duration", max_steps: int = MAX_WAVE_STEPS
) -> int:
    """Time steps of a run of ``duration`` [s] on the wave ``grid``; ConfigError if out of bounds.

    A run takes round(duration / dt) steps: at least one, at most ``max_steps`` and at
    most :data:`MAX_WAVE_WORK` node-steps. The error names ``key`` (the duration) when
    the run is too short, or too long even on the grid of the default time step; it names
    ``discretization.time_step`` when a shorter step than the default makes the work.

    Examples
    --------
    >>> from torsio.model.wave import WaveStrategy
    >>> from torsio.examples import ritto2017_string
    >>> grid = WaveStrategy().discretize(ritto2017_string())
    >>> check_wave_steps(grid, 306.0)
    212706
    >>> check_wave_steps(grid, 1e6)
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: simulation.duration: a run of 1e+06 s is 695,118,327 steps ...
    """
    dt = float(grid.time_step)
    nodes = int(grid.dofs)
    steps_float = float(duration) / dt
    if not steps_float >= 0.5:
        raise ConfigError(
            key,
            f"a run of {duration:g} s is shorter than one time step of the wave grid "
            f"({dt:g} s); expected a run of at least {dt:g} s",
        )
    most = most_fixed_steps(nodes, max_steps)
    if steps_float <= most + 0.5:
        return int(round(steps_float))
    longest = math.floor(most) * dt
    finest = max(duration / max_steps, math.sqrt(duration * nodes * dt / MAX_WAVE_WORK))
    limits = (
        f"more than a run may take ({max_steps:,} steps and {MAX_WAVE_WORK:g} node-steps, "
        "about 20 s of stepping)"
    )
    deciding = _deciding_grid_key(grid, duration, max_steps)
    if deciding is not None:
        hint = (
            f"expected a time step of at least about {finest:.3g} s for this run"
            if deciding == "discretization.time_step"
            else "expected a larger travel-time tolerance (the default "
            f"{DEFAULT_TRAVEL_TIME_TOLERANCE:g} gives a grid this run fits on)"
        )
        raise ConfigError(
            deciding,
            f"with the grid's time step of {dt:g} s ({nodes:,} nodes) a run of {duration:g} s "
            f"takes {steps_float:,.0f} steps and {steps_float * nodes:.3g} node-steps, {limits}; "
            f"{hint}, or a run of at most {longest:g} s on this grid",
        )
    raise ConfigError(
        key,
        f"a run of {duration:g} s is {steps_float:,.0f} steps of the wave grid's {dt:g} s "
        f"({nodes:,} nodes, {steps_float * nodes:.3g} node-steps), {limits}; expected a run "
        f"of at most {longest:g} s on this grid (or a longer discretization.time_step)",
    )


def _deciding_grid_key(grid: Any, duration: float, max_steps: int) -> str | None:
    """The grid's key that makes a run too long: None when the default grid is no coarser
    or too fine for it as well (the duration decides), else ``discretization.time_step`` or,
    when the time step alone would give a coarser grid, ``travel_time_tolerance``."""
    from torsio.model.wave import WaveStrategy

    dt = float(grid.time_step)
    default = WaveStrategy(rigid_bha=grid.rigid_bha).discretize(grid.string)
    fits = most_fixed_steps(default.dofs, max_steps) * float(default.time_step)
    if not dt < float(default.time_step) * (1 - 1e-9) or duration > fits:
        return None
    requested = grid.details.get("max_time_step_s")
    if requested is None:  # a grid built otherwise: its time step is what it has
        return "discretization.time_step"
    alone = WaveStrategy(time_step=requested, rigid_bha=grid.rigid_bha).discretize(grid.string)
    if float(alone.time_step) > dt * (1 + 1e-9):
        return "discretization.travel_time_tolerance"
    return "discretization.time_step"


def check_batch_work(
    system: Any, wob: Any, duration: float, rtol: Any, period: float, max_steps: int
) -> None:
    """ConfigError unless the runs of a map can be integrated as asked, before any starts.

    The runs of a map are held to the rules of a single run: ``rtol`` in
    :data:`RTOL_RANGE` and the law's time scale (:func:`check_law_time_scale`, at the
    largest weight on bit ``wob`` [N], the stiffest point for laws proportional to it).
    The batch engine takes steps of at most a quarter of the first-mode ``period`` [s]
    and at most ``max_steps`` of them, so a longer ``duration`` [s] is refused. The wave
    model's runs take the fixed steps of its grid (:func:`check_wave_steps`, checked
    first: it is the cause when a long run would also exceed the law's time-scale bound).
    """
    fixed_step = system.model.time_step  # None: the engine chooses its steps
    if fixed_step is not None:  # the wave model: fixed steps of its grid
        check_wave_steps(system.model, duration, "duration", max_steps)
    check_rtol(rtol, "rtol")
    if fixed_step is None and 4.0 * duration / period > max_steps:
        raise ConfigError(
            "duration",
            f"a run of {duration:g} s is {duration / period:.3g} periods of the first mode "
            f"({period:.3g} s); the batch engine takes steps of at most a quarter period and at "
            f"most {max_steps:,} per point, so no point could finish: shorten the run",
        )
    loads = np.asarray(wob, dtype=float)
    if loads.size:
        check_law_time_scale(system, float(loads.max()), duration)
