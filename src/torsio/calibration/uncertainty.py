"""How well a fit pins its parameters down: the statistics of the misfit, the spread
between recordings and the grid.

With residuals r (n of them, p parameters) and their Jacobian J at the best fit:

* the residual variance is s^2 = |r|^2 / (n - p), times the residual's integrated
  correlation time tau = 1 + 2 sum_k rho_k (in samples, summed while the autocorrelation
  rho_k is positive): a residual that is not white noise carries fewer independent samples
  than it has (n / tau of them);
* one standard deviation from the Jacobian: sqrt(diag(s^2 tau (J^T J)^-1));
* the profile (:mod:`torsio.calibration.profile`): chi^2(t) = (S(t) - S_min) / (s^2 tau)
  along the path on which parameter k moves by t and the others follow their conditional
  best values; where chi^2 = 1 and 4 are the statistical one- and two-sigma bounds. Where
  the profile's one-sigma half-width and the Jacobian's differ by more than
  :data:`SMOOTH_TOLERANCE`, the misfit is not smooth there and the larger of the two is the
  statistical sigma;
* the model-form part: the standard deviation of the recordings' own values (each
  recording's least misfit along the path; none with one recording);
* the discretization part: how far the least misfit against a twin grid's torque lies
  from the fit (the larger of the finer and the coarser twin);
* the speed record's part: likewise against the top held at the smoothed recorded speed
  (the record's noise on the speed is not motion of the top);
* the stated sigma is the four in quadrature, and the two-sigma interval is the
  statistical one widened on each side by twice the other three in quadrature, within the
  admissible range; no sigma is stated below :data:`RESOLUTION` times the value.

A parameter is **not identifiable** from the data when the statistical two-sigma interval
reaches an end of its admissible range (the profile is flat up to it: the data allow
anything beyond) or the interval's half-width exceeds :data:`WEAK_FRACTION` of its value.

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

from collections.abc import Sequence
from typing import Any

import attrs
import numpy as np

from torsio.calibration.parameters import TWIN_GRIDS
from torsio.calibration.profile import Profile, Twins, profile_parameter

__all__ = [
    "INTERVAL_METHODS",
    "ParameterSpread",
    "correlation_time",
    "jacobian_correlation",
    "parameter_uncertainty",
    "residual_scale",
    "rough_misfit",
]

SMOOTH_TOLERANCE = 0.3
WEAK_FRACTION = 0.25
RESOLUTION = 1e-4
"""The least relative sigma stated: the model's own resolution against a record. Measured:
with the top held at the recorded speed, linear between samples 0.01 s apart, the model
misses a record it made itself by 0.6 N m RMS, and mu_s fits 2e-5 (6e-5 relative) off."""


INTERVAL_METHODS = {
    "profile": (
        "profile: where the misfit along the parameter (the others at their conditional best "
        "values) rises by 4 s^2 tau from its least, s^2 the residual variance and tau the "
        "residuals' integrated correlation time (n / tau independent samples), widened by "
        "twice the spread between the recordings' own values, twice the larger shift a grid "
        "of a quarter or of twice the time step makes (discretization) and twice the shift the "
        "smoothed speed record makes, in quadrature"
    ),
    "jacobian": (
        "jacobian: the value +- 2 sqrt(s^2 tau (J^T J)^-1), s^2 the residual variance and tau "
        "the residuals' integrated correlation time (n / tau independent samples); no "
        "model-form or discretization part (not profiled)"
    ),
}
"""How a two-sigma interval was found, by its kind (``ParameterSpread.interval_method``)."""


@attrs.frozen
class ParameterSpread:
    """The uncertainty of one fitted parameter (units of the parameter).

    Attributes
    ----------
    sigma : float
        The stated one standard deviation (the parts below in quadrature).
    sigma_jacobian, sigma_profile : float
        From the Jacobian, and the profile's one-sigma half-width (NaN: not profiled).
    interval : tuple of float
        The two-sigma interval the data allow.
    method : str
        ``"jacobian"`` (the misfit is smooth there) or ``"profile"``: which gave the
        statistical part.
    identifiable : bool
        False: the data do not pin it down (module documentation).
    sigma_recordings : float
        The model-form part: the spread of the recordings' own values (0: one recording
        or not profiled).
    sigma_grid : float
        The discretization part: the larger shift a finer or a coarser grid makes (0: not
        profiled).
    sigma_speed_record : float
        The speed record's part: the shift the top held at the smoothed recorded speed
        makes (0: not profiled, or the configured top drive).
    recording_values : tuple of float
        Each recording's own value (empty: not profiled).
    profile : Profile or None
        The misfit along the parameter (:mod:`torsio.calibration.profile`).
    """

    sigma: float
    sigma_jacobian: float
    sigma_profile: float
    interval: tuple[float, float]
    method: str
    identifiable: bool
    sigma_recordings: float = 0.0
    sigma_grid: float = 0.0
    sigma_speed_record: float = 0.0
    recording_values: tuple[float, ...] = ()
    profile: Profile | None = attrs.field(default=None, eq=False, repr=False)

    @property
    def interval_method(self) -> str:
        """How :attr:`interval` was found (:data:`INTERVAL_METHODS`): from the profile of
        the misfit when it was profiled, else from the Jacobian."""
        return INTERVAL_METHODS["profile" if np.isfinite(self.sigma_profile) else "jacobian"]

    @property
    def sigma_statistical(self) -> float:
        """The statistical part of :attr:`sigma` (the misfit's curvature or profile)."""
        rest = self.sigma_recordings**2 + self.sigma_grid**2 + self.sigma_speed_record**2
        return float(np.sqrt(max(self.sigma**2 - rest, 0.0)))


def rough_misfit(name: str, value: float, spread: ParameterSpread) -> str | None:
    """What a fit says when its own profile found a better value more than the stated
    sigma away (None otherwise): the misfit is rough at the scale of the model's grid (the
    break-free moment moves by whole time steps), so the fit stopped in one of its dips and
    the stated sigma, which assumes a smooth bowl, may not hold the truth.

    Measured on the RGD deviated well's start-ups (docs/calibration.md): on its default
    grid (3.9e-3 s) mu_s fits 0.3194 with sigma 0.0014 while its profile is least at
    0.3215, and the truth 0.33 lies outside the interval; on half that step the profile's
    least is 0.0004 from the fit (sigma 0.0068), and the interval holds the truth.

    >>> spread = ParameterSpread(0.0014, 0.0002, 0.0, (0.3167, 0.3221), "profile", True)
    >>> profile = Profile(np.array([0.3194, 0.3215]), np.array([6.6, 0.0]), (), {}, False, False)
    >>> rough_misfit("friction_static", 0.3194, attrs.evolve(spread, profile=profile))[:60]
    'friction_static: its profile is least at 0.3215, 0.0021 from'
    """
    profile = spread.profile
    if profile is None or profile.values.size == 0:
        return None
    least_value = float(profile.values[int(np.argmin(profile.chi2))])
    if abs(least_value - value) <= spread.sigma:
        return None
    return (
        f"{name}: its profile is least at {least_value:.4g}, {abs(least_value - value):.2g} "
        f"from the fitted {value:.4g}, farther than its sigma {spread.sigma:.2g}: the misfit "
        "is rough at the scale of the model's grid and the interval may not hold the truth; "
        "fit on a finer grid (a smaller --time-step on the wave model, more elements on a "
        "lumped strategy)"
    )


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


def residual_scale(parts: Sequence[np.ndarray], count: int) -> float:
    """s^2 tau [N^2 m^2], the unit of chi^2: the residual variance of ``parts`` (one array
    per recording) with ``count`` fitted parameters, times their correlation time (averaged
    over the recordings, weighted by their lengths)."""
    r = np.concatenate(parts)
    tau = float(np.average([correlation_time(x) for x in parts], weights=[x.size for x in parts]))
    return max(float(np.dot(r, r)) / max(r.size - count, 1), 1e-12) * tau


def _crossing(values: np.ndarray, chi2: np.ndarray, centre: float, level: float) -> list[Any]:
    """The distances from ``centre`` below and above it where chi^2 first reaches
    ``level`` (linear in sqrt(chi^2) between points; None: not reached)."""
    found: list[Any] = []
    for side in (values < centre, values > centre):
        points = sorted(zip(np.abs(values[side] - centre), chi2[side], strict=True))
        previous = (0.0, 0.0)
        distance = None
        for t, c in points:
            if c >= level:
                a, b = np.sqrt(max(previous[1], 0.0)), np.sqrt(c)
                fraction = (np.sqrt(level) - a) / (b - a) if b > a else 1.0
                distance = float(previous[0] + fraction * (t - previous[0]))
                break
            previous = (t, c)
        found.append(distance)
    return found


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
    misfit: Any,
    best: np.ndarray,
    jacobian: np.ndarray,
    parts: Sequence[np.ndarray],
    *,
    bounds: tuple[np.ndarray, np.ndarray],
    profile: bool = True,
    twins: Twins = (),
) -> tuple[ParameterSpread, ...]:
    """The spread of every parameter of a least-squares fit (module documentation).

    ``misfit`` is the fit's :class:`~torsio.calibration.objectives.Misfit`; ``parts`` are
    the residuals at ``best`` per recording (their correlation times are averaged,
    weighted by their lengths); ``bounds`` the admissible (lower, upper) values; ``twins``
    the twins of the model (:mod:`torsio.calibration.profile`).
    """
    p = best.size
    scale = residual_scale(parts, p)
    covariance = np.linalg.pinv(jacobian.T @ jacobian) * scale
    sigma_j = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    spreads = []
    for k in range(p):
        floor = RESOLUTION * abs(best[k])
        if not profile:
            spreads.append(_jacobian_spread(float(best[k]), float(sigma_j[k]), bounds, k))
            continue
        path = np.zeros(p)
        path[k] = 1.0
        if covariance[k, k] > 0.0:
            path = covariance[:, k] / covariance[k, k]
        along = profile_parameter(
            misfit, best, path, k, bounds, scale, max(float(sigma_j[k]), floor), twins
        )
        spreads.append(_spread(float(best[k]), float(sigma_j[k]), along, bounds, k))
    return tuple(spreads)


