"""The operating window's region, its constraints and the objective.

A point (W, N) is **admissible** when it is not severe (S_SS at most the criterion, the
paper's 0.8: :data:`torsio.analysis.severity.SEVERE_THRESHOLD`), its mean surface torque
over the steady window is at most ``max_surface_torque`` (the top drive's continuous torque
or the connections' make-up torque) and W at most ``max_wob``; the rpm range is the
region's. Among admissible points the objective picks the best: the largest mean ROP
(``rop``) or the least mean MSE (``mse``).

Examples
--------
>>> region = Region(wob=(80e3, 140e3), rpm=(60.0, 180.0), wob_points=5, rpm_points=4)
>>> region.coarse_wob().tolist()
[80000.0, 95000.0, 110000.0, 125000.0, 140000.0]
>>> Constraints(max_surface_torque=-1.0)
Traceback (most recent call last):
...
torsio.errors.ConfigError: --max-surface-torque: expected a positive torque in N m, got -1.0
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.analysis.severity import SEVERE_THRESHOLD
from torsio.errors import ConfigError

__all__ = [
    "DEFAULT_RPM",
    "DEFAULT_WOB",
    "OBJECTIVES",
    "Constraints",
    "Region",
    "default_region",
    "objective_value",
]

DEFAULT_RPM = (40.0, 180.0, 5)
"""The rpm range and coarse points when neither ``--rpm`` nor the call gives one: the range
of a top drive drilling with a PDC bit."""

DEFAULT_WOB = (1.1, 2.0, 5)
"""The WOB range when none is given, in multiples of the weight the RGD bit's wear flats
carry (σ a l, below which it does not cut), and its coarse points (as ``torsio map``'s
axial default)."""

OBJECTIVES = {"rop": "largest mean ROP", "mse": "least mean MSE"}
"""The objectives the advisor takes, and what each picks among the admissible points."""


def _positive_or_none(flag: str, unit: str) -> Any:
    def check(instance: Any, attribute: Any, value: float | None) -> None:
        if value is not None and not (math.isfinite(value) and value > 0):
            raise ConfigError(flag, f"expected a positive {unit}, got {value!r}")

    return check


@attrs.frozen
class Region:
    """The (WOB, rpm) rectangle searched and its coarse map.

    ``wob`` [N] and ``rpm`` [rev/min] are (low, high); ``wob_points`` x ``rpm_points`` the
    coarse grid (each at least 2)."""

    wob: tuple[float, float]
    rpm: tuple[float, float]
    wob_points: int = 5
    rpm_points: int = 5

    def __attrs_post_init__(self) -> None:
        for flag, (low, high), count in (
            ("--wob", self.wob, self.wob_points),
            ("--rpm", self.rpm, self.rpm_points),
        ):
            if not (math.isfinite(low) and math.isfinite(high) and 0 < low < high):
                raise ConfigError(flag, f"expected 0 < START < STOP, got {low:g}:{high:g}")
            if isinstance(count, bool) or not isinstance(count, int) or count < 2:
                raise ConfigError(flag, f"expected N >= 2 coarse points, got {count!r}")

    def coarse_wob(self) -> NDArray[np.float64]:
        """The coarse map's weights on bit [N]."""
        return np.linspace(*self.wob, self.wob_points)

    def coarse_rpm(self) -> NDArray[np.float64]:
        """The coarse map's rotary speeds [rev/min]."""
        return np.linspace(*self.rpm, self.rpm_points)

    def to_dict(self) -> dict[str, Any]:
        """``wob`` [N] and ``rpm`` ranges and the coarse map's points."""
        return {
            "wob": list(self.wob),
            "rpm": list(self.rpm),
            "wob_points": self.wob_points,
            "rpm_points": self.rpm_points,
        }


@attrs.frozen
class Constraints:
    """What an admissible point respects (module documentation).

    Attributes
    ----------
    max_surface_torque : float or None
        Largest mean surface torque over the window [N m] (None: no limit).
    max_wob : float or None
        Largest weight on bit [N] (None: the region's).
    severity : float
        The S_SS above which a point is severe (default the paper's 0.8).
    objective : str
        ``"rop"`` or ``"mse"`` (:data:`OBJECTIVES`).
    torque_limit : str
        Where ``max_surface_torque`` comes from (a flag, or ``"top_drive.max_torque"``).
    """

    max_surface_torque: float | None = attrs.field(
        default=None, validator=_positive_or_none("--max-surface-torque", "torque in N m")
    )
    max_wob: float | None = attrs.field(
        default=None, validator=_positive_or_none("--max-wob", "weight on bit in N")
    )
    severity: float = attrs.field(
        default=SEVERE_THRESHOLD, validator=_positive_or_none("--severity", "S_SS")
    )
    objective: str = "rop"
    torque_limit: str = "--max-surface-torque"

    def __attrs_post_init__(self) -> None:
        if self.objective not in OBJECTIVES:
            raise ConfigError(
                "--objective",
                f"unknown objective {self.objective!r}; expected one of {', '.join(OBJECTIVES)}",
            )

    def admissible(self, evaluation: Any) -> NDArray[np.bool_]:
        """Which points of an :class:`~torsio.advice.evaluate.Evaluation` are admissible
        (a failed run, NaN, is not)."""
        ok = np.asarray(evaluation.severity <= self.severity)
        if self.max_surface_torque is not None:
            ok &= evaluation.surface_torque <= self.max_surface_torque
        if self.max_wob is not None:
            ok &= evaluation.wob <= self.max_wob
        return ok

    def to_dict(self) -> dict[str, Any]:
        """The constraints and the criterion: ``max_surface_torque`` [N m] and where it comes
        from, ``max_wob`` [N], ``severity`` (S_SS), ``objective``, ``criterion`` (in words)."""
        return {
            "max_surface_torque": self.max_surface_torque,
            "max_surface_torque_from": (
                self.torque_limit if self.max_surface_torque is not None else None
            ),
            "max_wob": self.max_wob,
            "severity": self.severity,
            "objective": self.objective,
            "criterion": (
                f"{OBJECTIVES[self.objective]} among points with S_SS <= {self.severity:g}"
                + (
                    f", mean surface torque <= {self.max_surface_torque:g} N m"
                    if self.max_surface_torque is not None
                    else ""
                )
                + (f", WOB <= {self.max_wob:g} N" if self.max_wob is not None else "")
            ),
        }


def default_region(bit: Any) -> Region:
    """The region of :data:`DEFAULT_WOB` (times ``bit.friction_weight`` [N]) and
    :data:`DEFAULT_RPM`."""
    low, high, count = DEFAULT_WOB
    weight = float(bit.friction_weight)
    rpm_low, rpm_high, rpm_count = DEFAULT_RPM
    return Region((low * weight, high * weight), (rpm_low, rpm_high), count, rpm_count)


def objective_value(evaluation: Any, objective: str) -> NDArray[np.float64]:
    """The score to maximize at each point: the ROP [m/s], or minus the MSE [Pa]."""
    if objective == "rop":
        return np.asarray(evaluation.rop, dtype=float)
    return -np.asarray(evaluation.mse, dtype=float)
