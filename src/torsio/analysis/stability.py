"""Linear stability of steady rotation: where the bit-law slope outweighs the damping.

Steady drilling is the rotation of the whole string at the surface speed,
theta' = Omega at every node (in twist coordinates a constant twist phi*). Small
perturbations about it obey (see :mod:`torsio.physics.system`)

    [I] dphi'' + ([C] + s e_N e_N^T) dphi' + [K] dphi = 0,   s = T_bit'(Omega),

where ``s`` [N m s/rad] is the slope of the bit torque at the steady bit speed: it
acts as a damper at the bit, a *negative* one on the velocity-weakening branch
of the law. Steady rotation is unstable when the first-order system of this
equation has an eigenvalue with positive real part.

Only ``s`` depends on the operating point, so the boundary is found once per
model as a critical bit damping ``s_c < 0`` (unstable for s < s_c). It is where an
eigenvalue crosses the imaginary axis at some lambda = i omega; with the bit
receptance G(omega) = [(K - omega^2 I + i omega C)^-1]_NN the determinant lemma gives

    1 + i omega s G(omega) = 0   =>   Re G(omega) = 0  and  s = 1 / (omega Im G(omega)),

and s_c is the least negative of those values (the first crossing as s decreases
from 0). G is evaluated for thousands of frequencies at once (a continued fraction
for a chain), so s_c costs milliseconds even for 150 DOFs; the result is checked
against the eigenvalues in the tests. For a law proportional to the weight on
bit (Tucker-Wang), T_bit' = W_ob R_bit T'(Omega) with T' the slope of the
normalized law, and the critical weight on bit of linear instability is

    W_ob,lin(Omega) = s_c / (R_bit T'(Omega))   where T'(Omega) < 0  (none elsewhere).

For the 1-DOF model s_c = -c with c = [C]_11 = alpha I + beta k, i.e. the analytic
condition c + W_ob R_bit T'(Omega) = 0.

A top drive with inertia and a controller (:mod:`torsio.physics.top_drives`) is
part of the linear system: the linearization is the Jacobian of the one
description of the dynamics (:class:`torsio.physics.dynamics.Dynamics`) about
steady rotation, top-drive node and controller states included, and the bit
receptance sees the top drive through its impedance Z(i omega) (node 0 of the
chain with dynamic stiffness i omega Z). So the boundary moves with the tuning.
A top drive without a speed loop (``torque``) leaves a rigid-body mode damped
only by the drag: steady rotation is then also lost through a real eigenvalue
at omega = 0 when s < -(total drag seen at the bit).

Examples
--------
>>> from torsio.examples import builtin_config
>>> system = builtin_config().system(strategy="A")
>>> c = system.damping_matrix[0, 0]                     # alpha I + beta k
>>> round(float(critical_bit_damping(system).slope / c), 9)   # s_c = -c for one DOF
-1.0
>>> boundary = stability_boundary(system, rpm=[40.0, 100.0])
>>> [round(float(w) / 1e3, 1) for w in boundary.critical_wob]   # kN
[87.4, 532.0]
>>> bool(growth_rate(system.at(wob=100e3, rpm=40.0)) > 0)
True
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.model.modal import natural_frequencies
from torsio.model.tridiagonal import is_tridiagonal
from torsio.physics.dynamics import Dynamics
from torsio.physics.law_slope import bit_slope
from torsio.physics.system import System
from torsio.units import RPM_TO_RAD_S

__all__ = [
    "CriticalDamping",
    "StabilityBoundary",
    "bit_receptance",
    "critical_bit_damping",
    "eigenvalues",
    "growth_rate",
    "linearized_matrix",
    "stability_boundary",
]


def _bit_slope(system: System, speed: Any, wob: Any) -> np.ndarray:
    return bit_slope(system.law, speed, wob, system.bit_radius)


def linearized_matrix(system: System, bit_slope: float | None = None) -> np.ndarray:
    """First-order matrix of small perturbations about steady rotation.

    State ``[dphi_0..dphi_(n-1), dv_0..dv_(n-1), dz_0..dz_(m-1)]`` (twists [rad], speeds
    [rad/s], then the top drive's controller states), n the chain nodes of
    :class:`torsio.physics.dynamics.Dynamics` (node 0 the top drive when it has
    inertia). It is the Jacobian of the same right-hand side the integrators use,
    reordered.

    Parameters
    ----------
    system : System
        Model, damping, law and top drive; its operating point sets the slope.
    bit_slope : float, optional
        s [N m s/rad] to use instead of the law's slope at the steady bit speed.
    """
    dynamics = Dynamics.from_system(system)
    jacobian = dynamics.linearized(bit_slope)
    m, n = dynamics.states, dynamics.dofs
    order = np.concatenate([m + 2 * np.arange(n), m + 1 + 2 * np.arange(n), np.arange(m)])
    return jacobian[np.ix_(order, order)]


def eigenvalues(system: System, bit_slope: float | None = None) -> np.ndarray:
    """Eigenvalues [1/s] of :func:`linearized_matrix`, largest real part first."""
    values = np.linalg.eigvals(linearized_matrix(system, bit_slope))
    return values[np.argsort(-values.real, kind="stable")]


def growth_rate(system: System, bit_slope: float | None = None) -> float:
    """Largest real part of the eigenvalues [1/s]: > 0 means steady rotation is unstable.

    Eigenvalues zero to round-off (below 1e3 eps of the largest in magnitude) are left
    out: a top drive whose controller integrates the speed error leaves the angle of the
    whole string neutral, an eigenvalue 0 whose computed real part is +-1e-16.
    """
    values = eigenvalues(system, bit_slope)
    neutral = np.abs(values) <= 1e3 * np.finfo(float).eps * np.max(np.abs(values))
    return float(values[~neutral][0].real) if np.any(~neutral) else 0.0


def bit_receptance(system: System, omega: Any) -> np.ndarray:
    """G(omega) = [D(i omega)^-1]_NN [rad/(N m)] at frequencies omega [rad/s].

    The angle at the bit per unit harmonic torque at the bit, with the System's top
    drive: held at constant speed, D = K - omega^2 I + i omega C; with inertia the
    top drive is node 0 with dynamic stiffness i omega Z(i omega) (its impedance)
    plus the top spring and damper. Vectorized over ``omega``.
    """
    return _receptance(Dynamics.from_system(system), omega)


def _receptance(dynamics: Dynamics, omega: Any) -> np.ndarray:
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    k = dynamics.stiffness_matrix
    m = dynamics.mass_matrix
    c = dynamics.damping_matrix
    n = dynamics.dofs
    top_term = np.zeros(w.shape, dtype=complex)
    if dynamics.has_top_node:
        # node 0's own inertia and drag are inside Z: remove them from the chain matrices
        top_impedance = np.asarray(dynamics.top.impedance(w), dtype=complex)
        top_term = 1j * w * (top_impedance - dynamics.top.drag) + w**2 * dynamics.top.inertia
    if is_tridiagonal(k) and is_tridiagonal(m) and is_tridiagonal(c):
        ww = w[:, None]
        diag = np.diag(k) - ww**2 * np.diag(m) + 1j * ww * np.diag(c)
        diag[:, 0] += top_term
        if n == 1:
            return 1.0 / diag[:, 0]
        off = np.diag(k, 1) - ww**2 * np.diag(m, 1) + 1j * ww * np.diag(c, 1)
        pivot = diag[:, 0]
        for i in range(1, n):
            pivot = diag[:, i] - off[:, i - 1] ** 2 / pivot
        return 1.0 / pivot
    dynamic = k[None] - w[:, None, None] ** 2 * m[None] + 1j * w[:, None, None] * c[None]
    dynamic[:, 0, 0] += top_term
    unit = np.zeros(n, dtype=complex)
    unit[-1] = 1.0
    return np.linalg.solve(dynamic, np.broadcast_to(unit, (w.size, n))[..., None])[:, -1, 0]


@attrs.frozen
class CriticalDamping:
    """Where steady rotation of a model loses stability.

    Attributes
    ----------
    slope : float
        s_c [N m s/rad]: steady rotation is unstable for bit-law slopes s < s_c
        (s_c < 0; -inf if no negative slope destabilizes it).
    frequency : float
        omega_c [rad/s]: frequency of the oscillation that grows at the onset.
    """

    slope: float
    frequency: float


def critical_bit_damping(system: System) -> CriticalDamping:
    """s_c and omega_c of a System (its operating point is ignored).

    See the module documentation for the method. ``s_c = 0`` when the model
    has no damping at all (any negative slope destabilizes it).
    """
    model = system.model
    dynamics = Dynamics.from_system(system)
    natural = natural_frequencies(model)  # once per model
    if not np.any(dynamics.damping_matrix) and dynamics.top.states == 0:
        return CriticalDamping(0.0, float(natural[0]))
    low, high = natural[0] / 1000.0, natural[-1] * 10.0
    grid = [np.geomspace(low, high, 4000)]
    for w in natural:
        grid.append(w * np.linspace(0.8, 1.25, 61))
    omegas = np.unique(np.concatenate(grid))
    receptance = _receptance(dynamics, omegas)
    real = receptance.real
    changes = np.flatnonzero(np.sign(real[:-1]) * np.sign(real[1:]) < 0)
    best = CriticalDamping(-math.inf, math.nan)
    if dynamics.has_top_node:  # a real eigenvalue through 0 (rigid rotation, no speed loop)
        static = _static_critical_slope(dynamics)
        if static < 0:
            best = CriticalDamping(static, 0.0)
    if changes.size == 0:
        return best
    # estimate s at each sign change by linear interpolation, refine the best few exactly
    fraction = real[changes] / (real[changes] - real[changes + 1])
    w_est = omegas[changes] + fraction * (omegas[changes + 1] - omegas[changes])
    g_est = receptance[changes].imag + fraction * (
        receptance[changes + 1].imag - receptance[changes].imag
    )
    with np.errstate(divide="ignore"):
        s_est = 1.0 / (w_est * g_est)
    order = np.argsort(np.where(s_est < 0, -s_est, np.inf))[:4]
    for index in order:
        if not s_est[index] < 0:
            continue
        a, b = omegas[changes[index]], omegas[changes[index] + 1]
        root = _sign_change(lambda x: _receptance(dynamics, x).real, a, b)
        g = complex(_receptance(dynamics, root)[0])
        s = 1.0 / (root * g.imag)
        if s < 0 and s > best.slope:
            best = CriticalDamping(float(s), float(root))
    return best


def _sign_change(function: Any, low: float, high: float) -> float:
    """The point in [low, high] where a continuous, vectorized ``function`` changes sign.

    Each round evaluates it at 33 points of the bracket at once and keeps the piece whose
    ends differ in sign (32 times shorter), until the bracket is 1e-13 of ``high``
    long; the root is then interpolated linearly. The function is called with arrays, so a
    round costs one vectorized evaluation (as against a scalar root search's one call per
    iterate, and without importing scipy.optimize into every map).

    >>> round(_sign_change(lambda x: x**2 - 2.0, 1.0, 2.0), 12)
    1.414213562373
    """
    for _ in range(12):
        points = np.linspace(low, high, 33)
        values = function(points)
        zero = np.flatnonzero(values == 0.0)
        if zero.size:
            return float(points[zero[0]])
        change = int(np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))[0])
        low, high = float(points[change]), float(points[change + 1])
        f_low, f_high = float(values[change]), float(values[change + 1])
        if high - low <= 1e-13 * abs(high):
            break
    return low + f_low / (f_low - f_high) * (high - low)


def _static_critical_slope(dynamics: Dynamics) -> float:
    """The slope s at which an eigenvalue of the linearization passes through 0 (-inf: none).

    The slope enters one entry of the Jacobian, so det A(s) is affine in s:
    s* = -det A(0) / (det A(1) - det A(0)), from log-determinants.
    """
    sign0, log0 = np.linalg.slogdet(dynamics.linearized(0.0))
    sign1, log1 = np.linalg.slogdet(dynamics.linearized(1.0))
    if sign0 == 0:
        return 0.0
    ratio = sign1 * sign0 * math.exp(log1 - log0) if sign1 != 0 else 0.0
    if abs(ratio - 1.0) < 1e-9:
        return -math.inf
    return -1.0 / (ratio - 1.0)


@attrs.frozen
class StabilityBoundary:
    """Critical weight on bit of linear instability over a range of rotary speeds.

    Attributes
    ----------
    rpm : ndarray
        Surface rotary speeds [rpm].
    critical_wob : ndarray
        Lowest weight on bit [N] at which steady rotation is linearly unstable;
        NaN where no weight on bit destabilizes it (law slope >= 0 at that speed).
    critical_slope : float
        s_c [N m s/rad] (see :class:`CriticalDamping`).
    onset_frequency : float
        omega_c [rad/s] of the oscillation that grows first.
    """

    rpm: np.ndarray
    critical_wob: np.ndarray
    critical_slope: float
    onset_frequency: float

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON (NaN -> None)."""
        return {
            "rpm": self.rpm.tolist(),
            "critical_wob": [None if not math.isfinite(w) else float(w) for w in self.critical_wob],
            "critical_slope": self.critical_slope,
            "onset_frequency": self.onset_frequency,
        }


def stability_boundary(system: System, rpm: Any) -> StabilityBoundary:
    """Critical weight on bit W_ob,lin(Omega) [N] of linear instability at each rpm.

    Parameters
    ----------
    system : System
    rpm : array_like
        Surface rotary speeds [rpm], > 0.

    Notes
    -----
    For laws proportional to the weight on bit the boundary is the closed form
    of the module documentation. For other laws the weight on bit where the
    slope reaches s_c is found by a root search up to 1e9 N.
    """
    speeds = np.atleast_1d(np.asarray(rpm, dtype=float))
    if not (np.isfinite(speeds).all() and (speeds > 0).all()):
        raise ConfigError("rpm", f"expected positive rotary speeds, got {speeds.tolist()!r}")
    critical = critical_bit_damping(system)
    omega = speeds * RPM_TO_RAD_S
    wob = np.full(speeds.shape, np.nan)
    if math.isfinite(critical.slope):
        reference = 1e5
        unit = _finite_slopes(system, omega, 1.0)
        scaled = _finite_slopes(system, omega, reference)
        if np.allclose(scaled, reference * unit, rtol=1e-9, atol=1e-12 * np.abs(scaled).max()):
            with np.errstate(divide="ignore", invalid="ignore"):
                wob = np.where(unit < 0, critical.slope / unit, np.nan)
            if critical.slope == 0.0:
                wob = np.where(unit < 0, 0.0, np.nan)
        else:
            for i, w in enumerate(omega):
                wob[i] = _wob_at_slope(system, w, critical.slope)
    return StabilityBoundary(speeds, wob, critical.slope, critical.frequency)


def _finite_slopes(system: System, omega: np.ndarray, wob: float) -> np.ndarray:
    """The law's slopes at the speeds ``omega`` [rad/s]; ConfigError naming it if not finite."""
    with np.errstate(all="ignore"):
        slopes = np.asarray(_bit_slope(system, omega, wob), dtype=float)
    if not np.isfinite(slopes).all():
        from torsio.plugins import describe_bit_law

        bad = int(np.flatnonzero(~np.isfinite(np.broadcast_to(slopes, omega.shape)))[0])
        raise ConfigError(
            "bit_rock",
            f"the slope of the bit-rock law {describe_bit_law(system.law)} {system.law!r} at "
            f"{omega[bad]:g} rad/s and wob = {wob:g} N is "
            f"{float(np.broadcast_to(slopes, omega.shape)[bad])}: the linear stability boundary "
            "needs a finite slope; check the law's parameters",
        )
    return slopes


def _wob_at_slope(system: System, omega: float, target: float) -> float:
    def excess(wob: float) -> float:
        return float(_finite_slopes(system, np.atleast_1d(omega), wob)[0]) - target

    if excess(0.0) < 0:
        return 0.0
    high = 1e3
    while excess(high) >= 0:
        high *= 4.0
        if high > 1e9:
            return math.nan
    import scipy.optimize  # a law not proportional to the weight on bit only

    return float(scipy.optimize.brentq(excess, 0.0, high, xtol=1e-9 * high))
