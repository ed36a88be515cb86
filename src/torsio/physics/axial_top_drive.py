"""The top drive of a lumped axial-torsional run: any kind, as node −1 with its controller.

Every top drive (:mod:`torsio.physics.top_drives`, plugins included) reduces to a
:class:`~torsio.physics.top_drive_boundary.TopDriveBoundary`: the inertia J and drag of the
top and a linear controller z' = a z + b y + w (u − u_free), u_free = u0 + c·z + d·y,
y = [Ω_set − Ω_top, T_pipe]. :func:`top_boundary` asks the top drive for it on what its
tunings read of a system (:class:`AxialTopSystem`: the set speed, the first torsional
frequency with the top held, the string when there is one); :class:`TopDriveArrays` is what
the compiled loop (:mod:`torsio.solvers.axial_kernel`) takes; :func:`top_drive_rates` gives the
eigenvalues of the top node and its controller against the string's top spring (the
fastest rate the explicit step must resolve); the controller state of steady drilling is the
boundary's :meth:`~torsio.physics.top_drive_boundary.TopDriveBoundary.steady_states`.

Examples
--------
>>> from torsio.model.axial_assembly import rgd_two_dof_example
>>> from torsio.physics.top_drives import PITopDrive
>>> boundary = top_boundary(PITopDrive(inertia=2900.0, kp=5000.0, ki=2900.0 * 0.8**2),
...                         rgd_two_dof_example(), 60.0)
>>> boundary.held, round(boundary.set_speed, 6)
(False, 6.283185)
>>> [round(float(z), 9) for z in boundary.steady_states(1000.0, 1000.0)]  # ki z = T₀
[0.538793103]
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.errors import ConfigError
from torsio.physics.top_drive_boundary import TopDriveBoundary
from torsio.solvers import axial_layouts as slot
from torsio.solvers.set_speed import twist_table
from torsio.units import RPM_TO_RAD_S

__all__ = [
    "AxialTopSystem",
    "TopDriveArrays",
    "top_boundary",
    "top_drive_rates",
]


@attrs.frozen
class AxialTopSystem:
    """What ``top_drive.boundary(system)`` reads of an axial run: ``omega`` the set speed
    [rad/s], ``model`` (the assembly: its ``first_frequency()``, ω₁ with the top held) and
    ``string`` (the drill string the assembly was built from, for the top pipe's impedance;
    None for a chain given directly)."""

    model: Any
    omega: float
    string: Any = None


def top_boundary(top_drive: Any, assembly: Any, rpm: float, string: Any = None) -> TopDriveBoundary:
    """The boundary of ``top_drive`` (any registered kind) on ``assembly`` (a chain or the
    distributed pipe: its ``first_frequency()``) at ``rpm``.

    Raises
    ------
    ConfigError
        A top drive that does not return a :class:`TopDriveBoundary`.
    """
    system = AxialTopSystem(assembly, float(rpm) * RPM_TO_RAD_S, string)
    boundary = top_drive.boundary(system)
    if not isinstance(boundary, TopDriveBoundary):
        raise ConfigError(
            "top_drive", f"{top_drive!r}.boundary() returned {boundary!r}, not a TopDriveBoundary"
        )
    return boundary


@attrs.frozen(eq=False)
class TopDriveArrays:
    """The compiled loop's top drive: ``top`` (slots
    :data:`torsio.solvers.axial_layouts.TOP_DRIVE`),
    the controller matrices a (m, m) and b (m, 2) row by row, c (m,), d (2,), w (m,), and
    the set speed against time (``speed_table``, :func:`torsio.solvers.set_speed.twist_table`
    for Ω_ref = 0: rows time [s], Ω_set [rad/s], its integral [rad])."""

    top: NDArray[np.float64]
    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    d: NDArray[np.float64]
    w: NDArray[np.float64]
    speed_table: NDArray[np.float64]

    @classmethod
    def from_boundary(cls, boundary: TopDriveBoundary | None, top_speed: float) -> TopDriveArrays:
        """The arrays of ``boundary`` (None or a held one: the top held, no controller; at a
        constant set speed, the run's Ω₀ ``top_speed`` [rad/s] from t = 0)."""
        top = np.zeros(len(slot.TOP_DRIVE))
        if boundary is None or (boundary.held and not boundary.varying):
            boundary = TopDriveBoundary(inertia=0.0, set_speed=top_speed)
        table = twist_table(boundary.set_speed_table(), 0.0)
        if boundary.held:
            top[slot.TOP_HELD] = 1.0
            none = np.zeros(0)
            return cls(top, none, none, none, np.zeros(2), none, table)
        top[slot.TOP_INVERSE_INERTIA] = 1.0 / boundary.inertia
        top[slot.TOP_DRAG] = boundary.drag
        top[slot.TOP_U0] = boundary.u0
        top[slot.TOP_MAX_TORQUE] = boundary.max_torque
        top[slot.TOP_SET_SPEED] = boundary.set_speed
        m = boundary.states
        return cls(
            top,
            np.ascontiguousarray(np.asarray(boundary.a, dtype=float).reshape(m * m)),
            np.ascontiguousarray(np.asarray(boundary.b, dtype=float).reshape(m * 2)),
            np.ascontiguousarray(np.asarray(boundary.c, dtype=float).reshape(m)),
            np.ascontiguousarray(np.asarray(boundary.d, dtype=float).reshape(2)),
            np.ascontiguousarray(np.asarray(boundary.w, dtype=float).reshape(m)),
            table,
        )


def top_drive_matrix(boundary: TopDriveBoundary, stiffness: float, damper: float) -> NDArray:
    """The linear system x' = A x of x = (θ_top, Ω_top, z) with the string's first node held
    (T_pipe = k θ_top + c Ω_top, ``stiffness`` [N m/rad], ``damper`` [N m s/rad]), the motor
    unsaturated and the set speed constant."""
    m = boundary.states
    a, b = np.asarray(boundary.a, float).reshape(m, m), np.asarray(boundary.b, float).reshape(m, 2)
    c, d = np.asarray(boundary.c, float).reshape(m), np.asarray(boundary.d, float).reshape(2)
    # y = [e, T] = Y x with e = −Ω_top, T = k θ + c Ω
    outputs = np.zeros((2, 2 + m))
    outputs[0, 1] = -1.0
    outputs[1, 0], outputs[1, 1] = stiffness, damper
    torque = outputs[1]
    motor = d @ outputs
    motor[2:] += c
    matrix = np.zeros((2 + m, 2 + m))
    matrix[0, 1] = 1.0
    matrix[1] = (motor - torque) / boundary.inertia
    matrix[1, 1] -= boundary.drag / boundary.inertia
    matrix[2:] = b @ outputs
    matrix[2:, 2:] += a
    return matrix


def top_drive_rates(
    boundary: TopDriveBoundary, stiffness: float, damper: float
) -> NDArray[np.complex128]:
    """The eigenvalues [1/s] of :func:`top_drive_matrix`: the top drive's own rates."""
    return np.linalg.eigvals(top_drive_matrix(boundary, stiffness, damper))
