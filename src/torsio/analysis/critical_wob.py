"""The critical weight on bit of each rotary speed of a severity map (the paper's Fig. 6).

:func:`locate_critical_wob` finds, on each row of the grid, the lowest weight on bit
above which every point is severe, and narrows the cell it falls in by bisection with
extra runs (conventions in :mod:`torsio.analysis.maps`).
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np

from torsio.errors import SolverError
from torsio.solvers.batch_results import STATUS_MESSAGES, BatchPoints

__all__ = ["BisectionRuns", "locate_critical_wob"]


class BisectionRuns(Protocol):
    """What runs the bisection points of any engine (a torsional map's
    :class:`~torsio.analysis.map_runs.PointRunner`, an axial map's runs)."""

    def run(self, points: BatchPoints) -> np.ndarray:
        """Rows (S_SS, solver status, ...) of ``points``."""

    def skip(self, count: int) -> None:
        """Count ``count`` planned runs as done without running them."""


def locate_critical_wob(
    runner: BisectionRuns,
    wob: np.ndarray,
    rpm: np.ndarray,
    severity: np.ndarray,
    threshold: float,
    refine: int,
    on_failure: str,
) -> tuple[np.ndarray, tuple[str, ...], np.ndarray]:
    """W_ob,cr of each row of ``severity``, with extra runs to bisect its grid cell.

    Parameters
    ----------
    runner : BisectionRuns
        Runs the bisection points (unused when ``refine`` is 0).
    wob, rpm : ndarray
        Axes of the grid [N], [rpm].
    severity : ndarray, shape (len(rpm), len(wob))
        S_SS of the grid.
    threshold : float
        S_SS above which a point is severe.
    refine : int
        Bisection steps.
    on_failure : {"raise", "mark"}
        On a failed bisection run: raise, or mark the row ``"unresolved"``.

    Returns
    -------
    critical : ndarray, shape (n,)
        W_ob,cr [N]; NaN where it is not inside the grid (status ``"none"``: above
        the largest weight on bit if anywhere; ``"below_range"``: at or below the
        smallest; ``"unresolved"``).
    status : tuple of str
        ``"bisected"``, ``"grid"``, ``"below_range"``, ``"none"`` or ``"unresolved"``.
    bracket : ndarray, shape (n, 2)
        Final bracket [N] (NaN where not bracketed).
    """
    rows = severity.shape[0]
    critical = np.full(rows, np.nan)
    bracket = np.full((rows, 2), np.nan)
    labels: list[str] = []
    low = np.full(rows, np.nan)
    high = np.full(rows, np.nan)
    for i in range(rows):
        s = severity[i]
        if not np.isfinite(s).all():
            labels.append("unresolved")
            continue
        severe = s > threshold
        if not severe[-1]:
            labels.append("none")
            continue
        tail = np.flatnonzero(~severe)
        first = 0 if tail.size == 0 else int(tail[-1]) + 1
        if first == 0:
            labels.append("below_range")  # W_ob,cr <= wob[0]: no value is invented
            continue
        low[i], high[i] = wob[first - 1], wob[first]
        labels.append("bisected" if refine else "grid")
    active = np.flatnonzero(np.isfinite(low))
    if runner is not None:  # rows not bisected: their planned runs are done
        runner.skip(refine * (rows - active.size))
    for step in range(refine):
        if active.size == 0:
            break
        middle = 0.5 * (low[active] + high[active])
        speeds = rpm[active]
        result = runner.run(BatchPoints(middle, speeds))  # within the checked axes
        values = result[:, 0]
        failed = result[:, 1] != 0
        if failed.any() and on_failure == "raise":
            k = int(np.argmax(failed))
            raise SolverError(
                f"the batch solver failed at wob={middle[k]:g} N, "
                f"rpm={speeds[k]:g} while bisecting the critical weight on bit: "
                f"{STATUS_MESSAGES.get(int(result[k, 1]))}"
            )
        is_severe = values > threshold
        high[active] = np.where(is_severe, middle, high[active])
        low[active] = np.where(is_severe, low[active], middle)
        for index in np.flatnonzero(failed):
            labels[active[index]] = "unresolved"
            low[active[index]] = np.nan
        active = active[~failed]
        if runner is not None:  # rows given up: their remaining runs are done
            runner.skip((refine - step - 1) * int(failed.sum()))
    for i in range(rows):
        if math.isfinite(low[i]):
            bracket[i] = (low[i], high[i])
            critical[i] = 0.5 * (low[i] + high[i])
    return critical, tuple(labels), bracket
