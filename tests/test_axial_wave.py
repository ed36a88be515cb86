"""The distributed (wave) axial-torsional model with the RGD bit (torsio.axial.wave_*).

Independent references: the exact continuum frequencies of the axial and the torsional bar
with a lumped end (torsio.model.continuum.bar_frequencies and continuum_modes with the BHA
rigid, Wittrick-Williams, checked in tests/test_continuum.py; and the closed form
sin x + r x cos x = 0 of a free-top bar found here by brentq), the eigenfrequencies of the
fine lumped chain (pipe_chain of tests/axial_files.py: strategy C of the same pipe), the
steady drilling state in closed form (torsio.axial.steady: RGD 2007, Teale 1965) and the
conservation of the power (p² − m²)/(4 Z) at a junction.
"""

from __future__ import annotations

import math

import attrs
import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
from axial_files import pipe_chain, wave_pipe

from torsio.analysis.axial_transient import simulate_axial
from torsio.axial import bit_step
from torsio.axial.rgd import rgd_example
from torsio.axial.wave_stability import distributed_stability
from torsio.errors import ConfigError
from torsio.model.axial_assembly import lumped_twin, tube_section
from torsio.model.components import DrillCollar
from torsio.model.continuum import bar_frequencies, continuum_modes
from torsio.model.lumped import chain_matrix
from torsio.model.wave import WaveModel, WaveStrategy
from torsio.report.axial import axial_frequencies
from torsio.solvers import axial_layouts as layouts
from torsio.solvers.axial_layouts import SAMPLE_COLUMNS, STATS
from torsio.solvers.axial_run_setup import BitRotation, RunOptions
from torsio.solvers.axial_wave_lines import (
    advance,
    close_bottom,
    junction_rows,
    set_top_force,
    set_top_velocity,
    smooth_end_terms,
)
from torsio.solvers.axial_wave_setup import pipe_grid, run_wave, wave_run_setup

BIT = rgd_example()
WOB = 100e3
# the BHA of the 2-DOF example of docs/axial.md (M = 29981.3 kg, I = 455.65 kg m²) and the
# steel drill pipe of torsio.solvers.axial_wave_setup's example (E = 210 GPa, G = 81 GPa, ρ = 7850
# kg/m³)
MASS, INERTIA = 29981.3, 455.65
E, G, RHO = 2.1e11, 8.1e10, 7850.0
STEPPED = [
    tube_section(600.0, E, G, RHO, 3.4e-3, 3.0e-5),
    tube_section(400.0, E, G, RHO, 6e-3, 5e-5),
]
MODES = 6
UNIFORM = tube_section(1000.0, E, G, RHO, 3.4e-3, 3e-5)


def _stepped(hook: str) -> WaveModel:
    return wave_pipe(STEPPED, MASS, INERTIA, hook=hook)


def _exact(assembly: WaveModel, line: str, count: int) -> np.ndarray:
    """The first ``count`` exact frequencies [rad/s] of a line of the pipe as given, the
    BHA free: axially with the top held (bar_frequencies of E A, √(E/ρ) and m_b), torsionally
    the string's continuum with the BHA rigid (the top drive held)."""
    rows = assembly.axial
    if line == "axial":
        return bar_frequencies(
            rows.rigidities, assembly.lengths, rows.wave_speeds, rows.bha_mass, count
        )
    return continuum_modes(assembly.string, count, rigid_bha=True).frequencies_rad


# --- frequencies of the grid --------------------------------------------------------------
def _free_step(p, m, velocity, line, top_value, held_top=True):
    """One step of a line with the BHA free at its bottom (the bit off bottom: no bit
    force), in place on p, m; the BHA's new velocity. The calls of
    torsio.solvers.axial_wave_kernel's
    step 2 (3 torsionally), in its order: advance, the top, the BHA, the end."""
    offsets, junctions, z_top, z_bottom, end_mass, step = line
    arrived = p[-1]
    advance(p, m, offsets, junctions)
    if held_top:
        set_top_velocity(p, m, z_top, top_value)
    else:
        set_top_force(p, m, top_value)
    force = 0.5 * (arrived + p[-1])
    free, inverse = smooth_end_terms(velocity, end_mass, z_bottom, step)
    new, _ = bit_step.wear_flat_contact(free, force, 0.0, inverse, step, 0.0, False)
    close_bottom(p, m, z_bottom, new)
    return new


