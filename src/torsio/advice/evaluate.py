"""The one place the advisor runs the model: :func:`evaluate` at a list of (WOB, rpm) points.

Everything else in :mod:`torsio.advice` sees the model only through :func:`evaluate` and
the named arrays it returns (:class:`Evaluation`): S_SS, mean ROP [m/s], mean MSE [Pa] and
the mean surface (top-drive) torque [N m] over each run's steady window.

Each point is one :func:`torsio.analysis.axial_transient.simulate_axial` run of the case
(:class:`AxialCase`: the assembly, the RGD bit and the run options of the configuration,
its top drive and friction possibly changed), the same run
:func:`torsio.analysis.axial_maps.axial_map`
makes at a grid point. The axial map keeps no signals, and the surface torque is a signal:
here each run keeps :data:`SURFACE_SAMPLES` rows of signals and the surface torque is the
mean of the ``surface_torque`` column over the window's rows
(:meth:`~torsio.analysis.axial_results.AxialChannels.top_drive_summary`).

Ctrl-C raises :class:`PointsInterrupted` with the rows of the points that finished.

Where the points run, as the maps (:mod:`torsio.analysis.sweep`): ``executor=None`` in this
process on ``threads`` threads (the compiled loop releases the GIL), else N local
processes, a Dask scheduler's address or any :class:`concurrent.futures.Executor`, in
chunks of points.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.analysis.axial_results import channels_of
from torsio.analysis.axial_transient import simulate_axial
from torsio.analysis.severity import run_times
from torsio.errors import ConfigError

__all__ = [
    "COLUMNS",
    "SURFACE_SAMPLES",
    "AxialCase",
    "Evaluation",
    "PointsInterrupted",
    "case_with",
    "evaluate",
]

SURFACE_SAMPLES = 1500
"""Rows of signals a run keeps for its mean surface torque (about 550 in the window of the
default run: 15 of its 40 periods)."""

COLUMNS = ("severity", "rop", "mse", "surface_torque", "surface_torque_max")
"""What :func:`evaluate` gives at each point: S_SS, mean ROP [m/s], mean MSE [Pa] (inf where
the bit did not advance), the mean and the largest surface torque over the window [N m]."""


@attrs.frozen(eq=False)
class AxialCase:
    """One model to advise on: an axial assembly, its bit and the run options of
    :func:`~torsio.analysis.axial_transient.simulate_axial` (top drive, contacts, start, step,
    ``duration`` and ``window`` resolved). Module-level and frozen: it pickles to workers.

    ``label`` names the case in tables (e.g. the top drive)."""

    assembly: Any
    bit: Any
    options: Mapping[str, Any]
    label: str = "configured"

    def __call__(self, wob: float, rpm: float) -> list[float]:
        """The :data:`COLUMNS` of one run at ``wob`` [N] and ``rpm`` [rev/min]."""
        run = channels_of(
            simulate_axial(
                self.assembly,
                self.bit,
                wob,
                rpm,
                samples=SURFACE_SAMPLES,
                growth_rate=False,
                **self.options,
            )
        )
        top = run.top_drive_summary()
        return [
            float(run.severity),
            float(run.rop_mean),
            float(run.mse_mean),
            float(top["mean_surface_torque"] or math.nan),
            float(top["surface_torque_max"] or math.nan),
        ]

    @classmethod
    def from_config(
        cls, config: Any, duration: float | None = None, window: float | None = None
    ) -> AxialCase:
        """The case of a configuration with axial dynamics (``[bit_rock] law = "rgd"`` or
        ``[chain] masses``); a torsional-only one is refused by key."""
        axial = getattr(config, "axial", None)
        if axial is None:
            raise ConfigError(
                "bit_rock.law",
                "the advisor needs the rate of penetration of the axial engine: a "
                "configuration with axial dynamics (law = 'rgd', or [chain] masses); this one "
                "is torsional only",
            )
        if not axial.bit.needs_axial:
            raise ConfigError(
                "bit_rock.law",
                f"the {axial.bit.name} law is a law of the torque alone: its bit rests on the "
                "rock and has no rate of penetration to advise on (law = 'rgd')",
            )
        if config.top_drive.speed_follows is not None:
            raise ConfigError(
                "top_drive.kind",
                f"{config.top_drive.kind!r}: {config.top_drive.speed_follows}; the advisor "
                "sets the rotary speed of every point (a top drive with a set speed: "
                "constant-speed, pi, soft-torque, z-torque)",
            )
        options = dict(axial.run_options())
        simulation = config.simulation.options
        duration = duration or simulation.get("duration")
        window = window or simulation.get("steady_window")
        options["duration"], options["window"] = run_times(axial.assembly, duration, window)
        label = f"{config.top_drive.kind} (configured)"
        return cls(axial.assembly, axial.bit, options, label)


def case_with(
    case: AxialCase,
    *,
    top_drive: Any = attrs.NOTHING,
    label: str | None = None,
    contacts: Any = None,
    bit: Any = None,
) -> AxialCase:
    """``case`` with another top drive, contacts along the string or bit (None: kept)."""
    options = dict(case.options)
    if top_drive is not attrs.NOTHING:
        options["top_drive"] = top_drive
    if contacts is not None:
        options["contacts"] = contacts
    return AxialCase(case.assembly, bit or case.bit, options, label or case.label)


@attrs.frozen(eq=False)
class Evaluation:
    """The model at paired points: every array has one entry per (``wob[k]``, ``rpm[k]``).

    Attributes: ``wob`` [N], ``rpm`` [rev/min] and the :data:`COLUMNS`."""

    wob: NDArray[np.float64]
    rpm: NDArray[np.float64]
    severity: NDArray[np.float64]
    rop: NDArray[np.float64]
    mse: NDArray[np.float64]
    surface_torque: NDArray[np.float64]
    surface_torque_max: NDArray[np.float64]


class PointsInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`evaluate`: ``finished`` holds the rows of the points that ran,
    by their index."""

    def __init__(self, finished: dict[int, list[float]]) -> None:
        super().__init__(f"interrupted after {len(finished)} points")
        self.finished = finished


