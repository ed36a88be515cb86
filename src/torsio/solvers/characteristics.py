"""Time stepping of the distributed model along characteristics (:mod:`torsio.model.wave`).

The state is the pair of Riemann invariants at every node: p = T + Z w travels down,
m = T - Z w travels up. One step of length dt:

1. **transport**: in every section each p moves one node down and each m one node up
   (exact: the grid matches the wave speed). The invariants live in buffers, one pair
   per section, so a step moves the buffers' read positions, not the values;
2. **drag**: the distributed drag alpha rho J of each section is lumped into point
   dampers c = alpha Z s dt at every ``drag_spacing``-th node, s the node's share of the
   section in cells (:func:`torsio.model.wave_grid.drag_lumping`). A damper at an inner node
   is a junction with a dashpot to the borehole, solved exactly: with the arriving p
   and m, ``v = (p - m) / (2 Z + c)``, then ``p <- m + 2 Z v``, ``m <- p - 2 Z v``; it
   dissipates c v^2. The shares of the end nodes join the junction, the top drive and
   the bit there;
3. **junctions** between sections: speed continuous, the torque jump the damper's,
   ``v = (p - m) / (Z1 + Z2 + c)``; the outgoing invariants follow (exact);
4. **top**: held at Omega (outgoing p = m + 2 Z Omega, a reflection R = -1), or a top
   drive (inertia and linear controller, :class:`torsio.physics.top_drives.TopDriveBoundary`,
   the top node's damper added to its drag) integrated by the trapezoidal rule with the
   incoming m linear over the step; a motor torque beyond ``max_torque`` is held at the
   limit for the step (back-calculation anti-windup as the description gives it). The set
   speed Omega(t) is read from a table (time, speed), linear between its points (a ramp,
   a recorded speed; :mod:`torsio.solvers.wave_top`);
5. **bit**: the bit's inertia J_b with torque on bit T_bit(w_b), drag alpha J_b plus the
   bottom node's damper, and the pipe torque p - Z w_b, by BDF2 (backward Euler on the
   first step), an L-stable second-order rule: the bit's own time scale J_b / Z (about
   2e-4 s for the Ritto string) is far below dt. Each step solves one scalar equation
   k w + T_bit(w) = r (k > 0): bracketed from the previous speed in the direction of
   motion, the first trial the linear extrapolation of the last two speeds, then
   safeguarded Newton to 1e-12 relative (or to where quadratic convergence puts the
   error below that).

Everything but the bit's and the top drive's time integration is exact for the lumped
drag: the energy of the string, sum of (p^2 + m^2) dt / (4 Z) over the nodes (half at
the ends of a section), changes by the boundary powers summed by the trapezoidal rule
(the transport and the junctions), less c v^2 dt at every inner damper. With every power
summed so, work in = stored + dissipated to O(dt^2) when the top speed is continuous.
A jump in speed reaching the bit (a held top started from rest) is not resolved when
dt >> J_b / Z: BDF2 then loses about J_b dw^2 / 2 of energy for a jump dw of the bit
speed.

The speed at an inner damper node is (p - m) / (2 Z - c) for the stored outgoing pair
(the torque steps by c v there; its mean is (p + m) / 2): :func:`node_impedances`.

A run can end early on a steady cycle (``steady_tolerance`` > 0, held top or a top drive
with a set speed): a cycle ends where the bit speed crosses the reference speed upwards,
at least ``cycle_gap`` (a quarter of the first natural period) after the last cycle's
end, so that a fast oscillation of the bit about the reference does not count; there
the speed and torque of every node are compared with those at the last cycle's end, in
S_SS units (speeds and torques / Z over 2 Omega), and the run ends once even the larger
of the last two changes, repeated at every cycle left, could not move the state by the
tolerance (the rule of :mod:`torsio.solvers.cycles`). A stick-slip cycle sends fronts down the
string that the grid places to one cell, so its state repeats to about 1e-3 only and
such runs go to the end; smooth motions (a decaying oscillation) end early.

The step is compiled with numba (cache=True) when the law brings a compiled kernel
(:func:`torsio.solvers.law_kernels.law_kernel`); otherwise the same algorithm runs as
plain Python with the law's ``torque`` and ``slope``.
"""