def _line(assembly, grid, name):
    """(offsets, junctions, Z top, Z bottom, end mass or inertia, h) of a line."""
    rows = assembly.axial
    z = rows.impedances if name == "axial" else assembly.impedances
    end = rows.bha_mass if name == "axial" else assembly.bit_inertia
    offsets, junctions = getattr(grid, f"{name}_offsets"), getattr(grid, f"{name}_junctions")
    return offsets, junctions, z[0], z[-1], end, grid.step


def _one_step_matrix(line, held_top):
    """The linear map of :func:`_free_step` (top input 0) on the state (p, m, V), built
    column by column."""
    n = int(line[0][-1])
    size = 2 * n + 1
    matrix = np.zeros((size, size))
    for column in range(size):
        state = np.eye(size)[column]
        p, m = state[:n].copy(), state[n : 2 * n].copy()
        new = _free_step(p, m, state[-1], line, 0.0, held_top)
        matrix[:, column] = np.concatenate([p, m, [new]])
    return matrix


def test_the_free_step_is_the_kernels_step_with_the_bit_off_bottom():
    # the frequency tests below read the one-step map of _free_step: here the compiled run
    # itself, its rock surface put 10 m below the bit (off bottom throughout: d < 0), gives
    # the same bit velocity and speed at every step, to the last bit
    assembly = _stepped("speed")
    setup = wave_run_setup(assembly, BIT, WOB, 180.0, RunOptions(0.5, 0.25, start="steady"))
    setup.history[3, : int(setup.cursor[1])] += 10.0
    lines = {name: _line(assembly, setup.grid, name) for name in ("axial", "torsional")}
    states = {
        "axial": [setup.axial_p.copy(), setup.axial_m.copy(), setup.bha[1]],
        "torsional": [setup.torsional_p.copy(), setup.torsional_m.copy(), setup.bha[3]],
    }
    tops = {"axial": setup.steady.rop, "torsional": setup.steady.bit_speed}
    samples = np.zeros((setup.steps, len(SAMPLE_COLUMNS)))
    stats = run_wave(setup, samples, 1)
    assert stats[STATS.index("off_bottom_steps")] == stats[STATS.index("window_steps")]
    for name, column in (("axial", "bit_velocity"), ("torsional", "bit_speed")):
        p, m, velocity = states[name]
        expected = [velocity]
        for _ in range(setup.steps - 1):
            expected.append(_free_step(p, m, expected[-1], lines[name], tops[name]))
        np.testing.assert_array_equal(samples[:, SAMPLE_COLUMNS.index(column)], expected)


def _grid_frequencies(assembly, line: str, held_top: bool = True):
    """The lowest MODES frequencies [rad/s] of the grid's one-step map (eigenvalues
    e^{iωh}), and the grid."""
    grid = pipe_grid(assembly, 2e-3)
    matrix = _one_step_matrix(_line(assembly, grid, line), held_top)
    roots = np.linalg.eigvals(matrix)
    # the scheme conserves energy: every nonzero root on the unit circle
    moving = np.abs(roots) > 1e-6
    np.testing.assert_allclose(np.abs(roots[moving]), 1.0, atol=1e-12)
    oscillating = roots[moving & (roots.imag > 1e-12)]
    return np.sort(np.angle(oscillating))[:MODES] / grid.step, grid


@pytest.mark.parametrize("line", ["axial", "torsional"])
def test_the_grid_frequencies_of_a_stepped_pipe_are_the_exact_continuum(line):
    # top held (the speed hook axially, the top drive torsionally), the BHA free: the exact
    # continuum of the stepped bar with a lumped end (κL tan κL = ρAL/m_b for one section).
    # The grid is the pipe of lengths n h c (travel times rounded to whole steps), exact but
    # for the BHA's trapezoidal rule, whose phase error is at most (ω h)²/12 relative
    assembly = _stepped("speed")
    measured, grid = _grid_frequencies(assembly, line)
    row = 0 if line == "axial" else 1
    speeds = assembly.axial.wave_speeds if line == "axial" else assembly.wave_speeds
    cells = np.array(getattr(grid, f"{line}_cells"))
    rigidity = [s.material.youngs_modulus * s.area for s in STEPPED]
    if line == "torsional":
        rigidity = [s.material.shear_modulus * s.polar_moment for s in STEPPED]
    end = MASS if line == "axial" else INERTIA
    rounded = bar_frequencies(rigidity, cells * grid.step * speeds, speeds, end, MODES)
    scheme = (measured * grid.step) ** 2 / 12
    assert np.all(np.abs(measured / rounded - 1) <= scheme)
    # against the pipe as given: the rounding moves each frequency by at most the largest
    # relative travel-time error (Rayleigh's quotient, docs/axial.md)
    exact = _exact(assembly, line, MODES)
    rounding = grid.travel_time_errors[row].max()
    assert np.all(np.abs(measured / exact - 1) <= rounding + scheme)


