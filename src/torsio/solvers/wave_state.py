"""The state of the distributed model and its layout for the stepping kernel.

:class:`WaveState` holds the Riemann invariants p = T + Z w (travelling down) and
m = T - Z w (travelling up) at every node of the characteristic grid, section by section,
with the top drive's and the bit's states. :func:`kernel_layout` lays the grid out for
:mod:`torsio.solvers.characteristics`: the buffers that make transport free, and the
point dampers into which the distributed drag is lumped
(:func:`torsio.model.wave_grid.drag_lumping`).

Examples
--------
>>> from torsio.model.wave import WaveStrategy
>>> from torsio.examples import ritto2017_string
>>> grid = WaveStrategy(drag_spacing=4).discretize(ritto2017_string())
>>> layout = kernel_layout(grid, alpha=0.35)
>>> from torsio.solvers.layouts import C_INNER, C_SPECIAL, INNER
>>> layout.integers[:, INNER].tolist()  # regular inner dampers per section (nodes 4, 8, ...)
[247, 8, 14]
>>> round(float(layout.end_dampers.sum() + layout.floats[:, C_INNER] @ layout.integers[:, INNER]
...             + layout.floats[:, C_SPECIAL].sum()) / (0.35 * float(grid.impedances @ grid.cells)
...             * grid.time_step), 12)  # every cell's drag, once
1.0
"""

from __future__ import annotations

import attrs
import numpy as np

from torsio.model.wave import WaveModel
from torsio.model.wave_grid import drag_lumping
from torsio.solvers.layouts import (
    BIT_SPEED,
    BIT_SPEED_BEFORE,
    BIT_STATE_SIZE,
    BUFFER_START,
    C_INNER,
    C_SPECIAL,
    CELLS,
    INNER,
    LAST_COLUMN,
    LAST_ROW,
    LIVE,
    NODE_START,
    RATIO_INNER,
    RATIO_SPECIAL,
    SECTION_FLOATS,
    SECTION_INTEGERS,
    SPECIAL,
    SPECIAL_COLUMN,
    SPECIAL_ROW,
    WIDTH,
    X_TOP_SPEED,
    Z,
)
from torsio.solvers.wave_top import TopArrays


@attrs.frozen(eq=False)
class WaveState:
    """State of the distributed model: invariants at every node, top and bit states.

    ``p`` and ``m`` hold every section's nodes (a junction node once per section),
    section s at ``offsets[s] .. offsets[s] + cells[s]``. ``bit`` = [w_b, w_b one step
    earlier, steps taken]. ``top`` = [Omega_0, z...] (empty when held).
    """

    p: np.ndarray
    m: np.ndarray
    top: np.ndarray
    bit: np.ndarray

    def copy(self) -> WaveState:
        """An independent copy."""
        return WaveState(self.p.copy(), self.m.copy(), self.top.copy(), self.bit.copy())


def node_offsets(grid: WaveModel) -> np.ndarray:
    """Start of each section's node block in the state arrays, and the total size."""
    return np.concatenate([[0], np.cumsum(np.array(grid.cells) + 1)]).astype(np.int64)


def rest_state(grid: WaveModel, top: TopArrays) -> WaveState:
    """Everything at rest: zero speed and torque along the string, top and bit still."""
    size = int(node_offsets(grid)[-1])
    top_state = np.zeros(max(top.states, 1))
    return WaveState(np.zeros(size), np.zeros(size), top_state, np.zeros(BIT_STATE_SIZE))


@attrs.frozen(eq=False)
class KernelLayout:
    """The grid and its lumped drag as arrays for the stepping kernel.

    Each section keeps its p and its m in a buffer of k = ``drag_spacing`` rows of W
    columns; slot sigma (row sigma % k, column sigma // k) holds node sigma - head, and a
    step moves the head by one slot (back for p, on for m). The nodes in use span L + 1
    columns (``live``); the buffer has W = 2 L of them, and when the span reaches an end
    it is copied to the other (every L k steps), so it never wraps: the regular dampers'
    p (and m) are one contiguous run of a row.

    ``integers[s]``: cells n, first node in the state arrays, first slot of the buffer, W,
    L, the regular inner dampers at nodes k, 2k, ... (their count), the node of the one
    inner damper with another share (-1: none), the row and column offsets of node n and
    of that damper. ``floats[s]``: Z, then (2 Z / (2 Z + c), c) of the regular inner
    dampers and of the other one. ``end_dampers``: c at the top node, at each junction,
    at the bit [N m s/rad]. ``impedances``: per node, Z' with speed = (p - m) / (2 Z')
    (Z - c/2 at an inner damper, where p and m are the outgoing pair, else Z).
    """

    integers: np.ndarray
    floats: np.ndarray
    end_dampers: np.ndarray
    impedances: np.ndarray
    buffer_size: int


