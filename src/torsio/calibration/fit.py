"""Fit friction and damping of a configuration to rig recordings (docs/calibration.md).

:func:`fit_recordings` runs the wave model of the configuration against each recording,
its top held at the recorded speed (``top="recorded"``, the default: the fit then does
not rest on a model of the rig's controller) or driven by the configured top drive
(``top="configured"``), and changes the named parameters
(:mod:`torsio.calibration.parameters`) in two stages: a global one over the admissible
box (:mod:`torsio.calibration.global_stage`: the closed forms of
:mod:`torsio.calibration.start`, the configured values and a scan of each non-smooth
parameter as candidate starts), then a local one from the best of them
(:mod:`torsio.calibration.local_stage`: a line search of each non-smooth parameter, then
least squares).

Uncertainty (:mod:`torsio.calibration.uncertainty`): the statistical part from the
Jacobian and a profile of the misfit along each parameter (the residual variance inflated
by its correlation time), the model-form part from the spread between the recordings'
own values, and the discretization part from a finer grid's torque
(:mod:`torsio.calibration.profile`).

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
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from torsio.calibration.fit_results import Alternative, FitResults, RecordingFit
from torsio.calibration.global_stage import global_fit
from torsio.calibration.local_stage import admissible_floor
from torsio.calibration.objectives import OBJECTIVES, Misfit
from torsio.calibration.parameters import TWIN_GRIDS, SystemFamily
from torsio.calibration.profile import grid_twin, reader_twin
from torsio.calibration.recording import RPM, Recording, read_recording
from torsio.calibration.start import closed_form_start, corrected_start
from torsio.calibration.uncertainty import (
    jacobian_correlation,
    parameter_uncertainty,
    residual_scale,
    rough_misfit,
)
from torsio.errors import ConfigError
from torsio.physics.recorded_top import RecordedTopDrive

__all__ = ["TOPS", "fit_recordings"]

START_STEPS = 1
"""Newton steps of the closed forms on the model's own torques before the least squares."""

SPEED_SMOOTHING = 0.2
"""Default window [s] of the recorded speed's smoothing (see :func:`fit_recordings`): the
record's noise on the speed is not motion of the top, and held at the noisy speed the model
reads mu_s low (measured in docs/calibration.md: -0.008 of 0.33 with 1 % speed noise, none
with the speed smoothed over 0.2 s, which keeps a ramp and is short against the string's
first torsional period, seconds)."""

DRAG_SPACING = 1
"""Default cells between the drag nodes of a fit's wave grid: contacts on every node (the
wave model's default, 4, lumps each node's friction on every fourth and reads mu_s 3 %
low against finer grids: docs/calibration.md)."""

TOPS = ("recorded", "configured")
"""What drives the top in the fit: the recorded speed, or the configured top drive."""


def _grid(config: Any, discretization: dict[str, Any]) -> dict[str, Any]:
    """The grid of the fit: the caller's options, then the file's, then (on the wave
    model) contacts on every node (:data:`DRAG_SPACING`)."""
    grid = dict(discretization)
    given = config.discretization
    in_file = given.strategy == "wave" and "drag_spacing" in given.options
    wave = grid.get("strategy", "wave") == "wave"
    if wave and "drag_spacing" not in grid and not in_file:
        grid["drag_spacing"] = DRAG_SPACING
    return grid


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
"""The shortest recording a fit takes, in time steps of the wave model's grid: its steady
window (a tenth of the run) must hold 10 of them (a chain's integrator steps freely)."""


def check_wob(value: Any, key: str, axial: bool = False) -> float:
    """The weight on bit [N] of a fit, a finite number >= 0, and 0 for a configuration with
    ``axial`` dynamics (else an error on ``key``)."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not value >= 0.0:
        raise ConfigError(key, f"expected a weight on bit >= 0 (0: off bottom), got {value!r}")
    if not np.isfinite(value):
        raise ConfigError(key, f"expected a finite weight on bit, got {value!r}")
    if axial and value > 0.0:
        raise ConfigError(
            key,
            f"{value:g} N on a configuration with axial dynamics: a fit runs its torsional "
            "model off bottom, and on bottom its bit needs the axial engine; fit start-ups "
            "off bottom (0)",
        )
    return float(value)


def _check_records(family: SystemFamily, records: Sequence[Recording]) -> None:
    """Each record long enough for the model's grid, and turning (errors name it)."""
    step = getattr(family.base.model, "time_step", None)  # a chain has no fixed step
    shortest = MIN_STEPS * float(step) if step else 0.0
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


SPEED_TWIN_SAMPLES = 10
"""The smoothed-speed twin's window, in sample intervals of the record (at least twice the
fit's own window): :func:`_twins`."""


