"""Cubic Hermite steps and the detection of a steady cycle, for the compiled batch kernel.

Between two accepted steps the kernel knows each state and its derivative at both ends,
so every state has a cubic Hermite interpolant on the step (fourth-order accurate,
like RODAS4 itself). From it:

* :func:`extremes_of_cubic` gives the bit speed's extremes inside a step, exactly for
  the cubic (S_SS needs the peaks, which fall between steps);
* :func:`integral_of_cubic` gives the mean top-drive speed over the window;
* :func:`track_cycle` watches the bit speed cross the reference speed upwards (a
  Poincaré section) and says when the motion has settled on a cycle, so that the run
  can end early with the same S_SS.

When does a run end early?
--------------------------
A cycle ends at each upward crossing of the bit speed through Omega_ref. At each crossing
the tracker takes the state of every node (by the Hermite interpolant) and its change
from the previous crossing, in S_SS units::

    d_k = max_i max(omega_1 |phi_i,k - phi_i,k-1|, |v_i,k - v_i,k-1|) / (2 Omega)

The run ends at crossing k (k >= 3: two complete cycles after the start-up) when

    N_left * max(d_k, d_{k-1}) <= tolerance,   N_left = (t_end - t_k) / (t_k - t_{k-1}),

that is, even if every cycle still to come moved the state as much as the larger of the
last two, it could not move by more than ``tolerance`` before the run's end; and when the
steady window holds at least one cycle. S_SS is then that of the last cycle (with the
part of the window already run), whose peaks carry the integration's own scatter, as the
full run's do. The state at a crossing is used rather than the peaks: it repeats to the
integration's accuracy (about 10 rtol here), the peaks only to about 10 times that.

A stick-slip cycle is reached within a cycle or two (the stuck start is on it); a
decaying oscillation ends early once its amplitude is far below the tolerance; a motion
that lingers near a cycle and leaves it (a saddle) changes too much to end early.
"""

from __future__ import annotations

import math

from torsio.solvers.compiled import njit, njit_inner
from torsio.solvers.layouts import (
    CROSS_RATE,
    CROSS_TWIST,
    CYCLE_CHANGE,
    CYCLE_COUNT,
    CYCLE_MAX,
    CYCLE_MIN,
    CYCLE_RUN_MAX,
    CYCLE_RUN_MIN,
    CYCLE_SET_OMEGA_1,
    CYCLE_SET_T_END,
    CYCLE_SET_TOLERANCE,
    CYCLE_SET_TWICE_OMEGA,
    CYCLE_SET_WINDOW,
    CYCLE_T_LAST,
)

__all__ = [
    "extremes_of_cubic",
    "hermite",
    "integral_of_cubic",
    "track_cycle",
    "upward_root",
]


