"""The time step of the characteristic grid: whole cells per section within a tolerance.

Each section's travel time L/c is rounded to a whole number of steps; :func:`choose_time_step`
takes the largest step at most the one asked for whose rounding stays within the
travel-time tolerance, within the :data:`MAX_CELLS` limit, and says so when no such grid
exists (:mod:`torsio.model.wave` builds the grid from it); :func:`drag_lumping` places the
distributed drag on its nodes.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.errors import ConfigError

MAX_CELLS = 200_000
"""Largest number of cells a wave grid may have (memory and run time grow with it)."""


def choose_time_step(
    travel_times: np.ndarray, max_time_step: float, tolerance: float, max_cells: int = MAX_CELLS
) -> tuple[float, np.ndarray]:
    """The largest dt <= ``max_time_step`` whose rounding of travel times stays within tolerance.

    Candidates make one section's travel time a whole number of steps (tau_k / n), none
    finer than the ``max_cells`` limit allows. Among those down to four times finer
    than ``max_time_step`` the largest meeting ``tolerance`` is taken; if none does, the
    search goes on down to the cell limit (a step below 2 tolerance min(tau) always
    meets it). Returns (dt, cells per section); a ConfigError on
    ``discretization.travel_time_tolerance`` when no grid within the cell limit meets it.

    >>> dt, cells = choose_time_step(np.array([1.0, 0.3]), 1.0, 1e-3)
    >>> float(dt), cells.tolist()
    (0.1, [10, 3])
    """
    taus = np.asarray(travel_times, dtype=float)
    finest = taus.sum() / max_cells  # the smallest step within the cell limit
    near = []
    for tau in taus:
        first = max(1, math.ceil(tau / max_time_step - 1e-12))
        near.append(tau / np.arange(first, 4 * first + 8))
    steps = np.sort(np.concatenate(near))[::-1]
    steps = steps[(steps <= max_time_step * (1 + 1e-12)) & (steps >= finest)]
    found = _first_within(steps, taus, tolerance)
    if found is not None:
        return found
    lowest = float(steps[-1]) if steps.size else min(max_time_step, float(taus.max()))
    best = (math.inf, 0.0)
    for block in _candidate_blocks(taus, lowest, finest):
        found = _first_within(block, taus, tolerance)
        if found is not None:
            return found
        errors = _rounding_errors(block, taus)
        if errors.size and errors.min() < best[0]:
            best = (float(errors.min()), float(block[int(np.argmin(errors))]))
    raise ConfigError(
        "discretization.travel_time_tolerance",
        f"no grid of at most {max_cells:,} cells rounds every section's travel time L/c to "
        f"whole steps within {tolerance:g} (the closest: {best[0]:.3g} at a time step of "
        f"{best[1]:.3g} s); expected a tolerance of at least {best[0]:.3g}",
    )


def _rounding_errors(steps: np.ndarray, taus: np.ndarray) -> np.ndarray:
    """Largest relative travel-time change of each candidate step."""
    cells = np.maximum(1, np.round(taus[None, :] / steps[:, None]))
    return (np.abs(cells * steps[:, None] - taus[None, :]) / taus[None, :]).max(axis=1)


def _first_within(
    steps: np.ndarray, taus: np.ndarray, tolerance: float
) -> tuple[float, np.ndarray] | None:
    """(dt, cells) of the first (largest) of ``steps`` within ``tolerance``, if any."""
    if not steps.size:
        return None
    good = np.flatnonzero(_rounding_errors(steps, taus) <= tolerance)
    if not good.size:
        return None
    dt = float(steps[int(good[0])])
    return dt, np.maximum(1, np.round(taus / dt)).astype(int)


def _candidate_blocks(taus: np.ndarray, below: float, finest: float, size: int = 20_000) -> Any:
    """Candidate steps tau_k / n in ``[finest, below)``, largest first, in blocks."""
    top = below
    while top > finest:
        bottom = max(finest, top / 2.0)
        parts = []
        for tau in taus:
            low = max(1, math.floor(tau / top))
            high = math.floor(tau / bottom)
            n = np.arange(low, high + 1)
            part = tau / n
            parts.append(part[(part < top) & (part >= bottom)])
        steps = np.sort(np.concatenate(parts))[::-1]
        for start in range(0, steps.size, size):
            yield steps[start : start + size]
        top = bottom


def drag_lumping(cells: int, spacing: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes of a section of ``cells`` cells that carry its drag, and their shares [cells].

    The drag of the section (alpha rho J per unit length, cells c dt long) is lumped into
    point dampers at nodes 0, k, 2k, ... and the last node (k = ``spacing``), each taking
    half of the cells on either side (the trapezoidal rule on that partition): the
    shares add up to ``cells``. A share s gives the damper c = alpha Z s dt [N m s/rad].

    >>> nodes, shares = drag_lumping(10, 4)
    >>> nodes.tolist(), shares.tolist()
    ([0, 4, 8, 10], [2.0, 4.0, 3.0, 1.0])
    >>> drag_lumping(3, 1)[1].tolist()  # spacing 1: every node, half shares at the ends
    [0.5, 1.0, 1.0, 0.5]
    """
    nodes = np.arange(0, cells + 1, spacing)
    if nodes[-1] != cells:
        nodes = np.append(nodes, cells)
    gaps = np.diff(nodes).astype(float)
    shares = np.zeros(nodes.size)
    shares[:-1] += 0.5 * gaps
    shares[1:] += 0.5 * gaps
    return nodes, shares
