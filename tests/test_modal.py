"""Modal analysis: shapes against the continuum, normalization, damping ratios."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio import LumpedModel, StrategyA, StrategyB, StrategyC, modal_analysis
from torsio.errors import ConfigError
from torsio.physics.damping import RayleighDamping


def shape_error(string, discretizer, mode: int) -> float:
    model = discretizer.discretize(string)
    results = modal_analysis(model, mode, string=string)
    comparison = results.compare()
    exact = comparison.reference.shape(mode, model.node_depths)
    return float(np.max(np.abs(results.mode_shapes[:, mode - 1] - exact)))


def test_strategy_c_mode_shapes_converge_to_the_continuum(ritto):
    # Source: exact continuum shape (rigid BHA) at the nodes; paper Fig. 3(b) shows modes 1-2
    # with 5 DP DOFs matching the FEM shapes. Second-order convergence of lumped elements.
    for mode in (1, 2):
        errors = [shape_error(ritto, StrategyC(dp_elements=n), mode) for n in (5, 10, 20, 40)]
        assert errors == sorted(errors, reverse=True)
        assert math.log2(errors[-2] / errors[-1]) == pytest.approx(2.0, abs=0.15)
    assert shape_error(ritto, StrategyC(dp_elements=5), 1) < 0.01


def test_strategy_b_mode_25_shape_at_120_30(ritto):
    # Source: paper Fig. 5(b): "good correspondence" of mode 25 with 120 + 30 DOFs, measured
    # here against the exact shape at every node (peak-normalized).
    assert shape_error(ritto, StrategyB(dp_elements=120, bha_elements=30), 25) < 0.05


def test_strategy_a_shape_is_the_single_node(ritto):
    results = modal_analysis(StrategyA().discretize(ritto), string=ritto)
    np.testing.assert_array_equal(results.mode_shapes, [[1.0]])


def test_mass_normalization_and_orthogonality(ritto):
    # Source: M-orthonormality of the generalized symmetric eigenproblem.
    model = StrategyB(dp_elements=8, bha_elements=4).discretize(ritto)
    phi = modal_analysis(model).mass_normalized_shapes
    np.testing.assert_allclose(phi.T @ model.inertia @ phi, np.eye(model.dofs), atol=1e-10)
    omega2 = modal_analysis(model).frequencies_rad ** 2
    np.testing.assert_allclose(
        phi.T @ model.stiffness @ phi, np.diag(omega2), atol=1e-9 * omega2.max()
    )


def test_two_dof_chain_against_closed_form():
    # Source: analytic: equal inertias I and springs k give omega^2 = k/I (3 -+ sqrt 5)/2.
    model = LumpedModel.from_chain([2.0, 2.0], [8.0, 8.0])
    expected = np.sqrt(4.0 * (3 - np.sqrt([5.0, -5.0 + 10.0])) / 2)
    expected = np.sqrt(np.array([4.0 * (3 - math.sqrt(5)) / 2, 4.0 * (3 + math.sqrt(5)) / 2]))
    np.testing.assert_allclose(modal_analysis(model).frequencies_rad, expected, rtol=1e-13)


def test_rayleigh_damping_ratios_from_targets(ritto):
    # Source: zeta = alpha/(2 omega) + beta omega/2 solved for two modes hits both targets.
    model = StrategyC(dp_elements=10).discretize(ritto)
    damping = RayleighDamping.from_modal_ratios(model, ratios=(0.05, 0.02), modes=(1, 3))
    omega = modal_analysis(model, 3).frequencies_rad
    np.testing.assert_allclose(damping.ratios(omega[[0, 2]]), [0.05, 0.02], rtol=1e-12)
    with pytest.raises(ConfigError, match="negative Rayleigh"):
        RayleighDamping.from_modal_ratios(model, ratios=(0.01, 0.5), modes=(1, 2))


def test_compare_without_string_is_a_clear_error():
    model = LumpedModel.from_chain([1.0], [1.0])
    with pytest.raises(ConfigError, match="no drill-string"):
        modal_analysis(model).compare()