from __future__ import annotations

import math
from typing import Any

from torsio.solvers import layouts as slot
from torsio.solvers.chain_kernel import compiled_motor_torque
from torsio.solvers.compiled import njit
from torsio.solvers.set_speed import table_speed
from torsio.solvers.wave_bit import _solve_bit
from torsio.solvers.wave_buffers import (
    _advance,
    _copy_nodes,
    _dampers,
    _dampers_with_power,
    _end_slots,
    _node_slots,
    _read_nodes,
)
from torsio.solvers.wave_contacts import _contact_node_speeds, _contact_speed, _contacts
from torsio.solvers.wave_cycles import _crossing
from torsio.solvers.wave_state import (
    KernelLayout,
    WaveState,
    kernel_layout,
    node_impedances,
    node_offsets,
    rest_state,
    state_from_fields,
)

__all__ = [
    "RECORD_CHANNELS",
    "KernelLayout",
    "WaveState",
    "kernel_layout",
    "node_impedances",
    "node_offsets",
    "rest_state",
    "state_from_fields",
]

try:  # a dependency; without an importable numba the steps run as plain Python (slowly)
    from numba import types

    _F8 = types.float64
    _VECTOR = types.float64[::1]
    _MATRIX = types.float64[:, ::1]
    _LAW = types.FunctionType(_F8(_VECTOR, _F8, _F8, _F8))
    _MARCH_SIGNATURE: Any = types.void(
        types.int64[:, ::1], _MATRIX, _VECTOR, _VECTOR, _VECTOR, _VECTOR, _VECTOR, _VECTOR,
        _VECTOR, types.float64[:, :, ::1], _MATRIX, _MATRIX, _VECTOR, _MATRIX, _MATRIX,
        _LAW, _LAW, _VECTOR, _MATRIX, _MATRIX, _VECTOR, _MATRIX,
        _MATRIX, _MATRIX, types.int64[:, ::1], _VECTOR, types.int64[:, ::1], _MATRIX,
    )  # fmt: skip
except ImportError:  # pragma: no cover - exercised only without numba
    _MARCH_SIGNATURE = None


RECORD_CHANNELS = ("bit_speed", "bit_torque", "surface_torque", "top_speed", "motor_torque")
"""Columns of the recorded time series: rad/s, N m, N m, rad/s, N m."""


