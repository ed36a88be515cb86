"""Contacts of the string with the borehole: Coulomb friction at the nodes of the wave grid.

A node of the distributed model (:class:`torsio.model.wave.WaveModel`) may touch the
borehole. Each contact has a static capacity C_s and a dynamic (sliding) capacity C_d
[N m], the friction torque of the string's length it stands for
(C = mu N r_o l: the friction factor, the normal force per metre, the outer radius and
the node's share of the string's length), and the contacts share one threshold speed
below which a contact may stick. The friction law and how the stepping solves it exactly
are in docs/wave.md ("Friction along the string"); the capacities of a string in a well
come from :func:`torsio.well.string_contacts.string_contacts`.

Examples
--------
>>> import numpy as np
>>> contacts = StringContacts(static=np.array([0.0, 3.0, 0.0]),
...                           dynamic=np.array([0.0, 2.0, 0.0]), threshold_speed=0.5)
>>> contacts.static_total, contacts.dynamic_total, contacts.count
(3.0, 2.0, 1)
>>> StringContacts(static=np.array([1.0]), dynamic=np.array([2.0]), threshold_speed=0.5)
Traceback (most recent call last):
...
torsio.errors.ConfigError: well.friction_dynamic: expected a dynamic capacity <= the static one ...
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.arrays import read_only

__all__ = ["StringContacts", "carried_contacts"]


@attrs.frozen(eq=False, repr=False)
class StringContacts:
    """Coulomb contacts of the wave grid's nodes with the borehole.

    Attributes
    ----------
    static, dynamic : ndarray
        Static and sliding friction capacities C_s >= C_d >= 0 [N m] at every node of the
        state layout (:func:`torsio.solvers.wave_state.node_offsets`; a junction node's
        capacity on the upper section's last node, 0 on the lower section's first; 0 where
        a node has no contact).
    threshold_speed : float
        |speed| below which a contact is on its static branch [rad/s] (Aarsnes & Shor 2018).
    details : dict
        Where the capacities came from (for reports): normal-force model, totals.
    wob : float
        Weight on bit [N] of the normal force the capacities are from (0: off bottom).
    rebuild : callable or None
        ``rebuild(wob)``: the contacts at another weight on bit (the soft-string normal
        force in a curved hole changes with the tension, which the weight on bit lowers);
        None: the capacities do not depend on it. :meth:`at_wob` calls it.
    """

    static: np.ndarray = attrs.field(converter=read_only)
    dynamic: np.ndarray = attrs.field(converter=read_only)
    threshold_speed: float = 0.5
    details: dict[str, Any] = attrs.field(factory=dict)
    wob: float = 0.0
    rebuild: Callable[[float], StringContacts] | None = attrs.field(default=None, repr=False)

    def at_wob(self, wob: float) -> StringContacts:
        """The contacts at weight on bit ``wob`` [N] (these, where they do not change).

        >>> contacts = StringContacts(static=np.array([3.0]), dynamic=np.array([2.0]))
        >>> contacts.at_wob(50e3) is contacts   # no rebuild: independent of the weight
        True
        """
        if self.rebuild is None or float(wob) == self.wob:
            return self
        return self.rebuild(float(wob))

    @property
    def depends_on_wob(self) -> bool:
        """Whether the capacities change with the weight on bit."""
        return self.rebuild is not None

    def __attrs_post_init__(self) -> None:
        if self.static.shape != self.dynamic.shape or self.static.ndim != 1:
            raise ConfigError(
                "well",
                f"expected static and dynamic capacities of the same nodes, got shapes "
                f"{self.static.shape} and {self.dynamic.shape}",
            )
        both = np.concatenate([self.static, self.dynamic])
        if not (np.all(np.isfinite(both)) and np.all(both >= 0.0)):
            raise ConfigError("well", "expected finite, non-negative friction capacities")
        if np.any(self.dynamic > self.static * (1.0 + 1e-12)):
            raise ConfigError(
                "well.friction_dynamic",
                "expected a dynamic capacity <= the static one at every contact "
                "(friction_dynamic <= friction_static)",
            )
        speed = self.threshold_speed
        if not (isinstance(speed, int | float) and math.isfinite(speed) and speed >= 0.0):
            raise ConfigError(
                "well.threshold_speed", f"expected a non-negative speed in rad/s, got {speed!r}"
            )

    def __repr__(self) -> str:
        return (
            f"StringContacts({self.count} contacts, C_s {self.static_total:.6g} N m, "
            f"C_d {self.dynamic_total:.6g} N m, threshold {self.threshold_speed:g} rad/s)"
        )

    @property
    def count(self) -> int:
        """Nodes with a contact (static capacity > 0)."""
        return int(np.count_nonzero(self.static))

    @property
    def carries_friction(self) -> bool:
        """Whether any contact carries friction (a vertical hole, friction factors 0 or a
        string without buoyed weight or tension carry none)."""
        return self.count > 0

    @property
    def static_total(self) -> float:
        """Sum of the static capacities: the break-off torque of the grid's string [N m]."""
        return float(self.static.sum())

    @property
    def dynamic_total(self) -> float:
        """Sum of the sliding capacities: the sliding torque of the grid's string [N m]."""
        return float(self.dynamic.sum())

    def describe(self) -> dict[str, Any]:
        """Facts for reports and JSON."""
        return {
            "contacts": self.count,
            "static_capacity_N_m": self.static_total,
            "dynamic_capacity_N_m": self.dynamic_total,
            "threshold_speed_rad_s": float(self.threshold_speed),
            **self.details,
        }


def carried_contacts(contacts: StringContacts | None) -> tuple[StringContacts | None, str | None]:
    """The contacts an engine runs with, and the warning where the well carries no friction.

    Contacts of which none carries friction (all capacities 0: a vertical hole, friction
    factors 0, mud as dense as the steel) leave the run as without contacts; every engine
    takes its contacts through here, so each says so alike.

    >>> carried_contacts(StringContacts(static=np.zeros(3), dynamic=np.zeros(3)))[1]
    'no contact along the string carries friction in this well (normal force or friction ...'
    >>> carried_contacts(None)
    (None, None)
    """
    if contacts is None or contacts.carries_friction:
        return contacts, None
    return None, (
        "no contact along the string carries friction in this well (normal force or friction "
        "factor 0 all along it: a vertical hole, friction factors 0, or mud as dense as the "
        "steel); the run is without contacts"
    )
