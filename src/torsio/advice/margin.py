"""The margin of a recommended point: its probability of severe stick-slip over the
uncertain parameters (Monte Carlo), and its distance to the severity boundary.

**The parameters.** From a fit (``torsio fit --json``: ``parameters``, ``uncertainty``
one-sigma, and where given ``interval`` and ``correlation``), drawn as the Monte Carlo
severity maps draw them (:func:`torsio.calibration.monte_carlo.parameter_draws`: joint
normal, each draw within its two-sigma interval); or from ranges (``name=LOW:HIGH``),
uniform. Names: the ``[well]`` factors ``friction_static``, ``friction_dynamic``,
``threshold_speed``, a hole section's ``hole[i].friction_static``/``friction_dynamic``, and
the bit law's parameters (``contact_friction``, ``intrinsic_specific_energy``, ... of
``[bit_rock]``). Each draw rebuilds the string's contacts
(:func:`torsio.well.axial_contacts.axial_contacts`) or the bit.

**The probability.** ``samples`` draws (seeded) run at the point; p = severe / samples. A
point is accepted when the one-sided 95 % Clopper-Pearson upper bound of p is below
``level`` (:func:`upper_bound`): with 30 samples, none severe (bound 9.5 %).

**The margin.** In kN: the row's critical WOB minus the point's WOB; in rpm: the distance
along the critical-WOB curve (linear between the rows searched) to the nearest rpm where
the curve falls to the point's WOB (None: not within the region).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError

__all__ = ["CONFIDENCE", "Uncertainty", "case_with_values", "severe_count", "upper_bound"]

CONFIDENCE = 0.95
"""One-sided confidence of the Clopper-Pearson bound on the probability of severe stick-slip."""

WELL_NAMES = ("friction_static", "friction_dynamic", "threshold_speed")


def upper_bound(severe: int, samples: int, confidence: float = CONFIDENCE) -> float:
    """The one-sided Clopper-Pearson upper bound of a binomial probability with ``severe``
    successes in ``samples`` trials (Clopper and Pearson 1934: the beta quantile)."""
    from scipy.stats import beta

    if severe >= samples:
        return 1.0
    return float(beta.ppf(confidence, severe + 1, samples - severe))


@attrs.frozen
class _Spread:
    """The sigma, two-sigma interval and identifiability :func:`parameter_draws` reads of a
    fit (a parameter the data do not pin down is drawn over its whole interval)."""

    sigma: float
    interval: tuple[float, float]
    identifiable: bool = True


@attrs.frozen
class _Bounds:
    def lower_bound(self, name: str) -> float:
        return 1e-3 if name == "threshold_speed" else 0.0


@attrs.frozen
class Uncertainty:
    """The uncertain parameters: a fitted distribution (``kind = "fit"``) or ranges
    (``"ranges"``: ``values`` the lows, ``highs`` the highs).

    Attributes: ``names``, ``values``, ``uncertainty`` (spreads of a fit),
    ``correlation`` (None: independent), ``highs``, ``kind``, ``flag`` (for errors)."""

    names: tuple[str, ...]
    values: tuple[float, ...]
    uncertainty: tuple[_Spread, ...] = ()
    correlation: Any = None
    highs: tuple[float, ...] = ()
    kind: str = "fit"
    flag: str = "--fit"

    @classmethod
    def from_fit(cls, path: str | Path) -> Uncertainty:
        """The distribution of a ``torsio fit --json`` file (module documentation)."""
        try:
            data = json.loads(Path(path).read_text(encoding="utf-8"))
            parameters, sigmas = data["parameters"], data["uncertainty"]
        except (OSError, ValueError, KeyError, TypeError) as exc:
            raise ConfigError(
                "--fit",
                f"cannot read {str(path)!r} as torsio fit --json output (keys 'parameters' "
                f"and 'uncertainty'): {exc}",
            ) from None
        names = tuple(parameters)
        intervals = data.get("interval") or {}
        identifiable = data.get("identifiable") or {}
        spreads = []
        for name in names:
            value, sigma = float(parameters[name]), sigmas.get(name)
            if sigma is None or not (math.isfinite(float(sigma)) and float(sigma) >= 0):
                raise ConfigError("--fit", f"{name}: expected a one-sigma >= 0, got {sigma!r}")
            low, high = intervals.get(name) or (value - 2 * sigma, value + 2 * sigma)
            pinned = bool(identifiable.get(name, True))
            spreads.append(_Spread(float(sigma), (float(low), float(high)), pinned))
        matrix = data.get("correlation")
        correlation = None
        if matrix:
            correlation = np.array([[matrix[a][b] for b in names] for a in names], dtype=float)
        values = tuple(float(parameters[n]) for n in names)
        return cls(names, values, tuple(spreads), correlation)

    @classmethod
    def from_ranges(cls, texts: Sequence[str]) -> Uncertainty:
        """Uniform ranges ``name=LOW:HIGH`` (``--vary``)."""
        names, lows, highs = [], [], []
        for text in texts:
            name, _, bounds = text.partition("=")
            parts = bounds.split(":")
            try:
                low, high = (float(p) for p in parts)
            except ValueError:
                raise ConfigError(
                    "--vary", f"expected NAME=LOW:HIGH (numbers), got {text!r}"
                ) from None
            if not (name.strip() and math.isfinite(low) and math.isfinite(high) and low <= high):
                raise ConfigError(
                    "--vary", f"expected NAME=LOW:HIGH with LOW <= HIGH, got {text!r}"
                )
            names.append(name.strip())
            lows.append(low)
            highs.append(high)
        return cls(tuple(names), tuple(lows), highs=tuple(highs), kind="ranges", flag="--vary")

    def draws(self, count: int, seed: int) -> list[dict[str, float]]:
        """``count`` draws, reproducible from ``seed``."""
        if self.kind == "ranges":
            rng = np.random.default_rng(seed)
            return [
                {
                    n: float(rng.uniform(lo, hi))
                    for n, lo, hi in zip(self.names, self.values, self.highs, strict=True)
                }
                for _ in range(count)
            ]
        from torsio.calibration.monte_carlo import parameter_draws

        return parameter_draws(self, _Bounds(), count, seed)

    def to_dict(self) -> dict[str, Any]:
        """``kind``, ``parameters`` and their ``sigma`` (fit) or ``high`` (ranges)."""
        data: dict[str, Any] = {
            "kind": self.kind,
            "parameters": dict(zip(self.names, self.values, strict=True)),
        }
        if self.kind == "fit":
            data["sigma"] = {n: s.sigma for n, s in zip(self.names, self.uncertainty, strict=True)}
        else:
            data["high"] = dict(zip(self.names, self.highs, strict=True))
        return data


def _hole_name(name: str) -> tuple[int, str] | None:
    if not name.startswith("hole[") or "]." not in name:
        return None
    index, _, key = name[5:].partition("].")
    return (int(index), key) if index.isdigit() and key in WELL_NAMES[:2] else None


def case_with_values(config: Any, case: Any, values: Mapping[str, float], flag: str) -> Any:
    """``case`` with the parameters ``values`` (module documentation); an unknown name is
    an error on ``flag``."""
    from torsio.advice.evaluate import case_with

    axial = config.axial
    well_values, bit_values, holes = {}, {}, {}
    bit_fields = set(attrs.fields_dict(type(axial.bit))) if attrs.has(type(axial.bit)) else set()
    for name, value in values.items():
        hole = _hole_name(name)
        if name in WELL_NAMES and config.well is not None:
            well_values[name] = value
        elif hole is not None and config.well is not None and hole[0] < len(config.well.hole):
            holes[hole] = value
        elif name in bit_fields:
            bit_values[name] = value
        else:
            known = [*WELL_NAMES, "hole[i].friction_static", "hole[i].friction_dynamic"]
            raise ConfigError(
                flag,
                f"unknown parameter {name!r}; expected one of "
                f"{', '.join(known if config.well is not None else []) or '(no [well])'}, "
                f"or the bit's {', '.join(sorted(bit_fields))}",
            )
    contacts = None
    if well_values or holes:
        from torsio.well.axial_contacts import axial_contacts

        sections = list(config.well.hole)
        for index in {i for i, _ in holes}:
            drawn = {key: value for (i, key), value in holes.items() if i == index}
            sections[index] = attrs.evolve(sections[index], **_factors(sections[index], drawn))
        well = attrs.evolve(config.well, hole=tuple(sections), **_factors(config.well, well_values))
        contacts = axial_contacts(well, axial.string, axial.stability_assembly.node_depths)
    bit = attrs.evolve(case.bit, **bit_values) if bit_values else None
    return case_with(case, contacts=contacts, bit=bit)


def _factors(table: Any, drawn: Mapping[str, float]) -> dict[str, Any]:
    """The drawn values for a well or hole section, its dynamic factor at most its static
    one (independent draws may cross them; the well requires dynamic <= static)."""
    values = {**drawn}
    static = values.get("friction_static", table.friction_static)
    dynamic = values.get("friction_dynamic", table.friction_dynamic)
    if static is not None and dynamic is not None and dynamic > static:
        values["friction_dynamic"] = static
    return values


def severe_count(severity: Any, threshold: float) -> tuple[int, int]:
    """(severe, valid) samples: S_SS above ``threshold``, of the finite ones."""
    values = np.asarray(severity, dtype=float)
    valid = np.isfinite(values)
    return int((values[valid] > threshold).sum()), int(valid.sum())


def rpm_margin(rows: Any, critical: Any, wob: float, rpm: float) -> float | None:
    """The distance [rev/min] from ``rpm`` along the critical-WOB curve (``critical`` at
    ``rows``, linear between them; +inf: no severe point in a row, -inf: all severe) to the
    nearest rpm where it falls to ``wob``; None: not within the rows."""
    best: float | None = None
    for a, b, ca, cb in zip(rows[:-1], rows[1:], critical[:-1], critical[1:], strict=True):
        if not ((ca - wob) * (cb - wob) <= 0):
            continue
        if np.isfinite(ca) and np.isfinite(cb) and ca != cb:
            crossing = a + (wob - ca) / (cb - ca) * (b - a)
        else:
            crossing = b if cb <= wob else a
        distance = abs(float(crossing) - rpm)
        best = distance if best is None else min(best, distance)
    return best
