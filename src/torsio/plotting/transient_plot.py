"""The plot of a transient run, whatever model and engine made it.

:func:`plot_transient` draws the bit speed (and the top drive's), the surface torque (and
the motor torque) and the torque on bit against time, the steady window shaded, from the
signals a run's results give by name: ``time``, ``bit_speed``, ``top_speed``,
``surface_torque``, ``motor_torque``, ``bit_torque``, and ``window_start``, ``duration``,
``omega``, ``severity``, ``has_top_drive_node``, ``dimensionless``, ``plot_label``.
Needs matplotlib (the ``[plot]`` extra).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from torsio.errors import ConfigError
from torsio.output_files import save_figure_file
from torsio.units import RPM_TO_RAD_S

__all__ = ["plot_transient"]


def plot_transient(results: Any, path: str | Path | None = None, ax: Any = None) -> Any:
    """Bit speed, surface torque and torque on bit of ``results`` against time.

    With a top drive that has inertia the top-drive speed and the motor torque are drawn
    too. ``path`` writes the figure (PNG by extension); ``ax`` (three matplotlib axes:
    speeds, surface torque, torque on bit) draws into existing ones. Returns the figure.

    Raises
    ------
    ImportError
        If matplotlib is not installed (``pip install 'torsio[plot]'``).
    """
    try:
        from matplotlib.figure import Figure
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(
            "plotting needs matplotlib, which is not installed: pip install 'torsio[plot]'"
        ) from exc
    axes = ax
    if axes is not None:
        if len(axes) != 3:
            raise ConfigError("ax", f"expected three matplotlib axes, got {len(axes)}")
        fig = axes[0].figure
    elif path is not None:  # no pyplot: no GUI backend, nothing left open
        fig = Figure(figsize=(8.0, 7.0))
        axes = fig.subplots(3, 1, sharex=True)
    else:
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8.0, 7.0))
    plain = results.dimensionless
    speed_unit, scale = ("-", 1.0) if plain else ("rpm", 1.0 / RPM_TO_RAD_S)
    torque_unit, torque_scale = ("-", 1.0) if plain else ("kN m", 1e-3)
    time = results.time
    axes[0].plot(time, results.bit_speed * scale, lw=0.8, label="bit")
    top_speed = np.asarray(results.top_speed, dtype=float)
    if results.has_top_drive_node or (top_speed.size and np.ptp(top_speed) > 0.0):  # recorded
        label = "top drive" if results.has_top_drive_node else "top"
        axes[0].plot(time, top_speed * scale, lw=0.8, color="k", label=label)
        axes[0].set_ylabel(f"speed [{speed_unit}]")
    else:
        axes[0].axhline(results.omega * scale, color="k", lw=0.6, ls="--", label="top")
        axes[0].set_ylabel(f"bit speed [{speed_unit}]")
    axes[0].legend(loc="upper right", fontsize="small")
    axes[1].plot(time, results.surface_torque * torque_scale, lw=0.8, color="C1", label="pipe")
    if results.has_top_drive_node:
        motor = results.motor_torque * torque_scale
        axes[1].plot(time, motor, lw=0.8, color="C4", label="motor")
        axes[1].legend(loc="upper right", fontsize="small")
    axes[1].set_ylabel(f"surface torque [{torque_unit}]")
    axes[2].plot(time, results.bit_torque * torque_scale, lw=0.8, color="C2")
    axes[2].set_ylabel(f"torque on bit [{torque_unit}]")
    axes[2].set_xlabel("tau = omega_1 t [-]" if plain else "time [s]")
    for one in axes:
        one.axvspan(results.window_start, results.duration, color="0.9", zorder=0)
        one.grid(True, lw=0.3)
    title = f"{results.plot_label}: S_SS = {results.severity:.3f} (steady window shaded)"
    axes[0].set_title(title)
    fig.tight_layout()
    if path is not None:
        save_figure_file(fig, path, dpi=120)  # whole or not at all (OutputError)
    return fig