def test_the_grid_frequencies_with_the_weight_hook_are_those_of_a_free_top():
    # a constant force at the top: the top is free (F = 0 for a perturbation). With U =
    # cos(κx), E A κ sin κL = m_b ω² cos κL, that is sin x + r x cos x = 0, x = κL,
    # r = m_b/(ρ A L): one root in each ((j − ½)π, jπ), found here by brentq
    section = STEPPED[0]
    assembly = wave_pipe([section], MASS, INERTIA)
    measured, grid = _grid_frequencies(assembly, "axial", held_top=False)
    ratio = MASS / (RHO * section.area * section.length)
    c = float(assembly.axial.wave_speeds[0])
    exact = [
        scipy.optimize.brentq(
            lambda x: math.sin(x) + ratio * x * math.cos(x), (j - 0.5) * math.pi, j * math.pi
        )
        * c
        / section.length
        for j in range(1, MODES + 1)
    ]
    bound = grid.travel_time_errors[0].max() + (measured * grid.step) ** 2 / 12
    assert np.all(np.abs(measured / exact - 1) <= bound)
    # the lumped chain under the weight hook (report.axial_frequencies, its rigid-body zero
    # left out) converges to the same roots at second order: the error ratio of halved
    # cells tends to 4 (3.76-3.92 at 50, 100, 200 nodes)
    errors = []
    for nodes in (50, 100, 200):
        chain = pipe_chain(nodes, section, MASS, INERTIA)
        hz = np.array(axial_frequencies(chain)[:3])
        errors.append(np.abs(2 * math.pi * hz / exact[:3] - 1))
    for coarse, fine in zip(errors, errors[1:], strict=False):
        assert np.all((3.5 < coarse / fine) & (coarse / fine < 4.5))


def _lumped_frequencies(nodes: int, line: str) -> np.ndarray:
    chain = pipe_chain(nodes, UNIFORM, MASS, INERTIA, hook="speed")
    springs = chain.axial.stiffnesses if line == "axial" else chain.springs
    masses = chain.axial.masses if line == "axial" else chain.node_inertias
    values = scipy.linalg.eigh(chain_matrix(springs), np.diag(masses), eigvals_only=True)
    return np.sqrt(values[:3])


@pytest.mark.parametrize("line", ["axial", "torsional"])
def test_a_fine_lumped_pipe_converges_to_the_same_continuum_as_the_grid(line):
    # one uniform section: the wave grid and pipe_chain of 50, 100, 200 nodes against the
    # exact continuum; the lumped error falls like 1/nodes² (second-order chain), the grid's
    # is bounded by its travel-time tolerance (here 3e-5: 1.03e-5 reached, h = 1.64 ms)
    assembly = wave_pipe([UNIFORM], MASS, INERTIA, hook="speed", travel_time_tolerance=3e-5)
    exact = _exact(assembly, line, 3)
    errors = [np.abs(_lumped_frequencies(n, line) / exact - 1) for n in (50, 100, 200)]
    for coarse, fine in zip(errors, errors[1:], strict=False):
        np.testing.assert_allclose(coarse / fine, 4.0, rtol=0.02)
    measured, grid = _grid_frequencies(assembly, line)
    row = 0 if line == "axial" else 1
    wave_error = np.abs(measured[:3] / exact - 1)
    assert np.all(
        wave_error <= grid.travel_time_errors[row].max() + (measured[:3] * grid.step) ** 2 / 12
    )


def test_a_junction_carries_the_power_through():
    # (p² − m²)/(4 Z) is the power F v; at a junction what arrives leaves (F, v continuous)
    z = np.array([2.0e4, 1.3e5])
    rows = junction_rows(z)
    rng = np.random.default_rng(7)
    for down, up in rng.normal(size=(5, 2)) * 1e5:
        reflected = rows[0, 0] * down + rows[1, 0] * up
        transmitted = rows[2, 0] * down + rows[3, 0] * up
        arriving = down**2 / z[0] + up**2 / z[1]
        leaving = reflected**2 / z[0] + transmitted**2 / z[1]
        assert leaving == pytest.approx(arriving, rel=1e-14)
        # the same force and velocity on both sides
        assert down + reflected == pytest.approx(transmitted + up, rel=1e-14)
        assert (down - reflected) / z[0] == pytest.approx((transmitted - up) / z[1], rel=1e-14)


