"""The top drive as the dynamics sees it: node 0 and a linear controller.

:class:`TopDriveBoundary` is what every top drive (:mod:`torsio.physics.top_drives`)
returns from ``boundary(system)``; :class:`ScaledTopDrive` is a top drive rescaled
to the dimensionless formulation; :func:`top_pipe_impedance` is the drill pipe's
characteristic impedance that the tunings refer to.

The controller is evaluated here, once for every engine: :func:`motor_torque` (u and
u_free) and :func:`controller_rates` (z') of the speed error e and the pipe torque T_pipe.
They are plain functions of floats or numpy arrays (Dynamics and the numpy batch engine
call them on arrays of samples or points) that numba compiles as they are for the
lumped RODAS4 kernel and the axial kernel (:mod:`torsio.solvers.chain_kernel`).

Examples
--------
>>> import numpy as np
>>> pi = TopDriveBoundary(inertia=2900.0, set_speed=6.0, a=np.zeros((1, 1)),
...                       b=np.array([[1.0, 0.0]]), c=np.array([2900.0 * 0.64]),
...                       d=np.array([5000.0, 0.0]), w=np.array([1 / 5000.0]))
>>> round(float(abs(pi.impedance(0.8) - 5000.0)), 9)  # ki = 0.8^2 J: pure damper at 0.8 rad/s
0.0
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import attrs
import numpy as np

from torsio.errors import ConfigError

__all__ = [
    "ScaledTopDrive",
    "TopDriveBoundary",
    "controller_rates",
    "limited",
    "motor_torque",
    "top_pipe_impedance",
]


def limited(torque, max_torque):
    """``torque`` [N m] held to +-``max_torque``: np.clip (numba compiles it as min(max()),
    :mod:`torsio.solvers.chain_kernel`)."""
    return np.clip(torque, -max_torque, max_torque)


def motor_torque(u0, kp, pipe_gain, max_torque, states, c, z, error, pipe):
    """(u, u_free) [N m]: u_free = u0 + kp e + pipe_gain T_pipe + c . z, u = clip(u_free,
    -max_torque, max_torque), for the speed error e [rad/s] and the pipe torque T_pipe [N m]
    (floats, or arrays of points with ``z`` shaped (m, points)); ``states`` m <= len(c).

    >>> tuple(float(t) for t in motor_torque(100.0, 5.0, 0.0, 110.0, 1, [2.0], [3.0], 1.0, 0.0))
    (110.0, 111.0)
    """
    free = u0 + kp * error + pipe_gain * pipe
    for j in range(states):
        free = free + c[j] * z[j]
    return limited(free, max_torque), free


def controller_rates(states, stride, a, b, w, z, error, pipe, u, free, rates):
    """rates = z' = a z + b [e, T_pipe] + w (u - u_free) of the first ``states`` states m:
    ``a`` flat, row j at ``stride`` j (the m x m matrix, or its block of a larger square),
    ``b`` flat, the gains on (e, T_pipe) of each state in turn, ``w`` (m,); floats or arrays
    of points as in :func:`motor_torque`."""
    for j in range(states):
        rate = b[2 * j] * error + b[2 * j + 1] * pipe + w[j] * (u - free)
        for k in range(states):
            rate = rate + a[stride * j + k] * z[k]
        rates[j] = rate


@attrs.frozen
class TopDriveBoundary:
    """The top drive as the dynamics sees it: node 0 and a linear controller.

    Attributes
    ----------
    inertia : float
        J [kg m^2]; 0 means the top is held at ``set_speed`` (no node, no state).
    drag : float
        Torque per unit absolute speed of the top drive to the ground [N m s/rad].
    set_speed : float
        Omega_set [rad/s], the speed the controller aims at (for ``torque``: none, NaN).
    u0 : float
        Constant part of the motor torque [N m].
    a, b, c, d, w : ndarray
        Controller matrices, shapes (m, m), (m, 2), (m,), (2,), (m,), with
        y = [e, T_pipe] (see the module documentation).
    max_torque : float
        |u| limit [N m] (inf: none).
    ramp : float
        The set speed rises linearly from 0 to ``set_speed`` over ``ramp`` [s] (0: a step).
    speed_table : ndarray or None
        Instead, the set speed against time: rows (time [s], speed [rad/s]), linear between
        the columns and constant beyond them (a recorded top-drive speed).
    """

    inertia: float
    drag: float = 0.0
    set_speed: float = math.nan
    u0: float = 0.0
    a: np.ndarray = attrs.field(factory=lambda: np.zeros((0, 0)), eq=False)
    b: np.ndarray = attrs.field(factory=lambda: np.zeros((0, 2)), eq=False)
    c: np.ndarray = attrs.field(factory=lambda: np.zeros(0), eq=False)
    d: np.ndarray = attrs.field(factory=lambda: np.zeros(2), eq=False)
    w: np.ndarray = attrs.field(factory=lambda: np.zeros(0), eq=False)
    max_torque: float = math.inf
    ramp: float = 0.0
    speed_table: np.ndarray | None = attrs.field(default=None, eq=False)

    @property
    def held(self) -> bool:
        """Whether the top is held at the set speed (no top-drive node)."""
        return self.inertia == 0.0

    @property
    def kp(self) -> float:
        """Motor torque per unit speed error [N m s/rad]: d[0], the ``kp`` of a speed loop."""
        return float(self.d[0])

    @property
    def pipe_gain(self) -> float:
        """Motor torque per unit pipe torque [-]: d[1] (the feedback of Z-Torque)."""
        return float(self.d[1])

    @property
    def states(self) -> int:
        """Number m of controller states."""
        return int(np.asarray(self.c).size)

    @property
    def varying(self) -> bool:
        """Whether the set speed changes in time (a ramp or a table)."""
        return self.ramp > 0.0 or self.speed_table is not None

    def set_speed_table(self) -> np.ndarray:
        """The set speed against time, shape (2, k): times [s], speeds [rad/s].

        >>> TopDriveBoundary(inertia=1.0, set_speed=6.0, ramp=3.0).set_speed_table().tolist()
        [[0.0, 3.0], [0.0, 6.0]]
        >>> TopDriveBoundary(inertia=1.0).set_speed_table().tolist()  # no set speed
        [[0.0], [0.0]]
        """
        if self.speed_table is not None:
            return np.asarray(self.speed_table, dtype=float)
        speed = 0.0 if math.isnan(self.set_speed) else float(self.set_speed)
        if self.ramp > 0.0:
            return np.array([[0.0, float(self.ramp)], [0.0, speed]])
        return np.array([[0.0], [speed]])

    def balance_speed(
        self, friction: float, drag: float, law: Any, wob: float, radius: float
    ) -> float:
        """The lowest speed [rad/s] where the constant motor torque ``u0`` balances a
        friction torque [N m], a drag [N m s/rad] and the bit (a torque-driven top drive).

        ConfigError (``top_drive.torque``) when no speed between 0 and 1e4 rad/s does.
        """
        torque = float(self.u0) - friction

        def excess(speed: float) -> float:
            return torque - drag * speed - float(np.asarray(law.torque(speed, wob, radius)))

        grid = np.concatenate([[0.0], np.geomspace(1e-3, 1e4, 2001)])
        values = np.array([excess(w) for w in grid])
        change = np.flatnonzero((values[:-1] > 0) & (values[1:] <= 0))
        if change.size == 0:
            raise ConfigError(
                "top_drive.torque",
                f"the motor torque {torque:g} N m is balanced by no speed between 0 and 1e4 "
                "rad/s (drag and torque on bit stay below it, or above it at rest)",
            )
        i = int(change[0])
        if values[i + 1] == 0.0:
            return float(grid[i + 1])
        import scipy.optimize  # a torque-driven top drive only

        return float(scipy.optimize.brentq(excess, grid[i], grid[i + 1], xtol=1e-13, rtol=1e-14))

    def steady_states(self, pipe_torque: float, motor: float) -> np.ndarray:
        """The controller states z of steady rotation at the set speed (e = 0) with the pipe
        torque ``pipe_torque`` [N m]: z' = a z + b [0, T_pipe] = 0 and u_free = ``motor``
        [N m], by least squares (a kind that cannot hold it gets the nearest z)."""
        m = self.states
        if m == 0:
            return np.zeros(0)
        outputs = np.array([0.0, float(pipe_torque)])
        a, b = np.asarray(self.a, float).reshape(m, m), np.asarray(self.b, float).reshape(m, 2)
        c, d = np.asarray(self.c, float).reshape(m), np.asarray(self.d, float).reshape(2)
        right = np.concatenate([-b @ outputs, [motor - self.u0 - d @ outputs]])
        return np.asarray(np.linalg.lstsq(np.vstack([a, c]), right, rcond=None)[0], float)

    def transfer(self, s: complex) -> np.ndarray:
        """H(s) = c (s I - a)^-1 b + d: motor torque per unit (e, T_pipe), shape (2,)."""
        m = self.states
        h = np.asarray(self.d, dtype=complex).copy()
        if m:
            h += np.asarray(self.c) @ np.linalg.solve(s * np.eye(m) - self.a, self.b)
        return h

    def impedance(self, omega: Any) -> np.ndarray:
        """Z(i omega) = -T_pipe / Omega_0 of the small motions [N m s/rad], unsaturated.

        From J s dOmega = du - drag dOmega - dT and du = H_e (-dOmega) + H_T dT:
        Z = (J s + drag + H_e(s)) / (1 - H_T(s)), s = i omega.
        """
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        values = []
        for frequency in w:
            s = 1j * frequency
            h = self.transfer(s)
            values.append((self.inertia * s + self.drag + h[0]) / (1.0 - h[1]))
        result = np.asarray(values)
        return result if np.ndim(omega) else result[0]


def top_pipe_impedance(system: Any) -> float:
    """zeta = J_p sqrt(G rho) of the top section of the system's string [N m s/rad].

    The characteristic impedance of the drill pipe at the top: the torque per unit
    speed a torsional wave carries. A clear error if the system has no string
    (a ``[chain]`` model): then give ``kp`` (or ``zeta``) explicitly.
    """
    string = getattr(system, "string", None)
    if string is None:
        raise ConfigError(
            "top_drive.kp",
            "the default tuning needs the drill-pipe impedance zeta = J_p sqrt(G rho) of a "
            "drill string, and this model is a chain without one; give kp (and zeta) explicitly",
        )
    section = string.sections[0]
    material = section.material
    return float(section.polar_moment * math.sqrt(material.shear_modulus * material.density))


@attrs.frozen
class ScaledTopDrive:
    """A top drive in the dimensionless formulation: a fixed, rescaled boundary.

    Built by :func:`torsio.physics.dimensionless.dimensionless_system` from any top
    drive: with time tau = omega_1 t, speeds over omega_1 and torques over k_eq,

        J/I_eq, drag omega_1/k_eq, u0/k_eq, max_torque/k_eq,
        a/omega_1, b diag(omega_1, k_eq)/omega_1, c/k_eq, d diag(omega_1, k_eq)/k_eq,
        w k_eq/omega_1

    (controller states keep their units). The set speed follows the System's
    Pi_1 (its ``omega``); a torque-driven top keeps none. Not registered: it is
    made, never named in a configuration.
    """

    name: ClassVar[str] = "scaled"
    source: str
    scaled: TopDriveBoundary

    @classmethod
    def from_boundary(
        cls, source: str, boundary: TopDriveBoundary, omega1: float, k_eq: float
    ) -> ScaledTopDrive:
        """The rescaled form of ``boundary`` for frequency omega_1 [rad/s] and k_eq [N m/rad]."""
        i_eq = k_eq / omega1**2
        outputs = np.array([omega1, k_eq])
        return cls(
            source,
            TopDriveBoundary(
                inertia=boundary.inertia / i_eq,
                drag=boundary.drag * omega1 / k_eq,
                set_speed=boundary.set_speed / omega1,
                u0=boundary.u0 / k_eq,
                a=np.asarray(boundary.a) / omega1,
                b=np.asarray(boundary.b) * outputs / omega1,
                c=np.asarray(boundary.c) / k_eq,
                d=np.asarray(boundary.d) * outputs / k_eq,
                w=np.asarray(boundary.w) * k_eq / omega1,
                max_torque=boundary.max_torque / k_eq,
            ),
        )

    def boundary(self, system: Any) -> TopDriveBoundary:
        """The rescaled boundary, aiming at the System's Pi_1."""
        speed = float(system.omega) if math.isfinite(self.scaled.set_speed) else math.nan
        return attrs.evolve(self.scaled, set_speed=speed)
