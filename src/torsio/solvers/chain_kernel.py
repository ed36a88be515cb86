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

__all__ = ["TOP_SIZE", "accelerations", "controller_solve", "forces", "mass_factors", "saturated"]

# the top-drive vector: [has node, m, u0, max_torque, k1, c1, d_e, d_T, a (3x3), b (3x2), c, w]
_A0, _B0, _C0, _W0 = 8, 17, 23, 26
TOP_SIZE = 29


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def forces(chain, top, torque, p, wob, radius, omega, omega_set, phi, v, z, fv, fz) -> float:
    """fv = chain forces (motor and bit included), fz = z'; returns the bit speed."""
    n = phi.size
    for i in range(n):
        fv[i] = chain[7, i] - chain[6, i] * omega - chain[2, i] * phi[i] - chain[4, i] * v[i]
    for i in range(n - 1):
        fv[i] -= chain[3, i] * phi[i + 1] + chain[5, i] * v[i + 1]
        fv[i + 1] -= chain[3, i] * phi[i] + chain[5, i] * v[i]
    bit_speed = omega + v[n - 1]
    fv[n - 1] -= torque(p, bit_speed, wob, radius)
    if top[0] != 0.0:
        m = int(top[1])
        error = omega_set - (omega + v[0]) if omega_set == omega_set else 0.0
        pipe = top[4] * (phi[0] - phi[1]) + top[5] * (v[0] - v[1])
        free = top[2] + top[6] * error + top[7] * pipe
        for j in range(m):
            free += top[_C0 + j] * z[j]
        u = min(max(free, -top[3]), top[3])
        fv[0] += u
        for j in range(m):
            s = top[_B0 + 2 * j] * error + top[_B0 + 2 * j + 1] * pipe
            s += top[_W0 + j] * (u - free)
            for q in range(m):
                s += top[_A0 + 3 * j + q] * z[q]
            fz[j] = s
    return bit_speed


@njit(cache=True, error_model="numpy", _nrt=False)
def mass_factors(chain, mpiv, mlow) -> None:
    """LU factors of the tridiagonal [I] (no pivoting: it is positive definite)."""
    md, mu = chain[0], chain[1]
    mpiv[0] = md[0]
    for i in range(1, md.size):
        mlow[i] = mu[i - 1] / mpiv[i - 1]
        mpiv[i] = md[i] - mlow[i] * mu[i - 1]


@njit(cache=True, error_model="numpy", _nrt=False)
def accelerations(chain, mpiv, mlow, fv, acc) -> None:
    """acc = [I]^-1 fv from the factors of :func:`mass_factors`."""
    n = fv.size
    mu = chain[1]
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
    m = int(top[1])
    work[:] = 0.0
    for j in range(m):
        for k in range(m):
            zz = top[_A0 + 3 * j + k]
            if saturated:
                zz -= top[_W0 + j] * top[_C0 + k]
            work[j, k] = (1.0 / g if j == k else 0.0) - zz
            work[j, 3 + k] = 1.0 if j == k else 0.0
    for col in range(m):  # Gauss-Jordan with partial pivoting on at most 3 x 3
        best = col
        for r in range(col + 1, m):
            if abs(work[r, col]) > abs(work[best, col]):
                best = r
        for k in range(6):
            work[col, k], work[best, k] = work[best, k], work[col, k]
        inverse = 1.0 / work[col, col]
        for k in range(6):
            work[col, k] *= inverse
        for r in range(m):
            if r != col:
                factor = work[r, col]
                for k in range(6):
                    work[r, k] -= factor * work[col, k]
    for j in range(m):
        for k in range(m):
            q[j, k] = work[j, 3 + k]
    uy_e = 0.0 if saturated else top[6]
    uy_t = 0.0 if saturated else top[7]
    gains[0] = uy_e
    gains[1] = uy_t
    for k in range(m):
        row_gain = 0.0
        if not saturated:
            for j in range(m):
                row_gain += top[_C0 + j] * q[j, k]
        gains[2 + k] = row_gain
        zy[k, 0] = top[_B0 + 2 * k] - (top[_W0 + k] * top[6] if saturated else 0.0)
        zy[k, 1] = top[_B0 + 2 * k + 1] - (top[_W0 + k] * top[7] if saturated else 0.0)
    for k in range(m):
        gains[0] += gains[2 + k] * zy[k, 0]
        gains[1] += gains[2 + k] * zy[k, 1]


@njit(cache=True, error_model="numpy", _nrt=False)
def saturated(top, omega, omega_set, phi, v, z) -> bool:
    if top[0] == 0.0 or not top[3] < np.inf:
        return False
    error = omega_set - (omega + v[0]) if omega_set == omega_set else 0.0
    free = top[2] + top[6] * error + top[7] * (top[4] * (phi[0] - phi[1]) + top[5] * (v[0] - v[1]))
    for j in range(int(top[1])):
        free += top[_C0 + j] * z[j]
    return abs(free) > top[3]