def _jacobian_spread(
    value: float, sigma_j: float, bounds: tuple[np.ndarray, np.ndarray], k: int
) -> ParameterSpread:
    sigma_j = max(sigma_j, RESOLUTION * abs(value))
    interval = (max(value - 2 * sigma_j, bounds[0][k]), min(value + 2 * sigma_j, bounds[1][k]))
    weak = not np.isfinite(sigma_j) or 2 * sigma_j > WEAK_FRACTION * abs(value)
    return ParameterSpread(sigma_j, sigma_j, np.nan, interval, "jacobian", not weak)


def _spread(
    value: float,
    sigma_j: float,
    along: Profile,
    bounds: tuple[np.ndarray, np.ndarray],
    k: int,
) -> ParameterSpread:
    floor = RESOLUTION * abs(value)
    sigma_j = max(sigma_j, floor)
    low_end, high_end = value - along.values[0], along.values[-1] - value
    ones = _crossing(along.values, along.chi2, value, 1.0)
    twos = _crossing(along.values, along.chi2, value, 4.0)
    one = [o if o is not None else e for o, e in zip(ones, (low_end, high_end), strict=True)]
    two = [t if t is not None else e for t, e in zip(twos, (low_end, high_end), strict=True)]
    sigma_p = float(np.mean(one))
    smooth = abs(sigma_p - sigma_j) <= SMOOTH_TOLERANCE * sigma_j
    statistical = max(sigma_j if smooth else max(sigma_p, sigma_j), floor)
    recordings = along.recording_values
    form = float(np.std(recordings, ddof=1)) if len(recordings) > 1 else 0.0
    shifts = {name: abs(v - value) for name, v in along.twin_values.items()}
    grid = max((shifts[name] for name in TWIN_GRIDS if name in shifts), default=0.0)
    speed = shifts.get("smoothed speed", 0.0)
    widening = 4.0 * (form**2 + grid**2 + speed**2)
    low = value - np.sqrt(max(two[0], 2 * floor) ** 2 + widening)
    high = value + np.sqrt(max(two[1], 2 * floor) ** 2 + widening)
    interval = (float(max(low, bounds[0][k])), float(min(high, bounds[1][k])))
    open_ended = along.open_low or along.open_high or None in twos
    weak = open_ended or (interval[1] - interval[0]) / 2 > WEAK_FRACTION * abs(value)
    return ParameterSpread(
        float(np.sqrt(statistical**2 + form**2 + grid**2 + speed**2)),
        float(sigma_j),
        sigma_p,
        interval,
        "jacobian" if smooth else "profile",
        not weak,
        sigma_recordings=form,
        sigma_grid=float(grid),
        sigma_speed_record=float(speed),
        recording_values=tuple(float(v) for v in recordings),
        profile=along,
    )
