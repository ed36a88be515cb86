"""Lumped drilling assemblies: chains whose nodes turn and move axially, the bit on the last.

A lumped drilling assembly is a :class:`~torsio.model.lumped.LumpedModel` with axial rows
(:class:`~torsio.model.axial_rows.AxialRows`): node i has a torsional inertia I_i and an
axial mass m_i; torsionally, spring k_i and damper c_i join node i − 1 to node i, node −1
being the top drive turning at Ω₀; axially, spring k_a,i and damper c_a,i join node i − 1
to node i, node −1 being the hook (its boundaries: :mod:`torsio.model.axial_rows`).
:func:`axial_chain` builds one from its vectors; the functions below read what the axial
engine needs from it (its kernel rows, its fastest rates, its steady angles and positions).

The 2-DOF model of Richard, Germay and Detournay (2007) is one node, no axial spring:
:func:`two_dof_assembly`. :func:`pipe_assembly` splits a uniform pipe section
(:class:`~torsio.axial.wave_assembly.PipeSection`) into nodes with springs E A / L and
G J / L (L the node spacing) and the BHA on the last node.

Examples
--------
>>> assembly = rgd_two_dof_example()
>>> assembly.dofs, assembly.axial.dofs, assembly.axial.hook
(1, 1, 'weight')
>>> from torsio.axial.wave_assembly import PipeSection
>>> pipe = PipeSection(1000.0, 2.0e11, 8.0e10, 7850.0, 3.4e-3, 1.5e-5)
>>> chain = pipe_assembly(4, pipe, 3.0e4, 230.0)
>>> round(float(chain.axial.stiffnesses[1]) / 1e6, 3)  # E A / (L / n), MN/m
2.72
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from torsio.errors import ConfigError
from torsio.model.arrays import check_count, read_only_vector
from torsio.model.axial_rows import AxialRows
from torsio.model.discretize import element_axial_rows, element_count, lumped_halves
from torsio.model.lumped import LumpedModel

if TYPE_CHECKING:
    from torsio.axial.wave_assembly import PipeSection

__all__ = [
    "assembly_description",
    "assembly_summary",
    "axial_chain",
    "axial_kernel_rows",
    "fastest_damping_rate",
    "fastest_frequency",
    "is_two_dof",
    "lumped_pipe",
    "pipe_assembly",
    "require_axial",
    "rgd_two_dof_example",
    "steady_angles",
    "steady_positions",
    "torsional_kernel_rows",
    "two_dof_assembly",
]


def axial_chain(
    inertias: Any,
    stiffnesses: Any,
    masses: Any,
    axial_stiffnesses: Any = (),
    dampings: Any = None,
    axial_dampings: Any = None,
    hook: str = "weight",
    node_depths: Any = None,
) -> LumpedModel:
    """A lumped chain of nodes that turn and move axially, the bit on the last one.

    Parameters
    ----------
    inertias, stiffnesses, dampings : array (n,)
        Torsional inertias I_i [kg m²], springs k_i [N m/rad] (k_0 joins the top drive to
        node 0) and dampers c_i [N m s/rad] in parallel with them (default none).
    masses, axial_stiffnesses, axial_dampings : array (n,)
        Axial masses m_i [kg], springs k_a,i [N/m] (k_a,0 joins the hook to node 0; empty:
        the nodes move axially as one body, weight hook only) and dampers c_a,i [N s/m].
    hook : str
        ``"weight"`` or ``"speed"`` (:mod:`torsio.model.axial_rows`).
    node_depths : array (n,), optional
        Depth of each node [m]; defaults to 1, 2, ..., n.

    Raises
    ------
    ConfigError
        Naming the file's keys (``chain.inertias[0]``, ``chain.masses``, ``axial.hook``).
    """
    if not np.size(inertias):
        raise ConfigError("chain.inertias", "is empty; expected one inertia per node")
    dampings = dampings if dampings is None or np.size(dampings) else None  # []: none
    try:
        chain = LumpedModel.from_chain(
            inertias, stiffnesses, dampings=dampings, node_depths=node_depths, strategy="chain"
        )
    except ConfigError as exc:  # from_chain names its arguments; the file names chain.*
        known = exc.key.split("[")[0] in ("inertias", "stiffnesses", "dampings")
        raise ConfigError(f"chain.{exc.key}" if known else exc.key, exc.message) from None
    check_count("chain.masses", read_only_vector(masses), chain.dofs)
    return chain.with_axial(AxialRows(masses, axial_stiffnesses, axial_dampings, hook))


def require_axial(assembly: LumpedModel) -> AxialRows:
    """The axial rows of a lumped assembly (a ConfigError on ``chain.masses`` without)."""
    if assembly.axial is None:
        raise ConfigError(
            "chain.masses", "missing: the chain has no axial rows (LumpedModel.with_axial)"
        )
    return assembly.axial


def is_two_dof(assembly: Any) -> bool:
    """Whether ``assembly`` is the 2-DOF model of RGD (2007): one node under the weight hook
    (:func:`two_dof_assembly`), whose characteristic equation
    :func:`torsio.axial.linearization.characteristic_function` writes out."""
    return bool(
        assembly.linearizable and assembly.dofs == 1 and require_axial(assembly).hook == "weight"
    )


def torsional_kernel_rows(assembly: LumpedModel) -> NDArray[np.float64]:
    """The axial kernel's torsional rows 1/I, k, c (:mod:`torsio.axial.kernel`)."""
    return np.ascontiguousarray(
        [1.0 / assembly.node_inertias, assembly.springs, assembly.dampers], dtype=float
    )


