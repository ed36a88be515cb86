"""Options of a severity map, validated once, each with its command-line flag.

:class:`MapOptions` is what :func:`torsio.analysis.maps.severity_map` and
:func:`~torsio.analysis.maps.dimensionless_map` run with. It is frozen and checks every
value on construction, so that the engine, the bisection and the executors take it as
given. Each field keeps the ``torsio map`` flag and the configuration key that set it
(:meth:`MapOptions.flag`), so an error raised for an option names the flag on the
command line and the keyword in Python, without a table of names in the CLI.

Examples
--------
>>> MapOptions(refine=2).refine
2
>>> MapOptions(refine=-1)
Traceback (most recent call last):
...
torsio.errors.ConfigError: refine: expected a whole number of bisection steps in 0..40, got -1
>>> MapOptions.flag("rtol")
'--rtol (simulation.rtol)'
"""

from __future__ import annotations

import math
from typing import Any

import attrs

from torsio.analysis.budget import check_rtol
from torsio.analysis.map_results import STICK_SLIP_THRESHOLD
from torsio.analysis.severity import SEVERE_THRESHOLD
from torsio.errors import ConfigError
from torsio.solvers.batch_options import DEFAULT_ATOL, DEFAULT_RTOL
from torsio.solvers.batch_results import DEFAULT_STEADY_TOLERANCE, check_steady_tolerance

__all__ = ["DEFAULT_REFINE", "MapOptions"]

DEFAULT_REFINE = 4
"""Bisection steps per critical-WOB cell: the bracket shrinks 16 times."""


def _number(key: str, value: Any, low: float, what: str, strict: bool = False) -> float:
    ok = isinstance(value, int | float) and not isinstance(value, bool)
    if not ok or not math.isfinite(value) or value < low or (strict and value == low):
        raise ConfigError(key, f"expected {what}, got {value!r}")
    return float(value)


