"""S_SS of a batch of operating points, and what each point's status code means."""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.units import RPM_TO_RAD_S

DEFAULT_STEADY_TOLERANCE = 1e-3
"""Default steady-cycle tolerance of the compiled engines, in S_SS units: a run ends once
the motion is on a cycle whose extremes can move by no more than this over the rest of
the run (:mod:`torsio.solvers.cycles`, :mod:`torsio.solvers.characteristics`); 0 runs
every point to the end."""

STATUS_OK = 0
STATUS_MAX_STEPS = 1
STATUS_STEP_UNDERFLOW = 2
STATUS_NOT_FINITE = 3
STATUS_SOLVER_FAILED = 4
STATUS_CHATTER = 5
STATUS_MESSAGES = {
    STATUS_OK: "ok",
    STATUS_MAX_STEPS: "too many steps",
    STATUS_STEP_UNDERFLOW: "step size underflow",
    STATUS_NOT_FINITE: "non-finite state",
    STATUS_SOLVER_FAILED: "solve_ivp failed (scipy engine)",
    STATUS_CHATTER: "the contacts along the string chatter (too many switches)",
}
"""What each per-point status code means."""


def check_steady_tolerance(value: Any) -> float:
    """A steady-cycle tolerance [S_SS units] in [0, 0.1], else a ConfigError naming it."""
    if isinstance(value, bool) or not (
        isinstance(value, int | float) and math.isfinite(value) and 0 <= value <= 0.1
    ):
        raise ConfigError(
            "steady_tolerance",
            f"expected a tolerance in S_SS units in [0, 0.1] (0: run to the end), got {value!r}",
        )
    return float(value)


@attrs.frozen(eq=False)
class BatchPoints:
    """Operating points of a batch, flat and checked: built once by :func:`batch_points`
    (or from a map's checked axes), then sliced into chunks without checking them again.

    Attributes
    ----------
    wob : ndarray
        Weight on bit of each point [N], finite and >= 0.
    rpm : ndarray
        Surface rotary (set) speed of each point [rpm], finite and > 0; NaN for a top drive
        without a set speed.
    torque_driven : bool
        Whether the top drive has no set speed (``torque``).
    """

    wob: np.ndarray
    rpm: np.ndarray
    torque_driven: bool = False

    @property
    def size(self) -> int:
        """Number of points."""
        return int(self.wob.size)

    def __getitem__(self, rows: Any) -> BatchPoints:
        return BatchPoints(self.wob[rows], self.rpm[rows], self.torque_driven)


def refuse_speed_table(top: Any, boundary: Any) -> None:
    """A batch (a map) of a ``top`` drive whose ``boundary`` follows a table of speeds (a
    recording) is a ConfigError (``top_drive.kind``): each point has its own set speed."""
    if boundary.speed_table is not None:
        raise ConfigError(
            "top_drive.kind",
            f"a batch (a map) runs every point at its own set speed, and the top drive "
            f"{getattr(top, 'name', top)!r} follows a table of speeds (a recording); map "
            "with a speed-controlled top drive (a single run, torsio simulate, follows the "
            "table)",
        )


def batch_points(system: Any, wob: Any, rpm: Any) -> BatchPoints:
    """The points (wob [N], rpm [rpm]) of a batch, broadcast, flat and checked.

    ``rpm`` is None exactly for a top drive without a set speed; its rpm are then NaN.
    Points already checked (a :class:`BatchPoints`, with ``rpm`` None) are returned as
    they are.
    """
    if isinstance(wob, BatchPoints) and rpm is None:
        return wob
    boundary = system.top.boundary(system)
    refuse_speed_table(system.top, boundary)
    torque_driven = not boundary.held and not math.isfinite(boundary.set_speed)
    if torque_driven != (rpm is None):
        raise ConfigError(
            "rpm",
            "a top drive without a set speed (kind 'torque') takes no rotary speeds (rpm=None);"
            " S_SS is relative to its mean speed"
            if torque_driven
            else "expected rotary speeds in rpm",
        )
    wob_arr, rpm_arr = np.broadcast_arrays(
        np.asarray(wob, dtype=float), np.asarray(60.0 if rpm is None else rpm, dtype=float)
    )
    wob_arr = np.ascontiguousarray(wob_arr.ravel())
    rpm_arr = np.ascontiguousarray(rpm_arr.ravel())
    if wob_arr.size and not (np.isfinite(wob_arr).all() and (wob_arr >= 0).all()):
        bad = wob_arr[~(np.isfinite(wob_arr) & (wob_arr >= 0))][0]
        raise ConfigError("wob", f"expected non-negative finite weights on bit in N, got {bad!r}")
    if rpm_arr.size and not (np.isfinite(rpm_arr).all() and (rpm_arr > 0).all()):
        bad = rpm_arr[~(np.isfinite(rpm_arr) & (rpm_arr > 0))][0]
        raise ConfigError("rpm", f"expected positive finite rotary speeds, got {bad!r}")
    if torque_driven:
        rpm_arr = np.full_like(wob_arr, np.nan)
    return BatchPoints(wob_arr, rpm_arr, torque_driven)


