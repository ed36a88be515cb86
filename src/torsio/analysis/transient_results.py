"""Results of a transient run: the sampled response, S_SS, JSON, CSV and the plot.

Returned by :func:`torsio.analysis.transient.simulate` and, with its axial channels, by
:func:`torsio.analysis.axial_transient.simulate_axial`; a results object never recomputes the
analysis.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np

from torsio.analysis.run_facts import RunFacts
from torsio.analysis.run_table import run_table
from torsio.analysis.severity import SEVERE_THRESHOLD
from torsio.errors import ConfigError
from torsio.output_files import save_columns, write_npz
from torsio.physics.system import System
from torsio.units import RPM_TO_RAD_S

if TYPE_CHECKING:
    from torsio.analysis.axial_results import AxialChannels

__all__ = [
    "RUN_ARRAYS",
    "RUN_FORMAT",
    "RUN_FORMAT_VERSION",
    "RUN_VALUES",
    "TransientResults",
    "run_file_path",
    "window_mask",
]

RUN_FORMAT, RUN_FORMAT_VERSION = "torsio transient", 1
"""A saved run's ``format`` and ``version`` (:meth:`TransientResults.save`)."""
RUN_ARRAYS = ("time", "bit_speed", "bit_angle", "node_speeds", "node_twists", "bit_torque",
              "surface_torque", "top_speed", "motor_torque", "states")  # fmt: skip
"""The arrays of a saved torsional run, one per field."""
RUN_VALUES = ("severity", "stick_fraction", "steady_window", "stick_threshold", "solver",
              "reference_speed", "severity_speed", "well_summary")  # fmt: skip
"""The other fields of a saved torsional run, in its metadata (with its facts, warnings
and bit-speed extremes)."""


