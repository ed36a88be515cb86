"""Bit-rock interaction laws: torque on bit as a function of bit speed.

Every law is a class with a unique ``name``, built from keyword parameters, whose
``torque(speed, wob, radius)`` returns the torque on bit [N m] for the bit speed
[rad/s], the weight on bit [N] and the bit radius [m], broadcasting over arrays.

Parameters that multiply the bit speed (``a1`` of Tucker-Wang has units of
s/rad) can be stated for a speed in rpm with ``speed_unit="rpm"``; they are then
converted once to rad/s: a parameter that multiplies speed^n is multiplied by
(30/pi)^n.

Examples
--------
>>> law = TuckerWang(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm")
>>> round(law.a1, 4), round(law.a2, 4), round(law.a3, 4)  # the same law in rad/s
(1.9099, 8.4989, 5.4713)
>>> round(float(law.torque(10.0, 100e3, 0.108)), 1)
2756.9
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, ClassVar

import attrs
import numpy as np

from torsio.errors import ConfigError, PluginError
from torsio.hookspecs import hookimpl
from torsio.physics.law_slope import central_difference

SPEED_UNITS: dict[str, float] = {"rad/s": 1.0, "rpm": 30.0 / math.pi}
"""Per speed unit, how many of that unit one rad/s is (1 rad/s = 30/pi rpm)."""


@attrs.frozen
class Parameter:
    """Description of one law parameter, for validation and ``torsio laws``.

    Parameters
    ----------
    unit : str
        Unit in the rad/s reading (e.g. ``"s/rad"``), ``"-"`` if dimensionless.
    description : str
        What the parameter is physically.
    default : float | None
        Value used when the parameter is not given; ``None`` makes it required.
    minimum : float
        Lower bound.
    strict : bool
        Whether the bound excludes ``minimum`` itself.
    speed_power : int
        n such that the parameter multiplies speed^n (0 for none); it converts
        between speed units.
    """

    unit: str
    description: str
    default: float | None = None
    minimum: float = 0.0
    strict: bool = False
    speed_power: int = 0


class BitRockLaw:
    """Base class of bit-rock laws: parameter validation, speed units, description.

    Subclasses set ``name``, ``parameters`` (a dict of :class:`Parameter`) and
    implement ``torque``. Validated parameters become attributes in the rad/s
    reading. ``needs_axial`` and ``gives`` are the law's declared capabilities
    (:func:`law_capabilities`): a law of the torque alone needs no axial motion.
    """

    name: ClassVar[str] = ""
    description: ClassVar[str] = ""
    parameters: ClassVar[Mapping[str, Parameter]] = {}
    needs_axial: ClassVar[bool] = False
    gives: ClassVar[tuple[str, ...]] = ("torque",)

    def __init__(self, *, speed_unit: str = "rad/s", **values: Any) -> None:
        if speed_unit not in SPEED_UNITS:
            raise ConfigError(
                "bit_rock.speed_unit", f"expected one of {sorted(SPEED_UNITS)}, got {speed_unit!r}"
            )
        unknown = sorted(set(values) - set(self.parameters))
        if unknown:
            raise ConfigError(
                f"bit_rock.{unknown[0]}",
                f"law {self.name!r} has no parameter {unknown[0]!r}; its "
                f"parameters are {', '.join(self.parameters) or 'none'}",
            )
        self.speed_unit = speed_unit
        self.given: dict[str, float] = {}
        scale = SPEED_UNITS[speed_unit]
        for key, spec in self.parameters.items():
            stated = key in values  # a default is in the rad/s reading, never converted
            value = values[key] if stated else spec.default
            if value is None:
                raise ConfigError(
                    f"bit_rock.{key}",
                    f"law {self.name!r} needs parameter {key!r} ({spec.description}, {spec.unit})",
                )
            if isinstance(value, bool) or not isinstance(value, int | float | np.floating):
                raise ConfigError(f"bit_rock.{key}", f"expected a number, got {value!r}")
            value = float(value)
            low_ok = value > spec.minimum if spec.strict else value >= spec.minimum
            if not (math.isfinite(value) and low_ok):
                bound = ">" if spec.strict else ">="
                raise ConfigError(
                    f"bit_rock.{key}",
                    f"law {self.name!r}: {key} must be "
                    f"{bound} {spec.minimum:g} and finite, got {value!r}",
                )
            if stated:
                self.given[key] = value
            setattr(self, key, value * scale**spec.speed_power if stated else value)

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """Torque on bit [N m] at bit speed [rad/s], weight on bit [N], bit radius [m]."""
        raise NotImplementedError

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """d torque / d speed [N m s/rad]; a central difference unless a law overrides it."""
        return np.asarray(central_difference(self.torque, np.asarray(speed, float), wob, radius))

    def values(self) -> dict[str, float]:
        """The parameters in the rad/s reading."""
        return {key: float(getattr(self, key)) for key in self.parameters}

    def __repr__(self) -> str:
        given = ", ".join(f"{k}={v!r}" for k, v in self.given.items())
        unit = "" if self.speed_unit == "rad/s" else f", speed_unit={self.speed_unit!r}"
        return f"{type(self).__name__}({given}{unit})"

    def __eq__(self, other: object) -> bool:
        return (
            isinstance(other, BitRockLaw)
            and type(other) is type(self)
            and (self.values() == other.values())
        )

    def __hash__(self) -> int:
        return hash((type(self), tuple(sorted(self.values().items()))))

    @classmethod
    def describe(cls) -> dict[str, Any]:
        """Name, description and parameters, as ``torsio laws --json`` prints them."""
        return {
            "name": cls.name,
            "description": cls.description,
            "parameters": [
                {
                    "name": key,
                    "unit": spec.unit,
                    "description": spec.description,
                    "default": spec.default,
                    "minimum": spec.minimum,
                    "speed_power": spec.speed_power,
                }
                for key, spec in cls.parameters.items()
            ],
        }


# --- the formulas, written once: numpy arrays here, numba scalars in the batch kernel -------
def _arrays(speed: Any, wob: Any, radius: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return np.asarray(speed, dtype=float), np.asarray(wob), np.asarray(radius)


def tucker_wang_torque(p: Any, w: Any, wob: Any, radius: Any) -> Any:
    """Tucker-Wang torque [N m] for parameters p = (a0, a1, a2, a3) in the rad/s reading."""
    return wob * radius * p[0] * (np.tanh(p[1] * w) + p[2] * w / (1.0 + p[3] * w * w))


def tucker_wang_slope(p: Any, w: Any, wob: Any, radius: Any) -> Any:
    """d torque / d speed [N m s/rad] of :func:`tucker_wang_torque`."""
    c = np.cosh(p[1] * w)
    d = 1.0 + p[3] * w * w
    return wob * radius * p[0] * (p[1] / (c * c) + p[2] * (1.0 - p[3] * w * w) / (d * d))


def constant_torque(p: Any, w: Any, wob: Any, radius: Any) -> float:
    """The constant torque ``p[0]`` in N m (the compiled form of :class:`ConstantTorque`)."""
    return p[0]


def constant_slope(p: Any, w: Any, wob: Any, radius: Any) -> float:
    """Zero: the constant torque does not depend on the speed."""
    return 0.0


class TuckerWang(BitRockLaw):
    """Tucker-Wang bit-rock law (paper Eq. 2).

    T = W_ob R_bit a0 (tanh(a1 w) + a2 w / (1 + a3 w^2)), w the bit speed.

    The paper (Ritto et al. 2017 data) gives a0 = 0.221, a1 = 0.2 s, a2 = 0.89 s,
    a3 = 0.06 s^2 without saying whether w is in rad/s or rpm; pass
    ``speed_unit="rpm"`` for the rpm reading (see the theory documentation).
    """

    name = "tucker-wang"
    description = "W R a0 (tanh(a1 w) + a2 w / (1 + a3 w^2))  (Tucker and Wang 1997, Eq. 2)"
    parameters = {
        "a0": Parameter("-", "friction coefficient scale", minimum=0.0, strict=True),
        "a1": Parameter(
            "s/rad", "tanh regularization of the sign", minimum=0.0, strict=True, speed_power=1
        ),
        "a2": Parameter("s/rad", "slope of the velocity-weakening term", speed_power=1),
        "a3": Parameter("s^2/rad^2", "speed scale of the velocity weakening", speed_power=2),
    }
    a0: float
    a1: float
    a2: float
    a3: float

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        return tucker_wang_torque(self._vector(), *_arrays(speed, wob, radius))

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """d torque / d speed [N m s/rad], analytic."""
        return tucker_wang_slope(self._vector(), *_arrays(speed, wob, radius))

    def _vector(self) -> np.ndarray:
        return np.array([self.a0, self.a1, self.a2, self.a3])

    def kernel(self) -> tuple[Any, Any, np.ndarray]:
        """Compiled torque and slope for the batch engine (:mod:`torsio.solvers.law_kernels`)."""
        from torsio.solvers.law_kernels import compile_law_function

        return (
            compile_law_function(tucker_wang_torque),
            compile_law_function(tucker_wang_slope),
            self._vector(),
        )


class ConstantTorque(BitRockLaw):
    """A constant torque on bit, whatever the speed: for static checks and tests.

    T = torque_on_bit [N m] (weight on bit and radius are ignored by definition).
    """

    name = "constant"
    description = "T = torque_on_bit, independent of speed, weight on bit and radius"
    parameters = {"torque_on_bit": Parameter("N m", "torque on bit", minimum=-math.inf)}
    torque_on_bit: float

    def torque(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """The constant torque [N m], broadcast to the shape of the inputs."""
        shape = np.broadcast_shapes(np.shape(speed), np.shape(wob), np.shape(radius))
        return np.full(shape, self.torque_on_bit)

    def slope(self, speed: Any, wob: Any, radius: Any) -> np.ndarray:
        """Zero [N m s/rad], broadcast to the shape of the inputs."""
        return self.torque(speed, wob, radius) * 0.0

    def kernel(self) -> tuple[Any, Any, np.ndarray]:
        """Compiled torque and slope for the batch engine (:mod:`torsio.solvers.law_kernels`)."""
        from torsio.solvers.law_kernels import compile_law_function

        return (
            compile_law_function(constant_torque),
            compile_law_function(constant_slope),
            np.array([self.torque_on_bit]),
        )


LAW_OUTPUTS = ("torque", "weight", "rate_of_penetration")
"""What a law may declare it gives (``gives``): the torque on bit [N m], and with axial
dynamics the weight on bit [N] and the rate of penetration [m/s] of its own."""


def law_capabilities(law: Any) -> dict[str, Any]:
    """What a law class (or object) declares it needs and gives, with the defaults of a law
    that declares nothing (the plugin contract: only ``name``, keyword parameters and
    ``torque(speed, wob, radius)``).

    ``needs_axial``: the law needs axial degrees of freedom and the history of the bit's
    axial position (absent: False); ``gives``: what it computes, among :data:`LAW_OUTPUTS`
    (absent: ``("torque",)``, the torque of ``torque(speed, wob, radius)`` at the weight on
    bit it is given).

    Examples
    --------
    >>> law_capabilities(TuckerWang)
    {'needs_axial': False, 'gives': ['torque']}
    >>> class Plain:  # a plugin law written from the contract alone
    ...     name = "plain"
    >>> law_capabilities(Plain)["needs_axial"]
    False
    """
    needs_axial = getattr(law, "needs_axial", False)
    gives = getattr(law, "gives", ("torque",))
    name = getattr(law, "name", None) or getattr(law, "__name__", repr(law))
    if not isinstance(needs_axial, bool):
        raise PluginError(f"law {name!r}: needs_axial must be True or False, got {needs_axial!r}")
    if isinstance(gives, str) or not set(gives) <= set(LAW_OUTPUTS) or "torque" not in gives:
        raise PluginError(
            f"law {name!r}: gives must list the torque and any of {', '.join(LAW_OUTPUTS)}, "
            f"got {gives!r}"
        )
    return {"needs_axial": needs_axial, "gives": list(gives)}


BUILTIN_LAWS: tuple[type[BitRockLaw], ...] = (TuckerWang, ConstantTorque)


@hookimpl
def torsio_bit_laws() -> tuple[type[BitRockLaw], ...]:
    """The built-in bit-rock laws, registered like any plugin's."""
    return BUILTIN_LAWS
