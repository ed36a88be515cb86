"""Coulomb contacts along the string in the compiled RODAS4 kernel (:mod:`torsio.solvers.rodas`).

The law is :mod:`torsio.solvers.contact_law`'s event form (Aarsnes & Shor 2018): each
node's state code sits in row ``VEC_CONTACT_STATE`` of the work space: 0 stuck (or no
contact: C_s = 0), +-1 slow, +-2 fast, the sign that of w = Omega_ref + v.

Within a step the states are fixed, so the equations are smooth: a moving contact adds
the constant torque -C sign w to its node (:func:`add_friction`); a stuck node's speed
equation is v_i' = 0: its row of the tridiagonal step matrix becomes the identity with
right-hand side 0 and its couplings are zeroed (:func:`decouple`, :func:`zero_stuck`;
its increment is 0, so the elimination still holds), while its twist moves at
v_i = -Omega_ref. The holding torque H_i is the node's force without friction (lumped
mass only: [I] diagonal).

After a step that passes the error test, :func:`check_step` evaluates each contact's margins
at the step's end (a moving node's speed sign w, or a stuck node's C_s - |H|; and a moving
node's distance to w_th). One falling through minus its tolerance
(:data:`torsio.solvers.contact_law.TOLERANCE` of its scale) rejects the step, which is
retried shortened to the crossing, aimed at half the tolerance below 0 on the step's cubic
Hermite interpolant of the margin's quantity (:func:`cubic_crossing`: a moving node's speed,
from its accelerations at both ends; a stuck node's holding torque, from its rate at both
ends, :func:`holding_rate`), so that the retry mostly lands within the tolerance at once
(the chord of the margin falls short or overshoots where the margin curves, and costs more
retries: docs/performance.md); a step is accepted when every margin at its end is above
minus its tolerance, and the contacts whose margin is then within it and falling switch
(:func:`switch`). A node that sticks gets v_i = -Omega_ref exactly. A margin already below
its tolerance at the step's start switches there (the run starts, or a node just set moving
turns back). The friction's work over a step is exact: its torque is constant, so C |delta
theta|. An accepted step's end forces are those :func:`check_step` computed there
(:func:`restart_at_end`).
"""

from __future__ import annotations

import math

from torsio.solvers import contact_law as law
from torsio.solvers.chain_kernel import accelerations, forces
from torsio.solvers.compiled import njit, njit_inner
from torsio.solvers.cycles import hermite
from torsio.solvers.layouts import (
    CHAIN_CONTACT_DYNAMIC,
    CHAIN_CONTACT_STATIC,
    CHAIN_CONTACT_THRESHOLD,
    CHAIN_DAMPING,
    CHAIN_DAMPING_UPPER,
    CHAIN_MASS,
    CHAIN_STIFFNESS,
    CHAIN_STIFFNESS_UPPER,
    TOP_HAS_NODE,
)

