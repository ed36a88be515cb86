"""Where each value sits in the arrays the axial kernels take and return.

The compiled step loops of the lumped chain (:mod:`torsio.solvers.axial_kernel`) and of the
distributed pipe (:mod:`torsio.solvers.axial_wave_kernel`) exchange index-packed float arrays with
the Python side (:mod:`torsio.solvers.axial_run_setup`, :mod:`torsio.solvers.axial_wave_setup`,
:mod:`torsio.analysis.axial_transient`). Each array's entries are named here, once, in order, and
each index is a module-level int unpacked from the names (numba compiles it as a
constant): the kernels, their shared bit step (:mod:`torsio.axial.bit_step`) and the
encoders index with these names only.

- ``stats``, what a run returns: :data:`STATS` (the same for both kernels);
- ``samples``, the bit's signals: :data:`SAMPLE_COLUMNS` (the same for both kernels);
- ``settings``, a run's scalars: :data:`CHAIN_SETTINGS` (the lumped chain's) and
  :data:`WAVE_SETTINGS` (the distributed pipe's), both beginning with the entries of
  :data:`RUN_SETTINGS`;
- ``bha``, the distributed pipe's lumped BHA: :data:`BHA_STATE`;
- ``top``, the lumped chain's top drive: :data:`TOP_DRIVE`, and ``top_state``, its node:
  :data:`TOP_NODE`;
- ``contacts``, the lumped chain's string contacts: :data:`CONTACT_ROW`;
- ``bit``, the law's row (:func:`torsio.solvers.axial_run_setup.bit_law_row`): :data:`BIT_ROW`.

Adding an entry: insert its name where it belongs and its index in the unpacking beside
it; write it in the encoder and read it in the kernel by name.

Examples
--------
>>> STATS[POSITION_END], SAMPLE_COLUMNS[BIT_TORQUE], WAVE_SETTINGS[SAMPLE_EVERY]
('position_end', 'bit_torque', 'sample_every')
>>> CHAIN_SETTINGS[FREQUENCY], WAVE_SETTINGS[BHA_MASS], BHA_STATE[BHA_SPEED]
('frequency', 'bha_mass', 'speed')
"""

from __future__ import annotations

__all__ = [
    "BHA_STATE",
    "BIT_ROW",
    "CHAIN_SETTINGS",
    "CONTACT_ROW",
    "RUN_SETTINGS",
    "SAMPLE_COLUMNS",
    "STATS",
    "TOP_DRIVE",
    "TOP_NODE",
    "WAVE_CONTACT_ROW",
    "WAVE_SETTINGS",
]

STATS = (
    "bit_speed_max",
    "bit_speed_min",
    "axial_speed_max",
    "axial_speed_min",
    "stuck_steps",
    "off_bottom_steps",
    "window_steps",
    "position_start",
    "position_end",
    "work",
    "torque_integral",
    "weight_integral",
    "failed",
    "steps_done",
    "depth_of_cut_max",
    "string_friction_work",
    "contact_switches",
    "top_work",
    "hook_work",
    "damper_work",
    "bit_work",
)
"""The entries of ``stats`` after a run, in order: the window's extremes of Ω_b and V_b,
its stuck and off-bottom steps and its steps, the bit's position at its start and end [m],
the work on the bit [J], the integrals of the bit torque [N m s] and weight [N s]; 1 in
``failed`` when the history was too short for the delay, and the steps done; the largest
depth of cut [m per rev]; then over the whole run (the lumped chain's energy balance,
docs/axial.md "Friction along the string"): the work of the friction along the string [J,
dissipated, >= 0], the contacts' stick-slip switches, the work into the string at the top
(surface torque × top speed) and at the hook [J], the dampers' dissipation [J] and the work
on the bit [J]."""

(
    SPEED_MAX,
    SPEED_MIN,
    VELOCITY_MAX,
    VELOCITY_MIN,
    STUCK,
    OFF_BOTTOM,
    COUNT,
    POSITION_START,
    POSITION_END,
    WORK,
    TORQUE_INTEGRAL,
    WEIGHT_INTEGRAL,
    FAILED,
    STEPS_DONE,
    DEPTH_MAX,
    FRICTION_WORK,
    CONTACT_SWITCHES,
    TOP_WORK,
    HOOK_WORK,
    DAMPER_WORK,
    BIT_WORK,
) = range(len(STATS))

