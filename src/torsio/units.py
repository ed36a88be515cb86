"""Units at the edge: parse ``"5.5 in"``, ``"100 kN"``, ``"120 rpm"`` into SI floats.

Inside torsio every quantity is a plain float in SI units (m, kg, s, N, Pa, rad).
Strings with units are accepted only where input enters (configuration files,
command line), and are converted here: the common units of :data:`COMMON_UNITS` directly,
any other with `pint` (loaded only then). A bare number is taken as SI.

Examples
--------
>>> to_si("5.5 in", "length", key="od")
0.1397
>>> to_si("100 kN", "force", key="wob")
100000.0
>>> round(to_si("120 rpm", "angular_speed", key="rpm"), 6)
12.566371
>>> to_si(7800, "density", key="density")
7800.0
>>> to_si("5 dimensionless", "length", key="od")
Traceback (most recent call last):
...
torsio.errors.ConfigError: od: '5 dimensionless' is a pure number, not a length ...
"""

from __future__ import annotations

import functools
import math
import re
from functools import lru_cache
from typing import Any

import attrs

from torsio.errors import ConfigError

#: SI unit of each physical dimension torsio accepts, as pint understands it.
SI_UNITS: dict[str, str] = {
    "length": "m",
    "force": "N",
    "pressure": "Pa",
    "density": "kg/m**3",
    "angular_speed": "rad/s",
    "time": "s",
    "inverse_time": "1/s",
    "torque": "N*m",
    "inertia": "kg*m**2",
    "stiffness": "N*m/rad",
    "rotational_damping": "N*m*s/rad",
    "dimensionless": "",
    "mass": "kg",
    "linear_density": "kg/m",
    "axial_stiffness": "N/m",
    "axial_damping": "N*s/m",
}

RPM_TO_RAD_S = math.pi / 30.0
"""Multiply a speed in rev/min by this to get rad/s."""


#: Units read without pint (the common ones on a command line), as (dimension, factor to SI).
#: Exact factors: 1 in = 0.0254 m, 1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N.
COMMON_UNITS: dict[str, tuple[str, float]] = {
    "N": ("force", 1.0),
    "kN": ("force", 1e3),
    "MN": ("force", 1e6),
    "lbf": ("force", 4.4482216152605),
    "klbf": ("force", 4.4482216152605e3),
    "m": ("length", 1.0),
    "mm": ("length", 1e-3),
    "cm": ("length", 1e-2),
    "km": ("length", 1e3),
    "in": ("length", 0.0254),
    "ft": ("length", 0.3048),
    "Pa": ("pressure", 1.0),
    "kPa": ("pressure", 1e3),
    "MPa": ("pressure", 1e6),
    "GPa": ("pressure", 1e9),
    "s": ("time", 1.0),
    "min": ("time", 60.0),
    "h": ("time", 3600.0),
    "rpm": ("angular_speed", math.pi / 30.0),
    "rad/s": ("angular_speed", 1.0),
    "kg/m^3": ("density", 1.0),
    "g/cm^3": ("density", 1e3),
}
_NUMBER_AND_UNIT = re.compile(
    r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z][A-Za-z/^\d]*)\s*"
)


#: The largest exponent a unit may carry ("m**3", "s^-2"): pint evaluates powers, and
#: "9**9**9 N" would take it hours, so nothing else reaches it.
MAX_UNIT_EXPONENT = 4
_UNIT_TEXT = re.compile(  # a number, then names, "*", "/", spaces and parentheses
    r"\s*(?:[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)?[\sA-Za-z_µΩ°\d*/^().+-]*"
)
_POWER = re.compile(r"(\*\*|\^)\s*")
_EXPONENT = re.compile(r"\(?\s*[-+]?\d(?:\.\d+)?\s*\)?")


def check_unit_text(text: str, key: str) -> None:
    """Refuse a quantity string pint must not see: only a plain number and unit names,
    ``*``, ``/`` and parentheses, each power a small exponent of a unit name.

    Raises
    ------
    ConfigError
        Naming ``key``, for other characters or for a power that is not
        ``name**n`` / ``name^n`` with ``|n| <= MAX_UNIT_EXPONENT``.

    Examples
    --------
    >>> check_unit_text("1.2 g/cm**3", "well.mud_density")
    >>> check_unit_text("9**9**9 N", "wob")
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: wob: '9**9**9 N': a power applies to a unit name only ...
    """
    if _UNIT_TEXT.fullmatch(text) is None:
        raise ConfigError(
            key,
            f"cannot read {text!r} as a quantity: expected a number and a unit "
            "(letters, '*', '/', '**n' or '^n', parentheses), e.g. '100 kN'",
        )
    for power in _POWER.finditer(text):
        before = text[: power.start()].rstrip()
        exponent = _EXPONENT.match(text, power.end())
        if not before or not (before[-1].isalpha() or before[-1] in "_µΩ°"):
            raise ConfigError(
                key,
                f"{text!r}: a power applies to a unit name only (e.g. 'm**3'), "
                "not to a number or a group",
            )
        if exponent is None or abs(float(exponent[0].strip("() "))) > MAX_UNIT_EXPONENT:
            raise ConfigError(
                key,
                f"{text!r}: expected a unit's exponent from -{MAX_UNIT_EXPONENT} to "
                f"{MAX_UNIT_EXPONENT} after {power[1]!r}",
            )


