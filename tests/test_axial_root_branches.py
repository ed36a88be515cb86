"""Characteristic roots followed over a parameter and the crossing of each one
(torsio.axial.root_branches, torsio.axial.stability.each_mode_crossing).

Independent references: the closed-form crossings of the delay oscillator
x'' + c x' + k x + d (x − x(t − τ)) = 0 (λ = iω: (k − ω² + d)² + c² ω² = d², τ from the
phase, the direction from dλ/dτ = −∂Δ/∂τ / ∂Δ/∂λ); those of the axial equation
M λ² + n ζ ε a (1 − e^{−λ t_n}) = 0 (ω t_n = (2j + 1)π, M ω² = 2 n ζ ε a); the number of
unstable roots counted afresh (collocation at twice the default order) at each rpm, which
the signed crossings below it must give; the growth rate's own sign changes
(:func:`mode_crossings`, grid and Brent's method on the rightmost root)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from axial_files import damped_pipe

from torsio.axial.delay_roots import LinearDelaySystem, rightmost_roots
from torsio.axial.linearization import axial_linearization, drilling_linearization
from torsio.axial.rgd import rgd_example
from torsio.axial.root_branches import branch_crossings, follow_roots, unstable_roots
from torsio.axial.stability import DrillingCase, each_mode_crossing, mode_crossings
from torsio.errors import ConfigError
from torsio.model.axial_assembly import rgd_two_dof_example

BIT = rgd_example()
WOB = 100e3
MASS = 29981.3  # the axial mass of the 2-DOF tests (test_axial_stability)

# the delay oscillator
C, K, D = 0.2, 4.0, 2.0


def _oscillator(tau):
    return LinearDelaySystem([[1.0]], [[C]], [[K]], [[D]], delay=tau)


def _oscillator_crossings(low, high):
    """(τ, ω, destabilizing) of every λ = iω root with τ in (low, high), in closed form."""
    b, q = 2 * (K + D) - C * C, (K + D) ** 2 - D * D
    found = []
    for u in ((b + s * math.sqrt(b * b - 4 * q)) / 2 for s in (1, -1)):
        omega = math.sqrt(u)
        phase = math.atan2(-C * omega / D, 1 + (K - u) / D) % (2 * math.pi)
        for j in range(20):
            tau = (phase + 2 * math.pi * j) / omega
            if low < tau < high:
                lam = 1j * omega
                slope = -(D * lam * np.exp(-lam * tau)) / (
                    2 * lam + C + D * tau * np.exp(-lam * tau)
                )
                found.append((tau, omega, bool(slope.real > 0)))
    return sorted(found)


def test_every_crossing_of_the_delay_oscillator_is_found_with_its_direction():
    expected = _oscillator_crossings(0.2, 12.0)
    branches = follow_roots(_oscillator, np.linspace(0.2, 12.0, 40), count=3)
    found = sorted(
        (c.parameter, c.frequency, c.destabilizing)
        for branch in branches
        for c in branch_crossings(_oscillator, branch)
    )
    assert len(expected) == 8 and len(found) == len(expected)
    for (tau, omega, rising), (tau_f, omega_f, rising_f) in zip(expected, found, strict=True):
        assert tau_f == pytest.approx(tau, rel=1e-12)
        assert omega_f == pytest.approx(omega, rel=1e-12)
        assert rising_f == rising


def test_a_branch_is_a_continuous_path_of_roots():
    for branch in follow_roots(_oscillator, np.linspace(0.2, 6.0, 12), count=2):
        assert np.all(np.diff(branch.parameters) > 0)
        for tau, root in zip(branch.parameters, branch.roots, strict=True):
            assert _oscillator(tau).relative_residual(root) < 1e-8
            assert root.imag >= 0


def _axial_crossings(low, high):
    omega = math.sqrt(2 * BIT.blades * BIT.cutting_weight_per_depth / MASS)
    rpms = []
    for j in range(50):
        t_n = (2 * j + 1) * math.pi / omega
        rpm = 60.0 / (BIT.blades * t_n)
        if low < rpm < high:
            rpms.append(rpm)
    return sorted(rpms), omega


def test_the_axial_equation_crosses_at_its_closed_form_rpm_one_mode_after_another():
    def system_at(rpm):
        return axial_linearization(BIT, MASS, WOB, rpm)

    expected, omega = _axial_crossings(12.0, 200.0)
    grid = 1.0 / np.linspace(1 / 12.0, 1 / 200.0, 20)
    found = sorted(
        (c.parameter, c.frequency, c.destabilizing)
        for branch in follow_roots(system_at, grid, count=2)
        for c in branch_crossings(system_at, branch)
    )
    assert len(expected) == 6  # j = 0..5: 153.8, 51.3, 30.8, 22.0, 17.1, 14.0 rpm
    assert [rpm for rpm, _, _ in found] == pytest.approx(expected, rel=1e-9)
    assert [w for _, w, _ in found] == pytest.approx([omega] * len(expected), rel=1e-9)
    assert not any(rising for _, _, rising in found)  # each turns stable as the rpm grows


def _unstable_roots(assembly, rpm):
    system = drilling_linearization(assembly, BIT, WOB, rpm, None)
    roots = rightmost_roots(system, 1 << 30, order=2 * system.default_order()).roots
    return int(np.sum(roots.real > 0))


CHECKED_RPM = [21, 23, 25, 27, 30, 33, 36, 40, 45, 55, 60, 80, 100, 130, 150, 200, 299]


@pytest.mark.parametrize(
    "assembly",
    [rgd_two_dof_example(), damped_pipe("weight"), damped_pipe("speed")],
    ids=["two-dof", "chain-weight-hook", "chain-speed-hook"],
)
def test_the_signed_crossings_count_the_unstable_roots_at_every_rpm(assembly):
    found = each_mode_crossing(DrillingCase(assembly, BIT, WOB), (20.0, 300.0), points=15)
    assert found.complete
    crossings = found.crossings
    at_start = _unstable_roots(assembly, 20.0)
    for rpm in CHECKED_RPM:
        signed = sum(1 if c.destabilizing else -1 for c in crossings if c.rpm < rpm)
        assert at_start + signed == _unstable_roots(assembly, float(rpm)), rpm
    for crossing in crossings:  # λ = iω is a root there
        system = drilling_linearization(assembly, BIT, WOB, crossing.rpm, None)
        assert system.relative_residual(1j * crossing.frequency) < 1e-9
        assert 0 <= crossing.axial_share <= 1


@pytest.mark.parametrize("assembly", [rgd_two_dof_example(), damped_pipe("weight")])
def test_the_growth_rate_changes_sign_at_one_of_the_crossings(assembly):
    case = DrillingCase(assembly, BIT, WOB)
    each = each_mode_crossing(case, (20.0, 300.0), points=15).crossings
    for crossing in mode_crossings(case, (20.0, 300.0), points=15):
        [same] = [c for c in each if abs(c.rpm - crossing.rpm) < 1e-7 * crossing.rpm]
        assert same.frequency == pytest.approx(crossing.frequency, rel=1e-7)
        assert same.destabilizing == crossing.destabilizing


def test_bad_grids_and_counts_are_refused_by_name():
    with pytest.raises(ConfigError, match="grid"):
        follow_roots(_oscillator, [1.0, 0.5])
    with pytest.raises(ConfigError, match="count"):
        follow_roots(_oscillator, [0.5, 1.0], count=0)
    with pytest.raises(ConfigError, match="rpm"):
        each_mode_crossing(DrillingCase(rgd_two_dof_example(), BIT, WOB), (100.0, 50.0))


def test_with_contacts_the_crossings_and_their_directions_are_those_of_one_linearization():
    # the friction's damping enters every linearization of the search: the growth rate's
    # crossing (mode_crossings, its direction from the root just above) is one of every
    # mode's crossings with the same direction, and the report's unstable modes are the
    # linearization's with the contacts (the built-in deviated well at 60 rpm)
    from torsio.examples import rgd_deviated_well_config
    from torsio.report.axial import axial_section
    from torsio.report.context import ReportContext
    from torsio.well.axial_contacts import AxialContacts

    chain = damped_pipe("weight")
    contacts = AxialContacts(
        np.array([2e3, 3e3, 0.0]), np.array([1.5e3, 2.5e3, 0.0]), np.full(3, 0.0635)
    )
    case = DrillingCase(chain, BIT, WOB, contacts=contacts)
    each = each_mode_crossing(case, (60.0, 250.0), points=9)
    assert each.complete
    [growth] = mode_crossings(case, (60.0, 250.0), points=9)
    [same] = [c for c in each.crossings if abs(c.rpm - growth.rpm) < 1e-7 * growth.rpm]
    assert same.destabilizing == growth.destabilizing
    config = rgd_deviated_well_config()
    axial = config.axial
    section = axial_section(ReportContext(config))
    system = drilling_linearization(
        axial.stability_assembly, axial.bit, config.operation.wob, config.operation.rpm,
        None, axial.contacts,
    )  # fmt: skip
    without = drilling_linearization(
        axial.stability_assembly, axial.bit, config.operation.wob, config.operation.rpm
    )
    assert unstable_roots(system) != unstable_roots(without)  # the contacts make a difference
    assert section.data["stability"]["unstable_modes"] == unstable_roots(system)
