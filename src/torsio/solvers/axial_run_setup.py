"""What one run of :mod:`torsio.solvers.axial_kernel` needs: the step, the initial state, the
history before t = 0, and the summary of the window it returns.

**Step rule.** h_max = 2π / (ω_fast × ``steps_per_period``), ω_fast the largest of the
bit's axial contact frequency √(2 n ζ ε a / m_b) (where the axial roots cross the
imaginary axis, docs/axial.md) and the chain's node frequencies; a given ``step`` caps it
further. The bound δ of the dampers' rates caps it at h δ <= :data:`DAMPER_STEP`
(:mod:`torsio.solvers.axial_step_rule`; fine elements with β dampers: δ = β ω² outgrows ω, and the
explicit dampers would diverge). h = t_n0 / ⌈t_n0 / h_max⌉: a whole number of steps per
steady delay t_n0 = 2π/(n Ω₀). With a top drive that is not held, ω_fast also counts the largest
|λ| of the top node and its controller against the string's top spring
(:func:`torsio.physics.axial_top_drive.top_drive_rates`), and a step with |λ| h above
:data:`TOP_DRIVE_STEP_LIMIT` is refused (``simulation.step``).

**Starts.** ``"steady"``: the steady drilling state (each spring carrying T₀ and W₀, every
node at Ω₀ and V₀, the history the steady motion), the bit speed raised by
``perturbation`` (relative; with a prescribed rotation the bit's axial velocity is raised
instead). ``"rest"``: every node at rest, the torsional springs untwisted, the axial
springs carrying W₀, the hole's bottom flat (U before t = 0 at U(0)), the top turning at
Ω₀ from t = 0.

**A law of the torque alone** (:class:`~torsio.physics.torque_law_bit.TorqueLawBit`): the steady
state turns at Ω₀ under the law's torque at W₀ and rests axially; the rock's surface is the
bit's position at t = 0, and no axial contact frequency enters the step rule; the law's
rate at rest, its slope at zero speed over the bit's inertia
(:meth:`~torsio.physics.torque_law_bit.TorqueLawBit.rate`), counts in ω_fast like a frequency:
``steps_per_period`` steps per 2π over it.

Examples
--------
>>> from torsio.model.axial_assembly import rgd_two_dof_example
>>> from torsio.axial.rgd import rgd_example
>>> setup = run_setup(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, RunOptions(10.0, 5.0))
>>> round(setup.step * 1e3, 6), setup.steps  # ms; 0.25 s / 129 steps
(1.937984, 5160)
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.analysis.severity import DEFAULT_STICK_THRESHOLD, check_window
from torsio.axial.steady import SteadyDrilling
from torsio.axial.steady_friction import steady_loads, steady_with_friction
from torsio.errors import ConfigError
from torsio.model.axial_assembly import (
    axial_kernel_rows,
    fastest_damping_rate,
    fastest_frequency,
    require_axial,
    steady_angles,
    steady_positions,
    torsional_kernel_rows,
)
from torsio.model.lumped import LumpedModel
from torsio.physics.axial_top_drive import TopDriveArrays, top_drive_rates
from torsio.physics.top_drive_boundary import TopDriveBoundary
from torsio.physics.torque_law_bit import AxialBit, TorqueLawBit, law_functions, steady_state
from torsio.solvers import axial_layouts as slot
from torsio.solvers.axial_run_budget import check_run_work
from torsio.solvers.axial_step_rule import DAMPER_STEP, DEFAULT_STEPS_PER_PERIOD, contact_frequency
from torsio.well.axial_contacts import AxialContacts, contact_rows

__all__ = [
    "BitRotation",
    "BitStart",
    "KernelSetup",
    "RunOptions",
    "RunSetup",
    "bit_law_row",
    "check_set_speed",
    "kernel_setup",
    "past_times",
    "run_settings",
    "run_setup",
    "start_history",
]


STARTS = ("rest", "steady")

TOP_DRIVE_STEP_LIMIT = 1.0
"""Largest |λ| h of the top drive's rates (:func:`torsio.physics.axial_top_drive.top_drive_rates`)
the explicit step takes: well inside the stability bound 2 of explicit and symplectic Euler
(a real rate and an oscillation alike)."""


@attrs.frozen
class BitRotation:
    """A prescribed bit rotation Ω(t) = Ω₀ (1 + A sin(f t)), Φ(t) = Ω₀ (t + A (1 − cos f t)/f).

    The torsional chain is then not integrated: the axial motion runs under the bit turning
    as given (A = 0: the axial model of Richard et al. 2004). ``amplitude`` A in [0, 1),
    ``frequency`` f [rad/s] > 0.
    """

    amplitude: float = attrs.field(default=0.0, converter=float)
    frequency: float = attrs.field(default=1.0, converter=float)

    def __attrs_post_init__(self) -> None:
        if not 0.0 <= self.amplitude < 1.0:
            raise ConfigError("bit_rotation.amplitude", f"{self.amplitude!r} must be in [0, 1)")
        if not (math.isfinite(self.frequency) and self.frequency > 0):
            raise ConfigError("bit_rotation.frequency", f"{self.frequency!r} must be > 0 rad/s")

    def angle(self, speed: float, t: NDArray | float) -> Any:
        """Φ(t) [rad] for the mean speed Ω₀ [rad/s]."""
        a, f = self.amplitude, self.frequency
        return speed * (t + a * (1.0 - np.cos(f * t)) / f)

    def speed(self, speed: float, t: NDArray | float) -> Any:
        """Ω(t) [rad/s] for the mean speed Ω₀ [rad/s]."""
        return speed * (1.0 + self.amplitude * np.sin(self.frequency * t))


@attrs.frozen
class BitStart:
    """The bit's state at t = 0, where the history before it ends (:func:`kernel_setup`):
    its angle Φ_b [rad] and position U_b [m] (the state's own: positions relative to the
    bit), its own speed Ω_b [rad/s] and axial velocity V_b [m/s] (raised by the
    perturbation on the steady start), and the prescribed ``rotation`` the angle and speed
    before t = 0 follow (None: turning steadily at Ω₀)."""

    angle: float
    position: float
    speed: float
    velocity: float
    rotation: BitRotation | None = None


@attrs.frozen
class RunOptions:
    """How a run is set up, lumped (:func:`run_setup`) or distributed
    (:func:`torsio.solvers.axial_wave_setup.wave_run_setup`): its length ``duration`` and the
    ``window`` at its end [s], its ``start`` (:data:`STARTS`; on the steady start the bit's
    speed raised by ``perturbation``, relative), its step rule (``steps_per_period``, a
    given ``step`` [s] capping h; see the module docstring) and the ``stick_threshold``
    (the bit stuck while |Ω_b| < stick_threshold Ω₀, as on every engine:
    :data:`torsio.analysis.severity.DEFAULT_STICK_THRESHOLD`). :meth:`check` validates them.
    ``default_duration`` [s] is the run length torsio would choose for the model (None: not
    known): :func:`torsio.solvers.axial_run_budget.check_run_work` tells by it a long run from a
    fast
    model.
    """

    duration: float
    window: float
    start: str = "rest"
    perturbation: float = 1e-3
    step: float | None = None
    steps_per_period: int = DEFAULT_STEPS_PER_PERIOD
    default_duration: float | None = None
    stick_threshold: float = DEFAULT_STICK_THRESHOLD

    def check(self) -> None:
        """A ConfigError unless ``start`` is one of :data:`STARTS`, -1 < perturbation < 1 and
        0 < window <= duration (:func:`torsio.analysis.severity.check_window`)."""
        if self.start not in STARTS:
            raise ConfigError(
                "simulation.start", f"{self.start!r} is not one of {', '.join(STARTS)}"
            )
        if not (-1 < self.perturbation < 1):
            raise ConfigError(
                "simulation.perturbation",
                f"{self.perturbation!r}: the relative raise of the bit speed over Ω₀ on the "
                "steady start; expected -1 < perturbation < 1 (1 already doubles the speed: "
                "no longer a perturbation of steady drilling)",
            )
        check_window(self.duration, self.window)
        if not 0 < self.stick_threshold < math.inf:
            raise ConfigError(
                "simulation.stick_threshold",
                f"{self.stick_threshold!r}: expected a positive fraction of Ω₀",
            )

    def largest_step(self, bit: AxialBit, mass: float, fastest: float) -> float:
        """h_max = 2π/(ω_fast × ``steps_per_period``) [s], ω_fast the larger of the bit's
        contact frequency on the ``mass`` [kg] (:func:`contact_frequency`) and ``fastest``
        [rad/s], capped by a given ``step``."""
        fastest = max(contact_frequency(bit, mass), fastest)
        h_max = 2 * math.pi / (fastest * self.steps_per_period)
        if self.step is not None:
            if not (math.isfinite(self.step) and self.step > 0):
                raise ConfigError("step", f"{self.step!r} must be a positive time step in s")
            h_max = min(h_max, self.step)
        return h_max

    def step_counts(self, step: float) -> tuple[int, int]:
        """(steps of the run, steps of its window) on the step h = ``step`` [s]."""
        steps = int(math.ceil(self.duration / step - 1e-9))
        return steps, min(steps, int(round(self.window / step)))


@attrs.frozen(eq=False)
class KernelSetup:
    """What a run of either axial kernel starts from (:class:`RunSetup` of the lumped chain,
    :class:`~torsio.solvers.axial_wave_setup.WaveRunSetup` of the distributed pipe): the steady
    state, the step h [s], the steps of the run and of its window, the bit law's row
    (:func:`bit_law_row`), the ``settings`` and the bit's history with its cursor
    (:func:`start_history`); both setups build it with :func:`kernel_setup`."""

    steady: SteadyDrilling
    step: float
    steps: int
    window_steps: int
    bit: NDArray[np.float64]
    settings: NDArray[np.float64]
    history: NDArray[np.float64]
    cursor: NDArray[np.float64]


@attrs.frozen(eq=False)
class RunSetup(KernelSetup):
    """The lumped kernel's arrays for one run (:func:`torsio.solvers.axial_kernel.march`): those of
    every run (:class:`KernelSetup`), the chain's rows and its state, the string contacts'
    rows and states, and ``friction`` their steady part
    (:class:`~torsio.axial.steady_friction.SteadyFriction`; None without contacts)."""

    torsional: NDArray[np.float64]
    axial: NDArray[np.float64]
    theta: NDArray[np.float64]
    omega: NDArray[np.float64]
    u: NDArray[np.float64]
    v: NDArray[np.float64]
    top: TopDriveArrays = attrs.field(factory=lambda: TopDriveArrays.from_boundary(None, 0.0))
    top_state: NDArray[np.float64] = attrs.field(factory=lambda: np.zeros(len(slot.TOP_NODE)))
    controller_state: NDArray[np.float64] = attrs.field(factory=lambda: np.zeros(0))
    contacts: NDArray[np.float64] = attrs.field(factory=lambda: np.zeros((3, 0)))
    contact_stuck: NDArray[np.float64] = attrs.field(factory=lambda: np.zeros(0))
    friction: Any = None
    law: Any = None
    """The law's compiled torque and slope (:func:`torsio.physics.torque_law_bit.law_functions`)."""


