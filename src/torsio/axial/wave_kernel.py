"""The compiled step loop of an axial-torsional run of the distributed pipe with the RGD bit.

Fixed step h, the step of the characteristic grid (:mod:`torsio.axial.wave_setup`). Per
step, from the state at t to t + h:

1. The depth of cut from the run's own history, as in the lumped loop
   (:func:`torsio.axial.bit_step.depth_of_cut`); the cutting forces W_c, T_c.
2. Axial line (:mod:`torsio.axial.wave_pipe`): the waves move one node, the junctions
   split them, the top takes the hook's force W₀ or its speed V₀. The BHA meets the
   arriving wave p at the pipe's bottom: m_b V' = p − Z_a V − W. Over the step p and the
   dashpot Z_a V by the trapezoidal rule, the bit's wear flats as in the lumped loop
   (:func:`torsio.axial.bit_step.wear_flat_contact` with the velocity and the inverse
   mass of :func:`torsio.axial.wave_pipe.smooth_end_terms`); the wave sent back up is
   m = p − 2 Z_a V.
3. Torsional line likewise: the top drive turning at Ω₀, the BHA's I_b Ω' = p − Z_t Ω − T
   with the bit's no-backward rotation (:func:`torsio.axial.bit_step.forward_rotation`).
4. The bit's position and angle by the trapezoidal rule; the new bit state to the history.

``settings`` holds the entries named by :data:`SETTINGS`, at those indices. ``bha`` is
[U_b (m, down), V_b (m/s), Φ_b (rad), Ω_b (rad/s)] (:data:`BHA_STATE`). Each line is its
``offsets`` (int, sections + 1), ``junctions`` (:func:`torsio.axial.wave_pipe.junction_rows`)
and state ``p``, ``m``. ``bit``, ``history``, ``cursor``, ``stats`` and ``samples`` are those
of the lumped loop (:mod:`torsio.axial.kernel`: :data:`~torsio.axial.kernel.STATS`,
:data:`~torsio.axial.kernel.SAMPLE_COLUMNS`; the top torque is the pipe's at the top drive).

Examples
--------
>>> SETTINGS[HOOK_WEIGHT], BHA_STATE[SPEED]  # the entries' names at their indices
('hook_weight', 'speed')
"""

from __future__ import annotations

import math

import numpy as np

from torsio.axial.bit_step import (
    FRICTION_TORQUE_PER_WEIGHT,
    FRICTION_WEIGHT,
    add_to_window,
    cutting_forces,
    depth_of_cut,
    forward_rotation,
    start_window,
    wear_flat_contact,
)
from torsio.axial.history import append
from torsio.axial.wave_pipe import (
    advance,
    close_bottom,
    set_top_force,
    set_top_velocity,
    smooth_end_terms,
)
from torsio.solvers.compiled import njit

__all__ = ["BHA_STATE", "SETTINGS", "march"]

SETTINGS = (
    "step",
    "steps",
    "top_speed",
    "hook_weight",
    "speed_hook",
    "hook_speed",
    "window_start",
    "sample_every",
    "start_time",
    "bha_mass",
    "bha_inertia",
    "axial_top_impedance",
    "axial_bottom_impedance",
    "torsional_top_impedance",
    "torsional_bottom_impedance",
)
"""The entries of ``settings``: h [s], steps, Ω₀ [rad/s], W₀ [N], the hook (0 weight, 1
speed), V_h [m/s], the window's first step, sample every (0: never), t at step 0 [s], m_b
[kg], I_b [kg m²], Z of the top and bottom sections axially [N s/m] and torsionally
[N m s/rad]."""

(
    STEP,
    STEPS,
    TOP_SPEED,
    HOOK_WEIGHT,
    SPEED_HOOK,
    HOOK_SPEED,
    WINDOW_START,
    SAMPLE_EVERY,
    START_TIME,
    BHA_MASS,
    BHA_INERTIA,
    AXIAL_TOP_IMPEDANCE,
    AXIAL_BOTTOM_IMPEDANCE,
    TORSIONAL_TOP_IMPEDANCE,
    TORSIONAL_BOTTOM_IMPEDANCE,
) = range(len(SETTINGS))

BHA_STATE = ("position", "velocity", "angle", "speed")
"""The entries of ``bha``: U_b [m, down], V_b [m/s], Φ_b [rad], Ω_b [rad/s]."""
POSITION, VELOCITY, ANGLE, SPEED = range(len(BHA_STATE))

# the entries of ``stats`` this loop sets itself (the others: torsio.axial.bit_step)
POSITION_START, POSITION_END, FAILED, STEPS_DONE = 7, 8, 12, 13


