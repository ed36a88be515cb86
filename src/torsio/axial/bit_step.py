"""The RGD bit's part of one time step, shared by the lumped and the distributed kernels.

Each function is the bit's treatment in Moreau's time stepping (docs/axial.md, "The
scheme"), written once and called from the step loops of :mod:`torsio.solvers.axial_kernel`
(lumped chain) and :mod:`torsio.solvers.axial_wave_kernel` (distributed pipe):

- :func:`depth_of_cut`: d = n (U_b − U(t − t_n)) from the run's history
  (:mod:`torsio.axial.history`), the rock surface kept off bottom;
- :func:`cutting_forces`: W_c = ζ ε a d and T_c = ε a² d/2 on bottom, zero off it;
- :func:`wear_flat_contact`: the bit's new axial velocity and the wear-flat weight
  W_f ∈ [0, σ a l] consistent with it (drilling down, at rest, moving up);
- :func:`forward_rotation`: the bit's new speed, never backwards, and the bit torque (the
  reaction while stuck);
- :func:`law_rotation`: the same for a law of the torque alone
  (:mod:`torsio.physics.torque_law_bit`), its torque taken linearly implicit;
- :func:`add_to_window`: the window's statistics (:data:`torsio.solvers.axial_layouts.STATS`);
- :func:`sample_motion`, :func:`record_step`: a row of the bit's signals
  (:data:`torsio.solvers.axial_layouts.SAMPLE_COLUMNS`), its motion at the step's start, then what
  acted over the step with the step's part of the window's statistics.

A step's smooth forces enter through ``force`` (or ``torque``) and the inverse mass (or
inertia) the step sees: the lumped kernel passes the spring forces and 1/m, the
distributed one the force of the arriving wave and 1/(m + h Z/2) (docs/axial.md, "The
distributed pipe").

``bit``, the law's row: [ζ ε a (N/m), ε a²/2 (N m/m), σ a l (N), μ γ a/2 (m), 2π/n (rad),
n] (:data:`torsio.solvers.axial_layouts.BIT_ROW`).

Examples
--------
>>> velocity, wear_flat = wear_flat_contact(0.01, 1.0e5, 2.0e4, 1.0 / 3.0e4, 1e-3, 7.0e4,
...                                         True)
>>> round(velocity, 12), wear_flat  # drilling down: the wear flats carry σ a l
(0.010333333333, 70000.0)
>>> speed, torque = forward_rotation(0.001, 10.0, 500.0, 100.0, 1.0 / 500.0, 1e-3)
>>> speed, round(torque, 9)  # stuck: the reaction 10 + I Ω/h, below T_c + T_f = 600
(0.0, 510.0)
"""

from __future__ import annotations

import math

import numpy as np

from torsio.axial.history import delayed_state, keep_surface
from torsio.solvers.axial_layouts import (
    ANGLE_PER_BLADE,
    BIT_ANGLE,
    BIT_POSITION,
    BIT_SPEED,
    BIT_TORQUE,
    BIT_VELOCITY,
    BIT_WEIGHT,
    BLADES,
    COUNT,
    CUTTING_TORQUE_PER_DEPTH,
    CUTTING_WEIGHT_PER_DEPTH,
    DELAY,
    DEPTH_MAX,
    DEPTH_OF_CUT,
    OFF_BOTTOM,
    SPEED_MAX,
    SPEED_MIN,
    STUCK,
    TIME,
    TOP_TORQUE,
    TORQUE_INTEGRAL,
    VELOCITY_MAX,
    VELOCITY_MIN,
    WEIGHT_INTEGRAL,
    WORK,
)
from torsio.solvers.compiled import njit

__all__ = [
    "add_to_window",
    "cutting_forces",
    "depth_of_cut",
    "forward_rotation",
    "law_rotation",
    "record_step",
    "sample_motion",
    "start_window",
    "wear_flat_contact",
]


