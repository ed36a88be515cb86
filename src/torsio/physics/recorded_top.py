"""A top drive that follows a recording: the top held at the recorded speed.

``kind = "recorded"`` with ``recording = FILE`` (a CSV of
:mod:`torsio.calibration.recording`; in a configuration file a relative path is read from
the file's folder) or, from Python, a :class:`~torsio.calibration.recording.Recording`.
The top turns at the recorded top-drive speed, linear between samples and constant after
the last one (time counted from the first sample), whatever the rig's controller did:
a calibration against the record then needs no model of the controller. The set speed
(for S_SS) is the last recorded speed. It runs on every model, the wave model and the
lumped strategies (a set speed that changes in time, docs/top_drives.md); maps refuse it
(no set speed per point).

Examples
--------
>>> import numpy as np
>>> from torsio.calibration.recording import Recording
>>> record = Recording(time=[0.0, 5.0, 10.0], top_speed=[0.0, 12.0, 12.0],
...                    surface_torque=[0.0, 9e3, 8e3], name="rig.csv")
>>> top = RecordedTopDrive(recording=record)
>>> boundary = top.boundary(None)
>>> boundary.held, boundary.set_speed, boundary.speed_table.tolist()
(True, 12.0, [[0.0, 5.0, 10.0], [0.0, 12.0, 12.0]])
>>> RecordedTopDrive(recording=3.0)
Traceback (most recent call last):
...
torsio.errors.ConfigError: top_drive.recording: expected a CSV file (a path) or a Recording, got 3.0
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, ClassVar

import attrs

from torsio.calibration.recording import Recording, read_recording
from torsio.errors import ConfigError
from torsio.physics.top_drive_boundary import TopDriveBoundary

__all__ = ["RecordedTopDrive"]


def _as_recording(value: Any) -> Recording:
    if isinstance(value, Recording):
        return value
    if isinstance(value, str | Path):
        try:
            return read_recording(value)
        except ConfigError as exc:
            raise ConfigError("top_drive.recording", exc.message) from None
    raise ConfigError(
        "top_drive.recording", f"expected a CSV file (a path) or a Recording, got {value!r}"
    )


def _as_window(value: Any) -> float:
    if isinstance(value, str):
        from torsio.units import to_si

        value = to_si(value, "time", key="top_drive.smoothing")
    if isinstance(value, bool) or not isinstance(value, int | float) or not value >= 0.0:
        raise ConfigError("top_drive.smoothing", f"expected a window >= 0 in s, got {value!r}")
    return float(value)


@attrs.frozen
class RecordedTopDrive:
    """The top held at the speed of a recording (no node, no state).

    Parameters
    ----------
    recording : Recording or str or Path
        The record (a path is read with :func:`~torsio.calibration.recording.read_recording`).
    smoothing : float or str
        Window [s] of the centred mean the recorded speed is smoothed with before it
        drives the top (:meth:`~torsio.calibration.recording.Recording.speed_table`):
        noise on the recorded speed would otherwise drive the string (an
        errors-in-variables bias of what is fitted to the torque); 0: as recorded.
    """

    name: ClassVar[str] = "recorded"
    description: ClassVar[str] = "Omega_0(t) = the recorded top-drive speed"
    path_parameters: ClassVar[tuple[str, ...]] = ("recording",)

    recording: Recording = attrs.field(converter=_as_recording)
    smoothing: float = attrs.field(default=0.0, converter=_as_window)

    def past_the_record(self, duration: float) -> str | None:
        """The warning for a run of ``duration`` [s] that outlasts the record, else None:
        the top is then held at the last recorded speed, which the rig may not have kept.

        >>> record = Recording(time=[0.0, 30.0], top_speed=[0.0, 12.5],
        ...                    surface_torque=[0.0, 9e3], name="rig.csv")
        >>> print(RecordedTopDrive(recording=record).past_the_record(173.5))
        the run (173.5 s) outlasts the recording rig.csv (30 s): the top is held at its last
        speed, 119.4 rpm, for the last 143.5 s
        >>> RecordedTopDrive(recording=record).past_the_record(30.0) is None
        True
        """
        record = self.recording
        if duration <= record.duration * (1.0 + 1e-9):
            return None
        return (
            f"the run ({duration:g} s) outlasts the recording {record.name} "
            f"({record.duration:g} s): the top is held at its last speed, "
            f"{float(record.top_speed[-1]) * 30.0 / math.pi:.4g} rpm, for the last "
            f"{duration - record.duration:g} s"
        )

    def boundary(self, system: Any) -> TopDriveBoundary:
        """A held top whose set speed is the recorded speed against time."""
        table = self.recording.speed_table(self.smoothing)
        return TopDriveBoundary(inertia=0.0, set_speed=float(table[1, -1]), speed_table=table)
