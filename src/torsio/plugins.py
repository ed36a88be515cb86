"""The plugin manager: collects bit-rock laws, top drives and discretizers from every plugin.

Built-in plugins are registered first, then the entry points of group ``torsio``.
A broken plugin (import error, hook raising, a class without ``name``, a name
already taken) is reported with a :class:`PluginWarning` naming it and skipped;
the other plugins keep working.

Examples
--------
>>> sorted(discretizers())
['A', 'B', 'C', 'consistent', 'mixed', 'wave']
>>> "tucker-wang" in bit_laws()
True
>>> sorted(top_drives())
['constant-speed', 'pi', 'recorded', 'soft-torque', 'torque', 'z-torque']
"""

from __future__ import annotations

import warnings
from functools import lru_cache
from typing import Any

import attrs
import pluggy

from torsio import hookspecs
from torsio.errors import ConfigError, PluginError, TorsioError


class PluginWarning(UserWarning):
    """A plugin could not be loaded or conflicts with another one."""


@lru_cache(maxsize=1)
def plugin_manager() -> pluggy.PluginManager:
    """The process-wide plugin manager, built on first use."""
    from torsio.axial import rgd
    from torsio.model import discretize, wave
    from torsio.physics import laws, top_drives

    manager = pluggy.PluginManager("torsio")
    manager.add_hookspecs(hookspecs)
    manager.register(laws, name="torsio.physics.laws")
    manager.register(rgd, name="torsio.axial.rgd")
    manager.register(top_drives, name="torsio.physics.top_drives")
    manager.register(discretize, name="torsio.model.discretize")
    manager.register(wave, name="torsio.model.wave")
    _load_entry_points(manager)
    return manager


def _load_entry_points(manager: pluggy.PluginManager) -> None:
    from importlib.metadata import entry_points

    for entry_point in entry_points(group="torsio"):
        label = f"{entry_point.name} = {entry_point.value}"
        if manager.get_plugin(entry_point.name) is not None or manager.is_blocked(entry_point.name):
            continue
        try:
            plugin = entry_point.load()
            manager.register(plugin, name=entry_point.name)
        except Exception as exc:  # a broken third-party plugin must not stop torsio
            dist = getattr(entry_point, "dist", None)
            where = f" from distribution {dist.name!r}" if dist is not None else ""
            warnings.warn(
                f"torsio plugin {label!r}{where} failed to load and is skipped: "
                f"{type(exc).__name__}: {exc}",
                PluginWarning,
                stacklevel=2,
            )


def _collect(hook_name: str, kind: str) -> dict[str, type[Any]]:
    return _collect_with_owners(hook_name, kind)[0]


def _collect_with_owners(hook_name: str, kind: str) -> tuple[dict[str, type[Any]], dict[str, str]]:
    manager = plugin_manager()
    found: dict[str, type[Any]] = {}
    owner: dict[str, str] = {}
    for impl in getattr(manager.hook, hook_name).get_hookimpls():  # registration order
        plugin = impl.plugin_name
        try:
            classes = list(impl.function())
        except Exception as exc:
            warnings.warn(
                f"torsio plugin {plugin!r}: hook {hook_name} raised "
                f"{type(exc).__name__}: {exc}; its {kind}s are skipped",
                PluginWarning,
                stacklevel=3,
            )
            continue
        for cls in classes:
            name = getattr(cls, "name", None)
            if not isinstance(name, str) or not name:
                warnings.warn(
                    f"torsio plugin {plugin!r}: {kind} {cls!r} has no string "
                    "attribute 'name'; skipped",
                    PluginWarning,
                    stacklevel=3,
                )
                continue
            if name in found:
                warnings.warn(
                    f"torsio plugin {plugin!r}: {kind} name {name!r} is already "
                    f"registered by {owner[name]!r}; the second one is skipped",
                    PluginWarning,
                    stacklevel=3,
                )
                continue
            found[name] = cls
            owner[name] = plugin
    return found, owner


def bit_laws() -> dict[str, type[Any]]:
    """Every registered bit-rock law class, by name."""
    return _collect("torsio_bit_laws", "bit-rock law")


def discretizers() -> dict[str, type[Any]]:
    """Every registered discretizer class, by name."""
    return _collect("torsio_discretizers", "discretizer")


def top_drives() -> dict[str, type[Any]]:
    """Every registered top-drive class, by name."""
    return _collect("torsio_top_drives", "top drive")


def get_top_drive(name: str) -> type[Any]:
    """The top-drive class registered as ``name``; a clear error if there is none."""
    found = top_drives()
    if name not in found:
        raise ConfigError(
            "top_drive.kind",
            f"unknown top drive {name!r}; registered: {', '.join(sorted(found))}",
        )
    return found[name]


