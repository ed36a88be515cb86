"""Coulomb contacts at the drag nodes of the distributed model, solved exactly each step.

At a drag node with the arriving invariants p (from above) and m (from below), the
torque above is p - Z v and below m + Z v, so the node's speed v solves

    (2 Z + c) v + F = p - m = d        (a junction: Z1 + Z2 + c in place of 2 Z)

with c the node's damper and F the contact's friction torque, set-valued: the step form of
:mod:`torsio.solvers.contact_law` (stuck, static branch C_s below v_th, dynamic C_d above).
On a branch of capacity C the solution is explicit: v = sign(d) excess(d, C) / (2 Z + c),
F = d - (2 Z + c) v (a stuck node, |d| <= C, takes exactly the torque d that holds it and
keeps speed 0: nothing creeps or leaks past it); the branch is
:func:`torsio.solvers.contact_law.static_branch`'s. No iteration: the contact is piecewise
linear. The energy leaving the node's pair of waves in a step is exactly (c v^2 + F v) dt.

:func:`_contacts` does this for a run of regular nodes (contiguous slices, vectorizable),
:func:`_contact_speed` for one node; :func:`contact_arrays` lays the capacities of a
:class:`torsio.model.contacts.StringContacts` out for the kernel.

Examples
--------
>>> import numpy as np
>>> below = speed_below(0.5)
>>> round(_contact_speed(10.0, 0.5, 4.0, 3.0, 0.0, below), 12)  # from rest: C_s, then fast
3.5
>>> _contact_speed(3.9, 0.5, 4.0, 3.0, 0.0, below)  # held: |d| <= C_s
0.0
>>> round(_contact_speed(4.5, 0.5, 4.0, 3.0, 0.0, below), 12)  # slow slip on C_s
0.25
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.model.wave_grid import drag_lumping
from torsio.solvers.compiled import njit
from torsio.solvers.contact_law import excess, static_branch
from torsio.solvers.layouts import (
    CONTACT_DYNAMIC,
    CONTACT_INDEX_COLUMNS,
    CONTACT_JUNCTION,
    CONTACT_NODE,
    CONTACT_OTHER,
    CONTACT_REGULAR,
    CONTACT_ROWS,
    CONTACT_SPEED,
    CONTACT_STATIC,
)

__all__ = ["contact_arrays", "speed_below"]


@njit(cache=True, nogil=True, _nrt=False)
def _contact_speed(d, inverse, static, dynamic, previous, below):  # type: ignore[no-untyped-def,unused-ignore]
    """Speed [rad/s] of a contact node: the solution of v / inverse + F(v) = d (module
    docstring) on the branch of its ``previous`` speed. ``inverse`` = 1 / (2 Z + c);
    ``below`` the largest speed under the threshold (:func:`speed_below`), so that
    |v| <= below is the static branch (v = 0 too with a threshold of 0). Written with
    selects only, so that a run of nodes vectorizes."""
    slow = excess(d, static) * inverse
    fast = excess(d, dynamic) * inverse
    return math.copysign(slow if static_branch(previous, below, slow, fast) else fast, d)


@njit(cache=True, nogil=True, _nrt=False)
def _contact_node(p, m, i, two_z, inverse, static, dynamic, speed, below):  # type: ignore[no-untyped-def,unused-ignore]
    """Solve regular contact node ``i`` of (p, m) in place (its pair leaves it); returns
    (its torque difference d, its speed v)."""
    arriving_p = p[i]
    d = arriving_p - m[i]
    v = _contact_speed(d, inverse, static[i], dynamic[i], speed[i], below)
    speed[i] = v
    jump = two_z * v
    p[i] = m[i] + jump
    m[i] = arriving_p - jump
    return d, v


@njit(cache=True, nogil=True, _nrt=False, error_model="numpy", fastmath={"reassoc"})
def _contacts(p, m, two_z, inverse, static, dynamic, speed, below, powers):  # type: ignore[no-untyped-def,unused-ignore]
    """Regular contact nodes on contiguous slices of arriving (p, m); in place, with the
    nodes' ``speed`` (their last step's, updated). Returns (sum of v^2, sum of F v) for the
    dampers' and the friction's power when ``powers`` is set, else (0, 0) (a map's runs:
    0.8 instead of 1.2 ns a node). The sums may be reassociated (``fastmath`` reassoc
    only: the loop vectorizes); the invariants are not."""
    squares = 0.0
    work = 0.0
    if powers:
        total = 1.0 / inverse
        for i in range(p.size):
            d, v = _contact_node(p, m, i, two_z, inverse, static, dynamic, speed, below)
            squares += v * v
            work += (d - total * v) * v
    else:
        for i in range(p.size):
            _contact_node(p, m, i, two_z, inverse, static, dynamic, speed, below)
    return squares, work


@njit(cache=True, nogil=True, _nrt=False)
def _contact_node_speeds(contacts, speeds):  # type: ignore[no-untyped-def,unused-ignore]
    """Put the contact nodes' speeds into ``speeds`` (state layout): at a contact the
    stored pair leaves it, (p - m) / (2 Z - c) = v - F / (2 Z - c), not its speed."""
    for j in range(contacts.shape[1]):
        speeds[int(contacts[CONTACT_NODE, j])] = contacts[CONTACT_SPEED, j]


def speed_below(threshold: float) -> float:
    """The largest float below ``threshold`` (0 for 0): |v| <= it is |v| < threshold."""
    return float(np.nextafter(threshold, 0.0)) if threshold > 0.0 else 0.0


def contact_arrays(grid: Any) -> tuple[np.ndarray, np.ndarray]:
    """(index, table) of ``grid.contacts`` for the kernel.

    ``table`` (``CONTACT_ROWS``, contacts): C_s, C_d [N m], the speed of the last step
    [rad/s] (zero: at rest) and the node in the state layout (as a float; its stored pair
    is the one leaving the contact, so its speed is read from here,
    :func:`_contact_node_speeds`). Per
    section s, ``index[s]`` = (first of its regular inner nodes k, 2k, ... in ``table``,
    its other inner drag node, its bottom junction; -1: none). Without contacts: one
    empty column, and the kernel takes the damper-only path.
    """
    sections = len(grid.cells)
    index = np.full((sections, CONTACT_INDEX_COLUMNS), -1, dtype=np.int64)
    contacts = grid.contacts
    if contacts is None:
        return index, np.zeros((CONTACT_ROWS, 1))
    offsets = np.concatenate([[0], np.cumsum(np.array(grid.cells) + 1)]).astype(int)
    columns: list[int] = []
    k = grid.drag_spacing
    for s, n in enumerate(grid.cells):
        nodes, shares = drag_lumping(int(n), k)
        inner = nodes[1:-1]
        regular = int(np.sum(shares[1:-1] == k))
        index[s, CONTACT_REGULAR] = len(columns)
        columns.extend(int(offsets[s] + j) for j in inner[:regular])
        if regular < inner.size:
            index[s, CONTACT_OTHER] = len(columns)
            columns.append(int(offsets[s] + inner[regular]))
        if s < sections - 1:
            index[s, CONTACT_JUNCTION] = len(columns)
            columns.append(int(offsets[s + 1] - 1))
    table = np.zeros((CONTACT_ROWS, max(len(columns), 1)))
    table[CONTACT_STATIC, : len(columns)] = contacts.static[columns]
    table[CONTACT_DYNAMIC, : len(columns)] = contacts.dynamic[columns]
    table[CONTACT_NODE, : len(columns)] = columns
    return index, table
