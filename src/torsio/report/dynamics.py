"""Report sections on the dynamics: operating point, dimensionless groups, response,
critical weight on bit."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from rich.table import Table
from rich.text import Text

from torsio.display_units import DisplayUnits
from torsio.report.context import ReportContext, ReportSection


# --- operating point ----------------------------------------------------------------------
def operation_section(ctx: ReportContext) -> ReportSection:
    """Weight on bit, rotary speed, bit radius and the bit-rock law with its parameters."""
    op = ctx.config.operation
    chain_without_law = ctx.config.string is None and ctx.config.bit_rock is None
    radius = None if chain_without_law else ctx.config.bit_radius
    law = ctx.law
    law_data: dict[str, Any] | None = None
    steady_torque = None
    if law is not None:
        read = ctx.config.bit_rock  # a law without `given` (a plain class): the file's
        file_unit, file_given = (read.speed_unit, read.parameters) if read else ("rad/s", {})
        law_data = {
            "name": str(getattr(law, "name", type(law).__name__)),
            "speed_unit": str(getattr(law, "speed_unit", file_unit)),
            "given": dict(getattr(law, "given", file_given)),
            "parameters_rad_s": law.values() if hasattr(law, "values") else {},
        }
        if op.wob is not None and op.omega is not None and radius is not None:
            steady_torque = float(law.torque(op.omega, op.wob, radius))
    data = {
        "wob_n": op.wob,
        "rpm": op.rpm,
        "omega_rad_s": op.omega,
        "bit_radius_m": radius,
        "bit_rock_law": law_data,
        "bit_torque_steady_n_m": steady_torque,
    }
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    units = ctx.units
    wob = "not set" if op.wob is None else units.text("force", op.wob, ".4g")
    rpm = "not set" if op.omega is None else f"{op.rpm:.4g} rpm (Ω = {op.omega:.4g} rad/s)"
    rows = [("weight on bit", wob), ("surface speed", rpm)]
    radius_text = "not set" if radius is None else units.text("diameter", radius, ".4g")
    rows.append(("bit radius", radius_text))
    if law_data is None:
        rows.append(("bit-rock law", "none: no [bit_rock] table (modal analyses only)"))
    else:
        given = ", ".join(
            f"{k} = {v:g}" if isinstance(v, (int, float)) else f"{k} = {v}"
            for k, v in law_data["given"].items()
        )
        unit = law_data["speed_unit"]
        rows.append(("bit-rock law", f"{law_data['name']} ({given}; bit speed in {unit})"))
        values = law_data["parameters_rad_s"]
        if values and unit != "rad/s":
            rows.append(("in rad/s", ", ".join(f"{k} = {v:.4g}" for k, v in values.items())))
    if steady_torque is not None:
        torque = units.text("torque", steady_torque, ".5g")
        rows.append(("torque on bit", f"{torque} at steady rotation (bit at Ω)"))
    for label, value in rows:
        table.add_row(label, Text(value))
    return ReportSection("operation", "Operating point", data, table)


# --- dimensionless groups -------------------------------------------------------------------
def dimensionless_section(ctx: ReportContext) -> ReportSection | None:
    """k_eq, omega_1, I_eq, Pi_1, Pi_2 and Tucker-Wang b0..b3 (Eqs. 9-11, ERRATA 2 and 3)."""
    if ctx.system is None:
        return None
    from torsio.physics.dimensionless import dimensionless_groups

    groups = dimensionless_groups(ctx.system)
    data = groups.to_dict()
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    stiffness = "k_eq = 1/[K⁻¹]_NN" if ctx.has_matrices else "k_eq = 1/Σ L/(G J)"  # continuum
    rows = [
        (stiffness, f"{groups.k_eq:.5g} N m/rad (Eq. 9)"),
        ("ω₁", f"{groups.omega1:.5g} rad/s"),
        ("I_eq = k_eq/ω₁²", f"{groups.i_eq:.5g} kg m² (Eq. 10)"),
        ("Π₁ = Ω/ω₁", f"{groups.pi1:.5g}"),
        ("Π₂ = W_ob R_bit/k_eq", f"{groups.pi2:.5g}"),
    ]
    if groups.tucker_wang is not None:
        b = ", ".join(f"b{i} = {v:.4g}" for i, v in enumerate(groups.tucker_wang))
        rows.append(("Tucker-Wang", f"{b} (b2 = ω₁ a2)"))
    for label, value in rows:
        table.add_row(label, Text(value))
    return ReportSection("dimensionless", "Dimensionless groups (Eq. 11)", data, table)


# --- response at the operating point ------------------------------------------------------------
def response_section(ctx: ReportContext) -> ReportSection | None:
    """S_SS (Eq. 12), the stick fraction and the stick-slip period (the cycle's fundamental,
    :func:`torsio.analysis.cycle_period.cycle_period`) of a start-up from rest at the
    operating point."""
    results = ctx.transient
    if results is None:
        return None
    start, end = results.window_start, results.duration
    solver = results.solver
    data = {
        "severity": results.severity,
        "stick_fraction": results.stick_fraction,
        "stick_threshold": results.stick_threshold,
        "steady_window_s": [start, end],
        "bit_speed_min_rad_s": float(results.bit_speed[results.window_mask].min()),
        "bit_speed_max_rad_s": float(results.bit_speed[results.window_mask].max()),
        "solver": {k: solver[k] for k in ("method", "rtol", "atol", "nfev") if k in solver},
    }
    from torsio.analysis.cycle_period import cycle_period
    from torsio.analysis.severity import SEVERE_THRESHOLD

    period, no_period = cycle_period(
        results.time[results.window_mask], results.bit_speed[results.window_mask]
    )
    data.update(stick_slip_period=period, stick_slip_period_reason=no_period)

    if results.severity > SEVERE_THRESHOLD:
        verdict = Text("severe stick-slip", style="bold red")
    elif results.severity > 1e-3:
        verdict = Text("torsional oscillation", style="yellow")
    else:
        verdict = Text("steady rotation", style="green")
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    table.add_row("S_SS", Text.assemble(f"{results.severity:.4f}  ", verdict))
    table.add_row(
        "stick fraction",
        Text(
            f"{results.stick_fraction:.3f} of the window (bit below {results.stick_threshold:g} Ω)"
        ),
    )
    table.add_row(
        "bit speed",
        Text(  # in rpm, as the rotary speed it is compared with (30/pi rpm per rad/s)
            f"{data['bit_speed_min_rad_s'] * 30.0 / math.pi:.4g} to "
            f"{data['bit_speed_max_rad_s'] * 30.0 / math.pi:.4g} rpm"
        ),
    )
    table.add_row(
        "stick-slip period",
        Text(f"none: {no_period}" if period is None else f"{period:.4g} s"),
    )
    table.add_row("window", Text(f"{start:.4g} to {end:.4g} s of a start-up from rest"))
    rtol, atol = solver.get("rtol"), solver.get("atol")
    tolerances = "fixed step" if rtol != rtol else f"rtol {rtol:g}, atol {atol:g}"  # NaN: none
    table.add_row(
        "integrator",
        Text(f"{solver.get('method')} ({tolerances}), {solver.get('nfev')} evaluations"),
    )
    return ReportSection("response", "Response at the operating point (Eq. 12)", data, table)


# --- distance to the critical weight on bit -----------------------------------------------
CRITICAL_SEARCH = (0.25, 4.0, 9, 6)
"""Critical-WOB search of the report: (lowest, highest) weight on bit as multiples of the
operating one, grid points, bisection steps (final bracket 3.75/8/2^6 = 0.7 % of W_ob)."""


def critical_section(ctx: ReportContext) -> ReportSection | None:
    """Critical weight on bit at the operating speed, and the operating point's distance to it.

    One row of a severity map at the operating rpm (:func:`torsio.analysis.maps.severity_map`,
    every point started from rest) over :data:`CRITICAL_SEARCH`, bisected between grid
    points, with the linear stability limit of steady rotation at the same speed.
    """
    op = ctx.config.operation
    if ctx.system is None or op.wob is None or op.rpm is None or op.wob <= 0:
        return None
    from torsio.analysis.maps import severity_map

    low, high, points, refine = CRITICAL_SEARCH
    grid = np.linspace(low * op.wob, high * op.wob, points)
    row = severity_map(ctx.system, wob=grid, rpm=[op.rpm], refine=refine)
    critical = float(row.critical_wob[0])
    status = row.critical_status[0]
    linear = float(row.stability_wob[0])
    margin = critical - op.wob if np.isfinite(critical) else None
    bound = row.critical_wob_bound[0]
    data = {
        "rpm": op.rpm,
        "wob_n": op.wob,
        "critical_wob_n": critical if np.isfinite(critical) else None,
        "status": status,
        "critical_wob_bound": bound,
        "margin_n": margin,
        "margin_fraction": None if margin is None else margin / op.wob,
        "search_wob_n": [float(grid[0]), float(grid[-1])],
        "bracket_n": [float(w) for w in row.critical_bracket[0]],
        "linear_stability_wob_n": linear if np.isfinite(linear) else None,
        "engine": row.engine,
    }
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    search = (float(grid[0]), float(grid[-1]))
    text, style = margin_text(op.rpm, op.wob, critical, bound, search, ctx.units)
    table.add_row("operating point", Text(text, style=style))
    table.add_row(
        "criterion",
        Text(f"severe (S_SS > {row.threshold:g}) above the critical WOB; runs from rest"),
    )
    table.add_row("batch engine", Text(row.engine))
    if np.isfinite(linear):
        table.add_row(
            "linear stability",
            Text(f"steady rotation unstable above {ctx.units.text('force', linear, '.4g')}"),
        )
    return ReportSection("critical", "Distance to the critical weight on bit", data, table)


def margin_text(
    rpm: float,
    wob: float,
    critical: float,
    bound: str | None,
    search: tuple[float, float],
    units: DisplayUnits | None = None,
) -> tuple[str, str]:
    """The critical weight on bit and the operating point's distance to it, in words.

    Parameters
    ----------
    rpm, wob : float
        Operating point [rpm], [N].
    critical : float
        W_ob,cr [N] (NaN when off the search grid).
    bound : {"above", "below"} or None
        Where W_ob,cr lies when off the grid.
    search : (float, float)
        Smallest and largest weight on bit of the search [N].
    units : DisplayUnits, optional
        The units the forces are written in (default SI: kN).

    Returns
    -------
    text, style : str
        The sentence and a rich style (green: the operating point is below the
        critical weight on bit; bold red: at or above it).

    Examples
    --------
    >>> print(margin_text(100.0, 100e3, 181.37e3, None, (25e3, 400e3))[0])
    the critical WOB at 100 rpm is 181.4 kN: 81.37 kN (81 %) above the operating 100 kN
    >>> print(margin_text(100.0, 100e3, float("nan"), "above", (25e3, 400e3))[0])
    the critical WOB at 100 rpm is above 400 kN (no severe point up to there):
    more than 300 kN (300 %) above the operating 100 kN
    """
    units = DisplayUnits() if units is None else units

    def force(value: float) -> str:
        return units.text("force", value, ".4g")

    head = f"the critical WOB at {rpm:.4g} rpm is"
    operating = f"the operating {force(wob)}"

    def amount(gap: float) -> str:
        return f"{force(abs(gap))} ({100.0 * abs(gap) / wob:.0f} %)"

    if bound == "above":
        return (
            f"{head} above {force(search[1])} (no severe point up to there): "
            f"more than {amount(search[1] - wob)} above {operating}",
            "green",
        )
    if bound == "below":
        return (
            f"{head} at or below {force(search[0])} (severe over the whole search): "
            f"at least {amount(wob - search[0])} below {operating}",
            "bold red",
        )
    if not np.isfinite(critical):
        return f"{head} unresolved (a run of the search failed)", "yellow"
    side = "above" if critical > wob else "below"
    return (
        f"{head} {force(critical)}: {amount(critical - wob)} {side} {operating}",
        "green" if critical > wob else "bold red",
    )
