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


def _weak_fit() -> _Fit:
    # mu_s not identifiable: the data allow [0.25, 0.45]; mu_d pinned to 0.30 +- 0.004
    weak = ParameterSpread(0.05, 0.05, math.nan, (0.25, 0.45), "profile", False)
    firm = ParameterSpread(0.004, 0.004, math.nan, (0.26, 0.34), "jacobian", True)
    return _Fit(
        ("friction_static", "friction_dynamic"),
        (0.35, 0.30),
        (weak, firm),
        np.array([[1.0, 0.9], [0.9, 1.0]]),
    )


def test_a_parameter_the_data_cannot_pin_down_is_drawn_over_the_range_they_allow():
    # uniform on [a, b]: mean (a + b)/2, standard deviation (b - a)/sqrt(12), each with the
    # sampling error sigma/sqrt(n); the firm parameter keeps its normal, now uncorrelated
    draws = _matrix(parameter_draws(_weak_fit(), _Family(), COUNT, 7))
    static, dynamic = draws[:, 0], draws[:, 1]
    assert static.min() >= 0.25 and static.max() <= 0.45
    width = 0.2 / math.sqrt(12.0)
    assert static.mean() == pytest.approx(0.35, abs=6 * width / math.sqrt(COUNT))
    assert static.std(ddof=1) == pytest.approx(width, rel=6 / math.sqrt(2 * COUNT))
    assert dynamic.std(ddof=1) == pytest.approx(0.004, rel=6 / math.sqrt(2 * COUNT))
    assert np.corrcoef(draws.T)[0, 1] == pytest.approx(0.0, abs=6 / math.sqrt(COUNT))


def test_a_parameter_the_user_fixes_is_held_and_a_bad_fix_is_named():
    from torsio.calibration.monte_carlo import distribution
    from torsio.errors import ConfigError

    draws = _matrix(parameter_draws(_weak_fit(), _Family(), 100, 7, {"friction_static": 0.4}))
    assert set(draws[:, 0].tolist()) == {0.4}
    said = distribution(_weak_fit(), {"friction_static": 0.4})
    assert said["friction_static"] == "fixed at 0.4"
    assert said["friction_dynamic"].startswith("normal 0.3 +- 0.004")
    assert "not identifiable" in distribution(_weak_fit())["friction_static"]
    with pytest.raises(ConfigError, match="^fixed: 'alpha' was not fitted"):
        parameter_draws(_weak_fit(), _Family(), 10, 7, {"alpha": 0.3})
    with pytest.raises(ConfigError, match=r"^fixed.friction_static: expected a finite value >= 0"):
        parameter_draws(_weak_fit(), _Family(), 10, 7, {"friction_static": -0.1})