Point = tuple[AxialCase, float, float]
"""One run: the case, the weight on bit [N] and the rotary speed [rev/min]."""


def _run_chunk(points: Sequence[Point]) -> list[list[float]]:
    """A task on an executor: the points, one after the other."""
    return [case(wob, rpm) for case, wob, rpm in points]


def _rows_here(
    points: list[Point], threads: int, progress: Callable[[int], None] | None
) -> list[list[float]]:
    rows: list[list[float]] = [[] for _ in points]
    lock = threading.Lock()

    def one(k: int) -> None:
        case, wob, rpm = points[k]
        rows[k] = case(wob, rpm)
        if progress is not None:
            with lock:
                progress(1)

    try:
        if threads <= 1 or len(points) == 1:
            for k in range(len(points)):
                one(k)
        else:  # the compiled loop releases the GIL: points run side by side
            with ThreadPoolExecutor(max_workers=min(threads, len(points))) as pool:
                list(pool.map(one, range(len(points))))
    except KeyboardInterrupt:
        raise PointsInterrupted({k: row for k, row in enumerate(rows) if row}) from None
    return rows


def _rows_on(
    points: list[Point], executor: Any, progress: Callable[[int], None] | None
) -> list[list[float]]:
    from torsio.analysis.sweep import run_tasks, worker_count

    size = max(1, math.ceil(len(points) / (2 * worker_count(executor))))
    tasks = [(points[k : k + size],) for k in range(0, len(points), size)]
    done = [0]

    def report(finished: int, total: int) -> None:
        if progress is not None:
            now = min(finished * size, len(points))
            progress(now - done[0])
            done[0] = now

    from torsio.analysis.sweep import SweepInterrupted

    try:
        outcome = run_tasks(_run_chunk, tasks, executor, progress=report)
    except SweepInterrupted as exc:
        finished = {}
        for task, chunk in enumerate(exc.results):
            for k, row in enumerate(chunk or ()):
                finished[task * size + k] = row
        raise PointsInterrupted(finished) from None
    return [row for chunk in outcome.results for row in chunk]


def evaluate(
    case: AxialCase | Sequence[AxialCase],
    wob: Sequence[float],
    rpm: Sequence[float],
    *,
    threads: int = 1,
    executor: Any = None,
    progress: Callable[[int], None] | None = None,
) -> Evaluation:
    """The model of ``case`` at the points (``wob[k]`` [N], ``rpm[k]`` [rev/min]); a
    sequence of cases gives each point its own (a Monte Carlo sample's).

    ``threads`` side by side in this process (``executor`` None), else on ``executor``
    (:data:`torsio.analysis.sweep.ExecutorSpec`); ``progress(n)`` after every n points."""
    wobs = np.asarray(wob, dtype=float).reshape(-1)
    rpms = np.asarray(rpm, dtype=float).reshape(-1)
    if wobs.shape != rpms.shape:
        raise ConfigError("wob", f"{wobs.size} weights on bit for {rpms.size} rotary speeds")
    cases = [case] * wobs.size if isinstance(case, AxialCase) else list(case)
    if len(cases) != wobs.size:
        raise ConfigError("case", f"{len(cases)} cases for {wobs.size} points")
    points = [(c, float(w), float(r)) for c, w, r in zip(cases, wobs, rpms, strict=True)]
    if not points:
        rows = np.zeros((0, len(COLUMNS)))
    elif executor is None or executor == "serial":
        rows = np.array(_rows_here(points, threads, progress), dtype=float)
    else:
        rows = np.array(_rows_on(points, executor, progress), dtype=float)
    named = {name: rows[:, k] for k, name in enumerate(COLUMNS)}
    return Evaluation(wob=wobs, rpm=rpms, **named)
