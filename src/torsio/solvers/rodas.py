"""The compiled batch kernel: RODAS4 on the chain of :mod:`torsio.physics.dynamics`.

One kernel for every chain length, bit-rock law and top drive. The chain (n nodes,
node n-1 the bit) in twist coordinates about Omega_ref, with [C] = [C_rel] + diag(drag)::

    phi' = v
    [I] v' = applied - drag Omega_ref - [K] phi - [C] v - T_bit(Omega_ref + v_{n-1}) e_{n-1} + u e_0
    z'     = a z + b y + w (u - u_free),   u_free = u0 + c.z + d.y,   u = clip(u_free, +-max)

with y = [e, T_pipe], e = Omega_set - Omega_0, T_pipe = k_1 (phi_0 - phi_1) + c_1 (v_0 - v_1);
u, z and y only with a top-drive node.

RODAS4 (Hairer and Wanner, *Solving ODEs II*, IV.7; ``rodas.f``, METH = 1): six stages, each
a linear solve with ``M/(gamma h) - J`` (J exact at the start of the step). Eliminating the
twist increments and the controller increments (m <= 3: they act on nodes 0 and 1 only)
leaves an n x n tridiagonal matrix, factored once per step in O(n) without pivoting.
Per-point step control: RMS of ``err_i / (atol + rtol max(|y_i|, |y_new_i|))`` over every
state <= 1, Gustafsson's predictive controller, steps capped at ``hmax``.

The extremes of the bit speed in the steady window come from the cubic Hermite
interpolant of each step (values and accelerations at both ends); the mean top-drive speed
over the window (for a torque-driven top) is the integral of the same interpolant.

The law enters through two first-class functions of signature
:data:`torsio.solvers.law_kernels.LAW_SIGNATURE`; the kernels below have explicit
signatures, so numba compiles and caches them once for every law.
"""

from __future__ import annotations

import math

import numpy as np

from torsio.solvers.compiled import kernel_signature, njit, prange

__all__ = [
    "GAMMA",
    "OUT_COLUMNS",
    "RODAS_A",
    "RODAS_C",
    "TOP_SIZE",
    "extremes_of_cubic",
    "integrate_parallel",
    "integrate_serial",
]

# --- RODAS4 (Hairer and Wanner, Solving ODEs II, Sec. IV.7; rodas.f, METH = 1) --------------
GAMMA = 0.25
RODAS_A = np.zeros((6, 6))
RODAS_A[1, 0] = 1.544
RODAS_A[2, :2] = (0.9466785280815826, 0.2557011698983284)
RODAS_A[3, :3] = (3.314825187068521, 2.896124015972201, 0.9986419139977817)
RODAS_A[4, :4] = (1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895)
RODAS_A[5, :5] = (*RODAS_A[4, :4], 1.0)
RODAS_C = np.zeros((6, 6))
RODAS_C[1, 0] = -5.6688
RODAS_C[2, :2] = (-2.430093356833875, -0.2063599157091915)
RODAS_C[3, :3] = (-0.1073529058151375, -9.594562251023355, -20.47028614809616)
RODAS_C[4, :4] = (7.496443313967647, -10.24680431464352, -33.99990352819905, 11.70890893206160)
RODAS_C[5, :5] = (
    8.083246795921522,
    -7.981132988064893,
    -31.52159432874371,
    16.31930543123136,
    -6.058818238834054,
)
# y_new = (argument of stage 6) + k6 and the embedded error estimate is k6 itself.

OUT_COLUMNS = 6
"""Per point: bit speed max, min [rad/s], accepted, rejected steps, status, mean top speed."""

# the top-drive vector: [has node, m, u0, max_torque, k1, c1, d_e, d_T, a (3x3), b (3x2), c, w]
_A0, _B0, _C0, _W0 = 8, 17, 23, 26
TOP_SIZE = 29


