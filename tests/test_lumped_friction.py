"""Coulomb friction along the string on the lumped models (docs/well.md, "Friction in the
dynamics"): a contact at every node, integrated by scipy between the contacts' switches
(torsio.solvers.contact_events, method="LSODA") and by the compiled engine (the default;
tests/test_compiled_contacts.py compares the two), against the closed forms of
torsio.well.break_off.

Every run is the built-in deviated well (torsio.examples.deviated_well_config: 2.5 km
string, mu_s 0.25/0.35, mu_d 0.2/0.3, threshold 0.5 rad/s) on strategy B with 10 drill-pipe
and 4 BHA elements, the bit off bottom.
"""

from __future__ import annotations

import attrs
import numpy as np
import pytest

from torsio.analysis.energy import energy_balance
from torsio.analysis.transient import simulate
from torsio.errors import ConfigError
from torsio.examples import deviated_well_config
from torsio.physics.damping import RayleighDamping
from torsio.well.break_off import break_off

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")


def _system(alpha: float, rpm: float, **discretization):
    config = deviated_well_config()
    options = {"strategy": "B", "dp_elements": 10, "bha_elements": 4, **discretization}
    system = config.system(**options)
    return attrs.evolve(system, damping=RayleighDamping(alpha=alpha)).at(wob=0.0, rpm=rpm)


@pytest.fixture(scope="module")
def reference():
    config = deviated_well_config()
    return break_off(config.well, config.string)


def test_node_capacities_add_up_to_the_closed_forms(reference):
    contacts = _system(0.0, 1.0).model.contacts
    assert contacts.static.size == 14  # a contact at every node
    assert contacts.static_total == pytest.approx(reference.torque, rel=1e-12)
    assert contacts.dynamic_total == pytest.approx(reference.sliding_torque, rel=1e-12)


def test_slow_start_up_breaks_the_bit_free_at_the_break_off_torque_and_twist(reference):
    # reference: break_off (int mu_s N r_o dx = 12.174 kN m, twist 19.255 rad). A held top at
    # 1 rpm twists the stuck string from the top down; the bit (speed exactly 0 while its
    # contact holds) turns once the torque has overcome the static friction of every node.
    # The twist of the lumped chain is a quadrature of int tau/(G J) dx: measured error
    # 1.3e-3, 7.7e-4, 5e-5 at 10, 20, 40 drill-pipe elements; the torque 1.4e-4.
    system = _system(alpha=0.0, rpm=1.0)
    duration = 1.1 * reference.twist / system.omega
    results = simulate(
        system, duration=duration, steady_window=0.1 * duration, output_step=0.05,
        method="LSODA", progress=False,
    )  # fmt: skip
    moved = int(np.flatnonzero(results.bit_speed != 0.0)[0])
    assert np.all(results.node_speeds[:moved, -1] == 0.0)  # stuck: exactly at rest
    assert results.surface_torque[moved - 1] == pytest.approx(reference.torque, rel=5e-3)
    assert system.omega * results.time[moved - 1] == pytest.approx(reference.twist, rel=5e-3)
    assert results.solver["engine"] == "scipy"
    assert results.solver["fallback"] is None  # LSODA asked for


def test_steady_rotation_takes_the_sliding_torque_plus_the_drag():
    # reference: the static balance of steady rotation with every contact sliding, surface
    # torque = sum C_d + alpha Omega sum I (no bit torque off bottom); from the steady state
    # the run stays there to round-off, and from rest it reaches it.
    system = _system(alpha=0.35, rpm=60.0)
    dynamics = system.dynamics()
    expected = dynamics.contacts.dynamic_total + float(dynamics.drag.sum()) * system.omega
    steady = simulate(
        system, duration=20.0, output_step=0.05, initial_state=dynamics.steady_state(),
        progress=False,
    )  # fmt: skip
    assert np.max(np.abs(steady.surface_torque / expected - 1.0)) < 1e-9
    assert steady.solver["contact_switches"] == 0
    started = simulate(system, duration=200.0, output_step=0.05, progress=False)
    assert started.surface_torque[-1] == pytest.approx(expected, rel=1e-3)
    summary = started.to_dict()
    assert summary["surface_torque_swing"] < 1e-3 * expected
    assert summary["bit_first_motion"] > 0.0
    assert summary["stick_slip_period"] is None  # steady: no period


def test_energy_balances_with_the_friction_work():
    # conservation law: the work of the held top = stored + drag + friction, the friction's
    # sampled power sum C |theta'| against the engine's exact sum C |d theta| per piece
    results = simulate(_system(alpha=0.35, rpm=60.0), duration=60.0, output_step=0.02,
                       progress=False)  # fmt: skip
    balance = energy_balance(results)
    assert balance.relative_residual < 1e-4
    exact = results.well_summary["friction_work"]
    assert balance.dissipated_friction[-1] == pytest.approx(exact, rel=1e-4)


def test_rodas4_and_lumped_maps_run_on_the_compiled_engine():
    system = _system(alpha=0.35, rpm=60.0)
    results = simulate(system, duration=20.0, method="RODAS4", progress=False)
    assert results.solver["engine"] == "compiled" and results.solver["fallback"] is None
    from torsio.analysis.maps import severity_map

    grid = severity_map(system, [0.0], [60.0], duration=20.0)
    assert np.all(np.isfinite(grid.severity))


def test_consistent_mass_is_refused_with_a_well():
    with pytest.raises(ConfigError, match=r"discretization\.strategy.*lumped-mass"):
        _system(alpha=0.35, rpm=60.0, strategy="consistent")


def test_a_chain_without_sections_is_refused_with_a_well():
    from torsio.well.string_contacts import with_contacts

    model = _system(alpha=0.35, rpm=60.0).model
    with pytest.raises(ConfigError, match=r"^well: .*\[chain\] has none"):
        with_contacts(model, deviated_well_config().well, None)
