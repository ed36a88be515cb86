"""Axial-torsional transients with the RGD bit on the compiled engine.

:func:`simulate_axial` runs a lumped assembly (:mod:`torsio.model.axial_assembly`) drilling
with an :class:`~torsio.axial.rgd.RGDBit` under the weight W₀ with the top turning at Ω₀,
from rest or from the steady state (:mod:`torsio.solvers.axial_run_setup`), with the fixed-step
scheme of :mod:`torsio.solvers.axial_kernel`, and returns the results every run has
(:class:`~torsio.analysis.transient_results.TransientResults`) with its axial channels
(:class:`~torsio.analysis.axial_results.AxialChannels`): the window's S_SS, axial severity,
stuck and off-bottom fractions, mean ROP and MSE, the bit's signals, and the growth rate
of the linearization of steady drilling (:func:`torsio.axial.stability.drilling_stability`;
not with a prescribed bit rotation).
A law of the torque alone (:mod:`torsio.physics.torque_law_bit`: Tucker-Wang, a plugin's) runs on
a lumped chain the same way, resting axially on the rock, and has no growth rate here.

Default run length and window as torsio's other runs
(:func:`torsio.analysis.severity.run_times`): 40 and 15 periods of the first torsional
mode, top held (the assembly's ``first_frequency()``).

Examples
--------
>>> from torsio.model.axial_assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> run = simulate_axial(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=2.0,
...                      window=1.0, start="steady", perturbation=0.0)
>>> round(run.axial.rop_mean / run.axial.steady.rop, 12), run.stick_fraction
(1.0, 0.0)
>>> sorted(run.to_dict())[:3]
['axial_severity', 'bit', 'bit_speed_max']
>>> run.axial.string_friction_work, run.axial.contact_switches  # no [well]: no contact
(0.0, 0)
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import NDArray

from torsio.analysis.axial_energy import energy_balance, stored_energy
from torsio.analysis.axial_results import SCHEME, AxialChannels, axial_results
from torsio.analysis.axial_warnings import run_warnings
from torsio.analysis.axial_window import summarize
from torsio.analysis.limits import past_the_record, saturated_motor, warning_list
from torsio.analysis.severity import DEFAULT_STICK_THRESHOLD, run_times
from torsio.axial.stability import NO_PIPE_FRICTION_RATE, growth_rate_skipped
from torsio.axial.steady import SteadyDrilling
from torsio.errors import ConfigError, SolverError
from torsio.model.axial_assembly import assembly_description, lumped_twin
from torsio.model.lumped import LumpedModel
from torsio.model.wave import WaveModel
from torsio.physics.torque_law_bit import AxialBit, TorqueLawBit
from torsio.solvers import axial_layouts as slot
from torsio.solvers.axial_kernel import march
from torsio.solvers.axial_run_setup import BitRotation, RunOptions, RunSetup, run_setup
from torsio.solvers.axial_step_rule import DEFAULT_STEPS_PER_PERIOD
from torsio.solvers.axial_wave_setup import WaveRunSetup, wave_chunk, wave_run_setup
from torsio.solvers.run_chunks import run_in_chunks
from torsio.solvers.set_speed import table_at
from torsio.units import RPM_TO_RAD_S, as_rpm, as_si

if TYPE_CHECKING:
    from torsio.analysis.transient_results import TransientResults

__all__ = ["run_top_boundary", "simulate_axial"]


def _chain_chunk(
    setup: RunSetup, settings: NDArray, stats: NDArray, samples: NDArray[np.float64]
) -> None:
    """One call of the lumped loop on ``setup`` with ``settings`` (its steps ``FIRST_STEP``
    .. ``STEPS`` - 1), adding to ``stats`` and ``samples``."""
    march(
        setup.bit,
        setup.torsional,
        setup.axial,
        settings,
        setup.theta,
        setup.omega,
        setup.u,
        setup.v,
        setup.history,
        setup.cursor,
        stats,
        samples,
        setup.top.top,
        setup.top_state,
        setup.controller_state,
        setup.top.a,
        setup.top.b,
        setup.top.c,
        setup.top.d,
        setup.top.w,
        setup.top.speed_table,
        setup.contacts,
        setup.contact_stuck,
        setup.law.torque,
        setup.law.slope,
        setup.law.parameters,
    )


def run_kernel(
    setup: RunSetup | WaveRunSetup,
    samples: NDArray[np.float64],
    sample_every: int,
    progress: Any = None,
) -> NDArray:
    """Run the compiled loop of ``setup``, lumped or distributed (its state arrays change),
    in chunks of bounded wall time (:func:`torsio.solvers.run_chunks.run_in_chunks`: a
    signal stops the run between two chunks, within about 0.2 s); the stats vector.
    ``progress(done, total)`` is called after every chunk.

    Raises SolverError when the history could not give the delay.
    """
    settings = setup.settings.copy()
    settings[slot.SAMPLE_EVERY] = sample_every
    stats = np.zeros(len(slot.STATS))
    chunk = wave_chunk if isinstance(setup, WaveRunSetup) else _chain_chunk
    done = [0]

    def advance(count: int) -> bool:
        settings[slot.FIRST_STEP] = done[0]
        settings[slot.STEPS] = done[0] + count
        chunk(setup, settings, stats, samples)  # type: ignore[arg-type]
        done[0] += count
        return bool(stats[slot.FAILED])

    run_in_chunks(setup.steps, advance, progress)
    if isinstance(setup, WaveRunSetup):
        state = [setup.axial_p, setup.torsional_p, setup.bha]
        times = samples[:, slot.TIME]  # the held top: at the set speed of its table
        samples[:, slot.TOP_DRIVE_SPEED] = table_at(setup.speed_table, times, 0.0)[0]
        samples[:, slot.MOTOR_TORQUE] = samples[:, slot.TOP_TORQUE]
        samples[:, slot.SURFACE_TORQUE] = samples[:, slot.TOP_TORQUE]
    else:
        state = [setup.u, setup.theta, setup.top_state]
    if stats[slot.FAILED]:
        done = stats[slot.STEPS_DONE]
        raise SolverError(
            f"the bit's history did not hold the delay at step {int(done)} "
            f"(t = {done * setup.step:.6g} s): non-finite state or a stalled bit"
        )
    if not all(np.isfinite(values).all() for values in state):
        raise SolverError("the run produced non-finite values; try a smaller step")
    return stats


def _top_held_in_stability(boundary: Any, steady: SteadyDrilling) -> bool:
    """Whether the linearization holds a top that the run does not hold (a controller other
    than a PI speed loop: :func:`torsio.axial.linearization.speed_loop`)."""
    if boundary is None or boundary.held:
        return False
    from torsio.axial.linearization import speed_loop

    return speed_loop(boundary, steady.bit_torque, steady.bit_speed) is None


def _steady_friction(setup: RunSetup | WaveRunSetup) -> dict[str, Any] | None:
    """What the string's friction takes in the run's steady state (None without it)."""
    friction = getattr(setup, "friction", None)
    return friction.to_dict() if friction is not None else None


def simulate_axial(
    assembly: LumpedModel | WaveModel,
    bit: AxialBit,
    wob: float,
    rpm: float,
    *,
    duration: float | None = None,
    window: float | None = None,
    start: str = "rest",
    perturbation: float = 1e-3,
    step: float | None = None,
    steps_per_period: int = DEFAULT_STEPS_PER_PERIOD,
    stick_threshold: float = DEFAULT_STICK_THRESHOLD,
    samples: int = 4000,
    bit_rotation: BitRotation | None = None,
    growth_rate: bool | None = None,
    top_drive: Any = None,
    string: Any = None,
    contacts: Any = None,
    progress: Any = None,
) -> TransientResults:
    """Run the assembly drilling at ``wob`` [N] and ``rpm`` [rev/min]: the run's results
    with its axial channels (:class:`~torsio.analysis.axial_results.AxialChannels` in
    ``axial``).

    Parameters
    ----------
    assembly : LumpedModel or WaveModel
        A lumped chain (:mod:`torsio.solvers.axial_kernel`) or a distributed pipe above a lumped
        BHA (:mod:`torsio.solvers.axial_wave_kernel`).
    duration, window : float, optional
        Run length and steady window at its end [s]
        (:func:`torsio.analysis.severity.run_times`).
    start : str
        ``"rest"`` (default) or ``"steady"`` with the bit speed raised by ``perturbation``.
    step, steps_per_period : float, int
        The step rule of :mod:`torsio.solvers.axial_run_setup` (lumped) or
        :mod:`torsio.solvers.axial_wave_setup` (distributed).
    stick_threshold : float
        The bit counts as stuck while |Ω_b| < ``stick_threshold`` Ω₀, as on the torsional
        engines (:data:`~torsio.analysis.severity.DEFAULT_STICK_THRESHOLD`).
    samples : int
        About how many rows of signals to keep (0: none; every step at most).
    bit_rotation : BitRotation, optional
        A prescribed bit rotation instead of the torsional chain (lumped assemblies only).
    growth_rate : bool, optional
        Compute the linear growth rate (any assembly; not with ``bit_rotation``, whose
        torsional chain is not integrated); None (default): unless the chain is too large
        (:func:`torsio.axial.stability.growth_rate_skipped`, then a warning says so). With
        a PI speed loop its top node is in the linearization; with another controller the
        top is held there
        (``stability_of_held_top`` says so).
    top_drive : top drive, optional
        Any registered top drive (:mod:`torsio.physics.top_drives`, plugins; e.g.
        ``PITopDrive(inertia=2900.0, kp=5000.0, ki=1800.0)``) turning the top as a node with
        its controller (:mod:`torsio.physics.axial_top_drive`); None or ``ConstantSpeedTop()``: held
        at Ω₀; ``RecordedTopDrive``: held at the recorded speed, linear between its samples
        (the one set-speed table of every engine, :mod:`torsio.solvers.set_speed`), the
        run's Ω₀ (its steady state, S_SS) the last recorded speed, whatever ``rpm`` says.
        A controller's ``ramp`` raises its set speed from 0. The distributed pipe takes a
        held top only (Ω₀ or a recording).
    string : DrillString, optional
        The drill string the assembly was built from, for tunings that read the top pipe's
        impedance (``soft-torque``, ``z-torque`` defaults).
    contacts : AxialContacts, optional
        Coulomb friction along the string at the chain's nodes, or at the distributed
        pipe's inner nodes nearest their ``depths`` (:mod:`torsio.well.axial_contacts`),
        its normal force rebuilt at ``wob``. The growth rate is then that of the
        linearization with the contacts' damping (:mod:`torsio.axial.steady_friction`;
        the distributed pipe has none with contacts).
    progress : callable, optional
        ``progress(steps_done, steps)`` after every chunk of the run (:func:`run_kernel`).
    """
    wob, rpm = as_si(wob, "force", "wob"), as_rpm(rpm)  # "100 kN", "60 rpm" as in a file
    typical, _ = run_times(assembly, None, None)
    duration, window = run_times(assembly, duration, window)
    options = RunOptions(
        duration, window, start, perturbation, step, steps_per_period,
        default_duration=typical, stick_threshold=stick_threshold,
    )  # fmt: skip
    setup: RunSetup | WaveRunSetup
    kind = getattr(top_drive, "name", "constant-speed") if top_drive is not None else None
    boundary, given_rpm = None, rpm
    if top_drive is not None:
        boundary = run_top_boundary(top_drive, assembly, rpm, string)
        if boundary.speed_table is not None:  # S_SS against the last recorded speed
            rpm = _last_recorded_rpm(boundary)
    torque_law = isinstance(bit, TorqueLawBit)
    if torque_law and growth_rate:
        raise ConfigError("growth_rate", f"{bit.name!r}: {TorqueLawBit.NO_GROWTH_RATE}")
    if not assembly.has_matrices:  # the distributed pipe
        if bit_rotation is not None:
            raise ConfigError(
                "bit_rotation",
                f"{bit_rotation!r} given; a prescribed rotation applies to lumped assemblies "
                "only (expected None with the distributed pipe)",
            )
        if contacts is not None and growth_rate:
            raise ConfigError("growth_rate", f"True given: {NO_PIPE_FRICTION_RATE}")
        setup = wave_run_setup(cast(WaveModel, assembly), bit, wob, rpm, options, contacts,
                               boundary)  # fmt: skip
    else:
        setup = run_setup(
            cast(LumpedModel, assembly), bit, wob, rpm, options, bit_rotation, boundary, contacts
        )
    every = max(1, setup.steps // samples) if samples > 0 else 0
    rows = (setup.steps - 1) // every + 1 if every else 0
    table = np.zeros((rows, len(slot.SAMPLE_COLUMNS)))
    start_energy = stored_energy(setup, 0.0)
    stats = run_kernel(setup, table, every, progress)
    energy = None
    end_energy = stored_energy(setup, setup.steps * setup.step)
    if start_energy is not None and end_energy is not None:
        energy = energy_balance(stats, start_energy, end_energy)
    rate, skipped = None, None  # a prescribed rotation has no growth rate
    if bit_rotation is None and not torque_law:
        skipped = growth_rate_skipped(assembly, contacts) if growth_rate is None else None
        if growth_rate or (growth_rate is None and skipped is None):
            rate = _growth_rate(assembly, bit, wob, rpm, boundary, contacts)
    channels = AxialChannels(
        wob=float(wob),
        rpm=float(rpm),
        steady=setup.steady,
        summary=summarize(stats, setup, bit),
        growth_rate=rate,
        step=setup.step,
        duration=duration,
        window=setup.window_steps * setup.step,
        start=start,
        samples=table,
        stick_threshold=stick_threshold,
        top_drive=kind or "constant-speed",
        has_set_speed=boundary is None
        or (boundary.speed_table is None and bool(np.isfinite(boundary.set_speed))),
        has_top_drive_node=boundary is not None and not boundary.held,
        stability_of_held_top=rate is not None and _top_held_in_stability(boundary, setup.steady),
        energy=energy,
        contact_switches=int(stats[slot.CONTACT_SWITCHES]),
        string_friction_work=float(stats[slot.FRICTION_WORK]),
        string_contacts=contacts.at_wob(wob).describe() if contacts is not None else None,
        steady_friction=_steady_friction(setup),
        solver={"engine": "axial", "method": "fixed-step", "scheme": SCHEME, "step": setup.step},
        model=assembly_description(assembly),
        bit=bit.to_dict(),
    )
    texts = warning_list(
        *run_warnings(channels.summary, bit, energy, stick_threshold),
        skipped,
        past_the_record(top_drive, duration),
        _rpm_of_the_record(given_rpm, rpm),
    )
    if boundary is not None and not boundary.held and channels.window_rows().any():
        in_window = channels.window_rows()
        motor = saturated_motor(
            channels.signal("motor_torque")[in_window],
            boundary.max_torque,
            float(channels.signal("top_speed")[in_window].mean()),
            boundary.set_speed,
        )
        texts = warning_list(motor, *texts)
    return axial_results(channels, texts)


def run_top_boundary(top_drive: Any, assembly: Any, rpm: float, string: Any = None) -> Any:
    """The boundary of ``top_drive`` on ``assembly`` at ``rpm``
    (:func:`torsio.physics.axial_top_drive.top_boundary`). The distributed pipe's top is held (at Ω₀
    or a recorded speed): a top drive with inertia there is a ConfigError naming the kind,
    whatever its tuning would need."""
    from torsio.physics.axial_top_drive import top_boundary

    refusal = ConfigError(
        "top_drive",
        f"{getattr(top_drive, 'name', top_drive)!r} given with the distributed pipe: its "
        "top is held, at Ω₀ or at a recorded speed (expected "
        "top_drive=None, 'constant-speed' or 'recorded', or a lumped assembly for a "
        "top drive with inertia)",
    )
    wave = not assembly.has_matrices
    try:
        boundary = top_boundary(top_drive, assembly, rpm, string)
    except ConfigError:
        if wave:  # e.g. a tuning that reads a chain the pipe is not
            raise refusal from None
        raise
    if wave and not boundary.held:
        raise refusal
    return boundary


def _rpm_of_the_record(given: float, last: float) -> str | None:
    """The warning for a given rpm that a recording's last speed replaced (else None)."""
    if abs(given - last) <= 1e-9 * last:
        return None
    return (
        f"the top follows a recording: the run's steady state and S_SS are at its last speed, "
        f"{last:.6g} rpm, not at the {given:.6g} rpm given"
    )


