"""Section 3 of the paper: the first natural frequency of strategy A, and its error.

Strategy A (Eq. 5) is the classic one-degree-of-freedom model: the BHA is rigid
and a third of the drill-pipe inertia is added to it, I = I_DP/3 + I_BHA, on the
drill-pipe spring k = G J_DP / L_DP. The paper reports 0.1344 Hz (printed as
"1.1344 Hz", see ERRATA 1), 2.8 % above its FEM value of 0.1307 Hz.

This script computes the strategy-A frequency, compares it with the exact
continuum (which replaces the paper's FEM) and with the paper's numbers, and
plots it next to the other one-degree-of-freedom readings of the drill pipes:
strategy C with one element (Eq. 8, I = I_DP/2 + I_BHA) and strategy B with one
drill-pipe element and a flexible BHA (paper Fig. 4: about 8 % low).

Usage: python examples/strategy_a.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from torsio import StrategyA, StrategyB, StrategyC, continuum_modes, modal_analysis
from torsio.examples import ritto2017_string
from torsio.plotting import pyplot, save_figure

PAPER_FEM_HZ = 0.1307
"""First natural frequency by FEM (ABAQUS, 2430 elements), paper Section 3."""
PAPER_A_HZ = 0.1344
"""Strategy A first frequency, paper Section 3 (printed 1.1344 Hz; ERRATA 1)."""
PAPER_A_ERROR = 0.028
"""Strategy A error against FEM, paper Section 3."""


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    string = ritto2017_string()

    # Eq. 5 by hand, from the string's totals
    k = string.drill_pipe_stiffness
    inertia = string.drill_pipe_inertia / 3 + string.bha_inertia
    by_hand = math.sqrt(k / inertia) / (2 * math.pi)
    print("Strategy A (Eq. 5), Ritto et al. (2017) string")
    print(f"  k = G J_DP / L_DP          = {k:.2f} N m/rad")
    print(
        f"  I = I_DP/3 + I_BHA         = {string.drill_pipe_inertia:.2f}/3 + "
        f"{string.bha_inertia:.2f} = {inertia:.2f} kg m^2"
    )
    print(f"  f = sqrt(k/I) / (2 pi)     = {by_hand:.5f} Hz")

    model = StrategyA().discretize(string)
    f_a = float(modal_analysis(model).frequencies_hz[0])
    exact = float(continuum_modes(string, 1).frequencies_hz[0])
    exact_rigid = float(continuum_modes(string, 1, rigid_bha=True).frequencies_hz[0])
    print(f"  torsio strategy A          = {f_a:.5f} Hz (paper: {PAPER_A_HZ} Hz)")
    print(f"  exact continuum            = {exact:.5f} Hz (paper FEM: {PAPER_FEM_HZ} Hz)")
    print(f"  exact continuum, rigid BHA = {exact_rigid:.5f} Hz")
    print(
        f"  error of A vs continuum    = {100 * (f_a / exact - 1):+.2f} % "
        f"(paper: +{100 * PAPER_A_ERROR:.1f} %)"
    )
    print(f"  error of A vs paper FEM    = {100 * (f_a / PAPER_FEM_HZ - 1):+.2f} %")
    print(f"  error of A vs rigid BHA    = {100 * (f_a / exact_rigid - 1):+.2f} %")

    # the other one-DOF readings of the drill pipes
    f_c = float(modal_analysis(StrategyC(dp_elements=1).discretize(string)).frequencies_hz[0])
    model_b = StrategyB(dp_elements=1, bha_elements=len(string.bha_sections)).discretize(string)
    f_b = float(modal_analysis(model_b).frequencies_hz[0])
    print("Other models with one drill-pipe degree of freedom")
    print(f"  C, 1 element (Eq. 8)       = {f_c:.5f} Hz ({100 * (f_c / exact - 1):+.2f} %)")
    print(
        f"  B, 1 DP element, BHA flex. = {f_b:.5f} Hz ({100 * (f_b / exact - 1):+.2f} %; "
        "paper: about -8 %)"
    )

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 3.6))
    rows = [
        ("exact continuum", exact, "0.2", 5),
        ("paper FEM", PAPER_FEM_HZ, "0.55", 4),
        ("A: I_DP/3 + I_BHA (torsio)", f_a, "C0", 5),
        ("A (paper)", PAPER_A_HZ, "C9", 4),
        ("C, 1 element: I_DP/2 + I_BHA", f_c, "C1", 5),
        ("B, 1 DP element, flexible BHA", f_b, "C2", 5),
    ]
    for i, (_, value, color, digits) in enumerate(rows):
        ax.barh(i, value, color=color)
        error = 100 * (value / exact - 1)
        ax.text(
            value + 0.0005,
            i,
            f"{value:.{digits}f} Hz  ({error:+.2f} %)",
            va="center",
            fontsize="small",
        )
    ax.set_yticks(range(len(rows)), [r[0] for r in rows])
    ax.invert_yaxis()
    ax.set_xlim(0.11, 0.142)
    ax.axvline(exact, color="0.2", linestyle="--", linewidth=1.0)
    ax.set_xlabel("first natural frequency [Hz] (error against the exact continuum)")
    ax.set_title("One drill-pipe degree of freedom: first frequency")
    print(f"wrote {save_figure(fig, args.out / 'strategy_a.png', palette=True)}")


if __name__ == "__main__":
    main()
