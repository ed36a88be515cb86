"""What the timing benchmarks print about the machine: the children's CPU time and the load.

Imported by the benchmarks that time whole ``torsio`` processes
(``bench_friction_maps.py``, ``bench_wave_map.py``); run as ``python benchmarks/bench_x.py``,
a script finds this module beside it.
"""

from __future__ import annotations

import os
import resource


def children_cpu() -> float:
    """User plus system CPU time of the finished child processes [s]."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def load_average() -> str:
    """The machine's load average over 1, 5 and 15 minutes, as one line."""
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f}, {five:.2f}, {fifteen:.2f} (1, 5, 15 min)"
