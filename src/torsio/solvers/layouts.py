"""Where each value sits in the packed arrays the compiled kernels take and return.

The kernels (numba, no objects) exchange index-packed float arrays with the Python side.
Each array's slots are named here, once, in order: one assignment per array unpacks
:func:`field_starts` (the start of each field from the fields' lengths), so a name's
position follows from the names before it and the last name is the array's size. The
names are module-level ints, which numba compiles as constants. Encoders and kernels
index with them only (``top[TOP_KP]``, ``settings[RUN_T_END]``); a field longer than one
slot (a controller matrix, the stages' increments) has a named start. A comment above
each assignment says what each slot holds, with its unit.

Lumped engine (:mod:`torsio.solvers.rodas`, :mod:`torsio.solvers.chain_kernel`,
:mod:`torsio.solvers.numpy_engine`; encoders in :mod:`torsio.solvers.lumped_inputs`):
``chain`` (``CHAIN_*``), ``top`` (``TOP_*``), a run's ``settings`` (``RUN_*``), a point's
results ``out`` (``OUT_*``), the work space ``vectors`` (``VEC_*``) and ``small``
(``SMALL_*``, its carried scalars ``CARRY_*`` and ``WINDOW_*``), the steady-cycle
tracker's state and settings (``CYCLE_*``, ``CYCLE_SET_*``).

Wave model (:mod:`torsio.solvers.characteristics`; encoders in
:mod:`torsio.solvers.wave_march`, :mod:`torsio.solvers.wave_state`,
:mod:`torsio.solvers.wave_top`, :mod:`torsio.solvers.wave_contacts`): a run's ``settings``
(``WAVE_*``) and ``summary`` (``SUM_*``, ``POWER_*``), the records (``REC_*``), the bit's
and the top's states (``BIT_*``, ``X_*``), the motor torque's coefficients (``COEF_*``), the
sections' columns (``CELLS`` .. ``SPECIAL_COLUMN``, ``Z`` .. ``C_SPECIAL``), the heads
(``HEAD_*``), buffers and node rows (``BUFFER_*``, ``NODE_*``, ``CROSS_*``), the set-speed
table (``TABLE_*``) and the contacts (``CONTACT_*``).

Adding a slot: insert its name where it belongs in the array's assignment (and its
length in the :func:`field_starts` call), write it in the encoder and read it in the
kernel by name; the size follows. numba's cache is keyed on every file of
:mod:`torsio.solvers` (:mod:`torsio.kernel_cache`), so the kernels recompile.
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
# the drag of each node [N m s/rad], the applied torque [N m]; each node's contact with the
# borehole (model/contacts.py): static and sliding capacities C_s >= C_d [N m] (0: no
# contact) and the speed below which it is on its static branch [rad/s]
(CHAIN_MASS, CHAIN_MASS_UPPER, CHAIN_STIFFNESS, CHAIN_STIFFNESS_UPPER, CHAIN_DAMPING,
 CHAIN_DAMPING_UPPER, CHAIN_DRAG, CHAIN_APPLIED, CHAIN_CONTACT_STATIC, CHAIN_CONTACT_DYNAMIC,
 CHAIN_CONTACT_THRESHOLD, CHAIN_ROWS) = field_starts(*(1,) * 11)  # fmt: skip

# --- the lumped engine: the top drive (a held top: only its spring and damper) ----------
# 1.0 with a top-drive node; m, the controller states (at most MAX_STATES); the constant
# motor torque u0 [N m]; the |u| limit [N m]; the model's top spring [N m/rad] and damper
# [N m s/rad] (the pipe torque of y; for a held top, k_t and c_t, through which a set
# speed that changes in time drives node 0); kp of [top_drive], the motor torque per unit speed
# error [N m s/rad] (TopDriveBoundary.kp, d[0]); the motor torque per unit pipe torque [-]
# (TopDriveBoundary.pipe_gain, d[1]); a (m x m in a MAX_STATES square, row-major), b
# (MAX_STATES x 2), c and w (MAX_STATES each)
(TOP_HAS_NODE, TOP_STATES, TOP_U0, TOP_MAX_TORQUE, TOP_K_PIPE, TOP_C_PIPE, TOP_KP,
 TOP_PIPE_GAIN, TOP_A, TOP_B, TOP_C, TOP_W, TOP_SIZE) = field_starts(
    1, 1, 1, 1, 1, 1, 1, 1, MAX_STATES * MAX_STATES, 2 * MAX_STATES, MAX_STATES, MAX_STATES
)  # fmt: skip

# --- the lumped engine: a run's settings -----------------------------------------------
# t_end, start of the steady window [s], rtol, atol, first and largest step [s], accepted
# steps allowed, bit radius [m], steady-cycle tolerance [S_SS units] (0: run to t_end),
# omega_1 [rad/s], the contacts' switches allowed (more: the run chatters), the time over
# which a batch point's set speed ramps from 0 to its own [s] (0: none)
(RUN_T_END, RUN_WINDOW_START, RUN_RTOL, RUN_ATOL, RUN_FIRST_STEP, RUN_MAX_STEP,
 RUN_MAX_STEPS, RUN_BIT_RADIUS, RUN_STEADY_TOLERANCE, RUN_OMEGA_1, RUN_MAX_SWITCHES,
 RUN_RAMP, RUN_SIZE) = field_starts(*(1,) * 12)  # fmt: skip

# --- the lumped engine: a point's results ----------------------------------------------
# bit speed max and min over the window [rad/s], accepted and rejected steps, status
# (batch_results.STATUS_MESSAGES), mean top speed [rad/s], the time the run ended [s]
(OUT_BIT_SPEED_MAX, OUT_BIT_SPEED_MIN, OUT_STEPS, OUT_REJECTED, OUT_STATUS,
 OUT_TOP_SPEED_MEAN, OUT_ENDED, OUT_COLUMNS) = field_starts(*(1,) * 7)  # fmt: skip

# --- the lumped engine: the work space of a run, rows of length n ----------------------
# the six stages' increments of the twists and twist rates; the state, the stage's
# argument and right-hand side, the mass-matrix terms, the solve, the step matrix's
# factors, the accelerations, the factors of [I], the state at the step's start, the
# state at the last crossing of the cycle tracker (two rows); each node's contact state
# (solvers/contact_kernel.py: 0 stuck or no contact, +-1 slow, +-2 fast, the sign the
# direction of motion) and the switch due at the end of the step (0 none, 1 its speed or
# holding torque, 2 its threshold)
# the rows of the state at the last crossing: twists [rad], twist rates [rad/s]
CROSS_TWIST, CROSS_RATE, CROSS_ROWS = field_starts(1, 1)
(VEC_K_PHI, VEC_K_V, VEC_PHI, VEC_V, VEC_A_PHI, VEC_A_V, VEC_F_PHI, VEC_F_V, VEC_F0_V,
 VEC_U_PHI, VEC_U_V, VEC_X, VEC_PIVOTS, VEC_LOWER, VEC_BAND, VEC_ACC, VEC_MASS_PIVOTS,
 VEC_MASS_LOWER, VEC_PHI0, VEC_V0, VEC_ACC0, VEC_CROSS, VEC_CONTACT_STATE,
 VEC_CONTACT_PENDING, VECTOR_ROWS) = field_starts(6, 6, *(1,) * 19, CROSS_ROWS, 1, 1)  # fmt: skip

# --- the lumped engine: the work space of a run, short rows ----------------------------
# the stages' controller increments; z and the stage's argument; z' and z' at the step's
# start; the mass-matrix term; the elimination's Q and Z_y; its gains (G_e, G_T, r);
# the 3 x 6 Gauss-Jordan work; the cycle tracker's state and settings; z and z' at the
# step's start; the carried scalars; the contacts' carried scalars; the time derivatives
# of z' and of node 0's force of a set speed that changes in time (first block; the
# force [N m/s] in column SECOND_BLOCK)
(SMALL_K_Z, SMALL_Z, SMALL_F_Z, SMALL_U_Z, SMALL_Q, SMALL_GAINS, SMALL_SOLVE, SMALL_CYCLE,
 SMALL_CYCLE_SETTINGS, SMALL_START, SMALL_CARRY, SMALL_WINDOW, SMALL_FRICTION, SMALL_SET_RATE,
 SMALL_ROWS) = field_starts(6, 1, 1, 1, MAX_STATES, 1, MAX_STATES, 1, 1, 1, 1, 1, 1, 1)  # fmt: skip
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

# row SMALL_FRICTION: the friction's work along the string since the start [J], the
# contacts' switches, any node with a contact (1.0)
(FRICTION_WORK, FRICTION_SWITCHES, FRICTION_ANY, FRICTION_SIZE) = field_starts(
    1, 1, 1
)  # fmt: skip

# --- the steady-cycle tracker of the lumped engine -------------------------------------
# crossings seen, time of the last one, running bit twist-rate max and min since it,
# the extremes of the last complete cycle, the change of the state at the last crossing
(CYCLE_COUNT, CYCLE_T_LAST, CYCLE_RUN_MAX, CYCLE_RUN_MIN, CYCLE_MAX, CYCLE_MIN,
 CYCLE_CHANGE, CYCLE_SIZE) = field_starts(*(1,) * 7)  # fmt: skip
# 2 Omega [rad/s], omega_1 [rad/s], t_end [s], window length [s], tolerance [S_SS units]
(CYCLE_SET_TWICE_OMEGA, CYCLE_SET_OMEGA_1, CYCLE_SET_T_END, CYCLE_SET_WINDOW,
 CYCLE_SET_TOLERANCE, CYCLE_SETTINGS_SIZE) = field_starts(*(1,) * 5)  # fmt: skip

# --- the wave model: a run's settings (solvers/characteristics.py) --------------------
# time step [s], bit inertia [kg m^2], drag alpha [1/s], weight on bit [N], bit radius
# [m], held top (1.0), final set speed [rad/s], |motor torque| limit [N m], steps of this
# call, first step of the window, record and field every so many steps (0: never), top
# drive's drag [N m s/rad], track the energies (1.0), drag spacing [nodes], steady-cycle
# tolerance [S_SS units], reference speed [rad/s], least time between two ends of a cycle
# [s], steps of the run, the contacts' threshold speed [rad/s], contacts along the string
# (1.0), the largest speed below the threshold [rad/s], the time from which the set speed
# is constant [s]
(WAVE_DT, WAVE_BIT_INERTIA, WAVE_ALPHA, WAVE_WOB, WAVE_BIT_RADIUS, WAVE_HELD,
 WAVE_SET_SPEED, WAVE_MAX_TORQUE, WAVE_STEPS, WAVE_WINDOW_START, WAVE_RECORD_EVERY,
 WAVE_FIELD_EVERY, WAVE_TOP_DRAG, WAVE_TRACK_ENERGY, WAVE_DRAG_SPACING,
 WAVE_STEADY_TOLERANCE, WAVE_REFERENCE, WAVE_CYCLE_GAP, WAVE_RUN_STEPS, WAVE_THRESHOLD,
 WAVE_CONTACTS, WAVE_BELOW_THRESHOLD, WAVE_RAMP_END, WAVE_SIZE) = field_starts(
    *(1,) * 23
)  # fmt: skip

# --- the wave model: a run's summary, carried from call to call ------------------------
# bit speed min and max over the window [rad/s], the sum of the top speed over it and its
# steps, the energies over the run [J] (work in, dissipated by the bit, the bit's drag,
# the string's drag, the top drive's drag), the step that failed (0: none); the powers of
# the last step (POWER_*) [W]; steps taken; the steady-cycle tracker (crossings, time of
# the last, running bit speed max and min since it, the last cycle's extremes, the change
# of the state, the step the run ended on a cycle (0: it did not), the state of the last
# crossing kept); the torque on bit of the last step [N m]; the contacts' work [J]; the
# largest surface torque of the run and the smallest and largest of the window [N m];
# the first step the bit is faster than the contacts' threshold (0: not yet)
(SUM_BIT_SPEED_MIN, SUM_BIT_SPEED_MAX, SUM_TOP_SPEED_SUM, SUM_WINDOW_STEPS, SUM_WORK_IN,
 SUM_BIT_DISSIPATION, SUM_BIT_DRAG_DISSIPATION, SUM_STRING_DRAG_DISSIPATION,
 SUM_TOP_DRAG_DISSIPATION, SUM_FAILED_STEP, SUM_POWERS, SUM_STEPS, SUM_COUNT, SUM_T_LAST,
 SUM_RUN_MAX, SUM_RUN_MIN, SUM_CYCLE_MAX, SUM_CYCLE_MIN, SUM_CHANGE, SUM_ENDED, SUM_KEPT,
 SUM_BIT_TORQUE, SUM_FRICTION_WORK, SUM_SURFACE_TORQUE_PEAK, SUM_SURFACE_TORQUE_MIN,
 SUM_SURFACE_TORQUE_MAX, SUM_BIT_FIRST_MOTION, SUMMARY_SIZE) = field_starts(
    *(1,) * 10, 5, *(1,) * 16
)  # fmt: skip
# within SUM_POWERS: motor, bit, bit drag, the end and junction dampers, top-drive drag
(POWER_IN, POWER_BIT, POWER_BIT_DRAG, POWER_STRING_DRAG, POWER_TOP_DRAG,
 POWER_COUNT) = field_starts(*(1,) * 5)  # fmt: skip

SUMMARY_FIELDS = (
    "bit_speed_min",
    "bit_speed_max",
    "top_speed_sum",
    "window_steps",
    "work_in",
    "bit_dissipation",
    "bit_drag_dissipation",
    "string_drag_dissipation",
    "top_drag_dissipation",
    "failed_step",
)
"""Keys of the run summary for slots SUM_BIT_SPEED_MIN .. SUM_FAILED_STEP, in order:
extremes and sums over the window; energies [J] over the run."""

# --- the wave model: the recorded signals, the bit's and the top drive's states ---------
# bit speed [rad/s], torque on bit, surface torque [N m], top speed [rad/s], motor torque
(REC_BIT_SPEED, REC_BIT_TORQUE, REC_SURFACE_TORQUE, REC_TOP_SPEED, REC_MOTOR_TORQUE,
 RECORD_COLUMNS) = field_starts(*(1,) * 5)  # fmt: skip
# WaveState.bit: w_b [rad/s], w_b one step earlier, steps taken
BIT_SPEED, BIT_SPEED_BEFORE, BIT_STEPS, BIT_STATE_SIZE = field_starts(1, 1, 1)
# WaveState.top and the top drive's state x: Omega_0 [rad/s], then the controller states
X_TOP_SPEED, X_CONTROLLER = field_starts(1)
# TopArrays.coefficients, the controller's gains (top_drive_boundary.motor_torque): u0
# [N m], kp of [top_drive] (the motor torque per unit speed error [N m s/rad]; 0 without a
# set speed), the motor torque per unit pipe torque [-], then c (one per controller state)
COEF_U0, COEF_KP, COEF_PIPE_GAIN, COEF_STATES = field_starts(1, 1, 1)

# --- the wave model: the grid's buffers (solvers/wave_state.py, wave_buffers.py) --------
# per section, integers: cells n, first node in the state arrays, first slot of the
# buffer, its width W, the live span L, the regular inner dampers, the node of the other
# inner damper (-1: none), the row and column offsets of node n and of that damper
(CELLS, NODE_START, BUFFER_START, WIDTH, LIVE, INNER, SPECIAL, LAST_ROW, LAST_COLUMN,
 SPECIAL_ROW, SPECIAL_COLUMN, SECTION_INTEGERS) = field_starts(*(1,) * 11)  # fmt: skip
# per section, floats: Z, (2 Z / (2 Z + c), c) of the regular inner dampers and of the other
(Z, RATIO_INNER, C_INNER, RATIO_SPECIAL, C_SPECIAL, SECTION_FLOATS) = field_starts(
    *(1,) * 5
)  # fmt: skip
# per section, the heads: row and column of node 0's slot of p, then of m
HEAD_P_ROW, HEAD_P_COLUMN, HEAD_M_ROW, HEAD_M_COLUMN, HEAD_SIZE = field_starts(1, 1, 1, 1)
# rows of the buffers: p, m
BUFFER_P, BUFFER_M, BUFFER_ROWS = field_starts(1, 1)
# rows of the node scratch and of the state kept at a cycle's end: speed [rad/s], torque
# / Z' [rad/s]; the kept state has two columns past the nodes: the bit's and the top's speed
NODE_SPEED, NODE_TORQUE, NODE_ROWS = field_starts(1, 1)
CROSS_BIT, CROSS_TOP, CROSS_EXTRA = field_starts(1, 1)
# the set-speed table (solvers/set_speed.py; TopArrays.speed_table): rows time [s], set
# speed [rad/s], and for the lumped engines the held top's twist psi [rad] (the integral
# of the set speed less Omega_ref from t = 0)
TABLE_TIME, TABLE_SPEED, TABLE_TWIST, TABLE_ROWS = field_starts(1, 1, 1)
# the contacts' table: C_s, C_d [N m], the speed of the last step [rad/s], the node
(CONTACT_STATIC, CONTACT_DYNAMIC, CONTACT_SPEED, CONTACT_NODE, CONTACT_ROWS) = field_starts(
    1, 1, 1, 1
)  # fmt: skip
# per section, the contacts' index: its first regular inner node, its other inner drag
# node, its bottom junction (-1: none)
(CONTACT_REGULAR, CONTACT_OTHER, CONTACT_JUNCTION, CONTACT_INDEX_COLUMNS) = field_starts(
    1, 1, 1
)  # fmt: skip

__all__ = ["field_starts", *(name for name in tuple(globals()) if name.isupper())]
