"""Energy accounting of a transient run: where the top drive's work goes.

With theta the absolute node angles, phi = theta - Omega t 1 the twists,
v = phi' = theta' - Omega 1, and the damping split as [C] = C_rel + D, where
C_rel acts across the dampers of the chain (including the one to the top drive,
so ``C_rel 1 = c_t``) and D acts on the absolute speeds (drag), the equations of
motion (:mod:`torsio.physics.system`) give, exactly,

    d/dt (E_kin + E_pot) = P_in - P_rel - P_drag - P_bit

with

* E_kin = 1/2 theta'^T [I] theta'                  kinetic energy [J]
* E_pot = 1/2 phi^T [K] phi                       strain energy of every spring,
  the one to the top included [J]
* P_in  = Omega T_s, T_s = -k_t . phi - c_t . v    power of the top drive [W]
* P_rel = v^T C_rel v                             relative dampers [W]
* P_drag = theta'^T D theta'                      drag on absolute rotation [W]
* P_bit = T_bit theta_N'                          work at the bit [W]

(multiply the absolute equation by theta'^T and use [K] 1 = k_t). A held top whose set
speed changes in time (a ramp, a recording) turns psi(t) ahead of Omega_ref t: then
P_in = Omega_set(t) T_s, and phi, v are taken about it (phi - psi 1, v - psi' 1) in
E_pot, T_s and P_rel. For Rayleigh
damping C_rel = beta [K] and D = alpha [I]: the alpha part damps absolute
rotation, so steady rotation at Omega already costs alpha Omega^2 1^T [I] 1. For
a model's own chain damping D is its diagonal drag, ``diag([C] 1 - c_t)``.

With a top drive that has inertia (node 0 of :class:`torsio.physics.dynamics.Dynamics`)
the same balance holds for the extended chain, with

* P_in = u Omega_0                 power of the motor torque u [W]
* E_kin including 1/2 J Omega_0^2  the top drive's kinetic energy (also given alone)
* P_drag including drag_td Omega_0^2, and E_pot and P_rel including the spring and
  damper between the top drive and the string.

Every term is computed from the run's states through the System's one description
of the dynamics (the same object the integrator used).

The powers are integrated over the sampled output with the cumulative Simpson
rule, so the balance holds to the quadrature error of the output grid (the
solver's own error is smaller at the default tolerances).

Examples
--------
>>> from torsio.examples import builtin_config
>>> from torsio.analysis.transient import simulate
>>> system = builtin_config().system(strategy="A").at(wob=100e3, rpm=60)
>>> balance = energy_balance(simulate(system))
>>> balance.relative_residual < 1e-4
True
"""

from __future__ import annotations

from typing import Any

import attrs
import numpy as np
import scipy.integrate

from torsio.physics.damping import RayleighDamping
from torsio.physics.dynamics import Dynamics
from torsio.physics.system import System

__all__ = ["EnergyBalance", "damping_split", "energy_balance"]


def damping_split(system: System) -> tuple[np.ndarray, np.ndarray]:
    """(C_rel, D): the relative and the absolute (drag) parts of [C], in N m s/rad.

    For Rayleigh damping C_rel = beta [K] and D = alpha [I]; otherwise the drag
    is taken diagonal, D = diag([C] 1 - c_t) (exact for a chain of dampers plus
    drag on each inertia).
    """
    damping = system.damping
    model = system.model
    if isinstance(damping, RayleighDamping):
        return damping.beta * np.asarray(model.stiffness), damping.alpha * np.asarray(model.inertia)
    matrix = system.damping_matrix
    drag = np.diag(system.drag_per_speed)
    return matrix - drag, drag


def _cumulative(power: np.ndarray, time_grid: np.ndarray) -> np.ndarray:
    if time_grid.size < 3:
        return np.asarray(scipy.integrate.cumulative_trapezoid(power, time_grid, initial=0.0))
    return np.asarray(scipy.integrate.cumulative_simpson(power, x=time_grid, initial=0.0))


