"""Validation of a saved severity map before it becomes a :class:`SeverityMap`.

A map file comes from outside (another version, another program, a truncated
copy, a hand edit), so :func:`check_map_data` checks everything a map's methods
rely on and names the first key that is wrong: the structure (a JSON object with
every key), the types and shapes of the arrays against the grid, the classes of
the critical curve, and the ``complete`` flag against the points done (a map
that says it is complete has every point done; a point not done has no
severity; a point done has a severity unless its solver status says it failed).

Examples
--------
>>> check_map_data([1, 2], "m.json")
Traceback (most recent call last):
...
torsio.errors.ConfigError: m.json: expected a JSON object with the keys of a severity map, got list
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.errors import ConfigError

__all__ = [
    "CRITICAL_STATUSES",
    "LAYERS",
    "FORMAT",
    "FORMAT_VERSION",
    "REQUIRED_KEYS",
    "check_map_data",
]

FORMAT = "torsio-severity-map"
"""The ``format`` key of saved maps (version :data:`FORMAT_VERSION`)."""

FORMAT_VERSION = 1

REQUIRED_KEYS = (
    "format",
    "complete",
    "wob",
    "rpm",
    "severity",
    "critical_wob",
    "critical_status",
    "critical_bracket",
    "stability_wob",
    "threshold",
    "stick_slip_threshold",
    "k_eq",
    "omega1",
    "bit_radius",
    "status",
    "steps",
    "done",
)
"""Keys every saved map has (others, e.g. ``info``, are optional)."""

LAYERS: tuple[str, ...] = ("rop", "mse", "stick_fraction", "off_bottom_fraction", "axial_severity")
LAYERS += ("growth_rate", "string_friction_work")
"""Optional layers of a map, shaped as ``severity`` (the axial engine's): mean ROP [m/s] and
MSE [Pa], stuck and off-bottom fractions, axial severity, the linear growth rate of steady
drilling [1/s], the work of the friction along the string [J]; None: asked, not computed."""

CRITICAL_STATUSES = (
    "bisected",
    "grid",
    "below_range",
    "above_range",
    "none",
    "unresolved",
)
"""Values ``critical_status`` may hold."""


def _array(data: dict[str, Any], key: str, where: str, dtype: Any) -> np.ndarray:
    value = data[key]
    try:
        if dtype is float:
            value = _none_to_nan(value)
        array = np.asarray(value, dtype=dtype)
    except (TypeError, ValueError, OverflowError) as exc:
        raise ConfigError(
            f"{where}: {key}", f"expected a regular array of numbers ({exc})"
        ) from None
    return array


def _none_to_nan(value: Any) -> Any:
    if value is None:
        return math.nan
    if isinstance(value, list):
        return [_none_to_nan(v) for v in value]
    return value


def _shape(array: np.ndarray, shape: tuple[int, ...], key: str, where: str) -> None:
    if array.shape != shape:
        raise ConfigError(
            f"{where}: {key}", f"expected shape {shape} for this grid, got {array.shape}"
        )


def check_map_data(data: Any, where: str) -> None:
    """ConfigError naming the key if ``data`` is not a consistent saved severity map.

    Parameters
    ----------
    data : Any
        What the file holds (a dict from JSON, or from an ``.npz`` archive).
    where : str
        The file, for messages.
    """
    if not isinstance(data, dict):
        raise ConfigError(
            where,
            f"expected a JSON object with the keys of a severity map, got {type(data).__name__}",
        )
    if data.get("format") != FORMAT:
        raise ConfigError(
            f"{where}: format", f"expected a {FORMAT!r} file, got format {data.get('format')!r}"
        )
    missing = [key for key in REQUIRED_KEYS if key not in data]
    if missing:
        raise ConfigError(f"{where}: {missing[0]}", "missing key of a saved severity map")
    wob = _array(data, "wob", where, float)
    rpm = _array(data, "rpm", where, float)
    for key, axis in (("wob", wob), ("rpm", rpm)):
        if axis.ndim != 1 or axis.size == 0 or not np.isfinite(axis).all():
            raise ConfigError(f"{where}: {key}", "expected a non-empty list of finite numbers")
        if axis.size > 1 and not (np.diff(axis) > 0).all():
            raise ConfigError(f"{where}: {key}", "expected strictly increasing values")
    grid = (rpm.size, wob.size)
    _shape(_array(data, "severity", where, float), grid, "severity", where)
    for key in ("critical_wob", "stability_wob"):
        _shape(_array(data, key, where, float), (rpm.size,), key, where)
    _shape(_array(data, "critical_bracket", where, float), (rpm.size, 2), "critical_bracket", where)
    for key in (key for key in LAYERS if data.get(key) is not None):  # optional layers
        _shape(_array(data, key, where, float), grid, key, where)
    for key in ("status", "steps"):
        array = _array(data, key, where, float)
        _shape(array, grid, key, where)
        if not (np.isfinite(array).all() and (array == np.round(array)).all()):
            raise ConfigError(f"{where}: {key}", "expected whole numbers")
    for key in ("done", "stuck") if "stuck" in data else ("done",):
        flags = np.asarray(data[key], dtype=object)
        _shape(flags, grid, key, where)
        if not all(isinstance(v, bool | np.bool_) for v in flags.ravel()):
            raise ConfigError(f"{where}: {key}", "expected true or false at every point")
    done_array = np.asarray(data["done"], dtype=object)
    statuses = data["critical_status"]
    if (
        not isinstance(statuses, list | tuple | np.ndarray)
        or len(statuses) != rpm.size
        or not all(str(s) in CRITICAL_STATUSES for s in statuses)
    ):
        raise ConfigError(
            f"{where}: critical_status",
            f"expected {rpm.size} values among {', '.join(CRITICAL_STATUSES)}",
        )
    for key in ("threshold", "stick_slip_threshold", "k_eq", "omega1", "bit_radius"):
        value = data[key]
        if isinstance(value, bool) or not isinstance(value, int | float | np.number):
            raise ConfigError(f"{where}: {key}", f"expected a number, got {value!r}")
        if not math.isfinite(float(value)) or float(value) < 0:
            raise ConfigError(f"{where}: {key}", f"expected a finite number >= 0, got {value!r}")
    complete = data["complete"]
    if not isinstance(complete, bool | np.bool_):
        raise ConfigError(f"{where}: complete", f"expected true or false, got {complete!r}")
    _check_points(data, where, done_array.astype(bool), bool(complete))


def _check_points(data: dict[str, Any], where: str, done: np.ndarray, complete: bool) -> None:
    severity = np.asarray(_none_to_nan(data["severity"]), dtype=float)
    status = np.asarray(data["status"], dtype=float)
    if complete and not done.all():
        raise ConfigError(
            f"{where}: complete",
            f"the map says it is complete but {int((~done).sum())} of {done.size} points "
            "are not done",
        )
    if np.isfinite(severity[~done]).any():
        raise ConfigError(f"{where}: severity", "a point not done has a severity")
    unexplained = done & (status == 0) & ~np.isfinite(severity)
    if unexplained.any():
        raise ConfigError(
            f"{where}: severity",
            f"{int(unexplained.sum())} points are done with solver status 0 but have no severity",
        )
    if (np.isfinite(severity) & (severity < 0)).any():
        raise ConfigError(f"{where}: severity", "expected severities >= 0")
