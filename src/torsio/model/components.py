"""Physical components of a drill-string: material, pipe sections, BHA components, bit.

All components are immutable value objects validated on construction, in SI units.
A section is a uniform hollow shaft; its torsional properties follow from its
geometry and material:

* polar moment of area ``J = pi/32 (od^4 - id^4)``  [m^4]
* mass moment of inertia ``rho J L``                [kg m^2]
* torsional stiffness ``G J / L``                    [N m/rad]

Examples
--------
>>> steel = Material(shear_modulus=85.3e9, density=7800.0)
>>> dp = DrillPipe(od=0.140, id=0.119, length=4733.6, material=steel)
>>> round(dp.stiffness, 2)
324.87
>>> round(dp.inertia, 2)
665.61
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import attrs

from torsio.errors import ConfigError
from torsio.units import as_si, si_field


def _finite(what: str, accept: Any) -> Any:
    """An attrs validator: a finite number with ``accept(value)`` true, else a ConfigError."""

    def check(instance: Any, attribute: attrs.Attribute[Any], value: float) -> None:
        if not (isinstance(value, int | float) and math.isfinite(value) and accept(value)):
            name = type(instance).__name__
            raise ConfigError(
                attribute.name,
                f"{name}.{attribute.name} must be a {what} finite number, got {value!r}",
            )

    return check


_positive_finite = _finite("positive", lambda value: value > 0)
_non_negative_finite = _finite("non-negative", lambda value: value >= 0)


def _pressure(value: Any) -> float:
    """E [Pa] from a number or a string with units (``"207 GPa"``)."""
    return as_si(value, "pressure", key="youngs_modulus")


@attrs.frozen
class Material:
    """Elastic material of a section.

    Parameters
    ----------
    shear_modulus : float or str
        Shear modulus G [Pa], or a string with units (``"79.3 GPa"``).
    density : float or str
        Density rho [kg/m^3], or a string with units (``"7.8 g/cm^3"``).
    youngs_modulus : float or str or None
        Young's modulus E [Pa] (``"207 GPa"``), which axial dynamics need (springs E A / L,
        axial waves sqrt(E/rho)); None: not given, the section is torsional only.

    Examples
    --------
    >>> Material(shear_modulus=85.3e9, density=7800.0).wave_speed
    3306.9...
    """

    shear_modulus: float = si_field("pressure", "shear_modulus", validator=_positive_finite)
    density: float = si_field("density", "density", validator=_positive_finite)
    youngs_modulus: float | None = attrs.field(
        default=None,
        converter=attrs.converters.optional(_pressure),
        validator=attrs.validators.optional(_positive_finite),
    )

    @property
    def wave_speed(self) -> float:
        """Torsional wave speed sqrt(G/rho) [m/s]."""
        return math.sqrt(self.shear_modulus / self.density)


STEEL = Material(shear_modulus=85.3e9, density=7800.0)
"""The steel of the paper's examples (G = 85.3 GPa, rho = 7800 kg/m^3)."""


def _check_inner_diameter(instance: Section, attribute: attrs.Attribute[Any], value: float) -> None:
    _non_negative_finite(instance, attribute, value)
    if value >= instance.od:
        raise ConfigError(
            "id",
            f"inner diameter {value!r} m must be smaller than the outer diameter "
            f"{instance.od!r} m of {instance.describe()}",
        )


