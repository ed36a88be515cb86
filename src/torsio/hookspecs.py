"""Plugin hooks of torsio (pluggy project ``torsio``).

A plugin is a module or object with functions marked ``@torsio.hookimpl``. A
third-party distribution registers it under the entry-point group ``torsio``::

    [project.entry-points.torsio]
    my_laws = "my_package.plugin"

The built-in bit-rock laws, top drives and discretizers register through these same hooks.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import pluggy

hookspec = pluggy.HookspecMarker("torsio")
hookimpl = pluggy.HookimplMarker("torsio")


@hookspec
def torsio_bit_laws() -> Iterable[type[Any]]:
    """Return bit-rock law classes.

    Each class has a unique class attribute ``name``, is built from keyword
    parameters (validated in ``__init__``, raising ``ValueError`` naming the
    parameter), and has ``torque(speed, wob, radius)``: torque on bit [N m] for
    bit speed [rad/s], weight on bit [N] and bit radius [m], broadcasting over
    numpy arrays. Subclassing :class:`torsio.physics.laws.BitRockLaw` gives the
    parameter description, validation and dimensionless form for free. Optionally a
    class declares ``needs_axial`` (True: it needs axial dynamics and has no such
    ``torque``; absent: False) and ``gives`` (what it computes; absent: the torque):
    :func:`torsio.physics.laws.law_capabilities`.
    """
    raise NotImplementedError


@hookspec
def torsio_discretizers() -> Iterable[type[Any]]:
    """Return discretizer classes.

    Each class has a unique class attribute ``name``, is built from keyword
    options, and has ``discretize(string) -> LumpedModel``.
    """
    raise NotImplementedError


@hookspec
def torsio_top_drives() -> Iterable[type[Any]]:
    """Return top-drive classes.

    Each class has a unique class attribute ``name``, is built from keyword
    parameters (validated on construction, raising
    :class:`torsio.errors.ConfigError` naming ``top_drive.<key>``), and has
    ``boundary(system) -> torsio.physics.top_drives.TopDriveBoundary``: its
    inertia, drag and linear controller (with optional torque limit) for the
    given System (see :mod:`torsio.physics.top_drives`).
    """
    raise NotImplementedError
