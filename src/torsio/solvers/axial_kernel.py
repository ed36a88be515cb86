"""The compiled step loop of an axial-torsional run with the RGD bit.

Fixed step h, semi-implicit (symplectic) Euler with the bit's set-valued contacts solved
at the velocity level over each step (Moreau's time stepping):

1. The depth of cut from the run's own history (:mod:`torsio.axial.history`):
   d = n (U_b − U(t − t_n)) with Φ(t − t_n) = Φ_b − 2π/n, U(t − t_n) the rock surface the
   last blade left there (the bit's position while it cut). Off bottom (d ≤ 0) every bit
   force is zero and the surface is kept.
2. Axial: V_i ← V_i + h F_i / m_i with the spring and damper forces of the current
   positions and velocities. At the bit, the free velocity V* = V_b + h (F_b − W_c)/m_b and
   the wear-flat weight W_f ∈ [0, σ a l] that makes the new velocity V_b consistent with
   it: W_f = σ a l if V* − h σ a l / m_b > 0 (drilling down), W_f = 0 if V* < 0 (moving
   up), else V_b = 0 and W_f = m_b V*/h (axially at rest, the contact set-valued).
3. Torsional: ω_i ← ω_i + h T_i / I_i; at the bit Ω* = Ω_b + h (T_b − T_c − T_f)/I_b with
   T_f = μ γ a W_f / 2, and Ω_b = max(Ω*, 0): the bit does not turn backwards and sticks
   while the string's torque is at most T_c + T_f (the bit torque is then the reaction
   T_b + I_b Ω_b/h). With a prescribed rotation Φ_b, Ω_b are set instead.
   3b. A node with a contact along the string (``contacts``, rows
   :data:`torsio.solvers.axial_layouts.CONTACT_ROW`, F_s > 0) takes its Coulomb friction on its free
   (V_i, ω_i) (:func:`torsio.solvers.contact_law.cone_step`; static branch while
   |s|/r at the step's start is below ``settings[THRESHOLD_SPEED]``), at the bit after the
   bit's contacts; ``contact_stuck`` keeps each contact's state to count its switches. With
   contacts the axial dampers read the node below at the step's start.
4. Positions from the new velocities: U ← U + h V, θ ← θ + h ω; the held top's angle the
   integral of its set speed (Ω₀ t at a constant one), the hook position U_h0 + V_h t.
   The new bit state is appended to the history. The works of the energy balance
   (:mod:`torsio.analysis.axial_energy`) are summed on the new velocities.

With a top drive that is not held (``top[TOP_HELD]`` 0), the top is a node (J, drag) with
a linear controller (:class:`torsio.physics.top_drive_boundary.TopDriveBoundary`), advanced
in step 3 after the chain with the surface torque T_pipe = k_0 (θ_top − θ_0) + c_0 (Ω_top −
ω_0) of the state at the step's start: y = [Ω_set − Ω_top, T_pipe], u_free = u0 + c·z +
d·y, u = clip(u_free, ±max_torque), z ← z + h (a z + b y + w (u − u_free)) (the one
evaluation of every engine, :func:`torsio.physics.top_drive_boundary.motor_torque` and
:func:`~torsio.physics.top_drive_boundary.controller_rates`),
Ω_top ← Ω_top + h (u − drag Ω_top − T_pipe)/J, θ_top ← θ_top + h Ω_top (the new speed).
``top`` holds the entries of :data:`torsio.solvers.axial_layouts.TOP_DRIVE`; ``top_state``
those of :data:`~torsio.solvers.axial_layouts.TOP_NODE`, ``controller_state`` z;
``ctrl_a`` (m, m) and ``ctrl_b`` (m, 2) row by row, ``ctrl_c`` (m,), ``ctrl_d`` (2,),
``ctrl_w`` (m,) the controller's matrices.
``speed_table`` is the set speed against time, the one table of every engine
(:func:`torsio.solvers.set_speed.twist_table` for Ω_ref = 0: rows time [s], Ω_set [rad/s]
and its integral [rad]): what a held top turns at (a recorded speed, or Ω₀) and what a
controller tracks (a ramp).

The bit's part of steps 1-3 is :mod:`torsio.axial.bit_step`, shared with the distributed
pipe's loop (:mod:`torsio.solvers.axial_wave_kernel`).

A law of the torque alone (``bit[LAW_TORQUE]`` 1, :mod:`torsio.physics.torque_law_bit`) takes no
depth of cut: the rock is rigid at ``settings[ROCK_SURFACE]`` (the bit on bottom at U_b
at or below it, down positive), step 2 gives the rock's reaction W (σ a l = inf: any
weight), and in step 3 the bit turns under ``law_torque(law_parameters, Ω_b, W, a)`` with
its slope ``law_slope`` (:func:`torsio.axial.bit_step.law_rotation`), numba functions of
:data:`torsio.solvers.law_kernels.LAW_SIGNATURE` passed as first-class functions: the loop
is compiled once (:func:`march_signature`) for every law.

``settings`` holds the entries named by :data:`torsio.solvers.axial_layouts.CHAIN_SETTINGS`, at
those indices. The bit law
``bit``: [ζ ε a, ε a²/2, σ a l, μ γ a / 2, 2π/n, n] (:data:`torsio.solvers.axial_layouts.BIT_ROW`).
``torsional``: rows 1/I, k, c (spring and damper i join node i − 1, the top for i = 0, to
node i). ``axial``: rows 1/m, k, c likewise (node 0's spring joins the hook; with the
weight hook it carries W₀ and is not used). ``stats`` on return and ``samples``: see
:data:`torsio.solvers.axial_layouts.STATS` and :data:`torsio.solvers.axial_layouts.SAMPLE_COLUMNS`.
"""

