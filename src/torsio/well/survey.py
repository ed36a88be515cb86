"""A directional survey and its minimum-curvature trajectory.

A survey is a list of stations: measured depth along the hole (m), inclination from the
vertical and azimuth clockwise from north (given in degrees, kept in radians). Between two
stations the hole is the circular arc of minimum curvature that joins their tangents
(SPE/ISCWSA practice; the ratio factor RF = (2/beta) tan(beta/2) of the textbooks is the
station-to-station form of :meth:`Survey.position`). Positions are north, east and true
vertical depth (down), in metres from the first station, which is the surface (md 0).

Everything along the arc is exact, at any measured depth: the unit tangent is the
spherical interpolation of the station tangents, the curvature vector dt/ds (pointing to
the centre of the arc, magnitude the dogleg severity beta/L) its derivative.

Examples
--------
>>> survey = Survey([0.0, 500.0, 800.0], [0.0, 0.0, 30.0], [0.0, 0.0, 90.0])
>>> round(float(survey.dogleg_severity(650.0)) * 30.0 * 180.0 / 3.141592653589793, 6)
3.0
>>> [round(float(x), 3) for x in survey.position(800.0)]
[0.0, 76.762, 786.479]
>>> Survey([0.0, 800.0, 500.0], [0.0, 0.0, 30.0], [0.0, 0.0, 90.0])
Traceback (most recent call last):
...
torsio.errors.ConfigError: md[2]: stations out of order: 500 m after 800 m; expected ...
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError

__all__ = ["Survey", "tangent_vector"]

_SMALL_DOGLEG = 1e-12
"""Below this dogleg [rad] an interval is straight (the arc formulas divide by it)."""


def tangent_vector(inclination: Any, azimuth: Any) -> np.ndarray:
    """Unit tangent (north, east, down) of a hole at ``inclination``, ``azimuth`` [rad].

    Examples
    --------
    >>> [round(float(x), 12) for x in tangent_vector(math.pi / 2, 0.0)]
    [1.0, 0.0, 0.0]
    """
    inc = np.asarray(inclination, dtype=float)
    azi = np.asarray(azimuth, dtype=float)
    return np.stack([np.sin(inc) * np.cos(azi), np.sin(inc) * np.sin(azi), np.cos(inc)], axis=-1)


def _floats(values: Any, key: str) -> np.ndarray:
    if isinstance(values, str | bytes) or not isinstance(values, Sequence | np.ndarray):
        raise ConfigError(key, f"expected an array of numbers, got {values!r}")
    out = []
    for i, value in enumerate(values):
        if isinstance(value, bool) or not isinstance(value, int | float | np.number):
            raise ConfigError(f"{key}[{i}]", f"expected a number, got {value!r}")
        if not math.isfinite(value):
            raise ConfigError(f"{key}[{i}]", f"expected a finite number, got {value!r}")
        out.append(float(value))
    return np.array(out, dtype=float)


MAX_DOGLEG_SEVERITY = 1.0
"""Largest dogleg severity a survey may have [rad/m] (a bend of radius 1 m, about 1719 deg
per 30 m): short-radius laterals, the tightest drilled, bend at radii of 6 to 12 m (1.5 to
3 deg/ft); a tighter survey is a typing error."""


@attrs.frozen(repr=False, eq=False)
class Survey:
    """Survey stations and the minimum-curvature hole through them.

    Parameters
    ----------
    md : sequence of float
        Measured depths of the stations [m], strictly increasing, the first 0 (the surface).
    inclination : sequence of float
        Inclination from the vertical at each station [deg], 0 to 180.
    azimuth : sequence of float
        Azimuth clockwise from north at each station [deg], any finite value.
    source : str
        Where the stations come from (shown in reports and errors).

    Raises
    ------
    ConfigError
        Arrays of different lengths, fewer than two stations, a first station below the
        surface, stations out of order, an inclination outside 0-180 deg, a value that is
        not a finite number, two stations whose tangents are opposite (no single arc), a
        dogleg severity above :data:`MAX_DOGLEG_SEVERITY`, or a station above the surface.
        The key named is ``md``, ``inclination`` or ``azimuth`` with the station index.
    """

    md: np.ndarray = attrs.field(converter=lambda v: _floats(v, "md"))
    inclination_deg: np.ndarray = attrs.field(converter=lambda v: _floats(v, "inclination"))
    azimuth_deg: np.ndarray = attrs.field(converter=lambda v: _floats(v, "azimuth"))
    source: str = ""
    _tangents: np.ndarray = attrs.field(init=False)
    _doglegs: np.ndarray = attrs.field(init=False)
    _positions: np.ndarray = attrs.field(init=False)
    _frames: dict[tuple[int, float], tuple[np.ndarray, np.ndarray]] = attrs.field(
        init=False, factory=dict
    )

    def __attrs_post_init__(self) -> None:
        md, inc, azi = self.md, self.inclination_deg, self.azimuth_deg
        if not len(md) == len(inc) == len(azi):
            raise ConfigError(
                "inclination" if len(inc) != len(md) else "azimuth",
                f"md, inclination and azimuth must have one value per station; got "
                f"{len(md)}, {len(inc)} and {len(azi)} values",
            )
        if len(md) < 2:
            raise ConfigError("md", f"expected at least two survey stations, got {len(md)}")
        if md[0] != 0.0:
            raise ConfigError(
                "md[0]",
                f"the first station must be the surface, md 0 (the tie-in), got {md[0]:g} m",
            )
        for i in range(1, len(md)):
            if not md[i] > md[i - 1]:
                raise ConfigError(
                    f"md[{i}]",
                    f"stations out of order: {md[i]:g} m after {md[i - 1]:g} m; expected "
                    "strictly increasing measured depths",
                )
        for i, value in enumerate(inc):
            if not 0.0 <= value <= 180.0:
                raise ConfigError(
                    f"inclination[{i}]",
                    f"expected an inclination from 0 to 180 degrees, got {value:g}",
                )
        tangents = tangent_vector(np.radians(inc), np.radians(azi))
        t1, t2 = tangents[:-1], tangents[1:]
        # 2 atan2(|t2 - t1|, |t2 + t1|): accurate for small and large doglegs alike
        doglegs = 2.0 * np.arctan2(np.linalg.norm(t2 - t1, axis=1), np.linalg.norm(t2 + t1, axis=1))
        for i, beta in enumerate(doglegs):
            if beta > math.pi - 1e-9:
                raise ConfigError(
                    f"inclination[{i + 1}]",
                    f"stations {i} and {i + 1} point in opposite directions (dogleg 180 deg); "
                    "no single arc joins them: add a station between them",
                )
        object.__setattr__(self, "_tangents", tangents)
        object.__setattr__(self, "_doglegs", doglegs)
        steps = np.array([self._arc(i, 1.0)[0] for i in range(len(md) - 1)]).reshape(-1, 3)
        object.__setattr__(self, "_positions", np.vstack([np.zeros(3), np.cumsum(steps, axis=0)]))
        severity = doglegs / np.diff(md)
        for i in np.flatnonzero(severity > MAX_DOGLEG_SEVERITY)[:1]:
            raise ConfigError(
                f"inclination[{i + 1}]",
                f"a dogleg of {math.degrees(doglegs[i]):.6g} deg over {md[i + 1] - md[i]:.4g} m "
                f"between stations {i} and {i + 1} (md {md[i]:g} and {md[i + 1]:g} m) bends the "
                f"hole at {severity[i]:.4g} rad/m; expected at most {MAX_DOGLEG_SEVERITY:g} "
                "rad/m (a radius of 1 m: the tightest drilled bends, short-radius laterals, "
                "have radii of 6 to 12 m)",
            )
        tvd = self._positions[:, 2]
        for i in np.flatnonzero(tvd < -1e-9 * md[-1])[:1]:
            raise ConfigError(
                f"inclination[{i}]",
                f"the hole is {-tvd[i]:.4g} m above the surface at station {i} (md {md[i]:g} "
                "m); expected a survey that stays at or below the rig floor (TVD >= 0)",
            )

    def __repr__(self) -> str:
        where = f", {self.source}" if self.source else ""
        return f"Survey({len(self.md)} stations to md {self.md[-1]:g} m{where})"

    # --- the stations -----------------------------------------------------------------
    @property
    def depth(self) -> float:
        """Measured depth of the last station [m]."""
        return float(self.md[-1])

    @property
    def station_positions(self) -> np.ndarray:
        """North, east, TVD of every station [m], shape (stations, 3)."""
        return self._positions.copy()

    @property
    def station_doglegs(self) -> np.ndarray:
        """Dogleg angle beta of each interval between stations [rad]."""
        return self._doglegs.copy()

    # --- the arc between stations -----------------------------------------------------
    def _interval(self, md: np.ndarray) -> np.ndarray:
        if np.any(md < 0.0) or np.any(md > self.md[-1]) or not np.all(np.isfinite(md)):
            bad = md[(md < 0.0) | (md > self.md[-1]) | ~np.isfinite(md)][0]
            raise ConfigError(
                "md", f"measured depth {bad:g} m is outside the survey (0 to {self.md[-1]:g} m)"
            )
        return np.clip(np.searchsorted(self.md, md, side="right") - 1, 0, len(self.md) - 2)

    def _arc(self, i: int, f: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement from station i, unit tangent and curvature vector at fraction f."""
        f = np.asarray(f, dtype=float)[..., None]
        t1, t2 = self._tangents[i], self._tangents[i + 1]
        length = self.md[i + 1] - self.md[i]
        beta = self._doglegs[i]
        if beta < _SMALL_DOGLEG:  # a straight interval
            tangent = (1.0 - f) * t1 + f * t2
            tangent = tangent / np.linalg.norm(tangent, axis=-1, keepdims=True)
            step = length * ((f - f * f / 2.0) * t1 + (f * f / 2.0) * t2)
            return step, tangent, np.zeros_like(tangent)
        sin_beta = math.sin(beta)
        a, b = (1.0 - f) * beta, f * beta
        tangent = (np.sin(a) * t1 + np.sin(b) * t2) / sin_beta
        curvature = (beta / length) * (-np.cos(a) * t1 + np.cos(b) * t2) / sin_beta
        # integral of the tangent, written without cancellation for small beta
        half = np.sin(b / 2.0)
        step = (length / (beta * sin_beta)) * (
            2.0 * np.sin((2.0 - f) * beta / 2.0) * half * t1 + 2.0 * half * half * t2
        )
        return step, tangent, curvature

    def interval(self, md: float) -> int:
        """Index i of the interval from station i to i + 1 that holds ``md`` (at a station,
        the interval below it; at the last station, the last interval)."""
        return int(self._interval(np.atleast_1d(np.asarray(md, dtype=float)))[0])

    def frame(self, interval: int, md: float) -> tuple[np.ndarray, np.ndarray]:
        """Unit tangent and curvature vector [1/m] at ``md`` on the arc of ``interval``
        (:meth:`interval`), also at its end stations, where the neighbour's arc differs."""
        key = (interval, float(md))
        kept = self._frames.get(key)
        if kept is None:  # torque and drag at another weight on bit asks the same points
            f = (md - self.md[interval]) / (self.md[interval + 1] - self.md[interval])
            _, tangent, curvature = self._arc(interval, f)
            tangent.setflags(write=False)
            curvature.setflags(write=False)
            kept = (tangent, curvature)
            if len(self._frames) < 200_000:
                self._frames[key] = kept
        return kept

    def _evaluate(self, md: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        depth = np.atleast_1d(np.asarray(md, dtype=float))
        index = self._interval(depth)
        steps = np.empty((depth.size, 3))
        tangents = np.empty((depth.size, 3))
        curvatures = np.empty((depth.size, 3))
        for i in np.unique(index):
            where = index == i
            f = (depth[where] - self.md[i]) / (self.md[i + 1] - self.md[i])
            step, tangent, curvature = self._arc(int(i), f)
            steps[where] = self._positions[i] + step
            tangents[where], curvatures[where] = tangent, curvature
        return steps, tangents, curvatures

    @staticmethod
    def _shape(md: Any, values: np.ndarray) -> np.ndarray:
        return values[0] if np.ndim(md) == 0 else values.reshape(np.shape(md) + values.shape[1:])

    def position(self, md: Any) -> np.ndarray:
        """North, east and true vertical depth at measured depth ``md`` [m], shape (..., 3)."""
        return self._shape(md, self._evaluate(md)[0])

    def tangent(self, md: Any) -> np.ndarray:
        """Unit tangent (north, east, down) of the hole at ``md``, shape (..., 3)."""
        return self._shape(md, self._evaluate(md)[1])

    def curvature(self, md: Any) -> np.ndarray:
        """Curvature vector dt/ds [1/m] at ``md``: towards the centre of the arc, magnitude
        the dogleg severity; zero on a straight interval. At a station, the interval below."""
        return self._shape(md, self._evaluate(md)[2])

    def dogleg_severity(self, md: Any) -> Any:
        """Dogleg severity |dt/ds| [rad/m] at ``md`` (multiply by 30 * 180/pi for deg/30 m)."""
        return np.linalg.norm(self.curvature(md), axis=-1)

    def inclination(self, md: Any) -> Any:
        """Inclination from the vertical at ``md`` along the arc [rad]."""
        t = self.tangent(md)
        return np.arctan2(np.hypot(t[..., 0], t[..., 1]), t[..., 2])

    def azimuth(self, md: Any) -> Any:
        """Azimuth clockwise from north at ``md`` along the arc [rad], in [0, 2 pi);
        NaN where the hole is vertical (no azimuth)."""
        t = self.tangent(md)
        horizontal = np.hypot(t[..., 0], t[..., 1])
        angle = np.mod(np.arctan2(t[..., 1], t[..., 0]), 2.0 * math.pi)
        return np.where(horizontal > 1e-15, angle, np.nan)

    def high_side(self, md: Any) -> np.ndarray:
        """Unit vector normal to the hole pointing up, towards the high side (d t / d inc);
        where the hole is vertical, the north-pointing normal."""
        inc = self.inclination(md)
        azi = np.nan_to_num(self.azimuth(md))
        return np.stack(
            [np.cos(inc) * np.cos(azi), np.cos(inc) * np.sin(azi), -np.sin(inc)], axis=-1
        )

    def build_rate(self, md: Any) -> Any:
        """Build rate d inc/ds [rad/m] at ``md`` (negative: a drop). Where the hole is
        vertical every bend builds: the rate is the dogleg severity (its negative pointing up)."""
        t, k = self.tangent(md), self.curvature(md)
        along_high_side = np.sum(k * self.high_side(md), axis=-1)
        vertical = np.hypot(t[..., 0], t[..., 1]) <= 1e-15
        return np.where(vertical, np.sign(t[..., 2]) * np.linalg.norm(k, axis=-1), along_high_side)

    def turn_rate(self, md: Any) -> Any:
        """Turn rate d azi/ds [rad/m] at ``md`` (positive: clockwise seen from above);
        NaN where the hole is vertical."""
        azi = np.nan_to_num(self.azimuth(md))
        right = np.stack([-np.sin(azi), np.cos(azi), np.zeros_like(azi)], axis=-1)
        sin_inc = np.sin(self.inclination(md))
        with np.errstate(divide="ignore", invalid="ignore"):
            rate = np.sum(self.curvature(md) * right, axis=-1) / sin_inc
        return np.where(sin_inc > 1e-15, rate, np.nan)
