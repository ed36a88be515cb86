"""Fit friction and damping of a configuration to rig recordings (docs/calibration.md).

:func:`fit_recordings` runs the wave model of the configuration against each recording,
its top held at the recorded speed (``top="recorded"``, the default: the fit then does
not rest on a model of the rig's controller) or driven by the configured top drive
(``top="configured"``), and changes the named parameters
(:mod:`torsio.calibration.parameters`) by least squares (scipy.optimize.least_squares,
trust-region reflective with finite differences), starting from the closed forms
(:mod:`torsio.calibration.start`).

Uncertainty (:mod:`torsio.calibration.uncertainty`): one standard deviation from the
Jacobian, s^2 (J^T J)^-1 with s^2 the residual variance inflated by the residual's
correlation time; and a profile of the misfit along each parameter (the others following
their conditional best values), which gives the interval the data allow where the misfit
is not smooth (the break-free moment) and reveals a parameter the data do not pin down.

Examples
--------
>>> from torsio.examples import deviated_well_config
>>> from torsio.calibration.recording import Recording
>>> fit_recordings(deviated_well_config(), [], ["friction_dynamic"])
Traceback (most recent call last):
...
torsio.errors.ConfigError: recording: no recording to fit; give at least one
"""

from __future__ import annotations

import time as clock
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from scipy.optimize import least_squares

from torsio.calibration.fit_results import FitResults, RecordingFit
from torsio.calibration.objectives import OBJECTIVES, model_torque, residuals
from torsio.calibration.parameters import SystemFamily
from torsio.calibration.recording import RPM, Recording, read_recording
from torsio.calibration.search import NON_SMOOTH, line_search
from torsio.calibration.start import closed_form_start, corrected_start
from torsio.calibration.uncertainty import jacobian_correlation, parameter_uncertainty
from torsio.errors import ConfigError
from torsio.physics.recorded_top import RecordedTopDrive

__all__ = ["TOPS", "fit_recordings"]

START_STEPS = 1
"""Newton steps of the closed forms on the model's own torques before the least squares."""

SPEED_SMOOTHING = 0.0
"""Default window [s] of the recorded speed's smoothing (see :func:`fit_recordings`)."""

TOPS = ("recorded", "configured")
"""What drives the top in the fit: the recorded speed, or the configured top drive."""

DIFF_STEP = 5e-3
"""Relative step of the finite-difference Jacobian (a step wider than the misfit's
fine structure at the break-free moment)."""


class _Misfit:
    """Residuals of a parameter vector over every recording, counting the runs."""

    def __init__(
        self,
        family: Any,
        recordings: Sequence[Recording],
        names: Sequence[str],
        tops: Sequence[Any],
        rpms: Sequence[float],
        wob: float,
        objective: str,
    ) -> None:
        self.family, self.recordings, self.names = family, recordings, tuple(names)
        self.tops, self.rpms, self.wob, self.objective = tops, rpms, wob, objective
        self.runs = 0

    def models(self, x: np.ndarray) -> list[np.ndarray]:
        system = self.family.system(dict(zip(self.names, map(float, x), strict=True)))
        torques = []
        for record, top, rpm in zip(self.recordings, self.tops, self.rpms, strict=True):
            torque, _ = model_torque(system.with_top(top).at(wob=self.wob, rpm=rpm), record)
            torques.append(torque)
        self.runs += len(self.recordings)
        return torques

    def split(self, x: np.ndarray) -> list[np.ndarray]:
        return [
            residuals(self.objective, torque, record)
            for torque, record in zip(self.models(x), self.recordings, strict=True)
        ]

    def __call__(self, x: np.ndarray) -> np.ndarray:
        return np.concatenate(self.split(x))


def _lower_bound(family: SystemFamily, name: str, names: Sequence[str]) -> float:
    """The least value a fit tries: a static factor not below a held sliding one."""
    dynamic = name.replace("friction_static", "friction_dynamic")
    if dynamic != name and dynamic not in names:
        return float(family.values[dynamic])
    return family.lower_bound(name)


