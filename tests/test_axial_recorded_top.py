"""A set speed that changes in time on the axial engine: a top that follows a recording.

The held top of the axial chain turns at the one set-speed table of every engine
(:mod:`torsio.solvers.set_speed`): a recording's speed, linear between its samples, and
through its integral. Numbers checked: a recording at the constant Ω₀ is the held top's
run, bit for bit (the same boundary); a start-up that follows a recorded ramp samples the
recorded speed at the top (the boundary itself) and closes its energy balance
(conservation of energy, the top's work at the recorded speed); Tucker-Wang on the RGD
2-DOF chain through the axial engine against the same chain through the torsional engine
(RODAS4, an independent engine) under the same recording, S_SS within 1e-3 as the held
top's comparison in tests/test_axial_torque_law.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_axial_torque_law import TUCKER_WANG, _table

from torsio.analysis.axial_maps import axial_map
from torsio.analysis.transient import simulate
from torsio.axial import rgd_two_dof_example, simulate_axial
from torsio.axial.rgd import rgd_example
from torsio.calibration.recording import Recording
from torsio.config.reading import parse_config
from torsio.errors import ConfigError
from torsio.examples import rgd_wave_pipe_config
from torsio.physics.recorded_top import RecordedTopDrive
from torsio.physics.top_drives import PITopDrive, SoftTorqueTopDrive
from torsio.solvers.axial_run_setup import BitRotation
from torsio.solvers.set_speed import table_speed
from torsio.units import RPM_TO_RAD_S

WOB, RPM = 100e3, 60.0
OMEGA = RPM * RPM_TO_RAD_S


def _recording(times, speeds):
    return Recording(
        time=times, top_speed=speeds, surface_torque=np.zeros(len(times)), name="rig.csv"
    )


RAMP = RecordedTopDrive(recording=_recording([0.0, 10.0, 400.0], [0.0, OMEGA, OMEGA]))


def test_a_constant_recording_is_the_held_top_bit_for_bit():
    steady = RecordedTopDrive(recording=_recording([0.0, 400.0], [OMEGA, OMEGA]))
    args = (rgd_two_dof_example(), rgd_example(), WOB, RPM)
    held = simulate_axial(*args, duration=20.0, window=5.0, growth_rate=False)
    recorded = simulate_axial(*args, duration=20.0, window=5.0, growth_rate=False,
                              top_drive=steady)  # fmt: skip
    np.testing.assert_array_equal(recorded.axial.samples, held.axial.samples)
    assert recorded.severity == held.severity
    assert recorded.axial.energy == held.axial.energy


def test_a_start_up_follows_the_recorded_speed_and_closes_its_energy_balance():
    run = simulate_axial(rgd_two_dof_example(), rgd_example(), WOB, RPM, duration=30.0,
                         window=10.0, growth_rate=False, top_drive=RAMP)  # fmt: skip
    table = RAMP.boundary(None).set_speed_table()
    expected = [table_speed(table, t) for t in run.time]
    np.testing.assert_array_equal(run.top_speed, expected)  # the boundary, at the top
    assert run.top_speed[0] == 0.0 and not run.has_set_speed
    # S_SS against the last recorded speed; rpm the mean top speed, as on a torsional run
    # (the record holds Ω₀ over the whole window: their mean is Ω₀ to round-off)
    assert run.severity_speed == OMEGA and run.rpm_source == "top_speed_mean"
    assert run.rpm == pytest.approx(RPM, rel=1e-12)
    # the first-order scheme's O(h) residual: measured 1.2e-4 (the held top's default run
    # 1.6e-4, docs/axial.md), under the engine's own warning level 1e-2
    assert run.axial.energy.relative_residual < 1e-3
    assert run.to_dict()["top_drive"] == "recorded"


def test_tucker_wang_under_a_recording_is_the_torsional_engines_run():
    axial = parse_config(_table(TUCKER_WANG)).axial
    torsional = parse_config(_table(TUCKER_WANG, masses=False)).system().at(wob=WOB, rpm=RPM)
    times = {"duration": 150.0}
    reference = simulate(torsional.with_top(RAMP), steady_window=50.0, **times)
    run = simulate_axial(axial.assembly, axial.bit, WOB, RPM, window=50.0, top_drive=RAMP,
                         **times)  # fmt: skip
    assert reference.severity > 1.0  # stick-slip after the start-up
    assert run.severity == pytest.approx(reference.severity, rel=1e-3)
    # measured 1.3e-6 (5.2e-7 with the top held at Ω₀); the bound of the held top's
    # Tucker-Wang run in tests/test_axial_torque_law.py
    assert run.axial.energy.relative_residual < 1e-5


def test_a_recording_sets_the_runs_speed_and_says_so():
    args = (rgd_two_dof_example(), rgd_example(), WOB, 90.0)
    run = simulate_axial(*args, duration=20.0, window=5.0, growth_rate=False, top_drive=RAMP)
    assert run.severity_speed == OMEGA  # the last recorded speed, not the 90 rpm given
    assert any("not at the 90 rpm given" in text for text in run.warnings)
    stopped = RecordedTopDrive(recording=_recording([0.0, 10.0, 400.0], [0.0, OMEGA, 0.0]))
    with pytest.raises(ConfigError, match="ends at 0 rpm") as info:
        simulate_axial(*args, top_drive=stopped)
    assert info.value.key == "top_drive.recording"


def test_what_a_recording_cannot_drive_is_refused_by_key():
    args = (rgd_two_dof_example(), rgd_example(), WOB, RPM)
    with pytest.raises(ConfigError) as info:
        simulate_axial(*args, top_drive=RAMP, start="steady")
    assert info.value.key == "simulation.start"
    with pytest.raises(ConfigError) as info:
        simulate_axial(*args, top_drive=RAMP, bit_rotation=BitRotation(0.1, 2.0))
    assert info.value.key == "top_drive"
    with pytest.raises(ConfigError, match="follows a table of speeds") as info:
        axial_map(rgd_two_dof_example(), rgd_example(), [WOB], [RPM], top_drive=RAMP)
    assert info.value.key == "top_drive.kind"


def test_the_distributed_pipe_follows_a_recording_too():
    pipe = rgd_wave_pipe_config().axial.assembly
    args = (pipe, rgd_example(), WOB, RPM)
    steady = RecordedTopDrive(recording=_recording([0.0, 400.0], [OMEGA, OMEGA]))
    held = simulate_axial(*args, duration=5.0, window=2.0, growth_rate=False)
    recorded = simulate_axial(*args, duration=5.0, window=2.0, growth_rate=False,
                              top_drive=steady)  # fmt: skip
    np.testing.assert_array_equal(recorded.axial.samples, held.axial.samples)
    run = simulate_axial(*args, duration=5.0, window=2.0, growth_rate=False, top_drive=RAMP)
    # d'Alembert: until the first reflection returns from the junction 900 m down (2 L / c),
    # the top of the drill pipe sends a torque wave Z_t Ω_top(t) down the pipe
    first = pipe.sections[0]
    g, rho = first.material.shear_modulus, first.material.density
    impedance = first.polar_moment * math.sqrt(g * rho)
    echo = 2 * first.length / math.sqrt(g / rho)
    early = (run.time > 0.0) & (run.time < 0.9 * echo)
    assert early.sum() > 50
    np.testing.assert_allclose(
        run.surface_torque[early], impedance * run.top_speed[early], rtol=1e-12
    )


def test_the_distributed_pipe_refuses_a_controller_and_a_map_of_a_recording_by_key():
    pipe = rgd_wave_pipe_config().axial.assembly
    pi = PITopDrive(inertia=2900.0, kp=5000.0, ki=2067.6)
    for top in (pi, SoftTorqueTopDrive(inertia=930.0)):  # whatever its tuning would read
        with pytest.raises(
            ConfigError, match=f"'{top.name}' given with the distributed pipe"
        ) as info:
            simulate_axial(pipe, rgd_example(), WOB, RPM, top_drive=top)
        assert info.value.key == "top_drive"
    with pytest.raises(ConfigError, match="follows a table of speeds") as info:
        axial_map(pipe, rgd_example(), [WOB], [RPM], top_drive=RAMP)
    assert info.value.key == "top_drive.kind"