@lru_cache(maxsize=1)
def _registry() -> Any:
    import pint  # imported lazily: only strings with units need it

    from torsio.kernel_cache import user_cache_dir

    try:  # pint's parsed definitions cached on disk: a registry in 0.1 s instead of 1 s
        return pint.UnitRegistry(cache_folder=str(user_cache_dir() / "pint"))
    except Exception:  # pragma: no cover - an unwritable cache: pint without it
        return pint.UnitRegistry()


def to_si(value: Any, dimension: str, *, key: str) -> float:
    """Convert a number or a string with units to a float in SI units.

    Parameters
    ----------
    value : float | int | str
        A bare number (taken as SI) or a string such as ``"85.3 GPa"``.
    dimension : str
        One of :data:`SI_UNITS`.
    key : str
        Name of the input, used in the error message.

    Raises
    ------
    ConfigError
        If the value is neither a finite number nor a parsable quantity of the
        expected dimension.
    """
    if isinstance(value, bool):
        raise ConfigError(key, f"expected a number or a quantity with units, got {value!r}")
    if isinstance(value, int | float):
        result = float(value)
    elif isinstance(value, str):
        try:  # a bare number in a string ("150"): SI, as a number, without loading pint
            result = float(value)
        except ValueError:
            result = _parse(value, dimension, key)
    else:
        raise ConfigError(
            key, f"expected a number or a string with units, got {type(value).__name__} {value!r}"
        )
    if not math.isfinite(result):
        raise ConfigError(key, f"expected a finite value, got {value!r}")
    return result


def _is_bare_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _parse(text: str, dimension: str, key: str) -> float:
    match = _NUMBER_AND_UNIT.fullmatch(text)
    if match is not None and COMMON_UNITS.get(match[2], ("", 0.0))[0] == dimension:
        return float(match[1]) * COMMON_UNITS[match[2]][1]  # "100 kN": no need for pint
    check_unit_text(text, key)
    import pint

    ureg = _registry()
    target = SI_UNITS[dimension]
    try:
        quantity = ureg.Quantity(text.strip())
    except Exception as exc:  # pint's parser raises many types on arbitrary text
        raise ConfigError(
            key, f"cannot read {text!r} as a quantity ({type(exc).__name__}: {exc})"
        ) from None
    if not isinstance(quantity, ureg.Quantity):  # a bare number in a string
        return float(quantity)
    if quantity.dimensionless and str(quantity.units) == "dimensionless":
        if _is_bare_number(text) or target == "":
            return float(quantity.magnitude)  # "5" is SI like the number 5
        raise ConfigError(  # "5 dimensionless" states explicitly that it has no unit
            key,
            f"{text!r} is a pure number, not a {dimension.replace('_', ' ')} "
            f"(expected units like {target})",
        )
    try:
        return float(quantity.to(target).magnitude)
    except (pint.errors.DimensionalityError, TypeError, ValueError):
        raise ConfigError(
            key, f"{text!r} is not a {dimension.replace('_', ' ')} (expected units like {target})"
        ) from None


def as_si(value: Any, dimension: str, key: str) -> float:
    """A string with units to SI (:func:`to_si`), anything else to float: for attrs converters.

    Lets Python constructors take what a configuration file takes, e.g.
    ``DrillPipe(od="5 in", ...)`` or ``Material(shear_modulus="79.3 GPa", ...)``;
    bare numbers stay SI (range checks are left to the class's validators).

    Examples
    --------
    >>> as_si("5 in", "length", "od")
    0.127
    >>> as_si(0.127, "length", "od")
    0.127
    """
    if isinstance(value, str):
        return to_si(value, dimension, key=key)
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ConfigError(key, f"expected a number or a string with units, got {value!r}") from None


def si_field(dimension: str, key: str, **field: Any) -> Any:
    """An attrs field in SI units that also takes a string with units (:func:`as_si`).

    ``key`` names the field in messages; ``field`` are the other arguments of
    ``attrs.field`` (``validator``, ``default``, ...).

    Examples
    --------
    >>> import attrs
    >>> @attrs.frozen
    ... class Pipe:
    ...     od: float = si_field("length", "od")
    >>> Pipe("5 in").od, Pipe(0.127).od
    (0.127, 0.127)
    """
    return attrs.field(converter=functools.partial(as_si, dimension=dimension, key=key), **field)


def as_rpm(value: Any, key: str = "rpm") -> float:
    """A rotary speed in rpm from ``"120 rpm"``, ``"12.6 rad/s"`` or a number (rpm).

    Examples
    --------
    >>> as_rpm("12.566370614359172 rad/s")
    120.0
    >>> as_rpm(60)
    60.0
    """
    if isinstance(value, str):
        try:  # a bare number in a string is rpm, as everywhere for this key
            return float(value)
        except ValueError:
            return to_si(value, "angular_speed", key=key) / RPM_TO_RAD_S
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ConfigError(
            key, f"expected a number (rpm) or a speed with units, got {value!r}"
        ) from None
