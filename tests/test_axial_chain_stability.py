"""Linear stability of steady drilling of a lumped chain (torsio.axial.linearization,
torsio.axial.stability), either hook.

Independent references: the 2-DOF linearization of docs/axial.md (step 6, M = diag(M, I),
C = diag(0, c), K = diag(0, k), D of the bit); the rigid axial body (no axial springs, mass
Σ m_i) as the limit of stiff axial springs; the characteristic determinant of one node under
the hook speed written out by hand,
Δ(λ) = (P_a + w E)(I λ² + c λ + k) − t (V₀/Ω₀) E P_a with P_a = M λ² + c_a λ + k_a,
w = n ζ ε a, t = n ε a²/2, E = 1 − e^{−λ t_n0}; and the growth of a small perturbation in
the nonlinear transient of torsio.analysis.axial_transient (its own engine, the bit's own
history)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from axial_files import PIPE, damped_pipe, pipe_chain
from axial_growth import envelope_rate, perturbed_run

from torsio.analysis.axial_maps import axial_map
from torsio.analysis.axial_transient import simulate_axial
from torsio.axial.linearization import delayed_matrix, drilling_linearization
from torsio.axial.rgd import rgd_example
from torsio.axial.stability import DrillingCase, drilling_stability, mode_crossings
from torsio.axial.steady import steady_drilling
from torsio.errors import ConfigError
from torsio.model.axial_assembly import axial_chain, two_dof_assembly
from torsio.solvers.axial_run_setup import BitRotation

# The 2-DOF example of docs/axial.md (I, k of strategy A of the built-in Ritto 2017 string,
# M of DESIGN.md, c = β k with β = 0.06 s) and the 3-node pipe of tests/test_axial_transient.py
INERTIA, STIFFNESS, MASS, DAMPING = 455.65, 324.857, 29981.3, 19.49
BIT = rgd_example()
WOB = 100e3


# --- one node is the 2-DOF model ---------------------------------------------------------------
def test_a_chain_of_one_node_is_the_two_dof_linearization():
    # one node under the weight hook with an axial spring: k_a,0 carries W₀ and is not used
    node = axial_chain([INERTIA], [STIFFNESS], [MASS], axial_stiffnesses=[5e6], dampings=[DAMPING])
    two_dof = two_dof_assembly(INERTIA, STIFFNESS, MASS, DAMPING)
    chain, reference = (drilling_linearization(a, BIT, WOB, 90.0) for a in (node, two_dof))
    steady = steady_drilling(BIT, WOB, 90.0)
    # docs/axial.md, step 6
    np.testing.assert_array_equal(chain.mass, np.diag([MASS, INERTIA]))
    np.testing.assert_array_equal(chain.damping, np.diag([0.0, DAMPING]))
    np.testing.assert_array_equal(chain.stiffness, np.diag([0.0, STIFFNESS]))
    np.testing.assert_array_equal(chain.delayed, delayed_matrix(BIT, steady))
    assert chain.delay == reference.delay == steady.delay
    assert chain.neutral_roots == reference.neutral_roots == (0.0,)
    ours, theirs = (drilling_stability(a, BIT, WOB, 90.0) for a in (node, two_dof))
    np.testing.assert_array_equal(ours.roots, theirs.roots)
    assert ours.growth_rate == theirs.growth_rate


# --- stiff axial springs: the rigid axial body ---------------------------------------------------
def test_stiff_axial_springs_tend_to_the_rigid_axial_body():
    chain = pipe_chain(*PIPE)
    rigid = axial_chain(chain.node_inertias, chain.springs, chain.axial.masses)
    reference = drilling_stability(rigid, BIT, WOB, 120.0, count=3).roots
    errors = []
    for scale in (1e3, 1e5):
        stiff = axial_chain(
            chain.node_inertias,
            chain.springs,
            chain.axial.masses,
            axial_stiffnesses=chain.axial.stiffnesses * scale,
        )
        roots = drilling_stability(stiff, BIT, WOB, 120.0, count=3).roots
        errors.append(np.max(np.abs(roots - reference) / np.abs(reference)))
    # the springs' compliance 1/k_a enters to first order: 100 times stiffer, 100 times closer
    assert errors[1] < 1e-8
    assert errors[0] / errors[1] == pytest.approx(100.0, rel=0.05)


# --- one node under the hook speed: the determinant by hand ------------------------------------
AXIAL_SPRING, AXIAL_DAMPER = 2.0e7, 5.0e4  # N/m, N s/m
SPEED_NODE = axial_chain(
    [INERTIA],
    [STIFFNESS],
    [MASS],
    axial_stiffnesses=[AXIAL_SPRING],
    dampings=[DAMPING],
    axial_dampings=[AXIAL_DAMPER],
    hook="speed",
)


def _speed_node_delta(rpm):
    steady = steady_drilling(BIT, WOB, rpm)
    w = BIT.blades * BIT.cutting_weight_per_depth
    t = BIT.blades * BIT.cutting_torque_per_depth
    ratio = steady.rop / steady.bit_speed

    def terms(lam):
        e = 1 - np.exp(-lam * steady.delay)
        axial = MASS * lam**2 + AXIAL_DAMPER * lam + AXIAL_SPRING
        torsional = INERTIA * lam**2 + DAMPING * lam + STIFFNESS
        return axial * torsional, w * e * torsional, -t * ratio * e * axial

    return terms


@pytest.mark.parametrize("rpm", [60.0, 150.0])
def test_one_node_under_the_hook_speed_solves_the_determinant_by_hand(rpm):
    result = drilling_stability(SPEED_NODE, BIT, WOB, rpm)
    terms = _speed_node_delta(rpm)
    for root in result.roots:
        parts = terms(root)
        assert abs(sum(parts)) < 1e-12 * sum(abs(p) for p in parts)


@pytest.mark.parametrize("rpm", [60.0, 150.0])
def test_roots_of_a_chain_agree_between_collocation_orders_n_and_2n(rpm):
    for assembly in (SPEED_NODE, pipe_chain(*PIPE), pipe_chain(*PIPE, hook="speed")):
        order = drilling_linearization(assembly, BIT, WOB, rpm).default_order()
        coarse = drilling_stability(assembly, BIT, WOB, rpm, order=order)
        fine = drilling_stability(assembly, BIT, WOB, rpm, order=2 * order)
        assert len(coarse.roots) >= 4
        np.testing.assert_allclose(coarse.roots[:4], fine.roots[:4], rtol=1e-9)


# --- the neutral root ---------------------------------------------------------------------------
def test_the_hook_speed_has_no_neutral_root():
    # k_a,0 pins the axial position: Λ(0) = K = diag(k_a, k), Δ(0) = k_a k ≠ 0
    for assembly in (SPEED_NODE, pipe_chain(*PIPE, hook="speed")):
        system = drilling_linearization(assembly, BIT, WOB, 60.0)
        assert system.neutral_roots == ()
        assert np.linalg.matrix_rank(system.stiffness) == system.dofs
        result = drilling_stability(assembly, BIT, WOB, 60.0)
        assert result.neutral_root is None and result.details.deflated == ()
        assert result.to_dict()["neutral_root"] is None
    assert _speed_node_delta(60.0)(0.0)[0] == AXIAL_SPRING * STIFFNESS


def test_the_hook_weight_has_its_neutral_root_found_and_not_reported():
    chain = pipe_chain(*PIPE)
    system = drilling_linearization(chain, BIT, WOB, 60.0)
    shift = np.r_[np.ones(chain.axial.dofs), np.zeros(chain.dofs)]  # u_i = const
    np.testing.assert_array_equal(system.stiffness @ shift, 0.0)
    assert abs(system.characteristic_slope(0.0)) > 0  # a simple root
    result = drilling_stability(chain, BIT, WOB, 60.0)
    assert result.neutral_root is not None and abs(result.neutral_root) * system.delay < 1e-10
    assert np.all(np.abs(result.roots) * system.delay > 1e-3)
    eigenvalues = np.sort(np.abs(system.collocation_eigenvalues(result.details.order)))
    assert eigenvalues[1] * system.delay > 1e-2  # only one eigenvalue at the origin


# --- the growth of a small perturbation in the transient ------------------------------------------
@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_a_small_perturbation_of_a_chain_grows_at_the_rightmost_root(hook):
    # at 80 rpm the rightmost root (3.55 1/s weight, 3.82 1/s speed) grows 8 times faster
    # than the next one: the envelope is its own (at 100 rpm the two beat)
    chain = pipe_chain(*PIPE, hook=hook)
    rpm = 80.0
    root = drilling_stability(chain, BIT, WOB, rpm).roots[0]
    run = perturbed_run(chain, BIT, WOB, rpm, 4.0, 1e-12)
    rate = envelope_rate(run, "bit_velocity", run.axial.steady.rop, root.imag, 1.0, 4.0)
    assert root.real > 0
    assert rate == pytest.approx(root.real, rel=5e-3)
    assert run.axial.growth_rate == root.real


# --- the crossings and the maps -------------------------------------------------------------------
@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_each_crossing_names_the_root_that_crosses(hook):
    chain = damped_pipe(hook)  # dampers β k (β = 0.06 s) and 1e-3 s k_a
    crossings = mode_crossings(DrillingCase(chain, BIT, WOB), (60.0, 250.0), points=9)
    assert len(crossings) >= 1
    for crossing in crossings:
        at = drilling_stability(chain, BIT, WOB, crossing.rpm, count=1)
        assert abs(at.growth_rate) < 1e-6  # the rightmost root is on the imaginary axis
        assert crossing.frequency == at.roots[0].imag > 0
        assert 0 <= crossing.axial_share <= 1
        assert crossing.mode in ("axial", "torsional")


def test_the_map_gives_the_growth_rate_of_a_chain_and_refuses_a_prescribed_rotation():
    chain = pipe_chain(*PIPE, hook="speed")
    grid = axial_map(chain, BIT, [90e3, 130e3], [100.0], duration=2.0, window=1.0,
                     growth_rate=True, threads=1)  # fmt: skip
    assert grid.growth_rate is not None
    for j, wob in enumerate([90e3, 130e3]):
        assert grid.growth_rate[0, j] == drilling_stability(chain, BIT, wob, 100.0).growth_rate
    with pytest.raises(ConfigError) as info:
        axial_map(chain, BIT, [90e3], [100.0], duration=2.0, window=1.0, growth_rate=True,
                  bit_rotation=BitRotation())  # fmt: skip
    assert info.value.key == "growth_rate"
    run = simulate_axial(chain, BIT, WOB, 100.0, duration=1.0, window=0.5, samples=0,
                         bit_rotation=BitRotation())  # fmt: skip
    assert run.axial.growth_rate is None
    assert math.isfinite(run.axial.rop_mean)
