"""The chain's forces, mass solve and top-drive elimination, for :mod:`torsio.solvers.rodas`.

The compiled form of :mod:`torsio.physics.dynamics`: the chain's torques in twist
coordinates (motor and bit included, and their time derivative for a set speed that
changes in time), the LU factors of the tridiagonal [I], and the elimination of the top
drive's controller states from the step's linear system (see the documentation of
:mod:`torsio.solvers.rodas`); the run's carried scalars. No allocation and no reference
counting: these run inside the step loop.
"""

from __future__ import annotations

import numpy as np

from torsio.physics.top_drive_boundary import controller_rates, limited, motor_torque
from torsio.solvers.compiled import HAVE_NUMBA, njit, njit_inner, numba
from torsio.solvers.layouts import (
    CARRY_ERR_ACCEPTED,
    CARRY_H,
    CARRY_H_ACCEPTED,
    CARRY_LAST_REJECTED,
    CARRY_REJECTED,
    CARRY_STATUS,
    CARRY_STEPS,
    CARRY_T,
    CHAIN_APPLIED,
    CHAIN_DAMPING,
    CHAIN_DAMPING_UPPER,
    CHAIN_DRAG,
    CHAIN_MASS,
    CHAIN_MASS_UPPER,
    CHAIN_STIFFNESS,
    CHAIN_STIFFNESS_UPPER,
    GAIN_E,
    GAIN_PIPE,
    GAIN_STATES,
    MAX_STATES,
    OUT_BIT_SPEED_MAX,
    OUT_BIT_SPEED_MIN,
    OUT_ENDED,
    OUT_REJECTED,
    OUT_STATUS,
    OUT_STEPS,
    OUT_TOP_SPEED_MEAN,
    RUN_T_END,
    RUN_WINDOW_START,
    SMALL_CARRY,
    SMALL_WINDOW,
    TOP_A,
    TOP_B,
    TOP_C,
    TOP_C_PIPE,
    TOP_HAS_NODE,
    TOP_K_PIPE,
    TOP_KP,
    TOP_MAX_TORQUE,
    TOP_PIPE_GAIN,
    TOP_SIZE,
    TOP_STATES,
    TOP_U0,
    TOP_W,
    WINDOW_BIT_MAX,
    WINDOW_BIT_MIN,
    WINDOW_DONE,
    WINDOW_NEXT_SAMPLE,
    WINDOW_TOP_INTEGRAL,
)

__all__ = [
    "accelerations",
    "compiled_controller_rates",
    "compiled_motor_torque",
    "controller_solve",
    "finish_run",
    "forces",
    "mass_factors",
    "sample_state",
    "saturated",
    "set_speed_rates",
    "store_carry",
    "store_window",
]


if HAVE_NUMBA:  # np.clip of floats, as numba compiles it (numpy's is for arrays)

    @numba.extending.overload(limited)
    def _limited(torque, max_torque):
        return lambda torque, max_torque: min(max(torque, -max_torque), max_torque)


