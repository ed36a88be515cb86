"""The local stage of a fit: from one start to the nearest minimum of the misfit.

Each non-smooth parameter (a static friction factor, the threshold speed: the break-free
moment moves with them in steps, :mod:`torsio.calibration.search`) is first searched alone
over [start / 2, 2 start] within its admissible range, the others held; then every
parameter moves together by least squares (scipy.optimize.least_squares, trust-region
reflective, finite differences of relative step :data:`DIFF_STEP`) in the gap variables
y = A x, in which each fitted static factor is replaced by its excess over the sliding one
(mu_s - mu_d >= 0), so that a box bound keeps the fit in the admissible set mu_d <= mu_s.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import attrs
import numpy as np
from scipy.optimize import least_squares

from torsio.calibration.search import NON_SMOOTH, line_search

__all__ = ["DIFF_STEP", "LocalFit", "admissible_floor", "local_fit", "static_pairs"]

DIFF_STEP = 5e-3
"""Relative step of the finite-difference Jacobian (a step wider than the misfit's
fine structure at the break-free moment)."""

MAX_EVALUATIONS = 60
"""The least squares' largest number of misfit evaluations (each runs every recording)."""


@attrs.frozen(eq=False)
class LocalFit:
    """A minimum of the misfit: the parameters, their Jacobian there, the misfit's sum of
    squares [N^2 m^2], the optimizer's word and the start it came from."""

    values: np.ndarray
    jacobian: np.ndarray
    cost: float
    message: str
    start: np.ndarray


def static_pairs(names: Sequence[str]) -> list[tuple[int, int]]:
    """(static, sliding) indices of the factors of a stretch fitted together."""
    pairs = []
    for k, name in enumerate(names):
        dynamic = name.replace("friction_static", "friction_dynamic")
        if dynamic != name and dynamic in names:
            pairs.append((k, list(names).index(dynamic)))
    return pairs


def admissible_floor(family: Any, names: Sequence[str], x: np.ndarray) -> np.ndarray:
    """The least value of each parameter at ``x``: its lower bound, and a static factor
    not below the sliding one of its stretch (fitted: its value in ``x``; held: the
    configured one)."""
    floor = np.array([family.lower_bound(n) for n in names])
    for k, name in enumerate(names):
        dynamic = name.replace("friction_static", "friction_dynamic")
        if dynamic == name:
            continue
        sliding = x[names.index(dynamic)] if dynamic in names else family.values[dynamic]
        floor[k] = max(floor[k], float(sliding))
    return floor


def _search_non_smooth(misfit: Any, x: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """Each non-smooth parameter searched alone over [x / 2, 2 x] within its admissible
    range (a static factor not below the sliding one), the others held."""
    x = x.copy()
    names = list(misfit.names)
    for k, name in enumerate(names):
        if name.split(".")[-1] not in NON_SMOOTH:
            continue
        floor = admissible_floor(misfit.family, names, x)[k]

        def cost(value: float, k: int = k) -> float:
            trial = x.copy()
            trial[k] = value
            return misfit.cost(trial)

        low = min(max(0.5 * x[k], floor), upper[k])
        high = max(min(2.0 * x[k], upper[k]), low)
        if high > low:
            x[k], _ = line_search(cost, float(np.clip(x[k], low, high)), (low, high))
    return x


def local_fit(misfit: Any, start: np.ndarray, upper: np.ndarray) -> LocalFit:
    """The minimum of ``misfit`` nearest ``start`` (module documentation), each parameter
    at most ``upper``."""
    names = list(misfit.names)
    x0 = np.minimum(np.maximum(start, admissible_floor(misfit.family, names, start)), upper)
    x0 = _search_non_smooth(misfit, x0, upper)
    pairs = static_pairs(names)
    gaps = np.eye(len(names))
    for static, dynamic in pairs:
        gaps[static, dynamic] = -1.0
    lower = np.array([misfit.family.lower_bound(n) for n in names])
    lower[[static for static, _ in pairs]] = 0.0  # the excess mu_s - mu_d
    y0 = np.clip(gaps @ x0, lower, upper)
    solution = least_squares(
        lambda y: misfit(np.linalg.solve(gaps, y)),
        y0,
        bounds=(lower, upper),
        x_scale=np.where(np.abs(y0) > 0.0, np.abs(y0), np.maximum(np.abs(x0), 1e-3)),
        diff_step=DIFF_STEP,
        method="trf",
        xtol=1e-8,
        ftol=1e-10,
        gtol=1e-10,
        max_nfev=MAX_EVALUATIONS,
    )
    return LocalFit(
        values=np.linalg.solve(gaps, solution.x),
        jacobian=solution.jac @ gaps,  # d r / d x = d r / d y  d y / d x
        cost=float(np.sum(solution.fun**2)),
        message=str(solution.message),
        start=np.asarray(start, dtype=float),
    )
