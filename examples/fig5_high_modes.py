"""Fig. 5 of the paper: modes 15 and 25 with the drill pipes and the BHA both refined.

The paper refines both parts (its Fig. 5(b): 120 drill-pipe and 30 BHA DOFs)
and finds modes 15 and 25 close to FEM. Here the models keep the paper's
4:1 split (4n drill-pipe and n BHA elements, n = 5, 6, ...) and three mass
matrices are compared, each against the exact continuum:

* B: lumped mass (the paper's Eq. 6), converging from below at second order;
* consistent: finite-element consistent mass, from above at the same second
  order and with about the same error (not faster);
* mixed: the average of the two, whose second-order dispersion errors cancel in
  a uniform shaft (fourth order); the bit and the section junctions leave a small
  second-order term, so the observed order falls from 4 towards 2 as elements
  shrink, the error staying tens of times below lumped mass.

(a) Frequencies against the total DOFs, the continuum as dashed lines.
(b) The relative errors on log-log axes, with the 1 % level.
(c) Mode shape 25 with 120 + 30 DOFs (strategy B) against the continuum.

Usage: python examples/fig5_high_modes.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from torsio import ConsistentMass, MixedMass, StrategyB, continuum_modes, modal_analysis
from torsio.examples import ritto2017_string
from torsio.plotting import (
    plot_convergence,
    plot_convergence_error,
    plot_mode_shapes,
    pyplot,
    save_figure,
)

MODES = (15, 25)
DISCRETIZERS = {"B": StrategyB, "consistent": ConsistentMass, "mixed": MixedMass}
MARKERS = {"B": "o", "consistent": "s", "mixed": "^"}
PAPER_DP, PAPER_BHA = 120, 30
"""The paper's Fig. 5(b) discretization."""


def frequencies_at(name: str, n: int) -> np.ndarray:
    """Frequencies [Hz] of modes 15 and 25 with 4n drill-pipe and n BHA elements."""
    model = DISCRETIZERS[name](dp_elements=4 * n, bha_elements=n).discretize(ritto2017_string())
    return modal_analysis(model, max(MODES)).frequencies_hz[[m - 1 for m in MODES]]


