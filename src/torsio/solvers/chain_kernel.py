"""The chain's forces, mass solve and top-drive elimination, for :mod:`torsio.solvers.rodas`.

The compiled form of :mod:`torsio.physics.dynamics`: the chain's torques in twist
coordinates (motor and bit included), the LU factors of the tridiagonal [I], and the
elimination of the top drive's controller states from the step's linear system (see the
documentation of :mod:`torsio.solvers.rodas`). No allocation and no reference counting:
these run inside the step loop.
"""

from __future__ import annotations

import numpy as np

from torsio.solvers.compiled import njit
from torsio.solvers.layouts import (
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
    TOP_STATES,
    TOP_U0,
    TOP_W,
    WINDOW_BIT_MAX,
    WINDOW_BIT_MIN,
    WINDOW_TOP_INTEGRAL,
)

__all__ = [
    "accelerations",
    "controller_solve",
    "finish_run",
    "forces",
    "mass_factors",
    "sample_state",
    "saturated",
]


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def forces(chain, top, torque, p, wob, radius, omega, omega_set, phi, v, z, fv, fz) -> float:
    """fv = chain forces (motor and bit included), fz = z'; returns the bit speed."""
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
        error = omega_set - (omega + v[0]) if omega_set == omega_set else 0.0
        pipe = top[TOP_K_PIPE] * (phi[0] - phi[1]) + top[TOP_C_PIPE] * (v[0] - v[1])
        free = top[TOP_U0] + top[TOP_KP] * error + top[TOP_PIPE_GAIN] * pipe
        for j in range(m):
            free += top[TOP_C + j] * z[j]
        u = min(max(free, -top[TOP_MAX_TORQUE]), top[TOP_MAX_TORQUE])
        fv[0] += u
        for j in range(m):
            s = top[TOP_B + 2 * j] * error + top[TOP_B + 2 * j + 1] * pipe
            s += top[TOP_W + j] * (u - free)
            for q in range(m):
                s += top[TOP_A + MAX_STATES * j + q] * z[q]
            fz[j] = s
    return bit_speed


@njit(cache=True, error_model="numpy", _nrt=False)
def mass_factors(chain, mpiv, mlow) -> None:
    """LU factors of the tridiagonal [I] (no pivoting: it is positive definite)."""
    md, mu = chain[CHAIN_MASS], chain[CHAIN_MASS_UPPER]
    mpiv[0] = md[0]
    for i in range(1, md.size):
        mlow[i] = mu[i - 1] / mpiv[i - 1]
        mpiv[i] = md[i] - mlow[i] * mu[i - 1]


@njit(cache=True, error_model="numpy", _nrt=False)
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


@njit(cache=True, error_model="numpy", _nrt=False)
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


@njit(cache=True, error_model="numpy", _nrt=False)
def saturated(top, omega, omega_set, phi, v, z) -> bool:
    if top[TOP_HAS_NODE] == 0.0 or not top[TOP_MAX_TORQUE] < np.inf:
        return False
    error = omega_set - (omega + v[0]) if omega_set == omega_set else 0.0
    pipe = top[TOP_K_PIPE] * (phi[0] - phi[1]) + top[TOP_C_PIPE] * (v[0] - v[1])
    free = top[TOP_U0] + top[TOP_KP] * error + top[TOP_PIPE_GAIN] * pipe
    for j in range(int(top[TOP_STATES])):
        free += top[TOP_C + j] * z[j]
    return abs(free) > top[TOP_MAX_TORQUE]


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
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
