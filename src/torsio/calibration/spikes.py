"""Spikes in a recorded surface torque: samples that leave their neighbours, and no string.

A sample is a spike when it departs from the median of its :data:`WINDOW` neighbours (itself
in the middle) by more than :data:`SIGMAS` times the record's scale. The median of the
window follows a ramp and a step (a break-free jump, a wave arriving at the top) sample for
sample, so what departs from it is a peak narrower than half the window: a glitch of the
torque sub, or noise. The scale is the larger of

* the robust standard deviation of the departures, 1.4826 x their median absolute value
  (the noise of the record), and
* :data:`SCALE_FLOOR` times the record's largest torque (its median-filtered absolute
  value). A rig logs the torque to 10 N m or coarser: most departures are then exactly 0,
  as they are on a noise-free record (a monotone stretch is its own median), and the
  median absolute deviation alone is 0, which would make every wiggle a spike.

What the physics does at the break-free moment stays below the threshold: on clean start-ups
of the built-in deviated well to 120 and 150 rpm (the recordings of ``tests/test_fit.py``),
the largest departure from the 11-sample median is 0.77 % and 0.48 % of the largest torque,
against SIGMAS x SCALE_FLOOR = 4 %; with 2 % Gaussian noise it is 5.8 robust standard
deviations, against 8.

Examples
--------
>>> import numpy as np
>>> torque = np.round(np.linspace(0.0, 12e3, 200), -1)   # a ramp logged to 10 N m
>>> torque[120] = 5 * torque[120]
>>> torque_spikes(torque).tolist()
[120]
>>> step = np.r_[np.full(50, 15e3), np.full(50, 12e3)]   # a break-free drop
>>> torque_spikes(step).tolist()
[]
>>> time = np.arange(200.0)
>>> repaired = without_spikes(time, torque, torque_spikes(torque))
>>> float(repaired[120]), float(0.5 * (torque[119] + torque[121]))
(7240.0, 7240.0)
"""

from __future__ import annotations

import numpy as np

__all__ = ["SCALE_FLOOR", "SIGMAS", "WINDOW", "spike_scale", "torque_spikes", "without_spikes"]

WINDOW = 11
"""Samples in the median a sample is compared with (itself in the middle)."""

SIGMAS = 8.0
"""Departure from the window's median, in the record's scale, beyond which a sample is a
spike."""

SCALE_FLOOR = 0.005
"""The least scale, as a fraction of the record's largest torque (module documentation)."""


def _departures(torque: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each sample minus the median of its window (the record's ends repeated), and that
    median [N m]."""
    half = WINDOW // 2
    padded = np.pad(np.asarray(torque, dtype=float), half, mode="edge")
    local = np.median(np.lib.stride_tricks.sliding_window_view(padded, WINDOW), axis=1)
    return torque - local, local


def spike_scale(torque: np.ndarray) -> float:
    """The record's scale [N m]: the larger of the robust standard deviation of the
    departures from the local median and :data:`SCALE_FLOOR` of the largest torque."""
    departure, local = _departures(torque)
    robust = 1.4826 * float(np.median(np.abs(departure)))
    return max(robust, SCALE_FLOOR * float(np.max(np.abs(local))))


def torque_spikes(torque: np.ndarray) -> np.ndarray:
    """Indices of the spikes of ``torque`` (module documentation); none in a record
    shorter than the window."""
    torque = np.asarray(torque, dtype=float)
    if torque.size < WINDOW:
        return np.zeros(0, dtype=int)
    departure, _ = _departures(torque)
    scale = spike_scale(torque)
    if scale <= 0.0:  # a record that is 0 throughout
        return np.zeros(0, dtype=int)
    return np.flatnonzero(np.abs(departure) > SIGMAS * scale)


def without_spikes(time: np.ndarray, torque: np.ndarray, spikes: np.ndarray) -> np.ndarray:
    """``torque`` with each spike replaced by the record linear between the samples that
    are not spikes on either side [N m]."""
    torque = np.array(torque, dtype=float)
    if spikes.size == 0:
        return torque
    kept = np.ones(torque.size, dtype=bool)
    kept[spikes] = False
    torque[spikes] = np.interp(time[spikes], time[kept], torque[kept])
    return torque
