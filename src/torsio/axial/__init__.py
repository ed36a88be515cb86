"""Axial-torsional drilling with the RGD bit (Richard, Germay and Detournay 2004, 2007).

The physics the torsional core does not have: the bit law with its depth of cut per
revolution (:mod:`torsio.axial.rgd`), its own history (:mod:`torsio.axial.history`) and its
part of a time step (:mod:`torsio.axial.bit_step`), the steady drilling state in closed form
(:mod:`torsio.axial.steady`, with friction along the string :mod:`torsio.axial.steady_friction`),
the linearization of a lumped assembly about it with the state-dependent delay
(:mod:`torsio.axial.linearization`), the roots of a linear delay system
(:mod:`torsio.axial.delay_roots`, :mod:`torsio.axial.root_branches`), the stability of steady
drilling over rpm (:mod:`torsio.axial.stability`) and the distributed pipe's characteristic
equation (:mod:`torsio.axial.wave_stability`).

The rest sits beside its torsional counterpart: the assemblies, models with axial rows
(:mod:`torsio.model.axial_assembly`), the axial engines (``torsio.solvers.axial_*``), their
runs, results and maps (:mod:`torsio.analysis.axial_transient`,
:mod:`torsio.analysis.axial_maps`), the top drive (:mod:`torsio.physics.axial_top_drive`), a
law of the torque alone (:mod:`torsio.physics.torque_law_bit`) and the contacts along a
chain (:mod:`torsio.well.axial_contacts`); docs/architecture.md says where each goes. This
package re-exports the names in its ``__all__``. The equations are in docs/axial.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from torsio.analysis.axial_energy import EnergyBalance
    from torsio.analysis.axial_maps import axial_map
    from torsio.analysis.axial_results import AxialChannels
    from torsio.analysis.axial_transient import simulate_axial
    from torsio.axial.delay_roots import LinearDelaySystem, rightmost_roots
    from torsio.axial.linearization import axial_linearization, drilling_linearization
    from torsio.axial.rgd import RGDBit, rgd_example, rgd_from_table
    from torsio.axial.root_branches import follow_roots
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
    from torsio.model.axial_assembly import (
        axial_chain,
        axial_model,
        lumped_twin,
        pipe_string,
        rgd_two_dof_example,
        rigid_bit,
        tube_section,
        two_dof_assembly,
    )
    from torsio.solvers.axial_run_setup import BitRotation
    from torsio.well.axial_contacts import AxialContacts, axial_contacts

# Every name is imported on first use (PEP 562): the stability analysis loads scipy.linalg,
# the transient and the maps numba, so that reading an RGD bit (``torsio laws``, a
# configuration) stays cheap.
_LAZY = {
    "axial_chain": "torsio.model.axial_assembly",
    "axial_model": "torsio.model.axial_assembly",
    "lumped_twin": "torsio.model.axial_assembly",
    "pipe_string": "torsio.model.axial_assembly",
    "rigid_bit": "torsio.model.axial_assembly",
    "tube_section": "torsio.model.axial_assembly",
    "rgd_two_dof_example": "torsio.model.axial_assembly",
    "two_dof_assembly": "torsio.model.axial_assembly",
    "LinearDelaySystem": "torsio.axial.delay_roots",
    "rightmost_roots": "torsio.axial.delay_roots",
    "axial_linearization": "torsio.axial.linearization",
    "drilling_linearization": "torsio.axial.linearization",
    "axial_map": "torsio.analysis.axial_maps",
    "RGDBit": "torsio.axial.rgd",
    "rgd_example": "torsio.axial.rgd",
    "rgd_from_table": "torsio.axial.rgd",
    "BitRotation": "torsio.solvers.axial_run_setup",
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
    "AxialContacts": "torsio.well.axial_contacts",
    "axial_contacts": "torsio.well.axial_contacts",
    "EnergyBalance": "torsio.analysis.axial_energy",
    "AxialChannels": "torsio.analysis.axial_results",
    "simulate_axial": "torsio.analysis.axial_transient",
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