def kernel_layout(grid: WaveModel, alpha: float) -> KernelLayout:
    """The buffers and the point dampers of ``grid`` with drag ``alpha`` [1/s]."""
    k = grid.drag_spacing
    dt = grid.time_step
    sections = len(grid.cells)
    integers = np.zeros((sections, SECTION_INTEGERS), dtype=np.int64)
    floats = np.zeros((sections, SECTION_FLOATS))
    end_dampers = np.zeros(sections + 1)
    offsets = node_offsets(grid)
    impedances = np.repeat(np.asarray(grid.impedances, dtype=float), np.array(grid.cells) + 1)
    buffer = 0
    for s, (n, z) in enumerate(zip(grid.cells, grid.impedances, strict=True)):
        n = int(n)
        nodes, shares = drag_lumping(n, k)
        dampers = alpha * float(z) * shares * dt  # c of each drag node [N m s/rad]
        end_dampers[s] += dampers[0]
        end_dampers[s + 1] += dampers[-1]
        inner = nodes[1:-1]
        regular = int(np.sum(shares[1:-1] == k))  # nodes k, 2k, ...: the first ones
        special = int(inner[regular]) if regular < inner.size else -1
        live = (k - 1 + n) // k + 1
        row = integers[s]
        row[CELLS], row[NODE_START], row[BUFFER_START] = n, offsets[s], buffer
        row[WIDTH], row[LIVE], row[INNER], row[SPECIAL] = 2 * live, live, regular, special
        row[LAST_ROW], row[LAST_COLUMN] = n % k, n // k
        row[SPECIAL_ROW], row[SPECIAL_COLUMN] = max(special, 0) % k, max(special, 0) // k
        c_regular = alpha * float(z) * k * dt
        floats[s, Z] = z
        floats[s, RATIO_INNER] = 2.0 * z / (2.0 * z + c_regular)
        floats[s, C_INNER] = c_regular
        if special >= 0:
            c_special = float(dampers[1 + regular])
            floats[s, RATIO_SPECIAL] = 2.0 * z / (2.0 * z + c_special)
            floats[s, C_SPECIAL] = c_special
        impedances[offsets[s] + inner] -= 0.5 * dampers[1:-1]
        buffer += 2 * live * k
    return KernelLayout(integers, floats, end_dampers, impedances, buffer)


def state_from_fields(
    grid: WaveModel, speed: np.ndarray, torque: np.ndarray, top: TopArrays, alpha: float = 0.0
) -> WaveState:
    """A state with angular speed [rad/s] and torque [N m] given at every node.

    ``speed`` and ``torque`` follow the state layout (:func:`node_offsets`); the bit
    starts at the speed of the last node. With drag ``alpha`` [1/s] the inner damper
    nodes get the outgoing pair of that speed and mean torque (:func:`node_impedances`).
    """
    state = rest_state(grid, top)
    z = node_impedances(grid, alpha)
    state.p[:] = torque + z * speed
    state.m[:] = torque - z * speed
    state.bit[BIT_SPEED] = state.bit[BIT_SPEED_BEFORE] = speed[-1]
    if not top.held:
        state.top[X_TOP_SPEED] = speed[0]
    return state


def node_impedances(grid: WaveModel, alpha: float) -> np.ndarray:
    """Per node, Z' [N m s/rad] with speed = (p - m) / (2 Z') and torque = (p + m) / 2.

    Z at every node but the inner drag nodes, where the stored pair is the one leaving
    the damper c: Z - c / 2 (module docstring).
    """
    return kernel_layout(grid, alpha).impedances
