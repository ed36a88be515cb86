"""Coulomb friction along the string on the lumped axial-torsional chain (docs/axial.md,
"Friction along the string"): one contact's set-valued step against its closed forms
(torsio.axial.string_friction), steady drilling with friction (torsio.axial.steady_friction),
the energy balance (torsio.axial.energy_balance), the break-off of torsio.well.break_off,
and the built-in rgd_deviated_well.toml through the command line.

Every run is rgd_deviated_well.toml (torsio.examples.rgd_deviated_well_config: the stepped
RGD string, 2.5 km, in the deviated well's survey; 24 nodes of at most 100 m), short.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from importlib import resources

import numpy as np
import pytest
import scipy.optimize

from torsio.axial.steady_friction import friction_damping, friction_split, steady_with_friction
from torsio.axial.string_friction import node_friction, sliding_speed
from torsio.axial.transient import simulate_axial
from torsio.config.reading import parse_config_text
from torsio.errors import ConfigError
from torsio.examples import rgd_deviated_well_config

TEXT = (
    resources.files("torsio").joinpath("data/rgd_deviated_well.toml").read_text(encoding="utf-8")
)


def _config(text: str = TEXT):
    return parse_config_text(text, source="test")


def _run(axial, wob=100e3, rpm=60.0, **options):
    run_options = {**axial.run_options(), **options}
    return simulate_axial(axial.assembly, axial.bit, wob, rpm, growth_rate=False, **run_options)


# --- one contact -------------------------------------------------------------------------


@pytest.mark.parametrize("free", [(0.01, 0.127), (-0.3, 0.002), (1e-4, -2.0)])
def test_sliding_step_against_the_closed_form_of_equal_metrics(free):
    # closed form (m = I/r²): s = s*(1 − h F_d/(m |s*|)); measured error 0 to 2e-16
    mass, radius, step, force = 500.0, 0.0635, 1e-3, 3000.0
    velocity, tangential = free
    inertia = mass * radius**2
    new_v, new_w, stuck = node_friction(
        velocity, tangential / radius, radius, 1 / mass, 1 / inertia, 4000.0, force, step, False
    )
    factor = 1.0 - step * force / (mass * math.hypot(velocity, tangential))
    assert not stuck
    assert new_v == pytest.approx(velocity * factor, rel=1e-12, abs=0)
    assert new_w * radius == pytest.approx(tangential * factor, rel=1e-12, abs=0)


def test_sliding_speed_is_the_root_with_unequal_metrics():
    # reference: the root of phi(rho) by brentq to 1e-15, m = 500 kg, I/r² = 20 kg (the
    # Newton steps from the lower bound reach it to round-off)
    m, j, p = 500.0, 20.0, 3.0
    a, b = 0.01, 0.127

    def phi(rho):
        return (m * a / (m * rho + p)) ** 2 + (j * b / (j * rho + p)) ** 2 - 1.0

    reference = scipy.optimize.brentq(phi, 0.0, math.hypot(a, b), xtol=1e-16, rtol=1e-15)
    assert sliding_speed(a, b, m, j, p) == pytest.approx(reference, rel=1e-13)


def test_contact_sticks_when_the_stopping_impulse_is_within_the_cone():
    # the impulse that stops the node, |(m V*, (I/r²) r Ω*)|, against h F_s (slow: static
    # cone) or h F_d (fast: sliding cone)
    m, r, inertia, h = 500.0, 0.0635, 2.0, 1e-3
    j = inertia / r**2
    velocity, speed = 0.004, 0.05
    stop = math.hypot(m * velocity, j * r * speed)
    just_above, just_below = stop / h * (1 + 1e-9), stop / h * (1 - 1e-9)
    assert node_friction(velocity, speed, r, 1 / m, 1 / inertia, just_above, 0.5 * just_above,
                         h, True) == (0.0, 0.0, True)  # fmt: skip
    assert not node_friction(velocity, speed, r, 1 / m, 1 / inertia, just_below, 0.5 * just_below,
                             h, True)[2]  # fmt: skip
    # on the sliding branch the cone is F_d: the same F_s does not hold the node
    assert not node_friction(velocity, speed, r, 1 / m, 1 / inertia, just_above, 0.5 * just_above,
                             h, False)[2]  # fmt: skip


def test_damping_matrix_against_finite_differences_of_the_friction_force():
    # reference: central differences (step 1e-7 relative) of f(s) = −F_d s/|s|, s = (V, r ω)
    config = rgd_deviated_well_config()
    contacts = config.axial.contacts.at_wob(100e3)
    rop, speed = 0.0074, 2 * math.pi
    matrices = friction_damping(contacts, rop, speed)
    for i in np.flatnonzero(contacts.sliding_force > 0)[:5]:
        r, f = contacts.radius[i], contacts.sliding_force[i]
        s0 = np.array([rop, r * speed])

        def force(s, f=f):
            return -f * s / np.linalg.norm(s)

        jac = np.zeros((2, 2))
        for k in range(2):
            delta = np.zeros(2)
            delta[k] = 1e-7 * np.linalg.norm(s0)
            jac[:, k] = (force(s0 + delta) - force(s0 - delta)) / (2 * delta[k])
        assert np.allclose(matrices[i], -jac, rtol=1e-6, atol=1e-9 * f / np.linalg.norm(s0))
        assert np.all(np.linalg.eigvalsh(matrices[i]) >= -1e-9 * f)  # positive semi-definite


# --- runs ----------------------------------------------------------------------------------


def test_vertical_well_is_bit_identical_to_the_run_without_well():
    # a vertical survey: zero normal force at every node, so no contact
    vertical = TEXT.replace(
        "inclination = [0.0, 0.0, 15.0, 35.0, 35.0, 25.0, 20.0, 20.0]",
        "inclination = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]",
    )
    start = vertical.index("[well]")
    without = vertical[:start] + vertical[vertical.index("[bit_rock]") :]
    with_well, no_well = _config(vertical).axial, _config(without).axial
    assert with_well.contacts.count == 0 and no_well.contacts is None
    a = _run(with_well, duration=4.0, window=2.0)
    b = _run(no_well, duration=4.0, window=2.0)
    assert np.array_equal(a.samples, b.samples)
    assert a.summary == b.summary
    assert a.string_friction_work == 0.0 and a.contact_switches == 0


@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_steady_start_stays_on_the_closed_form(hook):
    # closed form (torsio.axial.steady_friction): bit weight W_b (weight hook: W_h − Σ F_a),
    # ROP, MSE and surface torque T₀ + Σ F_d r² Ω₀/|s₀|; measured relative errors <= 3e-12
    text = TEXT.replace('hook = "weight"', f'hook = "{hook}"')
    axial = _config(text).axial
    run = _run(axial, start="steady", perturbation=0.0, duration=3.0, window=2.0)
    contacts = axial.contacts.at_wob(100e3)
    steady, friction = steady_with_friction(axial.bit, 100e3, 60.0, contacts, hook)
    assert run.contact_switches == 0
    assert run.rop_mean == pytest.approx(steady.rop, rel=1e-9)
    assert run.mse_mean == pytest.approx(steady.mse, rel=1e-9)
    assert run.weight_mean == pytest.approx(steady.wob, rel=1e-9)
    assert run.torque_mean == pytest.approx(steady.bit_torque, rel=1e-9)
    surface = run.signal("surface_torque")
    assert np.max(np.abs(surface / friction.surface_torque - 1.0)) < 1e-9
    if hook == "weight":
        assert steady.wob == pytest.approx(100e3 - friction.axial_friction, rel=1e-12)
    else:
        assert friction.hook_force == pytest.approx(100e3 + friction.axial_friction, rel=1e-12)


def test_energy_residual_halves_with_the_step():
    # the scheme's works summed on each step's new velocities: residual / top work of first
    # order in h. A stick-slip run from rest, 20 s: measured 2.17e-5, 1.32e-5, 7.17e-6 at
    # 100/200/400 steps per period (orders 0.72, 0.88, tending to 1)
    ratios = []
    for steps in (100, 200, 400):
        run = _run(rgd_deviated_well_config().axial, duration=20.0, window=5.0,
                   steps_per_period=steps, samples=0)  # fmt: skip
        ratios.append(abs(run.energy.residual) / run.energy.top_work)
    assert run.energy.string_friction_work > 0.1 * run.energy.top_work
    orders = [math.log2(ratios[k] / ratios[k + 1]) for k in range(2)]
    assert ratios[0] < 1e-4
    assert all(0.6 < order < 1.3 for order in orders), (ratios, orders)
