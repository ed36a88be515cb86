"""The Coulomb contact law along the string: its one definition, called by every engine.

A contact presses its node on the borehole with a static capacity C_s and a dynamic one
C_d <= C_s (torques [N m] torsionally, forces [N] on the cone) and a threshold speed w_th
(Aarsnes & Shor 2018; Karnopp's stick band): the node is

    stuck   (its absolute speed w = 0; the friction whatever holds it, |F| <= C_s),
    slow    (0 < |w| < w_th: F = C_s sign w, the static branch),
    fast    (|w| >= w_th: F = C_d sign w, the dynamic branch).

**Event form** (the compiled RODAS4 kernel :mod:`torsio.solvers.contact_kernel`, the numpy
batch :mod:`torsio.solvers.numpy_contacts`, the scipy reference
:mod:`torsio.solvers.contact_events`): each contact has a state code, 0 stuck, +-1 slow,
+-2 fast, the sign that of w (:func:`start_code`). Within a piece of the run it is fixed
(:func:`friction`); it switches where one of two margins (:func:`margin`) falls through
0 (within :func:`tolerance`): k = 0 a moving node's speed reaching 0 or a stuck node's
holding torque H reaching C_s, k = 1 a moving node's speed crossing w_th. The switch
(:func:`switched`): at rest a node sticks if |H| < C_s, else it moves the way of H (on the
static branch, or the dynamic one when w_th = 0); a stuck node breaks free the way of H;
slow and fast swap at w_th. :func:`frictions`, :func:`start_codes`, :func:`margins`,
:func:`tolerances` and :func:`switch_codes` apply these to arrays (points, nodes) (the
numpy and scipy engines).

**Step form** (the torsional wave march :mod:`torsio.solvers.wave_contacts`, the lumped
axial chain :mod:`torsio.solvers.axial_kernel`, the distributed axial pipe
:mod:`torsio.solvers.axial_wave_kernel`): over one step the law is solved at the velocity level
(Moreau) from the node's free motion. In one dimension, a free load d that the
capacity C cannot hold leaves :func:`excess` = max(|d| - C, 0) to move the node (stuck
when it is 0); the static branch is kept while its solution stays below w_th and taken
when the dynamic one has none (:func:`static_branch`). On the axial and tangential
sliding velocity s = (V, r w) the friction is one force on the cone of radius C
(:func:`cone_step`: stuck when the impulse that stops the node is within h C, else
sliding under h C along s), C_s while the node's |s|/r at the step's start is below w_th
and C_d above it; with no axial motion it is the one-dimensional law.

Examples
--------
>>> friction(-1.0, 4.0, 3.0), friction(2.0, 4.0, 3.0), start_code(-0.2, 0.5)
(-4.0, 3.0, -1.0)
>>> switched(1.0, 1, -5.0, 4.0, 0.5), switched(1.0, 1, 3.0, 4.0, 0.5)  # turns, sticks
(-1.0, 0.0)
>>> excess(-10.0, 4.0), excess(3.0, 4.0)
(6.0, 0.0)
>>> inertia = 500.0 * 0.0635**2  # I/r² = m = 500 kg: s = s*(1 − h F_d/(m |s*|))
>>> velocity, speed, stuck = cone_step(0.01, 2.0, 0.0635, 1 / 500.0, 1 / inertia,
...                                    4000.0, 3000.0, 1e-3, False)
>>> stuck, round(velocity, 9), round(speed, 9)
(False, 0.009529017, 1.90580337)
>>> cone_step(0.001, 0.01, 0.0635, 1 / 500.0, 1 / 2.0, 4000.0, 3000.0, 1e-3, True)
(0.0, 0.0, True)
"""

from __future__ import annotations

import math

from torsio.solvers.compiled import njit

__all__ = [
    "TOLERANCE",
    "cone_step",
    "excess",
    "friction",
    "frictions",
    "margin",
    "margins",
    "sliding_speed",
    "start_code",
    "start_codes",
    "static_branch",
    "switch_codes",
    "switched",
    "tolerance",
    "tolerances",
]

TOLERANCE = 1e-9
"""How near 0 a switch's margin counts as 0, relative to its scale: 1 + |Omega_ref| + w_th
[rad/s] for a speed, C_s [N m] for a holding torque."""


