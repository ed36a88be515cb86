"""Convergence plots: natural frequency, and its relative error, against the number of DOFs.

The layout of the paper's Figs. 3a, 4a-b and 5a: :func:`plot_convergence` draws each
mode's frequency against the degrees of freedom with the continuum value as a dashed
line; :func:`plot_convergence_error` draws the error on log-log axes, where a
convergence order is a slope; :func:`plot_reference_lines` draws reference frequencies.
All are re-exported by :mod:`torsio.plotting`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from torsio.errors import TorsioError
from torsio.plotting.figures import _axes, _ticker

__all__ = ["plot_convergence", "plot_convergence_error", "plot_reference_lines"]


def plot_reference_lines(
    values_hz: Sequence[float],
    ax: Any = None,
    *,
    labels: Sequence[str | None] | None = None,
    colors: Sequence[Any] | None = None,
    linestyle: str = "--",
) -> Any:
    """Horizontal lines (dashed by default) at reference frequencies [Hz], e.g. the continuum.

    Parameters
    ----------
    values_hz : sequence of float
        Reference frequencies [Hz].
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted.
    labels : sequence of str or None, optional
        Legend entry of each line (None: no entry).
    colors : sequence, optional
        Colour of each line (default grey).
    linestyle : str
        Matplotlib line style.

    Returns
    -------
    matplotlib Axes
    """
    ax = _axes(ax)
    for i, value in enumerate(values_hz):
        ax.axhline(
            float(value),
            linestyle=linestyle,
            linewidth=1.0,
            color=colors[i] if colors is not None else "0.35",
            label=labels[i] if labels is not None else None,
        )
    return ax


def _columns(values: Any, rows: int) -> np.ndarray:
    array = np.asarray(values, dtype=float)
    if array.ndim == 1:
        array = array[:, None]
    if array.ndim != 2 or array.shape[0] != rows:
        raise TorsioError(
            f"expected {rows} values per curve (one per model), got shape {np.shape(values)}"
        )
    return array


def _plot_curves(
    ax: Any,
    x: np.ndarray,
    curves: np.ndarray,
    labels: Sequence[str] | None,
    colors: Sequence[Any] | None,
    marker: str,
    linestyle: str,
) -> list[Any]:
    """Column j of ``curves`` against ``x`` in colour ``colors[j]`` (default Cj); the colours."""
    drawn = []
    for j in range(curves.shape[1]):
        color = colors[j] if colors is not None else f"C{j}"
        label = labels[j] if labels is not None else None
        ax.plot(x, curves[:, j], marker=marker, markersize=4, linestyle=linestyle,
                linewidth=1.0, color=color, label=label)  # fmt: skip
        drawn.append(color)
    return drawn


def plot_convergence(
    dofs: Sequence[int] | np.ndarray,
    frequencies_hz: Any,
    reference_hz: Sequence[float | None] | None = None,
    *,
    labels: Sequence[str] | None = None,
    ax: Any = None,
    colors: Sequence[Any] | None = None,
    marker: str = "o",
    linestyle: str = "-",
    reference_label: str = "continuum",
    xlabel: str = "degrees of freedom",
) -> Any:
    """Natural frequency [Hz] against the number of degrees of freedom.

    Parameters
    ----------
    dofs : sequence of int, shape (n,)
        Degrees of freedom of each model (the x axis).
    frequencies_hz : array_like, shape (n,) or (n, m)
        Frequency of each model [Hz]; column j is one curve (e.g. one mode).
        NaN where a model has no such mode.
    reference_hz : sequence of float or None, optional
        One exact value per curve [Hz], drawn as a dashed horizontal line in the
        curve's colour (``None`` for no line).
    labels : sequence of str, optional
        Legend entry of each curve.
    ax : matplotlib Axes, optional
        Where to draw; a new figure if omitted. Call again on the same axes
        to overlay another discretizer (with another ``marker``/``linestyle``).
    colors, marker, linestyle
        Matplotlib styling; colours default to C0, C1, ...
    reference_label : str
        Legend text of the reference lines.
    xlabel : str
        Label of the x axis.

    Returns
    -------
    matplotlib Axes

    Examples
    --------
    >>> ax = plot_convergence([1, 2, 4], [0.1306, 0.1309, 0.1310], [0.13102],
    ...                       labels=["mode 1"])
    >>> ax.get_ylabel()
    'natural frequency [Hz]'
    """
    ax = _axes(ax)
    x = np.asarray(dofs, dtype=float)
    curves = _columns(frequencies_hz, x.size)
    drawn = _plot_curves(ax, x, curves, labels, colors, marker, linestyle)
    for j, color in enumerate(drawn):
        reference = reference_hz[j] if reference_hz is not None and j < len(reference_hz) else None
        if reference is not None:
            ax.axhline(
                float(reference),
                linestyle="--",
                linewidth=1.0,
                color=color,
                label=f"{reference_label}" if j == 0 else None,
            )
    ax.set_xlabel(xlabel)
    ax.set_ylabel("natural frequency [Hz]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return ax


def plot_convergence_error(
    dofs: Sequence[int] | np.ndarray,
    relative_errors: Any,
    *,
    labels: Sequence[str] | None = None,
    ax: Any = None,
    colors: Sequence[Any] | None = None,
    marker: str = "o",
    linestyle: str = "-",
    xlabel: str = "degrees of freedom",
) -> Any:
    """Magnitude of the relative frequency error [%] against DOFs, log-log.

    Parameters
    ----------
    dofs : sequence of int, shape (n,)
        Degrees of freedom of each model.
    relative_errors : array_like, shape (n,) or (n, m)
        (lumped - exact) / exact [-]; column j is one curve. NaN is skipped.
    labels, ax, colors, marker, linestyle, xlabel
        As for :func:`plot_convergence`.

    Returns
    -------
    matplotlib Axes
        A convergence of order p is a straight line of slope -p.

    Examples
    --------
    >>> ax = plot_convergence_error([10, 20, 40], [-4e-3, -1e-3, -2.5e-4])
    >>> ax.get_yscale(), ax.get_ylabel()
    ('log', '|relative error| [%]')
    """
    ax = _axes(ax)
    x = np.asarray(dofs, dtype=float)
    curves = 100.0 * np.abs(_columns(relative_errors, x.size))
    _plot_curves(ax, x, curves, labels, colors, marker, linestyle)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ticker = _ticker()
    ax.xaxis.set_major_locator(ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(ticker.FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(ticker.NullFormatter())
    ax.set_xlabel(xlabel)
    ax.set_ylabel("|relative error| [%]")
    ax.grid(True, which="both", alpha=0.3)
    if labels is not None:
        ax.legend(fontsize="small")
    return ax