@attrs.frozen
class Section:
    """A uniform hollow shaft: the common base of every drill-string component.

    Use the subclasses (:class:`DrillPipe`, :class:`HeavyWeightDrillPipe`,
    :class:`DrillCollar`, :class:`MWD`, :class:`LWD`, :class:`Stabilizer`,
    :class:`BHASection`, :class:`Bit`); ``kind`` names each in configuration files.

    Parameters
    ----------
    od, id : float or str
        Outer and inner diameter [m]; ``0 <= id < od``. Strings with units are
        accepted as in configuration files (``"5 in"``).
    length : float or str
        Length along the string [m] (or e.g. ``"30 ft"``).
    material : Material
        Defaults to :data:`STEEL`.
    name : str
        Free text shown in reports.
    bha : bool | None
        Whether the section belongs to the bottom-hole assembly. ``None`` takes
        the kind's default (drill pipe: no; heavy-weight pipe and below: yes).
    """

    kind: ClassVar[str] = "section"
    default_bha: ClassVar[bool] = True

    od: float = si_field("length", "od", validator=_positive_finite)
    id: float = si_field("length", "id", validator=_check_inner_diameter)
    length: float = si_field("length", "length", validator=_positive_finite)
    material: Material = attrs.field(
        default=STEEL, validator=attrs.validators.instance_of(Material)
    )
    name: str = attrs.field(default="", converter=str)
    bha: bool | None = attrs.field(
        default=None, validator=attrs.validators.optional(attrs.validators.instance_of(bool))
    )

    def __init_subclass__(cls, kind: str | None = None, bha: bool = True, **kwargs: Any) -> None:
        """A kind of section: ``class DrillCollar(Section, kind="drill_collar")``; ``bha``
        is whether it belongs to the BHA by default."""
        super().__init_subclass__(**kwargs)
        if kind is not None:  # (attrs re-creates a slotted class without the keywords)
            cls.kind = kind
            cls.default_bha = bha

    def __attrs_post_init__(self) -> None:
        _check_derived(self)

    def describe(self) -> str:
        """Name of the section for messages: its name, else its kind."""
        return repr(self.name) if self.name else f"a {self.kind} section"

    @property
    def in_bha(self) -> bool:
        """Whether the section belongs to the BHA (explicit override, else the kind's default)."""
        return self.default_bha if self.bha is None else self.bha

    @property
    def polar_moment(self) -> float:
        """Polar moment of area J = pi/32 (od^4 - id^4) [m^4]."""
        return math.pi / 32.0 * (self.od**4 - self.id**4)

    @property
    def area(self) -> float:
        """Cross-section of the body, pi (od^2 - id^2) / 4 [m^2]: its axial springs E A / L
        and masses rho A L."""
        return math.pi * (self.od**2 - self.id**2) / 4

    @property
    def inertia(self) -> float:
        """Mass moment of inertia about the axis, rho J L [kg m^2]."""
        return self.material.density * self.polar_moment * self.length

    @property
    def stiffness(self) -> float:
        """Torsional stiffness G J / L [N m/rad]."""
        return self.material.shear_modulus * self.polar_moment / self.length

    @property
    def body_mass_per_length(self) -> float:
        """Mass per length of the body, rho pi/4 (od^2 - id^2) [kg/m]."""
        return self.material.density * math.pi / 4.0 * (self.od**2 - self.id**2)

    @property
    def mass_per_length(self) -> float:
        """Mass per length in air [kg/m] that the well's weight takes: the body's here
        (drill pipe and HWDP: their ``adjusted_weight``, with the tool joints)."""
        return self.body_mass_per_length

    @property
    def weighed_area(self) -> float:
        """Cross-section [m²] whose steel the well's weight takes: the body's,
        pi/4 (od^2 - id^2), here (drill pipe and HWDP: ``adjusted_weight`` / rho)."""
        return math.pi / 4.0 * (self.od**2 - self.id**2)

    @property
    def contact_radius(self) -> float:
        """Radius [m] at which the string touches the borehole: od/2 here (drill pipe and
        HWDP: their tool joints', ``tool_joint_od`` / 2)."""
        return self.od / 2.0

    @property
    def wave_travel_time(self) -> float:
        """Time a torsional wave takes to cross the section, L / sqrt(G/rho) [s]."""
        return self.length / self.material.wave_speed


DERIVED_RANGE = (1e-100, 1e100)
"""Range (SI) every derived quantity of a section must lie in (J, rho J L, G J / L, wave
speed and travel time): far beyond any drill-string, and narrow enough that products
and squares of them in the model's matrices and frequencies stay finite floats."""

#: Order of magnitude of each input of a steel drill-string section, to name the input
#: furthest from it when a derived quantity is not a finite positive number.
_TYPICAL = {"od": 0.15, "id": 0.1, "length": 100.0, "shear_modulus": 8e10, "density": 8e3}


def _check_derived(section: Section) -> None:
    """ConfigError naming the input if J, rho J L, G J / L, wave speed or travel time are not
    finite positive numbers in :data:`DERIVED_RANGE`."""
    inputs = {
        "od": section.od,
        "id": section.id,
        "length": section.length,
        "shear_modulus": section.material.shear_modulus,
        "density": section.material.density,
    }
    quantities = (
        ("polar moment of area J = pi/32 (od^4 - id^4)", "m^4", ("od", "id"), "polar_moment"),
        ("inertia rho J L", "kg m^2", ("density", "od", "id", "length"), "inertia"),
        ("stiffness G J / L", "N m/rad", ("shear_modulus", "od", "id", "length"), "stiffness"),
        ("wave speed sqrt(G/rho)", "m/s", ("shear_modulus", "density"), "wave_speed"),
        ("wave travel time L / sqrt(G/rho)", "s", ("length", "shear_modulus", "density"), None),
    )
    for label, unit, names, attribute in quantities:
        try:
            if attribute == "wave_speed":
                value = section.material.wave_speed
            elif attribute is None:
                value = section.wave_travel_time
            else:
                value = getattr(section, attribute)
        except (OverflowError, ZeroDivisionError):
            value = math.inf
        low, high = DERIVED_RANGE
        if math.isfinite(value) and low <= value <= high:
            continue
        culprit = max(
            (n for n in names if inputs[n] > 0),
            key=lambda n: abs(math.log10(inputs[n] / _TYPICAL[n])),
        )
        key = culprit if culprit in ("od", "id", "length") else f"material.{culprit}"
        given = ", ".join(f"{n} = {inputs[n]:g}" for n in names)
        raise ConfigError(
            key,
            f"{culprit} = {inputs[culprit]!r} makes the {label} of {section.describe()} "
            f"{value:g} {unit}, outside the range {low:g}..{high:g} that a model can "
            f"compute with ({given}; SI units)",
        )


