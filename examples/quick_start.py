"""Quick start: load a string, discretize it, compute its modes, compare, plot.

The built-in configuration is the string of the paper's Table 1 (Ritto et al.
2017), the same file ``torsio report`` uses when given no file; a TOML file of
your own loads with ``torsio.load_config(path)``.

Usage: python examples/quick_start.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import torsio
from torsio.plotting import pyplot, save_figure


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)

    # 1. the configuration: sections, bit-rock law, damping, discretization, operating point
    config = torsio.builtin_config()  # or torsio.load_config("my_string.toml")
    string = config.string
    print(
        f"{config.name}: {len(string.sections)} sections, top of the bit at "
        f"{string.section_tops[-1]:.1f} m"
    )
    for section in string.sections:
        print(
            f"  {section.kind:>10}  {section.name:<42} L = {section.length:7.2f} m  "
            f"I = {section.inertia:8.3f} kg m^2"
        )

    # 2. a lumped model: strategy B, the drill pipes in 20 elements, the BHA in 5
    dp, bha = (10, 4) if args.quick else (20, 5)
    model = torsio.StrategyB(dp_elements=dp, bha_elements=bha).discretize(string)
    print(f"strategy {model.strategy}: {model.dofs} degrees of freedom")

    # 3. its modes, against the exact continuum of the same string
    results = torsio.modal_analysis(model, count=4, string=string)
    comparison = results.compare()
    print(f"  {'mode':>4} {'lumped [Hz]':>12} {'continuum [Hz]':>15} {'error':>8}")
    for mode, lumped, exact, error in comparison.rows():
        print(f"  {mode:>4} {lumped:12.5f} {exact:15.5f} {100 * error:+7.3f}%")

    # 4. the mode shapes against depth (matplotlib)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5.5, 6.0))
    results.plot(modes=(1, 2), ax=ax)
    ax.set_title(f"Modes 1 and 2, strategy B, {dp} + {bha} DOFs")
    print(f"wrote {save_figure(fig, args.out / 'quick_start.png', palette=True)}")


if __name__ == "__main__":
    main()
