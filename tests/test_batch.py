"""The batch engine (torsio.solvers.batch) against closed forms and independent single runs.

Sources of the reference numbers:

* closed form: a constant torque on bit makes the equations linear; their exact
  solution from rest is the matrix exponential of the first-order system
  (scipy.linalg.eig), and for one DOF the damped-oscillator formula;
* independent single runs: torsio.analysis.transient.simulate (scipy LSODA) at
  rtol = 1e-8, atol = 1e-10, on the same run length and steady window;
* a cubic polynomial whose extremes are known by hand (Hermite interpolation of
  a cubic is exact).
"""

from __future__ import annotations

import math

import attrs
import numpy as np
import pytest
import scipy.linalg

from torsio.analysis.transient import simulate
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.model.lumped import LumpedModel
from torsio.physics.laws import ConstantTorque, TuckerWang
from torsio.physics.system import System
from torsio.solvers import batch, batch_results, cycles, numpy_engine

TIGHT = {"method": "LSODA", "rtol": 1e-8, "atol": 1e-10}
"""Tolerances of the independent reference runs."""


def reference(system: System, wob: float, rpm: float, duration: float, window: float) -> float:
    return simulate(
        system.at(wob=wob, rpm=rpm), duration=duration, steady_window=window, **TIGHT
    ).severity


# --- interpolation of the extremes ------------------------------------------------------------
def test_extremes_of_cubic_are_exact_for_a_cubic() -> None:
    # p(x) = 1 + 3x - 4x^3: p' = 3 - 12 x^2 = 0 at x = 1/2, p(1/2) = 2, p(1) = 0, p(0.6) = 1.936
    u0, u1, d0, d1 = 1.0, 0.0, 3.0, -9.0
    vmax, vmin = cycles.extremes_of_cubic(u0, u1, d0, d1, 0.0, 1.0, -np.inf, np.inf)
    assert (vmax, vmin) == pytest.approx((2.0, 0.0), abs=1e-14)
    vmax, vmin = cycles.extremes_of_cubic(u0, u1, d0, d1, 0.6, 1.0, -np.inf, np.inf)
    assert cycles.extremes_of_cubic(u0, u1, d0, d1, 0.0, 0.4, -np.inf, np.inf) == pytest.approx(
        (1.944, 1.0), abs=1e-14
    )  # p(0.4) = 1 + 1.2 - 0.256 = 1.944, increasing on [0, 0.4]
    assert (vmax, vmin) == pytest.approx((1.936, 0.0), abs=1e-14)
    mx, mn = numpy_engine.extremes_numpy(*(np.array([x]) for x in (u0, u1, d0, d1, 0.6)))
    assert (mx[0], mn[0]) == pytest.approx((1.936, 0.0), abs=1e-14)


# --- linear cases: exact solutions -------------------------------------------------------------
def _constant_torque(system: System, torque: float) -> System:
    return attrs.evolve(system, law=ConstantTorque(torque_on_bit=torque))


def _exact_severity(system: System, duration: float, window: float) -> float:
    """S_SS of the linear (constant-torque) response from rest, by the matrix exponential."""
    from torsio.analysis.stability import linearized_matrix

    model = system.model
    n = model.dofs
    a = linearized_matrix(system, bit_slope=0.0)
    forcing = np.zeros(2 * n)
    load = -system.omega * system.drag_per_speed
    load[-1] -= float(system.law.torque_on_bit)
    forcing[n:] = np.linalg.solve(model.inertia, load)
    steady = -np.linalg.solve(a, forcing)
    start = np.concatenate([np.zeros(n), np.full(n, -system.omega)])
    values, vectors = scipy.linalg.eig(a)
    coefficients = np.linalg.solve(vectors, start - steady)
    times = np.linspace(duration - window, duration, 400_001)
    speed = (vectors[2 * n - 1] * coefficients) @ np.exp(np.outer(values, times))
    bit_speed = speed.real + steady[-1] + system.omega
    return float((bit_speed.max() - bit_speed.min()) / (2 * system.omega))


