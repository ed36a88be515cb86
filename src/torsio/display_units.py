"""Units of printed tables and plots: SI (kN, kN m, m) or oilfield (klbf, kft·lbf, ft).

Results stay in SI everywhere (JSON included); only what a person reads is converted,
by a :class:`DisplayUnits` chosen with ``--units si|field``. Each quantity has one unit
in each system, and one factor from SI; the factors are exact by definition
(NIST SP 811, appendix B.8): 1 ft = 12 in = 0.3048 m, 1 lbf = 4.4482216152605 N,
1 lb = 0.45359237 kg, 1 US gal = 3.785411784e-3 m^3, 1 rev = 2 pi rad.

Examples
--------
>>> field = DisplayUnits("field")
>>> field.label("force"), round(field.value("force", 444822.16152605), 9)
('klbf', 100.0)
>>> field.text("torque", 13558.179483314004, ".2f"), field.text("length", 304.8, ".0f")
('10.00 kft·lbf', '1000 ft')
>>> DisplayUnits("si").text("force", 80e3, ".1f"), DisplayUnits("si").header("hookload", "force")
('80.0 kN', 'hookload [kN]')
>>> DisplayUnits("si").energy(2.623e7), DisplayUnits("si").energy(850.0)
('26.23 MJ', '850 J')
>>> DisplayUnits("field").energy(2.623e7)
'19,346 kft·lbf'
"""

from __future__ import annotations

import math

import attrs

from torsio.errors import ConfigError

__all__ = ["UNIT_SYSTEMS", "DisplayUnits"]

FOOT = 0.3048
POUND_FORCE = 4.4482216152605
POUND = 0.45359237
US_GALLON = 3.785411784e-3

#: Unit label and factor from SI (display = SI x factor) of each quantity, by system.
UNIT_SYSTEMS: dict[str, dict[str, tuple[str, float]]] = {
    "si": {
        "length": ("m", 1.0),
        "diameter": ("mm", 1e3),
        "force": ("kN", 1e-3),
        "torque": ("kN m", 1e-3),
        "speed": ("rpm", 30.0 / math.pi),
        "density": ("kg/m³", 1.0),
        "weight_per_length": ("kg/m", 1.0),
    },
    "field": {
        "length": ("ft", 1.0 / FOOT),
        "diameter": ("in", 12.0 / FOOT),
        "force": ("klbf", 1e-3 / POUND_FORCE),
        "torque": ("kft·lbf", 1e-3 / (FOOT * POUND_FORCE)),
        "speed": ("rpm", 30.0 / math.pi),
        "density": ("ppg", US_GALLON / POUND),
        "weight_per_length": ("lb/ft", FOOT / POUND),
    },
}

_ENERGY_PREFIXES = (("G", 1e9), ("M", 1e6), ("k", 1e3), ("", 1.0))


@attrs.frozen
class DisplayUnits:
    """The units tables and plots are printed in.

    Parameters
    ----------
    system : str
        ``"si"`` (default) or ``"field"`` (:data:`UNIT_SYSTEMS`).
    """

    system: str = attrs.field(default="si")

    @system.validator
    def _known(self, _: attrs.Attribute, value: str) -> None:
        if value not in UNIT_SYSTEMS:
            raise ConfigError(
                "--units", f"unknown unit system {value!r}; expected one of si, field"
            )

    def label(self, quantity: str) -> str:
        """The unit ``quantity`` is shown in (e.g. ``"klbf"``)."""
        return UNIT_SYSTEMS[self.system][quantity][0]

    def value(self, quantity: str, si: float) -> float:
        """``si`` (a value in SI units) in the unit of :meth:`label`."""
        return si * UNIT_SYSTEMS[self.system][quantity][1]

    def number(self, quantity: str, si: float, spec: str) -> str:
        """The number alone, formatted with ``spec`` (e.g. ``".1f"``)."""
        return format(self.value(quantity, si), spec)

    def text(self, quantity: str, si: float, spec: str) -> str:
        """The number and its unit: ``"80.0 kN"``."""
        return f"{self.number(quantity, si, spec)} {self.label(quantity)}"

    def header(self, name: str, quantity: str) -> str:
        """A column header carrying its unit: ``"hookload [klbf]"``."""
        return f"{name} [{self.label(quantity)}]"

    def energy(self, joules: float) -> str:
        """An energy without an exponent: SI with a prefix, four significant figures
        (``"26.23 MJ"``); field in kft·lbf, the rig's torque unit, thousands grouped
        (``"19,346 kft·lbf"``)."""
        if self.system == "field":
            value = joules / (FOOT * POUND_FORCE) / 1e3
            return f"{value:,.0f} kft·lbf" if abs(value) >= 1e3 else f"{value:.4g} kft·lbf"
        for prefix, scale in _ENERGY_PREFIXES:
            if abs(joules) >= scale or scale == 1.0:
                return f"{joules / scale:.4g} {prefix}J"
        raise AssertionError("unreachable")  # pragma: no cover