__all__ = [
    "add_friction",
    "check_step",
    "cubic_crossing",
    "decouple",
    "friction_work",
    "holding_rate",
    "is_stuck",
    "restart",
    "restart_at_end",
    "start_contacts",
    "switch",
    "zero_stuck",
]


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def start_contacts(chain, omega, v, state) -> bool:
    """Each contact's state from its speed (0: stuck); whether the chain has any contact."""
    found = False
    for i in range(v.size):
        state[i] = 0.0
        if chain[CHAIN_CONTACT_STATIC, i] > 0.0:
            found = True
            state[i] = law.start_code(omega + v[i], chain[CHAIN_CONTACT_THRESHOLD, i])
    return found


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def is_stuck(chain, state, i) -> bool:
    """Whether node i's contact holds it at rest."""
    return state[i] == 0.0 and chain[CHAIN_CONTACT_STATIC, i] > 0.0


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def _friction(chain, state, i) -> float:
    """Node i's friction torque in its state [N m] (0 stuck or without a contact)."""
    return law.friction(state[i], chain[CHAIN_CONTACT_STATIC, i], chain[CHAIN_CONTACT_DYNAMIC, i])


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def add_friction(chain, state, fv) -> None:
    """fv -= the friction of every moving contact."""
    for i in range(fv.size):
        fv[i] -= _friction(chain, state, i)


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def decouple(chain, state, band) -> None:
    """Zero the couplings of every stuck node in the step matrix's upper band."""
    for i in range(band.size):
        if is_stuck(chain, state, i):
            band[i] = 0.0
            if i > 0:
                band[i - 1] = 0.0


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def zero_stuck(chain, state, x) -> None:
    """x_i = 0 at every stuck node (its speed increment, or acceleration)."""
    for i in range(x.size):
        if is_stuck(chain, state, i):
            x[i] = 0.0


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def restart(
    chain, top, torque, p, wob, radius, omega, set_speed, top_twist, phi, v, z, f0v, f0z, mpiv,
    mlow, acc, state, contacts,
) -> None:  # fmt: skip
    """The forces (friction included) and accelerations at a state, in the present states
    (the set speed and the held top's twist at its time: :func:`chain_kernel.forces`)."""
    forces(chain, top, torque, p, wob, radius, omega, set_speed, top_twist, phi, v, z, f0v, f0z)
    if contacts:
        add_friction(chain, state, f0v)
    accelerations(chain, mpiv, mlow, f0v, acc)
    if contacts:
        zero_stuck(chain, state, acc)


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def restart_at_end(chain, f1, fz1, f0v, f0z, mpiv, mlow, acc, state) -> None:
    """:func:`restart` at the end of a step :func:`check_step` accepted, from the forces
    without friction it computed there (``f1``, ``fz1``): the same numbers, one force
    evaluation fewer."""
    for i in range(f1.size):
        f0v[i] = f1[i]
    for i in range(fz1.size):
        f0z[i] = fz1[i]
    add_friction(chain, state, f0v)
    accelerations(chain, mpiv, mlow, f0v, acc)
    zero_stuck(chain, state, acc)


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def _margin(chain, state, omega, speed, holding, i, k) -> float:
    """Margin k of node i (0: speed or holding torque, 1: threshold), falling through 0 at
    its switch; 1.0 where it cannot switch (:func:`torsio.solvers.contact_law.margin`)."""
    static, threshold = chain[CHAIN_CONTACT_STATIC, i], chain[CHAIN_CONTACT_THRESHOLD, i]
    return law.margin(state[i], static, threshold, omega + speed, holding, k)


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def _slope(state, acc, threshold, k) -> float:
    """d/dt of margin k (:func:`_margin`) of a moving node of acceleration ``acc``."""
    rate = math.copysign(1.0, state) * acc
    if k == 0:
        return rate
    if abs(state) == 1.0:
        return -rate
    return rate if threshold > 0.0 else 0.0


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def _tolerance(chain, state, omega, i, k) -> float:
    static, threshold = chain[CHAIN_CONTACT_STATIC, i], chain[CHAIN_CONTACT_THRESHOLD, i]
    return law.tolerance(state[i], static, threshold, omega, k)


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def _acceleration(chain, state, f, i) -> float:
    """Node i's acceleration from its force without friction f_i [rad/s^2] (lumped mass; 0
    where stuck, or beyond the chain's ends)."""
    if i < 0 or i >= f.size or is_stuck(chain, state, i):
        return 0.0
    return (f[i] - _friction(chain, state, i)) / chain[CHAIN_MASS, i]


@njit(cache=True, error_model="numpy", _nrt=False)
def holding_rate(chain, v, i, below, own, above) -> float:
    """d/dt of node i's force without friction [N m/s], at speeds ``v`` and the
    accelerations of nodes i - 1, i and i + 1 (``below``, ``own``, ``above``): the chain's
    springs and dampers (:func:`torsio.solvers.chain_kernel.forces`). For a stuck node, its
    holding torque's rate; the bit's torque is constant while it is stuck, and a top-drive
    node's motor torque is left out (the caller does not use it there)."""
    rate = -chain[CHAIN_STIFFNESS, i] * v[i] - chain[CHAIN_DAMPING, i] * own
    if i > 0:
        rate -= chain[CHAIN_STIFFNESS_UPPER, i - 1] * v[i - 1]
        rate -= chain[CHAIN_DAMPING_UPPER, i - 1] * below
    if i < v.size - 1:
        rate -= chain[CHAIN_STIFFNESS_UPPER, i] * v[i + 1]
        rate -= chain[CHAIN_DAMPING_UPPER, i] * above
    return rate