def test_one_dof_constant_torque_matches_the_damped_oscillator(one_dof: System) -> None:
    system = _constant_torque(one_dof, 2000.0).at(rpm=60.0)
    m = float(system.model.inertia[0, 0])
    k = float(system.model.stiffness[0, 0])
    c = float(system.damping_matrix[0, 0])
    omega = system.omega
    # closed form: m phi'' + c phi' + k phi = -omega d - T0 from phi = 0, phi' = -omega
    steady = -(omega * float(system.drag_per_speed[0]) + 2000.0) / k
    sigma, wd = c / (2 * m), math.sqrt(k / m - (c / (2 * m)) ** 2)
    a_, b_ = -steady, (-omega + sigma * -steady) / wd
    times = np.linspace(10.0, 20.0, 400_001)
    speed = omega + np.exp(-sigma * times) * (
        (-sigma * a_ + wd * b_) * np.cos(wd * times) + (-sigma * b_ - wd * a_) * np.sin(wd * times)
    )
    exact = (speed.max() - speed.min()) / (2 * omega)
    assert exact == pytest.approx(_exact_severity(system, 20.0, 10.0), rel=1e-9)
    # error control: the global error is proportional to the tolerance (measured: about
    # 1.5-2 rtol relative); check it stays within 5 rtol and falls with the tolerance
    errors = []
    for rtol in (1e-4, 1e-6, 1e-8):
        result = batch.simulate_batch(
            system, [0.0], [60.0], duration=20.0, steady_window=10.0, rtol=rtol, atol=rtol * 1e-2
        )
        errors.append(abs(result.severity[0] - exact) / exact)
        assert errors[-1] < 5 * rtol, rtol
    assert errors[0] / errors[2] > 1e3


@pytest.mark.parametrize(
    "strategy, options",
    [
        ("C", {"dp_elements": 10}),
        ("consistent", {"dp_elements": 6, "bha_elements": 2}),  # consistent (tridiagonal) mass
        ("B", {"dp_elements": 40, "bha_elements": 10}),  # stiff: beta K on short elements
    ],
)
def test_multi_dof_constant_torque_matches_the_matrix_exponential(
    strategy: str, options: dict
) -> None:
    system = _constant_torque(builtin_config().system(strategy=strategy, **options), 3000.0).at(
        rpm=80.0
    )
    exact = _exact_severity(system, 30.0, 15.0)
    for engine in ("numba", "numpy") if system.model.dofs < 20 else ("numba",):
        result = batch.simulate_batch(
            system,
            [0.0],
            [80.0],
            duration=30.0,
            steady_window=15.0,
            rtol=1e-8,
            atol=1e-10,
            engine=engine,
        )
        assert result.severity[0] == pytest.approx(exact, rel=1e-6, abs=1e-9), engine


# --- stick-slip points against independent single runs -------------------------------------------
POINTS = [(50e3, 120.0), (150e3, 60.0), (225e3, 40.0), (81e3, 60.0), (100e3, 100.0)]


def test_one_dof_points_match_single_transient_runs(one_dof: System) -> None:
    wob, rpm = np.array(POINTS).T
    result = batch.simulate_batch(one_dof, wob, rpm)
    assert result.ok.all()
    for k, (w, r) in enumerate(POINTS):
        expected = reference(one_dof, w, r, result.duration, result.steady_window)
        assert abs(result.severity[k] - expected) <= 0.01, (w, r, expected)


def test_stiff_model_needs_no_tiny_steps() -> None:
    # strategy B, 40 + 10 elements: the highest modes are overdamped by beta [K]
    system = builtin_config().system(strategy="B", dp_elements=40, bha_elements=10)
    model = batch.BatchModel.from_system(system)
    result = batch.simulate_batch(system, [150e3, 50e3], [60.0, 120.0])
    assert result.ok.all()
    expected = reference(system, 150e3, 60.0, result.duration, result.steady_window)
    assert abs(result.severity[0] - expected) <= 0.01
    # steady rotation (reference: S = 0 at 50 kN, 120 rpm); the run may end once the decaying
    # oscillation is within the steady-cycle tolerance (torsio.solvers.cycles)
    assert result.severity[1] < batch_results.DEFAULT_STEADY_TOLERANCE
    # an explicit method is stable only for h |lambda_max| < ~3.3 (RK45); the fastest
    # eigenvalue of the linearization is about beta omega_max^2
    from torsio.analysis.stability import eigenvalues

    fastest = float(np.max(np.abs(eigenvalues(system.at(wob=150e3, rpm=60.0)).real)))
    assert fastest > 0.5 * system.damping.beta * model.highest_frequency**2
    explicit_steps = result.duration * fastest / 3.3
    assert result.steps.max() + result.rejected.max() < explicit_steps / 20


# --- engines, determinism, failures ----------------------------------------------------------
def test_engines_agree(ten_dof: System) -> None:
    wob, rpm = np.array(POINTS[:2]).T
    numba_result = batch.simulate_batch(ten_dof, wob, rpm, engine="compiled")
    numpy_result = batch.simulate_batch(ten_dof, wob, rpm, engine="numpy")
    np.testing.assert_allclose(numpy_result.severity, numba_result.severity, atol=1e-3)
    scipy_result = batch.simulate_batch(ten_dof, wob[:1], rpm[:1], engine="scipy")
    assert abs(scipy_result.severity[0] - numba_result.severity[0]) < 1e-3


