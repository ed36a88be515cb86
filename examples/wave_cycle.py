"""One stick-slip cycle of the distributed model (the wave equation along characteristics).

On the paper's string (Table 1, Tucker-Wang in the rpm reading, Rayleigh alpha = 0.35 1/s and
beta = 0: the wave model carries alpha as distributed drag and refuses beta), at 150 kN and
60 rpm, from rest: the surface torque, the bit speed and the angular velocity along the
string over the last two periods (the wave picture), and the energy balance of the run.
The lumped strategies against the wave model: ``examples/wave_convergence.py``.

Usage: python examples/wave_cycle.py [OUT_FOLDER] [--quick]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import attrs

from torsio.analysis.wave import wave_response
from torsio.examples import builtin_config
from torsio.physics.damping import RayleighDamping
from torsio.plotting import pyplot, save_figure

DAMPING = RayleighDamping(alpha=0.35, beta=0.0)
POINT = (150e3, 60.0)  # (WOB [N], rpm): stick-slip in the paper's maps


def system(**discretization: object) -> object:
    """The paper's string with alpha-only damping, discretized as asked."""
    return attrs.evolve(builtin_config().system(**discretization), damping=DAMPING)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="out", type=Path, help="output folder")
    parser.add_argument("--quick", action="store_true", help="reduced sizes (CI)")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    times = {"duration": 60.0, "steady_window": 20.0} if args.quick else {}
    tolerance = 1e-3 if args.quick else None
    wave = system(strategy="wave", travel_time_tolerance=tolerance)

    point = wave.at(wob=POINT[0], rpm=POINT[1])
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
    axes[0].set_title(f"wave model at 150 kN, 60 rpm: S_SS = {result.severity:.3f}")
    save_figure(fig, args.out / "wave_cycle.png")
    print("energy balance [J]:", {k: round(v, 1) for k, v in response.energy.items()})


if __name__ == "__main__":
    main()
