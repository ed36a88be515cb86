"""Report sections for the distributed model (``[discretization] strategy = "wave"``).

The wave model has no mass and stiffness matrices: its discretization is the
characteristic grid (cells per section, one time step), its modes are the exact
continuum of the string on the grid, and its damping is alpha as distributed drag.
These sections stand in for the lumped ones under the same JSON keys
(``discretization``, ``modes``, ``damping``), with the lumped-only entries empty, and
a ``wave`` section adds the grid's facts and the S_SS it gives at the operating point.

Examples
--------
>>> from torsio.examples import builtin_config
>>> from torsio.report.context import ReportContext
>>> ctx = ReportContext(builtin_config(), strategy="wave", modes=3)
>>> data = wave_discretization_section(ctx).data
>>> data["strategy"], [part["cells"] for part in data["parts"]], round(data["time_step_s"], 7)
('wave', [995, 36, 62], 0.0014386)
>>> [round(f, 4) for f in wave_modes_section(ctx).data["frequencies_hz"]]
[0.1307, 0.4165, 0.7318]
"""

from __future__ import annotations

from typing import Any

import numpy as np
from rich.console import Group
from rich.table import Table
from rich.text import Text

from torsio.model.continuum import continuum_modes
from torsio.model.wave import WaveModel, interface_factors
from torsio.report.context import ReportContext, ReportSection, _number, _table

__all__ = [
    "wave_damping_section",
    "wave_discretization_section",
    "wave_modes_section",
    "wave_section",
]


def _grid(ctx: ReportContext) -> WaveModel:
    model: WaveModel = ctx.model  # type: ignore[assignment]
    return model


def wave_discretization_section(ctx: ReportContext) -> ReportSection:
    """The characteristic grid: cells per section, cell length, the time step."""
    grid = _grid(ctx)
    table = _table("section", "cells", "cell length [m]", "L/c change", left=("section",))
    rows = []
    for section, cells, dx, error in zip(
        grid.sections, grid.cells, grid.cell_lengths, grid.travel_time_errors, strict=True
    ):
        name = section.name or section.kind
        rows.append(
            {"part": name, "cells": int(cells), "cell_length_m": float(dx),
             "travel_time_error": float(error)}
        )  # fmt: skip
        table.add_row(Text(name), str(cells), f"{dx:.4g}", _number(float(error), 2, True))
    description = "distributed model: wave equation along characteristics"
    data = {
        "strategy": grid.strategy,
        "description": description,
        "dofs": grid.dofs,
        "elements": {},
        "parts": rows,
        "lumped_mass": None,
        "time_step_s": grid.time_step,
        "rigid_bha": grid.rigid_bha,
        "drag_spacing": grid.drag_spacing,
    }
    head = Text.assemble(
        ("strategy ", "dim"), (grid.strategy, "bold"), f" — {description}\n",
        ("time step ", "dim"), (f"{grid.time_step * 1e3:.5g} ms", "bold"),
        " (a wave crosses one cell a step), ", ("nodes ", "dim"), (str(grid.dofs), "bold"),
        ", ", ("drag ", "dim"), (f"every {grid.drag_spacing} cells", "bold"),
    )  # fmt: skip
    if grid.rigid_bha:
        head.append("\nBHA rigid with the bit (strategy C's string)", style="dim")
    return ReportSection("discretization", "Discretization", data, Group(head, table))


def wave_modes_section(ctx: ReportContext) -> ReportSection:
    """The exact continuum of the grid's string (what the model rings at) against the given."""
    grid = _grid(ctx)
    count = ctx.requested_modes
    on_grid = continuum_modes(grid.grid_string(), count, rigid_bha=grid.rigid_bha)
    given = continuum_modes(grid.string, count, rigid_bha=grid.rigid_bha)
    f_grid, f_given = on_grid.frequencies_hz, given.frequencies_hz
    error = f_grid / f_given - 1.0
    data = {
        "count": int(count),
        "frequencies_hz": f_grid.tolist(),
        "continuum_hz": f_given.tolist(),
        "relative_error": error.tolist(),
        "continuum": "the string as given" + (", BHA rigid" if grid.rigid_bha else ""),
    }
    table = _table("mode", "grid string\n[Hz]", "continuum\n[Hz]", "error\n[%]", "period\n[s]")
    for i in range(count):
        table.add_row(
            str(i + 1), f"{f_grid[i]:.5f}", f"{f_given[i]:.5f}", f"{100 * error[i]:+.4f}",
            f"{1.0 / f_grid[i]:.4g}",
        )  # fmt: skip
    note = Text("grid string: each section rounded to whole cells; exact continuum of both")
    note.stylize("dim")
    title = "Modes: the exact continuum of the string on the grid"
    return ReportSection("modes", title, data, Group(table, note))


