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
4. Positions from the new velocities: U ← U + h V, θ ← θ + h ω; the top angle Ω₀ t, the
   hook position U_h0 + V_h t. The new bit state is appended to the history.

With a top drive that is not held (``top[TOP_HELD]`` 0), the top is a node (J, drag) with
a linear controller (:class:`torsio.physics.top_drive_boundary.TopDriveBoundary`), advanced
in step 3 after the chain with the surface torque T_pipe = k_0 (θ_top − θ_0) + c_0 (Ω_top −
ω_0) of the state at the step's start: y = [Ω_set − Ω_top, T_pipe], u_free = u0 + c·z +
d·y, u = clip(u_free, ±max_torque), z ← z + h (a z + b y + w (u − u_free)),
Ω_top ← Ω_top + h (u − drag Ω_top − T_pipe)/J, θ_top ← θ_top + h Ω_top (the new speed).
``top`` holds the slots named ``TOP_*`` below; ``top_state`` is [θ_top (rad), Ω_top
(rad/s)], ``controller_state`` z; ``ctrl_a`` (m, m), ``ctrl_b`` (m, 2), ``ctrl_c`` (m,),
``ctrl_d`` (2,), ``ctrl_w`` (m,) the controller's matrices.

The bit's part of steps 1-3 is :mod:`torsio.axial.bit_step`, shared with the distributed
pipe's loop (:mod:`torsio.axial.wave_kernel`).