@attrs.frozen(eq=False)
class TransientResults:
    """The sampled transient response of a run, whatever model and engine made it.

    A torsional run (:func:`simulate`) has its System; an axial-torsional run
    (:func:`torsio.analysis.axial_transient.simulate_axial`) has its axial channels instead
    (:attr:`axial`): the rate of penetration, the weight on bit, the depth of cut, the MSE,
    the steady drilling state. Every signal is also read by name (:meth:`signal`).

    Attributes
    ----------
    time : ndarray, shape (m,)
        Sample times [s] (uniform grid from 0 to the run length; for an axial run every
        k-th step, the last at most k steps before the run's end, none with ``samples=0``).
    bit_speed : ndarray, shape (m,)
        Absolute bit speed theta_N' [rad/s].
    bit_angle : ndarray, shape (m,)
        Absolute bit angle theta_N [rad].
    node_speeds : ndarray, shape (m, dofs)
        Absolute speed of every degree of freedom [rad/s] (the last is the bit); shape
        (m, 0) for an axial run, whose samples keep the bit and the top (as do
        ``node_twists`` and ``states``).
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
        Fraction of the steady window during which ``|bit speed| < stick_threshold Omega``
        (an axial run: of the window's steps).
    steady_window : float
        Length of the steady-state window at the end of the run [s].
    stick_threshold : float
        Stick threshold as a fraction of Omega.
    solver : dict
        ``method``, ``rtol``, ``atol``, ``nfev``, ``njev``, ``nlu``, ``status``,
        ``message``, ``wall_time_s``; an axial run's ``engine``, ``method``, ``scheme``,
        ``step``.
    system : System or None
        The system that was integrated; None for an axial run (its assembly is
        ``axial.model``).
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
        speed over the steady window for a torque-driven top (an axial run: Ω₀ of its
        steady state, whatever its top drive).
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
    axial : AxialChannels or None
        An axial run's channels and outputs
        (:class:`~torsio.analysis.axial_results.AxialChannels`: ``steady``, ``summary`` with
        ``rop_mean`` and ``mse_mean``, ``growth_rate``, ``energy``, the signals
        ``bit_weight``, ``depth_of_cut`` ...); None for a torsional run. Its JSON, CSV
        and terminal table are the run's.
    facts : RunFacts
        The operating point, top drive, law and model the results read
        (:class:`~torsio.analysis.run_facts.RunFacts`); by default those of ``system``,
        or of ``axial``. A run read from a file (:func:`torsio.analysis.run_file.load_run`)
        has its facts and no System.
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
    system: System | None
    top_speed: np.ndarray
    motor_torque: np.ndarray
    states: np.ndarray
    reference_speed: float
    severity_speed: float
    bit_speed_extremes: tuple[float, float] | None = None
    warnings: tuple[str, ...] = ()
    well_summary: dict[str, Any] | None = None
    axial: AxialChannels | None = None
    facts: RunFacts = attrs.field(
        default=attrs.Factory(lambda run: run._facts_of_source(), takes_self=True)
    )

    def __repr__(self) -> str:  # short: no time series
        if self.axial is not None:
            return f"TransientResults({self.axial!r})"
        return (
            f"TransientResults({self.time.size} samples over {self.time[-1]:g} s, "
            f"S_SS {self.severity:.4g} over the last {self.steady_window:g} s, "
            f"{self.solver.get('method')} rtol {self.solver.get('rtol')}; "
            + (repr(self.system) if self.system is not None else self._read_back)
            + ")"
        )

    @property
    def _read_back(self) -> str:
        facts = self.facts
        return f"read from a file: {facts.strategy}, {facts.dofs} DOF, {facts.law}"

    def _facts_of_source(self) -> RunFacts:
        if self.axial is not None:
            return self.axial.facts()
        if self.system is None:
            raise TypeError("TransientResults needs a system, axial channels or its facts")
        return RunFacts.of_system(self.system)

    # --- derived views (no recomputation of the analysis) ---------------------------------

    def signal(self, name: str) -> np.ndarray:
        """A signal by name: ``time``, ``bit_speed``, ``bit_angle``, ``bit_torque``,
        ``surface_torque``, ``top_speed``, ``motor_torque`` of every run, and an axial
        run's :data:`torsio.solvers.axial_layouts.SAMPLE_COLUMNS` (``bit_weight``,
        ``depth_of_cut``, ``bit_velocity`` ...)."""
        if self.axial is not None:
            return self.axial.signal(name)
        if name not in _SIGNALS:
            raise KeyError(f"{name!r}: a torsional run's signals are {', '.join(_SIGNALS)}")
        return np.asarray(getattr(self, name))

    @property
    def wob(self) -> float:
        """The weight on bit of the run [N] (for a dimensionless system: Pi_2 / R_bit)."""
        return self.facts.wob

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
        """Whether the top drive is a node with inertia, its motor torque its own (a top held
        at a constant or a recorded speed is not)."""
        return self.facts.has_top_drive_node

    @property
    def has_set_speed(self) -> bool:
        """Whether the top drive turns at a set speed (False for a torque-driven top, and
        for a top that follows a recording: its speed is the record's)."""
        return self.facts.has_set_speed

    @property
    def rpm(self) -> float:
        """The rotary speed the run had [rpm] (:attr:`rpm_source` says which): the set
        speed, an axial run's given speed under a torque-driven top, else (a torque-driven
        top of a torsional run, a recording) the mean top-drive speed over the window."""
        if math.isfinite(self.facts.rpm):
            return self.facts.rpm
        return self.top_speed_mean / RPM_TO_RAD_S

    @property
    def rpm_source(self) -> str:
        """Where :attr:`rpm` comes from: ``"set"``, the top drive's set speed;
        ``"top_speed_mean"``, the mean top-drive speed over the window (a top drive without
        a set speed on a torsional run, a recorded top speed on any run); ``"given"``, the
        speed an axial run under a torque-driven top was given, its steady state's, which
        S_SS is read against."""
        if self.has_set_speed:
            return "set"
        return "given" if math.isfinite(self.facts.rpm) else "top_speed_mean"

    @property
    def top_speed_mean(self) -> float:
        """Mean top-drive speed over the steady window [rad/s] (NaN for an axial run that
        kept no samples)."""
        if self.axial is not None:
            mean = self.axial.top_drive_summary()["top_speed_mean"]
            return math.nan if mean is None else mean
        return float(self.top_speed[self.window_mask].mean())

    @property
    def duration(self) -> float:
        """Run length [s]."""
        return self.axial.duration if self.axial is not None else float(self.time[-1])

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
        if self.axial is not None:  # its samples may end before the run does
            return self.axial.window_rows()
        return window_mask(self.time, self.steady_window)

    @property
    def node_angles(self) -> np.ndarray:
        """Absolute angle of every degree of freedom [rad], shape (m, dofs)."""
        return self.node_twists + self.reference_speed * self.time[:, None]

    @property
    def bit_twist(self) -> np.ndarray:
        """Twist of the bit, theta_N - Omega_ref t [rad]."""
        if self.axial is not None:
            raise AttributeError("an axial run keeps no twists: its bit angle is bit_angle")
        return self.node_twists[:, -1]

    @property
    def severe(self) -> bool:
        """Whether S_SS exceeds the paper's 0.8 threshold."""
        return bool(self.severity > SEVERE_THRESHOLD)

    @property
    def _pi2(self) -> float:
        """Pi_2 = W_ob R_bit of a dimensionless system's run (its k_eq is 1)."""
        assert self.facts.bit_radius is not None  # a torsional model's
        return float(self.wob * self.facts.bit_radius)

    @property
    def dimensionless(self) -> bool:
        """Whether the system is a dimensionless one (time is tau = omega_1 t)."""
        return self.facts.dimensionless

    # --- output ---------------------------------------------------------------------------
    def to_dict(self, series: bool = False) -> dict[str, Any]:
        """Plain data for JSON: operating point, S_SS, window, solver statistics.

        The keys of every run (:meth:`run_keys`): ``wob`` [N], ``rpm``, ``severity`` and
        more. A torsional run adds its top drive's and torques' means over the window, its
        model (``dofs``, ``strategy``, ``bit_radius``) and, with a well, the well summary;
        for a dimensionless system ``wob`` and ``rpm`` are those of its System (Pi_2 and
        Pi_1 in rpm form) and ``pi1``, ``pi2`` are added. An axial run adds the keys of
        :meth:`torsio.analysis.axial_results.AxialChannels.to_dict` (DESIGN.md).
        ``series=True`` adds the time series.
        """
        if self.axial is not None:
            return {**self.run_keys(), **self.axial.to_dict(series)}
        window = self.window_mask
        facts = self.facts
        data: dict[str, Any] = {
            **self.run_keys(),
            "top_speed_mean": self.top_speed_mean,
            "mean_motor_torque": float(self.motor_torque[window].mean()),
            "mean_bit_torque": float(self.bit_torque[window].mean()),
            "mean_surface_torque": float(self.surface_torque[window].mean()),
            "output_step_s": self.output_step,
            "dofs": facts.dofs,
            "strategy": facts.strategy,
            "bit_radius": facts.bit_radius,
        }
        if self.well_summary is not None:
            data.update(self.well_summary)
        if self.dimensionless:
            data["pi1"] = float(self.omega)
            data["pi2"] = self._pi2
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

    def run_keys(self) -> dict[str, Any]:
        """The JSON keys of every run, whatever model and engine made it: ``wob`` [N],
        ``rpm``, ``rpm_source`` (:attr:`rpm_source`), ``severity``,
        ``severe``, ``stick_fraction``, ``stick_threshold`` (a fraction of Omega; 0 for
        an axial run saved before it counted below the threshold), ``omega_rad_s``,
        ``bit_speed_min``,
        ``bit_speed_max`` [rad/s], ``top_drive``, ``law``, ``duration_s``,
        ``steady_window_s``, ``samples`` (rows kept), ``dimensionless``, ``solver`` and
        ``warnings``."""
        return {
            "wob": self.wob,
            "rpm": self.rpm,
            "rpm_source": self.rpm_source,
            "severity": float(self.severity),
            "severe": self.severe,
            "stick_fraction": float(self.stick_fraction),
            "stick_threshold": float(self.stick_threshold),
            "omega_rad_s": float(self.omega),
            "bit_speed_min": float(self._extremes[1]),
            "bit_speed_max": float(self._extremes[0]),
            "top_drive": self.facts.top_drive,
            "law": self.facts.law,
            "duration_s": self.duration,
            "steady_window_s": float(self.steady_window),
            "samples": int(self.time.size),
            "dimensionless": self.dimensionless,
            "solver": dict(self.solver),
            "warnings": list(self.warnings),
        }

    def save(self, path: str | Path) -> Path:
        """Write the run to a numpy ``.npz`` archive, which
        :func:`torsio.analysis.run_file.load_run` reads back whole: every signal and
        state, S_SS, the solver's statistics, the warnings and the run's facts (not its
        System); an axial run its channels (:meth:`AxialChannels.saved`). Written
        atomically (an :class:`~torsio.errors.OutputError` names the path of a failed
        write). Returns the path written."""
        path = run_file_path(path)
        metadata: dict[str, Any] = {"format": RUN_FORMAT, "version": RUN_FORMAT_VERSION}
        metadata["warnings"] = list(self.warnings)
        if self.axial is not None:
            channels, samples = self.axial.saved()
            return write_npz(path, {**metadata, "axial": channels}, {"axial_samples": samples})
        metadata.update({name: getattr(self, name) for name in RUN_VALUES})
        metadata.update(facts=attrs.asdict(self.facts), bit_speed_extremes=self.bit_speed_extremes)
        return write_npz(path, metadata, {name: getattr(self, name) for name in RUN_ARRAYS})

    def to_csv(self, path: str | Path) -> Path:
        """Write the time series as CSV: time, bit speed/angle, torques, node speeds.

        Columns: ``time_s, bit_speed_rad_s, bit_angle_rad, bit_torque_Nm,
        surface_torque_Nm, top_speed_rad_s, motor_torque_Nm, node_speed_1_rad_s, ...``.
        Returns the path written. An axial run's columns are its
        :data:`torsio.solvers.axial_layouts.SAMPLE_COLUMNS` (:meth:`AxialChannels.to_csv`).
        """
        if self.axial is not None:
            return self.axial.to_csv(path)
        columns = [self.time, self.bit_speed, self.bit_angle, self.bit_torque]
        columns += [self.surface_torque, self.top_speed, self.motor_torque, *self.node_speeds.T]
        names = ["time_s", "bit_speed_rad_s", "bit_angle_rad", "bit_torque_Nm"]
        names += ["surface_torque_Nm", "top_speed_rad_s", "motor_torque_Nm"]
        names += [f"node_speed_{j + 1}_rad_s" for j in range(self.node_speeds.shape[1])]
        return save_columns(path, names, columns)

    def summary_rows(self, units: Any) -> tuple[str, list[tuple[str, str]]]:
        """The terminal table of the run (``torsio simulate``): its title and (quantity,
        value) rows (:func:`torsio.analysis.run_table.run_table`), forces and torques in
        ``units`` (a :class:`~torsio.display_units.DisplayUnits`)."""
        if self.axial is not None:
            return self.axial.summary_rows(self.to_dict(), units)
        return run_table(self, units)

    @property
    def plot_label(self) -> str:
        """The operating point, for the plot's title."""
        if self.dimensionless:
            return f"Pi1 = {self.omega:.4g}, Pi2 = {self._pi2:.4g}"
        source = {"set": "", "top_speed_mean": " (mean top speed)", "given": " (no set speed)"}
        return f"WOB = {self.wob / 1e3:.4g} kN, {self.rpm:.4g} rpm{source[self.rpm_source]}"

    def plot(self, path: str | Path | None = None, ax: Any = None) -> Any:
        """Bit speed, surface torque and torque on bit against time
        (:func:`torsio.plotting.transient_plot.plot_transient`); returns the figure."""
        from torsio.plotting.transient_plot import plot_transient

        return plot_transient(self, path, ax)


_SIGNALS = ("time", "bit_speed", "bit_angle", "bit_torque", "surface_torque", "top_speed",
            "motor_torque")  # fmt: skip
"""The signals every run has, by name (:meth:`TransientResults.signal`)."""


def run_file_path(path: str | Path, key: str = "path") -> Path:
    """``path`` of a saved run (:meth:`TransientResults.save`): a name ending in ``.npz``,
    else a ConfigError on ``key``."""
    path = Path(path)
    if path.suffix != ".npz":
        raise ConfigError(
            key,
            f"{str(path)!r}: a run is saved as a numpy archive of its arrays; expected a "
            "name ending in .npz (its JSON is to_dict(series=True), torsio simulate --json)",
        )
    return path


def window_mask(time_grid: np.ndarray, window: float) -> np.ndarray:
    """Boolean mask of the samples of ``time_grid`` [s] in the last ``window`` seconds."""
    start = time_grid[-1] - window
    return np.asarray(time_grid >= start - 1e-9 * max(1.0, abs(time_grid[-1])))
