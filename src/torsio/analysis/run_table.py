"""The terminal table of a torsional run (``torsio simulate``): :func:`run_table`."""

from __future__ import annotations

from typing import Any

from torsio.units import RPM_TO_RAD_S

__all__ = ["run_table"]


def run_table(run: Any, units: Any) -> tuple[str, list[tuple[str, str]]]:
    """The title and (quantity, value) rows of a torsional run's results ``run`` (a
    :class:`~torsio.analysis.transient_results.TransientResults`), forces and torques in
    ``units`` (a :class:`~torsio.display_units.DisplayUnits`)."""
    solver = run.solver
    title = f"Transient response: {run.facts.strategy}, {run.facts.dofs} DOF"
    window = run.window_mask
    rows = [
        ("weight on bit", units.text("force", run.wob, ".4g")),
        (
            "rotary speed",
            f"{run.rpm:.4g} rpm"
            + ("" if run.has_set_speed else "  (mean top-drive speed; none is set)"),
        ),
        ("bit-rock law", run.facts.law),
        (
            "run / steady window",
            f"{run.duration:.4g} s / last {run.steady_window:.4g} s",
        ),
        (
            "bit speed in window",
            f"{run.bit_speed[window].min() / RPM_TO_RAD_S:.4g} .. "
            f"{run.bit_speed[window].max() / RPM_TO_RAD_S:.4g} rpm",
        ),
        (
            "S_SS (Eq. 12)",
            f"{run.severity:.4f}" + ("  severe (> 0.8)" if run.severe else ""),
        ),
        (
            "stick fraction",
            f"{run.stick_fraction:.3f}  (|bit speed| < {run.stick_threshold:g} Omega)",
        ),
        (
            "mean surface torque",
            units.text("torque", run.surface_torque[window].mean(), ".4g"),
        ),
        ("mean torque on bit", units.text("torque", run.bit_torque[window].mean(), ".4g")),
        (
            "solver",
            f"{solver['method']} ({solver.get('engine', 'scipy')} engine) "
            f"rtol={solver['rtol']:g} atol={solver['atol']:g}: "
            + (f"{solver['steps']} steps, " if solver.get("steps") is not None else "")
            + f"{solver['nfev']} f-evals, {solver['njev']} Jacobians, "
            f"{solver['wall_time_s']:.2f} s",
        ),
    ]
    rows.extend(_well_rows(run.well_summary, units))
    return title, rows


def _well_rows(summary: Any, units: Any) -> list[tuple[str, str]]:
    """Rows of a run with friction along the string (a [well]); none without."""
    if summary is None:
        return []
    first = summary["bit_first_motion"]
    period = summary["stick_slip_period"]
    return [
        (
            "surface torque in window",
            f"{units.number('torque', summary['surface_torque_min'], '.4g')} .. "
            f"{units.text('torque', summary['surface_torque_max'], '.4g')}",
        ),
        ("peak surface torque", units.text("torque", summary["surface_torque_peak"], ".4g")),
        (
            "surface-torque swing in window",
            units.text("torque", summary["surface_torque_swing"], ".4g"),
        ),
        (
            "stick-slip period in window",
            f"none: {summary['stick_slip_period_reason']}" if period is None else f"{period:.4g} s",
        ),
        (
            f"bit first faster than {summary['threshold_speed']:g} rad/s",
            "never" if first is None else f"at {first:.4g} s",
        ),
        ("friction work along the string", units.energy(summary["friction_work"])),
    ]