# --- runs ----------------------------------------------------------------------------------
@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_steady_drilling_is_a_fixed_point_of_the_wave_model(hook):
    # started on the closed-form steady state (steady.py) at 180 rpm, where it is stable
    # (docs/axial.md), the run keeps ROP, torque and MSE at the closed form
    run = simulate_axial(
        _stepped(hook),
        BIT,
        WOB,
        180.0,
        duration=6.0,
        window=3.0,
        start="steady",
        perturbation=0.0,
        samples=0,
    )
    steady = run.axial.steady
    assert run.axial.rop_mean == pytest.approx(steady.rop, rel=1e-12)
    assert run.axial.torque_mean == pytest.approx(steady.bit_torque, rel=1e-12)
    assert run.axial.weight_mean == pytest.approx(WOB, rel=1e-12)
    assert run.axial.mse_mean == pytest.approx(steady.mse, rel=1e-12)
    assert run.severity < 1e-12 and run.axial.axial_severity < 1e-12
    assert run.stick_fraction == 0.0 and run.axial.off_bottom_fraction == 0.0
    # the growth rate of the pipe's own characteristic equation (test_axial_wave_stability)
    twin = lumped_twin(_stepped(hook))
    exact = distributed_stability(_stepped(hook), BIT, WOB, 180.0, twin=twin)
    assert run.axial.growth_rate == exact.growth_rate


def test_one_section_and_two_equal_sections_give_the_same_run():
    # a junction of equal impedances transmits exactly (coefficients 1 and 0): the same run
    # to the last bit, from rest in stick-slip at 60 rpm. Wave speeds 5000 and 3125 m/s
    # (E/ρ, G/ρ exact squares) and h = 1 ms make both grids alike: 200 and 320 cells
    e, g, rho = 2.0e11, 7.8125e10, 8000.0
    runs = []
    for sections in (1, 2):
        pipe = tube_section(1000.0, e, g, rho, 3.4e-3, 3e-5)
        piece = attrs.evolve(pipe, length=pipe.length / sections)
        assembly = wave_pipe([piece] * sections, MASS, INERTIA)
        assert pipe_grid(assembly, 1e-3).axial_cells == ((200,) if sections == 1 else (100, 100))
        runs.append(simulate_axial(assembly, BIT, WOB, 60.0, duration=20.0, window=10.0, step=1e-3))
    np.testing.assert_array_equal(runs[0].axial.samples, runs[1].axial.samples)
    assert runs[0].stick_fraction > 0  # the comparison covers the bit's stuck phases


def test_the_layout_indices_name_the_kernels_stats():
    # torsio.axial.bit_step and both kernels write STATS by the indices of layouts.py
    names = {
        "bit_speed_max": layouts.SPEED_MAX,
        "bit_speed_min": layouts.SPEED_MIN,
        "axial_speed_max": layouts.VELOCITY_MAX,
        "axial_speed_min": layouts.VELOCITY_MIN,
        "stuck_steps": layouts.STUCK,
        "off_bottom_steps": layouts.OFF_BOTTOM,
        "window_steps": layouts.COUNT,
        "position_start": layouts.POSITION_START,
        "position_end": layouts.POSITION_END,
        "work": layouts.WORK,
        "torque_integral": layouts.TORQUE_INTEGRAL,
        "weight_integral": layouts.WEIGHT_INTEGRAL,
        "failed": layouts.FAILED,
        "steps_done": layouts.STEPS_DONE,
        "depth_of_cut_max": layouts.DEPTH_MAX,
    }
    assert {name: STATS.index(name) for name in names} == names


