"""The capacities of a lumped chain's contacts with the borehole (the Python side of
:func:`torsio.solvers.contact_law.cone_step`).

Node i of the chain, at its depth below the string's top, stands for the string from
half-way to the node above (the top, for the first) to half-way to the node below (the
bottom of the string, for the last, which carries the rigid BHA), as the torsional lumped
contacts (:func:`torsio.well.string_contacts.node_contacts`). Its static and sliding
capacities are F_s = ∫ μ_s N dx and F_d = ∫ μ_d N dx [N] over that share, N the normal
force per metre of the rotating soft-string state at the run's weight on bit (or gravity's,
``normal_force = "gravity"``; :class:`torsio.well.rotating_column.RotatingColumn`), and its
radius r = ∫ μ_s N r_o dx / F_s [m], so that Σ F_s r is the break-off torque of
:func:`torsio.well.break_off.break_off` exactly.

Examples
--------
>>> import numpy as np
>>> contacts = AxialContacts(np.array([0.0, 2e3]), np.array([0.0, 1.5e3]),
...                          np.array([0.0, 0.0635]))
>>> contacts.count, contacts.static_torque, contact_rows(contacts, 2).shape
(1, 127.0, (3, 2))
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.errors import ConfigError
from torsio.model.arrays import read_only
from torsio.solvers import axial_layouts as slot
from torsio.well.break_off import friction_below
from torsio.well.rotating_column import RotatingColumn
from torsio.well.string_contacts import CONTACT_CELL_LENGTH, node_shares
from torsio.well.wellbore import Wellbore

__all__ = ["AxialContacts", "ContactsAtWob", "axial_contacts", "contact_rows"]


@attrs.frozen(eq=False, repr=False)
class AxialContacts:
    """The Coulomb contacts of a lumped chain's nodes with the borehole.

    Attributes
    ----------
    static_force, sliding_force : ndarray
        F_s >= F_d >= 0 [N] of every node, from the surface down (0: no contact).
    radius : ndarray
        r [m] of every node: the torque capacities are F r.
    threshold_speed : float
        |s|/r below which a contact is on its static branch [rad/s] (the well's).
    wob : float
        Weight on bit [N] of the normal force (0: off bottom).
    depths : ndarray or None
        Depth of every node [m below the string's top] (None: not given); the distributed
        pipe places its contacts there.
    details : dict
        Where the capacities came from (for reports): normal-force model, totals.
    rebuild : callable or None
        ``rebuild(wob)``: the contacts at another weight on bit (None: they do not depend
        on it, the gravity model); :meth:`at_wob` calls it.
    """

    static_force: NDArray[np.float64] = attrs.field(converter=read_only)
    sliding_force: NDArray[np.float64] = attrs.field(converter=read_only)
    radius: NDArray[np.float64] = attrs.field(converter=read_only)
    threshold_speed: float = 0.5
    wob: float = 0.0
    depths: NDArray[np.float64] | None = None
    details: dict[str, Any] = attrs.field(factory=dict)
    rebuild: Callable[[float], AxialContacts] | None = attrs.field(default=None)

    def __attrs_post_init__(self) -> None:
        sizes = {self.static_force.size, self.sliding_force.size, self.radius.size}
        if len(sizes) != 1:
            raise ConfigError("well", f"expected one capacity and radius per node, got {sizes}")
        if np.any(self.sliding_force > self.static_force * (1 + 1e-12) + 1e-12):
            raise ConfigError("well.friction_dynamic", "expected F_d <= F_s at every node")
        if np.any(self.sliding_force < 0.0) or np.any(self.radius < 0.0):
            raise ConfigError("well", "expected non-negative capacities and radii")

    def at_wob(self, wob: float) -> AxialContacts:
        """The contacts with the normal force at ``wob`` [N]."""
        if self.rebuild is None or wob == self.wob:
            return self
        return self.rebuild(wob)

    @property
    def count(self) -> int:
        """Nodes with a contact (F_s > 0)."""
        return int(np.count_nonzero(self.static_force > 0.0))

    @property
    def static_torque(self) -> float:
        """Σ F_s r [N m]: the break-off torque of the string (torsional closed form)."""
        return float(np.sum(self.static_force * self.radius))

    @property
    def sliding_torque(self) -> float:
        """Σ F_d r [N m]: the torque of every contact sliding tangentially."""
        return float(np.sum(self.sliding_force * self.radius))

    def describe(self) -> dict[str, Any]:
        """Plain data for JSON: ``count``, ``static_force``, ``sliding_force`` [N] and
        ``static_torque``, ``sliding_torque`` [N m] sums, ``threshold_speed``, ``wob``."""
        return {
            "count": self.count,
            "static_force": float(np.sum(self.static_force)),
            "sliding_force": float(np.sum(self.sliding_force)),
            "static_torque": self.static_torque,
            "sliding_torque": self.sliding_torque,
            "threshold_speed": self.threshold_speed,
            "wob": self.wob,
            "normal_force": self.details.get("normal_force"),
        }

    def __repr__(self) -> str:
        return (
            f"AxialContacts({self.count} nodes, F_s {np.sum(self.static_force):.6g} N, "
            f"break-off {self.static_torque:.6g} N m)"
        )


def contact_rows(contacts: AxialContacts | None, nodes: int) -> NDArray[np.float64]:
    """The kernel's ``contacts`` (:data:`torsio.solvers.axial_layouts.CONTACT_ROW` by ``nodes``):
    zeros without contacts."""
    rows = np.zeros((len(slot.CONTACT_ROW), nodes))
    if contacts is None:
        return rows
    if contacts.static_force.size != nodes:
        raise ConfigError(
            "well",
            f"{contacts.static_force.size} contacts given for a chain of {nodes} nodes "
            "(expected one per node)",
        )
    rows[slot.STATIC_FORCE] = contacts.static_force
    rows[slot.SLIDING_FORCE] = contacts.sliding_force
    rows[slot.CONTACT_RADIUS] = contacts.radius
    return rows


class ContactsAtWob:
    """The contacts of a chain's nodes at any weight on bit (:func:`axial_contacts`;
    picklable, so runs with them go to worker processes; the rotating state ``column`` is
    shared by every weight and rebuilt after unpickling)."""

    def __init__(
        self, well: Wellbore, string: Any, node_depths: NDArray, column: RotatingColumn | None
    ) -> None:
        self.well, self.string, self.node_depths, self._column = well, string, node_depths, column

    def __call__(self, wob: float) -> AxialContacts:
        if self._column is None:
            self._column = RotatingColumn(self.well, self.string, CONTACT_CELL_LENGTH)
        return axial_contacts(self.well, self.string, self.node_depths, wob, self._column)

    def __getstate__(self) -> dict[str, Any]:
        return {"well": self.well, "string": self.string, "node_depths": self.node_depths}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__init__(state["well"], state["string"], state["node_depths"], None)  # type: ignore[misc]


def axial_contacts(
    well: Wellbore,
    string: Any,
    node_depths: NDArray[np.float64],
    wob: float = 0.0,
    column: RotatingColumn | None = None,
) -> AxialContacts:
    """Capacities F_s, F_d [N] and radii [m] of the nodes at ``node_depths`` [m below the
    string's top] of ``string`` in ``well`` with ``wob`` [N] on bit.

    Node i stands for the string from half-way to the node above (the top, for the first)
    to half-way to the node below (the bottom of the string, for the last), as
    :func:`torsio.well.string_contacts.node_contacts`; the normal force per cell is the
    rotating soft-string state's (or gravity's) of :class:`RotatingColumn`.
    """
    column = column or RotatingColumn(well, string, CONTACT_CELL_LENGTH)
    md = column.md
    mid = 0.5 * (md[:-1] + md[1:])
    per_cell_torque = column.friction_per_cell(wob)  # ∫ N r_o over each cell
    per_cell_force = per_cell_torque / column.radii  # ∫ N over each cell
    depths = float(md[0]) + np.asarray(node_depths, dtype=float)

    def shares(per_cell: NDArray[np.float64], friction: NDArray[np.float64]) -> NDArray:
        return node_shares(md, friction_below(per_cell, friction), depths)

    mu_s, mu_d = well.friction_static_at(mid), well.friction_dynamic_at(mid)
    static, sliding = shares(per_cell_force, mu_s), shares(per_cell_force, mu_d)
    torque = shares(per_cell_torque, mu_s)
    radius = np.divide(torque, static, out=np.zeros_like(static), where=static > 0.0)
    rebuild = None
    if well.normal_force != "gravity":
        rebuild = ContactsAtWob(well, string, node_depths, column)
    return AxialContacts(
        static_force=static,
        sliding_force=np.minimum(sliding, static),
        radius=radius,
        threshold_speed=well.threshold_speed,
        wob=float(wob),
        depths=np.asarray(node_depths, dtype=float),
        details={"normal_force": well.normal_force},
        rebuild=rebuild,
    )
