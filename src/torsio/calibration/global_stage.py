"""The global stage of a fit: the same answer from any sensible start.

A least-squares search finds the minimum nearest its start, and the misfit along a static
friction factor or the threshold speed has several (the break-free moment moves in
steps). So before the local stage (:mod:`torsio.calibration.local_stage`) the fit looks
over the whole admissible box:

* candidate starts: the closed forms (:mod:`torsio.calibration.start`), the
  configuration's values, and the least points of a scan of each non-smooth parameter
  over its physical range (:data:`SCAN_POINTS` values,
  :data:`~torsio.calibration.parameters.PHYSICAL_RANGES`; a static factor from the sliding
  one up; the other parameters at the closed forms);
* the :data:`MAX_STARTS` best distinct candidates (by their misfit) go through the local
  stage; the least minimum is the fit, and every other minimum found is kept with its
  misfit: one nearly as good is information (the data do not choose between them), which
  the results report (``alternatives``).

Examples
--------
>>> distinct([np.array([0.3, 0.2]), np.array([0.301, 0.2]), np.array([0.45, 0.2])], [0.05, 0.0])
[0, 2]
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from torsio.calibration.local_stage import LocalFit, admissible_floor, local_fit
from torsio.calibration.search import NON_SMOOTH

__all__ = ["MAX_STARTS", "SCAN_POINTS", "distinct", "global_fit"]

SCAN_POINTS = 12
"""Values of each non-smooth parameter the scan runs over its range."""

MAX_STARTS = 3
"""Candidate starts that go through the local stage."""


def distinct(candidates: Sequence[np.ndarray], spacing: Any) -> list[int]:
    """Indices of the candidates that differ from every earlier one by more than half the
    scan's ``spacing`` in some scanned parameter (spacing 0: not scanned, a smooth
    parameter that the local stage moves to its minimum from anywhere)."""
    kept: list[int] = []
    steps = np.asarray(spacing, dtype=float)
    half = np.where(steps > 0.0, 0.5 * steps, np.inf)
    for i, candidate in enumerate(candidates):
        if all(np.any(np.abs(candidate - candidates[j]) > half) for j in kept):
            kept.append(i)
    return kept


def _scan_values(family: Any, name: str, floor: float) -> np.ndarray:
    low, high = max(family.lower_bound(name), floor), family.upper_bound(name)
    if name.split(".")[-1] == "threshold_speed":  # over decades
        return np.geomspace(low, high, SCAN_POINTS)
    return np.linspace(low, high, SCAN_POINTS)


def _scan(misfit: Any, centre: np.ndarray) -> tuple[list[np.ndarray], list[float], np.ndarray]:
    """The scan's local minima (as full parameter vectors), their misfits and the scan
    spacing of each parameter."""
    names = list(misfit.names)
    points: list[np.ndarray] = []
    costs: list[float] = []
    spacing = np.zeros(len(names))
    for k, name in enumerate(names):
        if name.split(".")[-1] not in NON_SMOOTH:
            continue
        values = _scan_values(
            misfit.family, name, admissible_floor(misfit.family, names, centre)[k]
        )
        spacing[k] = float(np.max(np.diff(values)))
        trials = []
        for value in values:
            trial = centre.copy()
            trial[k] = value
            trials.append(trial)
        scan = [misfit.cost(t) for t in trials]
        for i, cost in enumerate(scan):
            if cost <= scan[max(i - 1, 0)] and cost <= scan[min(i + 1, len(scan) - 1)]:
                points.append(trials[i])
                costs.append(cost)
    return points, costs, spacing


def global_fit(
    misfit: Any, closed_form: np.ndarray, configured: np.ndarray, upper: np.ndarray
) -> tuple[LocalFit, tuple[LocalFit, ...]]:
    """The least minimum of ``misfit`` over the admissible box (module documentation),
    and the other minima the local stage found from the other starts."""
    names = list(misfit.names)
    starts = [closed_form, np.minimum(configured, upper)]
    starts = [np.maximum(s, admissible_floor(misfit.family, names, s)) for s in starts]
    costs = [misfit.cost(s) for s in starts]
    scanned, scan_costs, spacing = _scan(misfit, starts[0])
    starts += scanned
    costs += scan_costs
    order = np.argsort(costs, kind="stable")
    chosen = [int(order[i]) for i in distinct([starts[i] for i in order], spacing)]
    fits = [local_fit(misfit, starts[i], upper) for i in chosen[:MAX_STARTS]]
    fits.sort(key=lambda fit: fit.cost)
    return fits[0], tuple(fits[1:])
