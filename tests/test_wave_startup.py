"""Start-ups on the wave model: a set speed that changes in time (docs/well.md, "Start-ups").

A controlled top drive's ``ramp = T`` raises its set speed linearly from 0 over T; a top may
also be held at a tabulated speed (a recorded top-drive speed). Every run is the built-in
deviated well (torsio.examples.deviated_well_config), wave strategy, bit off bottom.
"""

from __future__ import annotations

from typing import Any, ClassVar

import attrs
import numpy as np
import pytest

from torsio.analysis.wave import wave_response
from torsio.errors import ConfigError
from torsio.examples import deviated_well_config
from torsio.physics.damping import RayleighDamping
from torsio.physics.top_drive_boundary import TopDriveBoundary
from torsio.physics.top_drives import PITopDrive, SoftTorqueTopDrive
from torsio.well.break_off import break_off

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")

TABLE = np.array([[0.0, 2.0, 4.0, 6.0], [0.0, 3.0, 1.0, 2.0]])  # s, rad/s


@attrs.frozen
class TabledTop:
    """A top held at the speeds of ``TABLE`` (the top-drive contract: name, boundary)."""

    name: ClassVar[str] = "tabled"

    def boundary(self, system: Any) -> TopDriveBoundary:
        return TopDriveBoundary(inertia=0.0, set_speed=2.0, speed_table=TABLE)


def _system(top: Any, alpha: float = 0.0, rpm: float = 60.0, strategy: str = "wave"):
    system = deviated_well_config().system(strategy=strategy)
    system = attrs.evolve(system, damping=RayleighDamping(alpha=alpha))
    return system.with_top(top).at(wob=0.0, rpm=rpm)


def _run(system, duration: float, output_step: float | None = None):
    step = system.model.time_step if output_step is None else output_step
    return wave_response(
        system, duration=duration, steady_window=0.1 * duration, output_step=step, progress=False
    )


def test_a_held_top_turns_at_the_speeds_of_its_table():
    # reference: the table itself, linear between its points and constant beyond
    response = _run(_system(TabledTop()), 8.0)
    tr = response.transient
    expected = np.interp(tr.time, TABLE[0], TABLE[1])
    assert np.max(np.abs(tr.top_speed - expected)) < 1e-12
    assert tr.severity == pytest.approx(
        (tr.bit_speed[tr.window_mask].max() - tr.bit_speed[tr.window_mask].min()) / (2 * 2.0),
        rel=1e-9,
    )  # S_SS against the table's final speed


def test_a_ramped_pi_top_drive_balances_its_energy_and_ends_at_its_set_speed():
    # conservation law: motor work = stored + dissipated (bit drag, string drag, friction)
    # to the scheme's O(dt^2); PI integral action: no steady speed error once the string
    # slides (60 rpm, well above the threshold speed), so the window's mean top speed is
    # the set speed.
    top = PITopDrive(inertia=2900.0, kp=5000.0, ki=2900.0 * 0.8**2, ramp=10.0)
    response = _run(_system(top, alpha=0.35), 60.0, output_step=0.05)
    energy = response.energy
    assert abs(energy["residual"]) < 1e-5 * energy["work_in"]
    tr = response.transient
    assert tr.top_speed_mean == pytest.approx(2 * np.pi, rel=1e-3)
    assert tr.top_speed[tr.time <= 2.0].max() < 0.25 * 2 * np.pi  # still on the ramp at 2 s


def test_a_slow_ramped_start_up_breaks_the_bit_free_at_the_break_off_torque():
    # reference: break_off (int mu_s N r_o dx, int tau_s / (G J) dx), as the held top's
    # start-up in tests/test_wave_friction.py, here through a SoftTorque top drive whose
    # set speed ramps to 1 rpm over 20 s: the string is still stuck at the end of the ramp,
    # and the bit breaks free at the static torque of the string whatever drives the top.
    config = deviated_well_config()
    reference = break_off(config.well, config.string)
    top = SoftTorqueTopDrive(inertia=2900.0, ramp=20.0)
    system = _system(top, rpm=1.0)
    response = _run(system, 1.1 * reference.twist / system.omega + 20.0)
    tr = response.transient
    moved = int(np.flatnonzero(tr.bit_speed != 0.0)[0])
    angle = np.concatenate([[0.0], np.cumsum(0.5 * (tr.top_speed[1:] + tr.top_speed[:-1]))])
    angle *= system.model.time_step
    assert tr.surface_torque[moved - 1] == pytest.approx(reference.torque, rel=5e-3)
    assert angle[moved - 1] == pytest.approx(reference.twist, rel=5e-3)


@pytest.mark.parametrize("value", [-1.0, float("inf"), "ten"])
def test_a_bad_ramp_is_refused_by_key(value):
    with pytest.raises(ConfigError, match=r"top_drive\.ramp"):
        PITopDrive(inertia=2900.0, kp=5000.0, ki=1000.0, ramp=value)


def test_a_ramp_with_units_reads_as_seconds():
    assert PITopDrive(inertia=2900.0, kp=5000.0, ki=1000.0, ramp="1 min").ramp == 60.0