def check_set_speed(
    top_drive: TopDriveBoundary | None, options: RunOptions, bit_rotation: Any = None
) -> None:
    """Refuse what a top drive's boundary cannot run with (ConfigError by key): a prescribed
    ``bit_rotation`` with a top that is not held at a constant speed (no chain to turn), a
    steady start under a set speed that changes in time (a start-up starts from rest)."""
    if top_drive is None:
        return
    if bit_rotation is not None and (not top_drive.held or top_drive.varying):
        raise ConfigError(
            "top_drive",
            "a prescribed bit_rotation does not integrate the torsional chain, so it takes no "
            "top drive (expected top_drive=None or a top held at a constant speed)",
        )
    if top_drive.varying and options.start == "steady":
        raise ConfigError(
            "simulation.start",
            "'steady' starts the string in steady drilling at Ω₀, but the top drive's set "
            "speed changes in time from t = 0 (a ramp, a recording): a start-up starts from "
            "rest (expected start = 'rest')",
        )


def past_times(step: float, delay: float) -> NDArray[np.float64]:
    """The history's times before t = 0 [s]: over 1.5 steady delays and 4 steps, to 0."""
    past = int(math.ceil(1.5 * delay / step)) + 4
    return step * np.arange(-past, 1, dtype=float)


def start_history(
    times: NDArray[np.float64],
    angle: NDArray[np.float64],
    speed: NDArray[np.float64],
    position: NDArray[np.float64],
    velocity: float,
    bit_speed: float,
    bit_velocity: float,
    steps: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(history, cursor) of :mod:`torsio.axial.history` holding the bit's motion at the
    ``times`` up to 0 (Φ, Ω, U arrays, V constant), room for ``steps`` more, and the
    bit's own Ω_b, V_b at t = 0."""
    past = times.size - 1
    history = np.zeros((5, steps + past + 2))
    history[0, : past + 1] = times
    history[1, : past + 1] = angle
    history[2, : past + 1] = speed
    history[3, : past + 1] = position
    history[4, : past + 1] = velocity
    history[2, past], history[4, past] = bit_speed, bit_velocity
    return history, np.array([0.0, past + 1.0])


def bit_law_row(bit: AxialBit) -> NDArray[np.float64]:
    """The kernels' bit row [ζ ε a, ε a²/2, σ a l, μ γ a/2, 2π/n, n, 0, a]
    (:data:`torsio.solvers.axial_layouts.BIT_ROW`; a law of the torque alone's:
    :meth:`~torsio.physics.torque_law_bit.TorqueLawBit.row`)."""
    if isinstance(bit, TorqueLawBit):
        return bit.row()
    row = np.zeros(len(slot.BIT_ROW))
    row[slot.CUTTING_WEIGHT_PER_DEPTH] = bit.cutting_weight_per_depth
    row[slot.CUTTING_TORQUE_PER_DEPTH] = bit.cutting_torque_per_depth
    row[slot.FRICTION_WEIGHT] = bit.friction_weight
    row[slot.FRICTION_TORQUE_PER_WEIGHT] = bit.contact_friction * bit.bit_geometry * bit.radius / 2
    row[slot.ANGLE_PER_BLADE] = 2 * math.pi / bit.blades
    row[slot.BLADES] = float(bit.blades)
    row[slot.BIT_RADIUS] = bit.radius
    return row


def run_settings(
    size: int, steady: SteadyDrilling, step: float, steps: int, window_steps: int, hook: str
) -> NDArray[np.float64]:
    """A kernel's ``settings`` of ``size`` entries with the head both kernels share filled in
    (:data:`torsio.solvers.axial_layouts.RUN_SETTINGS`: the step h [s], the steps, Ω₀ and W₀ of
    ``steady``, the ``hook`` and its speed V₀ when it is ``"speed"``, the window of the last
    ``window_steps``), the rest 0 (the stick speed: :func:`kernel_setup`)."""
    settings = np.zeros(size)
    settings[slot.STEP], settings[slot.STEPS] = step, steps
    settings[slot.TOP_SPEED], settings[slot.HOOK_WEIGHT] = steady.bit_speed, steady.wob
    speed_hook = hook == "speed"
    settings[slot.SPEED_HOOK] = 1.0 if speed_hook else 0.0
    settings[slot.HOOK_SPEED] = steady.rop if speed_hook else 0.0
    settings[slot.WINDOW_START] = steps - window_steps
    return settings


def kernel_setup(
    steady: SteadyDrilling,
    bit: AxialBit,
    step: float,
    options: RunOptions,
    settings_size: int,
    hook: str,
    bit_start: BitStart,
) -> KernelSetup:
    """What every run starts from (:class:`KernelSetup`) on the step h = ``step`` [s]: the
    step counts of ``options``, the bit law's row, the head of the ``settings_size``
    settings (:func:`run_settings`), and the history of the bit's motion before t = 0 that
    ends at ``bit_start``: turning at Ω₀ (or as its prescribed rotation) and moving at V₀ on
    the steady start, at rest axially on the rest start (the hole's bottom flat)."""
    steps, window_steps = options.step_counts(step)
    omega0 = steady.bit_speed
    velocity = steady.rop if options.start == "steady" else 0.0
    times = past_times(step, steady.delay)
    rotation = bit_start.rotation
    if rotation is not None:
        angle, speed = rotation.angle(omega0, times), rotation.speed(omega0, times)
    else:
        angle, speed = bit_start.angle + omega0 * times, np.full(times.size, omega0)
    settings = run_settings(settings_size, steady, step, steps, window_steps, hook)
    settings[slot.STICK_SPEED] = options.stick_threshold * omega0  # |Ω_b| below it: stuck
    history, cursor = start_history(
        times,
        angle,
        speed,
        bit_start.position + velocity * times,
        velocity,
        bit_start.speed,
        bit_start.velocity,
        steps,
    )
    return KernelSetup(
        steady=steady,
        step=step,
        steps=steps,
        window_steps=window_steps,
        bit=bit_law_row(bit),
        settings=settings,
        history=history,
        cursor=cursor,
    )


def run_setup(
    assembly: LumpedModel,
    bit: AxialBit,
    wob: float,
    rpm: float,
    options: RunOptions,
    bit_rotation: BitRotation | None = None,
    top_drive: TopDriveBoundary | None = None,
    contacts: AxialContacts | None = None,
) -> RunSetup:
    """The step, the initial state and the history of a run (see the module docstring) at
    ``wob`` [N] and ``rpm`` [rev/min], set up as ``options`` say, the bit turning as
    ``bit_rotation`` prescribes when given; ``top_drive`` the top's boundary
    (:func:`torsio.physics.axial_top_drive.top_boundary`; None: held at Ω₀). A top drive that is not
    held starts with the string: from rest (angle, speed and controller states zero) or on
    the steady state (at Ω₀, the controller state of ``TopDriveBoundary.steady_states``).
    ``contacts``: the string's contacts with the borehole
    (:mod:`torsio.well.axial_contacts`; their normal force at ``wob``), the steady state
    then that of :mod:`torsio.axial.steady_friction` (``wob`` the hook's weight under the
    weight hook).
    """
    options.check()
    axial = require_axial(assembly)
    hook_force = float(wob)
    if isinstance(bit, TorqueLawBit) and (bit_rotation is not None or contacts is not None):
        raise ConfigError(
            "bit_rock.law",
            f"{bit.name!r} is a law of the torque alone, whose axial motion rests on the rock: "
            "a prescribed bit_rotation or friction along the string needs the RGD bit "
            "(law = 'rgd'); expected neither",
        )
    if contacts is not None and not isinstance(bit, TorqueLawBit):  # refused above
        if bit_rotation is not None or axial.dofs != assembly.dofs:
            raise ConfigError(
                "well",
                "friction along the string needs every node to turn and move axially "
                "(expected axial springs between the nodes and no prescribed bit_rotation)",
            )
        contacts = contacts.at_wob(wob)
        steady, friction = steady_with_friction(bit, wob, rpm, contacts, axial.hook)
        hook_force = friction.hook_force
        torques, forces = steady_loads(steady, friction)
    else:
        steady = steady_state(bit, wob, rpm)
    delay = steady.delay
    driven = top_drive is not None and not top_drive.held
    check_set_speed(top_drive, options, bit_rotation)
    top_rate = 0.0
    if top_drive is not None and driven:
        rates = top_drive_rates(top_drive, assembly.springs[0], assembly.dampers[0])
        top_rate = float(np.abs(rates).max())
    dampers = 2 * math.pi * fastest_damping_rate(assembly) / options.steps_per_period
    chain_fastest = max(fastest_frequency(assembly), top_rate, dampers / DAMPER_STEP)
    law_rate = bit.rate(wob, assembly.bit_inertia) if isinstance(bit, TorqueLawBit) else 0.0
    fastest = max(chain_fastest, law_rate)
    h_max = options.largest_step(bit, axial.bit_mass, fastest)
    h = delay / math.ceil(delay / h_max - 1e-9)
    if top_rate * h > TOP_DRIVE_STEP_LIMIT:
        raise ConfigError(
            "simulation.step",
            f"a step of {h:.6g} s does not resolve the top drive: its fastest rate "
            f"|λ| = {top_rate:.6g} 1/s (the top node and its controller) needs |λ| h <= "
            f"{TOP_DRIVE_STEP_LIMIT:g}, a step of at most {TOP_DRIVE_STEP_LIMIT / top_rate:.6g} s "
            "(or more steps per period)",
        )
    nodes = assembly.dofs + axial.dofs
    what = "bit_rock" if law_rate > chain_fastest else "chain"
    check_run_work(options, h, delay, nodes, bit, axial.bit_mass, fastest, what)
    omega0, v0 = steady.bit_speed, steady.rop
    if contacts is not None:  # each spring carries the bit's load and the friction below it
        angles, positions = steady_angles(assembly, torques), steady_positions(assembly, forces)
    else:
        angles = steady_angles(assembly, steady.bit_torque)
        positions = steady_positions(assembly, wob)
    on_steady = options.start == "steady"
    if bit_rotation is not None:
        theta, omega = np.zeros(1), np.array([omega0])
    elif on_steady:
        theta, omega = angles.copy(), np.full(assembly.dofs, omega0)
        omega[-1] *= 1.0 + options.perturbation
    else:
        theta, omega = np.zeros(assembly.dofs), np.zeros(assembly.dofs)
    u = positions.copy()
    v = np.full(u.size, v0 if on_steady else 0.0)
    if bit_rotation is not None and on_steady:
        v[-1] *= 1.0 + options.perturbation
    hook_start = 0.0
    if axial.hook == "speed":
        hook_start = u[0] + hook_force / axial.stiffnesses[0]
    bit_start = BitStart(theta[-1], u[-1], omega[-1], v[-1], bit_rotation)
    size = len(slot.CHAIN_SETTINGS)
    kernel = kernel_setup(steady, bit, h, options, size, axial.hook, bit_start)
    rotation = bit_rotation or BitRotation()
    top_state, controller_state = np.zeros(len(slot.TOP_NODE)), np.zeros(0)
    if top_drive is not None and driven:
        controller_state = np.zeros(top_drive.states)
        if on_steady:
            top_state[slot.TOP_NODE_SPEED] = omega0
            surface = steady.bit_torque if contacts is None else friction.surface_torque
            motor = surface + top_drive.drag * omega0  # u = T₀ + drag Ω₀
            controller_state = top_drive.steady_states(surface, motor)
    settings = kernel.settings
    settings[slot.HOOK_START] = hook_start
    settings[slot.HOOK_WEIGHT] = hook_force
    rows = contact_rows(contacts, assembly.dofs)
    settings[slot.THRESHOLD_SPEED] = contacts.threshold_speed if contacts is not None else 0.0
    settings[slot.PRESCRIBED] = 1.0 if bit_rotation is not None else 0.0
    settings[slot.AMPLITUDE], settings[slot.FREQUENCY] = rotation.amplitude, rotation.frequency
    settings[slot.ROCK_SURFACE] = u[-1]
    return RunSetup(
        **attrs.asdict(kernel, recurse=False),
        torsional=torsional_kernel_rows(assembly),
        axial=axial_kernel_rows(assembly),
        theta=theta,
        omega=omega,
        u=u,
        v=v,
        top=TopDriveArrays.from_boundary(top_drive, omega0),
        top_state=top_state,
        controller_state=controller_state,
        contacts=rows,
        contact_stuck=np.full(assembly.dofs, 0.0 if on_steady else 1.0),
        friction=friction if contacts is not None else None,
        law=law_functions(bit),
    )
