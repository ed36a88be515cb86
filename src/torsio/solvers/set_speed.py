"""The set speed against time: one table, read by every engine.

A top drive's set speed that changes in time (a start-up ramp, a recorded top-drive speed)
is a table (:meth:`torsio.physics.top_drive_boundary.TopDriveBoundary.set_speed_table`):
times [s] and set speeds [rad/s], linear between its points and constant before the first
and after the last. The wave model's stepping reads the speed (:func:`table_speed`); the
lumped engines, in twist coordinates about Omega_ref, also need the angle a held top has
turned through beyond Omega_ref t, the top's twist

    psi(t) = integral from 0 to t of (Omega_set(s) - Omega_ref) ds,

which the table carries as a third row (:func:`twist_table`: exact for the piecewise linear
speed) so that :func:`table_twist` reads it in O(log k), like the speed. For a ramp of
length T to Omega_ref, psi = -Omega_ref T / 2 from T on: the top is half a ramp's worth of
turns behind a top that turned at Omega_ref from t = 0.

The functions are compiled with numba into the kernels and callable from Python
(:func:`table_at` over an array of times), all but the kernels' own search of a segment;
without numba they run as plain Python.

Examples
--------
>>> import numpy as np
>>> ramp = twist_table(np.array([[0.0, 2.0], [0.0, 6.0]]), reference=6.0)
>>> table_speed(ramp, 0.5), table_twist(ramp, 1.0, 6.0), table_twist(ramp, 9.0, 6.0)
(1.5, -4.5, -6.0)
>>> next_table_time(ramp, 0.5), next_table_time(ramp, 2.0)
(2.0, inf)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from torsio.solvers.compiled import njit, njit_inner
from torsio.solvers.layouts import TABLE_ROWS, TABLE_SPEED, TABLE_TIME, TABLE_TWIST

__all__ = [
    "fill_twists",
    "next_table_time",
    "table_at",
    "table_rate",
    "table_speed",
    "table_twist",
    "twist_table",
]


@njit_inner(cache=True, nogil=True, _nrt=False, error_model="numpy")
def _segment(times, time):  # type: ignore[no-untyped-def,unused-ignore]
    """The index i of the table's segment [times[i], times[i + 1]) that holds ``time``
    (bisection; 0 before the table's second point, the last index from its last on)."""
    last = times.size - 1
    if time >= times[last]:
        return last
    low = 0
    high = last
    while high - low > 1:
        middle = (low + high) // 2
        if times[middle] <= time:
            low = middle
        else:
            high = middle
    return low


@njit(cache=True, nogil=True, _nrt=False, error_model="numpy")
def table_rate(table, time):  # type: ignore[no-untyped-def,unused-ignore]
    """d Omega_set / dt [rad/s^2] on the table's segment from ``time`` on (0 before the
    first point and from the last on)."""
    times = table[TABLE_TIME]
    speeds = table[TABLE_SPEED]
    if time < times[0]:
        return 0.0
    low = _segment(times, time)
    if low == times.size - 1:
        return 0.0
    return (speeds[low + 1] - speeds[low]) / (times[low + 1] - times[low])


@njit(cache=True, nogil=True, _nrt=False, error_model="numpy")
def table_speed(table, time):  # type: ignore[no-untyped-def,unused-ignore]
    """The speed of ``table`` (rows time [s], speed [rad/s]) at ``time``: linear between its
    points, constant beyond them.

    >>> ramp, step = np.array([[0.0, 2.0], [0.0, 6.0]]), np.array([[0.0], [3.0]])
    >>> table_speed(ramp, 0.5), table_speed(step, 9.0)
    (1.5, 3.0)
    """
    times = table[TABLE_TIME]
    speeds = table[TABLE_SPEED]
    if time <= times[0]:
        return speeds[0]
    low = _segment(times, time)
    if low == times.size - 1:
        return speeds[low]
    share = (time - times[low]) / (times[low + 1] - times[low])
    return speeds[low] + share * (speeds[low + 1] - speeds[low])


@njit(cache=True, nogil=True, _nrt=False, error_model="numpy")
def table_twist(table, time, reference):  # type: ignore[no-untyped-def,unused-ignore]
    """psi(t) [rad] of a :func:`twist_table` built for Omega_ref = ``reference`` [rad/s] at
    ``time``: the integral of the set speed less the reference from 0 to ``time``
    (quadratic between the points, exact)."""
    times = table[TABLE_TIME]
    speeds = table[TABLE_SPEED]
    twists = table[TABLE_TWIST]
    low = 0 if time <= times[0] else _segment(times, time)
    mean = 0.5 * (speeds[low] + table_speed(table, time))  # the speed's mean since times[low]
    return twists[low] + (time - times[low]) * (mean - reference)


@njit(cache=True, nogil=True, _nrt=False, error_model="numpy")
def fill_twists(table, reference):  # type: ignore[no-untyped-def,unused-ignore]
    """Write the row ``TABLE_TWIST`` of ``table``: psi at each of its times for Omega_ref =
    ``reference`` [rad/s] (the trapezoidal rule, exact for the linear pieces)."""
    times = table[TABLE_TIME]
    speeds = table[TABLE_SPEED]
    twists = table[TABLE_TWIST]
    twists[0] = 0.0
    for i in range(1, times.size):
        mean = 0.5 * (speeds[i] + speeds[i - 1])
        twists[i] = twists[i - 1] + (times[i] - times[i - 1]) * (mean - reference)
    at_zero = table_twist(table, 0.0, reference)  # psi(0) = 0
    for i in range(times.size):
        twists[i] -= at_zero


def twist_table(table: Any, reference: float) -> np.ndarray:
    """``table`` (rows time [s], set speed [rad/s]) with the row ``TABLE_TWIST``
    (:func:`fill_twists`) for Omega_ref = ``reference`` [rad/s], shape (``TABLE_ROWS``, k),
    C-contiguous for the kernels."""
    table = np.asarray(table, dtype=float)
    out = np.zeros((TABLE_ROWS, table.shape[1]))
    out[TABLE_TIME], out[TABLE_SPEED] = table[TABLE_TIME], table[TABLE_SPEED]
    fill_twists(out, float(reference))
    return out


def table_at(table: Any, time: Any, reference: float) -> tuple[Any, Any]:
    """(Omega_set [rad/s], psi [rad]) of a :func:`twist_table` for Omega_ref = ``reference``
    at ``time`` [s]: floats, or arrays of the shape of ``time``. ValueError if ``time`` is
    None (the set speed changes in time: a time is needed)."""
    if time is None:
        raise ValueError("the set speed changes in time: give the time")
    table = np.ascontiguousarray(table, dtype=float)
    flat = np.asarray(time, dtype=float).ravel()
    speeds = np.array([table_speed(table, t) for t in flat]).reshape(np.shape(time))
    twists = np.array([table_twist(table, t, reference) for t in flat]).reshape(np.shape(time))
    return speeds[()], twists[()]


@njit(cache=True, nogil=True, _nrt=False, error_model="numpy")
def next_table_time(table, time):  # type: ignore[no-untyped-def,unused-ignore]
    """The first time [s] of the table after ``time`` (inf: none), where the set speed's
    slope may jump: a step of a lumped engine ends there."""
    times = table[TABLE_TIME]
    if time < times[0]:
        return times[0]
    low = _segment(times, time)
    if low == times.size - 1:
        return np.inf
    return times[low + 1]
