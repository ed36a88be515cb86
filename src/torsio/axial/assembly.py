"""Lumped drilling assemblies that move axially and torsionally: nodes on a chain.

Each node i has a torsional inertia I_i and an axial mass m_i. Torsionally, spring k_i and
damper c_i join node i − 1 to node i, node −1 being the top drive turning at Ω₀; the last
node carries the bit. Axially, spring k_a,i and damper c_a,i join node i − 1 to node i,
node −1 being the hook:

- ``hook = "weight"``: the hook weight W₀ acts on node 0 (the string above it carries W₀
  whatever its stiffness, so k_a,0 is not used). Without axial springs the nodes move
  axially as one rigid body of mass Σ m_i (RGD 2007's form: the axial stiffness of the
  string neglected).
- ``hook = "speed"``: the hook moves down at a constant speed, the steady rate of
  penetration V₀ of the run's (W₀, Ω₀), through k_a,0 and c_a,0; it needs axial springs.

The 2-DOF model of Richard, Germay and Detournay (2007) is one node, no axial spring:
:func:`two_dof_assembly`. :func:`pipe_assembly` splits a uniform pipe section
(:class:`~torsio.axial.wave_assembly.PipeSection`) into nodes with springs E A / L and
G J / L (L the node spacing) and the BHA on the last node.

Examples
--------
>>> assembly = rgd_two_dof_example()
>>> assembly.nodes, assembly.axial_dofs, assembly.hook
(1, 1, 'weight')
>>> from torsio.axial.wave_assembly import PipeSection
>>> pipe = PipeSection(1000.0, 2.0e11, 8.0e10, 7850.0, 3.4e-3, 1.5e-5)
>>> chain = pipe_assembly(4, pipe, 3.0e4, 230.0)
>>> round(float(chain.axial_stiffnesses[1]) / 1e6, 3)  # E A / (L / n), MN/m
2.72
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.errors import ConfigError
from torsio.model.arrays import read_only_vector
from torsio.model.discretize import element_count, lumped_halves

if TYPE_CHECKING:
    from torsio.axial.wave_assembly import PipeSection

__all__ = [
    "DrillingAssembly",
    "assembly_summary",
    "lumped_node_depths",
    "lumped_pipe",
    "pipe_assembly",
    "rgd_two_dof_example",
    "two_dof_assembly",
]

HOOKS = ("weight", "speed")
"""The boundaries at the hook: a constant weight on the top node, or a constant speed."""


def _check(key: str, values: NDArray[np.float64], allow_zero: bool) -> None:
    bad = ~np.isfinite(values) | ((values < 0) if allow_zero else (values <= 0))
    if bad.any():
        i = int(np.argmax(bad))
        expected = "non-negative" if allow_zero else "positive"
        raise ConfigError(f"{key}[{i}]", f"expected a {expected} finite value, got {values[i]!r}")


def _same_size(key: str, values: NDArray[np.float64], size: int) -> None:
    if values.size != size:
        raise ConfigError(key, f"has {values.size} values; expected {size}, one per node")


@attrs.frozen(eq=False)
class DrillingAssembly:
    """A lumped chain of nodes that turn and move axially, the bit on the last one.

    Parameters
    ----------
    inertias : array (n,)
        Torsional inertias I_i [kg m²].
    stiffnesses : array (n,)
        Torsional springs k_i [N m/rad]; k_0 joins the top drive to node 0.
    masses : array (n,)
        Axial masses m_i [kg].
    axial_stiffnesses : array (n,) or empty
        Axial springs k_a,i [N/m]; k_a,0 joins the hook to node 0. Empty: the nodes move
        axially as one body (weight hook only).
    damping : array (n,)
        Torsional dampers c_i [N m s/rad] in parallel with the springs (default none).
    axial_damping : array (n,)
        Axial dampers c_a,i [N s/m] in parallel with the axial springs (default none).
    hook : str
        ``"weight"`` or ``"speed"`` (see the module docstring).
    """

    inertias: NDArray[np.float64] = attrs.field(converter=read_only_vector)
    stiffnesses: NDArray[np.float64] = attrs.field(converter=read_only_vector)
    masses: NDArray[np.float64] = attrs.field(converter=read_only_vector)
    axial_stiffnesses: NDArray[np.float64] = attrs.field(converter=read_only_vector, factory=tuple)
    damping: NDArray[np.float64] = attrs.field(converter=read_only_vector, default=None)
    axial_damping: NDArray[np.float64] = attrs.field(converter=read_only_vector, default=None)
    hook: str = "weight"

    def __attrs_post_init__(self) -> None:
        n = self.inertias.size
        if n == 0:
            raise ConfigError("chain.inertias", "is empty; expected one inertia per node")
        _check("chain.inertias", self.inertias, False)
        for key, values, zero in (
            ("chain.stiffnesses", self.stiffnesses, False),
            ("chain.masses", self.masses, False),
        ):
            _same_size(key, values, n)
            _check(key, values, zero)
        if not self.damping.size:  # none given: no dampers
            object.__setattr__(self, "damping", read_only_vector(np.zeros(n)))
        _same_size("chain.damping", self.damping, n)
        _check("chain.damping", self.damping, True)
        if self.axial_stiffnesses.size:
            _same_size("chain.axial_stiffnesses", self.axial_stiffnesses, n)
            _check("chain.axial_stiffnesses", self.axial_stiffnesses, False)
        m = self.axial_dofs
        if not self.axial_damping.size:
            object.__setattr__(self, "axial_damping", read_only_vector(np.zeros(m)))
        _same_size("chain.axial_damping", self.axial_damping, m)
        _check("chain.axial_damping", self.axial_damping, True)
        if self.hook not in HOOKS:
            raise ConfigError("axial.hook", f"{self.hook!r} is not one of {', '.join(HOOKS)}")
        if self.hook == "speed" and not self.axial_stiffnesses.size:
            raise ConfigError(
                "axial.hook",
                "'speed' needs chain.axial_stiffnesses (the spring k_a,0 joins the hook to "
                "node 0); with none the string is rigid and only 'weight' applies",
            )

    @property
    def nodes(self) -> int:
        """The number of torsional nodes n (the last one carries the bit)."""
        return int(self.inertias.size)

    @property
    def axial_dofs(self) -> int:
        """Axial degrees of freedom: n with axial springs, 1 (the rigid body) without."""
        return int(self.masses.size) if self.axial_stiffnesses.size else 1

    @property
    def is_two_dof(self) -> bool:
        """Whether this is the 2-DOF model of RGD (2007): one node under the weight hook
        (:func:`two_dof_assembly`), whose characteristic equation
        :func:`torsio.axial.linearization.characteristic_function` writes out."""
        return self.nodes == 1 and self.hook == "weight"

    @property
    def bit_mass(self) -> float:
        """The axial mass [kg] of the degree of freedom that carries the bit."""
        return float(self.masses[-1] if self.axial_stiffnesses.size else self.masses.sum())

    def axial_rows(self) -> NDArray[np.float64]:
        """The kernel's axial rows 1/m, k_a, c_a (:mod:`torsio.axial.kernel`)."""
        if self.axial_stiffnesses.size:
            return np.ascontiguousarray(
                [1.0 / self.masses, self.axial_stiffnesses, self.axial_damping], dtype=float
            )
        return np.array([[1.0 / self.masses.sum()], [0.0], [0.0]])

    def torsional_rows(self) -> NDArray[np.float64]:
        """The kernel's torsional rows 1/I, k, c (:mod:`torsio.axial.kernel`)."""
        return np.ascontiguousarray([1.0 / self.inertias, self.stiffnesses, self.damping])

    def first_frequency(self) -> float:
        """ω₁ [rad/s] of the torsional chain, top held, undamped
        (:func:`torsio.model.modal.pencil_first_frequency`)."""
        from torsio.model.lumped import chain_matrix  # scipy: not at import
        from torsio.model.modal import pencil_first_frequency

        return pencil_first_frequency(chain_matrix(self.stiffnesses), np.diag(self.inertias))

    def fastest_frequency(self) -> float:
        """An upper bound [rad/s] of the chain's node frequencies, √((k_i + k_i+1)/I_i) and
        √((k_a,i + k_a,i+1)/m_i): what the explicit step must resolve."""
        frequencies = [_node_frequencies(self.stiffnesses, self.inertias)]
        if self.axial_stiffnesses.size:
            frequencies.append(_node_frequencies(self.axial_stiffnesses, self.masses))
        return float(max(f.max() for f in frequencies))

    def fastest_damping_rate(self) -> float:
        """An upper bound [1/s] of the dampers' rates, the eigenvalues of M⁻¹C:
        2 (c_i + c_i+1)/I_i and 2 (c_a,i + c_a,i+1)/m_i (Gershgorin's discs; a uniform chain
        reaches it at its shortest wave). The explicit dampers' step keeps h times it at
        most :data:`torsio.axial.run_setup.DAMPER_STEP`."""
        rates = [2.0 * _node_rates(self.damping, self.inertias)]
        if self.axial_stiffnesses.size:
            rates.append(2.0 * _node_rates(self.axial_damping, self.masses))
        return float(max(r.max() for r in rates))

    def steady_offsets(self, torque: Any, weight: Any) -> tuple[NDArray, NDArray]:
        """Node angles [rad] relative to the top and positions [m] relative to the bit in
        steady drilling: each torsional spring carries the bit torque, each axial spring
        the weight (or, as arrays, spring j its own: with friction along the string,
        :func:`torsio.axial.steady_friction.steady_loads`). Angles −Σ_j≤i T_j/k_j;
        positions Σ_j>i W_j/k_a,j (0 at the bit)."""
        angles = -np.cumsum(torque / self.stiffnesses)
        if not self.axial_stiffnesses.size:
            return angles, np.zeros(1)
        springs = weight / self.axial_stiffnesses
        positions = np.concatenate([np.cumsum(springs[:0:-1])[::-1], [0.0]])
        return angles, positions

    def describe(self) -> dict[str, Any]:
        """Plain data for reports and JSON."""
        return {
            "kind": "lumped",
            "nodes": self.nodes,
            "axial_dofs": self.axial_dofs,
            "hook": self.hook,
            "inertias": self.inertias.tolist(),
            "stiffnesses": self.stiffnesses.tolist(),
            "masses": self.masses.tolist(),
            "axial_stiffnesses": self.axial_stiffnesses.tolist(),
        }


