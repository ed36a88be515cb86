"""The constants and frequencies of the axial engine's step rule
(:mod:`torsio.solvers.axial_run_setup`
applies it, :mod:`torsio.solvers.axial_run_budget` checks the work it makes).

Examples
--------
>>> from torsio.axial.rgd import rgd_example
>>> round(contact_frequency(rgd_example(), 29981.3), 2)  # rad/s, on a 29 981.3 kg bit
32.21
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from torsio.physics.torque_law_bit import AxialBit

__all__ = ["DAMPER_STEP", "DEFAULT_STEPS_PER_PERIOD", "contact_frequency"]

DEFAULT_STEPS_PER_PERIOD = 100
"""Steps per period of the fastest frequency the run resolves (docs/axial.md, convergence)."""

DAMPER_STEP = 1.0
"""The largest h δ, δ the bound of the dampers' rates (the eigenvalues of M⁻¹C,
:func:`~torsio.model.axial_assembly.fastest_damping_rate`): half the bound
h δ < 2 − (h ω)²/2 within which semi-implicit Euler keeps a damped mode x'' + δ x' + ω² x
= 0 stable (its step matrix has determinant 1 − h δ and trace 2 − h δ − (h ω)²). The 4 m
chain of ``rgd_deviated_well.toml`` with β = 0.01 s diverged at h δ = 2 and closes its
energy balance at h δ = 1."""


def contact_frequency(bit: AxialBit, mass: float) -> float:
    """√(2 n ζ ε a / m_b) [rad/s]: where the bit's axial roots cross (docs/axial.md); 0 for
    a law of the torque alone (ζ ε a = 0: the rock does not yield)."""
    return math.sqrt(2 * bit.blades * bit.cutting_weight_per_depth / mass)
