"""Coulomb contacts along the string in the compiled RODAS4 kernel (:mod:`torsio.solvers.rodas`).

The law is that of :mod:`torsio.solvers.contact_events` (Aarsnes & Shor 2018): a contact
node is stuck (its absolute speed w = Omega_ref + v held at exactly 0, the friction the
torque H that holds it, |H| <= C_s), slow (0 < |w| < w_th: friction C_s sign w) or fast
(|w| >= w_th: C_d sign w). Each node's state sits in row ``VEC_CONTACT_STATE`` of the work
space: 0 stuck (or no contact: C_s = 0), +-1 slow, +-2 fast, the sign that of w.

Within a step the states are fixed, so the equations are smooth: a moving contact adds
the constant torque -C sign w to its node (:func:`add_friction`); a stuck node's speed
equation is v_i' = 0: its row of the tridiagonal step matrix becomes the identity with
right-hand side 0 and its couplings are zeroed (:func:`decouple`, :func:`zero_stuck`;
its increment is 0, so the elimination still holds), while its twist moves at
v_i = -Omega_ref. The holding torque H_i is the node's force without friction (lumped
mass only: [I] diagonal).

After a step that passes the error test, :func:`check_step` evaluates each contact's
margins at the step's end (a moving node's speed sign w, or a stuck node's C_s - |H|;
and a moving node's distance to w_th). One falling through minus its tolerance
(:data:`TOLERANCE` of its scale) rejects the step, which is retried shortened to the
crossing, linearly interpolated between the step's ends (regula falsi from the step's
start); a step is accepted when every margin at its end is above minus its tolerance,
and the contacts whose margin is then within it and falling switch (:func:`switch`). A
node that sticks gets v_i = -Omega_ref exactly. A margin already below its tolerance at
the step's start switches there (the run starts, or a node just set moving turns back).
The friction's work over a step is exact: its torque is constant, so C |delta theta|.
"""

from __future__ import annotations

import math

from torsio.solvers.chain_kernel import accelerations, forces
from torsio.solvers.compiled import njit
from torsio.solvers.layouts import (
    CHAIN_CONTACT_DYNAMIC,
    CHAIN_CONTACT_STATIC,
    CHAIN_CONTACT_THRESHOLD,
)

__all__ = [
    "TOLERANCE",
    "add_friction",
    "check_step",
    "decouple",
    "friction_work",
    "is_stuck",
    "restart",
    "start_contacts",
    "switch",
    "zero_stuck",
]

TOLERANCE = 1e-9
"""How near 0 a switch's margin counts as 0, relative to its scale: 1 + |Omega_ref| + w_th
[rad/s] for a speed, C_s [N m] for a holding torque (as in :mod:`contact_events`)."""


@njit(cache=True, error_model="numpy", _nrt=False)
def start_contacts(chain, omega, v, state) -> bool:
    """Each contact's state from its speed (0: stuck); whether the chain has any contact."""
    found = False
    for i in range(v.size):
        state[i] = 0.0
        if chain[CHAIN_CONTACT_STATIC, i] > 0.0:
            found = True
            speed = omega + v[i]
            if speed != 0.0:
                fast = abs(speed) >= chain[CHAIN_CONTACT_THRESHOLD, i]
                state[i] = math.copysign(2.0 if fast else 1.0, speed)
    return found


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def is_stuck(chain, state, i) -> bool:
    """Whether node i's contact holds it at rest."""
    return state[i] == 0.0 and chain[CHAIN_CONTACT_STATIC, i] > 0.0


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def _friction(chain, state, i) -> float:
    """Node i's friction torque in its state [N m] (0 stuck or without a contact)."""
    code = state[i]
    if code == 0.0:
        return 0.0
    slow = abs(code) == 1.0
    return math.copysign(chain[CHAIN_CONTACT_STATIC if slow else CHAIN_CONTACT_DYNAMIC, i], code)


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def add_friction(chain, state, fv) -> None:
    """fv -= the friction of every moving contact."""
    for i in range(fv.size):
        fv[i] -= _friction(chain, state, i)


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def decouple(chain, state, band) -> None:
    """Zero the couplings of every stuck node in the step matrix's upper band."""
    for i in range(band.size):
        if is_stuck(chain, state, i):
            band[i] = 0.0
            if i > 0:
                band[i - 1] = 0.0


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def zero_stuck(chain, state, x) -> None:
    """x_i = 0 at every stuck node (its speed increment, or acceleration)."""
    for i in range(x.size):
        if is_stuck(chain, state, i):
            x[i] = 0.0