@njit(cache=True, error_model="numpy", _nrt=False)
def depth_of_cut(
    bit, history, cursor, angle, position, step, delayed
) -> float:  # pragma: no cover - compiled
    """d = n (U_b − U(t − t_n)) [m per rev] for the bit at ``angle`` [rad] and ``position``
    [m]; ``delayed`` receives [t − t_n, U(t − t_n)]. The newest history entry gets the rock
    surface the blade leaves, max(U_b, U(t − t_n)) (``step`` [s] for its slope). NaN when
    the history does not hold the delay (the history is then left as it was)."""
    if not delayed_state(history, cursor, angle - bit[ANGLE_PER_BLADE], delayed):
        return math.nan
    depth = bit[BLADES] * (position - delayed[1])
    keep_surface(history, cursor, max(position, delayed[1]), step)
    return depth


@njit(cache=True, error_model="numpy", _nrt=False)
def cutting_forces(bit, depth) -> tuple[float, float]:  # pragma: no cover - compiled
    """(W_c [N], T_c [N m]) of the depth of cut ``depth``: zero off bottom (d ≤ 0)."""
    if depth > 0.0:
        return bit[CUTTING_WEIGHT_PER_DEPTH] * depth, bit[CUTTING_TORQUE_PER_DEPTH] * depth
    return 0.0, 0.0


@njit(cache=True, error_model="numpy", _nrt=False)
def wear_flat_contact(
    velocity, force, cutting_weight, inverse_mass, step, friction_weight, on_bottom
) -> tuple[float, float]:  # pragma: no cover - compiled
    """(V_b [m/s], W_f [N]) after one step of ``step`` [s] from ``velocity`` under the smooth
    ``force`` [N] (down), less W_c and the wear-flat weight W_f ∈ [0, σ a l] (on bottom):
    W_f = σ a l when the bit still moves down with it, 0 when it moves up without it, else
    the bit stops (V_b = 0) and W_f is what stops it. ``inverse_mass`` [1/kg]."""
    free = velocity + step * (force - cutting_weight) * inverse_mass
    wear_flat = 0.0
    if on_bottom:
        if free - step * friction_weight * inverse_mass > 0.0:
            wear_flat = friction_weight
            free -= step * friction_weight * inverse_mass
        elif free >= 0.0:
            wear_flat = free / (step * inverse_mass)
            free = 0.0
    return free, wear_flat


@njit(cache=True, error_model="numpy", _nrt=False)
def forward_rotation(
    speed, torque, cutting_torque, friction_torque, inverse_inertia, step
) -> tuple[float, float]:  # pragma: no cover - compiled
    """(Ω_b [rad/s], bit torque [N m]) after one step of ``step`` [s] from ``speed`` under
    the smooth ``torque`` [N m] less T_c + T_f. The bit does not turn backwards: when the
    free speed is not positive it sticks, and the bit torque is the reaction that holds it,
    ``torque`` + Ω_b/(h/I). ``inverse_inertia`` [1/(kg m²)]."""
    free = speed + step * (torque - cutting_torque - friction_torque) * inverse_inertia
    if free <= 0.0:
        return 0.0, torque + speed / (step * inverse_inertia)
    return free, cutting_torque + friction_torque


@njit(cache=True, error_model="numpy", _nrt=False)
def law_rotation(
    speed, torque, law_torque, law_slope, inverse_inertia, step
) -> tuple[float, float]:  # pragma: no cover - compiled
    """(Ω_b [rad/s], bit torque [N m]) after one step of ``step`` [s] from ``speed`` under
    the smooth ``torque`` [N m] less a law's torque T(Ω_b) = ``law_torque`` [N m] of slope
    ``law_slope`` [N m s/rad], linearly implicit in its rising part s = max(slope, 0):
    Ω_b ← Ω_b + h (torque − T)/(I + h s); the bit torque T + s ΔΩ_b. A stiff smooth sign
    (s h/I large) is then damped, not amplified; a falling slope stays explicit.
    ``inverse_inertia`` [1/(kg m²)].

    >>> law_rotation(1.0, 10.0, 10.0, 5.0, 0.5, 0.1)  # the string's torque holds the law's
    (1.0, 10.0)
    """
    rising = max(law_slope, 0.0)
    change = (
        step * (torque - law_torque) * inverse_inertia / (1.0 + step * rising * inverse_inertia)
    )
    return speed + change, law_torque + rising * change


