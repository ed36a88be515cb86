"""Transient response of the distributed model (the ``wave`` strategy).

:func:`wave_response` runs a System whose model is a :class:`torsio.model.wave.WaveModel`
with the characteristic stepping of :mod:`torsio.solvers.characteristics`: start-up from
rest, the same defaults as the lumped transient (40 periods of the first exact continuum
mode, S_SS over the last 15, 200 output samples per period), the same bit-rock law and
top drive. S_SS takes the bit-speed extremes over every time step of the window.
:func:`torsio.analysis.transient.simulate` hands wave systems to it; :func:`simulate_wave`,
the transient engine the model names (:data:`torsio.model.wave.WAVE_ENGINES`), takes the
parameters of ``simulate``.

Integrator: exact transport along characteristics, exact junctions, the distributed drag
lumped into point dampers every ``drag_spacing`` cells (exact junctions too), BDF2 for
the bit, trapezoidal rule for a top drive; fixed step dt of the grid (no tolerances).

Examples
--------
>>> from torsio.examples import builtin_config
>>> from torsio.physics.damping import RayleighDamping
>>> import attrs
>>> system = builtin_config().system(strategy="wave")
>>> system = attrs.evolve(system, damping=RayleighDamping(alpha=0.35)).at(wob=150e3, rpm=60)
>>> response = wave_response(system, duration=5.0, steady_window=1.0)
>>> response.run.engine in ("numba", "python"), response.transient.solver["cells"]
(True, [995, 36, 62])
>>> abs(response.energy["residual"]) < 1e-3 * response.energy["work_in"]
True
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterable
from typing import Any

import attrs
import numpy as np

from torsio.analysis.budget import check_law_time_scale, check_output_size, check_wave_steps
from torsio.analysis.contact_summary import contact_summary
from torsio.analysis.limits import past_the_record, short_window, stuck_throughout, warning_list
from torsio.analysis.severity import (
    DEFAULT_SAMPLES_PER_PERIOD,
    DEFAULT_STICK_THRESHOLD,
    run_times,
    severity_of_extremes,
)
from torsio.analysis.simulation_options import SimulationOptions, check_window_samples
from torsio.analysis.transient_results import TransientResults
from torsio.errors import ConfigError
from torsio.model.contacts import carried_contacts
from torsio.model.wave import WAVE_ENGINES, WaveModel, check_wave_damping, first_frequency
from torsio.solvers.characteristics import RECORD_CHANNELS, WaveState, node_offsets
from torsio.solvers.run_chunks import QUIET_SECONDS, stderr_progress
from torsio.solvers.wave_march import WaveRun, march
from torsio.solvers.wave_top import top_boundary

INTEGRATOR_OPTIONS = ("method", "rtol", "atol")
"""Options of the lumped integrators that have no meaning on the characteristic grid."""


def refuse_integrator_options(given: dict[str, Any]) -> None:
    """ConfigError on the first option of ``given`` (key -> value, None: not given).

    The wave model steps on the fixed grid of its characteristics: no integrator to
    choose, no tolerance; its accuracy is the grid's (``discretization.time_step``,
    ``travel_time_tolerance``). The command line refuses ``--method``, ``--rtol``,
    ``--atol`` and ``--engine`` for it rather than record them unused.

    >>> refuse_integrator_options({"--rtol": None})
    >>> refuse_integrator_options({"--rtol": 1e-8})
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: --rtol: has no effect on the wave model (strategy = "wave"), ...
    """
    for key, value in given.items():
        if value is not None:
            raise ConfigError(
                key, f"has no effect on the wave model {_NO_INTEGRATOR}; got {value!r}"
            )


def integrator_note(keys: list[str]) -> str:
    """The note for ``[simulation]`` keys of a file that a wave run does not use."""
    return f"[simulation] {', '.join(keys)} not used: the wave model {_NO_INTEGRATOR}"


def fixed_step_note(file_keys: Iterable[str], given: dict[str, Any]) -> str | None:
    """On a model that steps at its own fixed step: a ConfigError on the first of the
    integrator options ``given`` (name -> value, None: not given;
    :func:`refuse_integrator_options`), and the note for those of the file's
    ``[simulation]`` keys ``file_keys`` (None: it gives none).

    >>> fixed_step_note(["duration", "rtol"], {"rtol": None})
    '[simulation] rtol not used: the wave model ...'
    """
    refuse_integrator_options(given)
    unused = sorted(set(file_keys) & set(INTEGRATOR_OPTIONS))
    return integrator_note(unused) if unused else None


_NO_INTEGRATOR = (
    '(strategy = "wave"), which steps on the fixed grid of its characteristics with no '
    "integrator to choose and no tolerance; its accuracy is set by discretization.time_step "
    "and travel_time_tolerance (docs/wave.md)"
)


@attrs.frozen(eq=False)
class WaveResponse:
    """A wave-model run: the transient results plus what only the distributed model has.

    Attributes
    ----------
    transient : TransientResults
        As the lumped transient gives them (``node_speeds``: the bit only).
    run : WaveRun
        Raw records, the speed along the string (``field``) and energy integrals.
    depths : ndarray
        Depth of every node on the grid string [m] (state layout: junction nodes twice).
    energy : dict
        ``work_in``, ``stored``, ``dissipated``, ``residual`` [J] over the run: work of the
        top (motor work for a top drive) = change of stored energy (string, bit, top drive)
        + dissipation (bit-rock, drags, friction along the string); ``friction`` [J] the
        contacts' part of it.
    """

    transient: Any
    run: WaveRun
    depths: np.ndarray
    energy: dict[str, float]

    @property
    def grid(self) -> WaveModel:
        """The characteristic grid."""
        model: WaveModel = self.transient.system.model
        return model


def _depths(grid: WaveModel) -> np.ndarray:
    offsets = node_offsets(grid)
    depths = np.empty(int(offsets[-1]))
    top = 0.0
    for s, (n, dx) in enumerate(zip(grid.cells, grid.cell_lengths, strict=True)):
        depths[offsets[s] : offsets[s + 1]] = top + dx * np.arange(n + 1)
        top += n * dx
    return depths


def _field_every(field_step: float, dt: float, duration: float, grid: WaveModel) -> int:
    """Steps between snapshots of the speed along the string; their memory checked."""
    if not (math.isfinite(field_step) and field_step > 0):
        raise ConfigError("field_step", f"expected a positive time in s, got {field_step!r}")
    every = max(1, int(round(field_step / dt)))
    check_output_size(duration, every * dt, int(grid.dofs) + len(grid.cells))
    return every


def _well_summary(
    grid: WaveModel, summary: dict[str, float], time: np.ndarray, bit_speed: np.ndarray
) -> dict[str, Any] | None:
    """What a run with friction along the string reports (None without contacts), from the
    extremes the kernel took at every step."""
    if grid.contacts is None:
        return None
    return contact_summary(
        grid.contacts,
        surface_range=(summary["surface_torque_min"], summary["surface_torque_max"]),
        surface_peak=summary["surface_torque_peak"],
        first_motion=summary["bit_first_motion"],
        friction_work=summary["friction_dissipation"],
        window_time=time,
        window_bit_speed=bit_speed,
    )


def _transient_results(values: dict[str, Any]) -> Any:
    """A TransientResults from the values it has fields for."""
    cls = TransientResults
    return cls(**{k: v for k, v in values.items() if k in attrs.fields_dict(cls)})


def simulate_wave(
    system: Any,
    options: SimulationOptions,
    initial_state: WaveState | None = None,
    progress: Any = None,
) -> TransientResults:
    """The transient engine of the distributed model (:data:`torsio.model.wave.WAVE_ENGINES`).

    Takes the System, the validated options and the ``initial_state`` and ``progress`` of
    :func:`torsio.analysis.transient.simulate`, and returns the transient results of
    :func:`wave_response`; ``method``, ``rtol`` and ``atol`` have no meaning on the fixed
    grid and are not used (:func:`~torsio.analysis.transient.simulate_config` refuses them,
    :func:`fixed_step_note`).
    """
    response = wave_response(
        system, options.duration, options.steady_window, options.output_step,
        options.stick_threshold, initial_state=initial_state, progress=progress,
    )  # fmt: skip
    return response.transient


def wave_response(
    system: Any,
    duration: float | None = None,
    steady_window: float | None = None,
    output_step: float | None = None,
    stick_threshold: float | None = None,
    field_step: float | None = None,
    initial_state: WaveState | None = None,
    progress: Any = None,
    **ignored: Any,
) -> WaveResponse:
    """Run the distributed model of ``system`` (its model must be a WaveModel).

    Parameters
    ----------
    system : System
        With ``model`` from the ``wave`` strategy, Rayleigh damping with beta = 0.
    duration, steady_window, output_step : float, optional
        Run length, steady window at its end, output sampling step [s] (defaults: 40
        and 15 periods of the first continuum mode, 1/200 period); the output step is
        rounded to whole time steps.
    stick_threshold : float, optional
        Fraction of Omega below which the bit counts as stuck (default 0.1).
    field_step : float, optional
        Record the angular speed along the string every so often [s] (default: never).
    initial_state : WaveState, optional
        Default: start-up from rest.
    progress : callable or bool, optional
        ``progress(steps_done, steps)`` between chunks of steps; None (default): a bar on
        stderr (a line every 4 s when stderr is not a terminal) once the run has taken
        2 s (:func:`torsio.solvers.run_chunks.stderr_progress`); True: from the start;
        False: none.
    **ignored
        Options of the lumped integrator (``method``, ``rtol``, ``atol``) that have no
        meaning on a fixed characteristic grid: not used (``simulate_config`` and the
        command line refuse them, :func:`fixed_step_note`).
    """
    grid = system.model
    if getattr(grid, "engines", None) != WAVE_ENGINES:  # a model this stepping runs
        raise ConfigError("discretization.strategy", f"expected the wave model, got {grid!r}")
    alpha = check_wave_damping(system.damping, system.model)
    contacts, no_friction = carried_contacts(grid.contacts)
    if contacts is not grid.contacts:
        grid = grid.with_contacts(contacts)
    dt = grid.time_step
    period = 2.0 * math.pi / first_frequency(grid)
    window_given = steady_window is not None
    duration, steady_window = run_times(system, duration, steady_window)
    output_step = period / DEFAULT_SAMPLES_PER_PERIOD if output_step is None else output_step
    if not (math.isfinite(output_step) and output_step > 0):
        raise ConfigError("simulation.output_step", f"expected a positive time, got {output_step}")
    threshold = DEFAULT_STICK_THRESHOLD if stick_threshold is None else float(stick_threshold)
    steps = check_wave_steps(grid, duration)  # the work, up front
    record_every = max(1, int(round(output_step / dt)))
    check_window_samples(
        float(steady_window), record_every * dt, dt, window_given, duration
    )  # the rule of the lumped transient, on the grid's steps
    check_output_size(duration, record_every * dt, len(RECORD_CHANNELS) + 4)
    field_every = 0 if field_step is None else _field_every(field_step, dt, duration, grid)
    check_law_time_scale(system, system.wob, duration)  # as a lumped run and a map
    window_steps = int(round(steady_window / dt))
    top = top_boundary(system, grid)
    started = time.perf_counter()
    reporter = None
    if progress is None or progress is True:
        reporter = stderr_progress("wave run", quiet=0.0 if progress else QUIET_SECONDS)
    try:
        run = march(
            grid, top, system.law, system.wob, system.bit_radius, alpha, steps,
            window_start=steps - window_steps + 1, record_every=record_every,
            field_every=field_every, state=initial_state,
            progress=reporter if reporter is not None else (progress or None),
        )  # fmt: skip
    finally:
        if reporter is not None:
            reporter.close()
    wall = time.perf_counter() - started
    t = run.time
    bit_speed, bit_torque, surface_torque, top_speed, motor = run.records.T
    window = t >= t[-1] - steady_window - 1e-9 * dt
    summary = run.summary
    if top.held:
        reference = top.set_speed  # its final speed (a recorded top: the table's last)
    elif math.isnan(top.set_speed):
        reference = summary["top_speed_sum"] / summary["window_steps"]
    else:
        reference = top.set_speed
    severity = severity_of_extremes(summary["bit_speed_max"], summary["bit_speed_min"], reference)
    stick = float(np.mean(np.abs(bit_speed[window]) < threshold * reference))
    bit_angle = np.concatenate(
        [[0.0], np.cumsum(0.5 * (bit_speed[1:] + bit_speed[:-1]) * np.diff(t))]
    )
    # energy: work in = change of stored + dissipated
    stored = summary["stored_final"] - summary["stored_initial"]
    dissipated = (
        summary["bit_dissipation"]
        + summary["bit_drag_dissipation"]
        + summary["string_drag_dissipation"]
        + summary["top_drag_dissipation"]
        + summary["friction_dissipation"]
    )
    energy = {
        "work_in": float(summary["work_in"]),
        "stored": float(stored),
        "dissipated": float(dissipated),
        "residual": float(summary["work_in"] - stored - dissipated),
        "friction": float(summary["friction_dissipation"]),
    }
    solver = {
        "method": "characteristics (exact transport, point dampers, BDF2 bit, "
        "trapezoidal top drive)",
        "drag_spacing": grid.drag_spacing,
        "time_step": dt,
        "cells": list(grid.cells),
        "travel_time_errors": [float(e) for e in grid.travel_time_errors],
        "engine": run.engine,
        "steps": steps,
        "rtol": math.nan,
        "atol": math.nan,
        "nfev": steps,
        "njev": 0,
        "nlu": 0,
        "status": 0,
        "message": "fixed-step characteristic grid",
        "wall_time_s": wall,
    }
    values = {
        "time": t,
        "bit_speed": bit_speed,
        "bit_angle": bit_angle,
        "node_speeds": bit_speed[:, None],
        "node_twists": (bit_angle - reference * t)[:, None],
        "bit_torque": bit_torque,
        "surface_torque": surface_torque,
        "severity": float(severity),
        "stick_fraction": stick,
        "steady_window": float(steady_window),
        "stick_threshold": threshold,
        "solver": solver,
        "system": system,
        "top_speed": top_speed,
        "motor_torque": motor,
        "states": np.zeros((t.size, 0)),
        "reference_speed": reference,
        "severity_speed": reference,
        "well_summary": _well_summary(grid, summary, t[window], bit_speed[window]),
        "warnings": warning_list(  # as the lumped transient says them
            no_friction,
            stuck_throughout(stick, threshold),
            short_window(float(steady_window), period),
            past_the_record(system.top, duration),
        ),
    }
    return WaveResponse(_transient_results(values), run, _depths(grid), energy)
