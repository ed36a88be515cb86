"""The bit's own history and the delayed position it gives: d = n (U(t) − U(t − t_n)).

A run keeps the bit's past motion in a ring buffer of (t, Φ, Ω, U, V), one entry per step.
The bit never turns backwards, so Φ never decreases along the buffer, and the time
t − t_n at which the bit was at the angle Φ(t) − 2π/n is found by walking forward from
the last segment used (the target angle never decreases either) and solving, on the
segment [t_j, t_j+1] that holds it, the cubic Hermite interpolant of Φ (values Φ_j, slopes
Ω_j) for the time, by Newton's method kept inside the segment. U there is the cubic
Hermite interpolant of (U_j, V_j) at the same time. The interpolants reproduce a motion
of degree three exactly and err by O(h⁴) otherwise, so a prescribed rotation gives the
delay to round-off at the steps used (tests/test_axial_transient.py).

Off bottom the blades cut nothing and the rock surface stays where the last cut left it:
the position stored for the blade now passing is the surface it leaves, max(U, the surface
it met) (:func:`keep_surface`), so the next blade meets the rock, not the path of a bit
that bounced (while the bit cuts the two are the same: d = n (U(t) − U(t − t_n))).

These functions are compiled and called from the step loop of
:mod:`torsio.solvers.axial_kernel`; the buffer is the 5 × capacity array ``history`` (rows t, Φ,
Ω, U, V) and ``cursor`` holds [segment start j (absolute), entries written].

Examples
--------
>>> import numpy as np
>>> history, cursor = np.zeros((5, 8)), np.zeros(2)
>>> for j in range(8):  # Φ = t, U = 2 t on t = 0..0.7
...     append(history, cursor, 0.1 * j, 0.1 * j, 1.0, 0.2 * j, 2.0)
>>> out = np.zeros(2)
>>> delayed_state(history, cursor, 0.45, out)
True
>>> [round(float(x), 12) for x in out]  # the time and U at the angle 0.45
[0.45, 0.9]
"""

from __future__ import annotations

from torsio.solvers.compiled import njit

__all__ = ["append", "delayed_state", "keep_surface"]


@njit(cache=True, error_model="numpy", _nrt=False)
def append(history, cursor, t, phi, omega, u, v) -> None:  # pragma: no cover - compiled
    """Write the entry (t, Φ, Ω, U, V) after the newest one (the oldest is overwritten)."""
    capacity = history.shape[1]
    k = int(cursor[1]) % capacity
    history[0, k] = t
    history[1, k] = phi
    history[2, k] = omega
    history[3, k] = u
    history[4, k] = v
    cursor[1] += 1.0


@njit(cache=True, error_model="numpy", _nrt=False)
def delayed_state(history, cursor, angle, out) -> bool:  # pragma: no cover - compiled
    """Time and axial position when the bit was at ``angle`` [rad]: out = [t, U].

    Returns False when the angle is older than the buffer holds (the bit stood still
    longer than the buffer spans) or newer than its newest entry.
    """
    capacity = history.shape[1]
    written = int(cursor[1])
    j = int(cursor[0])
    oldest = written - capacity
    if j < oldest:
        return False
    newest = written - 1
    while j + 1 < newest and history[1, (j + 1) % capacity] <= angle:
        j += 1
    cursor[0] = j
    a, b = j % capacity, (j + 1) % capacity
    p0, p1 = history[1, a], history[1, b]
    if angle < p0 or angle > p1 or p1 <= p0:
        return False
    t0, dt = history[0, a], history[0, b] - history[0, a]
    m0, m1 = history[2, a] * dt, history[2, b] * dt
    s = (angle - p0) / (p1 - p0)
    low, high = 0.0, 1.0
    for _ in range(30):
        s2 = s * s
        s3 = s2 * s
        value = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0
        value += (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1 - angle
        if value > 0:
            high = s
        else:
            low = s
        slope = (6 * s2 - 6 * s) * (p0 - p1) + (3 * s2 - 4 * s + 1) * m0 + (3 * s2 - 2 * s) * m1
        step = value / slope if slope > 0 else 2.0
        new = s - step
        if not (low <= new <= high):
            new = 0.5 * (low + high)
        if abs(new - s) <= 1e-16:
            s = new
            break
        s = new
    s2 = s * s
    s3 = s2 * s
    u0, u1 = history[3, a], history[3, b]
    w0, w1 = history[4, a] * dt, history[4, b] * dt
    out[0] = t0 + s * dt
    out[1] = (2 * s3 - 3 * s2 + 1) * u0 + (s3 - 2 * s2 + s) * w0
    out[1] += (-2 * s3 + 3 * s2) * u1 + (s3 - s2) * w1
    return True


@njit(cache=True, error_model="numpy", _nrt=False)
def keep_surface(history, cursor, surface, step) -> None:  # pragma: no cover - compiled
    """Replace the newest entry's position by the rock surface the blade leaves there,
    ``surface`` = max(U, the surface it met) [m], and its slope: V while the bit cuts
    (the two are then equal), the backward difference over ``step`` [s] off bottom."""
    capacity = history.shape[1]
    k = (int(cursor[1]) - 1) % capacity
    if surface != history[3, k]:
        before = history[3, (k - 1) % capacity]
        history[4, k] = (surface - before) / step
        history[3, k] = surface
