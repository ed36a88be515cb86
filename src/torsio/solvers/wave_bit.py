"""The bit's equation of the distributed model: one scalar root per time step.

BDF2 for the bit (inertia J_b, drag, the pipe torque p - Z w and the torque on bit of
any law) gives, at every step, k w + T_bit(w) = r with k > 0 (module
:mod:`torsio.solvers.characteristics`). :func:`_solve_bit` takes the root nearest the
previous speed in the direction of motion (the motion's branch, where a velocity-weakening
law gives several), with the law's compiled torque and slope.

Examples
--------
>>> import numpy as np
>>> from torsio.solvers.law_kernels import compile_law_function
>>> def torque(p, w, wob, radius):
...     return p[0] + p[1] * w
>>> def slope(p, w, wob, radius):
...     return p[1]
>>> w, t = _solve_bit(10.0, 20.0, 0.0, 5.0, 1.0, compile_law_function(torque),
...                   compile_law_function(slope), np.array([5.0, 2.0]), 0.0, 0.0)
>>> round(w, 12), round(t, 12)  # 10 w + 5 + 2 w = 20
(1.25, 7.5)
"""

from __future__ import annotations

import math
from typing import Any

from torsio.solvers.compiled import njit

try:  # a dependency; without an importable numba the solve runs as plain Python
    from numba import types

    _F8 = types.float64
    _VECTOR = types.float64[::1]
    _LAW = types.FunctionType(_F8(_VECTOR, _F8, _F8, _F8))
    _SOLVE_SIGNATURE: Any = types.UniTuple(_F8, 2)(
        _F8, _F8, _F8, _F8, _F8, _LAW, _LAW, _VECTOR, _F8, _F8
    )
except ImportError:  # pragma: no cover - exercised only without numba
    _SOLVE_SIGNATURE = None

_NEWTON_TOLERANCE = 1e-12
"""Relative tolerance on the bit speed."""


@njit(_SOLVE_SIGNATURE, cache=True, nogil=True, _nrt=False)
def _solve_bit(k, rhs, w_now, t_now, w_guess, torque, slope, parameters, wob, radius):  # type: ignore[no-untyped-def,unused-ignore]
    """(w, T_bit(w)): the root of f(w) = k w + T_bit(w) - rhs nearest ``w_now`` in the
    direction of motion, and the torque there.

    ``t_now`` = T_bit(w_now); the sign of f(w_now), that of the net decelerating torque,
    gives the direction. The search goes from ``w_now`` that way in steps no longer than
    |f(w_now)| / k, doubled while no sign change brackets the root (a root is within the
    first when T_bit' >= 0). ``w_guess`` (the extrapolated speed) is the first trial when
    it lies within that first step; it is kept if it brackets the root or f heads for one
    from it, else the search starts over from ``w_now`` (roots may lie between). Newton
    steps use the slope of the first trial (a chord method, refreshed when it converges
    slowly), inside the bracket once there is one; the root is taken when the step is
    below 1e-12 relative or the rate of the last two steps puts the error left below that.
    """
    f0 = k * w_now + t_now - rhs
    if f0 == 0.0:
        return w_now, t_now
    positive = f0 > 0.0
    direction = -1.0 if positive else 1.0
    expansion = abs(f0) / k + 1e-9 * (abs(w_now) + 1.0)  # the longest step from low
    if 0.0 < (w_guess - w_now) * direction <= expansion:
        x = w_guess
    else:
        x = w_now + direction * expansion
    low = w_now  # f has the sign of f0 at low, the other one at high
    high = math.nan
    t = torque(parameters, x, wob, radius)
    f = k * x + t - rhs
    if not math.isfinite(f):
        return math.nan, math.nan
    derivative = k + slope(parameters, x, wob, radius)
    if (f > 0.0) == positive and (abs(f) >= abs(f0) or derivative * direction * f > 0.0):
        # the guess brackets nothing and f is not heading for a root from it: start over
        # from w_now (roots may lie between the two)
        x, t, f = w_now, t_now, f0
        derivative = k + slope(parameters, x, wob, radius)
    last_delta = 0.0
    for _ in range(300):
        if f == 0.0:
            return x, t
        if (f > 0.0) == positive:
            low = x
        else:
            high = x
        candidate = x - f / derivative if derivative != 0.0 else math.nan
        scale = abs(x) + 1e-6
        delta = abs(candidate - x)
        if delta <= _NEWTON_TOLERANCE * scale:  # converged (the bracket holds x)
            return candidate, t + (derivative - k) * (candidate - x)
        if math.isnan(high):  # no bracket yet: on in the direction of motion, not too far
            safe = 0.0 < (candidate - low) * direction <= expansion
            if not safe:
                expansion *= 2.0
                candidate = low + direction * expansion
        else:
            lo, hi = (low, high) if low < high else (high, low)
            safe = lo < candidate < hi
            if not safe:
                candidate = 0.5 * (low + high)
                if hi - lo <= _NEWTON_TOLERANCE * scale:
                    return candidate, torque(parameters, candidate, wob, radius)
        delta = abs(candidate - x)
        rate = 1.0  # of convergence: this step over the last (1: unknown, or not Newton)
        if safe:
            if last_delta > 0.0:
                rate = delta / last_delta
                left = delta * rate / (1.0 - rate) if rate < 0.5 else math.inf
                if delta <= 1e-4 * scale and left <= _NEWTON_TOLERANCE * scale:
                    return candidate, t + (derivative - k) * (candidate - x)
            else:
                rate = 0.0  # the first Newton step: go on with its slope
        last_delta = delta if safe else 0.0
        x = candidate
        t = torque(parameters, x, wob, radius)
        f = k * x + t - rhs
        if not math.isfinite(f):
            return math.nan, math.nan
        if rate > 0.1:  # slow: a fresh slope (Newton)
            derivative = k + slope(parameters, x, wob, radius)
    return math.nan, math.nan