def axial_kernel_rows(assembly: LumpedModel) -> NDArray[np.float64]:
    """The axial kernel's axial rows 1/m, k_a, c_a; one row of the rigid body's Σ m
    without axial springs (:mod:`torsio.axial.kernel`)."""
    axial = require_axial(assembly)
    if axial.stiffnesses.size:
        return np.ascontiguousarray([1.0 / axial.masses, axial.stiffnesses, axial.dampings])
    return np.array([[1.0 / axial.masses.sum()], [0.0], [0.0]])


def _node_rates(elements: NDArray[np.float64], inertias: NDArray[np.float64]) -> NDArray:
    """(e_i + e_i+1)/I_i: each node's share of its two elements (springs [1/s²] or dampers
    [1/s]) over its inertia or mass."""
    total = np.array(elements, dtype=float)
    total[:-1] += elements[1:]
    return total / inertias


def fastest_frequency(assembly: LumpedModel) -> float:
    """An upper bound [rad/s] of the chain's node frequencies, √((k_i + k_i+1)/I_i) and
    √((k_a,i + k_a,i+1)/m_i): what the explicit step must resolve."""
    axial = require_axial(assembly)
    rates = [_node_rates(assembly.springs, assembly.node_inertias)]
    if axial.stiffnesses.size:
        rates.append(_node_rates(axial.stiffnesses, axial.masses))
    return float(np.sqrt(max(r.max() for r in rates)))


def fastest_damping_rate(assembly: LumpedModel) -> float:
    """An upper bound [1/s] of the dampers' rates, the eigenvalues of M⁻¹C:
    2 (c_i + c_i+1)/I_i and 2 (c_a,i + c_a,i+1)/m_i (Gershgorin's discs; a uniform chain
    reaches it at its shortest wave). The explicit dampers' step keeps h times it at
    most :data:`torsio.axial.run_setup.DAMPER_STEP`."""
    axial = require_axial(assembly)
    rates = [2.0 * _node_rates(assembly.dampers, assembly.node_inertias)]
    if axial.stiffnesses.size:
        rates.append(2.0 * _node_rates(axial.dampings, axial.masses))
    return float(max(r.max() for r in rates))


def steady_angles(assembly: LumpedModel, torque: Any) -> NDArray[np.float64]:
    """Node angles [rad] relative to the top in steady drilling, each torsional spring
    carrying the bit torque [N m] (or, as an array, spring j its own: with friction along
    the string, :func:`torsio.axial.steady_friction.steady_loads`): −Σ_j≤i T_j/k_j."""
    return -np.cumsum(torque / assembly.springs)


def steady_positions(assembly: LumpedModel, weight: Any) -> NDArray[np.float64]:
    """Axial positions [m] relative to the bit in steady drilling, each axial spring
    carrying the weight [N] (or, as an array, spring j its own): Σ_j>i W_j/k_a,j (0 at the
    bit); the rigid body's one position 0."""
    axial = require_axial(assembly)
    if not axial.stiffnesses.size:
        return np.zeros(1)
    springs = weight / axial.stiffnesses
    return np.concatenate([np.cumsum(springs[:0:-1])[::-1], [0.0]])


def assembly_description(assembly: Any) -> dict[str, Any]:
    """Plain data on a lumped or distributed assembly, for reports and JSON: a chain's
    kind, the strategy that lumped it (``"chain"``: a ``[chain]`` given directly), nodes,
    axial DOFs, hook and vectors; a distributed pipe's ``describe()``."""
    if not assembly.has_matrices:  # the distributed pipe
        return dict(assembly.describe())
    axial = require_axial(assembly)
    return {
        "kind": "lumped",
        "strategy": assembly.strategy,
        "nodes": assembly.dofs,
        "axial_dofs": axial.dofs,
        "hook": axial.hook,
        "inertias": assembly.node_inertias.tolist(),
        "stiffnesses": assembly.springs.tolist(),
        "masses": axial.masses.tolist(),
        "axial_stiffnesses": axial.stiffnesses.tolist(),
    }


def two_dof_assembly(
    inertia: float, stiffness: float, mass: float, damping: float = 0.0
) -> LumpedModel:
    """The 2-DOF model of RGD (2007): the BHA (I [kg m²], M [kg]) under the hook weight,
    a torsional spring k [N m/rad] and damper c [N m s/rad] to the top drive."""
    return axial_chain([inertia], [stiffness], [mass], dampings=[damping])


def rgd_two_dof_example() -> LumpedModel:
    """The 2-DOF example of docs/axial.md: I = 455.65 kg m², k = 324.857 N m/rad (strategy A
    of the built-in Ritto 2017 string), M = 29981.3 kg (DESIGN.md's ``[chain] masses``),
    c = β k = 19.49 N m s/rad (the built-in β = 0.06 s)."""
    return two_dof_assembly(455.65, 324.857, 29981.3, damping=19.49)