def steps_for(
    name: str,
    mode_index: int,
    exact: float,
    steps: np.ndarray,
    errors: np.ndarray,
    tolerance: float = 0.01,
) -> int | None:
    """Fewest n (5n DOFs) from which |error| stays within ``tolerance``.

    The plotted sweep brackets the crossing; every n in the bracket is then tried.
    """
    inside = np.abs(errors) <= tolerance
    if not inside[-1]:
        return None
    outside = np.flatnonzero(~inside)
    if outside.size == 0:
        return int(steps[0])
    first_inside = int(steps[outside[-1] + 1])
    for n in range(first_inside - 1, int(steps[outside[-1]]), -1):
        if abs(frequencies_at(name, n)[mode_index] / exact - 1.0) > tolerance:
            return n + 1
    return int(steps[outside[-1]]) + 1


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    string = ritto2017_string()
    # n = 5..60 (25..300 DOFs), evenly spread on the log axis of panel (a); n = 30 is 120 + 30
    steps = (
        np.array([5, 10, 20, 30])
        if args.quick
        else np.unique(np.concatenate([np.round(np.geomspace(5, 60, 20)).astype(int), [30]]))
    )
    dofs = 5 * steps  # 4n drill-pipe + n BHA elements

    exact = continuum_modes(string, max(MODES)).frequencies_hz[[m - 1 for m in MODES]]
    frequencies = {
        name: np.array([frequencies_at(name, int(n)) for n in steps]) for name in DISCRETIZERS
    }
    errors = {name: f / exact - 1.0 for name, f in frequencies.items()}

    print(
        "Modes 15 and 25, drill pipes and BHA refined 4:1; continuum: "
        + ", ".join(f"mode {m} {f:.5f} Hz" for m, f in zip(MODES, exact, strict=True))
    )
    print(f"At {PAPER_DP} + {PAPER_BHA} DOFs (paper Fig. 5(b); paper: B close to FEM):")
    at_paper = int(np.flatnonzero(dofs == PAPER_DP + PAPER_BHA)[0])
    for name in DISCRETIZERS:
        cells = ", ".join(
            f"mode {m} {frequencies[name][at_paper, j]:.5f} Hz "
            f"({100 * errors[name][at_paper, j]:+.4f} %)"
            for j, m in enumerate(MODES)
        )
        print(f"  {name:>10}: {cells}")
    print(f"DOFs needed for |error| <= 1 % (4n + n DOFs, n = {steps[0]}..{steps[-1]}):")
    for name in DISCRETIZERS:
        needed = [
            steps_for(name, j, exact[j], steps, errors[name][:, j]) for j in range(len(MODES))
        ]
        cells = ", ".join(
            f"mode {m}: {'> ' + str(dofs[-1]) if n is None else 5 * n}"
            for m, n in zip(MODES, needed, strict=True)
        )
        print(f"  {name:>10}: {cells}")
    print(f"Observed order of convergence between {dofs[-2]} and {dofs[-1]} DOFs:")
    for name in DISCRETIZERS:
        orders = np.log(np.abs(errors[name][-2] / errors[name][-1])) / np.log(dofs[-1] / dofs[-2])
        cells = ", ".join(f"mode {m}: {p:.2f}" for m, p in zip(MODES, orders, strict=True))
        print(f"  {name:>10}: {cells}")
    print("Frequencies [Hz] plotted:")
    print(f"  {'DOFs':>5} " + " ".join(f"{f'{n} m{m}':>17}" for n in DISCRETIZERS for m in MODES))
    for i, total in enumerate(dofs):
        print(
            f"  {total:>5} "
            + " ".join(
                f"{frequencies[n][i, j]:17.5f}" for n in DISCRETIZERS for j in range(len(MODES))
            )
        )

    plt = pyplot()
    fig = plt.figure(figsize=(12.5, 7.5))
    grid = fig.add_gridspec(2, 2, width_ratios=[1.4, 1.0])
    ax_f, ax_e = fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[1, 0])
    ax_s = fig.add_subplot(grid[:, 1])
    for k, name in enumerate(DISCRETIZERS):
        labels = [f"mode {m}, {name}" for m in MODES]
        plot_convergence(
            dofs,
            frequencies[name],
            exact if k == 0 else None,
            labels=labels,
            ax=ax_f,
            marker=MARKERS[name],
            linestyle=["-", "--", ":"][k],
            xlabel="total DOFs (drill pipes + BHA, 4:1)",
        )
        plot_convergence_error(
            dofs,
            errors[name],
            labels=labels,
            ax=ax_e,
            marker=MARKERS[name],
            linestyle=["-", "--", ":"][k],
            xlabel="total DOFs (drill pipes + BHA, 4:1)",
        )
    low = min(exact) - 0.08 * (max(exact) - min(exact))
    ax_f.set_ylim(
        max(low, np.nanmin([f.min() for f in frequencies.values()]) - 0.1),
        max(exact) + 0.25 * (max(exact) - min(exact)),
    )
    ax_f.legend(fontsize="x-small", ncol=2, loc="center right")
    ax_f.set_title("(a) modes 15 and 25: B (lumped), consistent and mixed mass", fontsize="medium")
    ax_e.axhline(1.0, color="0.3", linewidth=0.8, linestyle="-.", label="1 %")
    ax_e.legend(fontsize="x-small", ncol=2, loc="lower left")
    ax_e.set_title("(a, cont.) relative error against the exact continuum", fontsize="medium")

    model = StrategyB(dp_elements=PAPER_DP, bha_elements=PAPER_BHA).discretize(string)
    plot_mode_shapes(modal_analysis(model, max(MODES), string=string), (25,), ax=ax_s)
    ax_s.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.08))
    ax_s.set_title(f"(b) mode 25, {PAPER_DP} + {PAPER_BHA} DOFs", fontsize="medium")
    fig.tight_layout()
    print(f"wrote {save_figure(fig, args.out / 'fig5_high_modes.png', palette=True)}")


if __name__ == "__main__":
    main()
