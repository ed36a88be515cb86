"""The Monte Carlo draws of a fit's parameters carry the fit's correlation
(torsio.calibration.monte_carlo.parameter_draws, uncertainty.jacobian_correlation).

The fits are test doubles (names, values, spreads, a correlation): no model runs. The
sampling bounds are from the sampling distributions: a correlation estimated from n
normal pairs has standard error (1 - rho^2)/sqrt(n), a standard deviation sigma/sqrt(2n).
"""

from __future__ import annotations

import math

import attrs
import numpy as np
import pytest

from torsio.calibration.monte_carlo import parameter_draws
from torsio.calibration.uncertainty import ParameterSpread, jacobian_correlation

COUNT = 20_000


@attrs.frozen
class _Fit:
    names: tuple[str, ...]
    values: tuple[float, ...]
    uncertainty: tuple[ParameterSpread, ...]
    correlation: np.ndarray | None


class _Family:
    def lower_bound(self, name: str) -> float:
        return 0.0


def _fit(correlation: np.ndarray | None) -> _Fit:
    # intervals of +-10 sigma: the draws are not clipped (a clipped tail would lower rho)
    spreads = tuple(
        ParameterSpread(s, s, math.nan, (v - 10 * s, v + 10 * s), "jacobian", True)
        for v, s in ((0.35, 0.01), (0.30, 0.004))
    )
    return _Fit(("friction_static", "friction_dynamic"), (0.35, 0.30), spreads, correlation)


def _matrix(draws: list[dict[str, float]]) -> np.ndarray:
    return np.array([[d["friction_static"], d["friction_dynamic"]] for d in draws])


def test_the_jacobian_correlation_is_the_normalized_inverse_of_jtj():
    # analytic: J^T J = [[2, 1], [1, 1]], its inverse [[1, -1], [-1, 2]], rho = -1/sqrt(2)
    correlation = jacobian_correlation(np.array([[1.0, 0.0], [1.0, 1.0]]))
    assert correlation[0, 1] == pytest.approx(-1.0 / math.sqrt(2.0), rel=1e-12)
    assert np.diag(correlation).tolist() == [1.0, 1.0]


def test_a_parameter_the_jacobian_does_not_see_is_uncorrelated():
    correlation = jacobian_correlation(np.array([[1.0, 0.0], [2.0, 0.0]]))
    assert correlation.tolist() == [[1.0, 0.0], [0.0, 1.0]]


def test_draws_carry_the_fits_correlation_and_sigmas():
    rho = 0.9
    draws = _matrix(parameter_draws(_fit(np.array([[1.0, rho], [rho, 1.0]])), _Family(), COUNT, 7))
    error = (1 - rho**2) / math.sqrt(COUNT)  # 1.3e-3
    assert np.corrcoef(draws.T)[0, 1] == pytest.approx(rho, abs=6 * error)
    sigmas = draws.std(axis=0, ddof=1)
    assert sigmas == pytest.approx([0.01, 0.004], rel=6 / math.sqrt(2 * COUNT))
    assert draws.mean(axis=0) == pytest.approx([0.35, 0.30], abs=6 * 0.01 / math.sqrt(COUNT))


def test_without_a_correlation_the_draws_are_independent():
    draws = _matrix(parameter_draws(_fit(None), _Family(), COUNT, 7))
    assert np.corrcoef(draws.T)[0, 1] == pytest.approx(0.0, abs=6 / math.sqrt(COUNT))
