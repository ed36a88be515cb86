"""Axial-torsional transients with the RGD bit on the compiled engine.

:func:`simulate_axial` runs a :class:`~torsio.axial.assembly.DrillingAssembly` drilling
with an :class:`~torsio.axial.rgd.RGDBit` under the weight W₀ with the top turning at Ω₀,
from rest or from the steady state (:mod:`torsio.axial.run_setup`), with the fixed-step
scheme of :mod:`torsio.axial.kernel`, and returns :class:`AxialTransient`: the window's
S_SS, axial severity, stuck and off-bottom fractions, mean ROP and MSE, the bit's
signals, and the growth rate of the linearization of steady drilling
(:func:`torsio.axial.stability.drilling_stability`; not with a prescribed bit rotation).
A law of the torque alone (:mod:`torsio.axial.torque_law`: Tucker-Wang, a plugin's) runs on
a lumped chain the same way, resting axially on the rock, and has no growth rate here.

Default run length and window as torsio's other runs
(:func:`torsio.analysis.severity.run_times`): 40 and 15 periods of the first torsional
mode, top held (the assembly's ``first_frequency()``).

Examples
--------
>>> from torsio.axial.assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> run = simulate_axial(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=2.0,
...                      window=1.0, start="steady", perturbation=0.0)
>>> round(run.rop_mean / run.steady.rop, 12), run.stick_fraction
(1.0, 0.0)
>>> sorted(run.to_dict())[:3]
['axial_severity', 'bit_speed_max', 'bit_speed_min']
>>> run.string_friction_work, run.contact_switches  # no [well]: no contact along the string
(0.0, 0)
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.analysis.limits import saturated_motor, warning_list
from torsio.analysis.severity import run_times
from torsio.axial import layouts as slot
from torsio.axial.assembly import DrillingAssembly
from torsio.axial.energy_balance import EnergyBalance, chain_energy, energy_balance
from torsio.axial.kernel import march
from torsio.axial.run_setup import BitRotation, RunOptions, RunSetup, run_setup
from torsio.axial.run_warnings import run_warnings
from torsio.axial.stability import NO_PIPE_FRICTION_RATE, growth_rate_skipped
from torsio.axial.steady import SteadyDrilling
from torsio.axial.step_rule import DEFAULT_STEPS_PER_PERIOD
from torsio.axial.torque_law import AxialBit, TorqueLawBit
from torsio.axial.wave_assembly import WaveDrillingAssembly
from torsio.axial.wave_setup import WaveRunSetup, wave_chunk, wave_run_setup
from torsio.axial.window_summary import WindowSummary, summarize
from torsio.errors import ConfigError, SolverError
from torsio.solvers.run_chunks import run_in_chunks
from torsio.units import as_rpm, as_si

__all__ = ["AxialTransient", "simulate_axial"]


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
        samples[:, slot.TOP_DRIVE_SPEED] = setup.steady.bit_speed  # held at Ω₀
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


_SUMMARY_NAMES = frozenset(attrs.fields_dict(WindowSummary))


@attrs.frozen(eq=False)
class AxialTransient:
    """One axial-torsional run with the RGD bit.

    Attributes
    ----------
    wob, rpm : float
        W₀ [N] and Ω₀ [rev/min].
    steady : SteadyDrilling
        The steady drilling state of (W₀, Ω₀).
    summary : WindowSummary
        The window's outputs (also as attributes: ``severity``, ``rop_mean`` ...).
    growth_rate : float or None
        The rightmost root's real part [1/s] of the linearization about the steady state
        (a distributed pipe's from its exact characteristic equation,
        :func:`torsio.axial.wave_stability.distributed_stability`; None with a prescribed
        bit rotation or when not asked).
    step, duration, window : float
        The step h, the run's length and its window [s].
    start : str
        ``"rest"`` or ``"steady"``.
    samples : ndarray (k, 13)
        The bit's and the top drive's signals, columns
        :data:`torsio.axial.layouts.SAMPLE_COLUMNS`.
    top_drive : str
        The top drive's kind (``"constant-speed"``: the top held at Ω₀).
    stability_of_held_top : bool
        Whether ``growth_rate`` is that of the top held at Ω₀ while the run's top drive is
        not held: a controller other than a PI speed loop, which the linearization does not
        take (:func:`torsio.axial.linearization.speed_loop`).
    warnings : tuple of str
        What limits the meaning of the run, as the torsional runs say it: a top drive at its
        torque limit or short of its set speed over the window
        (:func:`torsio.analysis.limits.saturated_motor`), and a window or an energy balance
        that describe no drilling (:func:`torsio.axial.run_warnings.run_warnings`).
    energy : EnergyBalance or None
        The lumped chain's energy balance over the run
        (:mod:`torsio.axial.energy_balance`; None for the distributed pipe and a prescribed
        rotation).
    contact_switches : int
        Stick ↔ slip switches of the string's contacts over the run (0 without them).
    string_friction_work : float
        The work of the friction along the string over the run [J] (0 without it).
    string_contacts, steady_friction : dict or None
        The contacts' totals (:meth:`~torsio.axial.string_contacts.AxialContacts.describe`)
        and what they take in steady drilling
        (:meth:`~torsio.axial.steady_friction.SteadyFriction.to_dict`); None without them.
    """

    wob: float
    rpm: float
    steady: SteadyDrilling
    summary: WindowSummary
    growth_rate: float | None
    step: float
    duration: float
    window: float
    start: str
    samples: NDArray[np.float64]
    top_drive: str = "constant-speed"
    stability_of_held_top: bool = False
    warnings: tuple[str, ...] = ()
    energy: EnergyBalance | None = None
    contact_switches: int = 0
    string_friction_work: float = 0.0
    string_contacts: dict[str, Any] | None = None
    steady_friction: dict[str, Any] | None = None

    def __getattr__(self, name: str) -> Any:
        if name in _SUMMARY_NAMES:
            return getattr(self.summary, name)
        raise AttributeError(name)

    def signal(self, name: str) -> NDArray[np.float64]:
        """One column of :attr:`samples` by name (e.g. ``"bit_speed"``)."""
        return self.samples[:, slot.SAMPLE_COLUMNS.index(name)]

    def window_rows(self) -> NDArray[np.bool_]:
        """The sample rows inside the steady window."""
        return self.signal("time") >= self.duration - self.window - 0.5 * self.step

    def top_drive_summary(self) -> dict[str, float | None]:
        """The top drive over the window's samples: ``top_speed_mean`` [rad/s],
        ``surface_torque_min``, ``surface_torque_max``, ``mean_surface_torque``,
        ``mean_motor_torque`` [N m] (window), ``surface_torque_peak`` [N m] (whole run);
        null without samples."""
        keys = ("top_speed_mean", "surface_torque_min", "surface_torque_max",
                "mean_surface_torque", "mean_motor_torque", "surface_torque_peak")  # fmt: skip
        rows = self.window_rows() if self.samples.shape[0] else np.zeros(0, bool)
        if not rows.any():
            return dict.fromkeys(keys)
        surface = self.signal("surface_torque")
        values = (
            self.signal("top_speed")[rows].mean(),
            surface[rows].min(),
            surface[rows].max(),
            surface[rows].mean(),
            self.signal("motor_torque")[rows].mean(),
            surface.max(),
        )
        return {key: float(value) for key, value in zip(keys, values, strict=True)}

    def to_dict(self) -> dict[str, Any]:
        """DESIGN.md's JSON keys: ``wob``, ``rpm``, ``severity``, ``rop_mean`` (m/s),
        ``mse_mean`` (Pa; null when the bit did not advance), ``off_bottom_fraction``,
        ``stick_fraction``, ``axial_severity``, ``steady_state``, ``growth_rate``, the top
        drive's (:meth:`top_drive_summary`, ``top_drive``, ``stability_of_held_top``) and
        more."""
        data: dict[str, Any] = {"wob": self.wob, "rpm": self.rpm}
        for key, value in attrs.asdict(self.summary).items():
            data[key] = value if math.isfinite(value) else None
        data.update(self.top_drive_summary())
        data.update(
            steady_state=self.steady.to_dict(),
            growth_rate=self.growth_rate,
            step=self.step,
            duration=self.duration,
            steady_window=self.window,
            start=self.start,
            top_drive=self.top_drive,
            stability_of_held_top=self.stability_of_held_top,
            warnings=list(self.warnings),
            string_friction_work=self.string_friction_work,
            contact_switches=self.contact_switches,
            string_contacts=self.string_contacts,
            steady_friction=self.steady_friction,
            energy_balance=self.energy.to_dict() if self.energy is not None else None,
        )
        return data

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"AxialTransient(wob={self.wob:g} N, rpm={self.rpm:g}, S_SS={s.severity:.4g}, "
            f"stuck={s.stick_fraction:.3g}, rop={s.rop_mean * 3600:.4g} m/h)"
        )


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


def _stored_energy(setup: RunSetup | WaveRunSetup, time: float) -> float | None:
    """The lumped chain's kinetic and spring energy [J] at ``time`` [s] of its state (None:
    the distributed pipe, or a prescribed bit rotation)."""
    if not isinstance(setup, RunSetup) or setup.settings[slot.PRESCRIBED]:
        return None
    settings = setup.settings
    held = setup.top.top[slot.TOP_HELD] != 0.0
    top_angle = settings[slot.TOP_SPEED] * time if held else float(setup.top_state[0])
    hook = None
    if settings[slot.SPEED_HOOK]:
        hook = settings[slot.HOOK_START] + settings[slot.HOOK_SPEED] * time
    return chain_energy(
        setup.torsional, setup.axial, setup.theta, setup.omega, setup.u, setup.v, top_angle, hook
    )


def simulate_axial(
    assembly: DrillingAssembly | WaveDrillingAssembly,
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
    samples: int = 4000,
    bit_rotation: BitRotation | None = None,
    growth_rate: bool | None = None,
    top_drive: Any = None,
    string: Any = None,
    contacts: Any = None,
) -> AxialTransient:
    """Run the assembly drilling at ``wob`` [N] and ``rpm`` [rev/min].

    Parameters
    ----------
    assembly : DrillingAssembly or WaveDrillingAssembly
        A lumped chain (:mod:`torsio.axial.kernel`) or a distributed pipe above a lumped
        BHA (:mod:`torsio.axial.wave_kernel`).
    duration, window : float, optional
        Run length and steady window at its end [s]
        (:func:`torsio.analysis.severity.run_times`).
    start : str
        ``"rest"`` (default) or ``"steady"`` with the bit speed raised by ``perturbation``.
    step, steps_per_period : float, int
        The step rule of :mod:`torsio.axial.run_setup` (lumped) or
        :mod:`torsio.axial.wave_setup` (distributed).
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
        its controller (:mod:`torsio.axial.top_drive`); None or ``ConstantSpeedTop()``: held
        at Ω₀. Lumped assemblies only.
    string : DrillString, optional
        The drill string the assembly was built from, for tunings that read the top pipe's
        impedance (``soft-torque``, ``z-torque`` defaults).
    contacts : AxialContacts, optional
        Coulomb friction along the string at the chain's nodes, or at the distributed
        pipe's inner nodes nearest their ``depths`` (:mod:`torsio.axial.string_contacts`),
        its normal force rebuilt at ``wob``. The growth rate is then that of the
        linearization with the contacts' damping (:mod:`torsio.axial.steady_friction`;
        the distributed pipe has none with contacts).
    """
    wob, rpm = as_si(wob, "force", "wob"), as_rpm(rpm)  # "100 kN", "60 rpm" as in a file
    typical, _ = run_times(assembly, None, None)
    duration, window = run_times(assembly, duration, window)
    options = RunOptions(
        duration, window, start, perturbation, step, steps_per_period, default_duration=typical
    )
    setup: RunSetup | WaveRunSetup
    kind = getattr(top_drive, "name", "constant-speed") if top_drive is not None else None
    boundary = None
    held = top_drive is None or getattr(top_drive, "name", None) == "constant-speed"
    if not held and isinstance(assembly, WaveDrillingAssembly):
        raise ConfigError(
            "top_drive",
            f"{kind!r} given with a WaveDrillingAssembly: the distributed pipe's top is held "
            "at Ω₀ (expected top_drive=None, or a lumped DrillingAssembly)",
        )
    if top_drive is not None and isinstance(assembly, DrillingAssembly):
        from torsio.axial.top_drive import top_boundary

        boundary = top_boundary(top_drive, assembly, rpm, string)
    torque_law = isinstance(bit, TorqueLawBit)
    if torque_law and growth_rate:
        raise ConfigError("growth_rate", f"{bit.name!r}: {TorqueLawBit.NO_GROWTH_RATE}")
    if isinstance(assembly, WaveDrillingAssembly):
        if bit_rotation is not None:
            raise ConfigError(
                "bit_rotation",
                f"{bit_rotation!r} given; a prescribed rotation applies to lumped assemblies "
                "only (expected None with a WaveDrillingAssembly)",
            )
        if contacts is not None and growth_rate:
            raise ConfigError("growth_rate", f"True given: {NO_PIPE_FRICTION_RATE}")
        setup = wave_run_setup(assembly, bit, wob, rpm, options, contacts)
    else:
        setup = run_setup(assembly, bit, wob, rpm, options, bit_rotation, boundary, contacts)
    every = max(1, setup.steps // samples) if samples > 0 else 0
    rows = (setup.steps - 1) // every + 1 if every else 0
    table = np.zeros((rows, len(slot.SAMPLE_COLUMNS)))
    start_energy = _stored_energy(setup, 0.0)
    stats = run_kernel(setup, table, every)
    energy = None
    end_energy = _stored_energy(setup, setup.steps * setup.step)
    if start_energy is not None and end_energy is not None:
        energy = energy_balance(stats, start_energy, end_energy)
    rate, skipped = None, None  # a prescribed rotation has no growth rate
    if bit_rotation is None and not torque_law:
        skipped = growth_rate_skipped(assembly, contacts) if growth_rate is None else None
        if growth_rate or (growth_rate is None and skipped is None):
            rate = _growth_rate(assembly, bit, wob, rpm, boundary, contacts)
    result = AxialTransient(
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
        top_drive=kind or "constant-speed",
        stability_of_held_top=rate is not None and _top_held_in_stability(boundary, setup.steady),
        energy=energy,
        contact_switches=int(stats[slot.CONTACT_SWITCHES]),
        string_friction_work=float(stats[slot.FRICTION_WORK]),
        string_contacts=contacts.at_wob(wob).describe() if contacts is not None else None,
        steady_friction=_steady_friction(setup),
    )
    texts = warning_list(*run_warnings(result.summary, bit, energy), skipped)
    if boundary is not None and not boundary.held and result.window_rows().any():
        in_window = result.window_rows()
        motor = saturated_motor(
            result.signal("motor_torque")[in_window],
            boundary.max_torque,
            float(result.signal("top_speed")[in_window].mean()),
            boundary.set_speed,
        )
        texts = warning_list(motor, *texts)
    return attrs.evolve(result, warnings=texts)


def _growth_rate(
    assembly: Any, bit: Any, wob: float, rpm: float, boundary: Any, contacts: Any
) -> float:
    """The growth rate of steady drilling: a chain's linearization (with its ``contacts``'
    damping), or a distributed pipe's characteristic equation from its lumped twin's roots
    (its top held)."""
    if isinstance(assembly, DrillingAssembly):
        from torsio.axial.stability import drilling_stability

        return drilling_stability(
            assembly, bit, wob, rpm, count=1, top_drive=boundary, contacts=contacts
        ).growth_rate
    from torsio.axial.wave_stability import distributed_stability

    twin = assembly.lumped_twin()
    return distributed_stability(assembly, bit, wob, rpm, twin=twin).growth_rate
