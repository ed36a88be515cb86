"""How well a fit pins its parameters down: the Jacobian and a profile of the misfit.

With residuals r (n of them, p parameters) and their Jacobian J at the best fit:

* the residual variance is s^2 = |r|^2 / (n - p), times the residual's integrated
  correlation time tau = 1 + 2 sum_k rho_k (in samples, summed while the autocorrelation
  rho_k is positive): a residual that is not white noise (a model error, a slow drift)
  carries fewer independent samples than it has;
* one standard deviation from the Jacobian: sqrt(diag(s^2 tau (J^T J)^-1));
* the profile: the misfit chi^2(t) = (|r(p(t))|^2 - |r_min|^2) / (s^2 tau) along the path
  p(t) on which parameter k moves by t and the others follow their conditional best
  values (linearized: the k-th column of (J^T J)^-1 scaled to 1 in k); where chi^2 = 1 and
  4 are the one- and two-sigma bounds (the interval the data allow). Where the profile's
  one-sigma half-width and the Jacobian's differ by more than :data:`SMOOTH_TOLERANCE`,
  the misfit is not smooth there and the larger of the two is the stated sigma;
* no sigma is stated below :data:`RESOLUTION` times the value.

A parameter is **weakly identifiable** when its two-sigma interval is open (chi^2 stays
below 4 as far as the search went, :data:`PROFILE_DOUBLINGS` doublings of the step) or
wider than +-:data:`WEAK_FRACTION` of its value.

Examples
--------
>>> import numpy as np
>>> tau = correlation_time(np.random.default_rng(1).normal(size=4000))
>>> 0.8 < tau < 1.2   # white noise: every sample independent
True
>>> correlation_time(np.sin(np.linspace(0.0, 3.0, 4000))) > 100.0  # a slow model error
True
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import attrs
import numpy as np

__all__ = [
    "INTERVAL_METHODS",
    "ParameterSpread",
    "correlation_time",
    "jacobian_correlation",
    "parameter_uncertainty",
]

SMOOTH_TOLERANCE = 0.3
PROFILE_DOUBLINGS = 10
WEAK_FRACTION = 0.25
RESOLUTION = 1e-4
"""The least relative sigma stated: the model's own resolution against a record. Measured:
with the top held at the recorded speed, linear between samples 0.01 s apart, the model
misses a record it made itself by 0.6 N m RMS, and mu_s fits 2e-5 (6e-5 relative) off."""


INTERVAL_METHODS = {
    "profile": (
        "profile: where the misfit along the parameter (the others at their conditional best "
        "values) rises by 4 s^2 tau from its least, s^2 the residual variance and tau the "
        "residuals' integrated correlation time (n / tau independent samples)"
    ),
    "jacobian": (
        "jacobian: the value +- 2 sqrt(s^2 tau (J^T J)^-1), s^2 the residual variance and tau "
        "the residuals' integrated correlation time (n / tau independent samples)"
    ),
}
"""How a two-sigma interval was found, by its kind (``ParameterSpread.interval_method``)."""


@attrs.frozen
class ParameterSpread:
    """The uncertainty of one fitted parameter (units of the parameter).

    Attributes
    ----------
    sigma : float
        The stated one standard deviation.
    sigma_jacobian, sigma_profile : float
        From the Jacobian, and the profile's one-sigma half-width (NaN: not profiled).
    interval : tuple of float
        The two-sigma interval the data allow.
    method : str
        ``"jacobian"`` (the misfit is smooth there) or ``"profile"``.
    identifiable : bool
        False: weakly identifiable from the data (module documentation).
    """

    sigma: float
    sigma_jacobian: float
    sigma_profile: float
    interval: tuple[float, float]
    method: str
    identifiable: bool

    @property
    def interval_method(self) -> str:
        """How :attr:`interval` was found (:data:`INTERVAL_METHODS`): from the profile of
        the misfit when it was profiled, else from the Jacobian."""
        return INTERVAL_METHODS["profile" if np.isfinite(self.sigma_profile) else "jacobian"]


def correlation_time(residual: np.ndarray) -> float:
    """Integrated correlation time tau of a residual series [samples], >= 1."""
    r = np.asarray(residual, dtype=float) - np.mean(residual)
    n = r.size
    power = float(np.dot(r, r))
    if n < 3 or power == 0.0:
        return 1.0
    spectrum = np.fft.rfft(r, 2 * n)
    acf = np.fft.irfft(spectrum * np.conj(spectrum))[: n // 2] / power
    negative = np.flatnonzero(acf[1:] <= 0.0)
    end = int(negative[0]) + 1 if negative.size else acf.size
    return max(1.0, 1.0 + 2.0 * float(np.sum(acf[1:end])))


def _crossing(points: list[tuple[float, float]], level: float) -> float | None:
    """|t| where chi^2 first reaches ``level`` along one side (linear in sqrt(chi^2))."""
    previous = (0.0, 0.0)
    for t, chi2 in points:
        if chi2 >= level:
            a, b = np.sqrt(max(previous[1], 0.0)), np.sqrt(chi2)
            fraction = (np.sqrt(level) - a) / (b - a) if b > a else 1.0
            return abs(previous[0] + fraction * (t - previous[0]))
        previous = (t, chi2)
    return None


def jacobian_correlation(jacobian: np.ndarray) -> np.ndarray:
    """The correlation matrix of the fitted parameters from the Jacobian of the residuals:
    (J^T J)^-1 normalized by its diagonal (the residual variance cancels). A parameter the
    Jacobian does not see (a zero column) is uncorrelated with the others.

    >>> jacobian_correlation(np.array([[1.0, 0.0], [1.0, 1.0]])).round(6).tolist()
    [[1.0, -0.707107], [-0.707107, 1.0]]
    """
    covariance = np.linalg.pinv(jacobian.T @ jacobian)
    sigma = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    seen = sigma > 0.0
    correlation = np.eye(sigma.size)
    outer = np.outer(sigma, sigma)
    both = np.outer(seen, seen)
    correlation[both] = covariance[both] / outer[both]
    np.fill_diagonal(correlation, 1.0)
    return np.clip(correlation, -1.0, 1.0)


def parameter_uncertainty(
    misfit: Callable[[np.ndarray], np.ndarray],
    best: np.ndarray,
    jacobian: np.ndarray,
    parts: Sequence[np.ndarray],
    *,
    lower: np.ndarray,
    profile: bool = True,
) -> tuple[ParameterSpread, ...]:
    """The spread of every parameter of a least-squares fit (module documentation).

    ``misfit(x)`` gives the residual vector; ``parts`` are the residuals at ``best`` per
    recording (their correlation times are averaged, weighted by their lengths).
    """
    r = np.concatenate(parts)
    n, p = r.size, best.size
    rss = float(np.dot(r, r))
    tau = float(np.average([correlation_time(x) for x in parts], weights=[x.size for x in parts]))
    scale = max(rss / max(n - p, 1), 1e-12) * tau
    jtj = jacobian.T @ jacobian
    covariance = np.linalg.pinv(jtj) * scale
    sigma_j = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    spreads = []
    for k in range(p):
        path = np.zeros(p)
        path[k] = 1.0
        if covariance[k, k] > 0.0:
            path = covariance[:, k] / covariance[k, k]
        step = sigma_j[k] if sigma_j[k] > 0.0 else 1e-3 * abs(best[k]) + 1e-9
        sides: dict[float, list[tuple[float, float]]] = {-1.0: [], 1.0: []}
        if profile:
            for sign in sides:
                t = step
                for _ in range(PROFILE_DOUBLINGS + 1):
                    x = np.maximum(best + sign * t * path, lower)
                    chi2 = (float(np.sum(misfit(x) ** 2)) - rss) / scale
                    sides[sign].append((sign * t, chi2))
                    if chi2 >= 4.0 or x[k] <= lower[k]:
                        break
                    t *= 2.0
        spreads.append(_spread(best[k], sigma_j[k], sides, lower[k], profile))
    return tuple(spreads)


def _spread(
    value: float,
    sigma_j: float,
    sides: dict[float, list[tuple[float, float]]],
    lower: float,
    profiled: bool,
) -> ParameterSpread:
    sigma_j = max(sigma_j, RESOLUTION * abs(value))
    if not profiled:
        interval = (max(value - 2 * sigma_j, lower), value + 2 * sigma_j)
        weak = not np.isfinite(sigma_j) or 2 * sigma_j > WEAK_FRACTION * abs(value)
        return ParameterSpread(sigma_j, sigma_j, np.nan, interval, "jacobian", not weak)
    ones = [_crossing(points, 1.0) for points in sides.values()]
    twos = [_crossing(points, 4.0) for points in sides.values()]
    reach = [abs(points[-1][0]) for points in sides.values()]
    one = [o if o is not None else r for o, r in zip(ones, reach, strict=True)]
    two = [t if t is not None else r for t, r in zip(twos, reach, strict=True)]
    sigma_p = float(np.mean(one))
    smooth = abs(sigma_p - sigma_j) <= SMOOTH_TOLERANCE * max(sigma_j, 1e-300)
    floor = RESOLUTION * abs(value)
    sigma = max(sigma_j if smooth else max(sigma_p, sigma_j), floor)
    two = [max(t, 2.0 * floor) for t in two]
    interval = (max(value - two[0], lower), value + two[1])
    open_ended = any(t is None for t in twos)
    weak = open_ended or (interval[1] - interval[0]) / 2 > WEAK_FRACTION * abs(value)
    return ParameterSpread(
        float(sigma),
        float(sigma_j),
        sigma_p,
        (float(interval[0]), float(interval[1])),
        "jacobian" if smooth else "profile",
        not weak,
    )