def _node_frequencies(springs: NDArray, inertias: NDArray) -> NDArray:
    return np.sqrt(_node_rates(springs, inertias))


def _node_rates(elements: NDArray, inertias: NDArray) -> NDArray:
    """(e_i + e_i+1)/I_i: each node's share of its two elements (springs or dampers)."""
    total = elements.copy()
    total[:-1] += elements[1:]
    return total / inertias


def two_dof_assembly(
    inertia: float, stiffness: float, mass: float, damping: float = 0.0
) -> DrillingAssembly:
    """The 2-DOF model of RGD (2007): the BHA (I [kg m²], M [kg]) under the hook weight,
    a torsional spring k [N m/rad] and damper c [N m s/rad] to the top drive."""
    return DrillingAssembly([inertia], [stiffness], [mass], damping=[damping])


def rgd_two_dof_example() -> DrillingAssembly:
    """The 2-DOF example of docs/axial.md: I = 455.65 kg m², k = 324.857 N m/rad (strategy A
    of the built-in Ritto 2017 string), M = 29981.3 kg (DESIGN.md's ``[chain] masses``),
    c = β k = 19.49 N m s/rad (the built-in β = 0.06 s)."""
    return two_dof_assembly(455.65, 324.857, 29981.3, damping=19.49)


def pipe_assembly(
    nodes: int, pipe: PipeSection, bha_mass: float, bha_inertia: float, *, hook: str = "weight"
) -> DrillingAssembly:
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