@njit(cache=True)
def extremes_of_cubic(
    u0: float, u1: float, d0: float, d1: float, lo: float, vmax: float, vmin: float
) -> tuple[float, float]:
    """Max and min of the cubic Hermite interpolant on [lo, 1] (d0, d1 scaled by h)."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1
    ulo = u0 + lo * (d0 + lo * (c2 + lo * c3))
    vmax = max(vmax, ulo, u1)
    vmin = min(vmin, ulo, u1)
    a = 3.0 * c3  # u'(x) = d0 + 2 c2 x + 3 c3 x^2
    b = 2.0 * c2
    if abs(a) > 1e-14 * (abs(b) + abs(d0)):
        disc = b * b - 4.0 * a * d0
        if disc >= 0.0:
            sq = math.sqrt(disc)
            q = -0.5 * (b + math.copysign(sq, b))
            for root in (q / a, d0 / q if q != 0.0 else -1.0):
                if lo < root < 1.0:
                    u = u0 + root * (d0 + root * (c2 + root * c3))
                    vmax = max(vmax, u)
                    vmin = min(vmin, u)
    elif b != 0.0:
        root = -d0 / b
        if lo < root < 1.0:
            u = u0 + root * (d0 + root * (c2 + root * c3))
            vmax = max(vmax, u)
            vmin = min(vmin, u)
    return vmax, vmin


@njit(cache=True)
def _integral_of_cubic(u0: float, u1: float, d0: float, d1: float, lo: float) -> float:
    """Integral over x in [lo, 1] of the cubic Hermite interpolant (in units of the step)."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1
    upper = u0 + d0 / 2.0 + c2 / 3.0 + c3 / 4.0
    lower = lo * (u0 + lo * (d0 / 2.0 + lo * (c2 / 3.0 + lo * c3 / 4.0)))
    return upper - lower


@njit(cache=True)
def _forces(chain, top, torque, p, wob, radius, omega, omega_set, phi, v, z, fv, fz) -> float:
    """fv = chain forces (motor and bit included), fz = z'; returns the bit speed."""
    n = phi.size
    kd, ku, cd, cu, drag, applied = chain[2], chain[3], chain[4], chain[5], chain[6], chain[7]
    for i in range(n):
        fv[i] = applied[i] - drag[i] * omega - kd[i] * phi[i] - cd[i] * v[i]
    for i in range(n - 1):
        fv[i] -= ku[i] * phi[i + 1] + cu[i] * v[i + 1]
        fv[i + 1] -= ku[i] * phi[i] + cu[i] * v[i]
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


@njit(cache=True)
def _mass_factors(chain, mpiv, mlow) -> None:
    """LU factors of the tridiagonal [I] (no pivoting: it is positive definite)."""
    md, mu = chain[0], chain[1]
    mpiv[0] = md[0]
    for i in range(1, md.size):
        mlow[i] = mu[i - 1] / mpiv[i - 1]
        mpiv[i] = md[i] - mlow[i] * mu[i - 1]


@njit(cache=True)
def _accelerations(chain, mpiv, mlow, fv, acc) -> None:
    """acc = [I]^-1 fv from the factors of :func:`_mass_factors`."""
    n = fv.size
    mu = chain[1]
    acc[0] = fv[0]
    for i in range(1, n):
        acc[i] = fv[i] - mlow[i] * acc[i - 1]
    acc[n - 1] /= mpiv[n - 1]
    for i in range(n - 2, -1, -1):
        acc[i] = (acc[i] - mu[i] * acc[i + 1]) / mpiv[i]


@njit(cache=True)
def _controller_solve(top, g, saturated, q, zy, gains) -> None:
    """q = (I/g - Z_z)^-1, zy = Z_y and gains = (G_e, G_T, r_0.., r_m-1) of the elimination.

    Z_z = dz'/dz, Z_y = dz'/dy, U_z = du/dz, U_y = du/dy (zero when saturated);
    G = U_y + U_z q Z_y and r = U_z q (see the module documentation).
    """
    m = int(top[1])
    work = np.zeros((3, 6))
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


@njit(cache=True)
def _saturated(top, omega, omega_set, phi, v, z) -> bool:
    if top[0] == 0.0 or not top[3] < np.inf:
        return False
    error = omega_set - (omega + v[0]) if omega_set == omega_set else 0.0
    free = top[2] + top[6] * error + top[7] * (top[4] * (phi[0] - phi[1]) + top[5] * (v[0] - v[1]))
    for j in range(int(top[1])):
        free += top[_C0 + j] * z[j]
    return abs(free) > top[3]