``settings``: [h, steps, Ω₀ (top speed, rad/s), W₀ (hook weight, N), hook (0 weight,
1 speed), V_h (m/s), U_h0 (m), first step of the window, sample every, prescribed (0/1),
amplitude A, frequency f (rad/s), t at step 0]. The bit law ``bit``: [ζ ε a, ε a²/2,
σ a l, μ γ a / 2, 2π/n, n]. ``torsional``: rows 1/I, k, c (spring and damper i join node
i − 1, the top for i = 0, to node i). ``axial``: rows 1/m, k, c likewise (node 0's spring
joins the hook; with the weight hook it carries W₀ and is not used). ``stats`` on return:
see :data:`STATS`.
"""

from __future__ import annotations

import math

import numpy as np

from torsio.axial.bit_step import (
    add_to_window,
    cutting_forces,
    depth_of_cut,
    forward_rotation,
    start_window,
    wear_flat_contact,
)
from torsio.axial.history import append
from torsio.solvers.compiled import njit

__all__ = ["SAMPLE_COLUMNS", "STATS", "TOP_SLOTS", "march"]

TOP_SLOTS = (
    "held",
    "inverse_inertia",
    "drag",
    "motor_torque_constant",
    "max_torque",
    "set_speed",
    "ramp",
)
"""The slots of the kernel's ``top`` array, in order: 1 when the top is held at Ω₀ (no
node), 1/J [1/(kg m²)], drag [N m s/rad], u0 [N m], max_torque [N m] (inf: none), Ω_set
[rad/s] (NaN: none, e = 0), the set-speed ramp [s] (0: a step)."""
TOP_HELD, TOP_INVERSE_INERTIA, TOP_DRAG, TOP_U0, TOP_MAX_TORQUE, TOP_SET_SPEED, TOP_RAMP = range(7)

STATS = (
    "bit_speed_max",
    "bit_speed_min",
    "axial_speed_max",
    "axial_speed_min",
    "stuck_steps",
    "off_bottom_steps",
    "window_steps",
    "position_start",
    "position_end",
    "work",
    "torque_integral",
    "weight_integral",
    "failed",
    "steps_done",
    "depth_of_cut_max",
)
"""The entries of ``stats`` after :func:`march`, in order (window quantities; work [J],
integrals of the bit torque [N m s] and weight [N s]; ``failed`` 1 when the history was
too short for the delay; the largest depth of cut [m per rev])."""

SAMPLE_COLUMNS = (
    "time",
    "bit_angle",
    "bit_speed",
    "bit_position",
    "bit_velocity",
    "depth_of_cut",
    "bit_weight",
    "bit_torque",
    "delay",
    "top_torque",
    "top_speed",
    "motor_torque",
    "surface_torque",
)
"""The columns of ``samples``: s, rad, rad/s, m (down), m/s, m per rev, N, N m, s, N m, then
the top drive's speed [rad/s], its motor torque [N m] and the surface torque [N m] (the
torque in the string at the top, ``top_torque`` again under the name the torsional runs use;
with the top held the motor torque is the surface torque)."""


@njit(cache=True, nogil=True, error_model="numpy")
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
) -> None:  # pragma: no cover - compiled
    """Advance the run ``settings[1]`` steps from the state (θ, ω, U, V) and the top
    drive's (``top_state``, ``controller_state``) in place."""
    h, steps, top_speed, weight = settings[0], int(settings[1]), settings[2], settings[3]
    speed_hook, hook_speed, hook_start = settings[4] != 0.0, settings[5], settings[6]
    window_start, sample_every = int(settings[7]), int(settings[8])
    prescribed, amplitude, frequency, t_start = (
        settings[9] != 0.0,
        settings[10],
        settings[11],
        settings[12],
    )
    wf_max, tf_per_wf = bit[2], bit[3]
    nt, na = theta.size, u.size
    bt, ba = nt - 1, na - 1
    delayed = np.zeros(2)
    held = top[TOP_HELD] != 0.0
    states = controller_state.size
    rate = np.zeros(states)
    start_window(stats)
    row = 0
    for step in range(steps):
        t = t_start + step * h
        sampled = sample_every > 0 and step % sample_every == 0 and row < samples.shape[0]
        if sampled:
            samples[row, 0] = t
            samples[row, 1] = theta[bt]
            samples[row, 2] = omega[bt]
            samples[row, 3] = u[ba]
            samples[row, 4] = v[ba]
        if step == window_start:
            stats[7] = u[ba]
        # 1. depth of cut
        depth = depth_of_cut(bit, history, cursor, theta[bt], u[ba], h, delayed)
        if math.isnan(depth):
            stats[12] = 1.0
            stats[13] = step
            return
        on_bottom = depth > 0.0
        wc, tc = cutting_forces(bit, depth)
        # 2. axial
        hook_position = hook_start + hook_speed * (t - t_start)
        for i in range(na - 1, -1, -1):
            if i == 0:
                if speed_hook:
                    force = axial[1, 0] * (hook_position - u[0]) + axial[2, 0] * (hook_speed - v[0])
                else:
                    force = weight
            else:
                force = axial[1, i] * (u[i - 1] - u[i]) + axial[2, i] * (v[i - 1] - v[i])
            if i + 1 < na:
                force -= axial[1, i + 1] * (u[i] - u[i + 1]) + axial[2, i + 1] * (v[i] - v[i + 1])
            if i == ba:
                v[i], wf = wear_flat_contact(v[i], force, wc, axial[0, i], h, wf_max, on_bottom)
            else:
                v[i] += h * force * axial[0, i]
        # 3. torsional
        tf = tf_per_wf * wf
        if held:
            top_angle, top_rate = top_speed * t, top_speed
        else:
            top_angle, top_rate = top_state[0], top_state[1]
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
                if i == 0:
                    torque = top_torque
                else:
                    torque = torsional[1, i] * (theta[i - 1] - theta[i])
                    torque += torsional[2, i] * (omega[i - 1] - omega[i])
                if i + 1 < nt:
                    torque -= torsional[1, i + 1] * (theta[i] - theta[i + 1])
                    torque -= torsional[2, i + 1] * (omega[i] - omega[i + 1])
                if i == bt:
                    omega[i], bit_torque = forward_rotation(
                        omega[i], torque, tc, tf, torsional[0, i], h
                    )
                else:
                    omega[i] += h * torque * torsional[0, i]
            for i in range(nt):
                theta[i] += h * omega[i]
        if not held:
            set_speed = top[TOP_SET_SPEED]
            if top[TOP_RAMP] > 0.0:
                set_speed *= min(1.0, t / top[TOP_RAMP])
            error = 0.0 if math.isnan(set_speed) else set_speed - top_rate
            free = top[TOP_U0] + ctrl_d[0] * error + ctrl_d[1] * top_torque
            for j in range(states):
                free += ctrl_c[j] * controller_state[j]
            limit = top[TOP_MAX_TORQUE]
            motor = min(max(free, -limit), limit)
            for j in range(states):
                value = ctrl_b[j, 0] * error + ctrl_b[j, 1] * top_torque
                value += ctrl_w[j] * (motor - free)
                for k in range(states):
                    value += ctrl_a[j, k] * controller_state[k]
                rate[j] = value
            for j in range(states):
                controller_state[j] += h * rate[j]
            top_state[1] += (
                h * (motor - top[TOP_DRAG] * top_rate - top_torque) * top[TOP_INVERSE_INERTIA]
            )
            top_state[0] += h * top_state[1]
        # 4. positions and history
        for i in range(na):
            u[i] += h * v[i]
        append(history, cursor, t + h, theta[bt], omega[bt], u[ba], v[ba])
        bit_weight = wc + wf
        if step >= window_start:
            add_to_window(stats, omega[bt], v[ba], depth, h, bit_weight, bit_torque)
        if sampled:
            samples[row, 5] = depth
            samples[row, 6] = bit_weight
            samples[row, 7] = bit_torque
            samples[row, 8] = t - delayed[0]
            samples[row, 9] = top_torque
            samples[row, 10] = top_rate
            samples[row, 11] = motor
            samples[row, 12] = top_torque
            row += 1
    stats[8] = u[ba]
    stats[13] = steps