def get_bit_law(name: str) -> type[Any]:
    """The bit-rock law class registered as ``name``; a clear error if there is none."""
    laws = bit_laws()
    if name not in laws:
        raise ConfigError(
            "bit_rock.law",
            f"unknown bit-rock law {name!r}; registered laws: {', '.join(sorted(laws))}",
        )
    return laws[name]


def axial_need(name: str) -> str:
    """Why a model without axial dynamics refuses the law ``name`` that declares
    ``needs_axial`` (the message of ``bit_rock.law``), and what would take it.

    Examples
    --------
    >>> axial_need("rgd")[:36]
    'the rgd law needs axial dynamics (it'
    """
    return (
        f"the {name} law needs axial dynamics (it declares needs_axial: axial degrees of "
        "freedom and the history of the bit's axial position): give [chain] masses (or, for "
        "a [[section]] string, [material] youngs_modulus); the torsional engines take a law "
        "with torque(speed, wob, radius)"
    )


def get_discretizer(name: str) -> type[Any]:
    """The discretizer class registered as ``name``; a clear error if there is none."""
    found = discretizers()
    if name not in found:
        raise ConfigError(
            "discretization.strategy",
            f"unknown strategy {name!r}; registered: {', '.join(sorted(found))}",
        )
    return found[name]


def build_law(cls: type[Any], parameters: dict[str, Any], speed_unit: str = "rad/s") -> Any:
    """A bit-rock law built from keyword ``parameters``; errors name the law and the key.

    ``speed_unit`` reaches only a law whose constructor names it or that is a
    :class:`torsio.physics.laws.BitRockLaw`; for a plain class following the contract,
    the rad/s reading is the only one, and another unit is a ConfigError. Unknown or
    missing parameters, and a constructor that raises TypeError or ValueError, become a
    ConfigError naming the law and the key, never a traceback.

    Examples
    --------
    >>> class Viscous:
    ...     name = "viscous"
    ...     def __init__(self, c):
    ...         self.c = c
    ...     def torque(self, speed, wob, radius):
    ...         return self.c * speed
    >>> build_law(Viscous, {"c": 2.0}).c
    2.0
    >>> build_law(Viscous, {"k": 2.0})
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: bit_rock.k: law 'viscous' has no parameter 'k'; its parameters are c
    """
    import inspect

    from torsio.physics.laws import SPEED_UNITS, BitRockLaw

    name = getattr(cls, "name", cls.__name__)
    try:
        signature = inspect.signature(cls)
    except (TypeError, ValueError):  # a constructor without an inspectable signature
        signature = None
    values = dict(parameters)
    if speed_unit not in SPEED_UNITS:  # the readings a configuration may give, for every law
        raise ConfigError(
            "bit_rock.speed_unit", f"expected one of {sorted(SPEED_UNITS)}, got {speed_unit!r}"
        )
    if signature is not None:
        accepted = signature.parameters
        takes_any = any(p.kind is p.VAR_KEYWORD for p in accepted.values())
        if "speed_unit" in accepted or issubclass(cls, BitRockLaw):
            values["speed_unit"] = speed_unit
        elif speed_unit != "rad/s":
            raise ConfigError(
                "bit_rock.speed_unit",
                f"law {name!r} takes its parameters in the rad/s reading only; "
                f"got speed_unit = {speed_unit!r}",
            )
        named = [
            key
            for key, p in accepted.items()
            if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY) and key != "speed_unit"
        ]
        unknown = sorted(set(values) - set(accepted) - {"speed_unit"})
        if unknown and not takes_any:
            raise ConfigError(
                f"bit_rock.{unknown[0]}",
                f"law {name!r} has no parameter {unknown[0]!r}; its parameters are "
                f"{', '.join(named) or 'none'}",
            )
        for key, p in accepted.items():
            if p.default is p.empty and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY):
                if key not in values:
                    raise ConfigError(f"bit_rock.{key}", f"law {name!r} needs parameter {key!r}")
    try:
        return cls(**values)
    except ConfigError:
        raise
    except (TypeError, ValueError) as exc:
        key = next((k for k in parameters if repr(k) in str(exc)), "law")
        raise ConfigError(
            f"bit_rock.{key}", f"law {name!r} rejected its parameters {parameters!r}: {exc}"
        ) from None


def bit_law_origin(name: str) -> str:
    """Where the bit-rock law ``name`` comes from, for messages.

    ``"built-in"`` for torsio's own laws, else ``"plugin 'P' from distribution 'D'"``.

    Examples
    --------
    >>> bit_law_origin("tucker-wang")
    'built-in'
    """
    owner = _collect_with_owners("torsio_bit_laws", "bit-rock law")[1].get(name)
    if owner is None or owner.startswith("torsio."):  # torsio.physics.laws, torsio.axial.rgd
        return "built-in"
    from importlib.metadata import entry_points

    for entry_point in entry_points(group="torsio"):
        if entry_point.name == owner:
            dist = getattr(entry_point, "dist", None)
            if dist is not None:
                return f"plugin {owner!r} from distribution {dist.name!r}"
    return f"plugin {owner!r}"


