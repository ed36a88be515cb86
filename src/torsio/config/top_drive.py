"""The ``[top_drive]`` table: which top drive turns the string, and its parameters.

``kind`` is a registered top-drive name (``constant-speed`` when the table or the key is
absent; ``torsio.plugins.top_drives()`` lists them, plugins included). Every other key is
a parameter of that kind, a bare SI number or a string with units (``"2900 kg*m^2"``,
``"10 kN*m"``); unknown keys are errors naming the key. The top drive is built at reading
so that every error shows up with the file (see :mod:`torsio.physics.top_drives`).

Examples
--------
>>> config = parse_top_drive({"kind": "torque", "inertia": "930 kg*m^2", "torque": "10 kN*m"})
>>> config.kind, config.parameters["torque"]
('torque', 10000.0)
>>> parse_top_drive({"kind": "pi", "inertia": 2900.0, "kp": 1.0, "ki": 1.0, "gain": 2.0})
Traceback (most recent call last):
...
torsio.errors.ConfigError: top_drive.gain: top drive 'pi' has no parameter 'gain'; ...
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import attrs

from torsio.errors import ConfigError
from torsio.physics.top_drives import PARAMETER_DIMENSIONS as BUILTIN_DIMENSIONS
from torsio.units import SI_UNITS, to_si

DEFAULT_KIND = "constant-speed"
"""The top drive when ``[top_drive]`` (or its ``kind``) is absent: the paper's boundary."""

PARAMETER_DIMENSIONS: dict[str, str] = BUILTIN_DIMENSIONS
"""Physical dimension of each parameter of the built-in top drives (for strings with units).

A plugin top drive may declare its own in a class attribute ``parameter_dimensions``
(parameter name to a dimension of :data:`torsio.units.SI_UNITS`); its other parameters
take bare SI numbers.
"""

NO_SET_SPEED = ("torque",)
"""Kinds whose speed follows from a torque balance: no rotary speed may be set for them."""

SPEED_FOLLOWS = {
    "torque": "its speed follows from the torque balance",
    "recorded": "its speed follows the recording (top_drive.recording)",
}
"""Why a kind takes no rotary speed from the command line (``--rpm``)."""


@attrs.frozen
class TopDriveConfig:
    """The ``[top_drive]`` table: the kind and its parameters in SI units."""

    kind: str = DEFAULT_KIND
    parameters: Mapping[str, Any] = attrs.field(factory=dict)

    @property
    def has_set_speed(self) -> bool:
        """Whether the kind turns at a set speed (``--rpm``); False for ``torque``."""
        return self.kind not in NO_SET_SPEED

    @property
    def speed_follows(self) -> str | None:
        """Why the kind takes no ``--rpm`` (None: it takes one)."""
        return SPEED_FOLLOWS.get(self.kind)

    def build(self) -> Any:
        """The top-drive object (a registered kind built from the parameters)."""
        from torsio.plugins import top_drive_from_parameters

        return top_drive_from_parameters(self.kind, **self.parameters)


def _dimensions(kind: str) -> tuple[Mapping[str, str], set[str] | None, tuple[str, ...]]:
    """Dimension of each known parameter name, the kind's parameter names (if known) and
    the names of its file parameters (a class attribute ``path_parameters``)."""
    from torsio.plugins import get_top_drive

    cls = get_top_drive(kind)
    declared = getattr(cls, "parameter_dimensions", None)
    names = set(attrs.fields_dict(cls)) if attrs.has(cls) else None
    paths = tuple(getattr(cls, "path_parameters", ()))
    return {**PARAMETER_DIMENSIONS, **(declared or {})}, names, paths


def _file(value: Any, key: str, source: str) -> str:
    """A file parameter: a relative path is read from the configuration file's folder."""
    if not isinstance(value, str):
        raise ConfigError(f"top_drive.{key}", f"expected a file name, got {value!r}")
    path = Path(value)
    folder = Path(source).parent if source and Path(source).is_file() else None
    return str(folder / path) if folder is not None and not path.is_absolute() else value


def parse_top_drive(raw: Any, source: str = "") -> TopDriveConfig:
    """Validate a ``[top_drive]`` table and build its top drive once (errors name the key);
    ``source`` is the configuration file (relative file parameters are read from its folder)."""
    if not isinstance(raw, Mapping):
        raise ConfigError("top_drive", f"expected a table, got {raw!r}")
    kind = raw.get("kind", DEFAULT_KIND)
    if not isinstance(kind, str):
        raise ConfigError("top_drive.kind", f"expected a top-drive name, got {kind!r}")
    dimensions, names, paths = _dimensions(kind)  # an unknown kind: an error on top_drive.kind
    parameters: dict[str, Any] = {}
    for key, value in raw.items():
        if key == "kind":
            continue
        if names is not None and key not in names:
            raise ConfigError(
                f"top_drive.{key}",
                f"top drive {kind!r} has no parameter {key!r}; its parameters are "
                f"{', '.join(sorted(names)) or 'none'}",
            )
        if key in paths:
            parameters[key] = _file(value, key, source)
            continue
        dimension = dimensions.get(key)
        if dimension is None or dimension not in SI_UNITS:
            if isinstance(value, str):
                raise ConfigError(
                    f"top_drive.{key}",
                    f"expected a bare number in SI units, got {value!r} (units are read only "
                    "for parameters of known dimension)",
                )
            dimension = "dimensionless"
        parameters[key] = to_si(value, dimension, key=f"top_drive.{key}")
    config = TopDriveConfig(kind, parameters)
    config.build()
    return config
