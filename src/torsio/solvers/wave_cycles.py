"""The steady-cycle tracker of the distributed model's stepping
(:mod:`torsio.solvers.characteristics`, whose module docstring gives the rule): at each
upward crossing of the reference speed by the bit, whether the motion has settled on a
cycle. Its numbers live in the kernel's summary array, at the indices below.
"""

from __future__ import annotations

import math

from torsio.solvers.compiled import njit
from torsio.solvers.wave_buffers import _read_nodes

# the steady-cycle tracker in the summary array
_COUNT, _T_LAST, _RUN_MAX, _RUN_MIN, _CYCLE_MAX, _CYCLE_MIN, _CHANGE, _ENDED, _KEPT = range(16, 25)
_BIT_TORQUE = 25


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
    crossings = summary[_COUNT]
    period = t_cross - summary[_T_LAST]
    cycles_left = (t_end - t_cross) / period if crossings >= 1.0 else math.inf
    change = math.inf
    quick = 0.0
    bounded = crossings >= 1.0
    if bounded:
        quick = max(abs(w_bit - cross[0, nodes]), abs(top_speed - cross[0, nodes + 1]))
        bounded = cycles_left * quick / (2.0 * reference) <= tolerance
    cross[0, nodes] = w_bit
    cross[0, nodes + 1] = top_speed
    if bounded or crossings < 1.0:
        _read_nodes(layout, spacing, P, M, heads, impedances, speeds, torques)
        if summary[_KEPT] > 0.0:
            moved = 0.0
            for j in range(nodes):
                moved = max(moved, abs(speeds[j] - cross[0, j]), abs(torques[j] - cross[1, j]))
            change = max(moved, quick) / (2.0 * reference)
        for j in range(nodes):
            cross[0, j] = speeds[j]
            cross[1, j] = torques[j]
        summary[_KEPT] = 1.0
    else:
        summary[_KEPT] = 0.0
    steady = (
        crossings >= 3.0
        and period <= window_length
        and cycles_left * max(change, summary[_CHANGE]) <= tolerance
    )
    if crossings >= 1.0:
        summary[_CYCLE_MAX] = summary[_RUN_MAX]
        summary[_CYCLE_MIN] = summary[_RUN_MIN]
    summary[_CHANGE] = change
    summary[_COUNT] = crossings + 1.0
    summary[_T_LAST] = t_cross
    summary[_RUN_MAX] = w_bit
    summary[_RUN_MIN] = w_bit
    return steady
