"""Coulomb friction along the string at the nodes of the lumped axial-torsional chain.

Node i presses on the borehole with the normal force N_i of its share of the string; its
contact has a static and a sliding capacity F_s = ∫ μ_s N dx, F_d = ∫ μ_d N dx [N] over
that share and a radius r_i [m], the outer radius the torque capacities see
(r = ∫ μ_s N r_o dx / F_s, so Σ F_s r is the break-off torque of
:func:`torsio.well.break_off.break_off` exactly). The friction is one Coulomb force on the
contact's sliding velocity s = (V, r ω) (axial and tangential, m/s): sliding it is μ_d N
opposite to s (force −F_d V/|s|, torque −F_d r² ω/|s|); stuck it is anything in the disc of
radius F_s.

Over one step h it is solved at the velocity level, as the bit's contact is (Moreau): from
the free velocities s* = (V*, r Ω*) of the step, the impulse that stops the node is
P = M s*, M = diag(m, I/r²) (the node's mass and its inertia seen at the radius). The node
sticks (s = 0) when |P| <= h F_c, the cone's radius F_c being F_s while the node's speed
|s|/r at the step's start is below the well's threshold speed and F_d above it. Otherwise
it slides with the new velocity solving s = s* − h F_c M⁻¹ s/|s|: each component shrinks,
s_k = s*_k M_k ρ/(M_k ρ + h F_c) with ρ = |s| the root of

    φ(ρ) = Σ_k (M_k s*_k / (M_k ρ + h F_c))² − 1 = 0,

decreasing and convex on ρ >= 0 (:func:`sliding_speed`; where m = I/r² it is
ρ = |s*| − h F_c/m, so s = s*(1 − h F_c/(m |s*|))). Below the threshold speed a node
that creeps thus carries its static capacity, as a stuck one may (Karnopp's model, as the
torsional contacts: a slowly twisted string breaks free at Σ F_s r); above it, F_d.

:func:`node_friction` is the compiled step of one contact, called by
:mod:`torsio.axial.kernel`; :mod:`torsio.axial.string_contacts` builds the capacities of a
string in a well at the nodes of a chain.

Examples
--------
>>> inertia = 500.0 * 0.0635**2  # I/r² = m = 500 kg: s = s*(1 − h F_d/(m |s*|))
>>> velocity, speed, stuck = node_friction(0.01, 2.0, 0.0635, 1 / 500.0, 1 / inertia,
...                                        4000.0, 3000.0, 1e-3, False)
>>> stuck, round(velocity, 9), round(speed, 9)
(False, 0.009529017, 1.90580337)
>>> node_friction(0.001, 0.01, 0.0635, 1 / 500.0, 1 / 2.0, 4000.0, 3000.0, 1e-3, True)
(0.0, 0.0, True)
"""

from __future__ import annotations

import math

from torsio.solvers.compiled import njit

__all__ = ["node_friction", "sliding_speed"]


@njit(cache=True, error_model="numpy", _nrt=False)
def sliding_speed(
    axial, tangential, mass, tangential_mass, impulse
) -> float:  # pragma: no cover - compiled
    """ρ = |s| [m/s], the root of φ(ρ) = (m V*/(m ρ + p))² + (J v*/(J ρ + p))² − 1 for the
    free velocities ``axial`` V* and ``tangential`` v* = r Ω* [m/s], ``mass`` m [kg],
    ``tangential_mass`` J = I/r² [kg] and the sliding impulse ``impulse`` p = h F_d [N s];
    the node slides (|M s*| > p). Newton's steps from the lower bound |s*| − p/min(m, J)
    rise monotonically to the root (φ convex and decreasing), to round-off."""
    free = math.hypot(axial, tangential)
    rho = max(0.0, free - impulse / min(mass, tangential_mass))
    upper = free - impulse / max(mass, tangential_mass)
    for _ in range(200):
        qa = mass * axial / (mass * rho + impulse)
        qt = tangential_mass * tangential / (tangential_mass * rho + impulse)
        value = qa * qa + qt * qt - 1.0
        slope = -2.0 * (
            mass * qa * qa / (mass * rho + impulse)
            + tangential_mass * qt * qt / (tangential_mass * rho + impulse)
        )
        if value <= 0.0 or slope == 0.0:
            break
        new = min(rho - value / slope, upper)
        if not new > rho:
            break
        rho = new
    return rho


@njit(cache=True, error_model="numpy", _nrt=False)
def node_friction(
    velocity, speed, radius, inverse_mass, inverse_inertia, static_force, sliding_force,
    step, sticky,
) -> tuple[float, float, bool]:  # pragma: no cover - compiled  # fmt: skip
    """(V [m/s], ω [rad/s], stuck) of a contact after the step ``step`` [s] from its free
    ``velocity`` V* and ``speed`` Ω*: at rest when the impulse that stops it is within
    h F_c (F_c = ``static_force`` when ``sticky``, the node slow at the step's start, else
    ``sliding_force`` [N]), else sliding under h F_c (:func:`sliding_speed`).
    ``radius`` r [m], ``inverse_mass`` 1/m [1/kg], ``inverse_inertia`` 1/I [1/(kg m²)]."""
    mass = 1.0 / inverse_mass
    tangential_mass = 1.0 / (inverse_inertia * radius * radius)
    tangential = radius * speed
    stop = math.hypot(mass * velocity, tangential_mass * tangential)
    cone = static_force if sticky else sliding_force
    if stop <= step * cone:
        return 0.0, 0.0, True
    impulse = step * cone
    if impulse == 0.0:
        return velocity, speed, False
    rho = sliding_speed(velocity, tangential, mass, tangential_mass, impulse)
    new_velocity = velocity * mass * rho / (mass * rho + impulse)
    new_tangential = tangential * tangential_mass * rho / (tangential_mass * rho + impulse)
    return new_velocity, new_tangential / radius, False