SAMPLE_COLUMNS = (
    "time",
    "bit_angle",
    "bit_speed",
    "bit_position",
    "bit_velocity",
    "depth_of_cut",
    "bit_weight",
    "bit_torque",
    "delay",
    "top_torque",
    "top_speed",
    "motor_torque",
    "surface_torque",
)
"""The columns of ``samples``: s, rad, rad/s, m (down), m/s, m per rev, N, N m, s, N m, then
the top drive's speed [rad/s], its motor torque [N m] and the surface torque [N m] (the
torque in the string at the top: ``top_torque`` again, under the name the torsional runs
use; with the top held the motor torque is the surface torque)."""

SAMPLE_UNITS = ("s", "rad", "rad_s", "m", "m_s", "m_rev", "N", "Nm", "s", "Nm", "rad_s", "Nm", "Nm")
"""The units of :data:`SAMPLE_COLUMNS`, as CSV headers write them (``time_s``)."""

(
    TIME,
    BIT_ANGLE,
    BIT_SPEED,
    BIT_POSITION,
    BIT_VELOCITY,
    DEPTH_OF_CUT,
    BIT_WEIGHT,
    BIT_TORQUE,
    DELAY,
    TOP_TORQUE,
    TOP_DRIVE_SPEED,
    MOTOR_TORQUE,
    SURFACE_TORQUE,
) = range(len(SAMPLE_COLUMNS))

TOP_DRIVE = (
    "held",
    "inverse_inertia",
    "drag",
    "motor_torque_constant",
    "max_torque",
    "set_speed",
)
"""The entries of the lumped kernel's ``top`` (:mod:`torsio.solvers.axial_kernel`): 1 when the top
is held (no node), 1/J [1/(kg m²)], drag [N m s/rad], u0 [N m], max_torque [N m] (inf:
none), Ω_set [rad/s] (NaN: none, the speed error is then 0). The set speed in time (a
ramp, a recorded speed) is the run's set-speed table (:mod:`torsio.solvers.set_speed`)."""

(
    TOP_HELD,
    TOP_INVERSE_INERTIA,
    TOP_DRAG,
    TOP_U0,
    TOP_MAX_TORQUE,
    TOP_SET_SPEED,
) = range(len(TOP_DRIVE))

TOP_NODE = ("angle", "speed")
"""The entries of the lumped kernel's ``top_state``: the top drive's θ_top [rad] and Ω_top
[rad/s] when it is a node."""

TOP_NODE_ANGLE, TOP_NODE_SPEED = range(len(TOP_NODE))

RUN_SETTINGS = (
    "step",
    "steps",
    "top_speed",
    "hook_weight",
    "speed_hook",
    "hook_speed",
    "window_start",
    "sample_every",
    "start_time",
    "first_step",
    "stick_speed",
)
"""The head of both kernels' ``settings``: h [s], the step a call stops before, Ω₀ [rad/s],
W₀ [N], the hook (0 weight, 1 speed), V_h [m/s], the window's first step, sample every (0:
never), t at step 0 [s], the step a call starts at (a run goes in chunks of steps
``first_step`` .. ``steps`` - 1: :func:`torsio.analysis.axial_transient.run_kernel`), the speed
[rad/s] below which the bit counts as stuck (the stick threshold times Ω₀)."""

(
    STEP,
    STEPS,
    TOP_SPEED,
    HOOK_WEIGHT,
    SPEED_HOOK,
    HOOK_SPEED,
    WINDOW_START,
    SAMPLE_EVERY,
    START_TIME,
    FIRST_STEP,
    STICK_SPEED,
) = range(len(RUN_SETTINGS))

CHAIN_SETTINGS = (
    *RUN_SETTINGS,
    "hook_start",
    "prescribed",
    "amplitude",
    "frequency",
    "threshold_speed",
    "rock_surface",
)
"""The entries of the lumped chain's ``settings`` (:mod:`torsio.solvers.axial_kernel`): those of
:data:`RUN_SETTINGS`, then U_h0 [m] (the hook's position at step 0), a prescribed bit
rotation (0/1), its amplitude A and frequency f [rad/s], the string contacts' threshold
speed [rad/s], the rigid rock's surface [m] under a law of the torque alone (the bit is on
bottom at U_b >= it)."""