# the controller's one evaluation (physics/top_drive_boundary.py), compiled as it is written
_FLAGS = {"cache": True, "error_model": "numpy", "_nrt": False}
compiled_motor_torque = njit(**_FLAGS)(motor_torque)
compiled_controller_rates = njit(**_FLAGS)(controller_rates)


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def packed_motor_torque(top, z, error, pipe):
    """(u, u_free) [N m] of the packed top drive ``top`` (``TOP_*``) at the speed error
    ``error`` [rad/s] and the pipe torque ``pipe`` [N m]."""
    return compiled_motor_torque(
        top[TOP_U0], top[TOP_KP], top[TOP_PIPE_GAIN], top[TOP_MAX_TORQUE], int(top[TOP_STATES]),
        top[TOP_C:TOP_W], z, error, pipe,
    )  # fmt: skip


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def forces(
    chain, top, torque, p, wob, radius, omega, set_speed, top_twist, phi, v, z, fv, fz
) -> float:  # fmt: skip
    """fv = chain forces (motor and bit included), fz = z'; returns the bit speed.

    ``set_speed``: Omega_set [rad/s] now (NaN: none); ``top_twist``: a held top's psi [rad]
    now, its angle beyond Omega_ref t (:mod:`torsio.solvers.set_speed`), which with the
    top's speed less Omega_ref drives node 0 through the top spring and damper (no force
    at a constant set speed)."""
    n = phi.size
    for i in range(n):
        fv[i] = (
            chain[CHAIN_APPLIED, i]
            - chain[CHAIN_DRAG, i] * omega
            - chain[CHAIN_STIFFNESS, i] * phi[i]
            - chain[CHAIN_DAMPING, i] * v[i]
        )
    for i in range(n - 1):
        fv[i] -= (
            chain[CHAIN_STIFFNESS_UPPER, i] * phi[i + 1] + chain[CHAIN_DAMPING_UPPER, i] * v[i + 1]
        )
        fv[i + 1] -= chain[CHAIN_STIFFNESS_UPPER, i] * phi[i] + chain[CHAIN_DAMPING_UPPER, i] * v[i]
    bit_speed = omega + v[n - 1]
    fv[n - 1] -= torque(p, bit_speed, wob, radius)
    if top[TOP_HAS_NODE] != 0.0:
        m = int(top[TOP_STATES])
        error = set_speed - (omega + v[0]) if set_speed == set_speed else 0.0
        pipe = top[TOP_K_PIPE] * (phi[0] - phi[1]) + top[TOP_C_PIPE] * (v[0] - v[1])
        u, free = packed_motor_torque(top, z, error, pipe)
        fv[0] += u
        compiled_controller_rates(
            m, MAX_STATES, top[TOP_A:TOP_B], top[TOP_B:TOP_C], top[TOP_W:TOP_SIZE], z, error,
            pipe, u, free, fz,
        )  # fmt: skip
    else:
        fv[0] += top[TOP_K_PIPE] * top_twist + top[TOP_C_PIPE] * (set_speed - omega)
    return bit_speed


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def set_speed_rates(top, omega, set_speed, rate, saturated, fz_rate) -> float:
    """d/dt at a fixed state of the forces a set speed changing at ``rate`` [rad/s^2] puts
    on node 0 (returned, [N m/s]) and of z' (into ``fz_rate``): the time derivative
    RODAS4 takes for a non-autonomous system. A held top: k_t (Omega_set - Omega_ref) +
    c_t rate; a controller: its gains on the speed error e, times the rate."""
    if top[TOP_HAS_NODE] == 0.0:
        return top[TOP_K_PIPE] * (set_speed - omega) + top[TOP_C_PIPE] * rate
    if set_speed != set_speed:  # no set speed
        rate = 0.0
    for j in range(int(top[TOP_STATES])):
        fz_rate[j] = (
            top[TOP_B + 2 * j] - (top[TOP_W + j] * top[TOP_KP] if saturated else 0.0)
        ) * rate
    return 0.0 if saturated else top[TOP_KP] * rate


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def mass_factors(chain, mpiv, mlow) -> None:
    """LU factors of the tridiagonal [I] (no pivoting: it is positive definite)."""
    md, mu = chain[CHAIN_MASS], chain[CHAIN_MASS_UPPER]
    mpiv[0] = md[0]
    for i in range(1, md.size):
        mlow[i] = mu[i - 1] / mpiv[i - 1]
        mpiv[i] = md[i] - mlow[i] * mu[i - 1]


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def accelerations(chain, mpiv, mlow, fv, acc) -> None:
    """acc = [I]^-1 fv from the factors of :func:`mass_factors`."""
    n = fv.size
    mu = chain[CHAIN_MASS_UPPER]
    acc[0] = fv[0]
    for i in range(1, n):
        acc[i] = fv[i] - mlow[i] * acc[i - 1]
    acc[n - 1] /= mpiv[n - 1]
    for i in range(n - 2, -1, -1):
        acc[i] = (acc[i] - mu[i] * acc[i + 1]) / mpiv[i]


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def controller_solve(top, g, saturated, q, zy, gains, work) -> None:
    """q = (I/g - Z_z)^-1, zy = Z_y and gains = (G_e, G_T, r_0.., r_m-1) of the elimination.

    Z_z = dz'/dz, Z_y = dz'/dy, U_z = du/dz, U_y = du/dy (zero when saturated);
    G = U_y + U_z q Z_y and r = U_z q (see the module documentation).
    """
    m = int(top[TOP_STATES])
    work[:] = 0.0
    for j in range(m):
        for k in range(m):
            zz = top[TOP_A + MAX_STATES * j + k]
            if saturated:
                zz -= top[TOP_W + j] * top[TOP_C + k]
            work[j, k] = (1.0 / g if j == k else 0.0) - zz
            work[j, MAX_STATES + k] = 1.0 if j == k else 0.0
    for col in range(m):  # Gauss-Jordan with partial pivoting on at most 3 x 3
        best = col
        for r in range(col + 1, m):
            if abs(work[r, col]) > abs(work[best, col]):
                best = r
        for k in range(2 * MAX_STATES):
            work[col, k], work[best, k] = work[best, k], work[col, k]
        inverse = 1.0 / work[col, col]
        for k in range(2 * MAX_STATES):
            work[col, k] *= inverse
        for r in range(m):
            if r != col:
                factor = work[r, col]
                for k in range(2 * MAX_STATES):
                    work[r, k] -= factor * work[col, k]
    for j in range(m):
        for k in range(m):
            q[j, k] = work[j, MAX_STATES + k]
    uy_e = 0.0 if saturated else top[TOP_KP]
    uy_t = 0.0 if saturated else top[TOP_PIPE_GAIN]
    gains[GAIN_E] = uy_e
    gains[GAIN_PIPE] = uy_t
    for k in range(m):
        row_gain = 0.0
        if not saturated:
            for j in range(m):
                row_gain += top[TOP_C + j] * q[j, k]
        gains[GAIN_STATES + k] = row_gain
        zy[k, 0] = top[TOP_B + 2 * k] - (top[TOP_W + k] * top[TOP_KP] if saturated else 0.0)
        zy[k, 1] = top[TOP_B + 2 * k + 1] - (
            top[TOP_W + k] * top[TOP_PIPE_GAIN] if saturated else 0.0
        )
    for k in range(m):
        gains[GAIN_E] += gains[GAIN_STATES + k] * zy[k, 0]
        gains[GAIN_PIPE] += gains[GAIN_STATES + k] * zy[k, 1]


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def saturated(top, omega, set_speed, phi, v, z) -> bool:
    if top[TOP_HAS_NODE] == 0.0 or not top[TOP_MAX_TORQUE] < np.inf:
        return False
    error = set_speed - (omega + v[0]) if set_speed == set_speed else 0.0
    pipe = top[TOP_K_PIPE] * (phi[0] - phi[1]) + top[TOP_C_PIPE] * (v[0] - v[1])
    u, free = packed_motor_torque(top, z, error, pipe)
    return u != free


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def sample_state(row, phi, v, z, n, m) -> None:
    """The state [z, phi_0, v_0, ...] at a step's end, into one row of the output."""
    for i in range(m):
        row[i] = z[i]
    for i in range(n):
        row[m + 2 * i] = phi[i]
        row[m + 2 * i + 1] = v[i]