def _last_recorded_rpm(boundary: Any) -> float:
    """The last speed [rpm] of a top that follows a table (a recording): the run's Ω₀, its
    steady state and S_SS, as on the torsional engines; a ConfigError if it is not turning."""
    last = float(boundary.set_speed)
    if not last > 0.0:
        raise ConfigError(
            "top_drive.recording",
            f"ends at {last / RPM_TO_RAD_S:.6g} rpm: the run's steady state (its delay, S_SS) "
            "is at the last recorded speed; expected a recording that ends turning forward",
        )
    return last / RPM_TO_RAD_S


def _growth_rate(
    assembly: Any, bit: Any, wob: float, rpm: float, boundary: Any, contacts: Any
) -> float:
    """The growth rate of steady drilling: a chain's linearization (with its ``contacts``'
    damping), or a distributed pipe's characteristic equation from its lumped twin's roots
    (its top held)."""
    if assembly.linearizable:  # a lumped chain
        from torsio.axial.stability import drilling_stability

        return drilling_stability(
            assembly, bit, wob, rpm, count=1, top_drive=boundary, contacts=contacts
        ).growth_rate
    from torsio.axial.wave_stability import distributed_stability

    twin = lumped_twin(assembly)
    return distributed_stability(assembly, bit, wob, rpm, twin=twin).growth_rate
