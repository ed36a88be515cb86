"""The one description of a System's dynamics: a tridiagonal chain and its two boundaries.

Twist coordinates about a reference speed Omega_ref: phi_i = theta_i - Omega_ref t,
v_i = phi_i'. Nodes 0 .. n-1; node n-1 carries the bit. If the top drive has
inertia, node 0 IS the top drive, joined to the model's first node by the model's
top spring k_1 and damper c_1; a held top (``constant-speed``) adds no node and
Omega_ref = Omega_set. The chain, with [I], [K], [C_rel] tridiagonal (relative
dampers only) and ``drag`` the damping of each node's absolute rotation::

    [I] v' = -[K] phi - [C_rel] v - drag o (Omega_ref + v) + applied
             - T_bit(Omega_ref + v_{n-1}) e_{n-1} + u e_0            (u: with a top node)

(for a held top [K] 1 = k_t and [C_rel] 1 = c_t tie the first node to the top
turning at Omega_ref). The top drive's controller (:mod:`torsio.physics.top_drives`)
adds m <= 3 states z and the motor torque u; its outputs are the speed error
e = Omega_set - Omega_0 and the pipe torque T_pipe = k_1 (phi_0 - phi_1) + c_1 (v_0 - v_1).
A set speed that changes in time (:mod:`torsio.solvers.set_speed`) is read at each time,
Omega_ref its last value; a held top, psi(t) ahead of Omega_ref t, adds k_t psi + c_t psi'.

The first-order state for scipy is ``y = [z_0 .. z_{m-1}, phi_0, v_0, ..., phi_{n-1}, v_{n-1}]``
(controller states first, so the Jacobian of a lumped-mass chain stays banded).
Everything that integrates, linearizes or balances energy derives from this
object: :meth:`Dynamics.rhs`, :meth:`Dynamics.jacobian`, :meth:`Dynamics.linearized`.

Consistent (or mixed) mass with a top drive that has inertia, or a held top whose speed
changes, is refused: the first element's mass coupling to the top is not in the model.

Examples
--------
>>> from torsio.examples import builtin_config
>>> dynamics = Dynamics.from_system(builtin_config().system(strategy="A"))
>>> dynamics.dofs, dynamics.states, dynamics.has_top_node, dynamics.jacobian_bands
(1, 0, False, (1, 1))
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np
import scipy.linalg

from torsio.errors import ConfigError
from torsio.model.contacts import carried_contacts
from torsio.model.tridiagonal import is_tridiagonal, tridiagonal_bands, tridiagonal_matvec
from torsio.physics.law_slope import bit_slope
from torsio.physics.top_drive_boundary import TopDriveBoundary, controller_rates, motor_torque

__all__ = ["Dynamics"]

if TYPE_CHECKING:
    import scipy.sparse


def _extend(matrix: np.ndarray, top: float, link: float) -> np.ndarray:
    """Prepend a node with diagonal ``top`` coupled to the old first node by ``link``."""
    n = matrix.shape[0]
    out = np.zeros((n + 1, n + 1))
    out[1:, 1:] = matrix
    out[0, 0] = top
    out[0, 1] = out[1, 0] = link
    return out


@attrs.frozen(eq=False)
class Dynamics:
    """The chain matrices and the two boundary components of a System (see module doc).

    The matrices are kept dense (a model from a plugin discretizer need not be a
    chain); for a chain (tridiagonal matrices) the band arrays ``*_diag`` and
    ``*_upper`` (length n, ``upper[i]`` couples nodes i and i+1, ``upper[-1] = 0``)
    are what compiled engines take.

    Attributes
    ----------
    mass_matrix : ndarray, shape (n, n)
        [I], in kg m^2.
    stiffness_matrix : ndarray
        [K], in N m/rad.
    relative_damping_matrix : ndarray
        [C_rel], the dampers across the springs [N m s/rad].
    drag : ndarray, shape (n,)
        Damping of each node's absolute rotation [N m s/rad].
    applied : ndarray
        Constant applied torque per node [N m].
    top_spring, top_damper : ndarray
        k_t and c_t: coupling of each node to a held top [N m/rad], [N m s/rad]
        (zero with a top-drive node, whose spring is inside the chain).
    reference_speed : float
        Omega_ref [rad/s].
    top : TopDriveBoundary
    law : object
        Bit-rock law with ``torque(speed, wob, radius)``.
    wob, radius : float
        Weight on bit [N] and bit radius [m].
    contacts : StringContacts or None
        Coulomb contacts of the nodes with the borehole, one capacity per node (0 at a
        top-drive node). :meth:`rhs` leaves them out: their friction is set-valued, and the
        integrators that run them (the compiled :mod:`torsio.solvers.contact_kernel`, scipy's
        :mod:`torsio.solvers.contact_events`) add it by the state of each contact; steady
        rotation (:meth:`steady_state`) takes their sliding torque, and the linearization
        none (a sliding contact's torque has no slope).
    speed_table : ndarray or None
        The set speed against time with the held top's twist psi, rows ``TABLE_*`` of
        :mod:`torsio.solvers.layouts` (:func:`torsio.solvers.set_speed.twist_table`), or
        None for a constant set speed.
    """

    mass_matrix: np.ndarray
    stiffness_matrix: np.ndarray
    relative_damping_matrix: np.ndarray
    drag: np.ndarray
    applied: np.ndarray
    top_spring: np.ndarray
    top_damper: np.ndarray
    reference_speed: float
    top: TopDriveBoundary
    law: Any
    wob: float
    radius: float
    contacts: Any = attrs.field(default=None, repr=False)
    speed_table: np.ndarray | None = attrs.field(default=None, repr=False, eq=False)
    _bands: Any = attrs.field(init=False, default=None, repr=False)
    _inverse_mass: Any = attrs.field(init=False, default=None, repr=False)

    def __attrs_post_init__(self) -> None:
        m = self.mass_matrix
        if not np.count_nonzero(m - np.diag(np.diag(m))):
            object.__setattr__(self, "_inverse_mass", 1.0 / np.diag(m))
        matrices = (self.mass_matrix, self.stiffness_matrix, self.relative_damping_matrix)
        if all(is_tridiagonal(m) for m in matrices):
            bands = tuple(tridiagonal_bands(m, "model") for m in matrices)
            object.__setattr__(self, "_bands", bands)

    # --- construction ---------------------------------------------------------------------
    @classmethod
    def from_system(cls, system: Any) -> Dynamics:
        """The description of a :class:`torsio.physics.system.System`."""
        model = system.model
        n = model.dofs
        top = system.top.boundary(system)
        table = None  # a constant set speed; else its table with the held top's twist
        if top.varying:  # numba only then: the table is read by the kernels' function
            from torsio.solvers.set_speed import twist_table

            table = twist_table(top.set_speed_table(), float(top.set_speed))
        damping = np.asarray(system.damping_matrix, dtype=float)
        top_damper = np.asarray(system.top_damping, dtype=float)
        top_spring = np.asarray(model.top_stiffness, dtype=float)
        drag = damping.sum(axis=1) - top_damper
        mass = np.asarray(model.inertia, dtype=float)
        stiffness = np.asarray(model.stiffness, dtype=float)
        relative = damping - np.diag(drag)
        common = (top, system.law, float(system.wob), float(system.bit_radius))
        contacts, _ = carried_contacts(getattr(model, "contacts", None))
        if not model.has_lumped_mass and (top.varying or not top.held):
            what = "acceleration" if top.held else f"inertia ({system.top.name!r})"
            raise ConfigError(
                "discretization.strategy",
                f"the top's {what} needs a lumped-mass model; {model.strategy!r} has consistent "
                "mass, whose first element would couple it to the first node (use strategy A, "
                "B or C)",
            )
        if top.held:
            speed = float(top.set_speed)  # a table's last speed
            return cls(
                mass, stiffness, relative, drag, np.zeros(n), top_spring, top_damper, speed,
                *common, contacts, table,
            )  # fmt: skip
        if np.count_nonzero(top_spring[1:]) or np.count_nonzero(top_damper[1:]):
            raise ConfigError(
                "stiffness", "a top drive with inertia needs a chain tied to the top at node 1 only"
            )
        k1, c1 = float(top_spring[0]), float(top_damper[0])
        mass = _extend(mass, float(top.inertia), 0.0)
        stiffness = _extend(stiffness, k1, -k1)
        relative = _extend(relative, c1, -c1)
        drag = np.concatenate([[float(top.drag)], drag])
        speed = float(top.set_speed)
        if not math.isfinite(speed):
            sliding = 0.0 if contacts is None else contacts.dynamic_total  # friction at speed
            speed = top.balance_speed(sliding, float(drag.sum()), system.law, system.wob,
                                      system.bit_radius)  # fmt: skip
        zeros = np.zeros(n + 1)
        if contacts is not None:  # none at the top drive's node
            contacts = attrs.evolve(
                contacts,
                static=np.concatenate([[0.0], contacts.static]),
                dynamic=np.concatenate([[0.0], contacts.dynamic]),
            )
        return cls(
            mass, stiffness, relative, drag, zeros, zeros, zeros, speed, *common, contacts,
            table,
        )  # fmt: skip

    # --- chain bands ----------------------------------------------------------------------
    @property
    def is_chain(self) -> bool:
        """Whether [I], [K] and [C_rel] are tridiagonal (a chain)."""
        return self._bands is not None

    def _band(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        if self._bands is None:
            raise ConfigError(
                "model",
                "expected a chain (tridiagonal matrices); this model couples non-neighbour nodes",
            )
        return self._bands[index]

    @property
    def mass_diag(self) -> np.ndarray:
        """Diagonal of [I], in kg m^2 (chains only)."""
        return self._band(0)[0]

    @property
    def mass_upper(self) -> np.ndarray:
        """Upper diagonal of [I], last entry 0 (chains only)."""
        return self._band(0)[1]

    @property
    def stiffness_diag(self) -> np.ndarray:
        """Diagonal of [K], in N m/rad (chains only)."""
        return self._band(1)[0]

    @property
    def stiffness_upper(self) -> np.ndarray:
        """Upper diagonal of [K], last entry 0 (chains only)."""
        return self._band(1)[1]

    @property
    def damping_diag(self) -> np.ndarray:
        """Diagonal of [C_rel], in N m s/rad (chains only)."""
        return self._band(2)[0]

    @property
    def damping_upper(self) -> np.ndarray:
        """Upper diagonal of [C_rel], last entry 0 (chains only)."""
        return self._band(2)[1]

    # --- sizes ----------------------------------------------------------------------------
    @property
    def dofs(self) -> int:
        """Number n of chain nodes (the top drive included when it has inertia)."""
        return int(self.mass_matrix.shape[0])

    @property
    def states(self) -> int:
        """Number m of controller states."""
        return self.top.states

    @property
    def size(self) -> int:
        """Length m + 2 n of the first-order state."""
        return self.states + 2 * self.dofs

    @property
    def has_top_node(self) -> bool:
        """Whether node 0 is the top drive (every top drive with inertia)."""
        return not self.top.held

    @property
    def lumped_mass(self) -> bool:
        """Whether [I] is diagonal."""
        return self._inverse_mass is not None

    @property
    def set_speed(self) -> float:
        """Omega_set [rad/s] of the top drive (NaN for a torque-driven one)."""
        return float(self.top.set_speed)

    @property
    def damping_matrix(self) -> np.ndarray:
        """[C_rel] + diag(drag): all damping acting on v, dense [N m s/rad]."""
        return self.relative_damping_matrix + np.diag(self.drag)

    # --- state helpers --------------------------------------------------------------------
    def split(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(z, phi, v) of a state (or of states along the first axis, shape (size, ...))."""
        m = self.states
        return y[:m], y[m::2], y[m + 1 :: 2]

    def rest_state(self) -> np.ndarray:
        """Start-up from rest: every angle, absolute speed and controller state zero."""
        y = np.zeros(self.size)
        y[self.states + 1 :: 2] = -self.reference_speed
        return y

    def state(self, twist: Any, speed: Any, controller: Any = None) -> np.ndarray:
        """State from twists phi [rad], absolute speeds [rad/s] and controller states."""
        y = np.zeros(self.size)
        m = self.states
        if controller is not None:
            y[:m] = controller
        y[m::2] = twist
        y[m + 1 :: 2] = np.asarray(speed, dtype=float) - self.reference_speed
        return y

    # --- boundary torques -----------------------------------------------------------------
    def bit_torque(self, bit_speed: Any) -> np.ndarray:
        """Torque on bit [N m] at absolute bit speed [rad/s]."""
        return np.asarray(self.law.torque(bit_speed, self.wob, self.radius))

    def bit_slope(self, bit_speed: Any) -> np.ndarray:
        """d T_bit / d speed [N m s/rad] at absolute bit speed [rad/s]."""
        return bit_slope(self.law, bit_speed, self.wob, self.radius)

    def set_speed_at(self, time: Any = None) -> Any:
        """(Omega_set [rad/s] (NaN: none), a held top's psi [rad]) at ``time`` [s] (float or
        array; None only for a constant set speed, :func:`~torsio.solvers.set_speed.table_at`)."""
        if self.speed_table is None:
            return np.full(np.shape(time), self.set_speed)[()], np.zeros(np.shape(time))[()]
        from torsio.solvers.set_speed import table_at

        return table_at(self.speed_table, time, self.reference_speed)

    def pipe_torque(self, phi: np.ndarray, v: np.ndarray, time: Any = None) -> np.ndarray:
        """Torque the string takes from the top [N m] (phi, v: node-first arrays) at
        ``time`` [s] (needed, with the shape of a sample, when the set speed changes)."""
        if self.has_top_node:
            k1, c1 = -self.stiffness_matrix[0, 1], -self.relative_damping_matrix[0, 1]
            return np.asarray(k1 * (phi[0] - phi[1]) + c1 * (v[0] - v[1]))
        torque = -(self.top_spring @ phi) - self.top_damper @ v
        if self.speed_table is not None:  # the top ahead of Omega_ref t by psi
            speed, psi = self.set_speed_at(time)
            relative = speed - self.reference_speed
            torque += self.top_spring.sum() * psi + self.top_damper.sum() * relative
        return np.asarray(torque)

    def motor_torque(
        self, z: np.ndarray, phi: np.ndarray, v: np.ndarray, time: Any = None
    ) -> tuple[Any, Any]:
        """(u, u_free): the (limited) motor torque and the controller's demand [N m].

        Node-first arrays; ``z`` shape (m, ...); ``time`` [s] as for :meth:`pipe_torque`.
        For a held top both are the pipe torque.
        """
        if not self.has_top_node:
            torque = self.pipe_torque(phi, v, time)
            return torque, torque
        top = self.top
        error, pipe = self._outputs(phi, v, time)
        return motor_torque(top.u0, top.kp, top.pipe_gain, top.max_torque, top.states, top.c, z,
                            error, pipe)  # fmt: skip

    def _outputs(self, phi: np.ndarray, v: np.ndarray, time: Any = None) -> tuple[Any, Any]:
        """(e, T_pipe): the speed error [rad/s] (0 without a set speed) and the pipe torque."""
        set_speed = self.set_speed_at(time)[0]
        error = set_speed - (self.reference_speed + v[0]) if math.isfinite(self.set_speed) else 0.0
        return error, self.pipe_torque(phi, v)

    # --- first-order equations ------------------------------------------------------------
    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt of the state ``[z, phi_0, v_0, ...]``."""
        m = self.states
        z, phi, v = y[:m], y[m::2], y[m + 1 :: 2]
        if self._bands is not None:
            (_, _), (k_diag, k_upper), (c_diag, c_upper) = self._bands
            elastic = tridiagonal_matvec(k_diag, k_upper, phi) + tridiagonal_matvec(
                c_diag, c_upper, v
            )
        else:
            elastic = self.stiffness_matrix @ phi + self.relative_damping_matrix @ v
        force = self.applied - elastic - self.drag * (self.reference_speed + v)
        force[-1] -= float(self.bit_torque(self.reference_speed + v[-1]))
        time = t if self.speed_table is not None else None
        if time is not None and not self.has_top_node:  # the held top's own motion
            speed, twist = self.set_speed_at(time)
            force += self.top_spring * twist + self.top_damper * (speed - self.reference_speed)
        dy = np.empty_like(y)
        if self.has_top_node:
            top = self.top
            error, pipe = self._outputs(phi, v, time)
            u, free = motor_torque(top.u0, top.kp, top.pipe_gain, top.max_torque, m, top.c, z,
                                   error, pipe)  # fmt: skip
            force[0] += float(u)
            controller_rates(m, m, np.ravel(top.a), np.ravel(top.b), top.w, z, error, pipe, u,
                             free, dy)  # fmt: skip
        dy[m::2] = v
        dy[m + 1 :: 2] = self._solve_mass(force)
        return dy

    def _solve_mass(self, force: np.ndarray) -> np.ndarray:
        if self._inverse_mass is not None:
            return force * self._inverse_mass
        return np.asarray(scipy.linalg.solve(self.mass_matrix, force, assume_a="pos"))

    def _output_rows(self) -> np.ndarray:
        """d y_out / d(phi, v) in chain state order (2 x 2n): rows e and T_pipe."""
        n = self.dofs
        rows = np.zeros((2, 2 * n))
        rows[0, 1] = -1.0
        k1, c1 = -self.stiffness_matrix[0, 1], -self.relative_damping_matrix[0, 1]
        rows[1, [0, 1, 2, 3]] = [k1, c1, -k1, -c1]
        return rows

    def jacobian_matrix(self, bit_slope: float, saturated: bool = False) -> np.ndarray:
        """d(dy/dt)/dy, dense, for a bit-law slope s [N m s/rad] and saturation state."""
        n, m = self.dofs, self.states
        jac = np.zeros((self.size, self.size))
        chain_force = np.zeros((n, 2 * n))  # d(force)/d(phi, v) in chain state order
        chain_force[:, 0::2] = -self.stiffness_matrix
        damping = self.damping_matrix
        damping[-1, -1] += bit_slope
        chain_force[:, 1::2] = -damping
        controller_force = np.zeros((n, m))
        if self.has_top_node:
            top = self.top
            outputs = self._output_rows()
            if not saturated:
                chain_force[0] += top.d @ outputs
                controller_force[0] = top.c
            if m:
                a = top.a - (np.outer(top.w, top.c) if saturated else 0.0)
                b = top.b - (np.outer(top.w, top.d) if saturated else 0.0)
                jac[:m, :m] = a
                jac[:m, m:] = b @ outputs
        if self.lumped_mass:
            inverse = np.diag(1.0 / np.diag(self.mass_matrix))
        else:
            inverse = np.linalg.inv(self.mass_matrix)
        jac[m::2, m + 1 :: 2] = np.eye(n)
        rows = slice(m + 1, None, 2)
        jac[rows, m:] = inverse @ chain_force
        jac[rows, :m] = inverse @ controller_force
        return jac

    def _saturated(self, y: np.ndarray, time: float) -> bool:
        if not self.has_top_node or not math.isfinite(self.top.max_torque):
            return False
        m = self.states
        u, free = self.motor_torque(y[:m], y[m::2], y[m + 1 :: 2], time)
        return bool(float(u) != float(free))

    def jacobian(self, t: float, y: np.ndarray) -> scipy.sparse.csc_matrix:
        """d(dy/dt)/dy at state y, sparse (banded for lumped mass)."""
        import scipy.sparse  # the scipy integrators only: a map does not load it

        slope = float(self.bit_slope(self.reference_speed + y[-1]))
        return scipy.sparse.csc_matrix(self.jacobian_matrix(slope, self._saturated(y, t)))

    @property
    def jacobian_bands(self) -> tuple[int, int] | None:
        """(lower, upper) bandwidth of the Jacobian, or None when it is full."""
        if not (self.lumped_mass and self.is_chain):
            return None
        m = self.states
        lower, upper = (3, 2) if m == 0 else (max(3, m + 1), max(2, m + 3))
        return (min(lower, self.size - 1), min(upper, self.size - 1))

    def jacobian_sparsity(self) -> scipy.sparse.csc_matrix:
        """Where the Jacobian can be non-zero (any slope, either saturation state)."""
        import scipy.sparse

        pattern = (self.jacobian_matrix(1.0) != 0) | (self.jacobian_matrix(1.0, True) != 0)
        return scipy.sparse.csc_matrix(pattern)

    # --- steady rotation ------------------------------------------------------------------
    def steady_state(self) -> np.ndarray:
        """The state of steady rotation at Omega_ref (v = 0), unsaturated controller, once
        the set speed is constant (a held top then psi ahead of Omega_ref t).

        Twists from the static balance; for a top-drive node, phi_0 = 0 and the
        controller states hold the motor torque the balance needs.
        """
        n, m = self.dofs, self.states
        omega = self.reference_speed
        load = self.applied - self.drag * omega
        load[-1] -= float(self.bit_torque(omega))
        if self.contacts is not None:  # every contact slides at omega > 0
            load -= np.sign(omega) * self.contacts.dynamic
        y = np.zeros(self.size)
        stiffness = self.stiffness_matrix
        if not self.has_top_node:
            if self.speed_table is not None:  # the top's final twist
                load += self.top_spring * self.set_speed_at(math.inf)[1]
            y[0::2] = np.linalg.solve(stiffness, load)
            return y
        top = self.top
        motor = -float(load.sum())  # the motor carries every steady load
        load[0] += motor
        phi = np.zeros(n)
        phi[1:] = np.linalg.solve(stiffness[1:, 1:], load[1:])
        y[m::2] = phi
        y[:m] = top.steady_states(float(self.pipe_torque(phi, np.zeros(n))), motor)
        return y

    def linearized(self, bit_slope: float | None = None) -> np.ndarray:
        """The Jacobian about steady rotation (unsaturated), state order of :meth:`rhs`."""
        s = float(self.bit_slope(self.reference_speed)) if bit_slope is None else bit_slope
        return self.jacobian_matrix(s)
