"""The compiled step loop of an axial-torsional run of the distributed pipe with the RGD bit.

Fixed step h, the step of the characteristic grid (:mod:`torsio.solvers.axial_wave_setup`). Per
step, from the state at t to t + h:

1. The depth of cut from the run's own history, as in the lumped loop
   (:func:`torsio.axial.bit_step.depth_of_cut`); the cutting forces W_c, T_c.
2. Axial line (:mod:`torsio.solvers.axial_wave_lines`): the waves move one node, the junctions
   split them, the top takes the hook's force W₀ or its speed V₀. The BHA meets the
   arriving wave p at the pipe's bottom: m_b V' = p − Z_a V − W. Over the step p and the
   dashpot Z_a V by the trapezoidal rule, the bit's wear flats as in the lumped loop
   (:func:`torsio.axial.bit_step.wear_flat_contact` with the velocity and the inverse
   mass of :func:`torsio.solvers.axial_wave_lines.smooth_end_terms`); the wave sent back up is
   m = p − 2 Z_a V.
3. Torsional line likewise: the top held at the set speed of ``speed_table`` (the one
   set-speed table of every engine, :mod:`torsio.solvers.set_speed`: Ω₀, or a recorded
   speed) at the step's end, the BHA's I_b Ω' = p − Z_t Ω − T
   with the bit's no-backward rotation (:func:`torsio.axial.bit_step.forward_rotation`).
   3b. The contacts along the pipe (``contacts``, rows
   :data:`torsio.solvers.axial_layouts.WAVE_CONTACT_ROW`; none: zero columns) on the arriving waves
   of both lines (:func:`torsio.solvers.axial_wave_lines.pipe_contacts`), their work and switches
   added to ``stats``.
4. The bit's position and angle by the trapezoidal rule; the new bit state to the history.

``settings`` holds the entries named by :data:`torsio.solvers.axial_layouts.WAVE_SETTINGS`, at those
indices. ``bha`` is [U_b (m, down), V_b (m/s), Φ_b (rad), Ω_b (rad/s)]
(:data:`torsio.solvers.axial_layouts.BHA_STATE`). Each line is its ``offsets`` (int, sections + 1),
``junctions`` (:func:`torsio.solvers.axial_wave_lines.junction_rows`) and state ``p``, ``m``.
``bit``,
``history``, ``cursor``, ``stats`` and ``samples`` are those of the lumped loop
(:mod:`torsio.solvers.axial_kernel`; :data:`torsio.solvers.axial_layouts.STATS`,
:data:`torsio.solvers.axial_layouts.SAMPLE_COLUMNS`; the top torque is the pipe's at the top drive).
"""

from __future__ import annotations

import math

import numpy as np

from torsio.axial import bit_step
from torsio.axial.history import append
from torsio.solvers import axial_layouts as slot
from torsio.solvers.axial_wave_lines import (
    advance,
    close_bottom,
    pipe_contacts,
    set_top_force,
    set_top_velocity,
    smooth_end_terms,
)
from torsio.solvers.compiled import njit
from torsio.solvers.set_speed import table_speed

__all__ = ["march"]


