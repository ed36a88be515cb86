"""The distributed pipe's own characteristic equation (torsio.axial.wave_stability).

Independent references: the end stiffness of a uniform line in closed form (R γ coth γL with
the top held, R γ tanh γL free) and its static limits (E A / L; ρ A L λ², the pipe moving
as a body); the exact bar frequencies of :func:`torsio.model.continuum.bar_frequencies`
(axially) and :func:`~torsio.model.continuum.continuum_modes` (torsionally, the BHA rigid),
found by bisection of the frequency equation, which are the roots λ = iω when the bit
exerts nothing (D = 0); the lumped twins of the same sections
(:func:`torsio.model.axial_assembly.lumped_twin`), whose roots approach the continuum's like Δx²
as the elements shrink."""

from __future__ import annotations

import math

import numpy as np
import pytest
from axial_files import wave_pipe

from torsio.analysis.axial_transient import simulate_axial
from torsio.axial.rgd import rgd_example
from torsio.axial.stability import drilling_stability
from torsio.axial.wave_stability import (
    WaveCharacteristic,
    distributed_stability,
    end_stiffness,
    wave_characteristic,
)
from torsio.examples import rgd_wave_pipe_config
from torsio.model.axial_assembly import lumped_twin, tube_section
from torsio.model.continuum import bar_frequencies, continuum_modes

BIT = rgd_example()
WOB = 100e3
PIPE = tube_section(1000.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 3.0e-5)
EA = PIPE.material.youngs_modulus * PIPE.area
C_AXIAL = math.sqrt(PIPE.material.youngs_modulus / PIPE.material.density)


@pytest.mark.parametrize("root", [0.3 + 2.0j, -0.1 + 17.0j, 1.5 + 0.2j])
def test_a_uniform_line_has_its_closed_form_end_stiffness(root):
    gamma = root / C_AXIAL
    coth = 1 / np.tanh(gamma * PIPE.length)
    held = end_stiffness(root, [EA], [PIPE.length], [C_AXIAL], free_top=False)
    free = end_stiffness(root, [EA], [PIPE.length], [C_AXIAL], free_top=True)
    assert held == pytest.approx(EA * gamma * coth, rel=1e-12)
    assert free == pytest.approx(EA * gamma / coth, rel=1e-12)
    # two sections of half the length: the transfer matrices compose
    halves = end_stiffness(root, [EA, EA], [500.0, 500.0], [C_AXIAL] * 2, free_top=False)
    assert halves == pytest.approx(held, rel=1e-12)


def test_the_static_limits_are_the_spring_and_the_moving_body():
    lam = 1e-4j
    held = end_stiffness(lam, [EA], [PIPE.length], [C_AXIAL], free_top=False)
    free = end_stiffness(lam, [EA], [PIPE.length], [C_AXIAL], free_top=True)
    assert held.real == pytest.approx(EA / PIPE.length, rel=1e-9)
    body = PIPE.material.density * PIPE.area * PIPE.length * lam**2
    assert free == pytest.approx(body, rel=1e-9)


@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_without_the_bit_the_roots_are_the_exact_bar_frequencies(hook):
    # 1000 m of drill pipe above 200 m of a collar (od 169.5 mm, id 57.2 mm) and the BHA
    collar = tube_section(200.0, 2.1e11, 8.1e10, 7850.0, 2.0e-2, 8.0e-5)
    assembly = wave_pipe([PIPE, collar], 3.0e4, 455.65, hook=hook)
    rows = assembly.axial
    off_bottom = WaveCharacteristic(assembly, np.zeros((2, 2)), delay=0.25)
    axial = bar_frequencies(rows.rigidities, assembly.lengths, rows.wave_speeds, rows.bha_mass,
                            4, free_top=hook == "weight")  # fmt: skip
    torsional = continuum_modes(assembly.string, 4, rigid_bha=True).frequencies_rad
    for omega in [*axial, *torsional]:
        assert off_bottom.relative_residual(1j * omega) < 1e-11, omega
    assert off_bottom.relative_residual(1j * 0.9 * axial[0]) > 1e-3  # not a root between


def test_the_weight_hook_has_its_neutral_root_deflated():
    axial = rgd_wave_pipe_config().axial
    characteristic = wave_characteristic(axial.assembly, axial.bit, WOB, 60.0)
    assert characteristic.value(0.0) == 0 and characteristic.neutral_roots == (0j,)
    result = distributed_stability(
        axial.assembly, axial.bit, WOB, 60.0, twin=axial.stability_assembly
    )
    assert np.min(np.abs(result.roots)) > 1.0
    assert np.all(result.residuals < 1e-12)


def _twin_errors(hook, rpm, lengths):
    axial = rgd_wave_pipe_config().axial
    pipe = axial.assembly
    assembly = wave_pipe(pipe.sections, pipe.axial.bha_mass, pipe.bit_inertia, hook=hook)
    exact = distributed_stability(assembly, axial.bit, WOB, rpm, twin=lumped_twin(assembly, 25.0))
    errors = []
    for length in lengths:
        twin = lumped_twin(assembly, length)
        roots = drilling_stability(twin, axial.bit, WOB, rpm, count=8).roots
        errors.append([float(np.min(np.abs(roots - r))) for r in exact.roots[:2]])
    return exact, np.array(errors)


@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_the_lumped_twins_roots_converge_to_the_continuum_like_dx_squared(hook):
    exact, errors = _twin_errors(hook, 60.0, [50.0, 25.0, 12.5])
    orders = np.log2(errors[:-1] / errors[1:])
    # measured (weight hook): the first root's error 1.2e-3, 2.4e-4, 7.1e-5 (orders 2.4, 1.8)
    assert np.all(orders > 1.5), orders
    assert np.all(errors[-1] < 2e-2 * np.abs(exact.roots[:2]))


def test_simulate_gives_the_distributed_pipes_growth_rate():
    axial = rgd_wave_pipe_config().axial
    run = simulate_axial(axial.assembly, axial.bit, WOB, 60.0, duration=1.0, window=0.5,
                         samples=0)  # fmt: skip
    exact = distributed_stability(
        axial.assembly, axial.bit, WOB, 60.0, twin=axial.stability_assembly
    )
    assert run.axial.growth_rate == exact.growth_rate
    # the built-in file at 60 rpm: 3.2180 1/s, its 10-node twin's 3.2233 (docs/axial.md)
    assert exact.growth_rate == pytest.approx(3.2180, abs=1e-4)
    assert exact.twin_roots[0].real == pytest.approx(3.2233, abs=1e-4)
