"""The results of a severity map: :class:`SeverityMap`, its files and :func:`load_map`.

A :class:`SeverityMap` holds S_SS over a grid of rotary speed x weight on bit, the
classification of each point, the critical weight on bit per rotary speed and the
linear stability boundary (see :mod:`torsio.analysis.maps` for the conventions). It
describes itself (table rows, a dict for JSON, CSV, a plot) and never recomputes
anything. Built by :func:`torsio.analysis.maps.severity_map`; everything here is also
importable from :mod:`torsio.analysis.maps`.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from torsio.analysis.limits import stuck_points, warning_list
from torsio.analysis.map_checks import FORMAT, FORMAT_VERSION, LAYERS, check_map_data
from torsio.errors import ConfigError
from torsio.output_files import atomic_output, read_saved, write_npz, write_text
from torsio.solvers.batch_results import STATUS_MESSAGES
from torsio.units import RPM_TO_RAD_S

__all__ = [
    "BOUNDS",
    "CLASSES",
    "MapInterrupted",
    "STICK_SLIP_THRESHOLD",
    "SeverityMap",
    "critical_wob_text",
    "load_map",
]

STICK_SLIP_THRESHOLD = 0.05
"""S_SS above which a point is a sustained torsional oscillation ("stick-slip")."""

CLASSES = ("stable", "stick-slip", "severe")

_NPZ_ARRAYS = (
    *("wob", "rpm", "critical_wob", "critical_pi2", "stability_wob", "pi1", "pi2"),
    *("status", "steps", "done", "stuck", "classification", "critical_status"),
)
"""Keys of :meth:`SeverityMap.to_dict` that ``.npz`` holds as arrays."""
_EXACT = ("status", "steps", "done", "stuck", "classification", "critical_status")
"""Of those, the ones not stored as floats."""
"""Class names, in increasing severity (``"failed"`` marks a point the solver failed on)."""


class MapInterrupted(KeyboardInterrupt):
    """Ctrl-C during a map: ``partial`` is the map so far, with ``complete = False``."""

    def __init__(self, partial: SeverityMap) -> None:
        done = int(partial.done.sum())
        super().__init__(f"map interrupted: {done} of {partial.done.size} points computed")
        self.partial = partial


def _float_list(values: np.ndarray) -> list[Any]:
    return [None if not math.isfinite(float(v)) else float(v) for v in np.ravel(values)]


def critical_wob_text(
    value: float, bound: str | None, status: str, edge: tuple[float, float], scale: float = 1e3
) -> str:
    """W_ob,cr as table text: ``"181.4"``, ``"> 225"``, ``"≤ 25"`` or the status.

    Parameters
    ----------
    value : float
        W_ob,cr [N] (NaN where off the grid or unresolved).
    bound : {"above", "below"} or None
        Where W_ob,cr lies when off the grid (:attr:`SeverityMap.critical_wob_bound`).
    status : str
        The row's status, shown when there is neither a value nor a bound.
    edge : (float, float)
        Smallest and largest weight on bit of the grid [N].
    scale : float
        Divisor of the printed numbers (1e3: kN).

    Examples
    --------
    >>> critical_wob_text(float("nan"), "above", "none", (25e3, 225e3))
    '> 225'
    >>> critical_wob_text(float("nan"), "below", "below_range", (25e3, 225e3))
    '≤ 25'
    >>> critical_wob_text(181.4e3, None, "bisected", (25e3, 225e3))
    '181.4'
    """
    if bound == "above":
        return f"> {edge[1] / scale:.4g}"
    if bound == "below":
        return f"≤ {edge[0] / scale:.4g}"
    if math.isfinite(value):
        return f"{value / scale:.4g}"
    return status


BOUNDS = {"none": "above", "below_range": "below"}
"""Where W_ob,cr lies for each off-grid status: above the largest, at or below the smallest
weight on bit of the grid."""


@attrs.frozen(eq=False, repr=False)
class SeverityMap:
    """S_SS over a grid of rotary speed x weight on bit, with its critical curve.

    Attributes
    ----------
    wob : ndarray, shape (m,)
        Weights on bit [N], increasing.
    rpm : ndarray, shape (n,)
        Surface rotary speeds [rpm], increasing.
    severity : ndarray, shape (n, m)
        S_SS at (rpm[i], wob[j]); NaN where not computed or failed.
    critical_wob : ndarray, shape (n,)
        W_ob,cr per rpm [N]; NaN where it is not inside the grid (see
        :attr:`critical_wob_bound` and the module documentation).
    critical_status : tuple of str
        Per rpm: "bisected", "grid", "below_range", "none" or "unresolved".
    critical_bracket : ndarray, shape (n, 2)
        Final bisection bracket [N] (NaN where not bracketed).
    stability_wob : ndarray, shape (n,)
        Critical weight on bit of linear instability [N] (NaN where none).
    threshold : float
        S_SS above which a point is severe.
    stick_slip_threshold : float
        S_SS above which a point is a sustained oscillation.
    k_eq, omega1, bit_radius : float
        Equivalent stiffness [N m/rad], first natural frequency [rad/s] and bit
        radius [m]: the scales of Pi_1 and Pi_2.
    status : ndarray of int, shape (n, m)
        Solver status per point (0 ok; see :data:`torsio.solvers.batch_results.STATUS_MESSAGES`).
    steps : ndarray of int, shape (n, m)
        Accepted steps per point.
    done : ndarray of bool, shape (n, m)
        Whether each point was computed (all True for a complete map).
    complete : bool
        False for a map interrupted before the end.
    dimensionless : bool
        Whether the map was asked for over (Pi_1, Pi_2) (plots use those axes).
    info : dict
        Model, options, timing and executor (plain data).
    engine : str
        The batch engine that ran: ``"compiled"``, ``"numpy"`` or ``"scipy"``
        (:mod:`torsio.solvers.batch`; ``""`` in maps saved before it was recorded).
    stuck : ndarray of bool, shape (n, m)
        Whether the bit stuck throughout each point's steady window (S_SS then reads
        near 0 and says nothing of stick-slip: such points are classified ``"stuck"``);
        all False in maps saved before it was recorded.
    layers : dict
        Optional layers by name (:data:`~torsio.analysis.map_checks.LAYERS`), also
        attributes (``grid.rop``); empty for a torsional map.
    """

    wob: np.ndarray
    rpm: np.ndarray
    severity: np.ndarray
    critical_wob: np.ndarray
    critical_status: tuple[str, ...]
    critical_bracket: np.ndarray
    stability_wob: np.ndarray
    threshold: float
    stick_slip_threshold: float
    k_eq: float
    omega1: float
    bit_radius: float
    status: np.ndarray
    steps: np.ndarray
    done: np.ndarray
    complete: bool = True
    dimensionless: bool = False
    info: dict[str, Any] = attrs.field(factory=dict)
    engine: str = ""
    stuck: np.ndarray = attrs.field(
        default=attrs.Factory(lambda self: np.zeros(self.severity.shape, dtype=bool), True)
    )
    layers: Mapping[str, np.ndarray | None] = attrs.field(factory=dict)

    def __getattr__(self, name: str) -> Any:
        if name in LAYERS:  # a layer the map does not have: None
            return self.layers.get(name)
        raise AttributeError(name)

    @property
    def executor(self) -> str | None:
        """What ran the points (``"threads(2)"``, ``"processes(2)"``, ``"dask(...)"``)."""
        return self.info.get("executor")

    # --- derived ----------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, int]:
        """(number of rpm, number of wob)."""
        return (self.rpm.size, self.wob.size)

    @property
    def pi1(self) -> np.ndarray:
        """Pi_1 = Omega / omega_1 of each rpm."""
        return self.rpm * RPM_TO_RAD_S / self.omega1

    @property
    def pi2(self) -> np.ndarray:
        """Pi_2 = W_ob R_bit / k_eq of each wob."""
        return self.wob * self.bit_radius / self.k_eq

    @property
    def critical_pi2(self) -> np.ndarray:
        """Critical Pi_2 per rpm (NaN where none)."""
        return self.critical_wob * self.bit_radius / self.k_eq

    @property
    def stability_pi2(self) -> np.ndarray:
        """Pi_2 of the linear stability boundary per rpm."""
        return self.stability_wob * self.bit_radius / self.k_eq

    def classification(self) -> np.ndarray:
        """Class of each point (see the module documentation), shape (n, m), dtype str."""
        labels = np.full(self.severity.shape, "failed", dtype=object)
        s = self.severity
        ok = np.isfinite(s)
        labels[ok & (s <= self.stick_slip_threshold)] = "stable"
        labels[ok & (s > self.stick_slip_threshold) & (s <= self.threshold)] = "stick-slip"
        labels[ok & (s > self.threshold)] = "severe"
        labels[ok & self.stuck] = "stuck"
        labels[~self.done] = "missing"
        return labels.astype(str)

    def counts(self) -> dict[str, int]:
        """Number of points of each class."""
        labels = self.classification()
        names = (*CLASSES, "stuck", "failed", "missing")
        return {
            name: int((labels == name).sum())
            for name in names
            if (labels == name).any() or name in CLASSES
        }

    @property
    def warnings(self) -> tuple[str, ...]:
        """What limits the meaning of the map (:mod:`torsio.analysis.limits`)."""
        stuck = int((self.stuck & self.done).sum())
        return warning_list(
            self.info.get("contacts_warning"), stuck_points(stuck, self.severity.size)
        )

    def failures(self) -> list[str]:
        """One line per point the solver failed on."""
        rows = []
        for i, j in zip(*np.nonzero(self.done & (self.status != 0)), strict=True):
            reason = STATUS_MESSAGES.get(int(self.status[i, j]), f"status {self.status[i, j]}")
            rows.append(f"wob={self.wob[j]:g} N, rpm={self.rpm[i]:g}: {reason}")
        return rows

    # --- output -----------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON: the keys of ``torsio map --json`` and the rest of the map.

        ``severity[i][j]`` is at ``rpm[i]``, ``wob[j]``; missing values are None.
        """
        return {
            "format": FORMAT,
            "version": FORMAT_VERSION,
            "complete": self.complete,
            "wob": self.wob.tolist(),
            "rpm": self.rpm.tolist(),
            "severity": [_float_list(row) for row in self.severity],
            "critical_wob": _float_list(self.critical_wob),
            "critical_status": list(self.critical_status),
            "critical_wob_bound": list(self.critical_wob_bound),
            "critical_bracket": [_float_list(row) for row in self.critical_bracket],
            "critical_pi2": _float_list(self.critical_pi2),
            "stability_wob": _float_list(self.stability_wob),
            "classification": self.classification().tolist(),
            "threshold": self.threshold,
            "stick_slip_threshold": self.stick_slip_threshold,
            "pi1": self.pi1.tolist(),
            "pi2": self.pi2.tolist(),
            "k_eq": self.k_eq,
            "omega1": self.omega1,
            "bit_radius": self.bit_radius,
            "dimensionless": self.dimensionless,
            "counts": self.counts(),
            "status": self.status.tolist(),
            "steps": self.steps.tolist(),
            "done": self.done.tolist(),
            "info": self.info,
            "engine": self.engine,
            "stuck": self.stuck.tolist(),
            "warnings": list(self.warnings),
            **{key: self.info[key] for key in ("duration", "steady_window") if key in self.info},
            **{
                key: None if layer is None else [_float_list(row) for row in layer]
                for key, layer in self.layers.items()
            },
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> SeverityMap:
        """Rebuild a map from :meth:`to_dict` output."""
        if data.get("format") != FORMAT:
            raise ConfigError(
                "format", f"expected a {FORMAT!r} file, got format {data.get('format')!r}"
            )
        if int(data.get("version", 0)) > FORMAT_VERSION:
            raise ConfigError(
                "version",
                f"this torsio reads map format version "
                f"<= {FORMAT_VERSION}, got {data.get('version')!r}",
            )

        def array(key: str, dtype: Any = float) -> np.ndarray:
            value = data[key]
            if dtype is float:
                return np.array(
                    [[np.nan if x is None else x for x in row] for row in value]
                    if value and isinstance(value[0], list)
                    else [np.nan if x is None else x for x in value],
                    dtype=float,
                )
            return np.array(value, dtype=dtype)

        wob = array("wob")
        rpm = array("rpm")
        critical_status = tuple(data["critical_status"])
        critical_wob = array("critical_wob")
        # files of torsio <= 0.x gave wob[0] for a row severe throughout: not a value
        critical_wob[np.array([s == "below_range" for s in critical_status], dtype=bool)] = np.nan
        return cls(
            wob=wob,
            rpm=rpm,
            severity=array("severity").reshape(rpm.size, wob.size),
            critical_wob=critical_wob,
            critical_status=critical_status,
            critical_bracket=array("critical_bracket").reshape(rpm.size, 2),
            stability_wob=array("stability_wob"),
            threshold=float(data["threshold"]),
            stick_slip_threshold=float(data["stick_slip_threshold"]),
            k_eq=float(data["k_eq"]),
            omega1=float(data["omega1"]),
            bit_radius=float(data["bit_radius"]),
            status=array("status", np.int64).reshape(rpm.size, wob.size),
            steps=array("steps", np.int64).reshape(rpm.size, wob.size),
            done=array("done", bool).reshape(rpm.size, wob.size),
            complete=bool(data["complete"]),
            dimensionless=bool(data.get("dimensionless")),
            info=dict(data.get("info", {})),
            engine=str(data.get("engine", "")),
            stuck=(
                array("stuck", bool).reshape(rpm.size, wob.size)
                if "stuck" in data
                else np.zeros((rpm.size, wob.size), dtype=bool)
            ),
            layers={
                key: None if data[key] is None else array(key).reshape(rpm.size, wob.size)
                for key in LAYERS
                if key in data
            },
        )

    def save(self, path: str | Path) -> Path:
        """Write the map: JSON (``.json``, any other suffix) or numpy ``.npz``.

        JSON holds :meth:`to_dict`; ``.npz`` holds the same as arrays plus a
        ``metadata`` JSON string. The file is written to a temporary name and
        renamed once on the disk (:func:`torsio.output_files.atomic_output`), so a full
        disk or an interrupted write never leaves a truncated file: it raises
        :class:`~torsio.errors.OutputError` naming the path.
        An incomplete map is saved with ``"complete": false``.
        """
        path = Path(path)
        data = self.to_dict()
        directory = path.parent if str(path.parent) else Path(".")
        if not directory.is_dir():
            raise ConfigError("out", f"directory {str(directory)!r} does not exist")
        if path.suffix != ".npz":
            return write_text(path, json.dumps(data, indent=1))
        arrays: dict[str, Any] = {
            key: np.array(data[key], dtype=None if key in _EXACT else float) for key in _NPZ_ARRAYS
        }
        arrays["severity"] = self.severity
        arrays.update({k: v for k, v in self.layers.items() if v is not None})
        arrays["critical_bracket"] = self.critical_bracket
        return write_npz(path, {k: v for k, v in data.items() if k not in arrays}, arrays)

    def to_csv(self, path: str | Path) -> Path:
        """One row per grid point: rpm, wob [N], Pi_1, Pi_2, S_SS, class, solver status."""
        import csv

        path = Path(path)
        labels = self.classification()
        pi1, pi2 = self.pi1, self.pi2
        with atomic_output(path) as stream:
            writer = csv.writer(stream)
            writer.writerow(["rpm", "wob_N", "pi1", "pi2", "severity", "class", "status"])
            for (i, j), s in np.ndenumerate(self.severity):
                numbers = (self.rpm[i], self.wob[j], pi1[i], pi2[j])
                writer.writerow([*(repr(float(x)) for x in numbers),
                                 "" if not math.isfinite(s) else repr(float(s)),
                                 labels[i, j], int(self.status[i, j])])  # fmt: skip
        return path

    def __repr__(self) -> str:
        model = self.info.get("model", {})
        counts = ", ".join(f"{n} {name}" for name, n in self.counts().items())
        return (
            f"SeverityMap({model.get('name') or 'model'!r}, {model.get('strategy')}, "
            f"{model.get('dofs')} DOFs: {self.rpm.size} rpm x {self.wob.size} wob points, "
            f"rpm {self.rpm[0]:g}..{self.rpm[-1]:g}, wob {self.wob[0] / 1e3:g}.."
            f"{self.wob[-1] / 1e3:g} kN; {counts}" + ("" if self.complete else "; incomplete") + ")"
        )

    @property
    def critical_wob_bound(self) -> tuple[str | None, ...]:
        """Per rpm, where W_ob,cr lies when it is off the grid, else None.

        ``"above"``: no severe point at the largest weight on bit (status ``"none"``),
        so W_ob,cr, if any, exceeds ``wob[-1]``; ``"below"``: severe over the whole row
        (status ``"below_range"``), so W_ob,cr <= ``wob[0]``.
        """
        return tuple(BOUNDS.get(status) for status in self.critical_status)

    def critical_wob_texts(self, scale: float = 1e3) -> list[str]:
        """Per rpm, W_ob,cr as text divided by ``scale`` (``"> 225"``, ``"≤ 25"``, ``"181.4"``)."""
        edge = (float(self.wob[0]), float(self.wob[-1]))
        return [
            critical_wob_text(float(w), bound, status, edge, scale)
            for w, bound, status in zip(
                self.critical_wob, self.critical_wob_bound, self.critical_status, strict=True
            )
        ]

    def critical_rows(self) -> list[tuple[float, float | None, str, float | None]]:
        """(rpm, W_ob,cr [N] or None, status, linear-stability W_ob [N] or None) per rpm."""
        return [
            (
                float(r),
                None if not math.isfinite(w) else float(w),
                s,
                None if not math.isfinite(lin) else float(lin),
            )
            for r, w, s, lin in zip(
                self.rpm, self.critical_wob, self.critical_status, self.stability_wob, strict=True
            )
        ]

    def plot(
        self, path: str | Path | None = None, ax: Any = None, dimensionless: bool | None = None
    ) -> Any:
        """Heat map of S_SS with the critical curve and the linear stability boundary.

        Rotary speed on the x axis, weight on bit on the y axis (Pi_1 and Pi_2
        when ``dimensionless``; default: as the map was asked for). Needs
        matplotlib. Writes a PNG when ``path`` is given; returns the axes
        (:func:`torsio.plotting.map_plot.plot_severity_map`).
        """
        from torsio.plotting.map_plot import plot_severity_map

        return plot_severity_map(self, path=path, ax=ax, dimensionless=dimensionless)


def load_map(path: str | Path) -> SeverityMap:
    """Read a map written by :meth:`SeverityMap.save` (JSON or ``.npz``)."""
    data, arrays = read_saved(path, "severity map")
    if arrays:  # an .npz archive's (a JSON file's data is checked as it is)
        data.update({key: array.tolist() for key, array in arrays.items()})
    check_map_data(data, str(path))
    return SeverityMap.from_dict(data)
