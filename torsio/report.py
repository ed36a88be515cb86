"""Human-readable report of a configuration (rich tables)."""

from __future__ import annotations

from typing import Any

from rich.table import Table

from torsio.config import Config
from torsio.modal import ModalComparison


def string_table(config: Config) -> Table:
    """The drill-string as a table: geometry, J, inertia, stiffness, BHA membership."""
    table = Table(title=f"Drill-string: {config.name or 'unnamed'}", title_justify="left")
    for column in ("#", "section", "kind", "OD [m]", "ID [m]", "length [m]", "J [m^4]",
                   "inertia [kg m^2]", "stiffness [N m/rad]", "BHA"):
        table.add_column(column, justify="left" if column in ("section", "kind") else "right")
    for i, s in enumerate(config.string.sections):
        stiffness = "rigid" if s.kind == "bit" else f"{s.stiffness:.4g}"
        table.add_row(str(i), s.name or "-", s.kind, f"{s.od:.4g}", f"{s.id:.4g}",
                      f"{s.length:.5g}", f"{s.polar_moment:.4e}", f"{s.inertia:.5g}", stiffness,
                      "yes" if s.in_bha else "no")
    return table


def modes_table(comparison: ModalComparison) -> Table:
    """Lumped frequencies against the exact continuum, mode by mode."""
    model = comparison.modal.model
    reference = "rigid BHA" if comparison.reference.rigid_bha else "flexible BHA"
    table = Table(title=f"Modes: strategy {model.strategy}, {model.dofs} DOFs, against the exact "
                        f"continuum ({reference})", title_justify="left")
    for column in ("mode", "lumped [Hz]", "continuum [Hz]", "error [%]"):
        table.add_column(column, justify="right")
    for mode, lumped, exact, error in comparison.rows():
        table.add_row(str(mode), f"{lumped:.5f}", f"{exact:.5f}", f"{100 * error:+.3f}")
    return table


def render(config: Config, console: Any) -> None:
    """Print the report of ``config`` on a rich console."""
    from torsio.modal import modal_analysis

    console.print(string_table(config))
    model = config.model()
    results = modal_analysis(model, min(model.dofs, 5), string=config.string)
    console.print(modes_table(results.compare()))
