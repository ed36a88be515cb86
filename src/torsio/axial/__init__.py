"""Axial-torsional drilling with the RGD bit (Richard, Germay and Detournay 2004, 2007).

The bit law with its depth of cut per revolution (:mod:`torsio.axial.rgd`), the steady
drilling state in closed form (:mod:`torsio.axial.steady`), the linearization of the 2-DOF
model about it with the state-dependent delay (:mod:`torsio.axial.linearization`), the
roots of a linear delay system (:mod:`torsio.axial.delay_roots`) and the stability of steady
drilling over rpm (:mod:`torsio.axial.stability`). The equations are in docs/axial.md.
"""

from __future__ import annotations

from torsio.axial.delay_roots import LinearDelaySystem, rightmost_roots
from torsio.axial.linearization import axial_linearization, drilling_linearization
from torsio.axial.rgd import RGDBit, rgd_example, rgd_from_table
from torsio.axial.stability import DrillingStability, crossing_rpm, drilling_stability
from torsio.axial.steady import SteadyDrilling, steady_drilling

__all__ = [
    "DrillingStability",
    "LinearDelaySystem",
    "RGDBit",
    "SteadyDrilling",
    "axial_linearization",
    "crossing_rpm",
    "drilling_linearization",
    "drilling_stability",
    "rgd_example",
    "rgd_from_table",
    "rightmost_roots",
    "steady_drilling",
]
