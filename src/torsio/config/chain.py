"""The ``[chain]`` table: a lumped model given directly (published models), not discretized.

A chain is inertias joined by springs (and dampers), node 1 just below the top drive
down to node n, the bit (see :meth:`torsio.model.lumped.LumpedModel.from_chain`). There
is no drill-string behind it, hence no exact continuum to compare with, no default bit
radius (``[bit_rock] radius`` is required) and no ``[discretization]``.

Examples
--------
>>> chain = parse_chain({"inertias": [2.0, "1 kg*m^2"], "stiffnesses": [100.0, 50.0]})
>>> chain.inertias, chain.stiffnesses
((2.0, 1.0), (100.0, 50.0))
>>> chain.model().equivalent_stiffness  # Eq. 9: 1 / (1/100 + 1/50)
33.33...
>>> parse_chain({"inertias": [2.0, 1.0], "stiffnesses": [100.0]})
Traceback (most recent call last):
...
torsio.errors.ConfigError: chain.stiffnesses: expected 2 values (one per inertia), got 1
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.units import to_si

MAX_FREQUENCY_SPREAD = 1e10
"""Largest (omega_n / omega_1)^2 of a chain (estimated, see :func:`frequency_spread`):
the eigenvalues of the chain are found to an absolute accuracy of about eps omega_n^2,
so omega_1^2 keeps about 6 digits (the integrator's rtol) up to this spread. The
Navarro-Lopez and Cortes (2007) chain has 19.6; a rigid link of 1e12 N m/rad on a
930 kg m^2 table, 8e9."""

CHAIN_KEYS = {"inertias", "stiffnesses", "dampings", "drag"}

_DIMENSIONS = {
    "inertias": "inertia",
    "stiffnesses": "stiffness",
    "dampings": "rotational_damping",
    "drag": "rotational_damping",
}


@attrs.frozen
class ChainConfig:
    """The ``[chain]`` table, validated, in SI units.

    Attributes
    ----------
    inertias : tuple of float
        I_1..I_n [kg m^2], node 1 (below the top drive) to node n (the bit).
    stiffnesses : tuple of float
        k_1..k_n [N m/rad]; k_i joins node i-1 and node i (node 0: the top drive).
    dampings : tuple of float or None
        c_1..c_n [N m s/rad], dampers in parallel with the springs.
    drag : tuple of float or None
        Damping of each node to the borehole [N m s/rad].
    """

    inertias: tuple[float, ...]
    stiffnesses: tuple[float, ...]
    dampings: tuple[float, ...] | None = None
    drag: tuple[float, ...] | None = None

    @property
    def dofs(self) -> int:
        """Number of nodes (degrees of freedom) n."""
        return len(self.inertias)

    @property
    def carries_damping(self) -> bool:
        """Whether the chain gives its own dampers or drag (then ``[damping]`` is refused)."""
        return self.dampings is not None or self.drag is not None

    def model(self) -> Any:
        """The :class:`~torsio.model.lumped.LumpedModel` of the chain (strategy ``"chain"``)."""
        from torsio.model.lumped import LumpedModel

        return LumpedModel.from_chain(
            inertias=self.inertias,
            stiffnesses=self.stiffnesses,
            dampings=self.dampings,
            drag=self.drag,
            strategy="chain",
        )


def _values(raw: Any, key: str, dimension: str, positive: bool) -> tuple[float, ...]:
    if not isinstance(raw, list) or not raw:
        raise ConfigError(key, f"expected a non-empty array of numbers, got {raw!r}")
    values = []
    for i, item in enumerate(raw):
        value = to_si(item, dimension, key=f"{key}[{i}]")
        if not math.isfinite(value) or value < 0 or (positive and value == 0):
            expected = "positive" if positive else "non-negative"
            raise ConfigError(f"{key}[{i}]", f"expected a {expected} finite value, got {item!r}")
        values.append(value)
    return tuple(values)


def parse_chain(raw: Any) -> ChainConfig:
    """Validate a ``[chain]`` table (as read by ``tomllib``); errors name ``chain.<key>[i]``.

    Values are bare SI numbers or strings with units (``"930 kg*m^2"``,
    ``"425 N*m*s/rad"``); inertias and stiffnesses must be positive, dampings and drag
    non-negative, and every array has one value per inertia.
    """
    if not isinstance(raw, dict):
        raise ConfigError("chain", f"expected a table, got {raw!r}")
    unknown = sorted(set(raw) - CHAIN_KEYS)
    if unknown:
        raise ConfigError(
            f"chain.{unknown[0]}", f"unknown key; expected one of {', '.join(sorted(CHAIN_KEYS))}"
        )
    for required in ("inertias", "stiffnesses"):
        if required not in raw:
            raise ConfigError(f"chain.{required}", "missing required key")
    arrays: dict[str, tuple[float, ...] | None] = {}
    for key, dimension in _DIMENSIONS.items():
        if key not in raw:
            arrays[key] = None
            continue
        positive = key in ("inertias", "stiffnesses")
        arrays[key] = _values(raw[key], f"chain.{key}", dimension, positive)
    inertias = arrays["inertias"]
    assert inertias is not None
    for key in ("stiffnesses", "dampings", "drag"):
        values = arrays[key]
        if values is not None and len(values) != len(inertias):
            raise ConfigError(
                f"chain.{key}",
                f"expected {len(inertias)} values (one per inertia), got {len(values)}",
            )
    stiffnesses = arrays["stiffnesses"]
    assert stiffnesses is not None
    check_frequency_spread(inertias, stiffnesses)
    return ChainConfig(inertias, stiffnesses, arrays["dampings"], arrays["drag"])


def frequency_spread(inertias: Any, stiffnesses: Any) -> tuple[float, int, int]:
    """An estimate S of (omega_n / omega_1)^2 of a chain, the node i of its fastest local
    frequency and the node m of its largest flexibility term.

    S = max_i (k_i + k_(i+1)) / I_i * sum_m I_m f_m, f_m = sum_(j <= m) 1 / k_j: the
    first factor is within a factor 3 of omega_n^2 (Gershgorin), the second within a
    factor n of 1/omega_1^2 (Dunkerley), so S lies in [1/3, n] times (omega_n/omega_1)^2.
    """
    i_values = np.asarray(inertias, dtype=float)
    k_values = np.asarray(stiffnesses, dtype=float)
    with np.errstate(all="ignore"):
        below = np.append(k_values[1:], 0.0)
        local = (k_values + below) / i_values
        flexibility = np.cumsum(1.0 / k_values)
        terms = i_values * flexibility
        spread = float(local.max() * terms.sum())
    return (spread if math.isfinite(spread) else math.inf), int(local.argmax()), int(terms.argmax())


def check_frequency_spread(inertias: tuple[float, ...], stiffnesses: tuple[float, ...]) -> None:
    """ConfigError naming ``chain.inertias[i]`` or ``chain.stiffnesses[i]`` if the chain's
    natural frequencies spread over more than :data:`MAX_FREQUENCY_SPREAD` (no solver
    then finds its first frequency, or factors its stiffness matrix, in double precision).

    The key named is, of the inertias and springs that make the fastest node fast or the
    first mode slow, the value furthest (in decades) from the median of its array.
    """
    spread, fast, slow = frequency_spread(inertias, stiffnesses)
    if spread <= MAX_FREQUENCY_SPREAD:
        return
    n = len(inertias)
    springs = [fast] + ([fast + 1] if fast + 1 < n else [])
    candidates = [
        ("inertias", fast),
        ("stiffnesses", max(springs, key=lambda j: stiffnesses[j])),
        ("inertias", slow),
        ("stiffnesses", min(range(slow + 1), key=lambda j: stiffnesses[j])),
    ]
    arrays = {"inertias": list(inertias), "stiffnesses": list(stiffnesses)}
    medians = {key: float(np.median(values)) for key, values in arrays.items()}

    def decades(candidate: tuple[str, int]) -> float:
        key, i = candidate
        return abs(math.log10(arrays[key][i] / medians[key]))

    key, i = max(candidates, key=decades)
    unit = "kg m^2" if key == "inertias" else "N m/rad"
    value = arrays[key][i]
    raise ConfigError(
        f"chain.{key}[{i}]",
        f"{value:.6g} {unit} spreads the chain's natural frequencies over a factor of about "
        f"{math.sqrt(spread):.3g} ((omega_n/omega_1)^2 ~ {spread:.3g}, fastest at node {fast}, "
        f"the first mode set by node {slow}); a chain solves in double precision up to "
        f"(omega_n/omega_1)^2 = {MAX_FREQUENCY_SPREAD:.0e}; expected a value "
        f"{_spread_range(arrays, key, i, medians[key])} with the other values as given",
    )


def _spread_range(arrays: dict[str, list[float]], key: str, i: int, median: float) -> str:
    """The bound on ``arrays[key][i]`` (the others fixed) that keeps the spread in the limit,
    by bisection in decades between the array's median and the value."""
    values = dict(arrays)
    bad = values[key][i]

    def ok(x: float) -> bool:
        trial = list(values[key])
        trial[i] = x
        changed = {**values, key: trial}
        return frequency_spread(changed["inertias"], changed["stiffnesses"])[0] <= (
            MAX_FREQUENCY_SPREAD
        )

    if not ok(median):
        return "closer to the other values"
    good_log, bad_log = math.log10(median), math.log10(bad)
    for _ in range(60):
        middle = 0.5 * (good_log + bad_log)
        good_log, bad_log = (middle, bad_log) if ok(10.0**middle) else (good_log, middle)
    unit = "kg m^2" if key == "inertias" else "N m/rad"
    return f"{'at most' if bad > median else 'at least'} {10.0**good_log:.3g} {unit}"
