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
from torsio.solvers.layouts import (
    CHAIN_APPLIED,
    CHAIN_DAMPING,
    CHAIN_DAMPING_UPPER,
    CHAIN_DRAG,
    CHAIN_MASS,
    CHAIN_MASS_UPPER,
    CHAIN_ROWS,
    CHAIN_STIFFNESS,
    CHAIN_STIFFNESS_UPPER,
    MAX_STATES,
    RUN_ATOL,
    RUN_BIT_RADIUS,
    RUN_FIRST_STEP,
    RUN_MAX_STEP,
    RUN_MAX_STEPS,
    RUN_OMEGA_1,
    RUN_RTOL,
    RUN_SIZE,
    RUN_STEADY_TOLERANCE,
    RUN_T_END,
    RUN_WINDOW_START,
    TOP_A,
    TOP_B,
    TOP_C,
    TOP_C_PIPE,
    TOP_HAS_NODE,
    TOP_K_PIPE,
    TOP_KP,
    TOP_MAX_TORQUE,
    TOP_PIPE_GAIN,
    TOP_SIZE,
    TOP_STATES,
    TOP_U0,
    TOP_W,
)

__all__ = ["pack_chain", "pack_top", "run_settings", "step_limits"]


def pack_chain(dynamics: Any) -> np.ndarray:
    """The chain of a :class:`torsio.physics.dynamics.Dynamics`, (``CHAIN_ROWS``, n)."""
    chain = np.zeros((CHAIN_ROWS, np.size(dynamics.mass_diag)))
    chain[CHAIN_MASS] = dynamics.mass_diag
    chain[CHAIN_MASS_UPPER] = dynamics.mass_upper
    chain[CHAIN_STIFFNESS] = dynamics.stiffness_diag
    chain[CHAIN_STIFFNESS_UPPER] = dynamics.stiffness_upper
    chain[CHAIN_DAMPING] = dynamics.damping_diag + dynamics.drag
    chain[CHAIN_DAMPING_UPPER] = dynamics.damping_upper
    chain[CHAIN_DRAG] = dynamics.drag
    chain[CHAIN_APPLIED] = dynamics.applied
    return chain


def pack_top(boundary: Any, chain: np.ndarray) -> np.ndarray:
    """The top drive (a ``TopDriveBoundary``) packed for the kernel; all zero when held.

    ConfigError for a controller of more than :data:`MAX_STATES` states.
    """
    top = np.zeros(TOP_SIZE)
    if boundary.held:
        return top
    m = boundary.states
    if m > MAX_STATES:
        raise ConfigError(
            "top_drive",
            f"the batch engine takes top-drive controllers with at most {MAX_STATES} states, "
            f"got {m}; use engine='scipy'",
        )
    top[TOP_HAS_NODE] = 1.0
    top[TOP_STATES] = m
    top[TOP_U0] = boundary.u0
    top[TOP_MAX_TORQUE] = boundary.max_torque
    top[TOP_K_PIPE] = -chain[CHAIN_STIFFNESS_UPPER, 0]  # the model's top spring and damper
    top[TOP_C_PIPE] = -chain[CHAIN_DAMPING_UPPER, 0]
    top[TOP_KP] = boundary.kp
    top[TOP_PIPE_GAIN] = boundary.pipe_gain
    a = np.zeros((MAX_STATES, MAX_STATES))
    b = np.zeros((MAX_STATES, 2))
    a[:m, :m] = boundary.a
    b[:m] = boundary.b
    top[TOP_A:TOP_B] = a.ravel()
    top[TOP_B:TOP_C] = b.ravel()
    top[TOP_C : TOP_C + m] = boundary.c
    top[TOP_W : TOP_W + m] = boundary.w
    return top


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
) -> np.ndarray:
    """A run's settings for the kernel: run length and steady window [s], tolerances,
    (first, largest) step [s] (:func:`step_limits`), accepted steps allowed, bit radius [m],
    steady-cycle tolerance [S_SS units] (0: run to the end), omega_1 [rad/s]."""
    settings = np.zeros(RUN_SIZE)
    settings[RUN_T_END] = t_end
    settings[RUN_WINDOW_START] = t_end - window
    settings[RUN_RTOL] = rtol
    settings[RUN_ATOL] = atol
    settings[RUN_FIRST_STEP], settings[RUN_MAX_STEP] = steps
    settings[RUN_MAX_STEPS] = max_steps
    settings[RUN_BIT_RADIUS] = bit_radius
    settings[RUN_STEADY_TOLERANCE] = steady_tolerance
    settings[RUN_OMEGA_1] = first_frequency
    return settings
