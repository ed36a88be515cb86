"""What one run of the distributed pipe needs: its grid and step, the initial state, the
history before t = 0 (:mod:`torsio.solvers.axial_wave_kernel`).

**Step rule.** h_max = 2π / (ω_fast × ``steps_per_period``), ω_fast the largest of the
bit's axial contact frequency √(2 n ζ ε a / m_b) and the rates Z_a/m_b, Z_t/I_b at which the
bottom section takes the BHA's motion away; a given ``step`` caps it further. Then
:func:`torsio.model.wave_grid.choose_time_step` takes the largest h ≤ h_max that makes
every section's axial and torsional travel time L/c a whole number of steps within the
assembly's ``travel_time_tolerance`` (one h for both lines: the cells per section differ by
line). The grid is then the pipe of lengths n h c: the same impedances and wave speeds,
each travel time changed by at most the tolerance, and so (by Rayleigh's quotient: a
section's strain energy scales as 1/(1 + ε), its kinetic energy as 1 + ε) each natural
frequency by at most about the same fraction (docs/axial.md, "The distributed pipe").

**Starts.** ``"steady"``: the pipe carrying W₀ and T₀ throughout (a uniform strain and
twist gradient), every point at V₀ and Ω₀: p = F + Z v, m = F − Z v with (F, v) = (W₀, V₀)
axially and (T₀, Ω₀) torsionally (with contacts along the pipe, the bit's W_b and T_b, and
above each contact its steady friction more); the bit speed raised by ``perturbation``.
``"rest"``:
the pipe at rest carrying W₀ axially (p = m = W₀), untwisted (p = m = 0), the bottom flat,
the top drive turning at Ω₀ (and the speed hook moving at V₀) from t = 0.

Examples
--------
>>> from torsio.model.axial_assembly import axial_model, pipe_string, tube_section
>>> from torsio.model.wave import WaveStrategy
>>> string = pipe_string([tube_section(1000.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 3e-5)],
...                      3e4, 455.65)
>>> assembly = axial_model(string, WaveStrategy(rigid_bha=True))
>>> grid = pipe_grid(assembly, 2e-3)
>>> grid.axial_cells, grid.torsional_cells, round(grid.step * 1e3, 6)  # ms
((100,), (161,), 1.933599)
>>> bool(grid.travel_time_errors.max() <= assembly.travel_time_tolerance)
True
>>> from torsio.solvers.axial_layouts import STATS
>>> from torsio.axial.rgd import rgd_example
>>> from torsio.solvers.axial_run_setup import RunOptions
>>> options = RunOptions(1.0, 0.5, start="steady", perturbation=0.0)
>>> setup = wave_run_setup(assembly, rgd_example(), 100e3, 180.0, options)
>>> stats = run_wave(setup, np.zeros((0, 10)), 0)
>>> advance = stats[STATS.index("position_end")] - stats[STATS.index("position_start")]
>>> round(float(advance) / (setup.window_steps * setup.step) / setup.steady.rop, 12)  # V₀
1.0
"""

from __future__ import annotations

import attrs
import numpy as np
from numpy.typing import NDArray

from torsio.axial.steady import steady_drilling
from torsio.axial.steady_friction import SteadyFriction, steady_with_friction
from torsio.errors import ConfigError
from torsio.model.axial_assembly import pipe_rows
from torsio.model.wave import WaveModel
from torsio.model.wave_grid import choose_time_step
from torsio.physics.axial_top_drive import TopDriveArrays
from torsio.physics.top_drive_boundary import TopDriveBoundary
from torsio.physics.torque_law_bit import AxialBit, TorqueLawBit
from torsio.solvers import axial_layouts as slot
from torsio.solvers import axial_wave_kernel as wave_kernel
from torsio.solvers.axial_run_budget import check_run_work
from torsio.solvers.axial_run_setup import (
    BitStart,
    KernelSetup,
    RunOptions,
    check_set_speed,
    kernel_setup,
)
from torsio.solvers.axial_wave_lines import junction_rows
from torsio.well.axial_contacts import AxialContacts

__all__ = [
    "PipeGrid",
    "WaveRunSetup",
    "contact_nodes",
    "fastest_rate",
    "pipe_grid",
    "run_wave",
    "wave_chunk",
    "wave_run_setup",
]


def _offsets(cells: NDArray[np.int64]) -> NDArray[np.int64]:
    return np.concatenate([[0], np.cumsum(cells + 1)]).astype(np.int64)


