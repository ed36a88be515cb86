"""Convergence of the lumped strategies' S_SS to the distributed (wave) model.

On the paper's string (Table 1, Tucker-Wang in the rpm reading, Rayleigh alpha = 0.35 1/s and
beta = 0: the wave model carries alpha as distributed drag and refuses beta) at the paper's
operating points:

(a) S_SS of strategies C (rigid BHA), B, consistent and mixed mass as the drill pipes get
    n = 2, 4, ..., 128 elements (B and the finite elements: every section split into
    elements no longer than L_DP / n), against the wave model; the element count from
    which S_SS stays within 0.01 of it, and the observed order log2(e_n / e_2n) of the
    last refinements. Strategy C converges to the wave model of the string with a rigid
    BHA (``rigid_bha = true``), not to the flexible one: both references are printed.
(b) critical weight on bit against rotary speed (S_SS > 0.8 above it): strategy A
    (1 DOF), C (5 DOF) and the wave model (and its rigid-BHA string, C's limit), and
    where the 1-DOF model is wrong.

Every run starts from rest and lasts 40 periods of the exact continuum's first mode,
S_SS over the last 15 (the same times for every model). Lumped: compiled RODAS4 batch
engine, rtol 1e-5. Wave: the default characteristic grid (dt = 1.44 ms).
Prints the numbers it plots.

Usage: python examples/wave_convergence.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from torsio.analysis.maps import severity_map
from torsio.examples import builtin_config, ritto2017_string
from torsio.model.continuum import continuum_modes
from torsio.physics.damping import RayleighDamping
from torsio.plotting import pyplot, save_figure
from torsio.solvers.batch import simulate_batch

DAMPING = RayleighDamping(alpha=0.35, beta=0.0)
POINTS = ((100e3, 60.0), (150e3, 60.0), (200e3, 100.0))  # (WOB [N], rpm): stick-slip
TARGET = 0.01  # S_SS difference the study asks for


def _system(**discretization: Any) -> Any:
    """The paper's string with alpha-only damping, discretized as asked."""
    return attrs.evolve(builtin_config().system(**discretization), damping=DAMPING)


def _lumped(name: str, n: int) -> Any:
    """Strategy ``name`` with n drill-pipe elements (C), or elements of at most L_DP / n."""
    if name == "C":
        return _system(strategy="C", dp_elements=n)
    length = ritto2017_string().drill_pipe_sections[0].length
    return _system(strategy=name, max_element_length=length / n)


def _needed(counts: list[int], errors: np.ndarray) -> int | None:
    """The smallest count from which every error is within TARGET (None: never)."""
    for k, count in enumerate(counts):
        if np.all(errors[k:] <= TARGET):
            return count
    return None


