"""The exact continuum reference: paper value, closed forms, root-count robustness."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from torsio import Bit, DrillPipe, DrillString, Material, continuum_modes
from torsio.errors import ConfigError
from torsio.model.continuum import _members, count_below

STEEL = Material(shear_modulus=85.3e9, density=7800.0)


def test_first_frequency_matches_paper_fem(ritto):
    # Source: paper, Section 3: FEM (ABAQUS, 2430 elements) first frequency 0.1307 Hz.
    modes = continuum_modes(ritto, 1)
    assert round(float(modes.frequencies_hz[0]), 4) == 0.1307


def uniform_shaft_with_tip(tip_length: float = 0.5) -> DrillString:
    return DrillString(
        [
            DrillPipe(od=0.14, id=0.1, length=3000.0, material=STEEL),
            Bit(od=0.3, id=0.05, length=tip_length, material=STEEL),
        ]
    )


def closed_form_roots(inertia_ratio: float, count: int) -> np.ndarray:
    """Roots of beta tan(beta) = I_shaft / I_tip, one in each ((n-1) pi, (n-1/2) pi)."""

    def residual(beta: float) -> float:
        return beta * math.sin(beta) - inertia_ratio * math.cos(beta)

    return np.array(
        [
            brentq(residual, (n - 1) * math.pi + 1e-12, (n - 0.5) * math.pi - 1e-12, xtol=1e-15)
            for n in range(1, count + 1)
        ]
    )


def test_uniform_shaft_with_tip_inertia_matches_closed_form():
    # Source: analytic result for a fixed-free shaft with a tip inertia:
    # beta tan beta = I_shaft / I_tip, omega = beta c / L.
    string = uniform_shaft_with_tip()
    shaft, bit = string.sections
    betas = closed_form_roots(shaft.inertia / bit.inertia, 50)
    expected = betas * STEEL.wave_speed / shaft.length
    computed = continuum_modes(string, 50).frequencies_rad
    np.testing.assert_allclose(computed, expected, rtol=1e-12)


@pytest.mark.parametrize("tip_length", [1e-4, 0.5, 50.0])
def test_closed_form_over_tip_inertias_no_root_skipped(tip_length):
    # Same closed form, from a nearly free end (tiny tip) to a heavy tip: the
    # Wittrick-Williams count must neither skip nor duplicate a root.
    string = uniform_shaft_with_tip(tip_length)
    shaft, bit = string.sections
    betas = closed_form_roots(shaft.inertia / bit.inertia, 40)
    computed = continuum_modes(string, 40).frequencies_rad * shaft.length / STEEL.wave_speed
    np.testing.assert_allclose(computed, betas, rtol=1e-11)


def test_count_below_agrees_with_sign_changes_of_the_transfer_residual(ritto):
    # Independent check: the number of sign changes of the bottom boundary residual
    # T(end) - omega^2 I_bit Theta(end), an entire function of omega, on a fine grid.
    members, tip = _members(ritto, rigid_bha=False)
    omegas = np.linspace(1e-3, 20.0, 40001)
    residual = []
    for omega in omegas:
        rotation, torque = 0.0, 1.0
        for m in members:
            kappa, rk = omega / m.wave_speed, m.torsional_rigidity * omega / m.wave_speed
            phase = kappa * m.length
            rotation, torque = (
                math.cos(phase) * rotation + math.sin(phase) / rk * torque,
                -rk * math.sin(phase) * rotation + math.cos(phase) * torque,
            )
        residual.append(torque - omega**2 * tip * rotation)
    changes = int(np.count_nonzero(np.diff(np.sign(residual)) != 0))
    assert count_below(20.0, members, tip) == changes
    computed = continuum_modes(ritto, changes + 1).frequencies_rad
    assert computed[changes - 1] < 20.0 < computed[changes]


def test_splitting_a_section_into_two_halves_changes_nothing(ritto):
    # Source: exactness of the wave solution: two identical halves are the same shaft.
    dp = ritto.sections[0]
    half = DrillPipe(od=dp.od, id=dp.id, length=dp.length / 2, material=dp.material)
    split = DrillString([half, half, *ritto.sections[1:]])
    np.testing.assert_allclose(
        continuum_modes(split, 20).frequencies_rad,
        continuum_modes(ritto, 20).frequencies_rad,
        rtol=1e-12,
    )


def test_mode_shape_is_zero_at_top_and_normalized(ritto):
    modes = continuum_modes(ritto, 3)
    depths = np.linspace(0.0, ritto.flexible_length, 201)
    shape = modes.shape(2, depths)
    assert shape[0] == 0.0
    assert np.max(np.abs(shape)) == pytest.approx(1.0)
    assert shape[1] > 0


def test_mode_shape_satisfies_the_bit_boundary_condition():
    # Source: the bottom boundary condition of the continuum, G J Theta'(L) = omega^2 I_bit
    # Theta(L), checked on the computed shape by a finite difference.
    string = uniform_shaft_with_tip()
    shaft, bit = string.sections
    modes = continuum_modes(string, 3)
    length, h = shaft.length, 1e-3
    for mode in (1, 2, 3):
        omega = modes.frequencies_rad[mode - 1]
        values = modes.raw_shape(mode, [length - h, length])
        slope = (values[1] - values[0]) / h
        gj = shaft.material.shear_modulus * shaft.polar_moment
        assert gj * slope == pytest.approx(omega**2 * bit.inertia * values[1], rel=1e-3)


def test_bad_counts_are_rejected(ritto):
    with pytest.raises(ConfigError, match="count"):
        continuum_modes(ritto, 0)
    with pytest.raises(ConfigError, match="mode"):
        continuum_modes(ritto, 2).shape(3, [0.0])
