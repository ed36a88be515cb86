"""What limits the meaning of a result: the warnings a run or a map carries with it.

A result can be computed correctly and still say little. S_SS (Eq. 12) measures the
swing of the bit speed over the steady window, so it reads 0 for a bit that never
breaks free, and it misses a cycle longer than the window. Each function here returns
the warning text for one such case, or None where it does not apply; a results object
keeps the texts (``warnings``), its JSON lists them and the command line prints them on
stderr.

Examples
--------
>>> stuck_throughout(1.0, 0.1)
'the bit is stuck throughout the steady window (|bit speed| < 0.1 Omega at every sample): ...'
>>> stuck_throughout(0.4, 0.1) is None
True
>>> short_window(2.0, 7.65)
'the steady window (2 s) is shorter than one period of the first mode (7.65 s): ...'
>>> stuck_points(3, 100)
"at 3 of 100 points the bit is stuck throughout the steady window: ..."
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.units import RPM_TO_RAD_S

__all__ = [
    "SATURATION_FRACTION",
    "past_the_record",
    "saturated_motor",
    "short_window",
    "stuck_points",
    "stuck_throughout",
    "warning_list",
]


def stuck_throughout(stick_fraction: float, stick_threshold: float) -> str | None:
    """The warning for a bit that sticks at every sample of the window, else None
    (``stick_threshold`` 0: an axial run saved when its bit counted stuck at speed 0)."""
    if stick_fraction < 1.0:
        return None
    at_rest = (
        "the bit speed 0 at every step"
        if stick_threshold == 0.0
        else f"|bit speed| < {stick_threshold:g} Omega at every sample"
    )
    return (
        f"the bit is stuck throughout the steady window ({at_rest}): the string never "
        "breaks it free, and S_SS, which measures "
        "the swing of the bit speed, does not measure stick-slip here; lower the weight on "
        "bit or raise the torque the top drive can give"
    )


def stuck_points(count: int, total: int) -> str | None:
    """The warning for a map with ``count`` of ``total`` points stuck throughout, else None."""
    if count <= 0:
        return None
    return (
        f"at {count} of {total} points the bit is stuck throughout the steady window: S_SS "
        "does not measure stick-slip there; they are classified 'stuck', not by S_SS"
    )


def short_window(steady_window: float, period: float) -> str | None:
    """The warning for a steady window [s] shorter than the first-mode ``period`` [s]."""
    if steady_window >= period:
        return None
    return (
        f"the steady window ({steady_window:.4g} s) is shorter than one period of the first "
        f"mode ({period:.4g} s): S_SS may miss the extremes of a stick-slip cycle; give a "
        "window of several periods (--window, simulation.steady_window)"
    )


def past_the_record(top: Any, duration: float) -> str | None:
    """A top that follows a recording says when a run of ``duration`` [s] outlasts it
    (:meth:`torsio.physics.recorded_top.RecordedTopDrive.past_the_record`; else None)."""
    past = getattr(top, "past_the_record", None)
    return None if past is None else past(duration)


def warning_list(*texts: str | None) -> tuple[str, ...]:
    """The texts that apply (not None), in order.

    >>> warning_list(None, "a", None, "b")
    ('a', 'b')
    """
    return tuple(text for text in texts if text is not None)


SATURATION_FRACTION = 0.1
"""Fraction of the steady window at the motor torque limit from which a run says so."""

SPEED_SHORTFALL = 0.05
"""Relative shortfall of the mean top-drive speed below its set speed that a run says."""


def saturated_motor(
    motor_torque: Any, max_torque: float, top_speed_mean: float, set_speed: float
) -> str | None:
    """The warning for a top drive at its torque limit or short of its set speed, else None.

    ``motor_torque`` [N m] is sampled over the steady window, ``max_torque`` [N m] its
    limit (inf: none), ``top_speed_mean`` and ``set_speed`` [rad/s] the top drive's mean
    speed over the window and its set speed (NaN: none). Warns when the motor is at the
    limit during at least :data:`SATURATION_FRACTION` of the window, or when the top turns
    more than :data:`SPEED_SHORTFALL` below its set speed (e.g. a PI top drive whose
    inertia is too large to be brought up to speed within the run).

    >>> saturated_motor([1000.0, 1000.0], 1000.0, 0.5, 10.47)
    'the top drive is at its torque limit (max_torque = 1000 N m) during 100% of the ...'
    >>> saturated_motor([900.0, 1000.0], math.inf, 10.0, 10.47) is None
    True
    >>> saturated_motor([900.0, 1000.0], math.inf, 1.0, 10.47)
    "the top drive never reaches its set speed: its mean speed is 9.549 rpm against ..."
    """
    torque = np.abs(np.asarray(motor_torque, dtype=float))
    limited = math.isfinite(max_torque) and torque.size > 0
    fraction = float(np.mean(torque >= max_torque * (1.0 - 1e-9))) if limited else 0.0
    has_set = math.isfinite(set_speed) and set_speed > 0
    short = has_set and top_speed_mean < (1.0 - SPEED_SHORTFALL) * set_speed
    speeds = (
        f"its mean speed is {top_speed_mean / RPM_TO_RAD_S:.4g} rpm against the set "
        f"{set_speed / RPM_TO_RAD_S:.4g} rpm ({top_speed_mean / set_speed:.1%})"
        if has_set
        else ""
    )
    if fraction < SATURATION_FRACTION and not (short and fraction > 0):
        if not short:
            return None
        return (
            f"the top drive never reaches its set speed: {speeds} over the steady window, "
            "and S_SS is read against the set speed; check the top drive's inertia and "
            "gains against the run length (top_drive.inertia, kp, ki)"
        )
    never = ", which it never reaches" if short else ""
    return (
        f"the top drive is at its torque limit (max_torque = {max_torque:.6g} N m) during "
        f"{fraction:.0%} of the steady window{'; ' + speeds if speeds else ''}: the motor "
        f"cannot give the torque the string asks for, and S_SS is read against the set "
        f"speed{never}; raise top_drive.max_torque above the drilling torque or lower the "
        "weight on bit"
    )
