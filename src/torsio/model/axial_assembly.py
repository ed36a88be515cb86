"""Drilling assemblies: models whose nodes (or pipe) turn and move axially, the bit below.

A lumped drilling assembly is a :class:`~torsio.model.lumped.LumpedModel` with axial rows
(:class:`~torsio.model.axial_rows.AxialRows`): node i has a torsional inertia I_i and an
axial mass m_i; torsionally, spring k_i and damper c_i join node i − 1 to node i, node −1
being the top drive turning at Ω₀; axially, spring k_a,i and damper c_a,i join node i − 1
to node i, node −1 being the hook (its boundaries: :mod:`torsio.model.axial_rows`). A
distributed one is a :class:`~torsio.model.wave.WaveModel` with axial rows
(:class:`~torsio.model.axial_rows.PipeAxialRows`): the drill pipes' axial and torsional
wave lines above the rigid BHA. :func:`axial_model` builds either from a string with its
discretizer; :func:`axial_chain` a chain from its vectors; the functions below read what
the axial engine needs from a chain (its kernel rows, its fastest rates, its steady angles
and positions).

The 2-DOF model of Richard, Germay and Detournay (2007) is one node, no axial spring:
:func:`two_dof_assembly`. A pipe given by its E, G, ρ, A and J above a BHA given by its
mass and inertia, as the papers give them, is a string of :func:`tube_section` and
:func:`rigid_bit` (:func:`pipe_string`).

Examples
--------
>>> assembly = rgd_two_dof_example()
>>> assembly.dofs, assembly.axial.dofs, assembly.axial.hook
(1, 1, 'weight')
>>> from torsio.model.discretize import StrategyC
>>> string = pipe_string([tube_section(1000.0, 2.0e11, 8.0e10, 7850.0, 3.4e-3, 1.5e-5)],
...                      3.0e4, 230.0)
>>> chain = axial_model(string, StrategyC(dp_elements=4))
>>> round(float(chain.axial.stiffnesses[1]) / 1e6, 3)  # E A / (L / n), MN/m
2.72
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from typing import Any, cast

import numpy as np
from numpy.typing import NDArray

from torsio.errors import ConfigError
from torsio.model.arrays import check_count, read_only_vector
from torsio.model.axial_rows import AxialRows, PipeAxialRows
from torsio.model.components import Bit, DrillPipe, Material, Section
from torsio.model.discretize import StrategyC
from torsio.model.drillstring import DrillString
from torsio.model.lumped import LumpedModel
from torsio.model.wave import WaveModel

DEFAULT_ELEMENT_LENGTH = 100.0
"""Largest element [m] of a lumped chain of pipe sections by default: ``[axial]
element_length``, and a distributed pipe's lumped twin (:func:`lumped_twin`)."""

