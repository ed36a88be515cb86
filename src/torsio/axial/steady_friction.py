"""Steady drilling with Coulomb friction along the string, in closed form.

In steady drilling every node slides axially at the rate of penetration V₀ while it turns at
Ω₀, so each contact's sliding friction F_d (:func:`torsio.solvers.contact_law.cone_step`) splits
along its sliding direction ŝ₀ = (V₀, r Ω₀)/|s₀|:

    axial friction  F_a = F_d V₀/|s₀|,     friction torque  T_f = F_d r² Ω₀/|s₀|.

Under the weight hook the weight W_h hangs on the top node and the weight reaching the bit
is what the friction leaves, W_b = W_h − Σ F_a(V₀(W_b)), with V₀(W) of
:func:`torsio.axial.steady.steady_drilling` (one increasing scalar equation, solved to
round-off); under the speed hook the bit gets W_b = W₀ and the hook supplies the force
that takes, W_h = W₀ + Σ F_a. The surface torque is T₀ + Σ T_f. ROP, MSE (of the bit)
and bit torque are those of :func:`~torsio.axial.steady.steady_drilling` at W_b.

About this state the friction of a sliding contact linearizes to the damping matrix

    D = F_d/|s₀| (I − ŝ₀ŝ₀ᵀ)      (force on (V, r ω) per unit (δV, r δω)),

positive semi-definite: a perturbation along ŝ₀ does not change the friction, across it
turns the force (:func:`friction_damping`).

Examples
--------
>>> import numpy as np
>>> from torsio.axial.rgd import rgd_example
>>> from torsio.well.axial_contacts import AxialContacts
>>> contacts = AxialContacts(np.array([2e3, 3e3]), np.array([1.5e3, 2.5e3]),
...                          np.array([0.0635, 0.0635]))
>>> state, friction = steady_with_friction(rgd_example(), 100e3, 60.0, contacts, "speed")
>>> round(friction.axial_friction, 3), round(friction.surface_torque - state.bit_torque, 3)
(74.044, 253.956)
>>> friction.hook_force == state.wob + friction.axial_friction  # the speed hook's force
True
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
import scipy.optimize
from numpy.typing import NDArray

from torsio.axial.rgd import RGDBit
from torsio.axial.steady import SteadyDrilling, steady_drilling
from torsio.units import RPM_TO_RAD_S
from torsio.well.axial_contacts import AxialContacts

__all__ = [
    "SteadyFriction",
    "friction_damping",
    "friction_split",
    "drilling_state",
    "steady_loads",
    "steady_with_friction",
]


@attrs.frozen(eq=False)
class SteadyFriction:
    """What the string's friction takes in steady drilling.

    Attributes
    ----------
    hook_force : float
        The weight on the top node [N] (the applied one under the weight hook, the force
        needed under the speed hook).
    axial_friction, friction_torque : float
        Σ F_a [N] and Σ T_f [N m].
    surface_torque : float
        T₀ + Σ T_f [N m], the torque at the top.
    node_force, node_torque : ndarray
        F_a [N] and T_f [N m] of every node, from the surface down.
    """

    hook_force: float
    axial_friction: float
    friction_torque: float
    surface_torque: float
    node_force: NDArray[np.float64]
    node_torque: NDArray[np.float64]

    def to_dict(self) -> dict[str, Any]:
        """``hook_force``, ``axial_friction`` [N], ``friction_torque``, ``surface_torque``
        [N m]."""
        return {
            "hook_force": self.hook_force,
            "axial_friction": self.axial_friction,
            "friction_torque": self.friction_torque,
            "surface_torque": self.surface_torque,
        }


def friction_split(
    contacts: AxialContacts, rop: float, speed: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(F_a [N], T_f [N m]) of every contact sliding at V₀ = ``rop`` [m/s] and Ω₀ = ``speed``
    [rad/s]: F_d V₀/|s₀| and F_d r² Ω₀/|s₀|, |s₀| = √(V₀² + r²Ω₀²)."""
    r = contacts.radius
    norm = np.hypot(rop, r * speed)
    safe = np.where(norm > 0.0, norm, 1.0)
    force = np.where(norm > 0.0, contacts.sliding_force * rop / safe, 0.0)
    torque = np.where(norm > 0.0, contacts.sliding_force * r * r * speed / safe, 0.0)
    return force, torque


