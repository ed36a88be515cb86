"""Transient response of a System: start-up from rest, stick-slip, severity S_SS.

:func:`simulate` integrates the equations of motion in twist coordinates (see
:mod:`torsio.physics.system` and :mod:`torsio.physics.equations`) with ``scipy.integrate.solve_ivp``
and samples the response on a uniform time grid.

Defaults (the paper states none; see ``docs/dynamics.md``):

* **Initial condition**: start-up from rest, every angle and speed zero at t = 0
  while the top turns at Omega from t = 0 (the forcing ``c1 Omega + k1 Omega t`` of
  Eq. 3 implies it).
* **Run length and steady window**: :data:`torsio.analysis.severity.DEFAULT_DURATION_PERIODS`
  (40) periods of the first natural mode, S_SS read over the last
  :data:`torsio.analysis.severity.DEFAULT_WINDOW_PERIODS` (15), or over the second half of
  the run when a shorter run is asked for.
* **Integrator**: LSODA (switches between a non-stiff Adams method and a stiff BDF
  method by itself; the bit law makes the equations stiff during sticking and not
  otherwise) with the analytic Jacobian in banded form, rtol = 1e-6, atol = 1e-9.
  Radau and BDF get the sparse Jacobian; explicit methods need none.
* **Output step**: :data:`DEFAULT_SAMPLES_PER_PERIOD` (200) samples per period of
  the first mode. S_SS reads the extrema of the sampled bit speed; at the stick-slip
  points of the Ritto et al. (2017) string checked, this step changes S_SS by at most
  1.4e-5 against a ten times finer grid.

Examples
--------
>>> from torsio.physics.system import System, builtin_config
>>> system = System.from_config(builtin_config(), strategy="A").at(wob=175e3, rpm=100)
>>> results = simulate(system)
>>> round(results.severity, 3), results.severe
(1.099, True)
>>> data = results.to_dict()
>>> data["wob"], data["rpm"], data["solver"]["method"]
(175000.0, 100.0, 'LSODA')
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import attrs
import numpy as np
import scipy.integrate
import scipy.sparse

from torsio.analysis.budget import (
    BudgetExceeded,
    EvaluationBudget,
    check_law_time_scale,
    check_output_size,
    check_rtol,
)
from torsio.analysis.severity import (
    SEVERE_THRESHOLD,
    check_window,
    default_times,
    severity,
)
from torsio.errors import ConfigError, SolverError
from torsio.io.config import Config
from torsio.physics.equations import TwistEquations
from torsio.physics.system import System
from torsio.units import RPM_TO_RAD_S

__all__ = [
    "DEFAULT_SAMPLES_PER_PERIOD",
    "DEFAULT_STICK_THRESHOLD",
    "METHODS",
    "SEVERE_THRESHOLD",
    "SimulationOptions",
    "TransientResults",
    "first_natural_frequency",
    "simulate",
    "simulate_config",
    "system_from_config",
]

METHODS = ("LSODA", "RK45", "RK23", "DOP853", "Radau", "BDF")
"""The integrators of ``scipy.integrate.solve_ivp`` accepted by name."""

IMPLICIT_METHODS = ("Radau", "BDF")
"""Methods that take the (sparse) Jacobian."""

DEFAULT_SAMPLES_PER_PERIOD = 200
"""Default output samples per period 2 pi / omega_1 of the first natural mode."""

MIN_WINDOW_SAMPLES = 10
"""Fewest output samples the steady-state window may hold."""

DEFAULT_STICK_THRESHOLD = 0.1
"""Default stick threshold, as a fraction of Omega: the bit sticks while
``|bit speed| < 0.1 Omega``. With a regularized law (Tucker-Wang's tanh) the bit
creeps at a few per cent of Omega instead of stopping exactly."""


def _positive(key: str, value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ConfigError(f"simulation.{key}", f"expected {what}, got {value!r}")
    number = float(value)
    if not (math.isfinite(number) and number > 0):
        raise ConfigError(f"simulation.{key}", f"expected {what}, got {value!r}")
    return number


def _check_method(method: Any) -> Any:
    if isinstance(method, str):
        if method not in METHODS:
            raise ConfigError(
                "simulation.method",
                f"unknown integrator {method!r}; expected one of {', '.join(METHODS)}",
            )
        return method
    if isinstance(method, type) and issubclass(method, scipy.integrate.OdeSolver):
        return method
    raise ConfigError(
        "simulation.method",
        f"expected one of {', '.join(METHODS)} or a scipy OdeSolver class, got {method!r}",
    )


def _optional_positive(key: str, value: Any, what: str) -> float | None:
    return None if value is None else _positive(key, value, what)


@attrs.frozen
class SimulationOptions:
    """Options of the transient analyzer, as the ``[simulation]`` table gives them.

    Every field has the meaning of the :func:`simulate` argument of the same name;
    ``None`` means the documented default. Values are validated on construction
    and errors name the ``simulation.<key>``.

    Examples
    --------
    >>> SimulationOptions(rtol=1e-8).replace(duration=100.0, rtol=None).rtol
    1e-08
    >>> SimulationOptions(method="Euler")
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: simulation.method: unknown integrator 'Euler'; expected one of ...
    """

    duration: float | None = attrs.field(
        default=None, converter=lambda v: _optional_positive("duration", v, "a positive time in s")
    )
    steady_window: float | None = attrs.field(
        default=None,
        converter=lambda v: _optional_positive("steady_window", v, "a positive time in s"),
    )
    method: Any = attrs.field(default="LSODA", converter=_check_method)
    rtol: float = attrs.field(default=1e-6, converter=lambda v: check_rtol(v, "simulation.rtol"))
    atol: float = attrs.field(
        default=1e-9, converter=lambda v: _positive("atol", v, "a positive tolerance")
    )
    output_step: float | None = attrs.field(
        default=None,
        converter=lambda v: _optional_positive("output_step", v, "a positive time in s"),
    )
    stick_threshold: float | None = attrs.field(
        default=None,
        converter=lambda v: _optional_positive(
            "stick_threshold", v, "a positive fraction of Omega"
        ),
    )

    @classmethod
    def from_config(cls, config: Config) -> SimulationOptions:
        """The options of a configuration's ``[simulation]`` table (defaults elsewhere)."""
        return cls(**dict(config.simulation.options))

    def replace(self, **overrides: Any) -> SimulationOptions:
        """These options with ``overrides`` applied; ``None`` values are ignored."""
        unknown = sorted(set(overrides) - set(attrs.fields_dict(type(self))))
        if unknown:
            raise ConfigError(
                f"simulation.{unknown[0]}",
                f"unknown option; expected one of {', '.join(attrs.fields_dict(type(self)))}",
            )
        return attrs.evolve(self, **{k: v for k, v in overrides.items() if v is not None})

    def kwargs(self) -> dict[str, Any]:
        """Keyword arguments of :func:`simulate`."""
        return attrs.asdict(self)


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
        Twist phi = theta - Omega t of every degree of freedom [rad]: its angle
        relative to the top drive (negative: lagging behind the top).
    bit_torque : ndarray, shape (m,)
        Torque on bit T_bit from the bit-rock law [N m].
    surface_torque : ndarray, shape (m,)
        Torque the top drive applies to the string [N m],
        ``k1 (Omega t - theta_1) + c1 (Omega - theta_1')`` for a chain, in general
        ``-k_t . phi - c_t . v``.
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

    # --- derived views (no recomputation of the analysis) ---------------------------------
    @property
    def omega(self) -> float:
        """Surface speed Omega [rad/s] (for a dimensionless system: Pi_1)."""
        return self.system.omega

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
        return _window_mask(self.time, self.steady_window)

    @property
    def node_angles(self) -> np.ndarray:
        """Absolute angle of every degree of freedom [rad], shape (m, dofs)."""
        return self.node_twists + self.omega * self.time[:, None]

    @property
    def bit_twist(self) -> np.ndarray:
        """Twist of the bit against the top, theta_N - Omega t [rad]."""
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

        Keys ``wob`` [N], ``rpm`` and ``severity`` are always present. For a
        dimensionless system ``wob`` and ``rpm`` are those of its System (Pi_2 and
        Pi_1 in rpm form) and ``pi1``, ``pi2`` are added. ``series=True`` adds the
        time series.
        """
        window = self.window_mask
        system = self.system
        data: dict[str, Any] = {
            "wob": float(system.wob),
            "rpm": float(system.rpm),
            "severity": float(self.severity),
            "severe": self.severe,
            "stick_fraction": float(self.stick_fraction),
            "stick_threshold": float(self.stick_threshold),
            "omega_rad_s": float(self.omega),
            "bit_speed_min": float(self.bit_speed[window].min()),
            "bit_speed_max": float(self.bit_speed[window].max()),
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
        }
        if self.dimensionless:
            data["pi1"] = float(self.omega)
            data["pi2"] = float(system.wob * system.bit_radius)
        if series:
            data["series"] = {
                "time": self.time.tolist(),
                "bit_speed": self.bit_speed.tolist(),
                "bit_torque": self.bit_torque.tolist(),
                "surface_torque": self.surface_torque.tolist(),
            }
        return data

    def to_csv(self, path: str | Path) -> Path:
        """Write the time series as CSV: time, bit speed/angle, torques, node speeds.

        Columns: ``time_s, bit_speed_rad_s, bit_angle_rad, bit_torque_Nm,
        surface_torque_Nm, node_speed_1_rad_s, ...``. Returns the path written.
        """
        path = Path(path)
        columns = [self.time, self.bit_speed, self.bit_angle, self.bit_torque, self.surface_torque]
        names = ["time_s", "bit_speed_rad_s", "bit_angle_rad", "bit_torque_Nm", "surface_torque_Nm"]
        for j in range(self.node_speeds.shape[1]):
            columns.append(self.node_speeds[:, j])
            names.append(f"node_speed_{j + 1}_rad_s")
        try:
            np.savetxt(
                path,
                np.column_stack(columns),
                delimiter=",",
                header=",".join(names),
                comments="",
                fmt="%.10g",
            )
        except OSError as exc:
            raise ConfigError("csv", f"cannot write {str(path)!r}: {exc.strerror or exc}") from None
        return path

    def plot(self, path: str | Path | None = None, axes: Any = None) -> Any:
        """Bit speed, surface torque and torque on bit against time (matplotlib).

        The steady-state window is shaded. ``path`` writes the figure (PNG by
        extension); ``axes`` (three matplotlib axes) draws into existing ones.
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
        if axes is not None:
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
        axes[0].axhline(self.omega * scale, color="k", lw=0.6, ls="--", label="top")
        axes[0].set_ylabel(f"bit speed [{speed_unit}]")
        axes[0].legend(loc="upper right", fontsize="small")
        axes[1].plot(self.time, self.surface_torque * torque_scale, lw=0.8, color="C1")
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
            else f"WOB = {self.system.wob / 1e3:.4g} kN, {self.system.rpm:.4g} rpm"
        )
        axes[0].set_title(f"{op}: S_SS = {self.severity:.3f} (steady window shaded)")
        fig.tight_layout()
        if path is not None:
            try:
                fig.savefig(path, dpi=120)
            except OSError as exc:
                raise ConfigError(
                    "plot", f"cannot write {str(path)!r}: {exc.strerror or exc}"
                ) from None
        return fig


def _window_mask(time_grid: np.ndarray, window: float) -> np.ndarray:
    start = time_grid[-1] - window
    return np.asarray(time_grid >= start - 1e-9 * max(1.0, abs(time_grid[-1])))


def first_natural_frequency(system: System) -> float:
    """omega_1 [rad/s] of the system's lumped model (undamped)."""
    from torsio.model.modal import modal_analysis

    return float(modal_analysis(system.model, 1).frequencies_rad[0])


def _initial_state(equations: TwistEquations, initial_state: Any) -> np.ndarray:
    n = equations.dofs
    if initial_state is None:
        return equations.rest_state()
    if isinstance(initial_state, tuple):
        if len(initial_state) != 2:
            raise ConfigError(
                "initial_state", "expected (angles [rad], speeds [rad/s]) or a state vector"
            )
        angles, speeds = (np.asarray(a, dtype=float).reshape(-1) for a in initial_state)
        for key, values in (("angles", angles), ("speeds", speeds)):
            if values.size == 1:
                values = np.full(n, float(values[0]))
            if values.size != n:
                raise ConfigError(
                    f"initial_state.{key}", f"expected {n} values (one per DOF), got {values.size}"
                )
            if key == "angles":
                angles = values
            else:
                speeds = values
        y0 = equations.state(angles, speeds)  # at t = 0 the twist is the angle
    else:
        y0 = np.array(initial_state, dtype=float).reshape(-1)
        if y0.size != 2 * n:
            raise ConfigError(
                "initial_state",
                f"expected the interleaved twist state [phi_1, v_1, ..., phi_N, v_N] of "
                f"{2 * n} values, got {y0.size}",
            )
    if not np.all(np.isfinite(y0)):
        raise ConfigError("initial_state", "expected finite values")
    return y0


def _band_jacobian(equations: TwistEquations, lower: int, upper: int) -> Any:
    """The Jacobian in LSODA's packed banded format: packed[upper + i - j, j] = J[i, j]."""
    size = 2 * equations.dofs

    def jac(t: float, y: np.ndarray) -> np.ndarray:
        coo = equations.jacobian(t, y).tocoo()
        packed = np.zeros((lower + upper + 1, size))
        packed[upper + coo.row - coo.col, coo.col] = coo.data
        return packed

    return jac


def simulate(
    system: System,
    duration: float | None = None,
    steady_window: float | None = None,
    method: Any = "LSODA",
    rtol: float = 1e-6,
    atol: float = 1e-9,
    output_step: float | None = None,
    initial_state: Any = None,
    stick_threshold: float | None = None,
) -> TransientResults:
    """Integrate a System's equations of motion and read S_SS over the steady window.

    Parameters
    ----------
    system : System
        Model, damping, bit-rock law and operating point.
    duration : float, optional
        Run length [s]; default 40 periods of the first natural mode.
    steady_window : float, optional
        Length of the steady-state window at the end of the run [s] over which
        S_SS and the stick fraction are read; default 15 periods of the first
        mode, at most half the run.
    method : str or scipy OdeSolver class
        Any ``solve_ivp`` method; default LSODA with the banded Jacobian.
    rtol, atol : float
        Relative and absolute tolerances (atol applies to twists [rad] and
        relative speeds [rad/s]).
    output_step : float, optional
        Step of the uniform output grid [s]; default 1/200 of the first period
        (rounded down so that the grid ends exactly at ``duration``).
    initial_state : ndarray or tuple, optional
        Default: start-up from rest. A tuple ``(angles, speeds)`` gives absolute
        angles [rad] and speeds [rad/s] of every DOF at t = 0; an array gives
        the interleaved twist state of :class:`torsio.physics.equations.TwistEquations`.
    stick_threshold : float, optional
        The bit sticks while ``|bit speed| < stick_threshold * Omega``; default
        :data:`DEFAULT_STICK_THRESHOLD`.

    Returns
    -------
    TransientResults

    Raises
    ------
    ConfigError
        For invalid options (named ``simulation.<key>``).
    SolverError
        If the integrator fails or the solution is not finite; the message gives
        the solver's message and the time reached.
    """
    from torsio.model.wave import is_wave_model

    if is_wave_model(system.model):  # the distributed model: torsio.analysis.wave
        from torsio.analysis.wave import wave_response

        return wave_response(
            system, duration, steady_window, output_step, stick_threshold,
            initial_state=initial_state,
        ).transient  # fmt: skip
    options = SimulationOptions(
        duration=duration,
        steady_window=steady_window,
        method=method,
        rtol=rtol,
        atol=atol,
        output_step=output_step,
        stick_threshold=stick_threshold,
    )
    omega = system.omega
    if not (math.isfinite(omega) and omega > 0):  # System validates this; S_SS divides by it
        raise ConfigError("operation.rpm", f"expected a positive rotary speed, got {system.rpm!r}")
    needs_frequency = options.duration is None or options.steady_window is None
    needs_frequency = needs_frequency or options.output_step is None
    omega1 = first_natural_frequency(system) if needs_frequency else math.nan
    default_duration, default_window = (
        default_times(omega1) if needs_frequency else (math.nan, math.nan)
    )
    run = options.duration if options.duration is not None else default_duration
    if options.steady_window is not None:
        window = options.steady_window
    elif options.duration is None:
        window = default_window
    else:
        window = min(default_window, 0.5 * run)
    check_window(run, window)
    step = (
        options.output_step
        if options.output_step is not None
        else 2.0 * math.pi / omega1 / DEFAULT_SAMPLES_PER_PERIOD
    )
    intervals = check_output_size(run, step, 3 * system.model.dofs + 4)
    check_law_time_scale(system, system.wob, run)
    time_grid = np.linspace(0.0, run, intervals + 1)
    in_window = _window_mask(time_grid, window)
    if step > window / MIN_WINDOW_SAMPLES:
        raise ConfigError(
            "simulation.output_step",
            f"the output step ({step:g} s) leaves fewer than {MIN_WINDOW_SAMPLES} samples in "
            f"the steady window ({window:g} s); expected a step of at most "
            f"{window / MIN_WINDOW_SAMPLES:g} s",
        )
    threshold = (
        options.stick_threshold if options.stick_threshold is not None else DEFAULT_STICK_THRESHOLD
    )

    equations = TwistEquations(system)
    y0 = _initial_state(equations, initial_state)
    solver_kwargs: dict[str, Any] = {}
    chosen = options.method
    name = chosen if isinstance(chosen, str) else chosen.__name__
    bands = equations.jacobian_bands
    if chosen == "LSODA":
        if bands is not None:
            lower, upper = bands
            solver_kwargs.update(
                lband=lower, uband=upper, jac=_band_jacobian(equations, lower, upper)
            )
        else:
            solver_kwargs["jac"] = lambda t, y: equations.jacobian(t, y).toarray()
    elif chosen in IMPLICIT_METHODS or (
        isinstance(chosen, type) and issubclass(chosen, scipy.integrate.Radau | scipy.integrate.BDF)
    ):
        solver_kwargs["jac"] = equations.jacobian
    budget = EvaluationBudget.for_samples(intervals)
    start = time.perf_counter()
    with np.errstate(all="ignore"):
        try:
            solution = scipy.integrate.solve_ivp(
                budget.wrap(equations.rhs),
                (0.0, run),
                y0,
                method=chosen,
                t_eval=time_grid,
                rtol=options.rtol,
                atol=options.atol,
                **solver_kwargs,
            )
        except BudgetExceeded:
            where = f"WOB = {system.wob:g} N, {system.rpm:g} rpm"
            raise budget.error(name, run, where) from None
    elapsed = time.perf_counter() - start
    solution_times = np.asarray(solution.t, dtype=float)
    reached = float(solution_times[-1]) if solution_times.size else 0.0
    states = np.asarray(solution.y, dtype=float)
    if solution.status < 0 or states.ndim != 2 or states.shape[1] != time_grid.size:
        raise SolverError(
            f"the {name} integrator failed at t = {reached:.6g} s of {run:.6g} s: "
            f"{solution.message} (operating point WOB = {system.wob:g} N, "
            f"{system.rpm:g} rpm; try another method or tighter tolerances)"
        )
    finite = np.all(np.isfinite(states), axis=0)
    if not finite.all():
        bad = float(time_grid[int(np.argmin(finite))])
        raise SolverError(
            f"the {name} integrator returned non-finite values from t = {bad:.6g} s "
            f"(of {run:.6g} s) with the bit-rock law {_law_name(system.law)}: a law torque "
            f"that is NaN or infinite, or an unstable model ({solution.message})"
        )
    twists = states[0::2].T.copy()
    relative_speeds = states[1::2].T
    node_speeds = relative_speeds + omega
    bit_speed = node_speeds[:, -1].copy()
    with np.errstate(all="ignore"):
        bit_torque = np.broadcast_to(
            np.asarray(system.law.torque(bit_speed, system.wob, system.bit_radius), dtype=float),
            bit_speed.shape,
        ).copy()
    if not np.all(np.isfinite(bit_torque)):
        bad = float(time_grid[int(np.argmin(np.isfinite(bit_torque)))])
        raise SolverError(
            f"the bit-rock law {_law_name(system.law)} returned a non-finite torque at "
            f"t = {bad:.6g} s (bit speed {bit_speed[int(np.argmin(np.isfinite(bit_torque)))]:.6g}"
            " rad/s)"
        )
    surface_torque = -(twists @ system.model.top_stiffness) - relative_speeds @ system.top_damping
    window_speeds = bit_speed[in_window]
    stick = float(np.mean(np.abs(window_speeds) < threshold * omega))
    solver_info = {
        "method": name,
        "rtol": options.rtol,
        "atol": options.atol,
        "nfev": int(solution.nfev),
        "njev": int(solution.njev),
        "nlu": int(solution.nlu),
        "status": int(solution.status),
        "message": str(solution.message),
        "wall_time_s": elapsed,
    }
    return TransientResults(
        time=time_grid,
        bit_speed=bit_speed,
        bit_angle=twists[:, -1] + omega * time_grid,
        node_speeds=node_speeds,
        node_twists=twists,
        bit_torque=bit_torque,
        surface_torque=surface_torque,
        severity=severity(window_speeds, omega),
        stick_fraction=stick,
        steady_window=float(window),
        stick_threshold=float(threshold),
        solver=solver_info,
        system=system,
    )


def _law_name(law: Any) -> str:
    from torsio.plugins import bit_law_origin

    name = getattr(law, "name", "") or type(law).__name__
    try:
        origin = bit_law_origin(name)
    except Exception:  # naming must never hide the error being reported
        return repr(name)
    return f"{name!r} ({origin})"


def system_from_config(
    config: Config,
    wob: Any = None,
    rpm: Any = None,
    discretization: Mapping[str, Any] | None = None,
) -> System:
    """The System of a configuration at an operating point (overriding ``[operation]``).

    ``wob`` [N] and ``rpm`` may be numbers or strings with units (``"100 kN"``,
    ``"120 rpm"``). Without them, the file's ``[operation]`` values are used; a
    clear error names the key if neither gives one.
    """
    from torsio.io.config import parse_rpm
    from torsio.units import to_si

    if wob is None:
        wob = config.operation.wob
        if wob is None:
            raise ConfigError(
                "operation.wob",
                "no weight on bit: give one (e.g. --wob '100 kN') or set it in "
                "the [operation] table",
            )
    else:
        text = wob
        wob = to_si(wob, "force", key="wob")
        if wob < 0:
            raise ConfigError("wob", f"expected a non-negative weight on bit, got {text!r}")
    if rpm is None:
        rpm = config.operation.rpm
        if rpm is None:
            raise ConfigError(
                "operation.rpm",
                "no rotary speed: give one (e.g. --rpm 120) or set it in the [operation] table",
            )
    else:
        rpm = parse_rpm(rpm, "rpm")
    options = {k: v for k, v in (discretization or {}).items() if v is not None}
    return System.from_config(config, **options).at(wob=wob, rpm=rpm)


def simulate_config(
    config: Config,
    wob: Any = None,
    rpm: Any = None,
    *,
    discretization: Mapping[str, Any] | None = None,
    **overrides: Any,
) -> TransientResults:
    """Simulate a configuration: its System, its ``[simulation]`` options, ``overrides`` on top.

    Parameters
    ----------
    config : Config
    wob, rpm : float or str, optional
        Operating point overriding ``[operation]`` (weight on bit [N] or with
        units; rotary speed [rpm] or with units).
    discretization : mapping, optional
        Options overriding ``[discretization]`` (``strategy``, ``dp_elements``, ...).
    **overrides
        Options of :func:`simulate` overriding ``[simulation]`` (``None`` ignored),
        plus ``initial_state``.

    Examples
    --------
    >>> from torsio.io.config import builtin_config
    >>> results = simulate_config(builtin_config(), wob="175 kN", rpm=100,
    ...                           discretization={"strategy": "A"})
    >>> round(results.severity, 3)
    1.099
    """
    initial_state = overrides.pop("initial_state", None)
    options = SimulationOptions.from_config(config).replace(**overrides)
    system = system_from_config(config, wob, rpm, discretization)
    return simulate(system, initial_state=initial_state, **options.kwargs())
