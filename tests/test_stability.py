"""Linear stability of steady rotation (torsio.analysis.stability).

Sources of the reference numbers:

* the analytic 1-DOF condition c + W_ob R_bit T'(Omega) = 0, with c = [C]_11 =
  alpha I + beta k and T' the slope of the normalized Tucker-Wang law, written out
  here from Eq. 2 (not taken from the library);
* the roots of I lambda^2 + (c + s) lambda + k = 0 (1 DOF);
* the eigenvalues of the linearized first-order system computed directly with
  numpy (multi-DOF);
* the closed-form receptance 1 / (k - omega^2 I + i omega c) of one DOF.
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
import pytest

from torsio.analysis.stability import (
    bit_receptance,
    critical_bit_damping,
    eigenvalues,
    growth_rate,
    linearized_matrix,
    stability_boundary,
)
from torsio.examples import builtin_config
from torsio.physics.laws import BitRockLaw, Parameter
from torsio.physics.system import System

RPM = np.linspace(40.0, 140.0, 51)


@pytest.fixture(scope="module")
def one_dof() -> System:
    return builtin_config().system(strategy="A")


def normalized_slope(speed: np.ndarray) -> np.ndarray:
    """d/dw [a0 (tanh(a1 w) + a2 w / (1 + a3 w^2))], rpm reading of the built-in example."""
    k = 30.0 / math.pi  # the example's a1..a3 apply to the bit speed in rpm
    a0, a1, a2, a3 = 0.221, 0.2 * k, 0.89 * k, 0.06 * k**2
    w = np.asarray(speed)
    return a0 * (a1 / np.cosh(a1 * w) ** 2 + a2 * (1 - a3 * w**2) / (1 + a3 * w**2) ** 2)


def test_one_dof_boundary_is_the_analytic_condition(one_dof: System) -> None:
    inertia = float(one_dof.model.inertia[0, 0])
    stiffness = float(one_dof.model.stiffness[0, 0])
    c = 0.35 * inertia + 0.06 * stiffness  # alpha I + beta k of the built-in example
    omega = RPM * math.pi / 30.0
    expected = -c / (one_dof.bit_radius * normalized_slope(omega))  # c + W R T' = 0
    boundary = stability_boundary(one_dof, RPM)
    np.testing.assert_allclose(boundary.critical_wob, expected, rtol=1e-9)
    assert boundary.critical_slope == pytest.approx(-c, rel=1e-12)
    assert boundary.onset_frequency == pytest.approx(math.sqrt(stiffness / inertia), rel=1e-9)


def test_one_dof_eigenvalues_are_the_quadratic_roots(one_dof: System) -> None:
    m = float(one_dof.model.inertia[0, 0])
    k = float(one_dof.model.stiffness[0, 0])
    c = float(one_dof.damping_matrix[0, 0])
    for s in (-400.0, -c, 0.0, 500.0):
        roots = np.roots([m, c + s, k])
        np.testing.assert_allclose(
            np.sort_complex(eigenvalues(one_dof, s)), np.sort_complex(roots), rtol=1e-12, atol=1e-12
        )


def test_one_dof_receptance_closed_form(one_dof: System) -> None:
    m = float(one_dof.model.inertia[0, 0])
    k = float(one_dof.model.stiffness[0, 0])
    c = float(one_dof.damping_matrix[0, 0])
    w = np.array([0.1, 0.8, 0.85, 3.0])
    np.testing.assert_allclose(
        bit_receptance(one_dof, w), 1.0 / (k - w**2 * m + 1j * w * c), rtol=1e-13
    )


@pytest.mark.parametrize(
    "strategy, options",
    [
        ("C", {"dp_elements": 10}),
        ("B", {"dp_elements": 20, "bha_elements": 6}),
        ("consistent", {"dp_elements": 8, "bha_elements": 3}),
    ],
)
def test_multi_dof_boundary_is_where_an_eigenvalue_crosses(
    strategy: str, options: dict[str, Any]
) -> None:
    system = builtin_config().system(strategy=strategy, **options)
    critical = critical_bit_damping(system)
    # eigenvalues of the first-order system, computed here without the library
    n = system.model.dofs

    def rate(s: float) -> float:
        damping = system.damping_matrix.copy()
        damping[-1, -1] += s
        inverse = np.linalg.inv(system.model.inertia)
        matrix = np.block(
            [[np.zeros((n, n)), np.eye(n)], [-inverse @ system.model.stiffness, -inverse @ damping]]
        )
        return float(np.linalg.eigvals(matrix).real.max())

    assert rate(critical.slope * (1 - 1e-6)) < 0 < rate(critical.slope * (1 + 1e-6))
    # no crossing at any smaller |s| (scan from 0 to s_c)
    assert all(rate(f * critical.slope) < 0 for f in np.linspace(0.0, 0.999, 40))
    # and the onset frequency is the imaginary part of the crossing eigenvalue
    values = eigenvalues(system, critical.slope)
    assert abs(values[0].real) < 1e-6 * abs(values[0])
    assert abs(values[0].imag) == pytest.approx(critical.frequency, rel=1e-6)
    # boundary in WOB: growth rate changes sign across it at each rpm
    boundary = stability_boundary(system, [50.0, 90.0])
    for rpm, wob in zip(boundary.rpm, boundary.critical_wob, strict=True):
        assert growth_rate(system.at(wob=wob * 0.999, rpm=rpm)) < 0
        assert growth_rate(system.at(wob=wob * 1.001, rpm=rpm)) > 0


def test_linearized_matrix_uses_the_law_slope_at_the_operating_point(one_dof: System) -> None:
    system = one_dof.at(wob=120e3, rpm=70.0)
    slope = float(system.law.slope(system.omega, system.wob, system.bit_radius))
    np.testing.assert_array_equal(linearized_matrix(system), linearized_matrix(system, slope))


def test_no_boundary_where_the_law_is_not_weakening(one_dof: System) -> None:
    # below ~4 rpm the tanh branch makes the slope positive: no WOB destabilizes
    boundary = stability_boundary(one_dof, [0.5, 60.0])
    assert math.isnan(boundary.critical_wob[0])
    assert math.isfinite(boundary.critical_wob[1])


class SquareRootLaw(BitRockLaw):
    """A law not proportional to the weight on bit: T = sqrt(W/1 N) R a0 f(w) [N m]."""

    name = "square-root-test-law"
    parameters = {"a0": Parameter("-", "scale", minimum=0.0, strict=True)}
    a0: float

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        w = np.asarray(speed, dtype=float)
        return (
            np.sqrt(np.asarray(wob, dtype=float))
            * 1e3
            * np.asarray(radius)
            * self.a0
            * (np.tanh(2.0 * w) + 8.5 * w / (1.0 + 5.47 * w * w))
        )


def test_law_not_proportional_to_wob(one_dof: System) -> None:
    system = attrs.evolve(one_dof, law=SquareRootLaw(a0=0.221))
    boundary = stability_boundary(system, [60.0, 100.0])
    for rpm, wob in zip(boundary.rpm, boundary.critical_wob, strict=True):
        # source: the eigenvalues on either side of the boundary
        assert growth_rate(system.at(wob=wob * 0.999, rpm=rpm)) < 0
        assert growth_rate(system.at(wob=wob * 1.001, rpm=rpm)) > 0


def test_fine_model_boundary_matches_eigenvalues() -> None:
    # 150 DOFs (receptance scan, O(n) per frequency) against the eigenvalues
    system = builtin_config().system(strategy="C", dp_elements=150)
    critical = critical_bit_damping(system)
    assert (
        growth_rate(system, critical.slope * (1 - 1e-6))
        < 0
        < growth_rate(system, critical.slope * (1 + 1e-6))
    )