@attrs.frozen(eq=False)
class PipeGrid:
    """The characteristic grid of a distributed pipe, both lines on one step.

    Attributes
    ----------
    step : float
        h [s]; a wave crosses one cell per step.
    axial_cells, torsional_cells : tuple of int
        Cells per section, from the top down.
    axial_offsets, torsional_offsets : ndarray of int
        First node of each section in the line's state, and the line's size.
    axial_junctions, torsional_junctions : ndarray (4, sections − 1)
        :func:`torsio.solvers.axial_wave_lines.junction_rows`.
    travel_time_errors : ndarray (2, sections)
        |n h − L/c| / (L/c) of each section, axially (row 0) and torsionally (row 1).
    """

    step: float
    axial_cells: tuple[int, ...]
    torsional_cells: tuple[int, ...]
    axial_offsets: NDArray[np.int64]
    torsional_offsets: NDArray[np.int64]
    axial_junctions: NDArray[np.float64]
    torsional_junctions: NDArray[np.float64]
    travel_time_errors: NDArray[np.float64]


def fastest_rate(pipe: WaveModel) -> float:
    """The largest of Z_a/m_b and Z_t/I_b [1/s], the rates at which the pipe's bottom
    section takes the BHA's motion away: what the step must resolve beside the bit."""
    rows = pipe_rows(pipe)
    return float(max(rows.impedances[-1] / rows.bha_mass, pipe.impedances[-1] / pipe.bit_inertia))


def pipe_grid(assembly: WaveModel, max_step: float) -> PipeGrid:
    """The grid with the largest step ≤ ``max_step`` [s] within the assembly's travel-time
    tolerance (ConfigError on ``discretization.travel_time_tolerance`` when there is none)."""
    axial = assembly.lengths / pipe_rows(assembly).wave_speeds
    torsional = assembly.lengths / assembly.wave_speeds
    taus = np.concatenate([axial, torsional])
    h, cells = choose_time_step(taus, max_step, assembly.travel_time_tolerance)
    sections = axial.size
    axial_cells, torsional_cells = cells[:sections], cells[sections:]
    errors = (np.abs(cells * h - taus) / taus).reshape(2, sections)
    return PipeGrid(
        step=float(h),
        axial_cells=tuple(int(n) for n in axial_cells),
        torsional_cells=tuple(int(n) for n in torsional_cells),
        axial_offsets=_offsets(axial_cells),
        torsional_offsets=_offsets(torsional_cells),
        axial_junctions=junction_rows(pipe_rows(assembly).impedances),
        torsional_junctions=junction_rows(assembly.impedances),
        travel_time_errors=errors,
    )