@njit(cache=True, error_model="numpy", _nrt=False)
def friction(code, static, dynamic):  # type: ignore[no-untyped-def,unused-ignore]
    """The friction of a contact in state ``code`` [N m]: 0 stuck, C_s sign w slow, C_d
    sign w fast (the node's force is reduced by it)."""
    if code == 0.0:
        return 0.0
    return math.copysign(static if abs(code) == 1.0 else dynamic, code)


@njit(cache=True, error_model="numpy", _nrt=False)
def start_code(speed, threshold):  # type: ignore[no-untyped-def,unused-ignore]
    """The state of a contact at absolute speed ``speed`` [rad/s]: stuck at rest (until a
    margin says it is pushed beyond C_s), else on the branch of its speed."""
    if speed == 0.0:
        return 0.0
    return math.copysign(2.0 if abs(speed) >= threshold else 1.0, speed)


@njit(cache=True, error_model="numpy", _nrt=False)
def switched(code, kind, holding, static, threshold):  # type: ignore[no-untyped-def,unused-ignore]
    """The state after the switch ``kind`` (1: margin 0 of :func:`margin`, 2: margin 1)
    of a contact in state ``code`` whose node's force without friction is ``holding``."""
    moving = math.copysign(1.0 if threshold > 0.0 else 2.0, holding)
    if code == 0.0:  # the holding torque reached C_s: it slips its way
        return moving
    if kind == 1:  # at rest: it sticks if C_s holds it, else it turns back
        return 0.0 if abs(holding) < static else moving
    return math.copysign(2.0 if abs(code) == 1.0 else 1.0, code)  # across w_th


@njit(cache=True, error_model="numpy", _nrt=False)
def margin(code, static, threshold, speed, holding, k):  # type: ignore[no-untyped-def,unused-ignore]
    """Margin ``k`` of a contact in state ``code`` at absolute speed ``speed`` with holding
    torque ``holding``, falling through 0 at its switch: k = 0 a moving node's speed in its
    direction, a stuck node's C_s - |H|; k = 1 a moving node's distance to w_th. 1.0 where
    it cannot switch."""
    if code == 0.0:
        return static - abs(holding) if k == 0 else 1.0
    moving = math.copysign(1.0, code) * speed
    if k == 0:
        return moving
    if abs(code) == 1.0:
        return threshold - moving
    return moving - threshold if threshold > 0.0 else 1.0


@njit(cache=True, error_model="numpy", _nrt=False)
def tolerance(code, static, threshold, reference, k):  # type: ignore[no-untyped-def,unused-ignore]
    """How near 0 margin ``k`` counts as 0: :data:`TOLERANCE` of C_s for a stuck node's
    holding torque, of 1 + |Omega_ref| + w_th for a speed (``reference`` Omega_ref)."""
    if k == 0 and code == 0.0:
        return TOLERANCE * static
    return TOLERANCE * (1.0 + abs(reference) + threshold)


@njit(cache=True, error_model="numpy", _nrt=False)
def frictions(code, static, dynamic, out):  # type: ignore[no-untyped-def,unused-ignore]
    """:func:`friction` of contacts (points, nodes) into ``out``: states ``code`` (points,
    nodes), capacities ``static``, ``dynamic`` (nodes)."""
    for p in range(code.shape[0]):
        for i in range(code.shape[1]):
            out[p, i] = friction(code[p, i], static[i], dynamic[i])


@njit(cache=True, error_model="numpy", _nrt=False)
def start_codes(speed, static, threshold, out):  # type: ignore[no-untyped-def,unused-ignore]
    """:func:`start_code` of contacts (points, nodes) at absolute speeds ``speed`` into
    ``out`` (0 where a node has no contact, C_s = 0)."""
    for p in range(speed.shape[0]):
        for i in range(speed.shape[1]):
            out[p, i] = start_code(speed[p, i], threshold[i]) if static[i] > 0.0 else 0.0


