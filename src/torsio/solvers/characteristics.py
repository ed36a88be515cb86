"""Time stepping of the distributed model along characteristics (:mod:`torsio.model.wave`).

The state is the pair of Riemann invariants at every node: p = T + Z w travels down,
m = T - Z w travels up. One step of length dt:

1. **transport**: in every section each p moves one node down and each m one node up
   (exact: the grid matches the wave speed). The invariants live in buffers, one pair
   per section, so a step moves the buffers' read positions, not the values;
2. **drag**: the distributed drag alpha rho J of each section is lumped into point
   dampers c = alpha Z s dt at every ``drag_spacing``-th node, s the node's share of the
   section in cells (:func:`torsio.model.wave.drag_lumping`). A damper at an inner node
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

from torsio.solvers.compiled import njit
from torsio.solvers.wave_bit import _solve_bit
from torsio.solvers.wave_buffers import (
    _advance,
    _copy_nodes,
    _dampers,
    _dampers_with_power,
    _end_slots,
    _read_nodes,
    _slot,
)
from torsio.solvers.wave_contacts import _contact_node_speeds, _contact_speed, _contacts
from torsio.solvers.wave_state import (
    BUFFER_START,
    C_INNER,
    C_SPECIAL,
    INNER,
    RATIO_INNER,
    RATIO_SPECIAL,
    SPECIAL,
    SPECIAL_COLUMN,
    SPECIAL_ROW,
    WIDTH,
    KernelLayout,
    WaveState,
    Z,
    kernel_layout,
    node_impedances,
    node_offsets,
    rest_state,
    state_from_fields,
)

__all__ = [
    "RECORD_CHANNELS",
    "SUMMARY_FIELDS",
    "SUMMARY_SIZE",
    "KernelLayout",
    "WaveState",
    "kernel_layout",
    "node_impedances",
    "node_offsets",
    "rest_state",
    "state_from_fields",
]

try:  # numba is optional: without it the same steps run as plain Python (slowly)
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

SUMMARY_FIELDS = (
    "bit_speed_min",
    "bit_speed_max",
    "top_speed_sum",
    "window_steps",
    "work_in",
    "bit_dissipation",
    "bit_drag_dissipation",
    "string_drag_dissipation",
    "top_drag_dissipation",
    "failed_step",
)
"""Entries of the run summary: extremes and sums over the window; energies [J] over the run."""

SUMMARY_SIZE = 31
"""Length of the kernel's summary array: :data:`SUMMARY_FIELDS`, the powers of the last
step (10-14), the steps taken before (15), the steady-cycle tracker (16-22, 24), the
step the run ended on a steady cycle (23, 0: it did not) and the torque on bit of the
last step (25), so that a run continued by another call takes the same steps; then the
friction's work along the string [J] (26), the largest surface torque of the run and
the smallest and largest of the window [N m] (27-29), and the first step the bit is
faster than the contacts' threshold speed (30; 0: not yet)."""

# the steady-cycle tracker in the summary array
_COUNT, _T_LAST, _RUN_MAX, _RUN_MIN, _CYCLE_MAX, _CYCLE_MIN, _CHANGE, _ENDED, _KEPT = range(16, 25)
_BIT_TORQUE = 25


