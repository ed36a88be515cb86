"""Severity maps: S_SS over a grid of weight on bit x rotary speed, and over Pi_1 x Pi_2.

:func:`severity_map` runs the batch engine (:mod:`torsio.solvers.batch`) over every point
of a grid, in chunks on any executor (:mod:`torsio.analysis.sweep`), then locates the
critical weight on bit of each rotary speed with extra runs, and adds the linear
stability boundary (:mod:`torsio.analysis.stability`). :func:`dimensionless_map` does the
same over the groups of Eq. 11, Pi_1 = Omega/omega_1 and Pi_2 = W_ob R_bit/k_eq.

Conventions
-----------
``severity[i][j]`` is S_SS at ``rpm[i]`` and ``wob[j]`` (the JSON layout of
``torsio map --json``); both axes are strictly increasing.

Classification of each point:

* ``stable``: S_SS <= :data:`STICK_SLIP_THRESHOLD` (0.05): the bit speed swings by
  less than +-5 % of Omega over the steady window (steady rotation, or a
  transient that has almost died out);
* ``stick-slip``: :data:`STICK_SLIP_THRESHOLD` < S_SS <= threshold: a sustained
  torsional oscillation;
* ``severe``: S_SS > threshold (the paper's 0.8 by default).

Critical weight on bit W_ob,cr(Omega), per rotary speed (the paper's Fig. 6):
the lowest weight on bit above which the vibration is severe. On the grid row,
j* is the first index from which every point up to the largest weight on bit is
severe. Then

* no severe point at the largest weight on bit: none (``null``, status ``"none"``);
* j* = 0 (severe over the whole row): W_ob,cr <= wob[0]; reported as wob[0] with
  status ``"below_range"``;
* otherwise the cell [wob[j*-1], wob[j*]] is bisected ``refine`` times with extra
  runs (mid-point severe: keep the lower half, else the upper half) and
  W_ob,cr is the middle of the final bracket, within +- (wob[j*] - wob[j*-1]) /
  2^(refine+1); status ``"bisected"`` (``"grid"`` when refine = 0).

Bisection finds where S_SS crosses the threshold, which at the stick-slip onset is
usually a jump; if S_SS is not monotonic inside the cell it finds one crossing.

Examples
--------
>>> from torsio.physics.system import System, builtin_config
>>> system = System.from_config(builtin_config(), strategy="A")
>>> result = severity_map(system, wob=[50e3, 150e3], rpm=[60.0, 120.0], refine=2)
>>> result.severity.round(2).tolist()
[[0.0, 1.32], [0.0, 0.0]]
>>> result.classification().tolist()
[['stable', 'severe'], ['stable', 'stable']]
>>> [None if w != w else round(float(w) / 1e3, 1) for w in result.critical_wob]
[87.5, None]
"""

from __future__ import annotations

import json
import math
import os
import uuid
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from torsio.analysis.severity import SEVERE_THRESHOLD
from torsio.analysis.sweep import (
    ExecutorSpec,
    SweepInterrupted,
    open_executor,
    run_tasks_on,
    worker_count,
)
from torsio.errors import ConfigError, SolverError
from torsio.physics.system import System
from torsio.solvers.batch import DEFAULT_ATOL, DEFAULT_RTOL, STATUS_MESSAGES, simulate_batch
from torsio.units import RPM_TO_RAD_S

__all__ = [
    "BYTES_PER_POINT",
    "CLASSES",
    "DEFAULT_REFINE",
    "FORMAT",
    "MapInterrupted",
    "STICK_SLIP_THRESHOLD",
    "SeverityMap",
    "check_grid_size",
    "dimensionless_map",
    "load_map",
    "severity_map",
]

STICK_SLIP_THRESHOLD = 0.05
"""S_SS above which a point is a sustained torsional oscillation ("stick-slip")."""

CLASSES = ("stable", "stick-slip", "severe")
"""Class names, in increasing severity (``"failed"`` marks a point the solver failed on)."""