def test_results_do_not_depend_on_batch_composition_or_threads(ten_dof: System) -> None:
    wob = np.array([40e3, 120e3, 200e3, 90e3])
    rpm = np.array([50.0, 70.0, 90.0, 130.0])
    whole = batch.simulate_batch(ten_dof, wob, rpm, threads=2)
    for k in range(4):
        alone = batch.simulate_batch(ten_dof, wob[k : k + 1], rpm[k : k + 1], threads=1)
        assert alone.severity[0] == whole.severity[k]  # bitwise: each point is independent
        assert alone.steps[0] == whole.steps[k]


def test_law_without_compiled_kernel_uses_numpy(one_dof: System) -> None:
    class PlainTuckerWang:  # the documented contract only: no base class, no kernel
        name = "plain-tucker-wang"

        def __init__(self, **values: float) -> None:
            self.law = TuckerWang(**values, speed_unit="rpm")

        def torque(self, speed: object, wob: object, radius: object) -> np.ndarray:
            return self.law.torque(speed, wob, radius)

    system = attrs.evolve(one_dof, law=PlainTuckerWang(a0=0.221, a1=0.2, a2=0.89, a3=0.06))
    result = batch.simulate_batch(system, [150e3], [60.0])
    assert result.engine == "numpy"
    compiled = batch.simulate_batch(one_dof, [150e3], [60.0])
    assert compiled.engine == "compiled"
    # same law, same method: the engines agree to within the solver tolerance (the numpy
    # engine takes a central-difference slope, the compiled one the analytic slope)
    assert abs(result.severity[0] - compiled.severity[0]) < 1e-3
    with pytest.raises(ConfigError, match="no compiled kernel"):
        batch.simulate_batch(system, [150e3], [60.0], engine="compiled")


def test_failures_are_reported_not_hidden(one_dof: System) -> None:
    result = batch.simulate_batch(one_dof, [150e3, 50e3], [60.0, 120.0], max_steps=50)
    assert (result.status == batch_results.STATUS_MAX_STEPS).all()
    assert np.isnan(result.severity).all()
    assert "too many steps" in result.failures()[0] and "wob=150000 N" in result.failures()[0]


def test_bad_inputs_name_the_key(one_dof: System) -> None:
    with pytest.raises(ConfigError, match="wob"):
        batch.simulate_batch(one_dof, [-1.0], [60.0])
    with pytest.raises(ConfigError, match="rpm"):
        batch.simulate_batch(one_dof, [1e5], [0.0])
    with pytest.raises(ConfigError, match="engine"):
        batch.simulate_batch(one_dof, [1e5], [60.0], engine="euler")
    with pytest.raises(ConfigError, match="rtol"):
        batch.simulate_batch(one_dof, [1e5], [60.0], rtol=0.0)
    with pytest.raises(ConfigError, match="steady_window"):
        batch.simulate_batch(one_dof, [1e5], [60.0], duration=10.0, steady_window=20.0)


def test_non_chain_model_needs_the_scipy_engine(one_dof: System) -> None:
    # a 3-DOF model whose first and last inertias are joined by a spring: not tridiagonal
    k = np.array([[300.0, -100.0, -50.0], [-100.0, 200.0, -100.0], [-50.0, -100.0, 150.0]])
    model = LumpedModel(np.diag([100.0, 100.0, 200.0]), k, [1.0, 2.0, 3.0])
    system = attrs.evolve(one_dof, model=model)
    with pytest.raises(ConfigError, match="tridiagonal"):
        batch.simulate_batch(system, [1e4], [60.0])
    result = batch.simulate_batch(
        system, [1e4], [60.0], engine="scipy", duration=60.0, steady_window=20.0
    )
    expected = reference(system, 1e4, 60.0, 60.0, 20.0)
    assert abs(result.severity[0] - expected) < 1e-3


def test_a_failing_point_of_the_scipy_engine_is_marked_not_raised(one_dof: System) -> None:
    # one point's failure is reported by its status, as with the other engines, so that
    # a map with on_failure="mark" keeps the other points
    class NanAboveWeight:  # the documented contract: NaN torque above 150 kN
        name = "nan-above-150-kN"

        def __init__(self) -> None:
            self.law = TuckerWang(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm")

        def torque(self, speed: object, wob: object, radius: object) -> np.ndarray:
            values = self.law.torque(speed, wob, radius)
            return np.where(np.asarray(wob) > 150e3, np.nan, values)

    system = attrs.evolve(one_dof, law=NanAboveWeight())
    result = batch.simulate_batch(
        system, [100e3, 200e3], [120.0, 120.0], duration=30.0, steady_window=10.0, engine="scipy"
    )
    assert result.status.tolist() == [batch_results.STATUS_OK, batch_results.STATUS_SOLVER_FAILED]
    assert np.isfinite(result.severity[0]) and np.isnan(result.severity[1])
