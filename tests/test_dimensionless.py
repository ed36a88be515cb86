"""The dimensionless formulation (paper Eqs. 9-11 with ERRATA 2 and 3).

Sources: k_eq = 324.86 N m/rad and I = 455.65 kg m^2 of strategy A (ERRATA 1);
the definitions of Eqs. 9-11 (Pi_1 = Omega/omega_1, Pi_2 = W R/k_eq, b2 = omega_1 a2
by ERRATA 2); the change of variables tau = omega_1 t, which makes the dimensionless
run the dimensional one rescaled (theta'(tau) = theta_dot(t)/omega_1, same S_SS).
"""

from __future__ import annotations

import math

import attrs
import numpy as np
import pytest

from torsio.analysis.transient import simulate
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.model.modal import modal_analysis
from torsio.physics.dimensionless import (
    DimensionlessLaw,
    dimensional_system,
    dimensionless_groups,
    dimensionless_system,
)
from torsio.plugins import get_bit_law

RPM = 30.0 / math.pi  # rpm per rad/s


@pytest.fixture(scope="module")
def config():
    return builtin_config()


def test_groups_of_strategy_a(config):
    system = config.system(strategy="A").at(wob=100e3, rpm=60)
    groups = dimensionless_groups(system)
    assert groups.k_eq == pytest.approx(324.86, abs=0.005)  # ERRATA 1
    omega1 = math.sqrt(324.8566 / 455.6497)  # ERRATA 1: k / I of the single DOF
    assert groups.omega1 == pytest.approx(omega1, rel=1e-5)
    assert groups.i_eq == pytest.approx(455.65, abs=0.005)  # 1 DOF: I_eq = I (Eq. 10)
    assert groups.pi1 == pytest.approx(60 / RPM / groups.omega1)
    assert groups.pi2 == pytest.approx(100e3 * 0.108 / groups.k_eq)  # ERRATA 3
    # b0..b3 of the rpm reading a1..a3 = 0.2, 0.89, 0.06 (converted to rad/s first)
    a1, a2, a3 = 0.2 * RPM, 0.89 * RPM, 0.06 * RPM**2
    assert groups.b0 == 0.221
    assert groups.b1 == pytest.approx(groups.omega1 * a1)
    assert groups.b2 == pytest.approx(groups.omega1 * a2)  # ERRATA 2, not a2
    assert groups.b3 == pytest.approx(groups.omega1**2 * a3)
    wob, rpm = groups.operating_point(groups.pi1, groups.pi2)
    assert (wob, rpm) == (pytest.approx(100e3), pytest.approx(60.0))


@pytest.mark.parametrize("strategy", ["A", "C"])
def test_dimensionless_model_scales(config, strategy):
    options = {} if strategy == "C" else {"strategy": strategy}
    system = config.system(**options).at(wob=100e3, rpm=60)
    scaled = dimensionless_system(system)
    assert scaled.model.equivalent_stiffness == pytest.approx(1.0, rel=1e-12)
    first = modal_analysis(scaled.model, 1).frequencies_rad[0]
    assert first == pytest.approx(1.0, rel=1e-12)
    groups = dimensionless_groups(system)
    assert scaled.omega == pytest.approx(groups.pi1)
    assert scaled.wob * scaled.bit_radius == pytest.approx(groups.pi2)
    # [C] omega_1 / k_eq (Eq. 11)
    assert np.allclose(
        scaled.damping_matrix, system.damping_matrix * groups.omega1 / groups.k_eq, rtol=1e-12
    )


def test_tucker_wang_torque_is_equation_11(config):
    """The dimensionless bit torque is Pi_2 b0 (tanh(b1 s) + b2 s / (1 + b3 s^2))."""
    system = config.system().at(wob=100e3, rpm=60)
    groups = dimensionless_groups(system)
    scaled = dimensionless_system(system)
    s = np.linspace(-3.0, 12.0, 31)
    b0, b1, b2, b3 = groups.tucker_wang
    eq11 = groups.pi2 * b0 * (np.tanh(b1 * s) + b2 * s / (1 + b3 * s**2))
    assert np.allclose(scaled.bit_torque(s), eq11, rtol=1e-12, atol=0)
    dimensional = system.bit_torque(groups.omega1 * s) / groups.k_eq
    assert np.allclose(eq11, dimensional, rtol=1e-12, atol=0)


