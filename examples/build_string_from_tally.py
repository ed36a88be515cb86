"""Build a drill-string in Python from a BHA tally, then discretize it and compute its modes.

A rig's BHA tally lists the components from the bit up, with their outer and
inner diameters (in inches) and lengths; the drill pipe above comes in two
sizes here (two grades of one size, e.g. G-105 and S-135, differ in strength,
not in G, rho or geometry, so torsionally they would be one section). Each
tally row becomes a torsio section (a uniform hollow shaft of the row's body
diameters: stabilizer blades and tool internals are not torsional springs of
their own), the list is reversed to run from the surface down, and the string
is checked on construction (one bit, last; the BHA one block above it).

The dimensions are nominal catalogue sizes chosen for the example, not data
from the paper. Every frequency printed is compared with the exact continuum
of the same string.

Usage: python examples/build_string_from_tally.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
from pathlib import Path

from rich.console import Console

from torsio import (
    LWD,
    MWD,
    STEEL,
    Bit,
    DrillCollar,
    DrillPipe,
    DrillString,
    HeavyWeightDrillPipe,
    MixedMass,
    Stabilizer,
    StrategyB,
    StrategyC,
    modal_analysis,
)
from torsio.plotting import pyplot, save_figure
from torsio.report.model import string_table

INCH = 0.0254
"""Metres per inch."""

# from the bit up: (component, name, OD [in], ID [in], joints, joint length [m]);
# stabilizers are described by their body (6 3/4 in), not their 8 3/8 in blades
TALLY = [
    (Bit, "PDC bit 8 1/2 in", 8.5, 2.25, 1, 0.30),
    (Stabilizer, "Near-bit stabilizer 8 3/8 in", 6.75, 2.8125, 1, 1.80),
    (LWD, "LWD 6 3/4 in", 6.75, 3.0, 1, 8.50),
    (MWD, "MWD 6 3/4 in", 6.75, 3.0, 1, 9.00),
    (Stabilizer, "String stabilizer 8 3/8 in", 6.75, 2.8125, 1, 1.60),
    (DrillCollar, "Drill collars 6 3/4 in", 6.75, 2.8125, 3, 9.45),
    (DrillCollar, "Drill collars 6 1/2 in", 6.5, 2.8125, 6, 9.45),
    (HeavyWeightDrillPipe, "HWDP 5 in", 5.0, 3.0, 15, 9.30),
    (DrillPipe, "Drill pipe 5 in 19.50 lb/ft", 5.0, 4.276, 160, 9.40),
    (DrillPipe, "Drill pipe 5 1/2 in 21.90 lb/ft", 5.5, 4.778, 270, 9.40),
]


def string_from_tally(tally: list[tuple], name: str = "") -> DrillString:
    """A DrillString from tally rows listed from the bit up."""
    sections = [
        component(
            od=od * INCH, id=inner * INCH, length=joints * joint_length, material=STEEL, name=label
        )
        for component, label, od, inner, joints, joint_length in tally
    ]
    return DrillString(reversed(sections), name=name)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)

    string = string_from_tally(TALLY, name="8 1/2 in section, tapered drill pipe")
    Console(width=120).print(string_table(string))
    print(
        f"top of the bit at {string.section_tops[-1]:.2f} m; "
        f"BHA {len(string.bha_sections)} sections, "
        f"I_BHA = {string.bha_inertia:.2f} kg m^2; I_DP = {string.drill_pipe_inertia:.2f} "
        "kg m^2"
    )

    element = 50.0 if args.quick else 20.0
    models = {
        f"B, elements <= {element:g} m": StrategyB(max_element_length=element),
        f"mixed, elements <= {element:g} m": MixedMass(max_element_length=element),
        "C, 20 drill-pipe elements": StrategyC(dp_elements=20),
    }
    shapes = None
    for label, discretizer in models.items():
        model = discretizer.discretize(string)
        results = modal_analysis(model, 5, string=string)
        comparison = results.compare()
        which = "rigid BHA" if comparison.reference.rigid_bha else "flexible BHA"
        print(f"{label}: {model.dofs} DOFs, against the exact continuum ({which})")
        for mode, lumped, exact, error in comparison.rows():
            print(
                f"  mode {mode}: {lumped:.5f} Hz, continuum {exact:.5f} Hz, "
                f"error {100 * error:+.4f} %"
            )
        if shapes is None:
            shapes = results

    assert shapes is not None
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.0, 6.5))
    shapes.plot(modes=(1, 2, 3), ax=ax)
    ax.set_ylim(string.section_tops[-1] + 100, 0)
    ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, -0.09), ncol=2)
    ax.set_title(f"Tally string: modes 1-3, strategy B ({shapes.model.dofs} DOFs)")
    print(f"wrote {save_figure(fig, args.out / 'tally_mode_shapes.png', palette=True)}")


if __name__ == "__main__":
    main()
