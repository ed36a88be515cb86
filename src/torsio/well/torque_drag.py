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
string section and one hole section, so the coefficients are smooth within it). The two
rotating operations take their tension and normal force from
:class:`torsio.well.rotating_column.RotatingColumn` (sigma = 0: the tension needs no
integration of N, so one column serves every weight on bit).

Examples
--------
>>> from torsio import Bit, DrillPipe, DrillString
>>> from torsio.well import Survey, Wellbore
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
from torsio.units import as_si
from torsio.well.rotating_column import RotatingColumn, step_counts
from torsio.well.torque_drag_results import TorqueDragResults
from torsio.well.wellbore import Wellbore

__all__ = ["torque_drag"]

# the trip operations integrated side by side, and the sign of their axial friction
_SIGMA = np.array([1.0, -1.0])  # trip out, trip in


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
    bit). The string hangs from the rig floor: top at md 0, bit at md = its length.

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
    wob, bit_torque = as_si(wob, "force", "wob"), as_si(bit_torque, "torque", "bit_torque")
    cell_length = as_si(cell_length, "length", "cell_length")
    for name, value in (("friction", friction), ("wob", wob), ("bit_torque", bit_torque)):
        if value is not None and not (math.isfinite(value) and value >= 0.0):
            raise ConfigError(name, f"expected a non-negative finite number, got {value!r}")
    if not (math.isfinite(cell_length) and cell_length > 0.0):
        raise ConfigError("cell_length", f"expected a positive length, got {cell_length!r}")
    column = RotatingColumn(well, string, cell_length)  # the two rotating operations
    md, top = column.md, column.string_top_md
    survey = well.survey
    soft = well.normal_force == "soft-string"

    def rates(s: float, tension: np.ndarray, arc: int, w: float, mu: float) -> Any:
        t, k = survey.frame(arc, s)
        lateral = np.array([0.0, 0.0, 1.0]) - t[2] * t  # gravity's part normal to the hole
        if soft:
            normal = np.linalg.norm(tension[:, None] * k + w * lateral, axis=1)
        else:
            normal = np.full(tension.shape, abs(w) * np.linalg.norm(lateral))
        return w * t[2] + _SIGMA * mu * normal, normal

    n = md.size
    mid = 0.5 * (md[:-1] + md[1:])
    weights = column.weights
    mus = well.friction_dynamic_at(mid) if friction is None else np.full(mid.size, friction)
    arcs, counts = step_counts(well, md)
    trips = np.empty((n, 2))
    trips[-1] = 0.0
    for j in range(n - 2, -1, -1):  # from the bit up, classical Runge-Kutta, l = up the hole
        w, mu, arc = float(weights[j]), float(mus[j]), int(arcs[j])
        h = (md[j + 1] - md[j]) / counts[j]
        y, s = trips[j + 1].copy(), md[j + 1]
        for _ in range(counts[j]):
            k1, _n = rates(s, y, arc, w, mu)
            k2, _n = rates(s - h / 2, y + h / 2 * k1, arc, w, mu)
            k3, _n = rates(s - h / 2, y + h / 2 * k2, arc, w, mu)
            s = max(s - h, md[j])
            k4, _n = rates(s, y + h * k3, arc, w, mu)
            y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        trips[j] = y
    trip_normal = np.array(  # at each boundary, with the cell below's pipe
        [
            rates(md[j], trips[j], int(arcs[min(j, n - 2)]), float(weights[min(j, n - 2)]), 0.0)[1]
            for j in range(n)
        ]
    )

    def rotating_torque(on_bit: float, weight: float) -> np.ndarray:
        per_cell = mus * column.friction_per_cell(weight)
        return on_bit + np.concatenate([np.cumsum(per_cell[::-1])[::-1], [0.0]])

    tension = np.column_stack([trips, column.tension(0.0), column.tension(wob)])
    torque = np.column_stack([rotating_torque(0.0, 0.0), rotating_torque(bit_torque, wob)])
    normal = np.column_stack([trip_normal, column.normal_force(0.0), column.normal_force(wob)])
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