def _search_non_smooth(misfit: _Misfit, x: np.ndarray, lower: np.ndarray) -> np.ndarray:
    """Each non-smooth parameter searched alone over [start / 2, 2 start] (a static factor
    not below the sliding one of its stretch), the others held."""
    x = x.copy()
    for k, name in enumerate(misfit.names):
        if name.split(".")[-1] not in NON_SMOOTH:
            continue
        floor = lower[k]
        dynamic = name.replace("friction_static", "friction_dynamic")
        if dynamic != name:
            floor = max(floor, misfit.family.values[dynamic])
            if dynamic in misfit.names:
                floor = max(floor, x[misfit.names.index(dynamic)])

        def cost(value: float, k: int = k) -> float:
            trial = x.copy()
            trial[k] = value
            return float(np.sum(misfit(trial) ** 2))

        bracket = (max(0.5 * x[k], floor), max(2.0 * x[k], 2.0 * floor))
        x[k], _ = line_search(cost, float(min(max(x[k], bracket[0]), bracket[1])), bracket)
    return x


def _recordings(recordings: Sequence[Any], said: list[str]) -> list[Recording]:
    """The recordings read, each spike of their torque replaced by the record linear
    between its neighbours (a spike would otherwise drive the fit: the closed-form start
    reads the peak, and one sample far off outweighs thousands); ``said`` gets a warning
    per recording with spikes."""
    if not recordings:
        raise ConfigError("recording", "no recording to fit; give at least one")
    records = [r if isinstance(r, Recording) else read_recording(Path(r)) for r in recordings]
    cleaned = []
    for record in records:
        spikes = record.spikes()
        if spikes.size:
            at = ", ".join(f"{t:g}" for t in record.time[spikes[:3]])
            said.append(
                f"{record.name}: {spikes.size} surface-torque spike"
                f"{'s' if spikes.size > 1 else ''} (at {at}{' ...' if spikes.size > 3 else ''}"
                " s) left out of the fit: each replaced by the record linear between its "
                "neighbours"
            )
            record = record.without_spikes()
        cleaned.append(record)
    return cleaned


def _tops(config: Any, recordings: Sequence[Recording], top: str, smoothing: float) -> list[Any]:
    if top == "recorded":
        return [RecordedTopDrive(recording=r, smoothing=smoothing) for r in recordings]
    if top == "configured":
        return [config.top_drive.build()] * len(recordings)
    raise ConfigError("top", f"unknown top {top!r}; expected one of {', '.join(TOPS)}")


def _pairs(names: Sequence[str]) -> list[tuple[int, int]]:
    """(static, sliding) indices of the factors of a stretch fitted together."""
    pairs = []
    for k, name in enumerate(names):
        dynamic = name.replace("friction_static", "friction_dynamic")
        if dynamic != name and dynamic in names:
            pairs.append((k, list(names).index(dynamic)))
    return pairs


def _gaps(pairs: list[tuple[int, int]], size: int) -> np.ndarray:
    """The matrix A of y = A x: each fitted static factor replaced by its excess over the
    sliding one, mu_s - mu_d >= 0, so that a box bound keeps the fit in the admissible
    set mu_d <= mu_s (the one a configuration accepts)."""
    matrix = np.eye(size)
    for static, dynamic in pairs:
        matrix[static, dynamic] = -1.0
    return matrix


def _not_at_rest(
    family: SystemFamily, records: Sequence[Recording], names: Sequence[str], said: list[str]
) -> None:
    """A record whose first top speed is above the threshold speed starts with the string
    sliding: it holds no break-over and cannot inform a static factor. Refused when no
    record starts at rest and a static factor is fitted; said otherwise."""
    threshold = float(family.values["threshold_speed"])
    moving = [r for r in records if abs(float(r.top_speed[0])) > threshold]
    static = [n for n in names if n.split(".")[-1] == "friction_static"]
    why = ", ".join(f"{r.name} starts at {float(r.top_speed[0]) / RPM:.4g} rpm" for r in moving)
    where = (
        f"above the threshold speed {threshold / RPM:.3g} rpm: the string is already "
        "sliding and no break-over is recorded"
    )
    if static and len(moving) == len(records):
        raise ConfigError(
            "fit",
            f"{', '.join(static)} cannot be fitted from these recordings: none starts from "
            f"rest ({why}, {where}); fit the sliding factors alone, or give a start-up",
        )
    if moving:
        said.append(
            f"{why}, {where}; the model starts from rest at the first sample, so the "
            "start of the record is a transient the rig did not have"
            + (f"; only the other recordings inform {', '.join(static)}" if static else "")
        )