def _line_state(
    offsets: NDArray[np.int64],
    impedances: NDArray[np.float64],
    force: float,
    velocity: float,
    nodes: NDArray[np.int64],
    loads: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """p, m of a line moving at ``velocity`` that carries ``force`` at its bottom, and
    above each contact node ``nodes`` its friction ``loads`` more (the pair stored at a
    contact node is the one leaving it: p from the force below it, m from the one above)."""
    z = np.repeat(impedances, np.diff(offsets))
    below = np.full(z.size, float(force))
    above = below.copy()
    for node, load in zip(nodes, loads, strict=True):
        below[:node] += load
        above[: node + 1] += load
    return below + z * velocity, above - z * velocity


def contact_nodes(
    offsets: NDArray[np.int64], lengths: NDArray[np.float64], depths: NDArray[np.float64]
) -> NDArray[np.int64]:
    """The node of a line's state nearest each depth [m below the pipe's top] among the
    inner nodes of its section (not a junction, nor an end); a ConfigError naming
    ``well`` when a section has none or two contacts share a node."""
    tops = np.concatenate([[0.0], np.cumsum(lengths)])
    nodes = []
    for depth in depths:
        s = min(int(np.searchsorted(tops, depth, side="right")) - 1, lengths.size - 1)
        cells = int(offsets[s + 1] - offsets[s] - 1)
        if cells < 2:
            raise ConfigError(
                "well",
                f"a contact at {depth:.6g} m falls in pipe section {s + 1}, whose grid has no "
                "inner node to carry it (expected at least two cells: a smaller step)",
            )
        k = int(np.clip(round((depth - tops[s]) / lengths[s] * cells), 1, cells - 1))
        nodes.append(int(offsets[s]) + k)
    found = np.array(nodes, dtype=np.int64)
    if np.unique(found).size != found.size:
        raise ConfigError(
            "well",
            "two contacts along the pipe fall on one node of its grid (expected contacts "
            "farther apart than its cells)",
        )
    return found


@attrs.frozen(eq=False)
class WaveRunSetup(KernelSetup):
    """The distributed kernel's arrays for one run (:func:`torsio.solvers.axial_wave_kernel.march`):
    those of every run (:class:`~torsio.solvers.axial_run_setup.KernelSetup`), the grid and the
    state of its lines and of the BHA."""

    grid: PipeGrid
    axial_p: NDArray[np.float64]
    axial_m: NDArray[np.float64]
    torsional_p: NDArray[np.float64]
    torsional_m: NDArray[np.float64]
    bha: NDArray[np.float64]
    contacts: NDArray[np.float64] = attrs.field(
        factory=lambda: np.zeros((len(slot.WAVE_CONTACT_ROW), 0))
    )
    friction: SteadyFriction | None = None
    speed_table: NDArray[np.float64] = attrs.field(factory=lambda: np.zeros((3, 1)))
    """The held top's set speed against time (:func:`torsio.solvers.set_speed.twist_table`)."""


def wave_run_setup(
    assembly: WaveModel,
    bit: AxialBit,
    wob: float,
    rpm: float,
    options: RunOptions,
    contacts: AxialContacts | None = None,
    top_drive: TopDriveBoundary | None = None,
) -> WaveRunSetup:
    """The grid, the initial state and the history of a run (see the module docstring) at
    ``wob`` [N] and ``rpm`` [rev/min], set up as ``options`` say; the RGD bit only (a law of
    the torque alone runs on a lumped chain, a ConfigError naming ``bit_rock.law``).
    ``contacts``: the pipe's contacts with the borehole at their ``depths``
    (:mod:`torsio.well.axial_contacts`, the normal force at ``wob``), each on the inner
    node of both lines nearest it (:func:`contact_nodes`); the steady start then carries
    their steady friction (:mod:`torsio.axial.steady_friction`). ``top_drive``: a held
    top's boundary (a recorded speed; None: held at Ω₀); the pipe's top has no node.
    """
    if isinstance(bit, TorqueLawBit):
        raise ConfigError(
            "bit_rock.law",
            f"{bit.name!r} is a law of the torque alone: it runs on a lumped chain only "
            "(expected a lumped chain (axial_chain), or law = 'rgd' on the distributed pipe)",
        )
    rows = pipe_rows(assembly)
    friction = None
    if contacts is None:
        steady = steady_drilling(bit, wob, rpm)
    else:
        contacts = contacts.at_wob(wob)
        steady, friction = steady_with_friction(bit, wob, rpm, contacts, rows.hook)
    options.check()
    check_set_speed(top_drive, options)
    fastest = fastest_rate(assembly)
    grid = pipe_grid(assembly, options.largest_step(bit, rows.bha_mass, fastest))
    h = grid.step
    nodes = int(grid.axial_offsets[-1] + grid.torsional_offsets[-1])
    check_run_work(options, h, steady.delay, nodes, bit, rows.bha_mass, fastest, "section")
    omega0, v0 = steady.bit_speed, steady.rop
    on_steady = options.start == "steady"
    axial_z, torsional_z = rows.impedances, assembly.impedances
    speed, velocity = (omega0, v0) if on_steady else (0.0, 0.0)
    torque = steady.bit_torque if on_steady else 0.0
    hook_force = friction.hook_force if friction is not None else float(wob)
    table = np.zeros((len(slot.WAVE_CONTACT_ROW), 0))
    loads = np.zeros((2, 0))
    axial_nodes = torsional_nodes = np.zeros(0, dtype=np.int64)
    if contacts is not None and friction is not None:
        if contacts.depths is None:
            raise ConfigError("well", "the pipe's contacts need their depths (axial_contacts)")
        axial_nodes = contact_nodes(grid.axial_offsets, assembly.lengths, contacts.depths)
        torsional_nodes = contact_nodes(grid.torsional_offsets, assembly.lengths, contacts.depths)
        table = _contact_table(contacts, axial_nodes, torsional_nodes, assembly, grid)
        if on_steady:
            loads = np.array([friction.node_force, friction.node_torque])
            table[slot.CONTACT_VELOCITY], table[slot.CONTACT_SPEED] = v0, omega0
    axial_bottom = steady.wob if on_steady else float(wob)  # at rest: W₀ throughout
    axial_p, axial_m = _line_state(grid.axial_offsets, axial_z, axial_bottom, velocity,
                                   axial_nodes[: loads.shape[1]], loads[0])  # fmt: skip
    torsional_p, torsional_m = _line_state(grid.torsional_offsets, torsional_z, torque, speed,
                                           torsional_nodes[: loads.shape[1]], loads[1])  # fmt: skip
    bit_speed = speed * (1.0 + options.perturbation) if on_steady else 0.0
    torsional_m[-1] = torsional_p[-1] - 2.0 * torsional_z[-1] * bit_speed  # the bit's end
    bha = np.array([0.0, velocity, 0.0, bit_speed])
    angle, position = bha[slot.BHA_ANGLE], bha[slot.BHA_POSITION]
    bit_start = BitStart(angle, position, bha[slot.BHA_SPEED], bha[slot.BHA_VELOCITY])
    size = len(slot.WAVE_SETTINGS)
    kernel = kernel_setup(steady, bit, h, options, size, rows.hook, bit_start)
    settings = kernel.settings
    settings[slot.BHA_MASS], settings[slot.BHA_INERTIA] = rows.bha_mass, assembly.bit_inertia
    settings[slot.AXIAL_TOP_IMPEDANCE] = axial_z[0]
    settings[slot.AXIAL_BOTTOM_IMPEDANCE] = axial_z[-1]
    settings[slot.TORSIONAL_TOP_IMPEDANCE] = torsional_z[0]
    settings[slot.TORSIONAL_BOTTOM_IMPEDANCE] = torsional_z[-1]
    settings[slot.HOOK_WEIGHT] = hook_force
    settings[slot.PIPE_THRESHOLD_SPEED] = contacts.threshold_speed if contacts is not None else 0.0
    return WaveRunSetup(
        **attrs.asdict(kernel, recurse=False),
        grid=grid,
        axial_p=axial_p,
        axial_m=axial_m,
        torsional_p=torsional_p,
        torsional_m=torsional_m,
        bha=bha,
        contacts=table,
        friction=friction,
        speed_table=TopDriveArrays.from_boundary(top_drive, omega0).speed_table,
    )


def _contact_table(
    contacts: AxialContacts,
    axial_nodes: NDArray[np.int64],
    torsional_nodes: NDArray[np.int64],
    assembly: WaveModel,
    grid: PipeGrid,
) -> NDArray[np.float64]:
    """The kernel's ``contacts`` (:data:`torsio.solvers.axial_layouts.WAVE_CONTACT_ROW`), at
    rest."""
    table = np.zeros((len(slot.WAVE_CONTACT_ROW), axial_nodes.size))
    table[slot.STATIC_FORCE] = contacts.static_force
    table[slot.SLIDING_FORCE] = contacts.sliding_force
    table[slot.CONTACT_RADIUS] = contacts.radius
    table[slot.AXIAL_NODE], table[slot.TORSIONAL_NODE] = axial_nodes, torsional_nodes
    sections_a = np.searchsorted(grid.axial_offsets, axial_nodes, side="right") - 1
    sections_t = np.searchsorted(grid.torsional_offsets, torsional_nodes, side="right") - 1
    table[slot.AXIAL_IMPEDANCE] = pipe_rows(assembly).impedances[sections_a]
    table[slot.TORSIONAL_IMPEDANCE] = assembly.impedances[sections_t]
    return table


def run_wave(setup: WaveRunSetup, samples: NDArray[np.float64], sample_every: int) -> NDArray:
    """Run the compiled loop on ``setup`` in one call (its state arrays change); the stats
    vector (:data:`torsio.solvers.axial_layouts.STATS`). Long runs go in chunks instead:
    :func:`torsio.analysis.axial_transient.run_kernel`."""
    settings = setup.settings.copy()
    settings[slot.SAMPLE_EVERY] = sample_every
    stats = np.zeros(len(slot.STATS))
    wave_chunk(setup, settings, stats, samples)
    return stats


def wave_chunk(
    setup: WaveRunSetup,
    settings: NDArray[np.float64],
    stats: NDArray[np.float64],
    samples: NDArray[np.float64],
) -> None:
    """One call of the compiled loop on ``setup`` with ``settings`` (its steps
    ``FIRST_STEP`` .. ``STEPS`` - 1), adding to ``stats`` and ``samples``."""
    grid = setup.grid
    wave_kernel.march(
        setup.bit,
        settings,
        setup.speed_table,
        grid.axial_offsets,
        grid.axial_junctions,
        setup.axial_p,
        setup.axial_m,
        grid.torsional_offsets,
        grid.torsional_junctions,
        setup.torsional_p,
        setup.torsional_m,
        setup.bha,
        setup.contacts,
        setup.history,
        setup.cursor,
        stats,
        samples,
    )
