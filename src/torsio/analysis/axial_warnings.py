"""What limits the meaning of an axial run: the warnings its results carry.

An axial run can end with numbers that describe no drilling: a bit that never turns over
the window, a bit that moves up (negative mean ROP) or gives work back (negative MSE), a
depth of cut deeper than the bit's geometry, or an energy balance that does not close (the
fixed step does not resolve the motion). :func:`run_warnings` returns their texts, as
:mod:`torsio.analysis.limits` does for the torsional runs (and with its wording for a bit
stuck throughout the window).

Examples
--------
>>> depth_beyond_geometry(0.02, 4, 0.108) is None
True
>>> depth_beyond_geometry(2.17, 4, 0.108)
"the largest depth of cut, 2.17 m per revolution (0.542 m per blade), is deeper than ..."
"""

from __future__ import annotations

import math
from typing import Any

from torsio.analysis.limits import stuck_throughout, warning_list

__all__ = ["depth_beyond_geometry", "run_warnings"]


def depth_beyond_geometry(depth: float, blades: int, radius: float) -> str | None:
    """The warning for a depth of cut ``depth`` [m per rev] whose share per blade d/n is
    deeper than the bit's ``radius`` a [m] (a blade spans the radius and its cutters are
    far smaller), else None."""
    if not depth / blades > radius:
        return None
    return (
        f"the largest depth of cut, {depth:.3g} m per revolution ({depth / blades:.3g} m per "
        f"blade), is deeper than the bit's radius ({radius:g} m): outside any bit's geometry, "
        "where the RGD law (cutting force proportional to the depth of cut) does not hold; "
        "the bit bounces off the bottom and hits it again"
    )


def run_warnings(summary: Any, bit: Any, energy: Any, stick_threshold: float) -> tuple[str, ...]:
    """The warnings of a run's window ``summary``
    (:class:`~torsio.analysis.axial_window.WindowSummary`) with the RGD ``bit``, its ``energy``
    balance (:class:`~torsio.analysis.axial_energy.EnergyBalance`, None: not known) and the
    ``stick_threshold`` its stuck fraction was counted with."""
    upward = None
    if summary.rop_mean < 0:
        upward = (
            f"the bit moved up over the steady window (mean ROP {summary.rop_mean:.4g} m/s): "
            "it does not drill there; the mean ROP and MSE do not describe drilling"
        )
    negative_mse = None
    if math.isfinite(summary.mse_mean) and summary.mse_mean < 0:
        negative_mse = (
            f"the mean MSE is negative ({summary.mse_mean:.4g} Pa): the bit gave back more "
            "work than it took over the steady window, which no rock does; the run does not "
            "describe drilling"
        )
    return warning_list(
        stuck_throughout(summary.stick_fraction, stick_threshold),
        upward,
        negative_mse,
        depth_beyond_geometry(summary.depth_of_cut_max, bit.blades, bit.radius),
        energy.warning() if energy is not None else None,
    )
