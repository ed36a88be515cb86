"""One wave line of the distributed pipe on its characteristic grid: transport, junctions, ends.

A line is the pipe's axial motion or its torsion. In each uniform section the force F
(axially: the force the part above exerts on the part below, down positive, E A times the
shortening per length; torsionally the torque T) and the velocity v (axial velocity, or
angular speed) obey ρA v_t = −F_x, F_t = −E A v_x (ρJ, G J torsionally), so the Riemann
invariants

    p = F + Z v   (travels down at c),      m = F − Z v   (travels up at c),

Z = A √(E ρ) and c = √(E/ρ) (J √(G ρ) and √(G/ρ) torsionally), keep their values along
their characteristics. With cells of length c h a wave moves one node per step:
:func:`advance` shifts p down and m up inside each section, nothing interpolated.

**Junctions.** F and v are continuous where sections 1 (above) and 2 (below) meet, so the
waves leaving the junction are, exactly (:func:`junction_rows`),

    m₁ = ((Z₂ − Z₁) p₁ + 2 Z₁ m₂) / (Z₁ + Z₂),   p₂ = (2 Z₂ p₁ + (Z₁ − Z₂) m₂) / (Z₁ + Z₂),

which carry the power (p² − m²)/(4Z) through unchanged; with Z₁ = Z₂ the coefficients are
exactly 1 and 0, so a junction of equal sections changes nothing, to the last bit.

**Ends.** The top takes the arriving m: a set velocity v₀ gives p = m + 2 Z v₀
(:func:`set_top_velocity`), a set force F₀ gives p = 2 F₀ − m (:func:`set_top_force`).
At the bottom the pipe meets a lumped body moving at V: its force on the body is
F = p − Z V, the arriving wave's force less a dashpot Z, and the wave sent back up is
m = p − 2 Z V (:func:`close_bottom`).

**Contacts along the pipe.** At an inner node of both lines, massless, the arriving p and m
and the friction G on the node give its velocity from 2 Z v = p − m + G (the force above
p − Z v, below m + Z v): the free velocity v* = (p − m)/(2 Z), and over a step h the
friction acts as on a body of mass 2 Z h. :func:`pipe_contacts` solves each contact's
axial and tangential velocity on the cone of :func:`torsio.solvers.contact_law.cone_step`
with these masses and sends the waves p = m + 2 Z v down and m = p − 2 Z v up from it.

The state of a line is ``p``, ``m``: every section's nodes from the top down, section s at
``offsets[s]`` … ``offsets[s + 1] − 1`` (a junction node once in each section).

Examples
--------
>>> import numpy as np
>>> offsets = np.array([0, 3, 6])  # two sections of two cells
>>> junctions = junction_rows(np.array([1.0, 3.0]))
>>> p, m = np.array([4.0, 0, 0, 0, 0, 0]), np.zeros(6)
>>> for _ in range(2):
...     advance(p, m, offsets, junctions)
...     set_top_force(p, m, 0.0)
...     close_bottom(p, m, 3.0, 0.0)
>>> p.tolist(), m.tolist()  # at the junction: m₁ = p₁/2 back up, p₂ = 3 p₁/2 on down
([0.0, 0.0, 4.0, 6.0, 0.0, 0.0], [0.0, 0.0, 2.0, 0.0, 0.0, 0.0])
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from torsio.solvers import axial_layouts as slot
from torsio.solvers.compiled import njit
from torsio.solvers.contact_law import cone_step

__all__ = [
    "advance",
    "close_bottom",
    "junction_rows",
    "pipe_contacts",
    "set_top_force",
    "set_top_velocity",
    "smooth_end_terms",
]

REFLECTED_DOWN, TRANSMITTED_UP, TRANSMITTED_DOWN, REFLECTED_UP = 0, 1, 2, 3
"""Rows of :func:`junction_rows`: m₁ = r p₁ + t m₂ (rows 0, 1), p₂ = t' p₁ + r' m₂ (2, 3)."""


def junction_rows(impedances: NDArray[np.float64]) -> NDArray[np.float64]:
    """The junctions' coefficients, shape (4, sections − 1), from the sections' impedances
    Z [N s/m or N m s/rad]: (Z₂ − Z₁)/(Z₁ + Z₂), 2 Z₁/(Z₁ + Z₂), 2 Z₂/(Z₁ + Z₂),
    (Z₁ − Z₂)/(Z₁ + Z₂) (rows :data:`REFLECTED_DOWN` … :data:`REFLECTED_UP`)."""
    z = np.asarray(impedances, dtype=float)
    above, below = z[:-1], z[1:]
    total = above + below
    rows = [(below - above) / total, 2 * above / total, 2 * below / total, (above - below) / total]
    return np.ascontiguousarray(rows, dtype=float).reshape(4, max(z.size - 1, 0))


@njit(cache=True, error_model="numpy", _nrt=False)
def advance(p, m, offsets, junctions) -> None:  # pragma: no cover - compiled
    """One step of the line: p one node down and m one node up inside every section, then
    the waves leaving each junction. The top's p and the bottom's m are left to the ends."""
    sections = offsets.size - 1
    for s in range(sections):
        first, last = offsets[s], offsets[s + 1] - 1
        for j in range(last, first, -1):
            p[j] = p[j - 1]
        for j in range(first, last):
            m[j] = m[j + 1]
    for s in range(sections - 1):
        bottom, top = offsets[s + 1] - 1, offsets[s + 1]
        down, up = p[bottom], m[top]
        m[bottom] = junctions[REFLECTED_DOWN, s] * down + junctions[TRANSMITTED_UP, s] * up
        p[top] = junctions[TRANSMITTED_DOWN, s] * down + junctions[REFLECTED_UP, s] * up


@njit(cache=True, error_model="numpy", _nrt=False)
def set_top_velocity(p, m, impedance, velocity) -> None:  # pragma: no cover - compiled
    """The top moves at ``velocity``: p = m + 2 Z v₀ at node 0."""
    p[0] = m[0] + 2.0 * impedance * velocity


@njit(cache=True, error_model="numpy", _nrt=False)
def set_top_force(p, m, force) -> None:  # pragma: no cover - compiled
    """The top carries ``force``: p = 2 F₀ − m at node 0."""
    p[0] = 2.0 * force - m[0]


@njit(cache=True, error_model="numpy", _nrt=False)
def close_bottom(p, m, impedance, velocity) -> None:  # pragma: no cover - compiled
    """The bottom end moves with the body below at ``velocity``: m = p − 2 Z V there."""
    last = p.size - 1
    m[last] = p[last] - 2.0 * impedance * velocity


@njit(cache=True, error_model="numpy", _nrt=False)
def smooth_end_terms(
    velocity, mass, impedance, step
) -> tuple[float, float]:  # pragma: no cover - compiled
    """The body at the bottom end over one step, the pipe's dashpot by the trapezoidal rule.

    m (V₁ − V₀)/h = (p₀ + p₁)/2 − Z (V₀ + V₁)/2 − (bit forces) gives
    V₁ = V₀ (m − h Z/2)/(m + h Z/2) + h (p̄ − bit forces)/(m + h Z/2): returns the first
    term and 1/(m + h Z/2), the velocity and the inverse mass the bit's contact step sees
    (:func:`torsio.axial.bit_step.wear_flat_contact`, ``forward_rotation``).
    """
    inverse = 1.0 / (mass + 0.5 * step * impedance)
    return velocity * (mass - 0.5 * step * impedance) * inverse, inverse


@njit(cache=True, error_model="numpy", _nrt=False)
def pipe_contacts(
    axial_p, axial_m, torsional_p, torsional_m, contacts, step, threshold
) -> tuple[float, float]:  # pragma: no cover - compiled
    """The contacts along the pipe over one step ``step`` [s] on the arriving waves of both
    lines, in place (``contacts``: rows :data:`torsio.solvers.axial_layouts.WAVE_CONTACT_ROW`; the
    static branch while a contact's |s|/r at the step's start is below ``threshold``
    [rad/s]). Returns the friction's work [J] and the stick-slip switches of the step."""
    work = 0.0
    switches = 0.0
    for j in range(contacts.shape[1]):
        ia, it = int(contacts[slot.AXIAL_NODE, j]), int(contacts[slot.TORSIONAL_NODE, j])
        za, zt = contacts[slot.AXIAL_IMPEDANCE, j], contacts[slot.TORSIONAL_IMPEDANCE, j]
        radius = contacts[slot.CONTACT_RADIUS, j]
        last = math.hypot(
            contacts[slot.CONTACT_VELOCITY, j], radius * contacts[slot.CONTACT_SPEED, j]
        )
        sticky = last < radius * threshold
        static, sliding = contacts[slot.STATIC_FORCE, j], contacts[slot.SLIDING_FORCE, j]
        free_velocity = (axial_p[ia] - axial_m[ia]) / (2.0 * za)
        free_speed = (torsional_p[it] - torsional_m[it]) / (2.0 * zt)
        velocity, speed, stuck = cone_step(
            free_velocity, free_speed, radius, 1.0 / (2.0 * za * step), 1.0 / (2.0 * zt * step),
            static, sliding, step, sticky,
        )  # fmt: skip
        arriving = axial_p[ia]
        axial_p[ia] = axial_m[ia] + 2.0 * za * velocity
        axial_m[ia] = arriving - 2.0 * za * velocity
        arriving = torsional_p[it]
        torsional_p[it] = torsional_m[it] + 2.0 * zt * speed
        torsional_m[it] = arriving - 2.0 * zt * speed
        if stuck != (contacts[slot.CONTACT_STUCK, j] != 0.0):
            switches += 1.0
        contacts[slot.CONTACT_STUCK, j] = 1.0 if stuck else 0.0
        contacts[slot.CONTACT_VELOCITY, j], contacts[slot.CONTACT_SPEED, j] = velocity, speed
        work += step * (static if sticky else sliding) * math.hypot(velocity, radius * speed)
    return work, switches
