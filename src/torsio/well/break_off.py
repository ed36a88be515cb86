"""Break-off of a string lying in a well: the closed forms of Coulomb friction along it.

A string at rest in a deviated hole presses on the borehole with the normal force N(x)
per metre of the rotating soft-string state (:mod:`torsio.well.torque_drag`, sigma = 0:
no axial friction, so N does not depend on the friction factor). Turned slowly from the
top, every part of it sticks until the torque reaching it exceeds the static friction of
everything below, so at the moment the bit breaks free the torque in the string is

    tau_s(x) = int_x^L mu_s(x') N(x') r_o(x') dx'

(L the bit), the **break-off torque** is tau_s at the top, and the twist stored in the
string, the top's angle relative to the bit, is

    phi = int_0^L tau_s(x) / (G J(x)) dx .

Once everything slides, the **sliding torque** is the same integral with mu_d. These are
the references of the dynamics with friction along the string (a slowly ramped start-up
breaks the bit free at that torque and twist).

Numerics: the per-cell integrals of N r_o come from the rotating state of torque and drag
(:class:`torsio.well.rotating_column.RotatingColumn`, accurate to 1e-9 relative on its
closed forms); within a cell mu and G J are constant, and the twist
takes the trapezoidal rule over cells of ``cell_length`` (default 1 m: tau_s is smooth
in a cell, so the rule's relative error is of order (cell length / string length)^2).

Examples
--------
Straight inclined hole, one pipe: tau_s(x) = mu_s w sin(inc) r_o (L - x), so the break-off
torque is mu_s w sin(inc) r_o L and the twist mu_s w sin(inc) r_o L^2 / (2 G J).

>>> import math
>>> from torsio.model.components import Bit, DrillPipe, Material
>>> from torsio.model.drillstring import DrillString
>>> from torsio.well.survey import Survey
>>> from torsio.well.wellbore import Wellbore
>>> steel = Material(shear_modulus=80e9, density=7850.0)
>>> pipe = DrillPipe(od=0.127, id=0.1086, length=999.0, material=steel)
>>> bit = Bit(od=0.127, id=0.1086, length=1.0, material=steel)
>>> well = Wellbore(Survey([0.0, 1000.0], [60.0, 60.0], [0.0, 0.0]),
...                 friction_static=0.3, friction_dynamic=0.2, normal_force="gravity")
>>> result = break_off(well, DrillString([pipe, bit]))
>>> w = 9.80665 * math.pi / 4 * (0.127**2 - 0.1086**2) * 7850.0  # buoyed weight, in air [N/m]
>>> expected = 0.3 * w * math.sin(math.radians(60.0)) * 0.127 / 2 * 1000.0
>>> abs(result.torque / expected - 1) < 1e-9
True
>>> abs(result.twist / (expected * 1000.0 / (2 * 80e9 * pipe.polar_moment)) - 1) < 1e-6
True
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.drillstring import DrillString
from torsio.units import as_si
from torsio.well.rotating_column import RotatingColumn
from torsio.well.wellbore import Wellbore

__all__ = ["BreakOff", "break_off", "friction_below"]


@attrs.frozen(eq=False)
class BreakOff:
    """Break-off and sliding of a string in a well (:func:`break_off`).

    Attributes
    ----------
    torque : float
        Break-off torque at the top, int mu_s N r_o dx [N m].
    twist : float
        Angle of the top relative to the bit at break-off, int tau_s / (G J) dx [rad].
    sliding_torque : float
        Torque at the top with every part sliding, int mu_d N r_o dx [N m].
    md : ndarray
        Measured depths of the cell boundaries [m], from the string's top to the bit.
    static_torque : ndarray
        tau_s along ``md`` [N m]: the torque in the string at break-off.
    sliding_torque_profile : ndarray
        The same with mu_d [N m].
    """

    torque: float
    twist: float
    sliding_torque: float
    md: np.ndarray
    static_torque: np.ndarray
    sliding_torque_profile: np.ndarray

    def __repr__(self) -> str:
        return (
            f"BreakOff(torque {self.torque:.6g} N m, twist {self.twist:.6g} rad, "
            f"sliding torque {self.sliding_torque:.6g} N m)"
        )

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON: ``break_off_torque`` [N m], ``break_off_twist`` [rad],
        ``sliding_torque`` [N m]."""
        return {
            "break_off_torque": self.torque,
            "break_off_twist": self.twist,
            "sliding_torque": self.sliding_torque,
        }


def _torsional_rigidity(string: DrillString, top: float, md: np.ndarray) -> np.ndarray:
    """G J [N m^2] of the string's section at each measured depth ``md``."""
    ends = top + np.cumsum([s.length for s in string.sections])
    index = np.minimum(np.searchsorted(ends, md, side="left"), len(ends) - 1)
    rigidity = np.array([s.material.shear_modulus * s.polar_moment for s in string.sections])
    return rigidity[index]


def friction_below(per_cell: np.ndarray, friction: np.ndarray) -> np.ndarray:
    """The friction of the string below each cell edge (the last edge the bit's, 0): the
    friction factors ``friction`` times ``per_cell`` (each cell's integral of N r_o [N m],
    or of N [N]) summed from the bit up."""
    return np.concatenate([np.cumsum((friction * per_cell)[::-1])[::-1], [0.0]])


def break_off(
    well: Wellbore,
    string: DrillString,
    cell_length: float = 1.0,
    wob: float = 0.0,
    column: RotatingColumn | None = None,
) -> BreakOff:
    """The break-off torque and twist and the sliding torque of ``string`` in ``well``.

    Parameters
    ----------
    well : Wellbore
        Survey, hole sections (their mu_s and mu_d), mud and normal-force model.
    string : DrillString
        The string, hung from the rig floor (md 0), its bit at md = its length.
    cell_length : float
        Longest cell of the integration [m].
    wob : float
        Weight on bit [N]: the normal force of the rotating state on bottom, the tension
        less the weight on bit everywhere (0: off bottom). Only the soft-string normal
        force depends on it (a curved hole); the gravity model's does not.
    column : RotatingColumn, optional
        The rotating state of ``string`` in ``well`` on cells of ``cell_length``, kept to
        take the break-off at many weights on bit (built when not given).

    Returns
    -------
    BreakOff
    """
    wob, cell_length = as_si(wob, "force", "wob"), as_si(cell_length, "length", "cell_length")
    if not (math.isfinite(cell_length) and cell_length > 0.0):
        raise ConfigError("cell_length", f"expected a positive length in m, got {cell_length!r}")
    if not (math.isfinite(wob) and wob >= 0.0):
        raise ConfigError("wob", f"expected a non-negative weight on bit in N, got {wob!r}")
    if column is None:
        column = RotatingColumn(well, string, cell_length)
    md = column.md
    per_cell = column.friction_per_cell(wob)  # int N r_o over each cell
    mid = 0.5 * (md[:-1] + md[1:])

    static = friction_below(per_cell, well.friction_static_at(mid))
    sliding = friction_below(per_cell, well.friction_dynamic_at(mid))
    rigidity = _torsional_rigidity(string, column.string_top_md, mid)
    twist = float(np.sum(0.5 * (static[:-1] + static[1:]) * np.diff(md) / rigidity))
    return BreakOff(
        torque=float(static[0]),
        twist=twist,
        sliding_torque=float(sliding[0]),
        md=md,
        static_torque=static,
        sliding_torque_profile=sliding,
    )