@njit(cache=True, error_model="numpy", _nrt=False)
def margins(code, static, threshold, speed, holding, out):  # type: ignore[no-untyped-def,unused-ignore]
    """:func:`margin` of contacts (points, nodes) into ``out`` (points, 2, nodes): states
    ``code``, absolute speeds ``speed``, holding torques ``holding`` (points, nodes),
    ``static`` C_s and ``threshold`` w_th (nodes); inf where a node has no contact."""
    for p in range(code.shape[0]):
        for i in range(code.shape[1]):
            for k in range(2):
                if static[i] > 0.0:
                    out[p, k, i] = margin(code[p, i], static[i], threshold[i], speed[p, i],
                                          holding[p, i], k)  # fmt: skip
                else:
                    out[p, k, i] = math.inf


@njit(cache=True, error_model="numpy", _nrt=False)
def tolerances(code, static, threshold, reference, out):  # type: ignore[no-untyped-def,unused-ignore]
    """:func:`tolerance` of contacts (points, nodes) into ``out`` (points, 2, nodes), the
    points' Omega_ref ``reference`` (points)."""
    for p in range(code.shape[0]):
        for i in range(code.shape[1]):
            for k in range(2):
                out[p, k, i] = tolerance(code[p, i], static[i], threshold[i], reference[p], k)


@njit(cache=True, error_model="numpy", _nrt=False)
def switch_codes(code, kinds, holding, static, threshold):  # type: ignore[no-untyped-def,unused-ignore]
    """Switch every contact (points, nodes) whose ``kinds`` is 1 or 2 (:func:`switched`),
    in place."""
    for p in range(code.shape[0]):
        for i in range(code.shape[1]):
            if kinds[p, i] != 0:
                code[p, i] = switched(code[p, i], kinds[p, i], holding[p, i], static[i],
                                      threshold[i])  # fmt: skip


@njit(cache=True, nogil=True, _nrt=False)
def excess(load, capacity):  # type: ignore[no-untyped-def,unused-ignore]
    """The part of a free ``load`` a contact of ``capacity`` cannot hold, max(|load| - C, 0)
    (same units): the node's speed times its resistance, in the direction of the load;
    0: stuck."""
    return max(abs(load) - capacity, 0.0)


@njit(cache=True, nogil=True, _nrt=False)
def static_branch(previous, below, slow, fast):  # type: ignore[no-untyped-def,unused-ignore]
    """Whether a one-dimensional contact takes its static branch this step: its speed
    ``slow`` on it, ``fast`` on the dynamic one [rad/s], ``previous`` last step's;
    ``below`` the largest speed under w_th. The static branch is kept while it has a
    solution (|v| <= below) and taken when the dynamic one has none."""
    return (slow <= below) if abs(previous) <= below else (fast <= below)


@njit(cache=True, error_model="numpy", _nrt=False)
def sliding_speed(axial, tangential, mass, tangential_mass, impulse):  # type: ignore[no-untyped-def,unused-ignore]
    """ρ = |s| [m/s], the root of φ(ρ) = (m V*/(m ρ + p))² + (J v*/(J ρ + p))² − 1 for the
    free velocities ``axial`` V* and ``tangential`` v* = r Ω* [m/s], ``mass`` m [kg],
    ``tangential_mass`` J = I/r² [kg] and the sliding impulse ``impulse`` p = h F [N s];
    the node slides (|M s*| > p). φ is decreasing and convex on ρ >= 0, so Newton's steps
    from the lower bound |s*| − p/min(m, J) rise monotonically to the root, to round-off
    (where m = J it is ρ = |s*| − p/m)."""
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
def cone_step(
    velocity, speed, radius, inverse_mass, inverse_inertia, static_force, sliding_force,
    step, sticky,
):  # type: ignore[no-untyped-def,unused-ignore]  # fmt: skip
    """(V [m/s], ω [rad/s], stuck) of a contact after the step ``step`` [s] from its free
    ``velocity`` V* and ``speed`` Ω*. With M = diag(m, I/r²) (the node's mass and its
    inertia seen at the radius ``radius`` r [m]; ``inverse_mass`` 1/m [1/kg],
    ``inverse_inertia`` 1/I [1/(kg m²)]) the impulse that stops it is P = M s*, s* =
    (V*, r Ω*): it sticks (s = 0) when |P| <= h F_c, F_c = ``static_force`` when
    ``sticky`` (slow at the step's start) else ``sliding_force`` [N]; otherwise it slides
    with s = s* − h F_c M⁻¹ s/|s|, each component s_k = s*_k M_k ρ/(M_k ρ + h F_c), ρ = |s|
    of :func:`sliding_speed`."""
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