HOOK_START, PRESCRIBED, AMPLITUDE, FREQUENCY, THRESHOLD_SPEED, ROCK_SURFACE = range(
    len(RUN_SETTINGS), len(CHAIN_SETTINGS)
)

CONTACT_ROW = ("static_force", "sliding_force", "radius")
"""The rows of the lumped kernel's ``contacts`` (one column per node,
:mod:`torsio.well.axial_contacts`): F_s, F_d [N] and r [m]; all 0: no contact."""

STATIC_FORCE, SLIDING_FORCE, CONTACT_RADIUS = range(len(CONTACT_ROW))

WAVE_SETTINGS = (
    *RUN_SETTINGS,
    "bha_mass",
    "bha_inertia",
    "axial_top_impedance",
    "axial_bottom_impedance",
    "torsional_top_impedance",
    "torsional_bottom_impedance",
    "pipe_threshold_speed",
)
"""The entries of the distributed pipe's ``settings`` (:mod:`torsio.solvers.axial_wave_kernel`):
those of :data:`RUN_SETTINGS`, then m_b [kg], I_b [kg m²], Z of the top and bottom sections
axially [N s/m] and torsionally [N m s/rad], the string contacts' threshold speed
[rad/s]."""

(
    BHA_MASS,
    BHA_INERTIA,
    AXIAL_TOP_IMPEDANCE,
    AXIAL_BOTTOM_IMPEDANCE,
    TORSIONAL_TOP_IMPEDANCE,
    TORSIONAL_BOTTOM_IMPEDANCE,
    PIPE_THRESHOLD_SPEED,
) = range(len(RUN_SETTINGS), len(WAVE_SETTINGS))

WAVE_CONTACT_ROW = (
    *CONTACT_ROW,
    "axial_node",
    "torsional_node",
    "axial_impedance",
    "torsional_impedance",
    "velocity",
    "speed",
    "stuck",
)
"""The rows of the distributed pipe's ``contacts`` (one column per contact,
:func:`torsio.solvers.axial_wave_lines.pipe_contacts`): those of :data:`CONTACT_ROW`, the contact's
node in the axial and in the torsional line's state (as floats), Z there axially [N s/m]
and torsionally [N m s/rad], its last step's V [m/s] and ω [rad/s], 1 while it is stuck."""

(
    AXIAL_NODE,
    TORSIONAL_NODE,
    AXIAL_IMPEDANCE,
    TORSIONAL_IMPEDANCE,
    CONTACT_VELOCITY,
    CONTACT_SPEED,
    CONTACT_STUCK,
) = range(len(CONTACT_ROW), len(WAVE_CONTACT_ROW))

BHA_STATE = ("position", "velocity", "angle", "speed")
"""The entries of the distributed pipe's ``bha``: U_b [m, down], V_b [m/s], Φ_b [rad],
Ω_b [rad/s]."""

BHA_POSITION, BHA_VELOCITY, BHA_ANGLE, BHA_SPEED = range(len(BHA_STATE))

BIT_ROW = (
    "cutting_weight_per_depth",
    "cutting_torque_per_depth",
    "friction_weight",
    "friction_torque_per_weight",
    "angle_per_blade",
    "blades",
    "law_torque",
    "bit_radius",
)
"""The entries of ``bit``: ζ ε a [N/m], ε a²/2 [N m/m], σ a l [N], μ γ a/2 [m], 2π/n [rad],
n; 1 when the torque on bit is a law's ``torque(speed, wob, radius)`` (a law of the torque
alone, the rock rigid: :mod:`torsio.physics.torque_law_bit`; the lumped kernel only), 0 for the
RGD bit; the bit radius a [m] that law takes."""

(
    CUTTING_WEIGHT_PER_DEPTH,
    CUTTING_TORQUE_PER_DEPTH,
    FRICTION_WEIGHT,
    FRICTION_TORQUE_PER_WEIGHT,
    ANGLE_PER_BLADE,
    BLADES,
    LAW_TORQUE,
    BIT_RADIUS,
) = range(len(BIT_ROW))