from __future__ import annotations

import math

import numpy as np

from torsio.axial import bit_step
from torsio.axial.history import append
from torsio.solvers import axial_layouts as slot
from torsio.solvers.chain_kernel import compiled_controller_rates, compiled_motor_torque
from torsio.solvers.compiled import HAVE_NUMBA, njit
from torsio.solvers.contact_law import cone_step
from torsio.solvers.layouts import TABLE_SPEED
from torsio.solvers.set_speed import table_speed, table_twist

__all__ = ["march", "march_signature"]


def march_signature() -> object:
    """The explicit signature of :func:`march` (None without numba): every array float64
    and contiguous (the matrices C-ordered), the two law functions of
    :func:`torsio.solvers.law_kernels.law_type` before the law's parameters."""
    if not HAVE_NUMBA:
        return None
    from numba import types

    from torsio.solvers.law_kernels import law_type

    vector, matrix, law = types.float64[::1], types.float64[:, ::1], law_type()
    return types.void(
        vector, matrix, matrix, vector, vector, vector, vector, vector, matrix, vector, vector,
        matrix, vector, vector, vector, vector, vector, vector, vector, vector, matrix, matrix,
        vector, law, law, vector,
    )  # fmt: skip


@njit(march_signature(), cache=True, nogil=True, error_model="numpy")
def march(
    bit,
    torsional,
    axial,
    settings,
    theta,
    omega,
    u,
    v,
    history,
    cursor,
    stats,
    samples,
    top,
    top_state,
    controller_state,
    ctrl_a,
    ctrl_b,
    ctrl_c,
    ctrl_d,
    ctrl_w,
    speed_table,
    contacts,
    contact_stuck,
    law_torque,
    law_slope,
    law_parameters,
) -> None:  # pragma: no cover - compiled
    """Advance the run from step ``settings[slot.FIRST_STEP]`` to ``settings[slot.STEPS]``
    from the state (θ, ω, U, V) and the top drive's (``top_state``, ``controller_state``)
    in place (``stats`` carried over from the steps before)."""
    h, steps = settings[slot.STEP], int(settings[slot.STEPS])
    first = int(settings[slot.FIRST_STEP])
    top_speed, weight = settings[slot.TOP_SPEED], settings[slot.HOOK_WEIGHT]
    speed_hook, hook_speed = settings[slot.SPEED_HOOK] != 0.0, settings[slot.HOOK_SPEED]
    window_start, sample_every = int(settings[slot.WINDOW_START]), int(settings[slot.SAMPLE_EVERY])
    t_start, hook_start = settings[slot.START_TIME], settings[slot.HOOK_START]
    prescribed, amplitude = settings[slot.PRESCRIBED] != 0.0, settings[slot.AMPLITUDE]
    frequency = settings[slot.FREQUENCY]
    wf_max, tf_per_wf = bit[slot.FRICTION_WEIGHT], bit[slot.FRICTION_TORQUE_PER_WEIGHT]
    torque_law, radius = bit[slot.LAW_TORQUE] != 0.0, bit[slot.BIT_RADIUS]
    surface = settings[slot.ROCK_SURFACE]
    nt, na = theta.size, u.size
    bt, ba = nt - 1, na - 1
    delayed = np.zeros(2)
    held = top[slot.TOP_HELD] != 0.0
    no_set_speed = math.isnan(top[slot.TOP_SET_SPEED])
    constant = speed_table.shape[1] == 1  # a set speed that does not change in time
    set_speed = speed_table[TABLE_SPEED, 0]
    states = controller_state.size
    rate = np.zeros(states)
    threshold = settings[slot.THRESHOLD_SPEED]
    has_contacts = False
    for i in range(contacts.shape[1]):
        if contacts[slot.STATIC_FORCE, i] > 0.0:
            has_contacts = True
    v_start = np.zeros(na)
    if first == 0:
        bit_step.start_window(stats)
    friction_work, switches = stats[slot.FRICTION_WORK], stats[slot.CONTACT_SWITCHES]
    top_work, hook_work = stats[slot.TOP_WORK], stats[slot.HOOK_WORK]
    damper_work, bit_work = stats[slot.DAMPER_WORK], stats[slot.BIT_WORK]
    row = (first + sample_every - 1) // sample_every if sample_every > 0 else 0
    for step in range(first, steps):
        t = t_start + step * h
        sampled = sample_every > 0 and step % sample_every == 0 and row < samples.shape[0]
        if sampled:
            bit_step.sample_motion(samples, row, t, theta[bt], omega[bt], u[ba], v[ba])
        if step == window_start:
            stats[slot.POSITION_START] = u[ba]
        # 1. depth of cut (none under a law of the torque alone: the rock is rigid)
        if torque_law:
            depth, on_bottom = 0.0, u[ba] >= surface
            delayed[0] = math.nan
        else:
            depth = bit_step.depth_of_cut(bit, history, cursor, theta[bt], u[ba], h, delayed)
            if math.isnan(depth):
                stats[slot.FAILED] = 1.0
                stats[slot.STEPS_DONE] = step
                return
            on_bottom = depth > 0.0
        wc, tc = bit_step.cutting_forces(bit, depth)
        if has_contacts:
            for i in range(na):
                v_start[i] = v[i]
        # 2. axial
        hook_position = hook_start + hook_speed * (t - t_start)
        hook_force = weight
        for i in range(na - 1, -1, -1):
            if i == 0:
                if speed_hook:
                    force = axial[1, 0] * (hook_position - u[0]) + axial[2, 0] * (hook_speed - v[0])
                    hook_force = force
                else:
                    force = weight
            else:
                force = axial[1, i] * (u[i - 1] - u[i]) + axial[2, i] * (v[i - 1] - v[i])
            if i + 1 < na:
                # the node below at the step's start where contacts change its velocity later
                below = v_start[i + 1] if has_contacts else v[i + 1]
                force -= axial[1, i + 1] * (u[i] - u[i + 1]) + axial[2, i + 1] * (v[i] - below)
            if i == ba:
                v[i], wf = bit_step.wear_flat_contact(
                    v[i], force, wc, axial[0, i], h, wf_max, on_bottom
                )
            else:
                v[i] += h * force * axial[0, i]
        # 3. torsional
        tf = tf_per_wf * wf
        if held and constant:  # the table's one speed: Ω t, as table_twist gives it
            top_angle, top_rate = set_speed * t, set_speed
        elif held:  # at the set speed of the table, turned through its integral
            top_angle, top_rate = table_twist(speed_table, t, 0.0), table_speed(speed_table, t)
        else:
            top_angle, top_rate = top_state[slot.TOP_NODE_ANGLE], top_state[slot.TOP_NODE_SPEED]
        top_torque = torsional[1, 0] * (top_angle - theta[0]) + torsional[2, 0] * (
            top_rate - omega[0]
        )
        motor = top_torque
        bit_torque = tc + tf
        if prescribed:
            tt = t + h
            omega[bt] = top_speed * (1.0 + amplitude * math.sin(frequency * tt))
            theta[bt] = top_speed * (tt + amplitude * (1.0 - math.cos(frequency * tt)) / frequency)
        else:
            for i in range(nt - 1, -1, -1):
                speed_start = omega[i]
                if i == 0:
                    torque = top_torque
                else:
                    torque = torsional[1, i] * (theta[i - 1] - theta[i])
                    torque += torsional[2, i] * (omega[i - 1] - omega[i])
                if i + 1 < nt:
                    torque -= torsional[1, i + 1] * (theta[i] - theta[i + 1])
                    torque -= torsional[2, i + 1] * (omega[i] - omega[i + 1])
                if i == bt and torque_law:
                    omega[i], bit_torque = bit_step.law_rotation(
                        omega[i], torque, law_torque(law_parameters, omega[i], wf, radius),
                        law_slope(law_parameters, omega[i], wf, radius), torsional[0, i], h,
                    )  # fmt: skip
                elif i == bt:
                    omega[i], bit_torque = bit_step.forward_rotation(
                        omega[i], torque, tc, tf, torsional[0, i], h
                    )
                else:
                    omega[i] += h * torque * torsional[0, i]
                if has_contacts and contacts[slot.STATIC_FORCE, i] > 0.0:
                    # 3b. the node's contact with the borehole, on its free (V, ω)
                    radius = contacts[slot.CONTACT_RADIUS, i]
                    sticky = math.hypot(v_start[i], radius * speed_start) < radius * threshold
                    v[i], omega[i], stuck = cone_step(
                        v[i], omega[i], radius, axial[0, i], torsional[0, i],
                        contacts[slot.STATIC_FORCE, i], contacts[slot.SLIDING_FORCE, i], h, sticky,
                    )  # fmt: skip
                    if stuck != (contact_stuck[i] != 0.0):
                        switches += 1.0
                    contact_stuck[i] = 1.0 if stuck else 0.0
                    applied = contacts[slot.STATIC_FORCE if sticky else slot.SLIDING_FORCE, i]
                    friction_work += h * applied * math.hypot(v[i], radius * omega[i])
            for i in range(nt):
                theta[i] += h * omega[i]
        if not held:
            if not constant:
                set_speed = table_speed(speed_table, t)
            error = 0.0 if no_set_speed else set_speed - top_rate
            motor, free = compiled_motor_torque(
                top[slot.TOP_U0], ctrl_d[0], ctrl_d[1], top[slot.TOP_MAX_TORQUE], states, ctrl_c,
                controller_state, error, top_torque,
            )  # fmt: skip
            compiled_controller_rates(
                states, states, ctrl_a, ctrl_b, ctrl_w, controller_state, error, top_torque, motor,
                free, rate,
            )  # fmt: skip
            for j in range(states):
                controller_state[j] += h * rate[j]
            top_state[slot.TOP_NODE_SPEED] += (
                h
                * (motor - top[slot.TOP_DRAG] * top_rate - top_torque)
                * top[slot.TOP_INVERSE_INERTIA]
            )
            top_state[slot.TOP_NODE_ANGLE] += h * top_state[slot.TOP_NODE_SPEED]
        # the energy balance's works over the step, on the new velocities
        top_work += h * top_torque * top_rate
        hook_work += h * hook_force * (hook_speed if speed_hook else v[0])
        bit_work += h * ((wc + wf) * v[ba] + bit_torque * omega[bt])
        if speed_hook:
            damper_work += h * axial[2, 0] * (hook_speed - v[0]) ** 2
        for i in range(1, na):
            damper_work += h * axial[2, i] * (v[i - 1] - v[i]) ** 2
        if not prescribed:
            damper_work += h * torsional[2, 0] * (top_rate - omega[0]) ** 2
            for i in range(1, nt):
                damper_work += h * torsional[2, i] * (omega[i - 1] - omega[i]) ** 2
        # 4. positions and history
        for i in range(na):
            u[i] += h * v[i]
        append(history, cursor, t + h, theta[bt], omega[bt], u[ba], v[ba])
        if sampled:
            samples[row, slot.TOP_DRIVE_SPEED] = top_rate
            samples[row, slot.MOTOR_TORQUE] = motor
            samples[row, slot.SURFACE_TORQUE] = top_torque
        row = bit_step.record_step(
            stats, samples, row, step >= window_start, sampled, omega[bt], v[ba], depth,
            on_bottom, h, wc + wf, bit_torque, t - delayed[0], top_torque,
            settings[slot.STICK_SPEED],
        )  # fmt: skip
    stats[slot.POSITION_END] = u[ba]
    stats[slot.STEPS_DONE] = steps
    stats[slot.FRICTION_WORK], stats[slot.CONTACT_SWITCHES] = friction_work, switches
    stats[slot.TOP_WORK], stats[slot.HOOK_WORK] = top_work, hook_work
    stats[slot.DAMPER_WORK], stats[slot.BIT_WORK] = damper_work, bit_work