@njit(cache=True, nogil=True, _nrt=False)
def _crossing(  # type: ignore[no-untyped-def,unused-ignore]
    layout, spacing, P, M, heads, impedances, speeds, torques, cross, summary,
    w_bit, top_speed, t_cross, reference, t_end, window_length, tolerance,
):  # fmt: skip
    """At an upward crossing of the reference speed by the bit: whether the motion is on
    a steady cycle (module docstring). Updates the tracker in ``summary`` and the state
    kept in ``cross`` (2, nodes + 2: speeds and torques / Z', then the bit and top speeds).

    The state of every node is read only when the bit's and the top's change alone would
    let the run end (it bounds the change from below); otherwise the change counts as
    infinite and no state is kept, which can only delay the end.
    """
    nodes = speeds.size
    crossings = summary[_COUNT]
    period = t_cross - summary[_T_LAST]
    cycles_left = (t_end - t_cross) / period if crossings >= 1.0 else math.inf
    change = math.inf
    quick = 0.0
    bounded = crossings >= 1.0
    if bounded:
        quick = max(abs(w_bit - cross[0, nodes]), abs(top_speed - cross[0, nodes + 1]))
        bounded = cycles_left * quick / (2.0 * reference) <= tolerance
    cross[0, nodes] = w_bit
    cross[0, nodes + 1] = top_speed
    if bounded or crossings < 1.0:
        _read_nodes(layout, spacing, P, M, heads, impedances, speeds, torques)
        if summary[_KEPT] > 0.0:
            moved = 0.0
            for j in range(nodes):
                moved = max(moved, abs(speeds[j] - cross[0, j]), abs(torques[j] - cross[1, j]))
            change = max(moved, quick) / (2.0 * reference)
        for j in range(nodes):
            cross[0, j] = speeds[j]
            cross[1, j] = torques[j]
        summary[_KEPT] = 1.0
    else:
        summary[_KEPT] = 0.0
    steady = (
        crossings >= 3.0
        and period <= window_length
        and cycles_left * max(change, summary[_CHANGE]) <= tolerance
    )
    if crossings >= 1.0:
        summary[_CYCLE_MAX] = summary[_RUN_MAX]
        summary[_CYCLE_MIN] = summary[_RUN_MIN]
    summary[_CHANGE] = change
    summary[_COUNT] = crossings + 1.0
    summary[_T_LAST] = t_cross
    summary[_RUN_MAX] = w_bit
    summary[_RUN_MIN] = w_bit
    return steady


@njit(cache=True, nogil=True, _nrt=False, error_model="numpy", inline="always")
def table_speed(table, time):  # type: ignore[no-untyped-def,unused-ignore]
    """The speed of ``table`` (rows time [s], speed [rad/s]) at ``time``: linear between its
    points, constant beyond them.

    >>> import numpy as np
    >>> ramp, step = np.array([[0.0, 2.0], [0.0, 6.0]]), np.array([[0.0], [3.0]])
    >>> table_speed(ramp, 0.5), table_speed(step, 9.0)
    (1.5, 3.0)
    """
    times = table[0]
    last = times.size - 1
    if time <= times[0]:
        return table[1, 0]
    if time >= times[last]:
        return table[1, last]
    low = 0
    high = last
    while high - low > 1:
        middle = (low + high) // 2
        if times[middle] <= time:
            low = middle
        else:
            high = middle
    share = (time - times[low]) / (times[high] - times[low])
    return table[1, low] + share * (table[1, high] - table[1, low])


