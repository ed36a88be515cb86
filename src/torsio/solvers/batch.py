"""Batch engine: S_SS at many operating points of one System, integrated together.

A severity map is hundreds to tens of thousands of transient runs of the same
model at different weights on bit and rotary speeds. This module integrates a
whole batch of operating points in one call, each point with its own adaptive
step and its own error control, and returns S_SS (paper Eq. 12) for each.

Method
------
The equations are those of :mod:`torsio.physics.system` in twist coordinates, written
with the inertia matrix kept on the left so that consistent mass needs no inverse:

    phi' = v
    [I] v' = -[K] phi - [C] v - Omega d - T_bit(Omega + v_N) e_N,   d = [C] 1 - c_t

They are integrated with RODAS4 (Hairer and Wanner, *Solving ODEs II*, IV.7), a
linearly implicit (Rosenbrock) method of order 4 with an embedded order-3 error
estimate, L-stable and stiffly accurate. Each step solves six linear systems
with the matrix ``[M]/(gamma h) - J``, where J is the exact Jacobian. The model
is linear except for the scalar bit torque, so J differs from the constant
linear part only by the bit-law slope on one diagonal entry; eliminating the
twist increments leaves the n x n tridiagonal matrix

    [I]/(gamma h) + [C] + gamma h [K] + T_bit'(Omega + v_N) e_N e_N^T

(tridiagonal for any chain, lumped or consistent mass), factored once per step in
O(n) and reused by the six stages. Heavily overdamped high modes (stiffness-
proportional damping on fine models) are therefore no constraint on the step:
the step follows the accuracy of the slow stick-slip motion only.

Accuracy is controlled per point: the step is accepted when the RMS over the
state of ``err_i / (atol + rtol max(|y_i|, |y_new_i|))`` is <= 1 and the next
step is chosen from it (no step is shared by points of the batch). Steps are
also capped at ``max_step`` (a quarter of the first natural period by default).

The extremes of the bit speed in the steady window are not read at the accepted
steps only: on each step that overlaps the window, the bit speed is the cubic
Hermite interpolant of its values and accelerations at both ends (the
acceleration at the end of a step is the first stage of the next one, so it
costs nothing), and its maximum and minimum over the part of the step inside the
window are found from the roots of its derivative.

Engines
-------
``"numba"``
    The integrator compiled with numba, one point after the other in each
    thread, points shared dynamically between threads. Needs the bit-rock law
    compiled too: the built-in ``tucker-wang`` and ``constant`` laws are.
``"numpy"``
    The same method vectorized with numpy across the batch (each point still
    with its own step); works with any bit-rock law through its vectorized
    ``torque``/``slope``. Slower (see ``docs/performance.md``).
``"scipy"``
    One :func:`scipy.integrate.solve_ivp` run per point (the reference and the
    baseline; not a batch method).
``"auto"``
    ``"numba"`` when numba is installed and the law has a compiled kernel,
    else ``"numpy"``.

Examples
--------
>>> from torsio.physics.system import System, builtin_config
>>> system = System.from_config(builtin_config(), strategy="A")
>>> result = simulate_batch(system, wob=[50e3, 200e3], rpm=[120.0, 50.0])
>>> [round(float(s), 2) for s in result.severity]
[0.0, 1.77]
>>> result.ok.all()
np.True_
"""

from __future__ import annotations

import math
import time
from typing import Any

import attrs
import numpy as np

from torsio.analysis.severity import check_window, default_times
from torsio.errors import ConfigError, SolverError
from torsio.physics.system import System

numba: Any
njit: Any
prange: Any
try:  # numba is optional: without it the numpy engine is used
    import numba
    from numba import njit, prange

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    numba = None
    HAVE_NUMBA = False
    prange = range

    def _identity(*args: Any, **kwargs: Any) -> Any:
        """Stands in for numba.njit: the functions run as plain Python (slowly)."""
        if len(args) == 1 and callable(args[0]) and not kwargs:
            return args[0]
        return lambda function: function

    njit = _identity

__all__ = [
    "DEFAULT_ATOL",
    "DEFAULT_RTOL",
    "ENGINES",
    "HAVE_NUMBA",
    "BatchModel",
    "BatchResults",
    "reference_severity",
    "simulate_batch",
]

ENGINES = ("auto", "numba", "numpy", "scipy")
"""Names accepted by ``simulate_batch(engine=...)``."""

DEFAULT_RTOL = 1e-5
"""Default relative tolerance of the batch engine (see ``docs/performance.md`` for the
convergence study that chose it: |dS_SS| < 1e-3 against rtol = 1e-8 runs)."""

DEFAULT_ATOL = 1e-6
"""Default absolute tolerance [rad, rad/s]."""

DEFAULT_MAX_STEPS = 2_000_000
"""Accepted steps allowed per point before the point is reported as failed."""

STATUS_OK = 0
STATUS_MAX_STEPS = 1
STATUS_STEP_UNDERFLOW = 2
STATUS_NOT_FINITE = 3
STATUS_MESSAGES = {
    STATUS_OK: "ok",
    STATUS_MAX_STEPS: "too many steps",
    STATUS_STEP_UNDERFLOW: "step size underflow",
    STATUS_NOT_FINITE: "non-finite state",
}
"""What each per-point status code means."""

