"""The window on paper: severity and ROP over (rpm, WOB) from the points the search ran, the
critical-WOB curves of the top drives, the constraints and the recommended point with its
margin; and the points as CSV rows."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["REPORT_SEARCH", "draw_window", "plot_window", "report_figures", "write_points"]

REPORT_SEARCH = {"wob_points": 3, "rpm_points": 3, "bisections": 3, "refinements": 1}
"""The quick advice of ``torsio report --html``: the configured top drive on a 3 x 3 coarse
map of the default region, 3 halvings of each row's boundary, one rpm refinement, no
Monte Carlo (about 20 runs)."""


def draw_window(advice: Any, ax: Any) -> None:
    """Draw the window of ``advice`` on the matplotlib axes ``ax`` (rpm across, WOB in kN up)."""
    window = advice.window
    points = window.points
    severe = points.severity > advice.constraints.severity
    rop = points.rop * 3600
    if points.wob.size >= 3:
        contour = ax.tricontour(
            points.rpm, points.wob / 1e3, rop, levels=8, cmap="viridis", linewidths=0.8
        )
        ax.clabel(contour, fmt="%.0f m/h", fontsize=7)
    ax.scatter(
        points.rpm[~severe],
        points.wob[~severe] / 1e3,
        s=10,
        c="tab:green",
        label=f"runs, S_SS <= {advice.constraints.severity:g}",
    )
    ax.scatter(
        points.rpm[severe],
        points.wob[severe] / 1e3,
        s=10,
        c="tab:red",
        marker="x",
        label="runs, severe",
    )
    for other in advice.top_drives:
        finite = np.isfinite(other.critical)
        if finite.any():
            ax.plot(
                other.rows[finite],
                other.critical[finite] / 1e3,
                "-",
                lw=1.2,
                label=f"critical WOB, {other.label}",
            )
    limits = advice.constraints
    if limits.max_wob is not None:
        ax.axhline(limits.max_wob / 1e3, color="k", ls="--", lw=1, label="max WOB")
    if limits.max_surface_torque is not None:
        over = points.surface_torque > limits.max_surface_torque
        ax.scatter(
            points.rpm[over],
            points.wob[over] / 1e3,
            s=40,
            facecolors="none",
            edgecolors="k",
            label="above max surface torque",
        )
    point = advice.recommended
    if point is not None:
        margin = advice.margin
        ax.plot(
            point["rpm"], point["wob"] / 1e3, "*", ms=16, color="gold", mec="k", label="recommended"
        )
        if margin.wob is not None:
            ax.errorbar(
                point["rpm"],
                point["wob"] / 1e3,
                yerr=[[0.0], [margin.wob / 1e3]],
                color="k",
                capsize=4,
                lw=1,
            )
        if margin.rpm is not None:
            ax.errorbar(
                point["rpm"], point["wob"] / 1e3, xerr=margin.rpm, color="k", capsize=4, lw=1
            )
    ax.set_xlabel("rotary speed [rpm]")
    ax.set_ylabel("weight on bit [kN]")
    ax.set_title("Operating window" + ("" if advice.complete else " (incomplete)"))
    ax.legend(fontsize=7, loc="best")


def plot_window(advice: Any, path: str | Path) -> Path:
    """Write the window's PNG (or any format matplotlib writes) to ``path``."""
    from matplotlib.figure import Figure

    from torsio.output_files import save_figure_file

    figure = Figure(figsize=(8, 6))
    draw_window(advice, figure.add_subplot())
    return save_figure_file(figure, path, dpi=120)


def write_points(advice: Any, path: str | Path) -> Path:
    """Every point run for the configured top drive, one CSV row each: wob [N], rpm,
    severity, rop [m/s], mse [Pa], surface_torque [N m], admissible."""
    from torsio.output_files import write_text

    points = advice.window.points
    lines = ["wob_N,rpm,severity,rop_m_per_s,mse_Pa,surface_torque_N_m,admissible"]
    for k in range(points.wob.size):
        lines.append(
            f"{points.wob[k]:.6g},{points.rpm[k]:.6g},{points.severity[k]:.6g},"
            f"{points.rop[k]:.6g},{points.mse[k]:.6g},{points.surface_torque[k]:.6g},"
            f"{int(advice.window.admissible[k])}"
        )
    return write_text(path, "\n".join(lines) + "\n")


def report_figures(config: Any) -> list[tuple[Any, str]]:
    """The window of a quick advice (:data:`REPORT_SEARCH`) on a configuration with the RGD
    bit, with its caption, for ``torsio report --html``; none for another configuration."""
    from matplotlib.figure import Figure

    from torsio.advice.advise import advise
    from torsio.advice.region import Region, default_region
    from torsio.solvers.compiled import numba

    axial = getattr(config, "axial", None)
    if axial is None or not axial.bit.needs_axial or config.top_drive.speed_follows:
        return []
    default, quick = default_region(axial.bit), REPORT_SEARCH
    region = Region(default.wob, default.rpm, quick["wob_points"], quick["rpm_points"])
    threads = 1 if numba is None else int(numba.get_num_threads())
    advice = advise(
        config,
        region,
        compare=False,
        threads=threads,
        bisections=quick["bisections"],
        refinements=quick["refinements"],
    )
    figure = Figure(figsize=(8, 6))
    draw_window(advice, figure.add_subplot())
    point = advice.recommended
    found = (
        "no admissible point"
        if point is None
        else f"recommended {point['wob'] / 1e3:.4g} kN, {point['rpm']:.4g} rpm: ROP "
        f"{point['rop'] * 3600:.4g} m/h, S_SS {point['severity']:.3f}, mean surface torque "
        f"{point['surface_torque'] / 1e3:.4g} kN m"
    )
    caption = (
        "Operating window of the configured top drive, a quick "
        f"advice: {found}; {advice.window.runs} runs. torsio advise searches finer, with "
        "the margin and the top drives compared (docs/advise.md)."
    )
    return [(figure, caption)]
