"""The slope of a bit-rock law, d torque / d speed: the law's own, or a central difference.

One central difference for every law without ``slope`` and every engine (scipy's
Jacobian, the linearization, the numpy and the compiled engines: numba compiles
:func:`central_difference` too, :mod:`torsio.solvers.law_kernels`).

Examples
--------
>>> def torque(speed, wob, radius):
...     return wob * radius * speed**2
>>> round(float(central_difference(torque, 3.0, 1.0, 1.0)), 6)
6.0
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["SLOPE_STEP", "bit_slope", "central_difference"]

SLOPE_STEP = 1e-6
"""Relative step of :func:`central_difference` (of max(1, |speed|) [rad/s])."""


def central_difference(torque: Any, speed: Any, wob: Any, radius: Any) -> Any:
    """d torque / d speed [N m s/rad] by a central difference of ``torque(speed, wob, radius)``.

    The step is :data:`SLOPE_STEP` times max(1, |speed|); ``speed`` a float or an array.
    """
    step = SLOPE_STEP * np.maximum(1.0, np.abs(speed))
    return (torque(speed + step, wob, radius) - torque(speed - step, wob, radius)) / (2.0 * step)


def bit_slope(law: Any, speed: Any, wob: Any, radius: Any) -> np.ndarray:
    """d T_bit / d speed [N m s/rad]: the law's ``slope``, or :func:`central_difference`."""
    if hasattr(law, "slope"):
        return np.asarray(law.slope(speed, wob, radius), dtype=float)
    w = np.asarray(speed, dtype=float)
    return np.asarray(central_difference(law.torque, w, wob, radius), dtype=float)