# --- RODAS4 (Hairer and Wanner, Solving ODEs II, Sec. IV.7; rodas.f, METH = 1) --------------
GAMMA = 0.25
_A = np.zeros((6, 6))
_A[1, 0] = 1.544
_A[2, :2] = (0.9466785280815826, 0.2557011698983284)
_A[3, :3] = (3.314825187068521, 2.896124015972201, 0.9986419139977817)
_A[4, :4] = (1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895)
_A[5, :5] = (*_A[4, :4], 1.0)
_C = np.zeros((6, 6))
_C[1, 0] = -5.6688
_C[2, :2] = (-2.430093356833875, -0.2063599157091915)
_C[3, :3] = (-0.1073529058151375, -9.594562251023355, -20.47028614809616)
_C[4, :4] = (7.496443313967647, -10.24680431464352, -33.99990352819905, 11.70890893206160)
_C[5, :5] = (
    8.083246795921522,
    -7.981132988064893,
    -31.52159432874371,
    16.31930543123136,
    -6.058818238834054,
)
# y_new = (argument of stage 6) + k6 and the embedded error estimate is k6 itself.

# --- bit-rock laws with a compiled kernel ---------------------------------------------------
LAW_TUCKER_WANG = 0
LAW_CONSTANT = 1


def _law_kernel(law: Any) -> tuple[int, np.ndarray] | None:
    """(code, parameters in rad/s) of a law the compiled engine knows, else None."""
    from torsio.physics.laws import ConstantTorque, TuckerWang

    if type(law) is TuckerWang:
        return LAW_TUCKER_WANG, np.array([law.a0, law.a1, law.a2, law.a3], dtype=float)
    if type(law) is ConstantTorque:
        return LAW_CONSTANT, np.array([law.torque_on_bit], dtype=float)
    return None


