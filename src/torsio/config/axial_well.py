"""``[well]`` with axial dynamics: the contacts of the lumped chain's nodes with the borehole.

A ``[[section]]`` string with axial dynamics is a lumped axial-torsional chain (its
discretizer's, :func:`torsio.config.axial_string.string_axial`); with ``[well]`` each of its nodes
gets the
Coulomb contact of its share of the string (:func:`torsio.well.axial_contacts.axial_contacts`,
the normal force of the well's model at the run's weight on bit). The distributed axial pipe
(``[discretization] strategy = "wave"``) gets the contacts of its lumped twin's nodes
(elements of at most :data:`~torsio.model.axial_assembly.DEFAULT_ELEMENT_LENGTH`), each
with the share of the string down to half-way to the next (the last one's, at the pipe's
bottom, down to the bit: the rigid BHA's too); a ``[chain]`` has no diameters to press on
the borehole with (refused by :func:`torsio.config.well.well_table`).

Examples
--------
>>> from torsio.examples import rgd_deviated_well_config
>>> contacts = rgd_deviated_well_config().axial.contacts
>>> contacts.radius.size, contacts.count, round(contacts.static_torque)  # vertical top: no N
(24, 20, 11623)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import attrs

from torsio.config.axial import AxialConfig
from torsio.errors import ConfigError
from torsio.physics.torque_law_bit import TorqueLawBit
from torsio.well.axial_contacts import axial_contacts
from torsio.well.wellbore import Wellbore

__all__ = ["with_well"]


def with_well(axial: AxialConfig, table: Mapping[str, Any], well: Wellbore | None) -> AxialConfig:
    """``axial`` with the contacts of its lumped chain, or of its distributed pipe, in
    ``well`` (the parsed ``[well]`` of ``table``; None: absent, ``axial`` unchanged)."""
    if "well" not in table:
        return axial
    if well is None or axial.string is None:
        raise ConfigError("well", "[well] needs a drill-string ([[section]]), not a [chain]")
    if isinstance(axial.bit, TorqueLawBit):
        raise ConfigError(
            "well",
            f"friction along the string on the axial engine needs the RGD bit; the "
            f"{axial.bit.name!r} bit rests on the rock (a law of the torque alone): remove "
            "[axial] to run it with the well on the torsional engines, or [well]",
        )
    depths = axial.stability_assembly.node_depths  # the chain's nodes, or the lumped twin's
    return attrs.evolve(axial, contacts=axial_contacts(well, axial.string, depths))