def wave_damping_section(ctx: ReportContext) -> ReportSection:
    """alpha as distributed viscous drag: the damping ratio alpha / (2 omega_n) of each mode."""
    grid = _grid(ctx)
    damping = ctx.damping
    alpha = float(getattr(damping, "alpha", 0.0) or 0.0)
    beta = float(getattr(damping, "beta", 0.0) or 0.0)
    omega = continuum_modes(grid.grid_string(), ctx.requested_modes, rigid_bha=grid.rigid_bha)
    w = omega.frequencies_rad
    ratios = alpha / (2.0 * w)
    data = {
        "kind": "distributed drag",
        "alpha_per_s": alpha,
        "beta_s": beta,
        "target_ratios": None,
        "target_modes": None,
        "modes": list(range(1, w.size + 1)),
        "ratios": ratios.tolist(),
    }
    table = _table("mode", "ω [rad/s]", "ζ = α/(2ω) [%]")
    for i, (omega_n, zeta) in enumerate(zip(w, ratios, strict=True)):
        table.add_row(str(i + 1), f"{omega_n:.3f}", f"{100 * zeta:.2f}")
    head = Text(
        f"α = {alpha:.4g} 1/s as a drag α ρ J per unit length (and α J_b on the bit), "
        f"lumped into point dampers every {grid.drag_spacing} cells"
    )
    if beta:
        head.append(f"\nβ = {beta:g} s: not representable (Kelvin–Voigt); the run refuses it")
    return ReportSection("damping", "Damping: distributed viscous drag", data, Group(head, table))


def wave_section(ctx: ReportContext) -> ReportSection | None:
    """The grid's facts and the S_SS it gives at the operating point."""
    grid = _grid(ctx)
    impedances = [float(z) for z in grid.impedances]
    junctions = [
        {"upper": a.name or a.kind, "lower": b.name or b.kind, **interface_factors(za, zb)}
        for a, b, za, zb in zip(
            grid.sections[:-1], grid.sections[1:], impedances[:-1], impedances[1:], strict=True
        )
    ]
    results = ctx.transient
    data: dict[str, Any] = {
        **grid.describe(),
        "wave_speeds_m_s": [float(c) for c in grid.wave_speeds],
        "travel_time_s": float(np.sum(grid.grid_travel_times)),
        "junctions": junctions,
        "severity": None if results is None else float(results.severity),
        "steps": None if results is None else results.solver.get("steps"),
    }
    table = Table.grid(padding=(0, 2))
    table.add_column(style="dim")
    table.add_column()
    table.add_row("grid", Text(f"dt = {grid.time_step * 1e3:.5g} ms, cells {list(grid.cells)}"))
    table.add_row("impedance Z", Text(", ".join(f"{z:.4g}" for z in impedances) + " N m s/rad"))
    table.add_row("travel time", Text(f"{data['travel_time_s']:.4g} s top to bit"))
    for junction in junctions:
        table.add_row(
            "junction",
            Text(
                f"{junction['upper']} → {junction['lower']}: velocity transmitted "
                f"{junction['velocity_transmitted']:.3f}, reflected "
                f"{junction['velocity_reflected']:+.3f}"
            ),
        )
    if results is not None:
        table.add_row(
            "S_SS",
            Text(f"{results.severity:.4f} ({data['steps']} steps, bit extremes every step)"),
        )
    return ReportSection("wave", "Distributed model (wave equation)", data, table)