def _orders(counts: list[int], errors: np.ndarray) -> list[float]:
    """log(e_k / e_k+1) / log(n_k+1 / n_k) for consecutive counts."""
    return [
        math.log(errors[k] / errors[k + 1]) / math.log(counts[k + 1] / counts[k])
        if errors[k] > 0 and errors[k + 1] > 0
        else math.nan
        for k in range(len(counts) - 1)
    ]


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    quick = args.quick
    period = 2.0 * math.pi / float(continuum_modes(ritto2017_string(), 1).frequencies_rad[0])
    times = {"duration": 40.0 * period, "steady_window": 15.0 * period}
    if quick:
        times = {"duration": 60.0, "steady_window": 20.0}
    points = POINTS[1:2] if quick else POINTS
    tolerance = 1e-3 if quick else None  # travel-time rounding of the wave grid
    counts = [2, 4, 8] if quick else [2, 4, 8, 16, 32, 64, 128]
    strategies = ["C", "B"] if quick else ["C", "B", "consistent", "mixed"]
    wob = np.array([p[0] for p in points])
    rpm = np.array([p[1] for p in points])

    wave = _system(strategy="wave", travel_time_tolerance=tolerance)
    rigid = _system(strategy="wave", travel_time_tolerance=tolerance, rigid_bha=True)
    reference = simulate_batch(wave, wob, rpm, **times).severity
    reference_rigid = simulate_batch(rigid, wob, rpm, **times).severity
    one_dof = simulate_batch(_system(strategy="A"), wob, rpm, **times).severity
    print(f"grid: dt = {wave.model.time_step * 1e3:.4g} ms, cells {list(wave.model.cells)}")
    for j, (w, r) in enumerate(points):
        print(
            f"{w / 1e3:.0f} kN, {r:.0f} rpm: wave S_SS {reference[j]:.4f}, wave with rigid BHA "
            f"{reference_rigid[j]:.4f}, A (1 DOF) {one_dof[j]:.4f}"
        )

    fig, axes = pyplot().subplots(1, len(points), figsize=(4.2 * len(points), 4.2), squeeze=False)
    print("\n| strategy | point | DOFs | S_SS | error | within 0.01 from n = | orders |")
    print("|---|---|---|---|---|---|---|")
    for name in strategies:
        models = [_lumped(name, n) for n in counts]
        dofs = [m.model.dofs for m in models]
        values = np.array([simulate_batch(m, wob, rpm, **times).severity for m in models])
        for j, (w, r) in enumerate(points):
            targets = [("wave", reference[j])]
            if name == "C":
                targets.append(("wave, rigid BHA", reference_rigid[j]))
            for label, value in targets:
                errors = np.abs(values[:, j] - value)
                needed = _needed(counts, errors)
                orders = ", ".join(f"{o:.2f}" for o in _orders(counts, errors)[-3:])
                print(
                    f"| {name} vs {label} | {w / 1e3:.0f} kN, {r:.0f} rpm | {dofs} "
                    f"| {np.round(values[:, j], 4).tolist()} | {np.round(errors, 4).tolist()} "
                    f"| {needed if needed else f'not by {counts[-1]}'} | {orders} |"
                )
            axes[0, j].plot(dofs, values[:, j], "o-", label=name)
    for j, (w, r) in enumerate(points):
        ax = axes[0, j]
        ax.axhline(reference[j], color="k", linestyle="--", label="wave model")
        ax.axhline(reference_rigid[j], color="k", linestyle=":", label="wave, rigid BHA")
        ax.axhline(one_dof[j], color="grey", linestyle="-.", label="A (1 DOF)")
        ax.set_xscale("log", base=2)
        ax.set_xlabel("degrees of freedom")
        ax.set_ylabel("S_SS")
        ax.set_title(f"(a) {w / 1e3:.0f} kN, {r:.0f} rpm")
        ax.legend(fontsize=7)
    save_figure(fig, args.out / "wave_convergence_severity.png")

    # (b) critical WOB curves
    grid_rpm = np.linspace(40.0, 140.0, 3 if quick else 11)
    grid_wob = np.linspace(25e3, 225e3, 5 if quick else 21)
    fig, ax = pyplot().subplots(figsize=(6.0, 4.5))
    curves = {}
    models = (
        ("A (1 DOF)", _system(strategy="A")),
        ("C (5 DOF)", _system(strategy="C", dp_elements=5)),
        ("wave", wave),
        ("wave, rigid BHA", rigid),
    )
    for label, model in models:
        result = severity_map(model, wob=grid_wob, rpm=grid_rpm, refine=2 if quick else 4, **times)
        critical = np.array([np.nan if c is None else c for c in result.critical_wob], dtype=float)
        curves[label] = critical
        ax.plot(grid_rpm, critical / 1e3, "o-", label=label)
    print("\n| rpm | " + " | ".join(f"{label} [kN]" for label in curves) + " | A - wave [kN] |")
    print("|---" * (len(curves) + 2) + "|")
    for i, r in enumerate(grid_rpm):
        cells = " | ".join(f"{curves[label][i] / 1e3:.1f}" for label in curves)
        difference = (curves["A (1 DOF)"][i] - curves["wave"][i]) / 1e3
        print(f"| {r:.0f} | {cells} | {difference:+.1f} |")
    ax.set_xlabel("rotary speed [rpm]")
    ax.set_ylabel("critical WOB [kN]")
    ax.set_title("(b) critical weight on bit (S_SS > 0.8 above)")
    ax.legend()
    save_figure(fig, args.out / "wave_convergence_critical.png")


if __name__ == "__main__":
    main()
