"""Soft-string torque and drag (Johancsik, Friesen & Dawson 1984; Aadnøy's formulation).

The string lies along the hole's axis. From the bit up, cell by cell, the effective
(buoyed) tension T and the torque M obey, with l the distance up the hole,

    dT/dl = w_b t_z + sigma mu N,        dM/dl = mu N r_o  (rotating),
    N = | T kappa + w_b (e_z - t_z t) |  (soft-string; ``gravity``: N = |w_b| sin(inc))

where t is the unit tangent (north, east, down), t_z = cos(inc), kappa = dt/ds the
curvature vector of the minimum-curvature hole, e_z the downward vertical, w_b = g A
(rho_steel - rho_mud) the buoyed weight per metre of the section and r_o = od/2.
sigma = +1 tripping out (friction resists the upward motion: the tension above grows),
-1 tripping in, 0 rotating (the friction is all tangential: no axial drag). The normal
force keeps its physical sign: in a build (kappa towards the high side) under tension,
T kappa pulls the pipe to the high side against its weight. The equations are integrated
exactly enough to hold the closed forms to 1e-9: classical Runge-Kutta steps that turn the
tangent by at most :data:`MAX_STEP_TURN` on each cell (a cell lies on one survey arc, one
string section and one hole section, so the coefficients are smooth within it).

Examples
--------
>>> from torsio.model.components import Bit, DrillPipe
>>> from torsio.model.drillstring import DrillString
>>> from torsio.well.survey import Survey
>>> from torsio.well.wellbore import Wellbore
>>> string = DrillString([DrillPipe(od=0.127, id=0.1086, length=1999.7),
...                       Bit(od=0.2159, id=0.05, length=0.3)])
>>> well = Wellbore(Survey([0.0, 2000.0], [0.0, 0.0], [0.0, 0.0]), mud_density=1200.0)
>>> results = torque_drag(well, string)
>>> round(results.hookload_trip_out / 1e3, 3), results.surface_torque_rotating
(441.342, 0.0)
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.errors import ConfigError
from torsio.model.drillstring import DrillString
from torsio.well.torque_drag_results import TorqueDragResults
from torsio.well.wellbore import Wellbore, string_top_md

__all__ = ["GRAVITY", "MAX_STEP_TURN", "torque_drag"]

GRAVITY = 9.80665
"""Standard gravity [m/s^2]."""

MAX_STEP_TURN = 0.002
"""Largest turn of the tangent over one integration step [rad]."""

# the operations integrated side by side: tension states and the sign of their axial friction
_SIGMA = np.array([1.0, -1.0, 0.0, 0.0])  # trip out, trip in, rotating off / on bottom
_ROTATING = slice(2, 4)


def _grid(well: Wellbore, string: DrillString, top: float, cell_length: float) -> np.ndarray:
    """Cell boundaries [m]: every section end, survey station and hole bottom in the string,
    and at most ``cell_length`` apart."""
    lengths = np.array([s.length for s in string.sections])
    bottom = well.survey.depth  # the bit at the last station (top + the length, to round-off)
    marks = [top + np.concatenate([[0.0], np.cumsum(lengths)]), well.survey.md, well.hole_bottoms]
    edges = np.unique(np.clip(np.concatenate(marks), top, bottom))
    edges[-1] = bottom
    points = [edges[:1]]
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        count = max(1, math.ceil((b - a) / cell_length - 1e-9))
        points.append(np.linspace(a, b, count + 1)[1:])
    return np.concatenate(points)


def _section_properties(string: DrillString, top: float, md: np.ndarray, mud: float) -> Any:
    """Buoyed weight per metre [N/m] and outer radius [m] of the section at each ``md``."""
    ends = top + np.cumsum([s.length for s in string.sections])
    index = np.minimum(np.searchsorted(ends, md, side="left"), len(ends) - 1)
    area = np.array([math.pi / 4.0 * (s.od**2 - s.id**2) for s in string.sections])
    density = np.array([s.material.density for s in string.sections])
    radius = np.array([s.od / 2.0 for s in string.sections])
    return (GRAVITY * area * (density - mud))[index], radius[index]


def torque_drag(
    well: Wellbore,
    string: DrillString,
    *,
    friction: float | None = None,
    wob: float = 0.0,
    bit_torque: float = 0.0,
    cell_length: float = 10.0,
) -> TorqueDragResults:
    """Tension, torque and normal force along ``string`` in ``well``, four operations.

    Tripping out and in (off bottom, no rotation), rotating off bottom, and rotating on
    bottom with ``wob`` (compression at the bit, -wob) and ``bit_torque`` (added at the
    bit). The bit is at the survey's last station.

    Parameters
    ----------
    well : Wellbore
        The survey, hole sections (their sliding friction factors), mud and normal-force
        model (``soft-string`` or ``gravity``).
    string : DrillString
        Sections from the surface down; weight per metre rho g A, torque radius od/2.
    friction : float, optional
        Sliding friction factor for every hole section instead of the well's.
    wob : float
        Weight on bit [N] of the on-bottom case, >= 0.
    bit_torque : float
        Torque on bit [N m] of the on-bottom case, >= 0.
    cell_length : float
        Longest cell [m]; the results are given at the cell boundaries.

    Returns
    -------
    TorqueDragResults

    Raises
    ------
    ConfigError
        A string longer than the survey, or a negative or non-finite option (named).
    """
    for name, value in (("friction", friction), ("wob", wob), ("bit_torque", bit_torque)):
        if value is not None and not (math.isfinite(value) and value >= 0.0):
            raise ConfigError(name, f"expected a non-negative finite number, got {value!r}")
    if not (math.isfinite(cell_length) and cell_length > 0.0):
        raise ConfigError("cell_length", f"expected a positive length, got {cell_length!r}")
    length = float(sum(s.length for s in string.sections))
    top = string_top_md(well, length)
    md = _grid(well, string, top, cell_length)
    survey = well.survey
    soft = well.normal_force == "soft-string"

    def rates(s: float, tension: np.ndarray, arc: int, w: float, r: float, mu: float) -> Any:
        t, k = survey.frame(arc, s)
        lateral = np.array([0.0, 0.0, 1.0]) - t[2] * t  # gravity's part normal to the hole
        if soft:
            normal = np.linalg.norm(tension[:, None] * k + w * lateral, axis=1)
        else:
            normal = np.full(tension.shape, abs(w) * np.linalg.norm(lateral))
        return w * t[2] + _SIGMA * mu * normal, mu * normal[_ROTATING] * r, normal

    n = md.size
    tension = np.empty((n, 4))
    torque = np.empty((n, 2))
    normal = np.empty((n, 4))
    mid = 0.5 * (md[:-1] + md[1:])
    weights, radii = _section_properties(string, top, mid, well.mud_density)
    mus = well.friction_dynamic_at(mid) if friction is None else np.full(mid.size, friction)
    tension[-1] = [0.0, 0.0, 0.0, -wob]
    torque[-1] = [0.0, bit_torque]
    for j in range(n - 2, -1, -1):  # from the bit up
        w, r, mu = float(weights[j]), float(radii[j]), float(mus[j])
        h_cell = md[j + 1] - md[j]
        arc = survey.interval(mid[j])  # the cell lies on one arc of the survey
        turn = float(survey.station_doglegs[arc]) * h_cell / float(np.diff(survey.md)[arc])
        steps = max(1, math.ceil(turn / MAX_STEP_TURN))
        h = h_cell / steps
        y, m = tension[j + 1].copy(), torque[j + 1].copy()
        s = md[j + 1]
        for _ in range(steps):  # classical Runge-Kutta, l = up the hole
            k1, q1, _n = rates(s, y, arc, w, r, mu)
            k2, q2, _n = rates(s - h / 2, y + h / 2 * k1, arc, w, r, mu)
            k3, q3, _n = rates(s - h / 2, y + h / 2 * k2, arc, w, r, mu)
            s = max(s - h, md[j])
            k4, q4, _n = rates(s, y + h * k3, arc, w, r, mu)
            y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            m = m + h / 6 * (q1 + 2 * q2 + 2 * q3 + q4)
        tension[j], torque[j] = y, m
    for j in range(n):  # the normal force at each boundary, with the cell below's pipe
        cell = min(j, n - 2)
        arc = survey.interval(mid[cell])
        normal[j] = rates(md[j], tension[j], arc, float(weights[cell]), 0.0, 0.0)[2]
    return TorqueDragResults(
        md=md,
        tension=tension,
        torque=torque,
        normal_force=normal,
        wob=wob,
        bit_torque=bit_torque,
        string_top_md=top,
        buoyed_weight=float(np.sum(weights * np.diff(md))),
        normal_force_model=well.normal_force,
        friction=friction,
    )
