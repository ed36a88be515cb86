"""Recordings of start-ups made by the wave model, for the fits' tests (docs/calibration.md)."""

from __future__ import annotations

from typing import Any

from torsio.analysis.wave import wave_response
from torsio.calibration.recording import Recording
from torsio.physics.top_drives import SoftTorqueTopDrive


def soft_torque_top() -> SoftTorqueTopDrive:
    """The recordings' top drive: SoftTorque, J = 2900 kg m^2, set speed ramped over 5 s."""
    return SoftTorqueTopDrive(inertia=2900.0, ramp=5.0)


def wave_startup(
    system: Any, rpm: float, duration: float, seed: int, name: str, noise: tuple[float, float]
) -> Recording:
    """A start-up off bottom of ``system`` (its wave grid) by :func:`soft_torque_top` to
    ``rpm``, ``duration`` s sampled every 0.01 s, recorded with ``noise`` (relative, on the
    torque and on the speed) drawn from ``seed``."""
    run = wave_response(
        system.with_top(soft_torque_top()).at(wob=0.0, rpm=rpm),
        duration=duration,
        steady_window=0.1 * duration,
        output_step=0.01,
        progress=False,
    ).transient
    torque_noise, speed_noise = noise
    return Recording.from_transient(
        run, torque_noise=torque_noise, speed_noise=speed_noise, seed=seed, name=name
    )
