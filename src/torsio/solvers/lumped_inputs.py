"""The lumped kernels' inputs, packed by the layouts of :mod:`torsio.solvers.layouts`.

The chain, the top drive and a run's settings as the compiled kernel
(:mod:`torsio.solvers.rodas`) and the numpy engine read them, and the step-size rule of
every lumped RODAS4 run (batches and single runs alike).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsio.errors import ConfigError
from torsio.solvers import layouts as slot

__all__ = ["pack_chain", "pack_table", "pack_top", "run_settings", "step_limits"]


def pack_chain(dynamics: Any) -> np.ndarray:
    """The chain of a :class:`torsio.physics.dynamics.Dynamics`, (``CHAIN_ROWS``, n)."""
    chain = np.zeros((slot.CHAIN_ROWS, np.size(dynamics.mass_diag)))
    chain[slot.CHAIN_MASS] = dynamics.mass_diag
    chain[slot.CHAIN_MASS_UPPER] = dynamics.mass_upper
    chain[slot.CHAIN_STIFFNESS] = dynamics.stiffness_diag
    chain[slot.CHAIN_STIFFNESS_UPPER] = dynamics.stiffness_upper
    chain[slot.CHAIN_DAMPING] = dynamics.damping_diag + dynamics.drag
    chain[slot.CHAIN_DAMPING_UPPER] = dynamics.damping_upper
    chain[slot.CHAIN_DRAG] = dynamics.drag
    chain[slot.CHAIN_APPLIED] = dynamics.applied
    contacts = dynamics.contacts
    if contacts is not None:
        chain[slot.CHAIN_CONTACT_STATIC] = contacts.static
        chain[slot.CHAIN_CONTACT_DYNAMIC] = contacts.dynamic
        chain[slot.CHAIN_CONTACT_THRESHOLD] = contacts.threshold_speed
    return chain


def pack_top(boundary: Any, chain: np.ndarray, dynamics: Any = None) -> np.ndarray:
    """The top drive (a ``TopDriveBoundary``) packed for the kernel; when held, only the
    top spring and damper k_t, c_t of ``dynamics`` (a ``Dynamics``; none: zero), through
    which a set speed that changes in time drives node 0.

    ConfigError for a controller of more than :data:`~torsio.solvers.layouts.MAX_STATES` states.
    """
    top = np.zeros(slot.TOP_SIZE)
    if boundary.held:
        if dynamics is not None:  # a chain's top spring and damper tie node 0 alone
            top[slot.TOP_K_PIPE] = dynamics.top_spring[0]
            top[slot.TOP_C_PIPE] = dynamics.top_damper[0]
        return top
    m = boundary.states
    if m > slot.MAX_STATES:
        raise ConfigError(
            "top_drive",
            f"the batch engine takes top-drive controllers with at most {slot.MAX_STATES} states, "
            f"got {m}; use engine='scipy'",
        )
    top[slot.TOP_HAS_NODE] = 1.0
    top[slot.TOP_STATES] = m
    top[slot.TOP_U0] = boundary.u0
    top[slot.TOP_MAX_TORQUE] = boundary.max_torque
    top[slot.TOP_K_PIPE] = -chain[
        slot.CHAIN_STIFFNESS_UPPER, 0
    ]  # the model's top spring and damper
    top[slot.TOP_C_PIPE] = -chain[slot.CHAIN_DAMPING_UPPER, 0]
    top[slot.TOP_KP] = boundary.kp
    top[slot.TOP_PIPE_GAIN] = boundary.pipe_gain
    a = np.zeros((slot.MAX_STATES, slot.MAX_STATES))
    b = np.zeros((slot.MAX_STATES, 2))
    a[:m, :m] = boundary.a
    b[:m] = boundary.b
    top[slot.TOP_A : slot.TOP_B] = a.ravel()
    top[slot.TOP_B : slot.TOP_C] = b.ravel()
    top[slot.TOP_C : slot.TOP_C + m] = boundary.c
    top[slot.TOP_W : slot.TOP_W + m] = boundary.w
    return top


def pack_table(dynamics: Any) -> np.ndarray:
    """The set speed against time for the kernel, (``TABLE_ROWS``, k): the description's
    table with the held top's twist, or one point at the constant set speed (NaN: none)."""
    if dynamics.speed_table is not None:
        return np.ascontiguousarray(dynamics.speed_table, dtype=float)
    table = np.zeros((slot.TABLE_ROWS, 1))
    table[slot.TABLE_SPEED] = dynamics.set_speed
    return table


def step_limits(first_frequency: float, max_step: float | None = None) -> tuple[float, float]:
    """(first step, largest step) [s] of a RODAS4 run on a model of first natural frequency
    omega_1 [rad/s]: 1e-3 of the first natural period, at most the largest step, which is
    ``max_step`` or a quarter of the period (ConfigError unless positive and finite)."""
    period = 2.0 * math.pi / first_frequency
    if max_step is None:
        max_step = period / 4.0
    if not (math.isfinite(max_step) and max_step > 0):
        raise ConfigError("max_step", f"expected a positive step in s, got {max_step!r}")
    return min(1e-3 * period, max_step), max_step


def run_settings(
    t_end: float,
    window: float,
    rtol: float,
    atol: float,
    steps: tuple[float, float],
    max_steps: int,
    bit_radius: float,
    steady_tolerance: float,
    first_frequency: float,
    max_switches: int | None = None,
    ramp: float = 0.0,
) -> np.ndarray:
    """A run's settings for the kernel: run length and steady window [s], tolerances,
    (first, largest) step [s] (:func:`step_limits`), accepted steps allowed, bit radius [m],
    steady-cycle tolerance [S_SS units] (0: run to the end), omega_1 [rad/s], the contacts'
    switches allowed (default: as many as the accepted steps), the time [s] over which each
    point of a batch ramps its set speed from 0 (0: none)."""
    settings = np.zeros(slot.RUN_SIZE)
    settings[slot.RUN_T_END] = t_end
    settings[slot.RUN_WINDOW_START] = t_end - window
    settings[slot.RUN_RTOL] = rtol
    settings[slot.RUN_ATOL] = atol
    settings[slot.RUN_FIRST_STEP], settings[slot.RUN_MAX_STEP] = steps
    settings[slot.RUN_MAX_STEPS] = max_steps
    settings[slot.RUN_BIT_RADIUS] = bit_radius
    settings[slot.RUN_STEADY_TOLERANCE] = steady_tolerance
    settings[slot.RUN_OMEGA_1] = first_frequency
    settings[slot.RUN_MAX_SWITCHES] = max_steps if max_switches is None else max_switches
    settings[slot.RUN_RAMP] = ramp
    return settings
