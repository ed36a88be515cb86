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
from torsio.solvers.characteristics import (
    SUMMARY_FIELDS,
    SUMMARY_SIZE,
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
    records : ndarray, shape (len(time), 5)
        :data:`RECORD_CHANNELS` at those times.
    field_time : ndarray
        Times of the speed snapshots [s].
    field : ndarray, shape (len(field_time), nodes)
        Angular speed at every node [rad/s] (state layout, :func:`node_offsets`).
    summary : dict
        :data:`SUMMARY_FIELDS` (energies in J over the run), plus ``stored_initial`` and
        ``stored_final`` [J] (:func:`stored_energy`; the initial state with a held top
        already turning), ``steps`` (taken), ``ended_on_steady_cycle``, and
        ``friction_dissipation`` [J] (the contacts' work), ``surface_torque_peak`` (the
        run's largest), ``surface_torque_min``, ``surface_torque_max`` (the window's) [N m]
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
    energy = string_energy(grid, state) + 0.5 * grid.bit_inertia * state.bit[0] ** 2
    if not top.held:
        energy += 0.5 * top.inertia * state.top[0] ** 2
    return energy


def _end_damper_power(
    grid: WaveModel, layout: KernelLayout, state: WaveState, top_speed: float
) -> float:
    """Power [W] of the dampers at the top node, the junctions and the bit in ``state``."""
    offsets = node_offsets(grid)
    z = layout.impedances
    power = layout.end_dampers[0] * top_speed**2 + layout.end_dampers[-1] * state.bit[0] ** 2
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
    summary = np.zeros(SUMMARY_SIZE)
    summary[0], summary[1] = math.inf, -math.inf
    summary[27], summary[28], summary[29] = -math.inf, math.inf, -math.inf
    contact_index, contacts = contact_arrays(grid)
    threshold = 0.0 if grid.contacts is None else float(grid.contacts.threshold_speed)
    # powers at t = 0 for the trapezoidal energies
    speed0 = state.top[0] if not top.held else set_speed0
    surface0 = state.m[0] + (z_top + layout.end_dampers[0]) * speed0  # with the top node's drag
    if not top.held:
        x0 = state.top
        u0 = top.coefficients[0] + top.set_gain * set_speed0 + top.coefficients[1:-1] @ x0
        u0 += top.coefficients[-1] * state.m[0]
        motor0 = float(np.clip(u0, -top.max_torque, top.max_torque))
    else:
        motor0 = surface0 + layout.end_dampers[0] * speed0
    w_bit = state.bit[0]
    summary[10] = motor0 * speed0
    summary[11] = float(law.torque(w_bit, wob, radius)) * w_bit
    summary[12] = alpha * grid.bit_inertia * w_bit * w_bit
    summary[13] = _end_damper_power(grid, layout, state, speed0)
    summary[14] = top.drag * speed0 * speed0
    records = np.full((steps // record_every + 1 if record_every else 0, 5), np.nan)
    field = np.full((steps // field_every + 1 if field_every else 0, state.p.size), np.nan)
    if record_every:
        records[0] = [w_bit, float(law.torque(w_bit, wob, radius)), surface0, speed0, motor0]
    if field_every:
        field[0] = (state.p - state.m) / (2.0 * layout.impedances)
    reference = top.set_speed if top.held or math.isfinite(top.set_speed) else 0.0
    settings = np.array(
        [
            dt, grid.bit_inertia, alpha, wob, radius, 1.0 if top.held else 0.0, top.set_speed,
            top.max_torque, steps, window_start, record_every, field_every, top.drag,
            1.0 if track_energy else 0.0, grid.drag_spacing, steady_tolerance, reference,
            cycle_gap, steps, threshold, 0.0 if grid.contacts is None else 1.0,
            speed_below(threshold), top.set_gain, top.ramp_end,
        ]
    )  # fmt: skip
    cross = np.zeros((2, state.p.size + 2))
    work = (  # the kernel's work space: buffers, node scratch, heads, top states
        np.zeros((2, layout.buffer_size)), np.zeros((2, state.p.size)),
        np.zeros((len(grid.cells), 4), dtype=np.int64), np.zeros(state.top.size),
    )  # fmt: skip
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
        settings[8] = count  # the steps of this call (settings[18]: of the run)
        stepping(*arguments)
        return bool(summary[9] or summary[23] > 0)  # a failed step, or a steady cycle

    run_in_chunks(steps, advance, progress)
    if summary[9]:
        raise SolverError(
            f"the bit equation has no solution at step {int(summary[9])} "
            f"(t = {summary[9] * dt:.6g} s): the torque on bit is not finite there"
        )
    energies = dict(zip(SUMMARY_FIELDS, summary[:10].tolist(), strict=True))
    energies["stored_initial"] = stored_initial
    energies["stored_final"] = stored_energy(grid, state, top)
    energies["steps"] = float(summary[15])
    energies["ended_on_steady_cycle"] = float(summary[23] > 0)
    energies["friction_dissipation"] = float(summary[26])
    names = ("surface_torque_peak", "surface_torque_min", "surface_torque_max")
    energies.update(zip(names, summary[27:30].tolist(), strict=True))
    moved = summary[30] > 0 and grid.contacts is not None
    energies["bit_first_motion"] = float(summary[30] * dt) if moved else math.nan
    return WaveRun(
        time=np.arange(records.shape[0]) * dt * record_every,
        records=records,
        field_time=np.arange(field.shape[0]) * dt * field_every,
        field=field,
        summary=energies,
        state=state,
        engine=engine,
    )
