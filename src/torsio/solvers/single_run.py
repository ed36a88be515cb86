"""One run of the compiled RODAS4 engine, sampled on an output grid (for ``simulate``).

The kernel of severity maps (:mod:`torsio.solvers.rodas`) integrates a single run too:
the same chain, top drive, law kernel and steps, from any initial state, writing the
state ``[z, phi_0, v_0, ...]`` of :class:`torsio.physics.dynamics.Dynamics` at each time
of the output grid from the cubic Hermite interpolant of the step that covers it
(fourth-order accurate, like the method; the steps are not shortened to hit the grid).
It runs over chunks of the grid of bounded wall time (:mod:`torsio.solvers.run_chunks`),
state carried exactly, so Ctrl-C and SIGTERM stop it within about 0.2 s and a long run
reports its progress (in output samples); the chunking does not change a step.

:func:`compiled_engine` says whether the engine can run a System, and if not, why.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from torsio.analysis.simulation_options import COMPILED_METHODS, METHODS, SimulationOptions
from torsio.errors import ConfigError, SolverError
from torsio.physics.dynamics import Dynamics
from torsio.physics.system import System
from torsio.solvers.batch_results import STATUS_MESSAGES
from torsio.solvers.contact_events import MAX_SWITCHES_PER_SAMPLE
from torsio.solvers.law_kernels import LawKernel, law_kernel, python_law_kernel
from torsio.solvers.layouts import (
    CARRY_REJECTED,
    CARRY_STATUS,
    CARRY_STEPS,
    CARRY_T,
    FRICTION_ANY,
    FRICTION_SWITCHES,
    FRICTION_WORK,
    MAX_STATES,
    SMALL_CARRY,
    SMALL_COLUMNS,
    SMALL_FRICTION,
    SMALL_ROWS,
    SMALL_WINDOW,
    SMALL_Z,
    VEC_PHI,
    VEC_V,
    VECTOR_ROWS,
    WINDOW_BIT_MAX,
    WINDOW_BIT_MIN,
    WINDOW_NEXT_SAMPLE,
)
from torsio.solvers.lumped_inputs import pack_table, run_settings, step_limits
from torsio.solvers.run_chunks import CHUNK_SECONDS, run_in_chunks

__all__ = [
    "STEPS_PER_SAMPLE",
    "CompiledRun",
    "compiled_engine",
    "integrate_compiled",
    "integrate_run",
]

STEPS_PER_SAMPLE = 1000
"""Accepted steps allowed per output sample, beyond the batch engine's per-point limit
(the fine 240-DOF model of the Ritto et al. 2017 string at beta = 0 takes about 180 per
sample at rtol 1e-6): a run that needs more is reported, not left running."""


@attrs.frozen
class CompiledRun:
    """What :func:`integrate_compiled` returns.

    ``states`` (samples, size): the state at each grid time; ``reached``: the time the
    run reached [s]; ``status``: 0 or a key of
    :data:`torsio.solvers.batch_results.STATUS_MESSAGES`; ``steps``, ``rejected``;
    ``wall_time_s``; ``window_extremes``: (max, min) of the bit speed [rad/s] over the
    steady window, from the cubic interpolant of every step (as the batch engine reads
    them; the output grid's samples fall between the peaks); ``contacts``: whether the
    chain has contacts along the string, ``switches`` their switches and ``friction_work``
    the friction's work over the run [J] (exact, :mod:`torsio.solvers.contact_kernel`).
    """

    states: np.ndarray
    reached: float
    status: int
    steps: int
    rejected: int
    wall_time_s: float
    window_extremes: tuple[float, float]
    contacts: bool = False
    switches: int = 0
    friction_work: float = 0.0

    @property
    def message(self) -> str:
        """The status in words."""
        return STATUS_MESSAGES.get(self.status, f"status {self.status}")


def compiled_engine(system: System, dynamics: Dynamics) -> tuple[LawKernel | None, str]:
    """(the law's kernel, "") if the compiled engine runs ``system``, else (None, why not).

    It runs a chain (tridiagonal [I], [K], [C]) with a top drive of at most 3 controller
    states (``MAX_STATES``) and a law with a compiled kernel: the law's ``kernel()``, or one
    compiled from its Python ``torque`` (:func:`torsio.solvers.law_kernels.python_law_kernel`).
    """
    from torsio.solvers.compiled import HAVE_NUMBA

    if not HAVE_NUMBA:
        return None, "numba is not installed"
    if not dynamics.is_chain:
        return None, "the model's matrices are not tridiagonal (a chain)"
    if dynamics.states > MAX_STATES:
        return None, f"the top drive has {dynamics.states} controller states (at most {MAX_STATES})"
    if dynamics.contacts is not None and not dynamics.lumped_mass:
        return None, "its contacts along the string need a lumped-mass chain"
    try:
        kernel = law_kernel(system.law)
        if kernel is None:
            kernel = python_law_kernel(system.law, float(system.wob) or 1e5, system.bit_radius)
    except ConfigError as exc:
        return None, exc.message
    return kernel, ""


def integrate_compiled(
    system: System,
    dynamics: Dynamics,
    kernel: LawKernel,
    y0: np.ndarray,
    time_grid: np.ndarray,
    window: float,
    rtol: float,
    atol: float,
    progress: Callable[[int, int], None] | None = None,
    chunk_seconds: float = CHUNK_SECONDS,
) -> CompiledRun:
    """RODAS4 from ``y0`` at t = 0 over ``time_grid`` (uniform, from 0), sampled on it.

    Steps as the batch engine takes them (:mod:`torsio.solvers.rodas`): first step
    1e-3 of the first natural period, at most a quarter of it; ``window`` [s] is the
    steady window (the kernel's running extremes; S_SS is read from the samples).
    ``progress(samples_done, samples)`` after each chunk of about ``chunk_seconds``.
    """
    from torsio.solvers.batch import BatchModel
    from torsio.solvers.batch_options import DEFAULT_MAX_STEPS
    from torsio.solvers.rodas_kernels import run_chunk

    model = BatchModel.from_system(system)
    top = model.top  # packed at the system's own operating point
    run = float(time_grid[-1])
    samples = time_grid.size
    max_steps = DEFAULT_MAX_STEPS + STEPS_PER_SAMPLE * samples
    steps = step_limits(model.first_frequency)
    settings = run_settings(
        run, window, rtol, atol, steps, max_steps, model.bit_radius, 0.0, model.first_frequency,
        MAX_SWITCHES_PER_SAMPLE * samples,
    )  # fmt: skip
    m, n = dynamics.states, model.dofs
    vectors = np.zeros((VECTOR_ROWS, n))
    small = np.zeros((SMALL_ROWS, SMALL_COLUMNS))
    vectors[VEC_PHI] = y0[m::2]
    vectors[VEC_V] = y0[m + 1 :: 2]
    small[SMALL_Z, :m] = y0[:m]
    out = np.zeros((samples, y0.size))
    grid = np.ascontiguousarray(time_grid, dtype=float)
    omega = float(dynamics.reference_speed)
    table = pack_table(dynamics)  # the set speed against time (NaN: none)
    law = (kernel.torque, kernel.slope, kernel.parameters)
    wob = float(system.wob)
    start = time.perf_counter()

    def written() -> int:
        return int(small[SMALL_WINDOW, WINDOW_NEXT_SAMPLE])

    def advance(count: int) -> bool:
        """The next ``count`` samples (or more, if a step covers them); True: it ended."""
        stop = written() + count
        run_chunk(model.chain, top, *law, settings, wob, omega, table, vectors, small,
                  grid, out, stop)  # fmt: skip
        return written() < stop  # the end of the run, or a failure (the status says)

    report = None if progress is None else (lambda done, total: progress(written(), total))
    run_in_chunks(samples, advance, report, first=max(1, samples // 1000), seconds=chunk_seconds)
    carry, window_scalars = small[SMALL_CARRY], small[SMALL_WINDOW]
    friction = small[SMALL_FRICTION]
    return CompiledRun(
        out,
        float(carry[CARRY_T]),
        int(carry[CARRY_STATUS]),
        int(carry[CARRY_STEPS]),
        int(carry[CARRY_REJECTED]),
        time.perf_counter() - start,
        (
            float(window_scalars[WINDOW_BIT_MAX]) + omega,
            float(window_scalars[WINDOW_BIT_MIN]) + omega,
        ),
        bool(friction[FRICTION_ANY]),
        int(friction[FRICTION_SWITCHES]),
        float(friction[FRICTION_WORK]),
    )


def integrate_run(
    system: System,
    dynamics: Dynamics,
    y0: np.ndarray,
    time_grid: np.ndarray,
    window: float,
    options: SimulationOptions,
    where: str,
    progress: Callable[[int, int], None] | None,
) -> tuple[np.ndarray, dict[str, Any]]:
    """The states (size, samples) on the grid and the solver's record; errors never hidden.

    ``"auto"`` runs the compiled RODAS4 engine where it can run the System and LSODA
    otherwise, with the reason in ``solver["fallback"]``. With contacts along the string
    the record has ``contact_switches`` and ``friction_work`` [J]; a scipy method runs them
    between the contacts' switches (:mod:`torsio.solvers.contact_events`).
    """
    chosen = options.method
    fallback = None
    if chosen in COMPILED_METHODS:
        kernel, why = compiled_engine(system, dynamics)
        if kernel is not None:
            result = integrate_compiled(
                system, dynamics, kernel, y0, time_grid, window, options.rtol, options.atol,
                progress,
            )  # fmt: skip
            return result.states.T, _compiled_record(result, options, where, time_grid[-1])
        if chosen == "RODAS4":
            raise ConfigError(
                "simulation.method",
                f"RODAS4 runs on the compiled engine, which cannot run this System: {why}; "
                f"expected one of {', '.join(METHODS[2:])} for it",
            )
        fallback, chosen = why, "LSODA"
    if dynamics.contacts is not None:
        from torsio.solvers.contact_events import integrate_with_contacts

        scipy_options = attrs.evolve(options, method=chosen)
        states, info = integrate_with_contacts(
            dynamics, y0, time_grid, scipy_options, where, progress
        )
    else:
        from torsio.solvers.scipy_run import integrate_scipy

        states, info = integrate_scipy(dynamics, y0, time_grid, chosen, options, where, progress)
    info["fallback"] = fallback
    return states, info


def _compiled_record(
    result: CompiledRun, options: SimulationOptions, where: str, run: float
) -> dict[str, Any]:
    """The solver's record of a run of the compiled RODAS4 engine (SolverError if it failed)."""
    if result.status != 0:
        raise SolverError(
            f"the RODAS4 integrator (compiled engine) failed at t = {result.reached:.6g} s of "
            f"{run:.6g} s: {result.message} after {result.steps} steps (operating point "
            f"{where}; try method='LSODA' or other tolerances)"
        )
    attempts = result.steps + result.rejected
    info = {
        "engine": "compiled",
        "method": "RODAS4",
        "rtol": options.rtol,
        "atol": options.atol,
        "nfev": 5 * attempts + result.steps + 1,  # stages 2-6 of each step, f at its end
        "njev": attempts,  # the law's slope, once per step (the rest of J is constant)
        "nlu": attempts,
        "steps": result.steps,
        "rejected": result.rejected,
        "status": 0,
        "message": "reached the end of the run",
        "wall_time_s": result.wall_time_s,
        "fallback": None,
        "bit_speed_extremes": result.window_extremes,
    }
    if result.contacts:
        info["message"] = "reached the end of the run, the contacts' switches located"
        info["contact_switches"] = result.switches
        info["friction_work"] = result.friction_work
    return info
