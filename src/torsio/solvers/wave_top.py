"""The top of the distributed model as arrays for the stepping kernel.

A held top turns at Omega: the outgoing invariant is p = m + 2 Z Omega, a velocity
reflection R = -1. A top drive (:class:`torsio.physics.top_drives.TopDriveBoundary`:
inertia J, drag, linear controller with states z) sees the pipe torque
T_pipe = m + Z Omega_0; its state x = [Omega_0, z] obeys a linear ODE driven by the
incoming invariant m, integrated by the trapezoidal rule with m linear over the step.
For small motions of a PI top drive with no inertia and no integral gain this gives the
reflection R = (Z - kp) / (Z + kp); in general R = (Z - Z_td) / (Z + Z_td) with the top
drive's impedance Z_td(i omega) (``TopDriveBoundary.impedance``). With distributed drag
the top node carries its share of the string's drag as a damper c (module
:mod:`torsio.solvers.characteristics`), which adds to the top drive's own drag
(:func:`with_node_damper`).

The set speed may change in time (a start-up ramp, a recorded top-drive speed): a table of
(time, speed) read linearly in the kernel. A held top then turns at Omega(t); a controller's
set point enters its state equation affinely, so the trapezoidal step takes the constant
part ``constant + Omega_mid constant_per_speed`` with Omega_mid the mean set speed over
the step, and its motor torque ``u0 + kp Omega(t)``.
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.solvers import layouts as slot
from torsio.solvers.set_speed import table_speed


@attrs.frozen(eq=False)
class TopArrays:
    """The top boundary as arrays for the stepping kernel.

    ``held``: the top turns at the set speed. Otherwise the state x = [Omega_0, z] advances
    by ``x1 = L[k] x0 + g[k] (m0 + m1) + q[k] + Omega_mid r[k]`` (trapezoidal rule) in mode
    k = 0 (free), 1 (motor torque at +max) or 2 (at -max), with Omega_mid the mean set
    speed over the step; the motor torque is
    :func:`~torsio.physics.top_drive_boundary.motor_torque` of e = Omega_set - Omega_0 and
    T_pipe = m + Z Omega_0 with the gains ``coefficients`` (``COEF_*`` of
    :mod:`torsio.solvers.layouts`: u0, kp, the pipe torque's gain, c).
    ``speed_table`` (2, k) is the set speed
    [rad/s] against time [s]; ``set_speed`` its final value. ``drag`` is the top drive's own
    drag, ``node_damper`` the string's drag at the top node [N m s/rad], which the arrays
    include besides.
    """

    held: bool
    set_speed: float
    inertia: float
    drag: float
    max_torque: float
    propagator: np.ndarray  # (3, n, n)
    forcing: np.ndarray  # (3, n)
    constant: np.ndarray  # (3, n)
    coefficients: np.ndarray  # (COEF_STATES + m,)
    speed_table: np.ndarray  # (2, k): time [s], set speed [rad/s]
    constant_per_speed: np.ndarray  # (3, n): r[k]
    kp: float = 0.0  # the motor torque per unit set speed [N m s/rad] (0: no set speed)
    impedance: float = math.nan
    boundary: Any = None
    node_damper: float = 0.0

    @property
    def states(self) -> int:
        """Size of the top state [Omega_0, z] (0 when held)."""
        return int(self.forcing.shape[1])

    @property
    def ramp_end(self) -> float:
        """The time [s] from which the set speed is constant."""
        return float(self.speed_table[slot.TABLE_TIME, -1])

    def set_speed_at(self, time: float) -> float:
        """The set speed [rad/s] at ``time`` [s]: linear in the table, constant beyond it."""
        return float(table_speed(self.speed_table, time))


def held_top(speed: float, table: np.ndarray | None = None) -> TopArrays:
    """A top held at ``speed`` [rad/s], or at the speeds of ``table`` (rows time, speed)."""
    table = np.array([[0.0], [float(speed)]]) if table is None else np.asarray(table, float)
    return TopArrays(
        True, float(table[slot.TABLE_SPEED, -1]), 0.0, 0.0, math.inf, np.zeros((3, 1, 1)),
        np.zeros((3, 1)), np.zeros((3, 1)), np.zeros(3), np.ascontiguousarray(table),
        np.zeros((3, 1)),
    )  # fmt: skip


def top_arrays(
    boundary: Any, impedance: float, time_step: float, speed: float, node_damper: float = 0.0
) -> TopArrays:
    """Arrays of a top-drive description (``TopDriveBoundary``) on a pipe of ``impedance``.

    ``speed`` is Omega_set for a held top; ``node_damper`` [N m s/rad] a damper at the top
    node besides the top drive's drag. Derivation (module docstring of
    :mod:`torsio.physics.top_drives`): with the incoming invariant m, T_pipe = m + Z Omega_0,
    y = [Omega_set - Omega_0, T_pipe], u_free = u0 + c z + d y,
    J Omega_0' = u - drag Omega_0 - T_pipe, z' = a z + b y + w (u - u_free).
    """
    if getattr(boundary, "held", True):
        table = boundary.set_speed_table() if getattr(boundary, "varying", False) else None
        return held_top(speed, table)
    states = int(np.size(boundary.c))  # controller states (none for a torque top drive)
    a = np.asarray(boundary.a, dtype=float).reshape(states, states)
    b = np.asarray(boundary.b, dtype=float).reshape(-1, 2)
    c = np.asarray(boundary.c, dtype=float).ravel()
    d = np.asarray(boundary.d, dtype=float).ravel()
    w = np.asarray(boundary.w, dtype=float).ravel()
    m = c.size
    n = m + 1
    inertia, drag, z_pipe = float(boundary.inertia), float(boundary.drag), float(impedance)
    set_speed = float(boundary.set_speed)
    kp = 0.0 if math.isnan(set_speed) else float(d[0])  # no set speed: no speed error
    coefficients = np.zeros(slot.COEF_STATES + m)  # the gains motor_torque reads
    coefficients[slot.COEF_U0], coefficients[slot.COEF_KP] = boundary.u0, kp
    coefficients[slot.COEF_PIPE_GAIN], coefficients[slot.COEF_STATES :] = d[1], c
    # u_free = u0 + kp set + [(-kp + d1 Z), c] . x + d1 m, e = set - Omega_0, T = m + Z Omega_0
    gains = np.concatenate([[-kp + d[1] * z_pipe], c])
    m_gain, u0 = d[1], boundary.u0
    propagator = np.zeros((3, n, n))
    forcing = np.zeros((3, n))
    constant = np.zeros((3, n))
    per_speed = np.zeros((3, n))
    max_torque = float(boundary.max_torque)
    has_set = 0.0 if math.isnan(set_speed) else 1.0
    for mode, limit in enumerate((None, max_torque, -max_torque)):
        A = np.zeros((n, n))
        B = np.zeros(n)
        f = np.zeros(n)  # the constant forcing; r: the forcing per unit set speed
        r = np.zeros(n)
        # z' = a z + b0 (set - Omega) + b1 (m + Z Omega)   [+ w (u - u_free) when limited]
        A[1:, 1:] = a
        A[1:, 0] = -b[:, 0] + b[:, 1] * z_pipe
        B[1:] = b[:, 1]
        r[1:] = b[:, 0] * has_set
        if limit is None:  # u = u_free
            A[0, :] = gains
            B[0] = m_gain
            f[0] = u0
            r[0] = kp
        elif math.isfinite(limit):
            f[0] = limit
            A[1:, :] -= np.outer(w, gains)
            B[1:] -= w * m_gain
            f[1:] += w * (limit - u0)
            r[1:] -= w * kp
        A[0, 0] -= drag + node_damper + z_pipe
        B[0] -= 1.0
        A[0, :] /= inertia
        B[0] /= inertia
        f[0] /= inertia
        r[0] /= inertia
        left = np.eye(n) - 0.5 * time_step * A
        propagator[mode] = np.linalg.solve(left, np.eye(n) + 0.5 * time_step * A)
        forcing[mode] = np.linalg.solve(left, 0.5 * time_step * B)
        constant[mode] = np.linalg.solve(left, time_step * f)
        per_speed[mode] = np.linalg.solve(left, time_step * r)
    table = boundary.set_speed_table()  # zero speeds without a set speed (torque top)
    return TopArrays(
        False, set_speed, inertia, drag, max_torque, propagator, forcing, constant, coefficients,
        np.ascontiguousarray(table, dtype=float), per_speed, kp, z_pipe, boundary,
        float(node_damper),
    )  # fmt: skip


def with_node_damper(top: TopArrays, damper: float, time_step: float) -> TopArrays:
    """``top`` with a damper [N m s/rad] at the top node (the same top when it has it, or held)."""
    if top.held or top.node_damper == damper:
        return top
    if top.boundary is None:
        raise ValueError("these top arrays keep no top-drive description to rebuild them from")
    return top_arrays(top.boundary, top.impedance, time_step, top.set_speed, damper)


def top_boundary(system: Any, grid: Any) -> TopArrays:
    """The top of ``system`` on the wave grid: held at Omega, or its top drive, as arrays."""
    boundary = system.top.boundary(system) if hasattr(system.top, "boundary") else None
    if boundary is None:
        return held_top(system.omega)
    return top_arrays(boundary, float(grid.impedances[0]), grid.time_step, system.omega)
