"""The rotating soft-string state of a string in a well, at any weight on bit at once.

While the string turns, the friction along it is all tangential (sigma = 0 in
:mod:`torsio.well.torque_drag`), so the effective tension obeys dT/dl = w_b t_z alone: it
is the buoyed weight below less the weight on bit, T(l; W) = T(l; 0) - W, exactly. The
normal force N = |T kappa + w_b (e_z - t_z t)| (or |w_b| sin(inc) for the ``gravity``
model) is then a vector sum at fixed points, evaluated for any W without integrating
again. :class:`RotatingColumn` keeps those points: the cells of :func:`torque_drag` and
the stages of its classical Runge-Kutta steps, so that its integral of N r_o over each
cell is the torque-and-drag quadrature itself (Simpson's rule along each step, whose
stages 2 and 3 carry the tension of the Runge-Kutta stages).

Examples
--------
A straight inclined hole: N = w_b sin(inc) whatever the tension, so the friction torque
per unit friction factor is w_b sin(inc) r_o L at any weight on bit.

>>> import math
>>> from torsio.model.components import Bit, DrillPipe
>>> from torsio.model.drillstring import DrillString
>>> from torsio.well.survey import Survey
>>> from torsio.well.wellbore import Wellbore
>>> string = DrillString([DrillPipe(od=0.127, id=0.1086, length=999.7),
...                       Bit(od=0.127, id=0.1086, length=0.3)])
>>> column = RotatingColumn(Wellbore(Survey([0.0, 1000.0], [60.0, 60.0], [0.0, 0.0])), string)
>>> w = 9.80665 * math.pi / 4 * (0.127**2 - 0.1086**2) * 7850.0
>>> expected = w * math.sin(math.radians(60.0)) * 0.127 / 2 * 1000.0
>>> [round(float(column.friction_per_cell(wob).sum() / expected), 12) for wob in (0.0, 1e5)]
[1.0, 1.0]
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.model.drillstring import DrillString
from torsio.well.wellbore import Wellbore, bit_md, check_mud_density, string_top_md

__all__ = ["GRAVITY", "MAX_STEP_TURN", "RotatingColumn", "cell_boundaries", "section_properties"]

GRAVITY = 9.80665
"""Standard gravity [m/s^2]."""

MAX_STEP_TURN = 0.002
"""Largest turn of the tangent over one integration step [rad]."""

_SIMPSON = np.array([1.0, 2.0, 2.0, 1.0]) / 6.0  # classical Runge-Kutta weights of a step


def cell_boundaries(
    well: Wellbore, string: DrillString, top: float, cell_length: float
) -> np.ndarray:
    """Cell boundaries [m]: every section end, survey station and hole bottom in the string,
    and at most ``cell_length`` apart."""
    lengths = np.array([s.length for s in string.sections])
    bottom = bit_md(well, float(lengths.sum()))  # open hole below the bit carries nothing
    marks = [top + np.concatenate([[0.0], np.cumsum(lengths)]), well.survey.md, well.hole_bottoms]
    edges = np.unique(np.clip(np.concatenate(marks), top, bottom))
    edges[-1] = bottom
    points = [edges[:1]]
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        count = max(1, math.ceil((b - a) / cell_length - 1e-9))
        points.append(np.linspace(a, b, count + 1)[1:])
    return np.concatenate(points)


def section_properties(string: DrillString, top: float, md: np.ndarray, mud: float) -> Any:
    """Buoyed weight per metre [N/m] and contact radius [m] of the section at each ``md``.

    The buoyed weight is g A (rho_steel - rho_mud), A the section's steel cross-section
    (with the tool joints where given: ``adjusted_weight`` / rho_steel); the contact radius is the
    tool joints' where given (``tool_joint_od`` / 2), else od / 2."""
    ends = top + np.cumsum([s.length for s in string.sections])
    index = np.minimum(np.searchsorted(ends, md, side="left"), len(ends) - 1)
    weight = np.array(
        [GRAVITY * s.weighed_area * (s.material.density - mud) for s in string.sections]
    )
    radius = np.array([s.contact_radius for s in string.sections])
    return weight[index], radius[index]