__all__ = [
    "assembly_description",
    "assembly_summary",
    "axial_chain",
    "axial_kernel_rows",
    "axial_model",
    "check_axial_discretizer",
    "fastest_damping_rate",
    "fastest_frequency",
    "hook_of",
    "is_two_dof",
    "lumped_twin",
    "pipe_rows",
    "pipe_string",
    "require_axial",
    "rgd_two_dof_example",
    "rigid_bit",
    "steady_angles",
    "steady_positions",
    "torsional_kernel_rows",
    "tube_section",
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


def pipe_rows(pipe: WaveModel) -> PipeAxialRows:
    """The axial rows of a distributed pipe (a ConfigError on ``axial`` without)."""
    if pipe.axial is None:
        raise ConfigError(
            "axial",
            "missing: the wave model has no axial rows (expected axial_model(string, "
            "WaveStrategy(rigid_bha=True)), or WaveModel.with_axial)",
        )
    return pipe.axial


def hook_of(assembly: LumpedModel | WaveModel) -> str:
    """The hook of a chain's or a pipe's axial rows (:func:`require_axial`,
    :func:`pipe_rows`)."""
    if assembly.has_matrices:
        return require_axial(cast(LumpedModel, assembly)).hook
    return pipe_rows(cast(WaveModel, assembly)).hook


def is_two_dof(assembly: Any) -> bool:
    """Whether ``assembly`` is the 2-DOF model of RGD (2007): one node under the weight hook
    (:func:`two_dof_assembly`), whose characteristic equation
    :func:`torsio.axial.linearization.characteristic_function` writes out."""
    return bool(
        assembly.linearizable and assembly.dofs == 1 and require_axial(assembly).hook == "weight"
    )


def torsional_kernel_rows(assembly: LumpedModel) -> NDArray[np.float64]:
    """The axial kernel's torsional rows 1/I, k, c (:mod:`torsio.solvers.axial_kernel`)."""
    return np.ascontiguousarray(
        [1.0 / assembly.node_inertias, assembly.springs, assembly.dampers], dtype=float
    )


def axial_kernel_rows(assembly: LumpedModel) -> NDArray[np.float64]:
    """The axial kernel's axial rows 1/m, k_a, c_a; one row of the rigid body's Σ m
    without axial springs (:mod:`torsio.solvers.axial_kernel`)."""
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
    most :data:`torsio.solvers.axial_run_setup.DAMPER_STEP`."""
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
    axial DOFs, hook and vectors; a distributed pipe's sections (L, E, G, ρ, A, J), BHA
    and travel-time tolerance."""
    if not assembly.has_matrices:  # the distributed pipe
        sections = [
            {
                "length": s.length,
                "youngs_modulus": s.material.youngs_modulus,
                "shear_modulus": s.material.shear_modulus,
                "density": s.material.density,
                "area": s.area,
                "polar_moment": s.polar_moment,
            }
            for s in assembly.sections
        ]
        return {
            "kind": "distributed",
            "sections": sections,
            "bha_mass": pipe_rows(assembly).bha_mass,
            "bha_inertia": assembly.bit_inertia,
            "hook": pipe_rows(assembly).hook,
            "travel_time_tolerance": assembly.travel_time_tolerance,
        }
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


def axial_model(
    string: DrillString, discretizer: Any, hook: str = "weight"
) -> LumpedModel | WaveModel:
    """The drilling assembly of ``string`` by ``discretizer``: its model with the axial
    rows it builds on the same elements (``discretizer.axial_rows(string, hook)``), a
    lumped chain (strategies B, C, a plugin's) or the distributed pipe
    (``WaveStrategy(rigid_bha=True)``). Undamped; a chain takes dampers with
    :meth:`~torsio.model.lumped.LumpedModel.with_dampers` and ``attrs.evolve(rows,
    dampings=...)``."""
    check_axial_discretizer(discretizer)
    model: LumpedModel | WaveModel = discretizer.discretize(string)
    return model.with_axial(discretizer.axial_rows(string, hook))


def check_axial_discretizer(discretizer: Any) -> None:
    """A ConfigError on ``discretization.strategy`` unless ``discretizer`` builds axial
    rows (``axial_rows(string, hook)``)."""
    if not callable(getattr(discretizer, "axial_rows", None)):
        raise ConfigError(
            "discretization.strategy",
            f"{getattr(discretizer, 'name', discretizer)!r} builds no axial rows (springs "
            "E A / L and masses on its elements); axial dynamics take a discretizer with "
            "axial_rows ('B', 'C', the default, a plugin's, or 'wave')",
        )


def lumped_twin(pipe: WaveModel, element_length: float = DEFAULT_ELEMENT_LENGTH) -> LumpedModel:
    """The lumped chain of a distributed pipe's string (strategy C, elements of at most
    ``element_length`` [m]) under its hook, undamped like the pipe: what its stability's
    roots start from and where its contacts along the string are read."""
    strategy = StrategyC(max_element_length=element_length)
    return cast(LumpedModel, axial_model(pipe.string, strategy, pipe_rows(pipe).hook))


def _check_positive(key: str, value: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ConfigError(key, f"expected a number, got {value!r}")
    number = float(value)
    if not (math.isfinite(number) and number > 0):
        raise ConfigError(key, f"expected a positive finite value, got {value!r}")


def tube_section(
    length: float,
    youngs_modulus: float,
    shear_modulus: float,
    density: float,
    area: float,
    polar_moment: float,
) -> Section:
    """A drill pipe of ``length`` [m] whose body has the cross-section ``area`` A [m²] and
    polar moment ``polar_moment`` J [m⁴] (E, G [Pa], ρ [kg/m³]): the tube with
    od² + id² = 8 J / A and od² − id² = 4 A / π.

    >>> pipe = tube_section(1000.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 3.0e-5)
    >>> round(pipe.od, 4), round(pipe.id, 4), round(pipe.area / 3.4e-3, 12)
    (0.1935, 0.182, 1.0)
    """
    given = {"length": length, "youngs_modulus": youngs_modulus, "shear_modulus": shear_modulus,
             "density": density, "area": area, "polar_moment": polar_moment}  # fmt: skip
    for key, value in given.items():
        _check_positive(key, value)
    total, difference = 8.0 * polar_moment / area, 4.0 * area / math.pi
    if not total > difference:
        raise ConfigError(
            "polar_moment",
            f"{polar_moment!r} m⁴ with area {area!r} m² is no tube: expected J > A²/(2π) = "
            f"{area**2 / (2 * math.pi):.4g} m⁴",
        )
    material = Material(shear_modulus, density, youngs_modulus=youngs_modulus)
    od, inner = math.sqrt((total + difference) / 2), math.sqrt((total - difference) / 2)
    return DrillPipe(od=od, id=inner, length=length, material=material)


def rigid_bit(mass: float, inertia: float, material: Material) -> Bit:
    """A solid bit of ``material`` with the axial ``mass`` [kg] and the ``inertia``
    [kg m²] of a whole rigid BHA: od = √(8 I / m), its length m / (ρ A). A body for the
    models only: its od and length are no bit's (a radius for a bit law, contacts with a
    well and depths below it are the user's to give).

    >>> bit = rigid_bit(3.0e4, 230.0, Material(8.1e10, 7850.0, youngs_modulus=2.1e11))
    >>> round(bit.inertia, 9), round(bit.material.density * bit.area * bit.length, 6)
    (230.0, 30000.0)
    """
    _check_positive("bha_mass", mass)
    _check_positive("bha_inertia", inertia)
    if not isinstance(material, Material):
        raise ConfigError("material", f"expected a Material, got {material!r}")
    od = math.sqrt(8.0 * inertia / mass)
    length = mass / (material.density * math.pi * od**2 / 4.0)
    return Bit(od=od, id=0.0, length=length, material=material)


def pipe_string(pipes: Sequence[Section], bha_mass: float, bha_inertia: float) -> DrillString:
    """The string of drill ``pipes`` from the top down above a rigid BHA of ``bha_mass``
    [kg] and ``bha_inertia`` [kg m²] (:func:`rigid_bit`, of the last pipe's material)."""
    if isinstance(pipes, Section) or not isinstance(pipes, Sequence):
        raise ConfigError("pipes", f"expected a list of drill pipes, got {pipes!r}")
    if not pipes:
        raise ConfigError("pipes", "is empty; expected at least one drill pipe")
    for i, pipe in enumerate(pipes):
        if not isinstance(pipe, Section) or pipe.in_bha:
            raise ConfigError(
                f"pipes[{i}]",
                f"expected a drill pipe (tube_section; the BHA is bha_mass and bha_inertia), "
                f"got {pipe!r}",
            )
    return DrillString([*pipes, rigid_bit(bha_mass, bha_inertia, pipes[-1].material)])


def assembly_summary(model: dict[str, Any]) -> str:
    """One line on an assembly from :func:`assembly_description`'s data: a chain's nodes,
    or a distributed pipe's sections, with the hook and the total mass."""
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