def _optional_mass_per_length(value: Any) -> float | None:
    """``adjusted_weight`` in kg/m (a number, or a string with units), or None."""
    return None if value is None else as_si(value, "linear_density", key="adjusted_weight")


def _optional_length(value: Any) -> float | None:
    """``tool_joint_od`` in m (a number, or a string with units), or None."""
    return None if value is None else as_si(value, "length", key="tool_joint_od")


@attrs.frozen
class JointedPipe(Section):
    """Pipe joined by tool joints (drill pipe, HWDP): a body and, every joint, a tool joint.

    Parameters
    ----------
    adjusted_weight : float or str, optional
        Mass per length in air with the tool joints [kg/m] (``"22.3 lb/ft"``); default the
        body's. It sets the weight (normal force, buoyed weight, friction); the torsional
        model keeps the body's inertia and stiffness (docs/well.md, "Tool joints").
    tool_joint_od : float or str, optional
        Outer diameter of the tool joints [m] (``"6.625 in"``): the contact radius of the
        friction torque; default ``od``.
    """

    adjusted_weight: float | None = attrs.field(
        default=None,
        converter=_optional_mass_per_length,
    )
    tool_joint_od: float | None = attrs.field(
        default=None,
        converter=_optional_length,
    )

    def __attrs_post_init__(self) -> None:
        super().__attrs_post_init__()
        joint = self.tool_joint_od
        if joint is not None and not (math.isfinite(joint) and joint >= self.od):
            raise ConfigError(
                "tool_joint_od",
                f"expected a tool joint at least as wide as the body (od {self.od:g} m) and "
                f"finite, got {joint!r} m",
            )
        mass = self.adjusted_weight
        if mass is None:
            return
        body = self.body_mass_per_length
        # at most a solid bar of the widest diameter: steel cannot weigh more per length
        solid = self.material.density * math.pi / 4.0 * max(self.od, joint or 0.0) ** 2
        if not (math.isfinite(mass) and body * (1.0 - 1e-9) <= mass <= solid):
            raise ConfigError(
                "adjusted_weight",
                f"expected a mass per length in air between the body's {body:.4g} kg/m (the "
                f"tool joints add mass) and a solid bar's {solid:.4g} kg/m, got {mass!r} kg/m",
            )

    @property
    def mass_per_length(self) -> float:
        """``adjusted_weight`` [kg/m], else the body's."""
        return self.body_mass_per_length if self.adjusted_weight is None else self.adjusted_weight

    @property
    def weighed_area(self) -> float:
        """``adjusted_weight`` / rho [m²], else the body's cross-section."""
        if self.adjusted_weight is None:
            return super().weighed_area
        return self.adjusted_weight / self.material.density

    @property
    def contact_radius(self) -> float:
        """``tool_joint_od`` / 2 [m], else od/2."""
        return (self.od if self.tool_joint_od is None else self.tool_joint_od) / 2.0


# The other kinds of section add no fields: plain subclasses of the attrs class Section
# (frozen, validated, compared by kind and value); ``kind`` names each in configuration files.
class DrillPipe(JointedPipe, kind="drill_pipe", bha=False):
    """Drill pipe: the long slender upper part of the string (not BHA by default)."""


class HeavyWeightDrillPipe(JointedPipe, kind="hwdp"):
    """Heavy-weight drill pipe (HWDP): part of the BHA by default ("BHA 1" in the paper)."""


class DrillCollar(Section, kind="drill_collar"):
    """Drill collar: thick-walled BHA pipe that provides the weight on bit."""


class MWD(Section, kind="mwd"):
    """Measurement-while-drilling tool (BHA)."""


class LWD(Section, kind="lwd"):
    """Logging-while-drilling tool (BHA)."""


class Stabilizer(Section, kind="stabilizer"):
    """Stabilizer (BHA). Torsionally a short shaft of its body diameters."""


class BHASection(Section, kind="bha"):
    """Generic BHA section, e.g. "drill collars, MWD and LWD tools" lumped together."""


class Bit(Section, kind="bit"):
    """The drill bit: rigid, always last, part of the BHA.

    The bit is not a spring: its inertia rho J L is lumped into the last degree
    of freedom. Its radius (default od/2) is the R_bit of the bit-rock law.
    """

    @property
    def radius(self) -> float:
        """Bit radius R_bit = od/2 [m]."""
        return self.od / 2.0


SECTION_KINDS: dict[str, type[Section]] = {
    cls.kind: cls
    for cls in (DrillPipe, HeavyWeightDrillPipe, DrillCollar, MWD, LWD, Stabilizer, BHASection, Bit)
}
"""Section class of each ``kind`` accepted in configuration files."""