def lumped_node_depths(
    sections: Sequence[PipeSection], element_length: float
) -> NDArray[np.float64]:
    """Depths [m below the pipe's top] of the nodes of :func:`lumped_pipe`: the bottom of
    each element (the last node carries the rigid BHA)."""
    depths: list[float] = []
    top = 0.0
    for section in sections:
        count = element_count(section.length, element_length)
        depths.extend(top + section.length * np.arange(1, count + 1) / count)
        top += section.length
    return np.array(depths)


def lumped_pipe(
    sections: Sequence[PipeSection],
    bha_mass: float,
    bha_inertia: float,
    element_length: float,
    hook: str,
    beta: float = 0.0,
) -> DrillingAssembly:
    """The lumped chain of the pipe ``sections`` above a rigid BHA (``bha_mass`` [kg],
    ``bha_inertia`` [kg m²]): each section split into elements of at most
    ``element_length`` [m], with springs E A / Δ [N/m] and G J / Δ [N m/rad] and dampers
    β k; each element's mass ρ A Δ and inertia ρ J Δ shared by its two end nodes, the BHA
    rigid on the last node. The top element's upper half of inertia is at the top drive;
    its upper half of mass at the hook under the speed hook, on node 0 under the weight
    hook (the top of the pipe is free there). The one lumping of an axial pipe
    (:func:`torsio.axial.assembly.pipe_assembly` is its uniform case), by the rules of
    the torsional discretizers (:func:`torsio.model.discretize.element_count`,
    :func:`~torsio.model.discretize.lumped_halves`): its torsional rows are strategy C's
    with ``max_element_length`` (tests/test_axial_wave_config.py).
    """
    elements: list[tuple[PipeSection, float]] = []  # each element's section and length Δ
    for section in sections:
        count = element_count(section.length, element_length)
        elements += [(section, section.length / count)] * count
    torsional = np.array([s.shear_modulus * s.polar_moment / d for s, d in elements])
    axial = np.array([s.youngs_modulus * s.area / d for s, d in elements])
    element_masses = np.array([s.density * s.area * d for s, d in elements])
    inertias = lumped_halves(np.array([s.density * s.polar_moment * d for s, d in elements]))
    masses = lumped_halves(element_masses)
    inertias[-1] += bha_inertia
    masses[-1] += bha_mass
    if hook == "weight":  # the free top's half element rides on node 0
        masses[0] += element_masses[0] / 2
    return DrillingAssembly(
        inertias=inertias,
        stiffnesses=torsional,
        masses=masses,
        axial_stiffnesses=axial,
        damping=beta * torsional,
        axial_damping=beta * axial,
        hook=hook,
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
    return (
        f"{model['nodes']} node(s), {model['axial_dofs']} axial DOF, hook {model['hook']}, "
        f"total mass {sum(model['masses']) / 1e3:.4g} t"
    )
