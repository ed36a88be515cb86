"""What a run's results say of the system that made it: :class:`RunFacts`.

A :class:`~torsio.analysis.transient_results.TransientResults` reads its operating point,
its top drive, its law and its model from these facts, never from its System, so that a
torsional run, an axial run (which has no System) and a run read back from a file
(:func:`torsio.analysis.run_file.load_run`) answer alike.

Examples
--------
>>> from torsio.examples import builtin_config
>>> facts = RunFacts.of_system(builtin_config().system(strategy="A").at(wob=100e3, rpm=60))
>>> facts.wob, facts.rpm, facts.top_drive, facts.law, facts.strategy, facts.dofs
(100000.0, 60.0, 'constant-speed', 'tucker-wang', 'A', 1)
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np

__all__ = ["RunFacts"]


@attrs.frozen
class RunFacts:
    """The system of a run, as its results need it.

    Attributes
    ----------
    wob : float
        Weight on bit [N] (a dimensionless system's: Pi_2 / R_bit).
    rpm : float
        The rotary speed the run was given [rpm]: the top drive's set speed, or an axial
        run's steady state's under a torque-driven top; NaN for a torsional run without a
        set speed (a torque-driven top, a recorded top speed).
    has_set_speed : bool
        Whether the top drive turns at a set speed.
    top_drive, law : str
        The top drive's and the bit-rock law's names.
    has_top_drive_node : bool
        Whether the top drive is a node with inertia, its motor torque its own; a top held
        at a constant or a recorded speed is not (its motor torque is the pipe's).
    dimensionless : bool
        Whether the system is a dimensionless one (time is tau = omega_1 t).
    dofs, strategy, bit_radius : int, str, float or None
        The structural model's degrees of freedom and discretizer, and the bit's radius
        [m]; None for an axial run, whose assembly is described in ``axial.model``.
    """

    wob: float
    rpm: float
    has_set_speed: bool
    top_drive: str
    law: str
    has_top_drive_node: bool
    dimensionless: bool = False
    dofs: int | None = None
    strategy: str | None = None
    bit_radius: float | None = None

    @classmethod
    def of_system(cls, system: Any) -> RunFacts:
        """The facts of a :class:`~torsio.physics.system.System` at its operating point."""
        top = getattr(system.top, "name", type(system.top).__name__)
        boundary = system.top.boundary(system)
        has_set_speed = top != "recorded" and bool(np.isfinite(boundary.set_speed))
        return cls(
            wob=float(system.wob),
            rpm=float(system.rpm) if has_set_speed else math.nan,
            has_set_speed=has_set_speed,
            top_drive=top,
            law=getattr(system.law, "name", type(system.law).__name__),
            has_top_drive_node=not boundary.held,
            dimensionless=bool(getattr(system.law, "dimensionless", False)),
            dofs=int(system.model.dofs),
            strategy=system.model.strategy,
            bit_radius=float(system.bit_radius),
        )
