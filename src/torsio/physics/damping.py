"""Damping of a lumped model: Rayleigh [C] = alpha [I] + beta [K].

The stiffness-proportional part beta [K] acts across the springs (including the
one to the top drive, so c_1 = beta k_1); the mass-proportional part alpha [I]
damps each inertia's absolute rotation, like viscous drag of the mud on the
rotating string, and so takes torque even at steady rotation.

Examples
--------
>>> from torsio import StrategyA, ritto2017_string
>>> model = StrategyA().discretize(ritto2017_string())
>>> d = RayleighDamping.from_modal_ratios(model, ratios=(0.05, 0.05), modes=(1, 1))
Traceback (most recent call last):
...
torsio.errors.ConfigError: damping.modes: expected two different mode numbers, got (1, 1)
"""

from __future__ import annotations

import math

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.lumped import LumpedModel
from torsio.units import si_field


def _non_negative(instance: object, attribute: attrs.Attribute[float], value: float) -> None:
    if not (math.isfinite(value) and value >= 0):
        raise ConfigError(
            f"damping.{attribute.name}", f"expected a non-negative finite value, got {value!r}"
        )


@attrs.frozen
class RayleighDamping:
    """[C] = alpha [I] + beta [K].

    Parameters
    ----------
    alpha : float or str
        Mass-proportional coefficient [1/s] (or e.g. ``"0.35 1/s"``).
    beta : float or str
        Stiffness-proportional coefficient [s] (or e.g. ``"60 ms"``).
    """

    alpha: float = si_field("inverse_time", "alpha", default=0.0, validator=_non_negative)
    beta: float = si_field("time", "beta", default=0.0, validator=_non_negative)

    def matrix(self, model: LumpedModel) -> np.ndarray:
        """[C], in N m s/rad."""
        return self.alpha * model.inertia + self.beta * model.stiffness

    def top_coupling(self, model: LumpedModel) -> np.ndarray:
        """Damping between each node and the top drive, beta [K] 1 (c_1 e_1) [N m s/rad]."""
        return self.beta * model.top_stiffness

    def ratios(self, omega: np.ndarray) -> np.ndarray:
        """Modal damping ratios alpha/(2 omega) + beta omega/2 at frequencies omega [rad/s]."""
        omega = np.asarray(omega, dtype=float)
        return self.alpha / (2.0 * omega) + self.beta * omega / 2.0

    @classmethod
    def from_modal_ratios(
        cls, model: LumpedModel, ratios: tuple[float, float], modes: tuple[int, int] = (1, 2)
    ) -> RayleighDamping:
        """alpha and beta that give damping ratios ``ratios`` to modes ``modes`` (1-based).

        Solves zeta_i = alpha/(2 omega_i) + beta omega_i/2 for the two modes.
        """
        from torsio.model.modal import modal_analysis

        m1, m2 = modes
        if m1 == m2:
            raise ConfigError("damping.modes", f"expected two different mode numbers, got {modes}")
        if max(modes) > model.dofs or min(modes) < 1:
            raise ConfigError("damping.modes", f"the model has modes 1..{model.dofs}, got {modes}")
        omega = modal_analysis(model, max(modes)).frequencies_rad[[m1 - 1, m2 - 1]]
        matrix = np.array([[1 / (2 * omega[0]), omega[0] / 2], [1 / (2 * omega[1]), omega[1] / 2]])
        alpha, beta = np.linalg.solve(matrix, np.asarray(ratios, dtype=float))
        if alpha < 0 or beta < 0:
            raise ConfigError(
                "damping.ratios",
                f"ratios {ratios} at modes {modes} need a negative "
                f"Rayleigh coefficient (alpha={alpha:.3g}, beta={beta:.3g})",
            )
        return cls(alpha=alpha, beta=beta)


@attrs.frozen
class ModelDamping:
    """The damping a LumpedModel carries itself (e.g. a published lumped model's dampers)."""

    def matrix(self, model: LumpedModel) -> np.ndarray:
        """[C], in N m s/rad."""
        if model.damping is None:
            raise ConfigError("damping", "the model carries no damping; give Rayleigh damping")
        return np.asarray(model.damping)

    def top_coupling(self, model: LumpedModel) -> np.ndarray:
        """Damping between each node and the top drive [N m s/rad]."""
        assert model.top_damping is not None
        return np.asarray(model.top_damping)
