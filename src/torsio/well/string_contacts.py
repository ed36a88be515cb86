"""The contacts of a wave grid's string with its well: friction capacities per drag node.

Each drag node of the wave grid (:func:`torsio.model.wave_grid.drag_lumping`: nodes 0, k, 2k,
... and the last of every section) stands for its share of the string's length, half-way
to its neighbours. Its static capacity is the static friction torque of that share,

    C_s = int_share mu_s N r_o dx,      C_d = int_share mu_d N r_o dx,

with N the normal force per metre of the rotating off-bottom soft-string state (or the
buoyed weight's normal component alone, ``normal_force = "gravity"``), r_o = od / 2 and the
friction factors of the hole section there. The integrals are differences of the
break-off profiles of :func:`torsio.well.break_off.break_off` (torque and drag's per-cell
integrals), so the capacities add up to the break-off torque and the sliding torque
exactly. The shares of the two end nodes go to the nearest contact inside the string: the
top node is the top drive's (held, or its own equation) and the bit node the bit's
equation; so does the friction of what the grid does not carry (the bit section, and the
BHA with ``rigid_bha``).

Examples
--------
>>> from torsio.examples import deviated_well_config
>>> from torsio.model.wave import WaveStrategy
>>> config = deviated_well_config()
>>> grid = WaveStrategy(drag_spacing=4).discretize(config.string)
>>> contacts = string_contacts(grid, config.well)
>>> round(contacts.static_total), round(contacts.dynamic_total), contacts.threshold_speed
(12174, 10148, 0.5)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from torsio.errors import ConfigError
from torsio.model.contacts import StringContacts
from torsio.model.wave_grid import drag_lumping
from torsio.well.break_off import break_off
from torsio.well.rotating_column import RotatingColumn
from torsio.well.wellbore import Wellbore

__all__ = [
    "CONTACT_CELL_LENGTH",
    "model_contacts",
    "node_contacts",
    "node_shares",
    "string_contacts",
    "with_contacts",
]

CONTACT_CELL_LENGTH = 10.0
"""Cell of the torque-and-drag integrals the capacities are taken from [m]."""


def string_contacts(
    grid: Any, well: Wellbore, wob: float = 0.0, column: RotatingColumn | None = None
) -> StringContacts:
    """Static and sliding capacities [N m] of every drag node of ``grid`` in ``well``.

    Parameters
    ----------
    grid : WaveModel
        The characteristic grid (its string, sections, cells and ``drag_spacing``).
    well : Wellbore
        Survey, hole sections (mu_s, mu_d), mud, normal-force model, threshold speed.

    wob : float
        Weight on bit [N] of the rotating state's normal force (0: off bottom); the
        contacts rebuild themselves at another (:meth:`StringContacts.at_wob`).
    column : RotatingColumn, optional
        The string's rotating state in ``well`` on cells of :data:`CONTACT_CELL_LENGTH`,
        shared by the contacts at every weight (built when not given).

    Raises
    ------
    ConfigError
        On ``discretization.drag_spacing`` when the string has friction but no drag node
        inside it to carry the shares of its ends (without friction anywhere: every
        capacity 0, :func:`torsio.model.contacts.carried_contacts`).
    """
    column = column or RotatingColumn(well, grid.string, CONTACT_CELL_LENGTH)
    profile = break_off(well, grid.string, CONTACT_CELL_LENGTH, wob, column)
    md = profile.md
    top = float(md[0])

    def below(x: np.ndarray, torque: np.ndarray) -> np.ndarray:
        return np.interp(x, md, torque)  # the friction torque of everything below x [N m]

    cells = np.array(grid.cells)
    offsets = np.concatenate([[0], np.cumsum(cells + 1)]).astype(int)
    static = np.zeros(int(offsets[-1]))
    dynamic = np.zeros_like(static)
    profiles = ((static, profile.static_torque), (dynamic, profile.sliding_torque_profile))
    start = top
    for s, section in enumerate(grid.sections):
        nodes, _ = drag_lumping(int(cells[s]), grid.drag_spacing)
        x = start + nodes / cells[s] * section.length  # the section as given, not rounded
        edges = np.concatenate([[x[0]], 0.5 * (x[:-1] + x[1:]), [x[-1]]])
        index = offsets[s] + nodes
        if s > 0:  # a junction node's capacity on the upper section's last node
            index[0] = offsets[s] - 1
        for out, torque in profiles:
            levels = below(edges, torque)
            np.add.at(out, index, levels[:-1] - levels[1:])
        start += section.length
    inside = np.flatnonzero(static[1:-1] > 0.0) + 1
    carried = static.any() or below(np.array([start]), profile.static_torque)[0] > 0.0
    if inside.size == 0 and not carried:  # no friction anywhere: nothing to carry
        return StringContacts(
            static=np.zeros_like(static),
            dynamic=np.zeros_like(dynamic),
            threshold_speed=well.threshold_speed,
            details=_details(well, profile),
            wob=float(wob),
            rebuild=_rebuild(grid, well, grid.string, column),
        )
    if inside.size == 0:
        raise ConfigError(
            "discretization.drag_spacing",
            f"expected a drag node inside the string to carry its friction, but a spacing of "
            f"{grid.drag_spacing} cells leaves only the top and the bit; give a smaller one",
        )
    for out, torque in profiles:
        out[inside[0]] += out[0]  # the top's share
        out[inside[-1]] += out[-1] + below(np.array([start]), torque)[0]  # the bit's, the rest
        out[0] = out[-1] = 0.0
    return StringContacts(
        static=static,
        dynamic=dynamic,
        threshold_speed=well.threshold_speed,
        details=_details(well, profile),
        wob=float(wob),
        rebuild=_rebuild(grid, well, grid.string, column),
    )


class ContactsAtWob:
    """The contacts of a model's string in a well at any weight on bit (picklable, so a
    System with them goes to worker processes; a few weights kept per process).

    ``target``: the model without contacts (a lumped chain, or a wave grid); ``column``
    the string's rotating state in the well, one for every weight (built when first
    needed: it is not pickled).
    """

    KEPT = 64

    def __init__(
        self, target: Any, well: Wellbore, string: Any, column: RotatingColumn | None = None
    ) -> None:
        self.target, self.well, self.string = target, well, string
        self._column = column
        self._kept: dict[float, StringContacts] = {}

    def __call__(self, wob: float) -> StringContacts:
        kept = self._kept.get(wob)
        if kept is None:
            if self._column is None:
                self._column = RotatingColumn(self.well, self.string, CONTACT_CELL_LENGTH)
            if self.target.has_matrices:
                kept = node_contacts(self.target, self.well, self.string, wob, self._column)
            else:
                kept = string_contacts(self.target, self.well, wob, self._column)
            if len(self._kept) >= self.KEPT:
                self._kept.pop(next(iter(self._kept)))
            self._kept[wob] = kept
        return kept

    def __getstate__(self) -> dict[str, Any]:
        return {"target": self.target, "well": self.well, "string": self.string}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__init__(state["target"], state["well"], state["string"])  # type: ignore[misc]


def _rebuild(
    target: Any, well: Wellbore, string: Any, column: RotatingColumn
) -> ContactsAtWob | None:
    """How contacts rebuild at another weight on bit; None where the normal force does
    not depend on it (the gravity model)."""
    if well.normal_force == "gravity":
        return None
    return ContactsAtWob(target, well, string, column)


def node_contacts(
    model: Any,
    well: Wellbore,
    string: Any,
    wob: float = 0.0,
    column: RotatingColumn | None = None,
) -> StringContacts:
    """Static and sliding capacities [N m] of every node of a lumped chain in ``well``.

    Node i (at ``model.node_depths[i]`` below the top of ``string``) stands for the string
    from half-way to the node above (the top, for the first) to half-way to the node below
    (the bottom of the string, for the last: the bit node carries the bit section and what
    a rigid BHA lumps there), so the capacities add up to the break-off and sliding torques
    exactly. The normal force is the rotating state's at ``wob`` [N] (0: off bottom);
    ``column`` as for :func:`string_contacts`.

    >>> from torsio.examples import deviated_well_config
    >>> config = deviated_well_config()
    >>> model = config.system(strategy="B", dp_elements=20, bha_elements=4).model
    >>> contacts = node_contacts(model, config.well, config.string)
    >>> contacts.static.size, round(contacts.static_total), round(contacts.dynamic_total)
    (24, 12174, 10148)
    """
    column = column or RotatingColumn(well, string, CONTACT_CELL_LENGTH)
    profile = break_off(well, string, CONTACT_CELL_LENGTH, wob, column)
    md = profile.md
    depths = float(md[0]) + np.asarray(model.node_depths, dtype=float)
    capacities = [
        node_shares(md, torque, depths)
        for torque in (profile.static_torque, profile.sliding_torque_profile)
    ]
    return StringContacts(
        static=capacities[0],
        dynamic=np.minimum(capacities[1], capacities[0]),  # equal to round-off where mu_s = mu_d
        threshold_speed=well.threshold_speed,
        details=_details(well, profile),
        wob=float(wob),
        rebuild=_rebuild(model, well, string, column),
    )


def node_shares(md: np.ndarray, below: np.ndarray, depths: np.ndarray) -> np.ndarray:
    """The shares of nodes at measured depths ``depths`` [m] of a profile ``below`` along
    ``md`` (the friction of everything below each depth, :func:`break_off`): node i's
    from half-way to the node above (the string's top ``md[0]``, for the first) to half-way
    to the node below (the bit ``md[-1]``, for the last); they add up to ``below[0]``."""
    edges = np.concatenate([[md[0]], 0.5 * (depths[:-1] + depths[1:]), [md[-1]]])
    levels = np.interp(edges, md, below)
    return levels[:-1] - levels[1:]


def _details(well: Wellbore, profile: Any) -> dict[str, Any]:
    """Where the capacities came from, for reports: the normal force and the totals."""
    return {
        "normal_force": well.normal_force,
        "bit_md": float(profile.md[-1]),
        "break_off_torque_N_m": profile.torque,
        "break_off_twist_rad": profile.twist,
        "sliding_torque_N_m": profile.sliding_torque,
    }


def with_contacts(model: Any, well: Wellbore, string: Any, wob: float = 0.0) -> Any:
    """``model`` with the friction of ``string`` in ``well`` at weight on bit ``wob`` [N]:
    a contact at every node of a chain with matrices (the lumped models,
    :func:`node_contacts`), at every drag node of a characteristic grid
    (:func:`string_contacts`)."""
    if string is None:
        raise ConfigError(
            "well",
            "friction along the string needs the string's sections ([[section]]: diameters "
            "and lengths); a [chain] has none",
        )
    return model.with_contacts(model_contacts(model, well, string, wob))


def model_contacts(model: Any, well: Wellbore, string: Any, wob: float = 0.0) -> StringContacts:
    """The contacts of ``string`` in ``well`` on ``model`` at weight on bit ``wob`` [N]: at
    every node of a chain with matrices (:func:`node_contacts`), at every drag node of a
    characteristic grid (:func:`string_contacts`)."""
    if model.has_matrices:
        return node_contacts(model, well, string, wob)
    return string_contacts(model, well, wob)
