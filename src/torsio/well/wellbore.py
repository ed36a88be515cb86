"""The wellbore: a survey, hole sections with their friction factors, and the mud.

The string hangs from the rig floor: its top at md 0, its bit at md = the string's length
along the survey (a survey shorter than the string is an error; open hole below the bit
carries nothing).

Examples
--------
>>> from torsio.well.survey import Survey
>>> survey = Survey([0.0, 1000.0, 1600.0], [0.0, 0.0, 60.0], [0.0, 0.0, 0.0])
>>> well = Wellbore(survey, mud_density=1200.0, friction_static=0.3, friction_dynamic=0.25,
...                 hole=(HoleSection(to_md=1200.0, friction_static=0.2, friction_dynamic=0.15),))
>>> well.friction_dynamic_at([500.0, 1200.0, 1500.0]).tolist()
[0.15, 0.15, 0.25]
>>> Wellbore(survey, friction_static=0.2, friction_dynamic=0.3)
Traceback (most recent call last):
...
torsio.errors.ConfigError: friction_dynamic: expected a dynamic friction factor <= ...
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError
from torsio.units import si_field
from torsio.well.survey import Survey

__all__ = [
    "MAX_FRICTION_FACTOR",
    "NORMAL_FORCE_MODELS",
    "HoleSection",
    "Wellbore",
    "bit_md",
    "check_mud_density",
    "string_top_md",
]

NORMAL_FORCE_MODELS = ("soft-string", "gravity")
"""``soft-string``: buoyed weight and tension times curvature (Johancsik et al. 1984);
``gravity``: the buoyed weight's component normal to the hole alone (inclination only)."""


MAX_FRICTION_FACTOR = 1.0
"""Largest friction factor of string on borehole: factors measured in mud, cased and open
hole, lie from 0.1 to 0.5 (Johancsik et al. 1984 fitted 0.25 to 0.4); above 1 a contact
would hold more than the force pressing it, which no lubricated steel-on-rock contact does."""


def _check_friction(static: float, dynamic: float, key: str) -> None:
    for name, value in (("friction_static", static), ("friction_dynamic", dynamic)):
        if not (isinstance(value, int | float) and math.isfinite(value) and value >= 0.0):
            raise ConfigError(
                f"{key}{name}", f"expected a non-negative friction factor, got {value!r}"
            )
        if value > MAX_FRICTION_FACTOR:
            raise ConfigError(
                f"{key}{name}",
                f"expected a friction factor from 0 to {MAX_FRICTION_FACTOR:g} (measured "
                f"factors in mud are 0.1 to 0.5), got {value:g}",
            )
    if dynamic > static:
        raise ConfigError(
            f"{key}friction_dynamic",
            f"expected a dynamic friction factor <= the static one ({static:g}), got {dynamic:g}",
        )


@attrs.frozen
class HoleSection:
    """A stretch of hole from the section above (or the surface) down to ``to_md``.

    Parameters
    ----------
    to_md : float
        Measured depth of its bottom [m] (e.g. a casing shoe).
    friction_static, friction_dynamic : float or None
        Friction factors string on borehole (None: the well's defaults).
    name : str
        Free text for reports (``"casing 9 5/8 in"``).
    """

    to_md: float = si_field("length", "to_md")
    friction_static: float | None = None
    friction_dynamic: float | None = None
    name: str = ""


