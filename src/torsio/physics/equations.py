"""First-order equations of motion of a System for scipy, derived from its one description.

The equations, the state ordering and the Jacobian are those of
:class:`torsio.physics.dynamics.Dynamics` (nothing is written here a second time)::

    y = [z_0 .. z_{m-1}, phi_0, v_0, phi_1, v_1, ..., phi_{n-1}, v_{n-1}]

with z the top drive's controller states (none for a held top), phi = theta -
Omega_ref t and v = phi'. With lumped (diagonal) inertia the Jacobian is banded
(lower bandwidth 3 and upper 2 for a held top); with consistent mass it is full.

Examples
--------
>>> from torsio.examples import builtin_config
>>> eq = TwistEquations(builtin_config().system())
>>> y0 = eq.rest_state()          # start-up from rest: phi = 0, theta' = 0
>>> float(y0[-1]) == -eq.omega    # v_N = theta_N' - Omega
True
>>> eq.jacobian_bands
(3, 2)
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from torsio.physics.dynamics import Dynamics
from torsio.physics.system import System

if TYPE_CHECKING:
    import scipy.sparse


class TwistEquations:
    """Right-hand side and Jacobian of a System's equations for ``scipy.integrate.solve_ivp``.

    Parameters
    ----------
    system : System

    Attributes
    ----------
    dynamics : Dynamics
        The description everything is derived from.
    dofs : int
        Chain nodes n (the top drive included when it has inertia).
    omega : float
        Reference speed Omega_ref [rad/s] of the twist coordinates.
    """

    def __init__(self, system: System) -> None:
        self.system = system
        self.dynamics = dynamics = Dynamics.from_system(system)
        self.dofs = dynamics.dofs
        self.states = dynamics.states
        self.size = dynamics.size
        self.omega = dynamics.reference_speed
        self.lumped_mass = dynamics.lumped_mass

    def rest_state(self) -> np.ndarray:
        """Start-up from rest: every angle, speed and controller state zero."""
        return self.dynamics.rest_state()

    def state(self, twist: np.ndarray, speed: np.ndarray) -> np.ndarray:
        """State from twists phi [rad] and absolute speeds theta' [rad/s] (controller at 0)."""
        return self.dynamics.state(twist, speed)

    def bit_torque(self, bit_speed: Any) -> np.ndarray:
        """Torque on bit [N m] at absolute bit speed [rad/s]."""
        return self.dynamics.bit_torque(bit_speed)

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt."""
        return self.dynamics.rhs(t, y)

    @property
    def jacobian_bands(self) -> tuple[int, int] | None:
        """(lower, upper) bandwidth of the Jacobian, or None when it is full."""
        return self.dynamics.jacobian_bands

    def jacobian(self, t: float, y: np.ndarray) -> scipy.sparse.csc_matrix:
        """d(dy/dt)/dy as a sparse matrix (banded for lumped mass)."""
        return self.dynamics.jacobian(t, y)

    def jacobian_sparsity(self) -> scipy.sparse.csc_matrix:
        """Where the Jacobian can be non-zero."""
        return self.dynamics.jacobian_sparsity()
