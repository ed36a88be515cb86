"""The one description of the dynamics (torsio.physics.dynamics) and the top drives.

Expected values come from exact identities: the Jacobian against a central
difference of the same right-hand side, steady rotation as a fixed point of the
equations, the impedance of a PI loop written out by hand (J s + kp + ki/s at
s = i omega), and the torque balance of a torque-driven top.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio import (
    ConstantSpeedTop,
    PITopDrive,
    SoftTorqueTopDrive,
    TorqueTopDrive,
    ZTorqueTopDrive,
    top_drive_from_parameters,
)
from torsio.errors import ConfigError
from torsio.examples import builtin_config
from torsio.physics.dynamics import Dynamics
from torsio.physics.system import System
from torsio.plugins import top_drives

J_TD = 2900.0  # kg m^2, a top drive with gearbox (NORCE Simulator4nDOF default)


def tops() -> list[object]:
    return [
        ConstantSpeedTop(),
        TorqueTopDrive(inertia=J_TD, torque=2.0e4, drag=10.0),
        PITopDrive(inertia=J_TD, kp=2.0e4, ki=5 * J_TD),
        PITopDrive(inertia=J_TD, kp=2.0e4, ki=5 * J_TD, max_torque=5.0e3),
        SoftTorqueTopDrive(inertia=J_TD),
        ZTorqueTopDrive(inertia=J_TD),
    ]


def finite_difference_jacobian(dynamics: Dynamics, y: np.ndarray) -> np.ndarray:
    jac = np.zeros((y.size, y.size))
    for i in range(y.size):
        h = 1e-6 * max(1.0, abs(y[i]))
        step = np.zeros(y.size)
        step[i] = h
        jac[:, i] = (dynamics.rhs(0.0, y + step) - dynamics.rhs(0.0, y - step)) / (2 * h)
    return jac


@pytest.mark.parametrize("strategy", ["A", "B", "C"])
@pytest.mark.parametrize("top", tops(), ids=lambda t: getattr(t, "name", "?"))
def test_jacobian_is_the_derivative_of_the_rhs(strategy: str, top: object) -> None:
    # exact identity: the analytic Jacobian equals a central difference of rhs
    # (truncation error ~1e-12 relative at step 1e-6)
    system = builtin_config().system(strategy=strategy).at(wob=100e3, rpm=60)
    dynamics = system.with_top(top).dynamics()
    rng = np.random.default_rng(1)
    y = dynamics.steady_state() + 0.01 * rng.standard_normal(dynamics.size)
    analytic = dynamics.jacobian(0.0, y).toarray()
    numeric = finite_difference_jacobian(dynamics, y)
    assert np.max(np.abs(analytic - numeric)) < 1e-7 * np.max(np.abs(analytic))
    lower, upper = dynamics.jacobian_bands
    rows, cols = np.nonzero(analytic)
    assert np.all(rows - cols <= lower) and np.all(cols - rows <= upper)


@pytest.mark.parametrize("top", tops(), ids=lambda t: getattr(t, "name", "?"))
def test_steady_rotation_is_a_fixed_point(top: object) -> None:
    # steady rotation at Omega_ref solves the equations exactly (rhs = 0 to round-off)
    system = builtin_config().system(strategy="C").at(wob=60e3, rpm=80)
    dynamics = system.with_top(top).dynamics()
    y = dynamics.steady_state()
    scale = np.max(np.abs(dynamics.stiffness_matrix)) * max(1.0, np.max(np.abs(y)))
    assert np.max(np.abs(dynamics.rhs(0.0, y))) < 1e-12 * scale


def test_held_top_keeps_the_model_and_a_top_node_extends_it() -> None:
    system = builtin_config().system(strategy="C").at(wob=60e3, rpm=80)
    held = system.dynamics()
    assert held.dofs == system.model.dofs and held.states == 0
    assert held.reference_speed == system.omega
    driven = system.with_top(PITopDrive(inertia=J_TD, kp=1e4, ki=1e3)).dynamics()
    assert driven.dofs == system.model.dofs + 1 and driven.states == 1
    k1 = system.model.top_stiffness[0]
    assert driven.stiffness_diag[0] == k1 and driven.stiffness_upper[0] == -k1
    assert driven.mass_diag[0] == J_TD
    # the extended chain is free: rigid rotation stores no strain ([K] 1 = 0)
    assert np.allclose(driven.stiffness_matrix.sum(axis=1), 0.0, atol=1e-9 * k1)


def test_strategy_b_chain_is_tied_to_the_top_at_its_first_node_only() -> None:
    # [K] 1 of a chain is k_1 e_1 exactly (each lower row is -k_i + (k_i + k_i+1) - k_i+1);
    # strategy B's drill-pipe/BHA junction leaves round-off in that row sum (3.6e-12 N m/rad
    # for the built-in string), which is not a spring to the top: a top drive with inertia
    # takes the model, and its node joins the first node by k_1 and c_1 = beta k_1
    system = builtin_config().system(strategy="B").at(wob=100e3, rpm=60)
    k = system.model.stiffness
    assert k.sum(axis=1)[1] != 0.0  # the round-off this checks against is really there
    springs = -np.diag(k, 1)  # k_2 .. k_n: the chain's springs below the first node
    assert system.model.top_stiffness[0] == k[0, 0] - springs[0]
    assert not np.any(system.model.top_stiffness[1:])
    driven = system.with_top(PITopDrive(inertia=J_TD, kp=5e3, ki=J_TD)).dynamics()
    k1 = system.model.top_stiffness[0]
    assert driven.dofs == system.model.dofs + 1 and driven.states == 1
    assert driven.stiffness_upper[0] == -k1
    assert driven.damping_upper[0] == -system.damping.beta * k1


def test_consistent_mass_with_a_top_drive_is_refused() -> None:
    system = builtin_config().system(strategy="consistent")
    with pytest.raises(ConfigError, match="discretization.strategy.*lumped-mass"):
        system.with_top(PITopDrive(inertia=J_TD, kp=1e4, ki=1e3)).dynamics()


def test_torque_top_turns_at_the_torque_balance_speed() -> None:
    # u = sum(drag) Omega + T_bit(Omega): the reference speed solves the balance
    system = builtin_config().system(strategy="A").at(wob=50e3)
    top = TorqueTopDrive(inertia=930.0, torque=1.5e4, drag=425.0)
    dynamics = system.with_top(top).dynamics()
    omega = dynamics.reference_speed
    balance = dynamics.drag.sum() * omega + float(dynamics.bit_torque(omega))
    assert balance == pytest.approx(1.5e4, rel=1e-12)


def test_pi_impedance_is_a_pure_damper_at_the_tuning_frequency() -> None:
    # Z(i w) = kp + i (w J - ki / w) (PI loop written out); with ki = w_s^2 J, Z(w_s) = kp
    omega_s = 0.8444
    top = PITopDrive(inertia=J_TD, kp=7000.0, ki=omega_s**2 * J_TD)
    assert abs(top.impedance(omega_s) - 7000.0) <= 1e-12 * 7000.0
    boundary = top.boundary(builtin_config().system(strategy="A"))
    assert abs(boundary.impedance(omega_s) - 7000.0) <= 1e-12 * 7000.0
    assert top.reflection_coefficient(7000.0) == 0.0
    assert top.reflection_coefficient(3 * 7000.0) == pytest.approx(0.5, rel=1e-15)


def test_soft_torque_default_tuning() -> None:
    # ki = omega_1^2 J and kp = zeta = J_p sqrt(G rho) of the top section (SoftTorque tuning)
    from torsio.model.modal import modal_analysis

    system = builtin_config().system(strategy="C")
    omega_1 = float(modal_analysis(system.model, 1).frequencies_rad[0])
    section = system.string.sections[0]
    zeta = section.polar_moment * math.sqrt(
        section.material.shear_modulus * section.material.density
    )
    kp, ki = SoftTorqueTopDrive(inertia=J_TD).gains(system)
    assert kp == pytest.approx(zeta, rel=1e-15)
    assert ki == pytest.approx(omega_1**2 * J_TD, rel=1e-15)


def test_registry_and_parameter_errors() -> None:
    assert {"constant-speed", "torque", "pi", "soft-torque", "z-torque"} <= set(top_drives())
    pi = top_drive_from_parameters("pi", inertia=J_TD, kp=1e4, ki=1e3, max_torque=6e4)
    assert pi == PITopDrive(inertia=J_TD, kp=1e4, ki=1e3, max_torque=6e4)
    with pytest.raises(ConfigError, match="top_drive.kind: unknown top drive 'stiff'"):
        top_drive_from_parameters("stiff")
    with pytest.raises(ConfigError, match="top_drive.gain: top drive 'pi' has no parameter"):
        top_drive_from_parameters("pi", inertia=J_TD, kp=1e4, ki=1e3, gain=2.0)
    with pytest.raises(ConfigError, match="top_drive.inertia: top drive 'torque' needs"):
        top_drive_from_parameters("torque", torque=1e4)
    with pytest.raises(ConfigError, match="top_drive.kp: expected a positive finite value"):
        top_drive_from_parameters("pi", inertia=J_TD, kp=0.0, ki=1e3)
    with pytest.raises(ConfigError, match="top_drive.ki: cannot read 'fast' as a quantity"):
        top_drive_from_parameters("pi", inertia=J_TD, kp=1.0, ki="fast")
    with pytest.raises(ConfigError, match="top_drive.kp: expected a number"):
        PITopDrive(inertia=J_TD, kp=None, ki=1e3)  # None only where a tuning supplies it
    with pytest.raises(ConfigError, match="top_drive.alpha: expected a value in"):
        ZTorqueTopDrive(inertia=J_TD, alpha=1.5)


def test_soft_torque_on_a_chain_without_string_needs_kp(chain_with_own_dampers: System) -> None:
    system = chain_with_own_dampers.with_top(SoftTorqueTopDrive(inertia=J_TD))
    with pytest.raises(ConfigError, match="top_drive.kp: .*give kp"):
        system.dynamics()
    tuned = chain_with_own_dampers.with_top(SoftTorqueTopDrive(inertia=J_TD, kp=500.0))
    assert tuned.dynamics().states == 1


def test_system_refuses_an_object_that_is_no_top_drive(one_dof: System) -> None:
    with pytest.raises(ConfigError, match="top_drive: expected a top drive"):
        one_dof.with_top("pi")


def test_plugin_guide_top_drive_example() -> None:
    """The top-drive plugin of docs/plugins.md registers and runs as written."""
    import types
    from pathlib import Path

    from torsio.plugins import plugin_manager

    guide = (Path(__file__).resolve().parents[1] / "docs" / "plugins.md").read_text()
    section = guide[guide.index("## Top drives") :]
    start = section.index("```py\n") + 6
    code = section[start : section.index("\n```", start)]
    module = types.ModuleType("proportional_top")
    exec(compile(code, "docs/plugins.md", "exec"), module.__dict__)
    plugin_manager().register(module, name="proportional_top")
    try:
        top = top_drive_from_parameters("proportional", inertia=J_TD, kp=5e3)
        system = builtin_config().system(strategy="A").at(wob=20e3, rpm=60)
        dynamics = system.with_top(top).dynamics()
        # a pure proportional loop: a top-drive node, no controller state
        assert dynamics.states == 0 and dynamics.has_top_node
        assert dynamics.top.d[0] == 5e3
    finally:
        plugin_manager().unregister(name="proportional_top")
