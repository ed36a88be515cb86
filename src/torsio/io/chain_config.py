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

from torsio.errors import ConfigError
from torsio.units import to_si

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
    return ChainConfig(inertias, stiffnesses, arrays["dampings"], arrays["drag"])