# --- the model in the form the engines use ---------------------------------------------------
def _tridiagonal(key: str, matrix: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    matrix = np.asarray(matrix, dtype=float)
    n = matrix.shape[0]
    diagonal = np.ascontiguousarray(np.diag(matrix))
    upper = np.zeros(n)
    if n > 1:
        upper[:-1] = np.diag(matrix, 1)
    band = np.diag(diagonal) + np.diag(upper[:-1], 1) + np.diag(upper[:-1], -1)
    if not np.array_equal(band, matrix):
        raise ConfigError(
            key,
            "the batch engine needs tridiagonal (chain) matrices [I], [K], "
            "[C]; use engine='scipy' for other models",
        )
    return diagonal, upper


@attrs.frozen
class BatchModel:
    """A System's matrices as the batch engines use them (tridiagonal storage).

    Off-diagonal arrays have length n; entry i couples nodes i and i+1 and the
    last entry is zero.

    Attributes
    ----------
    dofs : int
    mass_diag, mass_upper : ndarray
        [I], in kg m^2.
    stiffness_diag, stiffness_upper : ndarray
        [K], in N m/rad.
    damping_diag, damping_upper : ndarray
        [C], in N m s/rad.
    drag : ndarray
        d = [C] 1 - c_t [N m s/rad]: torque per unit rigid rotation speed.
    bit_radius : float
        R_bit [m].
    law : object
        The bit-rock law.
    law_code : int
        Compiled kernel of the law (-1: none).
    law_parameters : ndarray
        Parameters of the compiled kernel (rad/s reading).
    first_frequency : float
        omega_1 [rad/s].
    highest_frequency : float
        omega_n [rad/s] (undamped), for the step-size diagnostics.
    """

    dofs: int
    mass_diag: np.ndarray
    mass_upper: np.ndarray
    stiffness_diag: np.ndarray
    stiffness_upper: np.ndarray
    damping_diag: np.ndarray
    damping_upper: np.ndarray
    drag: np.ndarray
    bit_radius: float
    law: Any
    law_code: int
    law_parameters: np.ndarray
    first_frequency: float
    highest_frequency: float

    @classmethod
    def from_system(cls, system: System) -> BatchModel:
        """Extract the tridiagonal matrices of ``system`` (ConfigError if not a chain)."""
        import scipy.linalg

        model = system.model
        mass = _tridiagonal("inertia", model.inertia)
        stiffness = _tridiagonal("stiffness", model.stiffness)
        damping = _tridiagonal("damping", system.damping_matrix)
        eigenvalues = scipy.linalg.eigh(
            np.asarray(model.stiffness), np.asarray(model.inertia), eigvals_only=True
        )
        kernel = _law_kernel(system.law)
        code, parameters = kernel if kernel is not None else (-1, np.zeros(1))
        return cls(
            model.dofs,
            *mass,
            *stiffness,
            *damping,
            np.ascontiguousarray(system.drag_per_speed, dtype=float),
            float(system.bit_radius),
            system.law,
            int(code),
            parameters,
            float(np.sqrt(eigenvalues[0])),
            float(np.sqrt(eigenvalues[-1])),
        )

    @property
    def lumped_mass(self) -> bool:
        """Whether [I] is diagonal."""
        return not np.any(self.mass_upper)


# --- compiled kernels -------------------------------------------------------------------------
@njit(cache=True, inline="always")
def _torque_nb(code: int, p: np.ndarray, w: float, wob: float, radius: float) -> float:
    if code == LAW_TUCKER_WANG:
        return wob * radius * p[0] * (math.tanh(p[1] * w) + p[2] * w / (1.0 + p[3] * w * w))
    return p[0]


@njit(cache=True, inline="always")
def _slope_nb(code: int, p: np.ndarray, w: float, wob: float, radius: float) -> float:
    if code == LAW_TUCKER_WANG:
        c = math.cosh(p[1] * w)
        d = 1.0 + p[3] * w * w
        return wob * radius * p[0] * (p[1] / (c * c) + p[2] * (1.0 - p[3] * w * w) / (d * d))
    return 0.0


@njit(cache=True)
def _extremes_of_cubic(
    u0: float, u1: float, d0: float, d1: float, lo: float, vmax: float, vmin: float
) -> tuple[float, float]:
    """Max and min of the cubic Hermite interpolant on [lo, 1] (d0, d1 scaled by h)."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1
    ulo = u0 + lo * (d0 + lo * (c2 + lo * c3))
    vmax = max(vmax, ulo, u1)
    vmin = min(vmin, ulo, u1)
    # u'(x) = d0 + 2 c2 x + 3 c3 x^2
    a = 3.0 * c3
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
def _tri_residual(
    n: int,
    kd: np.ndarray,
    ku: np.ndarray,
    cd: np.ndarray,
    cu: np.ndarray,
    drag: np.ndarray,
    omega: float,
    xphi: np.ndarray,
    xv: np.ndarray,
    gv: np.ndarray,
) -> None:
    """gv = -[K] xphi - [C] xv - omega d (the bit torque is added by the caller)."""
    for i in range(n):
        gv[i] = -kd[i] * xphi[i] - cd[i] * xv[i] - omega * drag[i]
    for i in range(n - 1):
        gv[i] -= ku[i] * xphi[i + 1] + cu[i] * xv[i + 1]
    for i in range(1, n):
        gv[i] -= ku[i - 1] * xphi[i - 1] + cu[i - 1] * xv[i - 1]


@njit(cache=True)
def _integrate_point(
    n: int,
    md: np.ndarray,
    mu: np.ndarray,
    kd: np.ndarray,
    ku: np.ndarray,
    cd: np.ndarray,
    cu: np.ndarray,
    drag: np.ndarray,
    code: int,
    p: np.ndarray,
    radius: float,
    wob: float,
    omega: float,
    t_end: float,
    t_window: float,
    rtol: float,
    atol: float,
    h0: float,
    hmax: float,
    max_steps: int,
    a_coef: np.ndarray,
    c_coef: np.ndarray,
    out: np.ndarray,
) -> None:
    """RODAS4 from rest to t_end; out = [max, min, steps, rejected, status] of the bit speed."""
    lumped = True
    for i in range(n - 1):
        if mu[i] != 0.0:
            lumped = False
    phi = np.zeros(n)
    v = np.full(n, -omega)  # start-up from rest: theta' = 0
    kphi = np.zeros((6, n))
    kv = np.zeros((6, n))
    aphi = np.empty(n)
    av = np.empty(n)
    fphi = np.empty(n)
    fv = np.empty(n)
    f0v = np.empty(n)
    uphi = np.empty(n)
    uv = np.empty(n)
    z = np.empty(n)
    ipiv = np.empty(n)
    low = np.zeros(n)
    band = np.zeros(n)
    # factors of [I], for the bit acceleration with consistent mass
    mpiv = np.empty(n)
    mlow = np.zeros(n)
    mpiv[0] = md[0]
    for i in range(1, n):
        mlow[i] = mu[i - 1] / mpiv[i - 1]
        mpiv[i] = md[i] - mlow[i] * mu[i - 1]
    tiny = 1e-12 * max(1.0, t_end)

    _tri_residual(n, kd, ku, cd, cu, drag, omega, phi, v, f0v)
    f0v[n - 1] -= _torque_nb(code, p, omega + v[n - 1], wob, radius)
    if lumped:
        acc0 = f0v[n - 1] / md[n - 1]
    else:
        zz = f0v[0]
        for i in range(1, n):
            zz = f0v[i] - mlow[i] * zz
        acc0 = zz / mpiv[n - 1]
    t = 0.0
    h = min(h0, hmax, t_end)
    vmax = -np.inf
    vmin = np.inf
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
        s = _slope_nb(code, p, omega + v[n - 1], wob, radius)
        # factor [I]/g + [C] + g [K] + s e_N e_N^T (tridiagonal, no pivoting)
        singular = False
        for i in range(n):
            band[i] = mu[i] / g + cu[i] + g * ku[i]
        for i in range(n):
            a = md[i] / g + cd[i] + g * kd[i]
            scale = md[i] / g + abs(cd[i]) + g * kd[i]
            if i == n - 1:
                a += s
            if i > 0:
                low[i] = band[i - 1] * ipiv[i - 1]
                a -= low[i] * band[i - 1]
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
            for j in range(stage):
                a_ij = a_coef[stage, j]
                c_ij = c_coef[stage, j] / h
                for i in range(n):
                    aphi[i] += a_ij * kphi[j, i]
                    av[i] += a_ij * kv[j, i]
                    uphi[i] += c_ij * kphi[j, i]
                    uv[i] += c_ij * kv[j, i]
            if stage == 0:
                for i in range(n):
                    fphi[i] = v[i]
                    fv[i] = f0v[i]
            else:
                _tri_residual(n, kd, ku, cd, cu, drag, omega, aphi, av, fv)
                fv[n - 1] -= _torque_nb(code, p, omega + av[n - 1], wob, radius)
                for i in range(n):
                    fphi[i] = av[i] + uphi[i]
                    fv[i] += md[i] * uv[i]
                for i in range(n - 1):
                    fv[i] += mu[i] * uv[i + 1]
                    fv[i + 1] += mu[i] * uv[i]
            # speeds: A x = f_v - g [K] f_phi ; twists: x_phi = g (f_phi + x)
            for i in range(n):
                z[i] = fv[i] - g * kd[i] * fphi[i]
            for i in range(n - 1):
                z[i] -= g * ku[i] * fphi[i + 1]
                z[i + 1] -= g * ku[i] * fphi[i]
            for i in range(1, n):
                z[i] -= low[i] * z[i - 1]
            z[n - 1] *= ipiv[n - 1]
            for i in range(n - 2, -1, -1):
                z[i] = (z[i] - band[i] * z[i + 1]) * ipiv[i]
            for i in range(n):
                kv[stage, i] = z[i]
                kphi[stage, i] = g * (fphi[i] + z[i])
        # y_new = argument of stage 6 + k6; k6 is the error estimate
        err = 0.0
        for i in range(n):
            yp = aphi[i] + kphi[5, i]
            yv = av[i] + kv[5, i]
            ep = kphi[5, i] / (atol + rtol * max(abs(phi[i]), abs(yp)))
            ev = kv[5, i] / (atol + rtol * max(abs(v[i]), abs(yv)))
            err += ep * ep + ev * ev
        err = math.sqrt(err / (2 * n))
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
            u0 = v[n - 1]
            for i in range(n):
                phi[i] = aphi[i] + kphi[5, i]
                v[i] = av[i] + kv[5, i]
            _tri_residual(n, kd, ku, cd, cu, drag, omega, phi, v, f0v)
            f0v[n - 1] -= _torque_nb(code, p, omega + v[n - 1], wob, radius)
            if lumped:
                acc1 = f0v[n - 1] / md[n - 1]
            else:
                zz = f0v[0]
                for i in range(1, n):
                    zz = f0v[i] - mlow[i] * zz
                acc1 = zz / mpiv[n - 1]
            t_new = t + h
            if t_new > t_window:
                lo = (t_window - t) / h if t < t_window else 0.0
                vmax, vmin = _extremes_of_cubic(u0, v[n - 1], h * acc0, h * acc1, lo, vmax, vmin)
            acc0 = acc1
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


@njit(cache=True)
def _integrate_one_dof(
    m: float,
    k: float,
    c: float,
    drag: float,
    code: int,
    p: np.ndarray,
    radius: float,
    wob: float,
    omega: float,
    t_end: float,
    t_window: float,
    rtol: float,
    atol: float,
    h0: float,
    hmax: float,
    max_steps: int,
    a_coef: np.ndarray,
    c_coef: np.ndarray,
    out: np.ndarray,
) -> None:
    """:func:`_integrate_point` written out for one degree of freedom (same method)."""
    kphi = np.zeros(6)
    kv = np.zeros(6)
    phi = 0.0
    v = -omega
    tiny = 1e-12 * max(1.0, t_end)
    f0v = -k * phi - c * v - omega * drag - _torque_nb(code, p, omega + v, wob, radius)
    acc0 = f0v / m
    t = 0.0
    h = min(h0, hmax, t_end)
    vmax = -np.inf
    vmin = np.inf
    steps = 0
    rejected = 0
    status = 0
    last_rejected = False
    h_accepted = h
    err_accepted = 1.0
    aphi = phi
    av = v
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
        s = _slope_nb(code, p, omega + v, wob, radius)
        a = m / g + c + g * k + s
        if not abs(a) > 1e-13 * (m / g + abs(c) + g * k):
            h *= 0.5
            rejected += 1
            last_rejected = True
            continue
        ia = 1.0 / a
        for stage in range(6):
            aphi = phi
            av = v
            uphi = 0.0
            uv = 0.0
            for j in range(stage):
                aphi += a_coef[stage, j] * kphi[j]
                av += a_coef[stage, j] * kv[j]
                uphi += c_coef[stage, j] * kphi[j]
                uv += c_coef[stage, j] * kv[j]
            if stage == 0:
                fphi = v
                fv = f0v
            else:
                fphi = av + uphi / h
                fv = (
                    -k * aphi
                    - c * av
                    - omega * drag
                    - _torque_nb(code, p, omega + av, wob, radius)
                    + m * uv / h
                )
            x = (fv - g * k * fphi) * ia
            kv[stage] = x
            kphi[stage] = g * (fphi + x)
        yp = aphi + kphi[5]
        yv = av + kv[5]
        ep = kphi[5] / (atol + rtol * max(abs(phi), abs(yp)))
        ev = kv[5] / (atol + rtol * max(abs(v), abs(yv)))
        err = math.sqrt(0.5 * (ep * ep + ev * ev))
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
            if steps > 0:
                predicted = h_accepted / h * math.sqrt(math.sqrt(err * err / err_accepted)) / 0.9
                predicted = max(1.0 / 6.0, min(5.0, predicted))
                h_new = h / max(factor, predicted)
            h_accepted = h
            err_accepted = max(1e-2, err)
            u0 = v
            phi = yp
            v = yv
            f0v = -k * phi - c * v - omega * drag - _torque_nb(code, p, omega + v, wob, radius)
            acc1 = f0v / m
            t_new = t + h
            if t_new > t_window:
                lo = (t_window - t) / h if t < t_window else 0.0
                vmax, vmin = _extremes_of_cubic(u0, v, h * acc0, h * acc1, lo, vmax, vmin)
            acc0 = acc1
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


@njit(cache=True)
def _integrate_index(
    k: int,
    n: int,
    md: np.ndarray,
    mu: np.ndarray,
    kd: np.ndarray,
    ku: np.ndarray,
    cd: np.ndarray,
    cu: np.ndarray,
    drag: np.ndarray,
    code: int,
    p: np.ndarray,
    radius: float,
    wobs: np.ndarray,
    omegas: np.ndarray,
    t_end: float,
    t_window: float,
    rtol: float,
    atol: float,
    h0: float,
    hmax: float,
    max_steps: int,
    a_coef: np.ndarray,
    c_coef: np.ndarray,
    out: np.ndarray,
) -> None:
    """Integrate grid point k (the 1-DOF kernel for one degree of freedom)."""
    if n == 1:
        _integrate_one_dof(
            md[0],
            kd[0],
            cd[0],
            drag[0],
            code,
            p,
            radius,
            wobs[k],
            omegas[k],
            t_end,
            t_window,
            rtol,
            atol,
            h0,
            hmax,
            max_steps,
            a_coef,
            c_coef,
            out[k],
        )
    else:
        _integrate_point(
            n,
            md,
            mu,
            kd,
            ku,
            cd,
            cu,
            drag,
            code,
            p,
            radius,
            wobs[k],
            omegas[k],
            t_end,
            t_window,
            rtol,
            atol,
            h0,
            hmax,
            max_steps,
            a_coef,
            c_coef,
            out[k],
        )


@njit(cache=True, nogil=True)
def _integrate_batch_serial(arguments: tuple) -> None:
    """Every point of ``arguments`` (see :func:`_integrate_index`) in turn, without the GIL."""
    for k in range(arguments[11].size):
        _integrate_index(k, *arguments)


@njit(cache=True, parallel=True)
def _integrate_batch(arguments: tuple) -> None:
    """Every point of ``arguments`` on numba's thread pool."""
    for k in prange(arguments[11].size):
        _integrate_index(k, *arguments)


# --- numpy engine: the same method vectorized across the batch -----------------------------
def _numpy_batch(
    model: BatchModel,
    wob: np.ndarray,
    omega: np.ndarray,
    t_end: float,
    t_window: float,
    rtol: float,
    atol: float,
    h0: float,
    hmax: float,
    max_steps: int,
) -> np.ndarray:
    n = model.dofs
    md, mu = model.mass_diag, model.mass_upper
    kd, ku = model.stiffness_diag, model.stiffness_upper
    cd, cu = model.damping_diag, model.damping_upper
    drag = model.drag
    law = model.law
    radius = model.bit_radius
    lumped = model.lumped_mass
    count = wob.size
    out = np.empty((count, 5))
    out[:, 0] = -np.inf
    out[:, 1] = np.inf
    out[:, 2:] = 0.0

    # mass-matrix factors, for the bit acceleration with consistent mass
    mpiv = np.empty(n)
    mlow = np.zeros(n)
    mpiv[0] = md[0]
    for i in range(1, n):
        mlow[i] = mu[i - 1] / mpiv[i - 1]
        mpiv[i] = md[i] - mlow[i] * mu[i - 1]

    def tri_mul(diag: np.ndarray, upper: np.ndarray, x: np.ndarray) -> np.ndarray:
        y = x * diag
        if n > 1:
            y[:, :-1] += upper[:-1] * x[:, 1:]
            y[:, 1:] += upper[:-1] * x[:, :-1]
        return y

    def rhs(
        xphi: np.ndarray, xv: np.ndarray, w: np.ndarray, om: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        gv = -tri_mul(kd, ku, xphi) - tri_mul(cd, cu, xv) - om[:, None] * drag
        gv[:, -1] -= np.asarray(law.torque(om + xv[:, -1], w, radius), dtype=float)
        return xv.copy(), gv

    def bit_acceleration(gv: np.ndarray) -> np.ndarray:
        if lumped:
            return gv[:, -1] / md[-1]
        z = gv[:, 0].copy()
        for i in range(1, n):
            z = gv[:, i] - mlow[i] * z
        return z / mpiv[-1]

    idx = np.arange(count)
    w = wob.copy()
    om = omega.copy()
    phi = np.zeros((count, n))
    v = np.repeat(-om[:, None], n, axis=1)
    f0phi, f0v = rhs(phi, v, w, om)
    acc0 = bit_acceleration(f0v)
    t = np.zeros(count)
    h = np.full(count, min(h0, hmax, t_end))
    vmax = np.full(count, -np.inf)
    vmin = np.full(count, np.inf)
    steps = np.zeros(count, dtype=np.int64)
    rejected = np.zeros(count, dtype=np.int64)
    status = np.zeros(count, dtype=np.int64)
    last_rejected = np.zeros(count, dtype=bool)
    h_accepted = h.copy()
    err_accepted = np.ones(count)
    tiny = 1e-12 * max(1.0, t_end)

    def retire(keep: np.ndarray) -> None:
        done = ~keep
        out[idx[done], 0] = vmax[done] + om[done]
        out[idx[done], 1] = vmin[done] + om[done]
        out[idx[done], 2] = steps[done]
        out[idx[done], 3] = rejected[done]
        out[idx[done], 4] = status[done]

    while idx.size:
        status[(steps >= max_steps) & (status == 0)] = STATUS_MAX_STEPS
        status[(h < tiny) & (status == 0)] = STATUS_STEP_UNDERFLOW
        keep = (t < t_end) & (status == 0)
        if not keep.all():
            retire(keep)
            (
                idx,
                w,
                om,
                phi,
                v,
                f0phi,
                f0v,
                acc0,
                t,
                h,
                vmax,
                vmin,
                steps,
                rejected,
                status,
                last_rejected,
                h_accepted,
                err_accepted,
            ) = (
                a[keep]
                for a in (
                    idx,
                    w,
                    om,
                    phi,
                    v,
                    f0phi,
                    f0v,
                    acc0,
                    t,
                    h,
                    vmax,
                    vmin,
                    steps,
                    rejected,
                    status,
                    last_rejected,
                    h_accepted,
                    err_accepted,
                )
            )
            if not idx.size:
                break
        h = np.minimum(h, t_end - t)
        g = GAMMA * h
        s = np.asarray(law.slope(om + v[:, -1], w, radius), dtype=float)
        piv = np.empty_like(phi)
        low = np.zeros_like(phi)
        upper = mu[None, :] / g[:, None] + cu[None, :] + g[:, None] * ku[None, :]
        for i in range(n):
            a = md[i] / g + cd[i] + g * kd[i]
            if i == n - 1:
                a = a + s
            if i > 0:
                low[:, i] = upper[:, i - 1] / piv[:, i - 1]
                a = a - low[:, i] * upper[:, i - 1]
            piv[:, i] = a
        scale = md[None, :] / g[:, None] + np.abs(cd)[None, :] + g[:, None] * kd[None, :]
        singular = ~(np.abs(piv) > 1e-13 * scale).all(axis=1)
        piv[singular] = 1.0
        kphi = np.zeros((6, idx.size, n))
        kv = np.zeros((6, idx.size, n))
        aphi, av = phi, v
        for stage in range(6):
            aphi = phi.copy()
            av = v.copy()
            uphi = np.zeros_like(phi)
            uv = np.zeros_like(phi)
            for j in range(stage):
                aphi += _A[stage, j] * kphi[j]
                av += _A[stage, j] * kv[j]
                uphi += _C[stage, j] * kphi[j]
                uv += _C[stage, j] * kv[j]
            if stage == 0:
                fphi, fv = f0phi, f0v
            else:
                fphi, fv = rhs(aphi, av, w, om)
                fphi = fphi + uphi / h[:, None]
                fv = fv + tri_mul(md, mu, uv / h[:, None])
            z = fv - g[:, None] * tri_mul(kd, ku, fphi)
            for i in range(1, n):
                z[:, i] -= low[:, i] * z[:, i - 1]
            x = np.empty_like(z)
            x[:, -1] = z[:, -1] / piv[:, -1]
            for i in range(n - 2, -1, -1):
                x[:, i] = (z[:, i] - upper[:, i] * x[:, i + 1]) / piv[:, i]
            kv[stage] = x
            kphi[stage] = g[:, None] * (fphi + x)
        yphi = aphi + kphi[5]
        yv = av + kv[5]
        sp = atol + rtol * np.maximum(np.abs(phi), np.abs(yphi))
        sv = atol + rtol * np.maximum(np.abs(v), np.abs(yv))
        with np.errstate(invalid="ignore", over="ignore"):
            err = np.sqrt(
                (((kphi[5] / sp) ** 2).sum(axis=1) + ((kv[5] / sv) ** 2).sum(axis=1)) / (2 * n)
            )
        finite = np.isfinite(err) & np.isfinite(yphi).all(axis=1) & np.isfinite(yv).all(axis=1)
        bad = singular | ~finite
        err = np.where(bad, np.inf, err)
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            factor = np.clip(np.sqrt(np.sqrt(err)) / 0.9, 1.0 / 6.0, 5.0)
            predicted = np.clip(
                h_accepted / h * np.sqrt(np.sqrt(err * err / err_accepted)) / 0.9, 1.0 / 6.0, 5.0
            )
        accept = err <= 1.0
        factor = np.where(accept & (steps > 0), np.maximum(factor, predicted), factor)
        h_new = np.where(singular, 0.5 * h, np.where(~finite, 0.25 * h, h / factor))
        h_accepted = np.where(accept, h, h_accepted)
        err_accepted = np.where(accept, np.maximum(1e-2, err), err_accepted)
        status[~finite & ~singular & (h_new < tiny)] = STATUS_NOT_FINITE
        if accept.any():
            a_ = accept
            u0 = v[a_, -1]
            phi[a_] = yphi[a_]
            v[a_] = yv[a_]
            nphi, nv = rhs(phi[a_], v[a_], w[a_], om[a_])
            f0phi[a_] = nphi
            f0v[a_] = nv
            acc1 = bit_acceleration(nv)
            t_old = t[a_]
            hh = h[a_]
            t[a_] = t_old + hh
            inside = t[a_] > t_window
            if inside.any():
                lo = np.where(t_old < t_window, (t_window - t_old) / hh, 0.0)
                mx, mn = _extremes_numpy(u0, v[a_, -1], hh * acc0[a_], hh * acc1, lo)
                sel = np.flatnonzero(a_)[inside]
                vmax[sel] = np.maximum(vmax[sel], mx[inside])
                vmin[sel] = np.minimum(vmin[sel], mn[inside])
            acc0[a_] = acc1
            steps[a_] += 1
            h_new[a_] = np.where(last_rejected[a_], np.minimum(h_new[a_], hh), h_new[a_])
            h_new[a_] = np.minimum(h_new[a_], hmax)
        rejected[~accept] += 1
        last_rejected = ~accept
        h = h_new
    return out


def _extremes_numpy(
    u0: np.ndarray, u1: np.ndarray, d0: np.ndarray, d1: np.ndarray, lo: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Vectorized :func:`_extremes_of_cubic` (max, min over [lo, 1])."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1

    def at(x: np.ndarray) -> np.ndarray:
        return u0 + x * (d0 + x * (c2 + x * c3))

    ulo = at(lo)
    vmax = np.maximum(ulo, u1)
    vmin = np.minimum(ulo, u1)
    a = 3.0 * c3
    b = 2.0 * c2
    with np.errstate(invalid="ignore", divide="ignore"):
        quadratic = np.abs(a) > 1e-14 * (np.abs(b) + np.abs(d0))
        disc = b * b - 4.0 * a * d0
        sq = np.sqrt(np.maximum(disc, 0.0))
        q = -0.5 * (b + np.copysign(sq, b))
        roots = [
            np.where(quadratic & (disc >= 0), q / a, np.nan),
            np.where(quadratic & (disc >= 0) & (q != 0), d0 / q, np.nan),
            np.where(~quadratic & (b != 0), -d0 / b, np.nan),
        ]
    for root in roots:
        ok = (root > lo) & (root < 1.0)
        u = at(np.where(ok, root, 1.0))
        vmax = np.where(ok, np.maximum(vmax, u), vmax)
        vmin = np.where(ok, np.minimum(vmin, u), vmin)
    return vmax, vmin


# --- reference: one solve_ivp run per point -----------------------------------------------
def reference_severity(
    system: System,
    duration: float | None = None,
    steady_window: float | None = None,
    method: str = "Radau",
    rtol: float = 1e-8,
    atol: float = 1e-10,
    samples_per_step: int = 16,
) -> tuple[float, dict[str, Any]]:
    """S_SS of one operating point with :func:`scipy.integrate.solve_ivp` (the reference).

    Integrates :class:`torsio.physics.equations.TwistEquations` from rest (the exact
    Jacobian for implicit methods) and reads the extremes of the bit speed from
    the dense output, sampled ``samples_per_step`` times in every step of the
    window. This is the per-point method the batch engine is measured against.

    Returns
    -------
    severity : float
        S_SS.
    info : dict
        ``nfev``, ``steps``, ``status`` and ``message`` of the solver, and the
        extremes ``bit_speed_max``, ``bit_speed_min`` [rad/s] over the window.
    """
    from scipy.integrate import solve_ivp

    from torsio.physics.equations import TwistEquations

    equations = TwistEquations(system)
    duration, steady_window = _times(system, duration, steady_window)
    implicit = method in ("Radau", "BDF", "LSODA")
    options: dict[str, Any] = {}
    if implicit:
        options["jac"] = equations.jacobian
    solution = solve_ivp(
        equations.rhs,
        (0.0, duration),
        equations.rest_state(),
        method=method,
        rtol=rtol,
        atol=atol,
        dense_output=True,
        **options,
    )
    info = {
        "nfev": int(solution.nfev),
        "steps": int(solution.t.size - 1),
        "status": int(solution.status),
        "message": str(solution.message),
    }
    if solution.status != 0:
        raise SolverError(
            f"solve_ivp ({method}) failed at wob={system.wob:g} N, "
            f"rpm={system.rpm:g}: {solution.message}"
        )
    start = duration - steady_window
    nodes = solution.t
    inside = nodes[(nodes > start) & (nodes < duration)]
    edges = np.concatenate(([start], inside, [duration]))
    fractions = np.linspace(0.0, 1.0, samples_per_step + 1)[:-1]
    times = (edges[:-1, None] + np.diff(edges)[:, None] * fractions).ravel()
    times = np.append(times, duration)
    bit_speed = solution.sol(times)[-1] + system.omega
    info["bit_speed_max"] = float(bit_speed.max())
    info["bit_speed_min"] = float(bit_speed.min())
    return float((bit_speed.max() - bit_speed.min()) / (2.0 * system.omega)), info


def _times(
    system: System, duration: float | None, steady_window: float | None
) -> tuple[float, float]:
    from torsio.model.modal import modal_analysis

    if duration is None or steady_window is None:
        omega1 = float(modal_analysis(system.model, 1).frequencies_rad[0])
        default_duration, default_window = default_times(omega1)
        duration = default_duration if duration is None else duration
        steady_window = default_window if steady_window is None else steady_window
    check_window(float(duration), float(steady_window))
    return float(duration), float(steady_window)


# --- results and the public entry point ---------------------------------------------------------
@attrs.frozen
class BatchResults:
    """S_SS of a batch of operating points.

    Attributes
    ----------
    wob : ndarray
        Weight on bit of each point [N].
    rpm : ndarray
        Surface rotary speed of each point [rpm].
    severity : ndarray
        S_SS (Eq. 12) of each point; NaN where the solver failed.
    bit_speed_max, bit_speed_min : ndarray
        Extremes of the bit speed over the steady window [rad/s].
    steps, rejected : ndarray
        Accepted and rejected steps of each point.
    status : ndarray
        0 for success, else a key of :data:`STATUS_MESSAGES`.
    engine : str
        The engine that ran.
    duration, steady_window : float
        Run length and steady window [s].
    rtol, atol : float
        Tolerances.
    elapsed : float
        Wall time [s].
    """

    wob: np.ndarray
    rpm: np.ndarray
    severity: np.ndarray
    bit_speed_max: np.ndarray
    bit_speed_min: np.ndarray
    steps: np.ndarray
    rejected: np.ndarray
    status: np.ndarray
    engine: str
    duration: float
    steady_window: float
    rtol: float
    atol: float
    elapsed: float

    @property
    def ok(self) -> np.ndarray:
        """Whether each point was integrated successfully."""
        return self.status == STATUS_OK

    def failures(self) -> list[str]:
        """One line per failed point: operating point and reason."""
        return [
            f"wob={w:g} N, rpm={r:g}: {STATUS_MESSAGES.get(int(s), f'status {s}')}"
            for w, r, s in zip(self.wob, self.rpm, self.status, strict=True)
            if s
        ]


def resolve_engine(engine: str, model: BatchModel) -> str:
    """The engine that ``engine`` ("auto" or a name) means for this model."""
    if engine not in ENGINES:
        raise ConfigError("engine", f"expected one of {', '.join(ENGINES)}, got {engine!r}")
    if engine == "auto":
        return "numba" if HAVE_NUMBA and model.law_code >= 0 else "numpy"
    if engine == "numba":
        if not HAVE_NUMBA:
            raise ConfigError("engine", "engine 'numba' needs numba (pip install numba)")
        if model.law_code < 0:
            raise ConfigError(
                "engine",
                f"bit-rock law {type(model.law).__name__} has no "
                "compiled kernel; use engine='numpy' (any law) or 'auto'",
            )
    return engine


def simulate_batch(
    system: System,
    wob: Any,
    rpm: Any,
    duration: float | None = None,
    steady_window: float | None = None,
    rtol: float = DEFAULT_RTOL,
    atol: float = DEFAULT_ATOL,
    max_step: float | None = None,
    max_steps: int = DEFAULT_MAX_STEPS,
    engine: str = "auto",
    threads: int | None = None,
) -> BatchResults:
    """S_SS of ``system`` at each operating point (wob[k], rpm[k]), started from rest.

    Parameters
    ----------
    system : System
        The model, damping and bit-rock law; its own operating point is ignored.
    wob : array_like
        Weights on bit [N], >= 0.
    rpm : array_like
        Surface rotary speeds [rpm], > 0; broadcast against ``wob``.
    duration, steady_window : float, optional
        Run length and steady-state window [s]; defaults of
        :func:`torsio.analysis.severity.default_times` (40 and 15 first-mode periods).
    rtol, atol : float
        Per-point local error tolerances (relative; absolute in rad and rad/s).
    max_step : float, optional
        Largest step [s]; default a quarter of the first natural period.
    max_steps : int
        Accepted steps allowed per point before it is reported as failed.
    engine : {"auto", "numba", "numpy", "scipy"}
        See the module documentation.
    threads : int, optional
        Threads of the numba engine (default: numba's default, all cores). Calls
        from other threads than the main one always run on one thread.

    Returns
    -------
    BatchResults
        Failed points have NaN severity and a non-zero status; they are never
        silently dropped.
    """
    wob_arr, rpm_arr = np.broadcast_arrays(
        np.asarray(wob, dtype=float), np.asarray(rpm, dtype=float)
    )
    wob_arr = np.ascontiguousarray(wob_arr.ravel())
    rpm_arr = np.ascontiguousarray(rpm_arr.ravel())
    if wob_arr.size and not (np.isfinite(wob_arr).all() and (wob_arr >= 0).all()):
        bad = wob_arr[~(np.isfinite(wob_arr) & (wob_arr >= 0))][0]
        raise ConfigError("wob", f"expected non-negative finite weights on bit in N, got {bad!r}")
    if rpm_arr.size and not (np.isfinite(rpm_arr).all() and (rpm_arr > 0).all()):
        bad = rpm_arr[~(np.isfinite(rpm_arr) & (rpm_arr > 0))][0]
        raise ConfigError("rpm", f"expected positive finite rotary speeds, got {bad!r}")
    for key, value in (("rtol", rtol), ("atol", atol)):
        if not (math.isfinite(value) and value > 0):
            raise ConfigError(key, f"expected a positive tolerance, got {value!r}")
    duration, steady_window = _times(system, duration, steady_window)
    model = BatchModel.from_system(system) if engine != "scipy" else None
    omega1 = model.first_frequency if model is not None else None
    if omega1 is None:
        from torsio.model.modal import modal_analysis

        omega1 = float(modal_analysis(system.model, 1).frequencies_rad[0])
    period = 2.0 * math.pi / omega1
    if max_step is None:
        max_step = period / 4.0
    if not (math.isfinite(max_step) and max_step > 0):
        raise ConfigError("max_step", f"expected a positive step in s, got {max_step!r}")
    name = "scipy" if model is None else resolve_engine(engine, model)
    omega = rpm_arr * (math.pi / 30.0)
    t_window = duration - steady_window
    h0 = min(1e-3 * period, max_step)
    start = time.perf_counter()
    if name == "scipy":
        out = np.empty((wob_arr.size, 5))
        for k in range(wob_arr.size):
            point = system.at(wob=float(wob_arr[k]), rpm=float(rpm_arr[k]))
            _, info = reference_severity(point, duration, steady_window, rtol=rtol, atol=atol)
            out[k] = (info["bit_speed_max"], info["bit_speed_min"], info["steps"], 0, 0)
    elif wob_arr.size == 0:
        out = np.empty((0, 5))
    elif name == "numpy":
        assert model is not None
        out = _numpy_batch(
            model, wob_arr, omega, duration, t_window, rtol, atol, h0, max_step, max_steps
        )
    else:
        out = np.empty((wob_arr.size, 5))
        assert model is not None
        _run_numba(
            model,
            wob_arr,
            omega,
            duration,
            t_window,
            rtol,
            atol,
            h0,
            max_step,
            max_steps,
            out,
            threads,
        )
    elapsed = time.perf_counter() - start
    status = out[:, 4].astype(np.int64)
    with np.errstate(invalid="ignore"):
        severity = np.where(status == 0, (out[:, 0] - out[:, 1]) / (2.0 * omega), np.nan)
    return BatchResults(
        wob_arr,
        rpm_arr,
        severity,
        out[:, 0],
        out[:, 1],
        out[:, 2].astype(np.int64),
        out[:, 3].astype(np.int64),
        status,
        name,
        duration,
        steady_window,
        float(rtol),
        float(atol),
        elapsed,
    )


def _run_numba(
    model: BatchModel,
    wob: np.ndarray,
    omega: np.ndarray,
    t_end: float,
    t_window: float,
    rtol: float,
    atol: float,
    h0: float,
    hmax: float,
    max_steps: int,
    out: np.ndarray,
    threads: int | None,
) -> None:
    import threading

    assert numba is not None
    arguments = (
        model.dofs,
        model.mass_diag,
        model.mass_upper,
        model.stiffness_diag,
        model.stiffness_upper,
        model.damping_diag,
        model.damping_upper,
        model.drag,
        model.law_code,
        model.law_parameters,
        model.bit_radius,
        wob,
        omega,
        t_end,
        t_window,
        rtol,
        atol,
        h0,
        hmax,
        max_steps,
        _A,
        _C,
        out,
    )
    # numba's thread pool must not be entered from several threads at once (a thread pool
    # executor, a Dask worker with several threads): only the main thread uses it
    if threads == 1 or wob.size == 1 or threading.current_thread() is not threading.main_thread():
        _integrate_batch_serial(arguments)
        return
    previous_threads = numba.get_num_threads()
    previous_chunk = numba.get_parallel_chunksize()
    try:
        if threads is not None:
            numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
        numba.set_parallel_chunksize(1)  # points differ 100x in cost: share them dynamically
        _integrate_batch(arguments)
    finally:
        numba.set_parallel_chunksize(previous_chunk)
        numba.set_num_threads(previous_threads)