DEFAULT_REFINE = 4
"""Bisection steps per critical-WOB cell: the bracket shrinks 16 times."""

FORMAT = "torsio-severity-map"
"""The ``format`` key of saved maps (version :data:`FORMAT_VERSION`)."""

FORMAT_VERSION = 1

BYTES_PER_POINT = 256
"""Memory a grid point costs, results and their JSON text included (an upper estimate)."""


class MapInterrupted(KeyboardInterrupt):
    """Ctrl-C during a map: ``partial`` is the map so far, with ``complete = False``."""

    def __init__(self, partial: SeverityMap) -> None:
        done = int(partial.done.sum())
        super().__init__(f"map interrupted: {done} of {partial.done.size} points computed")
        self.partial = partial


def _float_list(values: np.ndarray) -> list[Any]:
    return [None if not math.isfinite(float(v)) else float(v) for v in np.ravel(values)]


@attrs.frozen(eq=False)
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
        W_ob,cr per rpm [N]; NaN where none (see the module documentation).
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
        Solver status per point (0 ok; see :data:`torsio.solvers.batch.STATUS_MESSAGES`).
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
        labels[~self.done] = "missing"
        return labels.astype(str)

    def counts(self) -> dict[str, int]:
        """Number of points of each class."""
        labels = self.classification()
        names = (*CLASSES, "failed", "missing")
        return {
            name: int((labels == name).sum())
            for name in names
            if (labels == name).any() or name in CLASSES
        }

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
        return cls(
            wob=wob,
            rpm=rpm,
            severity=array("severity").reshape(rpm.size, wob.size),
            critical_wob=array("critical_wob"),
            critical_status=tuple(data["critical_status"]),
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
        )

    def save(self, path: str | Path) -> Path:
        """Write the map: JSON (``.json``, any other suffix) or numpy ``.npz``.

        JSON holds :meth:`to_dict`; ``.npz`` holds the same as arrays plus a
        ``metadata`` JSON string. The file is written to a temporary name and
        renamed, so an interrupted write never leaves a truncated file.
        An incomplete map is saved with ``"complete": false``.
        """
        path = Path(path)
        data = self.to_dict()
        directory = path.parent if str(path.parent) else Path(".")
        if not directory.is_dir():
            raise ConfigError("out", f"directory {str(directory)!r} does not exist")
        temporary = directory / f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp"
        try:
            with open(temporary, "xb") as stream:  # ordinary permissions (umask)
                if path.suffix == ".npz":
                    arrays: dict[str, Any] = {
                        key: np.array(
                            value,
                            dtype=float
                            if key
                            not in ("status", "steps", "done", "classification", "critical_status")
                            else None,
                        )
                        for key, value in data.items()
                        if key
                        in (
                            "wob",
                            "rpm",
                            "critical_wob",
                            "critical_pi2",
                            "stability_wob",
                            "status",
                            "steps",
                            "done",
                            "pi1",
                            "pi2",
                            "classification",
                            "critical_status",
                        )
                    }
                    arrays["severity"] = self.severity
                    arrays["critical_bracket"] = self.critical_bracket
                    meta = {k: v for k, v in data.items() if k not in arrays}
                    np.savez_compressed(stream, metadata=np.array(json.dumps(meta)), **arrays)
                else:
                    stream.write(json.dumps(data, indent=1).encode("utf-8"))
            os.replace(temporary, path)
        except BaseException:
            Path(temporary).unlink(missing_ok=True)
            raise
        return path

    def to_csv(self, path: str | Path) -> Path:
        """One row per grid point: rpm, wob [N], Pi_1, Pi_2, S_SS, class, solver status."""
        import csv

        path = Path(path)
        labels = self.classification()
        pi1, pi2 = self.pi1, self.pi2
        with path.open("w", newline="", encoding="utf-8") as stream:
            writer = csv.writer(stream)
            writer.writerow(["rpm", "wob_N", "pi1", "pi2", "severity", "class", "status"])
            for i in range(self.rpm.size):
                for j in range(self.wob.size):
                    s = self.severity[i, j]
                    writer.writerow(
                        [
                            repr(float(self.rpm[i])),
                            repr(float(self.wob[j])),
                            repr(float(pi1[i])),
                            repr(float(pi2[j])),
                            "" if not math.isfinite(s) else repr(float(s)),
                            labels[i, j],
                            int(self.status[i, j]),
                        ]
                    )
        return path

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
        matplotlib. Writes a PNG when ``path`` is given; returns the axes.
        """
        try:
            import matplotlib

            if path is not None and ax is None:
                matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            raise ConfigError(
                "plot", "plotting needs matplotlib: pip install 'torsio[plot]'"
            ) from None
        use_pi = self.dimensionless if dimensionless is None else dimensionless
        if use_pi:
            x, y = self.pi1, self.pi2
            crit, lin = self.critical_pi2, self.stability_pi2
            xlabel, ylabel = r"$\Pi_1 = \Omega/\omega_1$", r"$\Pi_2 = W_{ob} R_{bit}/k_{eq}$"
        else:
            x, y = self.rpm, self.wob / 1e3
            crit, lin = self.critical_wob / 1e3, self.stability_wob / 1e3
            xlabel, ylabel = "rotary speed [rpm]", "weight on bit [kN]"
        figure = None
        if ax is None:
            figure, ax = plt.subplots(figsize=(7.0, 5.0), constrained_layout=True)
        values = np.ma.masked_invalid(self.severity.T)
        mesh = ax.pcolormesh(
            x,
            y,
            values,
            shading="nearest",
            cmap="viridis",
            vmin=0.0,
            vmax=max(
                2.0, float(np.nanmax(self.severity)) if np.isfinite(self.severity).any() else 2.0
            ),
        )
        colorbar = ax.figure.colorbar(mesh, ax=ax)
        colorbar.set_label(r"$S_{SS}$")
        if np.isfinite(crit).any():
            ax.plot(
                x, crit, "w-o", ms=3, lw=2, label=f"critical WOB ($S_{{SS}}$ > {self.threshold:g})"
            )
        if np.isfinite(lin).any():
            ax.plot(x, lin, "r--", lw=1.5, label="linear stability boundary")
        ax.set_xlim(x.min() - 0.5 * _spacing(x), x.max() + 0.5 * _spacing(x))
        ax.set_ylim(y.min() - 0.5 * _spacing(y), y.max() + 0.5 * _spacing(y))
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        title = str(self.info.get("model", {}).get("name", "")) or "severity map"
        ax.set_title(title + ("" if self.complete else " (incomplete)"))
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper left", fontsize=8, framealpha=0.8)
        if path is not None:
            ax.figure.savefig(path, dpi=120)
            if figure is not None:
                plt.close(figure)
        return ax


def _spacing(values: np.ndarray) -> float:
    return (
        float(np.min(np.diff(values))) if values.size > 1 else max(abs(float(values[0])), 1.0) * 0.1
    )


def load_map(path: str | Path) -> SeverityMap:
    """Read a map written by :meth:`SeverityMap.save` (JSON or ``.npz``)."""
    path = Path(path)
    try:
        if path.suffix == ".npz":
            with np.load(path, allow_pickle=False) as archive:
                data = json.loads(str(archive["metadata"]))
                for key in archive.files:
                    if key != "metadata":
                        data[key] = archive[key].tolist()
        else:
            data = json.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ConfigError(
            "path", f"cannot read map file {str(path)!r}: {exc.strerror or exc}"
        ) from None
    except (ValueError, KeyError) as exc:
        raise ConfigError("path", f"{str(path)!r} is not a saved severity map ({exc})") from None
    return SeverityMap.from_dict(data)


# --- building a map ------------------------------------------------------------------------
def _axis(key: str, values: Any, positive: bool) -> np.ndarray:
    array = np.atleast_1d(np.asarray(values, dtype=float))
    if array.ndim != 1 or array.size == 0:
        raise ConfigError(
            key, f"expected a non-empty 1-D sequence of values, got shape {array.shape}"
        )
    bad = ~np.isfinite(array) | ((array <= 0) if positive else (array < 0))
    if bad.any():
        what = "positive" if positive else "non-negative"
        raise ConfigError(key, f"expected {what} finite values, got {array[bad][0]!r}")
    if array.size > 1 and not (np.diff(array) > 0).all():
        k = int(np.argmin(np.diff(array) > 0))
        raise ConfigError(
            key, f"expected strictly increasing values, got {array[k]!r} then {array[k + 1]!r}"
        )
    return array


def _available_memory() -> float | None:
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):  # pragma: no cover - not POSIX
        return None


def check_grid_size(rows: int, columns: int, memory: float | None = None) -> None:
    """ConfigError if a rows x columns grid's results would not fit in memory.

    Parameters
    ----------
    rows, columns : int
        Number of rotary speeds and of weights on bit.
    memory : float, optional
        Bytes available (default: free physical memory); the results may use half.
    """
    points = int(rows) * int(columns)
    needed = points * BYTES_PER_POINT
    memory = _available_memory() if memory is None else memory
    if memory is not None and needed > 0.5 * memory:
        raise ConfigError(
            "grid",
            f"a grid of {rows:,} rpm x {columns:,} wob = {points:,} "
            f"points needs about {_bytes(needed)} for its results; "
            f"{_bytes(memory)} of memory is available (split the map "
            f"or use fewer points)",
        )


def _bytes(value: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if value < 1000 or unit == "PB":
            return f"{value:.3g} {unit}"
        value /= 1000.0
    return f"{value:.3g} PB"  # pragma: no cover


def _chunk_task(
    system: System, wob: np.ndarray, rpm: np.ndarray, options: dict[str, Any]
) -> np.ndarray:
    """Worker side: S_SS and diagnostics of a chunk of points, shape (k, 4)."""
    result = simulate_batch(system, wob, rpm, **options)
    return np.column_stack([result.severity, result.status, result.steps, result.rejected])


def _scales(system: System) -> tuple[float, float]:
    from torsio.model.modal import modal_analysis
    from torsio.model.wave import is_wave_model

    if is_wave_model(system.model):
        from torsio.solvers.wave_batch import wave_scales

        return wave_scales(system.model)

    omega1 = float(modal_analysis(system.model, 1).frequencies_rad[0])
    return float(system.model.equivalent_stiffness), omega1


class _Runner:
    """Runs lists of points through the sweep, in chunks, with shared progress."""

    def __init__(
        self,
        system: System,
        handle: Any,
        options: dict[str, Any],
        chunk_size: int,
        retries: int,
        progress: Callable[[int, int], None] | None,
    ) -> None:
        self.system = system
        self.handle = handle
        self.options = options
        self.chunk_size = chunk_size
        self.retries = retries
        self.progress = progress
        self.done_points = 0
        self.total_points = 0
        self.retried = 0

    def run(
        self,
        wob: np.ndarray,
        rpm: np.ndarray,
        on_partial: Callable[[list[tuple[tuple[int, int], np.ndarray]]], None] | None = None,
    ) -> np.ndarray:
        """Rows (severity, status, steps, rejected) of the points (wob[k], rpm[k])."""
        count = wob.size
        size = self.chunk_size
        bounds = [(k, min(k + size, count)) for k in range(0, count, size)]
        tasks = [(self.system, wob[a:b], rpm[a:b], self.options) for a, b in bounds]
        base = self.done_points
        self.total_points += count
        progress = self.progress

        def report(done: int, total: int) -> None:
            if progress is not None:
                progress(
                    base + (count if done == total else min(done * size, count)), self.total_points
                )

        try:
            outcome = run_tasks_on(
                self.handle, _chunk_task, tasks, retries=self.retries, progress=report
            )
        except SweepInterrupted as exc:
            if on_partial is not None:
                on_partial([(bounds[k], r) for k, r in enumerate(exc.results) if r is not None])
            raise
        self.retried += outcome.retries
        self.done_points += count
        return np.concatenate(outcome.results) if outcome.results else np.empty((0, 4))


def _default_chunk_size(points: int, workers: int, serial: bool, dofs: int) -> int:
    largest = max(8, 4096 // max(1, dofs))  # about a second of work per chunk at most
    if serial:
        return max(1, min(points, 2 * largest))
    return max(1, min(largest, math.ceil(points / (4 * workers))))


def severity_map(
    system: System,
    wob: Any,
    rpm: Any,
    duration: float | None = None,
    steady_window: float | None = None,
    executor: ExecutorSpec = None,
    chunk_size: int | None = None,
    progress: bool | Callable[[int, int], None] | None = None,
    threshold: float = SEVERE_THRESHOLD,
    stick_slip_threshold: float = STICK_SLIP_THRESHOLD,
    refine: int = DEFAULT_REFINE,
    rtol: float = DEFAULT_RTOL,
    atol: float = DEFAULT_ATOL,
    engine: str = "auto",
    retries: int = 2,
    on_failure: str = "raise",
    timeout: float | None = None,
) -> SeverityMap:
    """S_SS over the grid ``rpm`` x ``wob``, its classification and critical curve.

    Parameters
    ----------
    system : System
        Model, damping and bit-rock law (its own operating point is ignored).
    wob : array_like
        Weights on bit [N], >= 0, strictly increasing.
    rpm : array_like
        Surface rotary speeds [rpm], > 0, strictly increasing.
    duration, steady_window : float, optional
        Run length and steady window [s] of every run (defaults: 40 and 15
        first-mode periods, :mod:`torsio.analysis.severity`). Every run starts from rest.
    executor : None, int, str or concurrent.futures.Executor
        Serial (default), N local processes, a Dask scheduler address, or an
        executor (:mod:`torsio.analysis.sweep`). The result does not depend on it.
    chunk_size : int, optional
        Grid points per task (default: about four tasks per worker, or one task
        serially, each at most 4096/DOFs points, 8192/DOFs serially).
    progress : bool or callable, optional
        ``progress(done_points, total_points)`` after each chunk; True shows a
        rich progress bar on stderr.
    threshold : float
        S_SS above which a point is severe (paper: 0.8).
    stick_slip_threshold : float
        S_SS above which a point is a sustained oscillation.
    refine : int
        Bisection steps of each critical-WOB cell (extra runs per rpm).
    rtol, atol : float
        Tolerances of the batch engine.
    engine : str
        Batch engine (:func:`torsio.solvers.batch.simulate_batch`).
    retries : int
        Resubmissions of a chunk whose worker died.
    on_failure : {"raise", "mark"}
        On points the solver failed on: raise :class:`~torsio.errors.SolverError`
        naming them, or keep them as NaN with their status (and warn).
    timeout : float, optional
        Seconds to wait for a Dask scheduler.

    Returns
    -------
    SeverityMap

    Raises
    ------
    MapInterrupted
        On Ctrl-C; its ``partial`` map has ``complete = False``.
    """
    wob_axis = _axis("wob", wob, positive=False)
    rpm_axis = _axis("rpm", rpm, positive=True)
    return _build_map(
        system,
        wob_axis,
        rpm_axis,
        duration,
        steady_window,
        executor,
        chunk_size,
        progress,
        threshold,
        stick_slip_threshold,
        refine,
        rtol,
        atol,
        engine,
        retries,
        on_failure,
        timeout,
        dimensionless=False,
    )


def dimensionless_map(system: System, pi1: Any, pi2: Any, **options: Any) -> SeverityMap:
    """S_SS over the grid Pi_1 x Pi_2 (Eq. 11) of ``system``.

    Pi_1 = Omega / omega_1 and Pi_2 = W_ob R_bit / k_eq (ERRATA 3) map linearly to
    rpm and weight on bit for a given System, so this is :func:`severity_map`
    on the corresponding grid (same options); ``severity[i][j]`` is at
    ``pi1[i]``, ``pi2[j]`` and the map's ``critical_pi2`` is the dimensionless
    critical curve.

    Examples
    --------
    >>> from torsio.physics.system import System, builtin_config
    >>> system = System.from_config(builtin_config(), strategy="A")
    >>> result = dimensionless_map(system, pi1=[5.0, 12.0], pi2=[10.0, 60.0], refine=0)
    >>> result.pi1.round(3).tolist(), result.pi2.round(3).tolist()
    ([5.0, 12.0], [10.0, 60.0])
    >>> result.classification().tolist()
    [['stable', 'severe'], ['stable', 'severe']]
    """
    pi1_axis = _axis("pi1", pi1, positive=True)
    pi2_axis = _axis("pi2", pi2, positive=False)
    k_eq, omega1 = _scales(system)
    rpm = pi1_axis * omega1 / RPM_TO_RAD_S
    wob = pi2_axis * k_eq / system.bit_radius
    keys = (
        "duration",
        "steady_window",
        "executor",
        "chunk_size",
        "progress",
        "threshold",
        "stick_slip_threshold",
        "refine",
        "rtol",
        "atol",
        "engine",
        "retries",
        "on_failure",
        "timeout",
    )
    unknown = sorted(set(options) - set(keys))
    if unknown:
        raise ConfigError(unknown[0], f"unknown option; expected one of {', '.join(keys)}")
    defaults: dict[str, Any] = {
        "duration": None,
        "steady_window": None,
        "executor": None,
        "chunk_size": None,
        "progress": None,
        "threshold": SEVERE_THRESHOLD,
        "stick_slip_threshold": STICK_SLIP_THRESHOLD,
        "refine": DEFAULT_REFINE,
        "rtol": DEFAULT_RTOL,
        "atol": DEFAULT_ATOL,
        "engine": "auto",
        "retries": 2,
        "on_failure": "raise",
        "timeout": None,
    }
    defaults.update(options)
    return _build_map(system, wob, rpm, dimensionless=True, **defaults)


def _rich_progress() -> tuple[Callable[[int, int], None], Callable[[], None]]:
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    bar = Progress(
        TextColumn("severity map"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("points"),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        transient=True,
        console=Console(stderr=True),
    )
    task = bar.add_task("map", total=None)
    bar.start()

    def update(done: int, total: int) -> None:
        bar.update(task, completed=done, total=total)

    return update, bar.stop


def _build_map(
    system: System,
    wob: np.ndarray,
    rpm: np.ndarray,
    duration: float | None,
    steady_window: float | None,
    executor: ExecutorSpec,
    chunk_size: int | None,
    progress: bool | Callable[[int, int], None] | None,
    threshold: float,
    stick_slip_threshold: float,
    refine: int,
    rtol: float,
    atol: float,
    engine: str,
    retries: int,
    on_failure: str,
    timeout: float | None,
    dimensionless: bool,
) -> SeverityMap:
    import time

    from torsio.analysis.stability import stability_boundary
    from torsio.analysis.sweep import CONNECT_TIMEOUT
    from torsio.solvers.reference import run_times

    for key, value in (("threshold", threshold), ("stick_slip_threshold", stick_slip_threshold)):
        if isinstance(value, bool) or not (
            isinstance(value, int | float) and math.isfinite(value) and value >= 0
        ):
            raise ConfigError(key, f"expected a non-negative number, got {value!r}")
    if stick_slip_threshold > threshold:
        raise ConfigError(
            "stick_slip_threshold",
            f"expected at most the severe threshold ({threshold:g}), got {stick_slip_threshold!r}",
        )
    if isinstance(refine, bool) or not isinstance(refine, int) or not 0 <= refine <= 40:
        raise ConfigError(
            "refine", f"expected a whole number of bisection steps in 0..40, got {refine!r}"
        )
    if on_failure not in ("raise", "mark"):
        raise ConfigError("on_failure", f"expected 'raise' or 'mark', got {on_failure!r}")
    if chunk_size is not None and (
        isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 1
    ):
        raise ConfigError("chunk_size", f"expected a whole number >= 1, got {chunk_size!r}")
    check_grid_size(rpm.size, wob.size)
    duration, steady_window = run_times(system, duration, steady_window)
    k_eq, omega1 = _scales(system)
    serial = executor is None or executor == "serial"
    options: dict[str, Any] = {
        "duration": duration,
        "steady_window": steady_window,
        "rtol": rtol,
        "atol": atol,
        "engine": engine,
        "threads": None if serial else 1,
    }
    boundary = system.top.boundary(system)
    if not boundary.held and not math.isfinite(boundary.set_speed):
        raise ConfigError(
            "rpm",
            f"a map runs over rotary (set) speeds, and the top drive "
            f"{getattr(system.top, 'name', system.top)!r} has none (its speed follows from "
            "the torque balance); map with a speed-controlled top drive or run "
            "torsio.solvers.batch.simulate_batch(system, wob) over weights on bit",
        )
    # validate options (engine, tolerances) here rather than in every worker
    engine_name = simulate_batch(system, np.empty(0), np.empty(0), **options).engine
    points = rpm.size * wob.size
    size = chunk_size or _default_chunk_size(
        points, worker_count(executor), serial, system.model.dofs
    )

    stop: Callable[[], None] | None = None
    callback: Callable[[int, int], None] | None
    if progress is True:
        callback, stop = _rich_progress()
    elif callable(progress):
        callback = progress
    else:
        callback = None

    severity = np.full((rpm.size, wob.size), np.nan)
    status = np.zeros((rpm.size, wob.size), dtype=np.int64)
    steps = np.zeros((rpm.size, wob.size), dtype=np.int64)
    done = np.zeros((rpm.size, wob.size), dtype=bool)
    grid_rpm, grid_wob = np.meshgrid(rpm, wob, indexing="ij")
    flat_wob = grid_wob.ravel()
    flat_rpm = grid_rpm.ravel()
    start = time.perf_counter()
    info: dict[str, Any] = {
        "model": {
            "name": getattr(system.string, "name", "") or "",
            "strategy": system.model.strategy,
            "dofs": system.model.dofs,
        },
        "law": repr(system.law),
        "damping": repr(system.damping),
        "duration": duration,
        "steady_window": steady_window,
        "rtol": rtol,
        "atol": atol,
        "refine": refine,
        "initial_state": "rest",
    }

    def store(rows: np.ndarray, at: np.ndarray) -> None:
        i, j = np.unravel_index(at, severity.shape)
        severity[i, j] = rows[:, 0]
        status[i, j] = rows[:, 1].astype(np.int64)
        steps[i, j] = rows[:, 2].astype(np.int64)
        done[i, j] = True

    def partial_map() -> SeverityMap:
        nan_rows = np.full(rpm.size, np.nan)
        return SeverityMap(
            wob,
            rpm,
            severity.copy(),
            nan_rows,
            ("unresolved",) * rpm.size,
            np.full((rpm.size, 2), np.nan),
            nan_rows.copy(),
            float(threshold),
            float(stick_slip_threshold),
            k_eq,
            omega1,
            system.bit_radius,
            status.copy(),
            steps.copy(),
            done.copy(),
            complete=False,
            dimensionless=dimensionless,
            info={**info, "elapsed_s": time.perf_counter() - start},
            engine=engine_name,
        )

    try:
        with open_executor(executor, CONNECT_TIMEOUT if timeout is None else timeout) as handle:
            info["executor"] = handle.name
            runner = _Runner(system, handle, options, size, retries, callback)
            indices = np.arange(points)

            def keep_partial(chunks: list[Any]) -> None:
                for (a, b), rows in chunks:
                    store(rows, indices[a:b])

            try:
                rows = runner.run(flat_wob, flat_rpm, keep_partial)
            except SweepInterrupted:
                raise MapInterrupted(partial_map()) from None
            store(rows, indices)
            failed = done & (status != 0)
            if failed.any() and on_failure == "raise":
                lines = _failure_lines(wob, rpm, status)
                raise SolverError(
                    f"the batch solver failed at {len(lines)} of {points} points: "
                    + "; ".join(lines[:5])
                    + (" ..." if len(lines) > 5 else "")
                    + " (on_failure='mark' keeps the others)"
                )
            try:
                critical, crit_status, bracket = _critical_wob(
                    runner, wob, rpm, severity, threshold, refine, on_failure
                )
            except SweepInterrupted:
                raise MapInterrupted(partial_map()) from None
            info["retried_chunks"] = runner.retried
    finally:
        if stop is not None:
            stop()
    if failed.any():
        warnings.warn(
            f"the batch solver failed at {int(failed.sum())} points; they are NaN in the map",
            RuntimeWarning,
            stacklevel=3,
        )
    info["elapsed_s"] = time.perf_counter() - start
    info["extra_runs"] = runner.done_points - points
    from torsio.model.wave import is_wave_model

    if is_wave_model(system.model):  # no linearization of the distributed model (yet)
        linear_wob = np.full(rpm.shape, np.nan)
    else:
        linear_wob = stability_boundary(system, rpm).critical_wob
    return SeverityMap(
        wob,
        rpm,
        severity,
        critical,
        crit_status,
        bracket,
        linear_wob,
        float(threshold),
        float(stick_slip_threshold),
        k_eq,
        omega1,
        system.bit_radius,
        status,
        steps,
        done,
        complete=True,
        dimensionless=dimensionless,
        info=info,
        engine=engine_name,
    )


def _failure_lines(wob: np.ndarray, rpm: np.ndarray, status: np.ndarray) -> list[str]:
    return [
        f"wob={wob[j]:g} N, rpm={rpm[i]:g}: "
        f"{STATUS_MESSAGES.get(int(status[i, j]), f'status {status[i, j]}')}"
        for i, j in zip(*np.nonzero(status), strict=True)
    ]


def _critical_wob(
    runner: _Runner,
    wob: np.ndarray,
    rpm: np.ndarray,
    severity: np.ndarray,
    threshold: float,
    refine: int,
    on_failure: str,
) -> tuple[np.ndarray, tuple[str, ...], np.ndarray]:
    rows = severity.shape[0]
    critical = np.full(rows, np.nan)
    bracket = np.full((rows, 2), np.nan)
    labels: list[str] = []
    low = np.full(rows, np.nan)
    high = np.full(rows, np.nan)
    for i in range(rows):
        s = severity[i]
        if not np.isfinite(s).all():
            labels.append("unresolved")
            continue
        severe = s > threshold
        if not severe[-1]:
            labels.append("none")
            continue
        tail = np.flatnonzero(~severe)
        first = 0 if tail.size == 0 else int(tail[-1]) + 1
        if first == 0:
            labels.append("below_range")
            critical[i] = wob[0]
            continue
        low[i], high[i] = wob[first - 1], wob[first]
        labels.append("bisected" if refine else "grid")
    active = np.flatnonzero(np.isfinite(low))
    for _ in range(refine):
        if active.size == 0:
            break
        middle = 0.5 * (low[active] + high[active])
        speeds = rpm[active]
        result = runner.run(middle, speeds)
        values = result[:, 0]
        failed = result[:, 1] != 0
        if failed.any() and on_failure == "raise":
            k = int(np.argmax(failed))
            raise SolverError(
                f"the batch solver failed at wob={middle[k]:g} N, "
                f"rpm={speeds[k]:g} while bisecting the critical weight on bit: "
                f"{STATUS_MESSAGES.get(int(result[k, 1]))}"
            )
        is_severe = values > threshold
        high[active] = np.where(is_severe, middle, high[active])
        low[active] = np.where(is_severe, low[active], middle)
        for index in np.flatnonzero(failed):
            labels[active[index]] = "unresolved"
            low[active[index]] = np.nan
        active = active[~failed]
    for i in range(rows):
        if math.isfinite(low[i]):
            bracket[i] = (low[i], high[i])
            critical[i] = 0.5 * (low[i] + high[i])
    return critical, tuple(labels), bracket