@attrs.frozen(eq=False, repr=False)
class EnergyBalance:
    """Cumulative works and stored energies of a transient run, sample by sample [J].

    For a dimensionless system the unit is k_eq rad^2 instead of J.

    Attributes
    ----------
    time : ndarray
        Sample times [s].
    work_in : ndarray
        Work done by the top drive since t = 0: integral of Omega T_s (held top) or of
        the motor power u Omega_0 (top drive with inertia).
    dissipated_relative : ndarray
        Dissipated by the dampers across the springs (beta [K]), the one to the
        top included.
    dissipated_drag : ndarray
        Dissipated by drag on the absolute rotation (alpha [I]).
    work_bit : ndarray
        Work done on the rock at the bit, integral of T_bit theta_N'.
    kinetic : ndarray
        Kinetic energy 1/2 theta'^T [I] theta' (the top drive's included).
    potential : ndarray
        Strain energy 1/2 phi^T [K] phi.
    kinetic_top : ndarray
        Kinetic energy of the top drive alone, 1/2 J Omega_0^2 (zero for a held top).
    dissipated_friction : ndarray
        Dissipated by the contacts along the string: the integral of C |theta_i'| over the
        moving contacts, C = C_s below the threshold speed and C_d above (zero without).
    """

    time: np.ndarray
    work_in: np.ndarray
    dissipated_relative: np.ndarray
    dissipated_drag: np.ndarray
    work_bit: np.ndarray
    kinetic: np.ndarray
    potential: np.ndarray
    kinetic_top: np.ndarray
    dissipated_friction: np.ndarray | None = None

    def __repr__(self) -> str:  # short: totals, no time series
        return (
            f"EnergyBalance({self.time.size} samples over {self.time[-1]:g} s, work in "
            f"{self.work_in[-1]:.4g}, relative residual {self.relative_residual:.2g})"
        )

    @property
    def dissipated(self) -> np.ndarray:
        """Dissipated by all damping and by the contacts along the string [J]."""
        total = self.dissipated_relative + self.dissipated_drag
        return total if self.dissipated_friction is None else total + self.dissipated_friction

    @property
    def stored(self) -> np.ndarray:
        """Change of kinetic plus potential energy since t = 0 [J]."""
        return self.kinetic + self.potential - (self.kinetic[0] + self.potential[0])

    @property
    def residual(self) -> np.ndarray:
        """work_in - (change of stored energy + dissipated + work at the bit) [J]."""
        return self.work_in - (self.stored + self.dissipated + self.work_bit)

    @property
    def relative_residual(self) -> float:
        """max |residual| over the run, relative to the total work in (or the largest term)."""
        scale = max(
            float(np.max(np.abs(self.work_in))),
            float(np.max(np.abs(self.dissipated + self.work_bit))),
            float(np.max(np.abs(self.stored))),
        )
        if scale == 0.0:
            return 0.0
        return float(np.max(np.abs(self.residual)) / scale)

    def to_dict(self) -> dict[str, Any]:
        """Totals over the run [J] and the relative residual, for JSON."""
        return {
            "work_in": float(self.work_in[-1]),
            "dissipated_relative": float(self.dissipated_relative[-1]),
            "dissipated_drag": float(self.dissipated_drag[-1]),
            "dissipated_friction": (
                0.0 if self.dissipated_friction is None else float(self.dissipated_friction[-1])
            ),
            "work_bit": float(self.work_bit[-1]),
            "kinetic_change": float(self.kinetic[-1] - self.kinetic[0]),
            "potential_change": float(self.potential[-1] - self.potential[0]),
            "top_kinetic_change": float(self.kinetic_top[-1] - self.kinetic_top[0]),
            "residual": float(self.residual[-1]),
            "relative_residual": self.relative_residual,
        }


def _with_top_node(matrix: np.ndarray, top: float, link: float) -> np.ndarray:
    n = matrix.shape[0]
    out = np.zeros((n + 1, n + 1))
    out[1:, 1:] = matrix
    out[0, 0], out[0, 1], out[1, 0] = top, link, link
    return out


def energy_balance(results: Any) -> EnergyBalance:
    """The energy balance of a :class:`torsio.analysis.transient.TransientResults`.

    Uses only the sampled response (no re-integration of the equations of motion). An axial
    run keeps no states: its balance is the kernel's, step by step (``results.axial.energy``,
    :mod:`torsio.analysis.axial_energy`).
    """
    if getattr(results, "axial", None) is not None:
        raise TypeError(
            "an axial run keeps the bit's and the top's signals, not its states: its energy "
            "balance is results.axial.energy, summed by the axial engine over every step"
        )
    system: System | None = results.system
    if system is None:
        raise TypeError(
            "this run keeps no System (it was read from a file): its energy balance needs "
            "the System the run integrated; run it again to have one"
        )
    dynamics = Dynamics.from_system(system)
    relative_damping, drag = damping_split(system)
    if dynamics.has_top_node:
        c1 = float(system.top_damping[0])
        relative_damping = _with_top_node(relative_damping, c1, -c1)
        drag = _with_top_node(drag, float(dynamics.top.drag), 0.0)
    time_grid = np.asarray(results.time)
    states = np.asarray(results.states).T
    z, twists, relative = dynamics.split(states)
    speeds = relative + dynamics.reference_speed
    if dynamics.has_top_node:
        motor = np.asarray(dynamics.motor_torque(z, twists, relative, time_grid)[0], float)
        power_in = motor * speeds[0]
        kinetic_top = 0.5 * dynamics.top.inertia * speeds[0] ** 2
    else:
        set_speed, psi = dynamics.set_speed_at(time_grid)
        power_in = set_speed * np.asarray(dynamics.pipe_torque(twists, relative, time_grid))
        kinetic_top = np.zeros(time_grid.shape)
        twists, relative = twists - psi, relative - (set_speed - dynamics.reference_speed)
    power_relative = np.einsum("it,ij,jt->t", relative, relative_damping, relative)
    power_drag = np.einsum("it,ij,jt->t", speeds, drag, speeds)
    power_bit = np.asarray(dynamics.bit_torque(speeds[-1]), dtype=float) * speeds[-1]
    kinetic = 0.5 * np.einsum("it,ij,jt->t", speeds, dynamics.mass_matrix, speeds)
    potential = 0.5 * np.einsum("it,ij,jt->t", twists, dynamics.stiffness_matrix, twists)
    friction = None
    if dynamics.contacts is not None:
        contacts = dynamics.contacts
        moving = np.abs(speeds)
        slow = moving < contacts.threshold_speed
        capacity = np.where(slow, contacts.static[:, None], contacts.dynamic[:, None])
        friction = _cumulative((capacity * moving).sum(axis=0), time_grid)
    return EnergyBalance(
        time=time_grid,
        work_in=_cumulative(np.broadcast_to(power_in, time_grid.shape), time_grid),
        dissipated_relative=_cumulative(power_relative, time_grid),
        dissipated_drag=_cumulative(power_drag, time_grid),
        work_bit=_cumulative(np.broadcast_to(power_bit, time_grid.shape), time_grid),
        kinetic=kinetic,
        potential=potential,
        kinetic_top=kinetic_top,
        dissipated_friction=friction,
    )
