"""Time stepping of the distributed model along characteristics (:mod:`torsio.model.wave`).

One step of length dt:

1. **transport**: in every section the invariant p = T + Z w moves one node down and
   m = T - Z w one node up (exact: the grid matches the wave speed);
2. **junctions**: speed and torque continuous, so with the incoming p (from above) and
   m (from below) ``w = (p - m) / (Z1 + Z2)``, ``T = (Z2 p + Z1 m) / (Z1 + Z2)`` and the
   outgoing invariants follow (exact);
3. **top**: held at Omega (outgoing p = m + 2 Z Omega, a reflection R = -1), or a top drive
   (inertia and linear controller, :class:`torsio.physics.top_drives.TopDriveBoundary`)
   integrated by the trapezoidal rule with the incoming m linear over the step; a motor
   torque beyond ``max_torque`` is held at the limit for the step (back-calculation
   anti-windup as the description gives it);
4. **bit**: the bit's inertia J_b with torque on bit T_bit(w_b), drag alpha J_b and the
   pipe torque p - Z w_b, by BDF2 (backward Euler on the first step), an L-stable
   second-order rule: the bit's own time scale J_b / Z (about 2e-4 s for the Ritto
   string) is far below dt. Each step solves one scalar equation
   k w + T_bit(w) = r (k > 0) by bracketing from the previous speed in the direction of
   motion and safeguarded Newton (to 1e-12 relative);
5. **distributed drag** d = alpha rho J: the speed at every node decays by exp(-alpha dt)
   with the torque unchanged, applied as half steps around 1-4 (Strang splitting,
   second order; consecutive half steps are merged).

The stored state is half a drag step behind the sampled one (T unchanged, w smaller by
exp(-alpha dt / 2)). The top and the bit act on the sampled state: the top speed and the
bit speed are node speeds there, so for a stored incoming invariant T = m + Z' w at the
top and T = p - Z' w at the bit, with Z' = Z exp(alpha dt / 2). (Applying them to the
stored state instead moves the boundary speeds by alpha dt / 2, a first-order error in
the boundary power: 3e-4 of the work at dt = 4 ms.)

Energy: exact transport and junctions change the string's energy by the trapezoidal
rule of the boundary powers, the drag steps by (1 - exp(-alpha dt)) of the kinetic
energy; the kernel sums every power by the trapezoidal rule, so work in = stored +
dissipated to O(dt^2) for a continuous top speed. A jump in speed reaching the bit
(a held top started from rest) is not resolved when dt >> J_b / Z: BDF2 then loses
about J_b dw^2 / 2 of energy for a jump dw of the bit speed.

The step is compiled with numba (cache=True) when the law brings a compiled kernel
(:func:`torsio.solvers.law_kernels.law_kernel`); otherwise the same algorithm runs on
numpy arrays with the law's Python ``torque`` and ``slope``.
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.model.wave import WaveModel
from torsio.solvers.wave_top import TopArrays

try:  # numba is optional: without it the same steps run as plain Python (slowly)
    from numba import njit, types

    _F8 = types.float64
    _VECTOR = types.float64[::1]
    _LAW = types.FunctionType(_F8(_VECTOR, _F8, _F8, _F8))
    _SOLVE_SIGNATURE: Any = _F8(_F8, _F8, _F8, _LAW, _LAW, _VECTOR, _F8, _F8)
    _MARCH_SIGNATURE: Any = types.void(
        types.int64[::1], _VECTOR, _VECTOR, _VECTOR, _VECTOR, _VECTOR, _VECTOR,
        types.float64[:, :, ::1], types.float64[:, ::1], types.float64[:, ::1], _VECTOR,
        _LAW, _LAW, _VECTOR, types.float64[:, ::1], types.float64[:, ::1], _VECTOR,
    )  # fmt: skip
except ImportError:  # pragma: no cover - exercised only without numba
    _SOLVE_SIGNATURE = _MARCH_SIGNATURE = None

    def njit(*args: Any, **kwargs: Any) -> Any:  # type: ignore[no-redef]
        """Stands in for numba.njit: the function runs as plain Python."""
        return lambda function: function


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

_NEWTON_TOLERANCE = 1e-12


@attrs.frozen(eq=False)
class WaveState:
    """State of the distributed model: invariants at every node, top and bit states.

    ``p`` and ``m`` hold every section's nodes (a junction node once per section),
    section s at ``offsets[s] .. offsets[s] + cells[s]``. ``bit`` = [w_b, w_b one step
    earlier, steps taken]. ``top`` = [Omega_0, z...] (empty when held).
    """

    p: np.ndarray
    m: np.ndarray
    top: np.ndarray
    bit: np.ndarray

    def copy(self) -> WaveState:
        """An independent copy."""
        return WaveState(self.p.copy(), self.m.copy(), self.top.copy(), self.bit.copy())


def node_offsets(grid: WaveModel) -> np.ndarray:
    """Start of each section's node block in the state arrays, and the total size."""
    return np.concatenate([[0], np.cumsum(np.array(grid.cells) + 1)]).astype(np.int64)


