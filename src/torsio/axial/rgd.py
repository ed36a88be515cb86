"""The RGD bit: cutting plus wear-flat friction of a drag bit with n blades.

Richard, Germay and Detournay (2004, 2007) split the weight W and the torque T on a drag
bit of radius a into a cutting part, proportional to the depth of cut per revolution d,
and a friction part on the wear flats of the cutters:

    W_c = ζ ε a d,      T_c = ε a² d / 2
    W_f = σ a l,        T_f = μ γ a W_f / 2

with ε the intrinsic specific energy of the rock [Pa], ζ the ratio of the normal to the
tangential cutting force, σ the contact stress under the wear flats [Pa], l their length
[m], μ the friction coefficient on them and γ a number for the bit's geometry. The depth
of cut comes from the bit's own history: d = n (U(t) − U(t − t_n)), with t_n the time
the bit took to turn its last 1/n revolution, Φ(t) − Φ(t − t_n) = 2π/n.

This module holds the law's parameters and its forces while the bit drills (moving down,
turning forward, the wear flats in full contact). The set-valued phases (the bit axially
at rest, torsionally stuck, off bottom) belong to the transient and are not here.

References: T. Richard, C. Germay and E. Detournay, "Self-excited stick-slip oscillations
of drill bits", C. R. Mécanique 332 (2004) 619-626; "A simplified model to explore the
root cause of stick-slip vibrations in drilling systems with drag bits", J. Sound Vib.
305 (2007) 432-456; C. Germay, V. Denoël and E. Detournay, "Multiple mode analysis of the
self-excited vibrations of rotary drilling systems", J. Sound Vib. 325 (2009) 362-381.

Examples
--------
>>> bit = rgd_example()
>>> bit.blades, bit.radius
(4, 0.108)
>>> round(bit.friction_weight, 1)  # σ a l, N
71280.0
>>> weight, torque = bit.forces(0.005)  # 5 mm per revolution
>>> round(weight, 1), round(torque, 2)
(90720.0, 4059.07)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import attrs

from torsio.errors import ConfigError
from torsio.hookspecs import hookimpl
from torsio.units import to_si

#: The keys of a ``[bit_rock]`` table with ``law = "rgd"``, their dimension for
#: :func:`torsio.units.to_si`, and the lower bound each must exceed (strict) or reach.
RGD_KEYS: dict[str, tuple[str, float, bool]] = {
    "radius": ("length", 0.0, True),
    "blades": ("dimensionless", 1.0, False),
    "intrinsic_specific_energy": ("pressure", 0.0, True),
    "cutting_force_ratio": ("dimensionless", 0.0, True),
    "contact_stress": ("pressure", 0.0, False),
    "wear_flat_length": ("length", 0.0, False),
    "contact_friction": ("dimensionless", 0.0, False),
    "bit_geometry": ("dimensionless", 0.0, True),
}

_DESCRIPTIONS = {
    "radius": "the bit radius a [m]",
    "blades": "the number of blades n",
    "intrinsic_specific_energy": "the intrinsic specific energy ε of the rock [Pa]",
    "cutting_force_ratio": "the ratio ζ of normal to tangential cutting force",
    "contact_stress": "the contact stress σ under the wear flats [Pa]",
    "wear_flat_length": "the wear-flat length l [m]",
    "contact_friction": "the friction coefficient μ on the wear flats",
    "bit_geometry": "the bit geometry number γ",
}


def _check(key: str, value: float | int, prefix: str = "bit_rock.") -> None:
    _, bound, strict = RGD_KEYS[key]
    what = _DESCRIPTIONS[key]
    if not math.isfinite(value):
        raise ConfigError(prefix + key, f"{value!r} is not finite; expected {what}")
    if strict and value <= bound:
        raise ConfigError(prefix + key, f"{value!r} must be > {bound:g} ({what})")
    if not strict and value < bound:
        raise ConfigError(prefix + key, f"{value!r} must be >= {bound:g} ({what})")


def _validator(key: str):
    def check(_instance: Any, _attribute: Any, value: float) -> None:
        _check(key, float(value))

    return check


def _blades(_instance: Any, _attribute: Any, value: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ConfigError(
            "bit_rock.blades", f"{value!r} is not a whole number; expected the number of blades n"
        )
    _check("blades", value)


@attrs.frozen
class RGDBit:
    """A drag bit in the RGD law, all parameters in SI units.

    Parameters
    ----------
    radius : float
        Bit radius a [m].
    blades : int
        Number of blades n (>= 1).
    intrinsic_specific_energy : float
        ε [Pa], the energy to cut a unit volume of rock.
    cutting_force_ratio : float
        ζ, normal over tangential cutting force.
    contact_stress : float
        σ [Pa], the contact stress under the wear flats.
    wear_flat_length : float
        l [m], the total length of the wear flats (0: a sharp bit).
    contact_friction : float
        μ, the friction coefficient on the wear flats.
    bit_geometry : float
        γ, the bit's geometry number in T_f = μ γ a W_f / 2.

    Raises
    ------
    ConfigError
        Naming the key (``bit_rock.<name>``), the value and what was expected.

    Examples
    --------
    >>> RGDBit(0.108, 4, 60e6, 0.6, 60e6, 0.011, 0.6, 1.0).cutting_weight(0.001)
    3888.0
    >>> RGDBit(0.108, 0, 60e6, 0.6, 60e6, 0.011, 0.6, 1.0)
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: bit_rock.blades: 0 must be >= 1 (the number of blades n)
    """

    radius: float = attrs.field(converter=float, validator=_validator("radius"))
    blades: int = attrs.field(validator=_blades)
    intrinsic_specific_energy: float = attrs.field(
        converter=float, validator=_validator("intrinsic_specific_energy")
    )
    cutting_force_ratio: float = attrs.field(
        converter=float, validator=_validator("cutting_force_ratio")
    )
    contact_stress: float = attrs.field(converter=float, validator=_validator("contact_stress"))
    wear_flat_length: float = attrs.field(converter=float, validator=_validator("wear_flat_length"))
    contact_friction: float = attrs.field(converter=float, validator=_validator("contact_friction"))
    bit_geometry: float = attrs.field(
        default=1.0, converter=float, validator=_validator("bit_geometry")
    )

    name = "rgd"
    description = (
        "W = zeta eps a d + sigma a l, T = eps a^2 d / 2 + mu gamma a sigma a l / 2, "
        "d = n (U(t) - U(t - t_n)) (Richard, Germay and Detournay 2007; a law with "
        "memory, axial dynamics only)"
    )
    needs_axial = True  # axial DOFs and the history of the bit's axial position
    gives = ("torque", "weight", "rate_of_penetration")

    @property
    def hole_area(self) -> float:
        """A = π a² [m²], the area of the hole the bit drills."""
        return math.pi * self.radius**2

    @property
    def friction_weight(self) -> float:
        """W_f = σ a l [N], the weight the wear flats carry while the bit drills."""
        return self.contact_stress * self.radius * self.wear_flat_length

    @property
    def friction_torque(self) -> float:
        """T_f = μ γ a W_f / 2 [N m], the friction torque on the wear flats."""
        return self.contact_friction * self.bit_geometry * self.radius * self.friction_weight / 2

    @property
    def cutting_weight_per_depth(self) -> float:
        """ζ ε a [N/m]: the cutting weight per metre of depth of cut per revolution."""
        return self.cutting_force_ratio * self.intrinsic_specific_energy * self.radius

    @property
    def cutting_torque_per_depth(self) -> float:
        """ε a² / 2 [N m/m]: the cutting torque per metre of depth of cut per revolution."""
        return self.intrinsic_specific_energy * self.radius**2 / 2

    def cutting_weight(self, depth_of_cut: float) -> float:
        """W_c = ζ ε a d [N] for the depth of cut per revolution d [m]."""
        return self.cutting_weight_per_depth * depth_of_cut

    def cutting_torque(self, depth_of_cut: float) -> float:
        """T_c = ε a² d / 2 [N m] for the depth of cut per revolution d [m]."""
        return self.cutting_torque_per_depth * depth_of_cut

    def forces(self, depth_of_cut: float) -> tuple[float, float]:
        """Weight [N] and torque [N m] on the bit while it drills with depth of cut d [m].

        The drilling phase: the bit moves down and turns forward, d > 0, the wear flats in
        full contact: W = W_c + W_f, T = T_c + T_f.
        """
        return (
            self.cutting_weight(depth_of_cut) + self.friction_weight,
            self.cutting_torque(depth_of_cut) + self.friction_torque,
        )

    def to_dict(self) -> dict[str, Any]:
        """The parameters by their ``[bit_rock]`` keys, plain data for reports and JSON."""
        return {"law": self.name, **attrs.asdict(self)}

    @classmethod
    def describe(cls) -> dict[str, Any]:
        """The RGD bit as ``torsio laws`` lists it, as every law: name, description and the
        ``[bit_rock]`` keys with their SI units and defaults (None: required).

        >>> names = [p["name"] for p in RGDBit.describe()["parameters"]]
        >>> names[0], names[1], len(names)
        ('radius', 'blades', 8)
        """
        from torsio.units import SI_UNITS

        return {
            "name": cls.name,
            "description": cls.description,
            "parameters": [
                {
                    "name": key,
                    "unit": SI_UNITS[dimension],
                    "default": 1.0 if key == "bit_geometry" else None,
                    "description": _DESCRIPTIONS[key],
                }
                for key, (dimension, _, _) in RGD_KEYS.items()
            ],
        }


@hookimpl
def torsio_bit_laws() -> tuple[type[RGDBit], ...]:
    """The RGD bit, registered like every bit-rock law (it declares ``needs_axial``)."""
    return (RGDBit,)


def rgd_from_table(table: Mapping[str, Any], *, prefix: str = "bit_rock.") -> RGDBit:
    """Build an :class:`RGDBit` from a ``[bit_rock]`` table with ``law = "rgd"``.

    Every key of :data:`RGD_KEYS` is required but ``bit_geometry`` (default 1); values may
    be strings with units (``"60 MPa"``, ``"11 mm"``). Unknown keys are refused.

    Parameters
    ----------
    table : Mapping
        The table as read from TOML.
    prefix : str
        Dotted path of the table, for error messages.

    Raises
    ------
    ConfigError
        A missing, unknown or invalid key, named with its value and what was expected.

    Examples
    --------
    >>> table = {"law": "rgd", "radius": 0.108, "blades": 4, "intrinsic_specific_energy":
    ...          "60 MPa", "cutting_force_ratio": 0.6, "contact_stress": 60e6,
    ...          "wear_flat_length": "11 mm", "contact_friction": 0.6}
    >>> rgd_from_table(table) == rgd_example()
    True
    >>> rgd_from_table({**table, "blade": 4})
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: bit_rock.blade: unknown key of the rgd law; expected one of ...
    """
    law = table.get("law")
    if law != "rgd":
        raise ConfigError(prefix + "law", f"{law!r} is not 'rgd'; this parser reads the RGD law")
    for key in table:
        if key != "law" and key not in RGD_KEYS:
            raise ConfigError(
                prefix + key, "unknown key of the rgd law; expected one of " + ", ".join(RGD_KEYS)
            )
    values: dict[str, Any] = {}
    for key, (dimension, _, _) in RGD_KEYS.items():
        if key not in table:
            if key == "bit_geometry":
                continue
            raise ConfigError(prefix + key, f"missing; the rgd law needs {_DESCRIPTIONS[key]}")
        raw = table[key]
        if key == "blades":
            if isinstance(raw, bool) or not isinstance(raw, int):
                raise ConfigError(
                    prefix + key, f"{raw!r} is not a whole number; expected the number of blades"
                )
            values[key] = raw
            continue
        values[key] = to_si(raw, dimension, key=prefix + key)
    return RGDBit(**values)


def rgd_example() -> RGDBit:
    """The reference bit of DESIGN.md's ``[bit_rock] law = "rgd"`` table.

    a = 0.108 m (the 8½ in bit of the built-in string), n = 4, ε = 60 MPa, ζ = 0.6,
    σ = 60 MPa, l = 0.011 m, μ = 0.6, γ = 1: the values DESIGN.md lists after Richard,
    Germay and Detournay (2007) and Germay et al. (2009); the papers' own tables were not at
    hand to check them against (docs/axial.md, "Parameters").

    Examples
    --------
    >>> rgd_example().intrinsic_specific_energy
    60000000.0
    """
    return RGDBit(
        radius=0.108,
        blades=4,
        intrinsic_specific_energy=60e6,
        cutting_force_ratio=0.6,
        contact_stress=60e6,
        wear_flat_length=0.011,
        contact_friction=0.6,
        bit_geometry=1.0,
    )
