"""What a fit compares: the model's surface torque against a recording's.

Two objectives (docs/calibration.md measures what each recovers):

* ``torque``: every sample, model minus record [N m] (the model's torque read at the
  record's times, linear between its output steps).
* ``features``: per recording, the sliding torque (the mean over the last quarter of the
  record), the break-over torque (the peak) and the time of the peak times the mean
  torque over the record's duration (a torque, so that the three weigh alike) [N m].

Examples
--------
>>> import numpy as np
>>> time = np.linspace(0.0, 8.0, 9)
>>> torque = np.array([0.0, 5.0, 9.0, 7.0, 6.0, 6.0, 6.0, 6.0, 6.0])
>>> [round(float(v), 3) for v in torque_features(time, torque)]
[6.0, 9.0, 1.5]
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from torsio.analysis.transient import simulate
from torsio.errors import ConfigError

__all__ = [
    "OBJECTIVES",
    "Misfit",
    "break_over",
    "model_torque",
    "residuals",
    "sliding_part",
    "torque_features",
]

OBJECTIVES = ("torque", "features")
"""The objectives a fit may take (module documentation)."""


SLIDING_PART = 0.25
"""The last part of a start-up's record where the string slides (a fraction of its span)."""


def sliding_part(time: np.ndarray) -> np.ndarray:
    """Mask of the samples in the record's last :data:`SLIDING_PART`, where it slides."""
    time = np.asarray(time, dtype=float)
    return time >= time[-1] - SLIDING_PART * (time[-1] - time[0])


def break_over(torque: np.ndarray) -> int:
    """Index of a start-up's break-over: the peak of its surface torque."""
    return int(np.argmax(torque))


def torque_features(time: np.ndarray, torque: np.ndarray) -> np.ndarray:
    """Sliding torque, break-over torque and the time of the break-over scaled by the
    mean torque over the duration (all N m): ``[mean of the last quarter, peak,
    t_peak * mean / duration]``."""
    time = np.asarray(time, dtype=float)
    torque = np.asarray(torque, dtype=float)
    span = time[-1] - time[0]
    peak = break_over(torque)
    sliding = float(np.mean(torque[sliding_part(time)]))
    return np.array([sliding, float(torque[peak]), (time[peak] - time[0]) * sliding / span])


def model_torque(system: Any, recording: Any) -> tuple[np.ndarray, Any]:
    """The surface torque of ``system`` (its top drive set) at the record's times [N m],
    and the transient it came from; the run lasts the record (from rest)."""
    duration = recording.duration
    # the wave model's own step; a chain's at the record's sampling (RODAS4 steps freely)
    step = getattr(system.model, "time_step", None) or float(np.min(np.diff(recording.time)))
    transient = simulate(
        system, duration=duration, steady_window=0.1 * duration, output_step=step, progress=False
    )
    torque = np.interp(recording.time - recording.time[0], transient.time, transient.surface_torque)
    return torque, transient


def residuals(objective: str, model: np.ndarray, recording: Any) -> np.ndarray:
    """Model minus record by ``objective`` [N m]."""
    if objective == "torque":
        return model - recording.surface_torque
    if objective == "features":
        return torque_features(recording.time, model) - torque_features(
            recording.time, recording.surface_torque
        )
    raise ConfigError(
        "objective", f"unknown objective {objective!r}; expected one of {', '.join(OBJECTIVES)}"
    )


class Misfit:
    """Residuals of a parameter vector over every recording, counting the runs.

    ``family`` makes the system of a parameter vector (:class:`~torsio.calibration.
    parameters.SystemFamily`); each recording is run with its top drive ``tops[i]`` at
    the set speed ``rpms[i]`` [rpm] and weight on bit ``wob`` [N]; ``progress(n)``, if
    given, after every n runs.
    """

    def __init__(
        self,
        family: Any,
        recordings: Sequence[Any],
        names: Sequence[str],
        tops: Sequence[Any],
        rpms: Sequence[float],
        wob: float,
        objective: str,
        progress: Callable[[int], None] | None = None,
    ) -> None:
        self.family, self.recordings, self.names = family, recordings, tuple(names)
        self.tops, self.rpms, self.wob, self.objective = tops, rpms, wob, objective
        self.progress = progress
        self.runs = 0

    def models(self, x: np.ndarray) -> list[np.ndarray]:
        """The model's surface torque at each record's times [N m]."""
        system = self.family.system(dict(zip(self.names, map(float, x), strict=True)))
        torques = []
        for record, top, rpm in zip(self.recordings, self.tops, self.rpms, strict=True):
            torque, _ = model_torque(system.with_top(top).at(wob=self.wob, rpm=rpm), record)
            torques.append(torque)
        self.runs += len(self.recordings)
        if self.progress is not None:
            self.progress(len(self.recordings))
        return torques

    def split(self, x: np.ndarray) -> list[np.ndarray]:
        """The residuals of each recording [N m]."""
        return [
            residuals(self.objective, torque, record)
            for torque, record in zip(self.models(x), self.recordings, strict=True)
        ]

    def __call__(self, x: np.ndarray) -> np.ndarray:
        return np.concatenate(self.split(x))

    def cost(self, x: np.ndarray) -> float:
        """The sum of squared residuals [N^2 m^2]."""
        return float(np.sum(self(x) ** 2))