@njit(_MARCH_SIGNATURE, cache=True, nogil=True, _nrt=False, error_model="numpy")
def _march(  # type: ignore[no-untyped-def,unused-ignore]
    layout, sections, end_dampers, impedances, settings, p, m, top_state, bit_state,
    propagator, forcing, constant, coefficients, speed_table, constant_per_speed,
    torque, slope, parameters, records, field, summary, cross, buffers, scratch, heads, top_work,
    contact_index, contacts,
):  # fmt: skip
    """Advance ``WAVE_STEPS`` steps of a run of ``WAVE_RUN_STEPS`` steps (the ``summary``
    counts those taken before: a run may take its steps in several calls, with the same
    result); see the module docstring. ``settings`` and ``summary`` as
    :mod:`torsio.solvers.layouts` lays them out. Works in place on the node-ordered state
    (p, m, top_state, bit_state) and the ``summary``; ``buffers`` (2,
    KernelLayout.buffer_size), ``scratch`` (2, nodes), ``heads`` (sections, 4) and
    ``top_work`` (top states) are its work space, allocated by the caller. With
    ``WAVE_CONTACTS`` set, the drag nodes carry Coulomb contacts (``contact_index``,
    ``contacts``: :func:`torsio.solvers.wave_contacts.contact_arrays`, threshold speed
    ``WAVE_THRESHOLD``), solved exactly at every step (:mod:`torsio.solvers.wave_contacts`).
    The set speed is ``speed_table``'s (:func:`table_speed`), constant from
    ``WAVE_RAMP_END`` on; the motor torque is the one evaluation of every engine
    (:func:`torsio.physics.top_drive_boundary.motor_torque`) of ``coefficients``
    (``COEF_*``)."""
    dt = settings[slot.WAVE_DT]
    bit_inertia = settings[slot.WAVE_BIT_INERTIA]
    alpha = settings[slot.WAVE_ALPHA]
    wob = settings[slot.WAVE_WOB]
    radius = settings[slot.WAVE_BIT_RADIUS]
    held = settings[slot.WAVE_HELD] != 0.0
    max_torque = settings[slot.WAVE_MAX_TORQUE]
    steps = int(settings[slot.WAVE_STEPS])
    window_start = int(settings[slot.WAVE_WINDOW_START])
    record_every = int(settings[slot.WAVE_RECORD_EVERY])
    field_every = int(settings[slot.WAVE_FIELD_EVERY])
    top_drag = settings[slot.WAVE_TOP_DRAG]
    track_energy = settings[slot.WAVE_TRACK_ENERGY] != 0.0
    spacing = int(settings[slot.WAVE_DRAG_SPACING])
    steady_tolerance = settings[slot.WAVE_STEADY_TOLERANCE]
    reference = settings[slot.WAVE_REFERENCE]
    cycle_gap = settings[slot.WAVE_CYCLE_GAP]
    run_steps = int(settings[slot.WAVE_RUN_STEPS])
    threshold = settings[slot.WAVE_THRESHOLD]
    below = settings[
        slot.WAVE_BELOW_THRESHOLD
    ]  # the largest speed under the threshold: the static branch
    rubbing = settings[slot.WAVE_CONTACTS] != 0.0
    ramp_end = settings[slot.WAVE_RAMP_END]
    t_end = run_steps * dt  # the run's end, for the cycles left, and its window's length
    window_length = (run_steps - window_start + 1) * dt
    track = steady_tolerance > 0.0 and reference > 0.0
    count = layout.shape[0]
    last = count - 1
    nodes = p.size
    P = buffers[slot.BUFFER_P]
    M = buffers[slot.BUFFER_M]
    # heads: (row, column) of node 0's slot of p and of m in each section
    heads[:, :] = 0
    _copy_nodes(layout, spacing, P, M, heads, p, m, True)
    c_top = end_dampers[0]
    c_bit = end_dampers[count]
    z_top = sections[0, slot.Z]
    z_bit = sections[last, slot.Z]
    n_top = top_state.size
    previous = summary[
        slot.SUM_POWERS : slot.SUM_POWERS + slot.POWER_COUNT
    ]  # powers at the previous step (trapezoidal energies)
    mode_x = top_work
    static, dynamic = contacts[slot.CONTACT_STATIC], contacts[slot.CONTACT_DYNAMIC]
    contact_speed = contacts[slot.CONTACT_SPEED]
    speeds = scratch[slot.NODE_SPEED]
    torques = scratch[slot.NODE_TORQUE]
    w_now = bit_state[slot.BIT_SPEED]
    if summary[slot.SUM_STEPS] > 0.0:  # a run continued: the torque the last step solved for
        t_now = summary[slot.SUM_BIT_TORQUE]
    else:
        t_now = torque(parameters, w_now, wob, radius)
    taken = 0
    set_speed = table_speed(speed_table, summary[slot.SUM_STEPS] * dt)  # at the step's start
    for step in range(steps):
        m_top_old = M[_end_slots(layout, spacing, heads, 0, False)[1]]
        t_next = (summary[slot.SUM_STEPS] + step + 1.0) * dt
        set_before = set_speed  # the set speed at t_next - dt, read by the step before
        set_speed = table_speed(speed_table, t_next)
        # 1. transport
        _advance(layout, spacing, P, M, heads)
        # 2. inner dampers: the regular ones a run of one row of p and one of m
        inner_power = 0.0
        friction_power = 0.0
        for s in range(count):
            start = layout[s, slot.BUFFER_START]
            width = layout[s, slot.WIDTH]
            regular = layout[s, slot.INNER]
            if regular > 0:
                ip = start + heads[s, slot.HEAD_P_ROW] * width + heads[s, slot.HEAD_P_COLUMN] + 1
                im = start + heads[s, slot.HEAD_M_ROW] * width + heads[s, slot.HEAD_M_COLUMN] + 1
                if rubbing:
                    a = contact_index[s, slot.CONTACT_REGULAR]
                    b = a + regular
                    z = sections[s, slot.Z]
                    c = sections[s, slot.C_INNER]
                    squares, rub = _contacts(
                        P[ip : ip + regular], M[im : im + regular], 2.0 * z, 1.0 / (2.0 * z + c),
                        static[a:b], dynamic[a:b], contact_speed[a:b], below, track_energy,
                    )  # fmt: skip
                    inner_power += c * squares
                    friction_power += rub
                elif track_energy:
                    total = _dampers_with_power(
                        P[ip : ip + regular], M[im : im + regular], sections[s, slot.RATIO_INNER]
                    )
                    z = sections[s, slot.Z]
                    c = sections[s, slot.C_INNER]
                    inner_power += c * total / ((2.0 * z + c) * (2.0 * z + c))
                else:
                    _dampers(
                        P[ip : ip + regular], M[im : im + regular], sections[s, slot.RATIO_INNER]
                    )
            if layout[s, slot.SPECIAL] >= 0:
                rows_on = layout[s, slot.SPECIAL_ROW]
                columns_on = layout[s, slot.SPECIAL_COLUMN]
                ip, im = _node_slots(layout, spacing, heads, s, rows_on, columns_on)
                arriving_p = P[ip]
                difference = arriving_p - M[im]
                z = sections[s, slot.Z]
                c = sections[s, slot.C_SPECIAL]
                if rubbing:
                    j = contact_index[s, slot.CONTACT_OTHER]
                    v = _contact_speed(
                        difference, 1.0 / (2.0 * z + c), static[j], dynamic[j],
                        contact_speed[j], below,
                    )  # fmt: skip
                    contact_speed[j] = v
                    friction_power += (difference - (2.0 * z + c) * v) * v
                    jump = 2.0 * z * v
                    inner_power += c * v * v
                else:
                    jump = sections[s, slot.RATIO_SPECIAL] * difference
                    inner_power += c * difference * difference / ((2.0 * z + c) * (2.0 * z + c))
                P[ip] = M[im] + jump
                M[im] = arriving_p - jump
        # 3. junctions (with the damper of the junction node)
        end_power = 0.0
        for s in range(last):
            ia, ja = _end_slots(layout, spacing, heads, s, True)
            ib, jb = _end_slots(layout, spacing, heads, s + 1, False)
            z1 = sections[s, slot.Z]
            z2 = sections[s + 1, slot.Z]
            c = end_dampers[s + 1]
            difference = P[ia] - M[jb]
            if rubbing:
                j = contact_index[s, slot.CONTACT_JUNCTION]
                speed = _contact_speed(
                    difference, 1.0 / (z1 + z2 + c), static[j], dynamic[j],
                    contact_speed[j], below,
                )  # fmt: skip
                contact_speed[j] = speed
                friction_power += (difference - (z1 + z2 + c) * speed) * speed
            else:
                speed = difference / (z1 + z2 + c)
            M[ja] = P[ia] - 2.0 * z1 * speed
            P[ib] = M[jb] + 2.0 * z2 * speed
            end_power += c * speed * speed
        # 4. top
        i_top, j_top = _end_slots(layout, spacing, heads, 0, False)
        m_in = M[j_top]
        if held:
            top_speed = set_speed
            motor = m_in + (z_top + c_top) * set_speed
        else:
            chosen = 0
            u_free = 0.0
            for mode in range(3):
                set_mean = 0.5 * (set_before + set_speed)
                for i in range(n_top):
                    acc = constant[mode, i] + set_mean * constant_per_speed[mode, i]
                    acc += forcing[mode, i] * (m_top_old + m_in)
                    for j in range(n_top):
                        acc += propagator[mode, i, j] * top_state[j]
                    mode_x[i] = acc
                speed = mode_x[slot.X_TOP_SPEED]
                u_free = compiled_motor_torque(
                    coefficients[slot.COEF_U0], coefficients[slot.COEF_KP],
                    coefficients[slot.COEF_PIPE_GAIN], max_torque, n_top - slot.X_CONTROLLER,
                    coefficients[slot.COEF_STATES :], mode_x[slot.X_CONTROLLER :],
                    set_speed - speed, m_in + z_top * speed,
                )[1]  # fmt: skip
                if mode == 0:
                    if u_free > max_torque:
                        continue
                    if u_free < -max_torque:
                        continue
                    chosen = 0
                    break
                if mode == 1 and u_free >= max_torque:
                    chosen = 1
                    break
                if mode == 2:
                    chosen = 2
            if chosen == 0:
                motor = u_free
            elif chosen == 1:
                motor = max_torque
            else:
                motor = -max_torque
            for i in range(n_top):
                top_state[i] = mode_x[i]
            top_speed = top_state[slot.X_TOP_SPEED]
        P[i_top] = m_in + 2.0 * z_top * top_speed
        surface_torque = m_in + (z_top + c_top) * top_speed  # the top node's drag: the string's
        end_power += c_top * top_speed * top_speed
        # 5. bit
        i_bit, j_bit = _end_slots(layout, spacing, heads, last, True)
        p_in = P[i_bit]
        w_old = bit_state[slot.BIT_SPEED_BEFORE]
        if bit_state[slot.BIT_STEPS] < 1.0:
            k = bit_inertia / dt + z_bit + alpha * bit_inertia + c_bit
            rhs = bit_inertia * w_now / dt + p_in
            guess = w_now
        else:
            k = 1.5 * bit_inertia / dt + z_bit + alpha * bit_inertia + c_bit
            rhs = bit_inertia * (4.0 * w_now - w_old) / (2.0 * dt) + p_in
            guess = 2.0 * w_now - w_old
        w_bit, bit_torque = _solve_bit(
            k, rhs, w_now, t_now, guess, torque, slope, parameters, wob, radius
        )
        if not math.isfinite(w_bit):
            summary[slot.SUM_FAILED_STEP] = summary[slot.SUM_STEPS] + step + 1.0
            break
        taken = step + 1
        bit_state[slot.BIT_SPEED_BEFORE] = w_now
        bit_state[slot.BIT_SPEED] = w_bit
        bit_state[slot.BIT_STEPS] += 1.0
        w_old = w_now
        w_now = w_bit
        t_now = bit_torque
        M[j_bit] = p_in - 2.0 * z_bit * w_bit
        end_power += c_bit * w_bit * w_bit
        # energies: the inner dampers' exactly, the rest by the trapezoidal rule
        power_in = motor * top_speed
        power_bit = bit_torque * w_bit
        power_bit_drag = alpha * bit_inertia * w_bit * w_bit
        power_top_drag = top_drag * top_speed * top_speed
        summary[slot.SUM_WORK_IN] += 0.5 * dt * (previous[slot.POWER_IN] + power_in)
        summary[slot.SUM_BIT_DISSIPATION] += 0.5 * dt * (previous[slot.POWER_BIT] + power_bit)
        summary[slot.SUM_BIT_DRAG_DISSIPATION] += (
            0.5 * dt * (previous[slot.POWER_BIT_DRAG] + power_bit_drag)
        )
        summary[slot.SUM_STRING_DRAG_DISSIPATION] += (
            0.5 * dt * (previous[slot.POWER_STRING_DRAG] + end_power) + dt * inner_power
        )
        summary[slot.SUM_TOP_DRAG_DISSIPATION] += (
            0.5 * dt * (previous[slot.POWER_TOP_DRAG] + power_top_drag)
        )
        summary[slot.SUM_FRICTION_WORK] += dt * friction_power
        previous[slot.POWER_IN] = power_in
        previous[slot.POWER_BIT] = power_bit
        previous[slot.POWER_BIT_DRAG] = power_bit_drag
        previous[slot.POWER_STRING_DRAG] = end_power
        previous[slot.POWER_TOP_DRAG] = power_top_drag
        # window extremes and records
        absolute = int(summary[slot.SUM_STEPS]) + step + 1
        summary[slot.SUM_SURFACE_TORQUE_PEAK] = max(
            summary[slot.SUM_SURFACE_TORQUE_PEAK], surface_torque
        )
        if summary[slot.SUM_BIT_FIRST_MOTION] == 0.0 and abs(w_bit) > threshold:
            summary[slot.SUM_BIT_FIRST_MOTION] = absolute
        if absolute >= window_start:
            summary[slot.SUM_SURFACE_TORQUE_MIN] = min(
                summary[slot.SUM_SURFACE_TORQUE_MIN], surface_torque
            )
            summary[slot.SUM_SURFACE_TORQUE_MAX] = max(
                summary[slot.SUM_SURFACE_TORQUE_MAX], surface_torque
            )
            if w_bit < summary[slot.SUM_BIT_SPEED_MIN]:
                summary[slot.SUM_BIT_SPEED_MIN] = w_bit
            if w_bit > summary[slot.SUM_BIT_SPEED_MAX]:
                summary[slot.SUM_BIT_SPEED_MAX] = w_bit
            summary[slot.SUM_TOP_SPEED_SUM] += top_speed
            summary[slot.SUM_WINDOW_STEPS] += 1.0
        if record_every > 0 and absolute % record_every == 0:
            row = absolute // record_every
            if row < records.shape[0]:
                records[row, slot.REC_BIT_SPEED] = w_bit
                records[row, slot.REC_BIT_TORQUE] = bit_torque
                records[row, slot.REC_SURFACE_TORQUE] = surface_torque
                records[row, slot.REC_TOP_SPEED] = top_speed
                records[row, slot.REC_MOTOR_TORQUE] = motor
        if field_every > 0 and absolute % field_every == 0:
            row = absolute // field_every
            if row < field.shape[0]:
                _read_nodes(layout, spacing, P, M, heads, impedances, speeds, torques)
                if rubbing:
                    _contact_node_speeds(contacts, speeds)
                for j in range(nodes):
                    field[row, j] = speeds[j]
        # 6. a steady cycle? (upward crossings of the reference speed by the bit)
        if track and t_next > ramp_end:
            crossed = w_old < reference <= w_bit
            t_cross = 0.0
            if crossed:
                t_cross = (absolute - 1.0 + (reference - w_old) / (w_bit - w_old)) * dt
                crossed = (
                    summary[slot.SUM_COUNT] < 1.0 or t_cross - summary[slot.SUM_T_LAST] >= cycle_gap
                )
            if not crossed:
                if summary[slot.SUM_COUNT] > 0.0:
                    summary[slot.SUM_RUN_MAX] = max(summary[slot.SUM_RUN_MAX], w_bit)
                    summary[slot.SUM_RUN_MIN] = min(summary[slot.SUM_RUN_MIN], w_bit)
                continue
            steady = _crossing(
                layout, spacing, P, M, heads, impedances, speeds, torques, cross, summary,
                w_bit, top_speed, t_cross, reference, t_end, window_length,
                steady_tolerance,
            )  # fmt: skip
            if steady:  # its extremes are those of the rest of the window
                summary[slot.SUM_BIT_SPEED_MIN] = min(
                    summary[slot.SUM_BIT_SPEED_MIN], summary[slot.SUM_CYCLE_MIN]
                )
                summary[slot.SUM_BIT_SPEED_MAX] = max(
                    summary[slot.SUM_BIT_SPEED_MAX], summary[slot.SUM_CYCLE_MAX]
                )
                summary[slot.SUM_ENDED] = absolute
                break
    summary[slot.SUM_STEPS] += taken
    summary[slot.SUM_BIT_TORQUE] = t_now
    _copy_nodes(layout, spacing, P, M, heads, p, m, False)
