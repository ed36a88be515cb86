"""Lumped strategies against the distributed model (the wave equation along characteristics).

On the paper's string (Table 1, Tucker-Wang in the rpm reading, Rayleigh alpha = 0.35 1/s and
beta = 0: the wave model carries alpha as distributed drag and refuses beta):

(a) S_SS of strategies A, B, C, consistent and mixed mass as the drill pipes get more
    elements, against the wave model, at the paper's operating points; the elements each
    strategy needs for S_SS within 0.01 of the wave model, and the observed order;
(b) critical weight on bit against rotary speed: strategy A (1 DOF), C (5 DOF) and the
    wave model;
(c) one stick-slip cycle of the wave model: surface torque, bit speed and the angular
    velocity along the string over time (the wave picture).

Every run starts from rest; S_SS over the steady window (lumped: compiled RODAS4 batch
engine, rtol 1e-5; wave: fixed characteristic grid). Prints the numbers it plots.

Usage: python examples/wave_vs_lumped.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import attrs
import numpy as np

from torsio.analysis.maps import severity_map
from torsio.analysis.wave import wave_response
from torsio.io.config import builtin_config
from torsio.physics.damping import RayleighDamping
from torsio.plotting import pyplot, save_figure
from torsio.solvers.batch import simulate_batch

DAMPING = RayleighDamping(alpha=0.35, beta=0.0)
POINTS = ((150e3, 60.0), (200e3, 100.0))  # (WOB [N], rpm): stick-slip in the paper's maps


def system(**discretization: object) -> object:
    """The paper's string with alpha-only damping, discretized as asked."""
    return attrs.evolve(builtin_config().system(**discretization), damping=DAMPING)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    quick = args.quick
    times = {"duration": 60.0, "steady_window": 20.0} if quick else {}
    tolerance = 1e-3 if quick else None
    wave = system(strategy="wave", travel_time_tolerance=tolerance)
    counts = [1, 2, 4] if quick else [1, 2, 4, 8, 16, 32]
    strategies = ["C", "B"] if quick else ["C", "B", "consistent", "mixed"]
    wob = np.array([p[0] for p in POINTS])
    rpm = np.array([p[1] for p in POINTS])
    reference = simulate_batch(wave, wob, rpm, **times).severity
    print("wave model S_SS at", POINTS, ":", np.round(reference, 4))
    one_dof = simulate_batch(system(strategy="A"), wob, rpm, **times).severity
    print("strategy A (1 DOF):", np.round(one_dof, 4))

    fig, axes = pyplot().subplots(1, len(POINTS), figsize=(11.0, 4.2), squeeze=False)
    for name in strategies:
        values = []
        for n in counts:
            options = {"dp_elements": n} if name == "C" else {"dp_elements": n, "bha_elements": 2}
            values.append(
                simulate_batch(system(strategy=name, **options), wob, rpm, **times).severity
            )
        values_arr = np.array(values)
        for j, (w, r) in enumerate(POINTS):
            error = np.abs(values_arr[:, j] - reference[j])
            within = [c for c, e in zip(counts, error, strict=True) if e <= 0.01]
            tail = error[-2:]
            order = (
                math.log(tail[0] / tail[1]) / math.log(counts[-1] / counts[-2])
                if tail.min() > 0
                else math.nan
            )
            print(
                f"{name:>10} at {w / 1e3:.0f} kN, {r:.0f} rpm: S_SS {np.round(values_arr[:, j], 4)}"
                f"; within 0.01 from {within[0] if within else 'none of'} DP elements;"
                f" observed order {order:.2f}"
            )
            axes[0, j].plot(counts, values_arr[:, j], "o-", label=name)
    for j, (w, r) in enumerate(POINTS):
        ax = axes[0, j]
        ax.axhline(reference[j], color="k", linestyle="--", label="wave model")
        ax.axhline(one_dof[j], color="grey", linestyle=":", label="A (1 DOF)")
        ax.set_xscale("log", base=2)
        ax.set_xlabel("drill-pipe elements")
        ax.set_ylabel("S_SS")
        ax.set_title(f"(a) {w / 1e3:.0f} kN, {r:.0f} rpm")
        ax.legend(fontsize=8)
    save_figure(fig, args.out / "wave_vs_lumped_severity.png")

    # (b) critical WOB curves
    grid_rpm = np.linspace(40.0, 140.0, 3 if quick else 11)
    grid_wob = np.linspace(25e3, 225e3, 4 if quick else 11)
    refine = 2 if quick else 4
    fig, ax = pyplot().subplots(figsize=(6.0, 4.5))
    models = (
        ("A (1 DOF)", system(strategy="A")),
        ("C (5 DOF)", system(strategy="C", dp_elements=5)),
        ("wave", wave),
    )
    for label, sys_ in models:
        result = severity_map(sys_, wob=grid_wob, rpm=grid_rpm, refine=refine, **times)
        critical = np.array([np.nan if c is None else c for c in result.critical_wob], dtype=float)
        print(f"critical WOB [kN] {label}: {np.round(critical / 1e3, 1)} at rpm {grid_rpm}")
        ax.plot(grid_rpm, critical / 1e3, "o-", label=label)
    ax.set_xlabel("rotary speed [rpm]")
    ax.set_ylabel("critical WOB [kN]")
    ax.set_title("(b) critical weight on bit (S_SS > 0.8 above)")
    ax.legend()
    save_figure(fig, args.out / "wave_vs_lumped_critical.png")

    # (c) one stick-slip cycle of the wave model
    point = wave.at(wob=POINTS[0][0], rpm=POINTS[0][1])
    response = wave_response(point, field_step=0.05, **times)
    result = response.transient
    period = 2.0 * math.pi / 0.8215  # about one first-mode period; a cycle is longer
    start = result.time[-1] - 2.0 * period
    shown = result.time >= start
    fig, axes = pyplot().subplots(3, 1, figsize=(8.0, 9.0), sharex=True)
    axes[0].plot(result.time[shown], result.surface_torque[shown] / 1e3)
    axes[0].set_ylabel("surface torque [kN m]")
    axes[1].plot(result.time[shown], result.bit_speed[shown] * 30 / math.pi)
    axes[1].set_ylabel("bit speed [rpm]")
    field_shown = response.run.field_time >= start
    image = axes[2].imshow(
        response.run.field[field_shown].T * 30 / math.pi,
        aspect="auto",
        origin="upper",
        extent=(start, float(response.run.field_time[-1]), float(response.depths[-1]), 0.0),
        cmap="viridis",
    )
    fig.colorbar(image, ax=axes[2], label="angular velocity [rpm]")
    axes[2].set_ylabel("depth [m]")
    axes[2].set_xlabel("time [s]")
    axes[0].set_title(f"(c) wave model at 150 kN, 60 rpm: S_SS = {result.severity:.3f}")
    save_figure(fig, args.out / "wave_vs_lumped_cycle.png")
    print("energy balance [J]:", {k: round(v, 1) for k, v in response.energy.items()})


if __name__ == "__main__":
    main()