def _twins(
    config: Any,
    family: SystemFamily,
    misfit: Misfit,
    top: str,
    smoothing: float,
    best: np.ndarray,
) -> list[tuple[str, Any]]:
    """The twins of the fitted model (:mod:`torsio.calibration.profile`), by name: the
    wave model's finer and coarser grid (:meth:`SystemFamily.twins`) and, with the top held
    at the recorded speed, that speed smoothed over :data:`SPEED_TWIN_SAMPLES` sample
    intervals (at least twice ``smoothing``: a record's noise on the speed is not motion of
    the top, and the fit should not rest on it), each as the records with its surface
    torque at ``best``; on a lumped strategy, the continuum reading the records itself."""
    records, names = misfit.recordings, misfit.names
    others = [(name, twin, misfit.tops) for name, twin in family.twins()]
    if top == "recorded":
        interval = max(float(np.median(np.diff(r.time))) for r in records)
        window = max(SPEED_TWIN_SAMPLES * interval, 2.0 * smoothing)
        others.append(("smoothed speed", family, _tops(config, records, top, window)))
    twins: list[tuple[str, Any]] = []
    for name, grid, tops in others:
        runs = Misfit(
            grid, records, names, tops, misfit.rpms, misfit.wob, misfit.objective, misfit.progress
        )
        torques = runs.models(best)
        misfit.runs += runs.runs
        twin = [
            attrs.evolve(r, surface_torque=t, name=f"{r.name} ({name})")
            for r, t in zip(records, torques, strict=True)
        ]
        twins.append((name, grid_twin(misfit.objective, twin)))
    continuum = family.continuum()
    if continuum is not None:
        reader = Misfit(
            continuum, records, names, misfit.tops, misfit.rpms, misfit.wob, misfit.objective,
            misfit.progress,
        )  # fmt: skip
        twins.append((TWIN_GRIDS[2], reader_twin(reader, misfit)))
    return twins


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
    progress: Callable[[int], None] | None = None,
    **discretization: Any,
) -> FitResults:
    """Fit the parameters ``names`` of ``config`` to the surface torque of ``recordings``.

    Parameters
    ----------
    config : Config
        With a ``[[section]]`` string and a ``[well]``; run on the wave model, or the
        strategy ``discretization`` names. A file with axial dynamics runs its torsional
        model off bottom (:meth:`~torsio.config.configuration.Config.off_bottom`).
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
        Weight on bit [N]; 0 (default): off bottom, no bit-rock torque (the only weight a
        file with axial dynamics takes).
    rpm : sequence of float, optional
        Set speed of the configured top drive per recording [rpm]; default the mean
        recorded speed over the last tenth of each record.
    profile : bool
        Profile the misfit along each parameter (the interval the data allow).
    speed_smoothing : float
        Window [s] the recorded speed is smoothed over before it drives the top
        (``top="recorded"``; :class:`~torsio.physics.recorded_top.RecordedTopDrive`).
    progress : callable, optional
        ``progress(n)`` after every n model runs (the command line's count on stderr,
        :func:`torsio.solvers.run_chunks.count_progress`).
    **discretization
        ``strategy`` and the options of its grid (:class:`SystemFamily`).

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
    wob = check_wob(wob, "wob", config.axial is not None)
    family = SystemFamily(config, fit=True, **_grid(config, discretization))
    names = family.check(names)
    if not (isinstance(speed_smoothing, int | float) and speed_smoothing >= 0.0):
        raise ConfigError(
            "speed_smoothing", f"expected a window >= 0 in s, got {speed_smoothing!r}"
        )
    tops = _tops(config, records, top, speed_smoothing)
    _check_records(family, records)
    rpms = list(rpm) if rpm is not None else [_final_rpm(r, top) for r in records]
    if len(rpms) != len(records):
        raise ConfigError("rpm", f"expected one set speed per recording ({len(records)})")
    _not_at_rest(family, records, names, said)
    misfit = Misfit(family, records, names, tops, rpms, wob, objective, progress)
    start = closed_form_start(family, records, names)
    for _ in range(START_STEPS):
        models = misfit.models(np.array([start[n] for n in names]))
        start = corrected_start(family, records, models, start)
    upper = np.array([family.upper_bound(n) for n in names])
    configured = np.array([family.values[n] for n in names])
    fit, others = global_fit(misfit, np.array([start[n] for n in names]), configured, upper)
    best = fit.values
    bounds = (admissible_floor(family, names, best), upper)
    parts = misfit.split(best)
    twins = _twins(config, family, misfit, top, speed_smoothing, best) if profile else []
    spread = parameter_uncertainty(
        misfit, best, fit.jacobian, parts, bounds=bounds, profile=profile, twins=twins
    )
    said += [w for n, v, s in zip(names, best, spread, strict=True) if (w := rough_misfit(n, v, s))]
    models = misfit.models(best)
    scale = residual_scale(parts, len(names))
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
        correlation=jacobian_correlation(fit.jacobian),
        residual=float(np.sqrt(np.mean(allsamples**2))),
        recordings=fits,
        objective=objective,
        top=top,
        model=family.description,
        runs=misfit.runs,
        seconds=clock.perf_counter() - started,
        message=fit.message,
        alternatives=tuple(
            Alternative(tuple(float(v) for v in other.values), (other.cost - fit.cost) / scale)
            for other in others
            if not np.allclose(other.values, best, rtol=1e-3, atol=0.0)
        ),
        warnings=tuple(said),
    )
