"""Plots of modal results (matplotlib, imported only when a plot is asked for).

Small functions that draw on a given axes (or a new one) and return it, so
that they compose into multi-panel figures:

* :func:`plot_mode_shapes`: lumped mode shapes against depth, with the exact
  continuum shape of the same mode as a line;
* :func:`plot_convergence`: natural frequency against the number of degrees
  of freedom, with the continuum values as dashed horizontal lines (the
  layout of the paper's Figs. 3a, 4a-b and 5a);
* :func:`plot_convergence_error`: the relative error against the number of
  degrees of freedom on log-log axes, where a convergence order is a slope;
* lower-level pieces: :func:`plot_lumped_shape`, :func:`plot_continuum_shape`,
  :func:`plot_reference_lines`, :func:`shade_bha`; :func:`save_figure`
  writes and closes a figure; :func:`pyplot` gives ``matplotlib.pyplot``
  (Agg backend when there is no display) or a clear error if matplotlib is
  missing (these two live in :mod:`torsio.plotting.figures`, the convergence plots in
  :mod:`torsio.plotting.convergence_plots`; all are importable from here).

Depth is measured from the surface [m] and increases downward, as in the
paper's figures. Mode shapes are normalized to a peak magnitude of 1
(:func:`torsio.model.shapes.normalize_shape`); the continuum shape is drawn with the
sign that best matches the lumped one at its nodes.

Examples
--------
>>> from torsio import StrategyC, modal_analysis, ritto2017_string
>>> string = ritto2017_string()
>>> results = modal_analysis(StrategyC(dp_elements=5).discretize(string), string=string)
>>> ax = plot_mode_shapes(results, modes=(1, 2))
>>> ax.get_xlabel(), ax.get_ylabel(), bool(ax.yaxis_inverted())
('normalized rotation [-]', 'depth [m]', True)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from torsio.errors import TorsioError
from torsio.plotting.convergence_plots import (
    plot_convergence,
    plot_convergence_error,
    plot_reference_lines,
)
from torsio.plotting.figures import _axes, pyplot, save_figure

if TYPE_CHECKING:
    from torsio.model.continuum import ContinuumModes
    from torsio.model.drillstring import DrillString
    from torsio.model.modal import ModalResults

__all__ = [
    "plot_continuum_shape",
    "plot_convergence",
    "plot_convergence_error",
    "plot_lumped_shape",
    "plot_mode_shapes",
    "plot_reference_lines",
    "pyplot",
    "save_figure",
    "shade_bha",
]

SHAPE_SAMPLES = 801
"""Depth samples of a continuum mode shape line (plus the section boundaries)."""

MAX_MARKERS = 80
"""Above this many nodes, a lumped shape marks only every k-th node (the line joins them all)."""


def _dofs(count: int) -> str:
    return f"{count} DOF" if count == 1 else f"{count} DOFs"


def _has_rigid_bha(results: ModalResults) -> bool:
    return bool(results.model.details.get("elements", {}).get("BHA") == "rigid")


def plot_lumped_shape(
    results: ModalResults,
    mode: int,
    ax: Any = None,
    *,
    label: str | None = None,
    color: Any = None,
    marker: str = "o",
    markersize: float | None = None,
) -> Any:
    """Draw one lumped mode shape: a marker per node, the fixed top at depth 0 included.

    When the model's BHA is rigid (strategies A and C), the rigid BHA is drawn
    as a thick segment at the last node's rotation down to the bottom of the bit.

    Parameters
    ----------
    results : ModalResults
        Modal results of a lumped model.
    mode : int
        Mode number, 1-based.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    label, color, marker, markersize
        Matplotlib styling; ``markersize`` defaults to smaller markers for
        models with many nodes, and above :data:`MAX_MARKERS` nodes only every
        k-th node is marked.

    Returns
    -------
    matplotlib Axes
    """
    count = results.mode_shapes.shape[1]
    if not 1 <= mode <= count:
        raise TorsioError(f"mode {mode} is not among the computed modes 1..{count}")
    ax = _axes(ax)
    depths = np.concatenate([[0.0], results.node_depths])
    shape = np.concatenate([[0.0], results.mode_shapes[:, mode - 1]])
    if markersize is None:
        markersize = 6.0 if depths.size <= 30 else 3.0
    (line,) = ax.plot(
        shape,
        depths,
        marker=marker,
        markevery=max(1, depths.size // MAX_MARKERS),
        markersize=markersize,
        linestyle="-",
        linewidth=0.8,
        color=color,
        label=label,
    )
    if _has_rigid_bha(results) and results.string is not None:
        bottom = float(results.string.section_tops[-1] + results.string.bit.length)
        ax.plot(
            [shape[-1], shape[-1]],
            [depths[-1], bottom],
            color=line.get_color(),
            linewidth=4.0,
            solid_capstyle="butt",
            alpha=0.6,
        )
    return ax


def plot_continuum_shape(
    continuum: ContinuumModes,
    mode: int,
    ax: Any = None,
    *,
    match: tuple[np.ndarray, np.ndarray] | None = None,
    label: str | None = None,
    color: Any = None,
    linestyle: str = "-",
) -> Any:
    """Draw the exact continuum shape of one mode as a line over the whole string.

    Parameters
    ----------
    continuum : ContinuumModes
        The exact reference (flexible or rigid BHA).
    mode : int
        Mode number, 1-based.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    match : (depths, values), optional
        Node depths [m] and normalized values of a lumped shape: the continuum
        shape is flipped if that makes it agree better with them.
    label, color, linestyle
        Matplotlib styling.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    string = continuum.string
    bottom = float(string.section_tops[-1] + string.bit.length)
    depths = np.unique(
        np.concatenate([np.linspace(0.0, bottom, SHAPE_SAMPLES), string.section_tops])
    )
    shape = continuum.shape(mode, depths)
    if match is not None:
        node_depths, values = match
        if float(np.dot(continuum.shape(mode, node_depths), values)) < 0:
            shape = -shape
    ax.plot(shape, depths, linestyle=linestyle, linewidth=1.5, color=color, label=label)
    return ax


