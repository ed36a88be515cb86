"""The controller, S_SS, ω₁ and the run-time defaults: one definition read by every engine.

References: S_SS = (max Ω_b − min Ω_b) / (2 Ω) is Eq. 12 of the paper; ω₁ of one node on a
spring to a held top is √(k/I) (exact); the default run is 40 and the window 15 periods
2π/ω₁ (torsio.analysis.severity, the paper gives neither); the PI top drive's law
u = clip(kp e + ki ∫e) with back-calculation anti-windup, tracking gain 1/kp (Åström and
Hägglund 2006, as torsio.physics.top_drives states it).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsio.analysis.axial_transient import simulate_axial
from torsio.analysis.severity import (
    DEFAULT_DURATION_PERIODS,
    DEFAULT_WINDOW_PERIODS,
    run_times,
    severity_of_extremes,
)
from torsio.axial.rgd import rgd_example
from torsio.errors import ConfigError
from torsio.model.axial_assembly import rgd_two_dof_example
from torsio.physics.top_drive_boundary import TopDriveBoundary, controller_rates, motor_torque
from torsio.solvers import layouts as slot
from torsio.solvers.chain_kernel import compiled_controller_rates, compiled_motor_torque
from torsio.solvers.wave_top import top_arrays

# the RGD 2-DOF example (docs/axial.md): I = 455.65 kg m², k = 324.857 N m/rad
INERTIA, STIFFNESS = 455.65, 324.857


def test_s_ss_is_eq_12_for_floats_and_arrays():
    # Eq. 12 of the paper: half the bit speed's range over the surface speed
    assert severity_of_extremes(15.0, 5.0, 10.0) == 0.5
    values = severity_of_extremes(np.array([12.0, 20.0]), np.array([8.0, 0.0]), 10.0)
    assert values.tolist() == [0.2, 1.0]


def test_an_axial_run_reads_s_ss_with_eq_12_from_its_own_extremes():
    # Eq. 12 of the paper on the run's reported extremes, Ω the set speed of 60 rpm
    run = simulate_axial(rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=40.0)
    data = run.to_dict()
    omega = 60.0 * 2.0 * math.pi / 60.0
    expected = (data["bit_speed_max"] - data["bit_speed_min"]) / (2.0 * omega)
    assert run.severity == pytest.approx(expected, rel=1e-12)


def test_an_axial_assembly_has_the_first_frequency_and_run_times_of_every_model():
    # one node on a spring to the held top: ω₁ = √(k/I) exactly; the defaults 40 and 15
    # periods of it, the window at most half a given run (torsio.analysis.severity)
    assembly = rgd_two_dof_example()
    omega1 = math.sqrt(STIFFNESS / INERTIA)
    assert assembly.first_frequency() == pytest.approx(omega1, rel=1e-12)
    period = 2.0 * math.pi / omega1
    expected = (DEFAULT_DURATION_PERIODS * period, DEFAULT_WINDOW_PERIODS * period)
    assert run_times(assembly) == pytest.approx(expected, rel=1e-12)
    assert run_times(assembly, 60.0) == (60.0, 30.0)


@pytest.mark.parametrize(
    ("duration", "window", "key"),
    [(2.0, 3.0, "simulation.steady_window"), (-2.0, 1.0, "simulation.duration")],
)
def test_an_axial_run_checks_its_times_as_every_run(duration, window, key):
    # the axial engine checked 0 < window <= duration on its own and named the window for a
    # bad duration; the one check names the key that is wrong
    with pytest.raises(ConfigError) as info:
        simulate_axial(
            rgd_two_dof_example(), rgd_example(), 100e3, 60.0, duration=duration, window=window
        )
    assert info.value.key == key


KP, KI, LIMIT = 5000.0, 2000.0, 1.5e4  # N m s/rad, N m/rad, N m


def _pi(set_speed: float = 6.0, kp: float = KP) -> TopDriveBoundary:
    # the PI of torsio.physics.top_drives: z = ∫e, u_free = kp e + ki z, w = 1/kp
    return TopDriveBoundary(
        inertia=2900.0, set_speed=set_speed, a=np.zeros((1, 1)), b=np.array([[1.0, 0.0]]),
        c=np.array([KI]), d=np.array([kp, 0.0]), w=np.array([1.0 / kp]), max_torque=LIMIT,
    )  # fmt: skip


@pytest.mark.parametrize("evaluate", ["python", "compiled"])
def test_the_pi_law_with_back_calculation(evaluate):
    # Åström and Hägglund: u = clip(kp e + ki z, ±limit), z' = e + (u − u_free)/kp; the
    # compiled form (every kernel's) and the plain one (Dynamics, numpy engine) alike
    pi = _pi()
    torque, rates_of = (
        (motor_torque, controller_rates)
        if evaluate == "python"
        else (compiled_motor_torque, compiled_controller_rates)
    )
    for error, z in ((0.5, 2.0), (2.0, 5.0), (-4.0, -3.0)):
        state = np.array([z])
        u, free = torque(0.0, pi.kp, pi.pipe_gain, LIMIT, 1, pi.c, state, error, 100.0)
        expected_free = KP * error + KI * z
        assert free == pytest.approx(expected_free, rel=1e-15)
        assert u == pytest.approx(min(max(expected_free, -LIMIT), LIMIT), rel=1e-15)
        rates = np.zeros(1)
        rates_of(1, 1, np.ravel(pi.a), np.ravel(pi.b), pi.w, state, error, 100.0, u, free, rates)
        assert rates[0] == pytest.approx(error + (u - expected_free) / KP, rel=1e-14)


def test_the_plain_law_takes_arrays_of_points():
    # the numpy engine's call: every point at once equals each point alone (the same law)
    pi = _pi()
    errors, states = np.array([0.5, 2.0, -4.0]), np.array([[2.0, 5.0, -3.0]])
    u, free = motor_torque(0.0, pi.kp, 0.0, LIMIT, 1, pi.c, states, errors, 0.0)
    for k in range(3):
        alone = motor_torque(0.0, pi.kp, 0.0, LIMIT, 1, pi.c, states[:, k], errors[k], 0.0)
        assert (u[k], free[k]) == alone


def test_without_a_set_speed_the_wave_top_has_no_speed_error():
    # a controller with kp but no set speed (NaN): no speed error, as in the lumped kernels
    # (torsio.solvers.layouts: "Ω_set NaN: none, the speed error is then 0"); the wave top
    # added −kp Ω₀ before the one evaluation. Expected: u0 + kp·0 + ki z, T_pipe = m + Z Ω₀
    # with no pipe gain
    impedance, speed, z, incoming = 465.0, 3.0, 2.0, 1000.0
    gains = top_arrays(_pi(set_speed=math.nan), impedance, 1e-3, math.nan).coefficients
    u, _ = motor_torque(
        gains[slot.COEF_U0],
        gains[slot.COEF_KP],
        gains[slot.COEF_PIPE_GAIN],
        LIMIT,
        1,
        gains[slot.COEF_STATES :],
        [z],
        0.0 - speed,
        incoming + impedance * speed,
    )  # fmt: skip; as solvers/characteristics.py reads them (set speed 0 without one)
    assert u == pytest.approx(KI * z, rel=1e-15)
