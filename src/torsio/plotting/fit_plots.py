"""The figure of a fit (:meth:`torsio.calibration.fit_results.FitResults.plot`).

One panel per recording: the recorded against the fitted surface torque [kN m] over time,
the break-over of each (the peak, :func:`torsio.calibration.objectives.break_over`)
marked. Below them, one panel per profiled parameter: the profile's chi^2 (the misfit's
rise over s^2 tau, :mod:`torsio.calibration.uncertainty`) along the parameter, its one-
and two-sigma levels (chi^2 = 1, 4), the fitted value, the stated two-sigma interval
shaded, and where each recording alone and each twin grid put their least misfit.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["plot_fit"]

CHI2_SHOWN = 25.0
"""The profile is drawn up to this chi^2 (five sigma): where its one- and two-sigma levels
can be read."""


def plot_fit(results: Any, path: str | Path | None = None, ax: Any = None) -> Any:
    """Draw a fit's record against model and its profiles (module documentation).

    ``ax`` draws the torque of every recording on that one axis (no profiles); ``path``
    writes the figure (format by suffix). Returns the figure.
    """
    from torsio.plotting.figures import pyplot, save_figure

    profiled = [
        (name, value, spread)
        for name, value, spread in zip(
            results.names, results.values, results.uncertainty, strict=True
        )
        if spread.profile is not None
    ]
    if ax is None:
        rows, columns = len(results.recordings), max(len(profiled), 1)
        figure = pyplot().figure(figsize=(4 * max(columns, 2), 3 * (rows + bool(profiled))))
        grid = figure.add_gridspec(rows + bool(profiled), columns)
        torque_axes = [figure.add_subplot(grid[i, :]) for i in range(rows)]
        profile_axes = [figure.add_subplot(grid[rows, k]) for k in range(len(profiled))]
    else:
        figure, torque_axes, profile_axes = ax.figure, [ax] * len(results.recordings), []
    for axis, record in zip(torque_axes, results.recordings, strict=True):
        _torque(axis, record)
    for axis, (name, value, spread) in zip(profile_axes, profiled, strict=True):
        _profile(axis, name, value, spread)
    fitted = ", ".join(f"{n} = {v:.4g}" for n, v in results.parameters.items())
    torque_axes[0].set_title(f"fit ({results.objective}): {fitted}")
    if ax is None:
        figure.tight_layout()
    if path is not None:
        save_figure(figure, path)
    return figure


def _torque(axis: Any, record: Any) -> None:
    from torsio.calibration.objectives import break_over

    for torque, style, label in (
        (record.surface_torque, {"lw": 0.6, "alpha": 0.7}, record.name),
        (record.model_torque, {"lw": 1.4, "ls": "--"}, "model"),
    ):
        (line,) = axis.plot(record.time, torque / 1e3, label=label, **style)
        peak = break_over(torque)
        axis.plot(record.time[peak], torque[peak] / 1e3, "v", color=line.get_color())
        axis.annotate(
            f"break-over {torque[peak] / 1e3:.3g}",
            (record.time[peak], torque[peak] / 1e3),
            textcoords="offset points",
            xytext=(8, -14) if label == "model" else (4, 4),
            fontsize=8,
            color=line.get_color(),
        )
    axis.set_xlabel("time [s]")
    axis.set_ylabel("surface torque [kN m]")
    axis.legend(loc="lower right")


def _profile(axis: Any, name: str, value: float, spread: Any) -> None:
    profile = spread.profile
    axis.plot(profile.values, profile.chi2, "o-", ms=3, lw=1.0, label="profile")
    for level, words in ((1.0, "1 sigma"), (4.0, "2 sigma")):
        axis.axhline(level, color="0.5", lw=0.7, ls=":")
        axis.annotate(words, (0.01, level), xycoords=("axes fraction", "data"), fontsize=7)
    low, high = spread.interval
    axis.axvspan(low, high, color="C2", alpha=0.15, label=f"stated 2 sigma {low:.4g}..{high:.4g}")
    axis.axvline(value, color="C3", lw=1.0, label=f"fitted {value:.4g}")
    marks = [(v, "|", f"recording {k + 1} alone") for k, v in enumerate(profile.recording_values)]
    marks += [(v, "x", str(twin)) for twin, v in profile.twin_values.items()]
    for k, (where, marker, label) in enumerate(marks):
        axis.plot(where, 0.0, marker, color=f"C{4 + k % 5}", ms=9, label=label)
    near = np.flatnonzero(profile.chi2 <= CHI2_SHOWN)  # the part of the path that matters
    first, last = max(near.min() - 1, 0), min(near.max() + 1, profile.values.size - 1)
    seen = [profile.values[first], profile.values[last], low, high, value]
    seen += [where for where, _, _ in marks]
    margin = 0.05 * (max(seen) - min(seen))
    axis.set_xlim(min(seen) - margin, max(seen) + margin)
    axis.set_ylim(-0.5, CHI2_SHOWN)
    axis.locator_params(axis="x", nbins=4)
    axis.set_xlabel(name)
    axis.set_ylabel(f"chi^2 (to {CHI2_SHOWN:g})")
    title = name if spread.identifiable else f"{name}: not identifiable"
    axis.set_title(title, fontsize=9)
    axis.legend(fontsize=6, loc="upper center")