MIN_SAMPLES = 11
"""The fewest samples of a recording a fit takes (the spike check's window)."""

MIN_STEPS = 100
"""The shortest recording a fit takes, in time steps of the model's grid: its steady window
(a tenth of the run) must hold 10 of them."""


def check_wob(value: Any, key: str) -> float:
    """The weight on bit [N] of a fit, a finite number >= 0 (else an error on ``key``)."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not value >= 0.0:
        raise ConfigError(key, f"expected a weight on bit >= 0 (0: off bottom), got {value!r}")
    if not np.isfinite(value):
        raise ConfigError(key, f"expected a finite weight on bit, got {value!r}")
    return float(value)


def _check_records(family: SystemFamily, records: Sequence[Recording]) -> None:
    """Each record long enough for the model's grid, and turning (errors name it)."""
    shortest = MIN_STEPS * float(family.base.model.time_step)
    threshold = float(family.values["threshold_speed"])
    for record in records:
        if record.time.size < MIN_SAMPLES or record.duration < shortest:
            raise ConfigError(
                "recording",
                f"{record.name}: {record.time.size} samples over {record.duration:g} s; a fit "
                f"needs at least {MIN_SAMPLES} samples over {shortest:.3g} s ({MIN_STEPS} "
                "time steps of the model's grid)",
            )
        if float(np.max(np.abs(record.top_speed))) <= threshold:
            raise ConfigError(
                "recording",
                f"{record.name}: the top-drive speed never exceeds the threshold speed "
                f"({threshold / RPM:.3g} rpm): the string does not turn, there is no friction "
                "torque to fit",
            )


def _final_rpm(record: Recording, top: str) -> float:
    """The set speed a run against ``record`` is labelled with [rpm]: the mean over its last
    tenth (with the recorded top, its largest speed if that mean is not above 0)."""
    tail = record.time >= record.time[-1] - 0.1 * record.duration
    final = float(np.mean(record.top_speed[tail]) / RPM)
    if final > 0.0:
        return final
    if top == "recorded":
        return float(np.max(record.top_speed) / RPM)
    raise ConfigError(
        "rpm",
        f"{record.name} ends at {final:.4g} rpm (the mean over its last tenth): the configured "
        "top drive needs a set speed > 0; give rpm per recording, or use the recorded top",
    )


