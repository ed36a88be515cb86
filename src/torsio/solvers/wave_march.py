"""Running the distributed model: :func:`march` sets up and calls the compiled stepping.

The stepping itself (transport, drag, junctions, top, bit) is in
:mod:`torsio.solvers.characteristics`; this module chooses the engine (the law's
compiled kernel, or plain Python), lays the grid out for it and returns records,
snapshots along the string and energy integrals.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import attrs
import numpy as np

from torsio.errors import SolverError
from torsio.model.wave import WaveModel
from torsio.physics.top_drive_boundary import motor_torque
from torsio.solvers import layouts as slot
from torsio.solvers.characteristics import (
    KernelLayout,
    WaveState,
    _march,
    kernel_layout,
    node_offsets,
    rest_state,
)
from torsio.solvers.run_chunks import run_in_chunks
from torsio.solvers.wave_contacts import contact_arrays, speed_below
from torsio.solvers.wave_top import TopArrays, with_node_damper


class RunCancelled(Exception):
    """Raised by :func:`march` when its ``should_stop`` says so between two chunks."""


@attrs.frozen(eq=False)
class WaveRun:
    """What :func:`march` produced.

    Attributes
    ----------
    time : ndarray
        Record times [s] (multiples of the record step, from 0).
    records : ndarray, shape (len(time), ``RECORD_COLUMNS``)
        :data:`RECORD_CHANNELS` at those times.
    field_time : ndarray
        Times of the speed snapshots [s].
    field : ndarray, shape (len(field_time), nodes)
        Angular speed at every node [rad/s] (state layout, :func:`node_offsets`).
    summary : dict
        ``SUMMARY_FIELDS`` of :mod:`torsio.solvers.layouts` (energies in J over the run),
        plus ``stored_initial`` and ``stored_final`` [J] (:func:`stored_energy`; the
        initial state with a held top already turning), ``steps`` (taken),
        ``ended_on_steady_cycle``, and ``friction_dissipation`` [J] (the contacts' work),
        ``surface_torque_peak`` (the run's largest), ``surface_torque_min``,
        ``surface_torque_max`` (the window's) [N m]
        over every step, ``bit_first_motion`` [s] (first time the bit is faster than the
        contacts' threshold speed; NaN: never, or no contacts).
    state : WaveState
        Final state.
    engine : str
        ``"numba"`` or ``"python"``.
    """

    time: np.ndarray
    records: np.ndarray
    field_time: np.ndarray
    field: np.ndarray
    summary: dict[str, float]
    state: WaveState
    engine: str


def _python_march() -> Any:
    """The stepping as plain Python (for laws without a compiled kernel)."""
    import types

    from torsio.solvers import characteristics

    function = getattr(_march, "py_func", _march)
    solve = getattr(characteristics._solve_bit, "py_func", characteristics._solve_bit)
    namespace = {**vars(characteristics), "_solve_bit": solve}
    namespace["compiled_motor_torque"] = motor_torque
    return types.FunctionType(function.__code__, namespace, function.__name__)


def law_functions(law: Any) -> tuple[Any, Any, np.ndarray, str]:
    """(torque, slope, parameters, engine) of a law: its compiled kernel when it has one.

    Without a kernel (or without numba) the law's Python ``torque`` and ``slope`` (a central
    difference when it has none) are wrapped to the kernel's call convention and the steps
    run as plain Python (slow: about 30 s for a default run of the paper's string).
    """
    try:
        from torsio.solvers.law_kernels import law_kernel
    except ImportError:  # pragma: no cover - older layouts
        kernel = None
    else:
        kernel = law_kernel(law)
    if kernel is not None:
        return kernel.torque, kernel.slope, kernel.parameters, "numba"

    from torsio.physics.law_slope import bit_slope

    def torque(parameters: np.ndarray, speed: float, wob: float, radius: float) -> float:
        return float(law.torque(speed, wob, radius))

    def slope(parameters: np.ndarray, speed: float, wob: float, radius: float) -> float:
        return float(bit_slope(law, speed, wob, radius))  # the law's, or a difference

    return torque, slope, np.zeros(1), "python"


def string_energy(grid: WaveModel, state: WaveState) -> float:
    """Kinetic plus strain energy of the string [J]: sum of (p^2 + m^2) dt / (4 Z), trapezoidal."""
    offsets = node_offsets(grid)
    total = 0.0
    for s, z in enumerate(grid.impedances):
        p = state.p[offsets[s] : offsets[s + 1]]
        m = state.m[offsets[s] : offsets[s + 1]]
        density = p * p + m * m
        total += (density.sum() - 0.5 * (density[0] + density[-1])) * grid.time_step / (4.0 * z)
    return float(total)


def stored_energy(grid: WaveModel, state: WaveState, top: TopArrays) -> float:
    """Energy of the string, the bit and the top drive [J] (kinetic and strain)."""
    energy = string_energy(grid, state) + 0.5 * grid.bit_inertia * state.bit[slot.BIT_SPEED] ** 2
    if not top.held:
        energy += 0.5 * top.inertia * state.top[slot.X_TOP_SPEED] ** 2
    return energy


def _end_damper_power(
    grid: WaveModel, layout: KernelLayout, state: WaveState, top_speed: float
) -> float:
    """Power [W] of the dampers at the top node, the junctions and the bit in ``state``."""
    offsets = node_offsets(grid)
    z = layout.impedances
    bit_speed = state.bit[slot.BIT_SPEED]
    power = layout.end_dampers[0] * top_speed**2 + layout.end_dampers[-1] * bit_speed**2
    for s in range(1, len(grid.cells)):
        node = offsets[s]  # the lower section's first node: speed continuous there
        speed = (state.p[node] - state.m[node]) / (2.0 * z[node])
        power += layout.end_dampers[s] * speed**2
    return float(power)


def march(
    grid: WaveModel,
    top: TopArrays,
    law: Any,
    wob: float,
    radius: float,
    alpha: float,
    steps: int,
    *,
    window_start: int = 0,
    record_every: int = 0,
    field_every: int = 0,
    state: WaveState | None = None,
    kernel: tuple[Any, Any, np.ndarray] | None = None,
    track_energy: bool = True,
    steady_tolerance: float = 0.0,
    cycle_gap: float = 0.0,
    progress: Callable[[int, int], None] | None = None,
    should_stop: Callable[[], bool] | None = None,
) -> WaveRun:
    """Advance the distributed model ``steps`` time steps from ``state`` (default: rest).

    Parameters
    ----------
    grid : WaveModel
    top : TopArrays
        :func:`held_top` or :func:`top_arrays`.
    law : bit-rock law
        Its compiled kernel is used when it has one (``kernel`` overrides it).
    wob, radius : float
        Weight on bit [N], bit radius [m].
    alpha : float
        Distributed drag per unit inertia [1/s] (Rayleigh alpha).
    steps : int
    window_start : int
        First step of the window over which bit-speed extremes are taken.
    record_every, field_every : int
        Record the signals / the speed along the string every so many steps (0: never).
    steady_tolerance : float
        End the run early once the motion is on a steady cycle that could not move S_SS
        by more than this over the steps left (module :mod:`torsio.solvers.characteristics`;
        0: never; a top with a set speed only).
    cycle_gap : float
        Least time [s] between two ends of a cycle for ``steady_tolerance`` (a quarter of
        the first natural period in maps).
    progress : callable, optional
        ``progress(steps_done, steps)`` between chunks (:mod:`torsio.solvers.run_chunks`).
    should_stop : callable, optional
        Asked between chunks; when it returns true the run stops with
        :class:`RunCancelled` (a map's other points after Ctrl-C).

    Notes
    -----
    The compiled steps run in chunks of about 0.2 s of wall time
    (:func:`torsio.solvers.run_chunks.run_in_chunks`), so that Ctrl-C and SIGTERM stop a
    run within that; the state passes from chunk to chunk unchanged, and the result is
    the same to the last bit as that of one call over every step.
    """
    dt = grid.time_step
    if kernel is not None:
        torque, slope, parameters = kernel
        engine = "numba"
    else:
        torque, slope, parameters, engine = law_functions(law)
    layout = kernel_layout(grid, alpha)
    top = with_node_damper(top, float(layout.end_dampers[0]), dt)
    state = rest_state(grid, top) if state is None else state.copy()
    if top.held and state.top.size == 0:
        state = WaveState(state.p, state.m, np.zeros(1), state.bit)
    z_top = float(grid.impedances[0])
    set_speed0 = top.set_speed_at(0.0)  # the set speed's time starts with the run
    if top.held:  # the held top turns at its speed from t = 0 on
        state.p[0] = state.m[0] + 2.0 * z_top * set_speed0
    stored_initial = stored_energy(grid, state, top)
    summary = np.zeros(slot.SUMMARY_SIZE)
    summary[slot.SUM_BIT_SPEED_MIN], summary[slot.SUM_BIT_SPEED_MAX] = math.inf, -math.inf
    summary[slot.SUM_SURFACE_TORQUE_PEAK] = -math.inf
    summary[slot.SUM_SURFACE_TORQUE_MIN] = math.inf
    summary[slot.SUM_SURFACE_TORQUE_MAX] = -math.inf
    contact_index, contacts = contact_arrays(grid)
    threshold = 0.0 if grid.contacts is None else float(grid.contacts.threshold_speed)
    # powers at t = 0 for the trapezoidal energies
    speed0 = state.top[slot.X_TOP_SPEED] if not top.held else set_speed0
    surface0 = state.m[0] + (z_top + layout.end_dampers[0]) * speed0  # with the top node's drag
    if not top.held:  # the motor torque of e = Omega_set - Omega_0, T_pipe = m + Z Omega_0
        gains, x0 = top.coefficients, state.top
        motor0 = float(motor_torque(
            gains[slot.COEF_U0], gains[slot.COEF_KP], gains[slot.COEF_PIPE_GAIN], top.max_torque,
            top.states - slot.X_CONTROLLER, gains[slot.COEF_STATES :], x0[slot.X_CONTROLLER :],
            set_speed0 - speed0, state.m[0] + z_top * speed0,
        )[0])  # fmt: skip
    else:
        motor0 = surface0 + layout.end_dampers[0] * speed0
    w_bit = state.bit[slot.BIT_SPEED]
    powers = summary[slot.SUM_POWERS : slot.SUM_POWERS + slot.POWER_COUNT]
    powers[slot.POWER_IN] = motor0 * speed0
    powers[slot.POWER_BIT] = float(law.torque(w_bit, wob, radius)) * w_bit
    powers[slot.POWER_BIT_DRAG] = alpha * grid.bit_inertia * w_bit * w_bit
    powers[slot.POWER_STRING_DRAG] = _end_damper_power(grid, layout, state, speed0)
    powers[slot.POWER_TOP_DRAG] = top.drag * speed0 * speed0
    rows = steps // record_every + 1 if record_every else 0
    records = np.full((rows, slot.RECORD_COLUMNS), np.nan)
    field = np.full((steps // field_every + 1 if field_every else 0, state.p.size), np.nan)
    if record_every:
        records[0, slot.REC_BIT_SPEED] = w_bit
        records[0, slot.REC_BIT_TORQUE] = float(law.torque(w_bit, wob, radius))
        records[0, slot.REC_SURFACE_TORQUE] = surface0
        records[0, slot.REC_TOP_SPEED] = speed0
        records[0, slot.REC_MOTOR_TORQUE] = motor0
    if field_every:
        field[0] = (state.p - state.m) / (2.0 * layout.impedances)
    reference = top.set_speed if top.held or math.isfinite(top.set_speed) else 0.0
    settings = np.zeros(slot.WAVE_SIZE)
    settings[slot.WAVE_DT] = dt
    settings[slot.WAVE_BIT_INERTIA] = grid.bit_inertia
    settings[slot.WAVE_ALPHA] = alpha
    settings[slot.WAVE_WOB] = wob
    settings[slot.WAVE_BIT_RADIUS] = radius
    settings[slot.WAVE_HELD] = 1.0 if top.held else 0.0
    settings[slot.WAVE_SET_SPEED] = top.set_speed
    settings[slot.WAVE_MAX_TORQUE] = top.max_torque
    settings[slot.WAVE_STEPS] = settings[slot.WAVE_RUN_STEPS] = steps
    settings[slot.WAVE_WINDOW_START] = window_start
    settings[slot.WAVE_RECORD_EVERY] = record_every
    settings[slot.WAVE_FIELD_EVERY] = field_every
    settings[slot.WAVE_TOP_DRAG] = top.drag
    settings[slot.WAVE_TRACK_ENERGY] = 1.0 if track_energy else 0.0
    settings[slot.WAVE_DRAG_SPACING] = grid.drag_spacing
    settings[slot.WAVE_STEADY_TOLERANCE] = steady_tolerance
    settings[slot.WAVE_REFERENCE] = reference
    settings[slot.WAVE_CYCLE_GAP] = cycle_gap
    settings[slot.WAVE_THRESHOLD] = threshold
    settings[slot.WAVE_CONTACTS] = 0.0 if grid.contacts is None else 1.0
    settings[slot.WAVE_BELOW_THRESHOLD] = speed_below(threshold)
    settings[slot.WAVE_RAMP_END] = top.ramp_end
    cross = np.zeros((slot.NODE_ROWS, state.p.size + slot.CROSS_EXTRA))
    work = (  # the kernel's work space: buffers, node scratch, heads, top states
        np.zeros((slot.BUFFER_ROWS, layout.buffer_size)),
        np.zeros((slot.NODE_ROWS, state.p.size)),
        np.zeros((len(grid.cells), slot.HEAD_SIZE), dtype=np.int64),
        np.zeros(state.top.size),
    )
    arguments = (
        layout.integers, layout.floats, layout.end_dampers, layout.impedances, settings,
        state.p, state.m, state.top, state.bit, top.propagator, top.forcing, top.constant,
        top.coefficients, top.speed_table, top.constant_per_speed, torque, slope, parameters,
        records, field, summary, cross, *work, contact_index, contacts,
    )  # fmt: skip
    stepping = _march if engine == "numba" else _python_march()

    def advance(count: int) -> bool:
        if should_stop is not None and should_stop():
            raise RunCancelled
        settings[slot.WAVE_STEPS] = count  # the steps of this call (WAVE_RUN_STEPS: of the run)
        stepping(*arguments)
        # a failed step, or a steady cycle
        return bool(summary[slot.SUM_FAILED_STEP] or summary[slot.SUM_ENDED] > 0)

    run_in_chunks(steps, advance, progress)
    failed = summary[slot.SUM_FAILED_STEP]
    if failed:
        raise SolverError(
            f"the bit equation has no solution at step {int(failed)} "
            f"(t = {failed * dt:.6g} s): the torque on bit is not finite there"
        )
    fields = summary[slot.SUM_BIT_SPEED_MIN : slot.SUM_FAILED_STEP + 1]
    energies = dict(zip(slot.SUMMARY_FIELDS, fields.tolist(), strict=True))
    energies["stored_initial"] = stored_initial
    energies["stored_final"] = stored_energy(grid, state, top)
    energies["steps"] = float(summary[slot.SUM_STEPS])
    energies["ended_on_steady_cycle"] = float(summary[slot.SUM_ENDED] > 0)
    energies["friction_dissipation"] = float(summary[slot.SUM_FRICTION_WORK])
    energies["surface_torque_peak"] = float(summary[slot.SUM_SURFACE_TORQUE_PEAK])
    energies["surface_torque_min"] = float(summary[slot.SUM_SURFACE_TORQUE_MIN])
    energies["surface_torque_max"] = float(summary[slot.SUM_SURFACE_TORQUE_MAX])
    first_motion = summary[slot.SUM_BIT_FIRST_MOTION]
    moved = first_motion > 0 and grid.contacts is not None
    energies["bit_first_motion"] = float(first_motion * dt) if moved else math.nan
    return WaveRun(
        time=np.arange(records.shape[0]) * dt * record_every,
        records=records,
        field_time=np.arange(field.shape[0]) * dt * field_every,
        field=field,
        summary=energies,
        state=state,
        engine=engine,
    )
