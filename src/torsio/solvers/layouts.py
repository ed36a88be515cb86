"""Where each value sits in the packed arrays the compiled kernels take and return.

The kernels (numba, no objects) exchange index-packed float arrays with the Python side.
Each array's slots are named here, once, in order: one assignment per array unpacks
:func:`field_starts` (the start of each field from the fields' lengths), so a name's position
follows from the names before it and the last name is the array's size. The names are
module-level ints, which numba compiles as constants. Encoders and kernels index with
them only (``top[TOP_KP]``, ``settings[RUN_T_END]``); a field longer than one slot (a
controller matrix, the steps' stages) has a named start.

Lumped engine (:mod:`torsio.solvers.rodas`, :mod:`torsio.solvers.chain_kernel`,
:mod:`torsio.solvers.numpy_engine`):

``chain`` (:data:`CHAIN_ROWS`, n): the chain's band matrices, drag and applied torque.
``top`` (:data:`TOP_SIZE`): the top drive; all zero for a held top.
    ``TOP_HAS_NODE`` 1.0 with a top-drive node; ``TOP_STATES`` m, the controller states
    (at most :data:`MAX_STATES`); ``TOP_U0`` constant motor torque [N m];
    ``TOP_MAX_TORQUE`` |u| limit [N m]; ``TOP_K_PIPE``, ``TOP_C_PIPE`` the model's top
    spring [N m/rad] and damper [N m s/rad] (y's pipe torque); ``TOP_KP`` ``kp`` of
    ``[top_drive]``, the motor torque per unit speed error [N m s/rad] (d[0] of
    :class:`torsio.physics.top_drive_boundary.TopDriveBoundary`); ``TOP_PIPE_GAIN`` the
    motor torque per unit pipe torque [-] (d[1]); ``TOP_A`` a (m x m in a 3 x 3 block,
    row-major), ``TOP_B`` b (3 x 2), ``TOP_C`` c (3), ``TOP_W`` w (3, anti-windup).
``settings`` (:data:`RUN_SIZE`): t_end, start of the steady window [s], rtol, atol,
    first and largest step [s], accepted steps allowed, bit radius [m], steady-cycle
    tolerance [S_SS units] (0: run to t_end), omega_1 [rad/s].
``out[k]`` (:data:`OUT_COLUMNS`): bit speed max and min over the window [rad/s],
    accepted and rejected steps, status, mean top speed [rad/s], the time the run ended [s].
The work space of a run: ``vectors`` (:data:`VECTOR_ROWS`, n) and ``small``
    (:data:`SMALL_ROWS`, :data:`SMALL_COLUMNS`), rows named ``VEC_*`` and ``SMALL_*``; a
    row of ``small`` holds up to two vectors of m controller states, at columns 0 and
    :data:`MAX_STATES`. Row ``SMALL_CARRY`` (``CARRY_*``) and ``SMALL_WINDOW``
    (``WINDOW_*``) carry the run's scalars from call to call.
The steady-cycle tracker (:func:`torsio.solvers.cycles.track_cycle`): its state
    ``CYCLE_*`` (:data:`CYCLE_SIZE`) and its settings ``CYCLE_SET_*``
    (:data:`CYCLE_SETTINGS_SIZE`).

Adding a slot: insert its name where it belongs in the array's assignment (and its
length in the :func:`field_starts` call), write it in the encoder and read it in the kernel by
name; the size follows. numba's cache is keyed on every file of :mod:`torsio.solvers`
(:mod:`torsio.kernel_cache`), so the kernels recompile.
"""

from __future__ import annotations


def field_starts(*lengths: int) -> tuple[int, ...]:
    """The start of each field of the given lengths, one after the other, then the total.

    >>> field_starts(1, 1, 9, 3)
    (0, 1, 2, 11, 14)
    """
    starts = [0]
    for length in lengths:
        starts.append(starts[-1] + length)
    return tuple(starts)


MAX_STATES = 3
"""Controller states the lumped kernels take (the 3-column blocks of ``top`` and ``small``)."""

# --- the lumped engine: the chain, rows of length n (upper[i] couples nodes i and i + 1) --
# [I] diagonal and upper [kg m^2], [K] [N m/rad], [C] = [C_rel] + diag(drag) [N m s/rad],
# the drag of each node [N m s/rad], the applied torque [N m]
(CHAIN_MASS, CHAIN_MASS_UPPER, CHAIN_STIFFNESS, CHAIN_STIFFNESS_UPPER, CHAIN_DAMPING,
 CHAIN_DAMPING_UPPER, CHAIN_DRAG, CHAIN_APPLIED, CHAIN_ROWS) = field_starts(*(1,) * 8)  # fmt: skip

# --- the lumped engine: the top drive --------------------------------------------------
(TOP_HAS_NODE, TOP_STATES, TOP_U0, TOP_MAX_TORQUE, TOP_K_PIPE, TOP_C_PIPE, TOP_KP,
 TOP_PIPE_GAIN, TOP_A, TOP_B, TOP_C, TOP_W, TOP_SIZE) = field_starts(
    1, 1, 1, 1, 1, 1, 1, 1, MAX_STATES * MAX_STATES, 2 * MAX_STATES, MAX_STATES, MAX_STATES
)  # fmt: skip

