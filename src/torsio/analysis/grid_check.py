"""Does the wave grid resolve the stick-slip cycle it reports? A coarse twin says.

The default characteristic grid converges the steady surface torque to 1e-5 but not always
the slip fronts that friction along the string sends down it (docs/wave.md, "How the grid
moves a stick-slip cycle"). A wave run with contacts whose bit speed has a cycle is run
again from rest on a grid of about twice the time step (a quarter of the work;
its travel-time tolerance :data:`TWIN_TRAVEL_TIME_TOLERANCE`) and the cycle's
features compared: S_SS, the stick fraction, the surface-torque swing and the period. The
twin's values go into the results (``grid_check``); a change beyond
:data:`GRID_CHANGE_LIMIT` is a warning naming ``discretization.time_step``.
"""

from __future__ import annotations

from typing import Any

import attrs

__all__ = ["GRID_CHANGE_LIMIT", "TWIN_TRAVEL_TIME_TOLERANCE", "with_grid_check"]

GRID_CHANGE_LIMIT = 0.10
"""Largest relative change of S_SS, surface-torque swing or period (and absolute change of
the stick fraction) between the run and its coarse twin taken as resolved (issue 37: the
features within 10 % of a finer grid's)."""


TWIN_TRAVEL_TIME_TOLERANCE = 3e-3
"""The twin's travel-time tolerance: ten times the default (3e-4), which otherwise keeps the
twin on the run's own time step; its rounding moves each section's travel time, and so the
period, by at most 0.3 %, well under :data:`GRID_CHANGE_LIMIT`."""


def with_grid_check(results: Any, twin: Any) -> Any:
    """``results`` with ``grid_check`` (the coarse ``twin``'s features and the largest
    change) in its well summary and a warning when a change exceeds the limit."""
    summary, coarse = results.well_summary, twin.well_summary
    changes = {
        "severity": _relative(twin.severity, results.severity),
        "stick_fraction": abs(twin.stick_fraction - results.stick_fraction),
        "surface_torque_swing": _relative(
            coarse["surface_torque_swing"], summary["surface_torque_swing"]
        ),
        "stick_slip_period": _relative(coarse["stick_slip_period"], summary["stick_slip_period"]),
    }
    largest = max(changes, key=lambda key: changes[key])
    check = {
        "time_step": float(twin.solver["time_step"]),
        "severity": float(twin.severity),
        "stick_fraction": float(twin.stick_fraction),
        "surface_torque_swing": float(coarse["surface_torque_swing"]),
        "stick_slip_period": coarse["stick_slip_period"],
        "largest_change": float(changes[largest]),
    }
    warnings = results.warnings
    if changes[largest] > GRID_CHANGE_LIMIT:
        step = float(results.solver["time_step"])
        warnings = (
            *warnings,
            f"discretization.time_step: the grid may not resolve the stick-slip cycle: on a "
            f"grid of about twice the time step ({check['time_step']:.4g} s) the "
            f"{largest.replace('_', ' ')} changes by {changes[largest]:.0%} (S_SS "
            f"{results.severity:.3g} here, {twin.severity:.3g} there); run with a time step "
            f"of {step / 2:.4g} s (half of {step:.4g} s) to see whether it settles",
        )
    return attrs.evolve(results, well_summary={**summary, "grid_check": check}, warnings=warnings)


def _relative(coarse: float | None, fine: float | None) -> float:
    """|coarse - fine| / |fine|; 1 (a whole change) when one of them has no value."""
    if coarse is None or fine is None or fine == 0.0:
        return 0.0 if coarse == fine else 1.0
    return abs(coarse - fine) / abs(fine)
