"""The parameters a fit may change, by their configuration keys, and the systems they make.

Fittable names (the keys of the configuration file):

* ``friction_static``, ``friction_dynamic``: the ``[well]`` factors, i.e. the factors of
  every stretch of hole that gives none of its own (in the built-in deviated well: the
  open hole below the casing). Hole sections with their own factors keep them: a cased
  hole's factor is usually known and the open hole's is the unknown (the practice of
  torque-and-drag calibration).
* ``hole[i].friction_static``, ``hole[i].friction_dynamic``: the factors of hole section i
  (from 0, as ``[[well.hole]]`` lists them).
* ``threshold_speed`` [rad/s]: below it a contact may stick.
* ``alpha`` [1/s]: the distributed (mass-proportional) damping of ``[damping]``.

The normal force does not depend on the friction factors (soft string rotating, no axial
friction), so the friction capacities of the wave grid are linear in the factors of each
stretch: :class:`SystemFamily` computes them once per stretch with unit factors and sums.

Examples
--------
>>> from torsio.examples import deviated_well_config
>>> family = SystemFamily(deviated_well_config())
>>> len(family.names), family.names[2]
(6, 'hole[0].friction_static')
>>> family.values["friction_static"], family.values["hole[0].friction_dynamic"]
(0.35, 0.2)
>>> round(family.system({"friction_static": 0.7}).at(wob=0.0).model.contacts.static_total)
19327
>>> family.check(["friction_static", "mu"])
Traceback (most recent call last):
...
torsio.errors.ConfigError: fit: unknown parameter 'mu'; the fittable ones are friction_static, ...
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import attrs
import numpy as np

from torsio.analysis.grid_check import TWIN_TRAVEL_TIME_TOLERANCE
from torsio.errors import ConfigError
from torsio.model.contacts import StringContacts
from torsio.physics.damping import RayleighDamping
from torsio.well.string_contacts import model_contacts
from torsio.well.wellbore import HoleSection

__all__ = ["PARAMETER_UNITS", "PHYSICAL_RANGES", "TWIN_GRIDS", "SystemFamily"]

PARAMETER_UNITS = {"threshold_speed": "rad/s", "alpha": "1/s"}
"""Units of the fittable parameters that have one (friction factors are pure numbers)."""

PHYSICAL_RANGES = {
    "friction_static": (0.0, 1.0),
    "friction_dynamic": (0.0, 1.0),
    "threshold_speed": (1e-3, 10.0),
    "alpha": (0.0, 10.0),
}
"""The range a fit searches each parameter in, by the last part of its name (the global
stage scans it, the profile stops at its ends, and a parameter whose data allow the whole
of it is not identifiable). Friction factors of pipe in a well are 0.25 to 0.40 in
water-based mud (Johancsik, Friesen and Dawson 1984, from field measurements), lower in
oil-based mud; 1 is their ceiling here; a threshold speed from 1e-3 rad/s to 10 rad/s
(0.01 to 95 rpm); mass-proportional damping up to 10 1/s (the default wave model's
alpha is 0.35 1/s)."""


def _unit_well(well: Any, zone: int) -> Any:
    """``well`` with friction factors 1 in stretch ``zone`` (a hole section; len(hole): the
    stretches under the well's defaults) and 0 elsewhere."""
    default = zone == len(well.hole)
    sections = []
    for i, section in enumerate(well.hole):
        own = section.friction_static is not None or section.friction_dynamic is not None
        factor: float | None = 1.0 if i == zone else 0.0
        if default and not own:
            factor = None
        sections.append(HoleSection(section.to_md, factor, factor, section.name))
    unit = 1.0 if default else 0.0
    return attrs.evolve(well, friction_static=unit, friction_dynamic=unit, hole=tuple(sections))


TWIN_GRIDS = ("finer grid", "coarser grid", "continuum")
"""The names of the grids whose reading of the records gives a fit's discretization part:
the wave model's finer and coarser grid (:meth:`SystemFamily.twins`) and the continuum a
lumped strategy approximates (:meth:`SystemFamily.continuum`)."""

DRAG_SPACING_CONTINUUM = 1
"""The continuum's contacts: on every node of its grid."""

FINER_STEP = 0.25
"""The finer twin's time step, relative to the fit's grid (:meth:`SystemFamily.twins`)."""


class SystemFamily:
    """The systems of a configuration as its fittable parameters change.

    Parameters
    ----------
    config : Config
        A configuration with a ``[[section]]`` string and a ``[well]``; it
        is run on the wave model (``strategy = "wave"``) whatever its ``[discretization]``
        says, unless ``strategy`` names another.
    fit : bool
        The systems of a fit (:func:`~torsio.calibration.fit.fit_recordings`): a file with
        axial dynamics runs its torsional model off bottom
        (:meth:`~torsio.config.configuration.Config.off_bottom`; its ``alpha`` is not
        fittable: the axial engine takes ``[damping]`` beta only), and the wave model
        leaves out ``[damping]`` beta, which it cannot carry (:attr:`description` says
        so): Kelvin-Voigt damping resists twist only, so it gives no torque while the
        string turns steadily and does not move the sliding torque a fit reads. False
        (severity maps of a fit's draws): such a file is refused, and beta on the wave
        model too (the wave model says how to carry it as alpha).
    **discretization
        ``strategy`` (default ``"wave"``: the continuum, converged in its grid) and the
        options of its grid (e.g. ``drag_spacing`` of the wave model, ``dp_elements`` of a
        lumped strategy).
    """

    def __init__(self, config: Any, *, fit: bool = False, **discretization: Any) -> None:
        if config.well is None:
            raise ConfigError("well", "a fit of friction needs a [well] (survey and friction)")
        if config.axial is not None and not fit:
            raise ConfigError(
                "bit_rock.law",
                "these systems are torsional at any weight on bit, and this configuration "
                "has axial dynamics (the rgd bit): on bottom its bit needs the axial engine "
                "(torsio advise --fit draws a fit's friction there); a fit (torsio fit) "
                "runs its torsional model off bottom",
            )
        self.fit = fit
        self.off_bottom = config.axial is not None
        """Whether ``config`` is a file with axial dynamics, run off bottom."""
        config = config.off_bottom()
        self.discretization = dict(discretization)
        strategy = discretization.pop("strategy", "wave")
        self.strategy = str(strategy)
        self.config = config
        self.base = config.system(strategy=strategy, **discretization)
        self.beta_left_out = 0.0
        """``[damping]`` beta [s] the fit's wave model leaves out (0: none)."""
        beta = float(getattr(self.base.damping, "beta", 0.0) or 0.0)
        if fit and self.strategy == "wave" and beta:
            self.beta_left_out = beta
            self.base = attrs.evolve(self.base, damping=attrs.evolve(self.base.damping, beta=0.0))
        well = config.well
        self.zones = len(well.hole) + 1
        self._unit = [
            model_contacts(self.base.model, _unit_well(well, z), config.string)
            for z in range(self.zones)
        ]
        values: dict[str, float] = {
            "friction_static": well.friction_static,
            "friction_dynamic": well.friction_dynamic,
        }
        for i, section in enumerate(well.hole):
            if section.friction_static is not None or section.friction_dynamic is not None:
                static, dynamic = well._factors(section)
                values[f"hole[{i}].friction_static"] = static
                values[f"hole[{i}].friction_dynamic"] = dynamic
        values["threshold_speed"] = well.threshold_speed
        values["alpha"] = float(getattr(self.base.damping, "alpha", 0.0))
        self.values: dict[str, float] = values
        self.names: tuple[str, ...] = tuple(
            n for n in values if n != "alpha" or not self.off_bottom
        )
        self.polar_inertia = float(
            sum(s.material.density * s.polar_moment * s.length for s in config.string.sections)
        )
        """I = int rho J dx of the string [kg m^2]: the distributed damping's torque is
        alpha I Omega when it all turns at Omega."""

    @property
    def description(self) -> str:
        """The model the systems run, in words: ``"wave model, time step 0.000688 s"``,
        ``"strategy C, 24 nodes"``; a file with axial dynamics off bottom says so."""
        model = self.base.model
        if self.strategy == "wave":
            text = f"wave model, time step {float(model.time_step):.3g} s"
            if self.beta_left_out:
                text += (
                    f", without [damping] beta {self.beta_left_out:g} s (the wave model "
                    "carries none; it gives no torque in steady rotation)"
                )
        else:
            text = f"strategy {self.strategy}, {model.dofs} nodes"
        if self.off_bottom:
            text += ", the bit off bottom (the torsional model of a file with axial dynamics)"
        return text

    def check(self, names: Iterable[str]) -> tuple[str, ...]:
        """The names, validated: each fittable, none twice (errors name the name)."""
        names = tuple(names)
        if not names:
            raise ConfigError("fit", f"no parameter to fit; the fittable ones are {self._list()}")
        for name in names:
            if name == "alpha" and self.off_bottom:
                raise ConfigError(
                    "fit",
                    "alpha: a file with axial dynamics takes [damping] beta only (the axial "
                    f"engine's dampers beside its springs); the fittable ones are {self._list()}",
                )
            if name not in self.names:
                hint = ""
                if name.startswith("hole[") and name.split(".")[-1] in self.values:
                    hint = " (a hole section without factors of its own follows the [well] ones)"
                raise ConfigError(
                    "fit",
                    f"unknown parameter {name!r}{hint}; the fittable ones are {self._list()}",
                )
        if len(set(names)) < len(names):
            raise ConfigError("fit", f"a parameter is given twice in {', '.join(names)}")
        return names

    def _list(self) -> str:
        return ", ".join(self.names)

    def lower_bound(self, name: str) -> float:
        """The smallest value a fit may try [the parameter's unit]."""
        return PHYSICAL_RANGES[name.split(".")[-1]][0]

    def upper_bound(self, name: str) -> float:
        """The largest value a fit may try [the parameter's unit]."""
        return PHYSICAL_RANGES[name.split(".")[-1]][1]

    def twins(self) -> tuple[tuple[str, SystemFamily], ...]:
        """The same friction on other grids of the wave model, by name (:data:`TWIN_GRIDS`),
        from which the fit reads its own grid's discretization error
        (:mod:`torsio.calibration.profile`): a quarter of the time step with contacts on
        every node (``drag_spacing = 1``), and twice the time step (the coarse twin of
        :mod:`torsio.analysis.grid_check`, its travel-time tolerance
        :data:`~torsio.analysis.grid_check.TWIN_TRAVEL_TIME_TOLERANCE`); none on a lumped
        strategy (its lumping's error is read against the :meth:`continuum`)."""
        if self.strategy != "wave":
            return ()
        step = float(self.base.model.time_step)
        finer = {**self.discretization, "time_step": FINER_STEP * step, "drag_spacing": 1}
        coarser = {
            **self.discretization,
            "time_step": 2.0 * step,
            "travel_time_tolerance": TWIN_TRAVEL_TIME_TOLERANCE,
        }
        return (
            (TWIN_GRIDS[0], SystemFamily(self.config, fit=self.fit, **finer)),
            (TWIN_GRIDS[1], SystemFamily(self.config, fit=self.fit, **coarser)),
        )

    def continuum(self) -> SystemFamily | None:
        """The continuum a lumped strategy approximates (the wave model with contacts on
        every node), which reads the same records for the fit's lumping error; None on the
        wave model."""
        if self.strategy == "wave":
            return None
        return SystemFamily(
            self.config, fit=self.fit, strategy="wave", drag_spacing=DRAG_SPACING_CONTINUUM
        )

    def _zone_factors(self, values: Mapping[str, float], kind: str) -> list[float]:
        factors = []
        for zone in range(self.zones):
            key = kind if zone == self.zones - 1 else f"hole[{zone}].{kind}"
            factors.append(float(values.get(key, self.values.get(key, 0.0))))
        return factors

    def contacts(self, values: Mapping[str, float]) -> StringContacts:
        """The friction capacities with ``values`` (the others as configured); a sliding
        factor above the static one counts as the static one."""
        merged = {**self.values, **values}
        static_factors = self._zone_factors(merged, "friction_static")
        dynamic_factors = self._zone_factors(merged, "friction_dynamic")
        zones = ZoneContacts(
            tuple(self._unit), tuple(static_factors), tuple(dynamic_factors),
            float(merged["threshold_speed"]),
        )  # fmt: skip
        return zones(0.0)

    def system(self, values: Mapping[str, float]) -> Any:
        """The base system with ``values`` of the fittable parameters (the rest as given)."""
        merged = {**self.values, **values}
        contacts = self.contacts(merged).at_wob(float(self.base.wob))  # as Config.system
        model = self.base.model.with_contacts(contacts)
        damping = attrs.evolve(self.base.damping, alpha=float(merged["alpha"]))
        if not isinstance(damping, RayleighDamping):  # pragma: no cover - a chain's dampers
            raise ConfigError("damping", "a fit takes Rayleigh damping ([damping] alpha, beta)")
        return attrs.evolve(self.base, model=model, damping=damping)


@attrs.frozen(eq=False)
class ZoneContacts:
    """Contacts from unit-friction contacts per hole zone (friction factor 1) scaled by the
    zones' factors, at any weight on bit (each unit rebuilt there: ``rebuild`` of the
    result, so a fitted system's contacts follow the weight as a configuration's do)."""

    units: tuple[StringContacts, ...]
    static_factors: tuple[float, ...]
    dynamic_factors: tuple[float, ...]
    threshold_speed: float

    def __call__(self, wob: float) -> StringContacts:
        units = [u.at_wob(wob) for u in self.units]
        zones = zip(self.static_factors, self.dynamic_factors, units, strict=True)
        static = sum(f * u.static for f, _, u in zones)
        zones = zip(self.static_factors, self.dynamic_factors, units, strict=True)
        dynamic = sum(min(d, f) * u.dynamic for f, d, u in zones)
        depends = any(u.depends_on_wob for u in self.units)
        return StringContacts(
            static=np.asarray(static),
            dynamic=np.minimum(np.asarray(dynamic), np.asarray(static)),
            threshold_speed=self.threshold_speed,
            wob=float(wob),
            rebuild=self if depends else None,
        )