# --- the lumped engine: a run's settings -----------------------------------------------
(RUN_T_END, RUN_WINDOW_START, RUN_RTOL, RUN_ATOL, RUN_FIRST_STEP, RUN_MAX_STEP,
 RUN_MAX_STEPS, RUN_BIT_RADIUS, RUN_STEADY_TOLERANCE, RUN_OMEGA_1, RUN_SIZE) = field_starts(
    *(1,) * 10
)  # fmt: skip

# --- the lumped engine: a point's results ----------------------------------------------
(OUT_BIT_SPEED_MAX, OUT_BIT_SPEED_MIN, OUT_STEPS, OUT_REJECTED, OUT_STATUS,
 OUT_TOP_SPEED_MEAN, OUT_ENDED, OUT_COLUMNS) = field_starts(*(1,) * 7)  # fmt: skip

# --- the lumped engine: the work space of a run, rows of length n ----------------------
# the six stages' increments of the twists and twist rates; the state, the stage's
# argument and right-hand side, the mass-matrix terms, the solve, the step matrix's
# factors, the accelerations, the factors of [I], the state at the step's start, the
# state at the last crossing of the cycle tracker (two rows)
(VEC_K_PHI, VEC_K_V, VEC_PHI, VEC_V, VEC_A_PHI, VEC_A_V, VEC_F_PHI, VEC_F_V, VEC_F0_V,
 VEC_U_PHI, VEC_U_V, VEC_X, VEC_PIVOTS, VEC_LOWER, VEC_BAND, VEC_ACC, VEC_MASS_PIVOTS,
 VEC_MASS_LOWER, VEC_PHI0, VEC_V0, VEC_ACC0, VEC_CROSS, VECTOR_ROWS) = field_starts(
    6, 6, *(1,) * 19, 2
)  # fmt: skip

# --- the lumped engine: the work space of a run, short rows ----------------------------
# the stages' controller increments; z and the stage's argument; z' and z' at the step's
# start; the mass-matrix term; the elimination's Q and Z_y; its gains (G_e, G_T, r);
# the 3 x 6 Gauss-Jordan work; the cycle tracker's state and settings; z and z' at the
# step's start; the carried scalars
(SMALL_K_Z, SMALL_Z, SMALL_F_Z, SMALL_U_Z, SMALL_Q, SMALL_GAINS, SMALL_SOLVE, SMALL_CYCLE,
 SMALL_CYCLE_SETTINGS, SMALL_START, SMALL_CARRY, SMALL_WINDOW, SMALL_ROWS) = field_starts(
    6, 1, 1, 1, MAX_STATES, 1, MAX_STATES, 1, 1, 1, 1, 1
)  # fmt: skip
FIRST_BLOCK, SECOND_BLOCK, BLOCKS_END = field_starts(MAX_STATES, MAX_STATES)
"""Columns of the two blocks of controller states in a short row (and their end)."""
SMALL_COLUMNS = BLOCKS_END + 2
"""Columns of the short rows: two blocks of controller states, or the carried scalars."""
GAIN_E, GAIN_PIPE, GAIN_STATES = field_starts(1, 1)
"""Columns of row ``SMALL_GAINS``: G_e, G_T, then r_0 .. r_m-1."""

# row SMALL_CARRY: time, step, the last accepted step and its error, last step rejected,
# accepted and rejected steps, status
(CARRY_T, CARRY_H, CARRY_H_ACCEPTED, CARRY_ERR_ACCEPTED, CARRY_LAST_REJECTED, CARRY_STEPS,
 CARRY_REJECTED, CARRY_STATUS, CARRY_SIZE) = field_starts(*(1,) * 8)  # fmt: skip
# row SMALL_WINDOW: bit twist-rate max and min over the window, the top speed's integral
# over it, the next output sample, ended on a steady cycle
(WINDOW_BIT_MAX, WINDOW_BIT_MIN, WINDOW_TOP_INTEGRAL, WINDOW_NEXT_SAMPLE, WINDOW_DONE,
 WINDOW_SIZE) = field_starts(*(1,) * 5)  # fmt: skip

# --- the steady-cycle tracker of the lumped engine -------------------------------------
# crossings seen, time of the last one, running bit twist-rate max and min since it,
# the extremes of the last complete cycle, the change of the state at the last crossing
(CYCLE_COUNT, CYCLE_T_LAST, CYCLE_RUN_MAX, CYCLE_RUN_MIN, CYCLE_MAX, CYCLE_MIN,
 CYCLE_CHANGE, CYCLE_SIZE) = field_starts(*(1,) * 7)  # fmt: skip
# 2 Omega [rad/s], omega_1 [rad/s], t_end [s], window length [s], tolerance [S_SS units]
(CYCLE_SET_TWICE_OMEGA, CYCLE_SET_OMEGA_1, CYCLE_SET_T_END, CYCLE_SET_WINDOW,
 CYCLE_SET_TOLERANCE, CYCLE_SETTINGS_SIZE) = field_starts(*(1,) * 5)  # fmt: skip

__all__ = ["field_starts", *(name for name in tuple(globals()) if name.isupper())]
