"""The stick-slip period: the fundamental of the cycle in a steady window.

A stick-slip cycle (a stuck phase, then a slip whose front rings along the string) has
energy at many frequencies; chatter and the slip front's ringing cross any level many times
per cycle, so counting crossings reads the ringing, not the cycle. The period here is the
lag of the autocorrelation's first major peak: the largest value of the first positive lobe
that follows the central lobe's end (its first zero) and reaches :data:`MAJOR_PEAK` of the
largest correlation beyond it. Ripples of chatter ride on the central lobe and never end it;
multiples of the period come after the first major lobe.
"""

from __future__ import annotations

import numpy as np

__all__ = ["MAJOR_PEAK", "MIN_CORRELATION", "cycle_period"]

MAJOR_PEAK = 0.5
"""A lobe of the autocorrelation is major when its peak reaches this share of the largest
correlation after the central lobe. A multiple of the period correlates about as well as the
period; slips that alternate in size, or an irregular cycle, correlate better at two cycles
than at one, and half the largest still takes the one: the time from slip to slip, where the
spectrum of the signal peaks."""

MIN_CORRELATION = 0.3
"""Below this normalized correlation at every lag after the central lobe, the window holds no
repeating cycle (noise, a decay, a drift)."""

STEADY = "steady rotation: the range of the bit speed in the window is under 1e-3 of its size"
SHORT = "the window holds fewer than two samples"
NO_CYCLE = (
    "no cycle repeats twice in the window (the autocorrelation of the bit speed up to half "
    "the window stays under 0.3 after its central lobe)"
)


def cycle_period(time: np.ndarray, speed: np.ndarray) -> tuple[float | None, str | None]:
    """(period [s], None) of the cycle of ``speed`` over ``time`` [s], or (None, reason).

    The samples are put on a uniform grid of their median step; the period is the lag of
    the autocorrelation's first major peak (module docstring), refined by a parabola through
    the peak and its neighbours, looked for up to half the window (two whole cycles).

    >>> t = np.linspace(0.0, 30.0, 30001)
    >>> period, reason = cycle_period(t, np.sin(2 * np.pi * t / 2.5))
    >>> round(period, 3), reason
    (2.5, None)
    >>> cycle_period(t, np.full(t.size, 6.0))
    (None, 'steady rotation: the range of the bit speed in the window is under 1e-3 of its size')
    """
    time, speed = np.asarray(time, dtype=float), np.asarray(speed, dtype=float)
    if speed.size < 2:
        return None, SHORT
    low, high = float(np.min(speed)), float(np.max(speed))
    if not high - low > 1e-3 * max(abs(low), abs(high)):
        return None, STEADY
    step = float(np.median(np.diff(time)))
    uniform = np.arange(time[0], time[-1] + 0.5 * step, step)
    values = np.interp(uniform, time, speed)
    correlation = _autocorrelation(values - values.mean())
    half = correlation[: uniform.size // 2 + 1]
    negative = np.flatnonzero(half < 0.0)
    if not negative.size:
        return None, NO_CYCLE
    beyond = half[negative[0] :]
    largest = float(beyond.max())
    if largest < MIN_CORRELATION:
        return None, NO_CYCLE
    first = negative[0] + int(np.flatnonzero(beyond >= MAJOR_PEAK * largest)[0])
    start = first
    while start > 0 and half[start - 1] > 0.0:
        start -= 1
    end = first
    while end + 1 < half.size and half[end + 1] > 0.0:
        end += 1
    peak = start + int(np.argmax(half[start : end + 1]))
    if peak + 1 >= half.size:  # the lobe runs past half the window: not two whole cycles
        return None, NO_CYCLE
    return float(_refined(half, peak) * step), None


def _autocorrelation(values: np.ndarray) -> np.ndarray:
    """Normalized (1 at lag 0) autocorrelation of ``values`` over every lag, by FFT, each
    lag's sum divided by its count of overlapping samples (unbiased)."""
    n = values.size
    size = 1 << (2 * n - 1).bit_length()
    spectrum = np.fft.rfft(values, size)
    sums = np.fft.irfft(spectrum * np.conj(spectrum), size)[:n]
    means = sums / np.arange(n, 0, -1)
    return means / means[0] if means[0] > 0.0 else means


def _refined(correlation: np.ndarray, peak: int) -> float:
    """The peak's lag [samples] from the parabola through it and its two neighbours."""
    left, centre, right = correlation[peak - 1 : peak + 2]
    curvature = left - 2.0 * centre + right
    if not curvature < 0.0:
        return float(peak)
    return peak + 0.5 * (left - right) / curvature
