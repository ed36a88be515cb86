"""What a run with friction along the string reports: surface torque, break-free, period.

One summary for every engine that runs contacts (the wave model's stepping takes its
extremes at every step, a lumped run from its output samples), merged into
``TransientResults.to_dict()`` and ``torsio simulate --json``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["contact_summary", "oscillation_period"]


def oscillation_period(time: np.ndarray, speed: np.ndarray) -> float | None:
    """Mean time [s] between upward crossings of the middle of ``speed``'s range, or None
    with fewer than three crossings (two whole cycles) or a range under 1e-3 of the
    largest speed (steady rotation, whose round-off has no period).

    >>> t = np.linspace(0.0, 10.0, 10001)
    >>> round(oscillation_period(t, np.sin(2 * np.pi * t / 2.5)), 6)
    2.5
    """
    if speed.size < 2:
        return None
    low, high = float(np.min(speed)), float(np.max(speed))
    if not high - low > 1e-3 * max(abs(low), abs(high)):
        return None
    level = 0.5 * (low + high)
    up = np.flatnonzero((speed[:-1] < level) & (speed[1:] >= level))
    if up.size < 3:
        return None
    share = (level - speed[up]) / (speed[up + 1] - speed[up])
    crossings = time[up] + share * (time[up + 1] - time[up])
    return float(np.mean(np.diff(crossings)))


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
    work [J], the stick-slip period of the bit speed in the window [s] and the contacts."""
    low, high = (float(value) for value in surface_range)
    return {
        "surface_torque_min": low,
        "surface_torque_max": high,
        "surface_torque_swing": high - low,
        "surface_torque_peak": float(surface_peak),
        "stick_slip_period": oscillation_period(window_time, window_bit_speed),
        "bit_first_motion": None if math.isnan(first_motion) else float(first_motion),
        "friction_work": float(friction_work),
        "threshold_speed": float(contacts.threshold_speed),
        "contacts": contacts.describe(),
    }
