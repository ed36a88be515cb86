"""Fig. 3 of the paper: strategy C (rigid BHA), drill pipes refined.

(a) The first three natural frequencies against the number of drill-pipe
degrees of freedom, with the exact continuum as dashed lines. Strategy C keeps
the BHA rigid, so it converges to the continuum with a rigid BHA (coloured
dashes); the continuum of the flexible string (the paper's FEM) is dotted.
(b) The relative error on log-log axes, and the observed order of convergence
(lumped mass on uniform elements: second order, error ~ -(kh)^2/24).
(c) Mode shapes 1 and 2 with 5 drill-pipe degrees of freedom.

Usage: python examples/fig3_strategy_c.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from torsio import StrategyC, continuum_modes, modal_analysis
from torsio.examples import ritto2017_string
from torsio.plotting import (
    plot_convergence,
    plot_convergence_error,
    plot_mode_shapes,
    plot_reference_lines,
    pyplot,
    save_figure,
)

MODES = 3


def observed_order(dofs: np.ndarray, errors: np.ndarray) -> float:
    """Order p of |error| ~ dofs^-p from the last two models."""
    return float(-math.log(abs(errors[-1] / errors[-2])) / math.log(dofs[-1] / dofs[-2]))


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    string = ritto2017_string()
    counts = np.arange(1, 9) if args.quick else np.arange(1, 31)

    rigid = continuum_modes(string, MODES, rigid_bha=True).frequencies_hz
    flexible = continuum_modes(string, MODES).frequencies_hz
    frequencies = np.full((counts.size, MODES), np.nan)
    for i, n in enumerate(counts):
        results = modal_analysis(StrategyC(dp_elements=int(n)).discretize(string), MODES)
        frequencies[i, : results.frequencies_hz.size] = results.frequencies_hz
    errors = frequencies / rigid - 1.0

    print("Strategy C: frequencies [Hz] (relative error against the rigid-BHA continuum)")
    print(f"  {'DP DOFs':>7}" + "".join(f"{f'mode {m + 1}':>22}" for m in range(MODES)))
    for n, row, err in zip(counts, frequencies, errors, strict=True):
        cells = "".join(
            f"{'-':>22}" if np.isnan(f) else f"{f:>12.5f} ({100 * e:+6.2f} %)"
            for f, e in zip(row, err, strict=True)
        )
        print(f"  {n:>7}{cells}")
    print("  continuum, rigid BHA:  " + ", ".join(f"{f:.5f}" for f in rigid) + " Hz")
    print(
        "  continuum, flexible:   " + ", ".join(f"{f:.5f}" for f in flexible) + " Hz"
        "  (paper FEM mode 1: 0.1307 Hz)"
    )
    print(
        f"Observed order of convergence (last two models, {counts[-2]} and {counts[-1]} DP DOFs):"
    )
    for m in range(MODES):
        print(f"  mode {m + 1}: {observed_order(counts, errors[:, m]):.2f}")

    plt = pyplot()
    fig = plt.figure(figsize=(11.5, 7.5))
    grid = fig.add_gridspec(2, 2, width_ratios=[1.25, 1.0])
    axes = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[:, 1])]
    labels = [f"mode {m + 1}, LP C" for m in range(MODES)]
    plot_convergence(
        counts,
        frequencies,
        rigid,
        labels=labels,
        ax=axes[0],
        reference_label="continuum, rigid BHA",
        xlabel="drill-pipe DOFs",
    )
    plot_reference_lines(
        flexible, axes[0], linestyle=":", labels=["continuum, flexible BHA", None, None]
    )
    axes[0].legend(fontsize="small", loc="center right")
    axes[0].set_title("(a) strategy C: natural frequencies")
    plot_convergence_error(counts, errors, labels=labels, ax=axes[1], xlabel="drill-pipe DOFs")
    x = np.array([counts[-1] / 4, counts[-1]], dtype=float)
    axes[1].plot(
        x,
        50 * abs(errors[-1, 0]) * (x / x[-1]) ** -2.0,
        color="0.4",
        linestyle=":",
        label="slope -2 (second order)",
    )
    axes[1].legend(fontsize="small")
    axes[1].set_title("(a) error against the rigid-BHA continuum")

    string_results = modal_analysis(StrategyC(dp_elements=5).discretize(string), string=string)
    plot_mode_shapes(string_results, (1, 2), ax=axes[2])
    axes[2].legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.08))
    axes[2].set_title("(b) mode shapes, 5 drill-pipe DOFs")
    fig.tight_layout()
    print(f"wrote {save_figure(fig, args.out / 'fig3_strategy_c.png', palette=True)}")


if __name__ == "__main__":
    main()
