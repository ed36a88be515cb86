"""Checks shared by the tables of the configuration file, and the drill-string tables.

Keys of a table, strings, numbers with units, rotary speeds; ``[[section]]`` and
``[material]`` are read here; :mod:`torsio.config.reading` reads the rest and assembles
the :class:`~torsio.config.configuration.Config`. Every error names its key.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from typing import Any

from torsio.errors import ConfigError
from torsio.model.components import SECTION_KINDS, JointedPipe, Material, Section
from torsio.units import RPM_TO_RAD_S, to_si

SECTION_KEYS = {
    "kind",
    "od",
    "id",
    "length",
    "name",
    "bha",
    "material",
    "adjusted_weight",
    "tool_joint_od",
}
JOINT_KEYS = ("adjusted_weight", "tool_joint_od")
"""Keys of drill pipe and HWDP only (:class:`torsio.model.components.JointedPipe`)."""
MATERIAL_KEYS = {"shear_modulus", "density", "youngs_modulus"}


# --- tables ---------------------------------------------------------------------------------
def _table(value: Any, key: str, allowed: set[str]) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise ConfigError(key, f"expected a table, got {value!r}")
    unknown = sorted(set(value) - allowed)
    if unknown:
        where = f"{key}." if key else ""
        raise ConfigError(
            f"{where}{unknown[0]}", f"unknown key; expected one of {', '.join(sorted(allowed))}"
        )
    return value


def _option_error(strategy: str, exc: TypeError) -> ConfigError:
    """The error for a discretizer that refused its options: the option named if possible."""
    unexpected = re.search(r"unexpected keyword argument '(\w+)'", str(exc))
    if unexpected:  # an option of another strategy (drag_spacing for C, ...)
        key = unexpected.group(1)
        return ConfigError(
            f"discretization.{key}", f"strategy {strategy!r} takes no option {key!r}"
        )
    return ConfigError("discretization", f"strategy {strategy!r}: {exc}")


def _string(value: Any, key: str) -> str:
    if not isinstance(value, str):
        raise ConfigError(key, f"expected a string, got {value!r}")
    return value


def _material(value: Any, key: str, default: Material) -> Material:
    if value is None:
        return default
    table = _table(value, key, MATERIAL_KEYS)
    try:
        return Material(
            shear_modulus=to_si(
                table.get("shear_modulus", default.shear_modulus),
                "pressure",
                key=f"{key}.shear_modulus",
            ),
            density=to_si(table.get("density", default.density), "density", key=f"{key}.density"),
            youngs_modulus=_optional_modulus(
                table.get("youngs_modulus", default.youngs_modulus), f"{key}.youngs_modulus"
            ),
        )
    except ConfigError as exc:
        full_key = exc.key if exc.key.startswith(key) else f"{key}.{exc.key}"
        raise ConfigError(full_key, exc.message) from None


def _optional_modulus(value: Any, key: str) -> float | None:
    """Young's modulus [Pa] of a material table (None: not given; Material checks it)."""
    return None if value is None else to_si(value, "pressure", key=key)


def _section(raw: Any, key: str, default_material: Material) -> Section:
    table = _table(raw, key, SECTION_KEYS)
    for required in ("kind", "od", "id", "length"):
        if required not in table:
            raise ConfigError(f"{key}.{required}", "missing required key")
    kind = table["kind"]
    if not isinstance(kind, str) or kind not in SECTION_KINDS:
        raise ConfigError(
            f"{key}.kind",
            f"unknown section kind {kind!r}; expected one of {', '.join(SECTION_KINDS)}",
        )
    bha = table.get("bha")
    if bha is not None and not isinstance(bha, bool):
        raise ConfigError(f"{key}.bha", f"expected true or false, got {bha!r}")
    values = {
        name: to_si(table[name], "length", key=f"{key}.{name}") for name in ("od", "id", "length")
    }
    for name in JOINT_KEYS:
        if name not in table:
            continue
        if not issubclass(SECTION_KINDS[kind], JointedPipe):
            raise ConfigError(
                f"{key}.{name}",
                f"a {kind} section has no tool joints; expected {name} on drill_pipe or hwdp only",
            )
        dimension = "linear_density" if name == "adjusted_weight" else "length"
        values[name] = to_si(table[name], dimension, key=f"{key}.{name}")
    try:
        return SECTION_KINDS[kind](
            **values,
            material=_material(table.get("material"), f"{key}.material", default_material),
            name=_string(table.get("name", ""), f"{key}.name"),
            bha=bha,
        )
    except ConfigError as exc:
        # a value of the file's [material] (the section has none of its own) keeps its key
        inherited = exc.key.startswith("material.") and "material" not in table
        full_key = exc.key if inherited or exc.key.startswith(f"{key}.") else f"{key}.{exc.key}"
        raise ConfigError(full_key, exc.message) from None


def _positive_number(value: Any, key: str, dimension: str, allow_zero: bool = True) -> float:
    number = to_si(value, dimension, key=key)
    if number < 0 or (number == 0 and not allow_zero):
        raise ConfigError(
            key, f"expected a {'non-negative' if allow_zero else 'positive'} value, got {value!r}"
        )
    return number


def parse_rpm(value: Any, key: str) -> float:
    """A rotary speed in rpm: a bare number (or numeric string) is rpm; a string may carry
    any angular-speed unit (``"10 rad/s"``)."""
    rpm: float
    if isinstance(value, str):
        try:
            rpm = float(value)
        except ValueError:
            rpm = to_si(value, "angular_speed", key=key) / RPM_TO_RAD_S
    else:
        rpm = to_si(value, "dimensionless", key=key)
    if not (math.isfinite(rpm) and rpm > 0):
        raise ConfigError(key, f"expected a positive rotary speed in rpm, got {value!r}")
    return rpm