def step_counts(well: Wellbore, md: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The survey arc of each cell and its number of Runge-Kutta steps, each turning the
    tangent by at most :data:`MAX_STEP_TURN`."""
    survey = well.survey
    mid = 0.5 * (md[:-1] + md[1:])
    arcs = np.array([survey.interval(x) for x in mid], dtype=int)  # a cell lies on one arc
    turn = survey.station_doglegs[arcs] * np.diff(md) / np.diff(survey.md)[arcs]
    return arcs, np.maximum(1, np.ceil(turn / MAX_STEP_TURN)).astype(int)


class RotatingColumn:
    """Tension and normal force of the rotating state of ``string`` in ``well``.

    Parameters
    ----------
    well : Wellbore
        The survey, mud and normal-force model.
    string : DrillString
        The string, hung from the rig floor (md 0), its bit at md = its length.
    cell_length : float
        Longest cell [m] (:func:`cell_boundaries`).

    Attributes
    ----------
    md : ndarray
        Cell boundaries [m], from the string's top to the bit.
    string_top_md : float
        Measured depth of the string's top [m].
    weights, radii : ndarray
        Buoyed weight per metre [N/m] and outer radius [m] of each cell's pipe.
    """

    def __init__(self, well: Wellbore, string: DrillString, cell_length: float = 10.0) -> None:
        length = float(sum(s.length for s in string.sections))
        self.string_top_md = top = string_top_md(well, length)
        check_mud_density(well, string)
        self.md = md = cell_boundaries(well, string, top, cell_length)
        self.weights, self.radii = section_properties(
            string, top, 0.5 * (md[:-1] + md[1:]), well.mud_density
        )
        self.soft = well.normal_force == "soft-string"
        arcs, counts = step_counts(well, md)
        self.arcs = arcs
        # the steps from the bit up: cell, length h, and the four stages' depths
        cells = np.repeat(np.arange(md.size - 1), counts)[::-1]
        h = (np.diff(md) / counts)[cells]
        starts = np.empty(cells.size)
        position = 0
        for j in range(md.size - 2, -1, -1):  # where each step starts, as torque_drag steps
            s = md[j + 1]
            for _ in range(counts[j]):
                starts[position] = s
                s = max(s - h[position], md[j])
                position += 1
        ends = np.maximum(starts - h, md[cells])
        stage_md = np.stack([starts, starts - h / 2, starts - h / 2, ends], axis=1)
        tangent, self._curvature = _frames(well, arcs[cells], stage_md)
        w = self.weights[cells][:, None, None]
        self._lateral = w * (np.array([0.0, 0.0, 1.0]) - tangent[..., 2:3] * tangent)
        self._cells, self._h = cells, h
        # the tension off bottom at the stages: dT/dl = w t_z from T = 0 at the bit
        slope = w[..., 0] * tangent[..., 2]
        risen = np.cumsum(h * (slope @ _SIMPSON))  # after each step, as the loop adds it
        start = np.concatenate([[0.0], risen[:-1]])
        self._tension = np.stack(
            [start, start + h / 2 * slope[:, 0], start + h / 2 * slope[:, 1],
             start + h * slope[:, 2]], axis=1,
        )  # fmt: skip
        last_step = np.cumsum(counts[::-1])[::-1] - 1  # each cell's last step, from the bit
        self._boundary_tension = np.concatenate([risen[last_step], [0.0]])
        below = np.minimum(np.arange(md.size), md.size - 2)  # each boundary's cell below
        t_b, k_b = _frames(well, arcs[below], md[:, None])
        self._boundary_curvature = k_b[:, 0]
        w_b = self.weights[below][:, None]
        self._boundary_lateral = w_b * (np.array([0.0, 0.0, 1.0]) - t_b[:, 0, 2:3] * t_b[:, 0])

    def tension(self, wob: float = 0.0) -> np.ndarray:
        """Effective tension [N] at the cell boundaries (``md``) while rotating with ``wob``
        [N] on bit (0: off bottom)."""
        return self._boundary_tension - wob

    def normal_force(self, wob: float = 0.0) -> np.ndarray:
        """Normal force per metre [N/m] at the cell boundaries, the cell below's pipe."""
        return self._normal(self.tension(wob), self._boundary_curvature, self._boundary_lateral)

    def friction_per_cell(self, wob: Any = 0.0) -> np.ndarray:
        """int N r_o dl over each cell [N m per unit friction factor] with ``wob`` [N] on
        bit; an array of weights gives one row per weight, shape (weights, cells)."""
        weights = np.asarray(wob, dtype=float)
        tension = self._tension - weights.reshape(-1, 1, 1)  # (weights, steps, 4)
        normal = self._normal(tension, self._curvature, self._lateral)
        per_step = self._h * (normal @ _SIMPSON) * self.radii[self._cells]
        per_cell = np.zeros((weights.size, self.md.size - 1))
        for row, values in zip(per_cell, per_step, strict=True):
            np.add.at(row, self._cells, values)
        return per_cell[0] if weights.ndim == 0 else per_cell

    def _normal(self, tension: np.ndarray, curvature: np.ndarray, lateral: np.ndarray) -> Any:
        if not self.soft:  # the buoyed weight's normal component alone
            return np.broadcast_to(np.linalg.norm(lateral, axis=-1), tension.shape)
        return np.linalg.norm(tension[..., None] * curvature + lateral, axis=-1)


def _frames(well: Wellbore, arcs: np.ndarray, md: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit tangents and curvature vectors, shape md.shape + (3,), at ``md`` (rows) on the
    survey arc of each row (:meth:`Survey.frame`: its end stations on its own arc)."""
    frames = [well.survey.frame(int(arc), float(x)) for arc, row in zip(arcs, md, strict=True)
              for x in row]  # fmt: skip
    shape = md.shape + (3,)
    return (np.array([t for t, _ in frames]).reshape(shape),
            np.array([k for _, k in frames]).reshape(shape))  # fmt: skip
