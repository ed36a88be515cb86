"""The torque-driven 4-DOF drill-string of Navarro-López and Cortés (2007), in a [chain] TOML.

Source: Navarro-López and Cortés (2007), "Sliding-mode control of a multi-DOF oilwell
drillstring with stick-slip oscillations", American Control Conference, 3837-3842: rotary
table J_r = 930 kg m^2 with drag c_r = 425 N m s/rad driven by u = 10 kN m, pipe inertias
2782.25 and 750 kg m^2, BHA 471.9698 kg m^2, springs 698.063, 1080, 907.48 N m/rad, dampers
139.6126, 190, 181.49 N m s/rad, bit drag c_b = 50 N m s/rad, bit radius 0.155575 m, bit
friction W R [mu_cb + (mu_sb - mu_cb) exp(-gamma_b |w| / v_f)] sign(w) with mu_sb = 0.8,
mu_cb = 0.5, gamma_b = 0.9, v_f = 1 rad/s; stick-slip at W_ob = 97,347 N, steady rotation at
50 kN at the speed of the torque balance. The sign is smoothed as tanh(w / 0.01 rad/s) (the
bundled ``coulomb-stribeck`` law). Every number is written out again below, independently of
the data file, and the reference runs are integrated here with scipy's Radau.
"""

from __future__ import annotations

import math
from importlib import resources

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from torsio.analysis.transient import simulate_config
from torsio.config.reading import parse_config_text

pytest.importorskip("torsio_friction_laws")

TABLE_INERTIA, TABLE_DRAG, MOTOR_TORQUE = 930.0, 425.0, 10.0e3
INERTIAS = np.array([2782.25, 750.0, 471.9698])
SPRINGS = np.array([698.063, 1080.0, 907.48])
DAMPERS = np.array([139.6126, 190.0, 181.49])
BIT_DRAG, BIT_RADIUS = 50.0, 0.155575
MU_STATIC, MU_COULOMB, GAMMA, V_F, SMOOTHING = 0.8, 0.5, 0.9, 1.0, 0.01
STICK_SLIP_WOB, STEADY_WOB = 97347.0, 50.0e3


def config(wob: float):
    text = resources.files("torsio").joinpath("data/navarro_lopez_cortes_2007.toml")
    data = text.read_text(encoding="utf-8").replace("wob = 97347.0", f"wob = {wob!r}")
    return parse_config_text(data, source="navarro_lopez_cortes_2007.toml")


def friction(speed, wob):
    mu = MU_COULOMB + (MU_STATIC - MU_COULOMB) * np.exp(-GAMMA * np.abs(speed) / V_F)
    return wob * BIT_RADIUS * mu * np.tanh(speed / SMOOTHING)


def balance_speed(wob: float) -> float:
    """The speed of steady rotation: u = (c_r + c_b) W + W_ob R mu(W), on the falling branch."""

    def residual(speed: float) -> float:
        return MOTOR_TORQUE - (TABLE_DRAG + BIT_DRAG) * speed - float(friction(speed, wob))

    return brentq(residual, 5.0, 30.0, xtol=1e-12)


def friction_slope(speed, wob):
    """d friction / d speed, analytic."""
    decay = (MU_STATIC - MU_COULOMB) * np.exp(-GAMMA * np.abs(speed) / V_F)
    smooth_sign = np.tanh(speed / SMOOTHING)
    d_mu = -decay * GAMMA / V_F * np.abs(smooth_sign)
    return wob * BIT_RADIUS * (d_mu + (MU_COULOMB + decay) * (1 - smooth_sign**2) / SMOOTHING)


def reference_run(wob: float, duration: float, times: np.ndarray):
    """The 4-DOF equations in absolute speeds and spring twists, from rest (Radau).

    State: the twists theta_i - theta_(i+1) of the three springs, then the speeds of the
    table, the two pipe inertias and the bit.
    """
    inertias = np.concatenate([[TABLE_INERTIA], INERTIAS])
    linear = np.zeros((7, 7))
    for joint in range(3):  # twist rate = speed above - speed below
        linear[joint, 3 + joint], linear[joint, 4 + joint] = 1.0, -1.0
        for node, sign in ((joint, -1.0), (joint + 1, 1.0)):  # joint torque on its two nodes
            linear[3 + node, joint] += sign * SPRINGS[joint] / inertias[node]
            linear[3 + node, 3 + joint] += sign * DAMPERS[joint] / inertias[node]
            linear[3 + node, 4 + joint] -= sign * DAMPERS[joint] / inertias[node]
    linear[3, 3] -= TABLE_DRAG / TABLE_INERTIA
    linear[6, 6] -= BIT_DRAG / inertias[3]
    forcing = np.zeros(7)
    forcing[3] = MOTOR_TORQUE / TABLE_INERTIA

    def rhs(t, y):
        dy = linear @ y + forcing
        dy[6] -= friction(y[6], wob) / inertias[3]
        return dy

    def jacobian(t, y):
        jac = linear.copy()
        jac[6, 6] -= friction_slope(y[6], wob) / inertias[3]
        return jac

    solution = solve_ivp(
        rhs,
        (0.0, duration),
        np.zeros(7),
        method="Radau",
        jac=jacobian,
        rtol=1e-7,  # bit-speed extremes agree with rtol = atol = 1e-9 to 2e-8 (checked once)
        atol=1e-7,
        t_eval=times,
    )
    assert solution.success, solution.message
    return solution.y[3], solution.y[6]  # table speed, bit speed


def test_torque_balance_gives_the_published_steady_speed():
    # Navarro-López and Cortés (2007): 12.864 rad/s at 50 kN.
    assert round(balance_speed(STEADY_WOB), 3) == 12.864


def test_steady_rotation_at_50_kN_at_the_balance_speed():
    results = simulate_config(config(STEADY_WOB), duration=300.0, steady_window=50.0)
    window = results.window_mask
    expected = balance_speed(STEADY_WOB)  # the torque balance, solved above
    assert results.bit_speed[window] == pytest.approx(expected, rel=1e-3)
    assert results.top_speed_mean == pytest.approx(expected, rel=1e-3)
    assert results.stick_fraction == 0.0


def test_stick_slip_at_97347_N_matches_an_independent_integration():
    results = simulate_config(config(STICK_SLIP_WOB), duration=100.0, steady_window=30.0)
    window = results.window_mask
    bit = results.bit_speed[window]
    assert results.stick_fraction > 0.1 and bit.max() > 2 * results.top_speed_mean  # stick-slip
    table_ref, bit_ref = reference_run(STICK_SLIP_WOB, results.duration, results.time)
    # Extremes within 1 % of the peak bit speed, mean table speed within 3 %.
    peak = bit_ref[window].max()
    assert abs(bit.max() - peak) <= 0.01 * peak
    assert abs(bit.min() - bit_ref[window].min()) <= 0.01 * peak
    assert results.top_speed_mean == pytest.approx(table_ref[window].mean(), rel=0.03)
    assert math.isfinite(results.severity)
