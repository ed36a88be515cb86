"""Fig. 2 of the paper: the first mode shape of strategy A against the continuum.

Strategy A has one degree of freedom at the bottom of the drill pipes, the BHA
rigid below it: its mode shape is drawn as a straight line from the fixed top
to that node, and a constant over the BHA. The paper compares it with its FEM
shape ("very similar, especially in the BHA"). Here the reference is the exact
continuum, both with the BHA rigid (the model's own limit) and with the BHA
flexible (the string as it is, what the paper's FEM computed).

Usage: python examples/fig2_mode_shape_a.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from torsio import StrategyA, continuum_modes, modal_analysis
from torsio.examples import ritto2017_string
from torsio.plotting import plot_continuum_shape, plot_mode_shapes, pyplot, save_figure


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    string = ritto2017_string()

    results = modal_analysis(StrategyA().discretize(string), string=string)
    rigid = continuum_modes(string, 1, rigid_bha=True)
    flexible = continuum_modes(string, 1)
    dp_bottom = float(results.node_depths[0])
    bit_bottom = float(string.section_tops[-1] + string.bit.length)

    # lumped shape: 0 at the top, 1 at the DP bottom, linear in between, constant in the BHA
    depths = np.array([0.0, 1000.0, 2000.0, 3000.0, 4000.0, dp_bottom, 4904.9, bit_bottom])
    lumped = np.clip(depths / dp_bottom, 0.0, 1.0)
    print("First mode shape, normalized to a peak of 1 (strategy A: 1 DOF, rigid BHA)")
    print(
        f"  frequency: A {results.frequencies_hz[0]:.5f} Hz, continuum rigid BHA "
        f"{rigid.frequencies_hz[0]:.5f} Hz, flexible {flexible.frequencies_hz[0]:.5f} Hz"
    )
    print(f"  {'depth [m]':>10} {'A (line)':>8} {'rigid BHA':>10} {'flexible':>10}")
    for d, a, r, f in zip(
        depths, lumped, rigid.shape(1, depths), flexible.shape(1, depths), strict=True
    ):
        print(f"  {d:10.1f} {a:8.4f} {r:10.4f} {f:10.4f}")
    fine = np.linspace(0.0, dp_bottom, 2001)
    gap = np.max(np.abs(np.clip(fine / dp_bottom, 0, 1) - flexible.shape(1, fine)))
    print(
        f"  largest gap between A's straight line and the flexible continuum over the "
        f"drill pipes: {gap:.4f}"
    )

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5.5, 6.0))
    plot_mode_shapes(results, (1,), ax=ax)
    plot_continuum_shape(
        flexible, 1, ax, color="0.3", linestyle=":", label="mode 1, continuum (flexible BHA)"
    )
    ax.legend(fontsize="small", loc="upper right")
    ax.set_title("Fig. 2: first mode, strategy A")
    print(f"wrote {save_figure(fig, args.out / 'fig2_mode_shape_a.png', palette=True)}")


if __name__ == "__main__":
    main()