@njit(cache=True, error_model="numpy", _nrt=False)
def cubic_crossing(chain, state, omega, i, k, u0, u1, d0, d1, start, end, tolerance) -> float:
    """Where in [0, 1] margin k of node i (:func:`_margin`, from ``start`` > 0 to ``end`` <
    0 over the step) reaches half its ``tolerance`` below 0 on the cubic Hermite interpolant
    of its quantity: values ``u0``, ``u1`` and derivatives times the step ``d0``, ``d1`` of
    the node's speed (moving) or holding torque (stuck). Illinois regula falsi on the cubic,
    to a quarter of the tolerance."""
    target = -0.5 * tolerance
    lo, hi, below_lo, below_hi = 0.0, 1.0, start - target, end - target
    x, side = 1.0, 0
    for _ in range(60):
        x = (lo * below_hi - hi * below_lo) / (below_hi - below_lo)
        u = hermite(u0, u1, d0, d1, x)
        gap = _margin(chain, state, omega, u, u, i, k) - target
        if abs(gap) <= 0.25 * tolerance:
            break
        if gap > 0.0:
            lo, below_lo = x, gap
            if side == 1:
                below_hi *= 0.5
            side = 1
        else:
            hi, below_hi = x, gap
            if side == -1:
                below_lo *= 0.5
            side = -1
    return x


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def check_step(
    chain, top, torque, p, wob, radius, omega, set_speed, top_twist, v, f0v, aphi, av, az, kphi,
    kv, kz, acc, phi1, v1, z1, f1, fz1, state, pending, h, h_min,
) -> float:  # fmt: skip
    """A step of length h that passed the error test, from (v, f0v, acc: speeds, forces and
    accelerations at its start) to (aphi + kphi, av + kv, az + kz), written into (phi1, v1,
    z1), its forces without friction into (f1, fz1), with the set speed and the held top's
    twist at its end. Returns 1.0 to accept it
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
    forces(chain, top, torque, p, wob, radius, omega, set_speed, top_twist, phi1, v1, z1, f1, fz1)
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
                if state[i] != 0.0:  # a speed margin: the speed's cubic
                    d1 = h * _acceleration(chain, state, f1, i)
                    fraction = cubic_crossing(
                        chain, state, omega, i, k, v[i], v1[i], h * acc[i], d1, start, end,
                        tolerance,
                    )  # fmt: skip
                elif i > 0 or top[TOP_HAS_NODE] == 0.0:  # the holding torque's cubic
                    d0 = h * holding_rate(chain, v, i, acc[i - 1] if i > 0 else 0.0, acc[i],
                                          acc[i + 1] if i < n - 1 else 0.0)  # fmt: skip
                    d1 = h * holding_rate(
                        chain, v1, i, _acceleration(chain, state, f1, i - 1),
                        _acceleration(chain, state, f1, i),
                        _acceleration(chain, state, f1, i + 1),
                    )  # fmt: skip
                    fraction = cubic_crossing(
                        chain, state, omega, i, k, holding, f1[i], d0, d1, start, end,
                        tolerance,
                    )  # fmt: skip
                else:  # a top-drive node: the chord of its margin
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


@njit_inner(cache=True, error_model="numpy", _nrt=False)
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
        static, threshold = chain[CHAIN_CONTACT_STATIC, i], chain[CHAIN_CONTACT_THRESHOLD, i]
        state[i] = law.switched(now, code, holding, static, threshold)
        if state[i] == 0.0 and now != 0.0:  # it sticks
            v[i] = -omega
    return made


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def friction_work(chain, state, phi, phi1, omega, h) -> float:
    """The friction's work over a step from twists ``phi`` to ``phi1`` [J] (exact: each
    moving contact's torque is constant in the step)."""
    total = 0.0
    for i in range(phi.size):
        torque = _friction(chain, state, i)
        if torque != 0.0:
            total += torque * (phi1[i] - phi[i] + omega * h)
    return total