@njit(_MARCH_SIGNATURE, cache=True, nogil=True, _nrt=False, error_model="numpy")
def _march(  # type: ignore[no-untyped-def,unused-ignore]
    layout, sections, end_dampers, impedances, settings, p, m, top_state, bit_state,
    propagator, forcing, constant, coefficients, speed_table, constant_per_speed,
    torque, slope, parameters, records, field, summary, cross, buffers, scratch, heads, top_work,
    contact_index, contacts,
):  # fmt: skip
    """Advance ``settings[8]`` steps of a run of ``settings[18]`` steps (the ``summary``
    counts those taken before: a run may take its steps in several calls, with the same
    result); see the module docstring. Works in place on the
    node-ordered state (p, m, top_state, bit_state) and the ``summary``; ``buffers``
    (2, KernelLayout.buffer_size), ``scratch`` (2, nodes), ``heads`` (sections, 4) and
    ``top_work`` (top states) are its work space, allocated by the caller. With
    ``settings[20]`` set, the drag nodes carry Coulomb contacts (``contact_index``,
    ``contacts``: :func:`torsio.solvers.wave_contacts.contact_arrays`, threshold speed
    ``settings[19]``), solved exactly at every step (:mod:`torsio.solvers.wave_contacts`).
    The set speed is ``speed_table``'s (:func:`table_speed`), constant from
    ``settings[23]`` on; ``settings[22]`` is the motor torque per unit set speed."""
    dt = settings[0]
    bit_inertia = settings[1]
    alpha = settings[2]
    wob = settings[3]
    radius = settings[4]
    held = settings[5] != 0.0
    max_torque = settings[7]
    steps = int(settings[8])
    window_start = int(settings[9])
    record_every = int(settings[10])
    field_every = int(settings[11])
    top_drag = settings[12]
    track_energy = settings[13] != 0.0
    spacing = int(settings[14])
    steady_tolerance = settings[15]
    reference = settings[16]
    cycle_gap = settings[17]
    run_steps = int(settings[18])
    threshold = settings[19]
    below = settings[21]  # the largest speed under the threshold: the static branch
    rubbing = settings[20] != 0.0
    set_gain = settings[22]
    ramp_end = settings[23]
    t_end = run_steps * dt  # the run's end, for the cycles left, and its window's length
    window_length = (run_steps - window_start + 1) * dt
    track = steady_tolerance > 0.0 and reference > 0.0
    count = layout.shape[0]
    last = count - 1
    nodes = p.size
    P = buffers[0]
    M = buffers[1]
    # heads: (row, column) of node 0's slot of p and of m in each section
    heads[:, :] = 0
    _copy_nodes(layout, spacing, P, M, heads, p, m, True)
    c_top = end_dampers[0]
    c_bit = end_dampers[count]
    z_top = sections[0, Z]
    z_bit = sections[last, Z]
    n_top = top_state.size
    previous = summary[10:15]  # powers at the previous step (trapezoidal energies)
    mode_x = top_work
    speeds = scratch[0]
    torques = scratch[1]
    w_now = bit_state[0]
    if summary[15] > 0.0:  # a run continued: the torque the last step solved for
        t_now = summary[_BIT_TORQUE]
    else:
        t_now = torque(parameters, w_now, wob, radius)
    taken = 0
    for step in range(steps):
        m_top_old = M[_end_slots(layout, spacing, heads, 0, False)[1]]
        t_next = (summary[15] + step + 1.0) * dt
        set_before = table_speed(speed_table, t_next - dt)
        set_speed = table_speed(speed_table, t_next)
        # 1. transport
        _advance(layout, spacing, P, M, heads)
        # 2. inner dampers: the regular ones a run of one row of p and one of m
        inner_power = 0.0
        friction_power = 0.0
        for s in range(count):
            start = layout[s, BUFFER_START]
            width = layout[s, WIDTH]
            regular = layout[s, INNER]
            if regular > 0:
                ip = start + heads[s, 0] * width + heads[s, 1] + 1
                im = start + heads[s, 2] * width + heads[s, 3] + 1
                if rubbing:
                    a = contact_index[s, 0]
                    b = a + regular
                    z = sections[s, Z]
                    c = sections[s, C_INNER]
                    squares, rub = _contacts(
                        P[ip : ip + regular], M[im : im + regular], 2.0 * z, 1.0 / (2.0 * z + c),
                        contacts[0, a:b], contacts[1, a:b], contacts[2, a:b], below,
                    )  # fmt: skip
                    inner_power += c * squares
                    friction_power += rub
                elif track_energy:
                    total = _dampers_with_power(
                        P[ip : ip + regular], M[im : im + regular], sections[s, RATIO_INNER]
                    )
                    z = sections[s, Z]
                    c = sections[s, C_INNER]
                    inner_power += c * total / ((2.0 * z + c) * (2.0 * z + c))
                else:
                    _dampers(P[ip : ip + regular], M[im : im + regular], sections[s, RATIO_INNER])
            if layout[s, SPECIAL] >= 0:
                rows_on = layout[s, SPECIAL_ROW]
                columns_on = layout[s, SPECIAL_COLUMN]
                ip = _slot(start, width, spacing, heads[s, 0], heads[s, 1], rows_on, columns_on)
                im = _slot(start, width, spacing, heads[s, 2], heads[s, 3], rows_on, columns_on)
                arriving_p = P[ip]
                difference = arriving_p - M[im]
                z = sections[s, Z]
                c = sections[s, C_SPECIAL]
                if rubbing:
                    j = contact_index[s, 1]
                    v = _contact_speed(
                        difference, 1.0 / (2.0 * z + c), contacts[0, j], contacts[1, j],
                        contacts[2, j], below,
                    )  # fmt: skip
                    contacts[2, j] = v
                    friction_power += (difference - (2.0 * z + c) * v) * v
                    jump = 2.0 * z * v
                    inner_power += c * v * v
                else:
                    jump = sections[s, RATIO_SPECIAL] * difference
                    inner_power += c * difference * difference / ((2.0 * z + c) * (2.0 * z + c))
                P[ip] = M[im] + jump
                M[im] = arriving_p - jump
        # 3. junctions (with the damper of the junction node)
        end_power = 0.0
        for s in range(last):
            ia, ja = _end_slots(layout, spacing, heads, s, True)
            ib, jb = _end_slots(layout, spacing, heads, s + 1, False)
            z1 = sections[s, Z]
            z2 = sections[s + 1, Z]
            c = end_dampers[s + 1]
            difference = P[ia] - M[jb]
            if rubbing:
                j = contact_index[s, 2]
                speed = _contact_speed(
                    difference, 1.0 / (z1 + z2 + c), contacts[0, j], contacts[1, j],
                    contacts[2, j], below,
                )  # fmt: skip
                contacts[2, j] = speed
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
                u_free = coefficients[0] + set_gain * set_speed + coefficients[n_top + 1] * m_in
                for i in range(n_top):
                    u_free += coefficients[1 + i] * mode_x[i]
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
            top_speed = top_state[0]
        P[i_top] = m_in + 2.0 * z_top * top_speed
        surface_torque = m_in + (z_top + c_top) * top_speed  # the top node's drag: the string's
        end_power += c_top * top_speed * top_speed
        # 5. bit
        i_bit, j_bit = _end_slots(layout, spacing, heads, last, True)
        p_in = P[i_bit]
        w_old = bit_state[1]
        if bit_state[2] < 1.0:
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
            summary[9] = summary[15] + step + 1.0
            break
        taken = step + 1
        bit_state[1] = w_now
        bit_state[0] = w_bit
        bit_state[2] += 1.0
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
        summary[4] += 0.5 * dt * (previous[0] + power_in)
        summary[5] += 0.5 * dt * (previous[1] + power_bit)
        summary[6] += 0.5 * dt * (previous[2] + power_bit_drag)
        summary[7] += 0.5 * dt * (previous[3] + end_power) + dt * inner_power
        summary[8] += 0.5 * dt * (previous[4] + power_top_drag)
        summary[26] += dt * friction_power
        previous[0] = power_in
        previous[1] = power_bit
        previous[2] = power_bit_drag
        previous[3] = end_power
        previous[4] = power_top_drag
        # window extremes and records
        absolute = int(summary[15]) + step + 1
        summary[27] = max(summary[27], surface_torque)
        if summary[30] == 0.0 and abs(w_bit) > threshold:
            summary[30] = absolute
        if absolute >= window_start:
            summary[28] = min(summary[28], surface_torque)
            summary[29] = max(summary[29], surface_torque)
            if w_bit < summary[0]:
                summary[0] = w_bit
            if w_bit > summary[1]:
                summary[1] = w_bit
            summary[2] += top_speed
            summary[3] += 1.0
        if record_every > 0 and absolute % record_every == 0:
            row = absolute // record_every
            if row < records.shape[0]:
                records[row, 0] = w_bit
                records[row, 1] = bit_torque
                records[row, 2] = surface_torque
                records[row, 3] = top_speed
                records[row, 4] = motor
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
                crossed = summary[_COUNT] < 1.0 or t_cross - summary[_T_LAST] >= cycle_gap
            if not crossed:
                if summary[_COUNT] > 0.0:
                    summary[_RUN_MAX] = max(summary[_RUN_MAX], w_bit)
                    summary[_RUN_MIN] = min(summary[_RUN_MIN], w_bit)
                continue
            steady = _crossing(
                layout, spacing, P, M, heads, impedances, speeds, torques, cross, summary,
                w_bit, top_speed, t_cross, reference, t_end, window_length,
                steady_tolerance,
            )  # fmt: skip
            if steady:  # its extremes are those of the rest of the window
                summary[0] = min(summary[0], summary[_CYCLE_MIN])
                summary[1] = max(summary[1], summary[_CYCLE_MAX])
                summary[_ENDED] = absolute
                break
    summary[15] += taken
    summary[_BIT_TORQUE] = t_now
    _copy_nodes(layout, spacing, P, M, heads, p, m, False)