def describe_bit_law(law: Any) -> str:
    """The name of a bit-rock law object and where it comes from, for error messages.

    Examples
    --------
    >>> describe_bit_law(build_bit_law("constant", {"torque_on_bit": 5e3}))
    "'constant' (built-in)"
    """
    name = getattr(law, "name", "") or type(law).__name__
    try:
        origin = bit_law_origin(name)
    except Exception:  # naming must never hide the error being reported
        return repr(name)
    return f"{name!r} ({origin})"


PROBE_SPEEDS = (-1.0, 0.0, 1.0, 10.0)
"""Bit speeds [rad/s] at which a new law's torque is tried once (a scalar, then an array)."""


def build_bit_law(
    name: str,
    parameters: Any = None,
    speed_unit: str = "rad/s",
    wob: float = 100e3,
    radius: float = 0.1,
) -> Any:
    """Build the bit-rock law ``name`` from its parameters and probe its torque once.

    The probe calls ``torque`` on a scalar speed and on an array of
    :data:`PROBE_SPEEDS` at ``wob`` [N] and ``radius`` [m]: each must give finite
    values of the broadcast shape. Any failure of a law (its constructor raising,
    a wrong shape, a non-finite torque) becomes a :class:`~torsio.errors.ConfigError`
    (bad parameters) or :class:`~torsio.errors.PluginError` (a broken law) that names
    the law and the plugin distribution it comes from.

    Examples
    --------
    >>> build_bit_law("constant", {"torque_on_bit": 5e3})
    ConstantTorque(torque_on_bit=5000.0)
    >>> build_bit_law("tucker-wang", {"a0": -1.0, "a1": 1.0})
    Traceback (most recent call last):
    ...
    torsio.errors.ConfigError: bit_rock.a0: law 'tucker-wang': a0 must be > 0 and finite, got -1.0
    """
    import numpy as np

    from torsio.physics.laws import law_capabilities

    law_class = get_bit_law(name)
    origin = bit_law_origin(name)
    what = f"bit-rock law {name!r} ({origin})"
    if law_capabilities(law_class)["needs_axial"]:
        raise ConfigError("bit_rock.law", axial_need(name))
    try:
        law = build_law(law_class, dict(parameters or {}), speed_unit)
    except ConfigError as exc:
        if origin == "built-in":
            raise
        raise ConfigError(exc.key, f"{exc.message} ({origin})") from None
    except TorsioError:
        raise
    except Exception as exc:
        raise PluginError(
            f"{what} failed in its constructor: {type(exc).__name__}: {exc}"
        ) from None
    speeds = np.array(PROBE_SPEEDS)
    for probe, shape in ((1.0, ()), (speeds, speeds.shape)):
        try:
            with np.errstate(all="ignore"):
                torque = np.asarray(law.torque(probe, wob, radius), dtype=float)
        except TorsioError:
            raise
        except Exception as exc:
            raise PluginError(
                f"{what}: torque(speed={probe!r}, wob={wob:g}, radius={radius:g}) raised "
                f"{type(exc).__name__}: {exc}"
            ) from None
        if torque.shape != shape:
            raise PluginError(
                f"{what}: torque(speed, wob, radius) must return the broadcast shape of "
                f"its inputs; for speed of shape {shape} it returned shape {torque.shape}"
            )
        if not np.all(np.isfinite(torque)):
            raise ConfigError(
                "bit_rock",
                f"{what}: torque is not finite at speed {probe!r} rad/s, wob {wob:g} N, "
                f"radius {radius:g} m (got {torque.tolist()!r}); check its parameters",
            )
    return law


def top_drive_from_parameters(kind: str, **parameters: Any) -> Any:
    """The top drive of kind ``kind`` (any registered name) built from keyword parameters.

    Errors name ``top_drive.kind`` for an unknown kind and ``top_drive.<key>``
    for an unknown, missing or invalid parameter.
    """
    cls = get_top_drive(kind)
    if attrs.has(cls):
        fields = attrs.fields_dict(cls)
        unknown = sorted(set(parameters) - set(fields))
        if unknown:
            raise ConfigError(
                f"top_drive.{unknown[0]}",
                f"top drive {kind!r} has no parameter {unknown[0]!r}; its parameters are "
                f"{', '.join(fields) or 'none'}",
            )
        missing = [
            key
            for key, field in fields.items()
            if field.default is attrs.NOTHING and field.init and key not in parameters
        ]
        if missing:
            raise ConfigError(
                f"top_drive.{missing[0]}", f"top drive {kind!r} needs parameter {missing[0]!r}"
            )
    try:
        return cls(**parameters)
    except ConfigError:
        raise
    except (TypeError, ValueError) as exc:
        raise ConfigError(
            "top_drive", f"top drive {kind!r} rejected its parameters: {exc}"
        ) from None