def fit_recordings(
    config: Any,
    recordings: Sequence[Recording | str | Path],
    names: Sequence[str],
    *,
    top: str = "recorded",
    objective: str = "torque",
    wob: float = 0.0,
    rpm: Sequence[float] | None = None,
    profile: bool = True,
    speed_smoothing: float = SPEED_SMOOTHING,
    **discretization: Any,
) -> FitResults:
    """Fit the parameters ``names`` of ``config`` to the surface torque of ``recordings``.

    Parameters
    ----------
    config : Config
        With a ``[[section]]`` string and a ``[well]``; run on the wave model.
    recordings : sequence of Recording or path
        Each a start-up from rest (the model starts every run from rest at the record's
        first sample).
    names : sequence of str, or str
        Fittable configuration keys (:mod:`torsio.calibration.parameters`); one key alone
        may be given as a string.
    top : {"recorded", "configured"}
        The top held at the recorded speed (default), or the configured top drive.
    objective : {"torque", "features"}
        Every sample, or the sliding and break-over torques (:mod:`.objectives`).
    wob : float
        Weight on bit [N]; 0 (default): off bottom, no bit-rock torque.
    rpm : sequence of float, optional
        Set speed of the configured top drive per recording [rpm]; default the mean
        recorded speed over the last tenth of each record.
    profile : bool
        Profile the misfit along each parameter (the interval the data allow).
    speed_smoothing : float
        Window [s] the recorded speed is smoothed over before it drives the top
        (``top="recorded"``; :class:`~torsio.physics.recorded_top.RecordedTopDrive`).
    **discretization
        Options of the wave grid.

    Returns
    -------
    FitResults
    """
    started = clock.perf_counter()
    names = (names,) if isinstance(names, str) else names  # one name, not its letters
    said: list[str] = []
    records = _recordings(recordings, said)
    if objective not in OBJECTIVES:
        raise ConfigError(
            "objective", f"unknown objective {objective!r}; expected one of {', '.join(OBJECTIVES)}"
        )
    family = SystemFamily(config, **discretization)
    names = family.check(names)
    if not (isinstance(speed_smoothing, int | float) and speed_smoothing >= 0.0):
        raise ConfigError(
            "speed_smoothing", f"expected a window >= 0 in s, got {speed_smoothing!r}"
        )
    tops = _tops(config, records, top, speed_smoothing)
    _check_records(family, records)
    wob = check_wob(wob, "wob")
    rpms = list(rpm) if rpm is not None else [_final_rpm(r, top) for r in records]
    if len(rpms) != len(records):
        raise ConfigError("rpm", f"expected one set speed per recording ({len(records)})")
    _not_at_rest(family, records, names, said)
    misfit = _Misfit(family, records, names, tops, rpms, wob, objective)
    start = closed_form_start(family, records, names)
    for _ in range(START_STEPS):
        models = misfit.models(np.array([start[n] for n in names]))
        start = corrected_start(family, records, models, start)
    lower = np.array([_lower_bound(family, n, names) for n in names])
    x0 = np.maximum(np.array([start[n] for n in names]), lower + 1e-6)
    x0 = _search_non_smooth(misfit, x0, lower)
    pairs = _pairs(names)
    gaps = _gaps(pairs, len(names))
    lower_gaps = lower.copy()
    lower_gaps[[static for static, _ in pairs]] = 0.0
    y0 = np.maximum(gaps @ x0, lower_gaps)
    solution = least_squares(
        lambda y: misfit(np.linalg.solve(gaps, y)),
        y0,
        bounds=(lower_gaps, np.inf),
        x_scale=np.where(np.abs(y0) > 0.0, np.abs(y0), np.abs(x0)),
        diff_step=DIFF_STEP,
        method="trf",
        xtol=1e-8,
        ftol=1e-10,
        gtol=1e-10,
        max_nfev=60,
    )
    best = np.linalg.solve(gaps, solution.x)
    jacobian = solution.jac @ gaps  # d r / d x = d r / d y  d y / d x
    for static, dynamic in pairs:  # the profile stays in the admissible set too
        lower[static] = max(lower[static], best[dynamic])
    parts = misfit.split(best)
    spread = parameter_uncertainty(misfit, best, jacobian, parts, lower=lower, profile=profile)
    models = misfit.models(best)
    fits = tuple(
        RecordingFit(
            name=r.name,
            time=r.time,
            surface_torque=r.surface_torque,
            model_torque=m,
            residual=float(np.sqrt(np.mean((m - r.surface_torque) ** 2))),
        )
        for r, m in zip(records, models, strict=True)
    )
    allsamples = np.concatenate([f.model_torque - f.surface_torque for f in fits])
    return FitResults(
        names=names,
        values=tuple(float(v) for v in best),
        start=tuple(float(start[n]) for n in names),
        configured=tuple(float(family.values[n]) for n in names),
        uncertainty=spread,
        correlation=jacobian_correlation(jacobian),
        residual=float(np.sqrt(np.mean(allsamples**2))),
        recordings=fits,
        objective=objective,
        top=top,
        runs=misfit.runs,
        seconds=clock.perf_counter() - started,
        message=str(solution.message),
        warnings=tuple(said),
    )