def plot_mode_shapes(
    modal_results: ModalResults,
    modes: Sequence[int] = (1,),
    ax: Any = None,
    reference: bool | ContinuumModes = True,
) -> Any:
    """Lumped mode shapes against depth, with the exact continuum shapes as lines.

    Parameters
    ----------
    modal_results : ModalResults
        Modal results of a lumped model (with its drill-string for the reference).
    modes : sequence of int
        Mode numbers, 1-based.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    reference : bool or ContinuumModes
        ``True``: the continuum of the model's string, with the BHA rigid when
        the model keeps it rigid (strategies A and C), drawn when the string is
        known; ``False``: none; a :class:`~torsio.model.continuum.ContinuumModes`:
        that one.

    Returns
    -------
    matplotlib Axes
        Rotation normalized to a peak magnitude of 1 [-] on x, depth [m] on y,
        increasing downward.
    """
    ax = _axes(ax)
    modes = tuple(int(m) for m in modes)
    continuum: ContinuumModes | None = None
    if reference is True and modal_results.string is not None:
        continuum = modal_results.compare().reference
    elif reference is not True and reference is not False:
        continuum = reference
    model = modal_results.model
    for i, mode in enumerate(modes):
        color = f"C{i}"
        plot_lumped_shape(
            modal_results,
            mode,
            ax,
            color=color,
            label=f"mode {mode}, LP {model.strategy} ({_dofs(model.dofs)})",
        )
        if continuum is not None and mode <= continuum.frequencies_rad.size:
            which = "rigid BHA" if continuum.rigid_bha else "flexible BHA"
            plot_continuum_shape(
                continuum,
                mode,
                ax,
                color=color if len(modes) > 1 else "0.15",
                linestyle="--",
                match=(modal_results.node_depths, modal_results.mode_shapes[:, mode - 1]),
                label=f"mode {mode}, continuum ({which})",
            )
    string = modal_results.string if continuum is None else continuum.string
    if string is not None:
        shade_bha(string, ax)
    _style_shape_axes(ax)
    return ax


def shade_bha(string: DrillString, ax: Any = None, *, label: str = "BHA") -> Any:
    """Shade the depth range of the BHA (bit included) on a depth-downward axes.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    bottom = float(string.section_tops[-1] + string.bit.length)
    top = bottom - sum(s.length for s in string.bha_sections) - string.bit.length
    ax.axhspan(top, bottom, color="0.5", alpha=0.12, linewidth=0, zorder=0, label=label)
    return ax


def _style_shape_axes(ax: Any) -> None:
    ax.axvline(0.0, color="0.6", linewidth=0.6, zorder=0)
    ax.set_xlabel("normalized rotation [-]")
    ax.set_ylabel("depth [m]")
    if not ax.yaxis_inverted():
        ax.invert_yaxis()
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