def test_any_law_rescaled(config):
    """Any law: T'(s) = T(omega_1 s, W, R) / k_eq, and its slope scales by omega_1/k_eq."""
    law = get_bit_law("coulomb-stribeck")()
    system = attrs.evolve(config.system(), law=law).at(wob=100e3, rpm=20)
    groups = dimensionless_groups(system)
    assert groups.tucker_wang is None and groups.b2 is None
    scaled = dimensionless_system(system)
    assert isinstance(scaled.law, DimensionlessLaw)
    s = np.linspace(-2.0, 5.0, 29)
    expected = law.torque(groups.omega1 * s, 100e3, 0.108) / groups.k_eq
    assert np.allclose(scaled.bit_torque(s), expected, rtol=1e-12, atol=1e-15)
    slope = scaled.law.slope(s, scaled.wob, scaled.bit_radius)
    assert np.allclose(
        slope, law.slope(groups.omega1 * s, 100e3, 0.108) * groups.omega1 / groups.k_eq
    )


def _compare(system):
    """Dimensional and dimensionless runs of the same case (tight tolerances).

    Both on LSODA: a wrapped plugin law (DimensionlessLaw) has no compiled kernel, and the
    two runs must read S_SS the same way (the compiled engine reads the continuous
    solution's extremes, LSODA the samples)."""
    groups = dimensionless_groups(system)
    tolerances = {"rtol": 1e-9, "atol": 1e-12, "method": "LSODA"}
    period = 2 * math.pi / groups.omega1  # 20 periods, the last 6 as steady window
    dimensional = simulate(system, duration=20 * period, steady_window=6 * period, **tolerances)
    dimensionless = simulate(
        dimensionless_system(system),
        duration=20 * 2 * math.pi,  # tau = omega_1 t
        steady_window=6 * 2 * math.pi,
        **tolerances,
    )
    assert dimensionless.time.size == dimensional.time.size
    assert np.allclose(dimensionless.time, groups.omega1 * dimensional.time, rtol=1e-12, atol=1e-9)
    scale = np.max(np.abs(dimensionless.bit_speed))
    speed_error = np.max(np.abs(dimensionless.bit_speed - dimensional.bit_speed / groups.omega1))
    return dimensional, dimensionless, speed_error / scale


@pytest.mark.parametrize("strategy", ["A", "C"])
@pytest.mark.parametrize(("law", "rpm"), [("tucker-wang", 60.0), ("coulomb-stribeck", 20.0)])
def test_dimensionless_run_equals_dimensional(config, strategy, law, rpm):
    options = {} if strategy == "C" else {"strategy": strategy}
    system = config.system(**options).at(wob=100e3, rpm=rpm)
    if law != "tucker-wang":
        system = attrs.evolve(system, law=get_bit_law(law)())
    dimensional, dimensionless, speed_error = _compare(system)
    assert dimensional.severity > 0.8  # a stick-slip case, not a trivial one
    assert speed_error < 1e-6
    assert dimensionless.severity == pytest.approx(dimensional.severity, abs=1e-6)
    assert dimensionless.stick_fraction == pytest.approx(dimensional.stick_fraction, abs=1e-3)
    groups = dimensionless_groups(system)
    # torques scale by k_eq (the surface torque is a smooth function of the state; the
    # bit torque of a steep smooth sign is not, and is checked law by law above)
    surface = dimensional.surface_torque / groups.k_eq
    surface_error = np.max(np.abs(dimensionless.surface_torque - surface))
    assert surface_error < 1e-6 * np.max(np.abs(surface))
    assert dimensionless.to_dict()["pi1"] == pytest.approx(groups.pi1)


def test_dimensionless_model_damping(chain_with_own_dampers):
    """A model's own damping matrix is scaled by omega_1/k_eq; the runs agree."""
    system = chain_with_own_dampers
    dimensional, dimensionless, speed_error = _compare(system)
    assert dimensional.severity > 0.8
    assert speed_error < 1e-6
    assert dimensionless.severity == pytest.approx(dimensional.severity, abs=1e-6)


def test_system_at_groups(config):
    system = config.system()
    at = dimensional_system(system, pi1=5.0, pi2=20.0)
    groups = dimensionless_groups(at)
    assert (groups.pi1, groups.pi2) == (pytest.approx(5.0), pytest.approx(20.0))
    scaled = dimensionless_system(system, pi1=5.0, pi2=20.0)
    assert scaled.omega == pytest.approx(5.0) and scaled.wob == pytest.approx(20.0)


@pytest.mark.parametrize(
    ("pi1", "pi2", "key"), [(0.0, 1.0, "pi1"), (-2.0, 1.0, "pi1"), (1.0, -1.0, "pi2")]
)
def test_bad_groups(config, pi1, pi2, key):
    system = config.system()
    with pytest.raises(ConfigError) as info:
        dimensionless_system(system, pi1=pi1, pi2=pi2)
    assert info.value.key == key
    assert repr(pi1 if key == "pi1" else pi2) in str(info.value)
