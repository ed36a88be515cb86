"""Coulomb contacts along the string on the numpy batch engine (torsio.solvers.numpy_contacts):
against scipy between the contacts' switches (torsio.solvers.contact_events) on the built-in
deviated well, and against the closed form of a one-node stick-slip oscillator."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio.analysis.transient import simulate
from torsio.examples import deviated_well_config
from torsio.solvers import layouts as slot
from torsio.solvers.batch import simulate_batch
from torsio.solvers.batch_results import STATUS_CHATTER, STATUS_MESSAGES
from torsio.solvers.lumped_inputs import run_settings
from torsio.solvers.numpy_engine import integrate_numpy

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

RTOL, ATOL = 1e-6, 1e-9  # torsio simulate's defaults, for both engines


class _NoBit:
    """A bit off bottom: no torque at any speed."""

    def torque(self, speed, wob, radius):
        return np.zeros_like(np.asarray(speed, dtype=float))

    def slope(self, speed, wob, radius):
        return np.zeros_like(np.asarray(speed, dtype=float))


def _oscillator(inertia, stiffness, static, dynamic, t_end, window, first_frequency):
    """One node on a spring from the held top, with a contact (no threshold speed)."""
    chain = np.zeros((slot.CHAIN_ROWS, 1))
    chain[slot.CHAIN_MASS] = inertia
    chain[slot.CHAIN_STIFFNESS] = stiffness
    chain[slot.CHAIN_CONTACT_STATIC] = static
    chain[slot.CHAIN_CONTACT_DYNAMIC] = dynamic
    chain[slot.CHAIN_CONTACT_THRESHOLD] = 0.0
    settings = run_settings(
        t_end, window, 1e-8, 1e-11, (1e-3, 0.1), 10**6, 0.1, 0.0, first_frequency
    )
    return chain, np.zeros(slot.TOP_SIZE), settings


def test_stick_slip_oscillator_reaches_the_closed_form_speed():
    # closed form: stuck, the spring's torque k (Omega t - theta) rises to C_s; sliding
    # (I theta'' = k (Omega t - theta) - C_d) it sticks again at 2 C_d - C_s, and the next
    # slip starts once the torque is back at C_s: every slip peaks at
    # Omega + sqrt(Omega^2 + (C_s - C_d)^2 / (k I)), and the node is at rest in between
    inertia, stiffness, static, dynamic = 10.0, 1000.0, 500.0, 300.0
    omega = np.array([1.0, 2.0, 4.0])
    chain, top, settings = _oscillator(
        inertia, stiffness, static, dynamic, 20.0, 10.0, math.sqrt(stiffness / inertia)
    )
    out = integrate_numpy(chain, top, _NoBit(), settings, np.zeros(3), omega, omega)
    assert np.all(out[:, slot.OUT_STATUS] == 0)
    peak = omega + np.sqrt(omega**2 + (static - dynamic) ** 2 / (stiffness * inertia))
    # measured: within 1e-8 rad/s of it (rtol 1e-8)
    assert out[:, slot.OUT_BIT_SPEED_MAX] == pytest.approx(peak, rel=1e-7)
    # at rest: to the switches' tolerance, 1e-9 (1 + Omega) rad/s (the step that ends on
    # the switch ends just past 0; the stuck node is then held at exactly 0)
    assert np.all(np.abs(out[:, slot.OUT_BIT_SPEED_MIN]) <= 1e-9 * (1.0 + omega))


def test_a_node_held_by_its_static_capacity_never_moves():
    # closed form: the spring's torque k Omega t stays below C_s over the run, so the
    # node is stuck throughout: its speed exactly 0
    chain, top, settings = _oscillator(10.0, 1000.0, 5000.0, 3000.0, 2.0, 1.0, 10.0)
    omega = np.array([1.0])
    out = integrate_numpy(chain, top, _NoBit(), settings, np.zeros(1), omega, omega)
    assert out[0, slot.OUT_STATUS] == 0
    assert out[0, slot.OUT_BIT_SPEED_MAX] == 0.0
    assert out[0, slot.OUT_BIT_SPEED_MIN] == 0.0


def test_a_point_that_switches_too_often_says_so():
    # the limit (numpy_contacts.MAX_SWITCHES_PER_PERIOD = 50 per contact and first natural
    # period, plus 50): with omega_1 given as ~0 it is 50 switches, which the oscillator
    # (two per stick-slip cycle, a cycle about 0.9 s at 1 rad/s) exceeds within 60 s
    chain, top, settings = _oscillator(10.0, 1000.0, 500.0, 300.0, 60.0, 10.0, 1e-12)
    omega = np.array([1.0])
    out = integrate_numpy(chain, top, _NoBit(), settings, np.zeros(1), omega, omega)
    assert out[0, slot.OUT_STATUS] == STATUS_CHATTER
    assert "chatter" in STATUS_MESSAGES[STATUS_CHATTER]


def test_deviated_well_agrees_with_scipy_between_switches():
    # reference: torsio simulate with contacts (LSODA between located switches, S_SS from
    # output samples every 1 ms), rtol 1e-6 for both. Measured |dS_SS| 1.3e-4 at most over
    # these points; at rtol 1e-8 the two agree to 6e-6, the numpy engine's S_SS moving by
    # 1e-5 from rtol 1e-6 to 1e-8 and scipy's by 1.2e-4: the difference is scipy's
    # tolerance, so the bound is 4 times the measured difference
    system = deviated_well_config().system(strategy="B", dp_elements=4, bha_elements=2)
    points = [(0.0, 60.0), (40e3, 60.0), (120e3, 40.0)]
    wob, rpm = np.array(points).T
    batch = simulate_batch(
        system, wob=wob, rpm=rpm, engine="numpy", duration=10.0, steady_window=5.0,
        steady_tolerance=0.0, rtol=RTOL, atol=ATOL,
    )  # fmt: skip
    assert batch.engine == "numpy"
    assert np.all(batch.status == 0)
    for k, (w, r) in enumerate(points):
        single = simulate(system.at(wob=w, rpm=r), duration=10.0, steady_window=5.0,
                          output_step=1e-3, rtol=RTOL, atol=ATOL, method="LSODA",
                          progress=False)  # fmt: skip
        assert single.solver["engine"] == "scipy"
        assert single.solver["contact_switches"] > 0
        assert batch.severity[k] == pytest.approx(single.severity, abs=5e-4)
