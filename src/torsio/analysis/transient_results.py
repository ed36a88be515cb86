"""Results of a transient run: the sampled response, S_SS, JSON, CSV and the plot.

Returned by :func:`torsio.analysis.transient.simulate`; a results object never
recomputes the analysis.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import attrs
import numpy as np

from torsio.analysis.severity import SEVERE_THRESHOLD
from torsio.errors import ConfigError
from torsio.output_files import atomic_output, save_figure_file
from torsio.physics.system import System
from torsio.units import RPM_TO_RAD_S

__all__ = ["TransientResults", "window_mask"]


@attrs.frozen(eq=False)
class TransientResults:
    """The sampled transient response of a System (returned by :func:`simulate`).

    Attributes
    ----------
    time : ndarray, shape (m,)
        Sample times [s] (uniform grid from 0 to the run length).
    bit_speed : ndarray, shape (m,)
        Absolute bit speed theta_N' [rad/s].
    bit_angle : ndarray, shape (m,)
        Absolute bit angle theta_N [rad].
    node_speeds : ndarray, shape (m, dofs)
        Absolute speed of every degree of freedom [rad/s] (the last is the bit).
    node_twists : ndarray, shape (m, dofs)
        Twist phi = theta - Omega_ref t of every degree of freedom [rad]: for a
        held top its angle relative to the top drive (negative: lagging behind).
    bit_torque : ndarray, shape (m,)
        Torque on bit T_bit from the bit-rock law [N m].
    surface_torque : ndarray, shape (m,)
        Torque the top drive applies to the string, T_pipe [N m]:
        ``k1 (theta_0 - theta_1) + c1 (theta_0' - theta_1')`` for a chain (theta_0 the
        top drive), for a held top in general ``-k_t . phi - c_t . v``.
    severity : float
        S_SS (Eq. 12) over the steady window.
    stick_fraction : float
        Fraction of the steady window during which ``|bit speed| < stick_threshold Omega``.
    steady_window : float
        Length of the steady-state window at the end of the run [s].
    stick_threshold : float
        Stick threshold as a fraction of Omega.
    solver : dict
        ``method``, ``rtol``, ``atol``, ``nfev``, ``njev``, ``nlu``, ``status``,
        ``message``, ``wall_time_s``.
    system : System
        The system that was integrated.
    top_speed : ndarray, shape (m,)
        Top-drive speed Omega_0 [rad/s] (constant for a held top).
    motor_torque : ndarray, shape (m,)
        Motor torque u of the top drive [N m] (for a held top: the surface torque).
    states : ndarray, shape (m, size)
        The integrated state ``[z, phi_0, v_0, ...]`` of
        :class:`torsio.physics.dynamics.Dynamics` at each sample.
    reference_speed : float
        Omega_ref [rad/s] of the twist coordinates.
    severity_speed : float
        Omega [rad/s] that S_SS divides by: the set speed, or the mean top-drive
        speed over the steady window for a torque-driven top.
    bit_speed_extremes : tuple of float or None
        (max, min) of the bit speed over the steady window [rad/s] from the integrator's
        continuous solution (the compiled engine: the cubic interpolant of every step,
        as severity maps read them), which S_SS is read from; None: S_SS and the
        extremes are those of the samples.
    warnings : tuple of str
        What limits the meaning of the result (:mod:`torsio.analysis.limits`): e.g. a
        bit stuck throughout the window, a window shorter than a period; empty if none.
    well_summary : dict or None
        With friction along the string (a ``[well]``): ``surface_torque_min``,
        ``surface_torque_max`` (steady window), ``surface_torque_peak`` (whole run) [N m],
        ``bit_first_motion`` [s] (first time the bit is faster than the threshold speed;
        None if never), ``friction_work`` [J], ``threshold_speed`` [rad/s], ``contacts``;
        merged into :meth:`to_dict`. None without a well.
    """

    time: np.ndarray
    bit_speed: np.ndarray
    bit_angle: np.ndarray
    node_speeds: np.ndarray
    node_twists: np.ndarray
    bit_torque: np.ndarray
    surface_torque: np.ndarray
    severity: float
    stick_fraction: float
    steady_window: float
    stick_threshold: float
    solver: dict[str, Any]
    system: System
    top_speed: np.ndarray
    motor_torque: np.ndarray
    states: np.ndarray
    reference_speed: float
    severity_speed: float
    bit_speed_extremes: tuple[float, float] | None = None
    warnings: tuple[str, ...] = ()
    well_summary: dict[str, Any] | None = None

    def __repr__(self) -> str:  # short: no time series
        return (
            f"TransientResults({self.time.size} samples over {self.time[-1]:g} s, "
            f"S_SS {self.severity:.4g} over the last {self.steady_window:g} s, "
            f"{self.solver.get('method')} rtol {self.solver.get('rtol')}; {self.system!r})"
        )

    # --- derived views (no recomputation of the analysis) ---------------------------------
    @property
    def _extremes(self) -> tuple[float, float]:
        """(max, min) of the bit speed over the window that S_SS is read from [rad/s]."""
        if self.bit_speed_extremes is not None:
            return self.bit_speed_extremes
        speeds = self.bit_speed[self.window_mask]
        return float(speeds.max()), float(speeds.min())

    @property
    def omega(self) -> float:
        """Omega [rad/s] of S_SS (for a dimensionless system: Pi_1); see ``severity_speed``."""
        return self.severity_speed

    @property
    def has_top_drive_node(self) -> bool:
        """Whether the top drive has inertia (its speed and motor torque vary)."""
        return bool(getattr(self.system.top, "name", "") != "constant-speed")

    @property
    def has_set_speed(self) -> bool:
        """Whether the top drive turns at a set speed (False for a torque-driven top, and
        for a top that follows a recording: its speed is the record's)."""
        if getattr(self.system.top, "name", "") == "recorded":
            return False
        return bool(np.isfinite(self.system.top.boundary(self.system).set_speed))

    @property
    def rpm(self) -> float:
        """The rotary speed the run had [rpm]: the set speed, or for a top drive without
        one (``torque``) the mean top-drive speed over the steady window."""
        if self.has_set_speed:
            return float(self.system.rpm)
        return self.top_speed_mean / RPM_TO_RAD_S

    @property
    def top_speed_mean(self) -> float:
        """Mean top-drive speed over the steady window [rad/s]."""
        return float(self.top_speed[self.window_mask].mean())

    @property
    def duration(self) -> float:
        """Run length [s]."""
        return float(self.time[-1])

    @property
    def output_step(self) -> float:
        """Sampling step of the output grid [s]."""
        return float(self.time[1] - self.time[0])

    @property
    def window_start(self) -> float:
        """Start of the steady-state window [s]."""
        return self.duration - self.steady_window

    @property
    def window_mask(self) -> np.ndarray:
        """Boolean mask of the samples in the steady-state window."""
        return window_mask(self.time, self.steady_window)

    @property
    def node_angles(self) -> np.ndarray:
        """Absolute angle of every degree of freedom [rad], shape (m, dofs)."""
        return self.node_twists + self.reference_speed * self.time[:, None]

    @property
    def bit_twist(self) -> np.ndarray:
        """Twist of the bit, theta_N - Omega_ref t [rad]."""
        return self.node_twists[:, -1]

    @property
    def severe(self) -> bool:
        """Whether S_SS exceeds the paper's 0.8 threshold."""
        return bool(self.severity > SEVERE_THRESHOLD)

    @property
    def dimensionless(self) -> bool:
        """Whether the system is a dimensionless one (time is tau = omega_1 t)."""
        return bool(getattr(self.system.law, "dimensionless", False))

    # --- output ---------------------------------------------------------------------------
    def to_dict(self, series: bool = False) -> dict[str, Any]:
        """Plain data for JSON: operating point, S_SS, window, solver statistics.

        Keys ``wob`` [N], ``rpm`` and ``severity`` are always present; ``rpm`` is the set
        speed, or for a top drive without one the mean top-drive speed over the steady
        window, and ``rpm_source`` says which (``"set"`` or ``"top_speed_mean"``). For a
        dimensionless system ``wob`` and ``rpm`` are those of its System (Pi_2 and
        Pi_1 in rpm form) and ``pi1``, ``pi2`` are added. ``series=True`` adds the
        time series.
        """
        window = self.window_mask
        system = self.system
        data: dict[str, Any] = {
            "wob": float(system.wob),
            "rpm": self.rpm,
            "rpm_source": "set" if self.has_set_speed else "top_speed_mean",
            "severity": float(self.severity),
            "severe": self.severe,
            "stick_fraction": float(self.stick_fraction),
            "stick_threshold": float(self.stick_threshold),
            "omega_rad_s": float(self.omega),
            "bit_speed_min": float(self._extremes[1]),
            "bit_speed_max": float(self._extremes[0]),
            "top_speed_mean": self.top_speed_mean,
            "top_drive": getattr(system.top, "name", type(system.top).__name__),
            "mean_motor_torque": float(self.motor_torque[window].mean()),
            "mean_bit_torque": float(self.bit_torque[window].mean()),
            "mean_surface_torque": float(self.surface_torque[window].mean()),
            "duration_s": self.duration,
            "steady_window_s": float(self.steady_window),
            "output_step_s": self.output_step,
            "samples": int(self.time.size),
            "dofs": int(system.model.dofs),
            "strategy": system.model.strategy,
            "law": getattr(system.law, "name", type(system.law).__name__),
            "bit_radius": float(system.bit_radius),
            "dimensionless": self.dimensionless,
            "solver": dict(self.solver),
            "warnings": list(self.warnings),
        }
        if self.well_summary is not None:
            data.update(self.well_summary)
        if self.dimensionless:
            data["pi1"] = float(self.omega)
            data["pi2"] = float(system.wob * system.bit_radius)
        if series:
            data["series"] = {
                "time": self.time.tolist(),
                "bit_speed": self.bit_speed.tolist(),
                "bit_torque": self.bit_torque.tolist(),
                "surface_torque": self.surface_torque.tolist(),
                "top_speed": self.top_speed.tolist(),
                "motor_torque": self.motor_torque.tolist(),
            }
        return data

    def to_csv(self, path: str | Path) -> Path:
        """Write the time series as CSV: time, bit speed/angle, torques, node speeds.

        Columns: ``time_s, bit_speed_rad_s, bit_angle_rad, bit_torque_Nm,
        surface_torque_Nm, top_speed_rad_s, motor_torque_Nm, node_speed_1_rad_s, ...``.
        Returns the path written.
        """
        path = Path(path)
        columns = [
            self.time,
            self.bit_speed,
            self.bit_angle,
            self.bit_torque,
            self.surface_torque,
            self.top_speed,
            self.motor_torque,
        ]
        names = [
            "time_s",
            "bit_speed_rad_s",
            "bit_angle_rad",
            "bit_torque_Nm",
            "surface_torque_Nm",
            "top_speed_rad_s",
            "motor_torque_Nm",
        ]
        for j in range(self.node_speeds.shape[1]):
            columns.append(self.node_speeds[:, j])
            names.append(f"node_speed_{j + 1}_rad_s")
        with atomic_output(path) as stream:  # whole or not at all (OutputError)
            np.savetxt(
                stream,
                np.column_stack(columns),
                delimiter=",",
                header=",".join(names),
                comments="",
                fmt="%.10g",
            )
        return path

    def plot(self, path: str | Path | None = None, ax: Any = None) -> Any:
        """Bit speed, surface torque and torque on bit against time (matplotlib).

        With a top drive that has inertia the top-drive speed and the motor torque
        are drawn too. The steady-state window is shaded. ``path`` writes the figure (PNG by
        extension); ``ax`` (a sequence of three matplotlib axes: speeds, surface torque,
        torque on bit) draws into existing ones, as ``ax=`` of every results' ``plot``.
        Returns the figure.

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
        time_label = "tau = omega_1 t [-]" if self.dimensionless else "time [s]"
        speed_unit = "-" if self.dimensionless else "rpm"
        scale = 1.0 if self.dimensionless else 1.0 / RPM_TO_RAD_S
        torque_unit = "-" if self.dimensionless else "kN m"
        torque_scale = 1.0 if self.dimensionless else 1e-3
        axes[0].plot(self.time, self.bit_speed * scale, lw=0.8, label="bit")
        if self.has_top_drive_node:
            axes[0].plot(self.time, self.top_speed * scale, lw=0.8, color="k", label="top drive")
            axes[0].set_ylabel(f"speed [{speed_unit}]")
        else:
            axes[0].axhline(self.omega * scale, color="k", lw=0.6, ls="--", label="top")
            axes[0].set_ylabel(f"bit speed [{speed_unit}]")
        axes[0].legend(loc="upper right", fontsize="small")
        axes[1].plot(
            self.time, self.surface_torque * torque_scale, lw=0.8, color="C1", label="pipe"
        )
        if self.has_top_drive_node:
            axes[1].plot(
                self.time, self.motor_torque * torque_scale, lw=0.8, color="C4", label="motor"
            )
            axes[1].legend(loc="upper right", fontsize="small")
        axes[1].set_ylabel(f"surface torque [{torque_unit}]")
        axes[2].plot(self.time, self.bit_torque * torque_scale, lw=0.8, color="C2")
        axes[2].set_ylabel(f"torque on bit [{torque_unit}]")
        axes[2].set_xlabel(time_label)
        for ax in axes:
            ax.axvspan(self.window_start, self.duration, color="0.9", zorder=0)
            ax.grid(True, lw=0.3)
        op = (
            f"Pi1 = {self.omega:.4g}, Pi2 = {self.system.wob * self.system.bit_radius:.4g}"
            if self.dimensionless
            else f"WOB = {self.system.wob / 1e3:.4g} kN, {self.rpm:.4g} rpm"
            + ("" if self.has_set_speed else " (mean top speed)")
        )
        axes[0].set_title(f"{op}: S_SS = {self.severity:.3f} (steady window shaded)")
        fig.tight_layout()
        if path is not None:
            save_figure_file(fig, path, dpi=120)  # whole or not at all (OutputError)
        return fig


def window_mask(time_grid: np.ndarray, window: float) -> np.ndarray:
    """Boolean mask of the samples of ``time_grid`` [s] in the last ``window`` seconds."""
    start = time_grid[-1] - window
    return np.asarray(time_grid >= start - 1e-9 * max(1.0, abs(time_grid[-1])))
