"""First-order equations of motion of a System, in twist coordinates, with their Jacobian.

State (interleaved, so the Jacobian of a lumped-mass chain is banded):

    y = [phi_1, v_1, phi_2, v_2, ..., phi_N, v_N],   phi = theta - Omega t,  v = phi'

    phi' = v
    [I] v' = -[K] phi - [C] v - Omega ([C] 1 - c_t) - T_bit(Omega + v_N) e_N

(see :mod:`torsio.physics.system`). Absolute bit speed is Omega + v_N. With lumped
(diagonal) inertia the Jacobian has lower bandwidth 3 and upper bandwidth 2 in
this ordering: tridiagonal [K] and [C] plus the scalar bit-law slope on the last
diagonal entry. With consistent mass [I]^-1 is full and so is the Jacobian.

Examples
--------
>>> from torsio.physics.system import System, builtin_config
>>> eq = TwistEquations(System.from_config(builtin_config()))
>>> y0 = eq.rest_state()          # start-up from rest: phi = 0, theta' = 0
>>> float(y0[-1]) == -eq.omega    # v_N = theta_N' - Omega
True
>>> eq.jacobian_bands
(3, 2)
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.linalg
import scipy.sparse

from torsio.physics.system import System


class TwistEquations:
    """Right-hand side and Jacobian of a System's equations of motion in twist coordinates.

    Parameters
    ----------
    system : System
    """

    def __init__(self, system: System) -> None:
        model = system.model
        self.system = system
        self.dofs = n = model.dofs
        self.omega = system.omega
        self.lumped_mass = model.has_lumped_mass
        inertia = np.asarray(model.inertia)
        stiffness = np.asarray(model.stiffness)
        damping = system.damping_matrix
        steady_drag = system.omega * system.drag_per_speed  # torque of rigid rotation at Omega
        if self.lumped_mass:
            inverse_inertia = 1.0 / np.diag(inertia)
            self._k = stiffness * inverse_inertia[:, None]
            self._c = damping * inverse_inertia[:, None]
            self._f = -steady_drag * inverse_inertia
            self._bit_column = np.zeros(n)
            self._bit_column[-1] = inverse_inertia[-1]
        else:
            factor = scipy.linalg.cho_factor(inertia)
            self._k = scipy.linalg.cho_solve(factor, stiffness)
            self._c = scipy.linalg.cho_solve(factor, damping)
            self._f = -scipy.linalg.cho_solve(factor, steady_drag)
            unit = np.zeros(n)
            unit[-1] = 1.0
            self._bit_column = scipy.linalg.cho_solve(factor, unit)
        self._law = system.law
        self._wob = system.wob
        self._radius = system.bit_radius

    # --- state helpers -------------------------------------------------------------------
    def rest_state(self) -> np.ndarray:
        """Start-up from rest: every angle and speed zero while the top turns at Omega."""
        y = np.zeros(2 * self.dofs)
        y[1::2] = -self.omega
        return y

    def state(self, twist: np.ndarray, speed: np.ndarray) -> np.ndarray:
        """Interleaved state from twists phi [rad] and absolute speeds theta' [rad/s]."""
        y = np.empty(2 * self.dofs)
        y[0::2] = twist
        y[1::2] = np.asarray(speed, dtype=float) - self.omega
        return y

    # --- equations -----------------------------------------------------------------------
    def bit_torque(self, bit_speed: Any) -> np.ndarray:
        """Torque on bit [N m] at absolute bit speed [rad/s]."""
        return np.asarray(self._law.torque(bit_speed, self._wob, self._radius))

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt."""
        phi = y[0::2]
        v = y[1::2]
        dy = np.empty_like(y)
        dy[0::2] = v
        torque = float(self.bit_torque(self.omega + v[-1]))
        dy[1::2] = self._f - self._k @ phi - self._c @ v - torque * self._bit_column
        return dy

    @property
    def jacobian_bands(self) -> tuple[int, int] | None:
        """(lower, upper) bandwidth of the Jacobian, or None when it is full.

        Never wider than the matrix itself (a 1-DOF model has a 2 x 2 Jacobian).
        """
        if not self.lumped_mass:
            return None
        size = 2 * self.dofs
        return (min(3, size - 1), min(2, size - 1))

    def jacobian(self, t: float, y: np.ndarray) -> scipy.sparse.csc_matrix:
        """d(dy/dt)/dy as a sparse matrix (banded for lumped mass)."""
        n = self.dofs
        slope = float(self._law.slope(self.omega + y[-1], self._wob, self._radius))
        jac = np.zeros((2 * n, 2 * n))
        jac[0::2, 1::2] = np.eye(n)
        jac[1::2, 0::2] = -self._k
        jac[1::2, 1::2] = -self._c
        jac[1::2, 2 * n - 1] -= slope * self._bit_column
        return scipy.sparse.csc_matrix(jac)

    def jacobian_sparsity(self) -> scipy.sparse.csc_matrix:
        """Where the Jacobian can be non-zero."""
        n = self.dofs
        pattern = np.zeros((2 * n, 2 * n), dtype=bool)
        pattern[0::2, 1::2] = np.eye(n, dtype=bool)
        pattern[1::2, 0::2] = self._k != 0
        pattern[1::2, 1::2] = self._c != 0
        pattern[1::2, 2 * n - 1] |= self._bit_column != 0
        return scipy.sparse.csc_matrix(pattern)