@njit(cache=True, error_model="numpy", _nrt=False)
def hermite(u0: float, u1: float, d0: float, d1: float, x: float) -> float:
    """The cubic Hermite interpolant at x in [0, 1] (d0, d1: derivatives times the step)."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1
    return u0 + x * (d0 + x * (c2 + x * c3))


@njit(cache=True, error_model="numpy", _nrt=False)
def extremes_of_cubic(
    u0: float, u1: float, d0: float, d1: float, lo: float, hi: float, vmax: float, vmin: float
) -> tuple[float, float]:
    """Max and min of the cubic Hermite interpolant on [lo, hi] within [0, 1], with the
    running (vmax, vmin) (d0, d1 scaled by the step)."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1
    ulo = u0 + lo * (d0 + lo * (c2 + lo * c3))
    uhi = u0 + hi * (d0 + hi * (c2 + hi * c3))
    vmax = max(vmax, ulo, uhi)
    vmin = min(vmin, ulo, uhi)
    a = 3.0 * c3  # u'(x) = d0 + 2 c2 x + 3 c3 x^2
    b = 2.0 * c2
    if abs(a) > 1e-14 * (abs(b) + abs(d0)):
        disc = b * b - 4.0 * a * d0
        if disc >= 0.0:
            sq = math.sqrt(disc)
            q = -0.5 * (b + math.copysign(sq, b))
            for root in (q / a, d0 / q if q != 0.0 else -1.0):
                if lo < root < hi:
                    u = u0 + root * (d0 + root * (c2 + root * c3))
                    vmax = max(vmax, u)
                    vmin = min(vmin, u)
    elif b != 0.0:
        root = -d0 / b
        if lo < root < hi:
            u = u0 + root * (d0 + root * (c2 + root * c3))
            vmax = max(vmax, u)
            vmin = min(vmin, u)
    return vmax, vmin


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def integral_of_cubic(u0: float, u1: float, d0: float, d1: float, lo: float) -> float:
    """Integral over x in [lo, 1] of the cubic Hermite interpolant (in units of the step)."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1
    upper = u0 + d0 / 2.0 + c2 / 3.0 + c3 / 4.0
    lower = lo * (u0 + lo * (d0 / 2.0 + lo * (c2 / 3.0 + lo * c3 / 4.0)))
    return upper - lower


@njit(cache=True, error_model="numpy", _nrt=False)
def upward_root(u0: float, u1: float, d0: float, d1: float) -> float:
    """The x in (0, 1] where the cubic crosses zero, for u0 < 0 <= u1 (Newton, bisection
    safeguard, to 1e-13)."""
    c2 = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1
    c3 = 2.0 * u0 + d0 - 2.0 * u1 + d1
    lo, hi = 0.0, 1.0
    x = u0 / (u0 - u1)  # the secant's root as the first guess
    for _ in range(100):
        u = u0 + x * (d0 + x * (c2 + x * c3))
        if u == 0.0:
            return x
        if u < 0.0:
            lo = x
        else:
            hi = x
        slope = d0 + x * (2.0 * c2 + 3.0 * x * c3)
        step = x - u / slope if slope != 0.0 else -1.0
        if not lo < step < hi:
            step = 0.5 * (lo + hi)
        if abs(step - x) < 1e-13:
            return step
        x = step
    return x


@njit_inner(cache=True, error_model="numpy", _nrt=False)
def track_cycle(
    cycle, t, h, bit0, bit_acc0, phi0, v0, acc0, phi1, v1, acc1, cross, settings
) -> bool:
    """Follow one accepted step [t, t + h]; True when the motion is on a steady cycle.

    ``cycle`` (``CYCLE_*`` of :mod:`torsio.solvers.layouts`) is the tracker's state and
    ``cross`` (``CROSS_ROWS``, n) the twists and twist rates of the nodes at the last
    crossing, both zeroed before the run. ``bit0``, ``bit_acc0``: the bit's twist rate and
    acceleration at t; (phi1, v1, acc1): twists, twist rates and accelerations of the nodes
    at t + h (bit last); (phi0, v0, acc0): the same at t, read only if the bit crosses the
    reference speed upwards in the step. ``settings`` (``CYCLE_SET_*``): 2 Omega [rad/s],
    omega_1 [rad/s], t_end [s], window length [s], tolerance. See the module documentation.
    """
    n = v1.size
    bit1 = v1[n - 1]
    d0 = h * bit_acc0
    d1 = h * acc1[n - 1]
    if not bit0 < 0.0 <= bit1:
        if cycle[CYCLE_COUNT] > 0.0:
            cycle[CYCLE_RUN_MAX], cycle[CYCLE_RUN_MIN] = extremes_of_cubic(
                bit0, bit1, d0, d1, 0.0, 1.0, cycle[CYCLE_RUN_MAX], cycle[CYCLE_RUN_MIN]
            )
        return False
    scale = settings[CYCLE_SET_TWICE_OMEGA]
    omega1 = settings[CYCLE_SET_OMEGA_1]
    t_end = settings[CYCLE_SET_T_END]
    window = settings[CYCLE_SET_WINDOW]
    tolerance = settings[CYCLE_SET_TOLERANCE]
    x = upward_root(bit0, bit1, d0, d1)
    t_cross = t + x * h
    count = cycle[CYCLE_COUNT]
    top, bottom = extremes_of_cubic(
        bit0, bit1, d0, d1, 0.0, x, cycle[CYCLE_RUN_MAX], cycle[CYCLE_RUN_MIN]
    )
    change = 0.0 if count >= 1.0 else math.inf
    for i in range(n):  # the state at this crossing against the last one's
        twist = hermite(phi0[i], phi1[i], h * v0[i], h * v1[i], x)
        rate = hermite(v0[i], v1[i], h * acc0[i], h * acc1[i], x)
        if count >= 1.0:
            moved = max(
                omega1 * abs(twist - cross[CROSS_TWIST, i]), abs(rate - cross[CROSS_RATE, i])
            )
            change = max(change, moved / scale)
        cross[CROSS_TWIST, i] = twist
        cross[CROSS_RATE, i] = rate
    period = t_cross - cycle[CYCLE_T_LAST]
    steady = (
        count >= 3.0
        and period <= window
        and (t_end - t_cross) / period * max(change, cycle[CYCLE_CHANGE]) <= tolerance
    )
    if count >= 1.0:
        cycle[CYCLE_MAX] = top
        cycle[CYCLE_MIN] = bottom
    cycle[CYCLE_CHANGE] = change
    cycle[CYCLE_COUNT] = count + 1.0
    cycle[CYCLE_T_LAST] = t_cross
    cycle[CYCLE_RUN_MAX], cycle[CYCLE_RUN_MIN] = extremes_of_cubic(
        bit0, bit1, d0, d1, x, 1.0, -math.inf, math.inf
    )
    return steady