@njit(cache=True)
def _integrate_point(chain, top, torque, slope, p, settings, wob, omega, omega_set, out) -> None:
    """RODAS4 from rest to t_end; ``out`` gets the :data:`OUT_COLUMNS` of the point."""
    t_end, t_window, rtol, atol, h0, hmax = (
        settings[0],
        settings[1],
        settings[2],
        settings[3],
        settings[4],
        settings[5],
    )
    max_steps = int(settings[6])
    radius = settings[7]
    n = chain.shape[1]
    md, mu, kd, ku, cd, cu = chain[0], chain[1], chain[2], chain[3], chain[4], chain[5]
    has_top = top[0] != 0.0
    m = int(top[1])
    k1, c1 = top[4], top[5]
    size = 2 * n + m
    phi = np.zeros(n)
    v = np.full(n, -omega)  # start-up from rest: theta' = 0, controller states 0
    z = np.zeros(3)
    kphi = np.zeros((6, n))
    kv = np.zeros((6, n))
    kz = np.zeros((6, 3))
    aphi = np.empty(n)
    av = np.empty(n)
    az = np.zeros(3)
    fphi = np.empty(n)
    fv = np.empty(n)
    fz = np.zeros(3)
    f0v = np.empty(n)
    f0z = np.zeros(3)
    uphi = np.empty(n)
    uv = np.empty(n)
    uz = np.zeros(3)
    x = np.empty(n)
    ipiv = np.empty(n)
    low = np.zeros(n)
    band = np.zeros(n)
    acc = np.empty(n)
    mpiv = np.empty(n)
    mlow = np.zeros(n)
    q = np.zeros((3, 3))
    zy = np.zeros((3, 2))
    gains = np.zeros(5)
    _mass_factors(chain, mpiv, mlow)
    tiny = 1e-12 * max(1.0, t_end)

    _forces(chain, top, torque, p, wob, radius, omega, omega_set, phi, v, z, f0v, f0z)
    _accelerations(chain, mpiv, mlow, f0v, acc)
    bit_acc0 = acc[n - 1]
    top_acc0 = acc[0]
    t = 0.0
    h = min(h0, hmax, t_end)
    vmax = -np.inf
    vmin = np.inf
    top_integral = 0.0
    steps = 0
    rejected = 0
    status = 0
    last_rejected = False
    h_accepted = h
    err_accepted = 1.0
    while t < t_end:
        if steps >= max_steps:
            status = 1
            break
        if h < tiny:
            status = 2
            break
        if t + h > t_end:
            h = t_end - t
        g = GAMMA * h
        s = slope(p, omega + v[n - 1], wob, radius)
        diag0 = 0.0
        extra01 = 0.0
        if has_top:  # eliminate the controller increments into rows 0 and 1
            saturated = _saturated(top, omega, omega_set, phi, v, z)
            _controller_solve(top, g, saturated, q, zy, gains)
            extra01 = gains[1] * (g * k1 + c1)
            diag0 = gains[0] - extra01
        # factor [I]/g + [C] + g [K] + s e_N e_N^T (+ the top drive's row-0 terms)
        singular = False
        for i in range(n):
            band[i] = mu[i] / g + cu[i] + g * ku[i]
        for i in range(n):
            a = md[i] / g + cd[i] + g * kd[i]
            scale = md[i] / g + abs(cd[i]) + g * kd[i]
            if i == n - 1:
                a += s
            if i == 0:
                a += diag0
            if i > 0:
                low[i] = band[i - 1] * ipiv[i - 1]
                a -= low[i] * (band[i - 1] + (extra01 if i == 1 else 0.0))
            if not abs(a) > 1e-13 * scale:
                singular = True
                a = 1.0
            ipiv[i] = 1.0 / a
        if singular:
            h *= 0.5
            rejected += 1
            last_rejected = True
            continue
        for stage in range(6):
            # argument y0 + sum_j a_ij k_j and mass-matrix term sum_j c_ij k_j / h
            for i in range(n):
                aphi[i] = phi[i]
                av[i] = v[i]
                uphi[i] = 0.0
                uv[i] = 0.0
            for i in range(m):
                az[i] = z[i]
                uz[i] = 0.0
            for j in range(stage):
                a_ij = RODAS_A[stage, j]
                c_ij = RODAS_C[stage, j] / h
                for i in range(n):
                    aphi[i] += a_ij * kphi[j, i]
                    av[i] += a_ij * kv[j, i]
                    uphi[i] += c_ij * kphi[j, i]
                    uv[i] += c_ij * kv[j, i]
                for i in range(m):
                    az[i] += a_ij * kz[j, i]
                    uz[i] += c_ij * kz[j, i]
            if stage == 0:
                for i in range(n):
                    fphi[i] = v[i]
                    fv[i] = f0v[i]
                for i in range(m):
                    fz[i] = f0z[i]
            else:
                _forces(chain, top, torque, p, wob, radius, omega, omega_set, aphi, av, az, fv, fz)
                for i in range(n):
                    fphi[i] = av[i] + uphi[i]
                    fv[i] += md[i] * uv[i]
                for i in range(n - 1):
                    fv[i] += mu[i] * uv[i + 1]
                    fv[i + 1] += mu[i] * uv[i]
                for i in range(m):
                    fz[i] += uz[i]
            # speeds: A x = f_v - g [K] f_phi (+ top-drive terms); twists: k_phi = g (f_phi + x)
            for i in range(n):
                x[i] = fv[i] - g * kd[i] * fphi[i]
            for i in range(n - 1):
                x[i] -= g * ku[i] * fphi[i + 1]
                x[i + 1] -= g * ku[i] * fphi[i]
            if has_top:
                x[0] += gains[1] * k1 * g * (fphi[0] - fphi[1])
                for k in range(m):
                    x[0] += gains[2 + k] * fz[k]
            for i in range(1, n):
                x[i] -= low[i] * x[i - 1]
            x[n - 1] *= ipiv[n - 1]
            for i in range(n - 2, -1, -1):
                x[i] = (x[i] - (band[i] + (extra01 if i == 0 else 0.0)) * x[i + 1]) * ipiv[i]
            for i in range(n):
                kv[stage, i] = x[i]
                kphi[stage, i] = g * (fphi[i] + x[i])
            if m:
                dy_e = -x[0]
                dy_t = k1 * (kphi[stage, 0] - kphi[stage, 1]) + c1 * (x[0] - x[1])
                for j in range(m):
                    total = 0.0
                    for k in range(m):
                        total += q[j, k] * (fz[k] + zy[k, 0] * dy_e + zy[k, 1] * dy_t)
                    kz[stage, j] = total
        # y_new = argument of stage 6 + k6; k6 is the error estimate
        err = 0.0
        for i in range(n):
            ep = kphi[5, i] / (atol + rtol * max(abs(phi[i]), abs(aphi[i] + kphi[5, i])))
            ev = kv[5, i] / (atol + rtol * max(abs(v[i]), abs(av[i] + kv[5, i])))
            err += ep * ep + ev * ev
        for i in range(m):
            ez = kz[5, i] / (atol + rtol * max(abs(z[i]), abs(az[i] + kz[5, i])))
            err += ez * ez
        err = math.sqrt(err / size)
        if not math.isfinite(err):
            h *= 0.25
            rejected += 1
            last_rejected = True
            if h < tiny:
                status = 3
                break
            continue
        factor = max(1.0 / 6.0, min(5.0, math.sqrt(math.sqrt(err)) / 0.9))
        h_new = h / factor
        if err <= 1.0:
            if steps > 0:  # Gustafsson's predictive controller (as in rodas.f)
                predicted = h_accepted / h * math.sqrt(math.sqrt(err * err / err_accepted)) / 0.9
                predicted = max(1.0 / 6.0, min(5.0, predicted))
                h_new = h / max(factor, predicted)
            h_accepted = h
            err_accepted = max(1e-2, err)
            bit0 = v[n - 1]
            top0 = v[0]
            for i in range(n):
                phi[i] = aphi[i] + kphi[5, i]
                v[i] = av[i] + kv[5, i]
            for i in range(m):
                z[i] = az[i] + kz[5, i]
            _forces(chain, top, torque, p, wob, radius, omega, omega_set, phi, v, z, f0v, f0z)
            _accelerations(chain, mpiv, mlow, f0v, acc)
            t_new = t + h
            if t_new > t_window:
                lo = (t_window - t) / h if t < t_window else 0.0
                vmax, vmin = extremes_of_cubic(
                    bit0, v[n - 1], h * bit_acc0, h * acc[n - 1], lo, vmax, vmin
                )
                if has_top:
                    top_integral += h * _integral_of_cubic(top0, v[0], h * top_acc0, h * acc[0], lo)
            bit_acc0 = acc[n - 1]
            top_acc0 = acc[0]
            t = t_new
            steps += 1
            if last_rejected:
                h_new = min(h_new, h)
            last_rejected = False
            h = min(h_new, hmax)
        else:
            rejected += 1
            last_rejected = True
            h = h_new
    out[0] = vmax + omega
    out[1] = vmin + omega
    out[2] = steps
    out[3] = rejected
    out[4] = status
    out[5] = omega + (top_integral / (t_end - t_window) if has_top else 0.0)


@njit(kernel_signature(), cache=True, nogil=True)
def integrate_serial(chain, top, torque, slope, p, settings, wob, omega, omega_set, out) -> None:
    """Every point in turn, without the GIL (arguments: :func:`kernel_signature`)."""
    for k in range(wob.size):
        _integrate_point(
            chain, top, torque, slope, p, settings, wob[k], omega[k], omega_set[k], out[k]
        )


@njit(kernel_signature(), cache=True, parallel=True)
def integrate_parallel(chain, top, torque, slope, p, settings, wob, omega, omega_set, out) -> None:
    """Every point on numba's thread pool (dynamic sharing: set the chunk size to 1)."""
    for k in prange(wob.size):
        _integrate_point(
            chain, top, torque, slope, p, settings, wob[k], omega[k], omega_set[k], out[k]
        )