def rest_state(grid: WaveModel, top: TopArrays) -> WaveState:
    """Everything at rest: zero speed and torque along the string, top and bit still."""
    size = int(node_offsets(grid)[-1])
    return WaveState(np.zeros(size), np.zeros(size), np.zeros(max(top.states, 1)), np.zeros(3))


def state_from_fields(
    grid: WaveModel, speed: np.ndarray, torque: np.ndarray, top: TopArrays
) -> WaveState:
    """A state with angular speed [rad/s] and torque [N m] given at every node.

    ``speed`` and ``torque`` follow the state layout (:func:`node_offsets`); the bit
    starts at the speed of the last node.
    """
    state = rest_state(grid, top)
    z = np.repeat(grid.impedances, np.array(grid.cells) + 1)
    state.p[:] = torque + z * speed
    state.m[:] = torque - z * speed
    state.bit[:2] = speed[-1]
    if not top.held:
        state.top[0] = speed[0]
    return state


# --- the compiled step ----------------------------------------------------------------------
@njit(_SOLVE_SIGNATURE, cache=True, nogil=True)
def _solve_bit(k, rhs, guess, torque, slope, parameters, wob, radius):  # type: ignore[no-untyped-def,unused-ignore]
    """Root of k w + T_bit(w) = rhs nearest ``guess`` in the direction of motion."""
    f0 = k * guess + torque(parameters, guess, wob, radius) - rhs
    if f0 == 0.0:
        return guess
    direction = -1.0 if f0 > 0.0 else 1.0
    low = guess
    f_low = f0
    step = abs(f0) / k + 1e-9 * (abs(guess) + 1.0)
    high = guess + direction * step
    f_high = k * high + torque(parameters, high, wob, radius) - rhs
    tries = 0
    while (f_high > 0.0) == (f0 > 0.0):
        low, f_low = high, f_high
        step *= 2.0
        high = low + direction * step
        f_high = k * high + torque(parameters, high, wob, radius) - rhs
        tries += 1
        if tries > 200:
            return math.nan
    # safeguarded Newton in the bracket [low, high]
    w = high if abs(f_high) < abs(f_low) else low
    for _ in range(100):
        f = k * w + torque(parameters, w, wob, radius) - rhs
        if f == 0.0:
            return w
        if (f > 0.0) == (f_low > 0.0):
            low, f_low = w, f
        else:
            high = w
        derivative = k + slope(parameters, w, wob, radius)
        candidate = w - f / derivative if derivative != 0.0 else math.nan
        lo, hi = (low, high) if low < high else (high, low)
        if not (lo < candidate < hi):
            candidate = 0.5 * (low + high)
        if abs(candidate - w) <= _NEWTON_TOLERANCE * (abs(w) + 1e-6):
            return candidate
        w = candidate
    return w


@njit(cache=True, nogil=True)
def _transport(offsets, half_plus, half_minus, p, m, p_next, m_next):  # type: ignore[no-untyped-def,unused-ignore]
    """Drag step, then every invariant one node along its characteristic (into ``*_next``).

    A function of its own, on slices indexed from 0: the compiler then vectorizes the
    loop (no swapped buffers, no possibly negative index), about 5 times faster.
    """
    for s in range(offsets.size - 1):
        start = offsets[s]
        stop = offsets[s + 1]
        p_in = p[start:stop]
        m_in = m[start:stop]
        p_out = p_next[start:stop]
        m_out = m_next[start:stop]
        for j in range(stop - start - 1):
            p_out[j + 1] = half_plus * p_in[j] + half_minus * m_in[j]
            m_out[j] = half_minus * p_in[j + 1] + half_plus * m_in[j + 1]


