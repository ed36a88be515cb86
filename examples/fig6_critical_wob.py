"""Fig. 6 of the paper: critical weight on bit of the Ritto (2017) string and variants.

For the base string and four variations of its parameters (drill pipes 30 %
shorter and 30 % longer, BHA twice as long, 5 in drill pipes instead of 5 1/2 in),
the critical weight on bit W_ob,cr(Omega) -- the lowest weight on bit above which
S_SS > 0.8 -- is located on severity maps, (a) over rotary speed x weight on bit
and (b) over the dimensionless groups Pi_1 = Omega/omega_1 x Pi_2 = W_ob R_bit/k_eq.

The paper claims the dimensionless curves are less sensitive to the string's
parameters. The script quantifies that: at each abscissa the spread of the
variants' critical values is their coefficient of variation (standard deviation
over mean); its mean over the abscissas where every variant has a critical value
is printed for each coordinate system, with their ratio.

The model is the built-in configuration (strategy C, 5 drill-pipe elements,
Tucker-Wang in the rpm reading, alpha = 0.35 1/s, beta = 0.06 s).

Usage: python examples/fig6_critical_wob.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

import attrs
import numpy as np

from torsio import DrillPipe, DrillString, builtin_config
from torsio.analysis.map_results import SeverityMap
from torsio.analysis.maps import dimensionless_map, severity_map
from torsio.plotting import pyplot, save_figure


def variants() -> dict[str, Callable[[DrillString], DrillString]]:
    """Each variant as a function of the base string."""

    def scale_section(index: int, factor: float) -> Callable[[DrillString], DrillString]:
        def change(string: DrillString) -> DrillString:
            sections = list(string.sections)
            sections[index] = attrs.evolve(sections[index], length=sections[index].length * factor)
            return string.with_sections(sections)

        return change

    def five_inch(string: DrillString) -> DrillString:
        sections = list(string.sections)
        dp = sections[0]
        sections[0] = DrillPipe(
            od=0.127, id=0.1086, length=dp.length, material=dp.material, name="Drill pipes 5 in"
        )
        return string.with_sections(sections)

    def longer_bha(string: DrillString) -> DrillString:
        return scale_section(2, 2.0)(string)

    return {
        "base (Ritto 2017)": lambda string: string,
        "drill pipes x 0.7": scale_section(0, 0.7),
        "drill pipes x 1.3": scale_section(0, 1.3),
        "collars x 2": longer_bha,
        "5 in drill pipes": five_inch,
    }


def spread(curves: np.ndarray) -> tuple[float, int]:
    """Mean coefficient of variation across variants (rows) over abscissas (columns)
    where every variant has a value, and the number of such abscissas."""
    complete = np.all(np.isfinite(curves), axis=0)
    if not complete.any():
        return float("nan"), 0
    values = curves[:, complete]
    return float(np.mean(values.std(axis=0) / values.mean(axis=0))), int(complete.sum())


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)

    config = builtin_config()
    if args.quick:
        rpm = np.linspace(50.0, 130.0, 3)
        wob = np.linspace(25e3, 325e3, 6)
        pi1 = np.linspace(7.0, 15.0, 3)
        pi2 = np.linspace(5.0, 105.0, 6)
        refine, overrides = 2, {"strategy": "A"}
    else:
        rpm = np.linspace(40.0, 140.0, 11)
        wob = np.linspace(25e3, 425e3, 17)
        pi1 = np.linspace(6.0, 16.0, 11)
        pi2 = np.linspace(5.0, 125.0, 17)
        refine, overrides = 5, {}
    base = config.system(**overrides)

    dimensional: dict[str, SeverityMap] = {}
    dimensionless: dict[str, SeverityMap] = {}
    for name, change in variants().items():
        string = change(config.string)
        model = (
            config.model(**overrides)
            if string is config.string
            else attrs.evolve(config, string=string).model(**overrides)
        )
        system = attrs.evolve(base, model=model, string=string)
        dimensional[name] = severity_map(system, wob=wob, rpm=rpm, refine=refine)
        dimensionless[name] = dimensionless_map(system, pi1=pi1, pi2=pi2, refine=refine)
        m = dimensional[name]
        print(f"{name:20s} omega_1 = {m.omega1:.4f} rad/s, k_eq = {m.k_eq:.1f} N m/rad")

    print("\nCritical weight on bit [kN] (NaN: none in the range)")
    print(f"  {'rpm':20s}" + "".join(f"{r:8.1f}" for r in rpm))
    for name, m in dimensional.items():
        print(f"  {name:20s}" + "".join(f"{w / 1e3:8.1f}" for w in m.critical_wob))
    print("\nCritical Pi_2 (NaN: none in the range)")
    print(f"  {'Pi_1':20s}" + "".join(f"{p:8.2f}" for p in pi1))
    for name, m in dimensionless.items():
        print(f"  {name:20s}" + "".join(f"{p:8.2f}" for p in m.critical_pi2))

    spread_w, n_w = spread(np.array([m.critical_wob for m in dimensional.values()]))
    spread_p, n_p = spread(np.array([m.critical_pi2 for m in dimensionless.values()]))
    print(
        f"\nspread of the critical curves across the {len(dimensional)} strings "
        "(mean coefficient of variation):"
    )
    print(f"  dimensional    W_ob,cr(rpm):  {100 * spread_w:.1f} % over {n_w} speeds")
    print(f"  dimensionless  Pi_2,cr(Pi_1): {100 * spread_p:.1f} % over {n_p} values of Pi_1")
    if np.isfinite(spread_w) and np.isfinite(spread_p) and spread_p > 0:
        print(f"  ratio dimensional / dimensionless: {spread_w / spread_p:.2f}")

    plt = pyplot()
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(11.0, 4.6))
    for name, m in dimensional.items():
        ax_a.plot(m.rpm, m.critical_wob / 1e3, marker="o", label=name)
    for name, m in dimensionless.items():
        ax_b.plot(m.pi1, m.critical_pi2, marker="o", label=name)
    ax_a.set(
        xlabel="surface speed [rpm]",
        ylabel="critical weight on bit [kN]",
        title=f"(a) dimensional: spread {100 * spread_w:.0f} %",
    )
    ax_b.set(
        xlabel="Π₁ = Ω/ω₁ [-]",
        ylabel="critical Π₂ = W_ob R_bit / k_eq [-]",
        title=f"(b) dimensionless: spread {100 * spread_p:.0f} %",
    )
    for ax in (ax_a, ax_b):
        ax.grid(True, alpha=0.4)
    ax_b.legend(fontsize="small")
    fig.suptitle("Fig. 6: critical weight on bit, S_SS > 0.8 above the curves")
    fig.tight_layout()
    print(f"wrote {save_figure(fig, args.out / 'fig6_critical_wob.png', palette=True)}")


if __name__ == "__main__":
    main()