# --- bad input ---------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("build", "key"),
    [
        (lambda: tube_section(-1.0, E, G, RHO, 3.4e-3, 3e-5), "length"),
        (lambda: tube_section(1e3, E, G, "steel", 3.4e-3, 3e-5), "density"),
        (lambda: tube_section(1e3, E, G, RHO, 3.4e-3, 1e-7), "polar_moment"),  # no tube
        (lambda: wave_pipe([], MASS, INERTIA), "pipes"),
        (lambda: wave_pipe(STEPPED, 0.0, INERTIA), "bha_mass"),
        (lambda: wave_pipe(STEPPED, MASS, math.nan), "bha_inertia"),
        (lambda: wave_pipe([1.0], MASS, INERTIA), "pipes[0]"),
        (lambda: wave_pipe(STEPPED, MASS, INERTIA, hook="up"), "axial.hook"),
        (
            lambda: wave_pipe(STEPPED, MASS, INERTIA, travel_time_tolerance=0.0),
            "discretization.travel_time_tolerance",
        ),
        (
            lambda: wave_pipe(STEPPED, MASS, INERTIA, travel_time_tolerance=0.5),
            "discretization.travel_time_tolerance",
        ),
        (
            lambda: simulate_axial(_stepped("weight"), BIT, WOB, 60.0, duration=1.0, start="x"),
            "simulation.start",
        ),
        (
            lambda: simulate_axial(
                _stepped("weight"), BIT, WOB, 60.0, duration=1.0, bit_rotation=BitRotation()
            ),
            "bit_rotation",
        ),
        (lambda: simulate_axial(_stepped("weight"), BIT, WOB, 60.0, step=-1.0), "step"),
    ],
)
def test_bad_input_names_the_key(build, key):
    with pytest.raises(ConfigError) as error:
        build()
    assert error.value.key == key


# --- the pipe as a wave model --------------------------------------------------------------
def test_the_pipe_takes_the_numbers_of_its_sections_and_its_exact_first_frequency():
    # by hand from the sections' data (c = √(E/ρ), Z = A √(E ρ), E A = Z c; the BHA's mass
    # and inertia as given) and ω₁ the string's exact continuum (Wittrick-Williams,
    # tests/test_continuum.py), not the continuum of a grid's rounded lengths
    pipe = _stepped("weight")
    rows = pipe.axial
    areas, polar = np.array([3.4e-3, 6e-3]), np.array([3.0e-5, 5e-5])
    np.testing.assert_allclose(rows.wave_speeds, math.sqrt(E / RHO), rtol=1e-15)
    np.testing.assert_allclose(rows.impedances, areas * math.sqrt(E * RHO), rtol=1e-12)
    np.testing.assert_allclose(rows.rigidities, E * areas, rtol=1e-12)
    np.testing.assert_allclose(pipe.impedances, polar * math.sqrt(G * RHO), rtol=1e-12)
    assert rows.bha_mass == pytest.approx(MASS, rel=1e-14)
    assert pipe.bit_inertia == pytest.approx(INERTIA, rel=1e-14)
    exact = continuum_modes(pipe.string, 1, rigid_bha=True).frequencies_rad[0]
    assert pipe.first_frequency() == exact


def test_a_short_pipe_is_a_pipe():
    # a 20 m pipe has fewer cells on the torsional grid than the default drag spacing (4):
    # the spacing falls to them (the pipe carries no drag), and its grid steps both lines
    pipe = wave_pipe([tube_section(20.0, E, G, RHO, 3.4e-3, 3e-5)], MASS, INERTIA)
    assert pipe.drag_spacing <= max(pipe.cells)
    grid = pipe_grid(pipe, 2e-4)
    assert grid.axial_cells[0] >= 1 and grid.torsional_cells[0] > grid.axial_cells[0]


@pytest.mark.parametrize(
    ("build", "key"),
    [
        (lambda: tube_section(1e3, E, G, RHO, 0.0, 3e-5), "area"),
        (lambda: tube_section(1e3, E, G, RHO, "3e-3", 3e-5), "area"),
        (lambda: tube_section(1e3, E, G, RHO, -3.4e-3, 3e-5), "area"),
        (lambda: tube_section(1e3, True, G, RHO, 3.4e-3, 3e-5), "youngs_modulus"),
        (lambda: wave_pipe(STEPPED[0], MASS, INERTIA), "pipes"),
        (
            lambda: wave_pipe(
                [*STEPPED, DrillCollar(od=0.2, id=0.07, length=10.0, material=STEPPED[0].material)],
                MASS,
                INERTIA,
            ),
            "pipes[2]",
        ),  # fmt: skip
        (lambda: wave_pipe(STEPPED, True, INERTIA), "bha_mass"),
    ],
)
def test_a_pipe_given_by_its_numbers_refuses_bad_ones_by_key(build, key):
    with pytest.raises(ConfigError) as info:
        build()
    assert info.value.key == key


def test_a_torsional_wave_model_is_no_axial_pipe():
    # the axial engine asks a wave model without axial rows for them by key
    torsional = WaveStrategy(rigid_bha=True).discretize(_stepped("weight").string)
    with pytest.raises(ConfigError) as info:
        simulate_axial(torsional, BIT, WOB, 60.0, duration=1.0)
    assert info.value.key == "axial"
