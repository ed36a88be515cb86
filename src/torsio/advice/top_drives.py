"""The top drives the advisor compares: the configured one and the alternatives.

With the top drive's inertia J (the configured one's, else
:data:`torsio.physics.top_drives.TYPICAL_INERTIA`, 2900 kg m²) and ζ the top drill pipe's
impedance J_p √(G ρ) (:func:`torsio.physics.top_drive_boundary.top_pipe_impedance`), the
tunings of docs/top_drives.md:

* ``stiff PI``: ``pi`` with kp = 50 ζ, ki = 5 J (Simulator4nDOF's stiff speed loop);
* ``SoftTorque``: ``soft-torque`` with its defaults (kp = ζ, ki = ω₁² J);
* ``Z-Torque``: ``z-torque`` with its defaults (stiff PI gains, α = 0.25, 20 s high-pass);
* ``SoftTorque kp = k ζ``: the tuning of SoftTorque's damping gain k (the documented
  k_p of kp = k_p ζ; ki kept at ω₁² J) among :data:`SOFT_TORQUE_GAINS` that widens the
  safe window most: the most non-severe points on a 3 x 3 grid of the region.

Examples
--------
>>> round(safe_share([0.2, 0.9, 0.5, float("nan")], 0.8), 3)
0.5
"""

from __future__ import annotations

from typing import Any

import numpy as np

from torsio.errors import ConfigError

__all__ = ["SOFT_TORQUE_GAINS", "alternatives", "safe_share", "soft_torque_tunings"]

SOFT_TORQUE_GAINS = (0.5, 2.0, 4.0, 8.0)
"""The SoftTorque damping gains k (kp = k ζ) tried besides the default k = 1;
Simulator4nDOF's default is 4 (docs/top_drives.md, "Tuning rules")."""


def _inertia_and_impedance(config: Any) -> tuple[float, float]:
    from torsio.physics.axial_top_drive import AxialTopSystem
    from torsio.physics.top_drive_boundary import top_pipe_impedance
    from torsio.physics.top_drives import TYPICAL_INERTIA

    inertia = float(config.top_drive.parameters.get("inertia", TYPICAL_INERTIA))
    string = config.axial.string
    if string is None:
        raise ConfigError(
            "top_drive",
            "the top drives compared are tuned on the drill pipe's impedance; a [chain] has "
            "no drill pipe (give [[section]]s, or compare none: --no-compare)",
        )
    return inertia, top_pipe_impedance(AxialTopSystem(None, 0.0, string))


def alternatives(config: Any) -> dict[str, Any]:
    """The alternatives' top drives by label (module documentation)."""
    from torsio.physics.top_drives import PITopDrive, SoftTorqueTopDrive, ZTorqueTopDrive

    inertia, zeta = _inertia_and_impedance(config)
    return {
        "stiff PI": PITopDrive(inertia=inertia, kp=50.0 * zeta, ki=5.0 * inertia),
        "SoftTorque": SoftTorqueTopDrive(inertia=inertia),
        "Z-Torque": ZTorqueTopDrive(inertia=inertia),
    }


def soft_torque_tunings(config: Any) -> dict[str, Any]:
    """SoftTorque with kp = k ζ for each k of :data:`SOFT_TORQUE_GAINS`, by label."""
    from torsio.physics.top_drives import SoftTorqueTopDrive

    inertia, zeta = _inertia_and_impedance(config)
    return {
        f"SoftTorque kp = {k:g} zeta": SoftTorqueTopDrive(inertia=inertia, kp=k * zeta)
        for k in SOFT_TORQUE_GAINS
    }


def safe_share(severity: Any, threshold: float) -> float:
    """The share of the points run that are not severe (S_SS at most ``threshold``; a failed
    run, NaN, counts as severe): how wide a top drive's safe window is on a map."""
    values = np.asarray(severity, dtype=float)
    return float(np.mean(np.isfinite(values) & (values <= threshold)))
