"""The probability of severe stick-slip over a map, from a fit's uncertainty (Monte Carlo).

Each sample draws the fitted parameters from a joint normal distribution: the fitted
values, each parameter's stated sigma, and the correlation between them from the fit's
Jacobian (:class:`~torsio.calibration.fit_results.FitResults`; independent where the fit
gives none), each draw kept within its two-sigma interval and at least its lower bound; a
parameter the data do not pin down is drawn uniformly over the whole interval they allow,
and one the user fixes is held there (:func:`parameter_draws`);
the configuration with those values runs a severity map
(:func:`torsio.analysis.maps.severity_map`, on any of its executors), and the probability
of severe stick-slip at a point is the fraction of samples whose S_SS there exceeds the
map's ``threshold``. Parameters that trade against each other in the fit (a static and a
dynamic friction factor read from the same torque) move together in the draws.

Examples
--------
>>> import numpy as np
>>> severe_fraction(np.array([[[0.2, 1.0]], [[0.9, 1.2]]]), threshold=0.8).tolist()
[[0.5, 1.0]]
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import attrs
import numpy as np

from torsio.analysis.maps import severity_map
from torsio.calibration.parameters import SystemFamily
from torsio.errors import ConfigError

if TYPE_CHECKING:
    from torsio.analysis.map_options import MapOptions
    from torsio.calibration.fit_results import FitResults
    from torsio.config.configuration import Config

__all__ = [
    "SeverityProbability",
    "distribution",
    "parameter_draws",
    "severe_fraction",
    "severity_probability",
]


def severe_fraction(severity: np.ndarray, threshold: float) -> np.ndarray:
    """Fraction of the samples (axis 0) with S_SS above ``threshold`` (NaN: a failed
    point, left out of its point's count)."""
    severity = np.asarray(severity, dtype=float)
    valid = np.isfinite(severity)
    severe = valid & (severity > threshold)
    counts = valid.sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(counts > 0, severe.sum(axis=0) / np.maximum(counts, 1), np.nan)


@attrs.frozen(eq=False)
class SeverityProbability:
    """Monte Carlo severity maps over a fit's distribution.

    Attributes
    ----------
    wob : ndarray, shape (m,)
        Weights on bit [N].
    rpm : ndarray, shape (n,)
        Rotary speeds [rpm].
    probability : ndarray, shape (n, m)
        Fraction of the samples severe at ``rpm[i]``, ``wob[j]``.
    severity : ndarray, shape (k, n, m)
        S_SS of every sample.
    samples : tuple of dict
        The parameter values of each sample.
    threshold : float
        S_SS above which a point is severe.
    distribution : dict of str to str
        How each parameter was drawn (:func:`distribution`).
    """

    wob: np.ndarray
    rpm: np.ndarray
    probability: np.ndarray
    severity: np.ndarray
    samples: tuple[dict[str, float], ...]
    threshold: float
    distribution: dict[str, str] = attrs.field(factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """Plain data: ``wob``, ``rpm``, ``probability`` (``[i][j]`` at ``rpm[i]``,
        ``wob[j]``), ``severity`` per sample, ``samples``, ``threshold``, ``distribution``."""
        return {
            "wob": self.wob.tolist(),
            "rpm": self.rpm.tolist(),
            "probability": self.probability.tolist(),
            "severity": self.severity.tolist(),
            "samples": [dict(s) for s in self.samples],
            "threshold": self.threshold,
            "distribution": dict(self.distribution),
        }


def parameter_draws(
    fit: Any, family: Any, count: int, seed: int, fixed: Mapping[str, float] | None = None
) -> list[dict[str, float]]:
    """``count`` draws of the fitted parameters (module documentation).

    An identifiable parameter: a standard normal correlated with the other identifiable
    ones by the Cholesky factor of the fit's correlation, scaled by its sigma, kept within
    its two-sigma interval. A parameter the data do not pin down (``identifiable`` false):
    uniform over the interval the data allow, independent of the others, since a normal
    around a point the data did not choose would claim a knowledge they do not give. A
    parameter in ``fixed``: that value in every draw (the user's choice).
    """
    fixed = dict(fixed or {})
    for name, value in fixed.items():
        if name not in fit.names:
            raise ConfigError(
                "fixed", f"{name!r} was not fitted; expected one of {', '.join(fit.names)}"
            )
        floor = family.lower_bound(name)
        if not (isinstance(value, int | float) and np.isfinite(value) and value >= floor):
            raise ConfigError(f"fixed.{name}", f"expected a finite value >= {floor}, got {value!r}")
    rng = np.random.default_rng(seed)
    spreads = dict(zip(fit.names, fit.uncertainty, strict=True))
    normal = [k for k, n in enumerate(fit.names) if n not in fixed and spreads[n].identifiable]
    correlation = getattr(fit, "correlation", None)
    if correlation is None:
        correlation = np.eye(len(fit.names))
    kept = np.asarray(correlation, dtype=float)[np.ix_(normal, normal)]
    eigenvalues, vectors = np.linalg.eigh(kept)
    factor = vectors * np.sqrt(np.maximum(eigenvalues, 0.0))  # factor @ factor.T = kept
    draws = []
    for _ in range(count):
        normals = dict(zip(normal, factor @ rng.normal(size=len(normal)), strict=True))
        values = {}
        for k, (name, value) in enumerate(zip(fit.names, fit.values, strict=True)):
            low, high = spreads[name].interval
            if name in fixed:
                drawn = float(fixed[name])
            elif k in normals:
                drawn = float(np.clip(value + spreads[name].sigma * normals[k], low, high))
            else:
                drawn = float(rng.uniform(low, high))
            values[name] = max(drawn, family.lower_bound(name))
        draws.append(values)
    return draws


def distribution(fit: Any, fixed: Mapping[str, float] | None = None) -> dict[str, str]:
    """How :func:`parameter_draws` draws each parameter, in words."""
    fixed = dict(fixed or {})
    said = {}
    for name, value, spread in zip(fit.names, fit.values, fit.uncertainty, strict=True):
        low, high = spread.interval
        if name in fixed:
            said[name] = f"fixed at {fixed[name]:.6g}"
        elif spread.identifiable:
            said[name] = f"normal {value:.6g} +- {spread.sigma:.2g}, within [{low:.6g}, {high:.6g}]"
        else:
            said[name] = f"uniform over [{low:.6g}, {high:.6g}] (not identifiable)"
    return said


def severity_probability(
    config: Config,
    fit: FitResults,
    wob: Any,
    rpm: Any,
    options: MapOptions | None = None,
    *,
    samples: int = 16,
    seed: int = 0,
    executor: Any = None,
    fixed: Mapping[str, float] | None = None,
    **values: Any,
) -> SeverityProbability:
    """The probability of severe stick-slip over ``rpm`` x ``wob`` from ``fit``.

    Parameters
    ----------
    config : Config
        The configuration the fit was made on (run on the wave model).
    fit : FitResults
        Fitted values and their one-sigma uncertainties.
    wob, rpm : array_like
        The map's axes [N], [rpm] (as :func:`~torsio.analysis.maps.severity_map`).
    options : MapOptions, optional
        How every map runs (:class:`~torsio.analysis.map_options.MapOptions`), as for
        :func:`~torsio.analysis.maps.severity_map`; ``**values`` change its fields.
    samples : int
        Number of Monte Carlo samples (each one map).
    seed : int
        Seed of the draws (the result is reproducible).
    executor
        Any executor :func:`~torsio.analysis.maps.severity_map` takes.
    fixed : mapping of str to float, optional
        Values to hold fitted parameters at (a parameter the data do not pin down is
        otherwise drawn over the whole interval they allow: :func:`parameter_draws`).
    """
    if isinstance(samples, bool) or not isinstance(samples, int | np.integer) or samples < 1:
        raise ConfigError("samples", f"expected a whole number of samples >= 1, got {samples!r}")
    family = SystemFamily(config)
    draws = parameter_draws(fit, family, int(samples), seed, fixed)
    maps = [
        severity_map(
            family.system(draw), wob, rpm, options, executor=executor, progress=False, **values
        )
        for draw in draws
    ]
    severity = np.stack([m.severity for m in maps])
    threshold = float(maps[0].threshold)
    return SeverityProbability(
        wob=np.asarray(maps[0].wob),
        rpm=np.asarray(maps[0].rpm),
        probability=severe_fraction(severity, threshold),
        severity=severity,
        samples=tuple(draws),
        threshold=threshold,
        distribution=distribution(fit, fixed),
    )