@njit(_MARCH_SIGNATURE, cache=True, nogil=True)
def _march(  # type: ignore[no-untyped-def,unused-ignore]
    offsets, impedance, settings, p, m, top_state, bit_state,
    propagator, forcing, constant, coefficients,
    torque, slope, parameters, records, field, summary,
):  # fmt: skip
    """Advance ``settings[9]`` steps; see the module docstring. Works in place."""
    dt = settings[0]
    decay = settings[1]
    bit_inertia = settings[2]
    alpha = settings[3]
    wob = settings[4]
    radius = settings[5]
    held = settings[6] != 0.0
    set_speed = settings[7]
    max_torque = settings[8]
    steps = int(settings[9])
    window_start = int(settings[10])
    record_every = int(settings[11])
    field_every = int(settings[12])
    top_drag = settings[13]
    sections = impedance.size
    last = offsets[sections] - 1
    # the boundaries act on the sampled state, half a drag step ahead of the stored one:
    # there T = m + (Z / sqrt(decay)) w for the stored incoming m (module docstring)
    root_decay = math.sqrt(decay)
    z_top = impedance[0] / root_decay
    z_bit = impedance[sections - 1] / root_decay
    n_top = top_state.size
    half_plus = 0.5 * (1.0 + decay)
    half_minus = 0.5 * (1.0 - decay)
    # power at the previous step (trapezoidal energies)
    previous = np.zeros(5)
    previous[:] = summary[10:15]
    mode_x = np.zeros(n_top)
    p_next = np.empty_like(p)
    m_next = np.empty_like(m)
    track_energy = settings[14] != 0.0
    for step in range(steps):
        m_top_old = m[0]
        # 1. drag (merged half steps) fused with the transport: the stored state is half a
        # drag step behind the sampled one, so this is the Strang splitting D(1/2) T D(1/2)
        _transport(offsets, half_plus, half_minus, p, m, p_next, m_next)
        p, p_next = p_next, p
        m, m_next = m_next, m
        # 2. junctions
        for s in range(sections - 1):
            a = offsets[s + 1] - 1
            b = offsets[s + 1]
            z1 = impedance[s]
            z2 = impedance[s + 1]
            speed = (p[a] - m[b]) / (z1 + z2)
            tq = (z2 * p[a] + z1 * m[b]) / (z1 + z2)
            m[a] = tq - z1 * speed
            p[b] = tq + z2 * speed
        # 3. top
        m_in = m[0]
        if held:
            top_speed = set_speed
            motor = m_in + z_top * set_speed
        else:
            chosen = 0
            for mode in range(3):
                for i in range(n_top):
                    acc = constant[mode, i] + forcing[mode, i] * (m_top_old + m_in)
                    for j in range(n_top):
                        acc += propagator[mode, i, j] * top_state[j]
                    mode_x[i] = acc
                u_free = coefficients[0] + coefficients[n_top + 1] * m_in
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
        p[0] = m_in + 2.0 * z_top * top_speed
        surface_torque = m_in + z_top * top_speed
        # 4. bit
        p_in = p[last]
        w_now = bit_state[0]
        if bit_state[2] < 1.0:
            k = bit_inertia / dt + z_bit + alpha * bit_inertia
            rhs = bit_inertia * w_now / dt + p_in
        else:
            k = 1.5 * bit_inertia / dt + z_bit + alpha * bit_inertia
            rhs = bit_inertia * (4.0 * w_now - bit_state[1]) / (2.0 * dt) + p_in
        w_bit = _solve_bit(k, rhs, w_now, torque, slope, parameters, wob, radius)
        if not math.isfinite(w_bit):
            summary[9] = step + 1.0
            return
        bit_state[1] = w_now
        bit_state[0] = w_bit
        bit_state[2] += 1.0
        m[last] = p_in - 2.0 * z_bit * w_bit
        bit_torque = torque(parameters, w_bit, wob, radius)
        # 5. the string's drag power alpha rho J dx w^2 = alpha dt (p - m)^2 / (4 Z) at this
        # step (the state is half a drag step ahead: w^2 times exp(-alpha dt) ... undone)
        drag_power = 0.0
        if track_energy and alpha > 0.0:
            for s in range(sections):
                start = offsets[s]
                stop = offsets[s + 1] - 1
                acc = 0.0
                for j in range(start, stop + 1):
                    difference = p[j] - m[j]
                    acc += difference * difference
                d0 = p[start] - m[start]
                d1 = p[stop] - m[stop]
                acc -= 0.5 * (d0 * d0 + d1 * d1)
                drag_power += alpha * dt * acc / (4.0 * impedance[s])
            drag_power *= decay
        # energies (trapezoidal in time)
        power_in = motor * top_speed if not held else surface_torque * top_speed
        power_bit = bit_torque * w_bit
        power_bit_drag = alpha * bit_inertia * w_bit * w_bit
        power_top_drag = top_drag * top_speed * top_speed
        summary[4] += 0.5 * dt * (previous[0] + power_in)
        summary[5] += 0.5 * dt * (previous[1] + power_bit)
        summary[6] += 0.5 * dt * (previous[2] + power_bit_drag)
        summary[7] += 0.5 * dt * (previous[3] + drag_power)
        summary[8] += 0.5 * dt * (previous[4] + power_top_drag)
        previous[0] = power_in
        previous[1] = power_bit
        previous[2] = power_bit_drag
        previous[3] = drag_power
        previous[4] = power_top_drag
        # window extremes and records
        absolute = int(summary[15]) + step + 1
        if absolute >= window_start:
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
                for s in range(sections):
                    z = impedance[s]
                    for j in range(offsets[s], offsets[s + 1]):
                        field[row, j] = root_decay * (p[j] - m[j]) / (2.0 * z)
    summary[10] = previous[0]
    summary[11] = previous[1]
    summary[12] = previous[2]
    summary[13] = previous[3]
    summary[14] = previous[4]
    summary[15] += steps
    if steps % 2 == 1:  # the buffers were swapped an odd number of times
        p_next[:] = p
        m_next[:] = m
