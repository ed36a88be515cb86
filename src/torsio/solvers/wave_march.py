"""Running the distributed model: :func:`march` sets up and calls the compiled stepping.

The stepping itself (transport, junctions, top, bit, drag) is in
:mod:`torsio.solvers.characteristics`; this module chooses the engine (the law's
compiled kernel, or plain Python), keeps the drag half step bookkeeping of the Strang
splitting, and returns records, snapshots along the string and energy integrals.
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.errors import SolverError
from torsio.model.wave import WaveModel
from torsio.solvers.characteristics import (
    SUMMARY_FIELDS,
    WaveState,
    _march,
    node_offsets,
    rest_state,
)
from torsio.solvers.wave_top import TopArrays, with_impedance


# --- driver ---------------------------------------------------------------------------------
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
        already turning).
    state : WaveState
        Final state (between drag half steps undone: the state at the final time).
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

    Without a kernel (or without numba) the law's Python ``torque``/``slope`` are wrapped
    to the kernel's call convention and the steps run as plain Python (slow: minutes for a
    default run).
    """
    try:
        from torsio.solvers.law_kernels import law_kernel
    except ImportError:  # pragma: no cover - older layouts
        kernel = None
    else:
        kernel = law_kernel(law)
    if kernel is not None:
        return kernel.torque, kernel.slope, kernel.parameters, "numba"

    def torque(parameters: np.ndarray, speed: float, wob: float, radius: float) -> float:
        return float(law.torque(speed, wob, radius))

    def slope(parameters: np.ndarray, speed: float, wob: float, radius: float) -> float:
        return float(law.slope(speed, wob, radius))

    return torque, slope, np.zeros(1), "python"


def _apply_drag(grid: WaveModel, state: WaveState, factor: float) -> None:
    """Scale the speed at every node by ``factor`` with the torque unchanged."""
    z = np.repeat(grid.impedances, np.array(grid.cells) + 1)
    torque = 0.5 * (state.p + state.m)
    speed = (state.p - state.m) / (2.0 * z) * factor
    state.p[:] = torque + z * speed
    state.m[:] = torque - z * speed


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
    """
    dt = grid.time_step
    decay = math.exp(-alpha * dt)
    if kernel is not None:
        torque, slope, parameters = kernel
        engine = "numba"
    else:
        torque, slope, parameters, engine = law_functions(law)
    offsets = node_offsets(grid)
    # the boundaries see the stored state half a drag step behind: Z exp(alpha dt / 2)
    top = with_impedance(top, float(grid.impedances[0]) / math.sqrt(decay), dt)
    state = rest_state(grid, top) if state is None else state.copy()
    if top.held and state.top.size == 0:
        state = WaveState(state.p, state.m, np.zeros(1), state.bit)
    if top.held:  # the held top turns at its speed from t = 0 on
        state.p[0] = state.m[0] + 2.0 * grid.impedances[0] * top.set_speed
    stored_initial = stored_energy(grid, state, top)
    summary = np.zeros(16)
    summary[0], summary[1] = math.inf, -math.inf
    # powers at t = 0 for the trapezoidal energies
    speed0 = state.top[0] if not top.held else top.set_speed
    if not top.held:
        x0 = state.top
        torque0 = 0.5 * (state.p[0] + state.m[0])
        m_stored = torque0 - top.impedance * (state.p[0] - state.m[0]) / (2 * grid.impedances[0])
        u0 = top.coefficients[0] + top.coefficients[1:-1] @ x0 + top.coefficients[-1] * m_stored
        summary[10] = float(np.clip(u0, -top.max_torque, top.max_torque)) * speed0
    else:
        summary[10] = (state.m[0] + grid.impedances[0] * speed0) * speed0
    w_bit = state.bit[0]
    summary[11] = float(law.torque(w_bit, wob, radius)) * w_bit
    summary[12] = alpha * grid.bit_inertia * w_bit * w_bit
    z = np.repeat(grid.impedances, np.array(grid.cells) + 1)
    weights = np.ones_like(z)
    weights[offsets[:-1]] = 0.5
    weights[offsets[1:] - 1] = 0.5
    summary[13] = float(alpha * dt * np.sum(weights * (state.p - state.m) ** 2 / (4.0 * z)))
    summary[14] = top.drag * speed0 * speed0
    _apply_drag(grid, state, 1.0 / math.sqrt(decay))  # the kernel keeps it half a drag behind
    records = np.full((steps // record_every + 1 if record_every else 0, 5), np.nan)
    field = np.full((steps // field_every + 1 if field_every else 0, z.size), np.nan)
    if record_every:
        records[0] = [
            state.bit[0], float(law.torque(state.bit[0], wob, radius)),
            state.m[0] + grid.impedances[0] * speed0, speed0, summary[10] / speed0
            if speed0 else 0.0,
        ]  # fmt: skip
    if field_every:
        field[0] = (state.p - state.m) / (2.0 * z) * math.sqrt(decay)
    settings = np.array(
        [
            dt, decay, grid.bit_inertia, alpha, wob, radius, 1.0 if top.held else 0.0,
            top.set_speed, top.max_torque, steps, window_start, record_every, field_every,
            top.drag, 1.0 if track_energy else 0.0,
        ]
    )  # fmt: skip
    arguments = (
        offsets, np.ascontiguousarray(grid.impedances, dtype=float), settings, state.p, state.m,
        state.top, state.bit, top.propagator, top.forcing, top.constant, top.coefficients,
        torque, slope, parameters, records, field, summary,
    )  # fmt: skip
    if engine == "numba":
        _march(*arguments)
    else:
        _python_march()(*arguments)
    if summary[9]:
        raise SolverError(
            f"the bit equation has no solution at step {int(summary[9])} "
            f"(t = {summary[9] * dt:.6g} s): the torque on bit is not finite there"
        )
    _apply_drag(grid, state, math.sqrt(decay))
    energies = dict(zip(SUMMARY_FIELDS, summary[:10].tolist(), strict=True))
    energies["stored_initial"] = stored_initial
    energies["stored_final"] = stored_energy(grid, state, top)
    return WaveRun(
        time=np.arange(records.shape[0]) * dt * record_every,
        records=records,
        field_time=np.arange(field.shape[0]) * dt * field_every,
        field=field,
        summary=energies,
        state=state,
        engine=engine,
    )