_POINT_FIELDS = (
    "wob",
    "rpm",
    "severity",
    "bit_speed_max",
    "bit_speed_min",
    "top_speed_mean",
    "steps",
    "rejected",
    "status",
    "ended",
)
"""The fields of :class:`BatchResults` with one value per point."""


@attrs.frozen(repr=False)
class BatchResults:
    """S_SS of a batch of operating points.

    Attributes
    ----------
    wob : ndarray
        Weight on bit of each point [N].
    rpm : ndarray
        Surface rotary speed (set speed) of each point [rpm]; NaN for a torque-driven top.
    severity : ndarray
        S_SS (Eq. 12) of each point; NaN where the solver failed.
    bit_speed_max, bit_speed_min : ndarray
        Extremes of the bit speed over the steady window [rad/s].
    top_speed_mean : ndarray
        Mean top-drive speed over the steady window [rad/s].
    steps, rejected : ndarray
        Accepted and rejected steps of each point.
    status : ndarray
        0 for success, else a key of :data:`STATUS_MESSAGES`.
    engine : str
        The engine that ran: ``"compiled"``, ``"numpy"`` or ``"scipy"``.
    duration, steady_window : float
        Run length and steady window [s].
    rtol, atol : float
        Tolerances.
    elapsed : float
        Wall time [s].
    ended : ndarray
        Time [s] each run ended: ``duration``, or earlier where the compiled engine found
        the motion on a steady cycle (:mod:`torsio.solvers.cycles`).
    steady_tolerance : float
        The steady-cycle tolerance used (0: every run went to the end).
    """

    wob: np.ndarray
    rpm: np.ndarray
    severity: np.ndarray
    bit_speed_max: np.ndarray
    bit_speed_min: np.ndarray
    top_speed_mean: np.ndarray
    steps: np.ndarray
    rejected: np.ndarray
    status: np.ndarray
    engine: str
    duration: float
    steady_window: float
    rtol: float
    atol: float
    elapsed: float
    ended: np.ndarray = attrs.field(
        default=attrs.Factory(lambda self: np.full(self.severity.shape, self.duration), True)
    )
    steady_tolerance: float = 0.0

    @classmethod
    def gather(cls, parts: list[tuple[np.ndarray, BatchResults]], size: int) -> BatchResults:
        """One batch of ``size`` points from parts run apart: ``(rows, results)``, the
        rows of the whole batch each part holds (times added; the rest from the first)."""
        first = parts[0][1]
        arrays: dict[str, Any] = {}
        for name in _POINT_FIELDS:
            column = np.empty(size, dtype=getattr(first, name).dtype)
            for rows, part in parts:
                column[rows] = getattr(part, name)
            arrays[name] = column
        return attrs.evolve(first, elapsed=sum(part.elapsed for _, part in parts), **arrays)

    def __repr__(self) -> str:  # short: counts, no arrays
        return (
            f"BatchResults({self.severity.size} points, {int(np.sum(self.status != 0))} failed, "
            f"engine {self.engine!r}, rtol {self.rtol:g}, {self.elapsed:.3g} s)"
        )

    @property
    def ok(self) -> np.ndarray:
        """Whether each point was integrated successfully."""
        return self.status == STATUS_OK

    def stuck(self, stick_threshold: float) -> np.ndarray:
        """Whether the bit stuck throughout each point's steady window: |bit speed| below
        ``stick_threshold`` times Omega (the set speed, or the mean top-drive speed of a
        torque-driven top) at every step there; False where the point failed."""
        reference = np.where(np.isnan(self.rpm), self.top_speed_mean, self.rpm * RPM_TO_RAD_S)
        with np.errstate(invalid="ignore"):
            fastest = np.maximum(np.abs(self.bit_speed_max), np.abs(self.bit_speed_min))
            return self.ok & (fastest < stick_threshold * reference)

    def failures(self) -> list[str]:
        """One line per failed point: operating point and reason."""
        return [
            f"wob={w:g} N, rpm={r:g}: {STATUS_MESSAGES.get(int(s), f'status {s}')}"
            for w, r, s in zip(self.wob, self.rpm, self.status, strict=True)
            if s
        ]
