"""The axial degrees of freedom of a model: what a :class:`~torsio.model.lumped.LumpedModel`
carries when its nodes also move along the hole (:class:`AxialRows`,
:meth:`LumpedModel.with_axial`), and a :class:`~torsio.model.wave.WaveModel` when its pipe
carries axial waves too (:class:`PipeAxialRows`, :meth:`WaveModel.with_axial`). A
discretizer builds them from the string's sections (``axial_rows(string, hook)``).

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

import math
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.errors import ConfigError
from torsio.model.arrays import check_count, check_values, read_only_vector

__all__ = ["HOOKS", "AxialRows", "PipeAxialRows", "check_hook", "youngs_modulus"]

HOOKS = ("weight", "speed")
"""The boundaries at the hook: a constant weight on the top node, or a constant speed."""


def check_hook(hook: str) -> None:
    """Raise a ConfigError on ``axial.hook`` unless ``hook`` is one of :data:`HOOKS` (the
    lumped chain's and the distributed pipe's one check)."""
    if hook not in HOOKS:
        raise ConfigError("axial.hook", f"{hook!r} is not one of {', '.join(HOOKS)}")


def youngs_modulus(section: Any) -> float:
    """E [Pa] of a section's material; a ConfigError on ``material.youngs_modulus``
    without (axial springs and waves need it)."""
    value = section.material.youngs_modulus
    if value is None:
        raise ConfigError(
            "material.youngs_modulus",
            f"missing: axial dynamics need Young's modulus E of {section.describe()} "
            "for its springs E A / L (e.g. youngs_modulus = '207 GPa')",
        )
    return float(value)


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
            check_count("chain.axial_stiffnesses", self.stiffnesses, n)
            check_values("chain.axial_stiffnesses", self.stiffnesses, False)
        if not self.dampings.size:  # none given: no dampers
            object.__setattr__(self, "dampings", read_only_vector(np.zeros(self.dofs)))
        check_count("chain.axial_dampings", self.dampings, self.dofs)
        check_values("chain.axial_dampings", self.dampings, True)
        check_hook(self.hook)
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

    def describe(self) -> dict[str, Any]:
        """Plain data for reports and JSON: the axial DOFs, the hook, the total mass [kg].

        >>> AxialRows([1.0e4, 2.0e4], stiffnesses=[5.0e6, 5.0e6], hook="speed").describe()
        {'axial_dofs': 2, 'hook': 'speed', 'total_mass_kg': 30000.0}
        """
        return {
            "axial_dofs": self.dofs,
            "hook": self.hook,
            "total_mass_kg": float(self.masses.sum()),
        }


@attrs.frozen(eq=False)
class PipeAxialRows:
    """The axial lines of a distributed pipe's sections, and the rigid BHA below them.

    Built by :meth:`torsio.model.wave.WaveStrategy.axial_rows` from the string's drill
    pipes (E, ρ, A of each) and its BHA and bit; the torsional lines are the
    :class:`~torsio.model.wave.WaveModel`'s own.

    Parameters
    ----------
    wave_speeds : array (sections,)
        c = √(E/ρ) of each section [m/s].
    impedances : array (sections,)
        Z = A √(E ρ) [N s/m]; the section's E A is Z c.
    bha_mass : float
        m_b, Σ ρ A L of the BHA's sections and the bit [kg].
    hook : str
        ``"weight"``: the constant force W₀ on the top of the pipe (its top free, the
        whole pipe carrying W₀ in steady drilling), or ``"speed"``: the top of the pipe
        moving down at the steady rate of penetration V₀ of the run's (W₀, Ω₀).

    Examples
    --------
    >>> rows = PipeAxialRows([5172.2], [138046.0], 3.0e4, hook="speed")
    >>> round(float(rows.rigidities[0]) / 1e6)  # E A [MN]
    714
    """

    wave_speeds: NDArray[np.float64] = attrs.field(converter=read_only_vector)
    impedances: NDArray[np.float64] = attrs.field(converter=read_only_vector)
    bha_mass: float
    hook: str = "weight"

    def __attrs_post_init__(self) -> None:
        sections = self.wave_speeds.size
        if not sections or self.impedances.size != sections:
            raise ConfigError(
                "axial.impedances",
                f"{self.impedances.size} impedances and {sections} wave speeds: expected one "
                "of each per pipe section, at least one",
            )
        check_values("axial.wave_speeds", self.wave_speeds, False)
        check_values("axial.impedances", self.impedances, False)
        mass = self.bha_mass
        if isinstance(mass, bool) or not isinstance(mass, int | float | np.floating):
            raise ConfigError("bha_mass", f"expected a mass [kg], got {mass!r}")
        if not (math.isfinite(mass) and mass > 0):
            raise ConfigError("bha_mass", f"expected a positive finite mass [kg], got {mass!r}")
        object.__setattr__(self, "bha_mass", float(mass))
        check_hook(self.hook)

    @property
    def rigidities(self) -> NDArray[np.float64]:
        """E A = Z c of each section [N]."""
        return self.impedances * self.wave_speeds

    def describe(self) -> dict[str, Any]:
        """Plain data for reports and JSON: the hook, the BHA's mass [kg], each section's
        axial wave speed [m/s] and impedance [N s/m]."""
        return {
            "hook": self.hook,
            "bha_mass_kg": self.bha_mass,
            "axial_wave_speeds_m_s": self.wave_speeds.tolist(),
            "axial_impedances_N_s_m": self.impedances.tolist(),
        }
