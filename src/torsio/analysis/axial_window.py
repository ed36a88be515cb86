"""What a run of either axial kernel gives over its window: :class:`WindowSummary`, read
from the kernel's ``stats`` (:data:`torsio.solvers.axial_layouts.STATS`) by :func:`summarize`."""

from __future__ import annotations

import math

import attrs
from numpy.typing import NDArray

from torsio.analysis.severity import severity_of_extremes
from torsio.physics.torque_law_bit import AxialBit
from torsio.solvers import axial_layouts as slot
from torsio.solvers.axial_run_setup import KernelSetup

__all__ = ["WindowSummary", "summarize"]


@attrs.frozen
class WindowSummary:
    """What a run gives over its window (docs/axial.md, "Outputs").

    severity: S_SS = (max Ω_b − min Ω_b)/(2 Ω₀); axial_severity: (max V_b − min V_b)/(2 V₀);
    stick_fraction, off_bottom_fraction: of the window's steps; rop_mean [m/s]: the bit's
    advance over the window's length; mse_mean [Pa]: the work on the bit ∫(W V + T Ω) dt
    over the volume drilled π a² ΔU (inf when the bit did not advance); torque_mean [N m],
    weight_mean [N]; depth_of_cut_max [m per rev], the largest depth of cut (a check: the
    law holds only while d stays within the cutters' height).
    """

    severity: float
    axial_severity: float
    stick_fraction: float
    off_bottom_fraction: float
    rop_mean: float
    mse_mean: float
    torque_mean: float
    weight_mean: float
    bit_speed_min: float
    bit_speed_max: float
    depth_of_cut_max: float


def summarize(stats: NDArray, setup: KernelSetup, bit: AxialBit) -> WindowSummary:
    """The window summary of a kernel's ``stats`` (:data:`torsio.solvers.axial_layouts.STATS`), the
    lumped or the distributed one (``setup.step`` and ``setup.steady`` are read)."""
    s = dict(zip(slot.STATS, stats, strict=True))
    count = s["window_steps"]
    length = count * setup.step
    advance = s["position_end"] - s["position_start"]
    steady = setup.steady
    return WindowSummary(
        severity=float(
            severity_of_extremes(s["bit_speed_max"], s["bit_speed_min"], steady.bit_speed)
        ),
        axial_severity=(  # NaN without a steady rate of penetration (a law of the torque alone)
            float((s["axial_speed_max"] - s["axial_speed_min"]) / (2 * steady.rop))
            if steady.rop > 0
            else math.nan
        ),
        stick_fraction=float(s["stuck_steps"] / count),
        off_bottom_fraction=float(s["off_bottom_steps"] / count),
        rop_mean=float(advance / length),
        mse_mean=float(s["work"] / (bit.hole_area * advance)) if advance > 0 else math.inf,
        torque_mean=float(s["torque_integral"] / length),
        weight_mean=float(s["weight_integral"] / length),
        bit_speed_min=float(s["bit_speed_min"]),
        bit_speed_max=float(s["bit_speed_max"]),
        depth_of_cut_max=float(s["depth_of_cut_max"]),
    )
