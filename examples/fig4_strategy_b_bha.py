"""Fig. 4 of the paper: strategy B with one drill-pipe DOF and the BHA refined.

A common model keeps the drill pipes as one degree of freedom and refines the
BHA. The paper shows that the first frequency stays about 8 % low whatever the
BHA discretization, that the second frequency converges to a value which is
not a natural frequency of the string, and that the third converges closer to
one; the mode shapes miss the large drill-pipe amplitudes.

(a, b) Modes 2 and 3 against the number of BHA degrees of freedom, with the
exact continuum frequencies of the flexible string near them as dashed lines.
(c) Mode shapes 1 and 2 with 50 BHA degrees of freedom, against the continuum
shapes of the same mode numbers.

Usage: python examples/fig4_strategy_b_bha.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from torsio import StrategyB, continuum_modes, modal_analysis
from torsio.examples import ritto2017_string
from torsio.plotting import (
    plot_convergence,
    plot_mode_shapes,
    plot_reference_lines,
    pyplot,
    save_figure,
)

PAPER_MODE1_ERROR = -0.08
"""Paper, Section 3: the first frequency "remains with a difference of 8 %"."""


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    string = ritto2017_string()
    counts = np.arange(2, 11) if args.quick else np.arange(2, 51)
    shape_count = int(counts[-1])  # 50 BHA DOFs in the paper's Fig. 4(c)

    continuum = continuum_modes(string, 30)
    exact = continuum.frequencies_hz
    frequencies = np.array(
        [
            modal_analysis(
                StrategyB(dp_elements=1, bha_elements=int(n)).discretize(string), 3
            ).frequencies_hz
            for n in counts
        ]
    )
    print("Strategy B, 1 drill-pipe DOF, BHA refined: frequencies [Hz]")
    print(f"  {'BHA DOFs':>8} {'total':>6} {'mode 1':>9} {'error':>8} {'mode 2':>9} {'mode 3':>9}")
    for n, total, f in zip(counts, counts + 1, frequencies, strict=True):
        print(
            f"  {n:>8} {total:>6} {f[0]:9.5f} {100 * (f[0] / exact[0] - 1):+7.2f}% "
            f"{f[1]:9.5f} {f[2]:9.5f}"
        )
    print(
        f"  continuum mode 1: {exact[0]:.5f} Hz; paper: mode 1 about "
        f"{100 * PAPER_MODE1_ERROR:+.0f} % whatever the BHA count"
    )
    for m in (1, 2):
        limit = frequencies[-1, m]
        nearest = int(np.argmin(np.abs(exact - limit)))
        print(
            f"  mode {m + 1} at {counts[-1]} BHA DOFs: {limit:.5f} Hz; continuum mode "
            f"{m + 1} is {exact[m]:.5f} Hz ({100 * (limit / exact[m] - 1):+.1f} %); nearest "
            f"continuum frequency: mode {nearest + 1}, {exact[nearest]:.5f} Hz "
            f"({100 * (limit / exact[nearest] - 1):+.2f} %)"
        )

    plt = pyplot()
    fig = plt.figure(figsize=(11.5, 7.5))
    grid = fig.add_gridspec(2, 2, width_ratios=[1.25, 1.0])
    axes = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[:, 1])]
    for panel, m in zip("ab", (1, 2), strict=True):
        ax = axes["ab".index(panel)]
        plot_convergence(
            counts,
            frequencies[:, m],
            labels=[f"mode {m + 1}, LP B"],
            ax=ax,
            colors=[f"C{m}"],
            xlabel="BHA DOFs (drill pipes: 1 DOF)",
        )
        # the data's range, widened to the continuum frequencies just below and above it
        limit = frequencies[-1, m]
        low = min(np.nanmin(frequencies[:, m]), exact[exact < limit].max())
        high = max(np.nanmax(frequencies[:, m]), exact[exact > limit].min())
        margin = 0.06 * (high - low)
        shown = exact[(exact >= low) & (exact <= high)]
        plot_reference_lines(
            shown, ax, labels=["continuum (flexible BHA)"] + [None] * (shown.size - 1)
        )
        for value in shown:
            index = int(np.flatnonzero(exact == value)[0]) + 1
            ax.annotate(
                f"continuum mode {index}",
                (counts[-1], value),
                xytext=(0, 2),
                textcoords="offset points",
                ha="right",
                va="bottom",
                fontsize="x-small",
                color="0.3",
            )
        ax.set_ylim(low - margin, high + margin)
        ax.get_legend().remove()  # the curve is named in the title, the lines annotated
        ax.set_title(
            f"({panel}) mode {m + 1}, LP strategy B with 1 drill-pipe DOF; dashed: continuum",
            fontsize="medium",
        )

    model = StrategyB(dp_elements=1, bha_elements=shape_count).discretize(string)
    plot_mode_shapes(modal_analysis(model, 2, string=string), (1, 2), ax=axes[2])
    axes[2].legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.08))
    axes[2].set_title(f"(c) mode shapes, 1 DP + {shape_count} BHA DOFs")
    fig.tight_layout()
    print(f"wrote {save_figure(fig, args.out / 'fig4_strategy_b_bha.png', palette=True)}")


if __name__ == "__main__":
    main()