@njit(cache=True, nogil=True, error_model="numpy")
def march(
    bit,
    settings,
    axial_offsets,
    axial_junctions,
    axial_p,
    axial_m,
    torsional_offsets,
    torsional_junctions,
    torsional_p,
    torsional_m,
    bha,
    history,
    cursor,
    stats,
    samples,
) -> None:  # pragma: no cover - compiled
    """Advance the run ``settings[STEPS]`` steps from the state (lines and ``bha``) in place."""
    h, steps = settings[STEP], int(settings[STEPS])
    top_speed, weight, hook_speed = settings[TOP_SPEED], settings[HOOK_WEIGHT], settings[HOOK_SPEED]
    speed_hook = settings[SPEED_HOOK] != 0.0
    window_start, sample_every = int(settings[WINDOW_START]), int(settings[SAMPLE_EVERY])
    t_start, mass, inertia = settings[START_TIME], settings[BHA_MASS], settings[BHA_INERTIA]
    za_top, za_bottom = settings[AXIAL_TOP_IMPEDANCE], settings[AXIAL_BOTTOM_IMPEDANCE]
    zt_top, zt_bottom = settings[TORSIONAL_TOP_IMPEDANCE], settings[TORSIONAL_BOTTOM_IMPEDANCE]
    wf_max, tf_per_wf = bit[FRICTION_WEIGHT], bit[FRICTION_TORQUE_PER_WEIGHT]
    axial_end, torsional_end = axial_p.size - 1, torsional_p.size - 1
    delayed = np.zeros(2)
    start_window(stats)
    row = 0
    for step in range(steps):
        t = t_start + step * h
        u, v, phi, omega = bha[POSITION], bha[VELOCITY], bha[ANGLE], bha[SPEED]
        sampled = sample_every > 0 and step % sample_every == 0 and row < samples.shape[0]
        if sampled:
            samples[row, 0] = t
            samples[row, 1] = phi
            samples[row, 2] = omega
            samples[row, 3] = u
            samples[row, 4] = v
        if step == window_start:
            stats[POSITION_START] = u
        top_torque = 0.5 * (torsional_p[0] + torsional_m[0])
        # 1. depth of cut
        depth = depth_of_cut(bit, history, cursor, phi, u, h, delayed)
        if math.isnan(depth):
            stats[FAILED] = 1.0
            stats[STEPS_DONE] = step
            return
        wc, tc = cutting_forces(bit, depth)
        # 2. axial line and the BHA's axial motion
        arrived = axial_p[axial_end]
        advance(axial_p, axial_m, axial_offsets, axial_junctions)
        if speed_hook:
            set_top_velocity(axial_p, axial_m, za_top, hook_speed)
        else:
            set_top_force(axial_p, axial_m, weight)
        force = 0.5 * (arrived + axial_p[axial_end])
        free, inverse_mass = smooth_end_terms(v, mass, za_bottom, h)
        v_new, wf = wear_flat_contact(free, force, wc, inverse_mass, h, wf_max, depth > 0.0)
        close_bottom(axial_p, axial_m, za_bottom, v_new)
        # 3. torsional line and the BHA's rotation
        arrived = torsional_p[torsional_end]
        advance(torsional_p, torsional_m, torsional_offsets, torsional_junctions)
        set_top_velocity(torsional_p, torsional_m, zt_top, top_speed)
        torque = 0.5 * (arrived + torsional_p[torsional_end])
        free, inverse_inertia = smooth_end_terms(omega, inertia, zt_bottom, h)
        tf = tf_per_wf * wf
        omega_new, bit_torque = forward_rotation(free, torque, tc, tf, inverse_inertia, h)
        close_bottom(torsional_p, torsional_m, zt_bottom, omega_new)
        # 4. the bit's position and angle, the history
        bha[POSITION] = u + 0.5 * h * (v + v_new)
        bha[VELOCITY] = v_new
        bha[ANGLE] = phi + 0.5 * h * (omega + omega_new)
        bha[SPEED] = omega_new
        append(history, cursor, t + h, bha[ANGLE], omega_new, bha[POSITION], v_new)
        bit_weight = wc + wf
        if step >= window_start:
            add_to_window(stats, omega_new, v_new, depth, h, bit_weight, bit_torque)
        if sampled:
            samples[row, 5] = depth
            samples[row, 6] = bit_weight
            samples[row, 7] = bit_torque
            samples[row, 8] = t - delayed[0]
            samples[row, 9] = top_torque
            row += 1
    stats[POSITION_END] = bha[POSITION]
    stats[STEPS_DONE] = steps
