"""Transient response of a System: start-up from rest, stick-slip, severity S_SS.

:func:`simulate` integrates the equations of motion in twist coordinates (see
:mod:`torsio.physics.dynamics`) with the compiled RODAS4 engine of severity maps
(:mod:`torsio.solvers.single_run`) or with ``scipy.integrate.solve_ivp``, and samples the
response on a uniform time grid.

Defaults (the paper states none; see ``docs/dynamics.md``):

* **Initial condition**: start-up from rest, every angle and speed zero at t = 0
  while the top turns at Omega from t = 0 (the forcing ``c1 Omega + k1 Omega t`` of
  Eq. 3 implies it).
* **Run length and steady window**: :func:`torsio.analysis.severity.run_times`, the one
  place every analyzer takes them from: 40 periods of the first natural mode, S_SS
  read over the last 15, or over at most the second half of a run whose length is given.
* **Top drive**: any top drive of the System (:mod:`torsio.physics.top_drives`); the
  equations are those of :class:`torsio.physics.dynamics.Dynamics`. For a torque-driven
  top S_SS is read relative to the mean top-drive speed over the steady window.
* **Integrator**: RODAS4 (L-stable, linearly implicit, order 4) on the compiled engine
  that also integrates severity maps, where it can run the System (a chain, a law with a
  compiled kernel or one numba compiles from its Python ``torque``); otherwise LSODA
  (switches between a non-stiff Adams method and a stiff BDF method by itself) with the
  analytic Jacobian in banded form, and ``solver["fallback"]`` says why. rtol = 1e-6,
  atol = 1e-9 for either. Any ``solve_ivp`` method can be asked for by name (the
  independent check); Radau and BDF get the sparse Jacobian, explicit methods none.
* **Output step**: :data:`torsio.analysis.severity.DEFAULT_SAMPLES_PER_PERIOD` (200)
  samples per period of the first mode. The compiled engine reads S_SS from the extremes
  of its continuous solution (as severity maps do), scipy from the sampled bit speed; at
  the stick-slip points of the Ritto et al. (2017) string checked, the samples under-read
  the extremes by up to 9e-5 (5 DOFs), 6.6e-4 on a 240-DOF model with beta = 0.

Examples
--------
>>> from torsio.examples import builtin_config
>>> system = builtin_config().system(strategy="A").at(wob=175e3, rpm=100)
>>> results = simulate(system)
>>> round(results.severity, 3), results.severe
(1.099, True)
>>> data = results.to_dict()
>>> data["wob"], data["rpm"], data["solver"]["engine"], data["solver"]["method"]
(175000.0, 100.0, 'compiled', 'RODAS4')
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np

from torsio.analysis.budget import (
    check_law_time_scale,
    check_output_size,
)
from torsio.analysis.contact_summary import contact_summary
from torsio.analysis.grid_check import TWIN_TRAVEL_TIME_TOLERANCE, with_grid_check
from torsio.analysis.limits import (
    past_the_record,
    saturated_motor,
    short_window,
    stuck_throughout,
    warning_list,
)
from torsio.analysis.severity import (
    DEFAULT_SAMPLES_PER_PERIOD,
    DEFAULT_STICK_THRESHOLD,
    first_natural_frequency,
    run_times,
    severity,
)
from torsio.analysis.simulation_options import (
    MIN_WINDOW_SAMPLES,
    SINGLE_RUN_ATOL,
    SINGLE_RUN_RTOL,
    SimulationOptions,
)
from torsio.analysis.time_scales import check_time_scales
from torsio.analysis.transient_results import TransientResults, window_mask
from torsio.errors import ConfigError, SolverError
from torsio.model.contacts import carried_contacts
from torsio.physics.dynamics import Dynamics
from torsio.physics.system import System

if TYPE_CHECKING:  # a configuration is read, never imported: torsio.config sits above
    from torsio.config.configuration import Config

__all__ = ["simulate", "simulate_config", "simulate_lumped"]


def _initial_state(dynamics: Dynamics, initial_state: Any) -> np.ndarray:
    n = dynamics.dofs
    if initial_state is None:
        return dynamics.rest_state()
    if isinstance(initial_state, tuple):
        if len(initial_state) != 2:
            raise ConfigError(
                "initial_state", "expected (angles [rad], speeds [rad/s]) or a state vector"
            )
        angles, speeds = (np.asarray(a, dtype=float).reshape(-1) for a in initial_state)
        for key, values in (("angles", angles), ("speeds", speeds)):
            if values.size == 1:
                values = np.full(n, float(values[0]))
            if values.size != n:
                raise ConfigError(
                    f"initial_state.{key}", f"expected {n} values (one per DOF), got {values.size}"
                )
            if key == "angles":
                angles = values
            else:
                speeds = values
        y0 = dynamics.state(angles, speeds)  # at t = 0 the twist is the angle
    else:
        y0 = np.array(initial_state, dtype=float).reshape(-1)
        if y0.size != dynamics.size:
            raise ConfigError(
                "initial_state",
                f"expected the state [z, phi_0, v_0, ..., phi_(n-1), v_(n-1)] of "
                f"{dynamics.size} values, got {y0.size}",
            )
    if not np.all(np.isfinite(y0)):
        raise ConfigError("initial_state", "expected finite values")
    return y0


def simulate(
    system: System,
    duration: float | None = None,
    steady_window: float | None = None,
    method: Any = "auto",
    rtol: float = SINGLE_RUN_RTOL,
    atol: float = SINGLE_RUN_ATOL,
    output_step: float | None = None,
    initial_state: Any = None,
    stick_threshold: float | None = None,
    progress: Any = None,
) -> TransientResults:
    """Integrate a System's equations of motion and read S_SS over the steady window.

    Parameters
    ----------
    system : System
        Model, damping, bit-rock law, top drive and operating point.
    duration : float, optional
        Run length [s]; default 40 periods of the first natural mode.
    steady_window : float, optional
        Length of the steady-state window at the end of the run [s] over which
        S_SS and the stick fraction are read; default 15 periods of the first
        mode, at most half the run.
    method : str or scipy OdeSolver class
        ``"auto"`` (default): RODAS4 on the compiled engine of severity maps
        (:mod:`torsio.solvers.single_run`) where it can run the System, else LSODA, with
        the reason in ``solver["fallback"]``. ``"RODAS4"``: the compiled engine only (a
        ConfigError if it cannot run the System). Any ``solve_ivp`` method (``"LSODA"``
        with the banded Jacobian, ``"Radau"``, ...): scipy, the independent check.
    rtol, atol : float
        Relative and absolute tolerances (atol applies to twists [rad] and
        relative speeds [rad/s]).
    output_step : float, optional
        Step of the uniform output grid [s]; default 1/200 of the first period
        (rounded down so that the grid ends exactly at ``duration``).
    initial_state : ndarray or tuple, optional
        Default: start-up from rest. A tuple ``(angles, speeds)`` gives absolute
        angles [rad] and speeds [rad/s] of every chain node at t = 0 (the top drive
        first when it has inertia; controller states zero); an array gives the
        state of :class:`torsio.physics.dynamics.Dynamics`.
    stick_threshold : float, optional
        The bit sticks while ``|bit speed| < stick_threshold * Omega``; default
        :data:`DEFAULT_STICK_THRESHOLD`.
    progress : callable or bool, optional
        ``progress(samples_done, samples)`` of the output grid during the run; None
        (default): a bar on stderr (a line every 4 s when stderr is not a terminal) once
        the run has taken 2 s (:func:`torsio.solvers.run_chunks.stderr_progress`, as for
        the wave model); True: from the start; False: none.

    Returns
    -------
    TransientResults

    Raises
    ------
    ConfigError
        For invalid options (named ``simulation.<key>``).
    SolverError
        If the integrator fails or the solution is not finite; the message gives
        the solver's message and the time reached.
    """
    from torsio.model.protocol import resolve

    options = SimulationOptions(  # validated once, whatever the model
        duration=duration,
        steady_window=steady_window,
        method=method,
        rtol=rtol,
        atol=atol,
        output_step=output_step,
        stick_threshold=stick_threshold,
    )
    engine = resolve(system.model.engines.transient)  # the model names what runs it
    return engine(system, options, initial_state=initial_state, progress=progress)


def simulate_lumped(
    system: System,
    options: SimulationOptions,
    initial_state: Any = None,
    progress: Any = None,
) -> TransientResults:
    """:func:`simulate` of a lumped model (its transient engine,
    :data:`torsio.model.lumped.LUMPED_ENGINES`): the System, its validated options and the
    ``initial_state`` and ``progress`` of :func:`simulate`."""
    if not (math.isfinite(system.omega) and system.omega > 0):  # System validates this
        raise ConfigError("operation.rpm", f"expected a positive rotary speed, got {system.rpm!r}")
    run, window = run_times(system, options.duration, options.steady_window)
    period = 2.0 * math.pi / first_natural_frequency(system)
    step = (
        options.output_step
        if options.output_step is not None
        else period / DEFAULT_SAMPLES_PER_PERIOD
    )
    intervals = check_output_size(run, step, 3 * system.model.dofs + 4)
    check_law_time_scale(system, system.wob, run)
    check_time_scales(system, run)
    time_grid = np.linspace(0.0, run, intervals + 1)
    in_window = window_mask(time_grid, window)
    if step > window / MIN_WINDOW_SAMPLES and options.output_step is None:
        # the default sampling: what is too short is the window (or the run it halves)
        key = "simulation.steady_window" if options.steady_window is not None else None
        raise ConfigError(
            key or "simulation.duration",
            f"the steady window ({window:g} s{'' if key else ', half the run by default'}) "
            f"holds fewer than {MIN_WINDOW_SAMPLES} samples of the default output step "
            f"({step:g} s, 1/{DEFAULT_SAMPLES_PER_PERIOD} of the first period {period:.4g} s); "
            f"expected a {'window' if key else 'run'} of at least "
            f"{(1 if key else 2) * MIN_WINDOW_SAMPLES * step:g} s (S_SS over a shorter window "
            "reads a fragment of a cycle), or give a finer --output-step",
        )
    if step > window / MIN_WINDOW_SAMPLES:
        raise ConfigError(
            "simulation.output_step",
            f"the output step ({step:g} s) leaves fewer than {MIN_WINDOW_SAMPLES} samples in "
            f"the steady window ({window:g} s); expected a step of at most "
            f"{window / MIN_WINDOW_SAMPLES:g} s",
        )
    threshold = (
        options.stick_threshold if options.stick_threshold is not None else DEFAULT_STICK_THRESHOLD
    )

    from torsio.solvers.run_chunks import run_progress
    from torsio.solvers.single_run import integrate_run  # numba only when a run starts

    dynamics = Dynamics.from_system(system)
    y0 = _initial_state(dynamics, initial_state)
    where = f"WOB = {system.wob:g} N, {system.rpm:g} rpm"
    with run_progress(progress) as report:
        states, solver_info = integrate_run(
            system, dynamics, y0, time_grid, window, options, where, report
        )
    name = solver_info["method"]
    finite = np.all(np.isfinite(states), axis=0)
    if not finite.all():
        bad = float(time_grid[int(np.argmin(finite))])
        raise SolverError(
            f"the {name} integrator returned non-finite values from t = {bad:.6g} s "
            f"(of {run:.6g} s) with the bit-rock law {_law_name(system.law)}: a law torque "
            f"that is NaN or infinite, or an unstable model ({solver_info['message']})"
        )
    z, twists_by_node, relative_by_node = dynamics.split(states)
    reference = dynamics.reference_speed
    speeds_by_node = relative_by_node + reference
    bit_speed = speeds_by_node[-1].copy()
    with np.errstate(all="ignore"):
        bit_torque = np.broadcast_to(
            np.asarray(dynamics.bit_torque(bit_speed), dtype=float), bit_speed.shape
        ).copy()
    if not np.all(np.isfinite(bit_torque)):
        bad = float(time_grid[int(np.argmin(np.isfinite(bit_torque)))])
        raise SolverError(
            f"the bit-rock law {_law_name(system.law)} returned a non-finite torque at "
            f"t = {bad:.6g} s (bit speed {bit_speed[int(np.argmin(np.isfinite(bit_torque)))]:.6g}"
            " rad/s)"
        )
    surface_torque = np.asarray(
        dynamics.pipe_torque(twists_by_node, relative_by_node, time_grid), float
    )
    motor_torque = np.broadcast_to(
        np.asarray(dynamics.motor_torque(z, twists_by_node, relative_by_node, time_grid)[0], float),
        bit_speed.shape,
    ).copy()
    first = 1 if dynamics.has_top_node else 0  # the model's own nodes
    held_speed = dynamics.set_speed_at(time_grid)[0]  # a held top's
    top_speed = speeds_by_node[0].copy() if first else np.array(held_speed, dtype=float)
    mean_top_speed = float(top_speed[in_window].mean())
    omega = dynamics.set_speed if math.isfinite(dynamics.set_speed) else mean_top_speed
    # a torque-driven top that did not turn: no speed to read S_SS against (a mean speed
    # below atol is not resolved by the integrator: RODAS4 gives 6e-304 rad/s for 1e-300 N m)
    if not omega > options.atol:
        raise ConfigError(
            "top_drive.torque",
            f"the top drive did not turn (mean speed {mean_top_speed:.3g} rad/s over the steady "
            f"window) with a motor torque of {dynamics.top.u0:.6g} N m; expected a torque "
            "above what the drag and the bit at rest hold",
        )
    window_speeds = bit_speed[in_window]
    stick = float(np.mean(np.abs(window_speeds) < threshold * omega))
    extremes = solver_info.pop("bit_speed_extremes", None)  # the continuous solution's
    read = np.array(extremes) if extremes is not None else window_speeds
    twists = twists_by_node[first:].T.copy()
    well_summary = None
    if dynamics.contacts is not None:  # from the output samples
        moved = np.flatnonzero(np.abs(bit_speed) > dynamics.contacts.threshold_speed)
        well_summary = contact_summary(
            dynamics.contacts,
            surface_range=(surface_torque[in_window].min(), surface_torque[in_window].max()),
            surface_peak=float(surface_torque.max()),
            first_motion=float(time_grid[moved[0]]) if moved.size else math.nan,
            friction_work=float(solver_info.pop("friction_work")),
            window_time=time_grid[in_window],
            window_bit_speed=bit_speed[in_window],
        )
    return TransientResults(
        time=time_grid,
        bit_speed=bit_speed,
        bit_angle=twists[:, -1] + reference * time_grid,
        node_speeds=speeds_by_node[first:].T.copy(),
        node_twists=twists,
        bit_torque=bit_torque,
        surface_torque=surface_torque,
        severity=severity(read, omega),
        stick_fraction=stick,
        steady_window=float(window),
        stick_threshold=float(threshold),
        solver=solver_info,
        system=system,
        top_speed=top_speed,
        motor_torque=motor_torque,
        states=states.T.copy(),
        reference_speed=float(reference),
        severity_speed=float(omega),
        bit_speed_extremes=extremes,
        well_summary=well_summary,
        warnings=warning_list(
            carried_contacts(getattr(system.model, "contacts", None))[1],
            stuck_throughout(stick, threshold),
            short_window(float(window), period),
            saturated_motor(
                motor_torque[in_window], dynamics.top.max_torque, mean_top_speed, dynamics.set_speed
            ),
            past_the_record(system.top, run),
        ),
    )


def _law_name(law: Any) -> str:
    from torsio.plugins import describe_bit_law

    return describe_bit_law(law)


def simulate_config(
    config: Config,
    wob: Any = None,
    rpm: Any = None,
    *,
    discretization: Mapping[str, Any] | None = None,
    **overrides: Any,
) -> TransientResults:
    """Simulate a configuration: its System, its ``[simulation]`` options, ``overrides`` on top;
    a configuration with axial dynamics on the axial engine
    (:func:`torsio.analysis.config_runs.simulate_axial_config`, with ``growth_rate``), whose
    results carry their axial channels.

    A wave run from rest with friction along the string whose bit speed has a cycle is
    checked against a coarse twin (:mod:`torsio.analysis.grid_check`: ``grid_check`` in
    its well summary, a warning when the grid does not resolve the cycle).

    Parameters
    ----------
    config : Config
    wob, rpm : float or str, optional
        Operating point overriding ``[operation]`` (weight on bit [N] or with
        units; rotary speed [rpm] or with units).
    discretization : mapping, optional
        Options overriding ``[discretization]`` (``strategy``, ``dp_elements``, ...).
    **overrides
        Options of :func:`simulate` overriding ``[simulation]`` (``None`` ignored),
        plus ``initial_state`` and ``progress``.

    Examples
    --------
    >>> from torsio.examples import builtin_config
    >>> results = simulate_config(builtin_config(), wob="175 kN", rpm=100,
    ...                           discretization={"strategy": "A"})
    >>> round(results.severity, 3)
    1.099
    """
    if config.axial is not None:  # the axial engine (torsio.analysis.config_runs)
        from torsio.analysis.config_runs import run_capabilities, simulate_axial_config

        given = {**overrides, **(discretization or {})}
        run_capabilities(config).refuse({key: (key, value) for key, value in given.items()})
        kept = ("duration", "steady_window", "growth_rate", "progress", "stick_threshold")
        for key, value in given.items():
            if value is not None and key not in kept:
                raise ConfigError(key, f"{value!r}: not an option of an axial run ({kept})")
        return simulate_axial_config(config, wob, rpm, **{k: given[k] for k in kept if k in given})
    initial_state = overrides.pop("initial_state", None)
    progress = overrides.pop("progress", None)
    options = SimulationOptions.from_config(config).replace(**overrides)
    point = config.operating_point(wob, rpm)
    given = {k: v for k, v in (discretization or {}).items() if v is not None}
    system = config.system(**given).at(**point)
    step = system.model.time_step
    unused = None
    if step is not None:  # its own fixed step: integrator options refused, the file's noted
        from torsio.analysis.wave import INTEGRATOR_OPTIONS, fixed_step_note

        given_options = {f"simulation.{k}": overrides.get(k) for k in INTEGRATOR_OPTIONS}
        unused = fixed_step_note(config.simulation.options, given_options)
    results = simulate(system, initial_state=initial_state, progress=progress, **options.kwargs())
    if unused is not None:
        results = attrs.evolve(results, warnings=(*results.warnings, unused))
    if step is None or not _checks_its_grid(results, initial_state):
        return results
    coarse = {
        **given,
        "time_step": 2.0 * step,
        "travel_time_tolerance": TWIN_TRAVEL_TIME_TOLERANCE,
    }
    try:
        quiet = False if progress is False else None  # as quiet as the run, else after 2 s
        twin = simulate(config.system(**coarse).at(**point), progress=quiet, **options.kwargs())
    except ConfigError as exc:  # no coarser grid for this string: the run stands, unchecked
        note = f"the grid was not checked against a grid of twice the time step: {exc}"
        return attrs.evolve(results, warnings=(*results.warnings, note))
    return with_grid_check(results, twin)


def _checks_its_grid(results: TransientResults, initial_state: Any) -> bool:
    """A run from rest with friction along the string whose bit speed has a cycle (on a
    model's own fixed grid: :mod:`torsio.analysis.grid_check`)."""
    summary = results.well_summary
    return (
        initial_state is None and summary is not None and summary["stick_slip_period"] is not None
    )