def steady_with_friction(
    bit: RGDBit, wob: float, rpm: float, contacts: AxialContacts, hook: str
) -> tuple[SteadyDrilling, SteadyFriction]:
    """The steady state at the bit and the friction's part (see the module docstring):
    ``wob`` [N] is the hook's weight under the weight ``hook``, the bit's under the speed
    hook."""
    speed = rpm * RPM_TO_RAD_S
    if hook == "speed":
        steady = steady_drilling(bit, wob, rpm)
    else:
        steady_drilling(bit, wob, rpm)  # the checks of the applied weight and speed
        floor = bit.friction_weight

        def excess(weight: float) -> float:
            rop = speed * (weight - floor) / (2 * math.pi * bit.cutting_weight_per_depth)
            return weight + float(np.sum(friction_split(contacts, rop, speed)[0])) - wob

        if excess(wob) <= 0.0:
            bit_weight = wob
        else:
            bit_weight = scipy.optimize.brentq(excess, floor, wob, xtol=1e-12, rtol=1e-15)
        steady = steady_drilling(bit, bit_weight, rpm)
    force, torque = friction_split(contacts, steady.rop, speed)
    axial, turning = float(np.sum(force)), float(np.sum(torque))
    friction = SteadyFriction(
        hook_force=float(wob) if hook != "speed" else steady.wob + axial,
        axial_friction=axial,
        friction_torque=turning,
        surface_torque=steady.bit_torque + turning,
        node_force=force,
        node_torque=torque,
    )
    return steady, friction


def drilling_state(
    bit: RGDBit, wob: float, rpm: float, contacts: AxialContacts | None, hook: str
) -> tuple[SteadyDrilling, SteadyFriction | None]:
    """The steady state at the bit, and the friction's part when there are ``contacts``
    (their normal force rebuilt at ``wob``, :func:`steady_with_friction`); without them
    :func:`~torsio.axial.steady.steady_drilling` and None."""
    if contacts is None:
        return steady_drilling(bit, wob, rpm), None
    return steady_with_friction(bit, wob, rpm, contacts.at_wob(wob), hook)


def steady_loads(
    steady: SteadyDrilling, friction: SteadyFriction
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(torque [N m], force [N]) each spring carries in steady drilling with friction:
    spring j (above node j) the bit's load and the friction of nodes j and below."""
    torque = steady.bit_torque + np.cumsum(friction.node_torque[::-1])[::-1]
    force = steady.wob + np.cumsum(friction.node_force[::-1])[::-1]
    return torque, force


def friction_damping(contacts: AxialContacts, rop: float, speed: float) -> NDArray[np.float64]:
    """The damping matrices D_i = F_d/|s₀| (I − ŝ₀ŝ₀ᵀ) of every contact, shape (nodes, 2, 2)
    [N s/m], in the (V, r ω) metric, at V₀ = ``rop`` [m/s] and Ω₀ = ``speed`` [rad/s]
    (zero where |s₀| = 0 or there is no contact)."""
    r = contacts.radius
    norm = np.hypot(rop, r * speed)
    matrices = np.zeros((r.size, 2, 2))
    for i, size in enumerate(norm):
        if size > 0.0 and contacts.sliding_force[i] > 0.0:
            unit = np.array([rop, r[i] * speed]) / size
            matrices[i] = contacts.sliding_force[i] / size * (np.eye(2) - np.outer(unit, unit))
    return matrices
