"""A search along one parameter whose misfit is not smooth (the break-free moment).

The static friction factor and the threshold speed decide when each part of the string
breaks free; the surface torque after that moment moves with them in steps, so a
finite-difference gradient can point anywhere. Before the least squares, each such
parameter is searched alone (the others held): the misfit on a grid over a bracket,
then a bounded Brent search (scipy.optimize.minimize_scalar) between the grid points
that flank the best one.

Examples
--------
>>> value, calls = line_search(lambda x: abs(x - 0.37) + 0.1, 0.3, (0.2, 0.6))
>>> round(value, 3), calls <= 40
(0.37, True)
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.optimize import minimize_scalar

__all__ = ["NON_SMOOTH", "line_search"]

NON_SMOOTH = ("friction_static", "threshold_speed")
"""Fittable names (the last part of a key) searched alone before the least squares."""

GRID_POINTS = 7


def line_search(
    cost: Callable[[float], float], start: float, bracket: tuple[float, float]
) -> tuple[float, int]:
    """The value in ``bracket`` where ``cost`` is least (grid, then Brent), and the
    number of calls; ``start`` is on the grid."""
    grid = np.unique(np.append(np.linspace(*bracket, GRID_POINTS), start))
    costs = [cost(float(x)) for x in grid]
    best = int(np.argmin(costs))
    low = grid[max(best - 1, 0)]
    high = grid[min(best + 1, grid.size - 1)]
    tolerance = 1e-3 * max(abs(grid[best]), 1e-6)
    result = minimize_scalar(
        cost, bounds=(low, high), method="bounded", options={"xatol": tolerance}
    )
    calls = len(grid) + int(result.nfev)
    if float(result.fun) <= costs[best]:
        return float(result.x), calls
    return float(grid[best]), calls