def pipe_assembly(
    nodes: int, pipe: PipeSection, bha_mass: float, bha_inertia: float, *, hook: str = "weight"
) -> LumpedModel:
    """A uniform ``pipe`` section (length [m], E, G [Pa], ρ [kg/m³], A [m²], J [m⁴]:
    :class:`~torsio.axial.wave_assembly.PipeSection`) in ``nodes`` lumps above a rigid BHA
    on the last one: the one-section chain of the lumping of every pipe
    (:func:`lumped_pipe`, elements of length / ``nodes``).

    Springs E A / Δ [N/m] and G J / Δ [N m/rad] with Δ = length / nodes join the top to
    node 0 and each node to the next, so node i is (i + 1) Δ below the top and the last one
    at the bottom. Each cell's mass ρ A Δ [kg] and inertia ρ J Δ [kg m²] is shared by the
    nodes at its ends: every node carries one cell, the last one half a cell (and the BHA's
    ``bha_mass`` [kg] and ``bha_inertia`` [kg m²]). The top cell's upper half is at the top
    drive (torsionally) and at the hook moving at its set speed (``hook = "speed"``); under
    the weight hook the top of the pipe is free, so node 0 carries it as well (1.5 cells):
    the frequencies converge to the continuum's like 1/nodes² (tests/test_axial_wave.py).
    """
    if not (isinstance(nodes, int) and nodes >= 1):
        raise ConfigError("nodes", f"{nodes!r} must be a whole number >= 1")
    return lumped_pipe([pipe], bha_mass, bha_inertia, pipe.length / nodes, hook)


def lumped_pipe(
    sections: Sequence[PipeSection],
    bha_mass: float,
    bha_inertia: float,
    element_length: float,
    hook: str,
    beta: float = 0.0,
) -> LumpedModel:
    """The lumped chain of the pipe ``sections`` above a rigid BHA (``bha_mass`` [kg],
    ``bha_inertia`` [kg m²]): each section split into elements of at most
    ``element_length`` [m], with springs E A / Δ [N/m] and G J / Δ [N m/rad] and dampers
    β k (``beta`` [s]); each element's mass ρ A Δ and inertia ρ J Δ shared by its two end
    nodes, the BHA rigid on the last node; its nodes' depths [m below the pipe's top] the
    bottoms of the elements. The top element's upper half of inertia is at the top drive;
    its upper half of mass at the hook under the speed hook, on node 0 under the weight
    hook (the top of the pipe is free there). The one lumping of an axial pipe
    (:func:`torsio.axial.assembly.pipe_assembly` is its uniform case), by the rules of
    the torsional discretizers (:func:`torsio.model.discretize.element_count`,
    :func:`~torsio.model.discretize.lumped_halves`): its torsional rows are strategy C's
    with ``max_element_length`` (tests/test_axial_wave_config.py).
    """
    elements: list[tuple[PipeSection, float]] = []  # each element's section and length Δ
    depths: list[float] = []  # each node's, at the bottom of its element [m below the top]
    top = 0.0
    for section in sections:
        count = element_count(section.length, element_length)
        elements += [(section, section.length / count)] * count
        depths.extend(top + section.length * np.arange(1, count + 1) / count)
        top += section.length
    torsional = np.array([s.shear_modulus * s.polar_moment / d for s, d in elements])
    axial = np.array([s.youngs_modulus * s.area / d for s, d in elements])
    element_masses = [s.density * s.area * d for s, d in elements]
    inertias = lumped_halves(np.array([s.density * s.polar_moment * d for s, d in elements]))
    inertias[-1] += bha_inertia
    rows = element_axial_rows(axial, element_masses, bha_mass, hook)
    return axial_chain(
        inertias=inertias,
        stiffnesses=torsional,
        masses=rows.masses,
        axial_stiffnesses=axial,
        dampings=beta * torsional if beta else None,
        axial_dampings=beta * axial,
        hook=hook,
        node_depths=depths,
    )


def assembly_summary(model: dict[str, Any]) -> str:
    """One line on an assembly from its ``describe()``: a chain's nodes, or a distributed
    pipe's sections, with the hook and the total mass."""
    if model.get("kind") == "distributed":
        sections = model["sections"]
        length = sum(s["length"] for s in sections)
        pipe_mass = sum(s["density"] * s["area"] * s["length"] for s in sections)
        return (
            f"distributed pipe, {len(sections)} section(s), {length:.6g} m, hook "
            f"{model['hook']}, total mass {(pipe_mass + model['bha_mass']) / 1e3:.4g} t "
            f"(BHA {model['bha_mass'] / 1e3:.4g} t, rigid)"
        )
    lumped = "" if model.get("strategy", "chain") == "chain" else f" (strategy {model['strategy']})"
    return (
        f"{model['nodes']} node(s){lumped}, {model['axial_dofs']} axial DOF, hook "
        f"{model['hook']}, total mass {sum(model['masses']) / 1e3:.4g} t"
    )
