"""Linear stability of steady drilling with the RGD bit and its state-dependent delay
(torsio.axial.delay_roots, torsio.axial.linearization, torsio.axial.stability).

Independent references: the Lambert-W roots of λ² + b e^{−λτ} = 0; the characteristic
determinant written out by hand; the nonlinear depth of cut with the delay solved from
Φ(t) − Φ(t − t_n) = 2π/n; the closed-form crossings of the axial equation
M λ² + n ζ ε a (1 − e^{−λ t_n}) = 0 (λ = iω with ω t_n = (2j + 1)π, M ω² = 2 n ζ ε a)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.optimize
import scipy.special
from axial_files import pipe_chain

from torsio.axial.delay_roots import LinearDelaySystem, rightmost_roots
from torsio.axial.linearization import (
    axial_linearization,
    characteristic_function,
    delayed_matrix,
    drilling_linearization,
)
from torsio.axial.rgd import rgd_example
from torsio.axial.stability import (
    DrillingCase,
    drilling_stability,
    growth_rate_crossings,
    mode_crossings,
)
from torsio.axial.steady import steady_drilling
from torsio.errors import ConfigError
from torsio.model.axial_assembly import tube_section, two_dof_assembly

# The string: M from DESIGN.md's [chain] masses; I and k the strategy-A pendulum of the
# built-in Ritto (2017) string (I = I_DP/3 + I_BHA = 455.65 kg m², k = G J_DP / L_DP =
# 324.857 N m/rad, 0.1344 Hz: docs/theory.md); c = β k with the built-in β = 0.06 s.
MASS, INERTIA, STIFFNESS = 29981.3, 455.65, 324.857
DAMPING = 0.06 * STIFFNESS
WOB = 100e3
BIT = rgd_example()
AXIAL_STIFFNESS = BIT.blades * BIT.cutting_weight_per_depth  # n ζ ε a, N/m


DAMPED = two_dof_assembly(INERTIA, STIFFNESS, MASS, DAMPING)


def _system(rpm, stiffness=STIFFNESS, damping=0.0):
    return drilling_linearization(
        two_dof_assembly(INERTIA, stiffness, MASS, damping), BIT, WOB, rpm
    )


# --- the root finder on a delay equation with roots in closed form ---------------------------
def test_collocation_and_newton_find_the_lambert_w_roots():
    # λ² + b e^{−λτ} = 0  <=>  (λτ/2) e^{λτ/2} = ±i √b τ/2  <=>  λ = (2/τ) W_k(±i √b τ/2)
    b, tau = 4.0, 1.0
    system = LinearDelaySystem([[1.0]], [[0.0]], [[b]], [[-b]], delay=tau)
    z = 1j * math.sqrt(b) * tau / 2
    exact = [
        2 / tau * complex(scipy.special.lambertw(w, k))
        for w in (z, z.conjugate())
        for k in range(-8, 9)
    ]
    exact = sorted((r for r in exact if r.imag >= 0), key=lambda r: -r.real)[:4]
    for r in exact:  # the closed form solves the equation
        assert abs(r**2 + b * np.exp(-r * tau)) < 1e-12 * abs(r) ** 2
    found = rightmost_roots(system, 4, order=64, deflate=()).roots
    np.testing.assert_allclose(found, exact, rtol=1e-11)
    # the default order sees the roots with |λ| < 1.5 ρ (ρ = 2 here): the first three
    default = rightmost_roots(system, 4, deflate=()).roots
    np.testing.assert_allclose(default, exact[:3], rtol=1e-11)


# --- the characteristic equation of the 2-DOF model -----------------------------------------
@pytest.mark.parametrize("root", [0.3 + 2.0j, -1.5 + 20.0j, 4.0 - 0.5j, 0.01j])
def test_the_determinant_equals_the_characteristic_equation_written_out(root):
    # det of M λ² + C λ + K + E D against Δ = (Mλ² + nζεaE)(Iλ² + cλ + k) − n(εa²/2)(V₀/Ω₀)Mλ²E
    system = _system(90.0, damping=DAMPING)
    delta = characteristic_function(DAMPED, BIT, WOB, 90.0)
    assert system.characteristic(root) == pytest.approx(delta(root), rel=1e-12)


def test_the_linearized_forces_match_the_nonlinear_state_dependent_delay():
    # perturb U and Φ about the steady motion, solve Φ(t) − Φ(t − t_n) = 2π/n for t_n and
    # compare W(d) − W₀, T(d) − T₀ with D (x(t) − x(t − t_n0)): the error is second order
    rpm = 80.0
    steady = steady_drilling(BIT, WOB, rpm)
    v0, omega0, tau0, n = steady.rop, steady.bit_speed, steady.delay, BIT.blades
    d_matrix = delayed_matrix(BIT, steady)

    def errors(amplitude):
        def u(t):
            return amplitude * 1e-3 * math.sin(7.0 * t)

        def phi(t):
            return amplitude * math.cos(3.0 * t + 0.4)

        t = 1.3
        angle = lambda s: omega0 * s + phi(s)  # noqa: E731
        lag = scipy.optimize.brentq(
            lambda s: angle(t) - angle(t - s) - 2 * math.pi / n, 0.5 * tau0, 1.5 * tau0, xtol=1e-15
        )
        depth = n * (v0 * lag + u(t) - u(t - lag))
        weight, torque = BIT.forces(depth)
        nonlinear = np.array([weight - WOB, torque - steady.bit_torque])
        history = np.array([u(t) - u(t - tau0), phi(t) - phi(t - tau0)])
        linear = d_matrix @ history
        return np.abs(nonlinear - linear) / np.abs(linear), linear

    small, linear = errors(1e-5)
    smaller, _ = errors(1e-6)
    assert np.all(np.abs(linear) > 0)
    assert np.all(small < 1e-4)
    # second order: a tenth of the amplitude, a tenth of the relative error
    np.testing.assert_allclose(smaller / small, 0.1, rtol=0.05)


def test_without_the_delay_perturbation_the_linearization_would_be_wrong():
    # the V₀/Ω₀ column of D is the state-dependent delay; it is not small beside ζεa
    steady = steady_drilling(BIT, WOB, 80.0)
    d_matrix = delayed_matrix(BIT, steady)
    assert d_matrix[0, 1] == pytest.approx(-d_matrix[0, 0] * steady.depth_of_cut / (2 * math.pi))


# --- roots of the drilling system -----------------------------------------------------------
@pytest.mark.parametrize("rpm", [40.0, 100.0, 160.0])
def test_refined_roots_solve_the_characteristic_equation(rpm):
    result = drilling_stability(DAMPED, BIT, WOB, rpm)
    system = _system(rpm, damping=DAMPING)
    for root in result.roots:
        assert system.relative_residual(root) < 1e-12
    assert np.all(result.details.residuals < 1e-12)


@pytest.mark.parametrize("rpm", [40.0, 100.0, 160.0])
def test_roots_agree_between_collocation_orders_n_and_2n(rpm):
    order = _system(rpm, damping=DAMPING).default_order()
    coarse = drilling_stability(DAMPED, BIT, WOB, rpm, order=order)
    fine = drilling_stability(DAMPED, BIT, WOB, rpm, order=2 * order)
    assert len(coarse.roots) >= 4
    np.testing.assert_allclose(coarse.roots[:4], fine.roots[:4], rtol=1e-9)
    # and the collocation eigenvalues themselves converge to the refined roots
    np.testing.assert_allclose(fine.details.collocation[:4], fine.roots[:4], rtol=1e-6)


@pytest.mark.parametrize("rpm", [40.0, 100.0, 160.0])
def test_the_neutral_root_is_found_and_not_reported(rpm):
    system = _system(rpm, damping=DAMPING)
    assert system.characteristic(0.0) == 0  # E(0) = 0: u = const is a steady motion too
    assert abs(system.characteristic_slope(0.0)) > 0  # simple root
    result = drilling_stability(DAMPED, BIT, WOB, rpm)
    assert abs(result.neutral_root) * system.delay < 1e-10
    eigenvalues = np.sort(np.abs(system.collocation_eigenvalues()))
    assert eigenvalues[1] * system.delay > 1e-2  # only one eigenvalue at the origin
    assert np.all(np.abs(result.roots) * system.delay > 1e-3)
    assert result.growth_rate == max(r.real for r in result.roots)


def test_the_growth_rate_is_the_largest_real_part_and_decides_stability():
    unstable = drilling_stability(DAMPED, BIT, WOB, 100.0)
    stable = drilling_stability(DAMPED, BIT, WOB, 180.0)
    assert unstable.growth_rate > 0 and not unstable.stable
    assert stable.growth_rate < 0 and stable.stable
    assert set(unstable.to_dict()) == {
        "growth_rate",
        "stable",
        "roots",
        "neutral_root",
        "steady_state",
    }


# --- the axial limit: M λ² + n ζ ε a (1 − e^{−λ t_n}) = 0 --------------------------------------
def _axial_crossing_rpm(j):
    # λ = iω: sin(ω t_n) = 0 and M ω² = n ζ ε a (1 − cos ω t_n) -> ω t_n = (2j+1)π, Mω² = 2nζεa
    omega = math.sqrt(2 * AXIAL_STIFFNESS / MASS)
    t_n = (2 * j + 1) * math.pi / omega
    return 2 * math.pi / (BIT.blades * t_n) * 30 / math.pi, omega


@pytest.mark.parametrize("j", [0, 1, 2, 3])
def test_the_axial_equation_has_its_closed_form_imaginary_roots(j):
    rpm, omega = _axial_crossing_rpm(j)
    system = axial_linearization(BIT, MASS, WOB, rpm)
    assert system.relative_residual(1j * omega) < 1e-14
    found = rightmost_roots(system, 12).roots
    assert np.min(np.abs(found - 1j * omega)) < 1e-9 * omega


def test_the_axial_growth_rate_crosses_at_the_closed_form_rpm():
    def growth(rpm):
        return rightmost_roots(axial_linearization(BIT, MASS, WOB, rpm), 1).roots[0].real

    crossings = growth_rate_crossings(growth, 100.0, 200.0, 11)
    expected, _ = _axial_crossing_rpm(0)  # 153.789 rpm
    assert crossings == pytest.approx([expected], rel=1e-9)


def test_a_stiff_string_tends_to_the_axial_equation_like_one_over_k():
    # Δ = A(λ) B(λ) − Cλ²E with B = Iλ² + k: the axial roots move by O(C/k)
    axial = rightmost_roots(axial_linearization(BIT, MASS, WOB, 60.0), 2).roots
    gaps = []
    for k in (1e8, 1e10):
        # order 64: the torsional roots ±i √(k/I) are far out of reach and not wanted here
        coupled = drilling_stability(
            two_dof_assembly(INERTIA, k, MASS), BIT, WOB, 60.0, count=2, order=64
        ).roots
        gaps.append(np.abs(coupled - axial))
    np.testing.assert_allclose(gaps[1] / gaps[0], 1e-2, rtol=0.02)


# --- crossings of the coupled model ----------------------------------------------------------
def test_the_growth_rate_crossing_brackets_and_refines_a_change_of_sign():
    crossings = mode_crossings(DrillingCase(DAMPED, BIT, WOB), (100.0, 200.0), points=11)
    assert len(crossings) == 1
    rpm = crossings[0].rpm
    at = drilling_stability(DAMPED, BIT, WOB, rpm)
    assert abs(at.growth_rate) < 1e-8
    below = drilling_stability(DAMPED, BIT, WOB, rpm - 1.0)
    above = drilling_stability(DAMPED, BIT, WOB, rpm + 1.0)
    assert below.growth_rate > 0 > above.growth_rate
    # the mode that crosses is the axial one: within 1 % of the axial equation's crossing
    assert rpm == pytest.approx(_axial_crossing_rpm(0)[0], rel=1e-2)


@pytest.mark.parametrize(
    ("key", "kwargs"),
    [
        ("chain.inertias[0]", {"inertia": 0.0}),
        ("chain.stiffnesses[0]", {"stiffness": -1.0}),
        ("chain.masses[0]", {"mass": float("nan")}),
        ("chain.dampings[0]", {"damping": -1.0}),
        ("wob", {"wob": 60e3}),
    ],
)
def test_invalid_inputs_name_the_key(key, kwargs):
    args = {"inertia": INERTIA, "stiffness": STIFFNESS, "mass": MASS, "damping": 0.0, **kwargs}
    wob = args.pop("wob", WOB)
    with pytest.raises(ConfigError) as info:
        drilling_stability(two_dof_assembly(**args), BIT, wob, 60.0)
    assert info.value.key == key


def test_the_determinant_is_written_out_for_the_two_dof_model_only():
    # chains are linearized too (tests/test_axial_chain_stability.py); Δ(λ) by hand is 2-DOF
    section = tube_section(1000.0, 2.0e11, 8.0e10, 7850.0, 3.4e-3, 1.5e-5)
    chain = pipe_chain(3, section, 3.0e4, 230.0)
    with pytest.raises(ConfigError) as info:
        characteristic_function(chain, BIT, WOB, 60.0)
    assert info.value.key == "assembly"
