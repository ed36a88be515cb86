"""How much the wave model's own discretization moves S_SS over the (WOB, rpm) map.

The distributed model has two numerical choices: the characteristic grid (its time step
dt, set by the travel-time tolerance) and the lumping of the distributed drag into
point dampers every ``drag_spacing`` cells. On the paper's string (Table 1, Tucker-Wang
in the rpm reading, Rayleigh alpha = 0.35 1/s and beta = 0) this script runs the 21 x 21
map (WOB 25-225 kN, 40-140 rpm, default run length and window, every run to its end)

- with the drag at every node (``drag_spacing = 1``): the reference;
- with the default drag spacing, and with 8 cells;
- with the drag at every node and the time step halved (``time_step = 0.75 ms``);
- with the drag at every node and the weight on bit moved by 1e-12 of itself: the
  round-off floor, how much S_SS depends on anything at all at that point,

and prints, over the stick-slip points (S_SS > 0.5) and the others, the median, 90th
percentile and largest |S_SS - reference|, and the number of points beyond 1e-3 and
1e-2. It draws the differences as maps.

Usage: python examples/wave_grid_study.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from torsio.examples import builtin_config
from torsio.model.wave import DEFAULT_DRAG_SPACING
from torsio.physics.damping import RayleighDamping
from torsio.plotting import pyplot, save_figure
from torsio.solvers.batch import simulate_batch

DAMPING = RayleighDamping(alpha=0.35, beta=0.0)


def _wave(**options: Any) -> Any:
    """The paper's string as the wave model with alpha-only damping."""
    system = builtin_config().system(strategy="wave", **options)
    return attrs.evolve(system, damping=DAMPING)


def _map(system: Any, wob: np.ndarray, rpm: np.ndarray, scale: float = 1.0) -> np.ndarray:
    """S_SS at every (wob, rpm), every run to its end."""
    result = simulate_batch(system, wob * scale, rpm, steady_tolerance=0.0)
    return np.asarray(result.severity)


def _statistics(difference: np.ndarray) -> str:
    """Median, 90th percentile, largest; points beyond 1e-3 and 1e-2."""
    if difference.size == 0:
        return "no points"
    median, p90, largest = np.percentile(difference, [50, 90, 100])
    return (
        f"median {median:.1e}, p90 {p90:.1e}, max {largest:.1e}; "
        f"{int(np.sum(difference > 1e-3))} > 1e-3, {int(np.sum(difference > 1e-2))} > 1e-2"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", help="folder for the figure")
    parser.add_argument("--quick", action="store_true", help="5 x 5 grid, short runs")
    args = parser.parse_args(argv)
    count = 5 if args.quick else 21
    wob_axis = np.linspace(25e3, 225e3, count)
    rpm_axis = np.linspace(40.0, 140.0, count)
    wob, rpm = (a.ravel() for a in np.meshgrid(wob_axis, rpm_axis, indexing="ij"))
    variants = {
        f"drag every {DEFAULT_DRAG_SPACING} cells (default)": (
            _wave(drag_spacing=DEFAULT_DRAG_SPACING),
            1.0,
        ),
        "drag every 8 cells": (_wave(drag_spacing=8), 1.0),
        "time step halved": (_wave(drag_spacing=1, time_step=0.75e-3), 1.0),
        "WOB x (1 + 1e-12)": (_wave(drag_spacing=1), 1.0 + 1e-12),
    }
    if args.quick:  # shorter runs: the comparison, not the numbers
        variants = dict(list(variants.items())[:1])
    started = time.perf_counter()
    reference_system = _wave(drag_spacing=1)
    print(f"grid: dt = {reference_system.model.time_step * 1e3:.4g} ms, cells "
          f"{list(reference_system.model.cells)}; {count} x {count} points")  # fmt: skip
    reference = _map(reference_system, wob, rpm)
    stick_slip = reference > 0.5
    print(f"reference (drag at every node): {int(stick_slip.sum())} stick-slip points")
    differences = {}
    for label, (system, scale) in variants.items():
        difference = np.abs(_map(system, wob, rpm, scale) - reference)
        differences[label] = difference
        print(f"{label}:")
        print(f"  stick-slip: {_statistics(difference[stick_slip])}")
        print(f"  others:     {_statistics(difference[~stick_slip])}")
    print(f"({time.perf_counter() - started:.0f} s)")

    plt = pyplot()
    figure, axes = plt.subplots(
        1, len(differences), figsize=(4.2 * len(differences), 3.8), squeeze=False
    )
    extent = (rpm_axis[0], rpm_axis[-1], wob_axis[0] / 1e3, wob_axis[-1] / 1e3)
    for axis, (label, difference) in zip(axes[0], differences.items(), strict=True):
        image = axis.imshow(
            np.log10(np.maximum(difference.reshape(count, count), 1e-12)), origin="lower",
            aspect="auto", extent=extent, vmin=-12, vmax=0, cmap="magma",
        )  # fmt: skip
        axis.set_title(label, fontsize=9)
        axis.set_xlabel("rpm")
    axes[0][0].set_ylabel("WOB [kN]")
    figure.colorbar(image, ax=axes[0].tolist(), label="log10 |S_SS - reference|")
    path = save_figure(figure, Path(args.out) / "wave_grid_study.png")
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
