"""Axial-torsional drilling with the RGD bit (Richard, Germay and Detournay 2004, 2007).

The bit law with its depth of cut per revolution (:mod:`torsio.axial.rgd`), the steady
drilling state in closed form (:mod:`torsio.axial.steady`), the linearization of the 2-DOF
model about it with the state-dependent delay (:mod:`torsio.axial.linearization`), the
roots of a linear delay system (:mod:`torsio.axial.delay_roots`) and the stability of steady
drilling over rpm (:mod:`torsio.axial.stability`). The equations are in docs/axial.md.
"""

from __future__ import annotations

from torsio.axial.rgd import RGDBit, rgd_example, rgd_from_table
from torsio.axial.steady import SteadyDrilling, steady_drilling

__all__ = [
    "RGDBit",
    "SteadyDrilling",
    "rgd_example",
    "rgd_from_table",
    "steady_drilling",
]
