"""The buffers of the distributed model: transport by moving heads, the point dampers.

Each section keeps its p and its m in a buffer of k = ``drag_spacing`` rows (layout in
:class:`torsio.solvers.wave_state.KernelLayout`): slot sigma, in row sigma % k and
column sigma // k, holds node sigma - head. A step of transport moves the p head one
slot back and the m head one slot on (:func:`_advance`), so no value is copied, and the
regular dampers at nodes k, 2k, ... are one contiguous run of a row of p and one of m
(:func:`_dampers`), which the compiler vectorizes.

Compiled with numba (cache=True, no runtime: work space comes from the caller); plain
Python without numba.
"""

from __future__ import annotations

from torsio.solvers.compiled import njit
from torsio.solvers.layouts import (
    BUFFER_START,
    CELLS,
    HEAD_M_COLUMN,
    HEAD_M_ROW,
    HEAD_P_COLUMN,
    HEAD_P_ROW,
    LAST_COLUMN,
    LAST_ROW,
    LIVE,
    NODE_START,
    WIDTH,
)


@njit(cache=True, nogil=True, _nrt=False)
def _dampers(p, m, ratio):  # type: ignore[no-untyped-def,unused-ignore]
    """Point dampers on contiguous slices of arriving (p, m); ratio = 2 Z / (2 Z + c).

    A function of its own on slices indexed from 0, so that the compiler vectorizes it.
    """
    for i in range(p.size):
        arriving_p = p[i]
        jump = ratio * (arriving_p - m[i])  # 2 Z v
        p[i] = m[i] + jump
        m[i] = arriving_p - jump


@njit(cache=True, nogil=True, _nrt=False)
def _dampers_with_power(p, m, ratio):  # type: ignore[no-untyped-def,unused-ignore]
    """:func:`_dampers`, returning the sum of (p - m)^2 of the arriving pairs."""
    total = 0.0
    for i in range(p.size):
        arriving_p = p[i]
        difference = arriving_p - m[i]
        total += difference * difference
        jump = ratio * difference
        p[i] = m[i] + jump
        m[i] = arriving_p - jump
    return total


@njit(cache=True, nogil=True, _nrt=False)
def _slot(start, width, spacing, row, column, rows_on, columns_on):  # type: ignore[no-untyped-def,unused-ignore]
    """Index of the slot ``rows_on`` rows and ``columns_on`` columns past (row, column),
    carrying into the next column (a node ``columns_on * spacing + rows_on`` on)."""
    r = row + rows_on
    c = column + columns_on
    if r >= spacing:
        r -= spacing
        c += 1
    return start + r * width + c


@njit(cache=True, nogil=True, _nrt=False)
def _move_span(buffer, start, width, spacing, first, count, to):  # type: ignore[no-untyped-def,unused-ignore]
    """Copy columns ``first .. first + count - 1`` of every row to ``to ..``."""
    for r in range(spacing):
        row = start + r * width
        for c in range(count):  # the two spans do not overlap
            buffer[row + to + c] = buffer[row + first + c]


@njit(cache=True, nogil=True, _nrt=False)
def _advance(layout, spacing, P, M, heads):  # type: ignore[no-untyped-def,unused-ignore]
    """Transport: every p one node down (its head one slot back), every m one node up."""
    for s in range(layout.shape[0]):
        start = layout[s, BUFFER_START]
        width = layout[s, WIDTH]
        live = layout[s, LIVE]
        if heads[s, HEAD_P_ROW] > 0:
            heads[s, HEAD_P_ROW] -= 1
        else:
            heads[s, HEAD_P_ROW] = spacing - 1
            if heads[s, HEAD_P_COLUMN] == 0:  # the span at the left end: over to the right half
                _move_span(P, start, width, spacing, 0, live, live)
                heads[s, HEAD_P_COLUMN] = live
            heads[s, HEAD_P_COLUMN] -= 1
        if heads[s, HEAD_M_ROW] < spacing - 1:
            heads[s, HEAD_M_ROW] += 1
        else:
            heads[s, HEAD_M_ROW] = 0
            if heads[s, HEAD_M_COLUMN] == live:  # the span at the right end: over to the left half
                _move_span(M, start, width, spacing, live, live, 0)
                heads[s, HEAD_M_COLUMN] = 0
            heads[s, HEAD_M_COLUMN] += 1


@njit(cache=True, nogil=True, _nrt=False)
def _copy_nodes(layout, spacing, P, M, heads, p, m, to_buffers):  # type: ignore[no-untyped-def,unused-ignore]
    """Node-ordered (p, m) into the buffers (``to_buffers``) or back."""
    for s in range(layout.shape[0]):
        start = layout[s, BUFFER_START]
        width = layout[s, WIDTH]
        first = layout[s, NODE_START]
        p_row, p_column, m_row, m_column = (
            heads[s, HEAD_P_ROW],
            heads[s, HEAD_P_COLUMN],
            heads[s, HEAD_M_ROW],
            heads[s, HEAD_M_COLUMN],
        )
        for j in range(first, first + layout[s, CELLS] + 1):
            ip = start + p_row * width + p_column
            im = start + m_row * width + m_column
            if to_buffers:
                P[ip] = p[j]
                M[im] = m[j]
            else:
                p[j] = P[ip]
                m[j] = M[im]
            p_row += 1  # the next node: the next slot of either buffer
            if p_row == spacing:
                p_row = 0
                p_column += 1
            m_row += 1
            if m_row == spacing:
                m_row = 0
                m_column += 1


@njit(cache=True, nogil=True, _nrt=False)
def _read_nodes(layout, spacing, P, M, heads, impedances, speeds, torques):  # type: ignore[no-untyped-def,unused-ignore]
    """Speed [rad/s] and torque / Z' [rad/s] of every node, in the state layout."""
    _copy_nodes(layout, spacing, P, M, heads, speeds, torques, False)  # p into speeds, m ...
    for j in range(speeds.size):
        p, m, z = speeds[j], torques[j], impedances[j]
        speeds[j] = (p - m) / (2.0 * z)
        torques[j] = 0.5 * (p + m) / z


@njit(cache=True, nogil=True, _nrt=False)
def _node_slots(layout, spacing, heads, s, rows_on, columns_on):  # type: ignore[no-untyped-def,unused-ignore]
    """(slot of p, slot of m) of the node of section ``s`` ``rows_on`` rows and
    ``columns_on`` columns past its node 0 (:func:`_slot`)."""
    start = layout[s, BUFFER_START]
    width = layout[s, WIDTH]
    p_row, p_column = heads[s, HEAD_P_ROW], heads[s, HEAD_P_COLUMN]
    m_row, m_column = heads[s, HEAD_M_ROW], heads[s, HEAD_M_COLUMN]
    return (
        _slot(start, width, spacing, p_row, p_column, rows_on, columns_on),
        _slot(start, width, spacing, m_row, m_column, rows_on, columns_on),
    )


@njit(cache=True, nogil=True, _nrt=False)
def _end_slots(layout, spacing, heads, s, last_node):  # type: ignore[no-untyped-def,unused-ignore]
    """(slot of p, slot of m) of node 0 of section ``s``, or of its last node."""
    rows_on = layout[s, LAST_ROW] if last_node else 0
    columns_on = layout[s, LAST_COLUMN] if last_node else 0
    return _node_slots(layout, spacing, heads, s, rows_on, columns_on)