@njit(cache=True, error_model="numpy", _nrt=False)
def finish_run(settings, omega, has_top, small, out) -> None:
    """A run's results (``out``, :mod:`torsio.solvers.layouts`) from its carried scalars."""
    carry, window = small[SMALL_CARRY], small[SMALL_WINDOW]
    t_end, t_window = settings[RUN_T_END], settings[RUN_WINDOW_START]
    out[OUT_BIT_SPEED_MAX] = window[WINDOW_BIT_MAX] + omega
    out[OUT_BIT_SPEED_MIN] = window[WINDOW_BIT_MIN] + omega
    out[OUT_STEPS] = carry[CARRY_STEPS]
    out[OUT_REJECTED] = carry[CARRY_REJECTED]
    out[OUT_STATUS] = carry[CARRY_STATUS]
    mean = window[WINDOW_TOP_INTEGRAL] / (t_end - t_window) if has_top else 0.0
    out[OUT_TOP_SPEED_MEAN] = omega + mean
    out[OUT_ENDED] = carry[CARRY_T]


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def store_carry(
    carry, t, h, h_accepted, err_accepted, last_rejected, steps, rejected, status
) -> None:
    """The stepper's state between two :func:`advance` calls into its row ``carry``:
    time [s], next step [s], last accepted step [s] and its error norm, whether the last
    step was rejected, the accepted and rejected step counts and the run's status."""
    carry[CARRY_T] = t
    carry[CARRY_H] = h
    carry[CARRY_H_ACCEPTED] = h_accepted
    carry[CARRY_ERR_ACCEPTED] = err_accepted
    carry[CARRY_LAST_REJECTED] = 1.0 if last_rejected else 0.0
    carry[CARRY_STEPS] = steps
    carry[CARRY_REJECTED] = rejected
    carry[CARRY_STATUS] = status


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def store_window(window, bit_max, bit_min, top_integral, next_sample, done) -> None:
    """What the steady window has read so far into its row ``window``: the bit speed's
    extremes [rad/s], the integral of the top speed [rad], the next output sample, and
    whether the window is done."""
    window[WINDOW_BIT_MAX] = bit_max
    window[WINDOW_BIT_MIN] = bit_min
    window[WINDOW_TOP_INTEGRAL] = top_integral
    window[WINDOW_NEXT_SAMPLE] = next_sample
    window[WINDOW_DONE] = 1.0 if done else 0.0
