"""The plot of a severity map: S_SS as a heat map with its critical curve.

:func:`plot_severity_map` draws a :class:`~torsio.analysis.map_results.SeverityMap`
(what :meth:`SeverityMap.plot <torsio.analysis.map_results.SeverityMap.plot>` calls).
Needs matplotlib (the ``[plot]`` extra).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from torsio.errors import ConfigError
from torsio.output_files import save_figure_file

if TYPE_CHECKING:
    from torsio.analysis.map_results import SeverityMap

__all__ = ["OFF_GRID_LABELS", "plot_severity_map"]


def plot_severity_map(
    result: SeverityMap,
    path: str | Path | None = None,
    ax: Any = None,
    dimensionless: bool | None = None,
) -> Any:
    """Heat map of S_SS with the critical curve and the linear stability boundary.

    Parameters
    ----------
    result : SeverityMap
        The map to draw.
    path : str or Path, optional
        PNG file to write.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    dimensionless : bool, optional
        Axes Pi_1 x Pi_2 instead of rpm x weight on bit [kN] (default: as the map
        was asked for).

    Returns
    -------
    matplotlib Axes
    """
    try:
        import matplotlib

        if path is not None and ax is None:
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise ConfigError("plot", "plotting needs matplotlib: pip install 'torsio[plot]'") from None
    use_pi = result.dimensionless if dimensionless is None else dimensionless
    if use_pi:
        x, y = result.pi1, result.pi2
        crit, lin = result.critical_pi2, result.stability_pi2
        xlabel, ylabel = r"$\Pi_1 = \Omega/\omega_1$", r"$\Pi_2 = W_{ob} R_{bit}/k_{eq}$"
    else:
        x, y = result.rpm, result.wob / 1e3
        crit, lin = result.critical_wob / 1e3, result.stability_wob / 1e3
        xlabel, ylabel = "rotary speed [rpm]", "weight on bit [kN]"
    figure = None
    if ax is None:
        figure, ax = plt.subplots(figsize=(7.0, 5.0), constrained_layout=True)
    values = np.ma.masked_invalid(result.severity.T)
    mesh = ax.pcolormesh(
        x,
        y,
        values,
        shading="nearest",
        cmap="viridis",
        vmin=0.0,
        vmax=max(
            2.0, float(np.nanmax(result.severity)) if np.isfinite(result.severity).any() else 2.0
        ),
    )
    colorbar = ax.figure.colorbar(mesh, ax=ax)
    colorbar.set_label(r"$S_{SS}$")
    if np.isfinite(crit).any():
        ax.plot(
            x, crit, "w-o", ms=3, lw=2, label=f"critical WOB ($S_{{SS}}$ > {result.threshold:g})"
        )
    _mark_off_grid(ax, result, x, y)
    if np.isfinite(lin).any():
        ax.plot(x, lin, "r--", lw=1.5, label="linear stability boundary")
    ax.set_xlim(x.min() - 0.5 * _spacing(x), x.max() + 0.5 * _spacing(x))
    ax.set_ylim(y.min() - 0.5 * _spacing(y), y.max() + 0.5 * _spacing(y))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    title = str(result.info.get("model", {}).get("name", "")) or "severity map"
    ax.set_title(title + ("" if result.complete else " (incomplete)"))
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper left", fontsize=8, framealpha=0.8)
    if path is not None:
        save_figure_file(ax.figure, path, dpi=120)  # whole or not at all (OutputError)
        if figure is not None:
            plt.close(figure)
    return ax


OFF_GRID_LABELS = {
    "above": "critical WOB above the grid (if any)",
    "below": "critical WOB at or below the grid",
}
"""Legend entries of the off-grid marks (:attr:`SeverityMap.critical_wob_bound`)."""


def _mark_off_grid(ax: Any, result: SeverityMap, x: np.ndarray, y: np.ndarray) -> None:
    """Triangles on the grid's edge row where W_ob,cr lies outside the grid: no value drawn."""
    bounds = np.array([b or "" for b in result.critical_wob_bound])
    for side, marker, edge in (("above", "^", y[-1]), ("below", "v", y[0])):
        rows = bounds == side
        if rows.any():
            ax.plot(
                x[rows],
                np.full(int(rows.sum()), edge),
                linestyle="none",
                marker=marker,
                ms=7,
                markerfacecolor="none",
                markeredgecolor="white",
                markeredgewidth=1.5,
                label=OFF_GRID_LABELS[side],
            )


def _spacing(values: np.ndarray) -> float:
    return (
        float(np.min(np.diff(values))) if values.size > 1 else max(abs(float(values[0])), 1.0) * 0.1
    )