def _whole(key: str, value: Any, low: int, high: int, what: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ConfigError(key, f"expected {what}, got {value!r}")
    return int(value)


def _optional(check: Any) -> Any:
    return lambda value: None if value is None else check(value)


def _option(
    default: Any,
    converter: Any,
    flag: str | None = None,
    key: str | None = None,
    help: str | None = None,
    choices: tuple[str, ...] | None = None,
) -> Any:
    """A field with its ``torsio map`` flag, its configuration key, the flag's help (the
    default is added to it) and its choices: the CLI adds the flag from these."""
    metadata = {"flag": flag, "key": key, "help": help, "choices": choices}
    return attrs.field(default=default, converter=converter, metadata=metadata)


@attrs.frozen
class MapOptions:
    """How every point of a map runs and how the map reads them.

    Attributes
    ----------
    duration, steady_window : float or None
        Run length and steady window of every run [s]; None: 40 and 15 first-mode
        periods (:mod:`torsio.analysis.severity`), the window at most half a given run.
    threshold : float
        S_SS above which a point is severe (the paper's 0.8).
    stick_slip_threshold : float
        S_SS above which a point is a sustained oscillation, at most ``threshold``.
    refine : int
        Bisection steps of each critical-WOB cell (extra runs per rpm), 0..40.
    rtol, atol : float
        Tolerances of the batch engine.
    engine : str
        Batch engine (:func:`torsio.solvers.batch.simulate_batch`): ``"auto"`` picks.
    steady_tolerance : float
        A run ends once its motion is on a steady cycle within this S_SS, in [0, 0.1]
        (0: every run to the end; :mod:`torsio.solvers.cycles`).
    on_failure : {"raise", "mark"}
        On points the solver failed on: raise naming them, or keep them as NaN.
    retries : int
        Resubmissions of a chunk whose worker died, 0..100.
    timeout : float or None
        Seconds to wait for a Dask scheduler (None: the sweep's default).
    chunk_size : int or None
        Grid points per task (None: about four tasks per worker).
    """

    duration: float | None = _option(
        None,
        _optional(lambda v: _number("duration", v, 0.0, "a positive time in s", strict=True)),
        "--duration",
        "simulation.duration",
    )
    steady_window: float | None = _option(
        None,
        _optional(lambda v: _number("steady_window", v, 0.0, "a positive time in s", True)),
        "--window",
        "simulation.steady_window",
    )
    threshold: float = _option(
        SEVERE_THRESHOLD,
        lambda v: _number("threshold", v, 0.0, "a non-negative number"),
        "--threshold",
        help="S_SS above which a point is severe",
    )
    stick_slip_threshold: float = _option(
        STICK_SLIP_THRESHOLD,
        lambda v: _number("stick_slip_threshold", v, 0.0, "a non-negative number"),
    )
    refine: int = _option(
        DEFAULT_REFINE,
        lambda v: _whole("refine", v, 0, 40, "a whole number of bisection steps in 0..40"),
        "--refine",
        help="bisection steps of the critical weight on bit",
    )
    rtol: float = _option(
        DEFAULT_RTOL,
        lambda v: check_rtol(v, "rtol"),
        "--rtol",
        "simulation.rtol",
        help="relative tolerance of the batch engine",
    )
    atol: float = _option(
        DEFAULT_ATOL,
        lambda v: _number("atol", v, 0.0, "a positive tolerance", strict=True),
        None,
        "simulation.atol",
    )
    engine: str = _option("auto", str, "--engine", help="batch engine: auto, numba, numpy or scipy")
    steady_tolerance: float = _option(
        DEFAULT_STEADY_TOLERANCE,
        check_steady_tolerance,
        "--steady-tol",
        help="end a run once it is on a steady cycle, within this S_SS (0 runs every point "
        "to the end)",
    )
    on_failure: str = _option(
        "raise",
        str,
        "--on-failure",
        help="points the solver fails on: stop with an error (raise) or keep the others "
        "and mark them failed (mark)",
        choices=("raise", "mark"),
    )
    retries: int = _option(
        2, lambda v: _whole("retries", v, 0, 100, "a whole number of resubmissions in 0..100")
    )
    timeout: float | None = _option(
        None,
        _optional(lambda v: _number("timeout", v, 0.0, "a positive time in s", strict=True)),
        "--timeout",
        help="seconds to wait for the Dask scheduler (default 10)",
    )
    chunk_size: int | None = _option(
        None, _optional(lambda v: _whole("chunk_size", v, 1, 2**62, "a whole number >= 1"))
    )

    def __attrs_post_init__(self) -> None:
        if self.stick_slip_threshold > self.threshold:
            raise ConfigError(
                "stick_slip_threshold",
                f"expected at most the severe threshold ({self.threshold:g}), got "
                f"{self.stick_slip_threshold!r}",
            )
        if self.on_failure not in ("raise", "mark"):
            raise ConfigError("on_failure", f"expected 'raise' or 'mark', got {self.on_failure!r}")

    @classmethod
    def of(cls, options: MapOptions | None, values: dict[str, Any]) -> MapOptions:
        """``options`` (default: the defaults) with the keyword ``values`` on top.

        An unknown keyword is a ConfigError naming it and listing the options.
        """
        base = cls() if options is None else options
        if not isinstance(base, cls):
            raise ConfigError("options", f"expected MapOptions, got {type(base).__name__}")
        names = attrs.fields_dict(cls)
        unknown = sorted(set(values) - set(names))
        if unknown:
            raise ConfigError(unknown[0], f"unknown option; expected one of {', '.join(names)}")
        return attrs.evolve(base, **values) if values else base

    @classmethod
    def flag(cls, name: str) -> str:
        """How the command line names option ``name`` (a field or its configuration key):
        its flag, and the configuration key that also sets it; ``name`` for other names.

        >>> MapOptions.flag("steady_tolerance"), MapOptions.flag("atol")
        ('--steady-tol', 'simulation.atol')
        >>> MapOptions.flag("simulation.steady_window"), MapOptions.flag("wob")
        ('--window (simulation.steady_window)', 'wob')
        """
        fields = attrs.fields(cls)
        field = next((f for f in fields if name in (f.name, f.metadata["key"])), None)
        if field is None:
            return name
        flag, key = field.metadata["flag"], field.metadata["key"]
        if flag and key:
            return f"{flag} ({key})"
        return str(flag or key or name)

    def batch_options(self, duration: float, steady_window: float, threads: int | None) -> Any:
        """The :class:`torsio.solvers.batch_options.BatchOptions` of the points: the run
        length and window [s] the map resolved, the threads of each batch."""
        from torsio.solvers.batch_options import BatchOptions

        return BatchOptions(
            duration=duration,
            steady_window=steady_window,
            rtol=self.rtol,
            atol=self.atol,
            engine=self.engine,
            threads=threads,
            steady_tolerance=self.steady_tolerance,
        )
