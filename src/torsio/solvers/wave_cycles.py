"""The steady-cycle test of the distributed model at an upward crossing of the bit speed.

:func:`_crossing` is called by the stepping (:mod:`torsio.solvers.characteristics`, whose
module documentation gives the rule) each time the bit speed crosses the reference speed
upwards; the tracker's state is kept in the run's summary (``SUM_*`` of
:mod:`torsio.solvers.layouts`).
"""

from __future__ import annotations

import math

from torsio.solvers import layouts as slot
from torsio.solvers.compiled import njit
from torsio.solvers.wave_buffers import _read_nodes


@njit(cache=True, nogil=True, _nrt=False)
def _crossing(  # type: ignore[no-untyped-def,unused-ignore]
    layout, spacing, P, M, heads, impedances, speeds, torques, cross, summary,
    w_bit, top_speed, t_cross, reference, t_end, window_length, tolerance,
):  # fmt: skip
    """At an upward crossing of the reference speed by the bit: whether the motion is on
    a steady cycle (module docstring). Updates the tracker in ``summary`` and the state
    kept in ``cross`` (2, nodes + 2: speeds and torques / Z', then the bit and top speeds).

    The state of every node is read only when the bit's and the top's change alone would
    let the run end (it bounds the change from below); otherwise the change counts as
    infinite and no state is kept, which can only delay the end.
    """
    nodes = speeds.size
    speed, torque = slot.NODE_SPEED, slot.NODE_TORQUE  # rows of cross; its bit and top columns
    bit, top = nodes + slot.CROSS_BIT, nodes + slot.CROSS_TOP
    crossings = summary[slot.SUM_COUNT]
    period = t_cross - summary[slot.SUM_T_LAST]
    cycles_left = (t_end - t_cross) / period if crossings >= 1.0 else math.inf
    change = math.inf
    quick = 0.0
    bounded = crossings >= 1.0
    if bounded:
        quick = max(abs(w_bit - cross[speed, bit]), abs(top_speed - cross[speed, top]))
        bounded = cycles_left * quick / (2.0 * reference) <= tolerance
    cross[speed, bit] = w_bit
    cross[speed, top] = top_speed
    if bounded or crossings < 1.0:
        _read_nodes(layout, spacing, P, M, heads, impedances, speeds, torques)
        if summary[slot.SUM_KEPT] > 0.0:
            moved = 0.0
            for j in range(nodes):
                moved = max(
                    moved, abs(speeds[j] - cross[speed, j]), abs(torques[j] - cross[torque, j])
                )
            change = max(moved, quick) / (2.0 * reference)
        for j in range(nodes):
            cross[speed, j] = speeds[j]
            cross[torque, j] = torques[j]
        summary[slot.SUM_KEPT] = 1.0
    else:
        summary[slot.SUM_KEPT] = 0.0
    steady = (
        crossings >= 3.0
        and period <= window_length
        and cycles_left * max(change, summary[slot.SUM_CHANGE]) <= tolerance
    )
    if crossings >= 1.0:
        summary[slot.SUM_CYCLE_MAX] = summary[slot.SUM_RUN_MAX]
        summary[slot.SUM_CYCLE_MIN] = summary[slot.SUM_RUN_MIN]
    summary[slot.SUM_CHANGE] = change
    summary[slot.SUM_COUNT] = crossings + 1.0
    summary[slot.SUM_T_LAST] = t_cross
    summary[slot.SUM_RUN_MAX] = w_bit
    summary[slot.SUM_RUN_MIN] = w_bit
    return steady
