"""The axial degrees of freedom of a lumped chain: what a :class:`~torsio.model.lumped.LumpedModel`
carries when its nodes also move along the hole (:meth:`LumpedModel.with_axial`).

Node i has an axial mass m_i; spring k_a,i and damper c_a,i join node i − 1 to node i,
node −1 being the hook:

- ``hook = "weight"``: the hook weight W₀ acts on node 0 (the string above it carries W₀
  whatever its stiffness, so k_a,0 is not used). Without axial springs the nodes move
  axially as one rigid body of mass Σ m_i (RGD 2007's form: the axial stiffness of the
  string neglected).
- ``hook = "speed"``: the hook moves down at a constant speed, the steady rate of
  penetration V₀ of the run's (W₀, Ω₀), through k_a,0 and c_a,0; it needs axial springs.

Examples
--------
>>> rows = AxialRows([3.0e4], hook="weight")  # the 2-DOF model's rigid body
>>> rows.dofs, rows.bit_mass
(1, 30000.0)
>>> AxialRows([1.0e4, 2.0e4], stiffnesses=[5.0e6, 5.0e6]).dofs
2
"""

from __future__ import annotations

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.errors import ConfigError
from torsio.model.arrays import check_values, read_only_vector

__all__ = ["HOOKS", "AxialRows", "node_rates"]

HOOKS = ("weight", "speed")
"""The boundaries at the hook: a constant weight on the top node, or a constant speed."""


def _same_size(key: str, values: NDArray[np.float64], size: int) -> None:
    if values.size != size:
        raise ConfigError(key, f"has {values.size} values; expected {size}, one per node")


@attrs.frozen(eq=False)
class AxialRows:
    """Axial masses, springs and dampers of a chain's nodes, and the hook above them.

    Parameters
    ----------
    masses : array (n,)
        Axial masses m_i [kg].
    stiffnesses : array (n,) or empty
        Axial springs k_a,i [N/m]; k_a,0 joins the hook to node 0. Empty: the nodes move
        axially as one body (weight hook only).
    dampings : array (n,) or empty
        Axial dampers c_a,i [N s/m] in parallel with the springs (default none).
    hook : str
        ``"weight"`` or ``"speed"`` (see the module docstring).
    """

    masses: NDArray[np.float64] = attrs.field(converter=read_only_vector)
    stiffnesses: NDArray[np.float64] = attrs.field(converter=read_only_vector, factory=tuple)
    dampings: NDArray[np.float64] = attrs.field(converter=read_only_vector, default=None)
    hook: str = "weight"

    def __attrs_post_init__(self) -> None:
        n = self.masses.size
        if n == 0:
            raise ConfigError("chain.masses", "is empty; expected one mass per node")
        check_values("chain.masses", self.masses, False)
        if self.stiffnesses.size:
            _same_size("chain.axial_stiffnesses", self.stiffnesses, n)
            check_values("chain.axial_stiffnesses", self.stiffnesses, False)
        if not self.dampings.size:  # none given: no dampers
            object.__setattr__(self, "dampings", read_only_vector(np.zeros(self.dofs)))
        _same_size("chain.axial_dampings", self.dampings, self.dofs)
        check_values("chain.axial_dampings", self.dampings, True)
        if self.hook not in HOOKS:
            raise ConfigError("axial.hook", f"{self.hook!r} is not one of {', '.join(HOOKS)}")
        if self.hook == "speed" and not self.stiffnesses.size:
            raise ConfigError(
                "axial.hook",
                "'speed' needs chain.axial_stiffnesses (the spring k_a,0 joins the hook to "
                "node 0); with none the string is rigid and only 'weight' applies",
            )

    @property
    def dofs(self) -> int:
        """Axial degrees of freedom: n with axial springs, 1 (the rigid body) without."""
        return int(self.masses.size) if self.stiffnesses.size else 1

    @property
    def bit_mass(self) -> float:
        """The axial mass [kg] of the degree of freedom that carries the bit."""
        return float(self.masses[-1] if self.stiffnesses.size else self.masses.sum())

    def kernel_rows(self) -> NDArray[np.float64]:
        """The axial kernel's rows 1/m, k_a, c_a (:mod:`torsio.axial.kernel`)."""
        if self.stiffnesses.size:
            return np.ascontiguousarray(
                [1.0 / self.masses, self.stiffnesses, self.dampings], dtype=float
            )
        return np.array([[1.0 / self.masses.sum()], [0.0], [0.0]])

    def steady_positions(self, weight: NDArray[np.float64] | float) -> NDArray[np.float64]:
        """Node positions [m] relative to the bit in steady drilling, each spring carrying
        the weight [N] (or, as an array, spring j its own): Σ_j>i W_j/k_a,j (0 at the bit);
        the rigid body's one position 0."""
        if not self.stiffnesses.size:
            return np.zeros(1)
        springs = weight / self.stiffnesses
        return np.concatenate([np.cumsum(springs[:0:-1])[::-1], [0.0]])


def node_rates(elements: NDArray[np.float64], inertias: NDArray[np.float64]) -> NDArray:
    """(e_i + e_i+1)/I_i [1/s or 1/s²]: each node's share of its two elements (springs or
    dampers) over its inertia or mass."""
    total = np.array(elements, dtype=float)
    total[:-1] += elements[1:]
    return total / inertias