@njit(cache=True, nogil=True, error_model="numpy")
def march(
    bit,
    settings,
    speed_table,
    axial_offsets,
    axial_junctions,
    axial_p,
    axial_m,
    torsional_offsets,
    torsional_junctions,
    torsional_p,
    torsional_m,
    bha,
    contacts,
    history,
    cursor,
    stats,
    samples,
) -> None:  # pragma: no cover - compiled
    """Advance the run from step ``settings[slot.FIRST_STEP]`` to ``settings[slot.STEPS]``
    from the state (the lines, ``bha``), ``stats`` carried over from the steps before."""
    h, steps = settings[slot.STEP], int(settings[slot.STEPS])
    first = int(settings[slot.FIRST_STEP])
    weight = settings[slot.HOOK_WEIGHT]
    speed_hook, hook_speed = settings[slot.SPEED_HOOK] != 0.0, settings[slot.HOOK_SPEED]
    window_start, sample_every = int(settings[slot.WINDOW_START]), int(settings[slot.SAMPLE_EVERY])
    t_start, mass, inertia = (
        settings[slot.START_TIME],
        settings[slot.BHA_MASS],
        settings[slot.BHA_INERTIA],
    )
    za_top, za_bottom = settings[slot.AXIAL_TOP_IMPEDANCE], settings[slot.AXIAL_BOTTOM_IMPEDANCE]
    zt_top, zt_bottom = (
        settings[slot.TORSIONAL_TOP_IMPEDANCE],
        settings[slot.TORSIONAL_BOTTOM_IMPEDANCE],
    )
    wf_max, tf_per_wf = bit[slot.FRICTION_WEIGHT], bit[slot.FRICTION_TORQUE_PER_WEIGHT]
    axial_end, torsional_end = axial_p.size - 1, torsional_p.size - 1
    threshold = settings[slot.PIPE_THRESHOLD_SPEED]
    delayed = np.zeros(2)
    if first == 0:
        bit_step.start_window(stats)
    row = (first + sample_every - 1) // sample_every if sample_every > 0 else 0
    for step in range(first, steps):
        t = t_start + step * h
        u, v, phi, omega = (
            bha[slot.BHA_POSITION],
            bha[slot.BHA_VELOCITY],
            bha[slot.BHA_ANGLE],
            bha[slot.BHA_SPEED],
        )
        sampled = sample_every > 0 and step % sample_every == 0 and row < samples.shape[0]
        if sampled:
            bit_step.sample_motion(samples, row, t, phi, omega, u, v)
        if step == window_start:
            stats[slot.POSITION_START] = u
        top_torque = 0.5 * (torsional_p[0] + torsional_m[0])
        # 1. depth of cut
        depth = bit_step.depth_of_cut(bit, history, cursor, phi, u, h, delayed)
        if math.isnan(depth):
            stats[slot.FAILED] = 1.0
            stats[slot.STEPS_DONE] = step
            return
        wc, tc = bit_step.cutting_forces(bit, depth)
        # 2. axial line and the BHA's axial motion
        arrived = axial_p[axial_end]
        advance(axial_p, axial_m, axial_offsets, axial_junctions)
        if speed_hook:
            set_top_velocity(axial_p, axial_m, za_top, hook_speed)
        else:
            set_top_force(axial_p, axial_m, weight)
        force = 0.5 * (arrived + axial_p[axial_end])
        free, inverse_mass = smooth_end_terms(v, mass, za_bottom, h)
        v_new, wf = bit_step.wear_flat_contact(
            free, force, wc, inverse_mass, h, wf_max, depth > 0.0
        )
        close_bottom(axial_p, axial_m, za_bottom, v_new)
        # 3. torsional line and the BHA's rotation
        arrived = torsional_p[torsional_end]
        advance(torsional_p, torsional_m, torsional_offsets, torsional_junctions)
        set_top_velocity(torsional_p, torsional_m, zt_top, table_speed(speed_table, t + h))
        torque = 0.5 * (arrived + torsional_p[torsional_end])
        free, inverse_inertia = smooth_end_terms(omega, inertia, zt_bottom, h)
        tf = tf_per_wf * wf
        omega_new, bit_torque = bit_step.forward_rotation(free, torque, tc, tf, inverse_inertia, h)
        close_bottom(torsional_p, torsional_m, zt_bottom, omega_new)
        if contacts.shape[1] > 0:  # 3b. the contacts along the pipe
            work, switches = pipe_contacts(
                axial_p, axial_m, torsional_p, torsional_m, contacts, h, threshold
            )
            stats[slot.FRICTION_WORK] += work
            stats[slot.CONTACT_SWITCHES] += switches
        # 4. the bit's position and angle, the history
        bha[slot.BHA_POSITION] = u + 0.5 * h * (v + v_new)
        bha[slot.BHA_VELOCITY] = v_new
        bha[slot.BHA_ANGLE] = phi + 0.5 * h * (omega + omega_new)
        bha[slot.BHA_SPEED] = omega_new
        append(
            history, cursor, t + h, bha[slot.BHA_ANGLE], omega_new, bha[slot.BHA_POSITION], v_new
        )
        row = bit_step.record_step(
            stats, samples, row, step >= window_start, sampled, omega_new, v_new, depth,
            depth > 0.0, h, wc + wf, bit_torque, t - delayed[0], top_torque,
            settings[slot.STICK_SPEED],
        )  # fmt: skip
    stats[slot.POSITION_END] = bha[slot.BHA_POSITION]
    stats[slot.STEPS_DONE] = steps