@attrs.frozen(repr=False)
class Wellbore:
    """The hole a drill-string turns in.

    Parameters
    ----------
    survey : Survey
        The stations and the minimum-curvature hole through them.
    mud_density : float
        Density of the mud [kg/m^3], inside and outside the string (0: in air).
    friction_static, friction_dynamic : float
        Static and sliding friction factors, string on borehole, the defaults of every
        hole section (``friction_dynamic <= friction_static``).
    threshold_speed : float
        Below this speed [rad/s] a contact may stick (used by the dynamics).
    normal_force : str
        One of :data:`NORMAL_FORCE_MODELS`.
    hole : tuple of HoleSection
        From the surface down, each ``to_md`` deeper than the one above and within the
        survey; below the last one the defaults apply.

    Raises
    ------
    ConfigError
        A negative density or friction factor, ``friction_dynamic > friction_static`` (of
        the well or of a hole section), an unknown normal-force model, hole sections out of
        order or below the survey. Keys are named as in the ``[well]`` table.
    """

    survey: Survey
    mud_density: float = si_field("density", "mud_density", default=0.0)
    friction_static: float = 0.3
    friction_dynamic: float = 0.25
    threshold_speed: float = si_field("angular_speed", "threshold_speed", default=0.5)
    normal_force: str = "soft-string"
    hole: tuple[HoleSection, ...] = attrs.field(default=(), converter=tuple)

    def __attrs_post_init__(self) -> None:
        if not (math.isfinite(self.mud_density) and self.mud_density >= 0.0):
            raise ConfigError(
                "mud_density", f"expected a non-negative density, got {self.mud_density!r}"
            )
        if not (math.isfinite(self.threshold_speed) and self.threshold_speed >= 0.0):
            raise ConfigError(
                "threshold_speed", f"expected a non-negative speed, got {self.threshold_speed!r}"
            )
        if self.normal_force not in NORMAL_FORCE_MODELS:
            raise ConfigError(
                "normal_force",
                f"unknown model {self.normal_force!r}; expected one of "
                f"{', '.join(NORMAL_FORCE_MODELS)}",
            )
        _check_friction(self.friction_static, self.friction_dynamic, "")
        above = 0.0
        for i, section in enumerate(self.hole):
            key = f"hole[{i}]."
            if not (math.isfinite(section.to_md) and section.to_md > above):
                raise ConfigError(
                    f"{key}to_md",
                    f"expected a measured depth below {above:g} m (the section above or the "
                    f"surface), got {section.to_md:g} m",
                )
            if section.to_md > self.survey.depth:
                raise ConfigError(
                    f"{key}to_md",
                    f"{section.to_md:g} m is below the survey's last station "
                    f"({self.survey.depth:g} m)",
                )
            static, dynamic = self._factors(section)
            _check_friction(static, dynamic, key)
            above = section.to_md

    def __repr__(self) -> str:
        return (
            f"Wellbore({self.survey!r}, {len(self.hole)} hole sections, mud "
            f"{self.mud_density:g} kg/m^3, mu_s {self.friction_static:g}, "
            f"mu_d {self.friction_dynamic:g})"
        )

    def _factors(self, section: HoleSection) -> tuple[float, float]:
        static = (
            self.friction_static if section.friction_static is None else section.friction_static
        )
        dynamic = (
            self.friction_dynamic if section.friction_dynamic is None else section.friction_dynamic
        )
        return static, dynamic

    @property
    def hole_bottoms(self) -> np.ndarray:
        """``to_md`` of every hole section [m]."""
        return np.array([section.to_md for section in self.hole], dtype=float)

    def _section_index(self, md: Any) -> np.ndarray:
        """Index of the hole section at ``md`` (len(hole): below the last, the defaults);
        a depth equal to a ``to_md`` belongs to the section above it."""
        return np.searchsorted(self.hole_bottoms, np.asarray(md, dtype=float), side="left")

    def friction_static_at(self, md: Any) -> np.ndarray:
        """Static friction factor at measured depth ``md``."""
        table = [self._factors(s)[0] for s in self.hole] + [self.friction_static]
        return np.asarray(table)[self._section_index(md)]

    def friction_dynamic_at(self, md: Any) -> np.ndarray:
        """Sliding (dynamic) friction factor at measured depth ``md``."""
        table = [self._factors(s)[1] for s in self.hole] + [self.friction_dynamic]
        return np.asarray(table)[self._section_index(md)]


def string_top_md(well: Wellbore, string_length: float, key: str = "md") -> float:
    """Measured depth of the string's top [m]: 0, the string hangs from the rig floor.

    The bit is at md = ``string_length`` along the survey (:func:`bit_md`, which checks
    the survey reaches it); open hole below the bit carries nothing.

    >>> survey = Survey([0.0, 2000.0], [0.0, 0.0], [0.0, 0.0])
    >>> string_top_md(Wellbore(survey), 1500.0)
    0.0
    """
    bit_md(well, string_length, key)
    return 0.0


def bit_md(well: Wellbore, string_length: float, key: str = "md") -> float:
    """Measured depth of the bit [m]: the string's length, the top at the rig floor (md 0).

    Raises
    ------
    ConfigError
        If the survey ends above the bit (named by ``key``).

    Examples
    --------
    >>> survey = Survey([0.0, 2000.0], [0.0, 0.0], [0.0, 0.0])
    >>> bit_md(Wellbore(survey), 1500.0)   # 500 m of open hole below the bit
    1500.0
    """
    depth = well.survey.depth
    if string_length > depth * (1.0 + 1e-12):
        raise ConfigError(
            key,
            f"the string is {string_length:g} m long but the survey ends at md {depth:g} m; "
            "the string hangs from the rig floor (md 0), so the survey must reach at least "
            "the string's length (add stations or shorten the string)",
        )
    return min(float(string_length), depth)  # a string as long as the survey, to round-off


def check_mud_density(well: Wellbore, string: Any, key: str = "mud_density") -> None:
    """Refuse a mud denser than a section of the string: its buoyed weight would be
    negative, a string that floats, which a string hung from the hook (the soft-string
    model) is not. Mud as dense as the steel (buoyed weight 0) is allowed."""
    for section in string.sections:
        density = section.material.density
        if well.mud_density > density:
            raise ConfigError(
                key,
                f"expected a mud no denser than the string ({density:g} kg/m^3 in "
                f"{section.describe()}: the string would float), got {well.mud_density:g} "
                "kg/m^3 (drilling muds weigh 1000 to 2500 kg/m^3)",
            )
