"""Axial-torsional drilling with the RGD bit (Richard, Germay and Detournay 2004, 2007).

The bit law with its depth of cut per revolution (:mod:`torsio.axial.rgd`), the steady
drilling state in closed form (:mod:`torsio.axial.steady`), the linearization of any lumped
assembly about it with the state-dependent delay (:mod:`torsio.axial.linearization`), the
roots of a linear delay system (:mod:`torsio.axial.delay_roots`), the stability of steady
drilling over rpm (:mod:`torsio.axial.stability`), the assemblies that move axially and
torsionally, lumped chains and the distributed pipe of axial and torsional wave lines above
a rigid BHA (:mod:`torsio.axial.assembly`: models with axial rows), their transients
on compiled fixed-step engines with the bit's own history (:mod:`torsio.axial.transient`) and
maps over (weight, rpm) (:mod:`torsio.axial.maps`), with Coulomb friction along a lumped
chain's string (:mod:`torsio.axial.string_contacts`, :mod:`torsio.axial.steady_friction`).
The equations are in docs/axial.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from torsio.axial.assembly import (
        axial_chain,
        axial_model,
        lumped_twin,
        pipe_string,
        rgd_two_dof_example,
        rigid_bit,
        tube_section,
        two_dof_assembly,
    )
    from torsio.axial.delay_roots import LinearDelaySystem, rightmost_roots
    from torsio.axial.energy_balance import EnergyBalance
    from torsio.axial.linearization import axial_linearization, drilling_linearization
    from torsio.axial.maps import axial_map
    from torsio.axial.rgd import RGDBit, rgd_example, rgd_from_table
    from torsio.axial.root_branches import follow_roots
    from torsio.axial.run_results import AxialChannels
    from torsio.axial.run_setup import BitRotation
    from torsio.axial.stability import (
        DrillingCase,
        DrillingStability,
        ModeCrossing,
        ModeCrossings,
        drilling_stability,
        each_mode_crossing,
        mode_crossings,
    )
    from torsio.axial.steady import SteadyDrilling, steady_drilling
    from torsio.axial.steady_friction import SteadyFriction, steady_with_friction
    from torsio.axial.string_contacts import AxialContacts, axial_contacts
    from torsio.axial.transient import simulate_axial

# Every name is imported on first use (PEP 562): the stability analysis loads scipy.linalg,
# the transient and the maps numba, so that reading an RGD bit (``torsio laws``, a
# configuration) stays cheap.
_LAZY = {
    "axial_chain": "torsio.axial.assembly",
    "axial_model": "torsio.axial.assembly",
    "lumped_twin": "torsio.axial.assembly",
    "pipe_string": "torsio.axial.assembly",
    "rigid_bit": "torsio.axial.assembly",
    "tube_section": "torsio.axial.assembly",
    "rgd_two_dof_example": "torsio.axial.assembly",
    "two_dof_assembly": "torsio.axial.assembly",
    "LinearDelaySystem": "torsio.axial.delay_roots",
    "rightmost_roots": "torsio.axial.delay_roots",
    "axial_linearization": "torsio.axial.linearization",
    "drilling_linearization": "torsio.axial.linearization",
    "axial_map": "torsio.axial.maps",
    "RGDBit": "torsio.axial.rgd",
    "rgd_example": "torsio.axial.rgd",
    "rgd_from_table": "torsio.axial.rgd",
    "BitRotation": "torsio.axial.run_setup",
    "DrillingStability": "torsio.axial.stability",
    "ModeCrossing": "torsio.axial.stability",
    "ModeCrossings": "torsio.axial.stability",
    "DrillingCase": "torsio.axial.stability",
    "drilling_stability": "torsio.axial.stability",
    "each_mode_crossing": "torsio.axial.stability",
    "follow_roots": "torsio.axial.root_branches",
    "mode_crossings": "torsio.axial.stability",
    "SteadyDrilling": "torsio.axial.steady",
    "steady_drilling": "torsio.axial.steady",
    "SteadyFriction": "torsio.axial.steady_friction",
    "steady_with_friction": "torsio.axial.steady_friction",
    "AxialContacts": "torsio.axial.string_contacts",
    "axial_contacts": "torsio.axial.string_contacts",
    "EnergyBalance": "torsio.axial.energy_balance",
    "AxialChannels": "torsio.axial.run_results",
    "simulate_axial": "torsio.axial.transient",
}

__all__ = [
    "AxialContacts",
    "AxialChannels",
    "BitRotation",
    "DrillingCase",
    "DrillingStability",
    "EnergyBalance",
    "LinearDelaySystem",
    "ModeCrossing",
    "ModeCrossings",
    "RGDBit",
    "SteadyDrilling",
    "SteadyFriction",
    "axial_chain",
    "axial_contacts",
    "axial_model",
    "axial_linearization",
    "axial_map",
    "drilling_linearization",
    "drilling_stability",
    "each_mode_crossing",
    "follow_roots",
    "lumped_twin",
    "mode_crossings",
    "pipe_string",
    "rigid_bit",
    "tube_section",
    "rgd_example",
    "rgd_from_table",
    "rgd_two_dof_example",
    "rightmost_roots",
    "simulate_axial",
    "steady_drilling",
    "steady_with_friction",
    "two_dof_assembly",
]


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'torsio.axial' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value
