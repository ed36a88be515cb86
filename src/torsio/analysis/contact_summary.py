"""What a run with friction along the string reports: surface torque, break-free, period.

One summary for every engine that runs contacts (the wave model's stepping takes its
extremes at every step, a lumped run from its output samples), merged into
``TransientResults.to_dict()`` and ``torsio simulate --json``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.analysis.cycle_period import cycle_period

__all__ = ["contact_summary"]


def contact_summary(
    contacts: Any,
    *,
    surface_range: tuple[float, float],
    surface_peak: float,
    first_motion: float,
    friction_work: float,
    window_time: np.ndarray,
    window_bit_speed: np.ndarray,
) -> dict[str, Any]:
    """The keys of a run with contacts (docs/cli.md): the surface torque's extremes in the
    steady window [N m] and their swing, its peak over the run, when the bit first turned
    faster than the threshold speed [s] (None if never; NaN in means never), the friction's
    work [J], the stick-slip period of the bit speed in the window [s]
    (:func:`~torsio.analysis.cycle_period.cycle_period`; None with the reason why) and the
    contacts."""
    low, high = (float(value) for value in surface_range)
    period, no_period = cycle_period(window_time, window_bit_speed)
    return {
        "surface_torque_min": low,
        "surface_torque_max": high,
        "surface_torque_swing": high - low,
        "surface_torque_peak": float(surface_peak),
        "stick_slip_period": period,
        "stick_slip_period_reason": no_period,
        "bit_first_motion": None if math.isnan(first_motion) else float(first_motion),
        "friction_work": float(friction_work),
        "threshold_speed": float(contacts.threshold_speed),
        "contacts": contacts.describe(),
    }