@njit(cache=True, error_model="numpy", _nrt=False)
def restart(
    chain, top, torque, p, wob, radius, omega, omega_set, phi, v, z, f0v, f0z, mpiv, mlow, acc,
    state, contacts,
) -> None:  # fmt: skip
    """The forces (friction included) and accelerations at a state, in the present states."""
    forces(chain, top, torque, p, wob, radius, omega, omega_set, phi, v, z, f0v, f0z)
    if contacts:
        add_friction(chain, state, f0v)
    accelerations(chain, mpiv, mlow, f0v, acc)
    if contacts:
        zero_stuck(chain, state, acc)


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def _margin(chain, state, omega, speed, holding, i, k) -> float:
    """Margin k of node i (0: speed or holding torque, 1: threshold), falling through 0 at
    its switch; 1.0 where it cannot switch."""
    code = state[i]
    if code == 0.0:
        return chain[CHAIN_CONTACT_STATIC, i] - abs(holding) if k == 0 else 1.0
    moving = math.copysign(1.0, code) * (omega + speed)
    if k == 0:
        return moving
    threshold = chain[CHAIN_CONTACT_THRESHOLD, i]
    if abs(code) == 1.0:
        return threshold - moving
    return moving - threshold if threshold > 0.0 else 1.0


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def _slope(state, acc, threshold, k) -> float:
    """d/dt of margin k (:func:`_margin`) of a moving node of acceleration ``acc``."""
    rate = math.copysign(1.0, state) * acc
    if k == 0:
        return rate
    if abs(state) == 1.0:
        return -rate
    return rate if threshold > 0.0 else 0.0


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def _tolerance(chain, state, omega, i, k) -> float:
    if k == 0 and state[i] == 0.0:
        return TOLERANCE * chain[CHAIN_CONTACT_STATIC, i]
    return TOLERANCE * (1.0 + abs(omega) + chain[CHAIN_CONTACT_THRESHOLD, i])


@njit(cache=True, error_model="numpy", _nrt=False)
def check_step(
    chain, top, torque, p, wob, radius, omega, omega_set, v, f0v, aphi, av, az, kphi, kv, kz,
    acc, phi1, v1, z1, f1, fz1, state, pending, h, h_min,
) -> float:  # fmt: skip
    """A step of length h that passed the error test, from (v, f0v, acc: speeds, forces and
    accelerations at its start) to (aphi + kphi, av + kv, az + kz), written into (phi1, v1,
    z1), its forces without friction into (f1, fz1). Returns 1.0 to accept it
    (``pending``: the switch due at its end per node, 1 speed or holding torque, 2
    threshold), the fraction of the step to retry it with (a margin falls through minus
    its tolerance; a half where one rising from its switch comes back through it), or
    -1.0 when contacts switch at the step's start (``pending``: which): a margin through
    its tolerance there, or a crossing closer than ``h_min`` [s]."""
    n = v.size
    for i in range(n):
        phi1[i] = aphi[i] + kphi[i]
        v1[i] = av[i] + kv[i]
        pending[i] = 0.0
    for i in range(z1.size):
        z1[i] = az[i] + kz[i]
    forces(chain, top, torque, p, wob, radius, omega, omega_set, phi1, v1, z1, f1, fz1)
    instant = False
    theta = 1.0
    for i in range(n):
        if chain[CHAIN_CONTACT_STATIC, i] <= 0.0:
            continue
        holding = f0v[i] + _friction(chain, state, i)
        for k in range(2):
            tolerance = _tolerance(chain, state, omega, i, k)
            start = _margin(chain, state, omega, v[i], holding, i, k)
            end = _margin(chain, state, omega, v1[i], f1[i], i, k)
            threshold = chain[CHAIN_CONTACT_THRESHOLD, i]
            if start > tolerance:  # a crossing in the step, or a switch at its end
                if end >= -tolerance:
                    if end <= tolerance and end < start and pending[i] == 0.0:
                        pending[i] = k + 1.0
                    continue
                fraction = start / (start - end)
                if fraction * h >= h_min:
                    theta = min(theta, fraction)
                    continue  # else too close to resolve: at the start
            elif not (end < start and end < -tolerance):  # at its switch, not falling through
                if end < start and end <= tolerance and pending[i] == 0.0:
                    pending[i] = k + 1.0
                continue
            elif state[i] != 0.0 and _slope(state[i], acc[i], threshold, k) > 0.0:
                theta = min(theta, 0.5)  # rising from its switch, through it later: shorter
                continue
            instant = True
            if pending[i] >= 0.0:
                pending[i] = -(k + 1.0)
    if instant:
        for i in range(n):  # only the switches at the start, as positive codes
            pending[i] = -pending[i] if pending[i] < 0.0 else 0.0
        return -1.0
    return theta


@njit(cache=True, error_model="numpy", _nrt=False)
def switch(chain, state, omega, v, f, pending) -> int:
    """Switch every contact with a ``pending`` switch at the state with speeds ``v`` and
    forces ``f`` (friction included); a node that sticks gets v_i = -Omega_ref. Returns
    the switches made."""
    made = 0
    for i in range(v.size):
        code = pending[i]
        if code == 0.0:
            continue
        pending[i] = 0.0
        made += 1
        holding = f[i] + _friction(chain, state, i)
        now = state[i]
        moving = 1.0 if chain[CHAIN_CONTACT_THRESHOLD, i] > 0.0 else 2.0
        if now == 0.0:  # the holding torque reached C_s: it slips its way
            state[i] = math.copysign(moving, holding)
        elif code == 1.0:  # at rest: it sticks if C_s holds it, else it turns back
            if abs(holding) < chain[CHAIN_CONTACT_STATIC, i]:
                state[i] = 0.0
                v[i] = -omega
            else:
                state[i] = math.copysign(moving, holding)
        else:  # across the threshold speed
            state[i] = math.copysign(2.0 if abs(now) == 1.0 else 1.0, now)
    return made


@njit(cache=True, error_model="numpy", _nrt=False)
def friction_work(chain, state, phi, phi1, omega, h) -> float:
    """The friction's work over a step from twists ``phi`` to ``phi1`` [J] (exact: each
    moving contact's torque is constant in the step)."""
    total = 0.0
    for i in range(phi.size):
        torque = _friction(chain, state, i)
        if torque != 0.0:
            total += torque * (phi1[i] - phi[i] + omega * h)
    return total
