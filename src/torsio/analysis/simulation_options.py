"""Options of the transient analyzer (the ``[simulation]`` table), validated.

Every field has the meaning of the :func:`torsio.analysis.transient.simulate`
argument of the same name; defaults shared with the other analyzers live in
:mod:`torsio.analysis.severity`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np
import scipy.integrate

from torsio.analysis.budget import check_rtol
from torsio.errors import ConfigError

if TYPE_CHECKING:  # read, never imported: torsio.config sits above the analyzers
    from torsio.config.configuration import Config

__all__ = [
    "COMPILED_METHODS",
    "IMPLICIT_METHODS",
    "METHODS",
    "MIN_WINDOW_SAMPLES",
    "SINGLE_RUN_ATOL",
    "SINGLE_RUN_RTOL",
    "SimulationOptions",
    "check_window_samples",
]

COMPILED_METHODS = ("auto", "RODAS4")
"""``"auto"``: the compiled RODAS4 engine where it can run the System, else LSODA;
``"RODAS4"``: the compiled engine only."""

METHODS = (*COMPILED_METHODS, "LSODA", "RK45", "RK23", "DOP853", "Radau", "BDF")
"""The integrators accepted by name: the compiled engine's, then ``scipy.integrate.solve_ivp``'s."""

IMPLICIT_METHODS = ("Radau", "BDF")
"""Methods that take the (sparse) Jacobian."""

MIN_WINDOW_SAMPLES = 10
"""Fewest output samples the steady-state window may hold."""

SINGLE_RUN_RTOL, SINGLE_RUN_ATOL = 1e-6, 1e-9
"""A single run's default tolerances (relative; absolute in rad, rad/s); a batch's are
:data:`torsio.solvers.batch_options.DEFAULT_RTOL` and ``DEFAULT_ATOL``."""


def check_window_samples(
    window: float,
    output_step: float | None,
    time_step: float = 0.0,
    window_given: bool = True,
    duration: float | None = None,
) -> None:
    """ConfigError unless the steady window holds :data:`MIN_WINDOW_SAMPLES` samples.

    ``output_step`` [s] samples the window (None: none, as in a map, which reads S_SS
    from every step). ``time_step`` [s] is the finest sampling a run has (the wave
    model's grid step): a window shorter than :data:`MIN_WINDOW_SAMPLES` of them cannot
    be sampled finer, and the error names the window, or the run length ``duration``
    when the window was not given (half the run by default).

    Examples
    --------
    >>> check_window_samples(10.0, 0.5)
    >>> check_window_samples(1e-6, 0.04, time_step=1.4e-3)
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: simulation.steady_window: the steady window (1e-06 s) holds ...
    """
    if window < MIN_WINDOW_SAMPLES * time_step * (1.0 - 1e-9):
        shortest = MIN_WINDOW_SAMPLES * time_step
        if window_given or duration is None:
            raise ConfigError(
                "simulation.steady_window",
                f"the steady window ({window:g} s) holds fewer than {MIN_WINDOW_SAMPLES} time "
                f"steps of the grid ({time_step:g} s each); expected a window of at least "
                f"{shortest:g} s",
            )
        raise ConfigError(
            "simulation.duration",
            f"a run of {duration:g} s leaves a steady window (by default half the run, "
            f"{window:g} s) of fewer than {MIN_WINDOW_SAMPLES} time steps of the grid "
            f"({time_step:g} s each); expected a run of at least {2.0 * shortest:g} s, or "
            "give the window (--window, simulation.steady_window)",
        )
    if output_step is not None and output_step > window / MIN_WINDOW_SAMPLES:
        raise ConfigError(
            "simulation.output_step",
            f"the output step ({output_step:g} s) leaves fewer than {MIN_WINDOW_SAMPLES} "
            f"samples in the steady window ({window:g} s); expected a step of at most "
            f"{window / MIN_WINDOW_SAMPLES:g} s",
        )


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
    method: Any = attrs.field(default="auto", converter=_check_method)
    rtol: float = attrs.field(
        default=SINGLE_RUN_RTOL, converter=lambda v: check_rtol(v, "simulation.rtol")
    )
    atol: float = attrs.field(
        default=SINGLE_RUN_ATOL, converter=lambda v: _positive("atol", v, "a positive tolerance")
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
