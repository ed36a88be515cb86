"""Stick-slip severity S_SS (paper Eq. 12) and the steady-state window it is read over.

    S_SS = (max theta_bit' - min theta_bit') / (2 Omega)

over a steady-state window at the end of a run started from rest. S_SS = 0 for
steady rotation; S_SS >= 1 means the bit stops (sticks); the paper calls
S_SS > 0.8 severe.

This module is the one place for the defaults every analyzer shares (single
runs, batch maps, reports): the first natural frequency omega_1
(:func:`first_natural_frequency`), the run length and steady window
(:func:`run_times`), the output sampling, the stick and severe thresholds.

Default run length and window (the paper states neither): the run lasts
``DEFAULT_DURATION_PERIODS`` periods of the first natural mode and S_SS is read
over the last ``DEFAULT_WINDOW_PERIODS``, or over at most the second half of the
run when a shorter run is asked for. A stick-slip cycle lasts about one to
two such periods, so the window holds about 7 to 15 cycles, and the first 25
periods (about 185 s for the Ritto et al. 2017 string, T1 = 7.4 s) let the
start-up transient die out (modal damping ratio >= 0.2 there). omega_1 is always
that of the model with the top held (a top drive with inertia does not change
the default times).

For a top drive with a set speed (constant speed, PI kinds) Omega in S_SS is the
set speed; for a torque-driven top drive it is the mean top-drive speed over the
steady window.

Examples
--------
>>> import numpy as np
>>> t = np.linspace(0.0, 10.0, 1001)
>>> severity(10.0 + 5.0 * np.sin(t), omega=10.0)
0.49999...
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.errors import ConfigError
from torsio.model.modal import first_natural_frequency as model_first_frequency

DEFAULT_DURATION_PERIODS = 40.0
"""Default run length, in periods 2 pi / omega_1 of the first natural mode."""

DEFAULT_WINDOW_PERIODS = 15.0
"""Default steady-state window at the end of a run, in periods of the first mode."""

SEVERE_THRESHOLD = 0.8
"""S_SS above which the paper calls the vibration severe."""

DEFAULT_SAMPLES_PER_PERIOD = 200
"""Default output samples per period 2 pi / omega_1 of the first natural mode."""

DEFAULT_STICK_THRESHOLD = 0.1
"""Default stick threshold, as a fraction of Omega: the bit sticks while
``|bit speed| < 0.1 Omega``. With a regularized law (Tucker-Wang's tanh) the bit
creeps at a few per cent of Omega instead of stopping exactly."""


def first_natural_frequency(system: Any) -> float:
    """omega_1 [rad/s] of a System's (or a model's) structure, top held, undamped.

    For the distributed model, the first frequency of its exact continuum
    (:func:`torsio.model.modal.first_natural_frequency`).
    """
    return model_first_frequency(system)


def run_times(
    system: Any, duration: float | None = None, steady_window: float | None = None
) -> tuple[float, float]:
    """(run length, steady window) [s] with the defaults of this module, checked.

    Without ``duration``: :data:`DEFAULT_DURATION_PERIODS` periods of omega_1.
    Without ``steady_window``: :data:`DEFAULT_WINDOW_PERIODS` periods, but at most
    half of a run whose length was given. ``system`` is a System, a structural model or an
    axial assembly: whatever has (or whose ``model`` has) ``first_frequency()``, read only
    when a default is needed. Every engine's defaults come from this function.
    """
    if duration is None or steady_window is None:
        default_duration, default_window = default_times(first_natural_frequency(system))
        if steady_window is None:
            steady_window = (
                default_window if duration is None else min(default_window, 0.5 * duration)
            )
        if duration is None:
            duration = default_duration
    check_window(float(duration), float(steady_window))
    return float(duration), float(steady_window)


def severity_of_extremes(speed_max: Any, speed_min: Any, omega: Any) -> Any:
    """S_SS (Eq. 12) of the bit speed's extremes [rad/s] over the steady window at the
    surface speed omega [rad/s]: the one formula every engine reads S_SS with (floats, or
    arrays elementwise: a batch's points).

    >>> severity_of_extremes(15.0, 5.0, 10.0)
    0.5
    """
    return (speed_max - speed_min) / (2.0 * omega)


def severity(bit_speed: np.ndarray, omega: float) -> float:
    """S_SS of bit speeds [rad/s] sampled over the steady window, at surface speed omega [rad/s]."""
    if not (math.isfinite(omega) and omega > 0):
        raise ConfigError(
            "rpm",
            f"S_SS divides by the surface speed; expected a positive speed, got {omega!r} rad/s",
        )
    speeds = np.asarray(bit_speed, dtype=float)
    if speeds.size == 0:
        raise ConfigError("steady_window", "no samples in the steady-state window")
    return float(severity_of_extremes(speeds.max(), speeds.min(), omega))


def default_times(first_frequency_rad: float) -> tuple[float, float]:
    """Default (run duration, steady window) [s] for a first natural frequency [rad/s]."""
    period = 2.0 * math.pi / first_frequency_rad
    return DEFAULT_DURATION_PERIODS * period, DEFAULT_WINDOW_PERIODS * period


def check_window(duration: float, steady_window: float) -> None:
    """A clear error unless 0 < steady_window <= duration."""
    for key, value in (("duration", duration), ("steady_window", steady_window)):
        if not (math.isfinite(value) and value > 0):
            raise ConfigError(f"simulation.{key}", f"expected a positive time in s, got {value!r}")
    if steady_window > duration:
        raise ConfigError(
            "simulation.steady_window",
            f"the steady window ({steady_window:g} s) is longer than the run ({duration:g} s)",
        )
