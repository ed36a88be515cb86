"""Axial-torsional transients with the RGD bit (torsio.analysis.axial_transient, kernel, history).

Independent references: the delay t_n solved by brentq from the prescribed rotation,
Φ(t) − Φ(t − t_n) = 2π/n, and U there from scipy's cubic Hermite spline of the run's own
samples; the steady drilling state in closed form (torsio.axial.steady: d₀, V₀, T₀, MSE,
RGD 2007 and Teale 1965); the rightmost characteristic roots of the linearization
(torsio.axial.stability, Chebyshev collocation + Newton, checked in
tests/test_axial_stability.py against Lambert-W roots)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.interpolate
import scipy.optimize
from axial_files import pipe_chain
from axial_growth import envelope_rate, perturbed_run

from torsio.analysis.axial_transient import simulate_axial
from torsio.axial.delay_roots import rightmost_roots
from torsio.axial.linearization import axial_linearization
from torsio.axial.rgd import rgd_example
from torsio.axial.stability import drilling_stability
from torsio.errors import ConfigError
from torsio.model.axial_assembly import axial_chain, rgd_two_dof_example, tube_section
from torsio.solvers.axial_run_setup import BitRotation

# The 2-DOF example of docs/axial.md: I = 455.65 kg m², k = 324.857 N m/rad (strategy A of
# the built-in Ritto 2017 string), M = 29981.3 kg (DESIGN.md), c = β k = 19.49 N m s/rad.
ASSEMBLY = rgd_two_dof_example()
BIT = rgd_example()
INERTIA, STIFFNESS, MASS, DAMPING = 455.65, 324.857, 29981.3, 19.49
WOB = 100e3
PIPE_900 = tube_section(900.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 1.5e-5)


def _every_step(run_time: float, rpm: float, rotation: BitRotation, perturbation: float):
    return simulate_axial(
        ASSEMBLY,
        BIT,
        WOB,
        rpm,
        duration=run_time,
        window=run_time / 2,
        start="steady",
        perturbation=perturbation,
        samples=10**9,
        bit_rotation=rotation,
        growth_rate=False,
    )


# --- the delay ----------------------------------------------------------------------------
def test_the_delay_at_constant_speed_is_the_blade_period_and_d_the_lagged_difference():
    # at 180 rpm the axial motion is stable (docs/axial.md), so the bit stays on bottom
    run = _every_step(1.0, 180.0, BitRotation(), 1e-2)
    tn0 = 2 * math.pi / (BIT.blades * 180.0 * math.pi / 30)
    lag = round(tn0 / run.axial.step)
    assert lag * run.axial.step == pytest.approx(tn0, rel=1e-13)  # the step rule: h = t_n0 / m
    np.testing.assert_allclose(run.signal("delay"), tn0, rtol=1e-12)
    u, d = run.signal("bit_position"), run.signal("depth_of_cut")
    expected = BIT.blades * (u[lag:] - u[:-lag])
    np.testing.assert_allclose(d[lag:], expected, rtol=0, atol=1e-14 * np.abs(u).max())
    assert run.axial.off_bottom_fraction == 0.0


def test_the_delay_of_a_non_uniform_rotation_matches_brentq_and_the_hermite_spline():
    # Ω(t) = Ω₀ (1 + 0.3 sin t): t_n from Φ(t) − Φ(t − t_n) = 2π/n by brentq, independently
    rotation = BitRotation(0.3, 1.0)
    rpm = 180.0
    omega0 = rpm * math.pi / 30
    run = _every_step(2.0, rpm, rotation, 1e-2)
    t, delay = run.signal("time"), run.signal("delay")
    angle = 2 * math.pi / BIT.blades

    def solved(time: float) -> float:
        def residual(lag: float) -> float:
            return rotation.angle(omega0, time) - rotation.angle(omega0, time - lag) - angle

        return scipy.optimize.brentq(residual, 0.0, 2.0, xtol=1e-15, rtol=1e-15)

    picks = np.arange(0, t.size, 37)
    reference = np.array([solved(float(t[k])) for k in picks])
    assert np.abs(delay[picks] - reference).max() < 1e-12  # s, against t_n ≈ 0.083 s
    # U(t − t_n) from scipy's cubic Hermite spline of the run's samples (U, V)
    u, v, d = run.signal("bit_position"), run.signal("bit_velocity"), run.signal("depth_of_cut")
    spline = scipy.interpolate.CubicHermiteSpline(t, u, v)
    late = t - delay >= 0
    expected = BIT.blades * (u[late] - spline(t[late] - delay[late]))
    np.testing.assert_allclose(d[late], expected, rtol=1e-10, atol=1e-14)
    assert run.axial.off_bottom_fraction == 0.0


# --- the steady state is a fixed point ---------------------------------------------------------
@pytest.mark.parametrize(
    "assembly",
    [
        ASSEMBLY,
        pipe_chain(3, PIPE_900, MASS, 230.0),
        pipe_chain(3, PIPE_900, MASS, 230.0, hook="speed"),
    ],
    ids=["2-DOF", "chain-weight", "chain-speed"],
)
def test_started_on_the_steady_state_the_run_stays_there(assembly):
    # at 180 rpm steady drilling is stable (round-off does not grow; docs/axial.md)
    run = simulate_axial(
        assembly, BIT, WOB, 180.0, duration=6.0, window=3.0, start="steady", perturbation=0.0
    )
    steady = run.axial.steady
    assert run.axial.rop_mean == pytest.approx(steady.rop, rel=1e-9)
    assert run.axial.torque_mean == pytest.approx(steady.bit_torque, rel=1e-9)
    assert run.axial.weight_mean == pytest.approx(WOB, rel=1e-9)
    assert run.axial.mse_mean == pytest.approx(steady.mse, rel=1e-9)  # the closed form, Teale 1965
    assert run.severity < 1e-9 and run.axial.axial_severity < 1e-9
    assert run.stick_fraction == 0.0 and run.axial.off_bottom_fraction == 0.0


# --- convergence ------------------------------------------------------------------------------
def test_halving_the_step_moves_a_stick_slip_run_by_less_than_one_percent():
    runs = [
        simulate_axial(ASSEMBLY, BIT, WOB, 60.0, steps_per_period=spp, samples=0, growth_rate=False)
        for spp in (100, 200)
    ]
    coarse, fine = runs
    assert coarse.axial.step == pytest.approx(2 * fine.axial.step, rel=0.02)
    assert coarse.severity > 1.0 and coarse.stick_fraction > 0.05  # stick-slip from rest
    assert abs(coarse.severity / fine.severity - 1) < 0.01
    assert abs(coarse.axial.rop_mean / fine.axial.rop_mean - 1) < 0.01
    assert abs(coarse.stick_fraction - fine.stick_fraction) < 0.01


def test_the_stuck_fraction_is_the_steps_below_the_stick_threshold():
    # recounted from the bit speed sampled at every step of the window: |Ω_b| < 0.1 Ω₀
    # (torsio.analysis.severity.DEFAULT_STICK_THRESHOLD, every engine's); the samples are
    # taken at the start of a step and the count at its end, so the two may differ by one
    # step of the window's 5160 (measured 0.30601 and 0.30620). With a threshold of 1e-9
    # Ω₀ it counts the RGD bit's stuck phase, Ω_b = 0 exactly
    runs = [
        simulate_axial(ASSEMBLY, BIT, WOB, 60.0, duration=20.0, window=10.0, samples=10**9,
                       growth_rate=False, stick_threshold=threshold)
        for threshold in (0.1, 1e-9)
    ]  # fmt: skip
    for run, threshold in zip(runs, (0.1, 1e-9), strict=True):
        speed = run.signal("bit_speed")[run.axial.window_rows()]
        recount = np.mean(np.abs(speed) < threshold * run.axial.steady.bit_speed)
        assert run.stick_threshold == threshold
        assert run.stick_fraction == pytest.approx(recount, abs=1.5 / speed.size)
    assert np.mean(speed == 0.0) == pytest.approx(runs[1].stick_fraction, abs=1.5 / speed.size)
    assert runs[0].stick_fraction > runs[1].stick_fraction > 0.1  # creeping counts at 0.1 Ω₀


# --- the growth of a small perturbation -----------------------------------------------------------
@pytest.mark.parametrize(
    ("rpm", "perturbation", "signal", "span", "tolerance"),
    [
        (100.0, 1e-12, "bit_velocity", (1.0, 4.0), 0.01),  # the axial mode, 4.02 1/s
        (140.0, 1e-9, "bit_velocity", (3.0, 12.0), 0.01),  # the axial mode, 1.27 1/s
        (170.0, 1e-6, "bit_speed", (50.0, 150.0), 0.01),  # the torsional mode, -0.0215 1/s
    ],
)
def test_a_small_perturbation_grows_at_the_rightmost_root(
    rpm, perturbation, signal, span, tolerance
):
    # the crossing of the 2-DOF model with this damper is 153.25 rpm (docs/axial.md)
    root = drilling_stability(ASSEMBLY, BIT, WOB, rpm).roots[0]
    run = perturbed_run(ASSEMBLY, BIT, WOB, rpm, span[1], perturbation)
    reference = run.axial.steady.rop if signal == "bit_velocity" else run.axial.steady.bit_speed
    rate = envelope_rate(run, signal, reference, abs(root.imag), *span)
    assert np.sign(rate) == np.sign(root.real) == (1 if rpm < 153.25 else -1)
    assert rate == pytest.approx(root.real, rel=tolerance)
    assert run.axial.growth_rate == pytest.approx(root.real, rel=1e-12)


@pytest.mark.parametrize(("rpm", "perturbation"), [(100.0, 1e-12), (170.0, 1e-4)])
def test_the_axial_model_grows_at_the_root_of_the_axial_equation(rpm, perturbation):
    # the bit turning at exactly Ω₀ (k -> infinity): M λ² + n ζ ε a (1 − e^{−λ t_n0}) = 0
    root = rightmost_roots(axial_linearization(BIT, MASS, WOB, rpm), 1, deflate=(0.0,)).roots[0]
    run = perturbed_run(ASSEMBLY, BIT, WOB, rpm, 4.0, perturbation, bit_rotation=BitRotation())
    rate = envelope_rate(run, "bit_velocity", run.axial.steady.rop, root.imag, 1.0, 4.0)
    assert rate == pytest.approx(root.real, rel=0.01)


# --- the set-valued phases and the outputs ----------------------------------------------------
def test_a_run_from_rest_sticks_and_reports_its_outputs():
    run = simulate_axial(ASSEMBLY, BIT, WOB, 60.0, samples=2000)
    assert run.stick_fraction > 0.05
    assert run.signal("bit_speed").min() == 0.0  # sticks, never turns backwards
    data = run.to_dict()
    for key in (
        "rop_mean",
        "mse_mean",
        "off_bottom_fraction",
        "severity",
        "stick_fraction",
        "steady_state",
        "growth_rate",
        "axial_severity",
    ):
        assert key in data
    assert data["steady_state"]["rop"] == pytest.approx(run.axial.steady.rop)
    assert data["growth_rate"] > 0


def test_a_bouncing_bit_leaves_the_bottom_and_the_forces_vanish_there():
    # at 40 rpm and 200 kN the axial motion is violently unstable: the bit bounces
    run = simulate_axial(
        ASSEMBLY, BIT, 200e3, 40.0, duration=40.0, window=20.0, samples=10**9, growth_rate=False
    )
    d = run.signal("depth_of_cut")
    off = d <= 0
    assert run.axial.off_bottom_fraction > 0.1 and off.any()
    assert np.all(run.signal("bit_weight")[off] == 0.0)
    turning = off & (run.signal("bit_speed") > 0)
    assert np.all(run.signal("bit_torque")[turning] == 0.0)


def test_a_chain_under_a_hook_moving_at_constant_speed_drills_at_that_speed():
    # the hook moves at V₀; over a long window the bit advances like the hook, up to the
    # change of the springs' compression (10 nodes of 250 m of pipe, stick-slip from rest)
    pipe = tube_section(2500.0, 2.1e11, 8.1e10, 7850.0, 3.4e-3, 3e-5)
    chain = pipe_chain(10, pipe, MASS, 230.0, hook="speed")
    run = simulate_axial(chain, BIT, WOB, 60.0, samples=0)
    # a chain has its growth rate too (tests/test_axial_chain_stability.py)
    assert run.axial.growth_rate == drilling_stability(chain, BIT, WOB, 60.0, count=1).growth_rate
    assert run.severity > 1.0 and run.stick_fraction > 0.02
    assert run.axial.rop_mean == pytest.approx(run.axial.steady.rop, rel=0.01)


def test_the_assembly_refuses_what_it_cannot_carry():
    with pytest.raises(ConfigError, match="chain.masses"):
        axial_chain([1.0, 2.0], [1.0, 2.0], [1.0])
    with pytest.raises(ConfigError, match="axial.hook"):
        axial_chain([1.0], [1.0], [1.0], hook="speed")
    with pytest.raises(ConfigError, match="simulation.start"):
        simulate_axial(ASSEMBLY, BIT, WOB, 60.0, duration=1.0, window=0.5, start="moving")
    with pytest.raises(ConfigError, match="bit_rotation.amplitude"):
        BitRotation(1.5)
