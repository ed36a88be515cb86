"""Energy accounting: work in = stored + dissipated + work at the bit.

Source of every check: the power balance of the equations of motion,
d/dt (E_kin + E_pot) = Omega T_s - v^T C_rel v - theta'^T D theta' - T_bit theta_N'
(derived in the docstring of torsio.analysis.energy from Eq. 3), and, for the steady
state, the torque balance of the whole string.

Stated tolerance: with the default output grid (200 samples per period of the
first mode) the cumulative Simpson quadrature of the sampled powers closes the
balance of a stick-slip run to within 1e-5 of the work in (measured: 3e-7 for
strategy C at 100 kN, 60 rpm; 2e-6 at 200 kN, 100 rpm).
"""

from __future__ import annotations

import attrs
import numpy as np
import pytest

from torsio.analysis.energy import damping_split, energy_balance
from torsio.analysis.transient import simulate
from torsio.examples import builtin_config
from torsio.model.modal import modal_analysis
from torsio.physics.damping import RayleighDamping
from torsio.physics.laws import ConstantTorque

BALANCE_TOLERANCE = 1e-5  # fraction of the work in, see the module docstring


@pytest.fixture(scope="module")
def config():
    return builtin_config()


@pytest.mark.parametrize(
    ("strategy", "wob", "rpm"),
    [("C", 100e3, 60.0), ("C", 200e3, 100.0), ("A", 100e3, 60.0), ("consistent", 100e3, 60.0)],
)
def test_energy_balance_stick_slip(config, strategy, wob, rpm):
    options = {} if strategy == "C" else {"strategy": strategy}
    if strategy == "consistent":
        options.update(dp_elements=5, bha_elements=2)
    results = simulate(config.system(**options).at(wob=wob, rpm=rpm))
    assert results.severity > 0.8  # a stick-slip run
    balance = energy_balance(results)
    assert balance.relative_residual < BALANCE_TOLERANCE
    totals = balance.to_dict()
    assert totals["work_in"] > 0 and totals["work_bit"] > 0
    assert totals["dissipated_relative"] > 0 and totals["dissipated_drag"] > 0
    # the stored energy at the end is small next to what went through the string
    assert abs(totals["kinetic_change"] + totals["potential_change"]) < 0.05 * totals["work_in"]


def test_energy_balance_model_damping(chain_with_own_dampers):
    """A chain with its own dampers and drag (ModelDamping): the same balance holds."""
    system = chain_with_own_dampers
    relative, drag = damping_split(system)
    assert np.allclose(drag, np.diag([20.0, 0.0, 50.0]))
    assert np.allclose(relative.sum(axis=1), [40.0, 0.0, 0.0])  # only c1 ties to the top
    results = simulate(system)
    balance = energy_balance(results)
    assert balance.relative_residual < BALANCE_TOLERANCE


def test_undamped_no_load_work_goes_into_stored_energy(config):
    """No damping and no bit torque: work in = change of kinetic + potential energy."""
    system = attrs.evolve(
        config.system(),
        damping=RayleighDamping(0.0, 0.0),
        law=ConstantTorque(torque_on_bit=0.0),
        rpm=60.0,
    )
    period = 2 * np.pi / float(modal_analysis(system.model, 1).frequencies_rad[0])
    # Undamped, every mode stays excited (the fifth at 6.7 rad/s): sample finely so that
    # the fourth-order quadrature error (measured 1e-6 at period/200, 1.7e-9 at
    # period/1000, 1e-10 at period/4000) is below the check.
    results = simulate(
        system,
        duration=5 * period,
        steady_window=period,
        rtol=1e-10,
        atol=1e-12,
        output_step=period / 1000,
    )
    balance = energy_balance(results)
    assert np.all(balance.dissipated == 0.0) and np.all(balance.work_bit == 0.0)
    assert np.max(np.abs(balance.residual)) < 1e-8 * np.max(np.abs(balance.work_in))


def test_steady_rotation_drag(config):
    """Steady rotation with constant bit torque T: the alpha [I] drag acts on absolute speed.

    Torque balance of the whole string: T_s = T + alpha Omega 1^T [I] 1, and the
    dissipation rate is alpha Omega^2 1^T [I] 1 (no relative motion at steady state).
    """
    alpha, torque = 0.35, 3000.0
    system = attrs.evolve(
        config.system(),
        damping=RayleighDamping(alpha, 1.0),
        law=ConstantTorque(torque_on_bit=torque),
        rpm=60.0,
    )
    results = simulate(system, rtol=1e-9, atol=1e-12)
    total_inertia = system.model.total_inertia
    expected = torque + alpha * system.omega * total_inertia
    assert results.surface_torque[-1] == pytest.approx(expected, rel=1e-7)
    balance = energy_balance(results)
    t, drag = balance.time, balance.dissipated_drag
    rate = (drag[-1] - drag[-101]) / (t[-1] - t[-101])
    assert rate == pytest.approx(alpha * system.omega**2 * total_inertia, rel=1e-6)
    rate_relative = (balance.dissipated_relative[-1] - balance.dissipated_relative[-101]) / (
        t[-1] - t[-101]
    )
    assert abs(rate_relative) < 1e-6 * rate


def test_an_axial_run_is_refused_for_its_own_balance():
    # an axial run keeps no states: energy_balance names the engine's balance instead, which
    # closes to the first-order scheme's residual (conservation of energy, docs/axial.md)
    from torsio.analysis.axial_energy import RESIDUAL_TOLERANCE
    from torsio.axial import rgd_example, rgd_two_dof_example, simulate_axial

    run = simulate_axial(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=2.0,
                         window=1.0, growth_rate=False)  # fmt: skip
    with pytest.raises(TypeError, match=r"results\.axial\.energy"):
        energy_balance(run)
    assert run.axial.energy.relative_residual < RESIDUAL_TOLERANCE
