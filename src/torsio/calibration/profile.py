"""The misfit along one fitted parameter: what the data allow, what each recording wants
on its own, and what a finer grid moves.

Parameter k moves by t along the path p(t) = best + t d on which the others follow their
conditional best values (linearized: d is the k-th column of (J^T J)^-1 scaled to 1 in k).
The path's offsets are geometric on each side, from half the Jacobian's sigma out to
:data:`SPAN` of the value (at least :data:`MIN_REACH` sigmas), :data:`PROFILE_POINTS` of
them, stopped at the admissible range's ends (mu_d <= mu_s, the physical range). At each
point the model runs once per recording, and three things are read from its torques:

* the misfit against the records, S(t): chi^2(t) = (S(t) - S_min) / (s^2 tau) is the
  statistical profile (:mod:`torsio.calibration.uncertainty`);
* each recording's own misfit: where it is least is that recording's value of the
  parameter, as if it were fitted alone; the spread between recordings is the part of the
  uncertainty the model's form leaves (a model that is not the rig reads each start-up a
  little differently);
* the misfit against the surface torque that each twin of the grid
  (:meth:`~torsio.calibration.parameters.SystemFamily.twins`: half the time step with
  contacts on every node, and twice the time step) gives at the best fit: where it is
  least is how far the fit's own grid misreads that grid, the discretization part (the
  larger of the two; noise-free: no record in it); on a lumped strategy, the continuum it
  approximates reads the records itself along the same path, and where its misfit is least
  is how far the lumping misreads them. Both wave twins are needed: measured on
  start-ups of the built-in deviated well made at 2.5e-4 s with contacts on every node,
  the default grid (6.9e-4 s) reads mu_s 0.010 low, while the shift to a grid of half its
  step is 0.002 and to one of twice its step 0.006 (docs/calibration.md).

Every side runs its full reach (or to the admissible range's end): the misfit against a
record or a twin is rough at the scale of the grid (the break-free moment moves in steps),
and a side stopped at the first rise would take a bump for the minimum.

Examples
--------
>>> values = np.array([0.1, 0.2, 0.3, 0.4])
>>> round(least(values, (values - 0.27) ** 2), 6)
0.27
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import attrs
import numpy as np

from torsio.calibration.objectives import residuals

__all__ = [
    "MIN_REACH",
    "PROFILE_POINTS",
    "SPAN",
    "Profile",
    "grid_twin",
    "least",
    "profile_parameter",
    "reader_twin",
]

PROFILE_POINTS = 10
"""Points of the path on each side of the best fit (at most)."""

SPAN = 0.25
"""How far the path reaches on each side, relative to the value (the model-form and grid
minima are sought within it)."""

Twins = Sequence[tuple[str, Callable[[np.ndarray, Sequence[np.ndarray]], float]]]
"""The twins of a fitted model: (name, its misfit [N^2 m^2] at a parameter vector given the
fitted model's torques there), made by :func:`grid_twin` and :func:`reader_twin`."""

MIN_REACH = 16.0
"""The least reach of the path, in the Jacobian's sigmas."""


@attrs.frozen(eq=False)
class Profile:
    """The misfit along one parameter (module documentation).

    Attributes
    ----------
    values : ndarray
        The parameter along the path, ascending, the best fit among them [its unit].
    chi2 : ndarray
        (S - S_min) / (s^2 tau) at each value.
    recording_values : tuple of float
        Where each recording's own misfit is least.
    twin_values : dict
        By twin's name, where the misfit against its torque is least (empty: no twin).
    open_low, open_high : bool
        The path reached the end of the admissible range with chi^2 < 4 on that side.
    """

    values: np.ndarray
    chi2: np.ndarray
    recording_values: tuple[float, ...]
    twin_values: dict[str, float]
    open_low: bool
    open_high: bool


def least(values: np.ndarray, costs: np.ndarray) -> float:
    """Where ``costs`` over ascending ``values`` is least: the vertex of the parabola
    through the least point and its neighbours, kept between them."""
    i = int(np.argmin(costs))
    if i == 0 or i == values.size - 1:
        return float(values[i])
    x, y = values[i - 1 : i + 2], costs[i - 1 : i + 2]
    a, b, _ = np.polyfit(x - x[1], y, 2)
    if a <= 0.0:
        return float(values[i])
    return float(np.clip(x[1] - b / (2.0 * a), x[0], x[2]))


def _offsets(sigma: float, reach: float) -> np.ndarray:
    """Geometric offsets from sigma / 2 to ``reach``."""
    first = min(0.5 * sigma, reach / 2 ** (PROFILE_POINTS - 1))
    return np.geomspace(first, reach, PROFILE_POINTS)


def grid_twin(objective: str, records: Sequence[Any]) -> Callable[..., float]:
    """A twin that made ``records`` (the recordings with its torque at the best fit): its
    misfit is the fitted model's against them, least where the fitted model reads the
    twin's data."""

    def cost(x: np.ndarray, models: Sequence[np.ndarray]) -> float:
        return sum(
            float(np.sum(residuals(objective, m, t) ** 2))
            for m, t in zip(models, records, strict=True)
        )

    return cost


def reader_twin(reader: Any, fitted: Any) -> Callable[..., float]:
    """A twin that reads the recordings itself (``reader`` a
    :class:`~torsio.calibration.objectives.Misfit` of another model): its misfit against
    them, least where that model reads them; its runs count in the ``fitted`` Misfit's."""

    def cost(x: np.ndarray, models: Sequence[np.ndarray]) -> float:
        value = float(np.sum(reader(x) ** 2))
        fitted.runs += len(reader.recordings)
        return value

    return cost


def _costs(misfit: Any, x: np.ndarray, twins: Twins) -> np.ndarray:
    """Per recording its misfit against the record, then each twin's [N^2 m^2]."""
    models = misfit.models(x)
    own = [
        float(np.sum(residuals(misfit.objective, m, r) ** 2))
        for m, r in zip(models, misfit.recordings, strict=True)
    ]
    return np.array([*own, *(cost(x, models) for _, cost in twins)])


def profile_parameter(
    misfit: Any,
    best: np.ndarray,
    direction: np.ndarray,
    k: int,
    bounds: tuple[np.ndarray, np.ndarray],
    scale: float,
    sigma: float,
    twins: Twins,
) -> Profile:
    """The profile of parameter ``k`` (module documentation).

    ``bounds`` are the admissible (lower, upper) values of every parameter, ``scale`` is
    s^2 tau [N^2 m^2], ``sigma`` the Jacobian's sigma of parameter k, and ``twins`` the
    twins of the model by name (:data:`Twins`; empty: no model-form parts).
    """
    lower, upper = bounds
    value = float(best[k])
    reach = max(SPAN * abs(value), MIN_REACH * sigma)
    centre = _costs(misfit, best, twins)
    rows: list[tuple[float, np.ndarray]] = [(value, centre)]
    count = len(misfit.recordings)
    least_cost = float(np.sum(centre[:count]))
    opened = {}
    for sign in (-1.0, 1.0):
        opened[sign] = False
        for t in _offsets(sigma, reach):
            x = np.clip(best + sign * t * direction, lower, upper)
            costs = _costs(misfit, x, twins)
            rows.append((float(x[k]), costs))
            if x[k] <= lower[k] or x[k] >= upper[k]:
                chi2 = (float(np.sum(costs[:count])) - least_cost) / scale
                opened[sign] = chi2 < 4.0
                break
    rows.sort(key=lambda row: row[0])
    values = np.array([v for v, _ in rows])
    table = np.array([c for _, c in rows])
    data = table[:, :count]
    chi2 = (data.sum(axis=1) - float(np.min(data.sum(axis=1)))) / scale
    return Profile(
        values=values,
        chi2=chi2,
        recording_values=tuple(least(values, data[:, r]) for r in range(data.shape[1])),
        twin_values={name: least(values, table[:, count + g]) for g, (name, _) in enumerate(twins)},
        open_low=opened[-1.0],
        open_high=opened[1.0],
    )