@njit(cache=True, error_model="numpy", _nrt=False)
def add_to_window(
    stats, speed, velocity, depth, on_bottom, step, weight, torque, stick_speed
) -> None:  # pragma: no cover - compiled
    """Add one step of the window to ``stats``: extremes of Ω_b and V_b, stuck (|Ω_b| below
    ``stick_speed`` [rad/s]) and off-bottom (not ``on_bottom``) steps, the work
    (W V_b + T Ω_b) h [J], the integrals of T and W, the largest d."""
    stats[SPEED_MAX] = max(stats[SPEED_MAX], speed)
    stats[SPEED_MIN] = min(stats[SPEED_MIN], speed)
    stats[VELOCITY_MAX] = max(stats[VELOCITY_MAX], velocity)
    stats[VELOCITY_MIN] = min(stats[VELOCITY_MIN], velocity)
    if abs(speed) < stick_speed:
        stats[STUCK] += 1.0
    if not on_bottom:
        stats[OFF_BOTTOM] += 1.0
    stats[COUNT] += 1.0
    stats[DEPTH_MAX] = max(stats[DEPTH_MAX], depth)
    stats[WORK] += step * (weight * velocity + torque * speed)
    stats[TORQUE_INTEGRAL] += step * torque
    stats[WEIGHT_INTEGRAL] += step * weight


@njit(cache=True, error_model="numpy", _nrt=False)
def start_window(stats) -> None:  # pragma: no cover - compiled
    """Empty statistics: extremes at ∓inf, every sum 0."""
    for q in range(stats.size):
        stats[q] = 0.0
    stats[SPEED_MAX], stats[SPEED_MIN] = -np.inf, np.inf
    stats[VELOCITY_MAX], stats[VELOCITY_MIN] = -np.inf, np.inf


@njit(cache=True, error_model="numpy", _nrt=False)
def sample_motion(
    samples, row, time, angle, speed, position, velocity
) -> None:  # pragma: no cover - compiled
    """Row ``row`` of ``samples`` gets the bit's motion at the step's start: t [s], Φ_b
    [rad], Ω_b [rad/s], U_b [m] and V_b [m/s]."""
    samples[row, TIME] = time
    samples[row, BIT_ANGLE] = angle
    samples[row, BIT_SPEED] = speed
    samples[row, BIT_POSITION] = position
    samples[row, BIT_VELOCITY] = velocity


@njit(cache=True, error_model="numpy", _nrt=False)
def record_step(
    stats,
    samples,
    row,
    in_window,
    sampled,
    speed,
    velocity,
    depth,
    on_bottom,
    step,
    weight,
    torque,
    delay,
    top_torque,
    stick_speed,
) -> int:  # pragma: no cover - compiled
    """What one step of ``step`` [s] leaves: its part of the window's statistics
    (:func:`add_to_window`, when ``in_window``; ``on_bottom`` whether the bit touched the
    rock; the bit stuck below ``stick_speed`` [rad/s]) and, when ``sampled``, the rest of row
    ``row`` of ``samples``: d [m per rev], the bit's weight [N] and torque [N m], the delay
    t − t_n [s], the top torque [N m]. Returns the next row to sample."""
    if in_window:
        add_to_window(stats, speed, velocity, depth, on_bottom, step, weight, torque, stick_speed)
    if not sampled:
        return row
    samples[row, DEPTH_OF_CUT] = depth
    samples[row, BIT_WEIGHT] = weight
    samples[row, BIT_TORQUE] = torque
    samples[row, DELAY] = delay
    samples[row, TOP_TORQUE] = top_torque
    return row + 1
