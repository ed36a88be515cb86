"""Where a fit starts: the closed forms of friction along the string, read off a record.

The friction capacities are linear in the factors of each stretch of hole
(:mod:`torsio.calibration.parameters`), so the sliding torque of a string turning at Omega
off bottom is

    T_slide = sum_z mu_d,z D_z + alpha I Omega,

with D_z the sliding torque of stretch z with a unit factor (the integral of N r_o over it,
:func:`torsio.well.break_off.break_off`) and I the string's polar inertia (the
distributed damping alpha acts on every cell's speed). The break-over torque, the peak of
the record, is likewise sum_z mu_s,z S_z + alpha I Omega at the peak. The fitted factors
of a kind (static or sliding) are started at their configured values times the one scale
that matches the record's torque (the others held), averaged over the recordings; with
``alpha`` fitted and recordings at two or more speeds, T_slide against Omega is a line
whose slope is alpha I.

Examples
--------
>>> import numpy as np
>>> from torsio.calibration.parameters import SystemFamily
>>> from torsio.calibration.recording import Recording
>>> from torsio.examples import deviated_well_config
>>> family = SystemFamily(deviated_well_config())
>>> time = np.linspace(0.0, 60.0, 601)
>>> slide = 0.2 * 20066.0 + 0.3 * 20450.0 + 0.35 * family.polar_inertia * 12.566
>>> record = Recording(time=time, top_speed=np.full(601, 12.566),
...                    surface_torque=np.full(601, slide))
>>> start = closed_form_start(family, [record], ["friction_dynamic"])
>>> round(start["friction_dynamic"], 3)
0.3
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from torsio.calibration.objectives import break_over, sliding_part

__all__ = ["closed_form_start"]

KINDS = {"friction_static": "static", "friction_dynamic": "dynamic"}


def _kind(name: str) -> str | None:
    return KINDS.get(name.split(".")[-1])


def _zone(family: Any, name: str) -> int:
    return family.zones - 1 if not name.startswith("hole[") else int(name[5 : name.index("]")])


def _levels(record: Any) -> dict[str, tuple[float, float]]:
    """(torque [N m], top speed [rad/s]) of the record's sliding and break-over."""
    tail = sliding_part(record.time)
    peak = break_over(record.surface_torque)
    return {
        "dynamic": (
            float(np.mean(record.surface_torque[tail])),
            float(np.mean(record.top_speed[tail])),
        ),
        "static": (float(record.surface_torque[peak]), float(record.top_speed[peak])),
    }


def _alpha(family: Any, recordings: Sequence[Any]) -> float | None:
    """alpha from the sliding torque against speed (None: fewer than two speeds)."""
    points = np.array([_levels(r)["dynamic"] for r in recordings])
    if len(points) < 2 or np.ptp(points[:, 1]) < 0.05 * np.max(np.abs(points[:, 1])):
        return None
    slope = np.polyfit(points[:, 1], points[:, 0], 1)[0]
    return max(float(slope) / family.polar_inertia, 0.0)


def closed_form_start(
    family: Any, recordings: Sequence[Any], names: Sequence[str]
) -> Mapping[str, float]:
    """Starting values of ``names`` from the closed forms (module documentation)."""
    start = {name: family.values[name] for name in names}
    if "alpha" in start:
        alpha = _alpha(family, recordings)
        start["alpha"] = family.values["alpha"] if alpha is None else alpha
    alpha = start.get("alpha", family.values["alpha"])
    for kind in ("dynamic", "static"):
        fitted = [name for name in names if _kind(name) == kind]
        if not fitted:
            continue
        key = f"friction_{kind}"
        units = [getattr(c, f"{kind}_total") for c in family._unit]
        factors = family._zone_factors(family.values, key)
        zones = {_zone(family, name) for name in fitted}
        held = sum(
            f * u for z, (f, u) in enumerate(zip(factors, units, strict=True)) if z not in zones
        )
        free = sum(factors[z] * units[z] for z in zones)
        scales = []
        for record in recordings:
            torque, speed = _levels(record)[kind]
            scales.append((torque - alpha * family.polar_inertia * speed - held) / free)
        scale = max(float(np.mean(scales)), 1e-3)
        for name in fitted:
            start[name] = family.values[name] * scale
    for name in names:  # a sliding factor starts at most at the static one
        if _kind(name) == "static":
            dynamic = name.replace("friction_static", "friction_dynamic")
            if dynamic in start:
                start[name] = max(start[name], start[dynamic])
    return start


def corrected_start(
    family: Any,
    recordings: Sequence[Any],
    models: Sequence[np.ndarray],
    start: Mapping[str, float],
) -> dict[str, float]:
    """One Newton step of the closed forms on the model's own torques: each fitted kind's
    factors move by (record - model) / (its torque per unit factor), for the break-over
    (peak) and the sliding torque, so the inertia and the waves of the start-up that the
    closed forms leave out are taken from the model run at ``start``."""
    corrected = dict(start)
    for kind in ("dynamic", "static"):
        fitted = [name for name in start if _kind(name) == kind]
        if not fitted:
            continue
        units = [getattr(c, f"{kind}_total") for c in family._unit]
        zones = {_zone(family, name) for name in fitted}
        key = f"friction_{kind}"
        factors = family._zone_factors({**family.values, **start}, key)
        free = sum(factors[z] * units[z] for z in zones)
        errors = []
        for record, model in zip(recordings, models, strict=True):
            measured = _levels(record)[kind][0]
            modelled = _levels(_RecordView(record, model))[kind][0]
            errors.append(measured - modelled)
        scale = max(1.0 + float(np.mean(errors)) / free, 1e-3)
        for name in fitted:
            corrected[name] = start[name] * scale
    for name in list(corrected):
        if _kind(name) == "static":
            dynamic = name.replace("friction_static", "friction_dynamic")
            if dynamic in corrected:
                corrected[name] = max(corrected[name], corrected[dynamic])
    return corrected


class _RecordView:
    """A record's times and top speed with the torque ``torque`` (for :func:`_levels`)."""

    def __init__(self, record: Any, torque: np.ndarray) -> None:
        self.time, self.top_speed = record.time, record.top_speed
        self.surface_torque = torque
