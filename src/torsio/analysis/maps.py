"""Severity maps: S_SS over a grid of weight on bit x rotary speed, and over Pi_1 x Pi_2.

:func:`severity_map` runs the batch engine (:mod:`torsio.solvers.batch`) over every point
of a grid, in chunks on any executor (:mod:`torsio.analysis.sweep`), then locates the
critical weight on bit of each rotary speed with extra runs, and adds the linear
stability boundary (:mod:`torsio.analysis.stability`). :func:`dimensionless_map` does the
same over the groups of Eq. 11, Pi_1 = Omega/omega_1 and Pi_2 = W_ob R_bit/k_eq.

Conventions
-----------
``severity[i][j]`` is S_SS at ``rpm[i]`` and ``wob[j]`` (the JSON layout of
``torsio map --json``); both axes are strictly increasing.

Classification of each point:

* ``stable``: S_SS <= :data:`STICK_SLIP_THRESHOLD` (0.05): the bit speed swings by
  less than +-5 % of Omega over the steady window (steady rotation, or a
  transient that has almost died out);
* ``stick-slip``: :data:`STICK_SLIP_THRESHOLD` < S_SS <= threshold: a sustained
  torsional oscillation;
* ``severe``: S_SS > threshold (the paper's 0.8 by default).

Critical weight on bit W_ob,cr(Omega), per rotary speed (the paper's Fig. 6):
the lowest weight on bit above which the vibration is severe. On the grid row,
j* is the first index from which every point up to the largest weight on bit is
severe. Then

* no severe point at the largest weight on bit: W_ob,cr, if any, is above the grid
  (``null``, status ``"none"``, bound ``"above"``, shown as "> wob[-1]");
* j* = 0 (severe over the whole row): W_ob,cr <= wob[0] (``null``, status
  ``"below_range"``, bound ``"below"``, shown as "≤ wob[0]"); no value is invented;
* otherwise the cell [wob[j*-1], wob[j*]] is bisected ``refine`` times with extra
  runs (mid-point severe: keep the lower half, else the upper half) and
  W_ob,cr is the middle of the final bracket, within +- (wob[j*] - wob[j*-1]) /
  2^(refine+1); status ``"bisected"`` (``"grid"`` when refine = 0).

Bisection finds where S_SS crosses the threshold, which at the stick-slip onset is
usually a jump; if S_SS is not monotonic inside the cell it finds one crossing.

Examples
--------
>>> from torsio.examples import builtin_config
>>> system = builtin_config().system(strategy="A")
>>> result = severity_map(system, wob=[50e3, 150e3], rpm=[60.0, 120.0], refine=2)
>>> result.severity.round(2).tolist()
[[0.0, 1.32], [0.0, 0.0]]
>>> result.classification().tolist()
[['stable', 'severe'], ['stable', 'stable']]
>>> [None if w != w else round(float(w) / 1e3, 1) for w in result.critical_wob]
[87.5, None]
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from torsio.analysis.budget import check_batch_work
from torsio.analysis.map_options import MapOptions
from torsio.analysis.map_results import MapInterrupted, SeverityMap
from torsio.analysis.map_runs import (
    MapFailed,
    MapWork,
    _axis,
    _chunk_task,
    _default_chunk_size,
    check_grid_size,
    drive_map,
)
from torsio.analysis.sweep import (
    ExecutorSpec,
    worker_count,
)
from torsio.analysis.time_scales import check_time_scales
from torsio.errors import ConfigError
from torsio.model.contacts import carried_contacts
from torsio.physics.system import System
from torsio.solvers.batch import (
    simulate_batch,
)
from torsio.solvers.batch_options import DEFAULT_MAX_STEPS
from torsio.units import RPM_TO_RAD_S

__all__ = ["dimensionless_map", "severity_map"]


def _scales(system: System) -> tuple[float, float]:
    """(k_eq [N m/rad], omega_1 [rad/s]) of the System's model (its protocol's numbers)."""
    from torsio.model.modal import first_natural_frequency

    return float(system.model.equivalent_stiffness), first_natural_frequency(system.model)


def severity_map(
    system: System,
    wob: Any,
    rpm: Any,
    options: MapOptions | None = None,
    *,
    executor: ExecutorSpec = None,
    progress: bool | Callable[[int, int], None] | None = None,
    **values: Any,
) -> SeverityMap:
    """S_SS over the grid ``rpm`` x ``wob``, its classification and critical curve.

    Parameters
    ----------
    system : System
        Model, damping and bit-rock law (its own operating point is ignored).
    wob : array_like
        Weights on bit [N], >= 0, strictly increasing.
    rpm : array_like
        Surface rotary speeds [rpm], > 0, strictly increasing.
    options : MapOptions, optional
        How every point runs and how the map reads it (run length and window,
        thresholds, bisection, tolerances, engine, steady-cycle ends, failures):
        :class:`torsio.analysis.map_options.MapOptions`; default its defaults.
        Every run starts from rest.
    executor : None, int, str or concurrent.futures.Executor
        Serial (default), N local processes, a Dask scheduler address, or an
        executor (:mod:`torsio.analysis.sweep`). The result does not depend on it.
    progress : bool or callable, optional
        ``progress(done_runs, total_runs)`` after each chunk; True shows the
        points done on stderr (a bar on a terminal, else a line every 4 s). The total
        is fixed from the start: the grid points plus ``refine`` bisection runs per
        rpm (runs a row turns out not to need are counted as done when that is known).
    **values
        Fields of :class:`MapOptions` given by name (``refine=2``, ``rtol=1e-6``, ...),
        on top of ``options``.

    Returns
    -------
    SeverityMap

    Raises
    ------
    MapInterrupted
        On Ctrl-C; its ``partial`` map has ``complete = False``.
    """
    from torsio.analysis.severity import run_times
    from torsio.analysis.stability import stability_boundary
    from torsio.plugins import describe_bit_law

    options = MapOptions.of(options, values)
    wob = _axis("wob", wob, positive=False)
    rpm = _axis("rpm", rpm, positive=True)
    check_grid_size(rpm.size, wob.size)
    duration, steady_window = run_times(system, options.duration, options.steady_window)
    k_eq, omega1 = _scales(system)
    check_batch_work(system, wob, duration, options.rtol, 2.0 * math.pi / omega1, DEFAULT_MAX_STEPS)
    check_time_scales(system, duration)
    serial = executor is None or executor == "serial"
    batch = options.batch_options(duration, steady_window, None if serial else 1)
    boundary = system.top.boundary(system)
    if not boundary.held and not math.isfinite(boundary.set_speed):
        raise ConfigError(
            "rpm",
            f"a map runs over rotary (set) speeds, and the top drive "
            f"{getattr(system.top, 'name', system.top)!r} has none (its speed follows from "
            "the torque balance); map with a speed-controlled top drive or run "
            "torsio.solvers.batch.simulate_batch(system, wob) over weights on bit",
        )
    # validate options (engine, tolerances) here rather than in every worker
    engine_name = simulate_batch(system, np.empty(0), np.empty(0), batch).engine
    scales: dict[str, Any] = {  # what every map of this call shares, partial or not
        "wob": wob,
        "rpm": rpm,
        "threshold": options.threshold,
        "stick_slip_threshold": options.stick_slip_threshold,
        "k_eq": k_eq,
        "omega1": omega1,
        "bit_radius": system.bit_radius,
        "dimensionless": False,
        "engine": engine_name,
    }
    points = rpm.size * wob.size
    size = options.chunk_size or _default_chunk_size(
        points, worker_count(executor), serial, system.model.dofs
    )
    info: dict[str, Any] = {
        "model": {
            "name": getattr(system.string, "name", "") or "",
            "strategy": system.model.strategy,
            "dofs": system.model.dofs,
        },
        "law": repr(system.law),
        "damping": repr(system.damping),
        "duration": duration,
        "steady_window": steady_window,
        "rtol": options.rtol,
        "atol": options.atol,
        "refine": options.refine,
        "initial_state": "rest",
        "steady_tolerance": options.steady_tolerance,
    }
    no_friction = carried_contacts(getattr(system.model, "contacts", None))[1]
    if no_friction is not None:
        info["contacts_warning"] = no_friction
    solver = f"the batch solver ({engine_name} engine, bit-rock law {describe_bit_law(system.law)})"
    work = MapWork(_chunk_task, system, batch, size, solver)
    grid = drive_map(work, scales, info, options, executor=executor, progress=progress)
    if system.model.linearizable:
        linear_wob = stability_boundary(system, rpm).critical_wob
    else:  # e.g. the distributed model: no linearization (yet)
        linear_wob = np.full(rpm.shape, np.nan)
    return attrs.evolve(grid, stability_wob=linear_wob)


def dimensionless_map(
    system: System,
    pi1: Any,
    pi2: Any,
    options: MapOptions | None = None,
    *,
    executor: ExecutorSpec = None,
    progress: bool | Callable[[int, int], None] | None = None,
    **values: Any,
) -> SeverityMap:
    """S_SS over the grid Pi_1 x Pi_2 (Eq. 11) of ``system``.

    Pi_1 = Omega / omega_1 and Pi_2 = W_ob R_bit / k_eq (ERRATA 3) map linearly to
    rpm and weight on bit for a given System, so this is :func:`severity_map`
    on the corresponding grid (same options); ``severity[i][j]`` is at
    ``pi1[i]``, ``pi2[j]`` and the map's ``critical_pi2`` is the dimensionless
    critical curve.

    Examples
    --------
    >>> from torsio.examples import builtin_config
    >>> system = builtin_config().system(strategy="A")
    >>> result = dimensionless_map(system, pi1=[5.0, 12.0], pi2=[10.0, 60.0], refine=0)
    >>> result.pi1.round(3).tolist(), result.pi2.round(3).tolist()
    ([5.0, 12.0], [10.0, 60.0])
    >>> result.classification().tolist()
    [['stable', 'severe'], ['stable', 'severe']]
    """
    chosen = MapOptions.of(options, values)
    pi1_axis = _axis("pi1", pi1, positive=True)
    pi2_axis = _axis("pi2", pi2, positive=False)
    k_eq, omega1 = _scales(system)
    rpm = pi1_axis * omega1 / RPM_TO_RAD_S
    wob = pi2_axis * k_eq / system.bit_radius
    try:  # the map over rpm x wob, its axes in the dimensionless groups
        grid = severity_map(system, wob, rpm, chosen, executor=executor, progress=progress)
    except (MapInterrupted, MapFailed) as exc:
        exc.partial = attrs.evolve(exc.partial, dimensionless=True)
        raise
    return attrs.evolve(grid, dimensionless=True)
